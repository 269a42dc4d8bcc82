"""TOML reading and writing of :class:`tefcore.config.configuration.Config`, and settings docs.

File layout: optional top-level ``name`` and ``description``, an optional
``[reference]`` table of stated values (see
:data:`tefcore.config.configuration.REFERENCE_PARAMS`), and one table per section.  A
scalar field is a ``"value unit"`` string or an inline table
``{value = 17.0, unit = "ft", source = "Table 1"}``; a blade array is
``{values = [...], unit = "lb/ft", source = "..."}`` (often written as a
``[blade.mass]`` sub-table).  A dimensionless field may be a bare number
(or list); a dimensional one needs its unit in a file (a bare number would
silently be SI; see :mod:`tefcore.config.text_input`), while
:func:`config_from_dict` called from Python takes SI numbers unless
``require_units=True``.  Unknown keys are errors.  Missing fields take their
defaults; fields declared ``REQUIRED`` (all rotor geometry, the blade
property tables, the hub springs and control linkage, the flap geometry and
inertia, and the actuator stiffness) must be present.  A relative path in a
file field (``model.c81_deck``) is relative to the folder of the TOML file
(of the package data for a packaged configuration).

Examples
--------
>>> cfg = load_config("mdart")
>>> cfg.sources["rotor.radius"]
'Table 1: Rotor Diameter 34 ft'
>>> loads_config(dumps_config(cfg)) == cfg
True
"""

from __future__ import annotations

import difflib
import errno
import os
import tomllib
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w

from ..safe_io import atomic_write_text
from .configuration import REFERENCE_PARAMS, SECTIONS, Config
from .settings import Param
from .text_input import require_unit

__all__ = [
    "available_configs",
    "config_from_dict",
    "config_to_dict",
    "dumps_config",
    "load_config",
    "loads_config",
    "save_config",
    "settings_markdown",
    "settings_table",
]

_PACKAGE_DATA = ("tefcore", "data")


def _unknown_keys(keys, allowed, where: str) -> None:
    unknown = [k for k in keys if k not in allowed]
    if unknown:
        hints = []
        for k in unknown:
            near = difflib.get_close_matches(k, list(allowed), n=1, cutoff=0.6)
            hints.append(f"{k!r}" + (f" (did you mean {near[0]!r}?)" if near else ""))
        raise ValueError(f"unknown key(s) in {where}: {', '.join(hints)}")


def config_from_dict(data: Mapping[str, Any], *, origin: str = "config",
                     require_units: bool = False, base_dir=None) -> Config:
    """Build a Config from parsed TOML data.

    Parameters
    ----------
    data : mapping
        Parsed TOML document (see the module docstring for the layout).
    origin : str
        Prefix for error messages, usually the file name.
    require_units : bool
        Refuse bare numbers for dimensional fields (as in a TOML file);
        ``False`` (the Python API) reads them as SI.
    base_dir : path-like, optional
        Folder that relative file paths (``model.c81_deck``) are relative to;
        ``None``: the working directory.

    Returns
    -------
    Config
        With ``sources`` from the ``source`` entries (``"default"`` for
        defaulted fields).

    Raises
    ------
    ValueError
        Unknown keys, missing required fields, or invalid values; the
        message starts with `origin` and names the dotted field.

    Examples
    --------
    >>> config_from_dict({"rotor": {"radius": "17 ft"}}, origin="x.toml")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: x.toml: missing required field(s) rotor.n_blades, rotor.rotor_speed, ...
    """
    try:
        return _from_dict(data, require_units, base_dir)
    except ValueError as err:
        raise ValueError(f"{origin}: {err}") from None


def _source_of(raw, dotted: str) -> str | None:
    if isinstance(raw, Mapping) and "source" in raw:
        if not isinstance(raw["source"], str):
            raise ValueError(f"{dotted}: source must be a string, got {raw['source']!r}")
        return raw["source"]
    return None


def _resolve_path(raw, base_dir):
    """A file field's value with a relative path joined to `base_dir`."""
    value = raw.get("value") if isinstance(raw, Mapping) else raw
    if base_dir is None or not isinstance(value, str) or not value:
        return raw
    joined = os.path.abspath(os.path.join(base_dir, os.path.expanduser(value)))
    return {**raw, "value": joined} if isinstance(raw, Mapping) else joined


def _from_dict(data: Mapping[str, Any], require_units: bool = False, base_dir=None) -> Config:
    if not isinstance(data, Mapping):
        raise ValueError(f"expected a table of sections, got {type(data).__name__}")
    _unknown_keys(data, ["name", "description", "reference", *SECTIONS], "the top level")
    sources: dict[str, str] = {}
    sections: dict[str, Any] = {}
    missing: list[str] = []
    for sname, cls in SECTIONS.items():
        table = data.get(sname, {})
        if not isinstance(table, Mapping):
            raise ValueError(f"[{sname}] must be a table, got {table!r}")
        params = {p.name: p for p in cls.PARAMS}
        _unknown_keys(table, params, f"[{sname}]")
        table = dict(table)
        for name, p in params.items():
            dotted = f"{sname}.{name}"
            if name in table:
                if require_units:
                    require_unit(p, table[name], dotted)
                if p.path:
                    table[name] = _resolve_path(table[name], base_dir)
                if src := _source_of(table[name], dotted):
                    sources[dotted] = src
            elif p.required:
                missing.append(dotted)
            else:
                sources[dotted] = "default"
        sections[sname] = table
    if missing:
        raise ValueError(f"missing required field(s) {', '.join(missing)} (no defaults)")
    reference = data.get("reference", {})
    if not isinstance(reference, Mapping):
        raise ValueError(f"[reference] must be a table, got {reference!r}")
    _unknown_keys(reference, REFERENCE_PARAMS, "[reference]")
    for key, raw in reference.items():
        if require_units:
            require_unit(REFERENCE_PARAMS[key], raw, f"reference.{key}")
        if src := _source_of(raw, f"reference.{key}"):
            sources[f"reference.{key}"] = src
    built = {name: cls(**sections[name]) for name, cls in SECTIONS.items()}
    return Config(
        **built,
        name=data.get("name", ""),
        description=data.get("description", ""),
        reference=reference,
        sources=sources,
    )


def _entry(p: Param, value, source: str | None) -> dict[str, Any]:
    key = "values" if p.kind == "array" else "value"
    entry: dict[str, Any] = {key: value.tolist() if isinstance(value, np.ndarray) else value}
    if p.unit:
        entry["unit"] = p.unit
    if source:
        entry["source"] = source
    return entry


def config_to_dict(cfg: Config) -> dict[str, Any]:
    """TOML-ready nested dict of `cfg`: SI values with units and sources.

    Optional fields set to None are left out (absent means None on loading).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.

    Returns
    -------
    dict

    Examples
    --------
    >>> d = config_to_dict(load_config("mdart"))
    >>> d["actuator"]["damping"]["unit"]
    'N*m*s/rad'
    """
    out: dict[str, Any] = {"name": cfg.name, "description": cfg.description}
    if cfg.reference:
        out["reference"] = {
            k: _entry(REFERENCE_PARAMS[k], v, cfg.sources.get(f"reference.{k}"))
            for k, v in cfg.reference.items()
        }
    for sname, cls in SECTIONS.items():
        section = getattr(cfg, sname)
        out[sname] = {
            p.name: _entry(p, getattr(section, p.name), cfg.sources.get(f"{sname}.{p.name}"))
            for p in cls.PARAMS
            if getattr(section, p.name) is not None
        }
    return out


def _literal(value) -> str:
    # tomli_w formats each scalar (floats via repr, so round trips are exact).
    if isinstance(value, list):
        return "[" + ", ".join(_literal(v) for v in value) + "]"
    return tomli_w.dumps({"x": value}).partition("=")[2].strip()


def _inline(entry: Mapping[str, Any]) -> str:
    return "{" + ", ".join(f"{k} = {_literal(v)}" for k, v in entry.items()) + "}"


def dumps_config(cfg: Config) -> str:
    """Serialise `cfg` to TOML text (SI values, unit strings, sources).

    Scalars are written as inline tables; blade arrays as sub-tables with
    several values per line.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.

    Returns
    -------
    str
    """
    data = config_to_dict(cfg)
    lines = [
        "# tefcore configuration; values in SI, see tefcore.config.sections for the fields.",
        f"name = {_literal(data.pop('name'))}",
        f"description = {_literal(data.pop('description'))}",
    ]
    for table, entries in data.items():
        scalars = {k: e for k, e in entries.items() if "values" not in e}
        arrays = {k: e for k, e in entries.items() if "values" in e}
        lines += ["", f"[{table}]"] + [f"{k} = {_inline(e)}" for k, e in scalars.items()]
        for k, e in arrays.items():
            values = [_literal(v) for v in e["values"]]
            rows = [", ".join(values[i : i + 4]) for i in range(0, len(values), 4)]
            lines += ["", f"[{table}.{k}]", "values = ["]
            lines += [f"    {row}," for row in rows] + ["]"]
            lines += [f"{key} = {_literal(v)}" for key, v in e.items() if key != "values"]
    return "\n".join(lines) + "\n"


def loads_config(text: str, *, origin: str = "<string>", base_dir=None) -> Config:
    """Parse TOML text into a Config (see :func:`config_from_dict`).

    Dimensional fields need their units (module docstring); relative file
    paths are relative to `base_dir` (default: the working directory).

    Parameters
    ----------
    text : str
        TOML text.
    origin : str, optional
        Where the text comes from, for messages.
    base_dir : str or os.PathLike, optional
        Folder that relative file paths are relative to.

    Returns
    -------
    tefcore.config.configuration.Config

    Raises
    ------
    ValueError
        A TOML syntax error or an invalid field, naming ``origin`` and the
        dotted field.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{origin}: invalid TOML: {err}") from None
    except RecursionError:
        raise ValueError(f"{origin}: invalid TOML: nested too deeply") from None
    return config_from_dict(data, origin=origin, require_units=True, base_dir=base_dir)


def available_configs() -> list[str]:
    """Names of the configurations shipped in ``tefcore/data``.

    Examples
    --------
    >>> "mdart" in available_configs()
    True
    """
    folder = resources.files(_PACKAGE_DATA[0]).joinpath(_PACKAGE_DATA[1])
    return sorted(
        f.name.removesuffix(".toml") for f in folder.iterdir() if f.name.endswith(".toml")
    )


#: Packaged configurations parsed so far: (name, text, folder) -> Config.
_PACKAGED: dict = {}


def _packaged(name: str, text: str, folder: str) -> Config:
    """A packaged configuration, parsed once per process for each text of its file.

    A :class:`Config` is immutable (frozen, its arrays read-only) and a
    function of its file's text and folder alone (a file field is a path,
    read where it is used), so the one parsed before is that configuration.
    Parsing MDART takes 5.6 ms, and the figures, claims and attribution ask
    for it many times (167 times in one lever of the attribution, measured).
    """
    key = (name, text, folder)
    if key not in _PACKAGED:
        _PACKAGED[key] = loads_config(text, origin=f"{name}.toml", base_dir=folder)
    return _PACKAGED[key]


def load_config(path_or_name: str | os.PathLike) -> Config:
    """Load a configuration file, or a packaged one by name (e.g. ``"mdart"``).

    Parameters
    ----------
    path_or_name : str or path-like
        A path to a TOML file, or the bare name of a file in ``tefcore/data``
        (a string without ``.toml`` suffix or directory part).

    Returns
    -------
    Config

    Raises
    ------
    FileNotFoundError
        No such file or packaged configuration.
    ValueError
        Invalid content (message starts with the file name).
    """
    if (
        isinstance(path_or_name, str)
        and not path_or_name.endswith(".toml")
        and (os.sep not in path_or_name and "/" not in path_or_name)
    ):
        name = path_or_name
        resource = resources.files(_PACKAGE_DATA[0]).joinpath(_PACKAGE_DATA[1], f"{name}.toml")
        if not resource.is_file():
            raise FileNotFoundError(
                f"no packaged configuration {name!r}; available: {', '.join(available_configs())}"
            )
        return _packaged(name, resource.read_text(encoding="utf-8"), str(resource.parent))
    path = Path(path_or_name)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise FileNotFoundError(errno.ENOENT, "no such configuration file", str(path)) from None
    except UnicodeDecodeError as err:
        line = path.read_bytes()[:err.start].count(b"\n") + 1
        raise ValueError(f"{path}: line {line}: not UTF-8 text (byte 0x{err.object[err.start]:02x})"
                         ) from None
    return loads_config(text, origin=str(path), base_dir=path.parent)


def save_config(cfg: Config, path: str | os.PathLike) -> Path:
    """Write `cfg` to `path` as TOML; ``load_config(path) == cfg`` exactly.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.
    path : str or os.PathLike
        The TOML file (written atomically).

    Returns
    -------
    pathlib.Path
        The written path.
    """
    return atomic_write_text(path, dumps_config(cfg))


def settings_table() -> list[dict[str, Any]]:
    """All declared settings as rows (section, name, dimension, unit, ...).

    Examples
    --------
    >>> rows = settings_table()
    >>> [r["range"] for r in rows if r["field"] == "flap.overhang"]
    ['[0, 1)']
    """
    return [
        {
            "field": f"{sname}.{p.name}",
            "kind": p.kind,
            "dimension": p.dimension,
            "unit": p.unit,
            "default": "required" if p.required else p.default,
            "range": p.range or ", ".join(p.choices),
            "description": p.doc,
        }
        for sname, cls in SECTIONS.items()
        for p in cls.PARAMS
    ]


def settings_markdown() -> str:
    """The settings table as a Markdown table (for the documentation)."""
    rows = settings_table()
    head = list(rows[0])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(str(r[h]) for h in head) + " |" for r in rows]
    return "\n".join(lines)
