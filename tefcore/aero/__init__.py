"""Aerodynamics: section airloads of the flapped airfoil, inflow, aerodynamic states.

Section models share one interface, ``loads(...)`` with ``lift, drag, moment,
hinge_moment``: the section's aerodynamic hinge moment is written once per
section model; the flap equation takes it from there (:mod:`tefcore.model.flap`).

Its modules (import each by name; the package itself exports nothing)::

    theodorsen      Theodorsen's flapped thin airfoil, quasi-steady
    thin_airfoil    the balanced-flap thin airfoil as a section model
    unsteady        finite-state shed wake of the balanced flap
    c81             C81 airfoil decks: format, reader, table models
    inflow          uniform momentum and Drees inflow
    dynamic_inflow  Pitt-Peters dynamic inflow
    states          aerodynamic states of the rotor model: shed wake per station, dynamic inflow
"""

__all__: list[str] = []
