"""Parameter sweeps of the Floquet stability.

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
point; the file format and its store are in :mod:`tefcore.sweep_store`.
:func:`~tefcore.boundary.stability_boundary` (in :mod:`tefcore.boundary`,
re-exported here) finds where a mode's damping crosses zero.

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
"""

from __future__ import annotations

import numbers
import os
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd
from tqdm import tqdm

from .config import SECTIONS, Config, resolve_field
from .errors import error_text
from .safe_io import atomic_output
from .sweep_store import _jsonable, _SweepFile, _value_key, config_hash, sweep_header
from .tracking import label_changes, track_modes

if TYPE_CHECKING:  # at run time re-exported by __getattr__ (end of the module)
    from .boundary import BoundaryResult, stability_boundary

__all__ = ["BoundaryResult", "SweepResult", "config_hash", "stability_boundary", "sweep"]

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
            "error": error_text(err), "trim": {}, "modes": None}


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
        rec["error"] = error_text(err)
        vecs = None
    rec["elapsed_s"] = round(time.perf_counter() - start, 6)
    return index, rec, vecs


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
        """Write :attr:`table` as CSV (no index), atomically; return the path."""
        with atomic_output(path, newline="") as f:
            self.table.to_csv(f, index=False, **kwargs)
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
    # label_weight stays 0: where TEF and torsion coalesce in flutter the
    # participation labels flip between points and a label-following track
    # jumps between the two branches (measured on Figs. 10 and 12)
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
        Sweep file (JSON lines, see :mod:`tefcore.sweep_store`); every finished
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
        A sweep file that cannot be resumed is a
        :class:`~tefcore.errors.SweepFileError` (a ``ValueError``) naming
        what changed (configuration, input files, tefcore version, model
        code) or the damaged line.
    tefcore.errors.OutputError
        `out` is a symbolic link, its folder cannot be created, or another
        sweep is writing it (advisory lock, :mod:`tefcore.safe_io`);
        raised before any point is computed.
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
        header = sweep_header(cfg, parameter, chash, _point_name(point))
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


# ------------------------------------------------------------------ re-exports

# tefcore.boundary imports this module, so its names are looked up on first
# use (PEP 562) rather than imported here: no import cycle either way round.
_BOUNDARY_NAMES = frozenset({"BoundaryResult", "stability_boundary"})


def __getattr__(name: str):
    if name in _BOUNDARY_NAMES:
        from . import boundary

        return getattr(boundary, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | _BOUNDARY_NAMES)
