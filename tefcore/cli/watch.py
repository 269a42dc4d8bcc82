"""The ``tefcore`` subcommands that let a user watch a root: ``simulate`` and ``explore``.

``simulate`` marches the linearised (and optionally the nonlinear) equations
from a small perturbation of the trim, fits the growth and compares it with
the Floquet root (:mod:`tefcore.timedomain.simulate`), and writes the time
history, a JSON summary and an animation.  ``explore`` serves the root-map
explorer as a web page with voila (:mod:`tefcore.paper.explorer_app`).
:func:`add_arguments` adds them to the parser of :mod:`tefcore.cli`.
"""

from __future__ import annotations

from ..safe_io import atomic_output, check_outputs
from ..timedomain.limits import MAX_AMPLITUDE, MAX_ANIMATED_REVS, MAX_REVS
from .common import config_file, inputs, load, number

__all__ = ["add_arguments", "run_explore", "run_simulate"]


def run_simulate(args) -> int:
    """Run ``tefcore simulate``: march from a perturbation, fit the growth, compare with Floquet.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments.

    Returns
    -------
    int
        The exit status.
    """
    import json

    from ..timedomain.animation import check_writer, save_animation
    from ..timedomain.outputs import json_document, summary_lines
    from ..timedomain.simulate import simulate
    from .text import wrap

    cfg = load(args)
    if args.nonlinear:
        from ..timedomain.nonlinear import check_nonlinear

        check_nonlinear(cfg)
    outputs = [(p, w, k) for p, w, k in ((args.csv, "--csv", None), (args.json, "--json", None),
                                         (args.gif, "--gif", "gif"), (args.mp4, "--mp4", "mp4"))
               if p]
    check_outputs(outputs, inputs=inputs(args, cfg))
    if args.mp4:
        check_writer(args.mp4, "mp4")
    res = simulate(cfg, args.mode, impulse=args.impulse, revs=args.revs,
                   amplitude=args.amplitude, nonlinear=args.nonlinear,
                   work=not args.no_work)
    for line in summary_lines(res):
        print(wrap(line, indent="    "))
    if args.csv:
        with atomic_output(args.csv, newline="", what="--csv") as f:
            res.history.to_csv(f, index=False, float_format="%.10g")
    if args.json:
        with atomic_output(args.json, what="--json") as f:
            json.dump(json_document(res.summary, res.work, res.floquet_work), f, indent=1)
            f.write("\n")
    for path, fmt in ((args.gif, "gif"), (args.mp4, "mp4")):
        if path:
            save_animation(res, path, fmt, revs=args.anim_revs)
    if outputs:
        print(f"wrote {', '.join(p for p, _, _ in outputs)}")
    return 0


def _simulate_parser(sub, add) -> None:
    """The ``simulate`` subcommand's options (docs/theory.md section 12)."""
    p = add(sub, "simulate", "march from a perturbation: growth against Floquet, animation",
             "Integrate the linearised periodic equations (the system the Floquet analysis "
             "uses) about the trim from a small perturbation -- the flutter root's periodic "
             "shape when it is unstable, else the TEF mode's -- fit the growth rate of the "
             "response (least squares on the log of its per-revolution envelope) and compare "
             "it with the Floquet real part. Growth rates are per radian of azimuth, as the "
             "real parts of 'tefcore stability'.", run_simulate,
             epilog="example:\n  tefcore simulate -s flight.advance_ratio=0.3 -s "
                    "flap.overhang=0.29 -s flap.cg_offset=0.33 --revs 6 --json s.json "
                    "--gif s.gif")
    p.add_argument("--mode", default=None,
                   help="start from this root: 'TEF', 'flutter' or a root's name, e.g. "
                        "'blade torsion 2' (default: the flutter root when unstable, else TEF)")
    p.add_argument("--impulse", action="store_true",
                   help="start from a flap impulse (an initial flap rate) instead of a shape")
    p.add_argument("--revs", type=number("--revs", 0, MAX_REVS, low_open=True,
                                         unit="revolutions"),
                   default=6, help=f"revolutions, at most {MAX_REVS} (default: 6)")
    p.add_argument("--amplitude", type=number("--amplitude", 0, MAX_AMPLITUDE, low_open=True,
                                              unit="chords"),
                   default=1e-3, help="largest initial displacement, in chords, at most "
                                      f"{MAX_AMPLITUDE:g} (default: 0.001)")
    p.add_argument("--nonlinear", action="store_true",
                   help="also march the full nonlinear equations from the same perturbation")
    p.add_argument("--no-work", action="store_true",
                   help="skip the work of the named terms per revolution (faster)")
    p.add_argument("--csv", default=None, help="time history: psi_rev, coordinates, physical")
    p.add_argument("--json", default=None, help="summary: growths, mode, agreement, work")
    p.add_argument("--gif", default=None, help="animation (GIF)")
    p.add_argument("--mp4", default=None, help="animation (MP4; needs ffmpeg)")
    p.add_argument("--anim-revs", type=number("--anim-revs", 0, MAX_ANIMATED_REVS,
                                              low_open=True, unit="revolutions"), default=2,
                   help="revolutions animated, 8 frames per cycle of the root, at most "
                        f"{MAX_ANIMATED_REVS} (default 2; the amplitude panel shows all)")


def add_arguments(sub, add) -> None:
    """Add ``simulate`` and ``explore`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    _simulate_parser(sub, add)
    _explore_parser(sub, add)


def run_explore(args) -> int:
    """Run ``tefcore explore``: serve the explorer page with voila.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed arguments.

    Returns
    -------
    int
        voila's exit status.
    """
    import os

    from ..paper.explorer_app import check_voila, serve

    check_voila()                      # one line, before the configuration is read
    load(args)                        # a wrong --set fails here, not in the page's kernel
    # the page's kernel starts in another folder: a configuration file is named absolutely
    config = os.path.abspath(args.config) if config_file(args.config) else args.config
    return serve(config, args.set, port=args.port, open_browser=args.open)


def _explore_parser(sub, add) -> None:
    p = add(sub, "explore", "serve the root-map explorer as a web page (voila)",
            "Serve the explorer as a web page on this machine (127.0.0.1) with voila "
            "(pip install 'tefcore[app]'): sliders for the flap CG offset, overhang, "
            "actuator stiffness and advance ratio redraw the root map and the flutter root's "
            "mechanism bars; a button animates the flutter root. --set changes the base "
            "configuration; Ctrl-C stops the server.", run_explore,
            epilog="example:\n  tefcore explore --port 8866 --open")
    p.add_argument("--port", type=number("--port", 0, 65535, integer=True), default=8866,
                   help="TCP port (default 8866; 0: any free)")
    p.add_argument("--open", action="store_true", help="open the page in the default browser")
