"""The rotor linearised about its trim: Floquet modes, labelled, and why a root is unstable.

``stability(cfg)`` is the paper's analysis of one point (eq. (5) about the
trim, Floquet eigenanalysis); ``mechanism`` writes a root's growth as the
work of named physical terms.  The folder is not called ``stability``
because :func:`tefcore.stability` is the function.

Its modules, bottom up::

    stability  linearisation about the trim and the labelled Floquet modes
    mechanism  a root's growth rate as the work of named terms, knockouts

Its public names (each loaded from its module on first use):

One point's stability
    :class:`~tefcore.linear.stability.StabilityResult`,
    :func:`~tefcore.linear.stability.linearize`,
    :func:`~tefcore.linear.stability.linear_system`,
    :func:`~tefcore.linear.stability.periodic_state_matrix`
The mechanism of a root
    :class:`~tefcore.linear.mechanism.MechanismResult`,
    :func:`~tefcore.linear.mechanism.energy_decomposition`,
    :func:`~tefcore.linear.mechanism.linearized_terms`,
    :data:`~tefcore.linear.mechanism.TERMS`

The two analyses themselves are :func:`tefcore.stability` and
:func:`tefcore.mechanism` (``tefcore.linear.stability.stability``,
``tefcore.linear.mechanism.mechanism``): each function has its module's name,
so this face does not export them.

Examples
--------
>>> import tefcore
>>> from tefcore import linear
>>> result = tefcore.stability(tefcore.load_config("mdart"))
>>> isinstance(result, linear.StabilityResult)
True
>>> bool((result.modes["real_part"] < 0).all())      # hover: every mode damped
True
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "StabilityResult": "tefcore.linear.stability",
    "linearize": "tefcore.linear.stability",
    "linear_system": "tefcore.linear.stability",
    "periodic_state_matrix": "tefcore.linear.stability",
    "MechanismResult": "tefcore.linear.mechanism",
    "energy_decomposition": "tefcore.linear.mechanism",
    "linearized_terms": "tefcore.linear.mechanism",
    "TERMS": "tefcore.linear.mechanism",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
