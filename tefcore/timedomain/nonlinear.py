"""The full nonlinear blade/flap equations marched from the trim plus a perturbation.

The coupled model's residual (:meth:`tefcore.model.coupled.CoupledModel.evaluate`,
the equations the trim solves) is affine in the accelerations (measured:
second differences in ``q**`` vanish to 3e-16), so at each azimuth one call
with ``n + 2`` columns gives ``R0 = R(q, q*, 0)``, the mass matrix
``M(q, q*)`` column by column and the trim's own residual ``r_t(psi)``, and

``q** = -M^-1 (R0 - r_t)``.

Subtracting ``r_t`` makes the trimmed motion an exact solution of the
marched equations: the harmonic balance meets ``R = 0`` only at its
collocation azimuths (between them ``|R|`` reaches 7e-5 at MDART, mu = 0.3,
24 azimuths, measured), and without the correction that residual would force
the unstable root from the first step.  The state marched is the perturbation
``x = [q - q_t, q* - q_t*]`` about the trim ``q_t(psi)``; controls and inflow
are held at their trimmed values, as in the linearisation (docs/theory.md
sections 8 and 12).  The march stops when the flap deflection reaches
:data:`FLAP_LIMIT_DEG` or when the section model refuses a state (a Mach
number beyond its range).

Examples
--------
>>> from tefcore.config.io import load_config
>>> from tefcore.linear.stability import stability
>>> res = stability(load_config("mdart"), identity=False)
>>> rhs = nonlinear_rhs(res.trim_result)
>>> x = np.zeros(2 * res.trim_result.model.n_dof)
>>> bool(np.abs(rhs(0.0, x)).max() < 1e-9)           # the trim is a solution
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["FLAP_LIMIT_DEG", "check_nonlinear", "flap_limit_event", "nonlinear_rhs"]

#: The nonlinear march stops when the flap deflection (trim plus
#: perturbation) reaches this [deg]: the flap at right angles to the blade, far
#: beyond attached flow and the thin-airfoil model (the trim refuses 20 deg).
FLAP_LIMIT_DEG = 90.0


def check_nonlinear(cfg) -> None:
    """Refuse, before anything is computed, a configuration the nonlinear march does not take.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.

    Raises
    ------
    ValueError
        With aerodynamic states (shed wake, dynamic inflow): their nonlinear
        equations are not marched.
    """
    if cfg.model.aero != "quasi_steady" or cfg.model.inflow == "dynamic":
        raise ValueError("the nonlinear march takes quasi-steady airloads and momentum inflow "
                         f"(here model.aero = {cfg.model.aero!r}, model.inflow = "
                         f"{cfg.model.inflow!r}); march the linearised equations instead "
                         "(without --nonlinear)")


def nonlinear_rhs(tr):
    """``x* = f(psi, x)`` of the perturbation about a trim, nonlinear.

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim (its model, controls and inflow are held).

    Returns
    -------
    callable
        ``rhs(psi, x)`` with ``x = [dq, dq*]`` (``2 n_dof``).

    Raises
    ------
    ValueError
        With aerodynamic states (shed wake, dynamic inflow): their nonlinear
        equations are not marched.
    """
    model = tr.model
    check_nonlinear(model.cfg)
    n = model.n_dof
    unit = np.zeros((n, n + 2))
    unit[:, 1:n + 1] = np.eye(n)

    def rhs(psi, x):
        p = np.array([float(psi)])
        qt, qdt, qddt = (a[:, 0] for a in tr.motion(p))
        q = np.repeat((qt + x[:n])[:, None], n + 2, axis=1)
        qd = np.repeat((qdt + x[n:])[:, None], n + 2, axis=1)
        qdd = unit.copy()
        q[:, -1], qd[:, -1], qdd[:, -1] = qt, qdt, qddt
        r, _ = model.evaluate(np.full(n + 2, float(psi)), q, qd, qdd, tr.controls, tr.inflow)
        mass = r[:, 1:n + 1] - r[:, :1]
        acc = -np.linalg.solve(mass, r[:, 0] - r[:, -1])
        return np.concatenate([x[n:], acc - qddt])

    return rhs


def flap_limit_event(tr, limit_deg: float = FLAP_LIMIT_DEG):
    """A terminal event: the flap deflection (trim plus perturbation) reaches ``limit_deg``.

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim.
    limit_deg : float, optional
        The limit [deg].

    Returns
    -------
    callable
        For :func:`scipy.integrate.solve_ivp` (``terminal``, ``reason``).
    """
    n, limit = tr.model.n_dof, np.deg2rad(limit_deg)

    def event(psi, x):
        delta = tr.motion(np.array([float(psi)]))[0][-1, 0] + x[n - 1]
        return abs(delta) - limit

    event.terminal = True
    event.reason = f"the flap deflection reached {limit_deg:g} deg"
    return event
