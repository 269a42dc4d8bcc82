"""Process settings: many small numerical problems fast.

tefcore solves thousands of small problems (matrices of a few hundred rows).
Two process-wide defaults of the numerical stack are tuned for large
problems and cost time here:

* BLAS threads (``TEFCORE_BLAS_THREADS``, default ``1``; ``default`` leaves
  them alone).  On two cores a threaded OpenBLAS took 320 ms for one
  183-dof eigenproblem that takes 3.6 ms on one thread; parallel sweeps use
  processes instead.
* glibc's heap trim threshold (``TEFCORE_MALLOC_TRIM``, bytes, default
  ``134217728`` = 128 MiB; ``default`` leaves it alone), and with it the
  mmap threshold (the same, at most 32 MiB).  A forward-flight
  point allocates and frees tens of MB of temporaries per Jacobian; with
  glibc's default (dynamic, a few hundred kB) the freed top of the heap is
  returned to the kernel after every call and faulted back in on the next
  one.  Measured on the 2-core VM: ~5100 page faults and 13 ms of system
  time per mu = 0.3 stability point, 59 ms against 36 ms per point.  The
  cost is that up to the threshold of freed memory stays with the process.

tefcore never chooses the BLAS kernels: OpenBLAS picks them by the processor
it finds, or by the user's own ``OPENBLAS_CORETYPE``.  Kernels differ in
round-off; no verdict of tefcore depends on it (every decision on a computed
number has a margin above the solver's accuracy, docs/theory.md 9.1, and the
test suite checks the claims under nudges far below engineering meaning).
What a stored result was computed with is recorded
(:func:`tefcore.provenance.numerical_environment`).

``import tefcore`` changes none of them.  All are applied by
:func:`apply_defaults` where tefcore owns the process: the ``tefcore``
command, the worker processes of a parallel sweep (joblib, dask) and the
notebooks (which call it in their set-up cell); a script that computes many
points may call it too.  Inside the solver, the main entry points
(:func:`tefcore.linear.stability.stability`, :func:`tefcore.trimming.trim.trim`,
:func:`tefcore.structure.blade.blade_modes`, :func:`tefcore.linear.mechanism.mechanism`, the
Floquet analysis) run under
:func:`blas_limit`, which limits BLAS threads for the duration of the call
only and restores them after: a plain ``import tefcore`` followed by
``stability(cfg)`` gets the BLAS setting without the process keeping it.
The allocator setting cannot be scoped like that (glibc has no way back to
its dynamic thresholds), so it is only ever applied by
:func:`apply_defaults`; ``benchmarks/bench_runtime.py`` measures what that
costs a plain script.  Measured on the shared 2-core VM (CPU time of the
process per MDART mu = 0.3 stability point, medians of 9 fresh processes,
load average ~5): 34 ms after :func:`apply_defaults`, as when ``import
tefcore`` applied both; 46 ms in a plain script (the BLAS limit of the
solver alone); the first point of a process 45 against 60 ms.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import platform
import sys
import threading

__all__ = ["apply_defaults", "blas_limit", "defaults_applied", "keep_freed_memory",
           "limit_blas_threads", "process_cap", "process_count", "usable_cores", "worker_init"]

#: ``mallopt`` parameter numbers (glibc ``malloc.h``).
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
#: Largest mmap threshold glibc accepts on 64-bit systems (32 MiB).
_MMAP_THRESHOLD_MAX = 32 * 2**20
_DEFAULT_BLAS_THREADS = "1"
_DEFAULT_MALLOC_TRIM = str(128 * 2**20)

_state = threading.local()
_controller = None
_lock = threading.Lock()
_process_applied = False


def _blas_threads_setting() -> int | None:
    """Threads from ``TEFCORE_BLAS_THREADS`` (None for ``default``)."""
    value = os.environ.get("TEFCORE_BLAS_THREADS", _DEFAULT_BLAS_THREADS)
    if value == "default":
        return None
    try:
        n = int(value)
    except ValueError:
        n = 0
    if n < 1:
        raise ValueError(f"TEFCORE_BLAS_THREADS = {value!r}: expected 'default' or a whole "
                         "number of threads >= 1")
    return n


def _threadpool_controller():
    """One :class:`threadpoolctl.ThreadpoolController` per process (made once:
    making one scans the loaded libraries, ~1 ms; limiting through it ~20 us)."""
    global _controller
    with _lock:
        if _controller is None:
            import numpy  # noqa: F401  (load both BLAS builds first: the
            import scipy.linalg  # noqa: F401  controller only sees loaded libraries)
            from threadpoolctl import ThreadpoolController

            _controller = ThreadpoolController()
        return _controller


def limit_blas_threads(value: str) -> None:
    """Limit BLAS to ``int(value)`` threads for the rest of the process.

    Parameters
    ----------
    value : str
        A whole number of threads (>= 1), or ``"default"`` to leave BLAS
        alone.

    Raises
    ------
    ValueError
        For anything else.
    """
    if value == "default":
        return
    try:
        n = int(value)
    except ValueError:
        n = 0
    if n < 1:
        raise ValueError(f"TEFCORE_BLAS_THREADS = {value!r}: expected 'default' or a whole "
                         "number of threads >= 1")
    _threadpool_controller().limit(limits=n, user_api="blas")


@contextlib.contextmanager
def _blas_limit_context():
    depth = getattr(_state, "depth", 0)
    if depth or _process_applied:
        # nested in another limited call, or the process is already set up:
        # nothing to do (this keeps the cost of a nested entry ~1 us)
        _state.depth = depth + 1
        try:
            yield
        finally:
            _state.depth = depth
        return
    n = _blas_threads_setting()
    if n is None:
        yield
        return
    _state.depth = 1
    try:
        with _threadpool_controller().limit(limits=n, user_api="blas"):
            yield
    finally:
        _state.depth = 0


class _BlasLimit(contextlib.ContextDecorator):
    def __enter__(self):
        self._cm = _blas_limit_context()
        return self._cm.__enter__()

    def __exit__(self, *exc):
        return self._cm.__exit__(*exc)


def blas_limit() -> contextlib.ContextDecorator:
    """Limit BLAS threads (``TEFCORE_BLAS_THREADS``) inside a ``with`` block or a call.

    A context manager and a decorator; the previous thread counts are
    restored on exit.  Nested uses, and any use after
    :func:`apply_defaults`, cost about a microsecond; the outermost one
    about 40 us (the thread pools are switched twice).

    Returns
    -------
    contextlib.ContextDecorator

    Examples
    --------
    With ``TEFCORE_BLAS_THREADS`` unset (one thread):

    >>> from threadpoolctl import threadpool_info
    >>> with blas_limit():
    ...     inside = {lib["num_threads"] for lib in threadpool_info()
    ...               if lib["user_api"] == "blas"}
    >>> inside
    {1}
    """
    return _BlasLimit()


def keep_freed_memory(value: str) -> bool:
    """Raise glibc's heap trim threshold to ``int(value)`` bytes (and the mmap threshold).

    Parameters
    ----------
    value : str
        Bytes, ``0 <= int(value) < 2**31``, or ``"default"`` to leave the
        allocator alone.

    Returns
    -------
    bool
        ``True`` when the setting was applied; ``False`` on ``"default"`` or
        where the C library is not glibc (macOS, Windows, musl), which leaves
        the allocator untouched.

    Raises
    ------
    ValueError
        For a value out of range or not a number (on glibc).
    """
    if value == "default" or not sys.platform.startswith("linux") \
            or platform.libc_ver()[0] != "glibc":
        return False
    try:
        threshold = int(value)
    except ValueError:
        threshold = -1
    if not 0 <= threshold < 2**31:
        raise ValueError(f"TEFCORE_MALLOC_TRIM = {value!r}: expected 'default' or a number "
                         f"of bytes in 0 ... 2**31 - 1")
    try:
        libc = ctypes.CDLL("libc.so.6")
    except OSError:
        return False
    # setting the trim threshold switches off glibc's dynamic mmap threshold,
    # which would leave every array above 128 kB in a fresh mmap (faulted in
    # page by page on each call: seen, 0.65 ms to zero and touch 691 kB), so
    # the mmap threshold is raised too
    return bool(libc.mallopt(_M_TRIM_THRESHOLD, threshold)
                and libc.mallopt(_M_MMAP_THRESHOLD, min(threshold, _MMAP_THRESHOLD_MAX)))


def apply_defaults() -> None:
    """Apply the settings to this process, from the environment.

    For processes tefcore owns: the ``tefcore`` command, the workers of a
    parallel sweep, the notebooks (their set-up cell).  Calling it again
    re-reads the environment.  ``TEFCORE_BLAS_THREADS`` and
    ``TEFCORE_MALLOC_TRIM`` (module docstring) set or turn off each.

    Raises
    ------
    ValueError
        For a malformed environment variable, naming it.
    """
    global _process_applied
    _process_applied = False
    limit_blas_threads(os.environ.get("TEFCORE_BLAS_THREADS", _DEFAULT_BLAS_THREADS))
    keep_freed_memory(os.environ.get("TEFCORE_MALLOC_TRIM", _DEFAULT_MALLOC_TRIM))
    _process_applied = True


def worker_init() -> None:
    """:func:`apply_defaults` once per process: the entry of tefcore's worker processes.

    Called first by every task a parallel sweep or stability map sends to a
    joblib (loky) or dask worker; later calls in the same process return at
    once.
    """
    if not _process_applied:
        apply_defaults()


def defaults_applied() -> bool:
    """Whether :func:`apply_defaults` has run in this process.

    Returns
    -------
    bool
    """
    return _process_applied


def usable_cores() -> int:
    """The cores this process may run on: its affinity mask where the system has one.

    ``os.cpu_count()`` counts the machine's cores; a container, ``taskset``
    or a batch scheduler may give the process fewer, which
    ``os.sched_getaffinity`` reports (Linux).

    Returns
    -------
    int
        At least 1.
    """
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):          # no affinity mask here (macOS, Windows)
        return max(1, os.cpu_count() or 1)


def process_count(n_jobs: int, n_tasks: int | None = None) -> int:
    """Processes worth starting for `n_tasks` independent tasks asked to run on `n_jobs`.

    Never more than the cores this process may use (:func:`usable_cores`) --
    a process per task beyond them only shares the same cores, each with its
    own copy of the solver in memory -- nor than the tasks (a process without
    a task is only a start-up).  A negative `n_jobs` asks for all the cores
    (as joblib reads it).

    Parameters
    ----------
    n_jobs : int
        Processes asked for, the caller included; negative: all the cores.
    n_tasks : int, optional
        Tasks to share among them (sweep chains, map rows, notebooks); None:
        not known yet.

    Returns
    -------
    int
        At least 1.

    Examples
    --------
    >>> cores = usable_cores()
    >>> process_count(100000, 5) == min(cores, 5), process_count(64, 1), process_count(1, 40)
    (True, 1, 1)
    """
    n = usable_cores() if n_jobs < 0 else min(int(n_jobs), usable_cores())
    if n_tasks is not None:
        n = min(n, int(n_tasks))
    return max(1, n)


def process_cap(n_jobs: int, n_tasks: int | None = None, task: str = "task",
                option: str = "--jobs") -> tuple[int, str | None]:
    """:func:`process_count`, and the line a command prints when it is fewer than asked.

    Parameters
    ----------
    n_jobs : int
        Processes asked for (``--jobs``); negative: all the cores.
    n_tasks : int, optional
        Tasks to share among them.
    task : str, optional
        What a task is, for the line (``"row"``).
    option : str, optional
        The option that asked, for the line.

    Returns
    -------
    processes : int
    line : str or None
        Why fewer processes than asked for (``"--jobs 64: 2 processes, the
        cores this process may use"``), or None when `n_jobs` processes are
        used (or all the cores were asked for).

    Examples
    --------
    >>> process_cap(100000, 1, "chain of points")
    (1, '--jobs 100000: 1 process, one per chain of points (there is 1)')
    """
    n = process_count(n_jobs, n_tasks)
    if n_jobs < 0 or n >= n_jobs:
        return n, None
    cores = usable_cores()
    if n_tasks is not None and n == n_tasks and n_tasks < cores:
        why = f"one per {task} (there {'is' if n == 1 else 'are'} {n})"
    else:
        why = f"the {cores} core{'s' if cores > 1 else ''} this process may use"
    return n, f"{option} {n_jobs}: {n} process{'es' if n > 1 else ''}, {why}"
