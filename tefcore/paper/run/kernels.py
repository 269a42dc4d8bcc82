"""Warm Jupyter kernels for the reproduction: imports paid once, a fresh namespace per notebook.

A notebook's own work is often smaller than what every fresh kernel pays
before its first cell: ~0.9 s to start and ~2.2 s to import numpy, scipy,
pandas, matplotlib and tefcore (measured on two shared cores).  :class:`WarmKernel`
starts one kernel, imports those modules in it once (:data:`WARM_IMPORTS`,
without binding a name in the user's namespace) and then executes notebook
after notebook in it (:func:`tefcore.paper.run.reproduce.execute_notebook`
passes its kernel manager to papermill).  Before every notebook but the
first, :data:`RESET` gives the notebook the state a fresh kernel would:

* the user namespace emptied (IPython's ``%reset -f``: every name a previous
  notebook bound is gone, its output history too);
* matplotlib's figures closed and its settings back to those the kernel had
  after the warm-up (a notebook that changes ``rcParams`` changes nothing
  for the next);
* the warnings filters, numpy's print options and floating-point error
  handling back to the warm-up's, numpy's global random state re-seeded from
  the operating system as in a new process;
* the previous notebook's garbage collected and the freed heap handed back
  to the operating system (glibc's ``malloc_trim``): the next notebook does
  not start on the previous one's peak memory.

The imported modules' objects are moved out of the garbage collector's
reach after the warm-up (``gc.freeze``): they live as long as the kernel,
and every full collection in every notebook would walk them again (measured,
each notebook run alone: notebooks 06, 08 and 11 spent 0.92 s in the
collector, 0.31 s with their imports frozen).

What stays are the imported modules and the caches of the solver that are
keyed by the structure they hold (e.g. the blade modes): a cache hit returns
what the notebook would have computed (tests/paper/test_kernels.py checks
that a notebook sees no name of another and that results are unchanged).
"""

from __future__ import annotations

__all__ = ["RESET", "WARM_IMPORTS", "KernelError", "WarmKernel", "remove_stale_folders"]

#: Modules every notebook imports: loaded once per kernel, bound to no user name.
WARM_IMPORTS = ("numpy", "scipy.linalg", "scipy.optimize", "scipy.sparse.csgraph", "pandas",
                "matplotlib.pyplot", "IPython.display", "tefcore", "tefcore.linear.stability",
                "tefcore.sweeps.sweep", "tefcore.sweeps.maps", "tefcore.paper.notebook_tools")

#: Run after the imports: remember the state a notebook must start from.
_SNAPSHOT = """
def _tefcore_snapshot():
    import importlib, warnings
    for name in {imports!r}:
        importlib.import_module(name)
    import matplotlib
    import numpy as np
    importlib.import_module("tefcore.paper.run.kernels")._start_state = (
        dict(matplotlib.rcParams), list(warnings.filters), np.get_printoptions(), np.geterr())
    import gc
    gc.collect()
    gc.freeze()
_tefcore_snapshot()
del _tefcore_snapshot
%reset -f
"""

#: Run before a notebook in a kernel that executed another: the fresh state.
RESET = """
%reset -f
def _tefcore_fresh():
    import importlib, warnings
    import matplotlib
    import matplotlib.pyplot as plt
    import numpy as np
    state = importlib.import_module("tefcore.paper.run.kernels")._start_state
    rc, filters, printing, errors = state
    plt.close("all")
    matplotlib.rcParams.clear()
    matplotlib.rcParams.update(rc)
    warnings.resetwarnings()
    warnings.filters.extend(filters)
    np.set_printoptions(**printing)
    np.seterr(**errors)
    np.random.seed()
    import gc
    gc.collect()
    import ctypes, sys
    if sys.platform.startswith("linux"):
        try:
            ctypes.CDLL("libc.so.6").malloc_trim(0)
        except (OSError, AttributeError):
            pass
_tefcore_fresh()
del _tefcore_fresh
%reset -f
"""

#: Seconds a warm-up or a reset may take before the kernel is taken for dead.
TIMEOUT = 120.0
#: Seconds between checks that the kernel still lives while a warm-up or reset runs.
POLL_S = 0.5

#: Longest path of a kernel's Unix socket (``sun_path`` holds 108 bytes on Linux,
#: 104 on macOS, the terminating zero included).
_SOCKET_PATH_MAX = 100

#: A warm kernel's socket folder: ``<prefix><pid of the process that started it>-<random>``.
_FOLDER_PREFIX = "tefcore-kernel-"

#: What a warm kernel's socket folder holds: its connection file and five sockets.
_FOLDER_FILES = frozenset({"k.json", *(f"k-ipc-{i}" for i in range(1, 6))})

#: In the kernel: the state after the warm-up (rcParams, warnings filters, numpy's print
#: options and error handling).
_start_state = None


class KernelError(RuntimeError):
    """A warm kernel that could not start, import or reset."""


class WarmKernel:
    """One Jupyter kernel that executes notebooks one after another.

    Create, use and shut it down in one thread: its messages run on that
    thread's event loop, the one papermill uses there.

    Parameters
    ----------
    kernel_name : str
        The Jupyter kernel (``python3``).
    extra_arguments : sequence of str, optional
        Passed to the kernel's command line.
    """

    def __init__(self, kernel_name: str, extra_arguments=()):
        from jupyter_client.manager import AsyncKernelManager
        from jupyter_core.utils import run_sync

        self._run_sync = run_sync
        self._folder = None
        self.notebooks = 0
        try:
            self.km = AsyncKernelManager(kernel_name=kernel_name, **self._transport())
        except Exception:
            self._remove_folder()
            raise
        try:
            run_sync(self.km.start_kernel)(extra_arguments=list(extra_arguments))
            self._execute(_SNAPSHOT.format(imports=WARM_IMPORTS), "warm-up")
        except Exception:
            self.shutdown()
            raise

    def _transport(self) -> dict:
        """The kernel's channels: Unix sockets in a private folder where there are any.

        Over TCP the client picks five free ports and the kernel binds them a
        second later; a port taken in between (by another kernel's connections:
        the reproduction starts two kernels at once) stops the kernel's thread
        on it with a traceback on the reproduction's stderr (seen once, the
        heartbeat's: ``ZMQError: Address already in use``).  Unix sockets are
        files in a folder only this kernel uses, removed on :meth:`shutdown`;
        a process killed outright leaves it, and the next warm kernel removes
        it (:func:`remove_stale_folders`).  A socket's path is limited to about
        100 characters: where the temporary folder's is too long (``TMPDIR``),
        ``/tmp``; where that is too, TCP.
        """
        import os
        import tempfile

        if os.name != "posix":
            return {}
        for where in (None, "/tmp"):
            try:
                remove_stale_folders(where)
                folder = tempfile.mkdtemp(prefix=f"{_FOLDER_PREFIX}{os.getpid()}-", dir=where)
            except OSError:
                continue
            if len(os.path.join(folder, "k-ipc-5")) <= _SOCKET_PATH_MAX:
                self._folder = folder
                return {"transport": "ipc", "connection_file": os.path.join(folder, "k.json")}
            os.rmdir(folder)
        return {}

    def _remove_folder(self) -> None:
        if self._folder is not None:
            import shutil

            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None

    def _execute(self, code: str, what: str) -> None:
        """Run `code`, its reply awaited while the kernel lives (a kernel stopped on
        Ctrl-C, :mod:`tefcore.paper.run.kernel_guard`, ends the wait within :data:`POLL_S`)."""
        import queue
        import time

        kc = self.km.client()
        kc.start_channels()
        try:
            msg_id = kc.execute(code, store_history=False)
            deadline = time.monotonic() + TIMEOUT
            while True:
                try:
                    reply = self._run_sync(kc.get_shell_msg)(timeout=POLL_S)
                except queue.Empty:
                    if not self.alive():
                        raise KernelError(f"kernel {what} failed: the kernel died") from None
                    if time.monotonic() > deadline:
                        raise KernelError(f"kernel {what} failed: no reply in "
                                          f"{TIMEOUT:.0f} s") from None
                    continue
                if reply.get("parent_header", {}).get("msg_id") == msg_id:
                    break
        finally:
            kc.stop_channels()
        content = reply.get("content", {})
        if content.get("status") != "ok":
            raise KernelError(f"kernel {what} failed: {content.get('ename', '?')}: "
                              f"{content.get('evalue', '')}")

    def prepare(self):
        """The kernel manager for the next notebook, its state fresh (:data:`RESET`).

        Returns
        -------
        jupyter_client.manager.AsyncKernelManager
            For ``papermill.execute_notebook(..., km=...)``.
        """
        if self.notebooks:
            self._execute(RESET, "reset")
        self.notebooks += 1
        return self.km

    def alive(self) -> bool:
        """Whether the kernel process is still running.

        Returns
        -------
        bool
        """
        return bool(self._run_sync(self.km.is_alive)())

    def shutdown(self) -> None:
        """Stop the kernel (now: nothing of it is needed any more)."""
        try:
            if self.km.has_kernel:
                self._run_sync(self.km.shutdown_kernel)(now=True)
        finally:
            self._remove_folder()


def remove_stale_folders(where=None) -> int:
    """Remove the socket folders of warm kernels whose process is gone.

    A reproduction killed outright (``kill -9``) cannot remove its kernels'
    folders (:meth:`WarmKernel.shutdown` does otherwise); its kernels exit by
    themselves (:mod:`tefcore.paper.run.kernel_guard`).  A folder is removed when
    it is this user's, named for a process that no longer runs, and holds
    nothing but a kernel's connection file and sockets.

    Parameters
    ----------
    where : path, optional
        The folder to look in (default: the temporary folder).

    Returns
    -------
    int
        How many folders were removed.
    """
    import os
    import shutil
    import tempfile
    from pathlib import Path

    import psutil

    removed = 0
    for folder in Path(where or tempfile.gettempdir()).glob(f"{_FOLDER_PREFIX}*-*"):
        pid = folder.name[len(_FOLDER_PREFIX):].split("-", 1)[0]
        try:
            if (not pid.isdigit() or folder.is_symlink() or not folder.is_dir()
                    or folder.stat().st_uid != os.getuid() or psutil.pid_exists(int(pid))
                    or not {p.name for p in folder.iterdir()} <= _FOLDER_FILES):
                continue
        except OSError:           # gone meanwhile, or not ours to read
            continue
        shutil.rmtree(folder, ignore_errors=True)
        removed += not folder.exists()
    return removed

