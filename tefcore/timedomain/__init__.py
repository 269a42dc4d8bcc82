"""Time-domain response: watch a root grow, and check its Floquet growth rate.

The linearised periodic equations (the same ``M, C, K`` the Floquet analysis
uses) and the full nonlinear residual marched in azimuth from a small
perturbation of the trim; the growth fitted to the response's envelope
against the Floquet real part; the work of the mechanism's named terms
revolution by revolution; an animation of the blade section.

Its modules (import each by name; the package itself exports nothing)::

    limits     the bounds of a march and its animation (imports nothing)
    march      integrate x* = A(psi) x revolution by revolution; fit the growth
    nonlinear  the coupled model's residual marched about the trim
    work       the work of each named term per revolution (the energy balance)
    simulate   simulate(cfg): perturbation, march, fit, comparison, outputs
    animation  the section, the side view and the work, animated
"""

__all__: list[str] = []
