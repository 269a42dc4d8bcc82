"""Configuration: what a rotor with a trailing-edge flap is, typed, validated, with units.

The ground floor of the solver: it imports no physics.  A configuration is
data (declared fields with units, ranges and sources) and the checks that
need only the fields; checks that need the assembled blade run where the
blade is built (:mod:`tefcore.structure.blade`).

Its modules, bottom up::

    settings       declarative settings: typed, unit-aware fields declared once as data
    sections       the sections rotor, blade, hub, flap, actuator, flight, model
    hub            the sections of the bearingless hub's multiple load paths
    configuration  the whole configuration: sections, relations, overrides
    text_input     values given as text (command line, TOML) and the units rule
    io             TOML reading and writing, packaged configurations, the settings table

Its public names (each loaded from its module on first use):

The configuration
    :class:`~tefcore.config.configuration.Config`
Reading and writing
    :func:`~tefcore.config.io.load_config`, :func:`~tefcore.config.io.save_config`,
    :func:`~tefcore.config.io.loads_config`, :func:`~tefcore.config.io.dumps_config`,
    :func:`~tefcore.config.io.available_configs`, :func:`~tefcore.config.io.settings_table`
Overrides given as text
    :func:`~tefcore.config.text_input.parse_overrides`
Sections
    :class:`~tefcore.config.sections.RotorConfig`, :class:`~tefcore.config.sections.BladeConfig`,
    :class:`~tefcore.config.sections.HubConfig`, :class:`~tefcore.config.sections.FlapConfig`,
    :class:`~tefcore.config.sections.ActuatorConfig`,
    :class:`~tefcore.config.sections.FlightConfig`, :class:`~tefcore.config.sections.ModelConfig`
Sections of the multiple-load-path hub
    :class:`~tefcore.config.hub.FlexbeamConfig`, :class:`~tefcore.config.hub.TorqueTubeConfig`,
    :class:`~tefcore.config.hub.PitchLinkConfig`, :class:`~tefcore.config.hub.SnubberConfig`

Examples
--------
>>> from tefcore import config
>>> cfg = config.load_config("mdart")
>>> isinstance(cfg.flap, config.FlapConfig), cfg.flap.overhang
(True, 0.29)
>>> config.loads_config(config.dumps_config(cfg)) == cfg
True
"""

import sys

from ..faces import lazy_face

#: Public name -> the module that defines it (loaded on first use).
API = {
    "Config": "tefcore.config.configuration",
    "load_config": "tefcore.config.io",
    "save_config": "tefcore.config.io",
    "loads_config": "tefcore.config.io",
    "dumps_config": "tefcore.config.io",
    "available_configs": "tefcore.config.io",
    "settings_table": "tefcore.config.io",
    "parse_overrides": "tefcore.config.text_input",
    "RotorConfig": "tefcore.config.sections",
    "BladeConfig": "tefcore.config.sections",
    "HubConfig": "tefcore.config.sections",
    "FlapConfig": "tefcore.config.sections",
    "ActuatorConfig": "tefcore.config.sections",
    "FlightConfig": "tefcore.config.sections",
    "ModelConfig": "tefcore.config.sections",
    "FlexbeamConfig": "tefcore.config.hub",
    "TorqueTubeConfig": "tefcore.config.hub",
    "PitchLinkConfig": "tefcore.config.hub",
    "SnubberConfig": "tefcore.config.hub",
}

__all__ = list(API)
__getattr__, __dir__ = lazy_face(sys.modules[__name__], API)
