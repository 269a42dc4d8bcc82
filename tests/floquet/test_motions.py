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
from tefcore.floquet.second_order import SecondOrderSystem
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


def test_the_shed_wake_lift_trusts_its_deep_roots_less():
    """With ``min_rate`` (fast states whose deep roots are not wanted) the lift
    trusts its most damped wanted root to a relative round-off of 1e-4
    (STATE_ROOT_RTOL) instead of 1e-6: MDART's 92-state shed-wake system at
    mu 0.3, c_cg 0.33, needs K = 4 instead of 8 (a lift of 368 instead of 736
    states).  The roots that are wanted -- every root above -6 /rev, the
    blade's and the flap's -- move by 7.8e-7 /rev (measured); gate 1e-5, a
    hundredth of the error control's default tolerance (DEFAULT_ATOL, 1e-3
    /rev), which a lift that lost a root (wrong by 1e-2 /rev or more) cannot
    meet."""
    from tefcore.config.io import load_config
    from tefcore.floquet import STATE_ROOT_RTOL, floquet_modes
    from tefcore.floquet.second_order import STATE_MIN_RATE
    from tefcore.linear.stability import stability

    assert STATE_ROOT_RTOL == 1e-4
    system = stability(load_config("mdart").with_overrides(
        {"flight.advance_ratio": 0.3, "model.aero": "unsteady", "flap.cg_offset": 0.33})).system
    kw = dict(n_steps=72, n_sub=1, method="magnus", min_rate=STATE_MIN_RATE, atol=None)
    relaxed = floquet_modes(system.state_matrix, **kw)
    strict = floquet_modes(system.state_matrix, root_rtol=1e-6, **kw)
    assert (relaxed.n_sub, strict.n_sub) == (4, 8)
    a = relaxed.exponents[relaxed.exponents.real >= -6.0]
    b = strict.exponents[strict.exponents.real >= -6.0]
    assert a.size == b.size > 40
    assert np.abs(a[:, None] - b[None, :]).min(axis=1).max() < 1e-5


def test_rate_function_is_the_state_matrix_times_the_state():
    # the time march's right-hand side, A(psi) x without building A: equal to
    # state_matrix([psi])[0] @ x to round-off for a periodic system (the new
    # arithmetic); constant and descriptor (first-order state) systems go
    # through state_matrix itself, checked here for the dispatch only.  1e-13
    # relative: two solves of well-conditioned 3 x 3 mass matrices, a few
    # hundred ulps at most
    rng = np.random.default_rng(7)
    psi = 2 * np.pi * np.arange(9) / 9
    base = np.array([[2.0, 0.3, 0.0], [0.3, 1.5, 0.2], [0.0, 0.2, 1.0]])
    m = base + 0.2 * np.sin(psi)[:, None, None] * np.eye(3)
    c = 0.1 * base + 0.05 * np.cos(2 * psi)[:, None, None] * rng.standard_normal((3, 3))
    k = 4 * base + np.cos(psi)[:, None, None] * rng.standard_normal((3, 3))
    desc_m = m.copy()
    desc_m[:, :, 2] = 0.0
    desc_m[:, 2, :] = 0.0
    desc_c = c.copy()
    desc_c[:, 2, 2] = 1.0
    for system in (SecondOrderSystem(m, c, k), SecondOrderSystem(m[:1], c[:1], k[:1]),
                   SecondOrderSystem(desc_m, desc_c, k, n_first=1)):
        f = system.rate_function()
        for p in (0.0, 0.7, 4.1, 9.0):
            x = rng.standard_normal(system.n_states)
            want = system.state_matrix(np.array([p]))[0] @ x
            np.testing.assert_allclose(f(p, x), want, rtol=1e-13,
                                       atol=1e-13 * np.abs(want).max())


def test_transient_coefficients_give_the_same_values_and_keep_nothing():
    # within transient_coefficients (the terms of an energy balance, evaluated
    # once each) the matrices must be bit for bit those of a system that keeps
    # its coefficients -- the same arithmetic -- and nothing is left on the
    # system after the block; a system that had its coefficients keeps them.
    # The interpolant itself is checked at the samples (trigonometric
    # interpolation returns them to round-off, 1e-13 relative)
    psi = 2 * np.pi * np.arange(8) / 8
    rng = np.random.default_rng(3)
    m = np.eye(2) + 0.1 * np.cos(psi)[:, None, None] * np.array([[0, 1], [1, 0]])
    c = 0.05 * rng.standard_normal((8, 2, 2))
    k = np.array([[3.0, 0.2], [0.2, 5.0]]) + 0.3 * np.sin(2 * psi)[:, None, None]
    at = np.array([0.1, 1.3, 5.9])
    fresh = SecondOrderSystem(m, c, k)
    with fresh.transient_coefficients() as same:
        assert same is fresh
        got = [fresh.matrices(at, d) for d in (0, 1, 2)]
    assert "_fourier" not in fresh.__dict__
    for d in (0, 1, 2):
        want = SecondOrderSystem(m, c, k).matrices(at, d)
        for g, w in zip(got[d], want, strict=True):
            assert np.array_equal(g, w)
    kept = SecondOrderSystem(m, c, k)
    kept.matrices(at)
    coefficients = kept.__dict__["_fourier"]
    with kept.transient_coefficients():
        kept.matrices(at, 1)
    assert kept.__dict__["_fourier"] is coefficients
    with fresh.transient_coefficients():
        for g, w in zip(fresh.matrices(psi), (m, c, k), strict=True):
            np.testing.assert_allclose(g, w, rtol=1e-13, atol=1e-13)


def _locked_jordan(sigma, omega):
    """Two coincident damped modes at ``omega`` /rev, one Jordan block: at omega = 1/2
    every multiplier is ``-exp(2 pi sigma)`` and the monodromy matrix is defective."""
    a = np.array([[sigma, -omega, 1.0, 0.0], [omega, sigma, 0.0, 1.0],
                  [0.0, 0.0, sigma, -omega], [0.0, 0.0, omega, sigma]])
    return lambda psi: np.broadcast_to(a, (len(psi), 4, 4))


@pytest.mark.parametrize("sigma", [-0.2, -2.0, -4.5])
def test_roots_at_a_lock_are_snapped_to_the_axis_whatever_the_round_off(sigma):
    # A defective multiplier on the negative real axis is where a k/2 lock forms:
    # round-off moves its roots off the axis by the square root of the machine
    # precision (more for a heavily damped, lifted root), with either sign.  A
    # fixed threshold on the angle made the count of roots (3 or 4 here, as a
    # relative 1e-12 nudge of sigma or omega decided: 9 of 30 draws at sigma -0.2)
    # a matter of round-off; within its accuracy a root is snapped onto the axis,
    # so every draw reads four real roots at exactly 1/2 /rev.
    rng = np.random.default_rng(0)
    for _ in range(30):
        s, w = (v * (1 + 1e-12 * rng.standard_normal()) for v in (sigma, 0.5))
        eta, _ = floquet_motions(_locked_jordan(s, w), 72)
        assert eta.size == 4
        assert np.all(eta.imag == 0.5)              # snapped: exactly k/2, no round-off
        np.testing.assert_allclose(eta.real, sigma, rtol=1e-5)


def test_a_complex_pair_clear_of_the_axis_is_not_snapped():
    # the snap is the root's own accuracy, not a band of frequency: a lightly damped
    # pair 1e-4 /rev from 1/2 /rev stays one complex root (a real root would be two)
    eta, _ = floquet_motions(_oscillator_at(0.5 - 1e-4), 72)
    assert eta.size == 1 and abs(eta.imag[0] - (0.5 - 1e-4)) < 1e-8


def _oscillator_at(omega, sigma=-0.05):
    b = np.array([[0.0, 1.0], [-(sigma**2 + omega**2), 2 * sigma]])
    return lambda psi: np.broadcast_to(b, (len(psi), 2, 2))
