"""Measure optuna's storages for the inference study: kill -9 mid-trial, two workers.

For a journal file (optuna ``JournalStorage``, the default of ``tefcore infer``)
and SQLite (``RDBStorage``):

* kill -9: a worker runs trials of 2 s each and is killed with SIGKILL 1 s into
  its third (after the storage shows two complete); the storage is reopened
  (does it load? which states?), the dead trial is recovered
  (:func:`tefcore.paper.inference.study.recover_dead_trials`) and the study
  resumed to its target;
* two workers: two processes run 15 trials of 0.1 s each on one study at once;
  every trial must be recorded once, with no error from the storage.

Run: ``python tools/measure_study_storage.py`` (about a minute); it prints one
line per measurement.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = []

TARGET = 5


def _objective(seconds):
    def f(trial):
        import socket

        trial.set_user_attr("worker", f"{socket.gethostname()}:{os.getpid()}")
        x = trial.suggest_float("x", -1.0, 1.0)
        time.sleep(seconds)
        return -x * x
    return f


def _study(url, name):
    import optuna

    from tefcore.paper.inference.study import open_storage

    optuna.logging.set_verbosity(optuna.logging.ERROR)
    return optuna.create_study(study_name=name, storage=open_storage(url),
                               sampler=optuna.samplers.RandomSampler(seed=1),
                               load_if_exists=True)


def _worker(url, name, n, seconds):
    from optuna.study import MaxTrialsCallback
    from optuna.trial import TrialState

    study = _study(url, name)
    study.optimize(_objective(float(seconds)), callbacks=[
        MaxTrialsCallback(int(n), states=(TrialState.COMPLETE,))])


def _spawn(url, name, n, seconds):
    return subprocess.Popen([sys.executable, __file__, "worker", url, name, str(n),
                             str(seconds)], stderr=subprocess.PIPE, text=True)


def _states(study):
    from collections import Counter

    return dict(Counter(t.state.name for t in study.get_trials(deepcopy=False)))


def _wait_for(url, name, n, timeout=120.0):
    """Poll the storage until the study holds `n` completed trials."""
    from optuna.trial import TrialState

    end = time.time() + timeout
    while time.time() < end:
        try:
            done = _study(url, name).get_trials(deepcopy=False, states=(TrialState.COMPLETE,))
            if len(done) >= n:
                return
        except Exception:                # the worker is still creating the storage
            pass
        time.sleep(0.2)
    raise TimeoutError(f"{n} trials not complete after {timeout} s")


def kill_and_resume(url) -> str:
    from tefcore.paper.inference.study import open_storage, recover_dead_trials

    p = _spawn(url, "kill", TARGET, 2.0)
    _wait_for(url, "kill", 2)            # two trials complete: the third is running
    time.sleep(1.0)                      # inside the third (2 s)
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    try:
        study = _study(url, "kill")
    except Exception as err:             # what a broken storage raises is the measurement
        return f"reopen after kill -9 FAILED: {type(err).__name__}: {err}"
    before = _states(study)
    recovered = recover_dead_trials(study, open_storage(url))
    q = _spawn(url, "kill", TARGET, 0.1)
    q.wait()
    after = _states(_study(url, "kill"))
    return (f"after kill -9: {before}; recovered {recovered}; resumed: {after}; "
            f"worker exit {q.returncode}{' ' + q.stderr.read()[-200:] if q.returncode else ''}")


def two_workers(url) -> str:
    ps = [_spawn(url, "two", 15, 0.1) for _ in range(2)]
    errs = []
    for p in ps:
        p.wait()
        if p.returncode:
            errs.append(p.stderr.read().strip().splitlines()[-1])
    study = _study(url, "two")
    numbers = [t.number for t in study.get_trials(deepcopy=False)]
    return (f"two workers: {_states(study)}, numbers unique {len(set(numbers)) == len(numbers)}"
            f", errors {errs or 'none'}")


def main():
    with tempfile.TemporaryDirectory() as d:
        for label, url in (("journal file", str(Path(d) / "study.journal")),
                           ("sqlite", f"sqlite:///{Path(d) / 'study.db'}")):
            print(f"{label}: {kill_and_resume(url)}")
            print(f"{label}: {two_workers(url)}")


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "worker":
        _worker(*sys.argv[2:])
    else:
        main()
