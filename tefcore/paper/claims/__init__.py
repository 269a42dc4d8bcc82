"""What the paper states and how each statement is checked.

A claim is one sentence of the paper (or a point of a digitised curve) made
checkable: the figure it reads, the mode, the quantity and the threshold.  Its
modules, bottom up::

    files        the reference-data folder and its TOML and digitised-curve files
    reference    the claim model: parsed, validated, loaded (``load_claims``)
    curves       zero crossings, stability intervals, digitised-curve comparison
    exceptional  where two roots exchange identity inside a claim's range
    checks       one check per kind of claim, against one figure's result
    validation   every figure with a claim run and checked; the recorded statuses
    variants     the packaged configurations (mdart, mdart-fig6): tags and records

Examples
--------
>>> from tefcore.paper import claims
>>> claim = next(c for c in claims.load_claims() if c.id == "fig9b-tef-unstable-after-0.26")
>>> claim.figure, claim.kind, claim.tag
('fig9', 'threshold', 'validation')
"""

import sys

from ...faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "Claim": "tefcore.paper.claims.reference",
    "KINDS": "tefcore.paper.claims.reference",
    "STATUSES": "tefcore.paper.claims.reference",
    "load_claims": "tefcore.paper.claims.reference",
    "parse_claim": "tefcore.paper.claims.reference",
    "validate_figure": "tefcore.paper.claims.checks",
    "claims_score": "tefcore.paper.claims.validation",
    "figure_values": "tefcore.paper.claims.validation",
    "reference_curves": "tefcore.paper.claims.validation",
    "sweep_values": "tefcore.paper.claims.validation",
    "validate_all": "tefcore.paper.claims.validation",
    "worse_than_recorded": "tefcore.paper.claims.validation",
    "Variant": "tefcore.paper.claims.variants",
    "apply_variant": "tefcore.paper.claims.variants",
    "load_variants": "tefcore.paper.claims.variants",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
