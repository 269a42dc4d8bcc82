"""Trim: the periodic blade and flap response and the controls, solved together.

The wind-tunnel trim of the paper (zero first-harmonic flapping at a
prescribed thrust) by harmonic balance and Newton iterations.  The folder
is not called ``trim`` because :func:`tefcore.trim` is the function.

Its modules, bottom up::

    newton  the linear algebra of the Newton iterations (Broyden, shed-wake Schur)
    newton_matrix  the Newton matrix from the residual's per-azimuth blocks
    trim           the trim: Newton iterations on the collocated residual, the result

Its public names (each loaded from its module on first use):

The trim's result and its failure
    :class:`~tefcore.trimming.trim.TrimResult`, :class:`~tefcore.trimming.trim.TrimError`
The first collective
    :func:`~tefcore.trimming.trim.initial_collective`
The flap's limit
    :data:`~tefcore.trimming.trim.MAX_FLAP_DEFLECTION_DEG`

The trim itself is :func:`tefcore.trim` (``tefcore.trimming.trim.trim``): the
function has its module's name, so this face does not export it.

Examples
--------
>>> import tefcore
>>> from tefcore import model, trimming
>>> cfg = tefcore.load_config("mdart")
>>> theta = trimming.initial_collective(cfg)
>>> result = tefcore.trim(model.coupled_model(cfg, collective=theta))
>>> isinstance(result, trimming.TrimResult), round(result.ct_sigma / cfg.flight.ct_sigma, 6)
(True, 1.0)
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "TrimResult": "tefcore.trimming.trim",
    "TrimError": "tefcore.trimming.trim",
    "initial_collective": "tefcore.trimming.trim",
    "MAX_FLAP_DEFLECTION_DEG": "tefcore.trimming.trim",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
