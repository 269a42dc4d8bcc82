"""Flap and actuator dynamics: closed forms and independent derivations."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from tefcore.config.io import load_config
from tefcore.fourier import spectral_derivative
from tefcore.model.flap import (
    FlapProperties,
    centrifugal_hinge_moment,
    flap_natural_frequency,
    flap_properties,
)
from tefcore.model.section_response import SectionMotion, flap_response

OMEGA = 41.05                      # MDART rotor speed [rad/s]


def props(**kw):
    base = dict(span=0.9, radius_mid=4.3, chord=0.254, chord_ratio=0.35, overhang=0.29,
                cg_offset=0.0, hinge_from_ea=-0.1, mass=0.3, inertia_cg=2e-4, k_a=110.0,
                c_a=0.5)
    base.update(kw)
    return FlapProperties(**base)


def point_masses(p: FlapProperties, n=4):
    """Three or more chordwise point masses with the flap's m_f, S_f and I_h."""
    s = np.linspace(-0.3, 1.2, n) * p.flap_chord           # along the flap chord, aft +
    # solve for masses matching the three moments (least-norm, all moments exact)
    a = np.vstack([np.ones(n), s, s**2])
    m = np.linalg.lstsq(a, [p.mass, p.first_moment, p.inertia_hinge], rcond=None)[0]
    return s, m


def centrifugal_potential(p, pitch, delta, s, m):
    """-1/2 Omega^2 sum m y^2 of point masses on the pitched flap.

    The radial part x^2 does not depend on delta on a rigid unflapped section,
    and leaving it out avoids cancellation in the finite difference.
    """
    phi = pitch + delta
    y = p.hinge_from_ea * np.cos(pitch) - s * np.cos(phi)
    return -0.5 * OMEGA**2 * np.sum(m * y**2)


@pytest.mark.parametrize("cg", [0.0, 0.2, 0.33])
@pytest.mark.parametrize("pitch", [0.0, 0.15, -0.1])
def test_centrifugal_moment_is_gradient_of_point_mass_potential(cg, pitch):
    # Independent of the symbolic derivation: the moment on the flap is
    # dV/d delta of the centrifugal potential of discrete masses with the same
    # m, S and I.  Central differences with h = 1e-6 are accurate to ~1e-9.
    p = props(cg_offset=cg)
    s, m = point_masses(p)
    for delta in (0.0, 0.05, -0.08):
        h = 1e-6
        fd = (centrifugal_potential(p, pitch, delta + h, s, m)
              - centrifugal_potential(p, pitch, delta - h, s, m)) / (2 * h)
        assert_allclose(centrifugal_hinge_moment(p, OMEGA, pitch, delta), fd, rtol=1e-6,
                        atol=1e-9)


def test_mass_balanced_flap_frequency_adds_one_per_rev_squared():
    # S_f = 0, zero pitch: omega^2 = k_a / (b I_h) + Omega^2 (propeller moment)
    p = props()
    expected = np.sqrt(p.k_a / (p.span * p.inertia_hinge) + OMEGA**2)
    assert_allclose(flap_natural_frequency(p, OMEGA), expected, rtol=1e-12)


def test_cg_offset_lowers_flap_frequency_and_raises_hinge_inertia():
    # Paper, Fig. 9a: "the moment of inertia of flap increases with flap CG
    # offset and the actuator stiffness is kept same"
    f = [flap_natural_frequency(props(cg_offset=c), OMEGA) for c in (0.0, 0.1, 0.2, 0.33)]
    ih = [props(cg_offset=c).inertia_hinge for c in (0.0, 0.1, 0.2, 0.33)]
    assert np.all(np.diff(f) < 0) and np.all(np.diff(ih) > 0)


def test_stiffer_actuator_raises_frequency_less_for_unbalanced_flap():
    # Fig. 12a: "the mass-imbalanced flap shows smaller variation slope"
    k = np.array([0.5, 1.0, 1.5, 2.0]) * 110.0
    bal = [flap_natural_frequency(props(k_a=x), OMEGA) for x in k]
    unb = [flap_natural_frequency(props(k_a=x, cg_offset=0.33), OMEGA) for x in k]
    assert np.all(np.diff(bal) > 0) and np.all(np.diff(unb) > 0)
    assert bal[-1] - bal[0] > unb[-1] - unb[0]


class NoAero:
    """A section model with no aerodynamic loads (vacuum)."""

    def loads(self, **kw):
        return {"hinge_moment": np.zeros_like(np.asarray(kw["delta"], float))}


def still_section(psi_fn_pitch=0.0):
    def z(p):
        return np.zeros_like(np.asarray(p, float))
    motion = SectionMotion(velocity=lambda p: z(p) + 100.0, alpha=z, alpha_rate=z,
                           alpha_accel=z, plunge_rate=z, plunge_accel=z,
                           pitch=lambda p: z(p) + psi_fn_pitch, pitch_accel=z,
                           flap_slope=z, flap_accel=z)
    return lambda r: motion


@pytest.mark.parametrize("harmonic", [1, 4, 7])
def test_vacuum_response_equals_single_dof_transfer_function(harmonic):
    # Harmonic input delta_a = A cos(n psi) on a flap in vacuum with zero pitch:
    # delta = A (k_a + i c_a w) / (k_a + b k_cf - b I_h w^2 + i c_a w), w = n Omega.
    # The centrifugal moment is nonlinear (sin Phi cos Phi); at 1e-4 rad its
    # relative effect is ~1e-10, and Fourier collocation is exact for the
    # band-limited linear response, so the gate is 1e-7 of the amplitude.
    p = props(c_a=2.0, cg_offset=0.2)
    amp = 1e-4
    out = flap_response(NoAero(), p, still_section(), lambda q: amp * np.cos(harmonic * q),
                        rotor_speed=OMEGA, density=1.225, speed_of_sound=340.0, n_psi=32)
    w = harmonic * OMEGA
    k_cf = OMEGA**2 * (p.inertia_hinge - p.first_moment * p.hinge_from_ea)
    tf = (p.k_a + 1j * p.c_a * w) / (p.k_a + p.span * k_cf - p.span * p.inertia_hinge * w**2
                                      + 1j * p.c_a * w)
    expected = np.real(amp * tf * np.exp(1j * harmonic * out.psi))
    assert_allclose(out.delta_f, expected, atol=1e-7 * amp)
    # power = actuator torque times base rate; it averages to the damper loss
    assert out.mean_power > 0


def test_rigid_actuator_limit_follows_the_input():
    # "If the actuator is infinitely rigid, the flap response should be
    # identical with the actuator input" (paper, Fig. 6 discussion)
    p = props(k_a=1e9)
    f = lambda q: np.deg2rad(2) * np.cos(4 * q - np.deg2rad(240))  # noqa: E731
    out = flap_response(NoAero(), p, still_section(), f, rotor_speed=OMEGA, density=1.225,
                        speed_of_sound=340.0, n_psi=32)
    assert_allclose(out.delta_f, out.delta_a, atol=1e-6 * np.deg2rad(2))


def test_spectral_derivative_of_mixed_harmonics():
    psi = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    f = 0.3 + np.cos(2 * psi) - 0.5 * np.sin(5 * psi)
    assert_allclose(spectral_derivative(24) @ f, -2 * np.sin(2 * psi) - 2.5 * np.cos(5 * psi),
                    atol=1e-12)


def test_mdart_flap_geometry():
    p = flap_properties(load_config("mdart"))
    # Table 1: 35 % chord flap, hinge 29 % of the flap chord behind its nose:
    # 0.65 c + 0.1015 c = 0.7515 c from the leading edge, EA at 0.25 c
    assert_allclose(p.hinge_from_ea, (0.25 - 0.7515) * 0.254, rtol=1e-12)
    assert p.first_moment == 0.0                      # mass-balanced baseline


def test_aerodynamic_balance_cuts_actuation_power_and_raises_response():
    # Section level, thin-airfoil aerodynamics: the overhang moves the hinge
    # toward the flap's centre of pressure, so for the same actuator input the
    # hinge moment the actuator fights falls (less power) and the flap follows
    # the aerodynamic load further (larger response) - the mechanism of Fig. 7.
    from tefcore.model.section_response import section_overhang_study

    cfg = load_config("mdart")
    f = lambda q: np.deg2rad(2) * np.cos(4 * q - np.deg2rad(240))  # noqa: E731
    out = section_overhang_study(cfg, [0.0, 0.15, 0.29], f, n_psi=48,
                                 controls=dict(advance_ratio=0.2, collective=0.09,
                                               cyclic_sin=-0.06, inflow=0.02))
    assert np.all(np.diff(out["peak_power"]) < 0)
    assert np.all(np.diff(out["half_peak_to_peak_deg"]) > 0)
