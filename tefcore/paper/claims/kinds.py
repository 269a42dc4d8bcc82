"""One check per kind of claim: how each statement of the paper is judged.

The kinds of ``reference_data/README.md`` (kinds table): values are
interpolated linearly, never extrapolated; thresholds and ranges use the zero
crossings of the real part (:func:`tefcore.paper.claims.curves.zero_crossings`);
trends the sign of the least-squares slope of the curve (:func:`curve_slope`:
the line nearest the curve over its range, whatever its sampling);
comparisons a statistic of two series; curves are compared at the digitised x
(:func:`tefcore.paper.claims.curves.compare_curve`); a mechanism claim
decomposes the root's growth into the work of named terms.  Each check returns
``(expected, computed, value, ok, why)`` and leaves its signed margin on the
context (``ctx.margin``: how far inside or outside its threshold, against the
claim's own tolerance or the panel's scale).
"""

from __future__ import annotations

import numpy as np

from ..figures.quantities import QUANTITY_NAMES, quantity_unit, x_to_si
from .context import Ambiguous, ClaimFailed, Context, g4, select_mode
from .curves import (
    X_SLACK,
    compare_curve,
    stability_intervals,
    threshold_onset,
    zero_crossings,
)
from .exceptional import exceptional_in_range, where
from .reference import Claim

__all__ = ["CHECKS", "curve_slope"]


def _unit(c: Claim) -> str:
    """The unit after a value of the claim's quantity; a dimensionless one by its name."""
    unit = quantity_unit(c.quantity)
    return unit if unit or not c.quantity else f"({QUANTITY_NAMES[c.quantity]})"


def _named(c: Claim, value: float, unit: str) -> str:
    """A computed value with its quantity's name: ``"damping ratio -0.0123"``."""
    return " ".join(t for t in (QUANTITY_NAMES.get(c.quantity, ""), g4(value), unit) if t)


def _plotted(c: Claim, ctx: Context, xs: float) -> str:
    """A damping ratio's real part at the same x [1/rev]: the panels plot a rate, not a ratio."""
    if c.quantity != "damping_ratio" or c.relative_to is not None:
        return ""
    try:
        x, y = ctx.series(c, quantity="real_part", until=xs, identity=False)
    except ClaimFailed:
        return ""
    return f" (real part {g4(float(np.interp(xs, x, y)))} 1/rev)" if len(x) else ""


def _at(c, x, y, xv):
    xs = float(x_to_si(c.figure, xv, c.x_unit))
    slack = X_SLACK * max(abs(xs), 1e-300)
    if not x[0] - slack <= xs <= x[-1] + slack:
        raise ClaimFailed(f"x = {g4(xv)} {c.x_unit} is outside the computed range")
    return float(np.interp(xs, x, y))


def _check_value(c: Claim, ctx: Context):
    if c.figure == "fig6":
        computed = float(ctx.frame("fig6")[c.quantity].iloc[0])
    else:
        last = max(v for v in (c.x, c.relative_to) if v is not None)
        x, y = ctx.series(c, until=float(x_to_si(c.figure, last, c.x_unit)))
        computed = _at(c, x, y, c.x)
        if c.relative_to is not None:
            computed = computed / _at(c, x, y, c.relative_to) - 1
    unit = "(relative change)" if c.relative_to is not None else quantity_unit(c.quantity)
    where = "" if c.x is None else f" at x = {g4(c.x)} {c.x_unit}".rstrip()
    name = QUANTITY_NAMES.get(c.quantity, "value")
    if c.expected is not None:
        tol = c.tolerance * (abs(c.expected) if c.tolerance_type == "relative" else 1)
        ok = abs(computed - c.expected) <= tol * (1 + X_SLACK)
        ctx.margin = (tol - abs(computed - c.expected)) / tol if tol > 0 else np.nan
        expected = f"{name} {g4(c.expected)} ± {g4(tol)} {unit}".rstrip() + where
        why = f"off by {g4(computed - c.expected)}, more than {g4(tol)}"
    else:
        lo = -np.inf if c.lower is None else c.lower
        hi = np.inf if c.upper is None else c.upper
        ok = lo <= computed <= hi
        ctx.margin = min(computed - lo, hi - computed) / _scale(lo, hi, computed)
        expected = f"{g4(lo)} <= {name} <= {g4(hi)} {unit}".rstrip() + where
        why = "outside the bounds"
    plotted = ("" if c.figure == "fig6" or c.x is None
               else _plotted(c, ctx, float(x_to_si(c.figure, c.x, c.x_unit))))
    return (expected, _named(c, computed, unit) + plotted, computed, ok,
            "" if ok else why)


def _fmt_x(c, xs, factor):
    return ", ".join(f"{g4(v / factor)}" for v in xs) + (f" {c.x_unit}" if c.x_unit else "")


def _check_threshold(c: Claim, ctx: Context):
    """A stability threshold: the root is in the claimed state above its onset, not before.

    The rule, on every zero crossing in the claim's range: the onset is the
    last crossing in the claimed direction, and the last crossing of all has
    that direction (the root stays in the claimed state above it); with an
    ``expected`` x, the onset lies within the tolerance, and below the
    tolerance band the root is never in the claimed state (a root unstable
    before 0.5 and stable again is not "unstable above 0.5").  A root that
    crosses more than once is said so in the reason, also when it passes.
    """
    x, y = ctx.series(c, interval=c.interval)
    f = float(x_to_si(c.figure, 1.0, c.x_unit))
    cross = zero_crossings(x, y)
    desc = "; ".join(f"{d} at {_fmt_x(c, [x0], f)}" for x0, d in cross) or (
        f"none (real part {g4(y.min())} to {g4(y.max())} 1/rev)")
    band = None if c.expected is None else c.tolerance * (1 + X_SLACK)
    expected = (f"a {c.direction} crossing" if c.expected is None else
                f"{c.direction} at {g4(c.expected)} ± {g4(c.tolerance)} {c.x_unit}".rstrip())
    onset, end_ok, early = threshold_onset(x, y, c.direction,
                                           None if band is None else (c.expected - band) * f)
    if onset is None:
        # never crossing: how far the root stays from zero, its extreme real part
        # against the panel's range; crossing only the other way: the opposite
        # change of state, a fail by structure (-1), never a near tie
        far = y.max() if c.direction == "destabilising" else -y.min()
        ctx.margin = (-1.0 if cross else
                      float(min(far, 0.0) / max(np.ptp(y), abs(far), 1e-12)))
        return expected, f"crossings: {desc}", np.nan, False, f"no {c.direction} crossing"
    state, other = ("unstable", "stable")[::1 if c.direction == "destabilising" else -1]
    reasons = [] if end_ok else [f"the last crossing is {cross[-1][1]}: the end state is not "
                                 "the claimed one"]
    if band is not None and abs(onset / f - c.expected) > band:
        reasons.append("crossing outside the tolerance")
    reasons += [f"{state} on {' and '.join(f'[{g4(a / f)}, {g4(b / f)}]' for a, b in early)} "
                f"below the claimed onset {g4(c.expected)} ± {g4(c.tolerance)}, then {other} "
                f"again: not {state} above {g4(c.expected)} only"] if early else []
    ok = not reasons
    ctx.margin = (1.0 if c.expected is None
                  else (c.tolerance - abs(onset / f - c.expected)) / c.tolerance)
    if not end_ok or early:
        ctx.margin = min(ctx.margin, -1.0)
    if len(cross) > 1:              # said also when it passes
        reasons.append(f"the root crosses {len(cross)} times; the onset is the last "
                       f"{c.direction} crossing, at {_fmt_x(c, [onset], f)}")
    return expected, f"crossings: {desc}", onset / f, ok, "; ".join(reasons)


def _check_range(c: Claim, ctx: Context):
    x, y = ctx.series(c)
    f = float(x_to_si(c.figure, 1.0, c.x_unit))
    got = [(a / f, b / f) for a, b in stability_intervals(x, y, c.state)]
    lo, hi = c.expected_interval
    expected = f"{c.state} on [{g4(lo)}, {g4(hi)}] ± {g4(c.tolerance)} {c.x_unit}".rstrip()
    computed = f"{c.state} on " + (" and ".join(f"[{g4(a)}, {g4(b)}]" for a, b in got) or "none")
    if len(got) != 1:
        ctx.margin = -1.0
        return expected, computed, np.nan, False, f"{len(got)} {c.state} intervals, expected one"
    err = max(abs(got[0][0] - lo), abs(got[0][1] - hi))
    ctx.margin = (c.tolerance - err) / c.tolerance if c.tolerance > 0 else np.nan
    ok = err <= c.tolerance * (1 + X_SLACK) + X_SLACK * max(abs(lo), abs(hi))
    return expected, computed, err, ok, "" if ok else (
        f"an end is {g4(err)} {c.x_unit}".rstrip() + " off")


def curve_slope(x, y) -> float:
    """Least-squares slope of the curve through the points, not of the points.

    The straight line closest to the piecewise-linear curve through ``(x, y)``
    over its whole range, ``min_{a,b} int (y(x) - a - b x)^2 dx``, in closed form
    segment by segment.  A point added on a straight stretch changes nothing,
    so the slope is the curve's whatever the sampling: a sweep's refinement
    points cluster where names exchange, and an unweighted fit of the points
    counts those stretches once per point (Fig. 12a's imbalanced-flap slope
    reads 0.0824 that way with the refinement points and 0.0876 without them).

    Parameters
    ----------
    x, y : array_like
        The curve's points, ``x`` non-decreasing (repeated values are a jump).

    Returns
    -------
    float
        NaN for fewer than two distinct ``x``.

    Examples
    --------
    >>> curve_slope([0.0, 1.0, 2.0], [0.0, 1.0, 4.0])
    2.0
    >>> curve_slope([0.0, 0.5, 1.0, 2.0], [0.0, 0.5, 1.0, 4.0])   # a point on a straight stretch
    2.0
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if x.size < 2 or np.ptp(x) <= 0:
        return np.nan
    x0, x1, y0, y1 = x[:-1], x[1:], y[:-1], y[1:]
    h = x1 - x0
    length = float(h.sum())
    sx = float(np.sum(h * (x0 + x1)) / 2)
    sy = float(np.sum(h * (y0 + y1)) / 2)
    sxx = float(np.sum(h * (x0 * x0 + x0 * x1 + x1 * x1)) / 3)
    sxy = float(np.sum(h * (x0 * (2 * y0 + y1) + x1 * (y0 + 2 * y1))) / 6)
    return (length * sxy - sx * sy) / (length * sxx - sx * sx)


def _stats(c, x, y, fig):
    xd = x / float(x_to_si(fig, 1.0, c.x_unit))  # slopes per x_unit
    slope = curve_slope(xd, y) if len(x) > 1 else np.nan
    return slope, float(y[-1] - y[0]), float(np.ptp(y))


def _check_trend(c: Claim, ctx: Context):
    x, y = ctx.series(c, interval=c.interval)
    if len(x) < 2:
        raise ClaimFailed(f"a trend needs at least 2 points, got {len(x)}")
    slope, net, p2p = _stats(c, x, y, c.figure)
    span = "" if c.interval is None else f" over [{g4(c.interval[0])}, {g4(c.interval[1])}]"
    computed = f"slope {g4(slope)}, net change {g4(net)}, peak-to-peak {g4(p2p)} {_unit(c)}"
    if c.direction != "constant":
        stat = slope if c.method == "slope" else net
        ok = stat > 0 if c.direction == "increasing" else stat < 0
        # against the change the panel shows: its range (per unit x for a slope)
        xd = x / float(x_to_si(c.figure, 1.0, c.x_unit))
        scale = max(float(np.ptp(y)) / (float(np.ptp(xd)) if c.method == "slope" else 1.0),
                    1e-12)
        ctx.margin = (stat if c.direction == "increasing" else -stat) / scale
        why = "" if ok else f"{c.method.replace('_', ' ')} has the opposite sign"
        return f"{c.direction}{span} ({c.method})", computed, stat, ok, why
    if c.tolerance_type == "absolute":
        scale, what = c.tolerance, f"{g4(c.tolerance)} {_unit(c)}"
    elif c.tolerance_type == "relative":
        scale, what = c.tolerance * np.mean(np.abs(y)), f"{g4(c.tolerance)} x mean |value|"
    else:
        # the panel's scale: the reference mode's range as drawn, whichever
        # root carries its name (a claim about the lag is not withheld for the
        # TEF's identity)
        _, yr = ctx.series(c, mode=c.reference_mode, interval=c.interval, identity=False)
        scale = c.tolerance * float(np.ptp(yr))
        what = f"{g4(c.tolerance)} x peak-to-peak of {c.reference_mode} ({g4(np.ptp(yr))})"
    ctx.margin = (scale - p2p) / scale if scale > 0 else np.nan
    return (f"constant{span}: peak-to-peak <= {what}", computed, p2p, p2p <= scale * (1 + X_SLACK),
            "" if p2p <= scale * (1 + X_SLACK) else f"varies by {g4(p2p)} > {g4(scale)}")


def _check_comparison(c: Claim, ctx: Context):
    xa, ya = ctx.series(c, interval=c.interval)
    xb, yb = ctx.series(c, fig=c.other_figure, mode=c.other_mode, quantity=c.other_quantity,
                        interval=c.other_interval, overrides=c.other_overrides)
    other = ", ".join(f"{k}={v}" for k, v in (
        ("figure", c.other_figure if c.other_figure != c.figure else ""),
        ("mode", c.other_mode if c.other_mode != c.mode else ""),
        ("quantity", c.other_quantity if c.other_quantity != c.quantity else ""),
        ("interval", c.other_interval if c.other_interval != c.interval else None),
        ("overrides", c.other_overrides)) if v)
    if c.statistic == "correlation":
        inside = (xa >= xb[0]) & (xa <= xb[-1])
        if inside.sum() < 3:
            raise ClaimFailed("fewer than 3 common x values to correlate")
        r = float(np.corrcoef(ya[inside], np.interp(xa[inside], xb, yb))[0, 1])
        ok = r >= c.tolerance if c.relation == "positive" else r <= -c.tolerance
        ctx.margin = ((r if c.relation == "positive" else -r) - c.tolerance) / (1 - c.tolerance)
        return (f"{c.relation} correlation with ({other}), |r| >= {g4(c.tolerance)}",
                f"r = {g4(r)}", r, ok, "" if ok else "correlation too weak or of the wrong sign")
    k = {"slope": 0, "abs_slope": 0, "peak_to_peak": 2}[c.statistic]
    a, b = _stats(c, xa, ya, c.figure)[k], _stats(c, xb, yb, c.other_figure)[k]
    if c.statistic == "abs_slope":
        a, b = abs(a), abs(b)
    ok = a < b if c.relation == "less" else a > b
    ctx.margin = (b - a if c.relation == "less" else a - b) / max(abs(a), abs(b), 1e-12)
    return (f"{c.statistic} {c.relation} than for ({other})",
            f"{g4(a)} vs {g4(b)}", a, ok, "" if ok else f"{c.statistic} is not {c.relation}")


def _check_curve(c: Claim, ctx: Context):
    x, y = ctx.series(c)
    cmp = compare_curve(x, y, c.points)
    n = int((~cmp["masked"]).sum())
    expected = f"{len(cmp)} digitised points within their band"
    if n == 0:
        return (expected, "no point inside the model's x range", np.nan, None,
                f"all {len(cmp)} points outside the computed range [{g4(x[0])}, {g4(x[-1])}]")
    worst = float(cmp["deviation"][~cmp["masked"]].max())
    inside = int(cmp["within"].sum())
    kept = cmp[~cmp["masked"]]
    ctx.margin = float(np.min(1.0 - kept["deviation"] / np.maximum(kept["allowed"], 1e-12)))
    computed = (f"{inside}/{n} compared points within band, max |dev| {g4(worst)} {_unit(c)}, "
                f"{len(cmp) - n} masked")
    return expected, computed, worst, inside == n, "" if inside == n else (
        f"{n - inside} point(s) outside their band")


def _check_mechanism(c: Claim, ctx: Context):
    from ...linear.mechanism import mechanism
    from ..figures.catalogue import FIGURES as FIGS
    from ..figures.catalogue import figure_config

    frame = ctx.frame(c.figure, c.overrides)
    xs = float(x_to_si(c.figure, c.x, c.x_unit))
    rows = select_mode(frame, c.mode)
    points = exceptional_in_range(frame, c.mode, xs, xs)
    if points:           # the root decomposed would be a choice: no verdict
        e = points[0]
        raise Ambiguous(f"an exceptional point of {e['modes']} lies {where(e)}: which root "
                         f"is {c.mode!r} at the claim's x has no answer")
    at = rows[np.abs(rows["x"].to_numpy(float) - xs) <= X_SLACK * max(abs(xs), 1.0)]
    if at.empty:
        raise ClaimFailed(f"no {c.mode} root at x = {g4(c.x)} {c.x_unit}".rstrip()
                    + " (validate_all adds the x of mechanism claims to the sweep)")
    root = complex(at["real_part"].iloc[0], at["frequency_per_rev"].iloc[0])
    cfg = figure_config(c.figure, ctx.cfg).with_overrides(
        {**c.overrides, FIGS[c.figure].parameter: xs})
    res = mechanism(cfg, mode="root", root=root, knockouts=bool(c.knockout_terms))
    terms = res.table[~res.table["term"].str.startswith(("total", "knockout"))]
    contrib = dict(zip(terms["term"], terms["contribution_real"], strict=True))
    found, reasons, wanted = [], [], []
    found.append(f"{res.kind} at {res.eigenvalue.real:+.3g} {res.eigenvalue.imag:+.3g}i /rev")
    if c.root_kind:
        wanted.append(f"a {c.root_kind}")
        if res.kind != c.root_kind:
            reasons.append(f"the root is a {res.kind}, not a {c.root_kind}")
    if c.driving_terms:
        top = max(contrib, key=contrib.get)
        found.append(f"driven most by {top} ({contrib[top]:+.3g} /rev)")
        wanted.append("driven most by " + " or ".join(c.driving_terms))
        if top not in c.driving_terms:
            reasons.append(f"the largest destabilising work is done by {top}")
    for kind, least in c.min_participation.items():
        got = res.participation.get(kind, 0.0)
        found.append(f"{kind} participation {got:.2f}")
        wanted.append(f"{kind} participation >= {least:g}")
        if got < least:
            reasons.append(f"{kind} participates {got:.2f} < {least:g}")
    if c.knockout_terms:
        _knockouts(c, res, found, wanted, reasons)
    # a decomposition's verdict has no distance: +1 when every part holds, -1 otherwise
    ctx.margin = 1.0 if not reasons else -1.0
    return ("; ".join(wanted) + f" at x = {g4(c.x)} {c.x_unit}".rstrip(), "; ".join(found),
            res.eigenvalue.real, not reasons, "; ".join(reasons))


def _knockouts(c, res, found, wanted, reasons):
    """The claimed path's knockouts (and a rival path's): the share of growth each removes."""
    sigma = res.eigenvalue.real

    def best_cut(terms):
        cut = {t: sigma - res.knockouts[t].eigenvalue.real for t in terms if t in res.knockouts}
        best = max(cut, key=cut.get)
        if not res.knockouts[best].clear:
            raise Ambiguous(f"the knockout of {best} passes a coalescence")
        return best, cut[best] / abs(sigma) if sigma else np.nan

    best, share = best_cut(c.knockout_terms)
    found.append(f"knocking out {best} removes {share:.0%} of the growth")
    wanted.append(f"a knockout of {' or '.join(c.knockout_terms)} removes >= "
                  f"{c.tolerance:.0%} of the growth rate")
    if not share >= c.tolerance:
        reasons.append(f"no knockout of {', '.join(c.knockout_terms)} removes "
                       f"{c.tolerance:.0%} of the growth rate")
    if c.rival_terms:
        rival, rshare = best_cut(c.rival_terms)
        found.append(f"knocking out {rival} removes {rshare:.0%}: the "
                     f"{'claimed' if share > rshare else 'rival'} path dominates")
        # and the work each path's terms do on the root (the energy balance)
        work = res.table.set_index("term")["contribution_real"]
        mine = float(sum(work.get(t, 0.0) for t in c.knockout_terms))
        theirs = float(sum(work.get(t, 0.0) for t in c.rival_terms))
        found.append(f"work of the claimed path's terms {mine:+.3g} /rev, of the rival's "
                     f"{theirs:+.3g} /rev")
        wanted.append(f"more than a knockout of {' or '.join(c.rival_terms)} removes")
        if not share > rshare:
            reasons.append(f"the rival path dominates: knocking out {rival} removes "
                           f"{rshare:.0%} of the growth, {best} {share:.0%}")


CHECKS = {"mechanism": _check_mechanism, "value": _check_value,
           "threshold": _check_threshold, "range": _check_range,
           "trend": _check_trend, "comparison": _check_comparison, "curve": _check_curve}


def _scale(lo, hi, value) -> float:
    """The size a bound's distance is measured against: the finite bounds', else the value's."""
    finite = [abs(v) for v in (lo, hi) if np.isfinite(v) and v != 0]
    return max(finite) if finite else max(abs(value), 1e-12)
