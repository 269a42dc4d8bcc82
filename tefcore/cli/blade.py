"""``tefcore modes`` and ``tefcore fanplot``: the rotating blade's modes, a table and a picture."""

from __future__ import annotations

import math
from pathlib import Path

from ..safe_io import atomic_output, check_outputs
from .common import inputs, load, load_for_csv, number, write_csv

__all__ = ["add_arguments", "run_fanplot", "run_modes"]


def run_modes(args) -> int:
    """``tefcore modes``: the coupled blade modes at one collective pitch, as a table.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``modes`` options.

    Returns
    -------
    int
        The exit status.
    """
    from ..structure.blade import blade_modes

    cfg = load_for_csv(args)
    table = blade_modes(cfg, n_modes=args.n_modes,
                        collective=math.radians(args.collective)).table()
    if args.csv:
        write_csv(table, args.csv)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    return 0


def run_fanplot(args) -> int:
    """``tefcore fanplot``: the blade's frequencies against rotor speed, to an image.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``fanplot`` options.

    Returns
    -------
    int
        The exit status.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.figure

    from ..structure.blade import fan_plot

    cfg = load(args)
    fmt = Path(args.out).suffix.lstrip(".").lower() or "png"
    if fmt not in matplotlib.figure.Figure().canvas.get_supported_filetypes():
        raise ValueError(f"--out {args.out}: unknown image format {fmt!r}")
    check_outputs([(args.out, "--out", fmt)], inputs=inputs(args, cfg))
    ax = fan_plot(cfg, n_modes=args.n_modes)
    ax.set_title(cfg.name)
    with atomic_output(args.out, "wb", what="--out") as f:
        ax.figure.savefig(f, format=fmt, dpi=120, bbox_inches="tight")
    print(f"wrote {args.out}")
    return 0


def add_arguments(sub, add) -> None:
    """Add ``modes`` and ``fanplot`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "modes", "coupled blade modes (frequencies, labels) as a table",
            "Rotating blade modes of the configuration (finite elements, flap included) "
            "at one collective pitch: frequency (/rev) and label of each mode.", run_modes)
    p.add_argument("--n-modes", type=number("--n-modes", 1, integer=True), default=None,
                   help="number of modes (default: the configuration's model.n_modes)")
    p.add_argument("--collective", type=number("--collective", -90, 90, unit="deg"),
                   default=0.0, help="pitch at 0.75R [deg]")
    p.add_argument("--csv", default=None, help="also write the table to this CSV file")
    p = add(sub, "fanplot", "fan plot (frequency vs rotor speed) to an image",
            "Blade mode frequencies against rotor speed (fan plot), written to an image "
            "whose format follows the file name (png, pdf, svg, ...).", run_fanplot)
    p.add_argument("--n-modes", type=number("--n-modes", 1, integer=True), default=None,
                   help="number of modes")
    p.add_argument("--out", default="fanplot.png", help="image file (default: fanplot.png)")
