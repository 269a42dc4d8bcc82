"""The flap inside its blade section: lumping, inertia checks, chord scaling.

docs/theory.md section 2.7.  Closed forms: the flap's share from discrete point
masses, the host's bound on the flap mass from its determinant, rigid-body
kinetic energies of the assembled finite-element mass.
"""

import math

import numpy as np
import pytest
import scipy.optimize
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from tefcore.config.io import load_config
from tefcore.model.coupled import coupled_model
from tefcore.model.flap import flap_properties
from tefcore.paper.figures.catalogue import FIGURES, figure_config
from tefcore.structure.blade import blade_model, element_nodes, pitch_function, rotor_units
from tefcore.structure.section_inertia import (
    check_coupled_mass,
    check_positive_definite,
    check_section_inertia,
    coupled_mass_matrix,
    flap_mass_limit,
    flap_share,
    host_section,
    lumped_section,
    section_mass_block,
)
from tefcore.units import to_si

MDART = load_config("mdart")
LBFT = to_si(1.0, "lb/ft", "mass_per_length")
# products of a few SI conversions: a few ulp
EPS = 1e-12


# ------------------------------------------------------------- the flap's share


def test_flap_share_equals_point_masses():
    # A flap of two point masses per span, a body m1 at s1 aft of the hinge and a
    # nose weight m2 at s2 ahead (s2 < 0), CG at c_cg: its first and second
    # moments about the elastic axis are sums over the points, independent of the
    # closed forms in flap_share.
    cfg = MDART.with_overrides({"flap.cg_offset": 0.2})
    f, r = cfg.flap, cfg.rotor
    m, c_cg = f.mass_per_span, 0.2 * f.chord_ratio * r.chord
    s1, s2 = 0.05, -0.02
    m1 = m * (c_cg - s2) / (s1 - s2)            # lever rule: m1 s1 + m2 s2 = m c_cg
    m2 = m - m1
    own = m1 * (s1 - c_cg) ** 2 + m2 * (s2 - c_cg) ** 2   # point masses' inertia about the CG
    cfg = cfg.with_overrides({"flap.inertia_cg": own})
    eta_h = (r.elastic_axis - f.hinge_position) * r.chord
    eta = np.array([eta_h - s1, eta_h - s2])     # ahead of the elastic axis
    masses = np.array([m1, m2])
    sh = flap_share(cfg.flap, cfg.rotor)
    assert_allclose(sh.mass, masses.sum(), rtol=EPS)
    assert_allclose(sh.first_moment, masses @ eta, rtol=EPS)
    assert_allclose(sh.inertia, masses @ eta**2, rtol=1e-10)
    assert_allclose(sh.inertia_hinge, masses @ np.array([s1, s2]) ** 2, rtol=1e-10)


def test_lumping_moves_only_first_moment_and_inertia_on_the_flap_span():
    cg = 0.33
    cfg = MDART.with_overrides({"flap.cg_offset": cg})
    f, r = cfg.flap, cfg.rotor
    x = np.array([0.5, f.inboard + 1e-3, f.midspan, f.outboard - 1e-3, 0.95])
    on = np.array([False, True, True, True, False])
    tab, lump = cfg.blade.section(x), lumped_section(cfg, x)
    assert_allclose(lump["mass"], tab["mass"], rtol=0)
    s_f = f.mass_per_span * cg * f.chord_ratio * r.chord
    eta_h = (r.elastic_axis - f.hinge_position) * r.chord
    d_first = lump["mass"] * lump["cg_offset"] - tab["mass"] * tab["cg_offset"]
    assert_allclose(d_first[on], -s_f, rtol=1e-9)
    assert_allclose(d_first[~on], 0.0, atol=0)
    d_inertia = lump["im_lag"] - tab["im_lag"]
    assert_allclose(d_inertia[on], s_f * (cg * f.chord_ratio * r.chord - 2 * eta_h), rtol=1e-9)
    assert_allclose(d_inertia[~on], 0.0, atol=0)
    # the mass-balanced flap is what the tables hold: nothing moves
    for k, v in lumped_section(MDART, x).items():
        assert_allclose(v, MDART.blade.section(x)[k], rtol=0, atol=0)


def test_section_totals_with_and_without_the_flap_offset():
    # host + current flap = lumped section; host + balanced flap = table (totals
    # of mass, first moment, polar inertia at every flap-span station)
    cfg = MDART.with_overrides({"flap.cg_offset": 0.25})
    x = np.linspace(cfg.flap.inboard, cfg.flap.outboard, 7)[:-1]
    host = host_section(cfg, x)
    fl, bal = flap_share(cfg.flap, cfg.rotor), flap_share(cfg.flap, cfg.rotor, balanced=True)
    tab, lump = cfg.blade.section(x), lumped_section(cfg, x)
    for sec, share in ((tab, bal), (lump, fl)):
        assert_allclose(host["mass"] + share.mass, sec["mass"], rtol=EPS)
        assert_allclose(host["first_moment"] + share.first_moment,
                        sec["mass"] * sec["cg_offset"], rtol=1e-9, atol=1e-15)
        assert_allclose(host["inertia"] + share.inertia, sec["im_lag"] + sec["im_flap"],
                        rtol=1e-9)
    assert np.all(host["inertia_cg"] > 0)


def test_structure_and_flap_equation_use_one_set():
    cfg = MDART.with_overrides({"flap.cg_offset": 0.33})
    props, share = flap_properties(cfg), flap_share(cfg.flap, cfg.rotor)
    assert props.mass == share.mass == cfg.flap.mass_per_span
    assert_allclose(props.first_moment, share.first_moment_hinge, rtol=EPS)
    assert_allclose(props.inertia_hinge, share.inertia_hinge, rtol=EPS)
    assert props.hinge_from_ea == share.hinge_from_ea
    model = coupled_model(cfg)
    units = rotor_units(cfg.rotor, cfg.blade)
    assert_allclose(model.flap["first_moment"] * units.mass_per_length * units.radius,
                    share.first_moment_hinge, rtol=1e-12)


def _rigid(beam, field):
    """Global vector of a rigid unit plunge (w) or twist (phi) of the beam.

    The documented dof layout (tefcore.structure.fem): six per node
    ``[u, v, v', w, w', phi]``, then three interior per element
    ``[u(1/3), u(2/3), phi(1/2)]``.
    """
    n_el = beam.n_elements
    v = np.zeros(beam.mass.shape[0])
    nodes = 6 * np.arange(n_el + 1)
    if field == "w":
        v[nodes + 3] = 1.0                  # values 1, slopes 0
    else:
        v[nodes + 5] = 1.0
        v[6 * (n_el + 1) + 3 * np.arange(n_el) + 2] = 1.0
    return v


@pytest.mark.parametrize("cg", [0.0, 0.33])
def test_assembled_mass_integrates_the_lumped_section_exactly(cg):
    # Rigid plunge w = 1 and rigid twist phi = 1: w'Mw = int m dx, phi'M phi =
    # int (I_m1 + I_m2) dx, w'M phi = int m e_g cos(theta) dx (docs/theory.md 2.3),
    # all in rotor units; the reference integrates piece by piece (12-point Gauss
    # between every table station and node).  The element quadrature (6 Gauss
    # points) is exact for properties linear inside an element; the flap's step
    # sits on nodes, but the tables' kinks at 0.19, 0.22, 0.25, 0.55, 0.94, 0.96
    # and 0.99 R fall inside elements: 1.7e-5 measured, hence rtol 1e-4.  The
    # flap's own share is integrated exactly (next test, 1e-9).
    cfg = MDART.with_overrides({"flap.cg_offset": cg})
    beam = blade_model(cfg)
    units = rotor_units(cfg.rotor, cfg.blade)
    w, phi = _rigid(beam, "w"), _rigid(beam, "phi")
    edges = np.unique(np.concatenate([cfg.blade.stations, beam.x_nodes]))
    g, gw = np.polynomial.legendre.leggauss(12)
    xs = (0.5 * (edges[:-1, None] + edges[1:, None])
          + 0.5 * np.diff(edges)[:, None] * g).ravel()
    ws = (0.5 * np.diff(edges)[:, None] * gw).ravel()
    sec = lumped_section(cfg, xs)
    m = units.mass_per_len(sec["mass"])
    e = units.length(sec["cg_offset"])
    im = units.inertia_per_length(sec["im_lag"] + sec["im_flap"])
    th = pitch_function(cfg.blade)(xs)
    assert_allclose(w @ beam.mass @ w, ws @ m, rtol=1e-4)
    assert_allclose(phi @ beam.mass @ phi, ws @ im, rtol=1e-4)
    assert_allclose(w @ beam.mass @ phi, ws @ (m * e * np.cos(th)), rtol=1e-4,
                    atol=1e-4 * abs(ws @ (m * np.abs(e))) + 1e-15)


def test_flap_cg_offset_moves_the_section_cg_in_the_structure():
    # The twist-plunge coupling of the assembled mass changes by -b_f S_f cos(theta)
    # (rotor units) when the flap CG moves aft: the structure sees the flap.
    units = rotor_units(MDART.rotor, MDART.blade)
    a, b = blade_model(MDART), blade_model(MDART.with_overrides({"flap.cg_offset": 0.33}))
    w, phi = _rigid(a, "w"), _rigid(a, "phi")
    f = MDART.flap
    s_f = f.mass_per_span * 0.33 * f.chord_ratio * MDART.rotor.chord
    g, gw = np.polynomial.legendre.leggauss(12)
    xs = 0.5 * (f.inboard + f.outboard) + 0.5 * f.span * g
    expected = -units.mass_per_len(s_f) * units.length(1.0) * (
        0.5 * f.span * gw) @ np.cos(pitch_function(MDART.blade)(xs))
    assert_allclose(w @ (b.mass - a.mass) @ phi, expected, rtol=1e-9)


# --------------------------------------------------------------- inertia checks


def test_a_heavy_flap_is_refused_naming_the_fields_and_the_bound():
    heavy = MDART.with_overrides({"flap.mass": "1.0 lb/ft"})  # a configuration, no physics
    with pytest.raises(ValueError) as err:
        check_section_inertia(heavy)
    msg = str(err.value)
    for word in ("flap.mass = 1.488 kg/m (1 lb/ft)", "flap.inertia_cg", "blade.im_lag",
                 "blade.mass", "does not fit", "Allowed here: flap.mass <"):
        assert word in msg, word
    limit = float(msg.split("flap.mass < ")[1].split(" kg/m")[0])
    assert_allclose(limit, flap_mass_limit(MDART), rtol=1e-3)   # message rounds to 4 digits
    # the bound is sharp: just below fits, just above does not
    check_section_inertia(MDART.with_overrides({"flap.mass": 0.999 * flap_mass_limit(MDART)}))
    with pytest.raises(ValueError, match="does not fit"):
        check_section_inertia(MDART.with_overrides({"flap.mass": 1.001 * flap_mass_limit(MDART)}))
    # where the blade and the coupled model are assembled, the same error
    for assemble in (blade_model, coupled_model):
        with pytest.raises(ValueError, match=r"flap.mass = 1.488 kg/m \(1 lb/ft\) does not fit"):
            assemble(heavy)


def test_flap_mass_limit_is_the_zero_of_the_host_determinant():
    # bisection on the host's m I - S^2 at the flap midspan (the closed form says
    # it is linear in the flap mass; brentq does not use that)
    x = MDART.flap.midspan
    b = MDART.blade.section([x])
    big_m, big_s = b["mass"][0], b["mass"][0] * b["cg_offset"][0]
    big_i = b["im_lag"][0] + b["im_flap"][0]
    eta = flap_share(MDART.flap, MDART.rotor, balanced=True).hinge_from_ea
    i_cg = MDART.flap.inertia_cg_per_span

    def det(m):
        return (big_m - m) * (big_i - i_cg - m * eta**2) - (big_s - m * eta) ** 2

    root = scipy.optimize.brentq(det, 0.0, 0.99 * big_m, xtol=1e-14)
    assert_allclose(flap_mass_limit(MDART, [x]), root, rtol=1e-9)


def test_the_baseline_flap_fits_with_margin():
    # 0.30 lb/ft against a bound of 0.485 lb/ft (mdart.toml im_lag source)
    assert 1.6 < flap_mass_limit(MDART) / MDART.flap.mass_per_span < 1.8
    blocks = section_mass_block(MDART, np.linspace(MDART.flap.inboard, 0.9, 5))
    assert np.all(np.linalg.eigvalsh(blocks)[:, 0] > 0)


def test_every_figure_sweep_value_is_accepted():
    # the baseline and every point the paper's figures sweep must pass the checks
    # (Figs. 8 and 13-15 move the hinge, the flap span and the chord)
    for name, fig in FIGURES.items():
        base = figure_config(name)
        for v in fig.values:
            check_section_inertia(base.with_overrides({fig.parameter: v}))


def test_section_that_cannot_hold_its_cg_offset_is_refused():
    with pytest.raises(ValueError, match=r"blade.im_lag \+ blade.im_flap .* blade.stations\[\d+\]"):
        check_section_inertia(MDART.with_overrides({"blade.cg_offset": "3 in"}))


def test_flap_without_inertia_about_its_hinge_is_refused():
    with pytest.raises(ValueError, match=r"mass block \(w, phi, delta\).*flap.inertia_cg"):
        check_section_inertia(MDART.with_overrides({"flap.inertia_cg": 0.0}))
    # a locked flap (no flap dof) needs no inertia of its own
    check_section_inertia(MDART.with_overrides({"flap.inertia_cg": 0.0, "model.tef": "none"}))


@given(mass=st.floats(0.0, 1.5), inertia=st.floats(0.0, 2e-3), cg=st.floats(-0.3, 0.6),
       overhang=st.floats(0.0, 0.7), chord=st.floats(0.1, 0.5))
@settings(max_examples=60, deadline=None)
def test_check_refuses_exactly_the_impossible_flaps(mass, inertia, cg, overhang, chord):
    # Accepted <=> the host section (table minus balanced flap) has positive
    # mass and inertia about its CG at every flap-span station, and then every
    # per-span (w, phi, delta) block is positive definite; refused with a
    # message naming the flap fields otherwise.
    over = {"flap.mass": mass, "flap.inertia_cg": inertia, "flap.cg_offset": cg,
            "flap.overhang": overhang, "flap.chord_ratio": chord}
    cfg = MDART.with_overrides(over)
    try:
        check_section_inertia(cfg)
    except ValueError as err:
        msg = str(err)
        assert "flap.mass" in msg or "flap.inertia_cg" in msg, msg
        probe = MDART.with_overrides({**over, "flap.mass": 0.0, "flap.inertia_cg": 1e-6})
        x = np.linspace(probe.flap.inboard, probe.flap.outboard, 9)[:-1]
        share = flap_share(probe.flap, probe.rotor, balanced=True)
        b = probe.blade.section(x)
        m_f = mass * probe.flap.chord_scale
        i_f = inertia * probe.flap.chord_scale**3
        eta = share.hinge_from_ea
        det = (b["mass"] - m_f) * (b["im_lag"] + b["im_flap"] - i_f - m_f * eta**2) \
            - (b["mass"] * b["cg_offset"] - m_f * eta) ** 2
        i_h = i_f + m_f * (cg * chord * MDART.rotor.chord) ** 2
        assert det.min() <= 1e-9 * (b["mass"] * (b["im_lag"] + b["im_flap"])).max() \
            or i_h <= 1e-12, msg
        return
    x = np.linspace(cfg.flap.inboard, cfg.flap.outboard, 9)[:-1]
    assert np.all(host_section(cfg, x)["inertia_cg"] > 0)
    assert np.all(np.linalg.eigvalsh(section_mass_block(cfg, x))[:, 0] > 0)


def test_assembled_mass_checks_can_fail():
    with pytest.raises(ValueError, match="not positive definite.*check blade.mass"):
        check_positive_definite(np.array([[1.0, 2.0], [2.0, 1.0]]), "M", "blade.mass")
    with pytest.raises(ValueError, match="not positive definite"):
        check_positive_definite(np.array([[1.0, np.nan], [np.nan, 1.0]]), "M", "blade.mass")
    model = coupled_model(MDART)
    check_coupled_mass(model)
    m = coupled_mass_matrix(model)
    # the modal mass Phi' M Phi is symmetric to round-off (1e-16 of its 0.3 diagonal)
    assert_allclose(m, m.T, rtol=0, atol=1e-14 * np.abs(m).max())
    # a flap whose first moment the section does not contain makes it indefinite
    model.flap = {**model.flap, "first_moment": 1e3 * model.flap["inertia_hinge"]}
    with pytest.raises(ValueError, match="coupled blade/flap mass matrix.*flap.mass"):
        check_coupled_mass(model)


# ----------------------------------------------------------------- chord scaling


def test_construction_scaling_of_flap_mass_and_inertia():
    f0 = MDART.flap
    assert f0.reference_chord_ratio == 0.35 and f0.scaling == "construction"
    wide = MDART.with_overrides({"flap.chord_ratio": 0.5}).flap
    assert_allclose(wide.mass_per_span, f0.mass * 0.5 / 0.35, rtol=EPS)
    assert_allclose(wide.inertia_cg_per_span, f0.inertia_cg * (0.5 / 0.35) ** 3, rtol=EPS)
    # per unit span nothing depends on the span: the flap's total mass goes with it
    long = MDART.with_overrides({"flap.span": 0.22, "flap.midspan": 0.8}).flap
    assert long.mass_per_span == f0.mass_per_span
    tot = [c.mass_per_span * c.span for c in (f0, long)]
    assert_allclose(tot[1] / tot[0], 0.22 / 0.18, rtol=EPS)
    # the flap dynamics see the scaled values
    props = flap_properties(MDART.with_overrides({"flap.chord_ratio": 0.5}))
    assert props.mass == wide.mass_per_span and props.inertia_cg == wide.inertia_cg_per_span


def test_fixed_scaling_and_no_reference_keep_the_per_span_values():
    for over in ({"flap.scaling": "fixed"}, {"flap.reference_chord_ratio": None}):
        f = MDART.with_overrides({**over, "flap.chord_ratio": 0.2}).flap
        assert f.mass_per_span == MDART.flap.mass and f.inertia_cg_per_span == MDART.flap.inertia_cg
    with pytest.raises(ValueError, match="flap.scaling = 'cubic' is not one of"):
        MDART.with_overrides({"flap.scaling": "cubic"})


def test_fig15_sweep_uses_the_construction_rule():
    # Fig. 15's widest flap weighs 0.5/0.35 of the baseline per span
    cfg = figure_config("fig15").with_overrides({"flap.chord_ratio": 0.5})
    assert_allclose(flap_properties(cfg).mass, MDART.flap.mass * 0.5 / 0.35, rtol=EPS)


# ----------------------------------------------------------------- FE mesh


def test_nodes_on_the_flap_edges():
    for mid, span in ((0.83, 0.18), (0.65, 0.18), (0.8, 0.06), (0.91, 0.18)):
        cfg = MDART.with_overrides({"flap.midspan": mid, "flap.span": span})
        nodes = element_nodes(cfg.flap, 20, cfg.rotor.root_offset)
        assert nodes.size == 21 and np.all(np.diff(nodes) > 0)
        assert nodes[0] == cfg.rotor.root_offset and nodes[-1] == 1.0
        for edge in (cfg.flap.inboard, cfg.flap.outboard):
            assert np.min(np.abs(nodes - edge)) < 1e-12
    # two edges inside one element: one node moves, the mesh stays valid
    cfg = MDART.with_overrides({"flap.midspan": 0.8, "flap.span": 0.01})
    nodes = element_nodes(cfg.flap, 20, cfg.rotor.root_offset)
    assert np.all(np.diff(nodes) > 0.05 * (1 - 0.05) / 20)


def test_lumped_blade_modes_converge_with_the_mesh():
    # 20 elements (paper) against 40 with the imbalanced flap lumped: 0.2 %
    # on the first 9 modes (the step sits on nodes in both meshes)
    from tefcore.structure.blade import blade_modes

    cfg = MDART.with_overrides({"flap.cg_offset": 0.33})
    a = blade_modes(cfg, n_elements=20).frequencies
    b = blade_modes(cfg, n_elements=40).frequencies
    assert_allclose(a, b, rtol=2e-3)
    assert math.isfinite(a.sum())
