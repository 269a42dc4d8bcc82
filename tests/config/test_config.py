"""Tests of tefcore.config.sections / tefcore.config.io: Table 1, validation, overrides, TOML."""

import copy
import dataclasses
import math
import pickle
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy import constants as sc

from tefcore.config.configuration import SECTIONS, Config, resolve_field
from tefcore.config.io import (
    config_from_dict,
    config_to_dict,
    dumps_config,
    load_config,
    loads_config,
    save_config,
    settings_markdown,
    settings_table,
)
from tefcore.config.sections import BLADE_PROPERTIES, REQUIRED, BladeConfig, mode_family_counts
from tefcore.units import to_si

MDART = load_config("mdart")
NST = MDART.blade.stations.size  # blade stations of the MDART tables
EPS4 = 4 * np.finfo(float).eps  # a product of constants in another order: few ulp


def names_field(err, dotted):
    """The message names exactly this field (not a longer one sharing a prefix)."""
    return re.search(rf"(?<![\w.]){re.escape(dotted)}(?!\w)", str(err.value)) is not None


# --------------------------------------------------------------- Table 1 / mdart


def test_table1_values_exact():
    r, f, a = MDART.rotor, MDART.flap, MDART.actuator
    assert r.n_blades == 5
    assert r.radius == 17 * sc.foot  # diameter 34 ft
    assert r.chord == 10 * sc.inch
    assert r.rotor_speed == to_si(392, "rpm")
    assert math.isclose(r.rotor_speed, 392 * 2 * math.pi / 60, rel_tol=EPS4)
    assert (f.midspan, f.span, f.chord_ratio, f.overhang) == (0.83, 0.18, 0.35, 0.29)
    assert math.isclose(a.stiffness, 81.52 * sc.foot * sc.pound_force, rel_tol=EPS4)
    assert math.isclose(a.damping, 0.005 * sc.foot * sc.pound_force, rel_tol=EPS4)


def test_stated_solidity_and_lock_number():
    # Table 1 prints 0.078 and 9.17: tolerance half the last printed digit.
    assert MDART.rotor.solidity == pytest.approx(0.078, abs=0.0005)
    assert MDART.lock_number == pytest.approx(9.17, abs=0.005)
    assert MDART.reference == {"lock_number": 9.17, "solidity": 0.078}
    stated, computed = MDART.reference_checks()["solidity"]
    assert stated == 0.078 and computed == MDART.rotor.solidity


def test_mdart_baseline_from_text():
    assert MDART.flight.advance_ratio == 0.3
    assert MDART.flight.ct_sigma == 0.075
    assert MDART.flight.collective is None
    assert MDART.flap.cg_offset == 0.0  # mass-balanced baseline flap
    assert MDART.blade.stations.size == 18
    assert MDART.blade.stations[0] == MDART.rotor.root_offset


def test_every_mdart_field_has_a_source():
    for sname, cls in SECTIONS.items():
        for p in cls.PARAMS:
            dotted = f"{sname}.{p.name}"
            if MDART.get(dotted) is None:
                continue  # optional and absent (flight.collective)
            src = MDART.sources.get(dotted, "")
            assert src.startswith(("Table 1:", "text:", "assumed:")), dotted
    for key in ("rotor.radius", "rotor.n_blades", "actuator.stiffness", "flap.overhang"):
        assert MDART.sources[key].startswith("Table 1:")


# ------------------------------------------------------------------- TOML I/O


def test_round_trip_exact(tmp_path):
    path = save_config(MDART, tmp_path / "cfg.toml")
    back = load_config(path)
    assert back == MDART
    assert back.rotor.radius == MDART.rotor.radius  # bitwise-equal floats
    assert np.array_equal(back.blade.twist, MDART.blade.twist)
    assert dict(back.sources) == dict(MDART.sources)
    assert dict(back.reference) == dict(MDART.reference)
    assert dumps_config(back) == path.read_text()  # idempotent


@given(
    mu=st.floats(0, 0.55),  # MDART: the advancing tip reaches the Mach limit at 0.5838
    # heavier than the flap's share everywhere, so that the flap fits (section_inertia)
    mass=st.lists(st.floats(2.5, 1e3), min_size=NST, max_size=NST),
    arm=st.floats(1e-6, 1e6),
)
@settings(max_examples=25, deadline=None)
def test_round_trip_arbitrary_floats(mu, mass, arm):
    cfg = MDART.with_overrides({"flight.advance_ratio": mu, "blade.mass": mass,
                                "hub.pitch_horn_arm": arm})  # fmt: skip
    assert loads_config(dumps_config(cfg)) == cfg


def test_equality_ignores_sources():
    other = dataclasses.replace(MDART, sources={})
    assert other == MDART
    assert MDART.with_overrides({"flap.cg_offset": 0.1}) != MDART


TOML_BASE = dumps_config(MDART)


def test_unknown_toml_key_raises():
    text = TOML_BASE.replace("overhang = {", "overhng = {")
    with pytest.raises(ValueError, match=r"\[flap\].*'overhng'.*did you mean 'overhang'"):
        loads_config(text, origin="x.toml")


def test_unknown_toml_section_and_inline_key_raise():
    with pytest.raises(ValueError, match="unknown key.*'rotorr'"):
        loads_config(TOML_BASE + "\n[rotorr]\nx = 1\n")
    text = TOML_BASE.replace("chord_ratio = {value", "chord_ratio = {vlaue")
    with pytest.raises(ValueError, match=r"flap\.chord_ratio: unknown key.*'vlaue'"):
        loads_config(text)
    with pytest.raises(ValueError, match="unknown key.*'lock_nmber'"):
        loads_config(TOML_BASE.replace("lock_number =", "lock_nmber ="))


def test_missing_required_field_raises():
    text = "\n".join(line for line in TOML_BASE.splitlines() if not line.startswith("radius"))
    with pytest.raises(ValueError, match=r"missing required field\(s\) rotor\.radius"):
        loads_config(text)


def test_defaults_fill_missing_optional_fields():
    data = config_to_dict(MDART)
    del data["model"], data["flight"]["ct_sigma"]
    cfg = config_from_dict(data)
    assert cfg.model.n_elements == 20 and cfg.flight.ct_sigma == 0.075
    assert cfg.sources["model.n_modes"] == "default"


def test_toml_value_forms():
    text = TOML_BASE.replace(
        'radius = {value = 5.1815999999999995, unit = "m"', 'radius = {value = 17, unit = "ft"'
    )
    assert loads_config(text).rotor.radius == 17 * sc.foot
    bare = re.sub(r"^radius = .*$", 'radius = "17 ft"', TOML_BASE, flags=re.M)
    assert loads_config(bare).rotor.radius == 17 * sc.foot
    with pytest.raises(ValueError, match="rotor.radius.*has dimension M"):
        loads_config(re.sub(r"^radius = .*$", 'radius = "17 lbm"', TOML_BASE, flags=re.M))


def test_load_unknown_packaged_name():
    with pytest.raises(FileNotFoundError, match="mdart"):
        load_config("mdrat")


# ------------------------------------------------------------------ overrides


def test_overrides_values_units_and_original_untouched():
    new = MDART.with_overrides(
        {
            "flap.cg_offset": 0.33,
            "hub.pitch_link_stiffness": "800 lb/in",
            "blade.gj_scale": 2.0,
            "flight.advance_ratio": 0.3,
        }
    )
    assert new.flap.cg_offset == 0.33 and MDART.flap.cg_offset == 0.0
    assert new.hub.pitch_link_stiffness == 800 * sc.pound_force / sc.inch
    assert new.blade.gj_scale == 2.0 and MDART.blade.gj_scale == 1.0
    assert new.get("flap.cg_offset") == 0.33
    assert new.sources["flap.cg_offset"].startswith("override")
    assert new.blade is not MDART.blade and new.rotor is MDART.rotor  # immutable: shared


def test_override_with_table_and_joint_changes():
    new = MDART.with_overrides(
        {
            "actuator.stiffness": {"value": 1.5 * 81.52, "unit": "ft-lb/rad", "source": "x1.5"},
            "rotor.root_offset": 0.1,
            "blade.stations": np.linspace(0.1, 1.0, NST),
            "model.n_modes": 12.0,  # integral float accepted for an int field
        }
    )
    assert new.sources["actuator.stiffness"] == "x1.5"
    assert new.model.n_modes == 12 and isinstance(new.model.n_modes, int)
    assert new.blade.stations[0] == 0.1


def test_unknown_override_lists_close_matches():
    with pytest.raises(ValueError, match="'flap.cg_ofset'.*did you mean 'flap.cg_offset'"):
        MDART.with_overrides({"flap.cg_ofset": 0.3})
    with pytest.raises(ValueError, match="'flapp.overhang'.*'flap.overhang'"):
        MDART.with_overrides({"flapp.overhang": 0.3})
    with pytest.raises(ValueError, match="unknown field 'flap'"):
        MDART.get("flap")
    assert resolve_field("name") == (None, "name")


def test_overhang_one_raises_with_exact_message():
    with pytest.raises(ValueError) as err:
        MDART.with_overrides({"flap.overhang": 1.0})
    assert str(err.value) == "flap.overhang = 1.0 is outside the allowed range [0, 1)"
    with pytest.raises(ValueError, match=re.escape("flap.overhang = 1.2 is outside")):
        MDART.with_overrides({"flap.overhang": 1.2})


def test_pickle_and_deepcopy_round_trip():
    # Sweeps ship configurations to worker processes.
    for back in (pickle.loads(pickle.dumps(MDART)), copy.deepcopy(MDART)):
        assert back == MDART and dict(back.sources) == dict(MDART.sources)
        assert not back.blade.mass.flags.writeable


def test_frozen_and_read_only():
    with pytest.raises(dataclasses.FrozenInstanceError):
        MDART.flap.overhang = 0.5
    with pytest.raises(ValueError):
        MDART.blade.gj[0] = 1.0  # read-only array


# ------------------------------------------------------------ cross-field checks


@pytest.mark.parametrize(
    ("overrides", "fields"),
    [
        ({"flap.midspan": 0.95}, ["flap.midspan", "flap.span"]),  # beyond the tip
        ({"flap.span": 0.4}, ["flap.midspan", "flap.span"]),
        ({"flap.midspan": 0.25}, ["flap.midspan", "rotor.root_cutout"]),  # inboard of cutout
        ({"flap.chord_ratio": 0.8}, ["flap.chord_ratio", "rotor.elastic_axis"]),
        ({"rotor.root_cutout": 0.01}, ["rotor.root_cutout"]),
        ({"rotor.root_offset": 0.1}, ["blade.stations[0]", "rotor.root_offset"]),
        ({"rotor.chord": 3.0}, ["rotor.chord"]),  # > radius/2
        ({"blade.cg_offset": 0.3}, ["blade.cg_offset[0]"]),  # beyond one chord (0.254 m)
        ({"blade.tension_offset": "-11 in"}, ["blade.tension_offset[0]"]),
        ({"model.aero_model": "c81"}, ["model.c81_deck"]),
        ({"model.aero_model": "panel"}, ["model.aero_model"]),
    ],
)
def test_cross_field_errors_name_fields(overrides, fields):
    with pytest.raises(ValueError) as err:
        MDART.with_overrides(overrides)
    for f in fields:
        assert f in str(err.value)


def test_flap_at_tip_within_rounding_is_accepted():
    cfg = MDART.with_overrides({"flap.midspan": 0.91})  # 0.91 + 0.09 = 1 up to rounding
    assert cfg.flap.outboard == pytest.approx(1.0, abs=1e-12)


# --------------------------------------------------------------- blade arrays


@pytest.mark.parametrize(
    ("overrides", "field", "text"),
    [
        ({"blade.mass": [3.0] * (NST - 1)}, "blade.mass", f"has {NST - 1} values"),
        ({"blade.gj": [4e4] * 5 + [0.0] + [4e4] * (NST - 6)}, "blade.gj[5]", "outside"),
        ({"blade.ei_lag": [-1.0] * NST}, "blade.ei_lag[0]", "outside"),
        ({"blade.mass": [3.0] * (NST - 1) + [math.nan]}, f"blade.mass[{NST - 1}]", "not finite"),
        ({"blade.mass": [3.0] * (NST - 1) + [True]}, f"blade.mass[{NST - 1}]",
         "must be a number"),
        ({"blade.ka": "2 furlong"}, "blade.ka", "unknown unit"),
        ({"blade.ka": {"value": 2.0}}, "blade.ka", "unknown key"),
        ({"blade.twist": 0.8}, "blade.twist[0]", "outside"),
        ({"blade.stations": [0.05, 0.5, 0.4, 1.0]}, "blade.stations[2]", "not greater"),
        ({"blade.stations": [0.05, 0.5, 0.9]}, "blade.stations[2]", "must be 1.0"),
        ({"blade.stations": [0.05]}, "blade.stations", "at least 2"),
    ],
)  # fmt: skip
def test_array_errors_name_field_and_index(overrides, field, text):
    with pytest.raises(ValueError) as err:
        MDART.with_overrides(overrides)
    assert names_field(err, field) and text in str(err.value)


def test_scalar_broadcast_and_unit_table():
    cfg = MDART.with_overrides(
        {"blade.mass": {"values": 2.0, "unit": "slug/ft"}, "blade.ka": "2 in"}
    )
    np.testing.assert_array_equal(cfg.blade.mass, np.full(NST, 2.0 * sc.slug / sc.foot))
    np.testing.assert_array_equal(cfg.blade.ka, np.full(NST, 2 * sc.inch))


def test_section_interpolates_and_scales():
    blade = MDART.with_overrides({"blade.gj_scale": 2.0, "blade.mass_scale": 1.5}).blade
    x = np.array([0.05, 0.5, 0.77, 1.0])
    sec = blade.section(x)
    assert set(sec) == set(BLADE_PROPERTIES)
    np.testing.assert_array_equal(sec["gj"], 2.0 * np.interp(x, blade.stations, blade.gj))
    for k in ("mass", "im_flap", "im_lag"):
        np.testing.assert_array_equal(sec[k], 1.5 * np.interp(x, blade.stations, getattr(blade, k)))
    np.testing.assert_array_equal(sec["twist"], np.interp(x, blade.stations, blade.twist))
    with pytest.raises(ValueError, match="within"):
        blade.section([0.01])


def test_reference_mass_matches_closed_form():
    # Uniform m from x0 to 1: m0 = 3 int m x^2 dx = m (1 - x0^3); linear m = a + b x
    # gives 3 (a (1 - x0^3)/3 + b (1 - x0^4)/4).  The quadrature is exact for
    # these cubics, so only rounding remains: 1e-12 relative.
    # The MDART mass is piecewise linear: per segment m = m0 + k (x - x0) integrates to
    # m0 (x1^3 - x0^3)/3 + k [(x1^4 - x0^4)/4 - x0 (x1^3 - x0^3)/3], summed here in closed form.
    xs, ms = MDART.blade.stations, MDART.blade.mass
    x0, x1, m0 = xs[:-1], xs[1:], ms[:-1]
    k = np.diff(ms) / np.diff(xs)
    cube = (x1**3 - x0**3) / 3
    exact = 3 * np.sum(m0 * cube + k * ((x1**4 - x0**4) / 4 - x0 * cube))
    assert MDART.reference_mass == pytest.approx(exact, rel=1e-12)
    blade = BladeConfig(stations=np.linspace(0.2, 1.0, 5), mass=2.0 + 3.0 * np.linspace(0.2, 1, 5),
                        ei_flap=1.0, ei_lag=1.0, gj=1.0, ea=1.0)  # fmt: skip
    exact = 3 * (2.0 * (1 - 0.2**3) / 3 + 3.0 * (1 - 0.2**4) / 4)
    assert blade.reference_mass() == pytest.approx(exact, rel=1e-12)
    assert MDART.flapping_inertia == pytest.approx(MDART.reference_mass * 17**3 * sc.foot**3 / 3)


def test_derived_properties():
    hub, flap, c = MDART.hub, MDART.flap, MDART.rotor.chord
    assert hub.pitch_link_torsion_stiffness == hub.pitch_link_stiffness * hub.pitch_horn_arm**2
    assert flap.inertia_hinge(c) == flap.inertia_cg  # mass-balanced: CG on the hinge
    off = MDART.with_overrides({"flap.cg_offset": 0.33}).flap
    assert off.inertia_hinge(c) == off.inertia_cg + off.mass * (0.33 * 0.35 * c) ** 2
    assert MDART.rotor.tip_speed == MDART.rotor.rotor_speed * MDART.rotor.radius


def test_config_accepts_section_mappings_and_rejects_junk():
    kwargs = {s: getattr(MDART, s) for s in SECTIONS}
    kwargs["flight"] = {"advance_ratio": 0.2}
    assert Config(**kwargs).flight.advance_ratio == 0.2
    kwargs["flight"] = {"advance_ration": 0.2}
    with pytest.raises(ValueError, match="'advance_ration' in flight"):
        Config(**kwargs)
    kwargs["flight"] = 3
    with pytest.raises(ValueError, match="flight must be a FlightConfig"):
        Config(**kwargs)


def test_settings_docs_cover_every_field():
    rows = settings_table()
    every = {f"{s}.{p.name}" for s, c in SECTIONS.items() for p in c.PARAMS}
    assert {r["field"] for r in rows} == every
    assert "flap.overhang" in settings_markdown()
    for cls in SECTIONS.values():
        for p in cls.PARAMS:
            assert f"{p.name} : " in cls.__doc__


# ------------------------------------------ per-field validation (hypothesis)

SCALARS = [(s, p) for s, cls in SECTIONS.items() for p in cls.PARAMS if p.kind in ("float", "int")]
IDS = [f"{s}.{p.name}" for s, p in SCALARS]
HYP = settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])


def _with(section_name, name, value):
    """Build the section alone with one field replaced (per-field checks only)."""
    return dataclasses.replace(getattr(MDART, section_name), **{name: value})


def _values(section, name, value):
    vals = {p.name: getattr(section, p.name) for p in section.PARAMS}
    vals[name] = value
    return vals


def _others_valid(section, name, value):
    """Other fields' ranges may reference this one (root_cutout >= root_offset), and
    the basis holds its families (model.n_modes at least model.mode_families' sum)."""
    vals = _values(section, name, value)
    if name == "n_modes" and value < sum(mode_family_counts(vals["mode_families"]).values()):
        return False
    return all(
        q.range_error(vals[q.name], q.name, vals.__getitem__) is None
        for q in section.PARAMS
        if q.name != name and name in q.refs
    )


def _inside(p, lookup):
    lo, hi = p.limits(lookup)
    lo_in, hi_in = p.closed
    if p.kind == "int":
        return st.integers(int(lo), int(hi))
    return st.floats(
        min_value=lo,
        max_value=None if math.isinf(hi) else hi,
        exclude_min=not lo_in,
        exclude_max=not hi_in and not math.isinf(hi),
        allow_nan=False,
        allow_infinity=False,
    )


def _outside(p, lookup):
    """Values beyond a finite bound (None if both bounds are infinite)."""
    lo, hi = p.limits(lookup)
    lo_in, hi_in = p.closed
    options = []
    if p.kind == "int":
        options += [st.integers(max_value=int(lo) - 1), st.integers(min_value=int(hi) + 1)]
    else:
        if not math.isinf(lo):
            options.append(st.floats(max_value=lo, exclude_max=lo_in, allow_infinity=False))
        if not math.isinf(hi):
            options.append(st.floats(min_value=hi, exclude_min=hi_in, allow_infinity=False))
    return st.one_of(options) if options else None


@pytest.mark.parametrize(("section_name", "p"), SCALARS, ids=IDS)
@HYP
@given(data=st.data())
def test_values_inside_range_construct(section_name, p, data):
    section = getattr(MDART, section_name)
    value = data.draw(_inside(p, _values(section, p.name, None).__getitem__))
    assume(_others_valid(section, p.name, value))
    new = _with(section_name, p.name, value)
    assert getattr(new, p.name) == value


@pytest.mark.parametrize(("section_name", "p"), SCALARS, ids=IDS)
@HYP
@given(data=st.data())
def test_values_outside_range_raise(section_name, p, data):
    section = getattr(MDART, section_name)
    strategy = _outside(p, _values(section, p.name, None).__getitem__)
    if strategy is None:
        return  # unbounded both ways: only finiteness applies (tested below)
    value = data.draw(strategy)
    with pytest.raises(ValueError) as err:
        _with(section_name, p.name, value)
    assert names_field(err, f"{section_name}.{p.name}") and "outside" in str(err.value)


@pytest.mark.parametrize(("section_name", "p"), SCALARS, ids=IDS)
@pytest.mark.parametrize(
    "bad", [math.nan, math.inf, -math.inf, True, "0.3", "3 kg*s", [1.0], None, "fast"]
)
def test_bad_types_and_non_finite_raise(section_name, p, bad):
    if bad is None and p.optional:
        return
    with pytest.raises(ValueError) as err:
        _with(section_name, p.name, bad)
    assert names_field(err, f"{section_name}.{p.name}")


def test_required_fields_have_no_default():
    required = {f"{s}.{p.name}" for s, c in SECTIONS.items() for p in c.PARAMS if p.required}
    assert {"rotor.radius", "rotor.chord", "rotor.n_blades", "rotor.rotor_speed",
            "rotor.root_offset", "rotor.root_cutout", "flap.overhang"} <= required  # fmt: skip
    assert all(p.default is not REQUIRED for p in SECTIONS["model"].PARAMS)


def test_a_packaged_configuration_is_parsed_once_and_cannot_be_changed():
    # load_config hands out the configuration it parsed before: safe only
    # because a Config is frozen and its arrays are read-only
    a, b = load_config("mdart"), load_config("mdart")
    assert a is b
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.blade = None
    with pytest.raises(ValueError, match="read-only"):
        a.blade.mass[0] = 1.0
    assert a.with_overrides({"flap.mass": 2 * a.flap.mass}) is not a
    assert load_config("mdart-fig6") is not a
