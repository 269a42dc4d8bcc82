"""The trailing-edge flap and its actuator: the flap's equation, written once (theory 4).

The flap is a rigid chordwise body hinged to the blade section, driven
through the actuator: a torsional spring ``k_a`` and damper ``c_a`` between
the flap and the actuator base, whose angle ``delta_a(psi)`` is the input.
Its equation comes from the kinetic energy of the flap riding on the
rotating, bending and twisting blade (Lagrange / Hamilton), per unit span:

``I_h (delta** + Theta**) - S_f eta_h Theta** - S_f (w** cos Theta - v** sin Theta)
+ Omega^2 [I_h sin Phi cos Phi - S_f eta_h cos Theta sin Phi]
- Omega^2 S_f r (w' cos Theta - v' sin Theta) + ... = H_aero``

integrated over the flap span, plus
``I_a delta** + k_a (delta - delta_a) + c_a (delta* - delta_a*)`` with ``I_a``
the actuator's moving parts reflected to the hinge (whole flap).
``Theta = theta + phi`` is the section pitch, ``Phi = Theta + delta`` the
flap's own pitch, ``eta_h`` the hinge position ahead of the elastic axis
(negative: the hinge is aft), ``S_f = m_f c_cg`` and ``I_h`` the flap's first
and second mass moments about its hinge (``c_cg`` positive aft).

:func:`flap_moments` is that equation's left-hand side per unit span, term by
term, together with the flap's reactions on the blade: the rotor model's
station terms (:mod:`tefcore.model.station_terms`, rotor units) and the
section analyses of Figs. 5-7 (:mod:`tefcore.model.section_response`, SI) both
use it; :func:`propeller_moment` is its centrifugal part alone.  The
aerodynamic hinge moment ``H_aero`` is the section model's
(``loads()["hinge_moment"]``, :mod:`tefcore.aero`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..structure.beam_element import gauss_legendre

__all__ = ["FlapProperties", "centrifugal_hinge_moment", "flap_moments",
           "flap_natural_frequency", "flap_properties", "propeller_moment"]


@dataclass(frozen=True)
class FlapProperties:
    """Mass, geometry and actuator of one trailing-edge flap (SI).

    Attributes
    ----------
    span : float
        Flap span [m].
    radius_mid : float
        Radial station of the flap mid-span [m].
    chord : float
        Blade chord c [m].
    chord_ratio, overhang, cg_offset : float
        c_f/c, c_b/c_f (hinge aft of the flap nose), c_cg/c_f (CG aft of hinge).
    hinge_from_ea : float
        eta_h, chordwise hinge position from the elastic axis, positive toward
        the leading edge [m] (negative for a trailing-edge flap).
    mass, inertia_cg : float
        Flap mass [kg/m] and inertia about its CG [kg m^2/m] per unit span.
    k_a, c_a : float
        Actuator torsional stiffness [N m/rad] and damping [N m s/rad] of the
        whole flap.
    reflected_inertia : float
        ``I_a``: the actuator's moving parts reflected to the hinge [kg m^2],
        of the whole flap; adds to ``b_f I_h`` in the ``delta**`` term only
        (docs/theory.md 4.1).  Default 0 (not modelled).
    """

    span: float
    radius_mid: float
    chord: float
    chord_ratio: float
    overhang: float
    cg_offset: float
    hinge_from_ea: float
    mass: float
    inertia_cg: float
    k_a: float
    c_a: float
    reflected_inertia: float = 0.0

    @property
    def flap_chord(self) -> float:
        return self.chord_ratio * self.chord

    @property
    def first_moment(self) -> float:
        """S_f = m_f c_cg per unit span [kg m / m] (positive: CG aft of hinge)."""
        return self.mass * self.cg_offset * self.flap_chord

    @property
    def inertia_hinge(self) -> float:
        """I_h = I_cg + m_f c_cg^2 per unit span [kg m^2 / m]."""
        return self.inertia_cg + self.mass * (self.cg_offset * self.flap_chord) ** 2

    def stations(self, n: int = 3):
        """Gauss-Legendre stations [m] and weights [m] over the flap span."""
        g, w = gauss_legendre(n)
        return self.radius_mid + 0.5 * self.span * g, 0.5 * self.span * w


def flap_properties(cfg) -> FlapProperties:
    """Flap properties of a configuration.

    The hinge lies ``overhang * c_f`` behind the flap nose, which is at
    ``(1 - E) c`` from the leading edge; the elastic axis is at
    ``rotor.elastic_axis * c``.  Mass and inertia are per span at the
    configured chord (:attr:`tefcore.config.sections.FlapConfig.mass_per_span`).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the flap, its actuator and the rotor's radius,
        chord and elastic axis.

    Returns
    -------
    FlapProperties
    """
    r, f = cfg.rotor, cfg.flap
    # per-span mass and inertia at the configured chord (flap.scaling rule); the
    # same numbers are lumped into the blade section (tefcore.structure.section_inertia)
    return FlapProperties(span=f.span * r.radius, radius_mid=f.midspan * r.radius,
                          chord=r.chord, chord_ratio=f.chord_ratio, overhang=f.overhang,
                          cg_offset=f.cg_offset,
                          hinge_from_ea=(r.elastic_axis - f.hinge_position) * r.chord,
                          mass=f.mass_per_span, inertia_cg=f.inertia_cg_per_span,
                          k_a=cfg.actuator.stiffness, c_a=cfg.actuator.damping,
                          reflected_inertia=cfg.actuator.reflected_inertia)


def _flap_pitch(c, s, cd, sd):
    """``sin Phi, cos Phi`` of the flap's pitch ``Phi = Theta + delta`` by angle addition."""
    return s * cd + c * sd, c * cd - s * sd


def _propeller(ih, sf, eta, c, s_f, c_f):
    """``I_h sin Phi cos Phi - S_f eta_h cos Theta sin Phi``."""
    return ih * s_f * c_f - sf * eta * c * s_f


def propeller_moment(inertia_hinge, first_moment, hinge_from_ea, pitch, delta):
    """Centrifugal (propeller) moment on the flap per unit span and per Omega^2.

    ``I_h sin Phi cos Phi - S_f eta_h cos Theta sin Phi`` with
    ``Phi = Theta + delta``, in whatever consistent units the inertias carry
    (SI in the section analyses, rotor units in the coupled model:
    :func:`flap_moments`, which computes it the same way). It sits on the
    inertial side of the flap equation, so it restores the flap toward the
    plane of rotation.

    Parameters
    ----------
    inertia_hinge : float
        I_h, flap inertia about the hinge per unit span.
    first_moment : float
        S_f, flap first moment about the hinge per unit span (positive: CG aft).
    hinge_from_ea : float
        eta_h, hinge position from the elastic axis, positive toward the leading edge.
    pitch : float or numpy.ndarray
        Section pitch Theta [rad].
    delta : float or numpy.ndarray
        Flap deflection [rad].

    Returns
    -------
    float or numpy.ndarray

    Examples
    --------
    A flap with its CG on the hinge (``S_f = 0``) at ``Phi = 45 deg``:
    ``I_h sin Phi cos Phi = I_h / 2``.

    >>> round(float(propeller_moment(2.0, 0.0, -0.1, np.pi / 8, np.pi / 8)), 12)
    1.0
    """
    c, s = np.cos(pitch), np.sin(pitch)
    s_f, c_f = _flap_pitch(c, s, np.cos(delta), np.sin(delta))
    return _propeller(inertia_hinge, first_moment, hinge_from_ea, c, s_f, c_f)


def flap_moments(inertia_hinge, first_moment, hinge_from_ea, x, pitch, pitch_accel,
                 plunge_accel, delta, delta_rate, delta_accel, *, slope, v=0.0, lag_slope=0.0,
                 lag_accel=0.0, lag_slope_rate=0.0, slope_rate=0.0, omega=None,
                 sin=np.sin, cos=np.cos):
    """The flap's equation per unit span, term by term, and its reactions on the blade.

    The left-hand side of the flap equation (module docstring; docs/theory.md
    4.1) and the flap's delta-dependent inertial loads on the blade (4.2) at
    one or many stations and azimuths.  In rotor units (the coupled model:
    derivatives per azimuth, lengths per R) ``omega`` is None; in SI (time
    derivatives, metres) it is the rotor speed, which scales the centrifugal
    terms by ``Omega^2`` and the Coriolis terms by ``Omega``.

    Parameters
    ----------
    inertia_hinge, first_moment, hinge_from_ea : float
        ``I_h``, ``S_f``, ``eta_h`` per unit span (module docstring).
    x : float or numpy.ndarray
        Radial station.
    pitch, pitch_accel : numpy.ndarray
        Section pitch ``Theta`` and its second derivative.
    plunge_accel : numpy.ndarray
        Flapwise acceleration ``w**`` of the section.
    delta, delta_rate, delta_accel : numpy.ndarray
        Flap deflection and its derivatives.
    slope : numpy.ndarray
        Flap slope ``w' + beta_p``.
    v, lag_slope, lag_accel, lag_slope_rate, slope_rate : numpy.ndarray or float, optional
        Lag deflection ``v``, slope ``v'``, acceleration ``v**``, slope rate
        ``v'*`` and flap slope rate ``w'*`` (0: a section without lag motion).
    omega : float, optional
        Rotor speed in SI; None in rotor units.
    sin, cos : callable, optional
        The sine and cosine (the coupled model passes its complex-step forms).

    Returns
    -------
    flap_row : dict of str to numpy.ndarray
        The named pieces of the flap equation's left-hand side (the
        aerodynamic hinge moment and the actuator aside): ``flap inertia``,
        ``flap inertial coupling to torsion``, ``flap inertial coupling to
        bending``, ``flap centrifugal``, ``flap Coriolis``.
    blade : list of (str, str, numpy.ndarray)
        ``(piece, field, load)``: the flap's loads on the blade through the
        fields ``w, v, phi, dw, dv`` of the mode shapes.

    Examples
    --------
    A balanced flap (``S_f = 0``) at rest in the plane of rotation
    (``Theta = 0``) deflected by ``delta``: only the propeller moment
    ``I_h sin delta cos delta`` remains.

    >>> row, _ = flap_moments(2.0, 0.0, -0.1, 0.8, np.zeros(1), np.zeros(1), np.zeros(1),
    ...                       np.full(1, 0.1), np.zeros(1), np.zeros(1), slope=np.zeros(1))
    >>> round(float(row["flap centrifugal"][0]), 12) == round(float(np.sin(0.2)), 12)
    True
    """
    ih, sf, eta = inertia_hinge, first_moment, hinge_from_ea
    dl, dld, dldd = delta, delta_rate, delta_accel
    th, th_dd, wdd = pitch, pitch_accel, plunge_accel
    c, s = cos(th), sin(th)
    cd, sd = cos(dl), sin(dl)
    ipe = ih - sf * eta
    s_f, c_f = _flap_pitch(c, s, cd, sd)
    s2, c2 = 2 * s * c, c * c - s * s                         # sin, cos 2 Theta
    m_cf = ih * (s_f * c_f - s * c) - eta * sf * ((s2 * cd + c2 * sd) - s2)
    prop = _propeller(ih, sf, eta, c, s_f, c_f)
    centrifugal = prop - sf * x * (slope * c - lag_slope * s) - sf * v * s
    coriolis = ipe * (lag_slope_rate * s2 + slope_rate * (1 - c2))
    if omega is not None:                   # SI: Omega^2 and Omega per the derivatives
        centrifugal, coriolis = omega**2 * centrifugal, omega * coriolis
    flap_row = {
        "flap inertia": ih * dldd,
        "flap inertial coupling to torsion": ipe * th_dd,
        "flap inertial coupling to bending": -sf * (wdd * c - lag_accel * s),
        "flap centrifugal": centrifugal,
        "flap Coriolis": coriolis,
    }
    if omega is not None:
        m_cf, dl, dld = omega**2 * m_cf, omega**2 * dl, omega * dld
    blade = [("flap inertial coupling to bending", "w", -sf * c * dldd),
             ("flap inertial coupling to bending", "v", sf * s * dldd),
             ("flap inertial coupling to torsion", "phi", ipe * dldd),
             ("flap centrifugal", "v", -sf * s * dl),
             ("flap centrifugal", "phi", m_cf),
             ("flap centrifugal", "dw", -sf * x * c * dl),
             ("flap centrifugal", "dv", sf * x * s * dl),
             ("flap Coriolis", "dw", -2 * ipe * s * s * dld),
             ("flap Coriolis", "dv", -2 * ipe * s * c * dld)]
    return flap_row, blade


def centrifugal_hinge_moment(props: FlapProperties, rotor_speed, pitch, delta):
    """Centrifugal (propeller) moment on the flap per unit span [N m/m].

    Parameters
    ----------
    props : FlapProperties
        The flap (:func:`flap_properties`).
    rotor_speed : float
        Omega [rad/s].
    pitch : float or numpy.ndarray
        Section pitch Theta [rad].
    delta : float or numpy.ndarray
        Flap deflection [rad].

    Returns
    -------
    float or numpy.ndarray
        ``Omega^2`` times :func:`propeller_moment` of the flap.
    """
    return rotor_speed**2 * propeller_moment(props.inertia_hinge, props.first_moment,
                                             props.hinge_from_ea, pitch, delta)


def flap_natural_frequency(props: FlapProperties, rotor_speed: float, pitch: float = 0.0):
    """Natural frequency of the flap on a rigid, non-moving section [rad/s].

    ``omega_f^2 = [k_a + b_f Omega^2 (I_h cos 2Theta - S_f eta_h cos^2 Theta)] / (b_f I_h + I_a)``,
    the linearisation of :func:`centrifugal_hinge_moment`; in vacuum
    (no aerodynamic stiffness or apparent mass).  The actuator's reflected
    inertia ``I_a`` adds to the flap's inertia only: its centrifugal moment
    is neglected (docs/theory.md 4.1).

    Parameters
    ----------
    props : FlapProperties
        The flap (:func:`flap_properties`).
    rotor_speed : float
        Omega [rad/s].
    pitch : float, optional
        Section pitch Theta [rad].

    Returns
    -------
    float
        omega_f [rad/s].

    Examples
    --------
    >>> p = FlapProperties(span=1.0, radius_mid=4.0, chord=0.25, chord_ratio=0.3,
    ...                    overhang=0.0, cg_offset=0.0, hinge_from_ea=-0.1, mass=0.5,
    ...                    inertia_cg=1e-4, k_a=100.0, c_a=0.0)
    >>> round(float(flap_natural_frequency(p, 0.0)), 6)
    1000.0
    """
    k_cf = rotor_speed**2 * (props.inertia_hinge * np.cos(2 * pitch)
                             - props.first_moment * props.hinge_from_ea * np.cos(pitch) ** 2)
    return np.sqrt((props.k_a + props.span * k_cf)
                   / (props.span * props.inertia_hinge + props.reflected_inertia))


