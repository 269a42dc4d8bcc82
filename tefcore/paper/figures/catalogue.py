"""The paper's figures as analyses: one definition per figure, tidy tables out.

Each stability figure (3-4, 8-17) is a sweep of one configuration field about
the MDART baseline with the fixed parameters of its caption
(:data:`FIGURES`); :func:`run_figure` runs it with :func:`tefcore.sweeps.sweep.sweep`.
Figures 5-7 are flap-response analyses about a trimmed forward-flight state
(:mod:`tefcore.paper.figures.responses`). Notebooks and
:mod:`tefcore.paper.claims.validation` both call these, so a figure is computed the
same way everywhere.

Examples
--------
>>> FIGURES["fig9"].parameter, [float(v) for v in FIGURES["fig9"].values[:3]]
('flap.cg_offset', [0.0, 0.04, 0.08])
>>> FIGURES["fig10"].values[0], FIGURES["fig10"].values[-1]
('150 lb/in', '800 lb/in')
>>> cfg = figure_config("fig10")
>>> cfg.flight.advance_ratio, cfg.flap.overhang, cfg.flap.cg_offset
(0.3, 0.29, 0.33)
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from ...config.io import load_config
from ...sweeps.sweep import sweep

__all__ = ["FIGURES", "FORWARD_03", "IMBALANCED", "KNOWN_FIGURES", "Figure", "figure_config",
           "run_figure", "variant_key"]

#: the mass-imbalanced flap of Figs. 10-17 and Fig. 9's overhang
IMBALANCED = {"flap.overhang": 0.29, "flap.cg_offset": 0.33}
#: the forward flight of Figs. 9-15 and 16b: "advance ratio of 0.30"
FORWARD_03 = {"flight.advance_ratio": 0.30}


@dataclass(frozen=True)
class Figure:
    """A stability figure: the swept field, its values and the fixed parameters.

    Parameters
    ----------
    name : str
        The figure's name in tefcore (``"fig9"``; Fig. 16's panels are
        ``"fig16a"`` and ``"fig16b"``), the key of :data:`FIGURES`.
    caption : str
        Short caption in the paper's symbols, with the fixed parameters.
    parameter : str
        Dotted configuration field swept along the figure's x axis
        (``"flap.cg_offset"``, ``"hub.pitch_link_stiffness"``, ...).
    values : tuple
        The paper's x values: SI numbers (fractions of a chord or of R, a GJ
        factor, radians of collective) or ``"value unit"`` strings where the
        paper gives a dimensional axis (``"150 lb/in"``, ``"81.520 ft-lb/rad"``).
    fixed : dict, optional
        Dotted fields set before sweeping: the caption's flight condition and
        flap (e.g. :data:`IMBALANCED` and ``mu = 0.3`` for Figs. 10-15).
    unit : str, optional
        Unit of numeric ``values`` when they are not fractions (``"rad"`` for
        the collective of Figs. 3, 4 and 16).
    """

    name: str
    caption: str
    parameter: str
    values: tuple
    fixed: dict = field(default_factory=dict)
    unit: str = ""


FIGURES = {f.name: f for f in (
    Figure("fig3", "Blade inplane stability in hover, baseline rotor without TEF",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 11.0, 1.0))),
           {"model.tef": "none", "flight.advance_ratio": 0.0}, "rad"),
    Figure("fig4", "Blade inplane stability, mu = 0.25, forward shaft tilt 7.3 deg, no TEF",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 11.0, 1.0))),
           {"model.tef": "none", "flight.advance_ratio": 0.25,
            "flight.shaft_angle": float(np.deg2rad(7.3))}, "rad"),
    Figure("fig8", "Effect of overhang length on stability in hover, c_cg/c_f = 0",
           "flap.overhang", tuple(np.round(np.arange(0.0, 0.71, 0.05), 2)),
           {"flight.advance_ratio": 0.0, "flap.cg_offset": 0.0}),
    Figure("fig9", "Effect of flap CG offset, c_b/c_f = 0.29, mu = 0.30",
           "flap.cg_offset", tuple(np.round(np.arange(0.0, 0.41, 0.04), 2)),
           {**FORWARD_03, "flap.overhang": 0.29}),
    Figure("fig10", "Effect of pitch link stiffness, mu = 0.30, c_b/c_f = 0.29, c_cg/c_f = 0.33",
           "hub.pitch_link_stiffness", tuple(f"{k} lb/in" for k in range(150, 801, 50)),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig11", "Effect of blade torsional stiffness (GJ factor), mu = 0.30, imbalanced flap",
           "blade.gj_scale", (0.75, 1.0, 1.25, 1.5, 1.75, 2.0), {**FORWARD_03, **IMBALANCED}),
    Figure("fig12", "Effect of actuator stiffness (factor on 81.52 ft-lb/rad), mu = 0.30",
           "actuator.stiffness", tuple(f"{81.52 * k:.3f} ft-lb/rad"
                                       for k in (0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0)),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig13", "Effect of flap spanwise location, mu = 0.30, imbalanced flap",
           "flap.midspan", (0.65, 0.70, 0.75, 0.80, 0.83, 0.86, 0.90),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig14", "Effect of flap length, mu = 0.30, imbalanced flap",
           "flap.span", (0.06, 0.08, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20, 0.22),
           {**FORWARD_03, **IMBALANCED, "flap.midspan": 0.80}),
    Figure("fig15", "Effect of flap chord size, mu = 0.30, imbalanced flap",
           "flap.chord_ratio", (0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig16a", "Effect of collective pitch in hover, imbalanced flap",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 13.0, 2.0))),
           {"flight.advance_ratio": 0.0, **IMBALANCED}, "rad"),
    Figure("fig16b", "Effect of collective pitch, mu = 0.30, imbalanced flap",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 13.0, 2.0))),
           {**FORWARD_03, **IMBALANCED}, "rad"),
    Figure("fig17", "Effect of forward speed, imbalanced flap",
           "flight.advance_ratio", (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35),
           IMBALANCED),
)}

#: Every figure tefcore computes: the stability figures and the flap responses (5-7).
KNOWN_FIGURES = tuple(FIGURES) + ("fig5", "fig6", "fig7")


def figure_config(name: str, cfg=None):
    """Baseline configuration with the figure's fixed parameters applied.

    Parameters
    ----------
    name : str
        Stability figure, a key of :data:`FIGURES` (``"fig3"`` ... ``"fig17"``).
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: the MDART baseline, ``load_config("mdart")``).

    Returns
    -------
    tefcore.config.configuration.Config
        ``cfg`` with :attr:`Figure.fixed` applied, before the swept field is set.
    """
    fig = FIGURES[name]
    return (cfg or load_config("mdart")).with_overrides(fig.fixed)


def run_figure(name: str, cfg=None, values=None, **sweep_kw):
    """Run a stability figure's sweep; ``values`` override the default range.

    Parameters
    ----------
    name : str
        Stability figure, a key of :data:`FIGURES`.
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART); the figure's fixed parameters
        are applied over it (:func:`figure_config`).
    values : sequence, optional
        Values of the swept field instead of the paper's :attr:`Figure.values`
        (SI numbers or ``"value unit"`` strings).
    **sweep_kw
        Passed to :func:`tefcore.sweeps.sweep.sweep` (``n_jobs``, ``out``, ``refine``,
        ...); ``progress`` defaults to False.

    Returns
    -------
    tefcore.sweeps.sweep.SweepResult
        One Floquet analysis per value; ``.table`` is tidy (one row per root
        and point, with the tracked mode, the TEF branch and the flutter root).

    Raises
    ------
    ValueError
        ``name`` is not a stability figure (the message lists the known ones).
    """
    if name not in FIGURES:
        raise ValueError(f"unknown figure {name!r}; known: {', '.join(FIGURES)}")
    fig = FIGURES[name]
    sweep_kw.setdefault("progress", False)
    return sweep(figure_config(name, cfg), fig.parameter,
                 list(fig.values if values is None else values), **sweep_kw)


def variant_key(overrides: dict) -> str:
    """Canonical key of a configuration variant (``""`` for the figure itself).

    Claims about a variant of a figure (e.g. Fig. 12a's mass-balanced flap,
    ``{"flap.cg_offset": 0.0}``) look their result up under this key, so two
    claims with the same overrides share one run.

    Parameters
    ----------
    overrides : dict
        Dotted configuration fields of the variant (a claim's ``overrides``
        or ``other_overrides``); empty or None for the figure as captioned.

    Returns
    -------
    str
        JSON of ``overrides`` with sorted keys, or ``""``.

    Examples
    --------
    >>> variant_key({"flap.cg_offset": 0.0, "flight.advance_ratio": 0.3})
    '{"flap.cg_offset": 0.0, "flight.advance_ratio": 0.3}'
    >>> variant_key({})
    ''
    """
    return json.dumps(overrides, sort_keys=True) if overrides else ""
