"""Quasi-steady against unsteady airloads, momentum against dynamic inflow: the imbalanced flap.

The paper's analysis is quasi-steady (Theodorsen with ``C(k) = 1``, or tables)
with a free wake in the trim; tefcore can add the shed wake of the balanced
flap (``model.aero = "unsteady"``) and Pitt-Peters dynamic inflow
(``model.inflow = "dynamic"``), both as states of the Floquet analysis
(docs/theory.md section 6.2).  :func:`compare_models` runs the imbalanced-flap
results of the paper under each option:

* the **Fig. 9 onset**: the flap CG offset ``c_cg/c_f`` at which the flutter
  root -- the least stable flap-induced root
  (:func:`tefcore.modes.roles.flutter_root`) -- turns unstable at ``mu = 0.3``,
  ``c_b/c_f = 0.29`` (paper: 0.26);
* the **growth rate** of that root at the imbalanced baseline
  (``c_cg/c_f = 0.33``, ``c_b/c_f = 0.29``) in hover and at ``mu = 0.3``;
* the **mechanism**: the flutter root's growth rate at ``mu = 0.3`` as the work
  of named terms (:func:`tefcore.linear.mechanism.mechanism`), one column per option,
  with the aerodynamic states' own terms (the lift deficiency ``1 - C``, the
  inflow) where they exist.

The onsets and growth rates are :func:`tefcore.paper.attribution.sensitivity.headline_results`,
so they are the same numbers as the sensitivity study's baseline row.

Examples
--------
>>> list(OPTIONS)
['quasi-steady', 'unsteady', 'dynamic inflow', 'unsteady + dynamic inflow']
"""

from __future__ import annotations

from dataclasses import dataclass, field

import pandas as pd

from ...config.io import load_config

__all__ = ["OPTIONS", "ComparisonResult", "compare_models"]

#: The model options compared: name -> configuration overrides.
OPTIONS = {
    "quasi-steady": {"model.aero": "quasi_steady"},
    "unsteady": {"model.aero": "unsteady"},
    "dynamic inflow": {"model.aero": "quasi_steady", "model.inflow": "dynamic"},
    "unsteady + dynamic inflow": {"model.aero": "unsteady", "model.inflow": "dynamic"},
}

#: The imbalanced flap of Figs. 10-17 and its flight condition for the mechanism.
_BASELINE = {"flap.overhang": 0.29, "flap.cg_offset": 0.33, "flight.advance_ratio": 0.3}


@dataclass
class ComparisonResult:
    """Result of :func:`compare_models`.

    Attributes
    ----------
    headlines : DataFrame
        One row per option: ``option``, ``fig9_onset`` (``c_cg/c_f``),
        ``growth_hover``, ``growth_mu03`` (1/rev) and ``status`` (why an onset
        is missing, else ``"ok"``).
    roots : DataFrame
        The flutter root at the imbalanced baseline per option and flight
        condition: ``option, advance_ratio, label, real_part, frequency_per_rev,
        share_TEF``.
    mechanism : DataFrame
        Growth-rate contributions (1/rev) of each term (rows) per option
        (columns) for the flutter root at ``mu = 0.3``; a term an option does
        not have is NaN; the last rows are ``total`` and ``closure``.
    details : dict
        Option -> its :class:`tefcore.linear.mechanism.MechanismResult`.
    """

    headlines: pd.DataFrame
    roots: pd.DataFrame
    mechanism: pd.DataFrame
    details: dict = field(default_factory=dict, repr=False)


def compare_models(cfg=None, options=None, *, onset: bool = True,
                   knockouts: bool = False) -> ComparisonResult:
    """Fig. 9 onset, growth rates and mechanism of the imbalanced flap under each option.

    Parameters
    ----------
    cfg : Config, optional
        Base configuration (default MDART); the options override its
        ``model.aero`` and ``model.inflow``.
    options : dict of str to dict, optional
        Name -> overrides (default :data:`OPTIONS`).
    onset : bool
        Also find the Fig. 9 onset (a scan and a root search per option: a
        minute with the unsteady airloads on two cores, measured).
    knockouts : bool
        Also the mechanism's knockouts (each a continuation).

    Returns
    -------
    ComparisonResult
    """
    from ...linear.mechanism import TERMS, mechanism
    from ...linear.stability import stability
    from ...sweeps.store import config_hash
    from .sensitivity import HEADLINES, flutter_root, headline_results

    cfg = cfg or load_config("mdart")
    options = OPTIONS if options is None else options
    wanted = [h for h in HEADLINES if h.name in ("growth_hover", "growth_mu03")
              or (onset and h.name == "fig9_onset")]
    heads, roots, columns, details = [], [], {}, {}
    for name, over in options.items():
        c = cfg.with_overrides(over)
        solved: dict = {}     # the growth headlines' points: the roots' points below
        h = headline_results(c, headlines=wanted, solved=solved)
        bad = h.loc[h["status"] != "ok", "status"]
        heads.append({"option": name, **dict(zip(h["headline"], h["value"], strict=True)),
                      "status": "; ".join(bad) if len(bad) else "ok"})
        for mu in (0.0, 0.3):
            point = c.with_overrides({**_BASELINE, "flight.advance_ratio": mu})
            res = solved.get(config_hash(point)) or stability(point)
            row = flutter_root(res)
            roots.append({"option": name, "advance_ratio": mu, "label": row["label"],
                          "real_part": row["real_part"],
                          "frequency_per_rev": row["frequency_per_rev"],
                          "share_TEF": row["share_TEF"]})
            if mu == 0.3:
                me = mechanism(c.with_overrides(_BASELINE), mode="flutter",
                               knockouts=knockouts, stability_result=res)
                details[name] = me
                t = me.table.set_index("term")["contribution_real"]
                columns[name] = pd.concat([t, pd.Series({"closure": me.closure})])
    mech = pd.DataFrame(columns)
    # rows in the order of the named terms, knockouts after them
    terms = [t for t in TERMS if t in mech.index]
    rest = [t for t in mech.index if t not in terms and t not in ("total", "closure")]
    mech = mech.loc[terms + rest + ["total", "closure"]]
    mech.index.name = "term"
    return ComparisonResult(headlines=pd.DataFrame(heads), roots=pd.DataFrame(roots),
                            mechanism=mech, details=details)
