"""tefcore: aeroelastic stability of helicopter rotors with trailing-edge flaps.

An open replication of *Aeroelastic Stability of Trailing-Edge Flap
Helicopter Rotors*: a rotating finite-element blade with a trailing-edge flap
and its actuator, flap aerodynamics (quasi-steady, C81 tables, finite-state
unsteady), trim and Floquet stability.

The solver is the flat set of modules ``tefcore.*``; the replication of the
paper (figures, reference data and claims, validation, notebooks, the
reproduction runner and report) is the subpackage :mod:`tefcore.paper`,
built on the solver and never imported by it.

The names a rotor dynamicist uses are importable from ``tefcore`` itself
(loaded on first use, so ``import tefcore`` stays light and changes no
process setting; see :mod:`tefcore.runtime`):

Configuration
    :class:`~tefcore.config.configuration.Config`, :func:`~tefcore.config.io.load_config`,
    :func:`~tefcore.config.io.save_config`
Blade modes
    :func:`~tefcore.structure.blade.blade_modes`, :func:`~tefcore.structure.blade.fan_plot`
Trim and stability
    :func:`~tefcore.trimming.trim.trim`, :func:`~tefcore.linear.stability.stability`
    (:class:`~tefcore.linear.stability.StabilityResult`: ``.modes``, one row per
    Floquet mode), :func:`~tefcore.floquet.floquet_modes`
Sweeps and maps
    :func:`~tefcore.sweeps.sweep.sweep`, :func:`~tefcore.sweeps.boundary.stability_boundary`,
    :func:`~tefcore.sweeps.maps.stability_map`
Mechanism of an instability
    :func:`~tefcore.linear.mechanism.mechanism`
Time-domain response (the Floquet growth watched)
    :func:`~tefcore.timedomain.simulate.simulate`
Mode tracking
    :func:`~tefcore.modes.tracking.track_modes`,
    :func:`~tefcore.modes.matching.match_modes`, :func:`~tefcore.modes.matching.mac`
C81 airfoil decks
    :func:`~tefcore.aero.c81.read_c81`, :func:`~tefcore.aero.c81.write_c81`,
    :class:`~tefcore.aero.c81.C81FlapTable`
Units
    :func:`~tefcore.units.to_si`, :func:`~tefcore.units.from_si`
Process settings
    :func:`~tefcore.runtime.apply_defaults`
Errors
    :class:`~tefcore.errors.TefcoreError`

Examples
--------
>>> import tefcore
>>> cfg = tefcore.load_config("mdart")
>>> cfg.flap.overhang
0.29
"""

import importlib

from ._version import __version__

#: Public name -> the module that defines it (loaded on first use, PEP 562).
API = {
    "Config": "tefcore.config.configuration",
    "load_config": "tefcore.config.io",
    "save_config": "tefcore.config.io",
    "blade_modes": "tefcore.structure.blade",
    "fan_plot": "tefcore.structure.blade",
    "trim": "tefcore.trimming.trim",
    "stability": "tefcore.linear.stability",
    "StabilityResult": "tefcore.linear.stability",
    "floquet_modes": "tefcore.floquet",
    "sweep": "tefcore.sweeps.sweep",
    "stability_boundary": "tefcore.sweeps.boundary",
    "stability_map": "tefcore.sweeps.maps",
    "mechanism": "tefcore.linear.mechanism",
    "simulate": "tefcore.timedomain.simulate",
    "track_modes": "tefcore.modes.tracking",
    "match_modes": "tefcore.modes.matching",
    "mac": "tefcore.modes.matching",
    "read_c81": "tefcore.aero.c81",
    "write_c81": "tefcore.aero.c81",
    "C81FlapTable": "tefcore.aero.c81",
    "to_si": "tefcore.units",
    "from_si": "tefcore.units",
    "apply_defaults": "tefcore.runtime",
    "TefcoreError": "tefcore.errors",
}

__all__ = ["__version__", *API]


def __getattr__(name: str):
    if name in API:
        value = getattr(importlib.import_module(API[name]), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(API))
