"""The paper layer's subcommands of ``tefcore``: ``reproduce``, ``batch``, ``notebooks``, ``infer``.

:func:`add_commands` adds them to the ``tefcore`` parser (:mod:`tefcore.cli`
calls it); the work is done by :mod:`tefcore.paper.run.reproduce`,
:mod:`tefcore.paper.run.batch` and :mod:`tefcore.paper.run.notebook_files`, imported
only when a command runs.
"""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_commands", "cmd_batch", "cmd_notebooks", "cmd_reproduce"]

_REPRODUCE = """\
Execute the numbered notebooks with papermill into OUT (several at once, up to
the cores), check every claim of the paper they cover, and write
OUT/report.html (self-contained, figures embedded), OUT/report.md and
OUT/claims.csv; each executed notebook also as OUT/notebooks/NAME.html.

Then it attributes every failing validation claim: what would flip each one
(OUT/attribution.csv, and "why we differ" in the report).  On the default
rotor it reads the package's attribution, a search made with this code and
data (tefcore/paper/reference_data/attribution-mdart.csv): the claims and
their verdicts are the same, so the search's answer is.  A what-if, another
variant, or edited code or data searches: each assumption and model option
is moved within its plausible range (about 1200 s of CPU for 15 failing
claims: about 15 minutes on two cores); --attribute-again searches on
the default rotor too, --no-attribution skips it.  Each phase shows a
progress bar with the time left, and the attribution prints its cost.

OUT must be new, empty or a previous reproduction, which is replaced whole
when the run has finished (written beside as OUT.incomplete meanwhile: a
stopped run leaves the previous result); one run at a time writes OUT.

Works from an installed wheel in any folder: the notebooks and the reference
data ship with tefcore.  Exit status 1 when a notebook fails, a claim is worse
than its recorded status, or no claim was checked.  A run with parameters
that change results (-p overrides, -p config my.toml, -p n_points ...) is a
what-if: its claims are compared with the previous run of the same
parameters in OUT, never called worse than recorded.

The notebooks run on the default configuration, mdart, or on another with
'-p config NAME' (a packaged one, e.g. mdart-fig6, the flap system's inertia
fitted to Fig. 6; or a TOML file).  Meanwhile the claims of the same figures
are checked on the other packaged variant (paper sweep values, no other
notebook parameter; --no-variants skips it): OUT/claims-variants.csv and the
report's table of both variants, with the physics of each difference and the
conflict Fig. 6's calibration brings out.

examples:
  tefcore reproduce --out out
  tefcore reproduce --only 04 --out out -p n_jobs 2
  tefcore reproduce --out out-fig6 -p config mdart-fig6
  tefcore reproduce --only 04 07 --out out --no-attribution
  tefcore reproduce -p overrides "{flight.advance_ratio: 0.2}" -p 03:n_points 8
"""

_BATCH = """\
Run many parameter sets through the notebooks and compare them.  RUNS.yaml
names runs; each has notebook parameters (as in 'reproduce --params'), and
optionally a base configuration (config: FILE.toml), a subset of the
notebooks and a grid (one run per combination of the listed values):

  notebooks: [03, 04]
  grid: {03:overrides.flap.cg_offset: [0.0, 0.15],
         04:overrides.flap.overhang: [0.2, 0.29, 0.4]}

The runs' notebooks execute in one pool (--jobs at once, default: the
cores), each run into OUT/RUN/ with its own report.  OUT/index.html (+
index.md, runs.csv, headlines.csv) compares the runs: their parameters,
claims scores, the flutter onset and growth per figure, and the runs' curves
overlaid.  Everything in RUNS.yaml is checked before anything runs.

Run it again to resume: unchanged finished runs are skipped, failed ones
recomputed; a run folder whose recorded inputs (parameters, configuration,
tefcore version and code, notebook cells, reference data) differ is refused
unless --force.  Exit status 1 when a run failed.

examples:
  tefcore batch examples/class_assignment.yaml --out class
  tefcore batch examples/flap_inertia_doubled.yaml --out review --only 04 05
  tefcore batch runs.yaml --out quick -p n_points 4 --dry-run
"""

_NOTEBOOKS = """\
List the numbered notebooks, or copy them for editing: --copy DIR writes each
notebook (.ipynb, with its outputs) and its jupytext source (.py) into DIR,
never overwriting a file there.  Open the copies in Jupyter; run them with
'tefcore reproduce' on your copies by setting TEFCORE_NOTEBOOKS=DIR.

examples:
  tefcore notebooks
  tefcore notebooks --copy my_notebooks
  tefcore notebooks --copy my_notebooks --only 04 05
"""


#: What a notebook without a paper figure is about.
_NO_FIGURE = {"08_assumptions": "what each assumption does to the results",
              "09_design_maps": "stability maps over two parameters (beyond the paper)",
              "10_unsteady": "unsteady airloads and dynamic inflow (beyond the paper)",
              "11_watch_it_flutter": "the Floquet growth watched in the time domain (beyond the "
                                     "paper)",
              "12_inferred_rotor": "which rotor the paper's statements describe: a seeded "
                                   "study, mdart-inferred"}


def cmd_reproduce(args) -> int:
    """Run ``tefcore reproduce`` with parsed arguments; return the exit status.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``reproduce`` options: ``out`` (output folder),
        ``params`` (YAML parameter file or None), ``param`` (``-p NAME
        VALUE`` pairs), ``only`` (notebooks to run or None), ``jobs``
        (notebooks executed at once), ``no_variants``, ``no_progress``,
        ``no_attribution`` and ``attribute_again``.

    Returns
    -------
    int
        0 when every notebook ran and no claim is worse than its recorded
        status, 1 otherwise (:func:`tefcore.paper.run.reproduce.reproduce`).
    """
    from .params import load_params_file, parse_cli_params
    from .reproduce import reproduce

    # later layers win: file "all" < file notebook < -p all < -p notebook
    layers = [load_params_file(args.params)] if args.params else []
    layers.append(parse_cli_params([tuple(p) for p in args.param or ()]))
    return reproduce(Path(args.out), params=layers, notebooks=args.only,
                     progress=not args.no_progress, jobs=args.jobs,
                     variants=not args.no_variants,
                     attribution=False if args.no_attribution
                     else {"again": True} if args.attribute_again else True)


def cmd_batch(args) -> int:
    """Run ``tefcore batch`` with parsed arguments; return the exit status.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``batch`` options: ``runs`` (the batch file), ``out``,
        ``jobs``, ``force``, ``only``, ``params`` (a YAML parameters file
        over every run), ``param`` (``-p NAME VALUE`` pairs), ``dry_run`` and
        ``no_progress``.

    Returns
    -------
    int
        0 when every run ran, 1 when one failed
        (:func:`tefcore.paper.run.batch.batch`).
    """
    from .batch import batch
    from .params import load_params_file, parse_cli_params

    if args.jobs is not None and args.jobs < 1:
        raise ValueError(f"--jobs {args.jobs}: must be at least 1")
    layers = [load_params_file(args.params)] if args.params else []
    layers.append(parse_cli_params([tuple(p) for p in args.param or ()]))
    result = batch(args.runs, args.out, jobs=args.jobs, force=args.force, only=args.only,
                   params=layers, progress=not args.no_progress, dry_run=args.dry_run)
    return result.exit_code


def cmd_notebooks(args) -> int:
    """Run ``tefcore notebooks`` with parsed arguments; return the exit status.

    Lists the numbered notebooks with the paper figures each reproduces, or
    copies them for editing.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``notebooks`` options: ``copy`` (folder to copy the
        ``.ipynb`` and ``.py`` files into, or None to list) and ``only``
        (notebook names or number prefixes, or None for all).

    Returns
    -------
    int
        0 (errors such as an existing file in the copy folder are raised,
        and the CLI prints them as one line).
    """
    from .notebook_files import (
        NOTEBOOK_FIGURES,
        NOTEBOOKS,
        copy_notebooks,
        notebooks_dir,
        resolve_notebook,
    )

    names = [resolve_notebook(n) for n in args.only] if args.only else list(NOTEBOOKS)
    if args.copy is None:
        print(f"notebooks in {notebooks_dir()}:")
        for n in names:
            figs = ", ".join(f.replace("fig", "Fig. ") for f in NOTEBOOK_FIGURES[n])
            print(f"  {n:38s} {figs or _NO_FIGURE.get(n, '')}")
        return 0
    written = copy_notebooks(args.copy, names)
    print(f"copied {len(written) // 2} notebooks (.ipynb and .py) into {args.copy}")
    return 0


def add_commands(sub, formatter_class=argparse.RawDescriptionHelpFormatter) -> None:
    """Add ``reproduce``, ``batch``, ``notebooks`` and ``infer`` to the ``tefcore`` subparsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    formatter_class : type
        Help formatter of the subcommands (the ``tefcore`` command's own).
    """
    fmt = formatter_class
    p = sub.add_parser("reproduce", formatter_class=fmt, description=_REPRODUCE,
                       help="run the notebooks, check the paper's claims, write the report")
    p.add_argument("--out", default="output",
                   help="output folder, outside the source checkout (default: output, in "
                        "the current folder)")
    p.add_argument("--params", default=None, metavar="FILE.yaml",
                   help="YAML parameters: {all: {...}, 03_overhang: {...}, ...}")
    p.add_argument("-p", "--param", nargs=2, action="append", metavar=("NAME", "VALUE"),
                   help="notebook parameter for all notebooks, or NOTEBOOK:NAME for one "
                        "(e.g. -p n_jobs 2 -p 03_overhang:n_points 8); VALUE is YAML")
    p.add_argument("--only", nargs="+", metavar="NOTEBOOK", default=None,
                   help="run only these notebooks (e.g. 03 04_cg_offset)")
    p.add_argument("--jobs", type=int, default=None,
                   help="notebooks executed at once (default: the number of cores)")
    p.add_argument("--no-variants", action="store_true",
                   help="do not check the claims on the other packaged variant")
    p.add_argument("--no-progress", "--quiet", action="store_true", help="no progress bar")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--no-attribution", action="store_true",
                       help="skip the attribution of the failing claims (OUT/attribution.csv)")
    which.add_argument("--attribute-again", action="store_true",
                       help="search the failing claims' attribution even where the package's "
                            "applies (the default rotor): the longest phase of a full run")
    p.set_defaults(func=cmd_reproduce)
    p = sub.add_parser("batch", formatter_class=fmt, description=_BATCH,
                       help="run many parameter sets through the notebooks, compare them")
    p.add_argument("runs", metavar="RUNS.yaml", help="the batch file: runs, parameters, grids")
    p.add_argument("--out", default="batch", help="output folder (default: batch)")
    p.add_argument("--jobs", type=int, default=None,
                   help="notebooks executed at once over all runs (default: the cores)")
    p.add_argument("--force", action="store_true",
                   help="recompute runs whose recorded inputs differ (instead of refusing)")
    p.add_argument("--only", nargs="+", metavar="NOTEBOOK", default=None,
                   help="keep only these notebooks in every run (e.g. 04)")
    p.add_argument("--params", default=None, metavar="FILE.yaml",
                   help="YAML parameters over every run: {all: {...}, 03_overhang: {...}}")
    p.add_argument("-p", "--param", nargs=2, action="append", metavar=("NAME", "VALUE"),
                   help="notebook parameter over every run (NOTEBOOK:NAME for one "
                        "notebook); VALUE is YAML")
    p.add_argument("--dry-run", action="store_true",
                   help="check the batch and show what would run (new, skip, retry); run "
                        "nothing")
    p.add_argument("--no-progress", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_batch)
    p = sub.add_parser("notebooks", formatter_class=fmt, description=_NOTEBOOKS,
                       help="list the notebooks, or copy them for editing (--copy DIR)")
    p.add_argument("--copy", default=None, metavar="DIR",
                   help="copy the notebooks (.ipynb and .py sources) into DIR")
    p.add_argument("--only", nargs="+", metavar="NOTEBOOK", default=None,
                   help="only these notebooks (e.g. 04 05_stiffness)")
    p.set_defaults(func=cmd_notebooks)
    from ..inference.command import add_infer_command  # infer: the study of the rotor

    add_infer_command(sub, fmt)
