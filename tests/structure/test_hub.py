"""The bearingless hub as multiple load paths (docs/theory.md section 2.5a).

Flexbeam, torque tube and main blade joined at the clevis, the pitch link
and the snubber (:func:`tefcore.structure.blade.multiple_load_path_model`, assembled by
:mod:`tefcore.structure.branched`).  Checks against the single-load-path model it must
reduce to, against closed forms of the torsion load paths (static and
dynamic) and of the pitch-link kinematics, the modal invariants, and the
input validation.  No published bearingless-hub or branched-beam case with
its numbers could be retrieved (searched: Sivaneri & Chopra's bearingless
element, Magari, Shultz & Murthy's multiple-load-path NASTRAN element
(Comput. Struct. 29(5) 1988), Nguyen's UMARC MDART study NASA TM-112912: the
stored copies give abstracts only); the exact twin-cantilever reduction of
the :mod:`tefcore.structure.branched` docstring stands in as a branched closed form.
"""

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from tefcore.config.configuration import SECTIONS
from tefcore.config.io import load_config
from tefcore.paper.calibration import frequency_checks, lag_damping_ratio, mode_frequency
from tefcore.structure.blade import (
    blade_modes,
    element_nodes,
    multiple_load_path_model,
    pitch_function,
    root_springs,
    rotor_units,
    section_function,
)
from tefcore.structure.branched import Component, Joint, assemble_branched
from tefcore.structure.fem import RootSprings, assemble_beam, beam_modes, tension_piecewise_linear
from tefcore.structure.hub_models import (
    kinematic_pitch_ratio,
    pitch_flap_delta3,
    pitch_input_response,
)

MDART = load_config("mdart")
MLP = MDART.with_overrides({"hub.model": "multiple_load_path"})


def _mac(a, b, m):
    return np.abs(np.sum(a * (m @ b), axis=0)) / np.sqrt(
        np.sum(a * (m @ a), axis=0) * np.sum(b * (m @ b), axis=0))


# --------------------------------------------------- reduction to a single path

def _uniform_inboard(cfg):
    """MDART with the blade tables uniform from the root to the clevis (0.05-0.19 R)
    and the flexbeam given exactly those properties: the single-path blade."""
    b = cfg.blade
    n_in = int(np.searchsorted(b.stations, cfg.flexbeam.clevis + 1e-12))   # stations <= clevis
    over = {}
    for name in ("mass", "ei_flap", "ei_lag", "gj", "ea", "im_flap", "im_lag", "ka"):
        arr = np.array(getattr(b, name), float)
        arr[:n_in] = arr[0]
        over[f"blade.{name}"] = arr
    c = cfg.with_overrides(over)
    s = c.blade.section([c.rotor.root_offset])
    return c.with_overrides({"flexbeam.mass": s["mass"][0], "flexbeam.ei_flap": s["ei_flap"][0],
                             "flexbeam.ei_lag": s["ei_lag"][0], "flexbeam.gj": s["gj"][0],
                             "flexbeam.ea": s["ea"][0], "flexbeam.im_flap": s["im_flap"][0],
                             "flexbeam.im_lag": s["im_lag"][0], "flexbeam.ka": s["ka"][0]})


@pytest.mark.parametrize("collective_deg", [0.0, 8.0])
def test_branched_model_without_torque_tube_is_the_single_path_blade(collective_deg):
    # The torque tube removed, the flexbeam given the blade's properties and the
    # equivalent root springs at its root: the branched assembly (a joint at the
    # clevis, the flexbeam's own tension and elastic wind-up) must be the single
    # beam on the same nodes -- the same matrices up to the order of the sums.
    # Gates: frequencies 1e-9 relative and shapes 1e-8 (round-off of two
    # eigen-solutions of a pencil with cond(K) ~ 1e9; seen: ~1e-12).
    coll = np.deg2rad(collective_deg)
    cfg = _uniform_inboard(MLP)
    theta_root = float(pitch_function(cfg.blade, coll)(cfg.rotor.root_offset))
    cfg = cfg.with_overrides({"flexbeam.precollective": theta_root})
    units = rotor_units(cfg.rotor, cfg.blade)
    root = root_springs(cfg.hub, units)
    branched = multiple_load_path_model(cfg, coll, 20, torque_tube=False, root=root)
    nodes = np.concatenate([branched.components["flexbeam"].x_nodes,
                            branched.components["blade"].x_nodes[1:]])
    sec = section_function(cfg, units)
    stations = np.asarray(cfg.blade.stations, float)
    single = assemble_beam(nodes, sec, pitch_function(cfg.blade, coll), root,
                           tension=tension_piecewise_linear(stations, sec(stations)["mass"]))
    a, b = beam_modes(branched, 12), beam_modes(single, 12)
    assert a.labels == b.labels
    assert_allclose(a.frequencies, b.frequencies, rtol=1e-9)
    x = np.linspace(cfg.rotor.root_offset, 1.0, 41)
    sa, sb = a.shapes(x), b.shapes(x)
    for f in ("w", "v", "phi", "dw", "dv"):
        assert_allclose(sa[f], sb[f], atol=1e-8)
    assert_allclose(a.modal_damping, b.modal_damping, atol=1e-10)
    assert_allclose(a.modal_gyroscopic, b.modal_gyroscopic, atol=1e-10)


def test_single_path_limit_is_close_to_the_equivalent_hub():
    # The same single-path blade with the default mesh (20 equal elements from
    # the root) against the reduced branched one (4 flexbeam + 16 blade
    # elements): the mesh is all that differs.  The default mesh has no node
    # on the tables' kink at the clevis (0.19 R; its node is at 0.1925 R), so
    # the quadrature of that element is not exact: measured 7.0e-4 on lag 1,
    # gate 1e-3 (a root spring off by 1 % moves lag 1 by 0.4 %, flap 1 by 0.2 %).
    cfg = _uniform_inboard(MLP)
    cfg = cfg.with_overrides({"flexbeam.precollective": float(
        pitch_function(cfg.blade, 0.0)(cfg.rotor.root_offset))})
    eq = blade_modes(cfg.with_overrides({"hub.model": "equivalent"}))
    root = root_springs(cfg.hub, rotor_units(cfg.rotor, cfg.blade))
    br = beam_modes(multiple_load_path_model(cfg, 0.0, 20, torque_tube=False, root=root), 9)
    assert br.labels == eq.labels
    assert_allclose(br.frequencies, eq.frequencies, rtol=1e-3)


def test_two_proportional_cantilevers_joined_at_the_tip_are_one():
    # Euler-Bernoulli: two beams clamped at the root and joined at the tip,
    # with the same ratio of mass to stiffness, deform alike, so they are one
    # beam with the sums of their properties -- exact, also in the finite
    # elements on the same mesh (round-off gate 1e-9).
    def sec(k):
        def f(x):
            x = np.asarray(x, float)
            p = dict(mass=k, ei_flap=0.02 * k, ei_lag=0.5 * k, gj=0.01 * k, ea=50.0 * k,
                     im_flap=1e-5 * k, im_lag=1e-3 * k, cg_offset=0.0, tension_offset=0.0,
                     ka=0.0)
            return {n: np.full_like(x, v) for n, v in p.items()}
        return f

    def flat(x):
        return np.zeros_like(np.asarray(x, float))

    def pitch(x):
        return 0.1 + 0.0 * np.asarray(x, float)

    nodes = np.linspace(0.1, 0.4, 5)
    blade = np.linspace(0.4, 1.0, 7)
    twin = assemble_branched(
        [Component("a", nodes, sec(1.0), pitch, flat), Component("b", nodes, sec(3.0), pitch, flat),
         Component("blade", blade, sec(0.7), pitch, flat)],
        joints=[Joint("a", 4, "b", 4), Joint("a", 4, "blade", 0)],
        clamps=[("a", 0), ("b", 0)], span=("blade", "a"))
    one = assemble_beam(np.concatenate([nodes, blade[1:]]),
                        lambda x: sec(np.where(np.asarray(x) < 0.4 - 1e-12, 4.0, 0.7))(x),
                        pitch, RootSprings(np.inf, np.inf, np.inf), tension=flat)
    fa, fb = (beam_modes(b, 8).frequencies for b in (twin, one))
    assert_allclose(fa, fb, rtol=1e-9)


# ------------------------------------------------------- torsion load paths

def _decoupled(cfg, **extra):
    """The torsion paths free of bending: link at the horn station, vertical, and the
    torque tube's inboard end held vertically (snubber flap stiffness 1e12 N/m, a
    relative compliance of ~1e-9 beside the pitch link)."""
    over = {"pitch_link.radial_offset": 0.0, "pitch_link.cant": 0.0,
            "snubber.flap_stiffness": 1e12}
    return cfg.with_overrides({**over, **extra})


@pytest.mark.parametrize("extra", [{}, {"hub.pitch_link_stiffness": "800 lb/in"},
                                   {"snubber.torsion_stiffness": "300 ft*lbf/rad",
                                    "torque_tube.gj": "2000 lbf*ft^2"},
                                   {"pitch_link.horn_arm": "3 in", "flexbeam.gj": "900 lbf*ft^2"}])
def test_unit_pitch_input_twists_the_blade_by_the_kinematic_ratio(extra):
    # Nonrotating statics: the swashplate moves the link's lower end by one
    # radian times the horn arm.  The link (k a^2), the snubber in pitch, the
    # torque tube (GJ/L) and the flexbeam (GJ/L) form a spring network whose
    # clevis rotation is the closed form of kinematic_pitch_ratio; the blade,
    # free outboard, turns rigidly with the clevis.  Uniform GJ twists
    # linearly, which the quadratic torsion elements represent exactly:
    # round-off and the 1e-9 flap compliance of the horn only (measured
    # 1.8e-9; gate 1e-7).
    cfg = _decoupled(MLP, **extra)
    r = pitch_input_response(cfg, rotating=False)
    ratio = kinematic_pitch_ratio(cfg)
    assert 0.0 < ratio < 1.0
    assert_allclose(r["blade_twist"], ratio, rtol=1e-7)
    assert_allclose(r["tip_twist"], ratio, rtol=1e-7)
    # the torque tube winds up between horn and clevis: the horn turns more
    assert r["horn_twist"] > r["clevis_twist"] > 0


def test_mdart_pitch_input_with_the_real_horn_support():
    # With the MDART snubber (1e5 lb/in vertically) the horn yields under the
    # link load: the link acts as k_PL in series with the horn's support
    # k_sup = k_snubber + k_structure.  The closed form with that series
    # stiffness must give the finite-element twist; the structure's own
    # vertical stiffness at the horn (~3 EI/L^3 of the flexbeam, < 1e-3 of
    # the snubber's) is left out, so the gate is 1e-6 against a 1e-4 effect.
    real = pitch_input_response(MLP, rotating=False)["blade_twist"]
    k_pl, k_sup = MLP.hub.pitch_link_stiffness, MLP.snubber.flap_stiffness
    series = MLP.with_overrides({"hub.pitch_link_stiffness": k_pl * k_sup / (k_pl + k_sup)})
    assert_allclose(real, kinematic_pitch_ratio(series), rtol=1e-6)
    assert real < kinematic_pitch_ratio(MLP) * (1 - 5e-5)


def _uniform_torsion_blade(cfg):
    """Uniform, untwisted blade in torsion; hub beams almost without torsional inertia."""
    return cfg.with_overrides({
        "blade.gj": "20000 lbf*ft^2", "blade.im_lag": "16 lbm*in^2/ft", "blade.im_flap": 0.0,
        "blade.twist": 0.0, "flexbeam.im_lag": 1e-9, "flexbeam.im_flap": 1e-9,
        "torque_tube.im_lag": 1e-9, "torque_tube.im_flap": 1e-9, "flap.cg_offset": 0.0})


def test_first_torsion_frequency_of_the_load_path_network():
    # Nonrotating: a uniform rod (GJ, I) of length L free at the tip on a root
    # spring K has (GJ/L) lam tan(lam) = K, omega = lam sqrt(GJ/I)/L, with K the
    # flexbeam in parallel with torque tube and link in series (the closed form
    # of kinematic_pitch_ratio).  The hub beams carry ~no torsional inertia
    # here.  Quadratic elements on 13 blade elements: 1e-6 (measured 3e-8).
    cfg = _decoupled(_uniform_torsion_blade(MLP))
    beam = multiple_load_path_model(cfg)
    f = beam.free
    k, m = beam.k_elastic[f][:, f], beam.mass[f][:, f]
    lam = 1.0 / scipy.linalg.eigh(m, k, eigvals_only=True)[::-1]
    units = rotor_units(cfg.rotor, cfg.blade)
    r = kinematic_pitch_ratio(cfg, parts=True)
    big_k = units.spring(r["root_stiffness"])
    length = 1.0 - cfg.flexbeam.clevis
    gj = units.bending_stiffness(cfg.blade.gj[0])
    # the balanced flap's share is part of the tables (section_inertia): I is the table's
    inertia = units.inertia_per_length(cfg.blade.im_lag[0])
    root = scipy.optimize.brentq(lambda x: gj / length * x * np.tan(x) - big_k, 1e-9,
                                 np.pi / 2 - 1e-12)
    omega = root * np.sqrt(gj / inertia) / length
    torsion = [np.sqrt(x) for x in lam if abs(np.sqrt(x) - omega) < 0.05 * omega]
    assert len(torsion) == 1
    assert_allclose(torsion[0], omega, rtol=1e-6)


@pytest.mark.parametrize(("arm_in", "offset_in"), [(-5.56, 2.0), (5.56, 2.0), (4.0, -1.5)])
def test_rigid_link_pitch_flap_coupling_is_delta3(arm_in, offset_in):
    # A rigid pitch link and a horn held vertically: flapping the torque tube
    # by w' at the horn turns it by -w' d/a (d radial offset of the link
    # attachment, a horn arm), i.e. pitch-flap coupling tan(delta_3) = d/a,
    # positive (flap up, pitch down) for a leading-edge horn with the link
    # outboard of the horn station.  Static tip flap load, nonrotating;
    # penalty 1e9 N/m link against ~1e3 N/m of the structure: gate 1e-5.
    cfg = _decoupled(MLP, **{"pitch_link.horn_arm": f"{arm_in} in",
                             "pitch_link.radial_offset": f"{offset_in} in",
                             "hub.pitch_link_stiffness": 1e9})
    beam = multiple_load_path_model(cfg)
    f = beam.free
    load = beam.rows("blade", [1.0])["w"][0]
    q = np.zeros(beam.n_dof)
    q[f] = np.linalg.solve(beam.k_elastic[f][:, f], load[f])
    xt = cfg.torque_tube.inboard
    horn = beam.component_fields("torque_tube", q, [xt])
    slope, twist = horn["dw"][0, 0], horn["phi"][0, 0]
    assert abs(slope) > 0
    tan_d3 = np.tan(pitch_flap_delta3(cfg.hub, cfg.pitch_link))
    assert_allclose(tan_d3, offset_in / arm_in, rtol=1e-12)
    assert_allclose(-twist / slope, tan_d3, rtol=1e-5)


# ------------------------------------------------------------ modal invariants

@pytest.mark.parametrize("speed_ratio", [0.6, 1.0])
def test_modes_are_mass_and_stiffness_orthogonal(speed_ratio):
    # The eigenvectors of the symmetric pencil (K, M) are M- and K-orthogonal;
    # round-off gate 1e-10 of the diagonal (seen ~1e-14).
    beam = multiple_load_path_model(MLP.with_overrides({"flap.cg_offset": 0.33}),
                                    np.deg2rad(8.0))
    m = beam_modes(beam, 12, speed_ratio)
    for mat in (m.modal_mass, m.modal_stiffness):
        d = np.sqrt(np.abs(np.outer(np.diag(mat), np.diag(mat))))
        off = np.abs(mat - np.diag(np.diag(mat))) / d
        assert off.max() < 1e-10
    assert_allclose(np.diag(m.modal_stiffness) / np.diag(m.modal_mass), m.frequencies**2,
                    rtol=1e-10)


def test_snubber_damper_enters_the_modal_damping():
    # C = c b b^T over the snubber's lag row, c = eta K' / omega_ref: Phi^T C Phi
    # from the coupling equals the modal damping; no loss, no damping at all.
    beam = multiple_load_path_model(MLP)
    m = beam_modes(beam, 9)
    units = rotor_units(MLP.rotor, MLP.blade)
    sn = MLP.snubber
    b = beam.couplings["snubber lag"]
    c = units.damper(sn.loss_factor * sn.lag_stiffness / sn.reference_frequency
                     * units.radius**2) * np.outer(b, b)
    assert_allclose(m.vectors.T @ c @ m.vectors, m.modal_damping, atol=1e-14)
    assert lag_damping_ratio(m) > 0.005
    lossless = beam_modes(multiple_load_path_model(MLP.with_overrides(
        {"snubber.loss_factor": 0.0})), 9)
    assert np.abs(lossless.modal_damping).max() == 0.0


# ---------------------------------------------------------------- calibration

def test_multiple_load_path_hub_meets_the_stated_torsion_frequencies():
    # the same four statements and the same 2 % gate as the equivalent hub
    # (tests/structure/test_mdart.py); flap and lag essentially unchanged (< 1 %)
    checks = frequency_checks(MLP)
    assert checks["error_percent"].abs().max() < 2.0, checks.to_string()
    for col in ("flap1_per_rev", "lag1_per_rev"):
        assert checks[col].max() / checks[col].min() - 1 < 0.01


def test_fundamental_modes_placed_where_the_equivalent_hub_has_them():
    # calibrate_multiple_load_path placed flap 1 and lag 1 and the lag damping
    # at the equivalent hub's values; the TOML rounds the fitted stiffnesses to
    # 3 figures, which moves them by < 0.1 %
    eq, ml = blade_modes(MDART), blade_modes(MLP)
    for lab in ("flap 1", "lag 1", "torsion 1"):
        assert_allclose(mode_frequency(ml, lab), mode_frequency(eq, lab), rtol=2e-3)
    assert_allclose(lag_damping_ratio(ml), lag_damping_ratio(eq), rtol=5e-3)


def test_same_flap_inertia_as_the_equivalent_hub():
    # flexbeam + torque tube carry the tables' 2.49 lb/ft of the hub region, so
    # the blade's flap inertia about the rotor axis, I_b (the Lock number of
    # Table 1 and the mass unit m0 = 3 I_b / R^3), is that of the tables: the
    # rigid flapping motion w = x has q^T M q = I_b / (m0 R^3) = 1/3.  The
    # tables ramp to the root joint's 3.44 lb/ft over 0.15-0.19 R, which the
    # uniform hub beams leave out: 0.12 % of I_b (measured; gate 2e-3).
    beam = multiple_load_path_model(MLP)
    q = np.zeros(beam.n_dof)
    for name, c in beam.components.items():
        n_node = len(c.x_nodes)
        q[beam.index[name][np.arange(n_node) * 6 + 3]] = c.x_nodes     # w = x
        q[beam.index[name][np.arange(n_node) * 6 + 4]] = 1.0           # w' = 1
    assert_allclose(q @ beam.mass @ q, 1.0 / 3.0, rtol=2e-3)


# ----------------------------------------------------------------- validation

@pytest.mark.parametrize(("over", "field"), [
    ({"hub.model": "bearingless"}, "hub.model"),
    ({"torque_tube.inboard": 0.3}, "torque_tube.inboard"),
    ({"torque_tube.inboard": 0.02}, "torque_tube.inboard"),
    ({"flexbeam.clevis": 0.25}, "flexbeam.clevis"),
    ({"flexbeam.clevis": 0.05}, "flexbeam.clevis"),
    ({"pitch_link.horn_arm": 0.0}, "pitch_link.horn_arm"),
    ({"pitch_link.horn_arm": "12 in"}, "pitch_link.horn_arm"),
    ({"pitch_link.radial_offset": "-11 in"}, "pitch_link.radial_offset"),
    ({"flexbeam.im_flap": 0.0, "flexbeam.im_lag": 0.0}, "flexbeam.im_flap"),
    ({"model.n_elements": 8}, "model.n_elements"),
    ({"snubber.loss_factor": -0.1}, "snubber.loss_factor"),
    ({"flexbeam.gj": 0.0}, "flexbeam.gj"),
    ({"torque_tube.mass": "-1 lb/ft"}, "torque_tube.mass"),
    ({"pitch_link.cant": "60 deg"}, "pitch_link.cant"),
])
def test_bad_hub_input_names_the_field(over, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        MLP.with_overrides(over)


def test_missing_hub_sections_are_named():
    from tefcore.config.io import config_from_dict, config_to_dict

    data = config_to_dict(MDART)
    del data["flexbeam"]
    del data["snubber"]["loss_factor"]
    data["hub"]["model"] = {"value": "multiple_load_path"}
    with pytest.raises(ValueError) as err:
        config_from_dict(data)
    msg = str(err.value)
    assert "flexbeam.clevis" in msg and "flexbeam.gj" in msg and "snubber.loss_factor" in msg
    assert "torque_tube" not in msg
    data["hub"]["model"] = {"value": "equivalent"}
    assert config_from_dict(data).hub.model == "equivalent"      # not needed there


HUB_FIELDS = [f"{s}.{p.name}" for s in ("flexbeam", "torque_tube", "pitch_link", "snubber")
              for p in SECTIONS[s].PARAMS]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(field=st.sampled_from(HUB_FIELDS),
       value=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-100, 100)))
def test_any_hub_value_gives_a_model_or_an_error_naming_it(field, value):
    # every value of a hub field either builds the branched blade or is refused
    # with a ValueError that names the field (never a traceback elsewhere).  The
    # refusal may come when the blade is assembled: a value inside the field's
    # range can still leave the assembled mass matrix singular to round-off
    # (hypothesis found flexbeam.mass = 5e-324 kg/m: smallest eigenvalue
    # -1.45e-17), which the positive-definiteness check refuses, naming the
    # fields to check
    names = {field, "model.n_elements"} if field.endswith("n_elements") else {field}
    try:
        cfg = MLP.with_overrides({field: value})
    except ValueError as err:
        assert any(n in str(err) for n in names), str(err)
        return
    try:
        m = blade_modes(cfg, n_modes=4)
    except ValueError as err:
        assert any(n in str(err) for n in names), str(err)
        return
    assert np.all(np.isfinite(m.frequencies))


def test_blade_nodes_start_at_the_clevis_with_the_flap_edges_on_nodes():
    nodes = element_nodes(MLP.flap, 13, MLP.flexbeam.clevis)
    assert nodes[0] == MLP.flexbeam.clevis and nodes[-1] == 1.0
    for edge in (MLP.flap.inboard, MLP.flap.outboard):
        assert np.isclose(nodes, edge).any()


def test_hub_comparison_for_the_notebook():
    # both hubs' fan data and the lag-1 track of Fig. 3 (hover, no flap) at
    # two collectives; the calibrated hubs share lag 1 and its structural
    # damping and have no kinematic pitch-lag coupling (pitch_link.cant = 0),
    # so their hover lag damping agrees (measured: within 1e-4 of critical at
    # 0 and 6 deg; gate 2e-3, a tenth of the level; a 15 deg cant moves it by
    # 1.5e-2)
    import matplotlib

    matplotlib.use("Agg")
    from tefcore.paper.attribution.hub_comparison import compare_hub_models, plot_hub_models

    c = compare_hub_models(speed_ratios=[0.5, 1.0], figures=("fig3",), collectives_deg=[0, 6])
    assert set(c.fan["hub_model"]) == {"equivalent", "multiple_load_path"}
    assert len(c.modes) == 18 and len(c.lag_damping) == 4
    lag = c.lag_damping.pivot(index="collective_deg", columns="hub_model", values="damping_ratio")
    assert np.all(lag > 0.01)
    assert_allclose(lag["equivalent"], lag["multiple_load_path"], atol=2e-3)
    fig = plot_hub_models(c)
    assert len(fig.axes) == 4
