"""The two bearingless-hub models side by side (docs/theory.md sections 2.5, 2.5a).

``hub.model = "equivalent"`` lumps the hub into root springs and a lag damper;
``"multiple_load_path"`` models flexbeam, torque tube, pitch link and snubber
(:func:`tefcore.blade.multiple_load_path_model`).  This module holds what is
specific to the second: the closed forms of its torsion load paths and of the
pitch-link kinematics (:func:`kinematic_pitch_ratio`,
:func:`pitch_flap_delta3`), its static response to a pitch input
(:func:`pitch_input_response`), and the comparison of both hubs -- fan plots
and the lag damping of Figs. 3 and 4 -- that notebook 01 shows
(:func:`compare_hub_models`, :func:`plot_hub_models`).

Examples
--------
>>> from tefcore.config_io import load_config
>>> cfg = load_config("mdart").with_overrides({"hub.model": "multiple_load_path"})
>>> round(kinematic_pitch_ratio(cfg), 4)
0.969
>>> round(float(np.degrees(pitch_flap_delta3(cfg))), 1) + 0.0   # no radial offset
0.0
>>> r = pitch_input_response(cfg)          # rotating: tension-torsion, propeller moment
>>> round(r["blade_twist"], 3)
0.858
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .blade import blade_modes, fan_data, multiple_load_path_model, rotor_units
from .config import load_config
from .figures import run_figure

__all__ = ["HUB_MODELS", "HubComparison", "compare_hub_models", "kinematic_pitch_ratio",
           "pitch_flap_delta3", "pitch_input_response", "plot_hub_models"]

#: The values of ``hub.model``.
HUB_MODELS = ("equivalent", "multiple_load_path")


def _require_mlp(cfg) -> None:
    if cfg.hub.model != "multiple_load_path":
        raise ValueError(f"hub.model = {cfg.hub.model!r}: this needs 'multiple_load_path'")


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
    cfg : Config
        With ``hub.model = "multiple_load_path"``.
    parts : bool
        Return the springs as well.

    Returns
    -------
    float or dict
        The ratio; with ``parts``: ``ratio``, ``flexbeam``, ``torque_tube``,
        ``link``, ``snubber`` [N m/rad] and ``root_stiffness``, the clevis's
        torsional stiffness to ground with the swashplate fixed [N m/rad].
    """
    _require_mlp(cfg)
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


def pitch_flap_delta3(cfg) -> float:
    """Kinematic pitch-flap angle of the pitch-link geometry, ``atan(d / a)`` [rad].

    With a rigid link and the horn station held vertically, flapping the
    torque tube by a slope ``w'`` at the horn moves the link attachment
    (``d = pitch_link.radial_offset`` outboard, ``a = pitch_link.horn_arm``
    ahead of the axis) by ``d w' + a phi``, so ``phi = -w' tan(delta_3)``:
    positive delta_3 pitches down as the blade flaps up.
    """
    _require_mlp(cfg)
    return float(np.arctan(cfg.pitch_link.radial_offset / cfg.pitch_link.horn_arm))


def pitch_input_response(cfg, rotating: bool = True, collective: float = 0.0) -> dict:
    """Static twist of the branched blade for a unit pitch input at the swashplate.

    The pitch link's lower end is moved by ``a cos(cant)`` (one radian
    through the horn); the finite-element statics ``K q = k_PL s b`` with
    ``b`` the link's row (docs/theory.md section 2.5a).

    Parameters
    ----------
    cfg : Config
        With ``hub.model = "multiple_load_path"``.
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
    _require_mlp(cfg)
    beam = multiple_load_path_model(cfg, collective)
    units = rotor_units(cfg)
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


@dataclass
class HubComparison:
    """Both hub models of one configuration (:func:`compare_hub_models`).

    Attributes
    ----------
    fan : DataFrame
        :func:`tefcore.blade.fan_data` of each hub, with ``hub_model``.
    modes : DataFrame
        The retained modes at the configured rotor speed: ``hub_model, mode,
        label, frequency_per_rev, damping_ratio`` (structural, in vacuum:
        ``C_ii / (2 omega_i M_ii)``, as
        :func:`tefcore.calibration.lag_damping_ratio` for lag 1).
    lag_damping : DataFrame
        Figs. 3 and 4 (no flap): ``hub_model, figure, collective_deg,
        frequency_per_rev, damping_ratio`` of the ``blade lag 1`` track.
    """

    fan: pd.DataFrame
    modes: pd.DataFrame
    lag_damping: pd.DataFrame


def _lag_track(result, hub_model, name):
    t = result.table
    t = t[(t["refinement"] == 0) & (t["status"] == "ok") & (t["label"] == "blade lag 1")]
    return pd.DataFrame({"hub_model": hub_model, "figure": name,
                         "collective_deg": np.degrees(t["value_si"].to_numpy(float)),
                         "frequency_per_rev": t["frequency_per_rev"].to_numpy(float),
                         "damping_ratio": t["damping_ratio"].to_numpy(float)})


def compare_hub_models(cfg=None, *, speed_ratios=None, figures=("fig3", "fig4"),
                       collectives_deg=None, n_jobs: int = 1) -> HubComparison:
    """Fan plots and the Figs. 3-4 lag damping of both hub models.

    Parameters
    ----------
    cfg : Config, optional
        Base configuration (default MDART); ``hub.model`` is set to each of
        :data:`HUB_MODELS` in turn.
    speed_ratios : array_like, optional
        Rotor speeds of the fan plot over the configured one (default
        0.2-1.2).
    figures : sequence of str
        Lag-damping figures to run (:data:`tefcore.figures.FIGURES`); empty
        for none (the fan plot alone takes well under a second).
    collectives_deg : array_like, optional
        Collective pitch values [deg] (default: the figures' 0-10 deg).
    n_jobs : int
        Parallel processes of the sweeps.

    Returns
    -------
    HubComparison
    """
    cfg = cfg or load_config("mdart")
    speed_ratios = np.linspace(0.2, 1.2, 26) if speed_ratios is None else speed_ratios
    values = None if collectives_deg is None else [float(np.radians(v)) for v in collectives_deg]
    fans, modes, lags = [], [], []
    for hub in HUB_MODELS:
        c = cfg.with_overrides({"hub.model": hub})
        fans.append(fan_data(c, speed_ratios).assign(hub_model=hub))
        m = blade_modes(c)
        damp = np.diag(m.modal_damping) / (2 * m.frequencies * np.diag(m.modal_mass))
        modes.append(pd.DataFrame({"hub_model": hub, "mode": np.arange(1, len(m.labels) + 1),
                                   "label": m.labels, "frequency_per_rev": m.frequencies,
                                   "damping_ratio": damp}))
        for name in figures:
            lags.append(_lag_track(run_figure(name, c, values, n_jobs=n_jobs), hub, name))
    lag = (pd.concat(lags, ignore_index=True) if lags else
           pd.DataFrame(columns=["hub_model", "figure", "collective_deg", "frequency_per_rev",
                                 "damping_ratio"]))
    return HubComparison(pd.concat(fans, ignore_index=True), pd.concat(modes, ignore_index=True),
                         lag)


def plot_hub_models(comparison: HubComparison, cfg=None):
    """Fan plots of both hubs and the lag damping of Figs. 3-4, side by side.

    Returns the matplotlib Figure (two fan plots on top, the lag damping of
    each figure below).
    """
    import matplotlib.pyplot as plt

    cfg = cfg or load_config("mdart")
    figs = list(dict.fromkeys(comparison.lag_damping["figure"]))
    fig, axes = plt.subplots(2, max(2, len(figs)), figsize=(11, 8), squeeze=False)
    styles = {"flap": "-", "lag": "--", "torsion": "-.", "axial": ":"}
    nominal = cfg.rotor.rotor_speed * 30 / np.pi
    for ax, hub in zip(axes[0], HUB_MODELS, strict=False):
        df = comparison.fan[comparison.fan["hub_model"] == hub]
        for lab, g in df.groupby("label", sort=False):
            ax.plot(g["rotor_speed_rpm"], g["frequency_hz"], styles[lab.split()[0]], label=lab)
        rpm = np.array([0.0, df["rotor_speed_rpm"].max()])
        for k in range(1, 9):
            ax.plot(rpm, k * rpm / 60, color="0.8", lw=0.7, zorder=0)
        ax.axvline(nominal, color="0.5", lw=0.8)
        ax.set(title=f"hub.model = {hub!r}", xlabel="rotor speed [RPM]", ylabel="frequency [Hz]",
               xlim=(0, rpm[1]), ylim=(0, df["frequency_hz"].max() * 1.05))
        ax.legend(fontsize="x-small", ncol=2)
    for ax, name in zip(axes[1], figs, strict=False):
        d = comparison.lag_damping[comparison.lag_damping["figure"] == name]
        for hub, style in zip(HUB_MODELS, ("o-", "s--"), strict=True):
            g = d[d["hub_model"] == hub]
            ax.plot(g["collective_deg"], 100 * g["damping_ratio"], style, label=hub)
        ax.set(title=f"{name}: lag 1 damping", xlabel="collective [deg]",
               ylabel="damping ratio [%]")
        ax.legend(fontsize="small")
    for ax in axes[1][len(figs):]:
        ax.set_visible(False)
    fig.tight_layout()
    return fig
