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

import numbers
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm import tqdm

from ..config.configuration import SECTIONS, Config, resolve_field
from ..modes.roles import exceptional_points, undecided_steps
from ..runtime import process_count
from ..safe_io import atomic_output
from .evaluate import (
    WARM_CHAIN,
    chains,
    clipped_summary,
    dask_client,
    default_point,
    min_chains,
    point_name,
    run_dask,
    run_joblib,
    run_serial,
    takes_warm_start,
    warn_clipped,
)
from .store import SweepFile, config_hash, sweep_header, value_key
from .table import MIN_REFINE_BUDGET, build_table, refinements

__all__ = ["SweepResult", "check_parameter", "sweep"]


# ------------------------------------------------------------------ helpers


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


# ------------------------------------------------------------------ backends


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
        ("ok"/"failed"), ``error`` (None when ok), ``warning`` (None, or
        what a point's result carries a doubt about: C81 table inputs clipped,
        how often and how far), ``track`` (the curve the
        root lies on: roots of neighbouring points linked by eigenvalue and
        shape, :func:`tefcore.modes.tracking.track_modes`), ``label`` (the
        root's name at its point: the uncoupled mode it continues from,
        :func:`tefcore.modes.continuation.continue_roots`), ``dominant`` (the
        coordinate it carries most there), ``identity`` (how the row
        continues its track), the mode columns (``mode_id``,
        ``frequency_per_rev``, ``frequency_tracked`` -- continuous along each
        name, :func:`tefcore.modes.matching.continuous_frequency` --,
        ``real_part``, ``damping_ratio``, ``real_part_uncoupled``,
        ``frequency_continued`` -- the frequency as continuation carried it
        from the uncoupled root --, ...), the
        roles ``tef_branch`` (the root named ``TEF``), ``tef_branch_certain``
        (and its path from zero coupling decided) and ``flutter_root`` (the
        least stable flap-induced root of its point,
        :func:`tefcore.modes.roles.flutter_root`), and the trim scalars as
        ``trim_<name>``.  A
        failed point is one row with its reason; its result columns are
        NaN/NA.  A pure function of the points' results: fresh, resumed
        and parallel runs give the same table.
    config_hash : str
        :func:`tefcore.sweeps.store.config_hash` of the base configuration without
        `parameter`.
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
    clipped : dict or None
        The C81 table inputs clipped over the sweep: evaluations, decks and
        extreme inputs (:func:`tefcore.aero.c81.range_summary.merge_clipped`).
    n_clipped : int
        Points with clipped inputs (their ``warning`` column says so).
    timing : dict
        How the points of this run were computed: ``wall_s`` (seconds of
        evaluation), ``point_s`` (the points' own seconds, summed),
        ``processes`` (at most at work) and ``speedup`` (``point_s / wall_s``).
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
    vectors: dict = field(default_factory=dict, repr=False)
    clipped: dict | None = None
    n_clipped: int = 0
    _modes: dict = field(default_factory=dict, repr=False)
    timing: dict = field(default_factory=dict)

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
    def exceptional_points(self) -> pd.DataFrame:
        """Where along the sweep which root is which has no answer.

        See :func:`tefcore.modes.roles.exceptional_points` (``x_low``,
        ``x_high`` in SI values of the parameter).
        """
        t = self.table[self.table["status"] == "ok"]
        return exceptional_points(t, x="value_si")

    @property
    def undecided_steps(self) -> pd.DataFrame:
        """Where a name moves to another root with no exceptional point located there.

        See :func:`tefcore.modes.roles.undecided_steps` (``x_low``, ``x_high``
        in SI values of the parameter; ``kind`` ``"identity undecided"`` or
        ``"named by participation"``).
        """
        t = self.table[self.table["status"] == "ok"]
        return undecided_steps(t, x="value_si")

    def curve(self, label: str) -> pd.DataFrame:
        """Rows of the root named `label` at each point, in sweep order.

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


def sweep(cfg: Config, parameter: str, values, *, point: Callable | None = None,
          n_jobs: int = 1, backend: str = "joblib", progress: bool | None = None,
          out=None, resume: bool = True, extra_overrides: Mapping[str, Any] | None = None,
          client=None, retry_failed: bool = False, refine: bool = True,
          warn: bool = True) -> SweepResult:
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
        again, up to :data:`~tefcore.sweeps.table.MAX_REFINE` bisections
        (:data:`~tefcore.sweeps.table.MAX_REFINE_BRANCH`
        where the TEF branch is ambiguous, those first, with their own budget
        of :data:`~tefcore.sweeps.table.MIN_REFINE_BUDGET` points) and at most that or twice as
        many added points as asked for, whichever is more, for the other
        modes; the added points are rows with
        ``refinement > 0``.
    warn : bool
        Emit one ``C81RangeWarning`` for the sweep when points had C81
        table inputs clipped (how many points, the extreme inputs); each
        such point says so in the table's ``warning`` column either way.

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
    cfg, point = _checked_arguments(cfg, parameter, point, n_jobs, backend, extra_overrides)
    chash = config_hash(cfg, exclude=[parameter])
    store, records = _open_store(out, cfg, parameter, chash, point, resume, retry_failed)
    n_loaded = sum(k in records for k in keys)
    jobs = chains(cfg, parameter, values, keys, records,
                  lambda i: (point, cfg, parameter, values[i], keys[i], 0),
                  WARM_CHAIN if takes_warm_start(point) else 1)
    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    run = _Run(keys, records, store, backend, n_jobs, client, progress,
               f"sweep {parameter}", len(values), n_loaded)
    try:
        # the TEF branch has its own budget: other modes' doubts cannot use it up
        budgets = ({"branch": MIN_REFINE_BUDGET, "other": max(2 * len(values), MIN_REFINE_BUDGET)}
                   if refine else {"branch": 0, "other": 0})
        while True:
            run.evaluate(jobs)
            if not any(budgets.values()):
                break
            jobs = run.refinement_jobs(budgets, point, cfg, parameter, retry_failed)
            if jobs is None:
                break
    finally:
        run.close()

    active = run.active()
    table, modes, shapes = build_table(parameter, values, keys, active, run.track_cache)
    index_of = {k: i for i, k in enumerate(keys)}
    n_clipped, clipped = clipped_summary(active.values())
    if warn:
        warn_clipped(f"sweep of {parameter}", n_clipped, len(active), clipped)
    return SweepResult(parameter=parameter, values=values, table=table, config_hash=chash,
                       eigenvectors={index_of[k]: v for k, v in run.vectors.items()
                                     if k in index_of},
                       n_computed=run.n_computed, n_loaded=n_loaded, n_refined=run.n_refined,
                       out=None if out is None else Path(out), vectors=shapes,
                       clipped=clipped, n_clipped=n_clipped, _modes=modes,
                       timing=run.timing())


def _checked_arguments(cfg, parameter, point, n_jobs, backend, extra_overrides):
    """The base configuration (with `extra_overrides`) and the point function, checked."""
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
    return cfg, point


def _open_store(out, cfg, parameter, chash, point, resume, retry_failed):
    """The sweep file (or None) and the records to keep from it (key -> record)."""
    records: dict[str, dict] = {}
    if out is None:
        return None, records
    store = SweepFile(out, sweep_header(cfg, parameter, chash, point_name(point)), resume)
    for k, rec in store.records.items():
        if not (retry_failed and rec["status"] != "ok"):
            records[k] = rec
    return store, records


class _Run:
    """The points of one sweep as they are evaluated: records, file, progress, backend."""

    def __init__(self, keys, records, store, backend, n_jobs, client, progress, desc, total,
                 n_loaded):
        self.keys, self.main, self.records, self.store = keys, set(keys), records, store
        self.backend, self.n_jobs, self.client = backend, n_jobs, client
        self.client_own = self.cluster = None
        self.vectors: dict[str, np.ndarray] = {}
        self.n_computed = self.n_refined = 0
        self.wall_s = self.point_s = 0.0
        self.processes = 1
        self.n_failed = sum(records[k]["status"] != "ok" for k in keys if k in records)
        self.wanted: dict[str, int] = {}    # refinement key -> depth, as this run decides them
        self.track_cache: dict = {}         # the last tracking (tefcore.sweeps.table._tracked)
        self.bar = tqdm(total=total, initial=n_loaded, disable=not progress, file=sys.stderr,
                        desc=desc, unit="pt")

    def active(self) -> dict:
        """The records of this sweep: the points asked for and its refinements."""
        out = {k: self.records[k] for k in self.keys if k in self.records}
        out.update({k: {**self.records[k], "refinement": d} for k, d in self.wanted.items()
                    if k in self.records})
        return out

    def _runner(self, jobs):
        if self.backend == "dask":
            if self.client_own is None:
                self.client_own, self.cluster = dask_client(self.n_jobs, self.client,
                                                            n_tasks=len(jobs))
            return run_dask(jobs, self.client_own)
        # small jobs stay serial: a cold pool's start costs more than they take
        if self.n_jobs == 1 or len(jobs) < min_chains() or process_count(self.n_jobs,
                                                                          len(jobs)) < 2:
            return run_serial(jobs)
        return run_joblib(jobs, self.n_jobs)

    def evaluate(self, jobs) -> None:
        """Evaluate the chains `jobs`; every finished point is recorded and stored at once."""
        if not jobs:
            return
        runner = self._runner(jobs)
        if runner.__name__ != "run_serial":
            self.processes = max(self.processes, process_count(self.n_jobs, len(jobs)))
        key_of = {i: args[4] for chain in jobs for i, args, _ in chain}
        start = time.perf_counter()
        try:
            for i, rec, vecs in runner:
                self.point_s += rec.get("elapsed_s") or 0.0
                key = key_of[i]
                self.records[key] = rec
                if vecs is not None:
                    self.vectors[key] = vecs
                if self.store is not None:
                    self.store.append(rec)
                self.n_failed += rec["status"] != "ok"
                if key in self.main:
                    self.n_computed += 1
                else:
                    self.n_refined += 1
                self.bar.set_postfix(failed=self.n_failed, refresh=False)
                self.bar.update()
        finally:
            runner.close()
            self.wall_s += time.perf_counter() - start

    def timing(self) -> dict:
        """Seconds of evaluation, the points' own seconds, processes and speed-up."""
        return {"wall_s": self.wall_s, "point_s": self.point_s, "processes": self.processes,
                "speedup": self.point_s / self.wall_s if self.wall_s > 0 else float("nan")}

    def refinement_jobs(self, budgets, point, cfg, parameter, retry_failed):
        """The next round of midpoints of undecided steps as jobs, or None when done.

        A midpoint already in the file (a resumed sweep) is reused; refinement
        points start cold: their neighbours' trims may not be at hand (a
        resumed sweep), and cold is the same in every run.
        """
        mids = [m for m in refinements(self.active(), budgets, self.main, self.track_cache)
                if value_key(m[0]) not in self.wanted and value_key(m[0]) not in self.main]
        if not mids:
            return None
        jobs = []
        for x, depth, which in mids:
            key = value_key(x)
            self.wanted[key] = depth
            budgets[which] -= 1
            if key not in self.records or (retry_failed and self.records[key]["status"] != "ok"):
                jobs.append([(len(self.keys) + len(self.wanted),
                              (point, cfg, parameter, float(x), key, depth), True)])
        self.bar.total += len(jobs)
        return jobs

    def close(self) -> None:
        self.bar.close()
        if self.store is not None:
            self.store.close()
        if self.cluster is not None:
            self.client_own.close()
            self.cluster.close()
