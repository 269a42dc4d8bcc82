"""The flap on a prescribed blade section: hinge moments and responses (Figs. 5-7).

The section-level analyses behind the paper's Figs. 5-7: the blade section
moves as a rigid blade in wind-tunnel trim (:func:`rotor_section_motion`),
the flap is prescribed (Fig. 5, :func:`hinge_moment_history`) or driven
through its actuator (Figs. 6-7, :func:`flap_response`,
:func:`section_overhang_study`).  The flap's equation is the rotor model's
(:func:`tefcore.model.flap.flap_moments`) on this motion, and its
aerodynamic hinge moment the section model's (``loads()["hinge_moment"]``)
integrated over the flap span; everything here is SI (seconds, not azimuth).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
import scipy.optimize

from ..fourier import azimuth_grid, spectral_derivative
from .flap import FlapProperties, flap_moments, flap_properties

__all__ = ["FlapResponse", "SectionMotion", "aerodynamic_hinge_moment", "flap_response",
           "hinge_moment_history", "inertial_hinge_moment", "rotor_motion",
           "rotor_section_motion", "section_overhang_study"]


@dataclass
class SectionMotion:
    """Prescribed blade-section motion over one revolution at one station.

    All callables take the azimuth ``psi`` [rad] (array) and return SI
    values: ``velocity`` [m/s], ``alpha`` [rad] and its time derivatives
    ``alpha_rate`` [rad/s], ``alpha_accel``, the plunge (up) velocity and
    acceleration of the elastic axis, and the section pitch ``pitch`` with
    ``pitch_accel`` (for the flap inertia), ``flap_slope`` w' and
    ``flap_accel`` (w** of the section, for the flap's first moment).

    Attributes
    ----------
    velocity : callable
        Tangential velocity U_T [m/s].
    alpha : callable
        Angle of attack [rad].
    alpha_rate, alpha_accel : callable
        Its first and second time derivatives [rad/s, rad/s^2].
    plunge_rate, plunge_accel : callable
        Upward velocity [m/s] and acceleration [m/s^2] of the elastic axis.
    pitch, pitch_accel : callable
        Section pitch Theta [rad] and its second time derivative [rad/s^2].
    flap_slope : callable
        Blade flap slope w' [-].
    flap_accel : callable
        Flap-wise acceleration w** of the section [m/s^2].
    """

    velocity: object
    alpha: object
    alpha_rate: object
    alpha_accel: object
    plunge_rate: object
    plunge_accel: object
    pitch: object
    pitch_accel: object
    flap_slope: object
    flap_accel: object


def rotor_section_motion(rotor, blade, x: float, *, advance_ratio: float, collective: float,
                         cyclic_cos: float = 0.0, cyclic_sin: float = 0.0,
                         inflow: float = 0.0, coning: float = 0.0) -> SectionMotion:
    """Section motion of a rigid blade with zero cyclic flapping (wind-tunnel trim).

    ``U_T = Omega R (x + mu sin psi)``, ``U_P = Omega R (lambda + mu beta_0 cos psi)``,
    ``theta = theta_0 + theta_1c cos psi + theta_1s sin psi`` (pretwist
    included at ``x``), ``alpha = theta - U_P / U_T``.

    Parameters
    ----------
    rotor : tefcore.config.sections.RotorConfig
        The rotor section (rotor speed and radius).
    blade : tefcore.config.sections.BladeConfig
        The blade section (its built-in twist).
    x : float
        Station, fraction of R.
    advance_ratio, collective, cyclic_cos, cyclic_sin, inflow, coning : float
        mu, theta_75 [rad], theta_1c, theta_1s [rad], inflow ratio lambda
        (positive down through the disk), coning beta_0 [rad].

    Returns
    -------
    SectionMotion
    """
    om, rad = rotor.rotor_speed, rotor.radius
    tw = np.interp(x, blade.stations, blade.twist) - np.interp(0.75, blade.stations, blade.twist)
    mu = advance_ratio

    def theta(p):
        return collective + tw + cyclic_cos * np.cos(p) + cyclic_sin * np.sin(p)

    def theta_dd(p):       # d2/dt2 = Omega^2 d2/dpsi2
        return -om**2 * (cyclic_cos * np.cos(p) + cyclic_sin * np.sin(p))

    def ut(p):
        return om * rad * (x + mu * np.sin(p))

    def up(p):
        return om * rad * (inflow + mu * coning * np.cos(p))

    def alpha(p):
        return theta(p) - up(p) / ut(p)

    def d_dt(f, p, h=1e-4):  # central difference in psi, exact enough for smooth f
        return om * (f(p + h) - f(p - h)) / (2 * h)

    return SectionMotion(
        velocity=ut, alpha=alpha,
        alpha_rate=lambda p: d_dt(alpha, p),
        alpha_accel=lambda p: om * (d_dt(alpha, p + 1e-4) - d_dt(alpha, p - 1e-4)) / 2e-4,
        plunge_rate=lambda p: np.zeros_like(np.asarray(p, float)),
        plunge_accel=lambda p: np.zeros_like(np.asarray(p, float)),
        pitch=theta, pitch_accel=theta_dd,
        flap_slope=lambda p: np.full_like(np.asarray(p, float), coning),
        flap_accel=lambda p: np.zeros_like(np.asarray(p, float)))


def rotor_motion(rotor, blade, **controls):
    """Factory ``motion_at(r)`` of :func:`rotor_section_motion` by radius [m].

    Parameters
    ----------
    rotor : tefcore.config.sections.RotorConfig
        The rotor section.
    blade : tefcore.config.sections.BladeConfig
        The blade section.
    **controls
        Keyword arguments of :func:`rotor_section_motion` (``advance_ratio``,
        ``collective``, ...).

    Returns
    -------
    callable
        ``motion_at(r) -> SectionMotion``.
    """
    radius = rotor.radius
    return lambda r: rotor_section_motion(rotor, blade, r / radius, **controls)


def _strips(props, motion_at, n_span):
    r_pts, weights = props.stations(n_span)
    return [(r, w, motion_at(r)) for r, w in zip(r_pts, weights, strict=True)]


def aerodynamic_hinge_moment(aero, props: FlapProperties, motion_at, psi, delta, delta_rate,
                             delta_accel, *, density: float, speed_of_sound: float,
                             n_span: int = 3):
    """Aerodynamic hinge moment of the whole flap [N m], positive TE down.

    Strip theory over the flap span with ``n_span`` Gauss points;
    ``motion_at(r)`` gives the :class:`SectionMotion` at radius ``r`` [m] and
    ``aero`` is a section model with the ``loads`` interface
    (:class:`tefcore.aero.thin_airfoil.ThinAirfoilFlap` or a C81 table model).
    ``delta_rate``/``delta_accel`` are time derivatives [rad/s, rad/s^2].

    Parameters
    ----------
    aero : object
        Section aerodynamics with the ``loads`` interface
        (:class:`tefcore.aero.thin_airfoil.ThinAirfoilFlap` or
        :class:`tefcore.aero.c81.C81FlapTable`).
    props : FlapProperties
        The flap (:func:`flap_properties`).
    motion_at : callable
        ``motion_at(r)``: the :class:`SectionMotion` at radius ``r`` [m]
        (e.g. :func:`rotor_motion`).
    psi : numpy.ndarray
        Azimuths [rad].
    delta, delta_rate, delta_accel : numpy.ndarray
        Flap deflection [rad] and its time derivatives [rad/s, rad/s^2] at ``psi``.
    density : float
        Air density [kg/m^3].
    speed_of_sound : float
        [m/s], for the Mach number of each strip.
    n_span : int, optional
        Gauss points over the flap span.

    Returns
    -------
    numpy.ndarray
        The hinge moment at ``psi`` [N m].
    """
    total = 0.0
    for _, wgt, m in _strips(props, motion_at, n_span):
        vel = m.velocity(psi)
        out = aero.loads(alpha=m.alpha(psi), alpha_rate=m.alpha_rate(psi),
                         alpha_accel=m.alpha_accel(psi), plunge_rate=m.plunge_rate(psi),
                         plunge_accel=m.plunge_accel(psi), delta=delta, delta_rate=delta_rate,
                         delta_accel=delta_accel, velocity=vel, density=density,
                         chord=props.chord, mach=vel / speed_of_sound)
        total = total + wgt * out["hinge_moment"]
    return total


def inertial_hinge_moment(props: FlapProperties, motion_at, psi, delta, delta_accel, *,
                          rotor_speed: float, n_span: int = 3):
    """Inertial and centrifugal moment of the whole flap [N m] (left-hand side).

    ``int [I_h (delta** + Theta**) - S_f eta_h Theta** - S_f w** cos Theta
    + M_cf(Theta, delta) - Omega^2 S_f r w' cos Theta] dr + I_a delta**`` for a
    section with no lag motion (the lag and Coriolis terms of docs/theory.md
    section 4 enter through the coupled model; ``I_a`` is the actuator's
    reflected inertia, :attr:`FlapProperties.reflected_inertia`).

    Parameters
    ----------
    props : FlapProperties
        The flap (:func:`flap_properties`).
    motion_at : callable
        ``motion_at(r)``: the :class:`SectionMotion` at radius ``r`` [m]
        (e.g. :func:`rotor_motion`).
    psi : numpy.ndarray
        Azimuths [rad].
    delta, delta_accel : numpy.ndarray
        Flap deflection [rad] and its second time derivative [rad/s^2] at ``psi``.
    rotor_speed : float
        Omega [rad/s].
    n_span : int, optional
        Gauss points over the flap span.

    Returns
    -------
    numpy.ndarray
        The moment at ``psi`` [N m].
    """
    total = 0.0
    for r, wgt, m in _strips(props, motion_at, n_span):
        row, _ = flap_moments(props.inertia_hinge, props.first_moment, props.hinge_from_ea, r,
                              m.pitch(psi), m.pitch_accel(psi), m.flap_accel(psi), delta,
                              np.zeros_like(delta), delta_accel, slope=m.flap_slope(psi),
                              omega=rotor_speed)
        total = total + wgt * sum(row.values())
    return total + props.reflected_inertia * delta_accel


def hinge_moment_history(aero, props: FlapProperties, motion_at, delta_f, *,
                         rotor_speed: float, density: float, speed_of_sound: float,
                         n_psi: int = 72) -> pd.DataFrame:
    """Hinge moment over one revolution for a prescribed flap motion (Fig. 5).

    Parameters
    ----------
    aero : object
        Section aerodynamics with the ``loads`` interface
        (:class:`tefcore.aero.thin_airfoil.ThinAirfoilFlap` or
        :class:`tefcore.aero.c81.C81FlapTable`).
    props : FlapProperties
        The flap (:func:`flap_properties`).
    motion_at : callable
        ``motion_at(r)``: the :class:`SectionMotion` at radius ``r`` [m]
        (e.g. :func:`rotor_motion`).
    delta_f : callable
        Flap deflection ``delta_f(psi)`` [rad], e.g.
        ``lambda p: np.deg2rad(2) * np.cos(4 * p - np.deg2rad(240))``.
    rotor_speed : float
        Omega [rad/s].
    density : float
        Air density [kg/m^3].
    speed_of_sound : float
        [m/s].
    n_psi : int, optional
        Azimuths per revolution.

    Returns
    -------
    pandas.DataFrame
        ``psi_deg, delta_deg, hinge_moment_aero, hinge_moment_inertial`` [N m].
    """
    psi = azimuth_grid(n_psi)
    d = spectral_derivative(n_psi) * rotor_speed
    delta = delta_f(psi)
    rate, accel = d @ delta, d @ (d @ delta)
    aero_h = aerodynamic_hinge_moment(aero, props, motion_at, psi, delta, rate, accel,
                                      density=density, speed_of_sound=speed_of_sound)
    inert = inertial_hinge_moment(props, motion_at, psi, delta, accel, rotor_speed=rotor_speed)
    return pd.DataFrame({"psi_deg": np.rad2deg(psi), "delta_deg": np.rad2deg(delta),
                         "hinge_moment_aero": aero_h, "hinge_moment_inertial": inert})


@dataclass
class FlapResponse:
    """Periodic flap response to an actuator input, with actuation power.

    Attributes
    ----------
    psi : numpy.ndarray
        Azimuths of one revolution [rad].
    delta_a : numpy.ndarray
        Actuator input [rad] at ``psi``.
    delta_f : numpy.ndarray
        Flap deflection [rad], positive trailing edge down.
    hinge_moment_aero : numpy.ndarray
        Aerodynamic hinge moment of the whole flap [N m].
    actuator_torque : numpy.ndarray
        Torque the actuator spring and damper apply to the flap [N m].
    power : numpy.ndarray
        Actuation power, torque times actuator rate [W].
    """

    psi: np.ndarray
    delta_a: np.ndarray
    delta_f: np.ndarray
    hinge_moment_aero: np.ndarray
    actuator_torque: np.ndarray
    power: np.ndarray

    @property
    def half_peak_to_peak(self) -> float:
        """Half the peak-to-peak flap deflection [rad]."""
        return 0.5 * float(np.ptp(self.delta_f))

    @property
    def peak_power(self) -> float:
        """Largest instantaneous actuation power magnitude [W]."""
        return float(np.max(np.abs(self.power)))

    @property
    def mean_power(self) -> float:
        """Mean absolute actuation power over the revolution [W]."""
        return float(np.mean(np.abs(self.power)))


def flap_response(aero, props: FlapProperties, motion_at, delta_a, *, rotor_speed: float,
                  density: float, speed_of_sound: float, n_psi: int = 72,
                  tol: float = 1e-10) -> FlapResponse:
    """Periodic flap deflection driven through the actuator (Fig. 6).

    Solves, by Fourier collocation on ``n_psi`` azimuths (harmonic balance),
    ``inertial(delta) + c_a (delta* - delta_a*) + k_a (delta - delta_a)
    = H_aero(delta, delta*, delta**)`` for the periodic ``delta_f(psi)``.

    Parameters
    ----------
    aero : object
        Section aerodynamics with the ``loads`` interface
        (:class:`tefcore.aero.thin_airfoil.ThinAirfoilFlap` or
        :class:`tefcore.aero.c81.C81FlapTable`).
    props : FlapProperties
        The flap (:func:`flap_properties`).
    motion_at : callable
        ``motion_at(r)``: the :class:`SectionMotion` at radius ``r`` [m]
        (e.g. :func:`rotor_motion`).
    delta_a : callable
        Actuator input ``delta_a(psi)`` [rad].
    rotor_speed : float
        Omega [rad/s].
    density : float
        Air density [kg/m^3].
    speed_of_sound : float
        [m/s].
    n_psi : int, optional
        Collocation azimuths per revolution.
    tol : float, optional
        Tolerance of :func:`scipy.optimize.root` on the residual (in radians).

    Returns
    -------
    FlapResponse

    Raises
    ------
    RuntimeError
        If the collocation equations do not converge (with the residual).
    """
    psi = azimuth_grid(n_psi)
    d = spectral_derivative(n_psi) * rotor_speed
    da = delta_a(psi)
    da_rate = d @ da

    def parts(delta):
        rate, accel = d @ delta, d @ (d @ delta)
        h = aerodynamic_hinge_moment(aero, props, motion_at, psi, delta, rate, accel,
                                     density=density, speed_of_sound=speed_of_sound)
        torque = props.k_a * (da - delta) + props.c_a * (da_rate - rate)
        inert = inertial_hinge_moment(props, motion_at, psi, delta, accel,
                                      rotor_speed=rotor_speed)
        return h, torque, inert

    def residual(delta):
        h, torque, inert = parts(delta)
        return (inert - torque - h) / props.k_a       # in radians: well scaled

    def jacobian(delta, h=1e-7):
        # forward differences with a step suited to radians (hybr's default
        # step, ~1e-8 |delta|, is lost in round-off for sub-degree motions)
        r0 = residual(delta)
        return np.stack([(residual(delta + h * e) - r0) / h for e in np.eye(n_psi)], axis=1)

    sol = scipy.optimize.root(residual, da.copy(), jac=jacobian, method="hybr", tol=tol)
    if not sol.success or np.max(np.abs(sol.fun)) > 1e-8:
        raise RuntimeError(f"flap response did not converge: {sol.message}; "
                           f"max residual {np.max(np.abs(sol.fun)):.3e} rad")
    h, torque, _ = parts(sol.x)
    return FlapResponse(psi=psi, delta_a=da, delta_f=sol.x, hinge_moment_aero=h,
                        actuator_torque=torque, power=torque * da_rate)


def section_overhang_study(cfg, overhangs, delta_a, *, controls: dict, n_psi: int = 72,
                           aero_factory=None) -> pd.DataFrame:
    """Section-level actuation power and flap response versus overhang (Fig. 7).

    The flap (at the configured station, rigid-blade section motion of
    :func:`rotor_section_motion` with ``controls``) is driven by
    ``delta_a(psi)``; for each overhang the periodic response is solved.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the study varies ``flap.overhang`` in it
        (:meth:`~tefcore.config.configuration.Config.with_overrides`).
    overhangs : sequence of float
        c_b / c_f values.
    delta_a : callable
        Actuator input [rad] versus azimuth.
    controls : dict
        Keyword arguments of :func:`rotor_section_motion` (advance_ratio,
        collective, cyclic_cos, cyclic_sin, inflow, coning).
    aero_factory : callable, optional
        ``aero_factory(cfg) -> section model``; default the thin-airfoil model
        with the configured lift slope.
    n_psi : int, optional
        Collocation azimuths per revolution.

    Returns
    -------
    pandas.DataFrame
        ``overhang, half_peak_to_peak_deg, peak_power, mean_power`` [W].
    """
    from ..aero.thin_airfoil import ThinAirfoilFlap

    def default(c):
        return ThinAirfoilFlap(c.flap.chord_ratio, c.flap.overhang,
                               lift_slope=c.rotor.lift_slope)

    aero_factory = aero_factory or default
    motion = rotor_motion(cfg.rotor, cfg.blade, **controls)
    rows = []
    for ov in overhangs:
        c = cfg.with_overrides({"flap.overhang": float(ov)})
        out = flap_response(aero_factory(c), flap_properties(c), motion, delta_a,
                            rotor_speed=c.rotor.rotor_speed, density=c.rotor.air_density,
                            speed_of_sound=c.rotor.speed_of_sound, n_psi=n_psi)
        rows.append({"overhang": float(ov),
                     "half_peak_to_peak_deg": np.rad2deg(out.half_peak_to_peak),
                     "peak_power": out.peak_power, "mean_power": out.mean_power})
    return pd.DataFrame(rows)
