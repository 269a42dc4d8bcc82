"""What a claim reads: its figure's frames, its mode's series, and how a check can end.

A claim's series is its mode -- at each point the root of that name, the
uncoupled mode it continues from (:mod:`tefcore.modes.continuation`), or the
point's flutter root -- and quantity, sorted by x, failed points left out
(:func:`claim_series`).  A range holding an exceptional point of the mode
raises :class:`Ambiguous` with the points; a locked root's frequency carries
its possible readings (:func:`lock_readings`).  :class:`Context` builds the
frames a claim asks for (its figure, a variant, another figure) on demand and
carries the choices a near tie is checked under.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from ...modes.matching import LOCK_TOL
from ...modes.roles import ModeNotFound, mode_rows
from ..figures.catalogue import variant_key
from ..figures.frames import compute_figure, figure_frame, natural_frequency_frame
from ..figures.quantities import x_to_si
from .curves import X_SLACK
from .exceptional import exceptional_in_range, swapped, where

if TYPE_CHECKING:
    from .reference import Claim

__all__ = ["Ambiguous", "ClaimFailed", "Context", "NotEvaluated", "claim_series",
           "lock_readings", "select_mode", "g4"]


class ClaimFailed(Exception):
    """The model result cannot support the claim (status ``fail``)."""


class NotEvaluated(Exception):
    """A result the claim needs was not given (status ``not reproducible``)."""


def g4(v) -> str:
    """A number as the claims table writes it: four significant digits.

    Parameters
    ----------
    v : float
        The number.

    Returns
    -------
    str
    """
    return f"{v:.4g}"


class Ambiguous(Exception):
    """The claim's mode cannot be identified over its range (status ``ambiguous``).

    ``points``: the exceptional points behind it, each ``(frame key, row of
    :func:`tefcore.modes.roles.exceptional_points`)`` -- the claim is checked
    with the names on either side of each before it is left undecided.

    Parameters
    ----------
    message : str
        Why: the point and its kind.
    points : sequence, optional
        The exceptional points behind it.
    """

    def __init__(self, message, points=()):
        super().__init__(message)
        self.points = list(points)


def select_mode(frame, mode) -> pd.DataFrame:
    """:func:`tefcore.modes.roles.mode_rows`; a mode not in the result fails the claim.

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's frame.
    mode : str
        The claim's mode.

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    ClaimFailed
        The mode is not in the result.
    """
    try:
        return mode_rows(frame, mode)
    except ModeNotFound as err:
        raise ClaimFailed(str(err)) from None


def claim_series(frame, mode, quantity, lo=None, hi=None, until=None, identity=True):
    """(x, y) of one mode and quantity, sorted by x, within [lo, hi].

    Only the points the figure asks for (``refinement == 0``); raises
    :class:`Ambiguous` when an exceptional point of the mode lies in the
    range (up to ``until`` if given: a value at one x needs the identity up
    to there) -- unless `identity` is False (a scale read off the panel, which
    is the same whichever root carries the name).

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's frame (:func:`tefcore.paper.figures.frames.figure_frame`).
    mode : str
        The claim's mode ("" for the whole frame).
    quantity : str
        The column read.
    lo, hi : float, optional
        The claim's range in SI x.
    until : float, optional
        The last x whose identity the claim needs.
    identity : bool, optional
        Whether an exceptional point of the mode stops the claim.

    Returns
    -------
    x, y : numpy.ndarray
        The series, sorted by x.
    locked : numpy.ndarray of bool
        Its points at a lock (a real multiplier), for a frequency.
    """
    if quantity not in frame:
        raise ClaimFailed(f"the result has no {quantity!r} column")
    if quantity == "frequency_per_rev" and "frequency_tracked" in frame:
        # the curve the panel plots: each root's frequency continuous along the
        # sweep (the point's own Floquet convention jumps by whole /rev where
        # its dominant harmonic changes: Fig. 9's TEF at c_cg 0.08-0.10 and
        # from 0.23 on, docs/theory.md 9.4)
        # -- except at a lock: a real multiplier reads k - 1/2 and k + 1/2 alike,
        # and continuity's choice between them moves with the points around it
        # (a refinement point more or less), so a locked root keeps its own
        # reading, its dominant harmonic, and the claim is checked with every
        # reading (lock_readings)
        own = frame["frequency_per_rev"].to_numpy(float)
        at_lock = np.abs(2 * own - np.round(2 * own)) <= 20 * LOCK_TOL
        frame = frame.assign(frequency_per_rev=np.where(
            at_lock, own, frame["frequency_tracked"].to_numpy(float)))
    t = select_mode(frame, mode) if mode else frame
    if identity:
        points = exceptional_in_range(frame, mode, lo, hi if until is None else until)
        if points:
            e = points[0]
            raise Ambiguous(f"an exceptional point of {e['modes']} lies {where(e)}, inside "
                             f"the claim's range ({e['kind']}): which root is {mode!r} has "
                             "no answer there", [(None, p) for p in points])
    if "refinement" in t:
        t = t[t["refinement"] == 0]
    t = t[np.isfinite(t[quantity].to_numpy(float))].sort_values("x")
    x, y = t["x"].to_numpy(float), t[quantity].to_numpy(float)
    locked = _locked_rows(t, quantity)
    if lo is not None:
        slack = X_SLACK * max(abs(lo), abs(hi), 1e-300)
        keep = (x >= lo - slack) & (x <= hi + slack)
        x, y, locked = x[keep], y[keep], locked[keep]
    return x, y, locked


def _locked_rows(t, quantity) -> np.ndarray:
    """Rows whose frequency is a lock's: a real Floquet multiplier (the point's own
    frequency at a multiple of 1/2 /rev, within :data:`LOCK_TOL` ten times)."""
    if quantity != "frequency_per_rev" or "frequency_per_rev" not in t:
        return np.zeros(len(t), bool)
    raw = t["frequency_per_rev"].to_numpy(float)
    return np.abs(2 * raw - np.round(2 * raw)) <= 20 * LOCK_TOL


def lock_readings(x, y, locked) -> list[tuple[int, tuple[float, ...]]]:
    """The frequencies a locked point may read, where the curve cannot tell them apart.

    A real multiplier is its own conjugate: its frequency is known modulo 1/rev
    *and* up to its sign, so a root locked at 4.5 /rev reads 3.5 or 5.5 as
    well, every representation a whole /rev from the next.  Continuity along
    the curve says which (:func:`tefcore.modes.matching.continuous_frequency`)
    only as far as the unlocked points beside it reach: a reading within 1 /rev
    of the straight line through the nearest unlocked point on each side (or
    the two nearest on one side, at an end of the curve) is possible; with no
    unlocked point, every reading within 1 /rev of the point's own.

    Parameters
    ----------
    x, y : numpy.ndarray
        The curve: the swept values and the frequencies as read (continuous).
    locked : numpy.ndarray of bool
        The points at a lock (a real multiplier).

    Returns
    -------
    list of (int, tuple of float)
        Per locked point: its index and its possible readings, its own first.

    Examples
    --------
    The imbalanced TEF locked at the soft end of Fig. 12, its curve rising
    through 7.04 and 9.24 /rev beyond:

    >>> lock_readings(np.array([55.3, 82.9, 110.5, 138.2]),
    ...               np.array([4.5, 5.5, 7.04, 9.24]), np.array([1, 1, 0, 0], bool))
    [(0, (4.5, 3.5)), (1, (5.5, 4.5))]
    """
    out = []
    free = np.flatnonzero(~locked)
    for i in np.flatnonzero(locked):
        left, right = free[free < i], free[free > i]
        pair = ([left[-1], right[0]] if left.size and right.size
                else list(right[:2]) if right.size >= 2 else list(left[-2:]))
        if len(pair) == 2 and x[pair[1]] != x[pair[0]]:
            line = y[pair[0]] + (y[pair[1]] - y[pair[0]]) * (x[i] - x[pair[0]]) / (
                x[pair[1]] - x[pair[0]])
        else:
            line = y[i]
        cand = [y[i]] + [y[i] + s for s in (-1.0, 1.0) if abs(y[i] + s - line) < 1.0]
        out.append((int(i), tuple(float(v) for v in cand)))
    return out


class Context:
    """Frames of the figure, its variants and other figures, built on demand.

    Parameters
    ----------
    name : str
        The figure whose claims are checked.
    result : object
        Its result (a sweep result, or a figure's table).
    cfg : tefcore.config.configuration.Config or None
        The base configuration runs it adds are computed on.
    variants : dict or None
        Variant key -> the figure's result with those overrides.
    others : dict or None
        Figure -> result, for claims that compare figures.
    compute_missing : bool
        Compute a result a claim needs and that was not given.
    """

    def __init__(self, name, result, cfg, variants, others, compute_missing):
        self.name, self.cfg, self.compute = name, cfg, compute_missing
        self.results = {(name, ""): result}
        for key, res in (variants or {}).items():
            self.results[(name, key)] = res
        for fig, res in (others or {}).items():
            self.results.setdefault((fig, ""), res)
        self.frames: dict = {}
        self.swaps: dict = {}        # frame key -> exceptional points taken the other way
        self.strict = True           # an exceptional point in a claim's range stops it
        self.reading: dict = {}      # (frame key, mode, x) -> a locked point's other reading
        self.locks: list = []        # the locked points the claim's series read, and theirs

    def frame(self, fig, overrides=None, quantity=""):
        key = (fig, variant_key(overrides or {}))
        if key not in self.frames:
            res = self.results.get(key)
            if res is None:
                if not self.compute:
                    what = f"{fig} with {key[1]}" if key[1] else fig
                    raise NotEvaluated(f"needs the result of {what} (validate_all runs it)")
                res = compute_figure(fig, self.cfg, overrides=overrides or {})
            self.frames[key] = figure_frame(fig, res)
        f = self.frames[key]
        if quantity == "natural_frequency_per_rev" and quantity not in f:
            nkey = key + ("natural",)
            if nkey not in self.frames:
                self.frames[nkey] = natural_frequency_frame(fig, f, self.cfg, overrides or {})
            f = self.frames[nkey]
        return f

    def series(self, c: Claim, fig=None, mode=None, quantity=None, interval=None,
               overrides=None, until=None, identity=True):
        fig, mode = fig or c.figure, c.mode if mode is None else mode
        quantity = quantity or c.quantity
        overrides = c.overrides if overrides is None else overrides
        lo = hi = None
        if interval is not None:
            lo, hi = (float(v) for v in x_to_si(fig, np.asarray(interval, float), c.x_unit))
        key = (fig, variant_key(overrides or {}))
        frame = self.frame(fig, overrides, quantity)
        if self.swaps.get(key):
            frame = swapped(frame, self.swaps[key])
        try:
            x, y, locked = claim_series(frame, mode, quantity, lo, hi, until,
                                   identity and self.strict)
        except Ambiguous as err:
            err.points = [(key, p) for _, p in err.points]
            raise
        if len(x) == 0:
            raise ClaimFailed(f"no {mode or quantity} points" + (f" in {interval}" if lo else ""))
        if locked.any():
            y = y.copy()
            for i, cand in lock_readings(x, y, locked):
                where = (key, mode, float(x[i]))
                self.locks.append((where, cand))
                y[i] = self.reading.get(where, y[i])
        return x, y
