"""Tests of tefcore.aero.c81: C81 deck reading/writing, errors, interpolation, table model."""

import importlib.util
import sys
import types
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tefcore.aero.c81 import (
    COEFFICIENTS,
    C81Airfoil,
    C81Deck,
    C81FlapTable,
    C81FormatError,
    C81RangeError,
    C81RangeWarning,
    example_deck_path,
    format_c81,
    generate_flap_deck,
    parse_c81,
    read_c81,
    write_c81,
)
from tefcore.aero.c81.format import coefficient_text
from tefcore.cli import main as tefcore_main

HAVE_FLAP_AERO = importlib.util.find_spec("tefcore.aero.thin_airfoil") is not None
needs_flap_aero = pytest.mark.skipif(
    not HAVE_FLAP_AERO,
    reason="tefcore.aero.thin_airfoil (ThinAirfoilFlap, section_loads) is not importable")

# A small blade deck, hand-written in fixed 7-column fields (line numbers in
# the comments are those of the file).
TOY = """\
# hand-written test deck
TOY                            2 3 2 3 2 3
           0.0    0.5
   -4.0  -.400  -.450
    0.0    0.0    0.0
    4.0   .400   .450
           0.0    0.5
   -4.0   .010   .012
    0.0   .008   .009
    4.0   .010   .012
           0.0    0.5
   -4.0  -.010  -.011
    0.0    0.0    0.0
    4.0   .010   .011
"""
#  line 2: title; 3: C_l Mach line; 4-6: C_l rows; 7: C_d Mach; 8-10: C_d rows;
#  11: C_m Mach; 12-14: C_m rows.

# The same deck, whitespace separated (cols 1-7 blank on Mach lines only).
TOY_FREE = """\
TOY                            2 3 2 3 2 3
        0 0.5
-4 -0.4 -0.45
0 0 0
4 0.4 0.45
        0 0.5
-4 0.01 0.012
0 0.008 0.009
4 0.01 0.012
        0 0.5
-4 -0.01 -0.011
0 0 0
4 0.01 0.011
"""

# A hand-written flap deck: 2 deltas, 2 Mach numbers, 2 angles, all tables.
FLAP = """\
SMALL FLAP                     2 2 2 2 2 2 2 2 2 2
DELTAS    -2.0    2.0
DELTA     -2.0
           0.0    0.5
   -5.0  -.600  -.700
    5.0   .500   .600
           0.0    0.5
   -5.0   .010   .011
    5.0   .010   .011
           0.0    0.5
   -5.0   .020   .021
    5.0   .020   .021
           0.0    0.5
   -5.0   .030   .031
    5.0   .030   .031
           0.0    0.5
   -5.0  -.100  -.110
    5.0   .100   .110
DELTA      2.0
           0.0    0.5
   -5.0  -.500  -.600
    5.0   .600   .700
           0.0    0.5
   -5.0   .012   .013
    5.0   .012   .013
           0.0    0.5
   -5.0  -.020  -.021
    5.0  -.020  -.021
           0.0    0.5
   -5.0  -.030  -.031
    5.0  -.030  -.031
           0.0    0.5
   -5.0  -.050  -.060
    5.0   .150   .160
"""


def print_tol(x):
    """Half the last printed digit of each written coefficient (plus a few ulp
    for the decimal -> binary conversion)."""
    d = np.vectorize(lambda v: coefficient_text(v)[1])(x)
    return 0.5 * 10.0 ** (-d) + 1e-12


def assert_within(actual, desired, tol, msg=""):
    """|actual - desired| <= tol elementwise (tol may be an array)."""
    err = np.abs(np.asarray(actual) - np.asarray(desired))
    assert np.all(err <= tol), (msg, float(np.max(err - tol)))


def parse_error(text, name="deck.c81"):
    with pytest.raises(C81FormatError) as info:
        parse_c81(text, name)
    return info.value


def replace_line(text, lineno, new):
    lines = text.splitlines()
    lines[lineno - 1] = new
    return "\n".join(lines) + "\n"


def delete_line(text, lineno):
    lines = text.splitlines()
    del lines[lineno - 1]
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------
# parsing


def test_parse_hand_written_blade_deck_exactly():
    deck = parse_c81(TOY)
    assert deck.name == "TOY" and not deck.is_flap and deck.delta is None
    assert deck.header == "hand-written test deck"
    assert deck.coefficients == ("cl", "cd", "cm")
    for c in deck.coefficients:
        np.testing.assert_array_equal(deck.alpha[c], [-4.0, 0.0, 4.0])
        np.testing.assert_array_equal(deck.mach[c], [0.0, 0.5])
    # Values are parsed exactly (float() of the printed decimal).
    np.testing.assert_array_equal(deck.tables["cl"], [[-0.4, -0.45], [0, 0], [0.4, 0.45]])
    np.testing.assert_array_equal(deck.tables["cd"],
                                  [[0.01, 0.012], [0.008, 0.009], [0.01, 0.012]])
    np.testing.assert_array_equal(deck.tables["cm"], [[-0.01, -0.011], [0, 0], [0.01, 0.011]])


def test_whitespace_separated_deck_equals_fixed_deck():
    fixed, free = parse_c81(TOY), parse_c81(TOY_FREE)
    for c in fixed.coefficients:
        np.testing.assert_array_equal(free.tables[c], fixed.tables[c])
        np.testing.assert_array_equal(free.alpha[c], fixed.alpha[c])
        np.testing.assert_array_equal(free.mach[c], fixed.mach[c])


def test_title_counts_may_be_whitespace_separated():
    text = replace_line(TOY_FREE, 1, "TOY".ljust(30) + "  2  3  2  3  2  3")
    assert parse_c81(text) == parse_c81(TOY_FREE)


# random edits may make a coefficient implausible (|c| > 10): warned, not tested here
@pytest.mark.filterwarnings("ignore::tefcore.aero.c81.C81PlausibilityWarning")
@settings(max_examples=300, deadline=None)
@given(deck=st.sampled_from([TOY, TOY_FREE, FLAP]), data=st.data())
def test_any_corruption_gives_a_format_error_or_a_valid_deck(deck, data):
    """Random edits never crash the reader with anything but C81FormatError."""
    kind = data.draw(st.sampled_from(["char", "delete", "truncate", "duplicate"]))
    if kind == "char":
        k = data.draw(st.integers(0, len(deck) - 1))
        ch = data.draw(st.sampled_from(list(" 0123456789.-+eDx#\n\t")))
        text = deck[:k] + ch + deck[k + 1:]
    elif kind == "truncate":
        text = deck[:data.draw(st.integers(0, len(deck)))]
    else:
        lines = deck.splitlines()
        k = data.draw(st.integers(0, len(lines) - 1))
        lines[k:k + 1] = [] if kind == "delete" else [lines[k], lines[k]]
        text = "\n".join(lines)
    try:
        parsed = parse_c81(text, "fuzz.c81")
    except C81FormatError as err:
        assert err.line >= 1 and err.column >= 1
        assert str(err).startswith(f"fuzz.c81 line {err.line}, column {err.column}: ")
    else:
        assert isinstance(parsed, C81Deck)
        for c in parsed.coefficients:
            assert np.all(np.isfinite(parsed.tables[c]))


def test_abutting_fixed_fields_are_read_by_column():
    # Fortran F7.4 output: negative numbers touch the previous field.
    text = replace_line(TOY, 4, "   -4.0-0.4000-0.4500")
    np.testing.assert_array_equal(parse_c81(text).tables["cl"][0], [-0.4, -0.45])


def test_exponents_and_fortran_d_exponent():
    text = replace_line(TOY, 8, "   -4.0 1.0E-2 1.2D-2")
    np.testing.assert_array_equal(parse_c81(text).tables["cd"][0], [0.01, 0.012])


def test_parse_hand_written_flap_deck_exactly():
    deck = parse_c81(FLAP)
    assert deck.is_flap and deck.name == "SMALL FLAP"
    np.testing.assert_array_equal(deck.delta, [-2.0, 2.0])
    assert deck.tables["cl"].shape == (2, 2, 2)
    np.testing.assert_array_equal(deck.tables["cl"][:, :, 0], [[-0.6, -0.7], [0.5, 0.6]])
    np.testing.assert_array_equal(deck.tables["cl"][:, :, 1], [[-0.5, -0.6], [0.6, 0.7]])
    np.testing.assert_array_equal(deck.tables["clf"][1, :, 1], [0.15, 0.16])
    np.testing.assert_array_equal(deck.tables["ch"][0, 1, :], [0.031, -0.031])


def test_read_c81_from_file(tmp_path):
    path = tmp_path / "toy.c81"
    path.write_text(TOY)
    deck = read_c81(path)
    assert deck.source == str(path)
    assert deck == parse_c81(TOY)


def test_mach_lines_and_rows_with_more_than_nine_mach_numbers():
    # 11 Mach numbers: 9 + 2 on a continuation line (7 blank columns first).
    machs = np.round(np.linspace(0.0, 1.0, 11), 10)
    alphas = np.array([-2.0, 0.0, 3.0])
    tab = np.add.outer(alphas / 10, machs)
    deck = C81Deck("WIDE", {c: alphas for c in "cl cd cm".split()},
                   {c: machs for c in "cl cd cm".split()},
                   {c: tab for c in "cl cd cm".split()})
    text = format_c81(deck)
    lines = text.splitlines()
    assert lines[0] == "WIDE".ljust(30) + "11 311 311 3"
    assert lines[1].startswith(" " * 7) and len(lines[1].split()) == 9
    assert lines[2].startswith(" " * 7) and len(lines[2].split()) == 2
    assert not lines[3].startswith(" " * 7) and len(lines[3].split()) == 10
    back = parse_c81(text)
    for c in deck.coefficients:
        assert_within(back.tables[c], tab, print_tol(tab), c)


# --------------------------------------------------------------------------
# writing and round trips


def random_deck(rng, flap, n_mach=(3, 4, 2, 12, 5), n_alpha=(5, 3, 4, 2, 6)):
    coefs = COEFFICIENTS if flap else COEFFICIENTS[:3]
    alpha, mach, tables = {}, {}, {}
    delta = np.array([-7.5, -2.0, 0.0, 3.25]) if flap else None
    for k, c in enumerate(coefs):
        alpha[c] = np.cumsum(rng.integers(1, 40, n_alpha[k]) * 0.25) - 10.0
        mach[c] = np.cumsum(rng.integers(1, 20, n_mach[k]) * 0.01)
        shape = (n_alpha[k], n_mach[k]) + ((delta.size,) if flap else ())
        # spread over the ranges that get different numbers of decimals
        tables[c] = rng.choice([-12.0, -1.5, -0.3, 0.02, 0.7, 3.0], shape) * rng.random(shape)
    return C81Deck("RANDOM " + ("FLAP" if flap else "BLADE"), alpha, mach, tables, delta=delta,
                   header="random test deck\nsecond line")


# the random decks go to |c| = 12 on purpose (number formats), beyond the plausible range
@pytest.mark.filterwarnings("ignore::tefcore.aero.c81.C81PlausibilityWarning")
@pytest.mark.parametrize("flap", [False, True])
def test_round_trip_within_printed_precision(tmp_path, flap):
    deck = random_deck(np.random.default_rng(7), flap)
    path = write_c81(deck, tmp_path / "rt.c81")
    back = read_c81(path)
    assert back.name == deck.name and back.header == deck.header
    assert back.is_flap == flap
    if flap:
        np.testing.assert_array_equal(back.delta, deck.delta)
    for c in deck.coefficients:
        # axes have at most 2 decimals and are written exactly
        np.testing.assert_array_equal(back.alpha[c], deck.alpha[c])
        np.testing.assert_allclose(back.mach[c], deck.mach[c], rtol=0, atol=1e-12)
        # coefficients: within half the last printed digit
        assert_within(back.tables[c], deck.tables[c], print_tol(deck.tables[c]), c)
    # Writing what was read reproduces the text exactly (a fixed point).
    assert format_c81(back) == path.read_text()


def test_header_false_writes_a_standard_deck():
    deck = parse_c81(TOY)
    text = format_c81(deck, header=False)
    assert not text.startswith("#") and text.splitlines()[0].startswith("TOY")
    assert parse_c81(text).header == ""


@given(st.floats(min_value=-9999.0, max_value=99999.0, allow_nan=False))
def test_coefficient_text_fits_and_is_within_half_a_digit(x):
    s, d = coefficient_text(x)
    assert len(s) <= 6  # leaves a separating blank in the 7-column field
    assert abs(float(s) - x) <= 0.5 * 10.0 ** (-d) * (1 + 1e-9) + 1e-12
    assert coefficient_text(float(s))[0] == s  # writing what was read is stable


def test_coefficient_precision_is_as_documented():
    # docs/c81_format.md section 6
    assert coefficient_text(0.123456) == (".12346", 5)
    assert coefficient_text(-0.123456) == ("-.1235", 4)
    assert coefficient_text(1.23456) == ("1.2346", 4)
    assert coefficient_text(-1.23456) == ("-1.235", 3)
    assert coefficient_text(-1e-7)[0] == "0.0"


def test_writer_rejects_long_names_and_counts():
    deck = parse_c81(TOY)
    deck.name = "X" * 31
    with pytest.raises(ValueError, match="columns 1-30"):
        format_c81(deck)
    deck.name = "#COMMENT"
    with pytest.raises(ValueError, match="'#'"):
        format_c81(deck)


def test_deck_validation():
    deck = parse_c81(TOY)
    with pytest.raises(ValueError, match="strictly increasing"):
        C81Deck("X", {**deck.alpha, "cl": deck.alpha["cl"][::-1]}, deck.mach, deck.tables)
    with pytest.raises(ValueError, match="shape"):
        C81Deck("X", deck.alpha, deck.mach, {**deck.tables, "cd": deck.tables["cd"][:2]})
    with pytest.raises(ValueError, match="NaN"):
        C81Deck("X", deck.alpha, deck.mach, {**deck.tables, "cm": deck.tables["cm"] * np.nan})
    with pytest.raises(ValueError, match="flap deck"):
        C81Deck("X", deck.alpha, deck.mach, deck.tables, delta=[0.0])


# --------------------------------------------------------------------------
# malformed decks: line and column


def test_bad_number_names_file_line_and_column(tmp_path):
    path = tmp_path / "deck.c81"
    path.write_text(replace_line(TOY, 9, "    0.0   .008    x.3"))
    with pytest.raises(C81FormatError) as info:
        read_c81(path)
    err = info.value
    assert isinstance(err, ValueError)
    assert (err.line, err.column) == (9, 19)  # 'x.3' starts in column 19
    assert str(err).startswith(f"{path} line 9, column 19: expected a number, got 'x.3'")
    assert "C_d at M = 0.5" in str(err)


def test_bad_number_in_whitespace_deck_points_at_token():
    err = parse_error(replace_line(TOY_FREE, 8, "0 0.008 0,009"))
    assert (err.line, err.column) == (8, 9)
    assert "got '0,009'" in err.reason


@pytest.mark.parametrize("bad", ["nan", "NaN", "inf", "-Infinity"])
def test_non_finite_numbers_are_errors(bad):
    line = f"    0.0    0.0 {bad:>6}"
    err = parse_error(replace_line(TOY, 5, line))
    assert (err.line, err.column) == (5, line.index(bad) + 1)
    assert "finite" in err.reason


def test_missing_value_on_a_row():
    err = parse_error(replace_line(TOY, 5, "    0.0    0.0"))
    assert (err.line, err.column) == (5, 15)  # the empty C_l(M=0.5) field
    assert "C_l at M = 0.5" in err.reason and "end of line" in err.reason


def test_extra_value_on_a_row():
    err = parse_error(replace_line(TOY, 5, "    0.0    0.0    0.0    0.0"))
    assert (err.line, err.column) == (5, 26)  # the 4th '0.0'
    assert "end of line after 3 number(s)" in err.reason


def test_missing_row():
    # Delete the last C_l row: line 6 is now the C_d Mach line, read as row 3.
    err = parse_error(delete_line(TOY, 6))
    assert (err.line, err.column) == (6, 1)
    assert "row 3 of 3 of the C_l table" in err.reason and "missing row" in err.reason


def test_decreasing_alpha():
    err = parse_error(replace_line(TOY, 10, "   -5.0   .010   .012"))
    assert (err.line, err.column) == (10, 4)
    assert "angles of attack of the C_d table must increase" in err.reason


def test_repeated_mach_number():
    err = parse_error(replace_line(TOY, 11, "           0.5    0.5"))
    assert (err.line, err.column) == (11, 19)
    assert "Mach numbers of the C_m table must increase" in err.reason


def test_count_too_small_is_an_extra_row():
    # NL = 2: the third C_l row (line 6) is found where the C_d Mach line should be.
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 2 2 3 2 3"))
    assert (err.line, err.column) == (6, 5)
    assert "Mach numbers of the C_d table" in err.reason and "too small" in err.reason


def test_count_too_large_is_a_missing_row():
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 4 2 3 2 3"))
    assert (err.line, err.column) == (7, 1)
    assert "row 4 of 4 of the C_l table" in err.reason


def test_count_too_small_at_the_end_leaves_content():
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 3 2 3 2 2"))
    assert (err.line, err.column) == (14, 5)
    assert "end of file after the last table" in err.reason


def test_wrong_number_of_counts():
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 3 2 3 2"))
    assert err.line == 2 and "6 counts" in err.reason and "found 5" in err.reason
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 3 2 x 2 3"))
    assert (err.line, err.column) == (2, 38)
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 2 3 0 3 2 3"))
    assert (err.line, err.column) == (2, 35) and "at least 1" in err.reason


def test_mach_count_larger_than_the_line():
    err = parse_error(replace_line(TOY, 2, "TOY".ljust(30) + " 3 3 2 3 2 3"))
    assert (err.line, err.column) == (3, 22)
    assert "Mach number 3 of 3" in err.reason


def test_truncated_file():
    text = "\n".join(TOY.splitlines()[:12]) + "\n"
    err = parse_error(text)
    assert (err.line, err.column) == (13, 1)
    assert "end of file" in err.reason and "row 2 of 3 of the C_m table" in err.reason
    # cut in the middle of a line
    err = parse_error(TOY[: TOY.index("   -4.0  -.010") + 7])
    assert (err.line, err.column) == (12, 8) and "end of line" in err.reason


def test_empty_file():
    err = parse_error("# only a comment\n")
    assert (err.line, err.column) == (2, 1) and "title line" in err.reason


def test_blank_line_inside_a_table():
    err = parse_error(replace_line(TOY, 9, ""))
    assert (err.line, err.column) == (9, 1) and "blank line" in err.reason


# 12.3456 is implausible for a coefficient: warned, not tested here
@pytest.mark.filterwarnings("ignore::tefcore.aero.c81.C81PlausibilityWarning")
def test_fixed_columns_win_when_numbers_run_together():
    # Fortran semantics: fields are columns 1-7, 8-14, 15-21 whatever the blanks.
    text = replace_line(TOY, 5, "   0.0  12.34567.1")
    np.testing.assert_array_equal(parse_c81(text).tables["cl"][1], [12.345, 67.1])


def test_flap_deck_errors():
    err = parse_error(delete_line(FLAP, 2))
    assert (err.line, err.column) == (2, 1) and "DELTAS" in err.reason
    err = parse_error(replace_line(FLAP, 19, "DELTA      3.0"))
    assert (err.line, err.column) == (19, 12) and "expected delta = 2" in err.reason
    err = parse_error(replace_line(FLAP, 19, "DELTAS     2.0"))
    assert (err.line, err.column) == (19, 1) and "'DELTA'" in err.reason
    err = parse_error(replace_line(FLAP, 2, "DELTAS     2.0   -2.0"))
    assert (err.line, err.column) == (2, 18) and "flap deflections" in err.reason
    # the grids of one coefficient must be the same for every delta
    err = parse_error(replace_line(FLAP, 23, "           0.0    0.6"))
    assert (err.line, err.column) == (23, 19) and "same for every delta" in err.reason
    err = parse_error(replace_line(FLAP, 33, "    4.0  -.030  -.031"))
    assert (err.line, err.column) == (33, 5) and "same for every delta" in err.reason
    # truncated in the second delta
    err = parse_error("\n".join(FLAP.splitlines()[:30]) + "\n")
    assert (err.line, err.column) == (31, 1) and "for delta = 2 deg" in err.reason


def test_many_deltas_use_continuation_delta_lines():
    rng = np.random.default_rng(3)
    deck = random_deck(rng, True)
    deck.delta = np.arange(11.0) - 5
    for c in deck.coefficients:
        deck.tables[c] = rng.random(deck.tables[c].shape[:2] + (11,))
    text = format_c81(deck)
    assert sum(ln.startswith("DELTAS ") for ln in text.splitlines()) == 2
    np.testing.assert_array_equal(parse_c81(text).delta, deck.delta)
    # a short DELTAS line that is not the last one is an error
    lines = text.splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("DELTAS"))
    lines[k] = lines[k][:-7]
    err = parse_error("\n".join(lines) + "\n")
    assert err.line == k + 2 and "only the last DELTAS line" in err.reason


# --------------------------------------------------------------------------
# interpolation


def multilinear_flap_deck():
    """Tables that are multilinear in (alpha, M, delta): trilinear interpolation
    reproduces them exactly (to rounding) everywhere inside the grid."""
    alpha = np.array([-8.0, -2.0, 0.0, 5.0, 9.0])
    mach = np.array([0.0, 0.3, 0.5, 0.8])
    delta = np.array([-4.0, 0.0, 3.0])
    A, M, D = np.meshgrid(alpha, mach, delta, indexing="ij")
    funcs = {
        "cl": lambda a, m, d: 0.1 * a + 0.5 * m + 0.05 * d + 0.2 * a * m,
        "cd": lambda a, m, d: 0.01 + 0.001 * a * d,
        "cm": lambda a, m, d: -0.01 * d * m,
        "ch": lambda a, m, d: -0.003 * a - 0.01 * d + 0.002 * a * m * d,
        "clf": lambda a, m, d: 0.02 * a + 0.04 * d,
    }
    deck = C81Deck("MULTILINEAR", {c: alpha for c in funcs}, {c: mach for c in funcs},
                   {c: f(A, M, D) for c, f in funcs.items()}, delta=delta)
    return deck, funcs


def test_interpolation_exact_at_grid_points():
    deck = parse_c81(FLAP)
    table = C81FlapTable(deck, 0.35, 0.29)
    A, M, D = np.meshgrid(deck.alpha["cl"], deck.mach["cl"], deck.delta, indexing="ij")
    got = table.static_coefficients(np.radians(A), M, np.radians(D))
    for c in COEFFICIENTS:
        # deg -> rad -> deg conversion: a few ulp of alpha, hence allclose
        np.testing.assert_allclose(got[c], deck.tables[c], rtol=0, atol=1e-12)


def test_interpolation_is_multilinear_between_points():
    deck, funcs = multilinear_flap_deck()
    table = C81FlapTable(deck, 0.35, 0.29)
    rng = np.random.default_rng(11)
    a = rng.uniform(-8, 9, 200)
    m = rng.uniform(0, 0.8, 200)
    d = rng.uniform(-4, 3, 200)
    got = table.static_coefficients(np.radians(a), m, np.radians(d))
    for c, f in funcs.items():
        np.testing.assert_allclose(got[c], f(a, m, d), rtol=0, atol=1e-12)  # rounding only


def test_interpolation_midpoint_is_mean_of_neighbours():
    deck = parse_c81(TOY)
    airfoil = C81Airfoil(deck)
    got = airfoil.static_coefficients(np.radians(2.0), 0.25)
    cell = deck.tables["cl"][1:3, :]
    assert got["cl"] == pytest.approx(cell.mean(), abs=1e-15)


def test_broadcasting_and_blade_deck_flap_coefficients_are_zero():
    airfoil = C81Airfoil(parse_c81(TOY))
    alpha = np.radians(np.linspace(-4, 4, 5))[:, None]
    mach = np.array([0.1, 0.2, 0.4])
    got = airfoil.static_coefficients(alpha, mach, 0.3)
    assert set(got) == set(COEFFICIENTS)
    for c in COEFFICIENTS:
        assert np.shape(got[c]) == (5, 3)
    assert np.all(got["ch"] == 0) and np.all(got["clf"] == 0)
    # delta is ignored by a blade deck
    other = airfoil.static_coefficients(alpha, mach, -0.2)
    np.testing.assert_array_equal(other["cl"], got["cl"])
    assert np.ndim(airfoil.static_coefficients(0.0, 0.3)["cl"]) == 0


def test_single_mach_table_is_constant_in_mach():
    text = """\
ONE MACH                       1 2 1 2 1 2
           0.3
   -2.0   -0.2
    2.0    0.2
           0.3
   -2.0   0.01
    2.0   0.01
           0.3
   -2.0    0.0
    2.0    0.0
"""
    airfoil = C81Airfoil(parse_c81(text))
    assert airfoil.static_coefficients(np.radians(1.0), 0.3)["cl"] == pytest.approx(0.1)
    with pytest.warns(C81RangeWarning, match="mach = 0.5"):
        assert airfoil.static_coefficients(np.radians(1.0), 0.5)["cl"] == pytest.approx(0.1)


# --------------------------------------------------------------------------
# out-of-range policy


def test_in_range_does_not_warn():
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        table.static_coefficients(np.radians([-5, 5]), [0.0, 0.5], np.radians([-2, 2]))


def test_out_of_range_clips_with_one_warning_per_call():
    deck = parse_c81(FLAP)
    table = C81FlapTable(deck, 0.35, 0.29)
    with pytest.warns(C81RangeWarning) as record:
        got = table.static_coefficients(np.radians([7.0, 0.0]), [0.9, 0.2], np.radians(-3.0))
    assert len(record) == 1
    msg = str(record[0].message)
    assert "alpha = 7 deg outside [-5, 5]" in msg
    assert "mach = 0.9 outside [0, 0.5]" in msg
    assert "delta = -3 deg outside [-2, 2]" in msg
    assert "C_l, C_d, C_m, C_h, C_lf" in msg
    # The clipped evaluation equals the evaluation at the edges; never NaN.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        edge = table.static_coefficients(np.radians([5.0, 0.0]), [0.5, 0.2], np.radians(-2.0))
    for c in COEFFICIENTS:
        assert np.all(np.isfinite(got[c]))
        np.testing.assert_array_equal(got[c], edge[c])
    np.testing.assert_array_equal(got["cl"][0], deck.tables["cl"][1, 1, 0])


def test_out_of_range_warns_again_on_the_next_call():
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29)
    for _ in range(2):
        with pytest.warns(C81RangeWarning, match="alpha = -6"):
            table.static_coefficients(np.radians(-6.0), 0.1, 0.0)


def test_out_of_range_raise():
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29, out_of_range="raise")
    with pytest.raises(C81RangeError, match="mach = 0.6 outside"):
        table.static_coefficients(0.0, 0.6, 0.0)
    assert issubclass(C81RangeError, ValueError)
    assert issubclass(C81RangeWarning, UserWarning)
    with pytest.raises(ValueError, match="'clip' or 'raise'"):
        C81Airfoil(parse_c81(TOY), out_of_range="extrapolate")


def test_non_finite_inputs_raise_instead_of_nan():
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29)
    with pytest.raises(ValueError, match="alpha"):
        table.static_coefficients(np.nan, 0.3, 0.0)
    with pytest.raises(ValueError, match="mach"):
        table.static_coefficients(0.0, np.inf, 0.0)


# --------------------------------------------------------------------------
# table model interface and generated decks


class LinearModel:
    """A stand-in with the ThinAirfoilFlap.static_coefficients interface."""

    def static_coefficients(self, alpha, mach, delta):
        inv_beta = 1 / np.sqrt(1 - np.asarray(mach) ** 2)
        return {"cl": (2 * np.pi * alpha + 3.0 * delta) * inv_beta,
                "cd": 0.01 + 0 * alpha,
                "cm": -0.5 * delta * inv_beta,
                "ch": (-0.1 * alpha - 0.6 * delta) * inv_beta,
                "clf": (1.1 * alpha + 2.3 * delta) * inv_beta}


def test_generate_flap_deck_tabulates_the_model():
    model = LinearModel()
    a, m, d = np.arange(-4.0, 5, 2), np.array([0.0, 0.4, 0.7]), np.array([-3.0, 0, 3])
    deck = generate_flap_deck(model, a, m, d, "LINEAR")
    assert deck.is_flap and "GENERATED" in deck.header and "NOT test data" in deck.header
    A, M, D = np.meshgrid(a, m, d, indexing="ij")
    ref = model.static_coefficients(np.radians(A), M, np.radians(D))
    for c in COEFFICIENTS:
        np.testing.assert_array_equal(deck.tables[c], np.broadcast_to(ref[c], A.shape))
    blade = generate_flap_deck(model, a, m, None, "LINEAR BLADE")
    assert not blade.is_flap
    np.testing.assert_array_equal(blade.tables["cl"], deck.tables["cl"][:, :, 1])


def test_loads_delegates_to_flap_aero_section_loads(monkeypatch):
    calls = []

    def fake_section_loads(static_model, **kw):
        calls.append((static_model, kw))
        return {"lift": 1.0}

    fake = types.ModuleType("tefcore.aero.thin_airfoil")
    fake.section_loads = fake_section_loads
    monkeypatch.setitem(sys.modules, "tefcore.aero.thin_airfoil", fake)
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29)
    assert table.loads(alpha=0.01, velocity=100.0) == {"lift": 1.0}
    assert calls == [(table, {"alpha": 0.01, "velocity": 100.0})]
    assert (table.chord_ratio, table.overhang) == (0.35, 0.29)


def test_constructor_accepts_a_path(tmp_path):
    path = tmp_path / "flap.c81"
    path.write_text(FLAP)
    assert C81FlapTable(path, 0.35, 0.29).deck == parse_c81(FLAP)


def test_cli_check(tmp_path, capsys):
    good = tmp_path / "good.c81"
    good.write_text(TOY)
    bad = tmp_path / "bad.c81"
    bad.write_text(replace_line(TOY, 9, "    0.0   .008    x.3"))
    assert tefcore_main(["c81", "check", str(good)]) == 0
    assert "blade deck" in capsys.readouterr().out
    assert tefcore_main(["c81", "check", str(good), str(bad)]) == 1
    err = capsys.readouterr().err
    # every problem line of the command starts as the other commands' errors do
    assert err.startswith(f"tefcore: error: c81 check: {bad} line 9, column 19")
    assert err.count("\n") == 1


# --------------------------------------------------------------------------
# the packaged example deck and the thin-airfoil model

EXAMPLE = example_deck_path()
needs_example = pytest.mark.skipif(
    not EXAMPLE.exists() and not HAVE_FLAP_AERO,
    reason="the example deck is generated from tefcore.aero.thin_airfoil, which does not exist yet")


@needs_example
def test_example_deck_is_labelled_generated_and_has_the_stated_grid():
    deck = read_c81(EXAMPLE)
    text = EXAMPLE.read_text()
    assert text.startswith("# GENERATED by tefcore from the thin-airfoil model "
                           "(Theodorsen quasi-steady + Prandtl-Glauert); NOT test data.")
    assert "NOT test data" in deck.header and "ThinAirfoilFlap(chord_ratio=0.35, " \
        "overhang=0.29, compressibility=True)" in deck.header
    assert deck.is_flap
    np.testing.assert_array_equal(deck.delta, np.arange(-6.0, 7.0, 2.0))
    for c in COEFFICIENTS:
        np.testing.assert_array_equal(deck.alpha[c], np.arange(-10.0, 11.0, 2.0))
        np.testing.assert_allclose(deck.mach[c], np.arange(9) / 10, rtol=0, atol=1e-15)
        assert deck.tables[c].shape == (11, 9, 7)


def inv_beta_second_derivative(m):
    """d²/dM² (1 - M²)^(-1/2) = (1 + 2 M²) / (1 - M²)^(5/2); increasing in M."""
    return (1 + 2 * m**2) / (1 - m**2) ** 2.5


@pytest.fixture(scope="module")
def thin_airfoil():
    from tefcore.aero.thin_airfoil import ThinAirfoilFlap

    return ThinAirfoilFlap(0.35, 0.29, compressibility=True)


@needs_flap_aero
def test_example_deck_reproduces_the_model_at_table_points(thin_airfoil):
    deck = read_c81(EXAMPLE)
    A, M, D = np.meshgrid(deck.alpha["cl"], deck.mach["cl"], deck.delta, indexing="ij")
    ref = thin_airfoil.static_coefficients(np.radians(A), M, np.radians(D))
    table = C81FlapTable(deck, 0.35, 0.29)
    got = table.static_coefficients(np.radians(A), M, np.radians(D))
    for c in COEFFICIENTS:
        r = np.broadcast_to(ref[c], A.shape)
        # printed to half the last digit; interpolation at nodes adds rounding only
        assert_within(deck.tables[c], r, print_tol(r), c)
        assert_within(got[c], r, print_tol(r) + 1e-12, c)


@needs_flap_aero
def test_example_deck_is_the_current_model(thin_airfoil, tmp_path):
    # The shipped file is what `tefcore c81 example` writes today
    # (else: regenerate it).  Values may differ by one in the last digit at
    # rounding ties, so compare through the reader at print precision.
    assert tefcore_main(["c81", "example", "--out", str(tmp_path / "new.c81")]) == 0
    new, shipped = read_c81(tmp_path / "new.c81"), read_c81(EXAMPLE)
    assert new.header == shipped.header and new.name == shipped.name
    for c in COEFFICIENTS:
        np.testing.assert_allclose(new.tables[c], shipped.tables[c], rtol=0,
                                   atol=2 * print_tol(new.tables[c]).max())


def test_the_example_command_writes_into_the_current_folder_not_the_package(tmp_path,
                                                                           monkeypatch):
    # a user's command never writes into the package (from a wheel, site-packages)
    before = EXAMPLE.stat().st_mtime_ns
    monkeypatch.chdir(tmp_path)
    assert tefcore_main(["c81", "example"]) == 0
    assert (tmp_path / EXAMPLE.name).is_file() and EXAMPLE.stat().st_mtime_ns == before


@needs_flap_aero
def test_example_deck_between_points_within_interpolation_bound(thin_airfoil):
    """Linear interpolation error <= h²/8 max|f''| per direction.

    The thin-airfoil coefficients are linear in alpha and delta (cd is
    constant with the default cd1 = cd2 = 0), so trilinear interpolation is
    exact in those directions; in Mach they scale as f(alpha, 0, delta)/beta
    with 1/beta = (1 - M²)^(-1/2).  Hence on a Mach cell [M0, M0 + h]
        |error| <= |f(alpha, 0, delta)| * h²/8 * (1/beta)''(M0 + h)
    ((1/beta)'' is increasing), plus the print rounding of the table values
    (interpolation weights are non-negative and sum to one, so at most the
    largest rounding error of the deck).
    """
    deck = read_c81(EXAMPLE)
    table = C81FlapTable(deck, 0.35, 0.29)
    rng = np.random.default_rng(2024)
    n = 2000
    a = rng.uniform(-10, 10, n)
    m = rng.uniform(0, 0.8, n)
    d = rng.uniform(-6, 6, n)
    got = table.static_coefficients(np.radians(a), m, np.radians(d))
    ref = thin_airfoil.static_coefficients(np.radians(a), m, np.radians(d))
    ref0 = thin_airfoil.static_coefficients(np.radians(a), 0.0 * m, np.radians(d))
    h = 0.1
    upper = np.minimum((np.floor(m / h) + 1) * h, 0.8)
    for c in COEFFICIENTS:
        rounding = print_tol(deck.tables[c]).max()
        bound = np.abs(ref0[c]) * h**2 / 8 * inv_beta_second_derivative(upper) + rounding
        err = np.abs(got[c] - np.broadcast_to(ref[c], a.shape))
        assert np.all(err <= bound), (c, float((err - bound).max()))
    # The bound is not vacuous: at the top Mach cell the C_l error is a
    # visible fraction of it (the curvature of 1/beta is real).
    sel = (m > 0.72) & (m < 0.78) & (np.abs(a) > 5)
    err_cl = np.abs(got["cl"] - ref["cl"])[sel]
    bound_cl = (np.abs(ref0["cl"]) * h**2 / 8 * inv_beta_second_derivative(0.8))[sel]
    assert np.max(err_cl / bound_cl) > 0.3


@needs_flap_aero
def test_table_model_loads_match_thin_airfoil_at_table_points(thin_airfoil):
    from tefcore.aero.thin_airfoil import section_loads

    deck = read_c81(EXAMPLE)
    table = C81FlapTable(deck, 0.35, 0.29)
    chord, alpha_rate = 0.254, 0.3
    # plunge_rate = b * alpha_rate puts the 3/4-chord angle alpha_eff on the
    # table node alpha = 4 deg (axis at the quarter chord: a = -1/2).
    kw = dict(alpha=np.radians(4.0), alpha_rate=alpha_rate, alpha_accel=2.0,
              plunge_rate=0.5 * chord * alpha_rate, plunge_accel=-3.0, delta=np.radians(2.0),
              delta_rate=0.5, delta_accel=40.0, velocity=150.0, density=1.2, chord=chord,
              axis=0.25, mach=0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # in range: no C81RangeWarning
        got = table.loads(**kw)
    ref = section_loads(thin_airfoil, **kw)
    assert got.keys() == ref.keys()
    # The rate terms are the same thin-airfoil terms, so the coefficients differ
    # only by the printed precision of the static table values.
    for c in COEFFICIENTS:
        assert abs(got[c] - ref[c]) <= print_tol(deck.tables[c]).max(), c
    assert abs(got["ch"] - ref["ch"]) > 0  # really the table, not the model


def test_grid_edge_after_rad_deg_round_trip_is_not_out_of_range():
    table = C81FlapTable(parse_c81(FLAP), 0.35, 0.29)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        table.static_coefficients(np.radians(-5.0), 0.5, np.radians(np.array([-2.0, 2.0])))


# ------------------------------------------------------------------ hostile files


def shipped_lines():
    return example_deck_path().read_bytes().split(b"\n")


def title_index(lines):
    return next(i for i, ln in enumerate(lines) if ln and not ln.startswith(b"#"))


def test_non_utf8_bytes_are_a_format_error_with_line_and_column(tmp_path):
    """A non-UTF-8 byte is a C81FormatError naming its line and column, not a
    bare UnicodeDecodeError (which 148 of 500 byte mutations of the deck would give)."""
    lines = shipped_lines()
    lines[20] = b"   -6.0 \xff" + lines[20][9:]
    path = tmp_path / "bad.c81"
    path.write_bytes(b"\n".join(lines))
    with pytest.raises(C81FormatError) as info:
        read_c81(path)
    assert (info.value.line, info.value.column) == (21, 9) and "not UTF-8" in info.value.reason


@pytest.mark.parametrize("count", ["²", "٣", "-1", "1e3"])
def test_counts_are_ascii_integers(count):
    """A count that is not an ASCII integer is refused naming its line and column (int()
    reads '٣' as 3 and refuses '²' with a bare ValueError)."""
    text = replace_line(TOY_FREE, 1, "TOY".ljust(30) + f" 2 3 2 3 2 {count}")
    err = parse_error(text)
    assert (err.line, err.column) == (1, 42) and "integer count" in err.reason


def test_a_huge_count_is_refused_before_allocating():
    """A count of 10^7 in a 3-line file is refused at once (allocating it takes 9.7 s
    and 1.2 GB)."""
    import tracemalloc

    text = "BIG".ljust(30) + " 10000000 3 2 3 2 3\n           0.0    0.5\n    0.0    0.0    0.0\n"
    tracemalloc.start()
    try:
        err = parse_error(text)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 10 * 2**20          # a few kB are needed; 10 MB is far below the 1.2 GB seen
    assert (err.line, err.column) == (1, 32) and "need at least 4444448 line(s)" in err.reason


def test_a_lost_decimal_point_warns_naming_the_number(tmp_path):
    """'.01000' typed as '01000' reads as 1000: a warning names the number."""
    lines = shipped_lines()
    k = next(i for i, ln in enumerate(lines) if b".01000" in ln)
    lines[k] = lines[k].replace(b" .01000", b" 01000", 1)
    path = tmp_path / "typo.c81"
    path.write_bytes(b"\n".join(lines))
    col = lines[k].index(b"01000") + 1
    with pytest.warns(UserWarning,
                      match=rf"typo\.c81 line {k + 1}, column {col}: C_d .* = 1000 is far "
                            r"outside") as record:
        deck = read_c81(path)
    assert [type(w.message).__name__ for w in record] == ["C81PlausibilityWarning"]
    assert deck.tables["cd"].max() == 1000.0      # read as written: a warning, not a guess
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_c81(example_deck_path())             # the shipped deck is plausible
