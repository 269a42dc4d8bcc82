"""Titles and captions of the paper's figures, from the configuration actually used.

A notebook draws a figure for whatever configuration the user asked for (the
paper's caption plus overrides); these functions describe that configuration
in the paper's symbols, so a title never says "μ = 0.30" when the user ran
μ = 0.2:

* :func:`conditions` -- flight condition, flap and aerodynamics of a configuration;
* :func:`figure_title` -- the paper figure's short title with those conditions;
* :func:`figure_caption` -- the report's caption: title, what the panels show,
  and what the markers and lines mean (:data:`MARKERS`).

Examples
--------
>>> from tefcore import load_config
>>> cfg = load_config("mdart").with_overrides({"flight.advance_ratio": 0.2})
>>> conditions(cfg, exclude=("flap.cg_offset",)).split(", ")  # doctest: +NORMALIZE_WHITESPACE
['μ = 0.20', 'C_T/σ = 0.075', 'c_b/c_f = 0.29', 'actuator 81.5 ft-lb/rad',
 'quasi-steady thin-airfoil aerodynamics']
"""

from __future__ import annotations

import re
import textwrap

import numpy as np

from ...units import from_si
from .catalogue import FIGURES
from .responses import RESPONSE_TITLES

__all__ = ["LOCUS_CAPTION", "MARKERS", "conditions", "figure_caption", "figure_title",
           "flight_condition"]

#: What the plots' markers and lines mean (the same in every stability figure).
MARKERS = ("Lines join the computed points of one root (including points added where an "
           "identity had to be decided); where a name moves to another root (an exceptional "
           "point between two points) its line stops and starts again on the other root. "
           "Filled markers are the figure's own sweep points. A hollow "
           "marker: the mode has the character (largest participation) of another mode "
           "there -- it exchanged character in a coupling. Dotted line and grey markers: "
           "its name is not certain there (a step of its continuation from zero coupling "
           "was not decided). Black crosses: the paper's curves, where digitised data were "
           "added. Each curve is the root of that name at every point: the uncoupled mode it "
           "continues from as the blade-flap coupling is switched on (\"TEF\": the flap's "
           "own mode).")

#: Caption of the root-locus and participation figures beside each stability figure.
LOCUS_CAPTION = ("Left: root locus of the tracked modes (square: first point; arrows: increasing "
                 "x; black dots: the flutter root of each point, the least stable flap-induced "
                 "root). Middle and right: participation of the flap, blade torsion, bending "
                 "and lag in the TEF mode and in the flutter root (participation factors, "
                 "summing to 1)")

_AERO_NAMES = {"thin_airfoil": "quasi-steady thin-airfoil aerodynamics",
               "c81": "C81 table aerodynamics"}


def flight_condition(cfg) -> str:
    """``"hover"`` or ``"μ = 0.30"``.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    """
    mu = cfg.flight.advance_ratio
    return "hover" if mu == 0 else f"μ = {mu:.2f}"


def conditions(cfg, exclude=()) -> str:
    """The flight condition and flap of ``cfg`` in the paper's symbols.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration actually analysed.
    exclude : iterable of str
        Dotted fields not to mention (the swept one).

    Returns
    -------
    str
        E.g. ``"μ = 0.30, C_T/σ = 0.07, c_b/c_f = 0.29, c_cg/c_f = 0.33, ..."``;
        hover is ``"hover"``; the flap is left out of a blade without one.
    """
    ex = set(exclude)
    fl, flap = cfg.flight, cfg.flap
    parts = []
    if "flight.advance_ratio" not in ex:
        parts.append(flight_condition(cfg))
    if "flight.collective" not in ex:
        if fl.collective is None:
            parts.append(f"C_T/σ = {fl.ct_sigma:.3g}")
        else:
            parts.append(f"θ₀ = {np.rad2deg(fl.collective):.1f} deg")
    if cfg.model.tef != "none":
        for field, text in (("flap.overhang", f"c_b/c_f = {flap.overhang:.2f}"),
                            ("flap.cg_offset", f"c_cg/c_f = {flap.cg_offset:.2f}")):
            if field not in ex:
                parts.append(text)
        if "actuator.stiffness" not in ex:
            parts.append(f"actuator {from_si(cfg.actuator.stiffness, 'ft-lbf/rad'):.1f} ft-lb/rad")
    else:
        parts.append("no flap")
    if "model.aero_model" not in ex:
        parts.append(_AERO_NAMES.get(cfg.model.aero_model, f"{cfg.model.aero_model} aerodynamics"))
    return ", ".join(parts)


def figure_title(name: str, cfg, width: int | None = None) -> str:
    """Short title of a paper figure with the conditions of ``cfg``.

    Parameters
    ----------
    name : str
        Paper figure (``"fig9"``).
    cfg : tefcore.config.configuration.Config
        The configuration actually analysed (:func:`conditions`).
    width : int, optional
        Wrap to lines of at most this many characters (for a plot title).

    Examples
    --------
    >>> from tefcore.paper.figures.runs import run_config
    >>> figure_title("fig9", run_config("fig9"))[:40]
    'Fig. 9: effect of flap CG offset (μ = 0.'
    """
    if name in FIGURES:
        fig = FIGURES[name]
        short = re.split(r",|\(", fig.caption, maxsplit=1)[0].strip()
        swept = (fig.parameter,)
    else:
        short, swept = RESPONSE_TITLES[name], ("flap.overhang",) if name == "fig7" else ()
    short = short[0].lower() + short[1:]
    title = f"Fig. {name[3:]}: {short} ({conditions(cfg, exclude=swept)})"
    return title if width is None else "\n".join(textwrap.wrap(title, width))


def figure_caption(name: str, cfg, what: str = "", markers: bool = True) -> str:
    """Report caption of a figure: what it shows, the conditions used, the markers.

    Parameters
    ----------
    name : str
        Paper figure (``"fig9"``).
    cfg : tefcore.config.configuration.Config
        The configuration actually analysed (caption fields and overrides).
    what : str
        What the panels show, e.g. ``"(a) TEF frequency; (b) damping"``.
    markers : bool
        Append what the markers and lines of a tracked-mode plot mean (:data:`MARKERS`).
    """
    text = figure_title(name, cfg) + "."
    if what:
        text += " " + what.rstrip(".") + "."
    return text + " " + MARKERS if markers else text
