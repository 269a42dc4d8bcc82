"""The sweep's table: its points tracked, the TEF branch and flutter roots, refinement.

A pure function of the points' records (:func:`build_table`): fresh, resumed,
reversed and parallel sweeps give the same table.  Where the identity of a
mode between two neighbouring points is not decided, :func:`refinements`
names the midpoints to evaluate.
"""

from __future__ import annotations

import numbers

import numpy as np
import pandas as pd

from ..modes.roles import anchor_row, assign_roles
from ..modes.tracking import ambiguous_steps, follow_branch, track_modes
from .evaluate import decode_complex

__all__ = ["MAX_REFINE", "MAX_REFINE_BRANCH", "MIN_REFINE_BUDGET", "build_table", "refinements"]


#: Bisections of an ambiguous step at most (a step of 1/8 of the original).
MAX_REFINE = 3


#: ... and of a step where the TEF branch itself is ambiguous (1/32): the
#: branch is what the paper's claims are about, and a flap mode veering with
#: a blade mode can turn its shape within a few per cent of a sweep's step.
MAX_REFINE_BRANCH = 5


#: Points refinement may add for the TEF branch, and at least for the other
#: modes (else twice the points asked for).
MIN_REFINE_BUDGET = 24


def ok_in_order(records: dict) -> list:
    """Keys of the ok records in the order of the parameter (SI), ties by key."""
    ok = [k for k, r in records.items() if r["status"] == "ok"
          and isinstance(r["value_si"], numbers.Real)]
    return sorted(ok, key=lambda k: (float(records[k]["value_si"]), str(k)))


def tracking_points(records: dict, order: list) -> list:
    """The ok records in `order` as points of :func:`tefcore.modes.tracking.track_modes`."""
    pts = []
    for k in order:
        r = records[k]
        vec = decode_complex(r["vectors"]) if r.get("vectors") is not None else None
        pts.append({"modes": pd.DataFrame(r["modes"]), "vectors": vec,
                    "periodic": bool(r.get("periodic", False))})
    return pts


def track_records(records: dict, order: list) -> pd.DataFrame:
    """:func:`tefcore.modes.tracking.track_modes` of the ok records in `order`."""
    return track_modes(tracking_points(records, order),
                       values=[float(records[k]["value_si"]) for k in order])


def branch_of(tracked: pd.DataFrame, records: dict, order: list, step: int, row: int):
    """:func:`tefcore.modes.tracking.follow_branch` from mode `row` of point `step` of `order`."""
    return follow_branch(tracked, tracking_points(records, order), (step, row),
                         values=[float(records[k]["value_si"]) for k in order])


def refinements(records: dict, budgets: dict, main: set,
                 use_anchor: bool = True) -> list[tuple[float, int, str]]:
    """Midpoints (SI value, depth, budget) of the steps whose tracking is ambiguous.

    While the TEF branch itself has ambiguous steps that may still be
    bisected (:data:`MAX_REFINE_BRANCH` times, from the ``"branch"`` budget),
    only those are returned; then the others (:data:`MAX_REFINE` times, from
    the ``"other"`` budget).

    Parameters
    ----------
    records : dict
        Key -> record of the sweep's points (asked for and refinements).
    budgets : dict
        Points left to add: ``{"branch": n, "other": m}``.
    main : set
        Keys of the points asked for.
    use_anchor : bool, optional
        Start the TEF branch at the continuation's root
        (:func:`tefcore.modes.roles.anchor_row`).

    Returns
    -------
    list of (float, int, str)
    """
    order = ok_in_order(records)
    if len(order) < 2:
        return []
    tracked = track_records(records, order)
    branch_steps = set()
    first = next((i for i, k in enumerate(order) if k in main), None)
    if first is not None:
        start = records[order[first]]
        row, _ = anchor_row(start.get("anchor"), pd.DataFrame(start["modes"]), use_anchor)
        if row is not None:
            path = branch_of(tracked, records, order, first, row)
            branch_steps = set(path.loc[path["doubt"], "step"])
    def mids(steps, limit, which):
        out = []
        for step in sorted(steps):
            a, b = records[order[step - 1]], records[order[step]]
            depth = max(a.get("refinement", 0), b.get("refinement", 0)) + 1
            if depth <= limit and len(out) < budgets[which]:
                out.append((0.5 * (float(a["value_si"]) + float(b["value_si"])), depth, which))
        return out

    # the TEF branch's own doubts first, round after round, then the others
    return (mids(branch_steps, MAX_REFINE_BRANCH, "branch")
            or mids(ambiguous_steps(tracked), MAX_REFINE, "other"))


def build_table(parameter, values, keys, records, anchor=True):
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
    anchor : bool, optional
        Start the TEF branch at the continuation's root.

    Returns
    -------
    table : pandas.DataFrame
        See :class:`tefcore.sweeps.sweep.SweepResult`.
    modes : dict
        Point index -> modes table.
    anchor : dict
        Where the TEF branch starts.
    shapes : dict
        Point index -> the shapes tracking compared.
    """
    n = len(values)
    main = {k: i for i, k in enumerate(keys)}
    extra = [k for k in ok_in_order(records) if k not in main]
    index_of = dict(main)
    index_of.update({k: n + r for r, k in enumerate(extra)})
    order = ok_in_order({k: records[k] for k in index_of})
    points = tracking_points(records, order)
    values_si = [float(records[k]["value_si"]) for k in order]
    tracked = track_modes(points, values=values_si)
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
    first = next((k for k in order if k in main), None)
    anchor = assign_roles(table, points, values_si, order, first,
                          records[first].get("anchor") if first is not None else None, anchor)
    modes = {index_of[k]: pd.DataFrame(records[k]["modes"]) for k in order}
    shapes = {index_of[k]: decode_complex(records[k]["vectors"]) for k in order
              if records[k].get("vectors") is not None}
    return table.drop(columns="key"), modes, anchor, shapes
