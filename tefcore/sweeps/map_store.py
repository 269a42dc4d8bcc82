"""The boundary file of a stability map (``OUT/boundary.jsonl``): format and store.

A map (:func:`tefcore.sweeps.maps.stability_map` with ``out``) keeps one sweep
file per row (``row_<k>.jsonl``, :mod:`tefcore.sweeps.store`) and the refined
zeros of the flutter growth between grid points in ``boundary.jsonl``.  Both
carry a header of what decides their content, and resuming refuses a file
whose header does not match (:class:`~tefcore.errors.SweepFileError`, a
``ValueError``), so a map never reuses work done for other inputs.

Format
------
UTF-8 JSON lines, written like a sweep file (one ``os.write`` per line on a
file opened with ``O_APPEND``, ``fsync``-ed; a new file created atomically;
a lock on ``boundary.jsonl.lock`` while the map runs):

* line 1, the header::

    {"format": "tefcore.map_boundary", "version": 1,
     "x_field": "flap.cg_offset", "y_field": "flap.overhang",
     "config_hash": "<16 hex>", "inputs": {...}, "tefcore_version": "0.1.0",
     "model_stamp": "<16 hex>", "point": "tefcore.linear.stability:stability",
     "created": "<ISO time>"}

  ``config_hash`` is :func:`tefcore.sweeps.store.config_hash` of the map's
  base configuration without the two mapped fields; ``inputs``,
  ``tefcore_version`` and ``model_stamp`` as in a sweep file.  Resuming with
  other fields, another configuration, changed input files or other code
  is refused naming what changed; another point function only warns.
* one line per refined crossing::

    {"key": "0.2|0.1|0.2|4e-05", "y": 0.2, "x": 0.1934, "direction": "destabilising",
     "x_lo": 0.1, "x_hi": 0.2, "converged": true, "error": ""}

  ``key`` is ``repr`` of the row's y (SI), of the bracket's ends and of the
  tolerance, joined by ``|``: a crossing is reused only for the same row
  value, bracket and tolerance.

A last line cut short by a crash is dropped (with a warning) and computed
again; any other line that is not a crossing raises
:class:`~tefcore.errors.SweepFileError` naming the file and the line.
"""

from __future__ import annotations

import datetime
import numbers
import warnings

from .._version import __version__
from ..config.configuration import Config
from ..errors import SweepFileError
from ..provenance import input_digests, model_stamp, numerical_environment
from .store import JsonLinesStore, check_provenance, config_hash

__all__ = ["BOUNDARY_FORMAT", "BOUNDARY_VERSION", "BoundaryFile", "boundary_header",
           "crossing_key"]

BOUNDARY_FORMAT = "tefcore.map_boundary"
BOUNDARY_VERSION = 1
_DIRECTIONS = ("destabilising", "stabilising")
_RESTART = ("delete the file (or the map's --out folder) or choose another --out; in Python "
            "use another out folder, or resume=False to overwrite it")


def boundary_header(cfg: Config, x_field: str, y_field: str, point_name: str) -> dict:
    """Header of a new boundary file: what decides every crossing in it.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The map's base configuration.
    x_field, y_field : str
        The mapped dotted fields.
    point_name : str
        ``module:qualname`` of the point function.

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        If a file the configuration refers to cannot be read.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> head = boundary_header(load_config("mdart"), "flap.cg_offset", "flap.overhang", "m:f")
    >>> head["format"], head["y_field"], len(head["config_hash"])
    ('tefcore.map_boundary', 'flap.overhang', 16)
    """
    return {"format": BOUNDARY_FORMAT, "version": BOUNDARY_VERSION, "x_field": x_field,
            "y_field": y_field, "config_hash": config_hash(cfg, exclude=[x_field, y_field]),
            "inputs": input_digests(cfg), "tefcore_version": __version__,
            "model_stamp": model_stamp(), "environment": numerical_environment(),
            "point": point_name,
            "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}


def crossing_key(y: float, x_lo: float, x_hi: float, xtol: float) -> str:
    """Key of a crossing: the row's value, the bracket and the tolerance.

    Parameters
    ----------
    y : float
        The row's y value (SI).
    x_lo, x_hi : float
        The bracket (two neighbouring grid x, SI).
    xtol : float
        The tolerance of the refined x.

    Returns
    -------
    str

    Examples
    --------
    >>> crossing_key(0.2, 0.1, 0.2, 4e-05)
    '0.2|0.1|0.2|4e-05'
    """
    return "|".join(repr(float(v)) for v in (y, x_lo, x_hi, xtol))


def _is_real(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


class BoundaryFile(JsonLinesStore):
    """The boundary crossings of a map, kept in ``boundary.jsonl`` (format above).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    header : dict
        :func:`boundary_header` of this map.
    resume : bool
        Keep and load an existing file (checked against `header`); otherwise
        start it anew.
    """

    what = "map boundary file"

    def check_header(self, head, header: dict) -> None:
        """Refuse a file of another format, fields, configuration, input files or code.

        Parameters
        ----------
        head : object
            The decoded first line of the file.
        header : dict
            This map's header (:func:`boundary_header`).
        """
        path = self.path
        if not isinstance(head, dict) or head.get("format") != BOUNDARY_FORMAT:
            raise SweepFileError(
                f"cannot resume {path}: line 1 is not the header of a tefcore map boundary "
                "file (files written before tefcore recorded the map's inputs have none, so "
                f"their crossings cannot be checked); {_RESTART}")
        if head.get("version") != BOUNDARY_VERSION:
            raise SweepFileError(f"{path}: unsupported map boundary file version "
                                 f"{head.get('version')!r} (this tefcore reads version "
                                 f"{BOUNDARY_VERSION}); {_RESTART}")
        for what in ("x_field", "y_field", "config_hash"):
            if head.get(what) != header[what]:
                raise SweepFileError(
                    f"cannot resume {path}: it holds the boundary of a map of "
                    f"{head.get('x_field')!r} x {head.get('y_field')!r} on configuration "
                    f"{head.get('config_hash')}, not of {header['x_field']!r} x "
                    f"{header['y_field']!r} on configuration {header['config_hash']} "
                    f"({what} differs); {_RESTART}")
        check_provenance(path, head, header, _RESTART)
        if head.get("point") != header["point"]:
            warnings.warn(f"resuming {path}, written by point function {head.get('point')}, "
                          f"with {header['point']}", UserWarning, stacklevel=5)

    def record_problem(self, rec) -> str | None:
        """Why `rec` is not a crossing (format above), or None.

        Parameters
        ----------
        rec : object
            A decoded line.

        Returns
        -------
        str or None
        """
        if not isinstance(rec, dict):
            return f"a JSON {type(rec).__name__}, not a crossing"
        missing = [k for k in ("key", "y", "x", "direction", "x_lo", "x_hi", "converged",
                               "error") if k not in rec]
        if missing:
            return f"a crossing without {', '.join(map(repr, missing))}"
        if not isinstance(rec["key"], str) or not rec["key"]:
            return f"'key' must be a non-empty string, got {rec['key']!r:.40}"
        for name in ("y", "x", "x_lo", "x_hi"):
            if not _is_real(rec[name]):
                return f"{name!r} must be a number, got {rec[name]!r:.40}"
        if rec["direction"] not in _DIRECTIONS:
            return f"'direction' must be one of {_DIRECTIONS}, got {rec['direction']!r:.40}"
        if not isinstance(rec["converged"], bool):
            return "'converged' must be true or false"
        if not isinstance(rec["error"], str):
            return "'error' must be a string"
        return None

    def append(self, rec: dict) -> None:
        """Append one crossing and keep it in :attr:`records`.

        Parameters
        ----------
        rec : dict
            The crossing, with its ``key`` (:func:`crossing_key`).
        """
        super().append(rec)
        self.records[rec["key"]] = rec
