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
their parent gone (``JPY_PARENT_PID``, set by jupyter_client), but nothing
ends the processes *they* started (a sweep's workers), nor the attribution's
joblib workers, which finish their task, minutes later.  :func:`watch_children`
starts a watcher (``python -m tefcore.paper.run.kernel_guard PID``, in a
session of its own so that a signal to the terminal's process group leaves
it): it notes the processes the command starts, every :data:`WATCH_S`
seconds, and when the command ends without saying it finished -- killed, or
interrupted -- it stops those still running (``SIGTERM``, ``SIGKILL`` after
:data:`STOP_GRACE_S`).
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time

__all__ = ["STOP_GRACE_S", "STOP_WAIT_S", "WATCH_S", "kernel_processes", "stop_kernels",
           "stop_notebooks", "watch_children"]

#: Seconds a kernel is given to end after ``SIGTERM`` before ``SIGKILL``.
STOP_GRACE_S = 3.0
#: Seconds between the watcher's looks at the command's processes.
WATCH_S = 0.5


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


#: Longest wait of :func:`stop_notebooks` for the notebooks' threads to return [s].
STOP_WAIT_S = 60.0


def stop_notebooks(futures, timeout: float = STOP_WAIT_S) -> None:
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


@contextlib.contextmanager
def watch_children():
    """Stop the processes started inside the block if this process dies or is interrupted.

    On a normal exit from the block nothing is stopped (each part of the run
    has ended its processes itself); on an exception (Ctrl-C) the processes
    started in the block that still run are stopped at once; if this process
    is killed, within :data:`WATCH_S` seconds.  Processes that were running
    before the block are never touched.

    Yields
    ------
    subprocess.Popen or None
        The watcher (None where it cannot start: no psutil, not POSIX).
    """
    try:
        import psutil
    except ImportError:      # pragma: no cover - psutil ships with the notebooks extra
        yield None
        return
    if os.name != "posix":   # pragma: no cover
        yield None
        return
    # the processes running now are named to the watcher, not looked up by it: what
    # the block starts while the watcher itself starts is the block's
    before = [str(p.pid) for p in psutil.Process().children(recursive=True)]
    watcher = subprocess.Popen(
        [sys.executable, "-m", "tefcore.paper.run.kernel_guard", str(os.getpid()), *before],
        stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, start_new_session=True)
    word = b"abort\n"
    try:
        yield watcher
        word = b"done\n"
    finally:
        with contextlib.suppress(OSError):
            watcher.stdin.write(word)
            watcher.stdin.close()
        with contextlib.suppress(subprocess.TimeoutExpired):
            watcher.wait(timeout=STOP_GRACE_S + 5.0)


def _stop(procs) -> None:
    """``SIGTERM`` to `procs` (and what they started since), ``SIGKILL`` after the grace."""
    import psutil

    procs = list(procs)
    for p in list(procs):
        with contextlib.suppress(psutil.Error):
            procs += p.children(recursive=True)
    for p in procs:
        with contextlib.suppress(psutil.Error):
            p.terminate()
    _, alive = psutil.wait_procs(procs, timeout=STOP_GRACE_S)
    for p in alive:
        with contextlib.suppress(psutil.Error):
            p.kill()
    psutil.wait_procs(alive, timeout=STOP_GRACE_S)


def _watch(parent_pid: int, before=()) -> int:
    """The watcher's loop (:func:`watch_children`): note, then stop what is left.

    ``before`` are the processes that ran before the block (never stopped).
    """
    import select

    import psutil

    signal.signal(signal.SIGINT, signal.SIG_IGN)      # Ctrl-C is the command's to handle
    me = os.getpid()
    before = set(before)
    try:
        parent = psutil.Process(parent_pid)
    except psutil.Error:
        return 0
    started: dict = {}
    stdin = sys.stdin.buffer
    heard = b""
    while True:
        ready, _, _ = select.select([stdin], [], [], WATCH_S)
        if ready:
            chunk = os.read(stdin.fileno(), 64)
            heard += chunk
            if not chunk or b"done" in heard or b"abort" in heard:
                break
        try:
            if not parent.is_running():
                break
            for p in parent.children(recursive=True):
                if p.pid != me and p.pid not in before:
                    started.setdefault(p.pid, p)
        except psutil.Error:
            break
    if b"done" not in heard:
        _stop(p for p in started.values() if p.is_running())
    return 0


if __name__ == "__main__":
    raise SystemExit(_watch(int(sys.argv[1]), [int(a) for a in sys.argv[2:]]))
