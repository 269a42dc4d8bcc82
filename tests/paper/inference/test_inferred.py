"""The packaged variant mdart-inferred: buildable, its sources say how, registered; mdart kept."""

import numpy as np
import pytest

from tefcore.config.io import config_to_dict, load_config
from tefcore.paper.calibration import TORSION_TARGETS, mode_frequency
from tefcore.paper.claims.reference import load_claims
from tefcore.paper.claims.variants import load_variants
from tefcore.paper.inference.protocol import load_protocol
from tefcore.paper.inference.space import load_space, sample_of
from tefcore.structure.blade import blade_modes
from tefcore.structure.section_inertia import check_section_inertia

INFERRED = load_config("mdart-inferred")
MDART = load_config("mdart")
SPACE = load_space()


def _differing_fields():
    a, b = config_to_dict(INFERRED), config_to_dict(MDART)
    for section, entries in a.items():
        if not isinstance(entries, dict):
            continue
        for name, e in entries.items():
            key = "values" if "values" in e else "value"
            if key in e and e[key] != b[section][name][key]:
                yield f"{section}.{name}"


def test_mdart_is_the_default_and_nothing_in_it_is_inferred():
    assert load_variants()["mdart"].config == "mdart"
    assert not any(s.startswith("inferred") for s in MDART.sources.values())


def test_every_inferred_value_lies_in_its_construction_range():
    sample = sample_of(INFERRED, MDART, SPACE)
    for name, v in sample.items():
        p = SPACE[name]
        if p.categorical:
            assert v in p.choices, name
        else:
            # the stored values are rounded to the TOML's 17 digits: no slack needed
            assert p.low <= v <= p.high, (name, v, p.low, p.high)


def test_every_field_that_differs_from_mdart_says_it_was_inferred():
    fields = list(_differing_fields())
    assert "flap.mass" in fields and "hub.pitch_link_stiffness" in fields
    for f in fields:
        assert INFERRED.sources[f].startswith("inferred"), f
    assert "spread [" in INFERRED.sources["flap.mass"]
    assert "study protocol-" in INFERRED.sources["flap.mass"]


def test_the_inferred_rotor_is_buildable_and_keeps_the_stated_frequencies():
    check_section_inertia(INFERRED)
    for _, over, stated, _ in TORSION_TARGETS:
        over = dict(over)
        if "blade.gj_scale" in over:                # the GJ sweep is relative to baseline
            over["blade.gj_scale"] *= INFERRED.blade.gj_scale
        f = mode_frequency(blade_modes(INFERRED.with_overrides(over), n_modes=6), "torsion 1")
        # the calibration claims' own tolerance (2 %)
        assert f == pytest.approx(stated, rel=0.02)


def test_it_is_registered_and_calibrated_to_the_claims_it_was_fitted_to():
    v = load_variants()["mdart-inferred"]
    fitted, _ = load_protocol().split(load_claims())
    assert set(v.calibration) == {c.id for c in fitted if c.tag == "validation"}
    assert set(v.recorded_status) == {c.id for c in load_claims()}
    assert np.isclose(INFERRED.rotor.lift_slope * MDART.blade.mass_scale,
                      MDART.rotor.lift_slope * INFERRED.blade.mass_scale)   # Lock number kept
