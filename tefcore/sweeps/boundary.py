"""Stability boundaries: where a tracked mode's damping crosses zero.

:func:`stability_boundary` scans a parameter range with
:func:`tefcore.sweeps.sweep.sweep` and refines the first sign change of the mode's
real part with :func:`scipy.optimize.brentq`, following the mode by MAC and
eigenvalue (:func:`tefcore.modes.matching.match_modes`).

Examples
--------
>>> import numpy as np, pandas as pd
>>> from types import SimpleNamespace
>>> from tefcore.config.io import load_config
>>> def toy(cfg):   # one mode whose real part crosses zero at cg_offset = 0.2
...     x = cfg.flap.cg_offset
...     return SimpleNamespace(
...         modes=pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [3.0],
...                             "real_part": [0.5 * (x - 0.2)],
...                             "damping_ratio": [-0.5 * (x - 0.2) / 3.0]}),
...         eigenvectors=np.ones((1, 1), complex), trim={"collective_deg": 8.0})
>>> cfg = load_config("mdart")
>>> b = stability_boundary(cfg, "flap.cg_offset", (0.0, 1.0), mode="TEF", point=toy)
>>> round(b.value, 9), b.bracket
(0.2, (0.125, 0.25))
"""

from __future__ import annotations

import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..config.configuration import Config
from ..modes.matching import match_modes
from .evaluate import check_result, default_point, shape_vectors
from .sweep import SweepResult, check_parameter, sweep

__all__ = ["BoundaryResult", "stability_boundary"]


@dataclass
class BoundaryResult:
    """Result of :func:`stability_boundary`.

    Attributes
    ----------
    parameter, mode : str
    value : float
        Parameter value (SI) where the mode's real part is zero.
    bracket : (float, float)
        Adjacent scan values between which the real part changes sign (the
        first such pair).
    crossings : list of (float, float)
        All scan brackets with a sign change (several: several boundaries).
    iterations, function_calls : int
        Of :func:`scipy.optimize.brentq` (calls include the two bracket ends,
        taken from the scan).
    converged : bool
    real_part, frequency_per_rev : float
        Of the tracked mode at `value`.
    direction : str
        ``"destabilising"`` when the real part grows through zero with the
        parameter, else ``"stabilising"``.
    scan : SweepResult
    xtol, rtol : float
    """

    parameter: str
    mode: str
    value: float
    bracket: tuple[float, float]
    crossings: list
    iterations: int
    function_calls: int
    converged: bool
    real_part: float
    frequency_per_rev: float
    direction: str
    scan: SweepResult = field(repr=False)
    xtol: float = 0.0
    rtol: float = 0.0


def _to_si(cfg: Config, parameter: str, v) -> float:
    si = cfg.with_overrides({parameter: v}).get(parameter)
    if not isinstance(si, numbers.Real):
        raise ValueError(f"{parameter} is not a numeric field (value {si!r})")
    return float(si)


def stability_boundary(cfg: Config, parameter: str, bracket, mode: str = "TEF", *,
                       point: Callable | None = None, scan=None, xtol: float | None = None,
                       rtol: float = 4 * np.finfo(float).eps, maxiter: int = 100,
                       extra_overrides: Mapping[str, Any] | None = None, n_jobs: int = 1,
                       progress: bool | None = False) -> BoundaryResult:
    """Parameter value where a mode's damping (real part) crosses zero.

    The range is scanned first (a :func:`sweep`, modes tracked by MAC and
    eigenvalue); the first pair of adjacent scan values where the tracked
    mode's real part changes sign is then refined by
    :func:`scipy.optimize.brentq`, each new evaluation identifying the mode
    by :func:`tefcore.modes.matching.match_modes` against the nearest evaluated
    point -- so a frequency crossing with another mode inside the bracket
    does not make the root finder jump to the other mode.

    Parameters
    ----------
    cfg : Config
        Base configuration.
    parameter : str
        Dotted numeric field.
    bracket : (lo, hi)
        Range, numbers (SI) or ``"value unit"`` strings; ``lo < hi``.
    mode : str
        Label of the mode (the track's label where it first appears,
        e.g. ``"TEF"``, ``"blade torsion 1"``).  If several tracks carry it,
        the one present at the most scan points is followed, preferring one
        whose real part changes sign (with a warning).
    point : callable, optional
        As in :func:`sweep`.
    scan : int or sequence, optional
        Number of equally spaced scan values over the bracket (default 9),
        or the values themselves (numbers/strings, at least 2).  Too coarse
        a scan can miss a pair of close crossings.
    xtol, rtol : float
        Of brentq: the root is within about ``xtol + rtol*|value|`` of the
        true crossing of the point function.  Default ``xtol`` is
        ``1e-6 * (hi - lo)``.
    maxiter : int
        Of brentq: iterations allowed.
    extra_overrides, n_jobs, progress
        Passed to :func:`sweep` for the scan (`extra_overrides` also for
        the refinement).

    Returns
    -------
    BoundaryResult

    Raises
    ------
    ValueError
        Bad arguments; the mode is absent at every scan point (the message
        lists the labels present); or its real part does not change sign in
        the range (the message gives its range there).
    RuntimeError
        The point function failed during the refinement (with the value),
        or the mode could not be followed.
    """
    parameter = check_parameter(parameter)
    base = cfg.with_overrides(extra_overrides) if extra_overrides else cfg
    try:
        lo, hi = bracket
    except (TypeError, ValueError):
        raise ValueError(f"bracket must be (lo, hi), got {bracket!r}") from None
    lo, hi = _to_si(base, parameter, lo), _to_si(base, parameter, hi)
    if not lo < hi:
        raise ValueError(f"bracket must have lo < hi, got ({lo!r}, {hi!r}) in SI")
    xs = _scan_values(base, parameter, lo, hi, scan)
    xtol = 1e-6 * (hi - lo) if xtol is None else float(xtol)

    res = sweep(base, parameter, xs, point=point, n_jobs=n_jobs, progress=progress)
    point = default_point() if point is None else point
    t = res.table[res.table["status"] == "ok"]
    if t.empty:
        raise ValueError(f"every scan point of {parameter} failed: "
                         f"{res.failed['error'].iloc[0]}")
    curve = _followed_curve(t, res, mode)
    cx = curve["value_si"].to_numpy(float)
    cr = curve["real_part"].to_numpy(float)

    real_part = _Follower(curve, res, point, base, parameter, mode)
    crossings = [(float(cx[k]), float(cx[k + 1])) for k in range(len(cx) - 1)
                 if cr[k] == 0 or np.sign(cr[k]) * np.sign(cr[k + 1]) < 0]
    if cr[-1] == 0:
        crossings.append((float(cx[-1]), float(cx[-1])))
    if not crossings:
        state = "stable" if cr.max() < 0 else "unstable"
        raise ValueError(
            f"no zero crossing of the {mode!r} real part for {parameter} in [{lo:g}, {hi:g}]: "
            f"it stays {state}, between {cr.min():.4g} and {cr.max():.4g} /rev over "
            f"{len(cx)} scan points; widen the bracket or refine the scan")
    a, b = crossings[0]
    if real_part(a) == 0:
        value, iterations, calls, converged = a, 0, 0, True
    else:
        value, rr = brentq(real_part, a, b, xtol=xtol, rtol=rtol, maxiter=maxiter,
                           full_output=True, disp=False)
        iterations, calls, converged = rr.iterations, rr.function_calls, rr.converged
    r_at = real_part(value)
    m, _, j = real_part.cache[float(value)]
    slope = np.sign(real_part(b) - real_part(a)) if b != a else 0.0
    return BoundaryResult(
        parameter=parameter, mode=mode, value=float(value), bracket=(a, b),
        crossings=crossings, iterations=int(iterations), function_calls=int(calls),
        converged=bool(converged), real_part=r_at,
        frequency_per_rev=float(m["frequency_per_rev"].iloc[j]),
        direction="destabilising" if slope > 0 else "stabilising", scan=res,
        xtol=xtol, rtol=rtol)


def _scan_values(base, parameter, lo, hi, scan) -> list[float]:
    """The scan's values in SI: ``scan`` equally spaced points, or the values given."""
    if scan is None:
        scan = 9
    if isinstance(scan, numbers.Integral) and not isinstance(scan, bool):
        if scan < 2:
            raise ValueError(f"scan needs at least 2 points, got {scan}")
        return np.linspace(lo, hi, int(scan)).tolist()
    xs = sorted({_to_si(base, parameter, v) for v in scan})
    if len(xs) < 2:
        raise ValueError("scan needs at least 2 distinct values")
    return xs


def _followed_curve(t, res, mode):
    """The scan's rows of the mode whose boundary is wanted: the root of that name
    at each point (``"TEF"``: the root the uncoupled flap continues into)."""
    curve = t[t["label"].astype(str) == mode]
    if curve.empty:
        raise ValueError(f"mode {mode!r} not found at any scan point of {res.parameter}; "
                         f"names present: {sorted(set(t['label'].astype(str)))}")
    twice = curve[curve.duplicated("point", keep=False)]
    if not twice.empty:
        x = twice["value_si"].iloc[0]
        raise ValueError(f"{len(twice[twice['value_si'] == x])} roots are named {mode!r} at "
                         f"{res.parameter} = {x:g}: a name must be one root (the point "
                         "function names its roots twice)")
    return curve.sort_values("value_si")


class _Follower:
    """The followed mode's real part at any parameter value, matched from the nearest
    evaluated point (the scan's, then brentq's): ``cache`` holds x -> (modes, shapes,
    row of the mode)."""

    def __init__(self, curve, res, point, base, parameter, mode):
        self.point, self.base, self.parameter, self.mode = point, base, parameter, mode
        self.cache: dict[float, tuple] = {}
        for p, x, mid in zip(curve["point"], curve["value_si"].to_numpy(float),
                             curve["mode_id"], strict=True):
            m = res._modes[p]
            self.cache[float(x)] = (m, res.vectors.get(p),
                                    int(np.flatnonzero(m["mode_id"] == mid)[0]))

    def __call__(self, x: float) -> float:
        x = float(x)
        if x not in self.cache:
            parameter, mode = self.parameter, self.mode
            try:
                result = self.point(self.base.with_overrides({parameter: x}))
                m, v, _ = check_result(result)
                v = shape_vectors(result, v)
            except Exception as err:
                raise RuntimeError(f"{parameter} = {x!r}: point failed while locating the "
                                   f"{mode!r} boundary: {type(err).__name__}: {err}") from err
            named = np.flatnonzero(m["label"].astype(str).to_numpy() == mode)
            if "real_part_uncoupled" in m and named.size:
                j = int(named[0])           # the root of that name (continued identity)
            else:
                near = min(self.cache, key=lambda y: abs(y - x))
                rm, rv, rj = self.cache[near]
                j = match_modes((rm, rv), (m, v))[rj]
            if j < 0:
                raise RuntimeError(f"{parameter} = {x!r}: mode {mode!r} lost (fewer modes)")
            self.cache[x] = (m, v, int(j))
        m, _, j = self.cache[x]
        return float(m["real_part"].iloc[j])
