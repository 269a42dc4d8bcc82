"""The configuration's sections: rotor, blade, hub, flap, actuator, flight, model.

Each section declares its fields once, as a table of
:class:`~tefcore.config.settings.Param` rows (name, dimension, default,
allowed range, source, description); the dataclass fields, validation, TOML
I/O (:mod:`tefcore.config.io`) and the settings documentation derive from
those tables (:mod:`tefcore.config.settings`).  The whole configuration and
its cross-section checks are :class:`tefcore.config.configuration.Config`.

Examples
--------
>>> from tefcore.config.io import load_config
>>> load_config("mdart").flap.overhang       # Table 1: 29 % of the flap chord
0.29
>>> [p.name for p in ActuatorConfig.PARAMS]
['stiffness', 'damping', 'reflected_inertia']
"""

from __future__ import annotations

import math
import os

import numpy as np

from .settings import (
    GEOMETRY_TOL,
    REQUIRED,
    Param,
    Section,
    format_value,
    settings_section,
)

__all__ = [
    "BLADE_PROPERTIES",
    "MACH_MAX",
    "MODE_FAMILIES",
    "ActuatorConfig",
    "BladeConfig",
    "FlapConfig",
    "FlightConfig",
    "HubConfig",
    "ModelConfig",
    "RotorConfig",
    "mode_family_counts",
]

#: Largest Mach number of the thin-airfoil aerodynamics
#: (:mod:`tefcore.aero.thin_airfoil` refuses a section beyond it; the advancing
#: tip is checked against it here, :meth:`Config.__post_init__`).
MACH_MAX = 0.99


# Tolerance for geometric equalities built from decimal fractions of R
# (e.g. 0.83 + 0.18/2 == 0.92 only to rounding).


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
        if abs(s[-1] - 1.0) > GEOMETRY_TOL:
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
        if x.size and (np.nanmin(x) < lo - GEOMETRY_TOL or np.nanmax(x) > 1.0 + GEOMETRY_TOL
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

    The actuator's moving parts on the flap side of the spring (its output, the
    linkage, the flap horn) turn with the flap: their inertia reflected to the
    hinge, ``reflected_inertia`` (``I_a``), adds to the flap's.  The upper bound
    of 1 kg m^2 (3400 lb in^2, several thousand times the MDART flap's own
    0.72 lb in^2) only refuses typing errors; what is plausible is argued in
    the configuration files.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("stiffness", "moment_per_angle", REQUIRED, "(0, inf)", "Actuator stiffness k_a."),
        Param("damping", "moment_damping", 0.0, "[0, inf)", "Actuator damping c_a."),
        Param("reflected_inertia", "inertia", 0.0, "[0, 1]",
              "I_a: mass moment of inertia of the actuator's moving parts (output, linkage, "
              "flap horn) reflected through the linkage to the flap hinge, of the whole flap "
              "(not per span); moving with the flap on the flap side of the actuator spring, "
              "it adds to the flap degree of freedom's own inertia b_f I_h (docs/theory.md "
              "4.1); its mass is part of blade.mass, so no mass is added."),
    )  # fmt: skip


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


#: The blade's mode families a basis can hold (the structure's labels).
MODE_FAMILIES = ("flap", "lag", "torsion", "axial")


def mode_family_counts(text: str) -> dict[str, int]:
    """The family counts of ``model.mode_families``: ``"flap 5, lag 2"`` -> ``{"flap": 5, ...}``.

    Parameters
    ----------
    text : str
        The field's value (``""``: no family held).

    Returns
    -------
    dict
        Family -> count, in the order written.

    Raises
    ------
    ValueError
        Naming the field, the part that is wrong and the form expected.

    Examples
    --------
    >>> mode_family_counts("flap 5, lag 2, torsion 2")
    {'flap': 5, 'lag': 2, 'torsion': 2}
    >>> mode_family_counts("")
    {}
    """
    counts: dict[str, int] = {}
    for part in (p.strip() for p in str(text).split(",") if p.strip()):
        words = part.split()
        if (len(words) != 2 or words[0] not in MODE_FAMILIES or not words[1].isdigit()
                or int(words[1]) < 1 or words[0] in counts):
            raise ValueError(f"model.mode_families = {text!r}: {part!r} is not '<family> <count>' "
                             f"with a family of {', '.join(MODE_FAMILIES)} (once each) and a "
                             "count from 1, e.g. 'flap 5, lag 2, torsion 2'")
        counts[words[0]] = int(words[1])
    return counts


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
        Param("mode_families", "dimensionless", "", "",
              "Blade modes of each family the basis holds at every point, e.g. 'flap 5, "
              "lag 2, torsion 2' (families: flap, lag, torsion, axial): the lowest modes of "
              "each family, then the lowest others up to n_modes; empty: the n_modes "
              "lowest at each point, whose families can change along a sweep.", "str"),
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
        counts = mode_family_counts(self.mode_families)
        if sum(counts.values()) > self.n_modes:
            raise ValueError(f"model.mode_families = {self.mode_families!r} holds "
                             f"{sum(counts.values())} modes, more than model.n_modes = "
                             f"{self.n_modes}; raise n_modes or hold fewer")
        if self.aero_model == "c81" and not self.c81_deck:
            raise ValueError("model.c81_deck must name a deck when model.aero_model = 'c81'")
        if self.aero_model == "c81" and not os.path.isfile(self.c81_deck):
            raise ValueError(f"model.c81_deck = {self.c81_deck!r}: no such file (in a TOML "
                             "file a relative path is relative to that file; in Python and "
                             "with --set, to the working directory)")


