"""Exceptional points inside a claim's range, and the other choice of names there.

At an exceptional point of the family in (parameter, blade-flap coupling)
which root carries a name has no answer (docs/theory.md 9.3).  A claim whose
range holds one of its mode is checked both ways
(:func:`tefcore.paper.claims.checks.validate_figure`); these are the pieces:
which points lie in a claim's range, a figure's table with a pair's names
exchanged beyond them, and what the flutter root says where the TEF's name
has no answer.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from ...modes.names import base_name, is_locked, locked_name, pair_labels
from ...modes.roles import FLUTTER_ROOT, exceptional_points
from .curves import X_SLACK

__all__ = ["exceptional_in_range", "flutter_reading", "swapped", "where"]


def exceptional_in_range(frame, mode, lo, hi):
    """The exceptional points of `mode` in [lo, hi] (rows of :func:`exceptional_points`).

    There the names of two roots exchange (or two paths from zero coupling
    meet): which root is `mode` has no answer.  The flutter root is a role
    decided at every point.

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's long table (``x``, ``track``, ``label``, ...).
    mode : str
        The claim's mode (a name, or ``"flutter root"``: none).
    lo, hi : float or None
        The claim's range (None: the table's).

    Returns
    -------
    list of pandas.Series
        Rows of :func:`tefcore.modes.roles.exceptional_points`: a names
        exchange strictly inside the range, paths that meet within it.
    """
    if not mode or mode == FLUTTER_ROOT or "track" not in frame:
        return []
    eps = exceptional_points(frame)
    if eps.empty:
        return []
    x = frame["x"].to_numpy(float)
    a = np.nanmin(x) if lo is None else lo
    b = np.nanmax(x) if hi is None else hi
    tol = X_SLACK * max(abs(a), abs(b), 1e-300)
    named = np.array([base_name(mode) in pair_labels(m) for m in eps["modes"]], bool)
    # names exchange strictly between two points (an open bracket); paths
    # meet at a point (closed, to the x slack)
    at = (eps["kind"] == "paths meet").to_numpy()
    lo_, hi_ = eps["x_low"].to_numpy(float), eps["x_high"].to_numpy(float)
    inside = np.where(at, (hi_ >= a - tol) & (lo_ <= b + tol), (hi_ > a + tol) & (lo_ < b - tol))
    return [r for _, r in eps[named & inside].iterrows()]


def where(e) -> str:
    """Where an exceptional point lies, in words.

    Parameters
    ----------
    e : mapping
        A row of :func:`tefcore.modes.roles.exceptional_points`.

    Returns
    -------
    str
        ``"at x = ..."`` or ``"between x = ... and ..."``, with the two
        modes' uncoupled frequencies in brackets where known
        (:func:`tefcore.modes.roles.uncoupled_relation`).
    """
    place = (f"at x = {e['x_low']:.4g}" if e["x_low"] == e["x_high"]
             else f"between x = {e['x_low']:.4g} and {e['x_high']:.4g}")
    note = e.get("uncoupled", "")
    return f"{place} [{note}]" if isinstance(note, str) and note else place


def swapped(frame, points) -> pd.DataFrame:
    """`frame` with the names of each exceptional point's pair exchanged beyond it.

    A names exchange: on the far side of the bracket (``x >= x_high``); paths
    that meet: at that point.  The other choice of which root carries each
    name there.

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's long table.
    points : list
        Rows of :func:`tefcore.modes.roles.exceptional_points`.

    Returns
    -------
    pandas.DataFrame
        A copy with ``label`` exchanged (a locked suffix kept).
    """
    frame = frame.copy()
    labels = frame["label"].astype(object).to_numpy().copy()
    x = frame["x"].to_numpy(float)
    for e in points:
        a, b = pair_labels(e["modes"])
        where = x == e["x_low"] if e["kind"] == "paths meet" else x >= e["x_high"]
        for i in np.flatnonzero(where):
            name = str(labels[i])
            base = base_name(name)
            if base in (a, b):
                other = b if base == a else a
                labels[i] = locked_name(other) if is_locked(name) else other
    frame["label"] = labels
    return frame


#: Quantities of a root's stability: a claim on them about the TEF has a reading
#: on the flutter root (:func:`flutter_reading`).
STABILITY_QUANTITIES = ("real_part", "damping", "damping_ratio")


def flutter_reading(claim, check) -> str:
    """The same check with the flutter root in the TEF's place, for an undecided TEF.

    Where an exceptional point leaves the TEF's name without an answer, the
    question the paper's sentence is about -- does the flap flutter, and
    where -- still has one: the flutter root (the least stable flap-induced
    root, :func:`tefcore.modes.roles.flutter_root`) is a role decided at
    every point.  Its verdict is told beside the claim's ``ambiguous``
    status, never in place of it: the claim is about the TEF mode.

    Parameters
    ----------
    claim : tefcore.paper.claims.reference.Claim
        An undecided claim.
    check : callable
        ``Claim -> row`` (a dict with ``status`` and ``computed``): the claim
        check of the figure it belongs to.

    Returns
    -------
    str
        ``"; the same check on the flutter root instead (...): fail (...)"``
        (what it computed, or why it could not), or empty for a claim that
        does not name the TEF with a stability quantity
        (:data:`STABILITY_QUANTITIES`), or that the flutter root does not
        decide either.
    """
    quantity = {"mode": claim.quantity, "other_mode": claim.other_quantity or claim.quantity}
    swap = {k: FLUTTER_ROOT for k in ("mode", "other_mode")
            if getattr(claim, k) == "TEF" and quantity[k] in STABILITY_QUANTITIES}
    if not swap:
        return ""
    row = check(dataclasses.replace(claim, **swap))
    # what was computed, or why nothing was (no flap-induced root in the sweep)
    detail = row["computed"] or row["reason"]
    if row["status"] not in ("pass", "fail") or not detail:
        return ""
    return (f"; the same check on the flutter root instead (the least stable flap-induced "
            f"root, a role decided at every point): {row['status']} ({detail})")
