"""The two bearingless-hub models side by side (docs/theory.md sections 2.5, 2.5a).

``hub.model = "equivalent"`` lumps the hub into root springs and a lag damper;
``"multiple_load_path"`` models flexbeam, torque tube, pitch link and snubber
(:func:`tefcore.structure.blade.multiple_load_path_model`).  This module holds what is
specific to the second: the closed forms of its torsion load paths and of the
pitch-link kinematics (:func:`kinematic_pitch_ratio`,
:func:`pitch_flap_delta3`) and its static response to a pitch input
(:func:`pitch_input_response`).  The comparison of both hubs that notebook 01
shows is in the paper layer (:mod:`tefcore.paper.attribution.hub_comparison`).

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart").with_overrides({"hub.model": "multiple_load_path"})
>>> round(kinematic_pitch_ratio(cfg), 4)
0.969
>>> round(float(np.degrees(pitch_flap_delta3(cfg.hub, cfg.pitch_link))), 1) + 0.0  # no offset
0.0
>>> r = pitch_input_response(cfg)          # rotating: tension-torsion, propeller moment
>>> round(r["blade_twist"], 3)
0.858
"""

from __future__ import annotations

import numpy as np

from .blade import multiple_load_path_model, rotor_units

__all__ = ["HUB_MODELS", "kinematic_pitch_ratio", "pitch_flap_delta3", "pitch_input_response"]

#: The values of ``hub.model``.
HUB_MODELS = ("equivalent", "multiple_load_path")


def _require_mlp(hub) -> None:
    if hub.model != "multiple_load_path":
        raise ValueError(f"hub.model = {hub.model!r}: this needs 'multiple_load_path'")


def kinematic_pitch_ratio(cfg, parts: bool = False):
    """Clevis rotation per unit pitch input through the torsion load paths (closed form).

    Nonrotating, without bending: the swashplate moves the pitch link's lower
    end by ``a cos(cant)`` per radian of input; the link (``k_PL a^2
    cos^2(cant)``) turns the horn, which the snubber (pitch stiffness
    ``k_s``) ties to the flexbeam at ``torque_tube.inboard``; the torque tube
    (``GJ_t / L_t``) carries the torque to the clevis, where the flexbeam
    (``GJ_f / L_f``, clamped at the hub) resists.  The network of these
    springs, solved for the horn, the flexbeam at the snubber and the clevis
    (docs/theory.md section 2.5a).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the hub sections ``flexbeam``, ``torque_tube``,
        ``pitch_link`` and ``snubber`` with ``hub`` (``hub.model =
        "multiple_load_path"``) and ``rotor``.
    parts : bool
        Return the springs as well.

    Returns
    -------
    float or dict
        The ratio; with ``parts``: ``ratio``, ``flexbeam``, ``torque_tube``,
        ``link``, ``snubber`` [N m/rad] and ``root_stiffness``, the clevis's
        torsional stiffness to ground with the swashplate fixed [N m/rad].
    """
    _require_mlp(cfg.hub)
    fb, tt, pl = cfg.flexbeam, cfg.torque_tube, cfg.pitch_link
    rad, r0 = cfg.rotor.radius, cfg.rotor.root_offset
    k_link = cfg.hub.pitch_link_stiffness * (pl.horn_arm * np.cos(pl.cant)) ** 2
    k_tube = tt.gj / ((fb.clevis - tt.inboard) * rad)
    k_snub = cfg.snubber.torsion_stiffness
    # unknowns: horn, flexbeam at the snubber, clevis (the middle one is the
    # flexbeam's clamp when the tube reaches the hub)
    at_root = tt.inboard - r0 < 1e-12
    k_in = np.inf if at_root else fb.gj / ((tt.inboard - r0) * rad)
    k_out = fb.gj / ((fb.clevis - tt.inboard) * rad)
    springs = [(0, None, k_link), (0, 1, k_snub), (0, 2, k_tube), (1, None, k_in),
               (1, 2, k_out)]
    keep = [0, 2] if at_root else [0, 1, 2]
    k = np.zeros((3, 3))
    for i, j, s in springs:
        if np.isinf(s):
            continue
        k[i, i] += s
        if j is not None:
            k[j, j] += s
            k[i, j] -= s
            k[j, i] -= s
    kk = k[np.ix_(keep, keep)]
    f = np.zeros(len(keep))
    f[0] = k_link                                   # unit input at the link's lower end
    ratio = float(np.linalg.solve(kk, f)[-1])
    if not parts:
        return ratio
    unit = np.zeros(len(keep))
    unit[-1] = 1.0                                  # unit torque at the clevis
    root = 1.0 / float(np.linalg.solve(kk, unit)[-1])
    return {"ratio": ratio, "flexbeam": fb.gj / ((fb.clevis - r0) * rad), "torque_tube": k_tube,
            "link": k_link, "snubber": k_snub, "root_stiffness": root}


def pitch_flap_delta3(hub, pitch_link) -> float:
    """Kinematic pitch-flap angle of the pitch-link geometry, ``atan(d / a)`` [rad].

    With a rigid link and the horn station held vertically, flapping the
    torque tube by a slope ``w'`` at the horn moves the link attachment
    (``d = pitch_link.radial_offset`` outboard, ``a = pitch_link.horn_arm``
    ahead of the axis) by ``d w' + a phi``, so ``phi = -w' tan(delta_3)``:
    positive delta_3 pitches down as the blade flaps up.

    Parameters
    ----------
    hub : tefcore.config.sections.HubConfig
        The hub section, with ``hub.model = "multiple_load_path"``.
    pitch_link : tefcore.config.hub.PitchLinkConfig
        The pitch link (its radial offset and horn arm).

    Returns
    -------
    float
        delta_3 [rad].
    """
    _require_mlp(hub)
    return float(np.arctan(pitch_link.radial_offset / pitch_link.horn_arm))


def pitch_input_response(cfg, rotating: bool = True, collective: float = 0.0) -> dict:
    """Static twist of the branched blade for a unit pitch input at the swashplate.

    The pitch link's lower end is moved by ``a cos(cant)`` (one radian
    through the horn); the finite-element statics ``K q = k_PL s b`` with
    ``b`` the link's row (docs/theory.md section 2.5a).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the branched hub and blade are built from all
        its structural sections (:func:`tefcore.structure.blade.multiple_load_path_model`),
        with ``hub.model = "multiple_load_path"``.
    rotating : bool
        Elastic plus centrifugal stiffness at the configured rotor speed
        (tension-torsion of the flexbeam, propeller moment), or the elastic
        stiffness alone (the closed form :func:`kinematic_pitch_ratio`).
    collective : float
        Pitch at 0.75 R [rad] of the structure.

    Returns
    -------
    dict
        ``horn_twist`` (torque tube at the horn), ``clevis_twist``,
        ``blade_twist`` (at 0.75 R) and ``tip_twist`` [rad per rad of input].
    """
    _require_mlp(cfg.hub)
    beam = multiple_load_path_model(cfg, collective)
    units = rotor_units(cfg.rotor, cfg.blade)
    pl = cfg.pitch_link
    k = beam.stiffness(1.0) if rotating else beam.k_elastic
    k_link = units.spring(cfg.hub.pitch_link_stiffness * units.radius**2)
    shift = units.length(pl.horn_arm) * np.cos(pl.cant)
    b = beam.couplings["pitch link"]
    f = beam.free
    q = np.zeros(beam.n_dof)
    q[f] = np.linalg.solve(k[f][:, f], k_link * shift * b[f])
    xc = cfg.flexbeam.clevis
    blade = beam.component_fields("blade", q, [xc, 0.75, 1.0])["phi"][:, 0]
    horn = beam.component_fields("torque_tube", q, [cfg.torque_tube.inboard])["phi"][0, 0]
    return {"horn_twist": float(horn), "clevis_twist": float(blade[0]),
            "blade_twist": float(blade[1]), "tip_twist": float(blade[2])}
