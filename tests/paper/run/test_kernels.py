"""Warm kernels: notebooks run one after another in one kernel see nothing of each other."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

pytest.importorskip("papermill")
nbformat = pytest.importorskip("nbformat")

from tefcore.paper.run import reproduce as rp  # noqa: E402
from tefcore.paper.run.kernels import WarmKernel  # noqa: E402


def _notebook(path: Path, *cells: str) -> Path:
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nb.metadata["kernelspec"] = {"name": rp.KERNEL_NAME, "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, str(path))
    return path


def test_a_notebook_cannot_see_anothers_state(tmp_path):
    # the first notebook binds names, changes matplotlib's settings, the warnings
    # filters and numpy's printing; the second, in the same kernel process, must
    # start as in a fresh kernel (its asserts fail the notebook otherwise)
    first = _notebook(
        tmp_path / "first.ipynb",
        "import os, warnings\nimport numpy as np\nimport matplotlib\n"
        "secret = 42\nnp.set_printoptions(precision=2)\nnp.seterr(all='raise')\n"
        "matplotlib.rcParams['lines.linewidth'] = 9.0\nwarnings.simplefilter('error')\n"
        f"open({str(tmp_path / 'pid1')!r}, 'w').write(str(os.getpid()))")
    second = _notebook(
        tmp_path / "second.ipynb",
        "assert 'secret' not in globals() and 'np' not in globals()\n"
        "import os, warnings\nimport numpy as np\nimport matplotlib\n"
        "assert np.get_printoptions()['precision'] == 8\n"
        # the warm-up's imports stay out of the collector's reach (frozen)
        "import gc\nassert gc.get_freeze_count() > 10_000\n"
        "assert np.geterr()['divide'] == 'warn'\n"
        "assert matplotlib.rcParams['lines.linewidth'] != 9.0\n"
        "warnings.warn('still only a warning')\n"
        f"open({str(tmp_path / 'pid2')!r}, 'w').write(str(os.getpid()))")
    kernel = WarmKernel(rp.KERNEL_NAME)
    folder = kernel._folder
    try:
        runs = [rp.execute_notebook(nb.stem, nb, tmp_path, {}, kernel=kernel, export=False)
                for nb in (first, second)]
        if os.name == "posix":
            # its channels are Unix sockets in its own folder: no TCP port that
            # another process could take between choosing and binding it
            assert kernel.km.transport == "ipc"
            assert sorted(p.name for p in Path(folder).iterdir()) == \
                ["k-ipc-1", "k-ipc-2", "k-ipc-3", "k-ipc-4", "k-ipc-5", "k.json"]
    finally:
        kernel.shutdown()
    assert [r.status for r in runs] == ["ok", "ok"], [r.error for r in runs]
    # one kernel process ran both: the test exercised the reuse
    assert (tmp_path / "pid1").read_text() == (tmp_path / "pid2").read_text()
    assert folder is None or not Path(folder).exists()     # nothing left behind


def test_a_failing_notebook_fails_alone(tmp_path):
    bad = _notebook(tmp_path / "bad.ipynb", "raise ValueError('on purpose')")
    good = _notebook(tmp_path / "good.ipynb", "x = 1")
    kernel = WarmKernel(rp.KERNEL_NAME)
    try:
        runs = [rp.execute_notebook(nb.stem, nb, tmp_path, {}, kernel=kernel, export=False)
                for nb in (bad, good)]
    finally:
        kernel.shutdown()
    assert runs[0].status == "failed" and "on purpose" in runs[0].error
    assert runs[1].status == "ok"


def test_a_kernel_stopped_while_it_works_ends_the_wait(tmp_path):
    # Ctrl-C stops the kernels (tefcore.paper.run.kernel_guard) also while a warm kernel
    # warms up or resets: its wait for the reply must end then, not after TIMEOUT
    import threading
    import time

    from tefcore.paper.run.kernel_guard import stop_kernels
    from tefcore.paper.run.kernels import KernelError

    kernel = WarmKernel(rp.KERNEL_NAME)
    try:
        stopper = threading.Timer(1.0, stop_kernels)
        stopper.start()
        start = time.monotonic()
        with pytest.raises(KernelError, match="died"):
            kernel._execute("import time\ntime.sleep(600)", "reset")
        assert time.monotonic() - start < 30
        stopper.join()
    finally:
        try:
            kernel.shutdown()
        except Exception:  # stopped already
            pass


@pytest.mark.skipif(os.name != "posix", reason="Unix sockets")
def test_a_long_temporary_folder_does_not_stop_the_warm_kernel(tmp_path, monkeypatch):
    # a Unix socket's path holds about 100 characters: a TMPDIR longer than
    # that made the kernel fail to start ("File name too long") and every
    # notebook fall back to a kernel of its own
    import tempfile

    long_dir = tmp_path / ("x" * 100)
    long_dir.mkdir()
    monkeypatch.setenv("TMPDIR", str(long_dir))
    monkeypatch.setattr(tempfile, "tempdir", None)
    kernel = WarmKernel.__new__(WarmKernel)      # the transport alone, no kernel started
    kernel._folder = None
    try:
        got = kernel._transport()
        assert got.get("transport") in (None, "ipc")
        if got:
            assert len(str(Path(kernel._folder) / "k-ipc-5")) <= 100
            assert not str(kernel._folder).startswith(str(long_dir))
    finally:
        kernel._remove_folder()
    assert list(long_dir.iterdir()) == []              # nothing left in the long folder


@pytest.mark.skipif(os.name != "posix", reason="Unix sockets")
def test_the_folders_of_a_killed_reproduction_are_removed_by_the_next(tmp_path):
    # kill -9 leaves a warm kernel's socket folder; the next warm kernel removes
    # those of processes that are gone, and nothing else
    import subprocess
    import sys

    from tefcore.paper.run.kernels import remove_stale_folders

    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    dead = int(gone.stdout)

    def folder(name, files=("k.json", "k-ipc-1", "k-ipc-5")):
        (tmp_path / name).mkdir()
        for f in files:
            (tmp_path / name / f).write_text("")
        return tmp_path / name

    stale = folder(f"tefcore-kernel-{dead}-abc123")
    live = folder(f"tefcore-kernel-{os.getpid()}-def456")          # this process's
    other = folder(f"tefcore-kernel-{dead}-ghi789", files=("k.json", "notes.txt"))
    unnamed = folder("tefcore-kernel-xyz")                            # no process in its name
    assert remove_stale_folders(tmp_path) == 1
    assert not stale.exists()
    assert live.exists() and other.exists() and unnamed.exists()
    assert remove_stale_folders(tmp_path) == 0
