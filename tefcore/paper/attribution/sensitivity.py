"""What each assumed property does to the headline results (tornado table).

tefcore's MDART blade and flap data are assumed (``tefcore/data/mdart.toml``
says why for each value).  A reviewer judging a replication built on assumed
data needs to know which assumption moves which result, and by how much.
This module re-runs four **headline results** with one assumption changed at
a time, to the low and the high end of its plausible range:

* ``fig9_onset``: the flap CG offset ``c_cg/c_f`` at which the TEF flutter
  root turns unstable at ``mu = 0.3``, ``c_b/c_f = 0.29`` (paper: 0.26);
* ``growth_hover`` and ``growth_mu03``: the growth rate (real part, 1/rev)
  of the TEF flutter root at the imbalanced baseline (``c_cg/c_f = 0.33``,
  ``c_b/c_f = 0.29``) in hover and at ``mu = 0.3`` (paper: "weakly
  unstable in hover and becomes more unstable with forward speed");
* ``fig8_onset``: the overhang ``c_b/c_f`` at which it turns unstable in
  hover with the mass-balanced flap (paper: above 0.50).

**Which root.**  The headlines use the *flutter root*
(:func:`tefcore.modes.roles.flutter_root`, the same rule as the sweeps'
``flutter_root`` role): the least stable flap-induced root -- unstable, or
much less stable, with the flap held at its trimmed motion -- whatever mode
it continues from.  Every function takes an ``identify`` callable
(``StabilityResult -> row with real_part and frequency_per_rev``).

The assumptions and their ranges are in :mod:`tefcore.paper.attribution.assumptions` (re-exported
here).  **Calibration is kept.**  Assumptions that move the stated first-torsion
frequencies (section inertia, the GJ distribution, the lift slope through the
blade mass that the Lock number then needs) are re-calibrated with
:func:`tefcore.paper.calibration.calibrate_torsion` before the results are
computed: the sensitivity is that of the whole derivation, with what the text
states held fixed.

Examples
--------
>>> names = [a.name for a in ASSUMPTIONS]
>>> "flap mass" in names and "lift slope" in names
True
>>> [h.name for h in HEADLINES]
['fig9_onset', 'growth_hover', 'growth_mu03', 'fig8_onset']
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd
import scipy.optimize

from ...config.io import load_config
from ...errors import TefcoreError
from ...modes.roles import FLUTTER_PARTICIPATION
from ...modes.roles import flutter_root as flutter_root_row
from ...runtime import worker_init
from .assumptions import ASSUMPTIONS, Assumption, apply_assumption  # re-exported

__all__ = [
    "ASSUMPTIONS",
    "HEADLINES",
    "Assumption",
    "Headline",
    "apply_assumption",
    "flutter_root",
    "headline_results",
    "sensitivity",
    "tornado_plot",
    "tornado_table",
]

#: The mass-imbalanced flap of Figs. 10-17 (tefcore.paper.figures.catalogue.IMBALANCED).
_IMBALANCED = {"flap.overhang": 0.29, "flap.cg_offset": 0.33}


# ------------------------------------------------------------ identification


def flutter_root(result, threshold: float = FLUTTER_PARTICIPATION) -> pd.Series:
    """The least stable flap-induced root (:func:`tefcore.modes.roles.flutter_root`).

    Parameters
    ----------
    result : tefcore.linear.stability.StabilityResult
        Floquet analysis of a configuration with the flap degree of freedom.
    threshold : float
        Least flap participation (``share_TEF``) of a root that counts, for
        results not named by continuation.

    Returns
    -------
    pandas.Series
        The row of ``result.modes`` (``real_part`` [1/rev],
        ``frequency_per_rev``, ``label``, participation shares ...).

    Raises
    ------
    ValueError
        No root carries the flap (``model.tef = "none"``).
    """
    row = flutter_root_row(result.modes, threshold)
    if row is None:
        raise ValueError("no root carries the flap: the configuration has no flap dof "
                         "(model.tef = 'none')")
    return result.modes.loc[row]


# ----------------------------------------------------------------- headlines


@dataclass(frozen=True)
class Headline:
    """A headline result: a growth rate at one point, or an onset along a sweep.

    ``fixed`` is applied over the configuration; an onset scans ``field``
    over ``grid`` (upwards) for the first sign change of the flutter root's
    real part and refines it with ``scipy.optimize.brentq``.

    Parameters
    ----------
    name : str
        Short identifier, the ``headline`` column of the tables
        (``"fig9_onset"``).
    description : str
        What is computed, in the paper's symbols and condition.
    fixed : dict
        Dotted configuration fields set for this headline (flight condition,
        flap overhang and CG offset).
    field : str or None
        Dotted field scanned for an onset (``"flap.cg_offset"``); None for a
        growth rate at the ``fixed`` point.
    grid : tuple of float
        Increasing values of ``field`` scanned for the first stable-to-unstable
        crossing (the paper's sweep points); empty for a growth rate.
    unit : str
        Unit of the result: the swept quantity's (``"c_cg/c_f"``) for an
        onset, ``"1/rev"`` for a growth rate (real part over Omega).
    paper : str
        What the paper states for comparison (``"0.26"``, ``"above 0.50"``).
    """

    name: str
    description: str
    fixed: dict
    field: str | None = None
    grid: tuple = ()
    unit: str = ""
    paper: str = ""

    @property
    def is_onset(self) -> bool:
        """True for an onset along ``field``, False for a growth rate."""
        return self.field is not None


HEADLINES = (
    Headline("fig9_onset", "Fig. 9 onset: c_cg/c_f where the TEF flutter root turns unstable, "
             "mu = 0.3, c_b/c_f = 0.29", {"flight.advance_ratio": 0.3, "flap.overhang": 0.29},
             "flap.cg_offset", tuple(np.round(np.arange(0.0, 0.41, 0.04), 2)), "c_cg/c_f",
             "0.26"),
    Headline("growth_hover", "TEF growth rate at the imbalanced baseline in hover "
             "(c_cg/c_f = 0.33, c_b/c_f = 0.29)", {**_IMBALANCED, "flight.advance_ratio": 0.0},
             unit="1/rev", paper="weakly unstable (> 0, small)"),
    Headline("growth_mu03", "TEF growth rate at the imbalanced baseline, mu = 0.3",
             {**_IMBALANCED, "flight.advance_ratio": 0.3}, unit="1/rev",
             paper="more unstable than in hover"),
    Headline("fig8_onset", "Fig. 8 onset: overhang c_b/c_f at which the TEF flutter root turns "
             "unstable in hover, c_cg/c_f = 0", {"flight.advance_ratio": 0.0,
                                                  "flap.cg_offset": 0.0},
             "flap.overhang", tuple(np.round(np.arange(0.0, 0.71, 0.05), 2)), "c_b/c_f",
             "above 0.50"),
)


def _real_part(cfg, identify, warm=None):
    from ...linear.stability import stability  # deferred: heavy
    from ...trimming.trim import TrimError

    try:
        res = stability(cfg, trim_result=warm)
    except (TrimError, ValueError):
        if warm is None:
            raise
        # a warm start from a neighbouring point can send Newton astray (seen:
        # Mach > 0.99 in the section loads at one Fig. 9 point); start cold
        res = stability(cfg)
    return float(identify(res)["real_part"]), res


def _onset(cfg, h: Headline, identify, xtol: float) -> tuple[float, str]:
    """First zero crossing (stable -> unstable) of the flutter root along ``h.grid``."""
    prev, warm = None, None
    for x in h.grid:
        try:
            c = cfg.with_overrides({h.field: float(x)})
        except ValueError as err:                 # the data do not admit this point
            return math.nan, f"no crossing below {h.field} = {x} (invalid: {err})"[:200]
        try:
            g, res = _real_part(c, identify, warm)
        except TefcoreError as err:               # e.g. a statically diverged flap
            return math.nan, f"no crossing below {h.field} = {x} ({err})"[:200]
        warm = res.trim_result
        if prev is None and g >= 0:
            return math.nan, f"unstable already at {h.field} = {x} (real part {g:+.3f})"
        if prev is not None and prev[1] < 0 <= g:
            lo, hi = prev[0], float(x)
            # the bracket's ends are the scan's last two points, already
            # solved: brentq is given their values instead of solving them
            # again (2 of about 8 points of an onset's search).  Solved again
            # they differed by up to 1e-4 /rev (each end's trim converges to
            # its tolerance from another warm start), which moved the onsets
            # by up to 5e-5, inside xtol (measured on notebook 08's 54 onsets)
            known = {lo: prev[1], hi: g}

            def f(v, warm=warm, known=known):
                if v in known:
                    return known[v]
                return _real_part(cfg.with_overrides({h.field: v}), identify, warm)[0]

            return float(scipy.optimize.brentq(f, lo, hi, xtol=xtol)), "ok"
        prev = (float(x), g)
    return math.nan, f"stable up to {h.field} = {h.grid[-1]}"


def headline_results(cfg=None, *, identify: Callable = flutter_root,
                     headlines=HEADLINES, xtol: float = 1e-4,
                     solved: dict | None = None) -> pd.DataFrame:
    """The headline results of one configuration.

    Parameters
    ----------
    cfg : Config, optional
        Default MDART.
    identify : callable
        ``StabilityResult -> row`` (with ``real_part``) of the root to follow;
        default :func:`tefcore.modes.roles.flutter_root`.
    headlines : sequence of Headline
        The results to compute (default :data:`HEADLINES`).
    xtol : float
        Absolute tolerance of the onsets in the swept field (1e-4: far below the
        0.01-0.05 steps of the paper's sweeps).
    solved : dict, optional
        Filled with the stability result of each growth-rate headline's point
        (solved from a cold start, as :func:`tefcore.linear.stability.stability`
        alone would), keyed by :func:`tefcore.sweeps.store.config_hash` of its
        configuration: for a caller that needs the same points again.

    Returns
    -------
    pandas.DataFrame
        ``headline, value, unit, status`` (``status`` is ``"ok"`` or says why
        an onset is missing: stable over the whole range, unstable at its start,
        or a point the data do not admit).
    """
    cfg = cfg or load_config("mdart")
    rows = []
    for h in headlines:
        c = cfg.with_overrides(h.fixed)
        if h.is_onset:
            value, status = _onset(c, h, identify, xtol)
        else:
            (value, res), status = _real_part(c, identify), "ok"
            if solved is not None:
                from ...sweeps.store import config_hash

                solved[config_hash(c)] = res
        rows.append({"headline": h.name, "value": value, "unit": h.unit, "status": status})
    return pd.DataFrame(rows)


def _case(cfg, a, end, identify, headlines, xtol):
    worker_init()          # a joblib worker is a process tefcore owns (tefcore.runtime)
    label = "baseline" if a is None else getattr(a, f"{end}_label")
    try:
        c = cfg if a is None else apply_assumption(cfg, a, end)
        out = headline_results(c, identify=identify, headlines=headlines, xtol=xtol)
    except ValueError as err:
        out = pd.DataFrame({"headline": [h.name for h in headlines], "value": math.nan,
                            "unit": [h.unit for h in headlines],
                            "status": f"not admitted: {err}"[:200]})
    return out.assign(assumption="baseline" if a is None else a.name,
                      end="baseline" if a is None else end, setting=label)


def sensitivity(cfg=None, assumptions=ASSUMPTIONS, *, identify: Callable = flutter_root,
                headlines=HEADLINES, n_jobs: int = 1, xtol: float = 1e-4) -> pd.DataFrame:
    """Headline results with each assumption at the ends of its range (tidy table).

    Parameters
    ----------
    cfg : Config, optional
        Baseline (default MDART).
    assumptions : sequence of Assumption
        Assumptions varied one at a time, each to its low and high end
        (default: all of :data:`ASSUMPTIONS`).
    identify : callable
        Root to follow (default :func:`tefcore.modes.roles.flutter_root`).
    headlines : sequence of Headline
        The results computed for each case (default :data:`HEADLINES`).
    n_jobs : int
        Cases run in joblib processes (1: serially).
    xtol : float
        Onset tolerance (:func:`headline_results`).

    Returns
    -------
    pandas.DataFrame
        ``assumption, end, setting, headline, value, unit, status, change``
        with ``change = value - baseline value`` of the same headline.
    """
    cfg = cfg or load_config("mdart")
    cases = [(None, "baseline")] + [(a, e) for a in assumptions for e in ("low", "high")]
    if n_jobs == 1:
        parts = [_case(cfg, a, e, identify, headlines, xtol) for a, e in cases]
    else:
        from joblib import Parallel, delayed

        parts = Parallel(n_jobs=n_jobs)(delayed(_case)(cfg, a, e, identify, headlines, xtol)
                                        for a, e in cases)
    table = pd.concat(parts, ignore_index=True)
    base = table[table["end"] == "baseline"].set_index("headline")["value"]
    table["change"] = table["value"] - table["headline"].map(base)
    cols = ["assumption", "end", "setting", "headline", "value", "unit", "status", "change"]
    return table[cols]


def tornado_table(table: pd.DataFrame, digits: int = 3) -> pd.DataFrame:
    """Wide table: one row per assumption, ``low``/``high`` value per headline.

    Rows are ordered by the largest change of any headline relative to its
    own baseline spread (the tornado order); values rounded to ``digits``.

    Parameters
    ----------
    table : pandas.DataFrame
        Tidy result of :func:`sensitivity`.
    digits : int
        Decimals kept (3: a thousandth of c_f for the onsets, of 1/rev for
        the growth rates).

    Returns
    -------
    pandas.DataFrame
        Index: the assumptions, most influential first, then ``"baseline"``;
        columns: ``(headline, "low" | "high")``.  A missing onset is NaN.
    """
    t = table[table["end"] != "baseline"]
    wide = t.pivot_table(index="assumption", columns=["headline", "end"], values="value",
                         aggfunc="first", dropna=False)
    heads = list(dict.fromkeys(table["headline"]))
    wide = wide.reindex(columns=pd.MultiIndex.from_product([heads, ["low", "high"]]))
    spread = t.assign(a=t["change"].abs()).groupby(["assumption", "headline"])["a"].max()
    scale = spread.groupby("headline").max().replace(0.0, np.nan)
    order = (spread / scale).groupby("assumption").max().sort_values(ascending=False).index
    base = table[table["end"] == "baseline"].set_index("headline")["value"]
    out = wide.reindex(order).round(digits)
    out.loc["baseline"] = [round(base.get(h, math.nan), digits) for h, _ in out.columns]
    return out


def tornado_plot(table: pd.DataFrame, headline: str, ax=None, *, labels: Mapping | None = None):
    """Tornado plot of one headline: a bar per assumption from low to high end.

    Bars are centred on the baseline value and sorted by their span; a
    missing end (onset outside the scanned range, or a configuration the
    data do not admit) is drawn as a hatched stub and named in the label.

    Parameters
    ----------
    table : pandas.DataFrame
        Tidy result of :func:`sensitivity`.
    headline : str
        Which headline to plot (``"fig9_onset"``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw in; default: a new figure sized to the number of
        assumptions.
    labels : mapping, optional
        Display names of the assumptions (``{"flap mass": "m_f"}``); others
        keep their own.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn in; the x axis is the headline in its unit.
    """
    import matplotlib.pyplot as plt

    t = table[table["headline"] == headline]
    base = float(t[t["end"] == "baseline"]["value"].iloc[0])
    rows = []
    for name, g in t[t["end"] != "baseline"].groupby("assumption", sort=False):
        lo = g[g["end"] == "low"].iloc[0]
        hi = g[g["end"] == "high"].iloc[0]
        span = np.nanmax(np.abs([lo["value"] - base, hi["value"] - base, 0.0]))
        rows.append((name, lo, hi, span))
    rows.sort(key=lambda r: (r[3] if np.isfinite(r[3]) else 0.0))
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 0.35 * len(rows) + 1.2))
    names = []
    for i, (name, lo, hi, _) in enumerate(rows):
        for row, color in ((lo, "C0"), (hi, "C3")):
            v = row["value"]
            if np.isfinite(v):
                ax.barh(i, v - base, left=base, color=color, alpha=0.8, height=0.6)
            else:
                ax.barh(i, 0.0, left=base, color="none", edgecolor=color, hatch="//",
                        height=0.6)
        names.append((labels or {}).get(name, name))
        ax.text(1.0, i, f"  {lo['setting']} / {hi['setting']}", va="center", fontsize="x-small",
                transform=ax.get_yaxis_transform())
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels(names, fontsize="small")
    ax.axvline(base, color="k", lw=0.8)
    unit = t["unit"].iloc[0]
    ax.set_xlabel(f"{headline} [{unit}]" if unit else headline)
    from matplotlib.patches import Patch

    ax.legend(handles=[Patch(color="C0", alpha=0.8, label="low end"),
                       Patch(color="C3", alpha=0.8, label="high end")],
              fontsize="x-small", loc="lower right")
    return ax
