"""Mode identity: which root is which, and the roles a root plays.

Labels from participation, matching between points (MAC and eigenvalue
distance), tracking along a parameter, continuation in the coupling and the
roles (the TEF mode, the flutter root).

Its modules, bottom up::

    matching      matching modes between two points: MAC, eigenvalue distances, cost
    labels        a root's label from the coordinate it carries (participation)
    tracking      tracks along a parameter: one curve is one physical mode
    march         (private) the paths of continuation, one step of eps at a time
    final_names   (private) names at full coupling of the roots a path does not decide
    continuation  identity by continuation in the blade-flap coupling (the names)
    roles         the TEF mode, the flutter root, exceptional points along a sweep

Its public names (each loaded from its module on first use):

Matching two points
    :func:`~tefcore.modes.matching.mac`, :func:`~tefcore.modes.matching.match_modes`
Tracking along a parameter
    :func:`~tefcore.modes.tracking.track_modes`, :func:`~tefcore.modes.tracking.follow_root`
    (:class:`~tefcore.modes.tracking.FollowResult`)
Labels of one point
    :func:`~tefcore.modes.labels.label_modes`, :func:`~tefcore.modes.labels.coordinate_shares`
Names by continuation in the coupling
    :func:`~tefcore.modes.continuation.continue_roots`
    (:class:`~tefcore.modes.continuation.ContinuedRoots`)
Roles
    :func:`~tefcore.modes.roles.flutter_root`, :func:`~tefcore.modes.roles.exceptional_points`,
    :class:`~tefcore.modes.roles.ModeNotFound`

Examples
--------
>>> import numpy as np
>>> from tefcore import modes
>>> modes.mac(np.array([1.0, 0.0]), np.array([1.0, 1.0]))    # 45 degrees apart
array([[0.5]])
>>> modes.mac(np.array([1.0, 2.0j]), np.array([2.0j, -4.0]))  # parallel, any complex scale
array([[1.]])
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "mac": "tefcore.modes.matching",
    "match_modes": "tefcore.modes.matching",
    "track_modes": "tefcore.modes.tracking",
    "follow_root": "tefcore.modes.tracking",
    "FollowResult": "tefcore.modes.tracking",
    "label_modes": "tefcore.modes.labels",
    "coordinate_shares": "tefcore.modes.labels",
    "continue_roots": "tefcore.modes.continuation",
    "ContinuedRoots": "tefcore.modes.continuation",
    "flutter_root": "tefcore.modes.roles",
    "exceptional_points": "tefcore.modes.roles",
    "ModeNotFound": "tefcore.modes.roles",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
