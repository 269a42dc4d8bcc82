"""The time-domain march and its growth fit against known Floquet exponents.

* **Mathieu** ``y_xx + 2 zeta y_x + (a - 2 q cos 2x) y = 0`` in its first
  instability tongue: the exponent is known independently of any time
  stepping from Hill's determinant (Whittaker & Watson, *Modern Analysis*,
  section 19.42): with ``y = e^{-zeta x} u``, ``u`` is Mathieu's with
  ``a' = a - zeta^2`` and ``cosh(pi mu) = 1 - 2 Delta(0) sin^2(pi sqrt(a')/2)``,
  ``Delta(0)`` the (rapidly converging) Hill determinant.
* **The rigid flapping blade in hover**, ``beta'' + (gamma/8) beta' + nu^2
  beta = 0``: growth ``-gamma/16`` in closed form.
* **The rigid flapping blade in forward flight** (periodic coefficients):
  against the Floquet analysis of the same system.
"""

import numpy as np
import pytest

from tefcore.floquet.second_order import SecondOrderSystem
from tefcore.timedomain.march import envelope, fit_growth, march

TWO_PI = 2 * np.pi


def hill_exponent(a, q, zeta, size=40):
    """Growth of the damped Mathieu equation per unit x (Hill's determinant)."""
    a1 = a - zeta**2
    r = np.arange(-size, size + 1)
    d = np.eye(r.size)
    off = q / (4.0 * r**2 - a1)
    d[np.arange(r.size - 1), np.arange(1, r.size)] = off[:-1]
    d[np.arange(1, r.size), np.arange(r.size - 1)] = off[1:]
    rhs = 1 - 2 * np.linalg.det(d) * np.sin(np.pi * np.sqrt(a1) / 2) ** 2
    mu = np.arccosh(abs(rhs)) / np.pi          # |.|: a negative multiplier (period doubling)
    return mu - zeta


def mathieu_system(a, q, zeta):
    """The damped Mathieu equation in psi = 2x: 4 y'' + 4 zeta y' + (a - 2q cos psi) y = 0."""
    psi = np.linspace(0, TWO_PI, 8, endpoint=False)
    ones = np.ones((8, 1, 1))
    return SecondOrderSystem(4 * ones, 4 * zeta * ones, (a - 2 * q * np.cos(psi))[:, None, None])


def fitted(system, x0, revs, first=0, floor=0.0):
    run = march(system, x0, revs)
    psi = np.linspace(0, TWO_PI * revs, 2048 * int(revs) + 1)
    return fit_growth(psi, run.at(psi)[0], first=first, floor=floor), run


def least_stable_state(system):
    res = system.modes(n_steps=288)
    j = int(np.argmax(res.damping_rates))
    return res.damping_rates[j], np.real(res.eigenvectors[:, j] / res.eigenvectors[0, j])


def test_hill_determinant_is_the_floquet_exponent():
    # the reference itself: Hill's determinant against the monodromy (Magnus steps)
    sys_ = mathieu_system(1.0, 0.4, 0.05)
    sigma, _ = least_stable_state(sys_)
    assert sigma == pytest.approx(hill_exponent(1.0, 0.4, 0.05) / 2, abs=1e-6)


@pytest.mark.parametrize("a, q, zeta", [(1.0, 0.4, 0.05), (1.0, 0.25, 0.1), (4.1, 0.9, 0.02)])
def test_mathieu_growth_from_the_envelope(a, q, zeta):
    """Per psi the exponent is half the one per x.  A Floquet solution's envelope
    grows by exactly |lambda| per period, so the fit is exact up to the march's
    error (rtol 1e-10) and the least-squares line: 1e-4 of the rate is 100 times
    the error measured (8e-7)."""
    exact = hill_exponent(a, q, zeta) / 2
    _, x0 = least_stable_state(mathieu_system(a, q, zeta))
    fit, _ = fitted(mathieu_system(a, q, zeta), x0, 6)
    assert fit.rate == pytest.approx(exact, rel=1e-4, abs=1e-6)
    assert fit.revolutions.tolist() == [0, 1, 2, 3, 4, 5]


def test_mathieu_from_a_generic_start_converges_to_the_least_stable_root():
    # from rest plus a push the decaying root dies out (relative e^{-2 mu pi} per
    # period); fitting from the third revolution leaves 1e-3 of it
    a, q, zeta = 1.0, 0.4, 0.05
    fit, _ = fitted(mathieu_system(a, q, zeta), [1.0, 0.0], 8, first=2)
    assert fit.rate == pytest.approx(hill_exponent(a, q, zeta) / 2, rel=0.02)


@pytest.mark.parametrize("gamma, nu", [(8.0, 1.05), (2.0, 1.1), (6.0, 1.15)])
def test_rigid_flapping_blade_in_hover(gamma, nu):
    """beta'' + (gamma/8) beta' + nu^2 beta = 0 decays at -gamma/16 exactly.  The
    per-revolution envelope of an oscillation at about 1 /rev finds its peak
    anywhere in the revolution: an error of at most one cycle's decay in each
    window, which the least squares divides by the span of revolutions --
    measured 8 % over 4 revolutions, at most 1.3 % over 8 (gamma 2-10, nu
    1-1.15).  So 8 revolutions and the agreement criterion, 2 % + 0.01 /rev."""
    one = np.ones((1, 1, 1))
    system = SecondOrderSystem(one, gamma / 8 * one, nu**2 * one)
    fit, _ = fitted(system, [1.0, 0.0], 8, floor=1e-12)
    assert fit.rate == pytest.approx(-gamma / 16, rel=0.02, abs=0.01)
    # and it is not the undamped answer or the damping ratio
    assert abs(fit.rate) > 0.5 * gamma / 16


def flapping_forward_flight(gamma=8.0, nu=1.08, mu=0.4):
    """beta'' + g/8 (1 + 4/3 mu sin psi) beta' + (nu^2 + g/8 (4/3 mu cos psi + mu^2 sin 2psi))
    beta = 0 (uniform inflow, no cut-out; Johnson, Helicopter Theory, ch. 11)."""
    psi = np.linspace(0, TWO_PI, 16, endpoint=False)
    g = gamma / 8
    c = g * (1 + 4 / 3 * mu * np.sin(psi))
    k = nu**2 + g * (4 / 3 * mu * np.cos(psi) + mu**2 * np.sin(2 * psi))
    return SecondOrderSystem(np.ones((16, 1, 1)), c[:, None, None], k[:, None, None])


def test_rigid_flapping_blade_in_forward_flight_locked_at_one_per_rev():
    """nu = 1.15, mu = 0.3: the flapping pair locks at 1 /rev (two real
    multipliers), and the periodic coefficients move the less damped root to
    -0.476, off the hover value -gamma/16.  A real multiplier's solution grows
    by exactly |lambda| each revolution: the fit is exact to the march's error
    (1e-6 relative, 1000 times what was measured)."""
    system = flapping_forward_flight(nu=1.15, mu=0.3)
    sigma, x0 = least_stable_state(system)
    assert abs(sigma - (-0.5)) > 0.02
    fit, _ = fitted(system, x0, 6, floor=1e-9)
    assert fit.rate == pytest.approx(sigma, rel=1e-6)


def test_rigid_flapping_blade_in_forward_flight_oscillatory():
    """nu = 1.35, mu = 0.4: a complex pair at 1.23 /rev, with sigma = -gamma/16
    exactly (Liouville: the two exponents add up to minus the mean damping).
    The shape from 288 Magnus steps is exact to 1e-9 for this one dof, so the
    fit may follow the decay that far (8 revolutions, e^{-25}); the envelope's
    tolerance as in hover.  (Near 1 /rev -- nu = 1.08, 0.957 /rev -- the peak
    drifts slowly through the periodic shape and the per-revolution envelope
    is 9 % off over 8 revolutions: docs/theory.md 12.2.)"""
    system = flapping_forward_flight(nu=1.35, mu=0.4)
    sigma, x0 = least_stable_state(system)
    assert sigma == pytest.approx(-0.5, abs=1e-9)
    fit, _ = fitted(system, x0, 8, floor=1e-9)
    assert fit.rate == pytest.approx(sigma, rel=0.02, abs=0.01)
    assert fit.revolutions.size >= 7


def test_renormalised_march_keeps_a_fast_root_exact():
    # +3 /rev over 10 revolutions: a factor 1e82; the renormalised march keeps
    # the relative error of the closed form e^{3 psi} cos(10 psi)
    one = np.ones((1, 1, 1))
    system = SecondOrderSystem(one, -6 * one, (9 + 100) * one)
    run = march(system, [1.0, 3.0], 10)
    psi = np.array([0.3, 20.0, TWO_PI * 10])
    exact = np.exp(3 * psi) * np.cos(10 * psi)
    assert run.at(psi)[0] == pytest.approx(exact, rel=1e-7)


def test_envelope_uses_whole_revolutions_only():
    psi = np.linspace(0, TWO_PI * 2.5, 2501)
    k, v = envelope(psi, np.exp(psi) * np.cos(3 * psi))
    assert k.tolist() == [0, 1]
    assert v[1] == pytest.approx(np.exp(TWO_PI * 2), rel=1e-3)


def test_fit_stops_at_the_floor():
    psi = np.linspace(0, TWO_PI * 4, 4001)
    signal = np.exp(-1.5 * psi) + 1e-9        # a root that dives under a floor of error
    fit = fit_growth(psi, signal, floor=1e-5)
    assert fit.revolutions.tolist() == [0, 1]
    assert fit.rate == pytest.approx(-1.5, rel=1e-3)
    assert fit_growth(psi, signal).rate > -1.2     # without the floor: the error's plateau
    assert np.isnan(fit_growth(psi[:2000], signal[:2000]).rate)   # one revolution: no fit
