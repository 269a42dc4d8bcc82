"""The coupled model: the blade/flap/actuator equations of motion, eq. (5) before linearisation.

The residual of the coupled equations in rotor units, station by station,
its exact Jacobian, and the flap's own physics (hinge moments, propeller
moment) used by both the rotor equations and the section analyses of
Figs. 5-7.

Its modules (import each by name; the package itself exports nothing)::

    flap           the flap and actuator: properties, hinge moments, section analyses (Figs. 5-7)
    station_terms  the nonlinear part of the residual, station by station
    station_kernel the station forces and their derivatives in one compiled pass (numba, optional)
    coupled        the coupled blade/flap/actuator model and its residual
    jacobian       exact (complex-step) and finite-difference Jacobians of the residual
"""

__all__: list[str] = []
