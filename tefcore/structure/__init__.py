"""Structure: the rotating finite-element blade, its hub and the flap inside its section.

The blade and hub in vacuum: 15-dof rotating beam elements, the equivalent
root springs or the multiple-load-path hub, the flap lumped into its blade
section, and the coupled blade modes (eta = 0 of the coupling: their
structural labels are where mode identity starts, :mod:`tefcore.modes`).

Its modules, bottom up::

    beam_element     the 15-dof rotating beam element
    fem              assembly, root springs, coupled modes and their structural labels
    branched         several beams joined by multi-point constraints (the bearingless hub)
    scaling          rotor nondimensional units
    section_inertia  the flap inside its blade section: lumping rule and inertia checks
    blade            the configured blade: finite-element model, modes, fan plot
    hub_models       the multiple-load-path hub's closed forms and pitch response

Its public names (each loaded from its module on first use):

Blade modes and fan plot
    :func:`~tefcore.structure.blade.blade_modes` (:class:`~tefcore.structure.fem.BladeModes`),
    :func:`~tefcore.structure.blade.fan_data`, :func:`~tefcore.structure.blade.fan_plot`
The finite-element blade
    :func:`~tefcore.structure.blade.blade_model`,
    :func:`~tefcore.structure.blade.multiple_load_path_model`,
    :func:`~tefcore.structure.blade.root_springs`, :func:`~tefcore.structure.blade.rotor_units`,
    :class:`~tefcore.structure.fem.BeamModel`, :class:`~tefcore.structure.fem.RootSprings`,
    :func:`~tefcore.structure.fem.assemble_beam`, :func:`~tefcore.structure.fem.beam_modes`,
    :class:`~tefcore.structure.scaling.RotorUnits`
The flap in its section
    :func:`~tefcore.structure.section_inertia.flap_share`,
    :func:`~tefcore.structure.section_inertia.lumped_section`,
    :func:`~tefcore.structure.section_inertia.flap_mass_limit`,
    :func:`~tefcore.structure.section_inertia.check_section_inertia`
The multiple-load-path hub
    :func:`~tefcore.structure.hub_models.kinematic_pitch_ratio`,
    :func:`~tefcore.structure.hub_models.pitch_flap_delta3`,
    :func:`~tefcore.structure.hub_models.pitch_input_response`

Examples
--------
>>> from tefcore import config, structure
>>> cfg = config.load_config("mdart")
>>> structure.blade_modes(cfg).labels[:3]
['lag 1', 'flap 1', 'flap 2']
>>> structure.flap_share(cfg.flap, cfg.rotor).mass == cfg.flap.mass_per_span
True
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "blade_modes": "tefcore.structure.blade",
    "fan_data": "tefcore.structure.blade",
    "fan_plot": "tefcore.structure.blade",
    "blade_model": "tefcore.structure.blade",
    "multiple_load_path_model": "tefcore.structure.blade",
    "root_springs": "tefcore.structure.blade",
    "rotor_units": "tefcore.structure.blade",
    "BladeModes": "tefcore.structure.fem",
    "BeamModel": "tefcore.structure.fem",
    "RootSprings": "tefcore.structure.fem",
    "assemble_beam": "tefcore.structure.fem",
    "beam_modes": "tefcore.structure.fem",
    "RotorUnits": "tefcore.structure.scaling",
    "flap_share": "tefcore.structure.section_inertia",
    "lumped_section": "tefcore.structure.section_inertia",
    "flap_mass_limit": "tefcore.structure.section_inertia",
    "check_section_inertia": "tefcore.structure.section_inertia",
    "kinematic_pitch_ratio": "tefcore.structure.hub_models",
    "pitch_flap_delta3": "tefcore.structure.hub_models",
    "pitch_input_response": "tefcore.structure.hub_models",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
