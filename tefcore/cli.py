"""Command line: ``tefcore modes | fanplot | stability | sweep | reproduce``.

``tefcore reproduce`` executes the numbered notebooks with papermill and
writes the claims report (:mod:`tefcore.reproduce`).

Values given with ``--set`` (and ``sweep --values/--range``) follow the
units rules of :mod:`tefcore.text_input`: a dimensional field needs its
unit.  Output files are checked before anything is computed and written
atomically (:mod:`tefcore.safe_io`).  Exit status: 0 success; 1 the
command ran but its result is not clean (failed sweep points, failing
notebooks or claims); 2 an error, printed as one line
(:mod:`tefcore.cli_errors`); 130 interrupted; 141 output pipe closed.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from .cli_errors import run_command
from .safe_io import atomic_output, check_output_file
from .text_input import sweep_values


def _load(args):
    from .config import load_config
    from .text_input import parse_overrides

    cfg = load_config(args.config)
    if args.set:
        cfg = cfg.with_overrides(parse_overrides(args.set))
    return cfg


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
    from .blade import blade_modes

    cfg = _load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    table = blade_modes(cfg, n_modes=args.n_modes,
                        collective=np.deg2rad(args.collective)).table()
    if args.csv:
        _write_csv(table, args.csv)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    return 0


def cmd_fanplot(args) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.figure

    from .blade import fan_plot

    cfg = _load(args)
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
    from .stability import stability

    cfg = _load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    res = stability(cfg)
    table = res.modes
    if args.csv:
        _write_csv(table, args.csv)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    print("trim: " + ", ".join(f"{k}={v:.4g}" for k, v in res.trim.items()))
    return 0


def cmd_sweep(args) -> int:
    from .sweep import sweep

    cfg = _load(args)
    values = sweep_values(args.parameter, args.values, args.range)
    check_output_file(args.csv, "--csv")
    if args.out:
        check_output_file(args.out, "--out", create_folder=True)
    result = sweep(cfg, args.parameter, values, n_jobs=args.jobs, out=args.out,
                   progress=False if args.quiet else None)
    path = result.to_csv(args.csv)
    n_bad = len(result.failed)
    print(f"wrote {path}: {len(values)} points, {n_bad} failed")
    if n_bad:
        print(result.failed.to_string(index=False))
        print(f"tefcore sweep: {n_bad} of {len(values)} point(s) failed (see {path}, column "
              "'error')", file=sys.stderr)
        return 1
    return 0


def cmd_reproduce(args) -> int:
    from .reproduce import load_params_file, parse_cli_params, reproduce

    # later layers win: file "all" < file notebook < -p all < -p notebook
    layers = [load_params_file(args.params)] if args.params else []
    layers.append(parse_cli_params([tuple(p) for p in args.param or ()]))
    return reproduce(Path(args.out), params=layers, notebooks=args.only,
                     progress=not args.no_progress)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="tefcore", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("modes", help="coupled blade modes as a table")
    _common(p)
    p.add_argument("--n-modes", type=int, default=None)
    p.add_argument("--collective", type=float, default=0.0, help="pitch at 0.75R [deg]")
    p.add_argument("--csv", default=None, help="also write the table to this CSV file")
    p.set_defaults(func=cmd_modes)
    p = sub.add_parser("fanplot", help="fan plot (frequency vs rotor speed) to an image")
    _common(p)
    p.add_argument("--n-modes", type=int, default=None)
    p.add_argument("--out", default="fanplot.png")
    p.set_defaults(func=cmd_fanplot)
    p = sub.add_parser("stability", help="trim + Floquet stability, one row per mode")
    _common(p)
    p.add_argument("--csv", default=None, help="also write the mode table to this CSV file")
    p.set_defaults(func=cmd_stability)
    p = sub.add_parser("sweep", help="stability over one parameter, tidy CSV")
    _common(p)
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
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_sweep)
    p = sub.add_parser(
        "reproduce", help="run the notebooks (papermill) and write the claims report",
        description="Execute notebooks/01-07 with papermill into OUT, then write "
                    "OUT/report.md and a self-contained OUT/report.html listing every claim. "
                    "Exit status 1 when a notebook fails or a claim is worse than recorded.")
    p.add_argument("--out", default="output", help="output folder (default: output)")
    p.add_argument("--params", default=None, metavar="FILE.yaml",
                   help="YAML parameters: {all: {...}, 03_overhang: {...}, ...}")
    p.add_argument("-p", "--param", nargs=2, action="append", metavar=("NAME", "VALUE"),
                   help="notebook parameter for all notebooks, or NOTEBOOK:NAME for one "
                        "(e.g. -p n_jobs 2 -p 03_overhang:n_points 8); VALUE is YAML")
    p.add_argument("--only", nargs="+", metavar="NOTEBOOK", default=None,
                   help="run only these notebooks (e.g. 03 04_cg_offset)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_reproduce)
    return parser


def main(argv=None) -> int:
    """Run the ``tefcore`` command; errors are one line, exit 2 (:mod:`tefcore.cli_errors`)."""
    def body():
        args = build_parser().parse_args(argv)
        return args.func(args)

    return run_command(body, prog="tefcore")


if __name__ == "__main__":
    raise SystemExit(main())
