"""Time-domain response: watch a root grow, and check its Floquet growth rate.

The linearised periodic equations (the same ``M, C, K`` the Floquet analysis
uses) and the full nonlinear residual marched in azimuth from a small
perturbation of the trim; the growth fitted to the response's envelope
against the Floquet real part; the work of the mechanism's named terms
revolution by revolution; an animation of the blade section.

Its modules, bottom up::

    limits     the bounds of a march and its animation (imports nothing)
    march      integrate x* = A(psi) x revolution by revolution; fit the growth
    nonlinear  the coupled model's residual marched about the trim
    work       the work of each named term per revolution (the energy balance)
    simulate   simulate(cfg): perturbation, march, fit, comparison, outputs
    outputs    what ``tefcore simulate`` prints and writes
    animation  the section, the side view and the work, animated

Its public names (each loaded from its module on first use):

The simulation's result
    :class:`~tefcore.timedomain.simulate.SimulationResult`
The growth of a response
    :func:`~tefcore.timedomain.march.fit_growth` (:class:`~tefcore.timedomain.march.GrowthFit`),
    :func:`~tefcore.timedomain.march.envelope`, :class:`~tefcore.timedomain.march.Trajectory`
The energy balance
    :func:`~tefcore.timedomain.work.work_per_revolution`
Animation
    :func:`~tefcore.timedomain.animation.animate`,
    :func:`~tefcore.timedomain.animation.save_animation`

The simulation itself is :func:`tefcore.simulate` (``tefcore.timedomain.simulate.simulate``),
and the march :func:`tefcore.timedomain.march.march`: each function has its
module's name, so this face does not export them.

Examples
--------
The growth rate of ``exp(0.05 psi) cos(3 psi)`` over ten revolutions:

>>> import numpy as np
>>> from tefcore import timedomain
>>> psi = np.linspace(0.0, 20 * np.pi, 2001)
>>> fit = timedomain.fit_growth(psi, np.exp(0.05 * psi) * np.cos(3 * psi))
>>> isinstance(fit, timedomain.GrowthFit), round(fit.rate, 6)
(True, 0.05)
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "SimulationResult": "tefcore.timedomain.simulate",
    "fit_growth": "tefcore.timedomain.march",
    "GrowthFit": "tefcore.timedomain.march",
    "envelope": "tefcore.timedomain.march",
    "Trajectory": "tefcore.timedomain.march",
    "work_per_revolution": "tefcore.timedomain.work",
    "animate": "tefcore.timedomain.animation",
    "save_animation": "tefcore.timedomain.animation",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
