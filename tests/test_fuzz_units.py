"""Fuzzing the unit parser: a result or a ValueError, nothing else, in bounded time.

Fuzzed unit strings can meet a ZeroDivisionError or OverflowError (299 of
3000 of them, e.g. ``"800 lb/in^99999999999"``) where the parser does not
bound them.  The strategies below build
unit expressions from the grammar's own pieces (names, operators, powers,
parentheses, numbers) so that most examples get deep into the parser, plus
arbitrary text.
"""

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from tefcore.units import DIMENSIONS, parse_quantity, parse_unit, to_si

PIECES = ["m", "s", "kg", "ft", "in", "lb", "lbf", "lbm", "slug", "N", "deg", "rad", "rev",
          "rpm", "RPM", "%", "percent", "1", "2", "0", "(", ")", "^", "**", "*", "/", "-", "·",
          " ", "^-", "^2", "^12", "^13", "^99999999999", "^(2)", "e", "1e308", "²", "µ", "\x00"]

unit_text = st.one_of(
    st.lists(st.sampled_from(PIECES), min_size=1, max_size=25).map("".join),
    st.text(max_size=40),
)
dimension = st.one_of(st.none(), st.sampled_from(sorted(DIMENSIONS)),
                      st.tuples(*[st.integers(-3, 3)] * 3))
number = st.one_of(st.floats(allow_nan=True, allow_infinity=True).map(repr),
                   st.integers(-10**30, 10**30).map(str),
                   st.sampled_from(["", "-", ".", "1e999", "0", "-0.0", "9" * 400]))

FUZZ = settings(max_examples=400, deadline=None)


@FUZZ
@given(unit=unit_text, dim=dimension)
def test_parse_unit_returns_a_finite_factor_or_raises_value_error(unit, dim):
    try:
        factor, dims = parse_unit(unit, dim)
    except ValueError:
        return
    assert math.isfinite(factor) and factor > 0
    assert len(dims) == 3 and all(isinstance(d, int) for d in dims)


@FUZZ
@given(value=number, unit=unit_text, dim=dimension)
def test_quantities_convert_or_raise_value_error(value, unit, dim):
    try:
        si = parse_quantity(f"{value} {unit}", dim)
    except ValueError:
        return
    assert isinstance(si, float)
    # the same through to_si (parse_quantity reads the number the same way)
    try:
        assert to_si(float(value), unit, dim) == si or not math.isfinite(si)
    except ValueError:
        raise AssertionError("to_si refused what parse_quantity accepted") from None
