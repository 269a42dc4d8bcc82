"""``tefcore batch``: one pool, failures recorded, resume, stale refusal, report.

A real small batch (notebook 04 at 4 CG offsets, two runs of the reviewer's
example) runs once per module; the rest replaces the notebooks with fakes
that write what a notebook writes, so the runner's logic is tested in
milliseconds.
"""

import datetime
import json
import threading
import time
from pathlib import Path

import nbformat
import numpy as np
import pandas as pd
import pytest

from tefcore.cli import main
from tefcore.errors import OutputError
from tefcore.paper.run import batch as bt
from tefcore.paper.run.batch_report import headlines
from tefcore.paper.run.batch_state import RECORD, StaleRunError, read_record
from tefcore.paper.run.reproduce import NotebookRun
from tefcore.provenance import numerical_environment
from tefcore.safe_io import FileLock
from tests.paper.run.test_report_html import check_page

pytest.importorskip("papermill")
EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
QUICK = {"only": ["04"], "params": [{"all": {"n_points": 4}}]}


# ------------------------------------------------------------------ a real batch


@pytest.fixture(scope="module")
def real(tmp_path_factory):
    """The reviewer's example, notebook 04 only, 4 points: two runs, two workers."""
    out = tmp_path_factory.mktemp("batch") / "out"
    first = bt.batch(EXAMPLES / "flap_inertia_doubled.yaml", out, jobs=2, progress=False,
                     **QUICK)
    return out, first


def _papermill_times(nb_path: Path):
    meta = nbformat.read(nb_path, as_version=4).metadata["papermill"]
    return (datetime.datetime.fromisoformat(meta["start_time"]),
            datetime.datetime.fromisoformat(meta["end_time"]))


def test_real_batch_runs_in_parallel_and_writes_every_report(real):
    out, res = real
    assert res.exit_code == 0 and [r.action for r in res.runs] == ["new", "new"]
    names = ["baseline", "flap-inertia-x2"]
    (a0, a1), (b0, b1) = (_papermill_times(out / n / "notebooks" / "04_cg_offset.ipynb")
                          for n in names)
    assert a0 < b1 and b0 < a1, "the two runs' kernels did not overlap: not run in parallel"
    for n in names:
        rec = read_record(out / n)
        assert rec["status"] == "ok" and rec["inputs"]["parameters"]["04_cg_offset"][
            "n_points"] == 4
        page = (out / n / "report.html").read_text()
        check_page(page)
        assert 'href="../index.html"' in page and f"tefcore batch run {n}" in page
    runs = pd.read_csv(out / "runs.csv")
    assert list(runs["run"]) == names and set(runs["status"]) == {"ok"}
    assert list(runs["overrides.flap.inertia_cg"].fillna("-")) == ["-", "0.48 lb*in^2/ft"]
    assert {"fig9.flutter_onset", "fig9.tef_max_growth", "passed", "total"} <= set(runs)
    assert (runs["total"] > 0).all()
    # the headlines are those of each run's own sweep table
    for i, n in enumerate(names):
        table = pd.read_csv(out / n / "04_cg_offset" / "fig09_modes.csv")
        h = headlines("fig9", table)["flutter root"]
        assert runs.loc[i, "fig9.flutter_onset"] == pytest.approx(h["onset"], rel=1e-5,
                                                                  nan_ok=True)
    long = pd.read_csv(out / "headlines.csv")
    assert len(long) == 2 * 2 and set(long["root"]) == {"flutter root", "TEF branch"}
    page = check_page((out / "index.html").read_text())
    assert {"runs", "fig9"} <= page.ids and len(page.imgs) >= 2
    assert (out / "figures" / "fig9.png").read_bytes()[:4] == b"\x89PNG"
    md = (out / "index.md").read_text()
    assert "(figures/fig9.png)" in md and "[flap-inertia-x2](flap-inertia-x2/report.html)" in md


def test_real_batch_resumes_without_recomputing_and_refuses_stale_runs(real):
    out, _ = real
    executed = [out / n / "notebooks" / "04_cg_offset.ipynb" for n in ("baseline",
                                                                       "flap-inertia-x2")]
    stamps = [p.stat().st_mtime_ns for p in executed]
    index = (out / "index.html").read_bytes()
    again = bt.batch(EXAMPLES / "flap_inertia_doubled.yaml", out, jobs=2, progress=False,
                     **QUICK)
    assert [r.action for r in again.runs] == ["skip", "skip"] and again.exit_code == 0
    assert [p.stat().st_mtime_ns for p in executed] == stamps          # nothing recomputed
    assert (out / "index.html").read_bytes() == index                  # deterministic report
    with pytest.raises(StaleRunError) as info:
        bt.batch(EXAMPLES / "flap_inertia_doubled.yaml", out, progress=False, only=["04"],
                 params=[{"all": {"n_points": 5}}])
    msg = str(info.value)
    assert "run 'baseline'" in msg and "04_cg_offset:n_points (4 then, 5 now)" in msg
    assert "1 more stale run" in msg and "--force" in msg and "--out" in msg
    assert [p.stat().st_mtime_ns for p in executed] == stamps          # refused before running


# ------------------------------------------------------------------ the runner, with fakes


def _fake_notebook(fail=(), delay=0.0, log=None):
    """What execute_notebook does, without a kernel: a claims table and a fig9 sweep table."""
    lock = threading.Lock()
    state = {"now": 0, "max": 0}

    def run(name, src, out, params, kernel_name="python3"):
        with lock:
            state["now"] += 1
            state["max"] = max(state["max"], state["now"])
        time.sleep(delay)
        nb_out = Path(params["output_dir"])
        nb_out.mkdir(parents=True, exist_ok=True)
        (out / "notebooks").mkdir(parents=True, exist_ok=True)
        (out / "notebooks" / f"{name}.ipynb").write_text("{}")
        pd.DataFrame([{"id": "fig9b-x", "figure": "fig9", "tag": "validation",
                       "statement": "s", "expected": "e", "computed": "c", "status": "pass",
                       "reason": "", "recorded_status": "pass"}]).to_csv(
            nb_out / "claims.csv", index=False)
        cg = params.get("overrides", {}).get("flap.cg_offset", 0.1)
        x = [0.0, 0.1, 0.2, 0.3, 0.4]
        pd.DataFrame({"status": "ok", "value": x, "real_part": [v - cg for v in x],
                      "flutter_root": True, "tef_branch": True, "tef_branch_certain": True}
                     ).to_csv(nb_out / "fig09_modes.csv", index=False)
        if log is not None:
            log.append(out.name)
        with lock:
            state["now"] -= 1
        failed = out.name in fail
        return NotebookRun(name, "failed" if failed else "ok",
                           "RuntimeError: boom" if failed else "", 0.01, params)

    return run, state


@pytest.fixture
def fake(monkeypatch):
    monkeypatch.setattr(bt, "baseline_blade", lambda out, cfg=None: None)
    monkeypatch.setattr(bt, "ensure_kernel", lambda name="python3": None)

    def install(**kw):
        run, state = _fake_notebook(**kw)
        monkeypatch.setattr(bt, "execute_notebook", run)
        return state
    return install


def _file(tmp_path, text):
    f = tmp_path / "runs.yaml"
    f.write_text(text)
    return f


def test_one_pool_of_jobs_workers_over_all_runs(tmp_path, fake):
    state = fake(delay=0.2)
    f = _file(tmp_path, "notebooks: [04]\ngrid: {overrides.flap.cg_offset: [0.1, 0.2, 0.3, "
                        "0.35]}\n")
    res = bt.batch(f, tmp_path / "out", jobs=2, progress=False)
    assert res.exit_code == 0 and len(res.runs) == 4
    assert state["max"] == 2          # never more than the pool's workers, and both used
    runs = pd.read_csv(tmp_path / "out" / "runs.csv")
    # the fake flutter root crosses zero at the run's CG offset
    assert list(runs["fig9.flutter_onset"]) == pytest.approx([0.1, 0.2, 0.3, 0.35])


def test_a_failed_run_is_recorded_the_batch_goes_on_and_it_is_retried(tmp_path, fake, capsys):
    fake(fail={"b"})
    f = _file(tmp_path, "notebooks: [04]\nruns: [{name: a}, {name: b}, {name: c}]\n")
    out = tmp_path / "out"
    res = bt.batch(f, out, jobs=2, progress=False)
    assert [r.status for r in res.runs] == ["ok", "failed", "ok"] and res.exit_code == 1
    assert read_record(out / "b")["error"] == "04_cg_offset: RuntimeError: boom"
    page = (out / "index.html").read_text()
    check_page(page)
    assert "RuntimeError: boom" in page
    assert "run(s) failed: b" in capsys.readouterr().err
    log = []
    fake(log=log)
    res = bt.batch(f, out, jobs=2, progress=False)
    assert [r.action for r in res.runs] == ["skip", "retry", "skip"] and log == ["b"]
    assert res.exit_code == 0
    assert main(["batch", str(f), "--out", str(out), "--no-progress"]) == 0


def test_stale_runs_are_refused_and_force_recomputes_them(tmp_path, fake):
    fake()
    out = tmp_path / "out"
    f = _file(tmp_path, "notebooks: [04, 05]\nruns: [{name: a}]\n")
    bt.batch(f, out, progress=False)
    assert (out / "a" / "05_stiffness").is_dir()
    f.write_text("notebooks: [04]\nruns: [{name: a, params: {all: {n_points: 3}}}]\n")
    with pytest.raises(StaleRunError, match=r"notebooks \(04_cg_offset 05_stiffness then, "
                                            r"04_cg_offset now\)"):
        bt.batch(f, out, progress=False)
    res = bt.batch(f, out, progress=False, force=True)
    assert res.runs[0].action == "redo" and res.exit_code == 0
    assert not (out / "a" / "05_stiffness").exists()      # the old run's results are gone
    assert read_record(out / "a")["inputs"]["notebooks"] == ["04_cg_offset"]


def test_a_changed_configuration_file_makes_a_run_stale(tmp_path, fake):
    from tefcore.config.io import load_config, save_config

    fake()
    save_config(load_config("mdart"), tmp_path / "rotor.toml")
    f = _file(tmp_path, "notebooks: [04]\nconfig: rotor.toml\nname: mine\n")
    bt.batch(f, tmp_path / "out", progress=False)
    save_config(load_config("mdart").with_overrides({"actuator.stiffness": 100.0}),
                tmp_path / "rotor.toml")
    with pytest.raises(StaleRunError, match="configuration file .*then"):
        bt.batch(f, tmp_path / "out", progress=False)


def test_folders_that_are_not_batch_runs_or_locked_are_refused(tmp_path, fake):
    fake()
    f = _file(tmp_path, "notebooks: [04]\nruns: [{name: a}]\n")
    out = tmp_path / "out"
    (out / "a").mkdir(parents=True)
    (out / "a" / "mine.txt").write_text("keep")
    with pytest.raises(StaleRunError, match="holds files but no batch record"):
        bt.batch(f, out, progress=False)
    (out / "a" / "mine.txt").unlink()
    (out / "a" / RECORD).write_text("{not json")
    with pytest.raises(StaleRunError, match="cannot be read"):
        bt.batch(f, out, progress=False)
    (out / "a" / RECORD).unlink()
    with FileLock(out / "batch"), pytest.raises(OutputError, match="another process"):
        bt.batch(f, out, progress=False)
    (tmp_path / "elsewhere").mkdir()
    (out / "a").rmdir()
    (out / "a").symlink_to(tmp_path / "elsewhere", target_is_directory=True)
    with pytest.raises(OutputError, match="symbolic link"):
        bt.batch(f, out, progress=False)


def test_dry_run_plans_and_writes_nothing(tmp_path, fake, capsys):
    fake()
    f = _file(tmp_path, "notebooks: [04]\ngrid: {overrides.flap.overhang: [0.2, 0.3]}\n")
    assert main(["batch", str(f), "--out", str(tmp_path / "out"), "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert "overhang=0.2" in text and "new" in text and not (tmp_path / "out").exists()


def test_record_keeps_what_decides_the_results(tmp_path, fake):
    fake()
    f = _file(tmp_path, "notebooks: [04]\nname: a\nparams: {all: {n_points: 3}}\n")
    bt.batch(f, tmp_path / "out", progress=False)
    rec = json.loads((tmp_path / "out" / "a" / RECORD).read_text())
    inputs = rec["inputs"]
    assert set(inputs) == {"notebooks", "parameters", "config", "config_files",
                           "tefcore_version", "model_stamp", "paper_stamp", "notebook_sources",
                           "reference_data"}
    assert inputs["parameters"]["04_cg_offset"] == {"n_points": 3, "interactive": False}
    assert inputs["notebook_sources"]["04_cg_offset"].startswith("sha256:")
    assert rec["environment"] == numerical_environment()


def test_a_run_from_another_numerical_stack_is_kept_and_says_so(tmp_path, fake, capsys):
    # names and verdicts do not depend on the numpy/scipy/BLAS build, so a finished run
    # computed on another stack is skipped, not refused, and the batch names what differs
    fake()
    f = _file(tmp_path, "notebooks: [04]\nname: a\n")
    out = tmp_path / "out"
    bt.batch(f, out, progress=False)
    rec = json.loads((out / "a" / RECORD).read_text())
    rec["environment"] = {**rec["environment"], "numpy": "1.26.4"}
    (out / "a" / RECORD).write_text(json.dumps(rec))
    capsys.readouterr()
    log = []
    fake(log=log)
    res = bt.batch(f, out, progress=False)
    assert [r.action for r in res.runs] == ["skip"] and log == []
    err = capsys.readouterr().err
    assert "numpy 1.26.4 (now " + numerical_environment()["numpy"] + ")" in err
    rec["environment"] = numerical_environment()           # the same stack: nothing said
    (out / "a" / RECORD).write_text(json.dumps(rec))
    bt.batch(f, out, progress=False)
    assert "note" not in capsys.readouterr().err


# ------------------------------------------------------------------ headlines and curves


def _sweep(x, real, tef=True, certain=None):
    return pd.DataFrame({"status": "ok", "value": x, "real_part": real, "flutter_root": True,
                         "tef_branch": tef,
                         "tef_branch_certain": True if certain is None else certain})


def test_headlines_onset_state_and_growth():
    x = [0.0, 0.1, 0.2, 0.3]
    h = headlines("fig9", _sweep(x, [-2.0, -1.0, 1.0, 0.5]))["flutter root"]
    # linear between the points around the sign change: -1 at 0.1, +1 at 0.2
    assert h["onset"] == pytest.approx(0.15) and h["state"] == "crosses"
    assert (h["max_growth"], h["max_growth_at"]) == (1.0, 0.2)
    stable = headlines("fig9", _sweep(x, [-2.0, -1.0, -0.5, -0.1]))["flutter root"]
    assert stable["state"] == "stable" and np.isnan(stable["onset"])
    unstable = headlines("fig9", _sweep(x, [0.5, 1.0, -0.5, 0.2]))["flutter root"]
    # unstable at the start, stable from 0.167, unstable again from 0.271: the onset is the
    # first stable-to-unstable crossing, and the state says it started unstable
    assert unstable["state"] == "unstable at start"
    assert unstable["onset"] == pytest.approx(0.2 + 0.1 * 5 / 7)
    assert unstable["stable_in"] == "0.167 to 0.271"
    # the TEF branch counts only where its identity is decided
    tef = headlines("fig9", _sweep(x, [-2.0, -1.0, 1.0, 2.0],
                                   certain=[True, True, False, False]))["TEF branch"]
    assert tef["state"] == "stable" and tef["points"] == 2 and np.isnan(tef["onset"])
    # x is the paper's axis: Fig. 12's actuator stiffness as a factor on 81.52 ft-lb/rad
    t = _sweep(["40.76 ft-lb/rad", "81.52 ft-lb/rad"], [-1.0, 1.0])
    assert headlines("fig12", t)["flutter root"]["onset"] == pytest.approx(0.75)


def test_identical_curves_are_drawn_once_and_labelled_by_what_they_share(tmp_path, fake):
    fake()      # the fake's curves depend on the CG offset only
    f = _file(tmp_path, "notebooks: [04]\ngrid: {overrides.flap.cg_offset: [0.1, 0.2],\n"
                        "       overrides.flap.overhang: [0.2, 0.3]}\n")
    bt.batch(f, tmp_path / "out", progress=False)
    md = (tmp_path / "out" / "index.md").read_text()
    assert md.count("| cg_offset=0.1 (2 runs) |") == 2 and "runs with identical curves" in md
    check_page((tmp_path / "out" / "index.html").read_text())


def test_run_parameters_give_each_notebook_its_folder_and_the_configuration(tmp_path):
    from tefcore.paper.run.batch_spec import RunSpec

    spec = RunSpec("r", ("04_cg_offset",), {"04_cg_offset": {"n_points": 3}},
                   config=str(tmp_path / "rotor.toml"))
    p = bt.run_parameters(spec, tmp_path)["04_cg_offset"]
    assert p == {"n_points": 3, "interactive": False, "config": str(tmp_path / "rotor.toml"),
                 "output_dir": str(tmp_path / "r" / "04_cg_offset")}
