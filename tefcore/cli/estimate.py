"""How long a sweep or map will take, said before it starts; past a bound it needs ``--yes``.

A run of :data:`TIMED_FROM_POINTS` points or more times one point of its
own (cold: the trim from scratch, as the first point of each warm-start
chain) and multiplies by its points over the processes it will use
(:func:`tefcore.runtime.process_count`).  An estimate above
:data:`ESTIMATE_ABOVE_S` is printed before the run starts; one above
:data:`LIMIT_S` is refused, naming the estimate, unless ``--yes`` is given.
The bound keeps a typo (``--range 0 1 100000``, a 1000 x 1000 map) from
occupying the machine for days; a run that long is still one ``--yes``
away.

Examples
--------
>>> duration_text(250), duration_text(7200), duration_text(1.08e9)
('4 min', '2.0 h', '300000.0 h')
"""

from __future__ import annotations

import sys
import time

__all__ = ["ESTIMATE_ABOVE_S", "LIMIT_S", "LIMIT_TEXT", "TIMED_FROM_POINTS", "YES_HELP",
           "announce", "duration_text", "point_seconds"]

#: A run whose estimated time exceeds this [s] prints the estimate before it starts.
ESTIMATE_ABOVE_S = 120.0
#: Runs of fewer points are not timed (timing costs one point; ~1 s at the defaults).
TIMED_FROM_POINTS = 20
#: A run estimated above this [s] is refused without ``--yes``.
LIMIT_S = 3600.0
#: :data:`LIMIT_S` in words, for messages and help.
LIMIT_TEXT = "1 h"
#: The help of ``--yes``.
YES_HELP = (f"start even when the run is estimated at more than {LIMIT_TEXT} (refused "
            "otherwise; the estimate times one point)")


def duration_text(seconds: float) -> str:
    """Seconds in words: minutes below 1.5 h, else hours.

    Parameters
    ----------
    seconds : float
        The duration.

    Returns
    -------
    str
    """
    return f"{seconds / 3600:.1f} h" if seconds >= 5400 else f"{seconds / 60:.0f} min"


def point_seconds(cfg, overrides: dict) -> float:
    """Seconds one point of the default point function takes, timed here (cold).

    A point that fails is timed too: failing is what it costs in the run.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The base configuration.
    overrides : dict
        The point's fields (the run's first point).

    Returns
    -------
    float
    """
    from ..sweeps.evaluate import default_point

    start = time.perf_counter()
    try:
        default_point()(cfg.with_overrides(overrides))
    except Exception:  # a failing point is recorded by the run: its time counts
        pass
    return time.perf_counter() - start


def announce(command: str, points: str, n_points: int, processes: int, cfg, overrides: dict,
             *, yes: bool, after: str) -> None:
    """Time one point; state the estimate above :data:`ESTIMATE_ABOVE_S`, refuse past
    :data:`LIMIT_S` without `yes`.

    Parameters
    ----------
    command : str
        The subcommand (``"map"``), for the lines.
    points : str
        The points in words (``"7 x 5 = 35 points"``).
    n_points : int
        How many.
    processes : int
        Processes that compute them.
    cfg : tefcore.config.configuration.Config
        The base configuration.
    overrides : dict
        The first point's fields.
    yes : bool
        ``--yes``: start past the bound.
    after : str
        What follows the points (``"the boundary is refined"``).

    Raises
    ------
    ValueError
        The estimate is above :data:`LIMIT_S` and `yes` is False; nothing has
        been written.
    """
    if n_points < TIMED_FROM_POINTS:
        return
    each = point_seconds(cfg, overrides)
    seconds = each * n_points / max(1, processes)
    if seconds <= ESTIMATE_ABOVE_S:
        return
    text = (f"{points} at about {each:.2g} s each (one point timed, cold) on {processes} "
            f"process{'es' if processes > 1 else ''}: about {duration_text(seconds)} before "
            f"{after}")
    if seconds > LIMIT_S and not yes:
        raise ValueError(f"{command}: {text}, more than {LIMIT_TEXT}; nothing started: ask "
                         "for fewer points, or add --yes to start it")
    print(f"tefcore {command}: {text}; Ctrl-C stops it (with --out it resumes)", file=sys.stderr,
          flush=True)
