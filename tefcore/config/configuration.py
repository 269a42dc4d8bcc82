"""Validated, immutable configuration of a trailing-edge-flap rotor: the whole of it.

A :class:`Config` bundles the sections ``rotor``, ``blade``, ``hub``,
``flap``, ``actuator``, ``flight`` and ``model`` (:mod:`tefcore.config.sections`)
and the multiple-load-path hub's ``flexbeam``, ``torque_tube``,
``pitch_link`` and ``snubber`` (:mod:`tefcore.config.hub`), checks the
relations between them, and reads and changes fields by their dotted names
(:func:`resolve_field`, :meth:`Config.with_overrides`).  Each section declares its
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
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from .hub import (
    FlexbeamConfig,
    PitchLinkConfig,
    SnubberConfig,
    TorqueTubeConfig,
    check_hub_relations,
)
from .sections import (
    MACH_MAX,
    ActuatorConfig,
    BladeConfig,
    FlapConfig,
    FlightConfig,
    HubConfig,
    ModelConfig,
    RotorConfig,
)
from .settings import (
    GEOMETRY_TOL,
    Param,
    Section,
    coerce_value,
    did_you_mean,
    format_value,
    rebuild_section,
)

__all__ = ["REFERENCE_PARAMS", "SECTIONS", "Config", "resolve_field"]


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
        if abs(s0 - rotor.root_offset) > GEOMETRY_TOL:
            raise ValueError(
                f"blade.stations[0] = {format_value(s0)} must equal rotor.root_offset = "
                f"{format_value(rotor.root_offset)} (the blade starts at the structural root)"
            )
        if flap.inboard < rotor.root_cutout - GEOMETRY_TOL:
            raise ValueError(
                f"flap.midspan - flap.span/2 = {flap.inboard:.6g} lies inboard of "
                f"rotor.root_cutout = {format_value(rotor.root_cutout)}"
            )
        if flap.outboard > 1.0 + GEOMETRY_TOL:
            raise ValueError(
                f"flap.midspan + flap.span/2 = {flap.outboard:.6g} lies beyond the blade tip (1)"
            )
        self._check_tip_mach()
        if 1.0 - flap.chord_ratio < rotor.elastic_axis - GEOMETRY_TOL:
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

