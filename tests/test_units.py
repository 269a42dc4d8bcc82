"""Tests of tefcore.units: factors, dimensions, the bare 'lb', and errors."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy import constants as sc

from tefcore.units import (
    DIMENSIONS,
    SI_UNITS,
    format_dims,
    from_si,
    parse_quantity,
    parse_unit,
    resolve_dimension,
    to_si,
)

# Conversions multiply exact scipy constants in a fixed order; comparing
# against the same constants combined in another order can differ by a few
# ulp, hence a relative tolerance of a few machine epsilons where noted.
EPS4 = 4 * np.finfo(float).eps


def test_length_factors_are_scipy_constants():
    assert to_si(1, "ft") == sc.foot
    assert to_si(17, "ft") == 17 * sc.foot
    assert to_si(10, "in") == 10 * sc.inch
    assert to_si(1, "inch") == sc.inch


@pytest.mark.parametrize("unit", ["rpm", "RPM", "Rpm"])
def test_rpm_is_case_insensitive(unit):
    # 2 pi / 60 evaluated in another order: a few ulp.
    assert math.isclose(to_si(392, unit), 392 * 2 * math.pi / 60, rel_tol=EPS4)
    assert parse_unit(unit)[1] == DIMENSIONS["angular_velocity"]


def test_angles_are_dimensionless():
    assert parse_unit("rad") == (1.0, (0, 0, 0))
    assert to_si(180, "deg") == 180 * sc.degree
    assert math.isclose(to_si(180, "deg"), math.pi, rel_tol=EPS4)
    assert to_si(29, "percent") == 29 * 0.01
    assert to_si(29, "%") == to_si(29, "percent")
    assert parse_unit("1") == (1.0, (0, 0, 0))


def test_lb_per_in_to_newton_per_metre():
    # Reference 175.1268 N/m is printed to 7 digits: half the last digit.
    assert to_si(1, "lb/in", "force_per_length") == pytest.approx(175.1268, abs=5e-5)
    assert to_si(1, "lbf/in") == sc.pound_force / sc.inch


def test_ft_lb_per_rad_to_newton_metre_per_rad():
    # Reference 1.355818 printed to 7 digits: half the last digit.
    assert to_si(1, "ft-lb/rad", "moment_per_angle") == pytest.approx(1.355818, abs=5e-7)
    assert parse_unit("ft-lb/rad", "moment_per_angle")[1] == (1, 2, -2)


@pytest.mark.parametrize("unit", ["ft-lb/rad/sec", "ft*lbf/rad/s", "ft-lb-sec/rad", "N*m/(rad/s)"])
def test_damping_units(unit):
    # "per rad/sec" engineering notation: same product of constants, few ulp.
    factor, dims = parse_unit(unit, "moment_damping")
    assert dims == (1, 2, -1)
    expected = 1.0 if unit.startswith("N") else sc.foot * sc.pound_force
    assert math.isclose(factor, expected, rel_tol=EPS4)


def test_literal_reading_of_chained_division_without_dimension():
    # Without an expected dimension "/rad/s" divides twice (no guessing).
    assert parse_unit("ft*lbf/rad/s")[1] == (1, 2, -3)


def test_mass_per_length_units():
    assert to_si(1, "slug/ft") == sc.slug / sc.foot
    assert to_si(1, "lb/ft", "mass_per_length") == sc.pound / sc.foot
    assert to_si(1, "kg/m", "mass_per_length") == 1.0


def test_inertia_per_length_units():
    factor, dims = parse_unit("slug*ft^2/ft")
    assert dims == DIMENSIONS["inertia_per_length"]
    assert math.isclose(factor, sc.slug * sc.foot, rel_tol=EPS4)
    assert parse_unit("kg*m^2/m") == (1.0, DIMENSIONS["inertia_per_length"])


def test_stiffness_units():
    assert parse_unit("N/m") == (1.0, DIMENSIONS["force_per_length"])
    assert parse_unit("N*m^2") == (1.0, DIMENSIONS["bending_stiffness"])
    # EI quoted in lb*in^2 means lbf*in^2.
    factor, _ = parse_unit("lb*in^2", "bending_stiffness")
    assert factor == sc.pound_force * sc.inch**2


def test_bare_lb_resolved_by_dimension():
    assert to_si(1, "lb/ft", "mass_per_length") == sc.pound / sc.foot
    assert to_si(1, "lb/ft", "force_per_length") == sc.pound_force / sc.foot
    assert parse_unit("lb*ft^2/ft", "inertia_per_length")[0] == sc.pound * sc.foot


def test_bare_lb_needs_a_dimension():
    with pytest.raises(ValueError, match="ambiguous"):
        parse_unit("lb/in")
    with pytest.raises(ValueError, match="'lb/in'.*velocity"):
        parse_unit("lb/in", "velocity")  # neither lbm/in nor lbf/in is a velocity


def test_lb_that_cancels_is_not_ambiguous():
    assert parse_unit("lb/lb") == (1.0, (0, 0, 0))


@pytest.mark.parametrize("name", sorted(SI_UNITS))
def test_si_units_have_unit_factor(name):
    assert parse_unit(SI_UNITS[name], name) == (1.0, DIMENSIONS[name])


def test_arrays_and_exponents():
    np.testing.assert_array_equal(to_si([1, 2], "in"), [sc.inch, 2 * sc.inch])
    assert parse_unit("ft^-1")[1] == (0, -1, 0)
    assert parse_unit("ft**2")[1] == (0, 2, 0)
    assert parse_unit("s^(-1)")[1] == (0, 0, -1)
    assert parse_unit("kg/m^3")[1] == DIMENSIONS["density"]


@pytest.mark.parametrize(
    "unit", ["furlong", "M", "Hz", "ft^x", "(ft", "ft)", "", "in2", "ft^", "*ft", "ft//s"]
)
def test_bad_units_raise(unit):
    # "M" is not metres (SI symbols are case-sensitive); "Hz" is refused so
    # it cannot be mistaken for rad/s; "in2" must not scale by 2.
    with pytest.raises(ValueError):
        parse_unit(unit)


def test_dimension_mismatch_names_unit_and_dimension():
    with pytest.raises(ValueError, match=r"'ft'.*expected mass_per_length"):
        to_si(3, "ft", "mass_per_length")
    with pytest.raises(ValueError, match="unknown dimension 'lenght'"):
        to_si(3, "ft", "lenght")


def test_dimension_vectors():
    assert resolve_dimension((1, 2, -1)) == DIMENSIONS["moment_damping"]
    assert format_dims((0, 0, 0)) == "1"
    with pytest.raises(ValueError):
        resolve_dimension((1, 2))


def test_parse_quantity():
    assert parse_quantity("34 ft", "length") == 34 * sc.foot
    assert parse_quantity("-2.5e1 deg") == -25 * sc.degree
    with pytest.raises(ValueError, match="has no unit"):
        parse_quantity("0.3")
    with pytest.raises(ValueError):
        parse_quantity("ft 34")


ROUND_TRIP_UNITS = ["ft", "in", "rpm", "deg", "slug/ft", "lbf/in", "ft*lbf/rad", "percent"]


@given(
    value=st.floats(min_value=-1e12, max_value=1e12, allow_nan=False),
    unit=st.sampled_from(ROUND_TRIP_UNITS),
)
def test_round_trip(value, unit):
    # x * f / f may be off by one rounding in each operation: 4 eps relative.
    back = from_si(to_si(value, unit), unit)
    assert math.isclose(back, value, rel_tol=EPS4, abs_tol=1e-300)


def test_unit_factors_are_scipys_bit_for_bit():
    # tefcore.units writes the definitions out (importing scipy.constants costs
    # 0.1 s of every command's start-up); the factors must be the very same
    # floats as scipy's, so no converted input changes in its last bit
    from tefcore import units

    expected = {"deg": sc.degree, "rpm": 2.0 * math.pi / sc.minute, "cm": sc.centi,
                "mm": sc.milli, "km": sc.kilo, "ft": sc.foot, "in": sc.inch, "g": sc.gram,
                "lbm": sc.pound, "slug": sc.slug, "min": sc.minute, "h": sc.hour,
                "kN": sc.kilo, "lbf": sc.pound_force, "psi": sc.psi, "kt": sc.knot,
                "mph": sc.mph}
    for unit, factor in expected.items():
        assert units._UNITS[unit][0] == factor, unit
    assert to_si(1, "lb", "mass") == sc.pound
    assert to_si(1, "lb", "force") == sc.pound_force
