"""The coupled model: the blade/flap/actuator equations of motion, eq. (5) before linearisation.

The residual of the coupled equations in rotor units, station by station,
its exact Jacobian, and the flap's own physics (hinge moments, propeller
moment) used by both the rotor equations and the section analyses of
Figs. 5-7.

Its modules, bottom up::

    flap              the flap and actuator: properties, hinge moments, natural frequency
    station_terms     the nonlinear part of the residual, station by station
    station_kernel    the station forces and their derivatives in one compiled pass
                      (numba, optional)
    coupled           the coupled blade/flap/actuator model and its residual
    jacobian          exact (complex-step) and finite-difference Jacobians of the residual
    section_response  the flap on a prescribed blade section: hinge moments, responses (Figs. 5-7)

Its public names (each loaded from its module on first use):

The coupled model
    :func:`~tefcore.model.coupled.coupled_model` (:class:`~tefcore.model.coupled.CoupledModel`,
    :class:`~tefcore.model.coupled.Controls`), :func:`~tefcore.model.coupled.section_model`,
    :func:`~tefcore.model.jacobian.jacobian_blocks`
The flap and its actuator
    :func:`~tefcore.model.flap.flap_properties` (:class:`~tefcore.model.flap.FlapProperties`),
    :func:`~tefcore.model.flap.flap_natural_frequency`,
    :func:`~tefcore.model.flap.flap_moments`, :func:`~tefcore.model.flap.propeller_moment`
The flap on a prescribed section (Figs. 5-7)
    :func:`~tefcore.model.section_response.rotor_motion`,
    :func:`~tefcore.model.section_response.flap_response`
    (:class:`~tefcore.model.section_response.FlapResponse`),
    :func:`~tefcore.model.section_response.hinge_moment_history`,
    :func:`~tefcore.model.section_response.section_overhang_study`

The residual's station terms are :func:`tefcore.model.station_terms.station_terms`: the
function has its module's name, so this face does not export it.

Examples
--------
The MDART flap on its actuator spring, per rev of the rotor:

>>> from tefcore import config, model
>>> cfg = config.load_config("mdart")
>>> omega = cfg.rotor.rotor_speed
>>> round(float(model.flap_natural_frequency(model.flap_properties(cfg), omega) / omega), 1)
17.5
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "coupled_model": "tefcore.model.coupled",
    "CoupledModel": "tefcore.model.coupled",
    "Controls": "tefcore.model.coupled",
    "section_model": "tefcore.model.coupled",
    "jacobian_blocks": "tefcore.model.jacobian",
    "flap_properties": "tefcore.model.flap",
    "FlapProperties": "tefcore.model.flap",
    "flap_natural_frequency": "tefcore.model.flap",
    "flap_moments": "tefcore.model.flap",
    "propeller_moment": "tefcore.model.flap",
    "rotor_motion": "tefcore.model.section_response",
    "flap_response": "tefcore.model.section_response",
    "FlapResponse": "tefcore.model.section_response",
    "hinge_moment_history": "tefcore.model.section_response",
    "section_overhang_study": "tefcore.model.section_response",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
