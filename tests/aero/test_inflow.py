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
