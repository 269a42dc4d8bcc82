"""Zero crossings, stability intervals and curve comparison of sampled curves.

The primitives behind the claim checks (:mod:`tefcore.paper.claims.checks`): a
real part that changes sign between two sweep points crosses zero where the
straight line between them does; a digitised curve is compared with the
model's curve at the digitised x, never extrapolated.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

__all__ = ["X_SLACK", "compare_curve", "stability_intervals", "threshold_onset",
           "zero_crossings"]

#: Relative slack on x and tolerance comparisons (round-off of unit conversions).
X_SLACK = 1e-9


def zero_crossings(x, y) -> list[tuple[float, str]]:
    """Interpolated zero crossings of ``y(x)`` (x increasing), with their direction.

    ``y >= 0`` counts as unstable, so a crossing is where a real part of a
    root changes sign: a stability threshold such as Fig. 9b's flap CG offset
    0.26 c_f.

    Parameters
    ----------
    x : array_like
        Sample positions, increasing (a figure's swept values).
    y : array_like
        Samples at ``x`` (a root's real part [1/rev]; positive: unstable).

    Returns
    -------
    list of tuple of (float, str)
        ``(x0, direction)`` per sign change, in order: ``x0`` on the straight
        line between the two samples, ``direction`` ``"destabilising"``
        (stable to unstable with increasing x) or ``"stabilising"``.

    Examples
    --------
    >>> zero_crossings([0, 1, 2, 3], [-1.0, 1.0, 3.0, -1.0])
    [(0.5, 'destabilising'), (2.75, 'stabilising')]
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    out = []
    for k in range(len(x) - 1):
        a, b = y[k] >= 0, y[k + 1] >= 0
        if a != b:
            x0 = x[k] - y[k] * (x[k + 1] - x[k]) / (y[k + 1] - y[k])
            out.append((float(x0), "destabilising" if b else "stabilising"))
    return out


def stability_intervals(x, y, state: str = "unstable") -> list[tuple[float, float]]:
    """Intervals of x where ``y >= 0`` (``"unstable"``) or ``y < 0`` (``"stable"``).

    An interval's ends are the interpolated zero crossings
    (:func:`zero_crossings`) or the ends of the samples; a range claim such as
    Fig. 15's "unstable with the flap chord in the range of 0.15 to 0.40"
    compares with them.

    Parameters
    ----------
    x : array_like
        Sample positions, increasing.
    y : array_like
        Samples at ``x`` (a root's real part [1/rev]).
    state : {"unstable", "stable"}
        Which intervals: ``y >= 0`` or ``y < 0``.

    Returns
    -------
    list of tuple of (float, float)
        ``(start, end)`` of each interval, in order.

    Examples
    --------
    >>> stability_intervals([0, 1, 2, 3], [-1.0, 1.0, 3.0, -1.0])
    [(0.5, 2.75)]
    >>> stability_intervals([0, 1, 2, 3], [-1.0, 1.0, 3.0, -1.0], "stable")
    [(0.0, 0.5), (2.75, 3.0)]
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    inside = (y[0] >= 0) == (state == "unstable")
    start, out = (float(x[0]) if inside else None), []
    for x0, _ in zero_crossings(x, y):
        if inside:
            out.append((start, x0))
        else:
            start = x0
        inside = not inside
    if inside:
        out.append((start, float(x[-1])))
    return out


def threshold_onset(x, y, direction: str, lower: float | None = None):
    """A stability threshold read on every crossing: its onset and what contradicts it.

    The onset is the last crossing in ``direction``; the root must end in
    the state that direction leads to (``end_ok``), and no interval in that
    state may start below ``lower`` (the tolerance band's lower end) and end
    before the onset (``early``): a root unstable before 0.5 and stable again
    is not "unstable above 0.5".

    Parameters
    ----------
    x, y : array_like
        Samples (:func:`zero_crossings`).
    direction : {"destabilising", "stabilising"}
        The claimed crossing.
    lower : float, optional
        Below this x the root must not be in the claimed state.

    Returns
    -------
    tuple
        ``(onset, end_ok, early)``: the onset (None without such a
        crossing), whether the last crossing has ``direction``, and the early
        intervals ``[(start, end), ...]``.

    Examples
    --------
    >>> threshold_onset([0, 1, 2, 3, 4], [-1.0, 1.0, -1.0, -1.0, 1.0], "destabilising", 3.0)
    (3.5, True, [(0.5, 1.5)])
    """
    cross = zero_crossings(x, y)
    wanted = [x0 for x0, d in cross if d == direction]
    if not wanted:
        return None, False, []
    onset, state = wanted[-1], "unstable" if direction == "destabilising" else "stable"
    early = [(a, b) for a, b in stability_intervals(x, y, state)
             if lower is not None and a < lower and b < onset]
    return onset, cross[-1][1] == direction, early


def compare_curve(x_model, y_model, points: pd.DataFrame) -> pd.DataFrame:
    """Model curve at digitised points; points outside the model's x range masked.

    Parameters
    ----------
    x_model, y_model : array_like
        The model curve (x increasing).
    points : DataFrame
        ``x``, ``y``, ``band`` (y half-width) and optionally ``x_band``.

    Returns
    -------
    DataFrame
        ``x, y_ref, y_model`` (NaN where masked), ``allowed`` (band plus
        ``|dy/dx| * x_band``), ``deviation``, ``masked``, ``within`` (NA
        where masked).  Never extrapolates or clamps.
    """
    xm, ym = np.asarray(x_model, float), np.asarray(y_model, float)
    xr = points["x"].to_numpy(float)
    masked = (xr < xm[0]) | (xr > xm[-1]) if len(xm) else np.ones(len(xr), bool)
    y = np.where(masked, np.nan, np.interp(xr, xm, ym) if len(xm) else np.nan)
    slope = np.interp(xr, xm, np.gradient(ym, xm)) if len(xm) > 1 else np.zeros(len(xr))
    dx = points["x_band"].to_numpy(float) if "x_band" in points else 0.0
    allowed = points["band"].to_numpy(float) + np.abs(slope) * dx
    dev = np.abs(y - points["y"].to_numpy(float))
    within = pd.array(np.where(masked, None, dev <= allowed * (1 + X_SLACK)), dtype="boolean")
    return pd.DataFrame({"x": xr, "y_ref": points["y"].to_numpy(float), "y_model": y,
                         "allowed": allowed, "deviation": dev, "masked": masked,
                         "within": within})
