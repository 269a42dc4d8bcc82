"""Validated, immutable configuration of a trailing-edge-flap rotor.

A :class:`Config` bundles the sections ``rotor``, ``blade``, ``hub``,
``flap``, ``actuator``, ``flight`` and ``model``, and the multiple-load-path
hub's ``flexbeam``, ``torque_tube``, ``pitch_link`` and ``snubber``
(:mod:`tefcore.config.hub`).  Each section declares its
settings once, as a table of :class:`~tefcore.config.settings.Param` rows (name,
dimension, default, allowed range, description); the dataclass fields,
validation, TOML I/O (:mod:`tefcore.config.io`) and the documentation below
all derive from those tables through the generic machinery of
:mod:`tefcore.config.settings`.  All values are stored in SI units (angles in rad);
strings such as ``"800 lb/in"`` are converted with :mod:`tefcore.units`
using the field's dimension.

A range such as ``"(0, radius/2]"`` may reference sibling fields (``radius``)
or fields of other sections (``rotor.chord``); the latter are checked when
the sections are assembled into a :class:`Config`.

The module is longer than ~400 lines because it is mostly the declarative
field tables of the seven sections, which belong next to their physics.

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart")
>>> cfg.get("flap.overhang")
0.29
>>> stiff = cfg.with_overrides({"hub.pitch_link_stiffness": "800 lb/in"})
>>> round(stiff.hub.pitch_link_stiffness, 2)
140101.47
>>> cfg.with_overrides({"flap.overhang": 1.2})
Traceback (most recent call last):
...
ValueError: flap.overhang = 1.2 is outside the allowed range [0, 1)
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from .hub import (
    FlexbeamConfig,
    PitchLinkConfig,
    SnubberConfig,
    TorqueTubeConfig,
    check_hub_relations,
)
from .settings import (
    REQUIRED,
    Param,
    Section,
    coerce_value,
    did_you_mean,
    format_value,
    rebuild_section,
    settings_section,
)

__all__ = [
    "BLADE_PROPERTIES",
    "MACH_MAX",
    "REFERENCE_PARAMS",
    "REQUIRED",
    "SECTIONS",
    "ActuatorConfig",
    "BladeConfig",
    "Config",
    "FlapConfig",
    "FlexbeamConfig",
    "FlightConfig",
    "HubConfig",
    "ModelConfig",
    "Param",
    "PitchLinkConfig",
    "RotorConfig",
    "SnubberConfig",
    "TorqueTubeConfig",
    "coerce_value",
    "resolve_field",
]

#: Largest Mach number of the thin-airfoil aerodynamics
#: (:mod:`tefcore.aero.thin_airfoil` refuses a section beyond it; the advancing
#: tip is checked against it here, :meth:`Config.__post_init__`).
MACH_MAX = 0.99


# Tolerance for geometric equalities built from decimal fractions of R
# (e.g. 0.83 + 0.18/2 == 0.92 only to rounding).
_GEOM_TOL = 1e-12


@settings_section("rotor")
class RotorConfig(Section):
    """Rotor geometry, rotor speed, airfoil aerodynamics and atmosphere.

    Parameters
    ----------
    {params}

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> rotor = load_config("mdart").rotor
    >>> round(rotor.solidity, 4)
    0.078
    """

    PARAMS = (
        Param("n_blades", "dimensionless", REQUIRED, "[1, 12]", "Number of blades.", "int"),
        Param("radius", "length", REQUIRED, "(0, 100]", "Rotor radius R."),
        Param("rotor_speed", "angular_velocity", REQUIRED, "(0, 200]", "Rotor speed Omega."),
        Param("chord", "length", REQUIRED, "(0, radius/2]", "Blade chord c."),
        Param("root_offset", "dimensionless", REQUIRED, "[0, 0.5)",
              "Structural root / R, where the equivalent bearingless-hub root springs attach."),
        Param("root_cutout", "dimensionless", REQUIRED, "[root_offset, 0.5)",
              "Start of the aerodynamic span / R."),
        Param("precone", "angle", 0.0, "[-0.2, 0.2]", "Precone angle."),
        Param("lift_slope", "per_angle", 2 * math.pi, "(0, 8]", "Section lift-curve slope a."),
        Param("cd0", "dimensionless", 0.01, "[0, 0.1]", "Drag polar Cd = cd0 + cd1 a + cd2 a^2."),
        Param("cd1", "dimensionless", 0.0, "[-1, 1]", "Linear drag-polar coefficient."),
        Param("cd2", "dimensionless", 0.0, "[0, 10]", "Quadratic drag-polar coefficient."),
        Param("cm0", "dimensionless", 0.0, "[-0.2, 0.2]", "Section pitching moment about c/4."),
        Param("air_density", "density", 1.225, "(0, 2]", "Air density rho."),
        Param("speed_of_sound", "velocity", 340.294, "[200, 400]", "Speed of sound."),
        Param("elastic_axis", "dimensionless", 0.25, "[0, 1]",
              "Elastic axis aft of the leading edge / c."),
    )  # fmt: skip

    @property
    def solidity(self) -> float:
        """Rotor solidity N c / (pi R)."""
        return self.n_blades * self.chord / (math.pi * self.radius)

    @property
    def tip_speed(self) -> float:
        """Tip speed Omega R [m/s]."""
        return self.rotor_speed * self.radius


#: Spanwise property arrays of the blade, in the order of BladeConfig.section.
BLADE_PROPERTIES = (
    "mass", "ei_flap", "ei_lag", "gj", "ea", "im_flap", "im_lag",
    "cg_offset", "tension_offset", "ka", "twist",
)  # fmt: skip
#: 3-point Gauss-Legendre rule (numpy recomputes it on every call).
_GAUSS3 = np.polynomial.legendre.leggauss(3)

_SCALES = {"mass": "mass_scale", "im_flap": "mass_scale", "im_lag": "mass_scale",
           "ei_flap": "ei_flap_scale", "ei_lag": "ei_lag_scale", "gj": "gj_scale",
           "ea": "ea_scale"}  # fmt: skip


@settings_section("blade")
class BladeConfig(Section):
    """Spanwise blade section properties, piecewise linear between stations.

    Property arrays have one value per station; a scalar is broadcast.
    Chordwise offsets are positive toward the leading edge.

    Parameters
    ----------
    {params}

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> blade = load_config("mdart").blade
    >>> sorted(blade.section([0.5, 1.0])) == sorted(BLADE_PROPERTIES)
    True
    """

    PARAMS = (
        Param("stations", "dimensionless", REQUIRED, "[0, 1]",
              "Radial stations / R, strictly increasing from rotor.root_offset to 1.", "array"),
        Param("mass", "mass_per_length", REQUIRED, "(0, inf)", "Mass per length.", "array"),
        Param("ei_flap", "bending_stiffness", REQUIRED, "(0, inf)",
              "Flapwise (out-of-plane) bending stiffness.", "array"),
        Param("ei_lag", "bending_stiffness", REQUIRED, "(0, inf)",
              "Chordwise (in-plane) bending stiffness.", "array"),
        Param("gj", "torsional_stiffness", REQUIRED, "(0, inf)", "Torsional stiffness.", "array"),
        Param("ea", "force", REQUIRED, "(0, inf)", "Axial stiffness.", "array"),
        Param("im_flap", "inertia_per_length", 0.0, "[0, inf)",
              "Mass moment of inertia about the chord line, int rho zeta^2 dA.", "array"),
        Param("im_lag", "inertia_per_length", 0.0, "[0, inf)",
              "Mass moment of inertia about the flapwise axis, int rho eta^2 dA.", "array"),
        Param("cg_offset", "length", 0.0, "(-rotor.chord, rotor.chord)",
              "Section CG ahead of the elastic axis.", "array"),
        Param("tension_offset", "length", 0.0, "(-rotor.chord, rotor.chord)",
              "Tension axis ahead of the elastic axis.", "array"),
        Param("ka", "length", 0.0, "[0, inf)",
              "Polar radius of gyration of the tension-carrying area.", "array"),
        Param("twist", "angle", 0.0, "(-0.7, 0.7)", "Built-in pretwist.", "array"),
        Param("mass_scale", "dimensionless", 1.0, "(0, 100]",
              "Factor on mass, im_flap and im_lag."),
        Param("ei_flap_scale", "dimensionless", 1.0, "(0, 100]", "Factor on ei_flap."),
        Param("ei_lag_scale", "dimensionless", 1.0, "(0, 100]", "Factor on ei_lag."),
        Param("gj_scale", "dimensionless", 1.0, "(0, 100]", "Factor on gj."),
        Param("ea_scale", "dimensionless", 1.0, "(0, 100]", "Factor on ea."),
    )  # fmt: skip

    def _normalize(self) -> None:
        # Stations first: the other arrays are checked against them.
        s = self.stations
        if s.ndim != 1 or s.size < 2:
            raise ValueError(f"blade.stations needs at least 2 stations, got {s.size}")
        step = np.flatnonzero(np.diff(s) <= 0)
        if step.size:
            i = int(step[0]) + 1
            raise ValueError(
                f"blade.stations[{i}] = {format_value(s[i])} is not greater than "
                f"blade.stations[{i - 1}] = {format_value(s[i - 1])}; stations must increase "
                "strictly"
            )
        if abs(s[-1] - 1.0) > _GEOM_TOL:
            raise ValueError(f"blade.stations[{s.size - 1}] = {format_value(s[-1])} must be 1.0 "
                             "(the tip)")
        for name in BLADE_PROPERTIES:
            arr = getattr(self, name)
            if arr.ndim == 0:
                arr = np.full(s.size, float(arr))
                arr.setflags(write=False)
                object.__setattr__(self, name, arr)
            elif arr.size != s.size:
                raise ValueError(
                    f"blade.{name} has {arr.size} values but blade.stations has {s.size}"
                )

    def section(self, x) -> dict[str, np.ndarray]:
        """Scaled section properties at radial positions `x`.

        Parameters
        ----------
        x : array_like
            Radial positions / R within ``[stations[0], 1]``.

        Returns
        -------
        dict of str to numpy.ndarray
            Keys are :data:`BLADE_PROPERTIES`; values are linearly
            interpolated, with the scale factors applied.

        Raises
        ------
        ValueError
            If any `x` lies outside the blade.
        """
        x = np.asarray(x, dtype=float)
        lo = self.stations[0]
        if x.size and (np.nanmin(x) < lo - _GEOM_TOL or np.nanmax(x) > 1.0 + _GEOM_TOL
                       or np.isnan(x).any()):  # fmt: skip
            raise ValueError(f"section positions must lie within [{format_value(lo)}, 1.0]")
        out = {}
        for name in BLADE_PROPERTIES:
            values = np.interp(x, self.stations, getattr(self, name))
            scale = _SCALES.get(name)
            out[name] = values * getattr(self, scale) if scale else values
        return out

    def reference_mass(self) -> float:
        """Rotor mass unit m0 = 3 I_b / R^3 = 3 int m x^2 dx [kg/m], x = r/R.

        Independent of R because I_b = R^3 int m x^2 dx (r measured from the
        rotation axis, from the structural root to the tip); mass_scale is
        applied.

        Returns
        -------
        float

        Examples
        --------
        >>> blade = BladeConfig(stations=[0.0, 1.0], mass=2.0, ei_flap=1.0,
        ...                     ei_lag=1.0, gj=1.0, ea=1.0)
        >>> blade.reference_mass()  # uniform blade from the axis: m0 = m
        2.0
        """
        xs = np.asarray(self.stations, float)
        m = np.broadcast_to(np.asarray(self.mass, float) * self.mass_scale, xs.shape)
        # m x^2 is cubic on each linear segment: 3-point Gauss is exact there
        # (all segments at once)
        g, w = _GAUSS3
        a, b = xs[:-1, None], xs[1:, None]
        t = 0.5 * (g + 1.0)
        x = a + (b - a) * t
        mx = m[:-1, None] + (m[1:, None] - m[:-1, None]) * t
        return 3.0 * math.fsum((0.5 * w * (b - a) * mx * x**2).ravel())

    def flapping_inertia(self, radius: float) -> float:
        """Blade flapping inertia I_b = int m r^2 dr = m0 R^3 / 3 [kg m^2].

        Parameters
        ----------
        radius : float
            Rotor radius R [m].
        """
        return self.reference_mass() * radius**3 / 3.0


@settings_section("hub")
class HubConfig(Section):
    """Bearingless hub: which model, control linkage and equivalent root springs/damper.

    ``model = "equivalent"`` (docs/theory.md section 2.5) uses the root springs,
    the lag damper and the pitch link on the horn arm here;
    ``"multiple_load_path"`` (section 2.5a) uses the pitch-link stiffness here
    and the sections ``flexbeam``, ``torque_tube``, ``pitch_link`` and
    ``snubber`` instead of the springs, damper and horn arm.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("model", "dimensionless", "equivalent", "",
              "Hub model: 'equivalent' (root springs) or 'multiple_load_path' (flexbeam, "
              "torque tube, pitch link, snubber).", "str",
              choices=("equivalent", "multiple_load_path")),
        Param("pitch_link_stiffness", "force_per_length", REQUIRED, "(0, inf)",
              "Pitch-link axial stiffness."),
        Param("pitch_horn_arm", "length", REQUIRED, "(0, inf)",
              "Pitch-horn arm of the equivalent hub."),
        Param("flap_spring", "moment_per_angle", REQUIRED, "[0, inf)",
              "Equivalent flexbeam flap root spring."),
        Param("lag_spring", "moment_per_angle", REQUIRED, "[0, inf)",
              "Equivalent flexbeam lag root spring."),
        Param("lag_damper", "moment_damping", 0.0, "[0, inf)",
              "Equivalent elastomeric lag damper/snubber (rotational)."),
        Param("torsion_spring_parallel", "moment_per_angle", 0.0, "[0, inf)",
              "Flexbeam torsion spring in parallel with the pitch-link path."),
    )  # fmt: skip

    @property
    def pitch_link_torsion_stiffness(self) -> float:
        """Pitch-link stiffness seen in pitch, k_pl h^2 [N m/rad]."""
        return self.pitch_link_stiffness * self.pitch_horn_arm**2


@settings_section("flap")
class FlapConfig(Section):
    """Trailing-edge flap geometry and inertia (paper notation c_f, c_b, c_cg).

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("midspan", "dimensionless", REQUIRED, "(0, 1)", "Flap midspan station / R."),
        Param("span", "dimensionless", REQUIRED, "(0, 1)", "Flap span / R."),
        Param("chord_ratio", "dimensionless", REQUIRED, "(0, 1)", "Flap chord c_f / c."),
        Param("overhang", "dimensionless", REQUIRED, "[0, 1)",
              "Hinge aft of the flap leading edge, c_b / c_f."),
        Param("cg_offset", "dimensionless", 0.0, "[-1, 1]",
              "Flap CG aft of the hinge, c_cg / c_f."),
        Param("mass", "mass_per_length", REQUIRED, "[0, inf)",
              "Flap mass per span, of the flap of chord ratio reference_chord_ratio "
              "(rescaled with the chord by scaling)."),
        Param("inertia_cg", "inertia_per_length", REQUIRED, "[0, inf)",
              "Flap mass moment of inertia per span about its own CG, of the flap of chord "
              "ratio reference_chord_ratio (rescaled with the chord by scaling)."),
        Param("reference_chord_ratio", "dimensionless", None, "(0, 1)",
              "Chord ratio c_f/c at which mass and inertia_cg are given (None: at any "
              "chord_ratio, i.e. never rescaled).", optional=True),
        Param("scaling", "dimensionless", "construction", "",
              "How mass and inertia_cg per span follow the flap chord: 'construction' (same "
              "construction: mass ~ c_f, inertia ~ c_f^3 per span; per-span values do not "
              "change with the span) or 'fixed' (per-span values kept).", "str",
              choices=("construction", "fixed")),
    )  # fmt: skip

    @property
    def chord_scale(self) -> float:
        """c_f / c_f,ref: the flap chord over the chord its mass and inertia are given for."""
        ref = self.reference_chord_ratio
        if ref is None or self.scaling == "fixed":
            return 1.0
        return self.chord_ratio / ref

    @property
    def mass_per_span(self) -> float:
        """Flap mass per span [kg/m] at the configured chord (the scaling rule applied).

        Same construction (skins, core, nose spar and balance weight scaled with the flap
        chord at a fixed section thickness): the mass per span grows as ``c_f``.
        """
        return self.mass * self.chord_scale

    @property
    def inertia_cg_per_span(self) -> float:
        """Flap inertia per span about its CG [kg m] at the configured chord.

        Same construction: mass ~ ``c_f`` and every chordwise distance ~ ``c_f``, so
        the inertia per span grows as ``c_f^3``.
        """
        return self.inertia_cg * self.chord_scale**3

    @property
    def hinge_position(self) -> float:
        """Hinge aft of the blade leading edge / c: ``1 - c_f/c + (c_b/c_f)(c_f/c)``."""
        return 1.0 - self.chord_ratio + self.overhang * self.chord_ratio

    @property
    def inboard(self) -> float:
        """Inboard edge / R."""
        return self.midspan - self.span / 2

    @property
    def outboard(self) -> float:
        """Outboard edge / R."""
        return self.midspan + self.span / 2

    def inertia_hinge(self, chord: float) -> float:
        """Inertia per span about the hinge [kg m] for blade chord `chord` [m]."""
        return (self.inertia_cg_per_span
                + self.mass_per_span * (self.cg_offset * self.chord_ratio * chord) ** 2)


@settings_section("actuator")
class ActuatorConfig(Section):
    """Flap actuator: torsional spring k_a and damper c_a in series with the flap.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("stiffness", "moment_per_angle", REQUIRED, "(0, inf)", "Actuator stiffness k_a."),
        Param("damping", "moment_damping", 0.0, "[0, inf)", "Actuator damping c_a."),
    )


@settings_section("flight")
class FlightConfig(Section):
    """Flight condition, trim target and prescribed actuator input.

    The shaft angle is positive for forward tilt (nose down, as in level
    flight).  The actuator input is delta_a = A cos(n psi - phase).

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("advance_ratio", "dimensionless", 0.0, "[0, 0.6]", "Advance ratio mu."),
        Param("shaft_angle", "angle", 0.0, "[-0.6, 0.6]", "Shaft tilt, positive forward."),
        Param("ct_sigma", "dimensionless", 0.075, "[0, 0.2]", "Trim thrust target C_T/sigma."),
        Param("collective", "angle", None, "[-0.2, 0.5]",
              "Prescribed collective (hover), used instead of ct_sigma when given.",
              optional=True),
        Param("actuator_amplitude", "angle", 0.0, "[0, 0.35]", "Actuator amplitude A."),
        Param("actuator_harmonic", "dimensionless", 0, "[0, 10]",
              "Actuator harmonic n (per rev).", "int"),
        Param("actuator_phase", "angle", 0.0, "[-2*pi, 2*pi]", "Actuator phase."),
    )  # fmt: skip


@settings_section("model")
class ModelConfig(Section):
    """Discretisation and aerodynamic model choices.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("n_elements", "dimensionless", 20, "[2, 200]", "Beam finite elements.", "int"),
        Param("n_modes", "dimensionless", 9, "[1, 60]", "Coupled modes retained.", "int"),
        Param("aero_model", "dimensionless", "thin_airfoil", "", "Section aerodynamics.", "str",
              choices=("thin_airfoil", "c81")),
        Param("c81_deck", "dimensionless", "", "", "C81 table file (aero_model = 'c81'); "
              "in a TOML file a relative path is relative to that file.", "str", path=True),
        Param("tef", "dimensionless", "dynamic", "",
              "Trailing-edge flap: 'dynamic' (flap dof with actuator) or 'none' (no flap, "
              "plain airfoil: the paper's baseline rotor).", "str", choices=("dynamic", "none")),
        Param("inflow", "dimensionless", "linear", "",
              "Inflow: 'linear' (uniform momentum in hover, Drees in forward flight), "
              "'uniform', or 'dynamic' (Pitt-Peters: steady part in the trim, three "
              "perturbation states in the stability analysis).", "str",
              choices=("linear", "uniform", "dynamic")),
        Param("aero", "dimensionless", "quasi_steady", "",
              "Unsteadiness of the section airloads (with either aero_model): "
              "'quasi_steady' (Theodorsen with C(k) = 1) or 'unsteady' (finite-state shed "
              "wake, model.wake_states states per aerodynamic station).", "str",
              choices=("quasi_steady", "unsteady")),
        Param("wake", "dimensionless", "fitted", "",
              "Shed-wake model of model.aero = 'unsteady': 'fitted' (real poles fitted to "
              "Theodorsen's C(k)) or 'peters' (Peters' published constants).", "str",
              choices=("fitted", "peters")),
        Param("wake_states", "dimensionless", 4, "[1, 10]",
              "Shed-wake states per aerodynamic station (model.aero = 'unsteady').", "int"),
        Param("n_azimuth", "dimensionless", 24, "[8, 240]",
              "Azimuth collocation points of the harmonic-balance trim.", "int"),
        Param("n_floquet_steps", "dimensionless", 72, "[8, 5000]",
              "Magnus (4th order) steps per revolution of the Floquet transition matrices.", "int"),
        Param("n_gauss", "dimensionless", 6, "[2, 40]",
              "Gauss points per aerodynamic span segment (inboard, flap, outboard).", "int"),
    )  # fmt: skip

    def _validate(self) -> None:
        if self.aero_model == "c81" and not self.c81_deck:
            raise ValueError("model.c81_deck must name a deck when model.aero_model = 'c81'")
        if self.aero_model == "c81" and not os.path.isfile(self.c81_deck):
            raise ValueError(f"model.c81_deck = {self.c81_deck!r}: no such file (in a TOML "
                             "file a relative path is relative to that file; in Python and "
                             "with --set, to the working directory)")


#: Section name -> section class, in file order.
SECTIONS: dict[str, type[Section]] = {
    cls.SECTION: cls
    for cls in (RotorConfig, BladeConfig, HubConfig, FlexbeamConfig, TorqueTubeConfig,
                PitchLinkConfig, SnubberConfig, FlapConfig, ActuatorConfig, FlightConfig,
                ModelConfig)
}  # fmt: skip
_TOP_LEVEL = ("name", "description")

#: Stated values in [reference]: checks against derived quantities, not inputs.
REFERENCE_PARAMS: dict[str, Param] = {
    p.name: p
    for p in (
        Param("lock_number", "dimensionless", None, "(0, inf)", "Lock number.", optional=True),
        Param("solidity", "dimensionless", None, "(0, 1)", "Rotor solidity.", optional=True),
        Param("tip_speed", "velocity", None, "(0, inf)", "Tip speed.", optional=True),
    )
}


def resolve_field(key: str) -> tuple[str | None, str]:
    """Split a dotted field name into (section, field), checking both exist.

    Returns ``(None, name)`` for the top-level ``name``/``description``.

    Parameters
    ----------
    key : str
        A dotted field name.

    Returns
    -------
    section : str or None
    field : str

    Raises
    ------
    ValueError
        Unknown section or field, with close matches.

    Examples
    --------
    >>> resolve_field("flap.overhang")
    ('flap', 'overhang')
    >>> resolve_field("flap.overhng")
    Traceback (most recent call last):
    ...
    ValueError: unknown field 'flap.overhng'; did you mean 'flap.overhang'?
    """
    if not isinstance(key, str):
        raise ValueError(f"field names must be strings, got {key!r}")
    section, dot, name = key.partition(".")
    if not dot and key in _TOP_LEVEL:
        return None, key
    cls = SECTIONS.get(section)
    if cls is None or not dot or name not in {p.name for p in cls.PARAMS}:
        every = [f"{s}.{p.name}" for s, c in SECTIONS.items() for p in c.PARAMS]
        raise ValueError(f"unknown field {key!r}{did_you_mean(key, [*every, *_TOP_LEVEL])}")
    return section, name


@dataclass(frozen=True, eq=False, kw_only=True)
class Config:
    """Complete, validated rotor configuration (SI units).

    Sections may be given as section objects or as mappings of their fields.
    `sources` (dotted name -> provenance) and `reference` (stated values,
    see :data:`REFERENCE_PARAMS`) are carried along but are not part of
    equality.

    Parameters
    ----------
    rotor : RotorConfig or mapping
        Rotor geometry, aerodynamics and operating condition.
    blade : BladeConfig or mapping
        Blade property tables.
    hub : HubConfig or mapping
        Hub springs and control linkage.
    flap : FlapConfig or mapping
        Flap geometry and inertia.
    actuator : ActuatorConfig or mapping
        Flap actuator.
    flight : FlightConfig or mapping, optional
        Flight condition and trim targets.
    model : ModelConfig or mapping, optional
        Modelling choices (discretisation, aerodynamic model, flap model).
    flexbeam, torque_tube, pitch_link, snubber : mapping or section, optional
        The multiple-load-path hub (:mod:`tefcore.config.hub`; used when
        ``hub.model = "multiple_load_path"``).
    name : str, optional
        Name of the configuration.
    description : str, optional
        Free text.
    sources : mapping of str to str, optional
        Dotted field -> where its value comes from.
    reference : mapping of str to object, optional
        Stated reference values (:data:`REFERENCE_PARAMS`).

    Raises
    ------
    ValueError
        If any field, or any relation between fields, is invalid; the
        message names the dotted field(s).

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> round(cfg.lock_number, 2)
    9.17
    >>> cfg.with_overrides({"flap.midspan": 0.95})
    Traceback (most recent call last):
    ...
    ValueError: flap.midspan + flap.span/2 = 1.04 lies beyond the blade tip (1)
    """

    rotor: RotorConfig
    blade: BladeConfig
    hub: HubConfig
    flap: FlapConfig
    actuator: ActuatorConfig
    flexbeam: FlexbeamConfig = field(default_factory=FlexbeamConfig)
    torque_tube: TorqueTubeConfig = field(default_factory=TorqueTubeConfig)
    pitch_link: PitchLinkConfig = field(default_factory=PitchLinkConfig)
    snubber: SnubberConfig = field(default_factory=SnubberConfig)
    flight: FlightConfig = field(default_factory=FlightConfig)
    model: ModelConfig = field(default_factory=ModelConfig)
    name: str = ""
    description: str = ""
    reference: Mapping[str, float] = field(default_factory=dict, repr=False)
    sources: Mapping[str, str] = field(default_factory=dict, repr=False)

    def __post_init__(self):
        for name, cls in SECTIONS.items():
            value = getattr(self, name)
            if isinstance(value, Mapping):
                unknown = sorted(set(value) - {p.name for p in cls.PARAMS})
                if unknown:
                    raise ValueError(f"unknown field(s) {', '.join(map(repr, unknown))} in {name}")
                object.__setattr__(self, name, value := cls(**value))
            if not isinstance(value, cls):
                raise ValueError(f"{name} must be a {cls.__name__}, got {type(value).__name__}")
        for name in _TOP_LEVEL:
            if not isinstance(getattr(self, name), str):
                raise ValueError(f"{name} must be a string, got {getattr(self, name)!r}")
        reference = {}
        for key, raw in self.reference.items():
            p = REFERENCE_PARAMS.get(key)
            if p is None:
                raise ValueError(f"unknown reference value "
                                 f"{key!r}{did_you_mean(key, REFERENCE_PARAMS)}")
            reference[key] = coerce_value(p, raw, f"reference.{key}")
            if msg := p.range_error(reference[key], f"reference.{key}", self._lookup):
                raise ValueError(msg)
        object.__setattr__(self, "reference", MappingProxyType(reference))
        object.__setattr__(self, "sources", MappingProxyType(dict(self.sources)))
        self._check_relations()

    def _lookup(self, key: str):
        section, name = resolve_field(key)
        return getattr(getattr(self, section), name) if section else getattr(self, name)

    def _check_relations(self) -> None:
        # Ranges that reference other sections (skipped by the sections).
        for sname in SECTIONS:
            getattr(self, sname).check_cross_refs(self._lookup)
        rotor, flap = self.rotor, self.flap
        s0 = self.blade.stations[0]
        if abs(s0 - rotor.root_offset) > _GEOM_TOL:
            raise ValueError(
                f"blade.stations[0] = {format_value(s0)} must equal rotor.root_offset = "
                f"{format_value(rotor.root_offset)} (the blade starts at the structural root)"
            )
        if flap.inboard < rotor.root_cutout - _GEOM_TOL:
            raise ValueError(
                f"flap.midspan - flap.span/2 = {flap.inboard:.6g} lies inboard of "
                f"rotor.root_cutout = {format_value(rotor.root_cutout)}"
            )
        if flap.outboard > 1.0 + _GEOM_TOL:
            raise ValueError(
                f"flap.midspan + flap.span/2 = {flap.outboard:.6g} lies beyond the blade tip (1)"
            )
        self._check_tip_mach()
        if 1.0 - flap.chord_ratio < rotor.elastic_axis - _GEOM_TOL:
            raise ValueError(
                f"flap.chord_ratio = {format_value(flap.chord_ratio)} does not fit behind the "
                f"elastic axis: flap leading edge at {1.0 - flap.chord_ratio:.6g} c is ahead of "
                f"rotor.elastic_axis = {format_value(rotor.elastic_axis)}"
            )
        # the multiple-load-path hub's parts, when selected (docs/theory.md 2.5a)
        check_hub_relations(self)
        # the flap inside its blade section (docs/theory.md section 2.7) is physics:
        # checked where the blade is assembled (tefcore.structure.blade.blade_model,
        # tefcore.model.coupled.coupled_model), naming the field as here

    def _check_tip_mach(self) -> None:
        """The advancing tip must stay within the thin-airfoil model's Mach range.

        The C81 tables clip the Mach number to the table (with a warning)
        instead.
        """
        if self.model.aero_model != "thin_airfoil":
            return
        rotor, mu = self.rotor, self.flight.advance_ratio
        tip = rotor.rotor_speed * rotor.radius / rotor.speed_of_sound
        if (1.0 + mu) * tip > MACH_MAX:
            raise ValueError(
                f"flight.advance_ratio = {format_value(mu)} puts the advancing blade tip at Mach "
                f"(1 + mu) M_tip = {(1.0 + mu) * tip:.4f} (tip Mach M_tip = Omega R / a "
                f"= {tip:.4f}), above {MACH_MAX}, the limit of the thin-airfoil aerodynamics; "
                f"with this rotor.rotor_speed, rotor.radius and rotor.speed_of_sound the "
                f"advance ratio must be at most "
                f"{math.floor(max(MACH_MAX / tip - 1.0, 0.0) * 1e4) / 1e4:.4f}")

    def __eq__(self, other):
        if not isinstance(other, Config):
            return NotImplemented
        return all(getattr(self, n) == getattr(other, n) for n in (*SECTIONS, *_TOP_LEVEL))

    __hash__ = None  # type: ignore[assignment]

    def __reduce__(self):
        # MappingProxyType cannot be pickled: hand plain dicts to the constructor.
        kwargs = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        kwargs.update(reference=dict(self.reference), sources=dict(self.sources))
        return rebuild_section, (Config, kwargs)

    def get(self, key: str):
        """Value of a dotted field, e.g. ``cfg.get("flap.cg_offset")`` (SI).

        Raises
        ------
        ValueError
            Unknown field (with close matches).
        """
        return self._lookup(key)

    def with_overrides(self, overrides: Mapping[str, Any]) -> Config:
        """Return a new validated Config with dotted fields replaced.

        Parameters
        ----------
        overrides : mapping
            Dotted name -> SI number, ``"value unit"`` string, sequence
            (blade arrays) or ``{value|values, unit, source}`` table.
            Overrides are applied together, then validated.

        Returns
        -------
        Config
            A new object; `self` is unchanged.  ``sources`` records each
            override.

        Raises
        ------
        ValueError
            Unknown field (with close matches) or invalid result.

        Examples
        --------
        >>> from tefcore.config.io import load_config
        >>> cfg = load_config("mdart")
        >>> cfg.with_overrides({"flap.cg_offset": 0.33}).flap.cg_offset, cfg.flap.cg_offset
        (0.33, 0.0)
        """
        per_section: dict[str, dict[str, Any]] = {}
        top: dict[str, Any] = {}
        sources = dict(self.sources)
        for key, value in overrides.items():
            section, name = resolve_field(key)
            (per_section.setdefault(section, {}) if section else top)[name] = value
            given = value.get("source") if isinstance(value, Mapping) else None
            sources[key] = given if isinstance(given, str) else f"override: {value!r}"
        new = {s: dataclasses.replace(getattr(self, s), **kw) for s, kw in per_section.items()}
        return dataclasses.replace(self, **new, **top, sources=sources)

    @property
    def flapping_inertia(self) -> float:
        """Blade flapping inertia I_b [kg m^2] about the rotation axis."""
        return self.blade.flapping_inertia(self.rotor.radius)

    @property
    def reference_mass(self) -> float:
        """Nondimensional mass unit m0 = 3 I_b / R^3 [kg/m]."""
        return self.blade.reference_mass()

    @property
    def lock_number(self) -> float:
        """Lock number gamma = rho a c R^4 / I_b."""
        r = self.rotor
        return r.air_density * r.lift_slope * r.chord * r.radius**4 / self.flapping_inertia

    def reference_checks(self) -> dict[str, tuple[float, float]]:
        """Stated reference values next to the values computed from the inputs.

        Returns
        -------
        dict of str to (stated, computed)
        """
        computed = {
            "lock_number": lambda: self.lock_number,
            "solidity": lambda: self.rotor.solidity,
            "tip_speed": lambda: self.rotor.tip_speed,
        }
        return {k: (v, computed[k]()) for k, v in self.reference.items()}

