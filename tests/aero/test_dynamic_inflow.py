"""Tests of tefcore.aero.dynamic_inflow: Pitt-Peters three-state dynamic inflow."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from tefcore.aero.dynamic_inflow import (
    APPARENT_MASS,
    apparent_mass,
    l_matrix,
    mass_flow,
    perturbation_matrices,
    steady_inflow,
    wake_skew,
)
from tefcore.aero.inflow import momentum_inflow


@pytest.mark.parametrize("ct", [0.002, 0.0064, 0.012])
def test_hover_is_momentum_theory(ct):
    st = steady_inflow(ct, advance_ratio=0.0)
    assert_allclose(st.mean, math.sqrt(ct / 2), rtol=1e-12)     # lambda = sqrt(C_T / 2)
    assert st.sine == 0.0 and st.cosine == 0.0 and st.chi == 0.0
    assert_allclose([st.v_total, st.v_mass], [st.mean, 2 * st.mean], rtol=1e-12)
    # a roll / pitch moment in hover: lambda_s = C_s / (2 lambda_0 / 2) = L22 C_s / v
    st2 = steady_inflow(ct, 1e-4, -2e-4, advance_ratio=0.0)
    assert_allclose([st2.sine, st2.cosine], np.array([1e-4, -2e-4]) * 2 / (2 * st.mean),
                    rtol=1e-12)


@pytest.mark.parametrize(("mu", "alpha_s_deg"), [(0.1, 2.0), (0.3, 7.3), (0.3, -1.0)])
def test_forward_flight_mean_is_glauert(mu, alpha_s_deg):
    ct = 0.0064
    st = steady_inflow(ct, advance_ratio=mu, shaft_angle=math.radians(alpha_s_deg))
    assert st.mean == momentum_inflow(ct, mu, math.radians(alpha_s_deg))
    lam = st.freestream + st.mean
    # lambda_0 = C_T / (2 v_T): Glauert, to the root finder's tolerance (xtol 1e-14)
    assert_allclose(st.mean, ct / (2 * math.hypot(mu, lam)), rtol=1e-10)


@pytest.mark.parametrize("chi_deg", [0.0, 15.0, 45.0, 73.0, 90.0])
def test_l_matrix_published_entries(chi_deg):
    # Pitt & Peters (1981), written with cos(chi) (their moments have the other sign,
    # hence |.| on the moment rows), and the disk-angle form of Peters & HaQuang (1988),
    # sin(alpha_d) = cos(chi), sqrt((1 - sin a)/(1 + sin a)) = tan(chi/2).
    chi = math.radians(chi_deg)
    ell = l_matrix(chi)
    cos = math.cos(chi)
    assert_allclose(ell[0, 0], 0.5, rtol=1e-15)
    assert_allclose(ell[1, 1], 4 / (1 + cos), rtol=1e-13)
    assert_allclose(ell[2, 2], 4 * cos / (1 + cos), rtol=1e-13, atol=1e-15)
    sin_ad = cos
    coupling = 15 * math.pi / 64 * math.sqrt((1 - sin_ad) / (1 + sin_ad))
    assert_allclose([ell[2, 0], -ell[0, 2]], [coupling, coupling], rtol=1e-12, atol=1e-15)
    assert ell[0, 1] == ell[1, 0] == ell[1, 2] == ell[2, 1] == 0.0


def test_l_matrix_edgewise_values():
    # chi = 90 deg: X = 1; L = [[1/2, 0, -15 pi/64], [0, 4, 0], [15 pi/64, 0, 0]]
    assert_allclose(l_matrix(math.pi / 2),
                    [[0.5, 0, -15 * math.pi / 64], [0, 4, 0], [15 * math.pi / 64, 0, 0]],
                    atol=1e-15)


@pytest.mark.parametrize(("mu", "alpha_s_deg"), [(0.05, 0.0), (0.2, 3.0), (0.3, 7.3)])
def test_longitudinal_gradient_is_pitt_peters(mu, alpha_s_deg):
    # kappa_x = lambda_c / lambda_0 = (15 pi / 32) tan(chi / 2) (Pitt & Peters 1981,
    # as tabulated in Leishman, Principles of Helicopter Aerodynamics, ch. 10);
    # more downwash at the rear of the disk; no lateral gradient from thrust alone.
    st = steady_inflow(0.0064, advance_ratio=mu, shaft_angle=math.radians(alpha_s_deg))
    assert st.cosine > 0 and st.sine == 0.0
    assert_allclose(st.cosine / st.mean, 15 * math.pi / 32 * math.tan(st.chi / 2), rtol=1e-12)
    inflow = st.to_inflow()
    assert_allclose(inflow(1.0, 0.0) - inflow.freestream, st.mean + st.cosine, rtol=1e-12)


@pytest.mark.parametrize("kind", sorted(APPARENT_MASS))
def test_hover_time_constants(kind):
    # Hover: L = diag(1/2, 2, 2), v = 2 lambda_0: tau_0 = M11 / (4 lambda_0) (8/(3 pi) =
    # 0.849 for the impermeable disk), tau_1 = 16/(45 pi) * 2 / (2 lambda_0).
    st = steady_inflow(0.008, advance_ratio=0.0)
    lam0 = st.mean
    tau = perturbation_matrices(st, kind).time_constants
    m1 = APPARENT_MASS[kind]
    expected = sorted([m1 / (4 * lam0), 16 / (45 * math.pi) / lam0,
                       16 / (45 * math.pi) / lam0], reverse=True)
    assert_allclose(tau, expected, rtol=1e-12)
    assert_allclose(APPARENT_MASS["peters_haquang"], 0.8488263631567751, rtol=1e-15)


@pytest.mark.parametrize(("mu", "alpha_s_deg"), [(0.0, 0.0), (0.15, 2.0), (0.3, 7.3)])
def test_mean_perturbation_is_linearised_momentum(mu, alpha_s_deg):
    # d lambda_0 / d C_T at fixed mu, shaft angle from momentum theory (central
    # difference of momentum_inflow, error ~ h^2 ~ 1e-10) equals the quasi-static mean
    # response (L V^-1)[0, 0] = L11 / v = 1 / (2 v): the mass-flow parameter is the
    # exact linearisation (the mean does not respond to lambda_c).
    a_s = math.radians(alpha_s_deg)
    ct, h = 0.0064, 1e-6
    dl = (momentum_inflow(ct + h, mu, a_s) - momentum_inflow(ct - h, mu, a_s)) / (2 * h)
    lin = perturbation_matrices(steady_inflow(ct, advance_ratio=mu, shaft_angle=a_s))
    assert_allclose(np.linalg.inv(lin.damping)[0, 0], dl, rtol=1e-7)
    assert_allclose(dl, 1 / (2 * lin.v_mass), rtol=1e-7)
    assert_allclose(lin.damping, lin.v_mass * np.linalg.inv(lin.l), rtol=1e-14)


def test_forward_flight_inflow_decays():
    # all inflow modes decay (the eigenvalues of -M^-1 V L^-1 have negative real parts)
    # in forward flight, where L is not symmetric
    lin = perturbation_matrices(steady_inflow(0.0064, advance_ratio=0.3,
                                              shaft_angle=math.radians(7.3)))
    a, b = lin.state_matrices()
    assert np.all(np.linalg.eigvals(a).real < 0)
    assert_allclose(b, np.linalg.inv(apparent_mass()), rtol=1e-15)


def test_validation():
    with pytest.raises(ValueError, match="chi"):
        l_matrix(-0.1)
    with pytest.raises(ValueError, match="apparent mass"):
        apparent_mass("theodorsen")
    with pytest.raises(ValueError, match="positive thrust"):
        steady_inflow(0.0, advance_ratio=0.0)
    with pytest.raises(ValueError, match="advance_ratio"):
        steady_inflow(0.005, advance_ratio=-0.1)
    with pytest.raises(ValueError, match="finite"):
        steady_inflow(float("nan"), advance_ratio=0.1)
    with pytest.raises(ValueError, match="no flow"):
        mass_flow(0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="hover needs"):
        wake_skew(0.0, 0.0)
