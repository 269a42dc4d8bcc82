"""The paper's figures as analyses: one definition per figure, tidy tables out.

Each stability figure (3-4, 8-17) is a sweep of one configuration field about
the MDART baseline with the fixed parameters of its caption
(:data:`FIGURES`); :func:`run_figure` runs it with :func:`tefcore.sweeps.sweep.sweep`.
Figures 5-7 are flap-response analyses about a trimmed forward-flight state
(:func:`hinge_moment_figure`, :func:`flap_response_figure`,
:func:`overhang_actuation_figure`). Notebooks and :mod:`tefcore.paper.validation`
both call these, so a figure is computed the same way everywhere.

Examples
--------
>>> FIGURES["fig9"].parameter, [float(v) for v in FIGURES["fig9"].values[:3]]
('flap.cg_offset', [0.0, 0.04, 0.08])
>>> FIGURES["fig10"].values[0], FIGURES["fig10"].values[-1]
('150 lb/in', '800 lb/in')
>>> cfg = figure_config("fig10")
>>> cfg.flight.advance_ratio, cfg.flap.overhang, cfg.flap.cg_offset
(0.3, 0.29, 0.33)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..config.io import load_config
from ..fourier import fourier_eval
from ..model.coupled import coupled_model
from ..model.flap import flap_properties
from ..model.section_response import SectionMotion, aerodynamic_hinge_moment
from ..sweeps.sweep import sweep
from ..trimming.trim import trim

__all__ = ["FIG5_FLIGHT", "FIGURES", "FORWARD_03", "IMBALANCED", "RESPONSE_TITLES", "Figure",
           "figure_config", "flap_response_figure", "hinge_moment_figure",
           "overhang_actuation_figure", "response_config", "run_figure",
           "trimmed_section_motion"]

#: the mass-imbalanced flap of Figs. 10-17 and Fig. 9's overhang
IMBALANCED = {"flap.overhang": 0.29, "flap.cg_offset": 0.33}
#: the forward flight of Figs. 9-15 and 16b: "advance ratio of 0.30"
FORWARD_03 = {"flight.advance_ratio": 0.30}
#: Figs. 5-7: "mu = 0.2, C_T/sigma = 0.0774, c_cg/c_f = 0"
FIG5_FLIGHT = {"flight.advance_ratio": 0.2, "flight.ct_sigma": 0.0774, "flap.cg_offset": 0.0}


@dataclass(frozen=True)
class Figure:
    """A stability figure: the swept field, its values and the fixed parameters.

    Parameters
    ----------
    name : str
        The figure's name in tefcore (``"fig9"``; Fig. 16's panels are
        ``"fig16a"`` and ``"fig16b"``), the key of :data:`FIGURES`.
    caption : str
        Short caption in the paper's symbols, with the fixed parameters.
    parameter : str
        Dotted configuration field swept along the figure's x axis
        (``"flap.cg_offset"``, ``"hub.pitch_link_stiffness"``, ...).
    values : tuple
        The paper's x values: SI numbers (fractions of a chord or of R, a GJ
        factor, radians of collective) or ``"value unit"`` strings where the
        paper gives a dimensional axis (``"150 lb/in"``, ``"81.520 ft-lb/rad"``).
    fixed : dict, optional
        Dotted fields set before sweeping: the caption's flight condition and
        flap (e.g. :data:`IMBALANCED` and ``mu = 0.3`` for Figs. 10-15).
    unit : str, optional
        Unit of numeric ``values`` when they are not fractions (``"rad"`` for
        the collective of Figs. 3, 4 and 16).
    """

    name: str
    caption: str
    parameter: str
    values: tuple
    fixed: dict = field(default_factory=dict)
    unit: str = ""


FIGURES = {f.name: f for f in (
    Figure("fig3", "Blade inplane stability in hover, baseline rotor without TEF",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 11.0, 1.0))),
           {"model.tef": "none", "flight.advance_ratio": 0.0}, "rad"),
    Figure("fig4", "Blade inplane stability, mu = 0.25, forward shaft tilt 7.3 deg, no TEF",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 11.0, 1.0))),
           {"model.tef": "none", "flight.advance_ratio": 0.25,
            "flight.shaft_angle": float(np.deg2rad(7.3))}, "rad"),
    Figure("fig8", "Effect of overhang length on stability in hover, c_cg/c_f = 0",
           "flap.overhang", tuple(np.round(np.arange(0.0, 0.71, 0.05), 2)),
           {"flight.advance_ratio": 0.0, "flap.cg_offset": 0.0}),
    Figure("fig9", "Effect of flap CG offset, c_b/c_f = 0.29, mu = 0.30",
           "flap.cg_offset", tuple(np.round(np.arange(0.0, 0.41, 0.04), 2)),
           {**FORWARD_03, "flap.overhang": 0.29}),
    Figure("fig10", "Effect of pitch link stiffness, mu = 0.30, c_b/c_f = 0.29, c_cg/c_f = 0.33",
           "hub.pitch_link_stiffness", tuple(f"{k} lb/in" for k in range(150, 801, 50)),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig11", "Effect of blade torsional stiffness (GJ factor), mu = 0.30, imbalanced flap",
           "blade.gj_scale", (0.75, 1.0, 1.25, 1.5, 1.75, 2.0), {**FORWARD_03, **IMBALANCED}),
    Figure("fig12", "Effect of actuator stiffness (factor on 81.52 ft-lb/rad), mu = 0.30",
           "actuator.stiffness", tuple(f"{81.52 * k:.3f} ft-lb/rad"
                                       for k in (0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0)),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig13", "Effect of flap spanwise location, mu = 0.30, imbalanced flap",
           "flap.midspan", (0.65, 0.70, 0.75, 0.80, 0.83, 0.86, 0.90),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig14", "Effect of flap length, mu = 0.30, imbalanced flap",
           "flap.span", (0.06, 0.08, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20, 0.22),
           {**FORWARD_03, **IMBALANCED, "flap.midspan": 0.80}),
    Figure("fig15", "Effect of flap chord size, mu = 0.30, imbalanced flap",
           "flap.chord_ratio", (0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50),
           {**FORWARD_03, **IMBALANCED}),
    Figure("fig16a", "Effect of collective pitch in hover, imbalanced flap",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 13.0, 2.0))),
           {"flight.advance_ratio": 0.0, **IMBALANCED}, "rad"),
    Figure("fig16b", "Effect of collective pitch, mu = 0.30, imbalanced flap",
           "flight.collective", tuple(np.deg2rad(np.arange(0.0, 13.0, 2.0))),
           {**FORWARD_03, **IMBALANCED}, "rad"),
    Figure("fig17", "Effect of forward speed, imbalanced flap",
           "flight.advance_ratio", (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35),
           IMBALANCED),
)}


def figure_config(name: str, cfg=None):
    """Baseline configuration with the figure's fixed parameters applied.

    Parameters
    ----------
    name : str
        Stability figure, a key of :data:`FIGURES` (``"fig3"`` ... ``"fig17"``).
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: the MDART baseline, ``load_config("mdart")``).

    Returns
    -------
    tefcore.config.configuration.Config
        ``cfg`` with :attr:`Figure.fixed` applied, before the swept field is set.
    """
    fig = FIGURES[name]
    return (cfg or load_config("mdart")).with_overrides(fig.fixed)


def run_figure(name: str, cfg=None, values=None, **sweep_kw):
    """Run a stability figure's sweep; ``values`` override the default range.

    Parameters
    ----------
    name : str
        Stability figure, a key of :data:`FIGURES`.
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART); the figure's fixed parameters
        are applied over it (:func:`figure_config`).
    values : sequence, optional
        Values of the swept field instead of the paper's :attr:`Figure.values`
        (SI numbers or ``"value unit"`` strings).
    **sweep_kw
        Passed to :func:`tefcore.sweeps.sweep.sweep` (``n_jobs``, ``out``, ``refine``,
        ...); ``progress`` defaults to False.

    Returns
    -------
    tefcore.sweeps.sweep.SweepResult
        One Floquet analysis per value; ``.table`` is tidy (one row per root
        and point, with the tracked mode, the TEF branch and the flutter root).

    Raises
    ------
    ValueError
        ``name`` is not a stability figure (the message lists the known ones).
    """
    if name not in FIGURES:
        raise ValueError(f"unknown figure {name!r}; known: {', '.join(FIGURES)}")
    fig = FIGURES[name]
    sweep_kw.setdefault("progress", False)
    return sweep(figure_config(name, cfg), fig.parameter,
                 list(fig.values if values is None else values), **sweep_kw)


def trimmed_section_motion(tr, x: float) -> SectionMotion:
    """Section motion at station ``x`` (fraction of R) of a trimmed coupled model.

    Includes the elastic twist and flap bending of the trimmed response, so
    the flap sees the same angle of attack as in the coupled analysis (the
    kinematics are the coupled model's own, :meth:`CoupledModel.kinematics`).

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        Converged trim of a coupled blade/flap model: its periodic response
        (``tr.motion(psi)``), controls and inflow.
    x : float
        Radial station as a fraction of the rotor radius R (e.g. the flap
        midspan, 0.83 in Table 1).

    Returns
    -------
    tefcore.model.section_response.SectionMotion
        Callables of the azimuth [rad] giving the section's speed [m/s],
        angle of attack [rad] and its rates, plunge acceleration, pitch and
        bending slope in SI units (dimensional with ``Omega`` and ``R``).
    """
    model = tr.model
    rad, om = model.cfg.rotor.radius, model.cfg.rotor.rotor_speed

    def kin(psi, key):
        psi = np.atleast_1d(np.asarray(psi, float))
        q, qd, qdd = tr.motion(psi)
        k = model.kinematics(psi, q, qd, qdd, tr.controls, tr.inflow, x=[x])
        return k[key][:, 0]

    return SectionMotion(
        velocity=lambda p: kin(p, "speed") * om * rad,
        alpha=lambda p: kin(p, "theta") - kin(p, "inflow_angle"),
        alpha_rate=lambda p: kin(p, "theta_d") * om,
        alpha_accel=lambda p: kin(p, "theta_dd") * om**2,
        plunge_rate=lambda p: np.zeros_like(np.asarray(p, float)),
        plunge_accel=lambda p: kin(p, "wdd") * om**2 * rad,
        pitch=lambda p: kin(p, "theta"), pitch_accel=lambda p: kin(p, "theta_dd") * om**2,
        flap_slope=lambda p: kin(p, "slope"), flap_accel=lambda p: kin(p, "wdd") * om**2 * rad)


#: Short titles of the flap-response figures 5-7 (the stability figures' are their captions).
RESPONSE_TITLES = {
    "fig5": "Hinge moment over one revolution, prescribed flap motion "
            "δ_f = 2° cos(4ψ − 240°)",
    "fig6": "Flap response to the actuator input δ_a = 2° cos(4ψ − 240°)",
    "fig7": "Actuation power and flap response versus overhang",
}


def response_config(cfg=None, **over):
    """Configuration of Figs. 5-7: ``cfg``, then :data:`FIG5_FLIGHT`, then ``over``.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    **over
        Dotted fields that win over the figures' flight condition.
    """
    return (cfg or load_config("mdart")).with_overrides({**FIG5_FLIGHT, **over})


def _fig5_trim(cfg, **over):
    cfg = response_config(cfg, **over)
    return cfg, trim(coupled_model(cfg))


def hinge_moment_figure(cfg=None, aero=None, n_psi: int = 72, **over) -> pd.DataFrame:
    """Fig. 5: aerodynamic hinge moment over a revolution, prescribed flap motion.

    ``delta_f = 2 deg cos(4 psi - 240 deg)`` on the trimmed blade at
    ``mu = 0.2, C_T/sigma = 0.0774`` (:func:`response_config`; ``over``
    wins).  The paper compares UMARC's table look-up and Theodorsen-based
    hinge moments with CAMRAD II's; here the section model decides which.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    aero : object, optional
        Section aerodynamics model evaluating the hinge moment
        (:func:`tefcore.model.coupled.section_model`, e.g. from
        :func:`tefcore.paper.figure_runs.section_aero`); default: the trimmed
        model's own.
    n_psi : int
        Azimuth samples over one revolution (72: every 5 deg).
    **over
        Dotted configuration fields that win over Fig. 5's condition
        (e.g. ``**{"flap.overhang": 0.0}``).

    Returns
    -------
    pandas.DataFrame
        ``psi_deg`` (azimuth [deg]), ``delta_deg`` (prescribed flap
        deflection [deg], positive flap down) and ``hinge_moment`` [N m].
    """
    cfg, tr = _fig5_trim(cfg, **over)
    props = flap_properties(cfg)
    aero = aero or tr.model.aero
    psi = np.linspace(0, 2 * np.pi, n_psi, endpoint=False)
    amp, ph = np.deg2rad(2.0), np.deg2rad(240.0)
    om = cfg.rotor.rotor_speed
    delta = amp * np.cos(4 * psi - ph)
    rate = -4 * om * amp * np.sin(4 * psi - ph)
    accel = -16 * om**2 * delta
    h = aerodynamic_hinge_moment(aero, props, lambda r: trimmed_section_motion(
        tr, r / cfg.rotor.radius), psi, delta, rate, accel, density=cfg.rotor.air_density,
        speed_of_sound=cfg.rotor.speed_of_sound)
    return pd.DataFrame({"psi_deg": np.rad2deg(psi), "delta_deg": np.rad2deg(delta),
                         "hinge_moment": h})


def flap_response_figure(cfg=None, **over) -> dict:
    """Fig. 6: coupled trimmed flap response to ``delta_a = 2 deg cos(4 psi - 240 deg)``.

    The actuator input enters the coupled blade/flap trim (as in the paper);
    the flap answers through the actuator spring ``k_a`` and damper ``c_a``,
    so its half peak-to-peak differs from the input's 2 deg (the paper: 15 %
    larger with the baseline actuator).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    **over
        Dotted configuration fields that win over Fig. 6's condition and the
        actuator input (e.g. ``**{"flap.overhang": 0.4}``).

    Returns
    -------
    dict
        ``table`` (``psi_deg, delta_a_deg, delta_f_deg, actuator_torque``
        [N m] ``= k_a (delta_a - delta_f) + c_a (...)*``, ``power`` [W]
        ``= T_a delta_a*``), ``half_peak_to_peak_deg`` of the flap response,
        ``input_half_peak_to_peak_deg`` (2.0), ``peak_power`` and
        ``mean_power`` (of ``|power|``, [W]) and the ``trim`` summary.
    """
    act = {"flight.actuator_amplitude": float(np.deg2rad(2.0)),
           "flight.actuator_harmonic": 4, "flight.actuator_phase": float(np.deg2rad(240.0))}
    cfg, tr = _fig5_trim(cfg, **act, **over)
    model = tr.model
    psi = np.linspace(0, 2 * np.pi, 144, endpoint=False)
    delta_f = fourier_eval(tr.q[-1], psi)
    delta_fd = fourier_eval(tr.q[-1], psi, 1)
    da, da_d = model.actuator_input(psi)
    om = cfg.rotor.rotor_speed
    k_a, c_a = cfg.actuator.stiffness, cfg.actuator.damping
    torque = k_a * (da - delta_f) + c_a * om * (da_d - delta_fd)
    power = torque * da_d * om
    table = pd.DataFrame({"psi_deg": np.rad2deg(psi), "delta_a_deg": np.rad2deg(da),
                          "delta_f_deg": np.rad2deg(delta_f), "actuator_torque": torque,
                          "power": power})
    return {"table": table, "half_peak_to_peak_deg": 0.5 * np.ptp(np.rad2deg(delta_f)),
            "input_half_peak_to_peak_deg": 2.0, "peak_power": float(np.abs(power).max()),
            "mean_power": float(np.abs(power).mean()), "trim": tr.summary()}


def overhang_actuation_figure(cfg=None, overhangs=(0.0, 0.1, 0.2, 0.29, 0.35, 0.4, 0.45, 0.5),
                              **over):
    """Fig. 7: actuation power and half peak-to-peak response versus overhang.

    Each overhang is :func:`flap_response_figure` with ``over`` (which wins
    over the figures' flight condition).  The paper: the power falls by 60 %
    from no overhang to 0.29 c_f (Fig. 7a), the response grows with the
    overhang, steeply above 0.40 c_f (Fig. 7b).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    overhangs : sequence of float
        Flap overhangs ``c_b/c_f`` (hinge behind the flap nose, fraction of
        the flap chord) at which to trim.
    **over
        Dotted configuration fields that win over Fig. 7's condition.

    Returns
    -------
    pandas.DataFrame
        One row per overhang: ``overhang``, ``half_peak_to_peak_deg``,
        ``peak_power`` and ``mean_power`` [W].
    """
    rows = []
    for ov in overhangs:
        out = flap_response_figure(cfg, **{**over, "flap.overhang": float(ov)})
        rows.append({"overhang": ov, "half_peak_to_peak_deg": out["half_peak_to_peak_deg"],
                     "peak_power": out["peak_power"], "mean_power": out["mean_power"]})
    return pd.DataFrame(rows)
