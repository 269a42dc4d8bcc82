"""The ``tefcore`` command.

Subcommands: ``modes``, ``fanplot``, ``stability``, ``sweep``, ``map``,
``mechanism``, ``simulate``, ``c81 example|check``, and from the paper layer
(:mod:`tefcore.paper.run.commands`) ``reproduce`` (executes the notebooks and
writes the claims report) and ``notebooks`` (lists them, copies them for
editing); ``tefcore --help`` lists them and ``tefcore SUBCOMMAND --help``
describes one.

Values given with ``--set`` (and ``sweep --values/--range``) follow the
units rules of :mod:`tefcore.config.text_input`: a dimensional field needs its
unit.  Output files are checked before anything is computed and written
atomically (:mod:`tefcore.safe_io`).  The command applies the process
settings of :func:`tefcore.runtime.apply_defaults` before it runs.  Exit
status: 0 success; 1 the command ran but its result is not clean (failed
sweep points, bad C81 decks, failing notebooks or claims); 2 an error,
printed as one line (:func:`tefcore.errors.run_command`); 130 interrupted; 141
output pipe closed.
"""

from __future__ import annotations

import argparse
import math
import sys
import textwrap
import warnings
from pathlib import Path

from .._version import __version__
from ..errors import run_command
from ..safe_io import atomic_output, check_output_file
from .common import load
from .maps import cmd_map

__all__ = ["build_parser", "entry_point", "main"]

#: ``tefcore --help``: what the command is, and where the details are.
DESCRIPTION = """\
Floquet aeroelastic stability of helicopter rotor blades with trailing-edge
flaps: blade modes, trim and stability, sweeps and stability maps, the
mechanism of an instability, C81 airfoil decks, and the reproduction of the
paper's figures and claims."""

EPILOG = """\
examples:
  tefcore stability
  tefcore stability --set flap.cg_offset=0.2 --csv modes.csv
  tefcore sweep flap.overhang --range 0 0.4 9 --jobs 2
  tefcore c81 check my_deck.c81
  tefcore SUBCOMMAND --help

values given with --set need their unit when the field has one
('hub.pitch_link_stiffness=800 lb/in'); output files are checked before
anything is computed and written atomically.

exit status: 0 success; 1 ran, but the result is not clean (failed sweep
points, bad C81 decks, failing notebooks or claims); 2 an error (one line);
130 interrupted; 141 output pipe closed."""


def _write_csv(table, path) -> None:
    """Write a table atomically (the destination was checked before computing)."""
    with atomic_output(path, newline="", what="--csv") as f:
        table.to_csv(f, index=False)


def _common(p):
    p.add_argument("--config", default="mdart",
                   help="configuration TOML file or packaged name (default: mdart)")
    p.add_argument("-s", "--set", action="append", metavar="NAME=VALUE",
                   help="override a field by dotted name, "
                        "e.g. hub.pitch_link_stiffness='800 lb/in'")


def cmd_modes(args) -> int:
    from ..structure.blade import blade_modes

    cfg = load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    table = blade_modes(cfg, n_modes=args.n_modes,
                        collective=math.radians(args.collective)).table()
    if args.csv:
        _write_csv(table, args.csv)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    return 0


def cmd_fanplot(args) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.figure

    from ..structure.blade import fan_plot

    cfg = load(args)
    fmt = Path(args.out).suffix.lstrip(".").lower() or "png"
    if fmt not in matplotlib.figure.Figure().canvas.get_supported_filetypes():
        raise ValueError(f"--out {args.out}: unknown image format {fmt!r}")
    check_output_file(args.out, "--out")
    ax = fan_plot(cfg, n_modes=args.n_modes)
    ax.set_title(cfg.name)
    with atomic_output(args.out, "wb", what="--out") as f:
        ax.figure.savefig(f, format=fmt, dpi=120, bbox_inches="tight")
    print(f"wrote {args.out}")
    return 0


def cmd_stability(args) -> int:
    from ..linear.stability import stability
    from .text import flutter_text, legend, modes_text, trim_lines, wrap

    cfg = load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    res = stability(cfg)
    # the table's columns: printing them needs no pandas (the CSV does)
    table = res.columns if hasattr(res, "columns") else res.modes
    if args.csv:
        _write_csv(res.modes, args.csv)
    print(modes_text(table))
    print("\n".join(legend(table)))
    if (sentence := flutter_text(table)) is not None:
        print(sentence)
    print("\n".join(trim_lines(res.trim)))
    if res.aero_modes is not None:
        am = res.aero_modes
        kinds = ", ".join(f"{(am['kind'] == k).sum()} {k}" for k in ("wake", "inflow")
                          if (am["kind"] == k).any())
        print(wrap(f"aerodynamic-state roots (no mode label): {kinds}; least stable "
                   f"{am['real_part'].max():+.4f} /rev") if len(am) else
              "aerodynamic-state roots: none")
    return 0


def cmd_sweep(args) -> int:
    from ..config.text_input import sweep_values
    from ..sweeps.evaluate import command_pool, start_pool_for

    values = sweep_values(args.parameter, args.values, args.range)
    # a forked worker is this process's copy, ready at once: started once the
    # inputs are checked; a spawned one starts and imports while they are.
    # The pool is closed when the command ends: no idle worker to wait for
    with command_pool() as forked:
        if not forked:
            start_pool_for(len(values), args.jobs)
        from ..sweeps.sweep import sweep
        from .text import sweep_summary, timing_lines

        cfg = load(args)
        check_output_file(args.csv, "--csv")
        if args.out:
            check_output_file(args.out, "--out", create_folder=True)
        if forked:
            start_pool_for(len(values), args.jobs)
        result = sweep(cfg, args.parameter, values, n_jobs=args.jobs, out=args.out,
                       progress=False if args.quiet else None)
    path = result.to_csv(args.csv)
    n_bad = len(result.failed)
    print(f"wrote {path}: {len(values)} points, {n_bad} failed")
    for line in timing_lines(result.timing) + sweep_summary(result):
        print(line)
    if n_bad:
        print(result.failed.to_string(index=False))
        print(f"tefcore sweep: {n_bad} of {len(values)} point(s) failed (see {path}, column "
              "'error')", file=sys.stderr)
        return 1
    return 0


def cmd_mechanism(args) -> int:
    from ..linear.mechanism import mechanism
    from ..linear.stability import stability
    from .text import mechanism_choice, wrap

    cfg = load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    point = stability(cfg)
    # no --mode: mechanism's default, the flutter root when unstable, else the TEF mode
    res = mechanism(cfg, mode=args.mode, knockouts=not args.no_knockouts,
                    stability_result=point)
    if args.csv:
        with atomic_output(args.csv, newline="", what="--csv") as f:
            res.table.to_csv(f, index=False, float_format="%.10g")
    if args.mode is None:
        print(mechanism_choice(res, point.modes))
    for line in res.summary().splitlines():
        print(wrap(line, indent="    "))
    doubtful = [t for t, f in res.knockouts.items() if not f.clear]
    if doubtful:
        print(wrap("knockouts through a coalescence (identity not certain): "
                   + ", ".join(doubtful)))
    if args.csv:
        print(f"wrote {args.csv}: {len(res.table)} rows")
    return 0


def cmd_c81_example(args) -> int:
    from ..aero.c81.format import write_c81
    from ..aero.c81.tables import example_deck_path, make_example_deck

    out = args.out or example_deck_path()
    check_output_file(out, "--out")
    print(f"wrote {write_c81(make_example_deck(), out)}")
    return 0


def cmd_c81_check(args) -> int:
    from ..aero.c81.format import COEFFICIENT_LABELS, C81FormatError
    from ..aero.c81.reader import read_c81

    status = 0
    for f in args.files:
        try:
            deck = read_c81(f)
        except C81FormatError as exc:       # names the file, line and column
            print(exc, file=sys.stderr)
            status = 1
            continue
        except OSError as exc:              # a folder, a dangling link, no permission
            print(f"{f}: cannot read the C81 deck ({exc.strerror or exc})", file=sys.stderr)
            status = 1
            continue
        kind = f"flap deck, {deck.delta.size} deltas" if deck.is_flap else "blade deck"
        sizes = ", ".join(f"{COEFFICIENT_LABELS[c]} {deck.alpha[c].size}x{deck.mach[c].size}"
                          for c in deck.coefficients)
        print(f"{f}: {deck.name!r} ({kind}; alpha x Mach: {sizes})")
    return status


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (:class:`~tefcore.errors.UsageError`).

    argparse prints the whole usage and exits; the command prints one line
    (``tefcore: error: map: the following arguments are required: Y_NUM (see
    'tefcore map --help')``) with status 2 (:func:`tefcore.errors.run_command`).
    Subcommands' parsers are of the same class (argparse's ``parser_class``).
    """

    def error(self, message: str):
        from ..errors import UsageError

        command = self.prog.removeprefix("tefcore").strip()
        where = f"{command}: " if command else ""
        raise UsageError(f"{where}{message} (see '{self.prog} --help')")


class _HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Descriptions and epilogs as written; each subcommand's help on its own line."""

    def __init__(self, prog: str) -> None:
        super().__init__(prog, max_help_position=32)

    def add_argument(self, action: argparse.Action) -> None:
        super().add_argument(action)
        if action.nargs == argparse.PARSER and action.help is not argparse.SUPPRESS:
            # argparse measures the subcommand names without the 4 columns of
            # indentation they are printed with, and wraps the longer ones
            for name in action.choices:
                self._action_max_length = max(self._action_max_length,
                                              len(name) + self._current_indent + 4)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        # paragraphs (blank-line separated) are filled; lines indented by two
        # spaces or more (examples) are kept as written
        out = []
        for para in text.split("\n\n"):
            if all(line.startswith("  ") or not line.strip() for line in para.splitlines()) \
                    or para.startswith(("examples:", "example:")):
                out.append("\n".join(indent + line for line in para.splitlines()))
            else:
                out.append(textwrap.fill(" ".join(para.split()), width, initial_indent=indent,
                                         subsequent_indent=indent))
        return "\n\n".join(out)


def _add(sub, name: str, help: str, description: str, func, *, common: bool = True,
         epilog: str | None = None):
    """One subcommand: a one-line ``help`` for ``tefcore --help``, a description."""
    p = sub.add_parser(name, help=help, description=description, epilog=epilog,
                       formatter_class=_HelpFormatter)
    if common:
        _common(p)
    p.set_defaults(func=func)
    return p


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``tefcore`` command.

    Returns
    -------
    argparse.ArgumentParser
        With one subparser per subcommand; each sets ``func``, the function
        that runs it (``func(args) -> exit status``).
    """
    parser = _Parser(prog="tefcore", description=DESCRIPTION, epilog=EPILOG,
                     formatter_class=_HelpFormatter)
    parser.add_argument("--version", action="version", version=f"tefcore {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="SUBCOMMAND",
                                title="subcommands")
    p = _add(sub, "modes", "coupled blade modes (frequencies, labels) as a table",
             "Rotating blade modes of the configuration (finite elements, flap included) "
             "at one collective pitch: frequency (/rev) and label of each mode.", cmd_modes)
    p.add_argument("--n-modes", type=int, default=None, help="number of modes (default: the "
                   "configuration's model.n_modes)")
    p.add_argument("--collective", type=float, default=0.0, help="pitch at 0.75R [deg]")
    p.add_argument("--csv", default=None, help="also write the table to this CSV file")
    p = _add(sub, "fanplot", "fan plot (frequency vs rotor speed) to an image",
             "Blade mode frequencies against rotor speed (fan plot), written to an image "
             "whose format follows the file name (png, pdf, svg, ...).", cmd_fanplot)
    p.add_argument("--n-modes", type=int, default=None, help="number of modes")
    p.add_argument("--out", default="fanplot.png", help="image file (default: fanplot.png)")
    p = _add(sub, "stability", "trim + Floquet stability, one row per mode",
             "Trim the rotor, linearise about the periodic trim and compute the Floquet "
             "modes: frequency (/rev), real part (/rev), damping ratio and label of each "
             "mode, and the trim controls.", cmd_stability,
             epilog="example:\n  tefcore stability --set flight.advance_ratio=0.3 "
                    "--csv modes.csv")
    p.add_argument("--csv", default=None, help="also write the mode table to this CSV file")
    p = _add(sub, "sweep", "stability over one parameter, tidy CSV",
             "Stability at each value of one configuration field, the modes tracked from "
             "point to point (tidy CSV, one row per mode and point). A failed point is "
             "recorded with its reason and the sweep goes on (exit status 1).", cmd_sweep,
             epilog="examples:\n"
                    "  tefcore sweep flap.cg_offset --values 0 0.1 0.2 0.3\n"
                    "  tefcore sweep hub.pitch_link_stiffness --range '400 lb/in' "
                    "'800 lb/in' 5 --out run.jsonl")
    p.add_argument("parameter", help="dotted field, e.g. flap.cg_offset")
    p.add_argument("--values", nargs="+",
                   help="values: numbers (dimensionless fields) or 'value unit' "
                        "(dimensional fields need their unit, as with --set)")
    p.add_argument("--range", nargs=3, metavar=("START", "STOP", "NUM"),
                   help="NUM evenly spaced values; START and STOP take units like --set "
                        "(e.g. '400 lb/in' '800 lb/in' 5)")
    p.add_argument("--csv", default="sweep.csv",
                   help="tidy table (default: sweep.csv); exit status 1 when points failed")
    p.add_argument("--out", default=None,
                   help="stream points to this JSON-lines file; re-running resumes it")
    p.add_argument("--jobs", type=int, default=1, help="parallel processes (joblib)")
    p.add_argument("--quiet", "--no-progress", action="store_true", help="no progress bar")
    p = _add(sub, "map", "stability map over two fields: flutter growth, boundary",
             "Stability map: one sweep of FIELD_X per value of FIELD_Y (resumable with "
             "--out), the flutter root's growth rate at every point and the flutter "
             "boundary refined between grid points. Ranges are START STOP NUM, numbers "
             "(SI or fractions) or 'value unit' strings.", cmd_map,
             epilog="example:\n  tefcore map flap.cg_offset 0 0.3 7 flap.overhang 0 0.4 5 "
                    "--png map.png")
    # one positional per item: argparse cannot format the usage of a positional
    # with a tuple metavar (nargs=3): its help raises a TypeError
    p.add_argument("x_field", help="dotted field on the x axis, e.g. flap.cg_offset")
    p.add_argument("x_start", metavar="X_START", help="first x value (a number or 'value unit')")
    p.add_argument("x_stop", metavar="X_STOP", help="last x value")
    p.add_argument("x_num", metavar="X_NUM", help="number of evenly spaced x values")
    p.add_argument("y_field", help="dotted field on the y axis, e.g. flap.overhang")
    p.add_argument("y_start", metavar="Y_START", help="first y value")
    p.add_argument("y_stop", metavar="Y_STOP", help="last y value")
    p.add_argument("y_num", metavar="Y_NUM", help="number of evenly spaced y values")
    p.add_argument("--csv", default=None,
                   help="tidy table (default: map.csv when neither --png nor --netcdf is given)")
    p.add_argument("--png", default=None, help="draw the map to this image")
    p.add_argument("--netcdf", default=None, help="write the xarray Dataset (netCDF3)")
    p.add_argument("--out", default=None, help="folder for resumable sweep files")
    p.add_argument("--jobs", type=int, default=1, help="parallel processes (joblib)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 (instead of "
                        "local processes)")
    p.add_argument("--no-refine", action="store_true", help="do not refine the boundary")
    p.add_argument("--quiet", "--no-progress", action="store_true", help="no progress bar")
    p = _add(sub, "mechanism", "why a root is (un)stable: work of each term, knockouts",
             "Decompose one root's growth rate into the work of the named terms of the "
             "linearised equations (they add up to its real part), and follow the root with "
             "each term knocked out. CSV columns: term, contribution_real, "
             "contribution_imag; rows: one per term, 'total' (the root's eigenvalue, /rev) "
             "and 'knockout <term>' (the root's eigenvalue with that term removed).",
             cmd_mechanism)
    p.add_argument("--mode", default=None,
                   help="'TEF' (the root the flap mode becomes), 'flutter' (the least stable "
                        "flap-induced root) or a root's name, e.g. 'blade torsion 1' "
                        "(default: the flutter root when it is unstable, else TEF)")
    p.add_argument("--csv", default=None, help="write the decomposition to this CSV file")
    p.add_argument("--no-knockouts", action="store_true", help="skip the knockouts (faster)")
    from .watch import add_commands as add_watch_commands  # simulate, explore

    add_watch_commands(sub, _add)
    p = _add(sub, "c81", "C81 airfoil decks: check decks, regenerate the example deck",
             "C81 airfoil decks (layout: docs/c81_format.md).", None, common=False)
    c81 = p.add_subparsers(dest="c81_command", required=True, metavar="C81COMMAND",
                           title="subcommands")
    q = _add(c81, "check", "parse decks and print a one-line summary of each",
             "Parse each deck and print its summary, or its first problem with file, line "
             "and column. Exit status 1 when a deck is bad.", cmd_c81_check, common=False)
    q.add_argument("files", nargs="+", metavar="FILE", help="C81 deck (blade or flap)")
    q = _add(c81, "example", "regenerate the packaged example flap deck",
             "Write the example flap deck, tabulated from the thin-airfoil model of the "
             "MDART flap (GENERATED data, not test data).", cmd_c81_example, common=False)
    q.add_argument("--out", default=None, help="output file (default: the packaged "
                                                "tefcore/data/example_flap_generated.c81)")
    from ..paper.run.commands import add_commands  # reproduce, notebooks: the paper layer

    add_commands(sub, formatter_class=_HelpFormatter)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the ``tefcore`` command.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status; errors are one line on stderr with status 2
        (:func:`tefcore.errors.run_command`).
    """
    def body():
        args = build_parser().parse_args(argv)
        from ..runtime import apply_defaults

        apply_defaults()  # the command owns its process (tefcore.runtime)
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.func(args)

    return run_command(body, prog="tefcore")


def entry_point() -> int:
    """The ``tefcore`` program: :func:`main`, then an exit without the final garbage collection.

    A process that has imported numpy, scipy and pandas spends 0.1-0.2 s
    when it exits in the interpreter's last collections, which walk every
    object those modules made, although the memory goes back with the process
    (measured: ``python -c "import tefcore.sweeps.sweep"`` 0.79 s, 0.61 s with
    ``gc.freeze()`` at its end; ``tefcore stability`` 0.81 times the wall time,
    interleaved medians of 11).  Once the command has returned -- its output
    files written and closed (:mod:`tefcore.safe_io`), its worker pools and
    kernels shut down -- this flushes the standard streams and moves every
    object out of the collector's reach (``gc.freeze``).  The exit handlers
    still run (loky's pool, temporary folders, coverage); objects left in
    reference cycles are not finalized, as the interpreter does not promise
    at exit anyway.  :func:`main` itself, which tests and programs call in
    their own process, leaves the collector alone.

    Returns
    -------
    int
        The exit status of :func:`main`.
    """
    import gc

    status = main()
    for stream in (sys.stdout, sys.stderr):
        if stream is None:                # pythonw and some launchers: no stream at all
            continue
        try:
            stream.flush()
        except (OSError, ValueError):     # closed or gone: nothing left to flush
            pass
    gc.freeze()
    return status


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as one line, ``tefcore: warning: <Category>: <message>``."""
    text = " ".join(str(message).split())
    print(f"tefcore: warning: {category.__name__}: {text}", file=file or sys.stderr)


if __name__ == "__main__":
    raise SystemExit(entry_point())
