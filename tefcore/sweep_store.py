"""The sweep file of :func:`tefcore.sweep.sweep` (``out=path``): format and store.

Also the two identities written to it: :func:`config_hash` of the base
configuration and the key of each swept value.

Format
------
UTF-8 JSON lines, one object per line, each line written by a single
``os.write`` on a file opened with ``O_APPEND`` and then ``fsync``-ed:

* line 1, the header::

    {"format": "tefcore.sweep", "version": 1, "parameter": "flap.cg_offset",
     "config_hash": "<16 hex>", "point": "tefcore.stability:stability",
     "tefcore_version": "0.1.0", "created": "<ISO time>"}

  ``config_hash`` is :func:`config_hash` of the base configuration (after
  ``extra_overrides``) without the swept field.  Resuming with another
  parameter or configuration raises ``ValueError``; another point function
  only warns (its name is recorded for information).
* one line per finished point::

    {"key": "0.25", "value": 0.25, "value_si": 0.25, "status": "ok",
     "error": null, "trim": {"collective_deg": 6.1, ...},
     "modes": {"mode_id": [0, 1], "label": ["blade flap 1", "TEF"],
               "frequency_per_rev": [...], "real_part": [...],
               "damping_ratio": [...]},
     "elapsed_s": 1.23}

  ``key`` identifies the value: ``repr(float(v))`` for numbers, the
  whitespace-normalised string for ``"value unit"`` strings.  ``value`` is
  the value as given, ``value_si`` the validated field value in SI (null
  when the configuration rejected it).  Failed points have
  ``"status": "failed"``, ``"error": "<ExceptionType>: <message>"`` and
  ``"modes": null``.  Non-finite floats are written as ``NaN``/``Infinity``
  (Python's JSON dialect).  Eigenvectors are not stored.

On resume the file is read back; when a key occurs several times (a retried
failed point) the last record wins, and records for values not requested
are ignored (and kept).  A last line cut short by a crash is dropped and
the file truncated to its last complete line.  Two sweeps must not write the
same file at the same time.
"""

from __future__ import annotations

import hashlib
import json
import numbers
import os
import warnings
from collections.abc import Iterable, Mapping
from pathlib import Path

import numpy as np

from .config import SECTIONS, Config

__all__ = ["config_hash"]

FORMAT = "tefcore.sweep"
FORMAT_VERSION = 2


# ------------------------------------------------------------------ identities


def _jsonable(v):
    """Plain JSON-able Python value (numpy scalars/arrays converted)."""
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, Mapping):
        return {str(k): _jsonable(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_jsonable(x) for x in v]
    return v


def _value_key(v) -> str:
    """Canonical key of a sweep value (see the file format)."""
    if isinstance(v, bool | np.bool_):
        raise ValueError(f"sweep values must be numbers or 'value unit' strings, got {v!r}")
    if isinstance(v, numbers.Real):
        return repr(float(v))
    if isinstance(v, str):
        key = " ".join(v.split())
        if key:
            return key
    raise ValueError(f"sweep values must be numbers or 'value unit' strings, got {v!r}")


def config_hash(cfg: Config, exclude: Iterable[str] = ()) -> str:
    """Hash (16 hex digits) of the field values of `cfg`, without `exclude`.

    Only the physical fields count (not ``name``, ``description``,
    ``sources`` or ``reference``), so two configurations with equal fields
    hash alike.  Floats enter by their exact ``repr``.

    Examples
    --------
    >>> from tefcore.config import load_config
    >>> cfg = load_config("mdart")
    >>> config_hash(cfg) == config_hash(cfg.with_overrides({"name": "other"}))
    True
    >>> other = cfg.with_overrides({"flap.cg_offset": 0.1})
    >>> config_hash(cfg) == config_hash(other)
    False
    >>> config_hash(cfg, ["flap.cg_offset"]) == config_hash(other, ["flap.cg_offset"])
    True
    """
    skip = set(exclude)
    data = {
        f"{s}.{p.name}": _jsonable(getattr(getattr(cfg, s), p.name))
        for s, cls in SECTIONS.items()
        for p in cls.PARAMS
        if f"{s}.{p.name}" not in skip
    }
    text = json.dumps(data, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


# ------------------------------------------------------------------ the file


class _SweepFile:
    """Append-only JSON-lines store of finished points (module docstring)."""

    def __init__(self, path, header: dict, resume: bool):
        self.path = Path(path)
        self.records: dict[str, dict] = {}
        self.path.parent.mkdir(parents=True, exist_ok=True)
        if resume and self.path.exists() and self.path.stat().st_size > 0:
            self._load(header)
        else:
            tmp = self.path.with_name(self.path.name + ".tmp")
            tmp.write_text(json.dumps(header) + "\n", encoding="utf-8")
            os.replace(tmp, self.path)
        self.fd = os.open(self.path, os.O_WRONLY | os.O_APPEND)

    def _load(self, header: dict) -> None:
        raw = self.path.read_bytes()
        lines = raw.split(b"\n")
        try:
            head = json.loads(lines[0])
        except json.JSONDecodeError:
            head = None
        if not isinstance(head, dict) or head.get("format") != FORMAT:
            raise ValueError(f"{self.path} is not a tefcore sweep file")
        if head.get("version") != FORMAT_VERSION:
            raise ValueError(f"{self.path}: unsupported sweep file version {head.get('version')}")
        for what in ("parameter", "config_hash"):
            if head.get(what) != header[what]:
                raise ValueError(
                    f"cannot resume {self.path}: it holds a sweep of {head.get('parameter')!r} "
                    f"on configuration {head.get('config_hash')}, not of "
                    f"{header['parameter']!r} on configuration {header['config_hash']} "
                    f"({what} differs); use another out path, or resume=False to overwrite it")
        if head.get("point") != header["point"]:
            warnings.warn(f"resuming {self.path}, written by point function {head.get('point')}, "
                          f"with {header['point']}", UserWarning, stacklevel=4)
        good = len(lines[0]) + 1
        body = lines[1:]
        for n, line in enumerate(body, start=2):
            last = n == len(lines)
            if last and not line:
                break
            try:
                if last:  # no newline after it: cut short by a crash
                    raise json.JSONDecodeError("unterminated line", "", 0)
                rec = json.loads(line)
            except json.JSONDecodeError:
                if not last:
                    raise ValueError(f"{self.path}, line {n}: not a JSON record; the file is "
                                     "damaged (remove the line or the file)") from None
                warnings.warn(f"{self.path}: dropping an incomplete last line (interrupted "
                              "write)", UserWarning, stacklevel=4)
                with open(self.path, "r+b") as f:
                    f.truncate(good)
                break
            self.records[rec["key"]] = rec
            good += len(line) + 1

    def append(self, rec: dict) -> None:
        data = (json.dumps(rec, separators=(",", ":"), allow_nan=True) + "\n").encode()
        view = memoryview(data)
        while view:
            view = view[os.write(self.fd, view):]
        os.fsync(self.fd)

    def close(self) -> None:
        os.close(self.fd)
