"""``tefcore reproduce`` never mixes two results in its output folder.

A second run into the same ``--out`` is refused while one runs (a lock beside
the folder); a folder that is not a reproduction is refused; a previous
reproduction is replaced whole (the run writes ``OUT.incomplete`` and swaps
it in at the end), so that no file of an earlier run stays beside a new
report; a run killed with ``kill -9`` leaves the previous result and ends the
processes it started -- its kernels, what they started, the attribution's
joblib workers.

The notebooks' execution is replaced by a fake that writes what papermill
would, except in the tests that kill a real run.
"""

import contextlib
import json
import os
import subprocess
import sys
import textwrap
import time

import pandas as pd
import pytest

from tefcore.errors import OutputError
from tefcore.paper.run import reproduce as rp

nbformat = pytest.importorskip("nbformat")
psutil = pytest.importorskip("psutil")
pytest.importorskip("papermill")

#: Longest wait for a kernel, or a worker, to start [s] (about 2 s measured on 2 busy cores).
START_S = 90
#: Longest time for the processes of a killed run to end [s]: the watcher looks every
#: 0.5 s (kernel_guard.WATCH_S) and gives SIGTERM 3 s before SIGKILL; a process left
#: running sleeps 600 s.
END_S = 15


def _claim(status, recorded="pass", cid="fig9b-x"):
    return {"id": cid, "figure": "fig9", "panel": "b", "kind": "trend", "tag": "validation",
            "statement": "s", "expected": "e", "computed": "c", "status": status,
            "reason": "the TEF root crosses at 0.43", "recorded_status": recorded}


@pytest.fixture
def fake(monkeypatch):
    """Fake notebooks writing ``state["rows"]`` as their claims; ``state["during"]`` runs
    while they 'execute'; the attribution writes ``attribution.csv`` and its stamp
    ``attribution.json``, as the real one does."""
    state = {"rows": [_claim("pass")], "during": None}

    def run(out, params, names, progress=True, nb_dir=None, kernel_name="python3", jobs=None,
            stop=None):
        if state["during"] is not None:
            state["during"]()
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame(state["rows"]).to_csv(out / name / "claims.csv", index=False)
        return [rp.NotebookRun(name, status="ok") for name in names]

    def attribute(out, claims, attribution):
        if attribution is None:
            return None
        (out / "attribution.csv").write_text("claim,assumption\nfig9b-x,old lever\n")
        (out / "attribution.json").write_text('{"code_stamp": "0000000000000000"}\n')
        return None

    monkeypatch.setattr(rp, "run_notebooks", run)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])
    monkeypatch.setattr(rp, "attribute_claims", attribute)
    return state


def test_a_second_reproduce_into_the_same_folder_is_refused_naming_the_holder(tmp_path, fake):
    out = tmp_path / "out"
    refused = []

    def second_run():
        fake["during"] = None                  # the second run's notebooks start no third
        try:
            rp.reproduce(out, notebooks=["04"], progress=False, attribution=False)
        except OutputError as err:
            refused.append(str(err))
    fake["during"] = second_run
    assert rp.reproduce(out, notebooks=["04"], progress=False, attribution=False) == 0
    assert len(refused) == 1
    assert str(out) in refused[0] and f"process {os.getpid()}" in refused[0]
    assert "another tefcore reproduce" in refused[0]


def test_a_folder_that_is_not_a_reproduction_is_refused_and_left_alone(tmp_path, fake):
    out = tmp_path / "thesis"
    out.mkdir()
    (out / "chapter1.tex").write_text("mine")
    with pytest.raises(OutputError, match="not empty and holds no reproduction"):
        rp.reproduce(out, notebooks=["04"], progress=False)
    assert [p.name for p in out.iterdir()] == ["chapter1.tex"]
    assert not out.with_name("thesis.incomplete").exists()


def test_a_file_of_the_user_in_a_previous_reproduction_is_never_deleted(tmp_path, fake):
    out = tmp_path / "out"
    rp.reproduce(out, notebooks=["04"], progress=False)
    (out / "my_notes.txt").write_text("mine")
    with pytest.raises(OutputError, match="my_notes.txt"):
        rp.reproduce(out, notebooks=["04"], progress=False)
    assert (out / "my_notes.txt").read_text() == "mine"


def test_a_previous_reproduction_is_replaced_whole(tmp_path, fake):
    # the report said "0 of 3" beside an old attribution.csv: the second run has
    # no attribution, and the first one's must not stay
    out = tmp_path / "out"
    fake["rows"] = [_claim("fail", "fail")]
    assert rp.reproduce(out, notebooks=["04"], progress=False) == 0
    assert (out / "attribution.csv").exists() and (out / "attribution.json").exists()
    # the same command again replaces it (every file it wrote is the reproduction's)
    assert rp.reproduce(out, notebooks=["04"], progress=False) == 0
    fake["rows"] = [_claim("pass")]
    assert rp.reproduce(out, notebooks=["04"], progress=False, attribution=False) == 0
    assert not (out / "attribution.csv").exists() and not (out / "attribution.json").exists()
    assert sorted(p.name for p in out.iterdir()) == [
        "04_cg_offset", "claims.csv", "report.html", "report.md", "reproduction.json"]
    assert json.loads((out / "reproduction.json").read_text())["notebooks"] == ["04_cg_offset"]
    assert not out.with_name("out.incomplete").exists()
    assert not out.with_name("out.replaced").exists()


def test_a_reproduction_of_a_version_without_marker_is_replaced(tmp_path, fake):
    out = tmp_path / "out"
    (out / "notebooks").mkdir(parents=True)
    (out / "report.md").write_text("old report")
    (out / "claims.csv").write_text("id,status\nfig9b-x,pass\n")
    (out / "attribution.csv").write_text("old")
    assert rp.reproduce(out, notebooks=["04"], progress=False, attribution=False) == 0
    assert not (out / "attribution.csv").exists() and (out / "reproduction.json").exists()


def test_an_interrupted_run_leaves_the_previous_result(tmp_path, fake, capsys):
    out = tmp_path / "out"
    rp.reproduce(out, notebooks=["04"], progress=False, attribution=False)
    before = (out / "report.md").read_text()

    def interrupt():
        raise KeyboardInterrupt
    fake["during"] = interrupt
    with pytest.raises(KeyboardInterrupt):
        rp.reproduce(out, notebooks=["04"], progress=False, attribution=False)
    assert (out / "report.md").read_text() == before
    assert (out.with_name("out.incomplete") / "INCOMPLETE.txt").exists()
    assert f"{out} is unchanged" in capsys.readouterr().err
    fake["during"] = None                     # the next run clears the partial one
    assert rp.reproduce(out, notebooks=["04"], progress=False, attribution=False) == 0
    assert not out.with_name("out.incomplete").exists()


# ------------------------------------------------------------------ kill -9, real processes


def _descendants(pid):
    with contextlib.suppress(psutil.Error):
        return psutil.Process(pid).children(recursive=True)
    return []


def _wait_for(pid, what, deadline_s=START_S):
    """The descendants of ``pid`` once one's command line holds ``what``."""
    deadline = time.monotonic() + deadline_s
    while time.monotonic() < deadline:
        kids = _descendants(pid)
        for k in kids:
            with contextlib.suppress(psutil.Error):
                if what in " ".join(k.cmdline()):
                    time.sleep(1.0)                  # whatever starts with it has started
                    return _descendants(pid)
        time.sleep(0.3)
    raise AssertionError(f"no process running {what!r} started")


def _kill_and_wait(proc, kids):
    """kill -9 ``proc``; the processes of ``kids`` still alive after END_S."""
    try:
        proc.kill()
        proc.wait()
        _, alive = psutil.wait_procs(kids, timeout=END_S)
        return alive
    finally:                                          # never leave a process behind
        for k in kids:
            with contextlib.suppress(psutil.Error):
                k.kill()


@pytest.fixture
def spawning_notebook(tmp_path):
    """Notebook 04 stood in by one that starts a process of its own, then sleeps."""
    folder = tmp_path / "nbs"
    folder.mkdir()
    nb = nbformat.v4.new_notebook()
    params = nbformat.v4.new_code_cell("output_dir = 'out'")
    params.metadata["tags"] = ["parameters"]
    nb.cells = [params, nbformat.v4.new_code_cell(
        "import subprocess, sys, time\n"
        "worker = subprocess.Popen([sys.executable, '-c', "
        "'import time; time.sleep(600)  # stand-in worker'])\n"
        "time.sleep(600)")]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, folder / "04_cg_offset.ipynb")
    return folder


def test_a_killed_reproduce_leaves_the_previous_result_and_no_process(tmp_path,
                                                                     spawning_notebook):
    out = tmp_path / "out"
    out.mkdir()
    (out / "report.md").write_text("the previous report")
    (out / "reproduction.json").write_text('{"notebooks": ["04_cg_offset"]}')
    env = {**os.environ, "TEFCORE_NOTEBOOKS": str(spawning_notebook)}
    proc = subprocess.Popen([sys.executable, "-m", "tefcore", "reproduce", "--only", "04",
                             "--out", str(out), "--no-progress", "--no-variants"],
                            cwd=tmp_path, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    kids = _wait_for(proc.pid, "stand-in worker")
    assert any("ipykernel" in " ".join(k.cmdline()) for k in kids)
    alive = _kill_and_wait(proc, [k for k in kids if "kernel_guard" not in " ".join(k.cmdline())])
    assert alive == []                                # the kernel and its worker too
    assert sorted(p.name for p in out.iterdir()) == ["report.md", "reproduction.json"]
    assert (out / "report.md").read_text() == "the previous report"
    assert (out.with_name("out.incomplete") / "INCOMPLETE.txt").exists()


_ATTRIBUTION_RUN = textwrap.dedent("""
    import sys, time
    import pandas as pd
    from tefcore.paper.run import reproduce as rp

    def run(out, params, names, **kw):
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame([{{"id": "fig9b-x", "figure": "fig9", "status": "fail",
                           "tag": "validation", "reason": "", "recorded_status": "fail"}}]
                         ).to_csv(out / name / "claims.csv", index=False)
        return [rp.NotebookRun(n, status="ok") for n in names]

    def attribute(out, claims, attribution):     # the attribution's joblib workers
        from joblib import Parallel, delayed
        Parallel(n_jobs=2, backend="loky")(delayed(time.sleep)(600) for _ in range(2))

    rp.run_notebooks, rp.attribute_claims = run, attribute
    rp.start_variant_runs = lambda *a, **k: []
    rp.reproduce({out!r}, notebooks=["04"], progress=False)
""")


def test_a_reproduce_killed_in_its_attribution_leaves_no_worker(tmp_path):
    pytest.importorskip("joblib")
    script = tmp_path / "run.py"
    script.write_text(_ATTRIBUTION_RUN.format(out=str(tmp_path / "out")))
    proc = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    kids = _wait_for(proc.pid, "LokyProcess")
    workers = [k for k in kids if "LokyProcess" in " ".join(k.cmdline())]
    assert len(workers) == 2
    assert _kill_and_wait(proc, workers) == []
