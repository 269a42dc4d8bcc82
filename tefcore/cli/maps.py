"""``tefcore map``: a stability map over two fields, its estimate, its table and picture."""

from __future__ import annotations

import os
import sys

from ..safe_io import atomic_output, check_output_file
from .common import load

__all__ = ["ESTIMATE_ABOVE_S", "TIMED_FROM_POINTS", "add_arguments", "run"]


def _grid(cfg, field: str, start: str, stop: str, num: str, axis: str) -> list:
    """Evenly spaced SI values of ``field`` from ``start`` to ``stop``, ``num`` of them
    (the units rules of ``--range``, :func:`tefcore.config.text_input.sweep_values`);
    ``axis`` (``"X"``, ``"Y"``) names the arguments in messages (``X_NUM``)."""
    from ..config.text_input import sweep_values

    names = tuple(f"{axis}_{n}" for n in ("START", "STOP", "NUM"))
    values = sweep_values(field, None, (start, stop, num), range_names=names)
    return [float(cfg.with_overrides({field: v}).get(field)) for v in values]


#: A map whose estimated time exceeds this [s] prints the estimate before it starts.
ESTIMATE_ABOVE_S = 120.0
#: Maps of fewer points are not timed (timing costs one point; ~1 s at the defaults).
TIMED_FROM_POINTS = 20


def _map_estimate(cfg, args, xs, ys) -> str | None:
    """The map's expected time from one point timed, when it exceeds :data:`ESTIMATE_ABOVE_S`."""
    import time

    from ..sweeps.evaluate import default_point

    n = len(xs) * len(ys)
    if n < TIMED_FROM_POINTS:
        return None
    start = time.perf_counter()
    try:
        default_point()(cfg.with_overrides({args.x_field: xs[0], args.y_field: ys[0]}))
    except Exception:  # a failing point costs little and the map records it
        return None
    each = time.perf_counter() - start
    workers = min(n, (os.cpu_count() or 1) if args.jobs < 0 else args.jobs)
    seconds = each * n / max(1, workers)
    if seconds <= ESTIMATE_ABOVE_S:
        return None
    span = (f"{seconds / 3600:.1f} h" if seconds >= 5400 else f"{seconds / 60:.0f} min")
    return (f"tefcore map: {len(xs)} x {len(ys)} = {n} points at about {each:.2g} s each (one "
            f"point timed, cold) on {workers} process{'es' if workers > 1 else ''}: about "
            f"{span} before the boundary is refined; Ctrl-C stops it (with --out it resumes)")


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
    """``tefcore map``: outputs checked, the estimate printed, the map computed and written.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``map`` options (fields, grids, outputs, ``--out``, jobs).

    Returns
    -------
    int
        0, or 1 when a point failed.
    """
    from ..sweeps import maps
    from ..sweeps.evaluate import command_pool

    cfg = load(args)
    xs = _grid(cfg, args.x_field, args.x_start, args.x_stop, args.x_num, "X")
    ys = _grid(cfg, args.y_field, args.y_start, args.y_stop, args.y_num, "Y")
    # the table is written when asked for, or when no other output is
    csv = args.csv or (None if args.png or args.netcdf else "map.csv")
    outputs = [(p, w) for p, w in ((csv, "--csv"), (args.netcdf, "--netcdf"),
                                   (args.png, "--png")) if p]
    for path, what in outputs:
        check_output_file(path, what)
    if args.out:
        from ..safe_io import check_output_folder

        check_output_folder(args.out, "--out", create=True)
    if not args.scheduler and (estimate := _map_estimate(cfg, args, xs, ys)):
        print(estimate, file=sys.stderr, flush=True)
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
    print(f"wrote {', '.join(p for p, _ in outputs)}: {len(xs)} x {len(ys)} points, "
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
    p.add_argument("--jobs", type=int, default=1, help="parallel processes (joblib)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 (instead of "
                        "local processes)")
    p.add_argument("--no-refine", action="store_true", help="do not refine the boundary")
    p.add_argument("--quiet", "--no-progress", action="store_true", help="no progress bar")
