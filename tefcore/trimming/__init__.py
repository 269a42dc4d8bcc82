"""Trim: the periodic blade and flap response and the controls, solved together.

The wind-tunnel trim of the paper (zero first-harmonic flapping at a
prescribed thrust) by harmonic balance and Newton iterations.  The folder
is not called ``trim`` because :func:`tefcore.trim` is the function.

Its modules (import each by name; the package itself exports nothing)::

    trim    the trim: Newton iterations on the collocated residual, the result
    newton  the linear algebra of the Newton iterations (Broyden, shed-wake Schur)
    newton_matrix  the Newton matrix from the residual's per-azimuth blocks
"""

__all__: list[str] = []
