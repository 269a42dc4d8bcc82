"""Evaluating sweep points: the point function, its checks, warm-start chains, backends.

A sweep point is ``point(cfg.with_overrides({parameter: value}))``
(:func:`evaluate_point`), recorded as a JSON-able dict whatever happens: an
``Exception`` is a failed point with its reason.  Points run in warm-start
chains (:func:`chains`, :data:`WARM_CHAIN`): each point starts its trim from
the previous point's.  Chains run serially, in joblib (loky) processes or on
a dask cluster (:func:`run_serial`, :func:`run_joblib`, :func:`run_dask`).
"""

from __future__ import annotations

import contextlib
import inspect
import numbers
import os
import time
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pandas as pd

from ..aero.c81.range_summary import (
    collected_range_warnings,
    describe_clipped,
    merge_clipped,
    range_warning,
)
from ..errors import error_text
from ..runtime import process_count, worker_init
from .store import jsonable

__all__ = ["MIN_COLD_CHAINS", "POOL_IDLE_SECONDS", "REQUIRED_MODE_COLUMNS", "WARM_CHAIN",
           "chains", "check_result", "clipped_summary", "close_pool", "command_pool",
           "decode_complex", "default_point", "encode_complex", "evaluate_point", "fork_workers",
           "forked_workers", "min_chains", "n_chains", "pool_ready", "pool_started", "run_joblib",
           "shape_vectors", "start_pool_for", "takes_warm_start", "warn_clipped", "worker_pool"]


#: Columns a point function's ``modes`` table must have.
REQUIRED_MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part", "damping_ratio")


_NUMERIC_MODE_COLUMNS = ("frequency_per_rev", "real_part", "damping_ratio")


def default_point() -> Callable:
    """The default point function, :func:`tefcore.linear.stability.stability`.

    Returns
    -------
    callable
        ``stability(cfg)``: one configuration to its modes, eigenvectors and trim.
    """
    from ..linear.stability import stability  # deferred: heavy, and written separately

    return stability


def point_name(point) -> str:
    target = point if hasattr(point, "__qualname__") else type(point)
    return f"{getattr(target, '__module__', '?')}:{getattr(target, '__qualname__', '?')}"


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


def failed_record(key, value, err) -> dict:
    return {"key": key, "value": jsonable(value), "value_si": None, "status": "failed",
            "error": error_text(err), "trim": {}, "modes": None}


def evaluate_point(index, point, cfg, parameter, value, key, depth=0, warm=None):
    """Evaluate one sweep point; never raises an ``Exception`` (it is recorded).

    ``depth``: 0 for a point the caller asked for, k for a point added by the
    k-th refinement.  ``warm``:
    the previous point's trim, passed as ``warm_start`` (a point function that
    takes it); should that fail, the point is computed cold.

    Parameters
    ----------
    index : int
        The point's index in the sweep (returned as is).
    point : callable
        The point function.
    cfg : tefcore.config.configuration.Config
        The base configuration.
    parameter : str
        The swept field.
    value : object
        Its value at this point, as given.
    key : str
        The point's key.
    depth : int, optional
        Refinement depth.
    warm : tefcore.trimming.trim.TrimResult, optional
        Warm start of the trim.

    Returns
    -------
    tuple
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
        # clipped C81 inputs are kept with the point (its 'warning'), not printed
        with collected_range_warnings() as found:
            result = _evaluate(point, cfg_v, warm)
        if found["clipped"] is not None:
            rec["clipped"] = found["clipped"]
            rec["warning"] = describe_clipped(found["clipped"])
        modes, vecs, trim = check_result(result)
        shapes = shape_vectors(result, vecs)
        rec.update(status="ok", trim=trim,
                   modes={c: jsonable(modes[c].to_numpy()) for c in modes.columns},
                   periodic=bool(getattr(result, "periodic", False)))
        if shapes is not None:
            rec["vectors"] = encode_complex(shapes)
    except Exception as err:  # recorded, the sweep goes on
        rec["error"] = error_text(err)
        vecs = result = None
    rec["elapsed_s"] = round(time.perf_counter() - start, 6)
    return index, rec, vecs, getattr(result, "trim_result", None)


def _evaluate(point, cfg_v, warm):
    """``point(cfg_v)``, from the warm start first when there is one."""
    if warm is not None:
        try:
            return point(cfg_v, warm_start=warm)
        except Exception:  # a warm start can send Newton astray: start cold
            pass
    return point(cfg_v)


def clipped_summary(records) -> tuple[int, dict | None]:
    """How many of the points `records` had C81 inputs clipped, and the merged summary.

    Parameters
    ----------
    records : iterable of dict
        Point records (:func:`evaluate_point`).

    Returns
    -------
    n : int
        Points with clipped inputs.
    clipped : dict or None
        :func:`tefcore.aero.c81.range_summary.merge_clipped` of them.
    """
    parts = [r.get("clipped") for r in records if r.get("clipped")]
    return len(parts), merge_clipped(parts)


def warn_clipped(what: str, n_clipped: int, n_points: int, clipped: dict | None,
                 stacklevel: int = 3) -> None:
    """One ``C81RangeWarning`` for a sweep or map: how many points, the extreme inputs.

    Parameters
    ----------
    what : str
        The sweep or map, for the message.
    n_clipped, n_points : int
        Points with clipped inputs, of all points.
    clipped : dict or None
        Their merged summary; nothing is emitted when None.
    stacklevel : int, optional
        Stack level of the warning.
    """
    if clipped is None:
        return
    warnings.warn(range_warning(
        f"{what}: C81 table inputs clipped at {n_clipped} of {n_points} points (see the "
        f"table's 'warning' column); {describe_clipped(clipped)}", clipped),
        stacklevel=stacklevel)


def evaluate_chain(chain):
    """Evaluate a warm-start chain: each point starts from the previous point's trim.

    ``chain`` is a list of ``(index, args, keep)`` (``args`` of :func:`evaluate_point`);
    a point with ``keep`` False is computed only as the warm start of the next
    (a resumed sweep: it is in the file already).  A failed point makes the next
    one start cold.  Yields the ``(index, record, vectors)`` of the kept points
    as they finish.
    """
    warm = None
    for index, args, keep in chain:
        point = args[0]
        i, rec, vecs, tr = evaluate_point(index, *args,
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


def evaluate_in_worker(chain):
    """The task of a worker process: the process settings first (tefcore.runtime)."""
    worker_init()
    return list(evaluate_chain(chain))


def run_serial(jobs):
    for chain in jobs:
        yield from evaluate_chain(chain)


#: Fewest chains of a cold pool worth worker processes.  A worker is ready
#: (spawned, the solver imported) 0.7-1 s after it is started, while a chain of
#: up to 8 points takes ~0.15 s at mu = 0.3: below ~10 chains the caller has done them
#: all before a cold worker could take one (measured: a 40-point sweep, 0.7 s of
#: points, ran wholly in the caller and the command took 0.27 s longer for
#: starting the pool).  A pool already started takes any two chains.
MIN_COLD_CHAINS = 10

#: Seconds an idle worker of the pool lives (loky reusable executor): long enough
#: for the next sweep of a script or notebook, not forever.
POOL_IDLE_SECONDS = 300


def _warm_worker():
    """A pool worker's start: the process settings and the solver imported, once."""
    worker_init()
    import tefcore.linear.stability  # noqa: F401  (the default point function's imports)


_pool = None          # (workers, executor, ready future, forked) of this process
_fork = False         # start the workers by forking this process (fork_workers)


def fork_workers(enabled: bool = True) -> bool:
    """Start this process's pool workers by forking it, where the platform can.

    For a short-lived process that has the solver imported already (the
    command line): a forked worker is ready in milliseconds with everything
    this process imported, where a spawned (loky) one starts a fresh
    interpreter and imports the solver, 0.7-1 s (:data:`MIN_COLD_CHAINS`), so
    that a sweep of a few chains could not use it.  Not for a notebook's
    kernel or a long-lived script, whose threads a fork would copy half-way;
    they keep loky's spawned pool, reused between sweeps.

    Parameters
    ----------
    enabled : bool, optional
        False: back to spawned workers.

    Returns
    -------
    bool
        Whether workers are forked from now on (False where the platform has
        no ``fork``).
    """
    import multiprocessing

    global _fork
    if _pool is not None and _pool[3] != enabled:
        close_pool()
    _fork = bool(enabled) and "fork" in multiprocessing.get_all_start_methods()
    return _fork


@contextlib.contextmanager
def command_pool():
    """Forked workers for one command (:func:`fork_workers`), the pool closed and
    the start method restored after it (a command run in-process, as the tests
    do, leaves nothing behind).

    Yields
    ------
    bool
        Whether the workers are forked.
    """
    previous = _fork
    try:
        yield fork_workers()
    finally:
        close_pool()
        fork_workers(previous)


def forked_workers() -> bool:
    """Whether this process's pool workers are forked (:func:`fork_workers`).

    Returns
    -------
    bool
    """
    return _fork


def min_chains() -> int:
    """Fewest chains worth the pool's workers: 2 when they are forked or started
    already, else :data:`MIN_COLD_CHAINS`.

    Returns
    -------
    int
    """
    return 2 if _fork or pool_started() else MIN_COLD_CHAINS


def worker_pool(n_workers: int):
    """The persistent pool of worker processes, started now.

    Spawned (a loky executor of tefcore's own): the workers apply the process
    settings and import the solver when they start (:func:`_warm_worker`),
    so a worker pays its start-up once, not per sweep, and an idle one exits
    after :data:`POOL_IDLE_SECONDS`; calling it early (the command does,
    before it loads its configuration) overlaps their start with the
    caller's own.  The pool is not joblib's reusable executor, which
    ``joblib.Parallel`` recreates whenever its arguments differ.  Forked
    (:func:`fork_workers`): the standard library's executor on the ``fork``
    context, the solver imported here first so that the workers have it.

    Parameters
    ----------
    n_workers : int
        Worker processes: at most the cores this process may use
        (:func:`tefcore.runtime.process_count`), however many are asked for.

    Returns
    -------
    concurrent.futures.Executor
        The executor (the same one while it has ``n_workers`` or more and works:
        a later, smaller task list, a sweep's refinement, keeps the pool).
    """
    global _pool
    n_workers = process_count(n_workers)
    if _pool is not None and (_pool[0] < n_workers or getattr(_pool[1], "_broken", False)):
        close_pool()
    if _pool is None:
        if _fork:
            import concurrent.futures as cf
            import multiprocessing

            import tefcore.linear.stability  # noqa: F401  (the workers inherit it imported)

            pool = cf.ProcessPoolExecutor(max_workers=n_workers, initializer=worker_init,
                                          mp_context=multiprocessing.get_context("fork"))
        else:
            from joblib.externals.loky import ProcessPoolExecutor

            pool = ProcessPoolExecutor(max_workers=n_workers, initializer=_warm_worker,
                                       timeout=POOL_IDLE_SECONDS)
        # done once a worker has started and imported: until then the caller
        # keeps the chains (a chain queued behind a worker's start could
        # finish after all the others)
        _pool = (n_workers, pool, pool.submit(int), _fork)
    return _pool[1]


def start_pool_for(n_points: int, n_jobs: int) -> None:
    """Start the worker pool now for a sweep of `n_points` on `n_jobs` processes, if it
    will use one (:func:`min_chains` warm-start chains or more, :func:`chains`; `n_jobs` as in
    :func:`run_joblib`): spawned workers start and import while the caller
    loads and checks its inputs (the command does); forked ones are copies of
    the caller as it is now.

    Parameters
    ----------
    n_points : int
        Points of the sweep.
    n_jobs : int
        Processes at work, the caller included (negative: all the cores), at
        most one per chain and per core (:func:`tefcore.runtime.process_count`).
    """
    chains_ = n_chains(n_points)
    if n_jobs != 1 and chains_ >= min_chains() and process_count(n_jobs, chains_) > 1:
        worker_pool(process_count(n_jobs, chains_) - 1)


def n_chains(n_points: int) -> int:
    """The warm-start chains of a sweep of `n_points` values (:func:`chains`): its tasks.

    Parameters
    ----------
    n_points : int
        Values of the sweep.

    Returns
    -------
    int

    Examples
    --------
    >>> n_chains(5), n_chains(40), n_chains(100000)
    (1, 6, 12500)
    """
    return len(_even_chains(range(n_points), WARM_CHAIN))


def pool_ready() -> bool:
    """Whether a worker of the pool has started and imported the solver.

    Returns
    -------
    bool
    """
    return _pool is not None and _pool[2].done() and _pool[2].exception() is None


def close_pool() -> None:
    """Stop the worker pool now (its workers killed), e.g. before the command exits."""
    global _pool
    if _pool is not None:
        pool, forked = _pool[1], _pool[3]
        _pool = None
        if forked:      # the standard library's executor: no kill_workers
            # the workers stopped first, then the executor's thread joined
            # (left running, it met a torn-down interpreter at exit)
            for proc in list((getattr(pool, "_processes", None) or {}).values()):
                proc.terminate()
            pool.shutdown(wait=True, cancel_futures=True)
        else:
            pool.shutdown(wait=False, kill_workers=True)


def pool_started() -> bool:
    """Whether this process has started the worker pool (:func:`worker_pool`).

    Returns
    -------
    bool
    """
    return _pool is not None


def run_joblib(jobs, n_jobs):
    """Chains in the caller and in ``n_jobs - 1`` pool workers, unordered as they finish.

    The caller computes chains too (it has the solver imported already): with
    ``n_jobs = 2`` one worker process is started, not two, and the caller
    works while it starts.  Each worker has at most one chain queued, so the
    chains go to whoever is free.  A worker that dies fails its chain's points
    (recorded), not the sweep.

    Parameters
    ----------
    jobs : list of list of tuple
        The chains (:func:`chains`).
    n_jobs : int
        Processes at work, the caller included (negative: all the cores), at
        most one per chain and per core (:func:`tefcore.runtime.process_count`).

    Yields
    ------
    tuple
        ``(index, record, vectors)`` of each kept point, as it finishes.
    """
    import concurrent.futures as cf

    n_workers = process_count(n_jobs, len(jobs)) - 1
    pending = list(jobs)
    pool = worker_pool(max(1, n_workers))
    running: dict = {}
    try:
        while pending or running:
            while pending and len(running) < (max(1, n_workers) if pool_ready() else 0):
                chain = pending.pop(0)
                running[pool.submit(evaluate_in_worker, chain)] = chain
            if pending:                          # the caller's share: one chain at a time
                yield from evaluate_chain(pending.pop())
            done = [f for f in running if f.done()] if pending or not running else \
                cf.wait(list(running), return_when=cf.FIRST_COMPLETED).done
            for fut in done:
                chain = running.pop(fut)
                try:
                    yield from fut.result()
                except Exception as err:  # e.g. a worker died: record it, go on
                    for i, args, keep in chain:
                        if keep:
                            yield i, failed_record(args[4], args[3], err), None
    finally:
        for fut in running:
            fut.cancel()


def dask_client(n_jobs, client, n_tasks=None):
    """(client, cluster to close or None) for backend='dask': a local cluster of
    at most one worker per core and per task (`n_tasks`, when known)."""
    try:
        from distributed import Client, LocalCluster
    except ImportError as err:
        raise ImportError("backend='dask' needs dask.distributed: pip install "
                          "'dask[distributed]' (or the tefcore[dask] extra)") from err
    if client is not None:
        return client, None
    workers = process_count(n_jobs, n_tasks)
    # dask sets its workers' environment (OMP_NUM_THREADS, MALLOC_TRIM_THRESHOLD_,
    # PYTHONHASHSEED, ...) in this process's os.environ and leaves it there
    # (measured, distributed 2026.8): the caller's later subprocesses would
    # inherit it.  The workers are spawned by now; the caller gets its own back.
    saved = dict(os.environ)
    try:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster), cluster
    finally:
        os.environ.clear()
        os.environ.update(saved)


def run_dask(jobs, client):
    from distributed import as_completed

    futures = {}
    try:
        for chain in jobs:
            futures[client.submit(evaluate_in_worker, chain, pure=False)] = chain
        for fut in as_completed(list(futures)):
            try:
                yield from fut.result()
            except Exception as err:  # e.g. a worker died: record it, go on
                for i, args, keep in futures[fut]:
                    if keep:
                        yield i, failed_record(args[4], args[3], err), None
    finally:
        client.cancel(list(futures))


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


#: Most points of a warm-start chain: the values, in the order of their SI values,
#: are cut into an even number of consecutive chains of at most this many points
#: (:func:`_even_chains`: lengths differing by one at most), each one job in which every
#: point starts its trim from the previous point's (:func:`tefcore.linear.stability.stability`,
#: ``warm_start``; point functions without that keyword are evaluated one by
#: one).  The chains depend on the values alone, so fresh, resumed and parallel
#: sweeps compute every point from the same start: identical tables.  A resumed
#: sweep recomputes the points of a chain before its first missing one (as warm
#: starts, not stored again); an interrupted parallel sweep loses the finished
#: points of the chains still running in the workers (a serial one loses none).
WARM_CHAIN = 8


def chains(cfg, parameter, values, keys, records, args_of, length=WARM_CHAIN):
    """The jobs of a sweep: warm-start chains of the points not in ``records``.

    Chains cut the values sorted by their SI value into runs of at most
    ``length`` (:data:`WARM_CHAIN`; 1 for a point function without
    ``warm_start``), as many as that takes rounded up to an even number, of
    lengths that differ by one at most (:func:`_even_chains`); a
    chain runs from its start to its last missing point, recomputing the points
    before it that are in the file (as warm starts only).  Values the
    configuration rejects are single jobs (failed points).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The base configuration.
    parameter : str
        The swept field.
    values : list
        The values asked for; ``keys`` their keys
        (:func:`tefcore.sweeps.store.value_key`).
    keys : list of str
        See `values`.
    records : dict
        Key -> record of the points already done (a resumed sweep).
    args_of : callable
        ``i -> args`` of :func:`evaluate_point` (after ``index``) for value ``i``.
    length : int, optional
        Most points per chain.

    Returns
    -------
    list of list of tuple
        The jobs: each a chain of ``(index, args, keep)``.
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
    for chain in _even_chains(order, length):
        missing = [j for j, i in enumerate(chain) if keys[i] not in records]
        if missing:
            jobs.append([(i, args_of(i), keys[i] not in records)
                         for i in chain[:missing[-1] + 1]])
    return jobs


def _even_chains(order, length: int) -> list:
    """`order` cut into an even number of consecutive runs of at most `length`,
    their lengths differing by one at most (one run where `length` holds them all).

    Two processes (the caller and one worker, ``--jobs 2`` on two cores) then
    share the chains evenly: 40 points in runs of 8 were five chains, three
    for one process and two for the other; six runs of 6 and 7 leave each
    three (measured, the two cuts interleaved in five pairs of the command
    ``tefcore sweep actuator.stiffness --range "60 ft-lb/rad" "160 ft-lb/rad" 40
    --jobs 2``: the evaluation 1.33 s with the five chains, 1.10 s with the
    six, medians).  The cost: where ``ceil(n / length)`` is odd, one chain, so
    one cold start, more -- also serially (a 40-point sweep at mu = 0.3: 167
    trim iterations against 163).  The cut depends on the number of values
    alone, never on the processes, so that fresh, resumed and parallel sweeps
    of the same values start every point from the same neighbour; a sweep of
    other values (one more, say) is cut anew.

    Parameters
    ----------
    order : sequence
        The values' indices in SI order.
    length : int
        Most points in a run, at least 1 (1: every value a run of its own).

    Returns
    -------
    list
        The runs, slices of `order`.
    """
    if length <= 1:
        return [order[i:i + 1] for i in range(len(order))]
    n = len(order)
    if n <= length:
        return [order] if order else []
    k = -(-n // length)
    k += k % 2
    bounds = [(j * n) // k for j in range(k + 1)]
    return [order[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True)]
