"""``tefcore reproduce``: run the notebooks, check the paper's claims, write the report.

:func:`reproduce` executes the numbered notebooks (:mod:`tefcore.paper.run.notebook_files`)
with papermill into an output folder -- several at once, up to the cores --
each with its own parameters (:mod:`tefcore.paper.run.params`), exports each
executed notebook to HTML (nbconvert), collects the claims tables and the
figures the notebooks wrote, and renders the report
(:mod:`tefcore.paper.run.report`).  It works from an installed wheel in any
folder: the notebooks and the reference data ship with the package.

Output layout (``--out OUT``)::

    OUT/report.md, OUT/report.html, OUT/claims.csv
    OUT/reproduction.json             what ran: the notebooks, their parameters, the version
                                      (it marks the folder as a reproduction's)
    OUT/attribution.csv               what would flip each failing validation claim
                                      (tefcore.paper.attribution.differences; skipped with
                                      attribution=False, --no-attribution)
    OUT/mdart_modes.csv, OUT/mdart_frequency_checks.csv, OUT/mdart_fanplot.png
                                      with notebook 01 (the baseline blade) only
    OUT/notebooks/<name>.ipynb, OUT/notebooks/<name>.html   executed notebooks
    OUT/<name>/                       each notebook's CSVs, PNGs (+ JSON captions), claims.csv
    OUT/claims-variants.csv, OUT/variants/   the claims on the other packaged variant
                                      (:mod:`tefcore.paper.run.variant_runs`)

The notebooks run on their ``config`` parameter (default ``mdart``); the claims
of the same figures are checked meanwhile on the other packaged variant
(``mdart-fig6``, or ``mdart`` when the notebooks run on ``mdart-fig6``).

The folder is written beside as ``OUT.incomplete`` and swapped in whole when
the run has finished, one run at a time
(:mod:`tefcore.paper.run.output_folder`); the processes a run starts end
with it (:func:`tefcore.paper.run.kernel_guard.watch_children`).

The exit code is 0 when every notebook ran and no validation claim is worse
than its recorded status (on either variant), 1 otherwise; a run with other
parameters than the recorded computation's is a what-if, never a regression
(:mod:`tefcore.paper.run.outcome`).  Missing reference data is an error
before anything runs (never "0 claims passed of 0").
"""

from __future__ import annotations

import os
import queue
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ...config.io import load_config
from ...errors import TefcoreError
from ...safe_io import atomic_output, atomic_write_text
from ..claims.files import ReferenceDataError, reference_dir
from ..claims.reference import load_claims
from ..claims.validation import claims_score, worse_than_recorded
from ..figures.plotting import deterministic_matplotlib, savefig
from .attribution_phase import attribute_claims, attribution_args
from .kernel_guard import stop_notebooks, watch_children
from .notebook_files import (
    NOTEBOOK_FIGURES,
    NOTEBOOK_SECONDS,
    NOTEBOOKS,
    check_parameters,
    notebook_parameters,
    notebooks_dir,
    resolve_notebook,
)
from .outcome import (
    previous_claims,
    print_summary,
    run_record,
    same_parameters,
    status_changes,
    what_if,
)
from .output_folder import ReproductionFolder, check_reproduce_folder, source_checkout
from .param_values import check_notebook_values
from .params import merge_params
from .report import build_report, write_report
from .variant_runs import (
    base_variant,
    finish_variant_runs,
    start_variant_runs,
    stop_variant_runs,
)

__all__ = ["BASELINE_NOTEBOOK", "KERNEL_NAME", "NotebookRun", "ReproductionError",
           "attribute_claims", "baseline_blade", "check_reference_data",
           "check_reproduce_folder", "check_tools", "collect_claims", "ensure_kernel",
           "execute_notebook", "export_html", "finish_report", "prepare_params",
           "regressions", "reproduce", "run_notebooks", "score", "source_checkout"]

KERNEL_NAME = "python3"
#: The notebook whose run also writes the baseline blade's files at the top of the
#: output folder (:func:`baseline_blade`): the blade's correlation.
BASELINE_NOTEBOOK = "01_baseline_mdart_correlation"
#: The progress bars of the run's phases: what, how far, the time spent and left.
BAR_FORMAT = "{desc} {percentage:3.0f}%|{bar:20}| [{elapsed}<{remaining}]{postfix}"
#: What to install when the notebook tools are missing.
INSTALL_HINT = 'python -m pip install "tefcore[notebooks]"'


class ReproductionError(TefcoreError, RuntimeError):
    """A reproduction that cannot run (missing tools or reference data) or checked nothing."""


@dataclass
class NotebookRun:
    """How one notebook's execution went.

    Parameters
    ----------
    name : str
        The notebook (``"04_cg_offset"``).
    status : str
        ``"not run"`` until executed, then ``"ok"`` or ``"failed"``.
    error : str
        Why it failed (the exception's type and last line) and whether its
        HTML export failed; ``""`` when neither.
    seconds : float
        Wall-clock time of the execution and HTML export [s]; printed, never
        written into the report (two runs must write identical reports).
    parameters : dict
        The papermill parameters it was executed with (after merging the
        layers of :mod:`tefcore.paper.run.params`).
    """

    name: str
    status: str = "not run"
    error: str = ""
    seconds: float = 0.0
    parameters: dict = field(default_factory=dict)


def check_tools(command: str = "tefcore reproduce"):
    """papermill and nbconvert, or a :class:`ReproductionError` saying what to install.

    Parameters
    ----------
    command : str
        The command that needs them, for the message.

    Returns
    -------
    module
        :mod:`papermill`.
    """
    try:
        import nbconvert  # noqa: F401  (the HTML export; checked before anything runs)
        import papermill
    except ImportError as exc:
        raise ReproductionError(f"{command} needs {exc.name}: {INSTALL_HINT}") from None
    return papermill


def ensure_kernel(name: str = KERNEL_NAME) -> None:
    """Register the current interpreter's ipykernel as ``name`` if there is no such kernelspec.

    Parameters
    ----------
    name : str
        The Jupyter kernel the notebooks are executed with.
    """
    from jupyter_client.kernelspec import NoSuchKernel, get_kernel_spec

    try:
        get_kernel_spec(name)
    except NoSuchKernel:
        from ipykernel.kernelspec import install

        install(user=True, kernel_name=name)


def _export_html(executed: Path) -> None:
    """``executed`` (.ipynb) as a standalone HTML page beside it, readable offline
    (:func:`tefcore.paper.run.notebook_page.notebook_html`)."""
    from .notebook_page import notebook_html

    atomic_write_text(executed.with_suffix(".html"), notebook_html(executed))


def execute_notebook(name: str, src: Path, out: Path, params: dict,
                     kernel_name: str = KERNEL_NAME, *, kernel=None,
                     export: bool = True) -> NotebookRun:
    """Execute one notebook with papermill into ``out/notebooks``; never raises for its failure.

    The kernel runs in the caller's working folder (papermill's own ``cwd``
    would change the folder of the whole process, which races between
    threads); the notebook writes its results into ``params["output_dir"]``.
    The executed notebook is exported to HTML beside it, also when it failed
    (unless ``export`` is False: the caller exports it, :func:`export_html`).

    Parameters
    ----------
    name : str
        The notebook (``"04_cg_offset"``).
    src : pathlib.Path
        The source ``.ipynb``.
    out : pathlib.Path
        Existing folder; the executed notebook goes to
        ``out/notebooks/<name>.ipynb`` (and ``.html``).
    params : dict
        Papermill parameters, including ``output_dir``.
    kernel_name : str
        Jupyter kernel (:func:`ensure_kernel`).
    kernel : tefcore.paper.run.kernels.WarmKernel, optional
        A warm kernel to execute it in (its namespace made fresh first); by
        default papermill starts a kernel of its own.
    export : bool, optional
        Export the HTML page here.

    Returns
    -------
    NotebookRun
        Its status (``"ok"`` or ``"failed"`` with the error's last line) and
        wall time.
    """
    import papermill

    run = NotebookRun(name, parameters=params)
    target = out / "notebooks" / f"{name}.ipynb"
    target.parent.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    try:
        warm = {} if kernel is None else {"km": kernel.prepare()}
        papermill.execute_notebook(
            str(src), str(target), parameters=params, kernel_name=kernel_name,
            progress_bar=False, log_output=False,
            # cwd None: the kernel runs in the caller's folder; papermill's cwd would
            # os.chdir the whole process, which races between the threads
            cwd=None, extra_arguments=["--IPKernelApp.log_level=ERROR"], **warm)
        run.status = "ok"
    except Exception as exc:      # recorded, the other notebooks still run
        run.status = "failed"
        text = str(exc).strip()
        run.error = (f"{type(exc).__name__}: {text.splitlines()[-1][:300]}" if text
                     else type(exc).__name__)
    run.seconds = time.perf_counter() - start
    if export:
        export_html(run, target)
    return run


def export_html(run: NotebookRun, target: Path) -> NotebookRun:
    """Export an executed notebook to HTML beside it; a failure is noted in ``run.error``.

    Parameters
    ----------
    run : NotebookRun
        Its execution (``seconds`` grows by the export's time).
    target : pathlib.Path
        The executed ``.ipynb``.

    Returns
    -------
    NotebookRun
        ``run``.
    """
    start = time.perf_counter()
    if target.exists():
        try:
            _export_html(target)
        except Exception as exc:  # the report links a missing page; say why
            run.error = (run.error + "; " if run.error else "") + \
                f"HTML export failed: {type(exc).__name__}"
    run.seconds += time.perf_counter() - start
    return run


def run_notebooks(out: Path, params: dict, names=NOTEBOOKS, progress: bool = True,
                  nb_dir: Path | None = None, kernel_name: str = KERNEL_NAME,
                  jobs: int | None = None, warm: bool = True,
                  stop: threading.Event | None = None) -> list[NotebookRun]:
    """Execute the notebooks with papermill into ``out``; never raises for a failing one.

    ``jobs`` notebooks run at once, the longest first
    (:data:`~tefcore.paper.run.notebook_files.NOTEBOOK_SECONDS`), so that the last
    to finish is a short one; each slot keeps one warm kernel
    (:class:`~tefcore.paper.run.kernels.WarmKernel`: started at once, its imports
    paid once, a fresh namespace for every notebook) and the HTML pages are
    exported in a thread of their own while the next notebooks run.  On
    Ctrl-C (in this thread, or ``stop`` set by the thread that got it) the
    slots take no further notebook and start no kernel, and the kernels are
    stopped (:mod:`tefcore.paper.run.kernel_guard`), warm ones included.

    Parameters
    ----------
    out : pathlib.Path
        Output folder (``out/notebooks/<name>.ipynb`` and ``.html``).
    params : dict
        ``{notebook: {name: value}}``; ``output_dir`` is set to ``out/<name>``.
    names : sequence of str
        The notebooks, in report order.
    progress : bool
        A progress bar on stderr.
    nb_dir : pathlib.Path, optional
        Source folder (default :func:`~tefcore.paper.run.notebook_files.notebooks_dir`).
    kernel_name : str
        Jupyter kernel.
    jobs : int, optional
        Notebooks executed at once (default: the number of cores, at most the
        number of notebooks).
    warm : bool, optional
        Warm kernels, one per slot (False: a fresh kernel per notebook).
    stop : threading.Event, optional
        Set by another thread to stop the run (its caller then stops the
        kernels: :func:`tefcore.paper.run.kernel_guard.stop_notebooks`); the
        notebooks not run are failed (``not run``).

    Returns
    -------
    list of NotebookRun
        In the order of ``names``.
    """
    from tqdm.auto import tqdm

    check_tools()
    nb_dir = nb_dir or notebooks_dir()
    ensure_kernel(kernel_name)
    (out / "notebooks").mkdir(parents=True, exist_ok=True)
    jobs = max(1, min(len(names), jobs or os.cpu_count() or 1))
    todo: queue.SimpleQueue = queue.SimpleQueue()
    for name in sorted(names, key=lambda n: -NOTEBOOK_SECONDS.get(n, 0.0)):
        todo.put(name)
    runs: dict = {}
    stop = threading.Event() if stop is None else stop   # set on Ctrl-C: the slots stop
    # the bar advances by each notebook's expected seconds (NOTEBOOK_SECONDS, from
    # 1 s for an unknown one) over the slots, so its estimate of the time left is
    # in seconds; it closes after the exporter, which finishes the last notebook
    cost = {n: max(1.0, NOTEBOOK_SECONDS.get(n, 1.0)) for n in names}
    with tqdm(total=sum(cost.values()), desc=f"notebooks 0/{len(names)}",
              disable=not progress, file=sys.stderr, bar_format=BAR_FORMAT) as bar, \
            ThreadPoolExecutor(max_workers=1) as exporter:
        def exported(fut):
            run = fut.result()
            runs[run.name] = run
            bar.set_description_str(f"notebooks {len(runs)}/{len(names)}", refresh=False)
            bar.set_postfix_str(run.name, refresh=False)
            bar.update(cost[run.name])

        def slot():
            _Slot(kernel_name, warm, stop).run(todo, out, params, nb_dir, exporter, exported)

        threads = [threading.Thread(target=slot, name=f"notebook slot {i}", daemon=True)
                   for i in range(jobs)]
        for t in threads:
            t.start()
        try:
            for t in threads:
                t.join()
        except BaseException:        # Ctrl-C here: the slots would run every notebook
            stop.set()
            stop_notebooks([_ThreadDone(t) for t in threads])
            raise
    # a slot that stopped early (its thread raised) leaves its notebooks not run
    return [runs.get(n) or NotebookRun(n, status="failed", error="not run") for n in names]


class _ThreadDone:
    """A thread as :func:`~tefcore.paper.run.kernel_guard.stop_notebooks` waits for it."""

    def __init__(self, thread: threading.Thread):
        self.thread = thread

    def cancel(self) -> bool:
        return False

    def done(self) -> bool:
        return not self.thread.is_alive()


class _Slot:
    """One of the notebooks executed at once: a warm kernel and the notebooks it runs.

    ``stop`` set (Ctrl-C): it takes no further notebook and starts no kernel.
    """

    def __init__(self, kernel_name, warm, stop: threading.Event):
        self.kernel_name, self.warm, self.kernel = kernel_name, warm, None
        self.stop = stop

    def _fresh_kernel(self):
        """A new warm kernel, or None (papermill's own kernel per notebook) when it fails."""
        self.close()
        if self.warm and not self.stop.is_set():
            from .kernels import WarmKernel

            try:
                self.kernel = WarmKernel(self.kernel_name, ["--IPKernelApp.log_level=ERROR"])
            except Exception:  # the notebooks still run, each in a kernel of its own
                self.kernel = None

    def close(self):
        if self.kernel is not None:
            try:
                self.kernel.shutdown()
            except Exception:  # a kernel that died already
                pass
            self.kernel = None

    def run(self, todo, out, params, nb_dir, exporter, exported):
        """Execute notebooks from ``todo`` until it is empty; each run goes to the exporter."""
        self._fresh_kernel()
        try:
            while not self.stop.is_set():
                try:
                    name = todo.get_nowait()
                except queue.Empty:
                    return
                p = dict(params.get(name, {}))
                p["output_dir"] = str((out / name).resolve())
                run = execute_notebook(name, nb_dir / f"{name}.ipynb", out, p,
                                       self.kernel_name, kernel=self.kernel, export=False)
                if self.kernel is not None and (run.status != "ok" or not self.kernel.alive()):
                    self._fresh_kernel()     # a failed notebook leaves no state behind
                exporter.submit(export_html, run, out / "notebooks" / f"{name}.ipynb") \
                    .add_done_callback(exported)
        finally:
            self.close()


def collect_claims(out: Path, names=NOTEBOOKS) -> pd.DataFrame:
    """The claims tables the notebooks wrote (``OUT/<name>/claims.csv``), concatenated.

    Parameters
    ----------
    out : pathlib.Path
        The reproduction folder.
    names : sequence of str
        The notebooks.
    """
    frames = []
    for name in names:
        path = out / name / "claims.csv"
        if path.exists() and path.stat().st_size:
            df = pd.read_csv(path, dtype=str, keep_default_na=False)
            df.insert(0, "notebook", name)
            frames.append(df)
    if not frames:
        return pd.DataFrame(columns=["notebook", "id", "figure", "statement", "expected",
                                     "computed", "status", "reason", "tag",
                                     "recorded_status"])
    return pd.concat(frames, ignore_index=True)


def regressions(claims: pd.DataFrame) -> pd.DataFrame:
    """Claims whose status is worse than recorded (empty when there are none).

    Parameters
    ----------
    claims : DataFrame
        Claims with ``status`` and ``recorded_status``.
    """
    if claims.empty:
        return claims.iloc[0:0]
    return pd.DataFrame(worse_than_recorded(claims.drop(columns=["notebook"],
                                                        errors="ignore")))


def score(claims: pd.DataFrame) -> tuple[int, int]:
    """(passed, total) of the validation claims of a claims table.

    Parameters
    ----------
    claims : DataFrame
        Claims with ``tag`` and ``status``.
    """
    if claims.empty:
        return 0, 0
    return tuple(int(v) for v in claims_score(claims.drop(columns=["notebook"],
                                                          errors="ignore")))


def baseline_blade(out: Path, cfg=None) -> pd.DataFrame:
    """Blade mode table, stated-frequency checks and fan plot at the top of ``out``.

    Writes ``mdart_modes.csv``, ``mdart_frequency_checks.csv`` and
    ``mdart_fanplot.png``.  Call from the main thread (pyplot).

    Parameters
    ----------
    out : pathlib.Path
        Existing output folder.
    cfg : tefcore.config.configuration.Config, optional
        The blade (default: the shipped MDART configuration); a batch run
        passes its own base configuration with its common overrides.

    Returns
    -------
    DataFrame
        The stated first-torsion frequencies against the model's
        (:func:`tefcore.paper.calibration.frequency_checks`).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ...structure.blade import blade_modes, fan_plot
    from ..calibration import frequency_checks

    deterministic_matplotlib()
    shipped = cfg is None
    cfg = load_config("mdart") if shipped else cfg
    with atomic_output(out / "mdart_modes.csv", newline="") as f:
        blade_modes(cfg).table().to_csv(f, index=False, float_format="%.6g")
    checks = frequency_checks(cfg)
    with atomic_output(out / "mdart_frequency_checks.csv", newline="") as f:
        checks.to_csv(f, index=False, float_format="%.6g")
    ax = fan_plot(cfg)
    ax.set_title("MDART blade (assumed properties), coupled modes" if shipped
                 else "the run's blade, coupled modes")
    savefig(ax.figure, out, "mdart_fanplot")
    plt.close(ax.figure)
    return checks


def check_reference_data() -> int:
    """Number of claims in the reference data; a :class:`ReproductionError` when there are none.

    Returns
    -------
    int
        The claims in :func:`tefcore.paper.claims.files.reference_dir`.
    """
    try:
        claims = load_claims()
    except (ReferenceDataError, FileNotFoundError, OSError) as exc:
        raise ReproductionError(f"reference data ({reference_dir()}) cannot be read: {exc}") \
            from None
    if not claims:
        raise ReproductionError(f"reference data ({reference_dir()}) holds no claims; nothing "
                                "to check")
    return len(claims)


def prepare_params(params, names, nb_dir: Path | None = None) -> dict:
    """Each notebook's papermill parameters from layers, checked against its parameters cell.

    Parameters
    ----------
    params : dict or list of dict
        ``{"all"|notebook: {name: value}}`` or a list of such layers (later
        wins, :func:`tefcore.paper.run.params.merge_params`).
    names : sequence of str
        The notebooks (full names).
    nb_dir : pathlib.Path, optional
        Their folder (default :func:`~tefcore.paper.run.notebook_files.notebooks_dir`).

    Returns
    -------
    dict
        ``{notebook: {name: value}}``, with ``interactive = False`` (the
        explorer's static figure) where a notebook has that parameter and it
        was not set.

    Raises
    ------
    ValueError
        A parameter a notebook does not declare (with a close match), a value
        it does not allow (:func:`tefcore.paper.run.param_values.check_notebook_values`),
        or a missing notebook.
    """
    nb_dir = nb_dir or notebooks_dir()
    layers = params if isinstance(params, list | tuple) else [params or {}]
    merged = merge_params(*layers, notebooks=names)
    check_parameters(merged, names, nb_dir)
    for n in names:   # the values too, before anything runs (a notebook given nothing has its own)
        if merged.get(n):
            check_notebook_values(n, merged[n], notebook_parameters(nb_dir / f"{n}.ipynb"),
                                  "-p/--params")
    out = {n: dict(merged.get(n, {})) for n in names}
    for n in names:
        if "interactive" not in out[n] and \
                "interactive" in notebook_parameters(nb_dir / f"{n}.ipynb"):
            out[n]["interactive"] = False
    return out


def _phase(desc: str, total, progress: bool):
    """A progress bar of one phase of the run (:data:`BAR_FORMAT`), on stderr."""
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=desc, disable=not progress, file=sys.stderr,
                bar_format=BAR_FORMAT)


def finish_report(out: Path, runs, names, checks: pd.DataFrame | None, *,
                  title: str = "tefcore reproduction report", up: str = "",
                  variant_runs=(), base=None, attribution: dict | None = None,
                  what_if: str = "", progress: bool = False) -> dict:
    """Collect the claims the notebooks wrote, write ``claims.csv`` and the report.

    Parameters
    ----------
    out : pathlib.Path
        The reproduction folder.
    runs : list of NotebookRun
        The notebooks' executions, in report order.
    names : sequence of str
        The notebooks run.
    checks : DataFrame or None
        The stated blade frequencies (:func:`baseline_blade`).
    title : str
        The report's title.
    up : str
        Link (relative to ``out``) to a page the report belongs to (a
        batch's comparison); ``""`` for none.
    variant_runs : sequence of tefcore.paper.run.variant_runs.VariantRun
        The other variants' claims being checked (:func:`start_variant_runs`);
        waited for here.
    base : str or None
        The notebooks' configuration (their ``config`` parameter).
    attribution : dict, optional
        Attribute the failing claims (:func:`attribute_claims`) with these
        arguments; None: no attribution.
    what_if : str
        The parameters that make the run a what-if
        (:func:`tefcore.paper.run.outcome.what_if`): its claims are not
        compared with the recorded statuses (``worse`` is empty).
    progress : bool
        A progress bar for each phase (the variants, the attribution, the
        report) on stderr.

    Returns
    -------
    dict
        ``claims`` (DataFrame), ``worse`` (claims worse than recorded),
        ``passed`` and ``total`` (validation claims), ``paths`` (report.md,
        report.html), ``variants`` (:func:`finish_variant_runs`, or None),
        ``attribution`` (its result or None).
    """
    from ... import __version__

    claims = collect_claims(out, names)
    with atomic_output(out / "claims.csv", newline="") as f:
        (claims if claims.empty else claims.drop(columns=["notebook"])).to_csv(f, index=False)
    if attribution is not None:
        with _phase("attribution", 0, progress) as bar:
            attributed = attribute_claims(out, claims, {**attribution, "progress": bar})
    else:
        attributed = None
    worse = claims.iloc[0:0] if what_if else regressions(claims)
    passed, total = score(claims)
    with _phase("other variants", len(variant_runs), progress and bool(variant_runs)) as bar:
        variants = finish_variant_runs(list(variant_runs), out, claims, base,
                                       done=lambda run: bar.update())
    with _phase("report", 2, progress) as bar:
        report = build_report(out, runs, claims, worse, figures_of=NOTEBOOK_FIGURES,
                              checks=checks, version=__version__, title=title, up=up,
                              variants=variants, what_if=what_if,
                              attribution=None if attributed is None else attributed.table,
                              attribution_source="" if attributed is None else attributed.source)
        bar.update()
        paths = write_report(report, out)
        bar.update()
    return {"claims": claims, "worse": worse, "passed": passed, "total": total,
            "paths": paths, "variants": variants, "attribution": attributed}


def _run_into(out: Path, merged: dict, names, *, nb_dir, jobs, progress, variants,
              attribution, what_if: str) -> tuple[list, dict]:
    """The notebooks, the other variant and the report, written into ``out``."""
    same, base = base_variant(merged, names)
    # the blade's files at the top belong to the baseline notebook: --only writes
    # what the chosen notebooks make; the other variant's claims run beside
    figures = [f for n in names for f in NOTEBOOK_FIGURES[n]]
    vruns = start_variant_runs(out, base, figures) if variants and same else []
    try:
        # the notebooks (their kernels starting and importing) run while this
        # thread draws the blade baseline (pyplot: the main thread)
        stop = threading.Event()
        with ThreadPoolExecutor(max_workers=1) as runner:
            running = runner.submit(run_notebooks, out, merged, names, progress=progress,
                                    nb_dir=nb_dir, jobs=jobs, stop=stop)
            try:
                checks = (baseline_blade(out, None if base is None else load_config(base))
                          if BASELINE_NOTEBOOK in names else None)
                runs = running.result()
            except BaseException:   # Ctrl-C: the runner would wait for every notebook
                stop.set()                    # the slots take no further notebook, no kernel
                stop_notebooks([running])     # the running ones' kernels stopped
                raise
        done = finish_report(out, runs, names, checks, variant_runs=vruns, base=base,
                             attribution=attribution_args(attribution, merged, jobs),
                             what_if=what_if, progress=progress)
    finally:
        stop_variant_runs(vruns)
    return runs, done


def reproduce(out, params=None, notebooks=None, progress: bool = True,
              nb_dir: Path | None = None, jobs: int | None = None,
              variants: bool = True, attribution: bool | dict = True) -> int:
    """Run the notebooks into ``out`` and write the report; return the exit code.

    ``out`` is locked for the run, written beside as ``OUT.incomplete`` and
    swapped in whole at the end (:class:`~tefcore.paper.run.output_folder.ReproductionFolder`):
    a second run into the same folder is refused, a killed run leaves the
    previous result, and the processes the run started end with it
    (:func:`~tefcore.paper.run.kernel_guard.watch_children`).

    Parameters
    ----------
    out : path
        Output folder (checked before anything runs: :func:`check_reproduce_folder`;
        missing, empty, or a previous reproduction, which is replaced).
    params : dict or list of dict, optional
        ``{"all"|notebook: {name: value}}`` or a list of such layers (later
        wins, :func:`tefcore.paper.run.params.merge_params`).  Any parameter
        but ``n_jobs``, ``interactive`` and a packaged ``config`` makes the
        run a what-if (:mod:`tefcore.paper.run.outcome`): its claims are
        compared with the previous run of the same parameters in ``out``,
        never with the recorded statuses.
    notebooks : sequence of str, optional
        Run only these (``"04"``, ``"04_cg_offset"`` ...).
    progress : bool
        A progress bar for each phase, with the time left.
    nb_dir : path, optional
        The notebooks' folder.
    jobs : int, optional
        Notebooks executed at once (default: the cores); also the attribution's
        processes.
    variants : bool
        Meanwhile check the same figures' claims on the other packaged variant
        (:mod:`tefcore.paper.run.variant_runs`), when the notebooks all run on a
        packaged variant (``config`` None, ``"mdart"`` or ``"mdart-fig6"``).
    attribution : bool or dict
        Attribute the failing validation claims after the notebooks
        (:mod:`tefcore.paper.attribution.differences`, ``OUT/attribution.csv``; its CPU
        cost is printed): True, False, or a dict of further arguments of
        :func:`tefcore.paper.attribution.differences.attribute` (``lever_list``,
        ``pairs``).

    Returns
    -------
    int
        0, or 1 when a notebook failed, a claim is worse than recorded (on
        any variant; never for a what-if), a variant's check failed, or no
        claim was checked.

    Raises
    ------
    ReproductionError
        Missing papermill/nbconvert or reference data (before anything runs).
    tefcore.errors.OutputError
        ``out`` is refused, or another run holds it.
    """
    from ... import __version__

    names = [resolve_notebook(n) for n in notebooks] if notebooks else list(NOTEBOOKS)
    nb_dir = (nb_dir or notebooks_dir())
    out = check_reproduce_folder(out, names, nb_dir)
    check_tools()
    check_reference_data()
    # the kernelspec looked up here, in this thread, before the notebooks'
    # thread starts: jupyter_client imports IPython for its kernel directories,
    # and matplotlib's first canvas (the fan plot, drawn here while the
    # notebooks start) reads IPython.version_info if IPython is in
    # sys.modules -- a half-imported one raised AttributeError (the import is
    # traced to jupyter_client.kernelspec._kernel_dirs_default)
    ensure_kernel()
    merged = prepare_params(params, names, nb_dir)
    change = what_if(merged, names)
    record = run_record(names, merged, __version__, change)
    start = time.perf_counter()
    with ReproductionFolder(out) as folder, watch_children():
        try:
            runs, done = _run_into(folder.staging, merged, names, nb_dir=nb_dir, jobs=jobs,
                                   progress=progress, variants=variants,
                                   attribution=attribution, what_if=change)
        except KeyboardInterrupt:
            print(f"tefcore reproduce: {out} is unchanged; what the run wrote is in "
                  f"{folder.staging}", file=sys.stderr)
            raise
        changes = (status_changes(done["claims"], previous_claims(out))
                   if same_parameters(folder.previous, record) else None)
        folder.commit(record)
    unclean = print_summary(runs, done, time.perf_counter() - start, out, what_if=change,
                       changes=changes)
    if done["claims"].empty and any(NOTEBOOK_FIGURES[n] for n in names):
        print("tefcore reproduce: no claim was checked", file=sys.stderr)
        return 1
    return 1 if unclean else 0
