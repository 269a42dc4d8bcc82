"""``tefcore mechanism``: why a root is (un)stable -- the work of each term, the knockouts."""

from __future__ import annotations

from .common import load_for_csv, write_csv

__all__ = ["add_arguments", "run"]


def run(args) -> int:
    """``tefcore mechanism``: decompose one root's growth rate into the named terms.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``mechanism`` options.

    Returns
    -------
    int
        The exit status.
    """
    from ..linear.mechanism import mechanism
    from ..linear.stability import stability
    from .text import mechanism_choice, wrap

    cfg = load_for_csv(args)
    point = stability(cfg)
    # no --mode: mechanism's default, the flutter root when unstable, else the TEF mode
    res = mechanism(cfg, mode=args.mode, knockouts=not args.no_knockouts,
                    stability_result=point)
    if args.csv:
        write_csv(res.table, args.csv, float_format="%.10g")
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


def add_arguments(sub, add) -> None:
    """Add ``mechanism`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "mechanism", "why a root is (un)stable: work of each term, knockouts",
            "Decompose one root's growth rate into the work of the named terms of the "
            "linearised equations (they add up to its real part), and follow the root with "
            "each term knocked out. CSV columns: term, contribution_real, "
            "contribution_imag; rows: one per term, 'total' (the root's eigenvalue, /rev) "
            "and 'knockout <term>' (the root's eigenvalue with that term removed).", run)
    p.add_argument("--mode", default=None,
                   help="'TEF' (the root the flap mode becomes), 'flutter' (the least stable "
                        "flap-induced root) or a root's name, e.g. 'blade torsion 1' "
                        "(default: the flutter root when it is unstable, else TEF)")
    p.add_argument("--csv", default=None, help="write the decomposition to this CSV file")
    p.add_argument("--no-knockouts", action="store_true", help="skip the knockouts (faster)")
