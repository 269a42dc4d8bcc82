"""Why the replication differs from the paper: the assumed properties and what they move.

MDART's blade, hub, flap and actuator properties are not public; tefcore
assumes them.  This room names every assumption with its plausible range,
moves each (the levers) to see which claims it can flip, and compares the
model options the paper's UMARC has and the compact model does not.  Its
modules, bottom up::

    assumptions       each assumed MDART property and the plausible range it is varied over
    departures        where the compact model departs from UMARC, as one shared text
    sensitivity       headline results with each assumption at its range's ends (tornado)
    model_comparison  the headline results under each model option
    hub_comparison    the equivalent root springs against the multiple-load-path hub
    modal_truncation  the imbalanced flap's flutter versus the blade modes retained
    levers            the assumptions and model options the attribution moves
    evaluate          a claim's own check on a moved configuration, on its deciding points
    search            the bisection of a lever for one claim, confirmation, conflicts
    differences       every failing claim attributed: what would flip it, and is that plausible
"""

import sys

from ...faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "ASSUMPTIONS": "tefcore.paper.attribution.assumptions",
    "Assumption": "tefcore.paper.attribution.assumptions",
    "apply_assumption": "tefcore.paper.attribution.assumptions",
    "headline_results": "tefcore.paper.attribution.sensitivity",
    "tornado_plot": "tefcore.paper.attribution.sensitivity",
    "tornado_table": "tefcore.paper.attribution.sensitivity",
    "Lever": "tefcore.paper.attribution.levers",
    "Attribution": "tefcore.paper.attribution.differences",
    "attribute": "tefcore.paper.attribution.differences",
    "attribute_run": "tefcore.paper.attribution.differences",
    "failing_claims": "tefcore.paper.attribution.differences",
    "departures_text": "tefcore.paper.attribution.departures",
    "show_departures": "tefcore.paper.attribution.departures",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
