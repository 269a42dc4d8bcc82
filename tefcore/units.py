"""Unit expressions and conversion to the SI units used internally.

Every quantity inside tefcore is SI (kg, m, s, N, rad).  Input files quote
the paper's units ("34 ft", "392 RPM", "81.52 ft-lb/rad"); this module turns
such unit expressions into an SI factor and a dimension vector
``(M, L, T)`` (mass, length, time exponents).  Angles are dimensionless:
``rad`` has factor 1, ``deg`` factor pi/180 and ``rpm`` factor 2 pi/60.

Grammar of a unit expression: base units joined by ``*``, ``-``, ``·`` or a
space (product) and ``/`` (each ``/`` divides by the next factor only, so
``ft-lb/rad/sec`` is ft lb rad^-1 s^-1), with integer powers ``^2``,
``**2`` or ``^-1``, and parentheses.  ``1`` and ``percent``/``%`` are
dimensionless.

Rates quoted per angular velocity, such as Table 1's actuator damping
"0.005 ft-lb/rad/sec", mean ft-lb per (rad/sec) although a literal reading
gives ft-lb rad^-1 s^-1.  When an expected dimension is given and the
literal reading does not match it, a trailing ``/<angle>/<time>`` is re-read
as ``/(<angle>/<time>)``; the result must then match.

The bare ``lb`` is ambiguous (pound-mass or pound-force).  It is resolved
by the expected dimension: both readings are tried and the one whose
dimension matches is kept.  ``lbm`` and ``lbf`` are never ambiguous.

Angles are dimensionless for the conversion, but the parser also counts the
net power of the angle units (``rad``, ``deg``, ``rev``, and the ``rev`` in
``rpm``), and the three named dimensions that differ only by it are told
apart: a ``"dimensionless"`` quantity refuses a unit with an angle
(``"5 deg"`` for C_T/sigma), an ``"angle"`` needs one angle unit and a
``"per_angle"`` quantity one inverse angle.  Other named dimensions (e.g.
``moment_per_angle``) and explicit (M, L, T) vectors do not check it.

Limits (so that no input can overflow, recurse or run long): a unit
expression has at most :data:`MAX_UNIT_LENGTH` characters, integer powers
at most :data:`MAX_POWER` in magnitude, parentheses nested at most
:data:`MAX_DEPTH` deep, and the SI factor must be a finite, normal
number; anything else is a ``ValueError``.

Examples
--------
>>> to_si(34, "ft")
10.363199999999999
>>> round(to_si(330, "lb/in", "force_per_length"), 3)
57791.856
>>> round(to_si(2.031, "lb/ft", "mass_per_length"), 4)
3.0225
>>> from_si(to_si(392, "RPM"), "rpm")
392.0
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Sequence

import numpy as np

# SI factors of the imperial and named units, as exact definitions (NIST SP 811;
# the international foot and pound of 1959, standard gravity), computed by the
# same expressions as ``scipy.constants`` so that every factor is bit for bit the
# same (tests/test_units.py checks it) without importing scipy.constants (0.1 s).
_DEGREE = math.pi / 180
_MINUTE = 60.0
_HOUR = 60 * _MINUTE
_INCH = 0.0254
_FOOT = 12 * _INCH
_MILE = 1760 * (3 * _FOOT)
_GRAVITY = 9.80665                           # standard acceleration of gravity
_POUND = 7000 * 64.79891e-6                  # 7000 grains
_SLUG = _POUND * _GRAVITY / 0.0254 / 12      # lbf s^2 / ft
_POUND_FORCE = _POUND * _GRAVITY
_PSI = _POUND * _GRAVITY / (_INCH * _INCH)
_KNOT = 1852.0 / _HOUR
_MPH = _MILE / _HOUR

__all__ = [
    "DIMENSIONS",
    "MAX_DEPTH",
    "MAX_POWER",
    "MAX_UNIT_LENGTH",
    "SI_UNITS",
    "dimension_name",
    "format_dims",
    "from_si",
    "parse_quantity",
    "parse_unit",
    "resolve_dimension",
    "to_si",
]

Dims = tuple[int, int, int]

_NONE: Dims = (0, 0, 0)
_MASS: Dims = (1, 0, 0)
_LENGTH: Dims = (0, 1, 0)
_TIME: Dims = (0, 0, 1)
_FORCE: Dims = (1, 1, -2)

#: Named physical dimensions as (M, L, T) exponent vectors.
DIMENSIONS: dict[str, Dims] = {
    "dimensionless": _NONE,
    "angle": _NONE,
    "per_angle": _NONE,
    "mass": _MASS,
    "length": _LENGTH,
    "time": _TIME,
    "velocity": (0, 1, -1),
    "angular_velocity": (0, 0, -1),
    "density": (1, -3, 0),
    "mass_per_length": (1, -1, 0),
    "mass_moment_per_length": (1, 1, 0),
    "inertia_per_length": (1, 1, 0),
    "inertia": (1, 2, 0),
    "force": _FORCE,
    "force_per_length": (1, 0, -2),
    "moment_per_angle": (1, 2, -2),
    "moment_damping": (1, 2, -1),
    "bending_stiffness": (1, 3, -2),
    "torsional_stiffness": (1, 3, -2),
}

#: SI unit string for each named dimension; every one parses to factor 1.0.
SI_UNITS: dict[str, str] = {
    "dimensionless": "1",
    "angle": "rad",
    "per_angle": "1/rad",
    "mass": "kg",
    "length": "m",
    "time": "s",
    "velocity": "m/s",
    "angular_velocity": "rad/s",
    "density": "kg/m^3",
    "mass_per_length": "kg/m",
    "mass_moment_per_length": "kg*m",
    "inertia_per_length": "kg*m^2/m",
    "inertia": "kg*m^2",
    "force": "N",
    "force_per_length": "N/m",
    "moment_per_angle": "N*m/rad",
    "moment_damping": "N*m*s/rad",
    "bending_stiffness": "N*m^2",
    "torsional_stiffness": "N*m^2",
}

#: Longest unit expression accepted (characters).
MAX_UNIT_LENGTH = 120
#: Largest magnitude of an integer power (``m^12``).
MAX_POWER = 12
#: Deepest nesting of parentheses.
MAX_DEPTH = 8
#: Net angle power each angle-like named dimension must have (see the module docstring).
_ANGLE_POWER = {"dimensionless": 0, "angle": 1, "per_angle": -1}
#: Base units that are angles (``rpm`` is rev/min: it counts one too).
_ANGLES = frozenset({"rad", "deg", "degree", "degrees", "rev", "rpm"})

# Base units: name -> (SI factor, dims).  "Hz" is left out on purpose: with
# rad dimensionless, 1 Hz would silently equal 1 rad/s; write "rev/s".
_UNITS: dict[str, tuple[float, Dims]] = {
    "1": (1.0, _NONE),
    "percent": (0.01, _NONE),
    "%": (0.01, _NONE),
    "rad": (1.0, _NONE),
    "deg": (_DEGREE, _NONE),
    "degree": (_DEGREE, _NONE),
    "degrees": (_DEGREE, _NONE),
    "rev": (2.0 * math.pi, _NONE),
    "rpm": (2.0 * math.pi / _MINUTE, (0, 0, -1)),
    "m": (1.0, _LENGTH),
    "cm": (1e-2, _LENGTH),
    "mm": (1e-3, _LENGTH),
    "km": (1e3, _LENGTH),
    "ft": (_FOOT, _LENGTH),
    "foot": (_FOOT, _LENGTH),
    "feet": (_FOOT, _LENGTH),
    "in": (_INCH, _LENGTH),
    "inch": (_INCH, _LENGTH),
    "inches": (_INCH, _LENGTH),
    "kg": (1.0, _MASS),
    "g": (1e-3, _MASS),
    "lbm": (_POUND, _MASS),
    "slug": (_SLUG, _MASS),
    "s": (1.0, _TIME),
    "sec": (1.0, _TIME),
    "min": (_MINUTE, _TIME),
    "h": (_HOUR, _TIME),
    "N": (1.0, _FORCE),
    "kN": (1e3, _FORCE),
    "lbf": (_POUND_FORCE, _FORCE),
    "Pa": (1.0, (1, -1, -2)),
    "psi": (_PSI, (1, -1, -2)),
    "J": (1.0, (1, 2, -2)),
    "kt": (_KNOT, (0, 1, -1)),
    "knot": (_KNOT, (0, 1, -1)),
    "mph": (_MPH, (0, 1, -1)),
}
# Imperial and named units are matched case-insensitively ("RPM", "Deg");
# SI symbols are not ("m" is not "M", "s" is not "S").
_CASELESS = {
    k.lower(): k
    for k in (
        "percent rad deg degree degrees rev rpm ft foot feet in inch inches "
        "lbm slug sec lbf psi kt knot mph"
    ).split()
}
_AMBIGUOUS_LB = "lb"

_TOKEN = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
    r"|(?P<name>[A-Za-z_%][A-Za-z_]*)"
    r"|(?P<op>\*\*|[*/^()·-]))"
)
_PER_RATE = re.compile(r"/\s*(rad|deg|degrees?|rev)\s*/\s*(s|sec|min)\s*$", re.IGNORECASE)
_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def resolve_dimension(dimension: str | Sequence[int]) -> Dims:
    """Return the (M, L, T) vector of a dimension name or vector.

    Parameters
    ----------
    dimension : str or sequence of 3 int
        A key of :data:`DIMENSIONS` or an explicit exponent vector.

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        If the name is unknown or the vector is not 3 integers.

    Examples
    --------
    >>> resolve_dimension("moment_damping")
    (1, 2, -1)
    """
    if isinstance(dimension, str):
        try:
            return DIMENSIONS[dimension]
        except KeyError:
            raise ValueError(
                f"unknown dimension {dimension!r}; known: {', '.join(sorted(DIMENSIONS))}"
            ) from None
    dims = tuple(int(d) for d in dimension)
    if len(dims) != 3 or any(d != e for d, e in zip(dims, dimension, strict=True)):
        raise ValueError(f"dimension vector must be 3 integers (M, L, T), got {dimension!r}")
    return dims  # type: ignore[return-value]


def format_dims(dims: Sequence[int]) -> str:
    """Format a dimension vector, e.g. ``M L^2 T^-1``; ``1`` if dimensionless.

    Parameters
    ----------
    dims : sequence of int
        Exponents of (M, L, T, angle).

    Returns
    -------
    str

    Examples
    --------
    >>> format_dims((1, 2, -1))
    'M L^2 T^-1'
    """
    parts = [sym if e == 1 else f"{sym}^{e}" for sym, e in zip("MLT", dims, strict=True) if e != 0]
    return " ".join(parts) or "1"


def dimension_name(dims: Sequence[int]) -> str:
    """Describe a dimension vector by its exponents and any matching names.

    Parameters
    ----------
    dims : sequence of int
        Exponents of (M, L, T, angle).

    Returns
    -------
    str

    Examples
    --------
    >>> dimension_name((0, 1, 0))
    'L (length)'
    """
    names = [k for k, v in DIMENSIONS.items() if v == tuple(dims)]
    return format_dims(dims) + (f" ({', '.join(names)})" if names else "")


class _Parser:
    """Recursive-descent parser; counts the net powers of the bare ``lb`` and of angles.

    Each production returns ``(factor, dims, n_lb, n_angle)``.
    """

    def __init__(self, text: str):
        if len(text) > MAX_UNIT_LENGTH:
            raise ValueError(f"unit {text[:20]!r}... is longer than {MAX_UNIT_LENGTH} characters")
        self.text = text
        self.depth = 0
        self.tokens: list[tuple[str, str]] = []
        pos, text = 0, text.rstrip()
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None or m.end() == pos:
                raise ValueError(f"cannot parse unit {self.text!r} at {text[pos:]!r}")
            kind = m.lastgroup
            self.tokens.append((kind, m.group(kind)))  # type: ignore[arg-type]
            pos = m.end()
        self.i = 0

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        if tok is None:
            raise ValueError(f"unit {self.text!r} ends unexpectedly")
        self.i += 1
        return tok

    def parse(self) -> tuple[float, list[int], int, int]:
        if not self.tokens:
            raise ValueError("empty unit string")
        try:
            result = self.expr()
        except (OverflowError, ZeroDivisionError):
            result = (math.inf, [0, 0, 0], 0, 0)
        if self.peek() is not None:
            raise ValueError(f"unexpected {self.peek()[1]!r} in unit {self.text!r}")
        if not (math.isfinite(result[0]) and result[0] >= sys.float_info.min):
            raise ValueError(f"unit {self.text!r} is out of range (its SI factor over- or "
                             "underflows)")
        return result

    def expr(self) -> tuple[float, list[int], int, int]:
        factor, dims, n_lb, n_ang = self.power()
        while (tok := self.peek()) is not None and tok != ("op", ")"):
            if tok[0] == "op" and tok[1] in "*-·/":
                self.i += 1
            sign = -1 if tok == ("op", "/") else 1  # otherwise implicit product
            f, d, n, a = self.power()
            factor *= f**sign
            dims = [x + sign * y for x, y in zip(dims, d, strict=True)]
            n_lb += sign * n
            n_ang += sign * a
        return factor, dims, n_lb, n_ang

    def power(self) -> tuple[float, list[int], int, int]:
        factor, dims, n_lb, n_ang = self.atom()
        if (tok := self.peek()) is not None and tok[1] in ("^", "**"):
            self.i += 1
            p = self.exponent()
            factor, dims, n_lb, n_ang = factor**p, [d * p for d in dims], n_lb * p, n_ang * p
        return factor, dims, n_lb, n_ang

    def exponent(self) -> int:
        kind, val = self.take()
        if val == "(":
            self.open()
            p = self.exponent()
            self.close()
            return p
        sign = 1
        if val == "-":
            sign, (kind, val) = -1, self.take()
        if kind != "num" or not (val.isascii() and val.isdigit()):
            raise ValueError(f"exponent must be an integer in unit {self.text!r}")
        if len(val) > 3 or int(val) > MAX_POWER:
            raise ValueError(f"exponent {sign * int(val[:20])} in unit {self.text!r} is out of "
                             f"range (at most {MAX_POWER} in magnitude)")
        return sign * int(val)

    def open(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ValueError(f"parentheses nested more than {MAX_DEPTH} deep in unit "
                             f"{self.text[:40]!r}")

    def close(self) -> None:
        if self.take()[1] != ")":
            raise ValueError(f"missing ')' in unit {self.text!r}")
        self.depth -= 1

    def atom(self) -> tuple[float, list[int], int, int]:
        kind, val = self.take()
        if val == "(":
            self.open()
            result = self.expr()
            self.close()
            return result
        if kind == "num":
            # Only "1" (as in "1/rad"): a stray number such as the "2" of
            # "in2" must not silently scale the unit.
            if float(val) != 1.0:
                raise ValueError(f"unexpected number {val!r} in unit {self.text!r}")
            return 1.0, [0, 0, 0], 0, 0
        if kind == "name":
            if val.lower() == _AMBIGUOUS_LB:
                return 1.0, [0, 0, 0], 1, 0
            key = val if val in _UNITS else _CASELESS.get(val.lower())
            if key is not None:
                factor, dims = _UNITS[key]
                return factor, list(dims), 0, int(key in _ANGLES)
            raise ValueError(f"unknown unit {val!r} in {self.text!r}")
        raise ValueError(f"unexpected {val!r} in unit {self.text!r}")


def parse_unit(unit: str, dimension: str | Sequence[int] | None = None) -> tuple[float, Dims]:
    """Parse a unit expression into its SI factor and dimension vector.

    Parameters
    ----------
    unit : str
        Unit expression, e.g. ``"ft-lb/rad/sec"`` or ``"slug*ft^2/ft"``.
    dimension : str or sequence of int, optional
        Expected dimension (a :data:`DIMENSIONS` key or an (M, L, T) vector).
        When given, the result must match it, and it decides whether a bare
        ``lb`` means pound-mass or pound-force.

    Returns
    -------
    factor : float
        Multiply a value in `unit` by this to get SI.
    dims : tuple of int
        (M, L, T) exponents.

    Raises
    ------
    ValueError
        Unknown unit, syntax error, dimension mismatch, or an ``lb`` that
        cannot be resolved.

    Examples
    --------
    >>> parse_unit("ft-lb/rad", "moment_per_angle")[1]
    (1, 2, -2)
    >>> parse_unit("lb*in^2", "bending_stiffness")[0] == 4.4482216152605 * 0.0254**2
    True
    >>> parse_unit("furlong")
    Traceback (most recent call last):
    ...
    ValueError: unknown unit 'furlong' in 'furlong'
    """
    if not isinstance(unit, str):
        raise ValueError(f"unit must be a string, got {unit!r}")
    try:
        return _parse_unit(unit, unit, dimension)
    except ValueError:
        # Engineering notation "ft-lb/rad/sec" = ft-lb per (rad/sec).
        rate = _PER_RATE.search(unit)
        if dimension is None or rate is None:
            raise
        alternative = f"{unit[: rate.start()]}/({rate.group(1)}/{rate.group(2)})"
        try:
            return _parse_unit(alternative, unit, dimension)
        except ValueError:
            pass
        raise


def _parse_unit(text: str, unit: str, dimension: str | Sequence[int] | None) -> tuple[float, Dims]:
    expected = None if dimension is None else resolve_dimension(dimension)
    where = "" if dimension is None else f" (expected {_describe(dimension)})"
    try:
        factor, dims_list, n_lb, n_angle = _Parser(text).parse()
    except ValueError as err:
        raise ValueError(f"{err}{where}") from None
    dims: Dims = tuple(dims_list)  # type: ignore[assignment]
    if isinstance(dimension, str) and dimension in _ANGLE_POWER:
        want = _ANGLE_POWER[dimension]
        if n_angle != want and dims == _NONE and not n_lb:
            got = {0: "has no angle unit", 1: "is an angle", -1: "is a per-angle unit"}.get(
                n_angle, f"has angle power {n_angle}")
            need = {"dimensionless": "a pure number (no unit, '1' or 'percent')",
                    "angle": "an angle (rad, deg, rev)",
                    "per_angle": "a per-angle quantity (1/rad, 1/deg)"}[dimension]
            raise ValueError(f"unit {unit!r} {got}, expected {need}")
    if n_lb:
        # Try both readings of the bare "lb"; keep the one that fits.
        readings = {
            "lbm": (factor * _POUND**n_lb, _add(dims, _MASS, n_lb)),
            "lbf": (factor * _POUND_FORCE**n_lb, _add(dims, _FORCE, n_lb)),
        }
        if expected is None:
            raise ValueError(
                f"'lb' in unit {unit!r} is ambiguous (lbm or lbf); write lbm/lbf "
                "or give the expected dimension"
            )
        fits = [r for r in readings.values() if r[1] == expected]
        if len(fits) != 1:
            raise ValueError(
                f"unit {unit!r} does not match the expected dimension "
                f"{_describe(dimension)} with 'lb' read as either lbm or lbf"
            )
        return fits[0]
    if expected is not None and dims != expected:
        raise ValueError(
            f"unit {unit!r} has dimension {dimension_name(dims)}, expected {_describe(dimension)}"
        )
    return factor, dims


def _add(dims: Dims, other: Dims, n: int) -> Dims:
    return tuple(a + n * b for a, b in zip(dims, other, strict=True))  # type: ignore[return-value]


def _describe(dimension: str | Sequence[int]) -> str:
    if isinstance(dimension, str):
        return f"{dimension} [{format_dims(resolve_dimension(dimension))}]"
    return format_dims(dimension)


def to_si(value, unit: str, dimension: str | Sequence[int] | None = None):
    """Convert `value` expressed in `unit` to SI.

    Parameters
    ----------
    value : float or array_like
        Value(s) in `unit`.
    unit : str
        Unit expression (see :func:`parse_unit`).
    dimension : str or sequence of int, optional
        Expected dimension; checked, and used to resolve a bare ``lb``.

    Returns
    -------
    float or numpy.ndarray
        A float for scalar input, otherwise an array.

    Raises
    ------
    ValueError
        As :func:`parse_unit`.

    Examples
    --------
    >>> round(to_si(81.52, "ft-lb/rad", "moment_per_angle"), 4)
    110.5263
    >>> to_si([1, 2], "in")
    array([0.0254, 0.0508])
    """
    factor, _ = parse_unit(unit, dimension)
    if np.ndim(value) == 0:
        return float(value) * factor
    return np.asarray(value, dtype=float) * factor


def from_si(value, unit: str, dimension: str | Sequence[int] | None = None):
    """Convert an SI `value` to `unit`; the inverse of :func:`to_si`.

    Parameters
    ----------
    value : float or array_like
        Value(s) in SI.
    unit : str
        Target unit expression.
    dimension : str or sequence of int, optional
        Expected dimension of `unit`.

    Returns
    -------
    float or numpy.ndarray

    Raises
    ------
    ValueError
        As :func:`parse_unit`.

    Examples
    --------
    >>> round(from_si(5.1816, "ft"), 12)
    17.0
    """
    factor, _ = parse_unit(unit, dimension)
    if np.ndim(value) == 0:
        return float(value) / factor
    return np.asarray(value, dtype=float) / factor


def parse_quantity(text: str, dimension: str | Sequence[int] | None = None) -> float:
    """Parse ``"<number> <unit>"`` into an SI float; the unit is mandatory.

    Parameters
    ----------
    text : str
        E.g. ``"34 ft"``, ``"800 lb/in"``, ``"29 percent"``.
    dimension : str or sequence of int, optional
        Expected dimension of the unit.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        No leading number, no unit, or a bad unit.

    Examples
    --------
    >>> parse_quantity("10 in", "length")
    0.254
    >>> parse_quantity("0.3")
    Traceback (most recent call last):
    ...
    ValueError: quantity '0.3' has no unit; pass a plain number for SI values
    """
    m = _QUANTITY.match(text) if isinstance(text, str) else None
    if m is None:
        raise ValueError(f"cannot read {text!r} as '<number> <unit>'")
    number, unit = m.groups()
    if not unit:
        raise ValueError(f"quantity {text!r} has no unit; pass a plain number for SI values")
    return to_si(float(number), unit, dimension)
