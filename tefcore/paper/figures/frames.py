"""Figure results as tidy tables, and running one figure for the validation.

:func:`figure_frame` turns any figure's result into one long table with an
``x`` column (the figure's swept value); :func:`natural_frequency_frame`
adds the blade's natural frequencies at the same x; :func:`compute_figure`
runs a figure, optionally with configuration overrides (the variants some
claims compare against).  Used by :mod:`tefcore.paper.claims.checks`.
"""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd

from . import catalogue, responses
from .catalogue import FIGURES, KNOWN_FIGURES

__all__ = ["FIG7_OVERHANGS", "compute_figure", "figure_frame", "natural_frequency_frame"]

#: Overhangs of Fig. 7 when no claim asks for others.
FIG7_OVERHANGS = inspect.signature(
    responses.overhang_actuation_figure).parameters["overhangs"].default


def figure_frame(name: str, result) -> pd.DataFrame:
    """A figure's result as one long table with an ``x`` column.

    Parameters
    ----------
    name : str
        The figure: a stability figure of
        :data:`tefcore.paper.claims.reference.FIGURES` (``"fig3"`` ... ``"fig17"``),
        or ``"fig5"``, ``"fig6"``, ``"fig7"``.
    result : tefcore.sweeps.sweep.SweepResult, DataFrame or dict
        The figure's result: a stability figure's SweepResult (or its
        ``.table``), the DataFrame of :func:`tefcore.paper.figures.responses.hinge_moment_figure`
        (Fig. 5) or :func:`~tefcore.paper.figures.responses.overhang_actuation_figure`
        (Fig. 7), the dict of :func:`~tefcore.paper.figures.responses.flap_response_figure`
        (Fig. 6).

    Returns
    -------
    pandas.DataFrame
        Stability figures: the ok rows with ``x = value_si`` (SI value of the
        swept field; ``value`` if there is no ``value_si``), ``track``,
        ``label`` and the quantities, plus ``damping = -real_part`` [1/rev].
        Fig. 5: ``x = psi_deg``; Fig. 6: one row (``x`` NaN) with the half
        peak-to-peak response and the powers; Fig. 7: ``x = overhang``.

    Raises
    ------
    ValueError
        Unknown figure.
    TypeError
        A stability figure's result that is neither a SweepResult nor a
        DataFrame.
    """
    if name in FIGURES:
        t = getattr(result, "table", result)
        if not isinstance(t, pd.DataFrame):
            raise TypeError(f"{name}: expected a SweepResult or DataFrame, got {type(t)}")
        if "status" in t:
            t = t[t["status"] == "ok"]
        t = t.assign(x=pd.to_numeric(t["value_si" if "value_si" in t else "value"]))
        if "track" not in t:
            t = t.assign(track=t["label"])
        return t.assign(damping=-t["real_part"]) if "real_part" in t else t
    if name == "fig5":
        return result.assign(x=result["psi_deg"], label="", track=0)
    if name == "fig6":
        keys = ("half_peak_to_peak_deg", "peak_power", "mean_power")
        return pd.DataFrame([{"x": np.nan, "label": "", "track": 0,
                              **{k: float(result[k]) for k in keys}}])
    if name == "fig7":
        return result.assign(x=result["overhang"], label="", track=0)
    raise ValueError(f"unknown figure {name!r}; known: {', '.join(KNOWN_FIGURES)}")


def natural_frequency_frame(name, frame, cfg, overrides) -> pd.DataFrame:
    """Blade natural frequencies (:func:`tefcore.structure.blade.blade_modes`) at the frame's x.

    The quantity ``natural_frequency_per_rev`` of the claims: the rotating
    blade's natural frequencies (flap mass lumped into its sections, no flap
    degree of freedom, no aerodynamics, zero collective) of Figs. 10a and
    11a, whose torsion frequencies the text states, computed at every x of
    the figure.

    Parameters
    ----------
    name : str
        Stability figure (its swept field is set to each x).
    frame : pandas.DataFrame
        The figure's frame (:func:`figure_frame`); only its ``x`` column (SI
        values of the swept field) is used.
    cfg : tefcore.config.configuration.Config or None
        Base configuration (None: MDART); the figure's fixed parameters are
        applied over it.
    overrides : dict
        Dotted fields of a variant of the figure (empty for the figure itself).

    Returns
    -------
    pandas.DataFrame
        One row per x and blade mode: ``x``, ``label`` and ``track``
        (``"blade flap 1"``, ...) and ``natural_frequency_per_rev``.
    """
    from ...structure.blade import blade_modes

    base = catalogue.figure_config(name, cfg).with_overrides(overrides)
    rows = []
    for x in np.unique(frame["x"].to_numpy(float)):
        m = blade_modes(base.with_overrides({FIGURES[name].parameter: float(x)}))
        rows += [{"x": x, "label": f"blade {lab}", "track": f"blade {lab}",
                  "natural_frequency_per_rev": float(f)}
                 for lab, f in zip(m.labels, m.frequencies, strict=True)]
    return pd.DataFrame(rows)


def compute_figure(name, cfg=None, values=None, overrides=None, n_jobs=1, progress=False,
                   refine=True):
    """Run one figure (optionally with configuration overrides).

    Parameters
    ----------
    name : str
        A stability figure of :data:`tefcore.paper.claims.reference.FIGURES`, or
        ``"fig5"``, ``"fig6"``, ``"fig7"`` (flap-response analyses).
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    values : sequence, optional
        Swept values instead of the paper's (stability figures), or the
        overhangs of Fig. 7 (default :data:`FIG7_OVERHANGS`); ignored for
        Figs. 5 and 6.
    overrides : dict, optional
        Dotted fields of a variant of a stability figure (e.g. Fig. 12a's
        mass-balanced flap, ``{"flap.cg_offset": 0.0}``), applied after the
        caption's fixed parameters.
    n_jobs : int
        Processes of the sweep (:func:`tefcore.sweeps.sweep.sweep`); 1 runs serially.
    progress : bool
        Show the sweep's progress bar.
    refine : bool
        Bisect the steps where a root's identity is undecided
        (:func:`tefcore.sweeps.sweep.sweep`).

    Returns
    -------
    tefcore.sweeps.sweep.SweepResult, pandas.DataFrame or dict
        As :func:`tefcore.paper.figures.catalogue.run_figure` for a stability figure;
        the DataFrame of Figs. 5 and 7 or the dict of Fig. 6.
    """
    if name == "fig5":
        return responses.hinge_moment_figure(cfg)
    if name == "fig6":
        return responses.flap_response_figure(cfg)
    if name == "fig7":
        return responses.overhang_actuation_figure(cfg, overhangs=values or FIG7_OVERHANGS)
    values = list(FIGURES[name].values if values is None else values)
    if not overrides:
        return catalogue.run_figure(name, cfg, values=values, n_jobs=n_jobs, progress=progress,
                                    refine=refine)
    from ...sweeps.sweep import sweep

    base = catalogue.figure_config(name, cfg).with_overrides(overrides)
    return sweep(base, FIGURES[name].parameter, values, n_jobs=n_jobs, progress=progress,
                 refine=refine)
