"""The actuator's reflected inertia: it adds to the flap's delta** term and nothing else."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from tefcore.config.io import load_config
from tefcore.model.coupled import Controls, coupled_model
from tefcore.model.flap import flap_natural_frequency, flap_properties
from tefcore.model.jacobian import jacobian_blocks
from tefcore.model.section_response import inertial_hinge_moment, rotor_motion
from tefcore.structure.blade import rotor_units
from tefcore.structure.section_inertia import check_coupled_mass, coupled_mass_matrix

FIG6 = load_config("mdart-fig6")
I_A = FIG6.actuator.reflected_inertia


def _blocks(cfg, q, qd, qdd, controls=None, inflow=0.0):
    model = coupled_model(cfg)
    controls = Controls() if controls is None else controls
    k, c, m = (b[0] for b in jacobian_blocks(
        model, np.zeros(1), q, qd, qdd, controls, lambda x, p: inflow + 0 * x * p,
        scheme="exact", n_second=model.n_dof)[0])
    res, _ = model.evaluate(np.zeros(1), q, qd, qdd, controls, lambda x, p: inflow + 0 * x * p)
    return model, m, c, k, res[:, 0]


@pytest.mark.parametrize("cg", [0.0, 0.33])
def test_flap_alone_in_vacuum_has_the_closed_form_frequency(cg):
    # Rigid, untwisted blade at zero pitch and no motion, air density 1e-12 (the
    # aerodynamic stiffness and apparent mass are ~1e-12 of the structural terms):
    # the flap row of the exact Jacobian is the flap on its actuator,
    # omega_f^2 = [k_a + b_f Omega^2 (I_h - S_f eta_h)] / (b_f I_h + I_a), written here
    # from the configuration's numbers, not from tefcore.model.flap.
    for cfg in (load_config("mdart"), FIG6):
        cfg = cfg.with_overrides({"flight.advance_ratio": 0.0, "blade.twist": 0.0,
                                  "rotor.air_density": 1e-12, "flap.cg_offset": cg})
        n = coupled_model(cfg).n_dof
        z = np.zeros((n, 1))
        _, m, _, k, _ = _blocks(cfg, z, z, z)
        r, f = cfg.rotor, cfg.flap
        c_f = f.chord_ratio * r.chord
        i_h = f.inertia_cg + f.mass * (cg * c_f) ** 2
        s_f, eta = f.mass * cg * c_f, (r.elastic_axis - f.hinge_position) * r.chord
        b_f, om = f.span * r.radius, r.rotor_speed
        expected = np.sqrt((cfg.actuator.stiffness + b_f * om**2 * (i_h - s_f * eta))
                           / (b_f * i_h + cfg.actuator.reflected_inertia)) / om
        # 1e-9: the Gauss rule integrates the constant per-span terms exactly; what
        # is left is the air (1e-12) and round-off
        assert np.sqrt(k[-1, -1] / m[-1, -1]) == pytest.approx(expected, rel=1e-9)
        assert flap_natural_frequency(flap_properties(cfg), om) / om == \
            pytest.approx(expected, rel=1e-12)


def test_reflected_inertia_adds_exactly_to_the_flap_inertia_and_nowhere_else():
    # At an arbitrary motion in an arbitrary pitch and inflow (air as in the
    # tables), the variants differ only by I_a delta**: in the residual's flap row
    # and in M_FF; every other entry of M, C, K is identical to round-off.
    base = load_config("mdart")
    n = coupled_model(base).n_dof
    rng = np.random.default_rng(3)
    q, qd, qdd = (0.01 * rng.standard_normal((n, 1)) for _ in range(3))
    ctl = Controls(0.12, 0.02, -0.03)
    _, m_a, c_a, k_a, r_a = _blocks(base, q, qd, qdd, ctl, 0.04)
    _, m_b, c_b, k_b, r_b = _blocks(FIG6, q, qd, qdd, ctl, 0.04)
    units = rotor_units(FIG6.rotor, FIG6.blade)
    ia = units.inertia(I_A)                      # the flap row is per m0 Omega^2 R^3
    assert ia == pytest.approx(I_A / (units.mass_per_length * FIG6.rotor.radius**3), rel=1e-15)
    dm = m_b - m_a
    assert dm[-1, -1] == pytest.approx(ia, rel=1e-10)
    dm[-1, -1] = 0.0
    scale = np.abs(m_a).max()
    assert np.abs(dm).max() <= 1e-13 * scale
    assert_allclose(c_b, c_a, rtol=0, atol=1e-13 * np.abs(c_a).max())
    assert_allclose(k_b, k_a, rtol=0, atol=1e-13 * np.abs(k_a).max())
    assert r_b[-1] - r_a[-1] == pytest.approx(ia * qdd[-1, 0], rel=1e-9)
    assert_allclose(r_b[:-1], r_a[:-1], rtol=0, atol=1e-14 * np.abs(r_a).max())


def test_residual_pieces_carry_it_as_flap_inertia():
    model = coupled_model(FIG6)
    n = model.n_dof
    qdd = np.zeros((n, 1))
    qdd[-1] = 1.0
    pieces, _ = model.residual_pieces(np.zeros(1), np.zeros((n, 1)), np.zeros((n, 1)), qdd,
                                      Controls(), lambda x, p: 0 * x * p)
    bf_ih = model.flap["inertia_hinge"] * model.flap["span"]
    assert pieces["flap inertia"][-1, 0] == pytest.approx(
        bf_ih + model.flap["reflected_inertia"], rel=1e-12)


@pytest.mark.parametrize("cg", [0.0, 0.33])
def test_coupled_mass_stays_positive_definite(cg):
    cfg = FIG6.with_overrides({"flap.cg_offset": cg})
    model = coupled_model(cfg)                  # runs check_section_inertia, check_coupled_mass
    check_coupled_mass(model)
    m = coupled_mass_matrix(model)
    assert m[-1, -1] == pytest.approx(model.flap["inertia_hinge"] * model.flap["span"]
                                      + model.flap["reflected_inertia"], rel=1e-12)
    assert np.linalg.eigvalsh(m).min() > 0
    # the Schur complement of the flap grows by exactly I_a (rotor units)
    base = coupled_mass_matrix(coupled_model(load_config("mdart").with_overrides(
        {"flap.cg_offset": cg})))

    def schur(a):
        return a[-1, -1] - a[-1, :-1] @ np.linalg.solve(a[:-1, :-1], a[:-1, -1])
    assert schur(m) - schur(base) == pytest.approx(model.flap["reflected_inertia"], rel=1e-9)


def test_section_response_inertial_moment_adds_i_a_delta_accel():
    cfg = FIG6.with_overrides({"flight.advance_ratio": 0.2})
    motion = rotor_motion(cfg.rotor, cfg.blade, advance_ratio=0.2, collective=0.1)
    psi = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    delta, accel = 0.03 * np.cos(4 * psi), -0.03 * 16 * cfg.rotor.rotor_speed**2 * np.cos(4 * psi)
    p = flap_properties(cfg)
    with_a = inertial_hinge_moment(p, motion, psi, delta, accel, rotor_speed=cfg.rotor.rotor_speed)
    p0 = flap_properties(load_config("mdart").with_overrides({"flight.advance_ratio": 0.2}))
    without = inertial_hinge_moment(p0, motion, psi, delta, accel,
                                    rotor_speed=cfg.rotor.rotor_speed)
    # round-off of the two strip sums: ~1e-15 of the moment's amplitude
    assert_allclose(with_a - without, I_A * accel, rtol=0,
                    atol=1e-12 * np.abs(I_A * accel).max())
