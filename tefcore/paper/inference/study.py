"""The optuna study of the inference: storage, samplers, workers, progress and resume.

A study samples the declared space (:mod:`tefcore.paper.inference.space`)
jointly, every parameter at once, and maximises the protocol's objective over
the fitted claims of one reading (:mod:`tefcore.paper.inference.protocol`);
each trial records every reading's objective, pass count and each fitted
claim's margin and status, so the readings and the analyses
(:mod:`tefcore.paper.inference.analysis`) read the same trials.

* storage: optuna's own.  A path is a journal file (optuna's
  ``JournalStorage``), which measured best on one machine: it survives a
  ``kill -9`` mid-trial and two or more workers on one study (file lock);
  ``sqlite:///file.db`` or any SQLAlchemy URL gives an RDB storage, the one for
  many machines (``postgresql://user@host/db``), where a heartbeat fails the
  trials of a dead worker.
* samplers (:data:`SAMPLERS`): ``tpe`` (multivariate TPE, seeded),
  ``qmc`` (scrambled Sobol points, independent of the objective), ``random``,
  ``nsga2`` (several objectives: one per fitted figure).
* resume: run the same command again.  A trial left running by a worker
  that was killed (its process is gone) is failed and its parameters are
  enqueued again, so the study evaluates the same point.
* a sample tefcore refuses (:class:`~tefcore.paper.inference.space.Refused`)
  is a *pruned* trial with the reason in ``refused``: counted, never reported
  as a rotor; TPE learns to avoid its region.

Examples
--------
>>> spec = StudySpec(reading="flutter", sampler="qmc", seed=3)
>>> spec.study_name
'protocol-flutter-qmc-seed3'
"""

from __future__ import annotations

import math
import os
import socket
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .protocol import READINGS, SAMPLERS, load_protocol
from .space import Refused, apply_sample, load_space, recalibrated

__all__ = ["SAMPLERS", "TRIAL_CPU_S", "StudySpec", "estimate", "make_sampler", "open_storage",
           "open_study", "recover_dead_trials", "run_study", "seconds_text", "worker"]

#: The samplers a study can use.

#: CPU seconds of one trial on the packaged protocol, before a study has measured its
#: own: the cheap evaluation of the fitted Figs. 6-9 and 12 plus the torsion re-fit
#: (0.7 s); the median of 83 trials over the space was 10.4-13.0 s per study (5-24 s).
TRIAL_CPU_S = 12.0


@dataclass(frozen=True)
class StudySpec:
    """Which study: protocol, reading, sampler, seed, where it is stored.

    Parameters
    ----------
    reading : str
        The reading the objective scores (:data:`~tefcore.paper.inference.protocol.READINGS`).
    sampler : str
        One of :data:`SAMPLERS`.
    seed : int
        The sampler's seed.
    storage : str
        A journal file path, or an RDB URL (``sqlite:///x.db``); default
        ``inference.journal`` in the working folder.
    cache : str
        Folder of the figures' sweep files (default ``<storage>.figures``).
    protocol : str
        The protocol file's name.
    name : str
        The study's name in its storage (default from the rest).
    """

    reading: str = "continued"
    sampler: str = "tpe"
    seed: int = 0
    storage: str = "inference.journal"
    cache: str = ""
    protocol: str = "protocol"
    name: str = ""

    def __post_init__(self):
        if self.reading not in READINGS:
            raise ValueError(f"reading = {self.reading!r} is not one of {', '.join(READINGS)}")
        if self.sampler not in SAMPLERS:
            raise ValueError(f"sampler = {self.sampler!r} is not one of {', '.join(SAMPLERS)}")

    @property
    def study_name(self) -> str:
        """Its name in the storage."""
        return self.name or f"{self.protocol}-{self.reading}-{self.sampler}-seed{self.seed}"

    @property
    def cache_folder(self) -> Path:
        """The folder of its figures' sweeps."""
        if self.cache:
            return Path(self.cache)
        base = self.storage.split("///", 1)[-1] if "://" in self.storage else self.storage
        return Path(f"{base}.figures")


def open_storage(url: str):
    """optuna storage for a journal file path or an RDB URL.

    Parameters
    ----------
    url : str
        A path (journal file, created with its folder if missing) or a
        SQLAlchemy URL.

    Returns
    -------
    optuna.storages.BaseStorage
    """
    import optuna

    if "://" in url:
        with warnings.catch_warnings():     # the heartbeat is experimental in optuna
            warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
            return optuna.storages.RDBStorage(url, heartbeat_interval=60, grace_period=300)
    from optuna.storages.journal import JournalFileBackend, JournalFileOpenLock

    path = Path(url)
    path.parent.mkdir(parents=True, exist_ok=True)
    path = str(path)
    return optuna.storages.JournalStorage(
        JournalFileBackend(path, lock_obj=JournalFileOpenLock(path)))


def make_sampler(kind: str, seed: int):
    """The optuna sampler of a study.

    Parameters
    ----------
    kind : str
        One of :data:`SAMPLERS`.
    seed : int
        The sampler's seed.

    Returns
    -------
    optuna.samplers.BaseSampler
    """
    import optuna

    if kind == "tpe":
        # multivariate: the parameters move jointly; constant liar: parallel
        # workers do not all sample where a running trial already is
        return optuna.samplers.TPESampler(seed=seed, multivariate=True, constant_liar=True,
                                          n_startup_trials=10)
    if kind == "qmc":
        with warnings.catch_warnings():     # experimental since optuna 3.0, and kept
            warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
            return optuna.samplers.QMCSampler(qmc_type="sobol", scramble=True, seed=seed,
                                              warn_independent_sampling=False)
    if kind == "random":
        return optuna.samplers.RandomSampler(seed=seed)
    if kind == "nsga2":
        return optuna.samplers.NSGAIISampler(seed=seed, population_size=12)
    raise ValueError(f"sampler = {kind!r} is not one of {', '.join(SAMPLERS)}")


def open_study(spec: StudySpec):
    """The study of `spec`, created on first use, loaded after.

    Parameters
    ----------
    spec : StudySpec
        The study.

    Returns
    -------
    optuna.Study
    """
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    protocol = load_protocol(spec.protocol)
    directions = (["maximize"] * len(protocol.fit_figures) if spec.sampler == "nsga2"
                  else ["maximize"])
    study = optuna.create_study(study_name=spec.study_name, storage=open_storage(spec.storage),
                                sampler=make_sampler(spec.sampler, spec.seed),
                                directions=directions, load_if_exists=True)
    for k, v in (("protocol", spec.protocol), ("reading", spec.reading),
                 ("sampler", spec.sampler), ("seed", spec.seed), ("space", protocol.space)):
        if k not in study.user_attrs:
            study.set_user_attr(k, v)
    return study


def _suggest(trial, space) -> dict:
    out = {}
    for p in space.values():
        if p.categorical:
            out[p.name] = trial.suggest_categorical(p.name, list(p.choices))
        else:
            out[p.name] = trial.suggest_float(p.name, p.low, p.high, log=p.log)
    return out


def _claims_evaluator(cfg, claims, readings, protocol, cache_folder):
    from ..attribution.evaluate import FigureCache, RunSettings
    from .evaluate import evaluate_rotor

    Path(cache_folder).mkdir(parents=True, exist_ok=True)
    return evaluate_rotor(cfg, claims, readings, cache=FigureCache(cache_folder),
                          settings=RunSettings(base=cfg, refine=protocol.refine),
                          flutter_quantities=protocol.flutter_quantities)


@dataclass
class Objective:
    """The study's objective: one sample's fitted claims, every reading recorded.

    Picklable, so that worker processes build their own.

    Parameters
    ----------
    spec : StudySpec
    evaluator : callable, optional
        ``(cfg, claims, readings, protocol, cache_folder) -> dict`` as
        :func:`tefcore.paper.inference.evaluate.evaluate_rotor` returns; the
        claims' own checks by default (tests pass a cheap stand-in).
    """

    spec: StudySpec
    evaluator: object = None
    claims: list = field(default=None, repr=False)

    def fitted(self):
        if self.claims is None:
            from ..claims.reference import load_claims

            self.claims = load_protocol(self.spec.protocol).split(load_claims())[0]
        return self.claims

    def __call__(self, trial):
        import optuna

        from .evaluate import objective

        protocol = load_protocol(self.spec.protocol)
        space = load_space(protocol.space)
        trial.set_user_attr("worker", f"{socket.gethostname()}:{os.getpid()}")
        start = time.process_time()
        sample = _suggest(trial, space)
        from ..figures.runs import base_config

        try:
            cfg = apply_sample(base_config("thin_airfoil"), space, sample)
        except Refused as err:
            trial.set_user_attr("refused", str(err))
            raise optuna.TrialPruned(f"refused: {err}") from None
        if protocol.torsion == "recalibrated":
            cfg = recalibrated(cfg)
        evaluate = self.evaluator or _claims_evaluator
        out = evaluate(cfg, self.fitted(), protocol.readings, protocol,
                       self.spec.cache_folder)
        trial.set_user_attr("broken", dict(out["broken"]))
        for r in protocol.readings:
            t = out[r]
            trial.set_user_attr(f"{r}:objective", objective(
                t, protocol.ambiguous_value, protocol.no_margin_fail_value))
            trial.set_user_attr(f"{r}:passes", int((t["status"] == "pass").sum()))
            trial.set_user_attr(f"{r}:margins", {
                i: (None if not np.isfinite(m) else float(m))
                for i, m in zip(t["id"], t["margin"].to_numpy(float), strict=True)})
            trial.set_user_attr(f"{r}:statuses", dict(zip(t["id"], t["status"], strict=True)))
        trial.set_user_attr("cpu_s", time.process_time() - start)
        table = out[self.spec.reading]
        if self.spec.sampler == "nsga2":
            return tuple(objective(table[table["figure"] == f], protocol.ambiguous_value,
                                   protocol.no_margin_fail_value) for f in protocol.fit_figures)
        return trial.user_attrs[f"{self.spec.reading}:objective"]


def _alive(worker: str) -> bool | None:
    """Whether a trial's worker (``host:pid``) runs; None when it is on another host."""
    import psutil

    host, _, pid = (worker or "").rpartition(":")
    if host != socket.gethostname() or not pid.isdigit():
        return None
    return psutil.pid_exists(int(pid))


def recover_dead_trials(study, storage) -> int:
    """Fail the trials a killed worker left running, and enqueue their parameters again.

    A trial is dead when its worker (user attribute ``worker``, ``host:pid``)
    ran on this host and its process is gone.  Trials of workers on other
    hosts are left to the RDB storage's heartbeat.

    Parameters
    ----------
    study : optuna.Study
        The study.
    storage : optuna.storages.BaseStorage
        The study's storage.

    Returns
    -------
    int
        The trials failed and enqueued again.
    """
    from optuna.trial import TrialState

    n = 0
    study_id = storage.get_study_id_from_name(study.study_name)
    for t in study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
        if _alive(t.user_attrs.get("worker", "")) is not False:
            continue
        tid = storage.get_trial_id_from_study_id_trial_number(study_id, t.number)
        storage.set_trial_state_values(tid, TrialState.FAIL)
        if t.params:
            study.enqueue_trial(t.params, user_attrs={"retry_of": t.number},
                                skip_if_exists=False)
        n += 1
    return n


def _finished(study) -> int:
    from optuna.trial import TrialState

    return len(study.get_trials(deepcopy=False, states=(TrialState.COMPLETE, TrialState.PRUNED)))


def estimate(spec: StudySpec, n_trials: int, jobs: int = 1) -> dict:
    """What a run of the study to `n_trials` finished trials would take.

    The CPU per trial is the median the study measured (``cpu_s`` of its
    completed trials), else :data:`TRIAL_CPU_S`; the wall time is the median
    duration of its completed trials (the pace on this machine, shared or
    not) spread over `jobs` workers, else the CPU time on free cores.

    Parameters
    ----------
    spec : StudySpec
        The study.
    n_trials : int
        Its target of finished trials.
    jobs : int
        Workers.

    Returns
    -------
    dict
        ``study``, ``done``, ``to_run``, ``cpu_per_trial_s``, ``measured``
        (bool) and ``wall_s``.
    """
    from optuna.trial import TrialState

    study = open_study(spec)
    done = _finished(study)
    complete = study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))
    cpu = [t.user_attrs["cpu_s"] for t in complete if "cpu_s" in t.user_attrs]
    wall = [t.duration.total_seconds() for t in complete if t.duration is not None]
    per = float(np.median(cpu)) if cpu else TRIAL_CPU_S
    pace = float(np.median(wall)) if wall else per
    to_run = max(n_trials - done, 0)
    return {"study": spec.study_name, "done": done, "to_run": to_run, "cpu_per_trial_s": per,
            "measured": bool(cpu), "wall_s": to_run * pace / max(jobs, 1)}


def _best_text(study, reading) -> str:
    try:
        best = study.best_trial
    except ValueError:
        return "best -"
    return (f"best {best.value:+.2f} ({best.user_attrs.get(f'{reading}:passes', '?')} "
            "fitted claims pass)")


def worker(spec: StudySpec, n_trials: int, evaluator=None, progress: bool = False) -> None:
    """One worker: run trials of the study until it holds `n_trials` finished ones.

    Parameters
    ----------
    spec : StudySpec
        The study.
    n_trials : int
        The study's target of finished (completed or refused) trials.
    evaluator : callable, optional
        :class:`Objective`'s evaluator.
    progress : bool
        Show a progress bar (trials, best objective, time left) on stderr.
    """
    from optuna.study import MaxTrialsCallback
    from optuna.trial import TrialState

    study = open_study(spec)
    if _finished(study) >= n_trials:
        return
    callbacks = [MaxTrialsCallback(n_trials, states=(TrialState.COMPLETE, TrialState.PRUNED))]
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=n_trials, initial=_finished(study), unit="trial",
                   desc=spec.study_name, dynamic_ncols=True)

        def show(st, _trial):
            bar.n = min(_finished(st), n_trials)
            if spec.sampler != "nsga2":
                bar.set_postfix_str(_best_text(st, spec.reading))
            bar.refresh()
        callbacks.append(show)
    try:
        study.optimize(Objective(spec, evaluator), callbacks=callbacks, catch=())
    finally:
        if bar is not None:
            bar.close()


def run_study(spec: StudySpec, n_trials: int, jobs: int = 1, *, evaluator=None,
              progress: bool = False):
    """Run (or resume) a study to `n_trials` finished trials with `jobs` workers.

    Dead trials of an earlier run are recovered first
    (:func:`recover_dead_trials`); the other workers are processes of their
    own on the same storage; this process is one of them and shows the
    progress.  With several workers a study may end up to ``jobs - 1`` trials
    past its target (each checks the count when it starts a trial), and its
    sequence of samples depends on their timing: only a study of one worker
    is re-created exactly from its seed.

    Parameters
    ----------
    spec : StudySpec
        The study.
    n_trials : int
        Its target of finished (completed or refused) trials.
    jobs : int
        Workers (this process and ``jobs - 1`` more).
    evaluator : callable, optional
        :class:`Objective`'s evaluator (default the claims' own checks).
    progress : bool
        Show the progress bar.

    Returns
    -------
    optuna.Study
    """
    import multiprocessing

    if n_trials < 0 or jobs < 1:
        raise ValueError(f"trials must be >= 0 and jobs >= 1, got {n_trials} and {jobs}")
    study = open_study(spec)
    recover_dead_trials(study, open_storage(spec.storage))
    ctx = multiprocessing.get_context("spawn")
    others = [ctx.Process(target=worker, args=(spec, n_trials, evaluator, False))
              for _ in range(jobs - 1)]
    for p in others:
        p.start()
    try:
        worker(spec, n_trials, evaluator, progress)
    finally:
        for p in others:
            p.join()
    return open_study(replace(spec))


def seconds_text(s: float) -> str:
    """A duration in words.

    Parameters
    ----------
    s : float
        Seconds.

    Returns
    -------
    str

    Examples
    --------
    >>> seconds_text(90), seconds_text(600), seconds_text(7200)
    ('90 s', '10 min', '2.0 h')
    """
    if not math.isfinite(s):
        return "?"
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.0f} min" if s < 5400 else f"{s / 3600:.1f} h"
