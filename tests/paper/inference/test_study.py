"""The study: re-created from its seed, resumed after kill -9, two workers, refusals counted.

The claims' checks are replaced by a stand-in of no cost (:mod:`.fakes`): what is
tested is the study's machinery, which the real objective uses unchanged.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import optuna
import pytest
from optuna.trial import TrialState

from tefcore.paper.inference.analysis import failures, leave_one_figure_out, pareto_front
from tefcore.paper.inference.study import StudySpec, estimate, open_study, run_study

from . import fakes

ROOT = Path(__file__).resolve().parents[3]


def _spec(tmp_path, protocol, **kw):
    return StudySpec(storage=str(tmp_path / "study.journal"), protocol=protocol,
                     name=kw.pop("name", "s"), **kw)


def _params(study):
    return [t.params for t in sorted(study.trials, key=lambda t: t.number)]


@pytest.mark.parametrize("sampler", ["tpe", "qmc"])
def test_a_short_study_is_recreated_from_its_seed(tmp_path, fixed_protocol, sampler):
    a = run_study(_spec(tmp_path / "a", fixed_protocol, sampler=sampler, seed=7), 12,
                  evaluator=fakes.quick)
    b = run_study(_spec(tmp_path / "b", fixed_protocol, sampler=sampler, seed=7), 12,
                  evaluator=fakes.quick)
    c = run_study(_spec(tmp_path / "c", fixed_protocol, sampler=sampler, seed=8), 12,
                  evaluator=fakes.quick)
    assert _params(a) == _params(b)
    assert _params(a) != _params(c)
    assert [t.value for t in a.trials] == [t.value for t in b.trials]


def test_tpe_finds_the_stand_ins_peak(tmp_path, fixed_protocol):
    study = run_study(_spec(tmp_path, fixed_protocol, seed=1), 30, evaluator=fakes.quick)
    best = study.best_trial.params["flap mass"]
    # the stand-in peaks at 0.40 lb/ft; 30 trials of TPE land within 0.03 of it
    assert abs(best - 0.40) < 0.03, best


def _wait_complete(spec, n, timeout=240.0):
    end = time.time() + timeout
    while time.time() < end:
        try:
            done = open_study(spec).get_trials(states=(TrialState.COMPLETE,))
            if len(done) >= n:
                return
        except Exception:                  # the worker is still creating the journal
            pass
        time.sleep(0.2)
    raise TimeoutError(f"{n} trials not complete after {timeout} s")


def test_kill_minus_9_mid_trial_and_resume(tmp_path, fixed_protocol, monkeypatch):
    spec = _spec(tmp_path, fixed_protocol, seed=3)
    code = ("import sys; from tests.paper.inference import fakes; "
            "from tefcore.paper.inference.study import StudySpec, run_study; "
            f"run_study(StudySpec(storage={spec.storage!r}, protocol={spec.protocol!r}, "
            f"name='s', seed=3), 5, evaluator=fakes.slow)")
    env = {**os.environ, "TEFCORE_FAKE_SECONDS": "2",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    worker = subprocess.Popen([sys.executable, "-c", code], cwd=ROOT, env=env)
    try:
        _wait_complete(spec, 2)
        time.sleep(0.7)                      # inside the third trial (2 s)
        os.kill(worker.pid, signal.SIGKILL)
        worker.wait()
    finally:
        worker.kill()
    study = open_study(spec)
    states = [t.state for t in study.trials]
    assert states.count(TrialState.COMPLETE) == 2 and states.count(TrialState.RUNNING) == 1
    killed = next(t for t in study.trials if t.state == TrialState.RUNNING)
    study = run_study(spec, 5, evaluator=fakes.quick)        # the same command again
    done = [t for t in study.trials if t.state == TrialState.COMPLETE]
    # finished: completed or refused (pruned) samples, the target of the study
    assert len([t for t in study.trials if t.state == TrialState.PRUNED]) + len(done) == 5
    assert study.trials[killed.number].state == TrialState.FAIL
    retry = [t for t in done if t.user_attrs.get("retry_of") == killed.number]
    assert len(retry) == 1 and retry[0].params == killed.params
    assert failures(study)["failed"] == 1


def test_two_workers_share_one_study(tmp_path, fixed_protocol, monkeypatch):
    # trials of 3 s: the second worker (a new process importing tefcore and optuna)
    # joins long before one worker alone would finish
    monkeypatch.setenv("TEFCORE_FAKE_SECONDS", "3")
    spec = _spec(tmp_path, fixed_protocol, seed=4)
    study = run_study(spec, 8, jobs=2, evaluator=fakes.slow)
    done = [t for t in study.trials if t.state in (TrialState.COMPLETE, TrialState.PRUNED)]
    # each worker checks the count before a trial: up to jobs - 1 past the target
    assert 8 <= len(done) <= 9
    workers = {t.user_attrs["worker"] for t in done}
    assert len(workers) == 2, workers
    assert len({t.number for t in study.trials}) == len(study.trials)


def test_a_refused_sample_is_pruned_and_counted(tmp_path, fixed_protocol):
    spec = _spec(tmp_path, fixed_protocol)
    study = open_study(spec)
    study.enqueue_trial({"flap mass": 0.55})     # solid at its thickness: does not fit
    study = run_study(spec, 3, evaluator=fakes.quick)
    first = study.trials[0]
    assert first.state == TrialState.PRUNED
    assert "does not fit in the blade section" in first.user_attrs["refused"]
    f = failures(study)
    assert f["refused"] >= 1 and f["completed"] == 3 - f["refused"]


def test_the_estimate_reads_the_studys_own_trials(tmp_path, fixed_protocol):
    spec = _spec(tmp_path, fixed_protocol)
    before = estimate(spec, 4)
    assert not before["measured"] and before["to_run"] == 4
    run_study(spec, 2, evaluator=fakes.quick)
    after = estimate(spec, 4, jobs=2)
    assert after["measured"] and after["done"] == 2 and after["to_run"] == 2
    # the pace of its trials (their median duration) spread over the two workers
    paces = [t.duration.total_seconds() for t in open_study(spec).trials]
    assert after["wall_s"] == pytest.approx(2 * np.median(paces) / 2)


def test_leave_one_figure_out_and_the_pareto_front(tmp_path, fixed_protocol):
    study = run_study(_spec(tmp_path, fixed_protocol, sampler="qmc"), 10,
                      evaluator=fakes.quick)
    lofo = leave_one_figure_out(study, "continued", ["fig6", "fig9"])
    assert list(lofo["figure"]) == ["fig6", "fig9"] and not lofo["guided"].any()
    # the stand-in gives every claim the same margin: leaving a figure out picks the
    # same best trial, where its claims fare as at the best
    assert (lofo["passes there"] == lofo["passes at best"]).all()
    front = pareto_front(study, "continued", ["fig6-response-15pct-above-input",
                                              "fig9b-tef-unstable-after-0.26"])
    # equal margins: one trial (or ties at the same value) dominates the rest
    assert front.iloc[:, 1].nunique() == 1
    assert front.iloc[0, 1] == pytest.approx(
        max(t.user_attrs["continued:margins"]["fig6-response-15pct-above-input"]
            for t in study.trials if t.state == TrialState.COMPLETE), abs=0.4)


def test_optuna_is_what_holds_the_study(tmp_path, fixed_protocol):
    spec = _spec(tmp_path, fixed_protocol)
    run_study(spec, 2, evaluator=fakes.quick)
    from tefcore.paper.inference.study import open_storage

    summaries = optuna.get_all_study_summaries(open_storage(spec.storage))
    assert [s.study_name for s in summaries] == ["s"]


def test_nsga2_scores_each_fitted_figure_apart(tmp_path, fixed_protocol):
    from tefcore.paper.inference.protocol import load_protocol

    study = run_study(_spec(tmp_path, fixed_protocol, sampler="nsga2", seed=2), 4,
                      evaluator=fakes.quick)
    figures = load_protocol(fixed_protocol).fit_figures
    done = [t for t in study.trials if t.state == TrialState.COMPLETE]
    assert done and all(len(t.values) == len(figures) for t in done)
    # the stand-in gives each fitted claim the same margin m: a figure's objective is
    # its fitted claims' count times tanh(m)
    t = done[0]
    m = t.user_attrs["continued:margins"]["fig6-response-15pct-above-input"]
    assert t.values[figures.index("fig6")] == pytest.approx(np.tanh(m))
