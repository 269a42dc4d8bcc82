"""actuator.reflected_inertia (the field) and the packaged variant mdart-fig6 (the data)."""

import re
from importlib import resources

import numpy as np
import pytest

from tefcore.config.io import available_configs, config_to_dict, load_config, loads_config
from tefcore.units import to_si

MDART = load_config("mdart")
FIG6 = load_config("mdart-fig6")
LB_IN2 = to_si(1.0, "lb*in^2", "inertia")
FIG6_TEXT = resources.files("tefcore").joinpath("data", "mdart-fig6.toml").read_text()


def test_field_units_default_and_source():
    assert MDART.actuator.reflected_inertia == 0.0
    assert MDART.sources["actuator.reflected_inertia"].startswith("assumed: not modelled")
    c = MDART.with_overrides({"actuator.reflected_inertia": "2 lb*in^2"})
    # lb*in^2 is 0.45359237 kg * 0.0254^2 m^2 exactly
    assert c.actuator.reflected_inertia == pytest.approx(2 * 0.45359237 * 0.0254**2, rel=1e-15)
    assert MDART.with_overrides({"actuator.reflected_inertia": 1e-4}).actuator \
        .reflected_inertia == 1e-4            # Python API: SI numbers


@pytest.mark.parametrize("value, pattern", [
    ("-1 lb*in^2", r"actuator\.reflected_inertia = .* outside the allowed range \[0, 1\]"),
    ("2 kg*m^2", r"actuator\.reflected_inertia = 2\.0 kg\*m\^2 is outside"),
    ("3 lb/ft", r"actuator\.reflected_inertia: unit 'lb/ft' does not match .*inertia"),
    (float("nan"), r"actuator\.reflected_inertia"),
])
def test_bad_values_are_named_errors(value, pattern):
    with pytest.raises(ValueError, match=pattern):
        MDART.with_overrides({"actuator.reflected_inertia": value})


def test_misspelled_field_gets_a_close_match():
    with pytest.raises(ValueError, match=r"did you mean 'actuator\.reflected_inertia'"):
        MDART.with_overrides({"actuator.reflected_inertai": 1e-4})


def test_toml_needs_its_unit():
    text = re.sub(r'(?m)^reflected_inertia = .*$', "reflected_inertia = 2.0",
                  FIG6_TEXT)
    with pytest.raises(ValueError, match=r"actuator\.reflected_inertia.*unit"):
        loads_config(text, origin="x.toml")


def test_fig6_variant_is_packaged_and_differs_from_mdart_only_in_the_fitted_field():
    assert {"mdart", "mdart-fig6"} <= set(available_configs())
    assert FIG6.name == "mdart-fig6"
    a, b = config_to_dict(MDART), config_to_dict(FIG6)
    for d in (a, b):
        d.pop("name"), d.pop("description")
    ia = b["actuator"].pop("reflected_inertia")
    a["actuator"].pop("reflected_inertia")
    assert a == b                   # same values AND the same sources, every other field
    # stored to 4 significant digits in lb in^2 (the header and docs quote 2.66)
    assert ia["value"] == pytest.approx(2.661 * LB_IN2, rel=1e-12)
    assert ia["source"].startswith("fitted")


def test_fig6_variant_file_lists_the_stated_numbers_and_the_default_choice():
    text = FIG6_TEXT
    for stated in ("Lock number 9.17", "2.3/rev at 158 lb/in", "4.2/rev at 800 lb/in",
                   "2.96/rev at 0.75 GJ", "3.18/rev at 2.0 GJ", "15% larger",
                   "mass-balanced", "Which variant is the default: mdart"):
        assert stated in text, stated


def test_reflected_inertia_changes_no_blade_section_or_mode():
    from tefcore.structure.blade import blade_modes
    from tefcore.structure.section_inertia import lumped_section

    x = np.linspace(0.05, 1.0, 40)
    for k, v in lumped_section(MDART, x).items():
        np.testing.assert_array_equal(v, lumped_section(FIG6, x)[k])   # no mass added
    np.testing.assert_array_equal(blade_modes(MDART).frequencies, blade_modes(FIG6).frequencies)
