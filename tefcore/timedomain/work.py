"""Work done on a marched response by the named terms, revolution by revolution.

The time-domain form of the energy balance of :mod:`tefcore.linear.mechanism`
(docs/theory.md sections 10 and 12.3).  Along a real response ``x = [q, q*, z]``
of ``M q** + C q* + K q + C_qz z* + K_qz z = 0`` the energy of the blade and
flap, ``E = 1/2 (q*^T M^h q* + q^T K^h q)`` (``^h`` the symmetric part, over
the ``q`` blocks), changes at the rate ``dE/dpsi = sum_t w_t`` with

``w_t = -q*^T (M_t^n q** + C_t q* + K_t^n q + C_t,qz z* + K_t,qz z)``
``      + 1/2 (q*^T M_t^h' q* + q^T K_t^h' q)``

for each term ``t`` (``^n`` the rest, ``'`` the azimuth derivative).  Over
revolution ``k`` each term's work, weighted by ``e^{-2 s psi}`` with ``s`` the
response's growth rate (the weight the Floquet decomposition uses: without
it a revolution of a +3 /rev root is all its last oscillation), is divided
by twice the energy weighted alike:

``c_t = int e^{-2 s psi} w_t dpsi / (2 int e^{-2 s psi} E dpsi)``.

They add up, integrating by parts, to the revolution's **energy growth**

``g = s + [e^{-2 s psi} E] / (2 int e^{-2 s psi} E dpsi)``,

which is ``sigma`` for an energy ``e^{2 sigma psi}`` times a periodic factor:
the growth rate of the revolution, split into what each term does.  A real
response's energy also beats at twice the frequency, which a revolution
averages over only approximately (the Floquet decomposition uses the complex
shape, which does not beat).

Examples
--------
A damped oscillator: all the work is the damper's, ``-0.1`` per radian.

>>> from tefcore.floquet.second_order import SecondOrderSystem
>>> from tefcore.timedomain.march import march
>>> one = np.ones((1, 1, 1))
>>> parts = {"spring": SecondOrderSystem(one, 0 * one, 4 * one),
...          "damper": SecondOrderSystem(0 * one, 0.2 * one, 0 * one)}
>>> run = march(SecondOrderSystem(one, 0.2 * one, 4 * one), [1.0, 0.0], revs=2)
>>> table = work_per_revolution(parts, run, rate=-0.1)
>>> [round(v, 2) for v in table["damper"]], [round(v, 3) for v in table["spring"]]
([-0.1, -0.1], [0.0, 0.0])
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import scipy.integrate

from ..floquet.second_order import combine

__all__ = ["WORK_SAMPLES", "work_per_revolution"]

#: Azimuth samples per revolution for the work integrals (Simpson's rule):
#: with 720, the closure ``sum_t W_t - Delta E`` of a 10 /rev root is below
#: 1e-6 of ``Delta E`` (tested).
WORK_SAMPLES = 720


def _sym(a):
    return 0.5 * (a + np.swapaxes(a, -1, -2))


def _rev_samples(run, k, samples):
    """Azimuths of revolution ``k`` and the state there, scaled to its largest element 1."""
    psi = 2 * np.pi * (k + np.linspace(0.0, 1.0, samples + 1))
    x = run.at(psi)
    return psi, x / np.abs(x).max()


def work_per_revolution(parts: dict, run, *, rate: float = 0.0,
                        samples: int = WORK_SAMPLES) -> pd.DataFrame:
    """Each term's weighted work over each whole revolution, over twice the weighted energy.

    Parameters
    ----------
    parts : dict of str to SecondOrderSystem
        The named terms (:func:`tefcore.linear.mechanism.linearized_terms`);
        their sum is the system that was marched.
    run : tefcore.timedomain.march.Trajectory
        The marched response of the linear system.
    rate : float, optional
        The response's growth rate ``s`` (per radian) of the weight
        ``e^{-2 s psi}`` (e.g. the fitted one).
    samples : int, optional
        Azimuth samples per revolution (even).

    Returns
    -------
    pandas.DataFrame
        One row per whole revolution: ``revolution`` (0, 1, ...), a column per
        term (``c_t``, per radian of azimuth as the Floquet real part),
        ``sum`` (of the terms) and ``energy_growth`` (``g``, from the energy
        itself): the two agree to the integration error.
    """
    system = combine(parts)
    n = system.n_dof
    rows = []
    for k in range(int(np.floor(run.psi_end / (2 * np.pi) + 1e-9))):
        psi, x = _rev_samples(run, k, samples)
        m, c, kk = system.matrices(psi)
        xdot = np.einsum("pij,jp->ip", system.state_matrix(psi), x)
        q, v, z = x[:n], x[n:2 * n], x[2 * n:]
        a, zd = xdot[n:2 * n], xdot[2 * n:]
        energy = 0.5 * (np.einsum("ip,pij,jp->p", v, _sym(m[:, :n, :n]), v)
                        + np.einsum("ip,pij,jp->p", q, _sym(kk[:, :n, :n]), q))
        weight = np.exp(-2.0 * rate * (psi - psi[0]))
        denom = 2.0 * scipy.integrate.simpson(weight * energy, x=psi)
        row = {"revolution": k}
        for name, part in parts.items():
            row[name] = scipy.integrate.simpson(
                weight * _term_rate(part, psi, q, v, a, z, zd, n), x=psi) / denom
        row["sum"] = sum(row[t] for t in parts)
        row["energy_growth"] = rate + (weight[-1] * energy[-1] - energy[0]) / denom
        rows.append(row)
    return pd.DataFrame(rows, columns=["revolution", *parts, "sum", "energy_growth"])


def _term_rate(part, psi, q, v, a, z, zd, n):
    """``w_t(psi)``: the rate of work of one term along the response."""
    mt, ct, kt = part.matrices(psi)
    q_ = slice(0, n)
    mq, kq = mt[:, q_, q_], kt[:, q_, q_]
    force = (np.einsum("pij,jp->ip", mq - _sym(mq), a) + np.einsum("pij,jp->ip", ct[:, q_, q_], v)
             + np.einsum("pij,jp->ip", kq - _sym(kq), q))
    if z.shape[0]:
        force += (np.einsum("pij,jp->ip", ct[:, q_, n:], zd)
                  + np.einsum("pij,jp->ip", kt[:, q_, n:], z))
    rate = -np.einsum("ip,ip->p", v, force)
    if part.periodic:
        dm, _, dk = part.matrices(psi, 1)
        rate = rate + 0.5 * (np.einsum("ip,pij,jp->p", v, _sym(dm[:, q_, q_]), v)
                             + np.einsum("ip,pij,jp->p", q, _sym(dk[:, q_, q_]), q))
    return rate
