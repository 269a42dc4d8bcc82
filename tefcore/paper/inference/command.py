"""``tefcore infer``: run or resume a study of the paper's rotor, and say what it found.

:func:`add_infer_command` adds the subcommand to the ``tefcore`` parser
(:func:`tefcore.paper.run.commands.add_commands` calls it); :func:`cmd_infer`
runs it: the estimate first, then the study (resumed where it stopped), then
its best rotors and the failures met in the space.
"""

from __future__ import annotations

__all__ = ["DESCRIPTION", "add_infer_command", "cmd_infer", "summary_text"]

DESCRIPTION = """\
Infer the paper's unknown rotor properties from its claims: an optuna study
samples the declared space (tefcore/data/inference/mdart-space.toml: every
assumed property a claim can move, each range argued from construction) and
maximises the signed margins of the fitted claims of the declared protocol
(tefcore/data/inference/protocol.toml: the calibration claims and Figs. 6-9
and 12; the held-out claims are never computed inside the study).

The study lives in STORAGE (a journal file, default inference.journal, or an
RDB URL such as sqlite:///inference.db or postgresql://host/db for workers on
many machines).  Run the same command again to resume it: a trial left
running by a killed worker is run again.  --jobs starts that many workers on
the one study.  A trial costs about 12 s of CPU (the estimate is shown before
the study starts, from the study's own trials once it has some).

examples:
  tefcore infer --trials 40
  tefcore infer --trials 40 --reading flutter --jobs 2
  tefcore infer --trials 32 --sampler qmc --seed 1 --storage studies.journal
  tefcore infer --trials 0          # the estimate and what the study holds
"""


def summary_text(study, reading: str, top: int = 3) -> str:
    """The study's best rotors and failures, as lines of text.

    Parameters
    ----------
    study : optuna.Study
        The study.
    reading : str
        The reading the best rotors are ranked by.
    top : int
        How many rotors.

    Returns
    -------
    str
    """
    from .analysis import failures, trials_frame

    f = failures(study)
    lines = [f"{study.study_name}: {f['completed']} rotors checked, {f['refused']} samples "
             f"refused as physically impossible, {f['failed']} trials failed"]
    if f["not_computable"]:
        lines.append("figures not computable: " + ", ".join(
            f"{k} in {v} trials" for k, v in sorted(f["not_computable"].items())))
    frame = trials_frame(study)
    key = f"{reading} objective"
    if frame.empty or key not in frame:
        return "\n".join(lines)
    lines.append(f"best rotors by the {reading} reading (objective: sum of tanh(margin) of the "
                 "fitted claims; passes of the fitted claims per reading):")
    for _, row in frame.sort_values(key, ascending=False).head(top).iterrows():
        per = ", ".join(f"{r} {int(row[f'{r} passes'])}" for r in ("continued", "flutter")
                        if f"{r} passes" in row)
        lines.append(f"  trial {int(row['number'])}: objective {row[key]:+.2f}; passes: {per}")
    return "\n".join(lines)


def cmd_infer(args) -> int:
    """Run ``tefcore infer`` with parsed arguments; return the exit status.

    Parameters
    ----------
    args : argparse.Namespace
        ``reading``, ``sampler``, ``seed``, ``trials``, ``jobs``, ``storage``,
        ``no_progress``.

    Returns
    -------
    int
        0.
    """
    try:
        import optuna  # noqa: F401
    except ImportError:
        raise ValueError("tefcore infer needs optuna: pip install 'tefcore[inference]'") from None
    from .study import StudySpec, estimate, open_study, run_study, seconds_text

    if args.trials < 0:
        raise ValueError(f"--trials {args.trials}: must be at least 0")
    if args.jobs < 1:
        raise ValueError(f"--jobs {args.jobs}: must be at least 1")
    spec = StudySpec(reading=args.reading, sampler=args.sampler, seed=args.seed,
                     storage=args.storage)
    e = estimate(spec, args.trials, args.jobs)
    how = ("measured on its trials, the time at their pace" if e["measured"]
           else "assumed before any trial, the time on free cores")
    print(f"{e['study']} in {args.storage}: {e['done']} trials done, {e['to_run']} to run; "
          f"about {e['cpu_per_trial_s']:.0f} s of CPU per trial, about "
          f"{seconds_text(e['wall_s'])} with {args.jobs} worker(s) ({how})", flush=True)
    study = run_study(spec, args.trials, args.jobs, progress=not args.no_progress) \
        if e["to_run"] else open_study(spec)
    print(summary_text(study, args.reading))
    return 0


def add_infer_command(sub, formatter_class) -> None:
    """Add ``infer`` to the ``tefcore`` subparsers `sub`.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    formatter_class : type
        The ``tefcore`` command's help formatter.
    """
    from .protocol import READINGS, SAMPLERS

    p = sub.add_parser("infer", formatter_class=formatter_class, description=DESCRIPTION,
                       help="infer the paper's unknown rotor properties from its claims "
                            "(an optuna study)")
    p.add_argument("--trials", type=int, default=40,
                   help="finished trials the study should hold (default 40)")
    p.add_argument("--reading", choices=READINGS, default="continued",
                   help="how the paper's 'TEF' is read: the continued root (default) or the "
                        "flutter root")
    p.add_argument("--sampler", choices=SAMPLERS, default="tpe",
                   help="tpe (default), qmc (Sobol points), random, nsga2 (one objective per "
                        "fitted figure)")
    p.add_argument("--seed", type=int, default=0, help="the sampler's seed (default 0)")
    p.add_argument("--jobs", type=int, default=1, help="workers on the study (default 1)")
    p.add_argument("--storage", default="inference.journal", metavar="STORAGE",
                   help="journal file or RDB URL (default inference.journal)")
    p.add_argument("--no-progress", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_infer)
