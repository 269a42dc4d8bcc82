"""The sweep's table: its points' named roots, tracked, with their roles; refinement.

A pure function of the points' records (:func:`build_table`): fresh, resumed,
reversed and parallel sweeps give the same table.  Each root carries its
point's name for it (the uncoupled mode it continues from,
:func:`tefcore.modes.continuation.continue_roots`); tracking along the
parameter (:func:`tefcore.modes.tracking.track_modes`) links the roots of
neighbouring points into curves (``track``) and unwraps Floquet frequencies
along them.  Where a root's name changes between neighbouring points (an
exceptional point between them) or tracking is not decided,
:func:`refinements` names the midpoints to evaluate.
"""

from __future__ import annotations

import numbers

import numpy as np
import pandas as pd

from ..modes.matching import continuous_frequency
from ..modes.roles import assign_roles, switch_steps
from ..modes.tracking import ambiguous_steps, track_modes
from .evaluate import decode_complex

__all__ = ["MAX_REFINE", "MAX_REFINE_BRANCH", "MIN_REFINE_BUDGET", "build_table", "refinements"]


#: Bisections of a step whose tracking is ambiguous, at most (1/8 of the step).
MAX_REFINE = 3


#: ... and of a step across which a root's name changes (1/32): an exceptional
#: point lies in it, and the claims about the paper's modes need it located.
MAX_REFINE_BRANCH = 5


#: Points refinement may add to locate exceptional points, and at least for the
#: other steps (else twice the points asked for).
MIN_REFINE_BUDGET = 24


def ok_in_order(records: dict) -> list:
    """Keys of the ok records in the order of the parameter (SI), ties by key."""
    ok = [k for k, r in records.items() if r["status"] == "ok"
          and isinstance(r["value_si"], numbers.Real)]
    return sorted(ok, key=lambda k: (float(records[k]["value_si"]), str(k)))


def tracking_points(records: dict, order: list, frames: dict | None = None) -> list:
    """The ok records in `order` as points of :func:`tefcore.modes.tracking.track_modes`
    (`frames`: their modes tables, key -> DataFrame, where already built)."""
    pts = []
    for k in order:
        r = records[k]
        vec = decode_complex(r["vectors"]) if r.get("vectors") is not None else None
        modes = frames[k] if frames is not None else pd.DataFrame(r["modes"])
        pts.append({"modes": modes, "vectors": vec, "periodic": bool(r.get("periodic", False))})
    return pts


def _tracked(records: dict, order: list, cache: dict | None = None,
             frames: dict | None = None) -> pd.DataFrame:
    """The ok records tracked, each row with its point's name (``label``) and x.

    `cache`: a dict the caller keeps between calls (a sweep's refinement
    rounds, then its table).  The last tracking is reused when the points are
    the very same records' results at the same values -- the final round of
    refinement adds nothing, and tracking them again for the table would
    cost 0.2 s of a 40-point sweep (measured).  The test is by identity of each
    record's ``modes`` and ``vectors`` (held by the cache, so never reused by
    other objects) and equality of the values.  Otherwise each record's point
    is built once (its modes table and decoded vectors), and the march of
    :func:`~tefcore.modes.tracking.track_modes` resumes after the points
    before the first one added (its ``memo``): a refinement round adds
    midpoints, and the steps before the first of them are tracked as before
    (measured on notebook 06's sweeps: without the cache, 1.0 s of decoding
    and 4.2 s of tracking over 28 rounds).
    """
    values = [float(records[k]["value_si"]) for k in order]
    key = ([records[k]["modes"] for k in order], [records[k].get("vectors") for k in order],
           [bool(records[k].get("periodic", False)) for k in order], values)
    if cache and cache.get("key") is not None and _same_points(cache["key"], key):
        return cache["tracked"].copy()
    if cache is None:
        tracked = track_modes(tracking_points(records, order, frames), values=values)
    else:
        tracked = track_modes(_cached_points(records, order, cache, frames), values=values,
                              memo=cache.setdefault("march", {}))
    tracked["label"] = tracked.pop("label_here")
    tracked.insert(1, "value_si", [values[s] for s in tracked["step"].to_numpy(int)])
    if cache is not None:
        cache.update(key=key, tracked=tracked.copy())
    return tracked


def _cached_points(records: dict, order: list, cache: dict, frames: dict | None) -> list:
    """:func:`tracking_points`, each built once per record result (kept in `cache`,
    with the result objects it was built from, so a replaced record is built anew)."""
    held = cache.setdefault("points", {})
    out = []
    for k in order:
        r = records[k]
        have = held.get(k)
        if have is None or have[0] is not r["modes"] or have[1] is not r.get("vectors"):
            pt = tracking_points(records, [k], None if frames is None else {k: frames[k]})[0]
            have = held[k] = (r["modes"], r.get("vectors"), pt)
        out.append(have[2])
    return out


def _same_points(a, b) -> bool:
    """Whether two keys of :func:`_tracked` are the same records' results."""
    return (len(a[0]) == len(b[0])
            and all(x is y for x, y in zip(a[0], b[0], strict=True))
            and all(x is y for x, y in zip(a[1], b[1], strict=True))
            and a[2] == b[2] and a[3] == b[3])


def refinements(records: dict, budgets: dict, main: set,
                cache: dict | None = None) -> list[tuple[float, int, str]]:
    """Midpoints (SI value, depth, budget) of the steps to bisect.

    First the steps across which a root's name changes
    (:func:`tefcore.modes.roles.switch_steps`: an exceptional point lies in
    them), bisected up to :data:`MAX_REFINE_BRANCH` times from the
    ``"branch"`` budget; then the steps whose tracking is ambiguous
    (:data:`MAX_REFINE` times, from the ``"other"`` budget).

    Parameters
    ----------
    records : dict
        Key -> record of the sweep's points (asked for and refinements).
    budgets : dict
        Points left to add: ``{"branch": n, "other": m}``.
    main : set
        Keys of the points asked for.
    cache : dict, optional
        Kept by the caller for :func:`build_table` (the tracking is reused
        when no point was added since).

    Returns
    -------
    list of (float, int, str)
    """
    order = ok_in_order(records)
    if len(order) < 2:
        return []
    tracked = _tracked(records, order, cache)
    step_of = {float(records[k]["value_si"]): i for i, k in enumerate(order)}
    switch = {step_of[b] for _, b in switch_steps(tracked, x="value_si")}

    def mids(steps, limit, which):
        out = []
        for step in sorted(steps):
            a, b = records[order[step - 1]], records[order[step]]
            depth = max(a.get("refinement", 0), b.get("refinement", 0)) + 1
            if depth <= limit and len(out) < budgets[which]:
                out.append((0.5 * (float(a["value_si"]) + float(b["value_si"])), depth, which))
        return out

    return (mids(switch, MAX_REFINE_BRANCH, "branch")
            or mids(ambiguous_steps(tracked), MAX_REFINE, "other"))


def build_table(parameter, values, keys, records, cache=None):
    """Tidy, tracked table from the records, in parameter order.

    Parameters
    ----------
    parameter : str
        The swept field.
    values : list
        The values asked for.
    keys : list of str
        Their keys.
    records : dict
        Key -> record of every point (asked for and refinements).
    cache : dict, optional
        The one :func:`refinements` filled, if any.

    Returns
    -------
    table : pandas.DataFrame
        See :class:`tefcore.sweeps.sweep.SweepResult`.
    modes : dict
        Point index -> modes table.
    shapes : dict
        Point index -> the shapes tracking compared.
    """
    n = len(values)
    main = {k: i for i, k in enumerate(keys)}
    extra = [k for k in ok_in_order(records) if k not in main]
    index_of = dict(main)
    index_of.update({k: n + r for r, k in enumerate(extra)})
    order = ok_in_order({k: records[k] for k in index_of})
    # each record's modes table: with a cache, the one its tracking point holds
    # (built once per record result by the refinement rounds; building all of
    # them again took 13 ms of a 40-point sweep's ~0.25 s after its points)
    frames = ({k: p["modes"] for k, p in zip(order, _cached_points(records, order, cache, None),
                                             strict=True)} if cache is not None
              else {k: pd.DataFrame(records[k]["modes"]) for k in order})
    tracked = _tracked(records, order, cache, frames).drop(columns="value_si")
    tracked.insert(0, "key", np.asarray(order, dtype=object)[tracked.pop("step").to_numpy(int)])
    all_keys = list(keys) + extra
    info = pd.DataFrame({
        "key": pd.Series(all_keys, dtype=object),
        "point": [index_of[k] for k in all_keys],
        "parameter": parameter,
        "value": pd.Series(list(values) + [records[k]["value"] for k in extra], dtype=object),
        "value_si": pd.Series([records[k]["value_si"] for k in all_keys], dtype=object),
        "refinement": [int(records[k].get("refinement", 0)) for k in all_keys],
        "status": [records[k]["status"] for k in all_keys],
        "error": pd.Series([records[k]["error"] for k in all_keys], dtype=object),
        # what the point's result carries a doubt about (C81 inputs clipped), or None
        "warning": pd.Series([records[k].get("warning") for k in all_keys], dtype=object),
    })
    for col in ("value", "value_si"):  # numbers -> float column, else keep objects
        try:
            info[col] = pd.to_numeric(info[col])
        except (TypeError, ValueError):
            pass
    trim = pd.DataFrame([records[k]["trim"] for k in all_keys]).add_prefix("trim_")
    table = info.merge(tracked, on="key", how="left", validate="one_to_many")
    table = table.merge(trim.assign(key=all_keys), on="key", how="left")
    for col in ("track", "mode_id"):
        table[col] = table[col].astype("Int64")
    si = pd.to_numeric(table["value_si"], errors="coerce")
    table = table.assign(_x=si.fillna(np.inf)).sort_values(
        ["_x", "point", "track"], kind="stable", ignore_index=True).drop(columns="_x")
    assign_roles(table)
    _unwrap_by_name(table, any(bool(records[k].get("periodic", False)) for k in order))
    modes = {index_of[k]: frames[k] for k in order}
    shapes = {index_of[k]: decode_complex(records[k]["vectors"]) for k in order
              if records[k].get("vectors") is not None}
    return table.drop(columns="key"), modes, shapes


def _unwrap_by_name(table: pd.DataFrame, periodic: bool) -> None:
    """``frequency_tracked``: each named root's frequency continuous along the sweep.

    Per name (the roots of one uncoupled mode, point by point) and per stretch
    of it on one root (consecutive points of one ``track``), the Floquet
    frequency's representation (1/rev shift, sign) that makes the curve
    smoothest and keeps nearest the points' own convention
    (:func:`tefcore.modes.matching.continuous_frequency`); the flutter root's
    rows are a name's rows too.  Where the name moves to another root (an
    exceptional point between two points) the frequency is that root's in its
    own stretch: smoothing across would write one root as the mirror image of
    its frequency to meet another's (measured on Fig. 12, mu 0.3: the TEF name
    alternating between the flutter root at 13.4-13.9 /rev and a root at
    10.5-11 /rev above 1.5x the actuator stiffness, smoothed as one curve,
    wrote the flutter root at 25 - 13.68 = 11.32).  Constant coefficients: the
    frequency itself.
    """
    if "frequency_tracked" not in table or not periodic:
        return
    ok = (table["status"] == "ok") & table["label"].notna()
    for _, g in table[ok].groupby(table.loc[ok, "label"].astype(str), sort=False):
        x = pd.to_numeric(g["value_si"]).to_numpy(float)
        order = np.argsort(x, kind="stable")
        # a row without a track (none linked it) is a stretch of its own
        track = pd.to_numeric(g["track"], errors="coerce").to_numpy(float)[order]
        new_run = ~(track[1:] == track[:-1])          # NaN: never equal
        run = np.concatenate([[0], np.cumsum(new_run)])
        freq = g["frequency_per_rev"].to_numpy(float)
        carried = (g["frequency_continued"].to_numpy(float) if "frequency_continued" in g
                   else np.full(len(g), np.nan))
        out = freq.copy()
        for r in np.unique(run):
            idx = order[run == r]
            out[idx] = continuous_frequency(x[idx], freq[idx], carried=carried[idx])
        table.loc[g.index, "frequency_tracked"] = out

