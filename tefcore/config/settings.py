"""Declarative settings: typed, unit-aware fields declared once as data.

A settings section is a frozen dataclass generated from a table of
:class:`Param` rows (name, dimension, default, allowed range, description)
by the :func:`settings_section` decorator on a :class:`Section` subclass.  Input is
converted to SI with :mod:`tefcore.units` (:func:`coerce_value`), checked
against the declared ranges, and the ``{params}`` placeholder of the class
docstring is filled with a numpydoc entry per field.  A range bound may be a
small expression of sibling fields (``"radius/2"``) or of fields of other
sections (``"-rotor.chord"``); the latter are checked by the owner of all
sections (:meth:`Section._check_cross_refs`).  Nothing here knows about
rotors: the concrete sections are in :mod:`tefcore.config.sections`.  (Over ~400
lines because the range grammar, coercion and section base are one unit.)

Examples
--------
>>> p = Param("span", "length", REQUIRED, "(0, width]", "Span.")
>>> span = coerce_value(p, "2 m", "demo.span")
>>> p.range_error(span, "demo.span", {"width": 1.5}.__getitem__)
'demo.span = 2.0 m is outside the allowed range (0, width] = (0.0, 1.5] m'
"""

from __future__ import annotations

import ast
import difflib
import math
import numbers
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..units import DIMENSIONS, SI_UNITS, parse_quantity, parse_unit

__all__ = ["GEOMETRY_TOL", "REQUIRED", "Param", "Section", "coerce_value", "did_you_mean",
           "format_value", "rebuild_section", "settings_section"]

#: Tolerance of the geometric cross-field checks, in fractions of the radius or
#: chord (stations that must coincide, a flap that must fit on the blade).
GEOMETRY_TOL = 1e-12


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


#: Sentinel default of a field that must be given explicitly.
REQUIRED: Any = _Required()

_RANGE = re.compile(r"^\s*([\[(])([^,]+),([^,]+)([\])])\s*$")
_BOUND_NODES = (
    ast.Expression, ast.BinOp, ast.UnaryOp, ast.Constant, ast.Name, ast.Attribute,
    ast.Load, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.USub, ast.UAdd,
)  # fmt: skip
_BOUND_CONSTANTS = {"inf": math.inf, "pi": math.pi}


def _compile_bound(text: str) -> ast.Expression:
    tree = ast.parse(text.strip(), mode="eval")
    for node in ast.walk(tree):
        if not isinstance(node, _BOUND_NODES) or (
            isinstance(node, ast.Attribute) and not isinstance(node.value, ast.Name)
        ):
            raise ValueError(f"unsupported range bound {text!r}")
    return tree


def _eval_bound(node: ast.AST, lookup: Callable[[str], Any]) -> float:
    match node:
        case ast.Expression(body=body):
            return _eval_bound(body, lookup)
        case ast.Constant(value=value):
            return float(value)
        case ast.Name(id=name):
            return _BOUND_CONSTANTS[name] if name in _BOUND_CONSTANTS else float(lookup(name))
        case ast.Attribute(value=ast.Name(id=section), attr=name):
            return float(lookup(f"{section}.{name}"))
        case ast.UnaryOp(op=op, operand=operand):
            value = _eval_bound(operand, lookup)
            return -value if isinstance(op, ast.USub) else value
        case ast.BinOp(left=left, op=op, right=right):
            a, b = _eval_bound(left, lookup), _eval_bound(right, lookup)
            ops = {ast.Add: a.__add__, ast.Sub: a.__sub__, ast.Mult: a.__mul__}
            return ops[type(op)](b) if type(op) in ops else a / b
    raise ValueError(f"unsupported range bound {ast.dump(node)}")


def _refs(tree: ast.AST) -> set[str]:
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    dotted = {f"{n.value.id}.{n.attr}" for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
    sections = {d.split(".")[0] for d in dotted}
    return (names - sections - set(_BOUND_CONSTANTS)) | dotted


@dataclass(frozen=True)
class Param:
    """One declared setting: the single source of truth for a field.

    Parameters
    ----------
    name : str
        Field name inside its section.
    dimension : str
        Key of :data:`tefcore.units.DIMENSIONS`; values are stored in
        ``SI_UNITS[dimension]``.
    default : object
        Default value, or :data:`REQUIRED`.
    range : str
        Allowed interval such as ``"[0, 1)"``; bounds are numbers, ``inf``,
        ``pi`` or small expressions of other fields (``"radius/2"``,
        ``"-rotor.chord"``).  Empty for strings.
    doc : str
        One-line meaning.
    kind : {'float', 'int', 'str', 'array'}
        Value type; arrays are checked element by element.
    choices : tuple of str
        Allowed values of a ``'str'`` field (empty: any string).
    optional : bool
        Whether None is allowed.
    path : bool
        A ``'str'`` field naming a file: relative paths in a TOML file are
        read relative to that file (:mod:`tefcore.config.io`).

    Examples
    --------
    >>> p = Param("chord", "length", REQUIRED, "(0, radius/2]", "Blade chord.")
    >>> p.limits({"radius": 2.0}.__getitem__)
    (0.0, 1.0)
    >>> p.unit
    'm'
    """

    name: str
    dimension: str
    default: Any
    range: str
    doc: str
    kind: str = "float"
    choices: tuple[str, ...] = ()
    optional: bool = False
    path: bool = False
    _bounds: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if self.dimension not in DIMENSIONS:
            raise ValueError(f"Param {self.name!r}: unknown dimension {self.dimension!r}")
        if self.kind not in ("float", "int", "str", "array"):
            raise ValueError(f"Param {self.name!r}: unknown kind {self.kind!r}")
        bounds: tuple = ()
        if self.kind != "str":
            m = _RANGE.match(self.range)
            if m is None:
                raise ValueError(f"Param {self.name!r}: cannot parse range {self.range!r}")
            lo, hi = _compile_bound(m.group(2)), _compile_bound(m.group(3))
            bounds = (lo, hi, m.group(1) == "[", m.group(4) == "]", _refs(lo) | _refs(hi))
        object.__setattr__(self, "_bounds", bounds)

    @property
    def required(self) -> bool:
        """True if the field has no default."""
        return self.default is REQUIRED

    @property
    def unit(self) -> str:
        """SI unit of the stored value (``''`` if dimensionless)."""
        unit = SI_UNITS[self.dimension]
        return "" if unit == "1" else unit

    @property
    def refs(self) -> frozenset[str]:
        """Fields referenced by the range bounds (dotted = other section)."""
        return frozenset(self._bounds[4]) if self._bounds else frozenset()

    @property
    def closed(self) -> tuple[bool, bool]:
        """Whether the lower and upper bounds are included."""
        return self._bounds[2], self._bounds[3]

    def limits(self, lookup: Callable[[str], Any]) -> tuple[float | None, float | None]:
        """Evaluate the bounds; a bound whose reference `lookup` lacks is None.

        Parameters
        ----------
        lookup : callable
            Maps a field name (``"radius"`` or ``"rotor.chord"``) to its value;
            raises KeyError (or AttributeError) if unavailable.

        Returns
        -------
        lo, hi : float or None
        """
        out = []
        for tree in self._bounds[:2]:
            try:
                out.append(_eval_bound(tree, lookup))
            except (KeyError, AttributeError):
                out.append(None)
        return out[0], out[1]

    def range_error(self, value, dotted: str, lookup: Callable[[str], Any]) -> str | None:
        """Message if `value` (scalar or array) is outside the range, else None."""
        if self.kind == "str" or value is None:
            return None
        lo, hi = self.limits(lookup)
        lo_in, hi_in = self.closed
        arr = np.asarray(value, dtype=float)
        bad = np.zeros(arr.shape, dtype=bool)
        if lo is not None:
            bad |= arr < lo if lo_in else arr <= lo
        if hi is not None:
            bad |= arr > hi if hi_in else arr >= hi
        if not bad.any():
            return None
        i = int(np.flatnonzero(bad)[0])
        where = f"{dotted}[{i}]" if arr.ndim else dotted
        unit = f" {self.unit}" if self.unit else ""
        resolved = ""
        if self.refs:
            lo_text, hi_text = format_value(lo), format_value(hi)
            resolved = f" = {'[' if lo_in else '('}{lo_text}, {hi_text}{']' if hi_in else ')'}"
        return (
            f"{where} = {format_value(arr.flat[i] if arr.ndim else value)}{unit} "
            f"is outside the allowed range {self.range.strip()}{resolved}{unit}"
        )


def format_value(value) -> str:
    """A number as error messages show it: ``repr(float)``, exact integers, ``?`` for None.

    Parameters
    ----------
    value : object
        A number (huge integers are summarised by their digit count), None
        or anything else (shown with ``repr``).

    Returns
    -------
    str

    Examples
    --------
    >>> format_value(0.1), format_value(3), format_value(None), format_value(10**100)
    ('0.1', '3', '?', '<an integer of 101 digits>')
    """
    if value is None:
        return "?"
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        if int(value).bit_length() > 64:  # no 400-digit numbers in messages
            return f"<an integer of {int(int(value).bit_length() * math.log10(2)) + 1} digits>"
        return str(int(value))
    return repr(float(value)) if isinstance(value, numbers.Real) else repr(value)


def _as_float(x) -> float:
    """``float(x)``, or inf where a huge integer does not fit a float."""
    try:
        return float(x)
    except OverflowError:
        return math.inf


def _is_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _unit_factor(p: Param, unit, dotted: str) -> float:
    if p.kind in ("int", "str"):
        raise ValueError(f"{dotted} takes no unit, got unit {unit!r}")
    if not isinstance(unit, str):
        raise ValueError(f"{dotted}: unit must be a string, got {unit!r}")
    try:
        return parse_unit(unit, p.dimension)[0]
    except ValueError as err:
        raise ValueError(f"{dotted}: {err}") from None


def coerce_value(p: Param, raw, dotted: str):
    """Convert user input for field `p` to its stored SI form, or raise.

    Parameters
    ----------
    p : Param
        Field declaration.
    raw : object
        A number (SI), a ``"value unit"`` string, a sequence (arrays), or a
        table ``{value|values = ..., unit = ..., source = ...}``.
    dotted : str
        Dotted field name used in error messages.

    Returns
    -------
    float, int, str, None or read-only numpy.ndarray

    Raises
    ------
    ValueError
        Wrong type, bool, NaN/inf, bad unit, or malformed table.

    Examples
    --------
    >>> p = Param("radius", "length", REQUIRED, "(0, 100]", "Rotor radius.")
    >>> coerce_value(p, {"value": 17, "unit": "ft", "source": "Table 1"}, "rotor.radius")
    5.1815999999999995
    >>> coerce_value(p, True, "rotor.radius")
    Traceback (most recent call last):
    ...
    ValueError: rotor.radius must be a number, got bool True
    """
    factor, has_unit = 1.0, False
    if isinstance(raw, Mapping):
        key = "values" if p.kind == "array" else "value"
        unknown = sorted(set(raw) - {key, "unit", "source"})
        if unknown:
            raise ValueError(
                f"{dotted}: unknown key(s) {', '.join(map(repr, unknown))} in table; "
                f"allowed keys are {key!r}, 'unit', 'source'"
            )
        if key not in raw:
            raise ValueError(f"{dotted}: table has no {key!r}")
        if "unit" in raw:
            factor, has_unit = _unit_factor(p, raw["unit"], dotted), True
        raw = raw[key]
    if raw is None and p.optional:
        return None
    if p.kind == "str":
        if not isinstance(raw, str):
            raise ValueError(f"{dotted} must be a string, got {raw!r}")
        if p.choices and raw not in p.choices:
            raise ValueError(f"{dotted} = {raw!r} is not one of {', '.join(map(repr, p.choices))}"
                             f"{did_you_mean(raw, p.choices)}")
        return raw
    if p.kind == "array":
        return _coerce_array(p, raw, factor, dotted)
    if isinstance(raw, str) and p.kind == "float" and not has_unit:
        try:
            raw = parse_quantity(raw, p.dimension)
        except ValueError as err:
            raise ValueError(f"{dotted}: {err}") from None
    if not _is_number(raw):
        what = f"{type(raw).__name__} {raw!r}"
        raise ValueError(
            f"{dotted} must be {'an integer' if p.kind == 'int' else 'a number'}, got {what}"
        )
    try:
        value = float(raw) * factor
    except OverflowError:
        value = math.inf
    if not math.isfinite(value):
        raise ValueError(f"{dotted} = {format_value(raw)} is not finite (or too large for a float)")
    if p.kind == "int":
        if value != int(value):
            raise ValueError(f"{dotted} = {format_value(raw)} must be an integer")
        return int(value)
    return value


def _coerce_array(p: Param, raw, factor: float, dotted: str) -> np.ndarray:
    if isinstance(raw, str) and factor == 1.0:  # one quantity, broadcast later
        try:
            raw = parse_quantity(raw, p.dimension)
        except ValueError as err:
            raise ValueError(f"{dotted}: {err}") from None
    if _is_number(raw):
        arr = np.array(_as_float(raw))
    elif isinstance(raw, np.ndarray):
        if raw.dtype.kind not in "iuf" or raw.ndim > 1:
            raise ValueError(
                f"{dotted} must be a 1-D array of numbers, got {raw.dtype} {raw.shape}"
            )
        arr = np.array(raw, dtype=float)
    elif isinstance(raw, (list, tuple)):
        for i, x in enumerate(raw):
            if not _is_number(x):
                raise ValueError(f"{dotted}[{i}] must be a number, got {type(x).__name__} {x!r}")
        try:
            arr = np.array(raw, dtype=float).reshape(-1)
        except OverflowError:
            i = next(i for i, x in enumerate(raw) if not math.isfinite(_as_float(x)))
            raise ValueError(f"{dotted}[{i}] = {format_value(raw[i])} is too large for a "
                             "float") from None
    else:
        raise ValueError(
            f"{dotted} must be a sequence of numbers, got {type(raw).__name__} {raw!r}"
        )
    arr = arr * factor
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        where = f"{dotted}[{bad[0]}]" if arr.ndim else dotted
        raise ValueError(f"{where} = {format_value(arr.flat[bad[0]])} is not finite")
    arr.setflags(write=False)
    return arr


def _param_doc(p: Param) -> str:
    kind = {"float": "float", "int": "int", "str": "str", "array": "array_like"}[p.kind]
    spec = [f"Dimension {p.dimension} [{p.unit or '-'}]"] if p.kind != "str" else []
    if p.range:
        spec.append(f"range {p.range}")
    if p.choices:
        spec.append("one of " + ", ".join(map(repr, p.choices)))
    spec.append("required" if p.required else f"default {format_value(p.default)}")
    opt = "" if p.required else ", optional"
    return (
        f"{p.name} : {kind}{' or None' if p.optional else ''}{opt}\n    {p.doc} {'; '.join(spec)}."
    )


class Section:
    """Base of the section dataclasses: coercion, range checks and equality.

    A subclass declares ``PARAMS`` (a tuple of :class:`Param`) and is
    decorated with :func:`settings_section`; on construction every field is
    coerced (:func:`coerce_value`) and checked against its range, then the
    hooks ``_normalize`` and ``_validate`` run.  Ranges that name fields of
    other sections are checked by :meth:`check_cross_refs`, called by the
    owner of all sections.
    """

    SECTION = ""
    PARAMS: tuple[Param, ...] = ()

    def __post_init__(self):
        for p in self.PARAMS:
            value = coerce_value(p, getattr(self, p.name), self._dotted(p.name))
            object.__setattr__(self, p.name, value)
        self._normalize()
        for p in self.PARAMS:
            msg = p.range_error(getattr(self, p.name), self._dotted(p.name), self._lookup)
            if msg:
                raise ValueError(msg)
        self._validate()

    def _dotted(self, name: str) -> str:
        return f"{self.SECTION}.{name}"

    def _lookup(self, name: str):
        if "." in name:  # another section: checked later by Config
            raise KeyError(name)
        return getattr(self, name)

    def _normalize(self) -> None:
        """Hook: reshape coerced values (arrays) before range checks."""

    def _validate(self) -> None:
        """Hook: checks involving several fields of this section."""

    def check_cross_refs(self, lookup: Callable[[str], Any]) -> None:
        """Check the ranges that reference fields of other sections.

        Parameters
        ----------
        lookup : callable
            Maps a dotted field name (``"rotor.chord"``) to its value.

        Raises
        ------
        ValueError
            Naming the first field outside its range.
        """

        def both(key):
            return lookup(key) if "." in key else getattr(self, key)

        for p in self.PARAMS:
            if any("." in r for r in p.refs):
                msg = p.range_error(getattr(self, p.name), self._dotted(p.name), both)
                if msg:
                    raise ValueError(msg)

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        for p in self.PARAMS:
            a, b = getattr(self, p.name), getattr(other, p.name)
            same = np.array_equal(a, b) if p.kind == "array" else a == b
            if not same:
                return False
        return True

    __hash__ = None  # type: ignore[assignment]

    def __reduce__(self):
        # Rebuild through the constructor so that unpickled copies (joblib
        # workers, deepcopy) are re-validated and their arrays read-only.
        return rebuild_section, (type(self), {p.name: getattr(self, p.name) for p in self.PARAMS})


def rebuild_section(section_type, kwargs):
    """``section_type(**kwargs)``: how pickled sections and configurations are rebuilt.

    Through the constructor, so the copy is validated again.

    Parameters
    ----------
    section_type : type
        A :class:`Section` subclass (or :class:`tefcore.config.configuration.Config`).
    kwargs : dict
        Its constructor arguments.

    Returns
    -------
    object
        The new, validated instance.
    """
    return section_type(**kwargs)


def settings_section(name: str):
    """Class decorator: a :class:`Section` subclass with a ``PARAMS`` table becomes a
    frozen dataclass named ``name`` in dotted field names.

    Parameters
    ----------
    name : str
        The section's name (``"flap"`` for ``flap.overhang``).

    Returns
    -------
    callable
        The decorator; it sets the fields' annotations and defaults and fills
        the ``{params}`` placeholder of the class docstring with one numpydoc
        entry per field.
    """

    def wrap(cls):
        cls.SECTION = name
        cls.__annotations__ = {}
        for p in cls.PARAMS:
            base = {"float": "float", "int": "int", "str": "str", "array": "np.ndarray"}[p.kind]
            cls.__annotations__[p.name] = f"{base} | None" if p.optional else base
            if not p.required:
                setattr(cls, p.name, p.default)
        table = "\n    ".join(_param_doc(p).replace("\n", "\n    ") for p in cls.PARAMS)
        cls.__doc__ = cls.__doc__.replace("{params}", table)
        return dataclass(frozen=True, eq=False, kw_only=True)(cls)

    return wrap


def did_you_mean(word: str, options) -> str:
    """A ``"; did you mean ...?"`` suffix naming close matches of `word`, or ``""``.

    Parameters
    ----------
    word : str
        What was given (an unknown name).
    options : iterable of str
        The allowed names.

    Returns
    -------
    str

    Examples
    --------
    >>> did_you_mean("flap.overhnag", ["flap.overhang", "flap.chord_ratio"])
    "; did you mean 'flap.overhang'?"
    """
    near = difflib.get_close_matches(word, list(options), n=3, cutoff=0.6)
    return f"; did you mean {' or '.join(map(repr, near))}?" if near else ""
