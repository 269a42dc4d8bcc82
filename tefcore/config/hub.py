"""Configuration sections of the bearingless hub's multiple load paths.

``hub.model = "multiple_load_path"`` (:mod:`tefcore.structure.hub_models`) replaces the
equivalent root springs of docs/theory.md section 2.5 by the parts of the
bearingless hub (docs/theory.md section 2.5a):

* ``[flexbeam]``: the flap/lag/torsion flexure clamped to the hub at
  ``rotor.root_offset`` and bolted to the blade at the clevis;
* ``[torque_tube]``: the pitchcase around the flexbeam, joined to flexbeam
  and blade at the clevis, carrying the pitch input from its horn;
* ``[pitch_link]``: the geometry of the pitch horn and link (its stiffness is
  ``hub.pitch_link_stiffness``, swept in Fig. 10);
* ``[snubber]``: the elastomeric snubber/damper between the torque tube's
  inboard end and the flexbeam, by its complex stiffness.

Every field is optional here (an equivalent-hub configuration needs none of
them); :func:`check_hub_relations` requires them all when
``hub.model = "multiple_load_path"``.  Section properties are uniform along
flexbeam and torque tube.

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart")
>>> cfg.hub.model
'equivalent'
>>> cfg.with_overrides({"hub.model": "multiple_load_path",
...                     "torque_tube.inboard": 0.3})  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: torque_tube.inboard = 0.3 must lie in [rotor.root_offset, flexbeam.clevis) = ...
"""

from __future__ import annotations

from .settings import GEOMETRY_TOL, Param, Section, format_value, settings_section

__all__ = ["HUB_SECTIONS", "FlexbeamConfig", "PitchLinkConfig", "SnubberConfig",
           "TorqueTubeConfig", "check_hub_relations"]



def _beam_params(what: str) -> tuple[Param, ...]:
    """Uniform section properties of a hub beam (optional: needed only by the MLP hub)."""
    return (
        Param("mass", "mass_per_length", None, "(0, 1000]", f"Mass per length of the {what}.",
              optional=True),
        Param("ei_flap", "bending_stiffness", None, "(0, 1e12]",
              f"Flapwise bending stiffness of the {what}.", optional=True),
        Param("ei_lag", "bending_stiffness", None, "(0, 1e12]",
              f"Chordwise bending stiffness of the {what}.", optional=True),
        Param("gj", "torsional_stiffness", None, "(0, 1e12]",
              f"Torsional stiffness of the {what}.", optional=True),
        Param("ea", "force", None, "(0, 1e12]", f"Axial stiffness of the {what}.",
              optional=True),
        Param("im_flap", "inertia_per_length", None, "[0, 100]",
              f"Mass moment of inertia of the {what} about its chord line, int zeta^2 dm.",
              optional=True),
        Param("im_lag", "inertia_per_length", None, "[0, 100]",
              f"Mass moment of inertia of the {what} about its flapwise axis, int eta^2 dm.",
              optional=True),
    )  # fmt: skip


@settings_section("flexbeam")
class FlexbeamConfig(Section):
    """Flexbeam: flap/lag/torsion flexure from the hub clamp to the clevis.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("clevis", "dimensionless", None, "(0, 1)",
              "Clevis station / R, in (rotor.root_offset, rotor.root_cutout], where flexbeam, "
              "torque tube and main blade are joined.", optional=True),
        Param("n_elements", "dimensionless", 4, "[1, 40]", "Flexbeam finite elements.", "int"),
        *_beam_params("flexbeam"),
        Param("ka", "length", None, "[0, 1]",
              "Polar radius of gyration of the flexbeam's tension-carrying area "
              "(tension-torsion stiffening).", optional=True),
        Param("precollective", "angle", 0.0, "[-0.7, 0.7]",
              "Unstrained pitch of the flexbeam at the hub; the flexbeam twists elastically "
              "from it to the blade pitch at the clevis."),
    )  # fmt: skip


@settings_section("torque_tube")
class TorqueTubeConfig(Section):
    """Torque tube (pitchcase): from its inboard end (pitch horn, snubber) to the clevis.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("inboard", "dimensionless", None, "[0, 1)",
              "Inboard end / R, in [rotor.root_offset, flexbeam.clevis): the pitch horn and "
              "the snubber are there.", optional=True),
        Param("n_elements", "dimensionless", 3, "[1, 40]", "Torque-tube finite elements.",
              "int"),
        *_beam_params("torque tube"),
    )  # fmt: skip


@settings_section("pitch_link")
class PitchLinkConfig(Section):
    """Pitch horn and link geometry of the multiple-load-path hub.

    The link's stiffness is ``hub.pitch_link_stiffness``.  Its attachment on
    the horn is ``horn_arm`` ahead of the torque tube's axis (negative: a
    trailing-edge horn) and ``radial_offset`` outboard of the horn station;
    the link leans ``cant`` toward the leading edge from the vertical.

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("horn_arm", "length", None, "[-1, 1]",
              "Chordwise arm of the pitch horn, positive ahead of the pitch axis "
              "(leading-edge horn); 0 < |horn_arm| < rotor.chord.", optional=True),
        Param("radial_offset", "length", 0.0, "[-1, 1]",
              "Radial position of the link attachment outboard of the horn station "
              "(kinematic pitch-flap coupling, tan delta_3 = radial_offset / horn_arm); "
              "|radial_offset| < rotor.chord."),
        Param("cant", "angle", 0.0, "[-0.7, 0.7]",
              "Inclination of the link from the vertical, upper end toward the leading edge "
              "(kinematic pitch-lag coupling)."),
    )  # fmt: skip


@settings_section("snubber")
class SnubberConfig(Section):
    """Elastomeric snubber/damper between the torque tube's inboard end and the flexbeam.

    Springs ``K'`` in flap, lag and pitch; in lag (the chordwise
    spring/damper restraint) the complex stiffness ``K* = K' (1 + i eta)``,
    represented as the spring with a viscous damper ``eta K' / omega_ref``
    (equal dissipation per cycle at ``omega_ref``, the lag frequency).

    Parameters
    ----------
    {params}
    """

    PARAMS = (
        Param("flap_stiffness", "force_per_length", None, "[0, 1e12]",
              "Storage stiffness K' in the flapwise (vertical) direction.", optional=True),
        Param("lag_stiffness", "force_per_length", None, "[0, 1e12]",
              "Storage stiffness K' in the chordwise (lag) direction.", optional=True),
        Param("torsion_stiffness", "moment_per_angle", None, "[0, 1e12]",
              "Storage stiffness K' in pitch.", optional=True),
        Param("loss_factor", "dimensionless", None, "[0, 2]",
              "Loss factor eta = K''/K' of the chordwise (lag) restraint.", optional=True),
        Param("reference_frequency", "angular_velocity", None, "(0, 1e4]",
              "Frequency at which the complex stiffness applies (the lag frequency).",
              optional=True),
    )  # fmt: skip


#: The hub's multiple-load-path sections, in file order.
HUB_SECTIONS = (FlexbeamConfig, TorqueTubeConfig, PitchLinkConfig, SnubberConfig)


def check_hub_relations(cfg) -> None:
    """Relations of the multiple-load-path hub fields.

    Only when ``hub.model = "multiple_load_path"`` (an equivalent-hub
    configuration does not use these fields; their own ranges are always
    checked).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.

    Raises
    ------
    ValueError
        A field the model needs is not set, the clevis is not between the
        structural root and the aerodynamic root, the torque tube does not
        end between the hub and the clevis, the horn arm is zero or longer
        than the chord, a hub beam has no torsional inertia, or no
        main-blade elements are left.
    """
    if cfg.hub.model != "multiple_load_path":
        return
    missing = [f"{cls.SECTION}.{p.name}" for cls in HUB_SECTIONS for p in cls.PARAMS
               if getattr(getattr(cfg, cls.SECTION), p.name) is None]
    if missing:
        raise ValueError(f"hub.model = 'multiple_load_path' needs {', '.join(missing)} "
                         "(not set)")
    r0, cutout, chord = cfg.rotor.root_offset, cfg.rotor.root_cutout, cfg.rotor.chord
    fb, tt, pl = cfg.flexbeam, cfg.torque_tube, cfg.pitch_link
    if not r0 < fb.clevis <= cutout + GEOMETRY_TOL:
        raise ValueError(f"flexbeam.clevis = {format_value(fb.clevis)} must lie in "
                         f"(rotor.root_offset, rotor.root_cutout] = "
                         f"({format_value(r0)}, {format_value(cutout)}]")
    if not 0.0 < abs(pl.horn_arm) < chord:
        raise ValueError(f"pitch_link.horn_arm = {format_value(pl.horn_arm)} m must be nonzero and "
                         f"shorter than rotor.chord = {format_value(chord)} m (allowed: "
                         f"(-{format_value(chord)}, 0) or (0, {format_value(chord)}) m)")
    if not abs(pl.radial_offset) < chord:
        raise ValueError(f"pitch_link.radial_offset = {format_value(pl.radial_offset)} m must be "
                         f"shorter than rotor.chord = {format_value(chord)} m")
    if not r0 - GEOMETRY_TOL <= tt.inboard < fb.clevis:
        raise ValueError(f"torque_tube.inboard = {format_value(tt.inboard)} must lie in "
                         f"[rotor.root_offset, flexbeam.clevis) = [{format_value(r0)}, "
                         f"{format_value(fb.clevis)})")
    for sec in (fb, tt):
        if sec.im_flap + sec.im_lag <= 0.0:
            raise ValueError(f"{sec.SECTION}.im_flap + {sec.SECTION}.im_lag = 0.0 kg*m^2/m: "
                             "the torsional inertia must be positive")
    n_blade = cfg.model.n_elements - fb.n_elements - tt.n_elements
    if n_blade < 2:
        raise ValueError(f"model.n_elements = {cfg.model.n_elements} leaves {n_blade} main-blade "
                         f"element(s) after flexbeam.n_elements = {fb.n_elements} and "
                         f"torque_tube.n_elements = {tt.n_elements}; at least 2 are needed")
