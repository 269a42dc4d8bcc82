"""Command line: ``tefcore modes | fanplot | stability | sweep | map | mechanism | reproduce``.

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
    if res.aero_modes is not None:
        am = res.aero_modes
        kinds = ", ".join(f"{(am['kind'] == k).sum()} {k}" for k in ("wake", "inflow")
                          if (am["kind"] == k).any())
        print(f"aerodynamic-state roots (no mode label): {kinds}; least stable "
              f"{am['real_part'].max():+.4f} /rev" if len(am) else
              "aerodynamic-state roots: none")
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


def cmd_mechanism(args) -> int:
    from .mechanism import mechanism

    cfg = _load(args)
    if args.csv:
        check_output_file(args.csv, "--csv")
    res = mechanism(cfg, mode=args.mode, knockouts=not args.no_knockouts)
    if args.csv:
        with atomic_output(args.csv, newline="", what="--csv") as f:
            res.table.to_csv(f, index=False, float_format="%.10g")
    print(res.summary())
    doubtful = [t for t, f in res.knockouts.items() if not f.clear]
    if doubtful:
        print("knockouts through a coalescence (identity not certain): " + ", ".join(doubtful))
    if args.csv:
        print(f"wrote {args.csv}: {len(res.table)} rows")
    return 0


def _grid(cfg, field: str, start: str, stop: str, num: str) -> list:
    """Evenly spaced SI values of ``field`` from ``start`` to ``stop``, ``num`` of them
    (the units rules of ``--range``, :func:`tefcore.text_input.sweep_values`)."""
    values = sweep_values(field, None, (start, stop, num))
    return [float(cfg.with_overrides({field: v}).get(field)) for v in values]


def cmd_map(args) -> int:
    from .stability_map import stability_map

    cfg = _load(args)
    xs = _grid(cfg, args.x_field, *args.x_range)
    ys = _grid(cfg, args.y_field, *args.y_range)
    check_output_file(args.csv, "--csv")
    for path, what in ((args.png, "--png"), (args.netcdf, "--netcdf")):
        if path:
            check_output_file(path, what)
    if args.out:
        from .safe_io import check_output_folder

        check_output_folder(args.out, "--out", create=True)
    client = None
    if args.scheduler:
        from distributed import Client

        client = Client(args.scheduler)
    try:
        res = stability_map(cfg, args.x_field, xs, args.y_field, ys, n_jobs=args.jobs,
                            backend="dask" if client is not None else "joblib", client=client,
                            out=args.out, refine_boundary=not args.no_refine,
                            progress=False if args.quiet else None)
    finally:
        if client is not None:
            client.close()
    with atomic_output(args.csv, newline="", what="--csv") as f:
        res.table.to_csv(f, index=False, float_format="%.10g")
    written = [args.csv]
    if args.netcdf:
        with atomic_output(args.netcdf, "wb", what="--netcdf") as f:
            f.write(res.dataset.to_netcdf(engine="scipy"))
        written.append(args.netcdf)
    if args.png:
        import matplotlib

        matplotlib.use("Agg")
        ax = res.plot()
        ax.set_title(f"{cfg.name}: flutter root growth", fontsize="medium")
        with atomic_output(args.png, "wb", what="--png") as f:
            ax.figure.savefig(f, format="png", dpi=110, bbox_inches="tight",
                              metadata={"Software": None})
        written.append(args.png)
    n_bad = int((res.table["status"] != "ok").sum())
    print(f"wrote {', '.join(written)}: {len(xs)} x {len(ys)} points, {n_bad} failed, "
          f"{len(res.boundary)} boundary points")
    return 1 if n_bad else 0


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
        "map", help="stability over a grid of two fields: flutter growth and boundary",
        description="Stability map: one sweep of FIELD_X per value of FIELD_Y (resumable "
                    "with --out), the flutter root's growth rate at every point and the "
                    "flutter boundary refined between grid points. Ranges are START STOP "
                    "NUM, numbers (SI or fractions) or 'value unit' strings.")
    _common(p)
    p.add_argument("x_field", help="dotted field on the x axis, e.g. flap.cg_offset")
    p.add_argument("x_range", nargs=3, metavar=("X_START", "X_STOP", "X_NUM"))
    p.add_argument("y_field", help="dotted field on the y axis, e.g. flap.overhang")
    p.add_argument("y_range", nargs=3, metavar=("Y_START", "Y_STOP", "Y_NUM"))
    p.add_argument("--csv", default="map.csv", help="tidy table (default: map.csv)")
    p.add_argument("--png", default=None, help="also draw the map to this image")
    p.add_argument("--netcdf", default=None, help="also write the xarray Dataset (netCDF3)")
    p.add_argument("--out", default=None, help="folder for resumable sweep files")
    p.add_argument("--jobs", type=int, default=1, help="parallel processes (joblib)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 (instead of "
                        "local processes)")
    p.add_argument("--no-refine", action="store_true", help="do not refine the boundary")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_map)
    p = sub.add_parser(
        "mechanism", help="why a root is (un)stable: work of each physical term, knockouts",
        description="Decompose one root's growth rate into the work of the named terms of "
                    "the linearised equations (they add up to its real part), and follow "
                    "the root with each term knocked out. CSV columns: term, "
                    "contribution_real, contribution_imag; rows: one per term, 'total' "
                    "(the root's eigenvalue, /rev) and 'knockout <term>' (the root's "
                    "eigenvalue with that term removed).")
    _common(p)
    p.add_argument("--mode", default="TEF",
                   help="'TEF' (the root the flap mode becomes), 'flutter' (least stable "
                        "root the flap takes part in) or a label, e.g. 'blade torsion 1'")
    p.add_argument("--csv", default=None, help="write the decomposition to this CSV file")
    p.add_argument("--no-knockouts", action="store_true", help="skip the knockouts (faster)")
    p.set_defaults(func=cmd_mechanism)
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
