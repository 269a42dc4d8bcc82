"""Values given as text (command line, TOML files) and the rule that dimensional ones carry a unit.

The units rules (docs/guide.md, "Units"):

* A **dimensionless** field (``flight.ct_sigma``, ``flap.overhang``, the
  counts) takes a bare number; a unit with a dimension is refused, angles
  included (``"5 deg"`` for C_T/sigma is an error, see :mod:`tefcore.units`).
* A **dimensional** field -- any field with an SI unit: lengths,
  stiffnesses, inertias, angles (``rad``) and per-angle slopes (``1/rad``)
  -- needs its unit **on the command line and in TOML files**:
  ``-s "hub.pitch_link_stiffness=800 lb/in"``, ``radius = "17 ft"``,
  ``radius = {value = 17.0, unit = "ft"}``, or SI with the SI unit written
  out (``"140101 N/m"``).  A bare number is refused there, because it would
  silently be read as SI (``800`` N/m instead of 800 lb/in).
* The **Python API** (``Config(...)``, :meth:`~tefcore.config.configuration.Config.with_overrides`,
  :func:`~tefcore.config.io.config_from_dict`) keeps plain numbers in SI
  units, and takes the same ``"value unit"`` strings.

:func:`require_unit` applies the rule to one raw value; :func:`parse_overrides`
reads ``--set name=value`` items; :func:`sweep_values` reads the values of
``tefcore sweep`` (``--values`` and ``--range``, which accept units like
``--set``).

Examples
--------
>>> parse_overrides(["hub.pitch_link_stiffness=800 lb/in", "flight.ct_sigma=0.08"])
{'hub.pitch_link_stiffness': '800 lb/in', 'flight.ct_sigma': 0.08}
>>> parse_overrides(["hub.pitch_link_stiffness=800"])  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: hub.pitch_link_stiffness = 800 needs a unit, e.g. '800 N/m' (SI) or '800 lb/in'; ...
>>> sweep_values("hub.pitch_link_stiffness", range_=("400 lb/in", "800 lb/in", "3"))
['400 lb/in', '600 lb/in', '800 lb/in']
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from .configuration import SECTIONS, resolve_field
from .settings import Param, coerce_value

__all__ = ["MAX_SWEEP_POINTS", "RANGE_NAMES", "field_param", "parse_overrides", "require_unit",
           "sweep_values"]

#: Most points ``--range`` may ask for.
MAX_SWEEP_POINTS = 100_000

#: An example unit other than SI per dimension, for messages.
_EXAMPLE_UNIT = {
    "length": "ft", "force_per_length": "lb/in", "moment_per_angle": "ft-lb/rad",
    "moment_damping": "ft-lb-sec/rad", "mass_per_length": "lb/ft", "angle": "deg",
    "per_angle": "1/deg", "angular_velocity": "rpm", "velocity": "ft/s",
    "inertia_per_length": "slug*ft^2/ft", "inertia": "lb*in^2", "bending_stiffness": "lb*ft^2",
    "torsional_stiffness": "lb*ft^2", "force": "lbf", "density": "slug/ft^3",
}  # fmt: skip
_NUMBER = re.compile(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*$")


def field_param(dotted: str) -> Param | None:
    """The :class:`~tefcore.config.settings.Param` of a dotted field.

    None for ``name`` and ``description``.

    Parameters
    ----------
    dotted : str
        A dotted field name, e.g. ``"flap.overhang"``.

    Returns
    -------
    tefcore.config.settings.Param or None

    Raises
    ------
    ValueError
        Unknown field, with close matches.
    """
    section, name = resolve_field(dotted)
    if section is None:
        return None
    return next(p for p in SECTIONS[section].PARAMS if p.name == name)


def _needs_unit(p: Param | None) -> bool:
    return p is not None and p.kind in ("float", "array") and p.dimension != "dimensionless"


def _unit_error(p: Param, shown, dotted: str) -> ValueError:
    example = _EXAMPLE_UNIT.get(p.dimension)
    alt = f" or '{shown} {example}'" if example else ""
    return ValueError(f"{dotted} = {shown} needs a unit, e.g. '{shown} {p.unit}' (SI){alt}; "
                      "a bare number is not read as SI here")


def require_unit(p: Param | None, raw, dotted: str) -> None:
    """Refuse a bare number for a dimensional field (the text-input rule above).

    Parameters
    ----------
    p : Param or None
        The field (None: ``name``/``description``, nothing to check).
    raw : object
        The value as written: number, string, list or
        ``{value|values, unit, source}`` table.
    dotted : str
        Field name for the message.

    Raises
    ------
    ValueError
        A dimensional field given without its unit.
    """
    if not _needs_unit(p) or raw is None:
        return
    if isinstance(raw, Mapping):
        if "unit" in raw:
            return
        raw = raw.get("values" if p.kind == "array" else "value")
        if raw is None:
            return  # a malformed table: coerce_value says what is missing
    if isinstance(raw, str):
        if _NUMBER.match(raw):
            raise _unit_error(p, raw.strip(), dotted)
        return  # "value unit": the unit is checked on conversion
    if isinstance(raw, bool):
        return  # refused as a non-number on conversion
    if isinstance(raw, int | float):
        raise _unit_error(p, raw, dotted)
    if isinstance(raw, list | tuple):
        raise _unit_error(p, "[...]", dotted)


def _value_of_text(dotted: str, text: str):
    """A command-line value: number or text, the unit rule applied."""
    p = field_param(dotted)
    text = text.strip()
    if p is None or p.kind == "str":
        return text
    if _NUMBER.match(text):
        require_unit(p, text, dotted)
        number = float(text)
        return int(number) if p.kind == "int" and number.is_integer() else number
    return text


def parse_overrides(items: Iterable[str]) -> dict:
    """``["name=value", ...]`` from ``--set`` -> ``{dotted: value}`` (rule above).

    Parameters
    ----------
    items : iterable of str
        ``"name=value"`` items.

    Returns
    -------
    dict of str to str
        Dotted field -> value text (converted when the configuration takes it).

    Raises
    ------
    ValueError
        An item without ``=``, an unknown field, or a dimensional value
        without its unit.
    """
    out = {}
    for item in items or ():
        key, sep, value = item.partition("=")
        if not sep:
            raise ValueError(f"--set expects name=value, got {item!r}")
        key = key.strip()
        out[key] = _value_of_text(key, value)
    return out


def _split_quantity(text: str, p: Param, dotted: str) -> tuple[float, str]:
    """``"400 lb/in"`` -> (400.0, "lb/in"); a bare number -> (x, "")."""
    text = text.strip()
    m = re.match(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$", text)
    if m is None:
        raise ValueError(f"{dotted}: cannot read {text!r} as a number with an optional unit")
    number, unit = float(m.group(1)), m.group(2)
    if not unit:
        require_unit(p, text, dotted)
    else:
        coerce_value(p, text, dotted)  # checks the unit against the field's dimension
    if not math.isfinite(number):
        raise ValueError(f"{dotted}: {text!r} is not finite")
    return number, unit


#: How ``tefcore sweep`` names the items of ``--range`` in messages.
RANGE_NAMES = ("--range START", "--range STOP", "--range NUM")


def sweep_values(parameter: str, values: Sequence[str] | None = None,
                 range_: Sequence[str] | None = None,
                 range_names: Sequence[str] = RANGE_NAMES) -> list:
    """The values of ``tefcore sweep`` from ``--values`` or ``--range START STOP NUM``.

    ``--values`` items are numbers (dimensionless fields), ``"value unit"``
    strings, or text (string fields).  ``--range`` takes START and STOP as
    numbers or as quantities with units; with one unit on both the values
    are ``"value unit"`` strings in that unit, otherwise numbers in SI.

    Parameters
    ----------
    parameter : str
        The swept dotted field.
    values : sequence of str, optional
        The ``--values`` items.
    range_ : sequence of str, optional
        ``(START, STOP, NUM)`` of ``--range``.
    range_names : sequence of str, optional
        What the messages call START, STOP and NUM (``tefcore map``:
        ``X_START``, ...); default :data:`RANGE_NAMES`.

    Returns
    -------
    list
        Numbers or ``"value unit"`` strings, as :func:`tefcore.sweeps.sweep.sweep` takes them.

    Raises
    ------
    ValueError
        Unknown parameter, a dimensional value without its unit, a unit of
        the wrong dimension, or a bad NUM.
    """
    p = field_param(parameter)
    if range_ is not None:
        if p is None or p.kind not in ("float", "int"):
            raise ValueError(f"{', '.join(range_names)}: a range needs a numeric parameter; "
                             f"{parameter} is not one")
        start, stop, num = range_
        try:
            n = int(str(num).strip())
        except ValueError:
            n = 0
        if not 1 <= n <= MAX_SWEEP_POINTS:
            raise ValueError(f"{range_names[2]} must be an integer in [1, {MAX_SWEEP_POINTS}], "
                             f"got {num!r}")
        (a, ua), (b, ub) = (_split_quantity(x, p, parameter) for x in (start, stop))
        if ua and ua == ub:
            return [f"{x:.12g} {ua}" for x in np.linspace(a, b, n)]
        if ua or ub:
            a, b = (coerce_value(p, f"{x} {u}" if u else x, parameter)
                    for x, u in ((a, ua), (b, ub)))
        return [float(x) for x in np.linspace(a, b, n)]
    if not values:
        raise ValueError("tefcore sweep: give --values or --range")
    out = [_value_of_text(parameter, v) for v in values]
    if p is not None and p.kind in ("float", "int"):
        for v in out:       # units checked now; a value out of range is a failed point later
            if isinstance(v, str):
                coerce_value(p, v, parameter)
    return out
