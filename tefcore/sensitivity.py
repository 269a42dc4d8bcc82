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

**Which root is "the TEF".**  Where the flap frequency meets a blade mode the
two roots coalesce and share the flap's motion; one is destabilised, the
other stabilised, and names based on one root are ambiguous there.  Here the
*flutter root* (:func:`flutter_root`) is the least stable of the roots in
which the flap participates materially: those whose TEF kinetic-energy share
(:func:`tef_energy_share`, the flap coordinate's ``|q_F|^2 M_FF`` over all
coordinates' ``|q_k|^2 M_kk``, with the structural mass of
:func:`tefcore.section_inertia.coupled_mass_matrix`) is at least
:data:`SHARE_RATIO` (0.15) of the largest share among all roots.  Both
members of a coalesced pair pass that test, so the destabilised one is found
wherever the coalescence happens; away from coalescences only the flap mode
itself does.  Every function takes an
``identify`` callable (``StabilityResult -> row with real_part and
frequency_per_rev``), so the mode tracking of :mod:`tefcore.tracking` can
replace this rule in one place.

**Calibration is kept.**  Assumptions that move the stated first-torsion
frequencies (section inertia, the GJ distribution, the lift slope through the
blade mass that the Lock number then needs) are re-calibrated with
:func:`tefcore.calibration.calibrate_torsion` before the results are
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
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
import scipy.optimize

from .config import load_config
from .section_inertia import coupled_mass_matrix

__all__ = [
    "ASSUMPTIONS",
    "HEADLINES",
    "Assumption",
    "Headline",
    "apply_assumption",
    "flutter_root",
    "headline_results",
    "sensitivity",
    "tef_energy_share",
    "tornado_plot",
    "tornado_table",
]

#: The mass-imbalanced flap of Figs. 10-17 (tefcore.figures.IMBALANCED).
_IMBALANCED = {"flap.overhang": 0.29, "flap.cg_offset": 0.33}
#: Minimum TEF share of a root, relative to the largest over all roots, for the
#: root to count as one the flap takes part in.  Measured on MDART over every
#: point of Figs. 8-17: the unstable flap-involved root carries 0.19-1.0 of the
#: largest share (0.19 at half the actuator stiffness of Fig. 12), roots the
#: flap does not take part in below 1e-3; both roots of a coalesced pair carry
#: similar shares (0.06 and 0.06 at the Fig. 9 onset).
SHARE_RATIO = 0.15


# ------------------------------------------------------------ identification


def tef_energy_share(result) -> np.ndarray:
    """Share of each root's kinetic energy in the flap coordinate, in ``result.modes`` order.

    ``|q_F|^2 M_FF / sum_k |q_k|^2 M_kk`` over the displacement part of the
    eigenvector, with the structural mass diagonal of the coupled model
    (:func:`tefcore.section_inertia.coupled_mass_matrix`); zeros without a flap.
    """
    model = result.trim_result.model
    n = model.n_dof
    if not model.has_flap:
        return np.zeros(len(result.modes))
    mass = np.abs(np.diag(coupled_mass_matrix(model)))
    energy = np.abs(np.asarray(result.eigenvectors)[:n]) ** 2 * mass[:, None]
    return energy[-1] / energy.sum(axis=0)


def flutter_root(result, share_ratio: float = SHARE_RATIO) -> pd.Series:
    """The least stable root among those the flap participates in.

    Parameters
    ----------
    result : tefcore.stability.StabilityResult
    share_ratio : float
        A root counts when its TEF energy share is at least this fraction of
        the largest share among all roots (:data:`SHARE_RATIO`).

    Returns
    -------
    pandas.Series
        The row of ``result.modes`` with ``tef_share`` added.
    """
    share = tef_energy_share(result)
    if not share.size or share.max() <= 0:
        raise ValueError("no root carries the flap: the configuration has no flap dof "
                         "(model.tef = 'none')")
    table = result.modes.assign(tef_share=share)
    keep = table[share >= share_ratio * share.max()]
    return keep.loc[keep["real_part"].idxmax()]


# ----------------------------------------------------------------- headlines


@dataclass(frozen=True)
class Headline:
    """A headline result: a growth rate at one point, or an onset along a sweep.

    ``fixed`` is applied over the configuration; an onset scans ``field``
    over ``grid`` (upwards) for the first sign change of the flutter root's
    real part and refines it with ``scipy.optimize.brentq``.
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
    from .stability import stability  # deferred: heavy
    from .trim import TrimError

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
        g, res = _real_part(c, identify, warm)
        warm = res.trim_result
        if prev is None and g >= 0:
            return math.nan, f"unstable already at {h.field} = {x} (real part {g:+.3f})"
        if prev is not None and prev[1] < 0 <= g:
            lo, hi = prev[0], float(x)

            def f(v, warm=warm):
                return _real_part(cfg.with_overrides({h.field: v}), identify, warm)[0]

            return float(scipy.optimize.brentq(f, lo, hi, xtol=xtol)), "ok"
        prev = (float(x), g)
    return math.nan, f"stable up to {h.field} = {h.grid[-1]}"


def headline_results(cfg=None, *, identify: Callable = flutter_root,
                     headlines=HEADLINES, xtol: float = 1e-4) -> pd.DataFrame:
    """The headline results of one configuration.

    Parameters
    ----------
    cfg : Config, optional
        Default MDART.
    identify : callable
        ``StabilityResult -> row`` (with ``real_part``) of the root to follow;
        default :func:`flutter_root`.
    headlines : sequence of Headline
    xtol : float
        Absolute tolerance of the onsets in the swept field (1e-4: far below the
        0.01-0.05 steps of the paper's sweeps).

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
            value, status = _real_part(c, identify)[0], "ok"
        rows.append({"headline": h.name, "value": value, "unit": h.unit, "status": status})
    return pd.DataFrame(rows)


# --------------------------------------------------------------- assumptions


def _times(field_name: str, factor: float) -> Callable:
    def apply(cfg):
        v = cfg.get(field_name)
        return {field_name: (np.asarray(v) * factor).tolist() if np.ndim(v) else v * factor}
    return apply


def _outboard_gj(factor: float) -> Callable:
    def apply(cfg):
        b = cfg.blade
        return {"blade.gj": np.where(np.asarray(b.stations) >= 0.5, factor, 1.0) * b.gj}
    return apply


def _section_inertia(factor: float) -> Callable:
    def apply(cfg):
        return {"blade.im_lag": cfg.blade.im_lag * factor,
                "blade.im_flap": cfg.blade.im_flap * factor}
    return apply


def _lift_slope(value: float) -> Callable:
    def apply(cfg):
        # the Lock number 9.17 is stated: a different lift slope means a blade
        # whose flapping inertia is larger by the same factor
        return {"rotor.lift_slope": value,
                "blade.mass_scale": cfg.blade.mass_scale * value / cfg.rotor.lift_slope}
    return apply


def _cg_shift(shift_in: float) -> Callable:
    def apply(cfg):
        return {"blade.cg_offset": cfg.blade.cg_offset + shift_in * 0.0254}
    return apply


def _set(field_name: str, value) -> Callable:
    return lambda cfg: {field_name: value}


@dataclass(frozen=True)
class Assumption:
    """One assumed property and the plausible range it is varied over.

    ``low`` and ``high`` map the baseline Config to the overrides of the two
    ends; ``basis`` says why the range is what it is; ``recalibrate`` re-fits
    GJ, horn arm and pitch-link stiffness to the stated torsion frequencies
    after the change.
    """

    name: str
    fields: tuple
    low: Callable
    high: Callable
    low_label: str
    high_label: str
    basis: str
    recalibrate: bool = False
    extra: dict = field(default_factory=dict)


ASSUMPTIONS = (
    Assumption("flap mass", ("flap.mass",), _times("flap.mass", 0.75), _times("flap.mass", 1.25),
               "x0.75", "x1.25", "construction estimate (skins, core, fittings, balance weight) "
               "good to about a quarter; x1.25 = 0.375 lb/ft still fits in the section"),
    Assumption("flap inertia", ("flap.inertia_cg",), _times("flap.inertia_cg", 0.5),
               _times("flap.inertia_cg", 1.5), "x0.5", "x1.5",
               "radius of gyration about the hinge 0.18-0.31 c_f around the construction "
               "estimate 0.25 c_f (where the balance weight and skins sit)"),
    Assumption("section polar inertia", ("blade.im_lag", "blade.im_flap"), _section_inertia(0.9),
               _section_inertia(1.1), "x0.9", "x1.1",
               "radius of gyration 0.27-0.29 c +-5 %; torsion re-calibrated", recalibrate=True),
    Assumption("section CG", ("blade.cg_offset",), _cg_shift(-0.2), _cg_shift(0.2),
               "0.2 in aft", "0.2 in fwd", "ballast placement: section CG at the quarter chord "
               "+-2 % c"),
    Assumption("flap bending stiffness (flap modes 3-5)", ("blade.ei_flap",),
               _times("blade.ei_flap", 0.6), _times("blade.ei_flap", 1.6), "x0.6", "x1.6",
               "flap 3/4/5 at 4.46/6.75/9.68 (x0.6) to 5.03/8.06/12.3 per rev (x1.6), the band "
               "of soft-inplane hingeless and bearingless blades"),
    Assumption("lag bending stiffness (lag 2)", ("blade.ei_lag",), _times("blade.ei_lag", 0.7),
               _times("blade.ei_lag", 1.4), "x0.7", "x1.4",
               "lag 2 at 4.15 to 5.16 per rev"),
    Assumption("outboard GJ (torsion 2)", ("blade.gj",), _outboard_gj(0.7), _outboard_gj(1.4),
               "x0.7", "x1.4", "GJ outboard of 0.5 R relative to inboard; level re-calibrated, "
               "so torsion 1 stays (3.12 per rev) and torsion 2 moves (11.2 to 12.4 per rev)",
               recalibrate=True),
    Assumption("lift slope", ("rotor.lift_slope",), _lift_slope(5.5), _lift_slope(2 * math.pi),
               "5.5", "2 pi", "compressible airfoil data to thin-airfoil theory; blade mass "
               "scaled to keep the stated Lock number 9.17, torsion re-calibrated",
               recalibrate=True),
    Assumption("root flap spring", ("hub.flap_spring",), _times("hub.flap_spring", 0.5),
               _times("hub.flap_spring", 2.0), "x0.5", "x2",
               "first flap mode 1.04 to 1.06 per rev"),
    Assumption("root lag spring", ("hub.lag_spring",), _times("hub.lag_spring", 0.7),
               _times("hub.lag_spring", 1.4), "x0.7", "x1.4", "first lag mode 0.54 to 0.66 "
               "per rev (soft in-plane)"),
    Assumption("lag damper", ("hub.lag_damper",), _times("hub.lag_damper", 0.5),
               _times("hub.lag_damper", 2.0), "x0.5", "x2", "snubber placeholder (~2 % "
               "critical), halved or doubled"),
    Assumption("elastic axis", ("rotor.elastic_axis",), _set("rotor.elastic_axis", 0.23),
               _set("rotor.elastic_axis", 0.27), "0.23 c", "0.27 c",
               "quarter chord +-2 % c"),
    Assumption("modes retained", ("model.n_modes",), _set("model.n_modes", 6),
               _set("model.n_modes", 12), "6", "12",
               "the paper keeps nine coupled modes of its (unknown) blade; on this blade 6 "
               "drops flap 4, flap 5 and torsion 2 (7.3-11.8 per rev), 12 adds lag 3, flap 6 "
               "and 7"),
)


def _by_name(name: str) -> Assumption:
    for a in ASSUMPTIONS:
        if a.name == name:
            return a
    known = ", ".join(a.name for a in ASSUMPTIONS)
    raise ValueError(f"unknown assumption {name!r}; known: {known}")


def apply_assumption(cfg, assumption: Assumption | str, end: str):
    """The configuration with one assumption at its ``'low'`` or ``'high'`` end.

    Re-calibrates the torsion (GJ scale, horn arm, pitch-link stiffness) when
    the assumption asks for it.

    Raises
    ------
    ValueError
        Unknown end or assumption, or a changed configuration the data do not
        admit (e.g. a flap that no longer fits its section).
    """
    a = _by_name(assumption) if isinstance(assumption, str) else assumption
    if end not in ("low", "high"):
        raise ValueError(f"end must be 'low' or 'high', got {end!r}")
    new = cfg.with_overrides(getattr(a, end)(cfg))
    if a.recalibrate:
        from .calibration import calibrate_torsion

        fit = calibrate_torsion(new)
        new = new.with_overrides({"blade.gj_scale": fit["gj_scale"],
                                  "hub.pitch_horn_arm": fit["pitch_horn_arm"],
                                  "hub.pitch_link_stiffness": fit["pitch_link_stiffness"]})
    return new


def _case(cfg, a, end, identify, headlines, xtol):
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
    identify : callable
        Root to follow (default :func:`flutter_root`).
    headlines : sequence of Headline
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
    Returns the Axes.
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
