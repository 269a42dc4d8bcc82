"""Jupyter kernels stopped when a reproduction or a batch is interrupted.

``tefcore reproduce`` and ``tefcore batch`` execute notebooks in threads,
each notebook in a kernel process that papermill starts.  On Ctrl-C the main
thread gets the ``KeyboardInterrupt``, but a thread executing a notebook
goes on until its kernel finishes: the command hung for as long as the
longest running notebook, its kernels busy.  :func:`stop_notebooks` cancels
the notebooks not yet started and stops the kernels of this process (each
started in its own session, with the sweep workers it started: the process
group is signalled, ``SIGTERM`` then ``SIGKILL``), so every running notebook
fails at once and its thread returns.  The reproduction's warm kernels
(:mod:`tefcore.paper.run.kernels`, one per notebook slot) are such kernels too: a
slot told to stop takes no further notebook and starts no kernel, and a warm
kernel stopped while it warms up or resets ends its wait within a second.

A process killed outright (``kill -9``) cannot stop anything: its kernels
exit by themselves within about a second, when ipykernel's parent poller sees
their parent gone (``JPY_PARENT_PID``, set by jupyter_client).
"""

from __future__ import annotations

import contextlib
import os
import signal
import time

__all__ = ["STOP_GRACE_S", "kernel_processes", "stop_kernels", "stop_notebooks"]

#: Seconds a kernel is given to end after ``SIGTERM`` before ``SIGKILL``.
STOP_GRACE_S = 3.0


def kernel_processes() -> list:
    """The Jupyter kernels this process started (``psutil.Process``, children running ipykernel).

    Returns
    -------
    list of psutil.Process
    """
    import psutil

    out = []
    for child in psutil.Process().children(recursive=False):
        with contextlib.suppress(psutil.Error):
            if any("ipykernel" in part for part in child.cmdline()):
                out.append(child)
    return out


def _signal(proc, sig) -> None:
    """`sig` to the kernel's process group (its own session), else to the kernel alone."""
    with contextlib.suppress(OSError):
        if os.getpgid(proc.pid) == proc.pid:
            os.killpg(proc.pid, sig)
            return
    with contextlib.suppress(OSError):
        os.kill(proc.pid, sig)


def stop_kernels(grace: float = STOP_GRACE_S) -> int:
    """Stop the kernels of this process: ``SIGTERM``, then ``SIGKILL`` after `grace` seconds.

    Parameters
    ----------
    grace : float, optional
        Seconds to wait for the kernels to end after ``SIGTERM``.

    Returns
    -------
    int
        How many kernels were stopped.
    """
    import psutil

    kernels = kernel_processes()
    for proc in kernels:
        _signal(proc, signal.SIGTERM)
    _, alive = psutil.wait_procs(kernels, timeout=grace)
    for proc in alive:
        _signal(proc, signal.SIGKILL)
    psutil.wait_procs(alive, timeout=grace)
    return len(kernels)


def stop_notebooks(futures, timeout: float = 60.0) -> None:
    """After an interruption: cancel the notebooks not started, stop the running ones' kernels.

    Waits until every notebook's thread has returned (a thread starting a
    kernel just now gets it stopped too), at most `timeout` seconds.

    Parameters
    ----------
    futures : iterable of concurrent.futures.Future
        The notebooks submitted to the thread pool.
    timeout : float, optional
        Longest wait [s].
    """
    futures = list(futures)
    for fut in futures:
        fut.cancel()
    deadline = time.monotonic() + timeout
    while not all(f.done() for f in futures) and time.monotonic() < deadline:
        stop_kernels()
        time.sleep(0.2)
