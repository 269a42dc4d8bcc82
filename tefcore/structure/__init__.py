"""Structure: the rotating finite-element blade, its hub and the flap inside its section.

The blade and hub in vacuum: 15-dof rotating beam elements, the equivalent
root springs or the multiple-load-path hub, the flap lumped into its blade
section, and the coupled blade modes (eta = 0 of the coupling: their
structural labels are where mode identity starts, :mod:`tefcore.modes`).

Its modules (import each by name; the package itself exports nothing)::

    beam_element     the 15-dof rotating beam element
    fem              assembly, root springs, coupled modes and their structural labels
    branched         several beams joined by multi-point constraints (the bearingless hub)
    scaling          rotor nondimensional units
    section_inertia  the flap inside its blade section: lumping rule and inertia checks
    blade            the configured blade: finite-element model, modes, fan plot
    hub_models       the two hub models side by side
"""

__all__: list[str] = []
