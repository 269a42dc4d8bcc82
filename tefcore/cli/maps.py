"""``tefcore map``: a stability map over two fields, its estimate, its table and picture."""

from __future__ import annotations

import sys

from ..safe_io import atomic_output, check_outputs
from .common import inputs, jobs, load
from .estimate import YES_HELP, announce

__all__ = ["add_arguments", "run"]


def _grid(cfg, field: str, start: str, stop: str, num: str, axis: str) -> list:
    """Evenly spaced SI values of ``field`` from ``start`` to ``stop``, ``num`` of them
    (the units rules of ``--range``, :func:`tefcore.config.text_input.sweep_values`);
    ``axis`` (``"X"``, ``"Y"``) names the arguments in messages (``X_NUM``)."""
    from ..config.text_input import sweep_values

    names = tuple(f"{axis}_{n}" for n in ("START", "STOP", "NUM"))
    values = sweep_values(field, None, (start, stop, num), range_names=names)
    return [float(cfg.with_overrides({field: v}).get(field)) for v in values]


def _map_plot(res, cfg, path) -> None:
    """The map's PNG, axes labelled as in the notebooks (``paper.plotting.field_axis``)."""
    import matplotlib

    matplotlib.use("Agg")
    from ..paper.figures.plotting import field_axis

    (x_label, x_unit), (y_label, y_unit) = field_axis(res.x_field), field_axis(res.y_field)
    ax = res.plot(x_unit=x_unit, x_label=x_label, y_unit=y_unit, y_label=y_label)
    ax.set_title(f"{cfg.name}: flutter root growth", fontsize="medium")
    with atomic_output(path, "wb", what="--png") as f:
        ax.figure.savefig(f, format="png", dpi=110, bbox_inches="tight",
                          metadata={"Software": None})


def run(args) -> int:
    """``tefcore map``: outputs checked, the estimate stated, the map computed and written.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``map`` options (fields, grids, outputs, ``--out``, jobs).

    Returns
    -------
    int
        0, or 1 when a point failed.
    """
    from ..runtime import process_cap
    from ..sweeps import maps
    from ..sweeps.evaluate import command_pool, n_chains

    cfg = load(args)
    xs = _grid(cfg, args.x_field, args.x_start, args.x_stop, args.x_num, "X")
    ys = _grid(cfg, args.y_field, args.y_start, args.y_stop, args.y_num, "Y")
    # the table is written when asked for, or when no other output is
    csv = args.csv or (None if args.png or args.netcdf else "map.csv")
    outputs = [(p, w, k) for p, w, k in ((csv, "--csv", None), (args.netcdf, "--netcdf",
                                                                "netcdf"),
                                         (args.png, "--png", "png")) if p]
    stores = [(f, "--out") for f in maps.map_files(args.out, len(ys))] if args.out else []
    check_outputs(outputs, inputs=inputs(args, cfg), stores=stores)
    if args.out:
        from ..safe_io import check_output_folder

        check_output_folder(args.out, "--out", create=True)
    if not args.scheduler:
        # rows side by side, one per process; a single row shares its chains
        tasks = (len(ys), "row") if len(ys) > 1 else (n_chains(len(xs)), "chain of points")
        processes, line = process_cap(args.jobs, *tasks)
        if line:
            print(f"tefcore map: {line}", file=sys.stderr, flush=True)
        announce("map", f"{len(xs)} x {len(ys)} = {len(xs) * len(ys)} points",
                 len(xs) * len(ys), processes, cfg, {args.x_field: xs[0], args.y_field: ys[0]},
                 yes=args.yes, after="the boundary is refined")
    client = None
    if args.scheduler:
        from distributed import Client

        client = Client(args.scheduler)
    try:
        # the rows' workers: copies of this process, ready at once
        with command_pool():
            res = maps.stability_map(cfg, args.x_field, xs, args.y_field, ys,
                                     n_jobs=args.jobs,
                                     backend="dask" if client is not None else "joblib",
                                     client=client, out=args.out,
                                     refine_boundary=not args.no_refine,
                                     progress=False if args.quiet else None)
    finally:
        if client is not None:
            client.close()
    if csv:
        with atomic_output(csv, newline="", what="--csv") as f:
            res.table.to_csv(f, index=False, float_format="%.10g")
    if args.netcdf:
        with atomic_output(args.netcdf, "wb", what="--netcdf") as f:
            f.write(res.dataset.to_netcdf(engine="scipy"))
    if args.png:
        _map_plot(res, cfg, args.png)
    n_bad = int((res.table["status"] != "ok").sum())
    print(f"wrote {', '.join(p for p, _, _ in outputs)}: {len(xs)} x {len(ys)} points, "
          f"{n_bad} failed, {len(res.boundary)} boundary points")
    return 1 if n_bad else 0


def add_arguments(sub, add) -> None:
    """Add ``map`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "map", "stability map over two fields: flutter growth, boundary",
            "Stability map: one sweep of FIELD_X per value of FIELD_Y (resumable with "
            "--out), the flutter root's growth rate at every point and the flutter "
            "boundary refined between grid points. Ranges are START STOP NUM, numbers "
            "(SI or fractions) or 'value unit' strings.", run,
            epilog="example:\n  tefcore map flap.cg_offset 0 0.3 7 flap.overhang 0 0.4 5 "
                   "--png map.png")
    # one positional per item: argparse cannot format the usage of a positional
    # with a tuple metavar (nargs=3)
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
    p.add_argument("--jobs", type=jobs, default=1,
                   help="parallel processes (joblib); at most one per core and per row")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 (instead of "
                        "local processes)")
    p.add_argument("--no-refine", action="store_true", help="do not refine the boundary")
    p.add_argument("--quiet", "--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--yes", action="store_true", help=YES_HELP)
