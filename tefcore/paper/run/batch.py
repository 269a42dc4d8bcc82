"""``tefcore batch``: many parameter sets through the notebooks, one comparison report.

:func:`batch` reads a batch file (:mod:`tefcore.paper.run.batch_spec`: named
runs, each with notebook parameters, a base configuration, a subset of the
notebooks, grids), checks everything before anything runs, and executes
every run's notebooks with papermill in **one** pool of ``jobs`` workers
(default: the cores).  The pool's tasks are single notebooks, run by run,
so two cores stay busy whether a batch has many small runs or one run of
eight notebooks, and no pool is nested in another (each notebook's own
sweeps keep ``n_jobs = 1`` unless a run sets it).  A papermill kernel is
not reused between tasks: a notebook's globals, module state and caches
would leak into the next run's results.  What reuse would save was
measured: a fresh kernel executing one empty cell takes 1.3 s, one that
imports ``tefcore.paper.notebook_tools`` 2.8 s, against 10-16 s for
notebook 04 (up to 110 s where refinement has to decide identities).

Output layout (``--out OUT``)::

    OUT/index.html, OUT/index.md     the comparison report
    OUT/runs.csv                     one row per run: parameters, claims score, headlines
    OUT/headlines.csv                the headline results, one row per run, figure and result
    OUT/figures/<figure>.png         per figure, the runs' flutter root and TEF branch overlaid
    OUT/<run>/                       each run as `tefcore reproduce` writes it (report.html
                                     with a link back), and batch_run.json: its inputs

A run that fails (a notebook raises, a kernel dies) is recorded with its
error and the batch goes on; the exit status is 1 when any run failed.
Claims worse than their recorded status do not fail a run: a batch changes
parameters on purpose, and the report shows the claims' scores side by side.

**Resuming.**  Running the same batch again skips every run whose recorded
inputs (:mod:`tefcore.paper.run.batch_state`: parameters, configuration file
content, tefcore version and code, notebook cells, reference data) are
unchanged and that finished; a failed or interrupted run is recomputed; a
run folder whose recorded inputs differ is refused before anything runs,
naming what changed (``force=True`` / ``--force`` recomputes it).  A batch
holds ``OUT/batch.lock`` while it runs: a second batch into the same folder
fails at once.
"""

from __future__ import annotations

import os
import shutil
import sys
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path

from ...errors import OutputError, error_text
from ...safe_io import FileLock, check_output_file, check_output_folder
from .batch_report import write_comparison
from .batch_spec import RunSpec, load_batch
from .batch_state import plan_runs, read_record, write_record
from .kernel_guard import stop_notebooks, watch_children
from .notebook_files import NOTEBOOKS, notebooks_dir
from .reproduce import (
    BASELINE_NOTEBOOK,
    KERNEL_NAME,
    NotebookRun,
    baseline_blade,
    check_reference_data,
    check_reproduce_folder,
    check_tools,
    ensure_kernel,
    execute_notebook,
    finish_report,
    prepare_params,
)

__all__ = ["BatchResult", "RunOutcome", "batch", "run_parameters"]

#: Files of a run folder that a recomputation replaces (besides the notebooks' folders).
_RUN_FILES = ("report.md", "report.html", "claims.csv", "mdart_modes.csv",
              "mdart_frequency_checks.csv", "mdart_fanplot.png")


@dataclass
class RunOutcome:
    """How one run of a batch went.

    Parameters
    ----------
    spec : RunSpec
        The run.
    action : str
        What the batch did: ``"new"``, ``"retry"``, ``"redo"`` (computed) or
        ``"skip"`` (unchanged, its earlier results kept).
    status : str
        ``"ok"`` (every notebook ran) or ``"failed"``.
    error : str
        Why it failed (the notebooks' errors, or the report's); ``""``.
    seconds : float
        Wall time of its notebooks and report [s] (0 when skipped).
    notebooks : list of dict
        Each notebook's ``name``, ``status``, ``error`` and ``seconds``.
    claims : dict
        ``passed``, ``total`` (validation claims) and ``worse`` (claims
        worse than recorded).
    """

    spec: RunSpec
    action: str
    status: str = "not run"
    error: str = ""
    seconds: float = 0.0
    notebooks: list = field(default_factory=list)
    claims: dict = field(default_factory=dict)


@dataclass
class BatchResult:
    """What :func:`batch` did.

    Parameters
    ----------
    out : pathlib.Path
        The output folder.
    runs : list of RunOutcome
        One per run, in the batch file's order.
    paths : tuple of pathlib.Path
        The comparison report's files (``index.md``, ``index.html``,
        ``runs.csv``), or ``()`` for a dry run.
    seconds : float
        Wall time of the batch [s].
    """

    out: Path
    runs: list
    paths: tuple = ()
    seconds: float = 0.0

    @property
    def exit_code(self) -> int:
        """1 when a run failed, else 0 (a dry run's runs are ``"not run"``)."""
        return 1 if any(r.status == "failed" for r in self.runs) else 0


def run_parameters(spec: RunSpec, out: Path, nb_dir=None) -> dict:
    """The papermill parameters of each of a run's notebooks.

    Parameters
    ----------
    spec : RunSpec
        The run.
    out : pathlib.Path
        The batch's output folder (absolute); each notebook writes into
        ``out/<run>/<notebook>``.
    nb_dir : path, optional
        The notebooks' folder.

    Returns
    -------
    dict
        ``{notebook: {name: value}}`` with ``output_dir``, ``config`` (when
        the run has a base configuration) and ``interactive = False`` where
        the notebook has the explorer (:func:`tefcore.paper.run.reproduce.prepare_params`).
    """
    params = prepare_params([spec.params], spec.notebooks, Path(nb_dir or notebooks_dir()))
    for nb in spec.notebooks:
        params[nb]["output_dir"] = str(out / spec.name / nb)
        if spec.config is not None:
            params[nb]["config"] = spec.config
    return params


def _check_outputs(out: Path, specs, nb_dir: Path) -> None:
    """Every destination checked before anything runs (links, tracked files, folders)."""
    if out.exists() or out.is_symlink():
        check_output_folder(out, "batch --out")
    for f in ("index.md", "index.html", "runs.csv", "headlines.csv"):
        if (out / f).exists() or (out / f).is_symlink():
            check_output_file(out / f, "batch output")
    if (out / "figures").is_symlink():
        raise OutputError(f"batch output folder {out / 'figures'} is a symbolic link")
    for spec in specs:
        folder = out / spec.name
        if folder.is_symlink():
            raise OutputError(f"run folder {folder} is a symbolic link; tefcore does not "
                              "write through links")
        check_reproduce_folder(folder, spec.notebooks, nb_dir)
        for sub in (folder / "notebooks", *(folder / nb for nb in NOTEBOOKS)):
            if sub.is_symlink():
                raise OutputError(f"{sub} is a symbolic link; tefcore does not write "
                                  "through links")


def _clear(folder: Path) -> None:
    """Remove a run's earlier results (only the files and folders a run writes)."""
    for sub in (folder / "notebooks", *(folder / nb for nb in NOTEBOOKS)):
        if sub.is_dir() and not sub.is_symlink():
            shutil.rmtree(sub)
    for f in _RUN_FILES:
        if (folder / f).is_file():
            (folder / f).unlink()


def _blade_config(spec: RunSpec, params: dict):
    """The run's base configuration with the overrides all its notebooks share."""
    from ..figures.runs import base_config

    per_nb = [params[nb].get("overrides") or {} for nb in spec.notebooks]
    common = {k: v for k, v in per_nb[0].items() if all(o.get(k) == v for o in per_nb[1:])}
    cfg = base_config("thin_airfoil", config=spec.config)
    return cfg.with_overrides(common) if common else cfg


def _finish_run(out: Path, spec: RunSpec, params: dict, runs: list[NotebookRun],
                outcome: RunOutcome, inputs: dict) -> None:
    """Blade checks, claims and the run's report; the record; never raises for the run."""
    folder = out / spec.name
    errors = [f"{r.name}: {r.error}" for r in runs if r.status != "ok"]
    try:
        checks = (baseline_blade(folder, _blade_config(spec, params))
                  if BASELINE_NOTEBOOK in spec.notebooks else None)
        done = finish_report(folder, runs, spec.notebooks, checks,
                             title=f"tefcore batch run {spec.name}", up="../index.html")
        outcome.claims = {"passed": int(done["passed"]), "total": int(done["total"]),
                          "worse": len(done["worse"])}
    except Exception as exc:        # recorded; the batch goes on with the other runs
        errors.append(f"report: {error_text(exc, 300)}")
    outcome.status = "failed" if errors else "ok"
    outcome.error = "; ".join(errors)
    outcome.notebooks = [{"name": r.name, "status": r.status, "error": r.error,
                          "seconds": round(r.seconds, 1)} for r in runs]
    write_record(folder, spec.name, inputs, outcome.status, error=outcome.error,
                 notebooks=outcome.notebooks, claims=outcome.claims)


def _from_record(out: Path, plan) -> RunOutcome:
    rec = read_record(out / plan.spec.name) or {}
    return RunOutcome(plan.spec, "skip", rec.get("status", "ok"), rec.get("error", ""), 0.0,
                      rec.get("notebooks", []), rec.get("claims", {}))


def batch(runs_file, out, *, jobs: int | None = None, force: bool = False, only=None,
          params=None, progress: bool = True, nb_dir=None, dry_run: bool = False,
          kernel_name: str = KERNEL_NAME) -> BatchResult:
    """Run a batch file's runs into ``out`` and write the comparison report.

    Parameters
    ----------
    runs_file : path
        The batch file (:mod:`tefcore.paper.run.batch_spec`).
    out : path
        The output folder (created; checked before anything runs).
    jobs : int, optional
        Notebooks executed at once, over all runs (default: the cores).
    force : bool
        Recompute runs whose recorded inputs differ, instead of refusing.
    only : sequence of str, optional
        Keep only these notebooks in every run.
    params : list of dict, optional
        Parameter layers over every run (``-p``, ``--params``).
    progress : bool
        A progress bar on stderr.
    nb_dir : path, optional
        The notebooks' folder (default
        :func:`~tefcore.paper.run.notebook_files.notebooks_dir`).
    dry_run : bool
        Check and plan only: print what would run, run nothing, write nothing.
    kernel_name : str
        Jupyter kernel.

    Returns
    -------
    BatchResult
        The runs' outcomes; its ``exit_code`` is 1 when any run failed.

    Raises
    ------
    tefcore.paper.run.batch_spec.BatchFileError
        A bad batch file (before anything runs).
    tefcore.paper.run.batch_state.StaleRunError
        A run folder with other recorded inputs, without ``force``.
    tefcore.errors.OutputError
        An unusable output destination, or another batch writing ``out``.
    tefcore.paper.run.reproduce.ReproductionError
        Missing papermill/nbconvert or reference data.
    """
    start = time.perf_counter()
    nb_dir = Path(nb_dir or notebooks_dir()).resolve()
    specs = load_batch(runs_file, only=only, extra_params=params, nb_dir=nb_dir)
    out = Path(out).resolve()
    _check_outputs(out, specs, nb_dir)
    check_tools("tefcore batch")
    check_reference_data()
    params_of = {s.name: run_parameters(s, out, nb_dir) for s in specs}
    if dry_run:
        return _dry_run(out, specs, params_of, force, nb_dir)
    check_output_folder(out, "batch --out", create=True)
    with FileLock(out / "batch", "batch folder"), watch_children():
        plans = plan_runs(out, specs, lambda s: params_of[s.name], force=force, nb_dir=nb_dir)
        ensure_kernel(kernel_name)
        todo, outcomes = _start_runs(out, plans)
        _execute_runs(out, todo, params_of, outcomes, nb_dir=nb_dir, kernel_name=kernel_name,
                      jobs=_pool_size(todo, params_of, jobs), progress=progress)
        done = [outcomes[p.spec.name] for p in plans]
        paths = write_comparison(out, done)
    result = BatchResult(out, done, paths, time.perf_counter() - start)
    failed = [r.spec.name for r in done if r.status != "ok"]
    print(f"{len(done)} runs: {len(todo)} computed, {len(done) - len(todo)} skipped, "
          f"{len(failed)} failed; wrote {paths[1]} in {result.seconds:.1f} s")
    if failed:
        print(f"tefcore batch: run(s) failed: {', '.join(failed)}", file=sys.stderr)
    return result


def _dry_run(out, specs, params_of, force, nb_dir) -> BatchResult:
    """Print what each run would do (new, skip, retry, recompute); run and write nothing."""
    plans = plan_runs(out, specs, lambda s: params_of[s.name], force=force, nb_dir=nb_dir)
    for p in plans:
        print(f"{p.spec.name:40s} {p.action:6s} {' '.join(p.spec.notebooks)}"
              f"{'  (' + p.reason + ')' if p.reason else ''}")
        if p.note:
            print(f"tefcore batch: note: {p.note}", file=sys.stderr)
    return BatchResult(out, [RunOutcome(p.spec, p.action) for p in plans])


def _start_runs(out: Path, plans) -> tuple[list, dict]:
    """The runs to compute, their folders cleared and recorded as running; every run's outcome
    (a skipped one read from its record)."""
    todo = [p for p in plans if p.action != "skip"]
    outcomes = {p.spec.name: (_from_record(out, p) if p.action == "skip"
                              else RunOutcome(p.spec, p.action)) for p in plans}
    for p in plans:
        if p.action == "skip":
            print(f"{p.spec.name:40s} skipped: inputs unchanged since it finished")
        if p.note:
            print(f"tefcore batch: note: {p.note}", file=sys.stderr)
    for p in todo:
        folder = out / p.spec.name
        folder.mkdir(parents=True, exist_ok=True)
        _clear(folder)
        write_record(folder, p.spec.name, p.inputs, "running")
    return todo, outcomes


def _pool_size(todo, params_of, jobs) -> int:
    """Notebooks executed at once: ``jobs`` (default the cores), at most the notebooks;
    a note when their sweep processes (``n_jobs``) would share the cores."""
    n_tasks = sum(len(p.spec.notebooks) for p in todo)
    jobs = max(1, min(n_tasks or 1, jobs or os.cpu_count() or 1))
    inner = max((int(params_of[p.spec.name][nb].get("n_jobs") or 1) for p in todo
                 for nb in p.spec.notebooks), default=1)
    if jobs * inner > (os.cpu_count() or 1):
        print(f"tefcore batch: note: {jobs} notebooks at once, each with up to {inner} "
              f"sweep processes (n_jobs), on {os.cpu_count()} cores", file=sys.stderr)
    return jobs


def _execute_runs(out: Path, todo, params_of, outcomes, *, nb_dir, kernel_name, jobs,
                  progress) -> None:
    """Every notebook of the runs in one pool; a run is finished (claims, report, record)
    as soon as its last notebook is.  Ctrl-C cancels the rest and stops the kernels."""
    from tqdm.auto import tqdm

    pending = {p.spec.name: len(p.spec.notebooks) for p in todo}
    results: dict[str, dict] = {p.spec.name: {} for p in todo}
    by_name = {p.spec.name: p for p in todo}
    with ThreadPoolExecutor(max_workers=jobs) as pool, \
            tqdm(total=sum(pending.values()), desc="batch", unit="nb", disable=not progress,
                 file=sys.stderr) as bar:
        futures = {}
        for p in todo:
            for nb in p.spec.notebooks:
                fut = pool.submit(execute_notebook, nb, nb_dir / f"{nb}.ipynb",
                                  out / p.spec.name, params_of[p.spec.name][nb], kernel_name)
                futures[fut] = (p.spec.name, nb)
        try:
            for fut in as_completed(futures):
                name, nb = futures[fut]
                results[name][nb] = fut.result()
                bar.update()
                pending[name] -= 1
                if pending[name]:
                    continue
                p = by_name[name]
                runs = [results[name][n] for n in p.spec.notebooks]
                outcome = outcomes[name]
                _finish_run(out, p.spec, params_of[name], runs, outcome, p.inputs)
                outcome.seconds = sum(r.seconds for r in runs)
                bar.write(f"{name:40s} {outcome.status:6s} {outcome.seconds:6.1f} s "
                          f"(notebook time)  {outcome.error}")
        except BaseException:   # Ctrl-C: cancel the rest, stop the running kernels
            stop_notebooks(futures)
            raise
