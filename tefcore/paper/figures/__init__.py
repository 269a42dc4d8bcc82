"""The paper's figures: what each one sweeps, how it is run, tabled, drawn and captioned.

Its modules, bottom up::

    catalogue   Figs. 3-4 and 8-17 as sweeps: the swept field, values, fixed caption
    responses   Figs. 5-7: hinge moment, flap response, actuation versus overhang
    quantities  the quantities on the paper's axes, their units and the swept dimension
    plotting    tracked modes, root loci, participation on the paper's axes; byte-stable PNGs
    runs        a figure's configuration as the notebooks run it; the point function
    frames      any figure's result as one long table with an x column
    captions    figure titles and captions written from the configuration run

Examples
--------
>>> from tefcore.paper import figures
>>> figures.FIGURES["fig12"].parameter
'actuator.stiffness'
>>> figures.figure_config("fig12").flap.cg_offset
0.33
"""

import sys

from ...faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "FIGURES": "tefcore.paper.figures.catalogue",
    "Figure": "tefcore.paper.figures.catalogue",
    "IMBALANCED": "tefcore.paper.figures.catalogue",
    "KNOWN_FIGURES": "tefcore.paper.figures.catalogue",
    "figure_config": "tefcore.paper.figures.catalogue",
    "run_figure": "tefcore.paper.figures.catalogue",
    "variant_key": "tefcore.paper.figures.catalogue",
    "flap_response_figure": "tefcore.paper.figures.responses",
    "hinge_moment_figure": "tefcore.paper.figures.responses",
    "overhang_actuation_figure": "tefcore.paper.figures.responses",
    "response_config": "tefcore.paper.figures.responses",
    "base_config": "tefcore.paper.figures.runs",
    "quiet_stability": "tefcore.paper.figures.runs",
    "run_config": "tefcore.paper.figures.runs",
    "natural_frequencies": "tefcore.paper.figures.runs",
    "compute_figure": "tefcore.paper.figures.frames",
    "figure_frame": "tefcore.paper.figures.frames",
    "locus_figure": "tefcore.paper.figures.plotting",
    "plot_modes": "tefcore.paper.figures.plotting",
    "plot_root_locus": "tefcore.paper.figures.plotting",
    "savefig": "tefcore.paper.figures.plotting",
    "figure_caption": "tefcore.paper.figures.captions",
    "figure_title": "tefcore.paper.figures.captions",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
