"""``tefcore sweep``: stability over one parameter, the modes tracked, a tidy CSV."""

from __future__ import annotations

import sys

from ..safe_io import check_output_file, check_outputs
from .common import inputs, jobs, load
from .estimate import YES_HELP, announce

__all__ = ["add_arguments", "run"]


def run(args) -> int:
    """``tefcore sweep``: the sweep's points computed (in parallel with ``--jobs``) and written.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``sweep`` options.

    Returns
    -------
    int
        0, or 1 when a point failed.
    """
    from ..config.text_input import sweep_values
    from ..runtime import process_cap
    from ..sweeps.evaluate import command_pool, n_chains, start_pool_for

    values = sweep_values(args.parameter, args.values, args.range)
    processes, line = process_cap(args.jobs, n_chains(len(values)), "chain of points")
    # a forked worker is this process's copy, ready at once: started once the
    # inputs are checked; a spawned one starts and imports while they are.
    # The pool is closed when the command ends: no idle worker to wait for
    with command_pool() as forked:
        if not forked:
            start_pool_for(len(values), args.jobs)
        from ..sweeps.sweep import sweep
        from .text import sweep_summary, timing_lines

        cfg = load(args)
        for v in values:   # each value in its field's range before any point runs, as -s is
            cfg.with_overrides({args.parameter: v})
        check_outputs([(args.csv, "--csv")], inputs=inputs(args, cfg),
                      stores=[(args.out, "--out")])
        if args.out:
            check_output_file(args.out, "--out", create_folder=True)
        if line:
            print(f"tefcore sweep: {line}", file=sys.stderr, flush=True)
        announce("sweep", f"{len(values)} points", len(values), processes, cfg,
                 {args.parameter: values[0]}, yes=args.yes, after="the steps are refined")
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


def add_arguments(sub, add) -> None:
    """Add ``sweep`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "sweep", "stability over one parameter, tidy CSV",
            "Stability at each value of one configuration field, the modes tracked from "
            "point to point (tidy CSV, one row per mode and point). A failed point is "
            "recorded with its reason and the sweep goes on (exit status 1).", run,
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
    p.add_argument("--jobs", type=jobs, default=1,
                   help="parallel processes (joblib); at most one per core and per "
                        "warm-start chain (up to 8 points)")
    p.add_argument("--quiet", "--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--yes", action="store_true", help=YES_HELP)
