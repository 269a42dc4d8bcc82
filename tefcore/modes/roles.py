"""The roles a root plays: the TEF mode, the flutter root, and a claim's mode.

A role is a name given to one root of each point, by a rule that says why:

* **the TEF mode** -- the root the uncoupled flap mode becomes when the
  blade-flap coupling is switched on (:func:`anchor_root`, by
  :func:`tefcore.modes.continuation.tef_root`); along a sweep the TEF
  *branch* is that root at the sweep start followed from point to point
  (:func:`assign_roles`, by :func:`tefcore.modes.tracking.follow_branch`);
* **the flutter root** -- the least stable root of a point in which the flap
  participates by at least :data:`FLUTTER_PARTICIPATION`
  (:func:`flutter_root`, :func:`flutter_root_rows`);
* **a claim's mode** -- the rows of a figure's table that a claim about
  ``"TEF"``, ``"blade torsion 1"`` or ``"flutter root"`` is about
  (:func:`mode_rows`), and where their identity is not decided
  (:func:`undecided_at`, :func:`branch_gap`).

Examples
--------
>>> import pandas as pd
>>> modes = pd.DataFrame({"label": ["blade flap 1", "TEF", "blade torsion 1"],
...                       "real_part": [-0.2, -0.05, 0.3], "share_TEF": [0.01, 0.8, 0.4]})
>>> flutter_root(modes)        # the torsion root, unstable and 40 % flap
2
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .continuation import tef_root
from .tracking import follow_branch

__all__ = ["FLUTTER_PARTICIPATION", "FLUTTER_ROOT", "ModeNotFound", "anchor_root",
           "anchor_row", "assign_roles", "branch_gap", "flutter_root", "flutter_root_rows",
           "has_label", "mode_rows", "undecided_at"]

#: Least share of the flap's participation for a root to count as a flutter
#: root of the flap: a tenth, so that a blade mode barely touched by the flap
#: (shares of 1e-3 ... 1e-2 on MDART) is not named, while both partners of a
#: flap-torsion coalescence (0.3-0.5 each, measured) are.
FLUTTER_PARTICIPATION = 0.1

#: The ``mode`` of a claim about the flutter root of each point.
FLUTTER_ROOT = "flutter root"


class ModeNotFound(ValueError):
    """The rows a mode's role asks for are not in the table."""


# ------------------------------------------------------------------ one point


def flutter_root(modes: pd.DataFrame, threshold: float = FLUTTER_PARTICIPATION):
    """Row of the least stable root with a flap participation >= ``threshold``, or None.

    Parameters
    ----------
    modes : pandas.DataFrame
        A stability modes table (:attr:`tefcore.linear.stability.StabilityResult.modes`)
        with ``real_part`` and ``share_TEF`` (without it, a point function that
        does not report the flap's share: every root counts).
    threshold : float, optional
        Smallest flap participation of a flutter root.

    Returns
    -------
    int or None
        The row's index label.
    """
    if "share_TEF" not in modes:
        return int(modes["real_part"].idxmax()) if len(modes) else None
    cand = modes[modes["share_TEF"] >= threshold]
    if cand.empty:
        return None
    return int(cand["real_part"].idxmax())


def anchor_root(result) -> dict | None:
    """The flap mode of a point by continuation from zero coupling.

    Parameters
    ----------
    result : object
        A point function's result; the continuation
        (:func:`tefcore.modes.continuation.tef_root`) needs its linear system
        (``result.system``) and trim (``result.trim_result``).

    Returns
    -------
    dict or None
        ``{"row", "clear"}``: the row of ``result.modes`` nearest the TEF root
        and whether the continuation met no coalescence; None when the result
        does not carry its linear system (other point functions) or has no flap.
    """
    system = getattr(result, "system", None)
    tr = getattr(result, "trim_result", None)
    if system is None or tr is None or not getattr(tr.model, "has_flap", False):
        return None
    eta, follow = tef_root(system, basis=tr.model.tracking_basis())
    m = result.modes
    eig = m["real_part"].to_numpy() + 1j * m["frequency_per_rev"].to_numpy()
    return {"row": int(np.argmin(np.abs(eig - eta))), "clear": bool(follow.clear)}


def anchor_row(anchor: dict | None, modes: pd.DataFrame, use_anchor: bool = True):
    """Row of the flap mode at a sweep's start, and how it was found.

    Parameters
    ----------
    anchor : dict or None
        The start point's :func:`anchor_root`.
    modes : pandas.DataFrame
        The start point's modes table.
    use_anchor : bool, optional
        Use the continuation where it was clear; else (or when it was not)
        the root with the largest flap participation, else the one labelled
        ``TEF``.

    Returns
    -------
    row : int or None
    method : str
        ``"zero coupling"``, ``"largest flap participation"``, ``"label"`` or ``""``.
    """
    anchor = (anchor or {}) if use_anchor else {}
    if anchor.get("clear"):
        return int(anchor["row"]), "zero coupling"
    if "share_TEF" in modes and len(modes) and modes["share_TEF"].max() > 0:
        return int(modes["share_TEF"].to_numpy().argmax()), "largest flap participation"
    hits = np.flatnonzero(modes["label"].to_numpy() == "TEF")
    return (int(hits[0]), "label") if hits.size else (None, "")


# ------------------------------------------------------------------ along a sweep


def flutter_root_rows(table: pd.DataFrame, threshold: float = FLUTTER_PARTICIPATION):
    """Index of the flutter root's row at each ok point of a sweep table.

    Parameters
    ----------
    table : pandas.DataFrame
        Rows of (point, mode) with ``point``, ``status``, ``real_part`` and
        ``share_TEF``.
    threshold : float, optional
        Smallest flap participation of a flutter root.

    Returns
    -------
    numpy.ndarray
        Index labels of the rows (one per point that has a flutter root).
    """
    if "share_TEF" not in table:
        return np.array([], dtype=table.index.dtype)
    ok = table["status"] == "ok"
    share = table["share_TEF"].where(ok, -1.0).fillna(-1.0)
    cand = table[ok & (share >= threshold)]
    if cand.empty:
        return np.array([], dtype=table.index.dtype)
    return cand.groupby("point", sort=False)["real_part"].idxmax().to_numpy()


def assign_roles(table: pd.DataFrame, points: list, values: list, order: list,
                 first, start_anchor: dict | None, use_anchor: bool = True) -> dict:
    """Columns ``tef_branch``, ``tef_branch_certain`` and ``flutter_root`` of a sweep table.

    Parameters
    ----------
    table : pandas.DataFrame
        The tracked sweep table: one row per (point, mode), with ``key``
        (the point's key), ``status``, ``point``, ``mode_id`` and the mode
        columns; changed in place.
    points : list
        The ok points in parameter order (as :func:`tefcore.modes.tracking.track_modes`
        takes them); ``order`` their keys.
    values : list of float
        Their parameter values (SI).
    order : list
        Keys of `points`.
    first : object or None
        Key of the sweep's start (the first point asked for).
    start_anchor : dict or None
        The start point's :func:`anchor_root`.
    use_anchor : bool, optional
        See :func:`anchor_row`.

    Returns
    -------
    dict
        Where the TEF branch starts: ``point``, ``mode_id``, ``method``; empty
        without one.
    """
    table["tef_branch"] = False
    table["tef_branch_certain"] = False
    table["flutter_root"] = False
    ok = table["status"] == "ok"
    table.loc[flutter_root_rows(table), "flutter_root"] = True
    if first is None:
        return {}
    step_of = {k: i for i, k in enumerate(order)}
    start_modes = points[step_of[first]]["modes"]
    mode_row, method = anchor_row(start_anchor, start_modes, use_anchor)
    if mode_row is None:
        return {}
    rows = table[ok & (table["key"] == first)]
    row = rows.index[rows["mode_id"] == mode_row][0]
    # the branch goes on past an undecided match (tefcore.modes.tracking.follow_branch);
    # a coalescence is a documented convention (the less stable root goes
    # on), not a doubt; an undecided match is
    tracked = table[ok].assign(step=table.loc[ok, "key"].map(step_of))
    path = follow_branch(tracked, points, (step_of[first], mode_row), values=values)
    where = {(order[s], m): c for s, m, c in
             zip(path["step"], path["mode_id"], path["certain"], strict=True)}
    hit = [where.get((k, int(m))) if good else None
           for k, m, good in zip(table["key"], table["mode_id"], ok, strict=True)]
    table["tef_branch"] = [h is not None for h in hit]
    table["tef_branch_certain"] = [bool(h) for h in hit]          # None: not on it
    return {"point": int(table.at[row, "point"]), "mode_id": int(table.at[row, "mode_id"]),
            "method": method}


# ------------------------------------------------------------------ a claim's mode


def has_label(labels: pd.Series, mode: str) -> pd.Series:
    """True where a point label is `mode` (or its locked partner, ``mode (locked)``).

    Parameters
    ----------
    labels : pandas.Series
        Point labels.
    mode : str
        A mode label, e.g. ``"blade torsion 1"``.

    Returns
    -------
    pandas.Series of bool
    """
    return (labels == mode) | (labels == f"{mode} (locked)")


def mode_rows(frame: pd.DataFrame, mode: str, identify: str = "track") -> pd.DataFrame:
    """Rows of a figure's table that are `mode`.

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's long table (an ``x`` column, a sweep's role and track columns).
    mode : str
        ``"TEF"`` (the TEF branch), :data:`FLUTTER_ROOT` (the flutter root of
        each point) or a label (``"blade torsion 1"``: its track, the longest
        one labelled so at its start).
    identify : {"track", "label"}, optional
        ``"label"``: at each point the root labelled `mode` there instead
        (the most participating one if several).

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    ModeNotFound
        The table has no such rows.
    """
    col = "label_here" if identify == "label" and "label_here" in frame else "label"
    if mode == FLUTTER_ROOT:
        if "flutter_root" not in frame:
            raise ModeNotFound("the result has no flutter roots (no flap participation)")
        rows = frame[frame["flutter_root"].fillna(False).astype(bool)]
        if rows.empty:
            raise ModeNotFound(f"no root with a flap participation >= {FLUTTER_PARTICIPATION} "
                               "in the sweep")
        return rows
    if mode == "TEF" and identify == "track" and "tef_branch" in frame:
        rows = frame[frame["tef_branch"].fillna(False).astype(bool)]
        if rows.empty:
            raise ModeNotFound("the sweep has no TEF branch (no flap mode at its start)")
        return rows
    ok = has_label(frame[col], mode)
    if not ok.any():
        raise ModeNotFound(f"no mode {mode!r} in the result; labels: "
                           f"{sorted(set(frame[col].dropna().astype(str)))}")
    if col == "label_here":
        t = frame[ok]
        if "participation" in t:
            t = t.sort_values("participation", ascending=False, kind="stable")
        return t.drop_duplicates("x")
    sizes = frame[ok].groupby("track", sort=False).agg(n=("x", "size"), label=("label", "first"))
    sizes = sizes.assign(exact=sizes["label"] == mode).sort_values(
        ["n", "exact"], ascending=False, kind="stable")
    return frame[frame["track"] == sizes.index[0]]


def undecided_at(rows: pd.DataFrame, mode: str, lo, hi, slack: float) -> list[float]:
    """x of the rows of `mode` (within [lo, hi] and before) whose identity is not decided.

    Parameters
    ----------
    rows : pandas.DataFrame
        :func:`mode_rows` of `mode`.
    mode : str
        The mode.
    lo, hi : float or None
        The range a claim checks (None: the whole sweep).
    slack : float
        Relative tolerance on the range's ends.

    Returns
    -------
    list of float
    """
    if "identity" not in rows:
        return []
    x = rows["x"].to_numpy(float)
    upto = np.ones(len(rows), bool) if hi is None else x <= hi * (1 + slack) + slack
    if mode == "TEF" and "tef_branch_certain" in rows:
        bad = ~rows["tef_branch_certain"].fillna(False).astype(bool).to_numpy()
    else:
        # a coalescence is followed by convention (the less stable root goes
        # on, tefcore.modes.tracking); only an undecided match is a doubt
        bad = rows["identity"].astype(str).to_numpy() == "ambiguous"
    inside = upto if lo is None else upto & (x >= lo * (1 - slack) - slack)
    if mode == "TEF":
        bad &= inside
    else:
        bad &= upto
    return sorted(set(np.round(x[bad], 12).tolist()))


def branch_gap(frame: pd.DataFrame, branch: pd.DataFrame, lo, hi, slack: float) -> str | None:
    """Why the TEF branch does not cover a checked range, or None when it does.

    The branch ends where no root of the next point continues it
    (:func:`tefcore.modes.tracking.follow_branch`); beyond it, which root is the
    TEF is not decided.

    Parameters
    ----------
    frame : pandas.DataFrame
        The figure's long table.
    branch : pandas.DataFrame
        Its TEF-branch rows.
    lo, hi : float or None
        The checked range (None: the sweep's).
    slack : float
        Relative tolerance on the range's ends.

    Returns
    -------
    str or None
    """
    own = frame[frame["refinement"] == 0] if "refinement" in frame else frame
    xs = own["x"].to_numpy(float)
    xs = xs[np.isfinite(xs)]
    if xs.size == 0 or branch.empty:
        return None
    a = xs.min() if lo is None else lo
    b = xs.max() if hi is None else hi
    bx = branch["x"].to_numpy(float)
    tol = slack * max(abs(a), abs(b), 1e-300)
    if bx.max() < min(b, xs.max()) - tol:
        return (f"the TEF branch ends at x = {bx.max():.4g} (no root continues it), before "
                f"{min(b, xs.max()):.4g}")
    if bx.min() > max(a, xs.min()) + tol:
        return f"the TEF branch starts at x = {bx.min():.4g}, after {max(a, xs.min()):.4g}"
    return None
