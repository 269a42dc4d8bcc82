"""Verdicts that round-off cannot tip: the claims checked again on nudged inputs.

A relative change of 1e-12 or 1e-9 of the blade's mass, the rotor speed, the
air density or the radius has no engineering meaning; it changes the
round-off of every number the solver computes, as another BLAS kernel or
another machine does.  A verdict that such a nudge moves was decided by
round-off.  :func:`nudged_runs` checks a set of figures' claims on the
configuration and on nudged copies of it; :func:`differences` lists what
moved: a claim's status, a computed value beyond a relative 1e-6, a root's
name or the certainty of its name at any point of any figure.  A value is
compared relative to the larger of its own size and the scale its claim's
margin measures it against (a near-zero slope against the panel's change).  The test suite
runs it on the figures whose roots lock at k/2 (Figs. 12 and 15).

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = nudge(load_config("mdart"), "rotor.rotor_speed", 1e-9)
>>> float(cfg.rotor.rotor_speed / load_config("mdart").rotor.rotor_speed - 1) < 2e-9
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ...config.configuration import resolve_field
from ..figures.frames import compute_figure
from .reference import load_claims
from .validation import sweep_values, validate_all

__all__ = ["NUDGES", "VALUE_ATOL", "VALUE_RTOL", "NudgedRun", "differences", "nudge",
           "nudged_runs"]

#: The nudges: (field, relative change).  Far below any engineering meaning,
#: of the size of the round-off another BLAS kernel gives.
NUDGES = (("blade.mass_scale", 1e-12), ("rotor.rotor_speed", 1e-9),
          ("rotor.air_density", -1e-12), ("rotor.radius", 1e-9))

#: Relative agreement required of a claim's computed value under a nudge: a
#: nudge of 1e-9 moves a smooth result by about 1e-9 times its sensitivity
#: (order one for these fields), so 1e-6 leaves a thousandfold room for the
#: solver's own error control while any reading that jumps (a lock read at
#: k - 1/2 instead of k + 1/2: 6 % on Fig. 12's slope) fails it.
VALUE_RTOL = 1e-6

#: Absolute agreement below which two values are the same: a statistic that is
#: itself round-off (the peak-to-peak of a frequency that does not change,
#: 1e-10 /rev) is compared to the solver's resolution -- the Floquet exponents'
#: round-off bound, 1e-9 /rev, ten times over -- not relatively.
VALUE_ATOL = 1e-8

#: The columns of a figure's table compared point by point.
_NAMED = ("label", "identity_certain")


@dataclass
class NudgedRun:
    """The claims and the figures' tables on one configuration.

    Parameters
    ----------
    label : str
        ``"base"`` or the nudge (``"rotor.radius +1e-09"``).
    claims : pandas.DataFrame
        :func:`tefcore.paper.claims.validation.validate_all` of the figures' claims.
    tables : dict
        Figure -> its sweep table.
    """

    label: str
    claims: pd.DataFrame
    tables: dict


def nudge(cfg, field: str, rel: float):
    """``cfg`` with one numeric field scaled by ``1 + rel``.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    field : str
        A scalar numeric field (``"rotor.radius"``).
    rel : float
        The relative change.

    Returns
    -------
    tefcore.config.configuration.Config
    """
    section, name = resolve_field(field)
    value = getattr(getattr(cfg, section), name)
    return cfg.with_overrides({field: float(value) * (1.0 + rel)})


def _run(cfg, figures, label) -> NudgedRun:
    claims = [c for c in load_claims() if c.figure in figures]
    results = {}
    for fig in figures:
        mine = [c for c in claims if c.figure == fig and c.kind != "not_reproducible"]
        results[fig] = compute_figure(fig, cfg, sweep_values(fig, mine))
    table = validate_all(cfg=cfg, results=results, claims=claims)
    return NudgedRun(label, table, {f: r.table for f, r in results.items()})


def nudged_runs(cfg, figures, nudges=NUDGES) -> list[NudgedRun]:
    """The claims of ``figures`` on ``cfg`` and on each nudged copy of it.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    figures : sequence of str
        Stability figures (``"fig12"``).
    nudges : sequence of (str, float)
        (field, relative change); default :data:`NUDGES`.

    Returns
    -------
    list of NudgedRun
        The base run first.
    """
    out = [_run(cfg, figures, "base")]
    for field, rel in nudges:
        out.append(_run(nudge(cfg, field, rel), figures, f"{field} {rel:+.0e}"))
    return out


def _allowed(va: float, vb: float, claims, cid, rtol: float) -> float:
    """How far a claim's computed value may move under a nudge.

    ``rtol`` of the value's own size, or of the size its claim measures it
    against, whichever is larger: a statistic near zero -- a slope whose sign
    is the claim, a difference of two larger numbers -- is compared to the
    change the panel shows (the scale of the claim's signed ``margin``,
    ``value / margin``), as the verdict is.  (Measured: Fig. 10b's slope
    4.96e-6 /rev per lb/in at margin 0.028, a scale of 1.8e-4, moves by
    7.5e-11 under a radius nudge of 1e-9: 1.5e-5 of the slope, 4e-7 of the
    scale.)  Other values: never below :data:`VALUE_ATOL`.
    """
    size = max(abs(va), abs(vb))
    if _signed_statistic(claims, cid):
        margin = float(claims.at[cid, "margin"])
        if np.isfinite(margin) and margin != 0 and np.isfinite(va):
            # the claim's own units, whatever they are (a slope per lb/in is
            # 1e-5 where an absolute 1e-8 would be a thousandth of it)
            return rtol * max(size, abs(va / margin))
    return max(rtol * size, VALUE_ATOL)


def _signed_statistic(claims, cid) -> bool:
    """Whether the claim's margin is its value over a scale: a trend with a direction
    (slope or net change, :func:`tefcore.paper.claims.kinds._check_trend`)."""
    if "margin" not in claims.columns or "kind" not in claims.columns:
        return False
    return claims.at[cid, "kind"] == "trend" and str(claims.at[cid, "expected"]).startswith(
        ("increasing", "decreasing"))


def differences(base: NudgedRun, other: NudgedRun, rtol: float = VALUE_RTOL,
                certainty: bool = True) -> list[str]:
    """What a nudge moved: statuses, values, names and their certainty.

    Parameters
    ----------
    base : NudgedRun
        The run on the configuration as it is.
    other : NudgedRun
        A run on a nudged copy.
    rtol : float
        Relative agreement of computed values (:data:`VALUE_RTOL`).
    certainty : bool, optional
        Compare the certainty of the names too (``identity_certain``).

    Returns
    -------
    list of str
        One line per difference (empty: the verdicts are the physics').
    """
    out = []
    a = base.claims.set_index("id")
    b = other.claims.set_index("id").reindex(a.index)
    for cid in a.index:
        if a.at[cid, "status"] != b.at[cid, "status"]:
            out.append(f"{other.label}: {cid} {a.at[cid, 'status']} -> {b.at[cid, 'status']}")
        va, vb = float(a.at[cid, "computed_value"]), float(b.at[cid, "computed_value"])
        if np.isnan(va) != np.isnan(vb) or (
                np.isfinite(va) and abs(va - vb) > _allowed(va, vb, a, cid, rtol)):
            out.append(f"{other.label}: {cid} value {va:.10g} -> {vb:.10g}")
    for fig, ta in base.tables.items():
        tb = other.tables[fig]
        if len(ta) != len(tb):
            out.append(f"{other.label}: {fig} has {len(tb)} rows, {len(ta)} without the nudge")
            continue
        for col in _NAMED if certainty else _NAMED[:1]:
            # a failed point has no name on either side (NaN == NaN here)
            diff = (ta[col].astype(object).fillna("").astype(str).to_numpy()
                    != tb[col].astype(object).fillna("").astype(str).to_numpy())
            for i in np.flatnonzero(diff):
                out.append(f"{other.label}: {fig} at {ta['value'].iloc[i]} row {i}: {col} "
                           f"{ta[col].iloc[i]} -> {tb[col].iloc[i]}")
    return out
