"""Aerodynamics: section airloads of the flapped airfoil, inflow, aerodynamic states.

Section models share one interface, ``loads(...)`` with ``lift, drag, moment,
hinge_moment``: the section's aerodynamic hinge moment is written once per
section model; the flap equation takes it from there (:mod:`tefcore.model.flap`).

Its modules, bottom up::

    theodorsen      Theodorsen's flapped thin airfoil, quasi-steady
    thin_airfoil    the balanced-flap thin airfoil as a section model
    unsteady        finite-state shed wake of the balanced flap
    c81             C81 airfoil decks: format, reader, table models (a package)
    inflow          uniform momentum and Drees inflow
    dynamic_inflow  Pitt-Peters dynamic inflow
    states          aerodynamic states of the rotor model: shed wake per station, dynamic inflow

Its public names (each loaded from its module on first use):

Section models
    :class:`~tefcore.aero.thin_airfoil.ThinAirfoilFlap`,
    :class:`~tefcore.aero.unsteady.UnsteadyFlapAirfoil`,
    :class:`~tefcore.aero.c81.C81Airfoil`, :class:`~tefcore.aero.c81.C81FlapTable`,
    :func:`~tefcore.aero.thin_airfoil.prandtl_glauert`
Unsteady aerodynamics
    :func:`~tefcore.aero.unsteady.theodorsen_function`,
    :func:`~tefcore.aero.unsteady.wagner_function`,
    :func:`~tefcore.aero.theodorsen.quasi_steady_loads`
C81 decks
    :func:`~tefcore.aero.c81.read_c81`, :func:`~tefcore.aero.c81.write_c81`,
    :class:`~tefcore.aero.c81.C81Deck`
Inflow
    :func:`~tefcore.aero.inflow.momentum_inflow`, :func:`~tefcore.aero.inflow.rotor_inflow`,
    :func:`~tefcore.aero.inflow.drees_gradients`,
    :func:`~tefcore.aero.dynamic_inflow.steady_inflow`,
    :func:`~tefcore.aero.dynamic_inflow.perturbation_matrices`
Aerodynamic states of the rotor model
    :class:`~tefcore.aero.states.ShedWake`

Examples
--------
Momentum inflow in hover, ``lambda = sqrt(C_T / 2)``:

>>> from tefcore import aero
>>> round(aero.momentum_inflow(0.008, 0.0), 10)
0.0632455532
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "ThinAirfoilFlap": "tefcore.aero.thin_airfoil",
    "prandtl_glauert": "tefcore.aero.thin_airfoil",
    "UnsteadyFlapAirfoil": "tefcore.aero.unsteady",
    "theodorsen_function": "tefcore.aero.unsteady",
    "wagner_function": "tefcore.aero.unsteady",
    "quasi_steady_loads": "tefcore.aero.theodorsen",
    "C81Airfoil": "tefcore.aero.c81",
    "C81FlapTable": "tefcore.aero.c81",
    "C81Deck": "tefcore.aero.c81",
    "read_c81": "tefcore.aero.c81",
    "write_c81": "tefcore.aero.c81",
    "momentum_inflow": "tefcore.aero.inflow",
    "rotor_inflow": "tefcore.aero.inflow",
    "drees_gradients": "tefcore.aero.inflow",
    "steady_inflow": "tefcore.aero.dynamic_inflow",
    "perturbation_matrices": "tefcore.aero.dynamic_inflow",
    "ShedWake": "tefcore.aero.states",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
