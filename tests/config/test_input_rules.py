"""Input rules: paths relative to their TOML file, units where text is read, bounded
parsers, and a Mach limit that agrees with the advance-ratio range."""

import re
import shutil

import numpy as np
import pytest
from scipy import constants as sc

from tefcore.aero.c81 import example_deck_path
from tefcore.aero.thin_airfoil import prandtl_glauert
from tefcore.config.io import config_from_dict, config_to_dict, dumps_config, load_config
from tefcore.sweeps.sweep import sweep
from tefcore.units import parse_quantity, parse_unit, to_si
from tests.sweeps.test_sweep import ToyPoint

MDART = load_config("mdart")
TOML = dumps_config(MDART)


def set_line(text, key, line):
    """Replace the line ``key = ...`` of a TOML text (exactly one)."""
    new, n = re.subn(rf"(?m)^{re.escape(key)} = .*$", line, text)
    assert n == 1, key
    return new


# ------------------------------------------------------------------ paths


def c81_toml(deck: str) -> str:
    text = set_line(TOML, "aero_model", 'aero_model = "c81"')
    return set_line(text, "c81_deck", f'c81_deck = "{deck}"')


def test_a_relative_c81_deck_is_relative_to_its_toml_file(tmp_path, monkeypatch):
    """The deck is looked up beside the TOML file, not in the working directory."""
    folder = tmp_path / "study"
    folder.mkdir()
    shutil.copyfile(example_deck_path(), folder / "deck.c81")
    (folder / "cfg.toml").write_text(c81_toml("deck.c81"))
    decks = []
    for cwd in (tmp_path, folder):                # the same answer from any folder
        monkeypatch.chdir(cwd)
        decks.append(load_config(folder.relative_to(tmp_path) / "cfg.toml"
                                 if cwd == tmp_path else "cfg.toml").model.c81_deck)
    assert decks[0] == decks[1] == str(folder / "deck.c81")


def test_a_missing_c81_deck_is_a_field_error_at_load_time(tmp_path):
    (tmp_path / "cfg.toml").write_text(c81_toml("decks/none.c81"))
    with pytest.raises(ValueError, match=r"model\.c81_deck = '.*decks/none\.c81': no such file"):
        load_config(tmp_path / "cfg.toml")


def test_an_absolute_deck_path_is_kept(tmp_path):
    (tmp_path / "cfg.toml").write_text(c81_toml(str(example_deck_path())))
    assert load_config(tmp_path / "cfg.toml").model.c81_deck == str(example_deck_path())


# ------------------------------------------------------------------ units


@pytest.mark.parametrize("field, value", [
    ("flight.ct_sigma", "5 deg"), ("flap.overhang", "0.29 rad"), ("flap.span", "3 ft"),
    ("flight.advance_ratio", "0.3 1/rad"),
])
def test_dimensionless_fields_refuse_units_with_a_dimension(field, value):
    """``flight.ct_sigma = "5 deg"`` is refused, not read as 0.0873."""
    with pytest.raises(ValueError, match=re.escape(field)):
        MDART.with_overrides({field: value})


def test_pure_number_units_are_fine_for_dimensionless_fields():
    assert MDART.with_overrides({"flap.overhang": "29 percent"}).flap.overhang == 0.29


def test_in_toml_a_dimensional_field_needs_its_unit():
    """A bare number for a dimensional field is refused, not silently SI."""
    text = set_line(TOML, "pitch_link_stiffness", "pitch_link_stiffness = 800")
    with pytest.raises(ValueError, match=r"hub\.pitch_link_stiffness = 800 needs a unit"):
        from tefcore.config.io import loads_config

        loads_config(text, origin="x.toml")
    # with the unit, or as a table with a unit, it loads
    from tefcore.config.io import loads_config

    ok = set_line(TOML, "pitch_link_stiffness", 'pitch_link_stiffness = "800 lb/in"')
    assert loads_config(ok).hub.pitch_link_stiffness == pytest.approx(800 * 175.126835, rel=1e-6)
    table = set_line(TOML, "pitch_link_stiffness", "pitch_link_stiffness = {value = 140101.0}")
    with pytest.raises(ValueError, match="needs a unit"):
        loads_config(table)
    arr = TOML.replace('unit = "kg/m"\n', "", 1)        # [blade.mass] values without a unit
    with pytest.raises(ValueError, match=r"blade\.mass = \[\.\.\.\] needs a unit"):
        loads_config(arr)


def test_the_python_api_keeps_si_numbers():
    cfg = MDART.with_overrides({"hub.pitch_link_stiffness": 800.0})
    assert cfg.hub.pitch_link_stiffness == 800.0
    data = config_to_dict(MDART)
    data["hub"]["pitch_link_stiffness"] = 800.0
    assert config_from_dict(data).hub.pitch_link_stiffness == 800.0
    with pytest.raises(ValueError, match="needs a unit"):
        config_from_dict(data, require_units=True)


def test_angle_fields_take_angles_only():
    assert MDART.with_overrides({"flight.shaft_angle": "2 deg"}).flight.shaft_angle == \
        pytest.approx(2 * sc.degree, rel=1e-15)
    with pytest.raises(ValueError, match="has no angle unit"):
        MDART.with_overrides({"flight.shaft_angle": "2 percent"})
    with pytest.raises(ValueError, match="per-angle"):
        MDART.with_overrides({"rotor.lift_slope": "5.7 deg"})


# ------------------------------------------------------------------ no crashes


@pytest.mark.parametrize("unit", [
    "lb/in^99999999999", "lb/in^-99999999999", "(km^12)^12", "mm^-12^-12", "m" + "(" * 50,
    "(" * 30 + "m" + ")" * 30, "m^2.5", "m^" + "9" * 400, "ft" * 200,
])
def test_unit_strings_fail_with_value_errors_only(unit):
    """'800 lb/in^99999999999' is a ValueError, not ZeroDivisionError/OverflowError."""
    with pytest.raises(ValueError):
        parse_unit(unit, "force_per_length")
    with pytest.raises(ValueError):
        parse_quantity(f"800 {unit}")


def test_units_within_the_limits_still_work():
    assert to_si(1, "m^12/m^12") == 1.0
    assert to_si(1, "((((ft))))") == sc.foot


@pytest.mark.parametrize("text", ["n_blades = " + "9" * 400, "radius = {value = 1" + "0" * 400
                                  + ', unit = "ft"}'])
def test_a_400_digit_integer_in_toml_is_a_field_error(text):
    """A 400-digit integer is a field error, not an OverflowError."""
    from tefcore.config.io import loads_config

    key = text.split(" =")[0]
    bad = set_line(TOML, key, text)
    with pytest.raises(ValueError, match=rf"rotor\.{key} = <an integer of 40[01] digits>"):
        loads_config(bad)


# ------------------------------------------------------------------ Mach


def test_the_advance_ratio_range_agrees_with_the_tip_mach_limit():
    """mu = 0.6 is refused naming the tip Mach number, not accepted to fail later with a
    Mach array dump."""
    with pytest.raises(ValueError, match=r"flight\.advance_ratio = 0\.6 .*tip.*Mach .*1\.000"
                                         r".*at most 0\.5838"):
        MDART.with_overrides({"flight.advance_ratio": 0.6})
    # MDART: M_tip = Omega R / a = 0.6251, so (1 + mu) M_tip = 0.99 at mu = 0.5838
    MDART.with_overrides({"flight.advance_ratio": 0.5838})
    # C81 tables clip the Mach number (with a warning) instead
    MDART.with_overrides({"flight.advance_ratio": 0.6, "model.aero_model": "c81",
                          "model.c81_deck": str(example_deck_path())})


def test_a_failed_sweep_point_has_a_short_message():
    res = sweep(MDART, "flight.advance_ratio", [0.3, 0.6], point=ToyPoint(), progress=False)
    err = res.failed["error"].item()
    assert err.startswith("ValueError: flight.advance_ratio = 0.6") and len(err) < 500


def test_mach_errors_do_not_dump_arrays():
    with pytest.raises(ValueError) as info:
        prandtl_glauert(np.full((40, 72), 0.5) + np.eye(40, 72))
    msg = str(info.value)
    assert msg == "mach must lie in [0, 0.99], got 1.5 (40 of 2880 values outside)"
