"""The rotor linearised about its trim: Floquet modes, labelled, and why a root is unstable.

``stability(cfg)`` is the paper's analysis of one point (eq. (5) about the
trim, Floquet eigenanalysis); ``mechanism`` writes a root's growth as the
work of named physical terms.  The folder is not called ``stability``
because :func:`tefcore.stability` is the function.

Its modules (import each by name; the package itself exports nothing)::

    stability  linearisation about the trim and the labelled Floquet modes
    mechanism  a root's growth rate as the work of named terms, knockouts
"""

__all__: list[str] = []
