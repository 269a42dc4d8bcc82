"""The search of the attribution: where along a lever a failing claim's verdict flips.

:func:`find_flip` is the search on its own: given ``passes(t)`` (does the
claim pass with the lever a fraction ``t`` of the way to an end of its
plausible range?) it scans each side of the baseline at the fractions of
``scan``, then beyond the range at ``beyond``, and bisects between the last
failing and the first passing fraction ``depth`` times.  The grid is dyadic,
so the claims of one figure ask for the same configurations and share their
sweeps (:class:`tefcore.paper.attribution.evaluate.FigureCache`).

:func:`lever_rows` runs it for one lever over every failing claim -- one
task of the attribution's parallel run -- and at each flip checks the
flipping claim again on refined sweeps (``confirmed``) and the figure's other
claims, which passed, for conflicts.

Examples
--------
>>> flip = find_flip(lambda t: t >= 0.3)        # passes from 30 % of the way up
>>> flip.t, flip.evaluations                    # 1.0 passes; bisected 3 times
(0.375, 4)
>>> find_flip(lambda t: False, beyond=None).t is None
True
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

from ...runtime import worker_init
from .evaluate import FigureCache, check_claims

__all__ = ["BEYOND", "DEPTH", "SCAN", "Flip", "Target", "band_side", "find_flip", "lever_rows"]

#: Fractions of the way to each end scanned before bisecting (1.0: the end itself;
#: a flip between the baseline and a failing end is not looked for).
SCAN = (1.0,)
#: Fraction scanned beyond the range when it does not flip inside (2: twice as far
#: from the baseline as the end); None: not looked for.
BEYOND = 2.0
#: Bisections of the step where the verdict flips: 3 give an eighth of the step.
DEPTH = 3


@dataclass
class Flip:
    """Result of :func:`find_flip`.

    Attributes
    ----------
    t : float or None
        Signed fraction of the way to an end where the claim first passes
        (within ``1/2**depth`` of the step it flips in), None if it never does.
    evaluations : int
        Calls of ``passes``.
    seen : dict
        Fraction -> the side ``passes`` returned there.
    """

    t: float | None
    evaluations: int
    seen: dict = field(default_factory=dict)


def _state(v):
    """A verdict as a side of the pass band: True -> 0, False -> -1; ints and None as they are."""
    if v is None or (isinstance(v, int) and not isinstance(v, bool)):
        return v
    return 0 if v else -1


def _bisect(call, sign, lo, hi, depth, s0):
    """The first fraction in (lo, hi] whose side is not `s0`, to ``1/2**depth`` of the step;
    if that side is beyond the band (the value jumped over it), up to `depth` more
    bisections look for the band itself."""
    for _ in range(depth):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if call(sign * mid) in (s0, None) else (lo, mid)
    for _ in range(depth):
        if call(sign * hi) == 0:
            return hi
        mid = (lo + hi) / 2
        state = call(sign * mid)
        if state == 0:
            return mid
        lo, hi = (mid, hi) if state in (s0, None) else (lo, mid)
    return hi if call(sign * hi) == 0 else None


def _side(call, sign, limit, grid, depth, s0):
    prev = 0.0
    for t in (g for g in grid if g <= limit):
        state = call(sign * t)
        if state is None:            # the data do not admit it: nothing further out either
            return None
        if state != s0:              # in the band, or across it
            return _bisect(call, sign, prev, t, depth, s0)
        prev = t
    return None


def find_flip(passes: Callable, *, scan=SCAN, beyond=BEYOND, depth: int = DEPTH,
              sides=(1, -1), check_zero: bool = False, baseline: int = -1) -> Flip:
    """The smallest move, on either side, that makes the claim pass.

    Parameters
    ----------
    passes : callable
        ``t -> verdict`` a signed fraction ``t`` of the way to the high
        (``t > 0``) or low end: True (passes) or False (fails), or the side
        of the claim's pass band its value lies on (0 inside: passes; -1
        below, +1 above, so a value that jumps over the band between two
        fractions is found too), or None (the configuration is not admitted).
    scan : sequence of float
        Increasing fractions scanned on each side inside the range.
    beyond : float or None
        A fraction beyond the range (> 1) scanned when nothing inside flips.
    depth : int
        Bisections of the step in which it flips.
    sides : sequence of {1, -1}
        The sides to search (the high side first by default); the second
        only closer to the baseline than a flip on the first.
    check_zero : bool
        Evaluate ``t = 0`` first (a pair whose anchor alone may flip it).
    baseline : int
        The side at ``t = 0`` (-1: a failing claim, or a value below its band).

    Returns
    -------
    Flip
    """
    seen: dict = {}

    def call(t):
        t = float(t)
        if t not in seen:
            seen[t] = _state(passes(t))
        return seen[t]

    if check_zero and call(0.0) == 0:
        return Flip(0.0, len(seen), seen)
    grid = sorted({*scan, *((beyond,) if beyond else ())})
    best = None
    for sign in sides:
        t = _side(call, sign, math.inf if best is None else abs(best), grid, depth, baseline)
        if t is not None and (best is None or t < abs(best)):
            best = sign * t
    return Flip(best, len(seen), seen)


def band_side(claim, status: str, value) -> int | None:
    """Where a claim's check leaves it: 0 passes, -1/+1 below/above its pass band, None refused.

    A value claim (and a threshold with an expected x) has a band; its
    computed value outside it says on which side.  Any other failure is -1.

    Parameters
    ----------
    claim : tefcore.paper.claims.reference.Claim
        The claim.
    status : str
        Its status, or ``"not admitted"``.
    value : float
        Its ``computed_value``.

    Returns
    -------
    int or None

    Examples
    --------
    >>> from tefcore.paper.claims.reference import load_claims
    >>> c = next(c for c in load_claims() if c.id == "fig6-response-15pct-above-input")
    >>> band_side(c, "fail", 1.94), band_side(c, "fail", 2.5), band_side(c, "pass", 2.3)
    (-1, 1, 0)
    """
    if status == "pass":
        return 0
    if status == "not admitted":
        return None
    v = float(value) if value not in ("", None) else math.nan
    if not math.isfinite(v) or claim.kind not in ("value", "threshold") \
            or (claim.kind == "threshold" and claim.expected is None):
        return -1
    if claim.expected is not None:
        tol = claim.tolerance * (abs(claim.expected) if claim.tolerance_type == "relative"
                                 else 1.0)
        hi = claim.expected + tol
    else:
        hi = math.inf if claim.upper is None else claim.upper
    return 1 if v > hi else -1          # below the band, or failing inside it


@dataclass(frozen=True)
class Target:
    """A failing claim to attribute, and the claims of its figure that passed.

    Parameters
    ----------
    claim : tefcore.paper.claims.reference.Claim
        The failing claim.
    notebook : str
        The notebook that checked it (its :class:`RunSettings`).
    peers : tuple of Claim
        The other claims of its figure in that notebook that passed (a change
        that fails one of them is a conflict).
    side : int
        :func:`band_side` of the claim at the baseline (-1 unless its value
        lies above its band).
    """

    claim: object
    notebook: str
    peers: tuple = ()
    side: int = -1


class _Task:
    """One lever over the targets: configurations, checks and cache, memoised."""

    def __init__(self, lever, settings_of, folder):
        self.lever, self.settings_of = lever, settings_of
        self.cache = FigureCache(folder)
        self.configs: dict = {}
        self.checks: dict = {}

    def config(self, notebook, where):
        base = self.settings_of[notebook].base
        if where is None:
            return base
        # keyed by the base's fields, not its notebook: the notebooks share
        # one base configuration unless their parameters differ, and a move
        # can be a whole re-calibration of the torsion (0.5 s; 27 moves for 7
        # settings in the lift slope's task, measured)
        from ...sweeps.store import config_hash

        key = (config_hash(base), where)
        if key not in self.configs:
            try:
                self.configs[key] = self.lever.move(base, where)
            except ValueError as err:
                self.configs[key] = err
        return self.configs[key]

    def check(self, claims, notebook, where, refine=False) -> dict:
        """Claim id -> (status, computed value); ``"not admitted"`` for a refused configuration."""
        key = (tuple(c.id for c in claims), notebook, where, refine)
        if key not in self.checks:
            refused = dict.fromkeys(key[0], ("not admitted", ""))
            cfg = self.config(notebook, where)
            settings = self.settings_of[notebook]
            if refine:
                from dataclasses import replace

                settings = replace(settings, refine=True)
            try:
                t = None if isinstance(cfg, ValueError) else check_claims(
                    claims, cfg, settings, self.cache)
            except ValueError:
                t = None
            self.checks[key] = refused if t is None else {
                i: (st, v) for i, st, v in zip(t["id"], t["status"], t["computed_value"],
                                               strict=True)}
        return self.checks[key]

    def status(self, claim, notebook, where, refine=False) -> str:
        """The claim's status with the lever at `where`."""
        return self.check([claim], notebook, where, refine)[claim.id][0]


def _shown(lever, where) -> str:
    return str(where) if lever.discrete else f"{lever.value(where):.4g}"


def _flip_of(task, target):
    """(where it flips or None, what was seen, evaluations) for one claim and lever."""
    lever, c = task.lever, target.claim

    def passes(where):
        return band_side(c, *task.check([c], target.notebook, where)[c.id])

    if lever.discrete:
        seen = {o: passes(o) for o in lever.options}
        flips = [o for o in lever.options if seen[o] == 0]
        return (flips[0] if flips else None), seen, len(seen)
    sides = [s for s in (1, -1) if (lever.high if s > 0 else lever.low) != lever.base]
    pair = " at " in lever.name and " + " in lever.name
    flip = find_flip(passes, check_zero=pair, sides=sides, baseline=target.side)
    return flip.t, flip.seen, flip.evaluations


def _row(task, target, where, seen, n) -> dict:
    lever, c = task.lever, target.claim
    order = list(seen) if lever.discrete else sorted(seen)
    tried = "; ".join(f"{_shown(lever, w)}: {task.status(c, target.notebook, w)}"
                      for w in order)
    row = {"claim": c.id, "status": "fail", "assumption": lever.name, "flips_at": "",
           "plausible_low": lever.low, "plausible_high": lever.high, "within_plausible": False,
           "figure": c.figure, "setting": lever.setting, "baseline": lever.base,
           "confirmed": "", "conflicts": "", "tried": tried, "evaluations": n,
           "note": lever.note}
    if where is None:
        return row
    inside = lever.discrete or abs(where) <= 1 + 1e-12
    row.update(flips_at=_shown(lever, where), within_plausible=bool(inside))
    row["confirmed"] = task.status(c, target.notebook, where, refine=True) == "pass"
    if target.peers:
        now = task.check(list(target.peers), target.notebook, where)
        row["conflicts"] = "; ".join(f"{k} (pass -> {st})" for k, (st, _) in now.items()
                                     if st != "pass")
    return row


def lever_rows(lever, targets, settings_of: dict, folder) -> tuple[list[dict], float]:
    """Attribution rows of one lever for every target: one parallel task.

    Parameters
    ----------
    lever : tefcore.paper.attribution.levers.Lever or None
        The lever; None checks the targets at the baseline (rows with their
        ``status`` and :func:`band_side` ``side`` there).
    targets : sequence of Target
        The failing claims.
    settings_of : dict
        Notebook -> :class:`~tefcore.paper.attribution.evaluate.RunSettings`.
    folder : path
        This task's own folder of sweep files.

    Returns
    -------
    rows : list of dict
        One per target.
    cpu : float
        CPU seconds of this task's process.
    """
    worker_init()
    start = time.process_time()
    task = _Task(lever, settings_of, folder)
    rows = []
    with warnings.catch_warnings():      # numerical doubts are the notebooks' to report
        warnings.simplefilter("ignore")
        for tg in targets:
            if lever is None:
                status, value = task.check([tg.claim], tg.notebook, None)[tg.claim.id]
                rows.append({"claim": tg.claim.id, "status": status,
                             "side": band_side(tg.claim, status, value)})
                continue
            where, seen, n = _flip_of(task, tg)
            rows.append(_row(task, tg, where, seen, n))
    return rows, time.process_time() - start
