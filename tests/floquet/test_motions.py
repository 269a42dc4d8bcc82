"""floquet_motions: the exponents and motions a continuation step compares.

Checked against :func:`tefcore.floquet.floquet_modes` on the same grid (its
harmonic analysis chooses a frequency convention, floquet_motions does not):
the exponents agree modulo 1/rev and up to the conjugate, and each motion
``exp(-sigma psi) x(psi)`` is the full result's ``exp(i omega psi) p(psi)``
(:func:`tefcore.modes.labels.trajectory_shapes`) up to a complex scale --
the one thing no convention changes.  And a known answer: the damped
oscillator seen through a periodic change of variables.
"""

from __future__ import annotations

import numpy as np
import pytest

from tefcore.floquet import floquet_modes, floquet_motions
from tefcore.modes.labels import trajectory_shapes


def _oscillator(psi):
    """Frequency 0.7/rev, damping rate -0.05/rev, through x = (1 + 0.3 sin psi) z."""
    b = np.array([[0.0, 1.0], [-(0.05**2 + 0.7**2), -0.1]])
    s = 1 + 0.3 * np.sin(psi)
    return b + (0.3 * np.cos(psi) / s)[:, None, None] * np.eye(2)


def test_known_exponent_on_the_principal_branch():
    eta, x = floquet_motions(_oscillator, 72)
    # sigma -0.05; 0.7 /rev is 0.3 /rev of the conjugate on the principal branch
    # (|Im| <= 1/2); 72 Magnus steps resolve it to 1e-8
    np.testing.assert_allclose(eta, [-0.05 + 0.3j], atol=1e-8)
    assert x.shape == (72, 2, 1)


def _rotor_like(n=4, seed=3):
    """A random lightly damped periodic second-order system (2 n states)."""
    rng = np.random.default_rng(seed)
    k0 = np.diag(np.arange(1, n + 1) ** 2 * 1.3)
    k1, c1 = 0.4 * rng.standard_normal((2, n, n))

    def a(psi):
        k = k0 + np.cos(psi)[:, None, None] * k1
        c = 0.1 * np.eye(n) + np.sin(psi)[:, None, None] * 0.05 * c1
        top = np.broadcast_to(np.hstack([np.zeros((n, n)), np.eye(n)]), (psi.size, n, 2 * n))
        return np.concatenate([top, np.concatenate([-k, -c], axis=2)], axis=1)
    return a


def test_exponents_and_motions_are_those_of_floquet_modes():
    a = _rotor_like()
    eta, x = floquet_motions(a, 72)
    full = floquet_modes(a, n_steps=72, shapes=True, atol=None, method="magnus",
                         n_sub=4).positive_frequency()
    assert eta.size == full.exponents.size
    for e, xm in zip(eta, np.moveaxis(x, -1, 0), strict=True):
        # the same root: equal real part, frequency equal modulo 1 up to sign
        fold = np.abs(full.exponents.imag[:, None] - np.array([e.imag, -e.imag])[None]) % 1.0
        gap = np.minimum(fold, 1 - fold).min(axis=1) + np.abs(full.exponents.real - e.real)
        j = int(np.argmin(gap))
        # both from the same step propagators and lift: round-off apart
        assert gap[j] < 1e-9
        ref = trajectory_shapes(np.eye(x.shape[1]), full.select([j]), x.shape[1], samples=72)
        got = xm.reshape(-1)
        # the same motion up to scale (or its conjugate, for the other sign)
        mac = max(abs(np.vdot(ref[:, 0], v)) ** 2 / (np.vdot(v, v).real
                                                      * np.vdot(ref[:, 0], ref[:, 0]).real)
                  for v in (got, got.conj()))
        assert mac == pytest.approx(1.0, abs=1e-9)


def test_motions_of_a_second_order_system_refuse_what_they_cannot_do():
    from tefcore.floquet.second_order import SecondOrderSystem

    m, c, k = np.eye(2)[None], 0.1 * np.eye(2)[None], np.diag([1.0, 4.0])[None]
    # constant coefficients: the modes are direct eigenvalues, not a path's motions
    with pytest.raises(ValueError, match="periodic"):
        SecondOrderSystem(m, c, k).motions()
