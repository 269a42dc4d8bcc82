"""Process settings that make many small numerical problems fast.

tefcore solves thousands of small problems (matrices of a few hundred rows)
in one process.  Two process-wide defaults of the numerical stack are tuned
for large problems and cost time here, so ``import tefcore`` changes them;
each can be turned off with an environment variable set before the import.

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
"""

from __future__ import annotations

import ctypes
import os
import platform
import sys

from threadpoolctl import threadpool_limits

#: ``mallopt`` parameter numbers (glibc ``malloc.h``).
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
#: Largest mmap threshold glibc accepts on 64-bit systems (32 MiB).
_MMAP_THRESHOLD_MAX = 32 * 2**20


def limit_blas_threads(value: str) -> None:
    """Limit BLAS to ``int(value)`` threads, or do nothing for ``"default"``."""
    if value != "default":
        threadpool_limits(int(value), user_api="blas")


def keep_freed_memory(value: str) -> bool:
    """Raise glibc's heap trim threshold to ``int(value)`` bytes.

    Returns ``True`` when the setting was applied; ``False`` on ``"default"``
    or where the C library is not glibc (macOS, Windows, musl), which leaves
    the allocator untouched.
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
    """Apply both settings from the environment (called by ``import tefcore``)."""
    limit_blas_threads(os.environ.get("TEFCORE_BLAS_THREADS", "1"))
    keep_freed_memory(os.environ.get("TEFCORE_MALLOC_TRIM", str(128 * 2**20)))
