"""Momentum and Drees inflow against closed forms (Leishman, ch. 2 and 3)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from tefcore.aero.inflow import drees_gradients, momentum_inflow, rotor_inflow


def test_hover_momentum():
    assert_allclose(momentum_inflow(0.0072, 0.0), np.sqrt(0.0036), rtol=1e-14)


def test_high_speed_limit_is_glauert():
    # mu >> lambda: lambda_i -> C_T / (2 mu); at mu = 0.4 the correction is
    # (lambda/mu)^2 ~ 2e-4 relative, hence the gate
    ct, mu = 0.008, 0.4
    assert_allclose(momentum_inflow(ct, mu), ct / (2 * mu), rtol=5e-4)


def test_momentum_equation_holds_with_shaft_tilt():
    ct, mu, a = 0.007, 0.25, np.deg2rad(7.3)
    li = momentum_inflow(ct, mu, a)
    lam = mu * np.tan(a) + li
    assert_allclose(li, ct / (2 * np.hypot(mu, lam)), rtol=1e-12)


def test_drees_gradients():
    # hover: no gradient; edgewise flight (chi -> 90 deg): kx -> 4/3 (1 - 1.8 mu^2)
    assert drees_gradients(0.0, 0.05) == (0.0, 0.0)
    kx, ky = drees_gradients(0.3, 1e-12)
    assert_allclose(kx, 4 / 3 * (1 - 1.8 * 0.09), rtol=1e-9)
    assert ky == -0.6


def test_field_and_validation():
    f = rotor_inflow(0.008, 0.2, 0.0)
    assert_allclose(f(0.0, 1.0), f.total)                       # centre of the disk
    assert f(1.0, 0.0) > f(1.0, np.pi)                           # more inflow at the back
    assert rotor_inflow(0.008, 0.2, model="uniform").kx == 0.0
    with pytest.raises(ValueError, match="inflow model"):
        rotor_inflow(0.008, 0.2, model="free-wake")
    with pytest.raises(ValueError, match="finite"):
        momentum_inflow(float("nan"), 0.1)


@pytest.mark.parametrize("ct", [-0.006, -0.001, 1e-5, 0.002, 0.0075, 0.015])
@pytest.mark.parametrize("mu", [1e-3, 0.02, 0.1, 0.3, 0.5])
@pytest.mark.parametrize("alpha_deg", [-12.0, -3.0, 0.0, 4.0, 10.0])
def test_momentum_root_is_the_bracketing_solvers_root(ct, mu, alpha_deg):
    # the safeguarded Newton iteration finds the root scipy's brentq finds on
    # the same bracket (where the bracket holds one); brentq's own xtol is
    # 1e-14, so the two agree to a few 1e-14 -- a wrong slope or a step out of
    # the bracket shows as a different root or a residual of order C_T
    scipy_optimize = pytest.importorskip("scipy.optimize")
    a = np.deg2rad(alpha_deg)
    lam_fs = mu * np.tan(a)

    def g(li):
        return li - ct / (2 * np.hypot(mu, lam_fs + li))

    hover = np.sqrt(abs(ct) / 2)
    lo, hi = (1e-12, 2 * hover) if ct > 0 else (-2 * hover, -1e-12)
    if np.sign(g(lo)) == np.sign(g(hi)):
        with pytest.raises(ValueError, match="no root"):
            momentum_inflow(ct, mu, a)
        return
    expected = scipy_optimize.brentq(g, lo, hi, xtol=1e-14)
    li = momentum_inflow(ct, mu, a)
    assert abs(li - expected) <= 5e-14
    assert abs(g(li)) <= 1e-13


def test_forward_flight_inflow_limits():
    # small mu: hover's sqrt(C_T/2) to O(mu^2 / lambda_h^2) (1.6 % at mu = 0.01
    # with lambda_h = 0.0632: the gate 2 %); large mu: Glauert's C_T / (2 mu)
    ct = 0.008
    assert_allclose(momentum_inflow(ct, 0.01), np.sqrt(ct / 2), rtol=2e-2)
    assert not np.isclose(momentum_inflow(ct, 0.01), np.sqrt(ct / 2), rtol=1e-4)
    assert_allclose(momentum_inflow(-ct, 0.3), -momentum_inflow(ct, 0.3), rtol=1e-13)
