"""Parameter sweeps of the Floquet stability.

:func:`sweep` evaluates a point function (by default
:func:`tefcore.linear.stability.stability`) at each value of one configuration
field -- flap overhang, CG offset, pitch-link stiffness, GJ factor, actuator
stiffness, flap location/length/chord, collective, advance ratio, ... --
serially, in joblib (loky) processes or on a dask cluster, and returns a
tidy table with the modes tracked along the sweep (:mod:`tefcore.modes.tracking`).
A point that fails (invalid configuration, trim not converged: any
``Exception``) is recorded with its reason and the sweep goes on.  With
``out=path`` every finished point is appended to a JSON-lines file at once,
so an interrupted sweep can be resumed without losing or recomputing a
point; the file format and its store are in :mod:`tefcore.sweeps.store`.
:func:`tefcore.sweeps.boundary.stability_boundary` finds where a mode's damping
crosses zero.

Examples
--------
>>> import numpy as np, pandas as pd
>>> from types import SimpleNamespace
>>> from tefcore.config.io import load_config
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

import inspect
import numbers
import os
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm import tqdm

from ..config.sections import SECTIONS, Config, resolve_field
from ..errors import error_text
from ..modes.roles import anchor_root, anchor_row, assign_roles
from ..modes.tracking import ambiguous_steps, follow_branch, label_changes, track_modes
from ..runtime import worker_init
from ..safe_io import atomic_output
from .store import SweepFile, config_hash, jsonable, sweep_header, value_key

__all__ = ["MAX_REFINE", "WARM_CHAIN", "REQUIRED_MODE_COLUMNS", "SweepResult",
           "check_parameter", "check_result", "config_hash", "decode_complex", "default_point",
           "encode_complex", "shape_vectors", "sweep", "takes_warm_start"]

#: Columns a point function's ``modes`` table must have.
REQUIRED_MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part", "damping_ratio")
_NUMERIC_MODE_COLUMNS = ("frequency_per_rev", "real_part", "damping_ratio")


# ------------------------------------------------------------------ helpers


def default_point() -> Callable:
    """The default point function, :func:`tefcore.linear.stability.stability`.

    Returns
    -------
    callable
        ``stability(cfg)``: one configuration to its modes, eigenvectors and trim.
    """
    from ..linear.stability import stability  # deferred: heavy, and written separately

    return stability


def _point_name(point) -> str:
    target = point if hasattr(point, "__qualname__") else type(point)
    return f"{getattr(target, '__module__', '?')}:{getattr(target, '__qualname__', '?')}"


def check_parameter(parameter: str) -> str:
    """Check that ``parameter`` is a scalar configuration field one can sweep.

    Parameters
    ----------
    parameter : str
        Dotted field name, e.g. ``"flap.cg_offset"``.

    Returns
    -------
    str
        ``parameter`` unchanged.

    Raises
    ------
    ValueError
        For an unknown field (with a close match), a top-level field
        (``name``) or an array field.
    """
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
    keys = [value_key(v) for v in values]
    seen: dict[str, int] = {}
    for i, k in enumerate(keys):
        if k in seen:
            raise ValueError(f"duplicate sweep value {values[i]!r} (same as values[{seen[k]}])")
        seen[k] = i
    return values, keys


def check_result(result) -> tuple[pd.DataFrame, np.ndarray | None, dict]:
    """Check a point function's result and take it apart.

    Parameters
    ----------
    result : object
        What a point function returned: an object with a ``modes``
        DataFrame (the columns of :data:`REQUIRED_MODE_COLUMNS`, finite) and
        optionally ``eigenvectors`` (one column per mode) and ``trim`` (a
        mapping).

    Returns
    -------
    modes : pandas.DataFrame
        The modes table, index reset.
    eigenvectors : numpy.ndarray or None
    trim : dict
        The trim values, made JSON-serialisable.

    Raises
    ------
    TypeError
        Without a ``modes`` DataFrame.
    ValueError
        For missing columns, no modes, non-finite values or eigenvectors
        that do not match the modes.
    """
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
    return modes, vecs, {str(k): jsonable(v) for k, v in dict(trim).items()}


def shape_vectors(result, eigenvectors):
    """The mode shapes tracking compares: ``result.vectors``, else the eigenvectors.

    Parameters
    ----------
    result : object
        A point function's result (see :func:`check_result`).
    eigenvectors : numpy.ndarray or None
        Its eigenvectors, as returned by :func:`check_result`.

    Returns
    -------
    numpy.ndarray or None
        One column per mode, or None when the result has neither.

    Raises
    ------
    ValueError
        For non-finite shapes.
    """
    vecs = getattr(result, "vectors", None)
    vecs = eigenvectors if vecs is None else np.asarray(vecs)
    if vecs is None:
        return None
    if not np.isfinite(vecs).all():
        raise ValueError("point function returned non-finite mode shapes")
    return vecs


def _failed_record(key, value, err) -> dict:
    return {"key": key, "value": jsonable(value), "value_si": None, "status": "failed",
            "error": error_text(err), "trim": {}, "modes": None}


def _evaluate(index, point, cfg, parameter, value, key, anchor=False, depth=0, warm=None):
    """Evaluate one sweep point; never raises an ``Exception`` (it is recorded).

    ``anchor``: also identify the flap mode by continuation from zero
    coupling (the start of the TEF branch). ``depth``: 0 for a point the
    caller asked for, k for a point added by the k-th refinement.  ``warm``:
    the previous point's trim, passed as ``warm_start`` (a point function that
    takes it); should that fail, the point is computed cold.  Returns
    ``(index, record, vectors, trim_result or None)``.
    """
    start = time.perf_counter()
    rec: dict[str, Any] = {"key": key, "value": jsonable(value), "value_si": None,
                           "status": "failed", "error": None, "trim": {}, "modes": None}
    if depth:
        rec["refinement"] = depth
    vecs = result = None
    try:
        cfg_v = cfg.with_overrides({parameter: value})
        rec["value_si"] = jsonable(cfg_v.get(parameter))
        result = None
        if warm is not None:
            try:
                result = point(cfg_v, warm_start=warm)
            except Exception:  # a warm start can send Newton astray: start cold
                result = None
        if result is None:
            result = point(cfg_v)
        modes, vecs, trim = check_result(result)
        shapes = shape_vectors(result, vecs)
        rec.update(status="ok", trim=trim,
                   modes={c: jsonable(modes[c].to_numpy()) for c in modes.columns},
                   periodic=bool(getattr(result, "periodic", False)))
        if shapes is not None:
            rec["vectors"] = encode_complex(shapes)
        if anchor:
            rec["anchor"] = anchor_root(result)
    except Exception as err:  # recorded, the sweep goes on
        rec["error"] = error_text(err)
        vecs = result = None
    rec["elapsed_s"] = round(time.perf_counter() - start, 6)
    return index, rec, vecs, getattr(result, "trim_result", None)


def _evaluate_chain(chain):
    """Evaluate a warm-start chain: each point starts from the previous point's trim.

    ``chain`` is a list of ``(index, args, keep)`` (``args`` of :func:`_evaluate`);
    a point with ``keep`` False is computed only as the warm start of the next
    (a resumed sweep: it is in the file already).  A failed point makes the next
    one start cold.  Yields the ``(index, record, vectors)`` of the kept points
    as they finish.
    """
    warm = None
    for index, args, keep in chain:
        point = args[0]
        i, rec, vecs, tr = _evaluate(index, *args,
                                     warm=warm if takes_warm_start(point) else None)
        warm = tr if rec["status"] == "ok" else None
        if keep:
            yield i, rec, vecs


def takes_warm_start(point) -> bool:
    """Whether the point function takes a ``warm_start`` keyword (as
    :func:`tefcore.linear.stability.stability` does).

    Parameters
    ----------
    point : callable
        A point function.

    Returns
    -------
    bool
    """
    try:
        return "warm_start" in inspect.signature(point).parameters
    except (TypeError, ValueError):
        return False


# ------------------------------------------------------------------ backends


def _evaluate_in_worker(chain):
    """The task of a worker process: the process settings first (tefcore.runtime)."""
    worker_init()
    return list(_evaluate_chain(chain))


def _run_serial(jobs):
    for chain in jobs:
        yield from _evaluate_chain(chain)


def _run_joblib(jobs, n_jobs):
    from joblib import Parallel, delayed

    par = Parallel(n_jobs=n_jobs, backend="loky", return_as="generator_unordered")
    for done in par(delayed(_evaluate_in_worker)(chain) for chain in jobs):
        yield from done


def _dask_client(n_jobs, client):
    """(client, cluster to close or None) for backend='dask'."""
    try:
        from distributed import Client, LocalCluster
    except ImportError as err:
        raise ImportError("backend='dask' needs dask.distributed: pip install "
                          "'dask[distributed]' (or the tefcore[dask] extra)") from err
    if client is not None:
        return client, None
    workers = os.cpu_count() if n_jobs < 0 else n_jobs
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster), cluster


def _run_dask(jobs, client):
    from distributed import as_completed

    futures = {}
    try:
        for chain in jobs:
            futures[client.submit(_evaluate_in_worker, chain, pure=False)] = chain
        for fut in as_completed(list(futures)):
            try:
                yield from fut.result()
            except Exception as err:  # e.g. a worker died: record it, go on
                for i, args, keep in futures[fut]:
                    if keep:
                        yield i, _failed_record(args[4], args[3], err), None
    finally:
        client.cancel(list(futures))


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
        One row per (value, mode), in the order of the parameter (SI), with
        the points added by refinement between them: ``point`` (index in
        `values`; refinement points follow, numbered by value),
        ``parameter``, ``value`` (as given), ``value_si`` (validated field
        value, SI), ``refinement`` (0 for the points asked for, k for a
        point added by the k-th bisection of an ambiguous step), ``status``
        ("ok"/"failed"), ``error`` (None when ok), ``track``, ``label`` (the
        track's label where it starts), ``label_here`` (the point's own
        label), ``identity`` (how the row continues its track:
        :mod:`tefcore.modes.tracking`), the mode columns (``mode_id``,
        ``frequency_per_rev``, ``real_part``, ``damping_ratio``, ...), the
        named roles ``tef_branch`` (the row is on the TEF branch: the flap
        mode at the sweep start, followed along its track and past the
        track's end by :func:`tefcore.modes.tracking.follow_branch`),
        ``tef_branch_certain`` (no undecided match or change of track on the
        branch between the start and this row) and
        ``flutter_root`` (the least stable root of its point with a flap
        participation >= 0.1), and the trim scalars as ``trim_<name>``.  A
        failed point is one row with its reason; its result columns are
        NaN/NA.  A pure function of the points' results: fresh, resumed
        and parallel runs give the same table.
    config_hash : str
        :func:`config_hash` of the base configuration without `parameter`.
    eigenvectors : dict of int to ndarray
        Point index -> state eigenvectors (columns as the rows of that
        point's modes table); only for points computed in this run.
    vectors : dict of int to ndarray
        Point index -> the shapes tracking compared (columns as the rows of
        that point's modes table), for every ok point, loaded or computed.
    n_computed, n_loaded : int
        Of the points asked for: evaluated in this run / loaded from the
        `out` file.
    n_refined : int
        Points added by refinement and evaluated in this run.
    out : Path or None
        The sweep file.
    anchor : dict
        Where the TEF branch starts: ``point``, ``mode_id`` and ``method``
        (``"zero coupling"``: the root the uncoupled flap mode becomes;
        ``"largest flap participation"``; ``"label"``), or empty.
    """

    parameter: str
    values: list
    table: pd.DataFrame
    config_hash: str
    eigenvectors: dict = field(default_factory=dict, repr=False)
    n_computed: int = 0
    n_loaded: int = 0
    n_refined: int = 0
    out: Path | None = None
    anchor: dict = field(default_factory=dict)
    vectors: dict = field(default_factory=dict, repr=False)
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
        """Where a tracked mode's point label changes.

        See :func:`tefcore.modes.tracking.label_changes`.
        """
        return label_changes(self.table)

    def curve(self, label: str) -> pd.DataFrame:
        """Rows of the track(s) whose label is `label`, in sweep order.

        ``"TEF branch"`` gives the TEF branch (the ``tef_branch`` rows) and
        ``"flutter root"`` the flutter root of each point.
        """
        t = self.table[self.table["status"] == "ok"]
        if label == "TEF branch":
            return t[t["tef_branch"].fillna(False).astype(bool)]
        if label == "flutter root":
            return t[t["flutter_root"].fillna(False).astype(bool)]
        return t[t["label"] == label]

    def to_csv(self, path, **kwargs) -> Path:
        """Write :attr:`table` as CSV (no index), atomically; return the path."""
        with atomic_output(path, newline="") as f:
            self.table.to_csv(f, index=False, **kwargs)
        return Path(path)


#: Bisections of an ambiguous step at most (a step of 1/8 of the original).
MAX_REFINE = 3
#: ... and of a step where the TEF branch itself is ambiguous (1/32): the
#: branch is what the paper's claims are about, and a flap mode veering with
#: a blade mode can turn its shape within a few per cent of a sweep's step.
MAX_REFINE_BRANCH = 5
#: Points refinement may add for the TEF branch, and at least for the other
#: modes (else twice the points asked for).
MIN_REFINE_BUDGET = 24


def encode_complex(a) -> dict:
    """A complex array as ``{"re": [...], "im": [...]}`` (exact in JSON).

    Parameters
    ----------
    a : array_like of complex
        Any shape.

    Returns
    -------
    dict
        Nested lists of the real and imaginary parts.

    Examples
    --------
    >>> encode_complex([1 + 2j])
    {'re': [1.0], 'im': [2.0]}
    >>> decode_complex(encode_complex([1 + 2j]))
    array([1.+2.j])
    """
    a = np.asarray(a)
    return {"re": np.real(a).tolist(), "im": np.imag(a).tolist()}


def decode_complex(d) -> np.ndarray:
    """Inverse of :func:`encode_complex`.

    Parameters
    ----------
    d : dict
        ``{"re": [...], "im": [...]}``.

    Returns
    -------
    numpy.ndarray of complex
    """
    return np.asarray(d["re"], float) + 1j * np.asarray(d["im"], float)


def _ok_in_order(records: dict) -> list:
    """Keys of the ok records in the order of the parameter (SI), ties by key."""
    ok = [k for k, r in records.items() if r["status"] == "ok"
          and isinstance(r["value_si"], numbers.Real)]
    return sorted(ok, key=lambda k: (float(records[k]["value_si"]), str(k)))


def _points(records: dict, order: list) -> list:
    """The ok records in `order` as points of :func:`tefcore.modes.tracking.track_modes`."""
    pts = []
    for k in order:
        r = records[k]
        vec = decode_complex(r["vectors"]) if r.get("vectors") is not None else None
        pts.append({"modes": pd.DataFrame(r["modes"]), "vectors": vec,
                    "periodic": bool(r.get("periodic", False))})
    return pts


def _track(records: dict, order: list) -> pd.DataFrame:
    """:func:`tefcore.modes.tracking.track_modes` of the ok records in `order`."""
    return track_modes(_points(records, order),
                       values=[float(records[k]["value_si"]) for k in order])


def _branch(tracked: pd.DataFrame, records: dict, order: list, step: int, row: int):
    """:func:`tefcore.modes.tracking.follow_branch` from mode `row` of point `step` of `order`."""
    return follow_branch(tracked, _points(records, order), (step, row),
                         values=[float(records[k]["value_si"]) for k in order])


def _refinements(records: dict, budgets: dict, main: set,
                 use_anchor: bool = True) -> list[tuple[float, int, str]]:
    """Midpoints (SI value, depth, budget) of the steps whose tracking is ambiguous.

    While the TEF branch itself has ambiguous steps that may still be
    bisected (:data:`MAX_REFINE_BRANCH` times, from the ``"branch"`` budget),
    only those are returned; then the others (:data:`MAX_REFINE` times, from
    the ``"other"`` budget).
    """
    order = _ok_in_order(records)
    if len(order) < 2:
        return []
    tracked = _track(records, order)
    branch_steps = set()
    first = next((i for i, k in enumerate(order) if k in main), None)
    if first is not None:
        start = records[order[first]]
        row, _ = anchor_row(start.get("anchor"), pd.DataFrame(start["modes"]), use_anchor)
        if row is not None:
            path = _branch(tracked, records, order, first, row)
            branch_steps = set(path.loc[path["doubt"], "step"])
    def mids(steps, limit, which):
        out = []
        for step in sorted(steps):
            a, b = records[order[step - 1]], records[order[step]]
            depth = max(a.get("refinement", 0), b.get("refinement", 0)) + 1
            if depth <= limit and len(out) < budgets[which]:
                out.append((0.5 * (float(a["value_si"]) + float(b["value_si"])), depth, which))
        return out

    # the TEF branch's own doubts first, round after round, then the others
    return (mids(branch_steps, MAX_REFINE_BRANCH, "branch")
            or mids(ambiguous_steps(tracked), MAX_REFINE, "other"))


def _build_table(parameter, values, keys, records, anchor=True):
    """Tidy, tracked table from the records (key -> record), in parameter order."""
    n = len(values)
    main = {k: i for i, k in enumerate(keys)}
    extra = [k for k in _ok_in_order(records) if k not in main]
    index_of = dict(main)
    index_of.update({k: n + r for r, k in enumerate(extra)})
    order = _ok_in_order({k: records[k] for k in index_of})
    points = _points(records, order)
    values_si = [float(records[k]["value_si"]) for k in order]
    tracked = track_modes(points, values=values_si)
    tracked.insert(0, "key", np.asarray(order, dtype=object)[tracked.pop("step").to_numpy(int)])
    all_keys = list(keys) + extra
    info = pd.DataFrame({
        "key": pd.Series(all_keys, dtype=object),
        "point": [index_of[k] for k in all_keys],
        "parameter": parameter,
        "value": pd.Series(list(values) + [records[k]["value"] for k in extra], dtype=object),
        "value_si": pd.Series([records[k]["value_si"] for k in all_keys], dtype=object),
        "refinement": [int(records[k].get("refinement", 0)) for k in all_keys],
        "status": [records[k]["status"] for k in all_keys],
        "error": pd.Series([records[k]["error"] for k in all_keys], dtype=object),
    })
    for col in ("value", "value_si"):  # numbers -> float column, else keep objects
        try:
            info[col] = pd.to_numeric(info[col])
        except (TypeError, ValueError):
            pass
    trim = pd.DataFrame([records[k]["trim"] for k in all_keys]).add_prefix("trim_")
    table = info.merge(tracked, on="key", how="left", validate="one_to_many")
    table = table.merge(trim.assign(key=all_keys), on="key", how="left")
    for col in ("track", "mode_id"):
        table[col] = table[col].astype("Int64")
    si = pd.to_numeric(table["value_si"], errors="coerce")
    table = table.assign(_x=si.fillna(np.inf)).sort_values(
        ["_x", "point", "track"], kind="stable", ignore_index=True).drop(columns="_x")
    first = next((k for k in order if k in main), None)
    anchor = assign_roles(table, points, values_si, order, first,
                          records[first].get("anchor") if first is not None else None, anchor)
    modes = {index_of[k]: pd.DataFrame(records[k]["modes"]) for k in order}
    shapes = {index_of[k]: decode_complex(records[k]["vectors"]) for k in order
              if records[k].get("vectors") is not None}
    return table.drop(columns="key"), modes, anchor, shapes


def sweep(cfg: Config, parameter: str, values, *, point: Callable | None = None,
          n_jobs: int = 1, backend: str = "joblib", progress: bool | None = None,
          out=None, resume: bool = True, extra_overrides: Mapping[str, Any] | None = None,
          client=None, retry_failed: bool = False, refine: bool = True,
          anchor: bool = True) -> SweepResult:
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
        "800 lb/in"]``; no duplicates; any order (the table is in the order
        of the parameter).  Point ``i`` is
        ``point(cfg.with_overrides({parameter: values[i]}))``.
    point : callable, optional
        Config -> result with ``modes`` (DataFrame with columns
        ``mode_id``, ``label``, ``frequency_per_rev``, ``real_part``,
        ``damping_ratio``), optional ``eigenvectors`` (n_states, n_modes),
        ``vectors`` (shapes to compare between points, one column per
        mode), ``periodic`` (Floquet exponents) and ``trim`` (dict of
        scalars).  Default :func:`tefcore.linear.stability.stability`.  Must be
        picklable for ``n_jobs != 1``.
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
        Sweep file (JSON lines, see :mod:`tefcore.sweeps.store`); every finished
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
    refine : bool
        Where the identity of a mode between two neighbouring points is
        ambiguous (:mod:`tefcore.modes.tracking`), evaluate the midpoint and track
        again, up to :data:`MAX_REFINE` bisections (:data:`MAX_REFINE_BRANCH`
        where the TEF branch is ambiguous, those first, with their own budget
        of :data:`MIN_REFINE_BUDGET` points) and at most that or twice as
        many added points as asked for, whichever is more, for the other
        modes; the added points are rows with
        ``refinement > 0``.
    anchor : bool
        Identify the TEF branch at the sweep start by continuation from zero
        coupling (:func:`tefcore.modes.continuation.tef_root`) where the point function's
        result carries its linear system; otherwise by the largest flap
        participation.

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
    parameter = check_parameter(parameter)
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
    point = default_point() if point is None else point
    if not callable(point):
        raise ValueError(f"point must be callable, got {point!r}")

    chash = config_hash(cfg, exclude=[parameter])
    records: dict[str, dict] = {}
    store = None
    if out is not None:
        header = sweep_header(cfg, parameter, chash, _point_name(point))
        store = SweepFile(out, header, resume)
        for k, rec in store.records.items():
            if not (retry_failed and rec["status"] != "ok"):
                records[k] = rec
    main = set(keys)
    n_loaded = sum(k in records for k in keys)
    anchor_key = _anchor_key(cfg, parameter, values, keys) if anchor else None
    if anchor_key in records and records[anchor_key]["status"] == "ok" and \
            "anchor" not in records[anchor_key]:
        del records[anchor_key]     # computed before as an ordinary point: again, as the start
        n_loaded -= 1
    jobs = _chains(cfg, parameter, values, keys, records,
                   lambda i: (point, cfg, parameter, values[i], keys[i], keys[i] == anchor_key, 0),
                   WARM_CHAIN if takes_warm_start(point) else 1)

    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    n_failed = sum(records[k]["status"] != "ok" for k in keys if k in records)
    bar = tqdm(total=len(values), initial=n_loaded, disable=not progress, file=sys.stderr,
               desc=f"sweep {parameter}", unit="pt")
    vectors: dict[str, np.ndarray] = {}
    client_own = cluster = None
    n_computed = n_refined = 0
    wanted: dict[str, int] = {}        # refinement key -> depth, as this run decides them

    def active():
        out = {k: records[k] for k in keys if k in records}
        out.update({k: {**records[k], "refinement": d} for k, d in wanted.items()
                    if k in records})
        return out

    try:
        # the TEF branch has its own budget: other modes' doubts cannot use it up
        budgets = ({"branch": MIN_REFINE_BUDGET, "other": max(2 * len(values), MIN_REFINE_BUDGET)}
                   if refine else {"branch": 0, "other": 0})
        while True:
            if jobs:
                if backend == "dask":
                    if client_own is None:
                        client_own, cluster = _dask_client(n_jobs, client)
                    runner = _run_dask(jobs, client_own)
                elif n_jobs == 1 or len(jobs) <= 1:
                    runner = _run_serial(jobs)
                else:
                    runner = _run_joblib(jobs, n_jobs)
                key_of = {i: args[4] for chain in jobs for i, args, _ in chain}
                try:
                    for i, rec, vecs in runner:
                        records[key_of[i]] = rec
                        if vecs is not None:
                            vectors[key_of[i]] = vecs
                        if store is not None:
                            store.append(rec)
                        n_failed += rec["status"] != "ok"
                        if key_of[i] in main:
                            n_computed += 1
                        else:
                            n_refined += 1
                        bar.set_postfix(failed=n_failed, refresh=False)
                        bar.update()
                finally:
                    runner.close()
            # bisect the steps where a mode's identity is not decided; a
            # midpoint already in the file (a resumed sweep) is reused
            jobs = []
            if not any(budgets.values()):
                break
            mids = [m for m in _refinements(active(), budgets, main, anchor)
                    if value_key(m[0]) not in wanted and value_key(m[0]) not in main]
            if not mids:
                break
            for x, depth, which in mids:
                key = value_key(x)
                wanted[key] = depth
                budgets[which] -= 1
                if key not in records or (retry_failed and records[key]["status"] != "ok"):
                    # refinement points start cold: their neighbours' trims may
                    # not be at hand (a resumed sweep), and cold is the same in
                    # every run
                    jobs.append([(len(keys) + len(wanted),
                                  (point, cfg, parameter, float(x), key, False, depth), True)])
            bar.total += len(jobs)
    finally:
        bar.close()
        if store is not None:
            store.close()
        if cluster is not None:
            client_own.close()
            cluster.close()

    table, modes, start, shapes = _build_table(parameter, values, keys, active(), anchor)
    index_of = {k: i for i, k in enumerate(keys)}
    return SweepResult(parameter=parameter, values=values, table=table, config_hash=chash,
                       eigenvectors={index_of[k]: v for k, v in vectors.items() if k in index_of},
                       n_computed=n_computed, n_loaded=n_loaded, n_refined=n_refined,
                       out=None if out is None else Path(out), anchor=start, vectors=shapes,
                       _modes=modes)


#: Points of a warm-start chain: the values, in the order of their SI values, are
#: cut into consecutive chains of this many points, each one job in which every
#: point starts its trim from the previous point's (:func:`tefcore.linear.stability.stability`,
#: ``warm_start``; point functions without that keyword are evaluated one by
#: one).  The chains depend on the values alone, so fresh, resumed and parallel
#: sweeps compute every point from the same start: identical tables.  A resumed
#: sweep recomputes the points of a chain before its first missing one (as warm
#: starts, not stored again); an interrupted parallel sweep loses the finished
#: points of the chains still running in the workers (a serial one loses none).
WARM_CHAIN = 8


def _chains(cfg, parameter, values, keys, records, args_of, length=WARM_CHAIN):
    """The jobs of a sweep: warm-start chains of the points not in ``records``.

    Chains cut the values sorted by their SI value into runs of ``length``
    (:data:`WARM_CHAIN`; 1 for a point function without ``warm_start``); a
    chain runs from its start to its last missing point, recomputing the points
    before it that are in the file (as warm starts only).  Values the
    configuration rejects are single jobs (failed points).
    """
    if length == 1:
        return [[(i, args_of(i), True)] for i, k in enumerate(keys) if k not in records]
    si = {}
    for i, v in enumerate(values):
        try:
            x = cfg.with_overrides({parameter: v}).get(parameter)
        except Exception:  # a rejected value: a failed point of its own
            continue
        if isinstance(x, numbers.Real):
            si[i] = float(x)
    order = sorted(si, key=lambda i: (si[i], keys[i]))
    jobs = [[(i, args_of(i), True)] for i in range(len(values))
            if i not in si and keys[i] not in records]
    for start in range(0, len(order), length):
        chain = order[start:start + length]
        missing = [j for j, i in enumerate(chain) if keys[i] not in records]
        if missing:
            jobs.append([(i, args_of(i), keys[i] not in records)
                         for i in chain[:missing[-1] + 1]])
    return jobs


def _anchor_key(cfg, parameter, values, keys):
    """Key of the value with the smallest SI value (the sweep start), or None."""
    best = None
    for v, k in zip(values, keys, strict=True):
        try:
            si = cfg.with_overrides({parameter: v}).get(parameter)
        except Exception:  # a rejected value is a failed point, not the start
            continue
        if isinstance(si, numbers.Real) and (best is None or si < best[0]):
            best = (float(si), k)
    return None if best is None else best[1]
