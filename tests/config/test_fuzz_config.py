"""Fuzzing configuration input: overrides and TOML documents give a Config or a ValueError.

A 400-digit integer in TOML meets an OverflowError, and a unit a field
does not take is refused: the command-line overrides (``--set name=value``) and TOML
documents -- mutations of the shipped MDART file and arbitrary TOML tables --
must end in a validated :class:`~tefcore.config.configuration.Config` or a ``ValueError``.
"""

import re

import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tefcore.config.configuration import SECTIONS, Config
from tefcore.config.io import dumps_config, load_config, loads_config
from tefcore.config.text_input import parse_overrides

MDART = load_config("mdart")
FIELDS = [f"{s}.{p.name}" for s, cls in SECTIONS.items() for p in cls.PARAMS]
TEXT = dumps_config(MDART)
LINES = TEXT.splitlines()

FUZZ = settings(max_examples=150, deadline=None,
                suppress_health_check=[HealthCheck.too_slow])

value_text = st.one_of(
    st.sampled_from(["0", "0.3", "-1", "1e308", "1e-320", "nan", "inf", "9" * 400, "", " ",
                     "800 lb/in", "800", "5 deg", "0.2 rad", "3 ft", "17 ft/s", "1/rad",
                     "c81", "dynamic", "thin_airfoil", "2.5", "40", "[1, 2]", "{}", "true",
                     "0.3 percent", "1e5 N*m/rad", "392 rpm", "12 in^99999999999"]),
    st.floats(allow_nan=True).map(repr),
    st.text(max_size=20),
)
field_name = st.one_of(st.sampled_from(FIELDS), st.sampled_from(["name", "flap.overhng", "x",
                                                                 "", "flap.", ".x"]),
                       st.text(max_size=15))


@FUZZ
@given(items=st.lists(st.tuples(field_name, value_text), min_size=1, max_size=3))
def test_overrides_give_a_config_or_a_value_error(items):
    try:
        cfg = MDART.with_overrides(parse_overrides([f"{k}={v}" for k, v in items]))
    except ValueError:
        return
    assert isinstance(cfg, Config)


toml_scalar = st.one_of(st.integers(-10**500, 10**500), st.floats(allow_nan=True),
                        st.booleans(), st.text(max_size=12),
                        st.sampled_from(["17 ft", "800 lb/in", "5 deg", "c81"]))
toml_value = st.recursive(toml_scalar, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.sampled_from(["value", "values", "unit",
                                                                  "source", "x"]), inner,
                                                 max_size=3)), max_leaves=8)


@FUZZ
@given(data=st.data())
def test_mutated_mdart_toml_gives_a_config_or_a_value_error(data):
    lines = list(LINES)
    for _ in range(data.draw(st.integers(1, 3))):
        k = data.draw(st.integers(0, len(lines) - 1))
        kind = data.draw(st.sampled_from(["value", "delete", "duplicate", "chars"]))
        if kind == "value" and " = " in lines[k]:
            key = lines[k].split(" = ")[0]
            value = data.draw(toml_value)
            lines[k] = tomli_w.dumps({key: value}).strip() if re.fullmatch(r"[\w.]+", key) \
                else lines[k]
        elif kind == "delete":
            del lines[k]
        elif kind == "duplicate":
            lines.insert(k, lines[k])
        else:
            pos = data.draw(st.integers(0, len(lines[k])))
            lines[k] = lines[k][:pos] + data.draw(st.text(max_size=3)) + lines[k][pos + 1:]
        if not lines:
            break
    try:
        cfg = loads_config("\n".join(lines), origin="fuzz.toml")
    except ValueError as err:
        assert str(err).startswith("fuzz.toml: ")
        return
    assert isinstance(cfg, Config)


@FUZZ
@given(doc=st.dictionaries(st.sampled_from(["rotor", "flap", "flight", "model", "reference",
                                            "name", "blade", "x"]),
                           st.dictionaries(st.sampled_from(["radius", "overhang", "ct_sigma",
                                                            "c81_deck", "mass", "y"]),
                                           toml_value, max_size=3), max_size=4))
def test_arbitrary_toml_tables_give_a_config_or_a_value_error(doc):
    try:
        text = tomli_w.dumps(doc)
    except (TypeError, ValueError):
        return                      # not representable as TOML (e.g. nan keys)
    try:
        loads_config(text)
    except ValueError:
        pass
