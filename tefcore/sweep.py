"""Parameter sweeps of the Floquet stability, and stability boundaries.

:func:`sweep` evaluates a point function (by default
:func:`tefcore.stability.stability`) at each value of one configuration
field -- flap overhang, CG offset, pitch-link stiffness, GJ factor, actuator
stiffness, flap location/length/chord, collective, advance ratio, ... --
serially, in joblib (loky) processes or on a dask cluster, and returns a
tidy table with the modes tracked along the sweep (:mod:`tefcore.tracking`).
A point that fails (invalid configuration, trim not converged: any
``Exception``) is recorded with its reason and the sweep goes on.  With
``out=path`` every finished point is appended to a JSON-lines file at once,
so an interrupted sweep can be resumed without losing or recomputing a
point.  :func:`stability_boundary` finds where a mode's damping crosses zero.

Sweep file format (``out=path``)
--------------------------------
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

Examples
--------
>>> import numpy as np, pandas as pd
>>> from types import SimpleNamespace
>>> from tefcore.config import load_config
>>> def toy(cfg):   # one mode whose real part crosses zero at cg_offset = 0.2
...     x = cfg.flap.cg_offset
...     return SimpleNamespace(
...         modes=pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [3.0],
...                             "real_part": [0.5 * (x - 0.2)],
...                             "damping_ratio": [-0.5 * (x - 0.2) / 3.0]}),
...         eigenvectors=np.ones((1, 1), complex), trim={"collective_deg": 8.0})
>>> cfg = load_config("mdart")
>>> res = sweep(cfg, "flap.cg_offset", [0.0, 0.4, 1.5], point=toy, progress=False)
>>> res.table[["value", "status", "label", "real_part", "trim_collective_deg"]]
   value  status label  real_part  trim_collective_deg
0    0.0      ok   TEF       -0.1                  8.0
1    0.4      ok   TEF        0.1                  8.0
2    1.5  failed   NaN        NaN                  NaN
>>> print(res.failed["error"].iloc[0])
ValueError: flap.cg_offset = 1.5 is outside the allowed range [-1, 1]
>>> b = stability_boundary(cfg, "flap.cg_offset", (0.0, 1.0), mode="TEF", point=toy)
>>> round(b.value, 9), b.bracket
(0.2, (0.125, 0.25))
"""

from __future__ import annotations

import datetime
import hashlib
import json
import numbers
import os
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy.optimize import brentq
from tqdm import tqdm

from .config import SECTIONS, Config, resolve_field
from .tracking import label_changes, match_modes, track_modes

__all__ = ["BoundaryResult", "SweepResult", "config_hash", "stability_boundary", "sweep"]

FORMAT = "tefcore.sweep"
FORMAT_VERSION = 1
#: Columns a point function's ``modes`` table must have.
REQUIRED_MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part", "damping_ratio")
_NUMERIC_MODE_COLUMNS = ("frequency_per_rev", "real_part", "damping_ratio")


# ------------------------------------------------------------------ helpers


def _default_point() -> Callable:
    from .stability import stability  # deferred: heavy, and written separately

    return stability


def _point_name(point) -> str:
    target = point if hasattr(point, "__qualname__") else type(point)
    return f"{getattr(target, '__module__', '?')}:{getattr(target, '__qualname__', '?')}"


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


def _check_parameter(parameter) -> str:
    try:
        section, name = resolve_field(parameter)
    except ValueError as err:
        raise ValueError(f"sweep parameter {parameter!r} is not a configuration field: "
                         f"{err}") from None
    if section is None:
        raise ValueError(f"sweep parameter {parameter!r} is not a physical field")
    kind = next(p.kind for p in SECTIONS[section].PARAMS if p.name == name)
    if kind == "array":
        raise ValueError(f"sweep parameter {parameter!r} is an array field; sweep a scalar "
                         "(e.g. blade.gj_scale)")
    return parameter


def _check_values(values) -> tuple[list, list[str]]:
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise ValueError(f"values must be a sequence of numbers or 'value unit' strings, "
                         f"got {values!r}")
    values = list(np.asarray(values).tolist() if isinstance(values, np.ndarray) else values)
    if not values:
        raise ValueError("values is empty: nothing to sweep")
    keys = [_value_key(v) for v in values]
    seen: dict[str, int] = {}
    for i, k in enumerate(keys):
        if k in seen:
            raise ValueError(f"duplicate sweep value {values[i]!r} (same as values[{seen[k]}])")
        seen[k] = i
    return values, keys


def _unpack(result) -> tuple[pd.DataFrame, np.ndarray | None, dict]:
    """Check a point function's result; return (modes, eigenvectors, trim)."""
    modes = getattr(result, "modes", None)
    if not isinstance(modes, pd.DataFrame):
        raise TypeError(f"point function returned {type(result).__name__} without a "
                        "'modes' DataFrame")
    missing = [c for c in REQUIRED_MODE_COLUMNS if c not in modes.columns]
    if missing:
        raise ValueError(f"point function's modes table lacks column(s) {missing}")
    if modes.empty:
        raise ValueError("point function returned no modes")
    modes = modes.reset_index(drop=True)
    numeric = modes[list(_NUMERIC_MODE_COLUMNS)].to_numpy(float)
    if not np.isfinite(numeric).all():
        bad = modes.loc[~np.isfinite(numeric).all(axis=1), "label"].tolist()
        raise ValueError(f"point function returned non-finite results for mode(s) {bad}")
    vecs = getattr(result, "eigenvectors", None)
    if vecs is not None:
        vecs = np.asarray(vecs)
        if vecs.ndim != 2 or vecs.shape[1] != len(modes):
            raise ValueError(f"eigenvectors of shape {vecs.shape} do not match {len(modes)} "
                             "modes (one column per mode)")
    trim = getattr(result, "trim", None) or {}
    return modes, vecs, {str(k): _jsonable(v) for k, v in dict(trim).items()}


def _failed_record(key, value, err) -> dict:
    return {"key": key, "value": _jsonable(value), "value_si": None, "status": "failed",
            "error": f"{type(err).__name__}: {err}", "trim": {}, "modes": None}


def _evaluate(index, point, cfg, parameter, value, key):
    """Evaluate one sweep point; never raises an ``Exception`` (it is recorded)."""
    start = time.perf_counter()
    rec: dict[str, Any] = {"key": key, "value": _jsonable(value), "value_si": None,
                           "status": "failed", "error": None, "trim": {}, "modes": None}
    vecs = None
    try:
        cfg_v = cfg.with_overrides({parameter: value})
        rec["value_si"] = _jsonable(cfg_v.get(parameter))
        modes, vecs, trim = _unpack(point(cfg_v))
        rec.update(status="ok", trim=trim,
                   modes={c: _jsonable(modes[c].to_numpy()) for c in modes.columns})
    except Exception as err:  # recorded, the sweep goes on
        rec["error"] = f"{type(err).__name__}: {err}"
        vecs = None
    rec["elapsed_s"] = round(time.perf_counter() - start, 6)
    return index, rec, vecs


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


# ------------------------------------------------------------------ backends


def _run_serial(todo, args):
    for i in todo:
        yield _evaluate(i, *args(i))


def _run_joblib(todo, args, n_jobs):
    from joblib import Parallel, delayed

    par = Parallel(n_jobs=n_jobs, backend="loky", return_as="generator_unordered")
    yield from par(delayed(_evaluate)(i, *args(i)) for i in todo)


def _run_dask(todo, args, n_jobs, client):
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError as err:
        raise ImportError("backend='dask' needs dask.distributed: pip install "
                          "'dask[distributed]' (or the tefcore[dask] extra)") from err
    cluster = None
    if client is None:
        workers = os.cpu_count() if n_jobs < 0 else n_jobs
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    futures = {}
    try:
        for i in todo:
            futures[client.submit(_evaluate, i, *args(i), pure=False)] = i
        for fut in as_completed(list(futures)):
            try:
                yield fut.result()
            except Exception as err:  # e.g. a worker died: record it, go on
                i = futures[fut]
                yield i, _failed_record(args(i)[4], args(i)[3], err), None
    finally:
        client.cancel(list(futures))
        if cluster is not None:
            client.close()
            cluster.close()


# ------------------------------------------------------------------ results


@dataclass
class SweepResult:
    """Result of :func:`sweep`.

    Attributes
    ----------
    parameter : str
        Swept dotted field.
    values : list
        Values as given.
    table : DataFrame
        One row per (value, mode), tracked: ``point`` (index in `values`),
        ``parameter``, ``value`` (as given), ``value_si`` (validated field
        value, SI), ``status`` ("ok"/"failed"), ``error`` (None when ok),
        ``track``, ``label`` (the track's label where it starts),
        ``label_here`` (the point function's label at this point), the mode
        columns (``mode_id``, ``frequency_per_rev``, ``real_part``,
        ``damping_ratio``, ...) and the trim scalars as ``trim_<name>``.  A
        failed point is one row with its reason; its result columns are
        NaN/NA.
    config_hash : str
        :func:`config_hash` of the base configuration without `parameter`.
    eigenvectors : dict of int to ndarray
        Point index -> eigenvectors (columns as the rows of that point's
        modes table); only for points computed in this run (not stored on
        disk, so points loaded on resume are tracked by eigenvalue only).
    n_computed, n_loaded : int
        Points evaluated in this run / loaded from the `out` file.
    out : Path or None
        The sweep file.
    """

    parameter: str
    values: list
    table: pd.DataFrame
    config_hash: str
    eigenvectors: dict = field(default_factory=dict, repr=False)
    n_computed: int = 0
    n_loaded: int = 0
    out: Path | None = None
    _modes: dict = field(default_factory=dict, repr=False)

    @property
    def failed(self) -> pd.DataFrame:
        """The failed points: ``point``, ``value``, ``value_si``, ``error``."""
        t = self.table
        return t.loc[t["status"] == "failed", ["point", "value", "value_si", "error"]]

    @property
    def ok(self) -> bool:
        """True when no point failed."""
        return bool((self.table["status"] == "ok").all())

    @property
    def label_changes(self) -> pd.DataFrame:
        """Where a tracked mode's point label changes (:func:`tefcore.tracking.label_changes`)."""
        return label_changes(self.table)

    def curve(self, label: str) -> pd.DataFrame:
        """Rows of the track(s) whose label is `label`, in sweep order."""
        t = self.table
        return t[(t["status"] == "ok") & (t["label"] == label)]

    def to_csv(self, path, **kwargs) -> Path:
        """Write :attr:`table` as CSV (no index); return the path."""
        self.table.to_csv(path, index=False, **kwargs)
        return Path(path)


def _build_table(parameter, values, records, vectors):
    """Tidy, tracked table from the records (index -> record)."""
    n = len(values)
    ok = [i for i in range(n) if records[i]["status"] == "ok"]
    modes = {i: pd.DataFrame(records[i]["modes"]) for i in ok}
    xs = []
    for k, i in enumerate(ok):
        si = records[i]["value_si"]
        xs.append(float(si) if isinstance(si, numbers.Real) else float(k))
    tracked = track_modes([(modes[i], vectors.get(i)) for i in ok], values=xs)
    tracked.insert(0, "point", np.asarray(ok, dtype=int)[tracked.pop("step").to_numpy(int)])
    info = pd.DataFrame({
        "point": range(n),
        "parameter": parameter,
        "value": pd.Series(values, dtype=object),
        "value_si": pd.Series([records[i]["value_si"] for i in range(n)], dtype=object),
        "status": [records[i]["status"] for i in range(n)],
        "error": pd.Series([records[i]["error"] for i in range(n)], dtype=object),
    })
    for col in ("value", "value_si"):  # numbers -> float column, else keep objects
        try:
            info[col] = pd.to_numeric(info[col])
        except (TypeError, ValueError):
            pass
    trim = pd.DataFrame([records[i]["trim"] for i in range(n)]).add_prefix("trim_")
    table = info.merge(tracked, on="point", how="left", validate="one_to_many")
    table = table.merge(trim.assign(point=range(n)), on="point", how="left")
    for col in ("track", "mode_id"):
        table[col] = table[col].astype("Int64")
    table = table.sort_values(["point", "track"], kind="stable", ignore_index=True)
    return table, modes


def sweep(cfg: Config, parameter: str, values, *, point: Callable | None = None,
          n_jobs: int = 1, backend: str = "joblib", progress: bool | None = None,
          out=None, resume: bool = True, extra_overrides: Mapping[str, Any] | None = None,
          client=None, retry_failed: bool = False) -> SweepResult:
    """Evaluate `point` at each value of one configuration field.

    Parameters
    ----------
    cfg : Config
        Base configuration.
    parameter : str
        Dotted scalar field, e.g. ``"flap.cg_offset"``,
        ``"hub.pitch_link_stiffness"``, ``"flight.advance_ratio"``.
    values : sequence
        Numbers (SI) or ``"value unit"`` strings, e.g. ``["400 lb/in",
        "800 lb/in"]``; no duplicates.  Point ``i`` is
        ``point(cfg.with_overrides({parameter: values[i]}))``.
    point : callable, optional
        Config -> result with ``modes`` (DataFrame with columns
        ``mode_id``, ``label``, ``frequency_per_rev``, ``real_part``,
        ``damping_ratio``), optional ``eigenvectors`` (n_states, n_modes)
        and ``trim`` (dict of scalars).  Default
        :func:`tefcore.stability.stability`.  Must be picklable for
        ``n_jobs != 1``.
    n_jobs : int
        Parallel processes (joblib/loky) or dask workers of an own
        LocalCluster; ``-1``: all cores.  ``1`` runs serially in-process.
    backend : {"joblib", "dask"}
        ``"dask"`` uses ``client`` if given, else starts a LocalCluster of
        `n_jobs` single-threaded worker processes (needs
        ``dask[distributed]``).
    progress : bool or None
        tqdm progress bar on stderr; ``None``: only if stderr is a terminal.
    out : path, optional
        Sweep file (JSON lines, see the module docstring); every finished
        point is appended at once.
    resume : bool
        With `out`: load the points already in the file instead of
        recomputing them (refusing a file of another parameter or base
        configuration).  ``False`` replaces the file.
    extra_overrides : mapping, optional
        Applied to `cfg` before the sweep (part of the base configuration).
    client : distributed.Client, optional
        Existing dask client for ``backend="dask"``.
    retry_failed : bool
        On resume, recompute points recorded as failed.

    Returns
    -------
    SweepResult

    Raises
    ------
    ValueError
        Bad arguments: unknown or non-scalar `parameter` (named in the
        message), empty or duplicate `values`, invalid `extra_overrides`,
        `n_jobs` or `backend`, or a sweep file that does not match.  A value
        that the configuration rejects is *not* raised: it is a failed point.
    KeyboardInterrupt
        Propagated; the points finished so far are in `out`.
    """
    parameter = _check_parameter(parameter)
    values, keys = _check_values(values)
    if extra_overrides:
        if parameter in extra_overrides:
            raise ValueError(f"extra_overrides sets the swept parameter {parameter!r}")
        cfg = cfg.with_overrides(extra_overrides)
    if not isinstance(cfg, Config):
        raise ValueError(f"cfg must be a Config, got {type(cfg).__name__}")
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, numbers.Integral) or n_jobs == 0:
        raise ValueError(f"n_jobs must be a non-zero integer, got {n_jobs!r}")
    if backend not in ("joblib", "dask"):
        raise ValueError(f"backend must be 'joblib' or 'dask', got {backend!r}")
    point = _default_point() if point is None else point
    if not callable(point):
        raise ValueError(f"point must be callable, got {point!r}")

    chash = config_hash(cfg, exclude=[parameter])
    records: dict[int, dict] = {}
    vectors: dict[int, np.ndarray] = {}
    store = None
    if out is not None:
        from . import __version__

        header = {"format": FORMAT, "version": FORMAT_VERSION, "parameter": parameter,
                  "config_hash": chash, "point": _point_name(point),
                  "tefcore_version": __version__,
                  "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}
        store = _SweepFile(out, header, resume)
        for i, k in enumerate(keys):
            rec = store.records.get(k)
            if rec is not None and not (retry_failed and rec["status"] != "ok"):
                records[i] = rec
    n_loaded = len(records)
    todo = [i for i in range(len(values)) if i not in records]

    def args(i):
        return point, cfg, parameter, values[i], keys[i]

    if backend == "dask":
        runner = _run_dask(todo, args, n_jobs, client)
    elif n_jobs == 1 or len(todo) <= 1:
        runner = _run_serial(todo, args)
    else:
        runner = _run_joblib(todo, args, n_jobs)

    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    n_failed = sum(r["status"] != "ok" for r in records.values())
    bar = tqdm(total=len(values), initial=n_loaded, disable=not progress, file=sys.stderr,
               desc=f"sweep {parameter}", unit="pt")
    try:
        if todo:
            for i, rec, vecs in runner:
                records[i] = rec
                if vecs is not None:
                    vectors[i] = vecs
                if store is not None:
                    store.append(rec)
                n_failed += rec["status"] != "ok"
                bar.set_postfix(failed=n_failed, refresh=False)
                bar.update()
    finally:
        runner.close()
        bar.close()
        if store is not None:
            store.close()

    table, modes = _build_table(parameter, values, records, vectors)
    return SweepResult(parameter=parameter, values=values, table=table, config_hash=chash,
                       eigenvectors=vectors, n_computed=len(todo), n_loaded=n_loaded,
                       out=None if out is None else Path(out), _modes=modes)


# ------------------------------------------------------------------ boundary


@dataclass
class BoundaryResult:
    """Result of :func:`stability_boundary`.

    Attributes
    ----------
    parameter, mode : str
    value : float
        Parameter value (SI) where the mode's real part is zero.
    bracket : (float, float)
        Adjacent scan values between which the real part changes sign (the
        first such pair).
    crossings : list of (float, float)
        All scan brackets with a sign change (several: several boundaries).
    iterations, function_calls : int
        Of :func:`scipy.optimize.brentq` (calls include the two bracket ends,
        taken from the scan).
    converged : bool
    real_part, frequency_per_rev : float
        Of the tracked mode at `value`.
    direction : str
        ``"destabilising"`` when the real part grows through zero with the
        parameter, else ``"stabilising"``.
    scan : SweepResult
    xtol, rtol : float
    """

    parameter: str
    mode: str
    value: float
    bracket: tuple[float, float]
    crossings: list
    iterations: int
    function_calls: int
    converged: bool
    real_part: float
    frequency_per_rev: float
    direction: str
    scan: SweepResult = field(repr=False)
    xtol: float = 0.0
    rtol: float = 0.0


def _to_si(cfg: Config, parameter: str, v) -> float:
    si = cfg.with_overrides({parameter: v}).get(parameter)
    if not isinstance(si, numbers.Real):
        raise ValueError(f"{parameter} is not a numeric field (value {si!r})")
    return float(si)


def stability_boundary(cfg: Config, parameter: str, bracket, mode: str = "TEF", *,
                       point: Callable | None = None, scan=None, xtol: float | None = None,
                       rtol: float = 4 * np.finfo(float).eps, maxiter: int = 100,
                       extra_overrides: Mapping[str, Any] | None = None, n_jobs: int = 1,
                       progress: bool | None = False) -> BoundaryResult:
    """Parameter value where a mode's damping (real part) crosses zero.

    The range is scanned first (a :func:`sweep`, modes tracked by MAC and
    eigenvalue); the first pair of adjacent scan values where the tracked
    mode's real part changes sign is then refined by
    :func:`scipy.optimize.brentq`, each new evaluation identifying the mode
    by :func:`tefcore.tracking.match_modes` against the nearest evaluated
    point -- so a frequency crossing with another mode inside the bracket
    does not make the root finder jump to the other mode.

    Parameters
    ----------
    cfg : Config
    parameter : str
        Dotted numeric field.
    bracket : (lo, hi)
        Range, numbers (SI) or ``"value unit"`` strings; ``lo < hi``.
    mode : str
        Label of the mode (the track's label where it first appears,
        e.g. ``"TEF"``, ``"blade torsion 1"``).  If several tracks carry it,
        the one present at the most scan points is followed, preferring one
        whose real part changes sign (with a warning).
    point : callable, optional
        As in :func:`sweep`.
    scan : int or sequence, optional
        Number of equally spaced scan values over the bracket (default 9),
        or the values themselves (numbers/strings, at least 2).  Too coarse
        a scan can miss a pair of close crossings.
    xtol, rtol : float
        Of brentq: the root is within about ``xtol + rtol*|value|`` of the
        true crossing of the point function.  Default ``xtol`` is
        ``1e-6 * (hi - lo)``.
    maxiter : int
    extra_overrides, n_jobs, progress
        Passed to :func:`sweep` for the scan (`extra_overrides` also for
        the refinement).

    Returns
    -------
    BoundaryResult

    Raises
    ------
    ValueError
        Bad arguments; the mode is absent at every scan point (the message
        lists the labels present); or its real part does not change sign in
        the range (the message gives its range there).
    RuntimeError
        The point function failed during the refinement (with the value),
        or the mode could not be followed.
    """
    parameter = _check_parameter(parameter)
    base = cfg.with_overrides(extra_overrides) if extra_overrides else cfg
    try:
        lo, hi = bracket
    except (TypeError, ValueError):
        raise ValueError(f"bracket must be (lo, hi), got {bracket!r}") from None
    lo, hi = _to_si(base, parameter, lo), _to_si(base, parameter, hi)
    if not lo < hi:
        raise ValueError(f"bracket must have lo < hi, got ({lo!r}, {hi!r}) in SI")
    if scan is None:
        scan = 9
    if isinstance(scan, numbers.Integral) and not isinstance(scan, bool):
        if scan < 2:
            raise ValueError(f"scan needs at least 2 points, got {scan}")
        xs = np.linspace(lo, hi, int(scan)).tolist()
    else:
        xs = sorted({_to_si(base, parameter, v) for v in scan})
        if len(xs) < 2:
            raise ValueError("scan needs at least 2 distinct values")
    xtol = 1e-6 * (hi - lo) if xtol is None else float(xtol)

    res = sweep(base, parameter, xs, point=point, n_jobs=n_jobs, progress=progress)
    point = _default_point() if point is None else point
    t = res.table[res.table["status"] == "ok"]
    if t.empty:
        raise ValueError(f"every scan point of {parameter} failed: "
                         f"{res.failed['error'].iloc[0]}")
    sizes = t[t["label"] == mode].groupby("track").size()
    if sizes.empty:
        raise ValueError(f"mode {mode!r} not found at any scan point of {parameter}; labels "
                         f"present: {sorted(set(t['label_here'].astype(str)))}")
    candidates = sizes.index[sizes.to_numpy() == sizes.max()].tolist()
    crossing = [k for k in candidates
                if np.ptp(np.sign(t.loc[t["track"] == k, "real_part"].to_numpy())) > 0]
    track = (crossing or candidates)[0]
    if len(sizes) > 1:
        warnings.warn(f"{len(sizes)} tracks are labelled {mode!r}; following track {track} "
                      "(present at the most scan points, preferring one whose real part "
                      "changes sign)", UserWarning, stacklevel=2)
    curve = t[t["track"] == track].sort_values("value_si")
    cx = curve["value_si"].to_numpy(float)
    cr = curve["real_part"].to_numpy(float)

    # evaluated points: x -> (modes, eigenvectors, row of the tracked mode)
    cache: dict[float, tuple] = {}
    for p, x, mid in zip(curve["point"], cx, curve["mode_id"], strict=True):
        m = res._modes[p]
        cache[float(x)] = (m, res.eigenvectors.get(p), int(np.flatnonzero(m["mode_id"] == mid)[0]))

    def real_part(x: float) -> float:
        x = float(x)
        if x not in cache:
            try:
                m, v, _ = _unpack(point(base.with_overrides({parameter: x})))
            except Exception as err:
                raise RuntimeError(f"{parameter} = {x!r}: point failed while locating the "
                                   f"{mode!r} boundary: {type(err).__name__}: {err}") from err
            near = min(cache, key=lambda y: abs(y - x))
            rm, rv, rj = cache[near]
            j = match_modes((rm, rv), (m, v))[rj]
            if j < 0:
                raise RuntimeError(f"{parameter} = {x!r}: mode {mode!r} lost (fewer modes)")
            cache[x] = (m, v, int(j))
        m, _, j = cache[x]
        return float(m["real_part"].iloc[j])

    crossings = [(float(cx[k]), float(cx[k + 1])) for k in range(len(cx) - 1)
                 if cr[k] == 0 or np.sign(cr[k]) * np.sign(cr[k + 1]) < 0]
    if cr[-1] == 0:
        crossings.append((float(cx[-1]), float(cx[-1])))
    if not crossings:
        state = "stable" if cr.max() < 0 else "unstable"
        raise ValueError(
            f"no zero crossing of the {mode!r} real part for {parameter} in [{lo:g}, {hi:g}]: "
            f"it stays {state}, between {cr.min():.4g} and {cr.max():.4g} /rev over "
            f"{len(cx)} scan points; widen the bracket or refine the scan")
    a, b = crossings[0]
    if real_part(a) == 0:
        value, iterations, calls, converged = a, 0, 0, True
    else:
        value, rr = brentq(real_part, a, b, xtol=xtol, rtol=rtol, maxiter=maxiter,
                           full_output=True, disp=False)
        iterations, calls, converged = rr.iterations, rr.function_calls, rr.converged
    r_at = real_part(value)
    m, _, j = cache[float(value)]
    slope = np.sign(real_part(b) - real_part(a)) if b != a else 0.0
    return BoundaryResult(
        parameter=parameter, mode=mode, value=float(value), bracket=(a, b),
        crossings=crossings, iterations=int(iterations), function_calls=int(calls),
        converged=bool(converged), real_part=r_at,
        frequency_per_rev=float(m["frequency_per_rev"].iloc[j]),
        direction="destabilising" if slope > 0 else "stabilising", scan=res,
        xtol=xtol, rtol=rtol)
