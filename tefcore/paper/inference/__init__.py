"""What the paper's rotor must have been: its unknown properties inferred from its claims.

The blade, hub, flap and actuator properties behind the paper's figures are not
public.  This room declares the space of the assumed ones with ranges argued from
construction, fits a declared subset of the claims with an optuna study whose
objective is their signed margins, holds the rest out, and reports what the data
support.  Its modules, bottom up::

    space        the declared parameter space (tefcore/data/inference/mdart-space.toml)
    protocol     fitted and held-out claims, readings of the TEF (protocol.toml)
    evaluate     one rotor checked against claims, surviving figures that fail
    study        the optuna study: storage, samplers, workers, progress, resume
    analysis     best rotors, failures, leave-one-figure-out, conflicts, Pareto fronts
    sensitivity  Sobol indices of each claim's margin over the space (SALib)
    inferred     the packaged variant mdart-inferred written from a study
    command      tefcore infer
"""

import sys

from ...faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "load_space": "tefcore.paper.inference.space",
    "apply_sample": "tefcore.paper.inference.space",
    "Refused": "tefcore.paper.inference.space",
    "load_protocol": "tefcore.paper.inference.protocol",
    "read_claims": "tefcore.paper.inference.protocol",
    "evaluate_rotor": "tefcore.paper.inference.evaluate",
    "objective": "tefcore.paper.inference.evaluate",
    "StudySpec": "tefcore.paper.inference.study",
    "run_study": "tefcore.paper.inference.study",
    "open_study": "tefcore.paper.inference.study",
    "trials_frame": "tefcore.paper.inference.analysis",
    "failures": "tefcore.paper.inference.analysis",
    "leave_one_figure_out": "tefcore.paper.inference.analysis",
    "pareto_front": "tefcore.paper.inference.analysis",
    "check_rotor": "tefcore.paper.inference.analysis",
    "sobol_indices": "tefcore.paper.inference.sensitivity",
    "inferred_rotor": "tefcore.paper.inference.inferred",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
