"""``tefcore stability``: trim the rotor, compute its Floquet roots, print them named."""

from __future__ import annotations

from .common import load_for_csv, write_csv

__all__ = ["add_arguments", "run"]


def run(args) -> int:
    """``tefcore stability``: the modes table, its legend, the flutter root and the trim.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``stability`` options.

    Returns
    -------
    int
        The exit status.
    """
    from ..linear.stability import stability
    from .text import flutter_text, legend, modes_text, trim_lines, wrap

    cfg = load_for_csv(args)
    res = stability(cfg)
    # the table's columns: printing them needs no pandas (the CSV does)
    table = res.columns if hasattr(res, "columns") else res.modes
    if args.csv:
        write_csv(res.modes, args.csv)
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


def add_arguments(sub, add) -> None:
    """Add ``stability`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "stability", "trim + Floquet stability, one row per mode",
            "Trim the rotor, linearise about the periodic trim and compute the Floquet "
            "modes: frequency (/rev), real part (/rev), damping ratio and label of each "
            "mode, and the trim controls.", run,
            epilog="example:\n  tefcore stability --set flight.advance_ratio=0.3 "
                   "--csv modes.csv")
    p.add_argument("--csv", default=None, help="also write the mode table to this CSV file")
