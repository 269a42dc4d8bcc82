"""The flap-response figures 5-7 about a trimmed forward-flight state.

Fig. 5 is the hinge moment over a revolution with the flap's motion prescribed
(:func:`hinge_moment_figure`), Fig. 6 the flap's response to the actuator
input (:func:`flap_response_figure`), Fig. 7 the actuation power and response
versus overhang (:func:`overhang_actuation_figure`), all at the flight
condition of :data:`FIG5_FLIGHT`.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...config.io import load_config
from ...fourier import fourier_eval
from ...model.coupled import coupled_model
from ...model.flap import flap_properties
from ...model.section_response import SectionMotion, aerodynamic_hinge_moment
from ...trimming.trim import trim

__all__ = ["FIG5_FLIGHT", "RESPONSE_TITLES", "flap_response_figure", "hinge_moment_figure",
           "overhang_actuation_figure", "response_config", "trimmed_section_motion"]

#: Figs. 5-7: "mu = 0.2, C_T/sigma = 0.0774, c_cg/c_f = 0"
FIG5_FLIGHT = {"flight.advance_ratio": 0.2, "flight.ct_sigma": 0.0774, "flap.cg_offset": 0.0}


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
        :func:`tefcore.paper.figures.runs.section_aero`); default: the trimmed
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
