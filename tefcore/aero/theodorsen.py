"""Theodorsen's flapped thin airfoil, quasi-steady (docs/theory.md section 3).

Three things live here, all in Theodorsen's own variables (semichord ``b``,
positions in semichords from mid-chord, positive aft):

* :func:`t_functions` -- the T-functions ``T1 .. T14`` of NACA Report 496
  (1935) from their closed forms, for a hinge at ``x = c`` and an axis at
  ``x = a``.  ``T6`` is not listed: no load below uses it.
* :func:`quasi_steady_loads` -- Theodorsen's lift, moment and hinge moment with
  ``C(k) = 1``, plus the normal force on the flap alone (derived for tefcore,
  section 3.4 of the theory), in **Theodorsen's sign conventions**:
  ``h`` and the forces ``P``, ``P_flap`` positive *down*, ``alpha`` nose up,
  ``beta`` trailing edge down, ``M_alpha`` nose up about ``a`` and ``M_beta``
  about the hinge in the ``beta`` sense.  :func:`motion_to_theodorsen` and
  :func:`loads_to_tefcore` convert from/to tefcore conventions (plunge and
  lift positive *up*).
* A numerical reference, independent of the closed forms:
  :func:`kutta_circulation`, :func:`apparent_mass_potential` and
  :func:`quadrature_loads` compute the quasi-steady loads of an arbitrary
  upwash distribution by quadrature of the thin-airfoil pressure
  ``dp = rho U gamma_K[w] + rho d/dt dphi_nc[w]``.  The tests use them to check
  every closed form.

Examples
--------
The flap effectiveness of a 20 % flap (hinge at ``c = 0.6``):

>>> t = t_functions(0.6, -0.5)
>>> round(float(2 * t["T10"]), 5)          # dC_l/dbeta
3.45459
>>> round(float(-t["T12"] / 2 / 0.2**2), 5)  # C_h,alpha on flap chord
-0.49938
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "T_NAMES",
    "apparent_mass_potential",
    "kutta_circulation",
    "loads_to_tefcore",
    "motion_to_theodorsen",
    "quadrature_loads",
    "quasi_steady_loads",
    "t_functions",
]

T_NAMES = ("T1", "T2", "T3", "T4", "T5", "T7", "T8", "T9", "T10", "T11", "T12", "T13",
           "T14")


def _hinge(c):
    c = np.asarray(c, dtype=float)
    if not np.all(np.isfinite(c)) or np.any(np.abs(c) >= 1.0):
        raise ValueError(f"hinge location c must lie in (-1, 1) semichords, got {c}")
    return c


def t_functions(c, a=0.0) -> dict[str, np.ndarray]:
    """Theodorsen's T-functions for hinge ``c`` and axis ``a`` (semichords).

    With ``s = sqrt(1 - c^2)`` and ``mu = arccos c``::

        T1  = -s (2 + c^2)/3 + c mu
        T2  = c (1 - c^2) - s (1 + c^2) mu + c mu^2
        T3  = -(1/8 + c^2) mu^2 + (1/4) c s mu (7 + 2 c^2) - (1/8)(1 - c^2)(5 c^2 + 4)
        T4  = -mu + c s
        T5  = -(1 - c^2) - mu^2 + 2 c s mu
        T7  = -(1/8 + c^2) mu + (1/8) c s (7 + 2 c^2)
        T8  = -s (2 c^2 + 1)/3 + c mu
        T9  = (s^3/3 + a T4) / 2
        T10 = s + mu
        T11 = mu (1 - 2c) + s (2 - c)
        T12 = s (2 + c) - mu (2c + 1)
        T13 = (-T7 - (c - a) T1) / 2
        T14 = 1/16 + a c / 2

    Vectorised: ``c`` and ``a`` broadcast.  ``-1 < c < 1`` (ValueError
    otherwise).  Section 3.2 of the theory gives the integrals they come from.

    >>> t = t_functions(-1 + 1e-12)        # hinge at the leading edge: whole airfoil
    >>> round(float(t["T10"]), 6), round(float(t["T4"]), 6)
    (3.141593, -3.141593)

    Parameters
    ----------
    c : float or array_like
        Flap hinge, semichords from mid-chord (aft positive), ``-1 < c < 1``.
    a : float or array_like, optional
        Pitch axis, semichords from mid-chord.

    Returns
    -------
    dict
        ``"T1"`` ... ``"T14"`` (no T6), broadcast arrays.
    """
    c = _hinge(c)
    a = np.asarray(a, dtype=float)
    c, a = np.broadcast_arrays(c, a)
    s = np.sqrt(1.0 - c * c)
    mu = np.arccos(c)
    t = {}
    t["T1"] = -s * (2.0 + c * c) / 3.0 + c * mu
    t["T2"] = c * (1.0 - c * c) - s * (1.0 + c * c) * mu + c * mu * mu
    t["T3"] = (-(0.125 + c * c) * mu * mu + 0.25 * c * s * mu * (7.0 + 2.0 * c * c)
               - 0.125 * (1.0 - c * c) * (5.0 * c * c + 4.0))
    t["T4"] = -mu + c * s
    t["T5"] = -(1.0 - c * c) - mu * mu + 2.0 * c * s * mu
    t["T7"] = -(0.125 + c * c) * mu + 0.125 * c * s * (7.0 + 2.0 * c * c)
    t["T8"] = -s * (2.0 * c * c + 1.0) / 3.0 + c * mu
    t["T9"] = 0.5 * (s**3 / 3.0 + a * t["T4"])
    t["T10"] = s + mu
    t["T11"] = mu * (1.0 - 2.0 * c) + s * (2.0 - c)
    t["T12"] = s * (2.0 + c) - mu * (2.0 * c + 1.0)
    t["T13"] = 0.5 * (-t["T7"] - (c - a) * t["T1"])
    t["T14"] = 1.0 / 16.0 + 0.5 * a * c
    return {k: v[()] for k, v in t.items()}


def quasi_steady_loads(*, alpha, alpha_dot, alpha_ddot, h, h_dot, h_ddot, beta, beta_dot,
                       beta_ddot, U, b, rho, a, c) -> dict[str, np.ndarray]:
    """Theodorsen's plain-flap loads per unit span with ``C(k) = 1`` (SI).

    Theodorsen's conventions: ``h`` plunge positive DOWN, ``alpha`` nose up,
    ``beta`` flap angle relative to the airfoil, trailing edge down; ``a``
    axis and ``c`` hinge in semichords from mid-chord (aft positive).  Dots
    are time derivatives.  With
    ``Q = U alpha + h_dot + b (1/2 - a) alpha_dot + T10 U beta / pi + b T11 beta_dot / (2 pi)``::

        P       = -rho b^2 [U pi alpha_dot + pi h_ddot - pi b a alpha_ddot
                            - U T4 beta_dot - T1 b beta_ddot] - 2 pi rho U b Q
        M_alpha = -rho b^2 [pi (1/2 - a) U b alpha_dot + pi b^2 (1/8 + a^2) alpha_ddot
                            + (T4 + T10) U^2 beta + (T1 - T8 - (c - a) T4 + T11/2) U b beta_dot
                            - (T7 + (c - a) T1) b^2 beta_ddot - a pi b h_ddot]
                  + 2 pi rho U b^2 (a + 1/2) Q
        M_beta  = -rho b^2 [(-2 T9 - T1 + T4 (a - 1/2)) U b alpha_dot + 2 T13 b^2 alpha_ddot
                            + U^2 beta (T5 - T4 T10)/pi - U b beta_dot T4 T11 / (2 pi)
                            - T3 b^2 beta_ddot / pi - T1 b h_ddot]
                  - rho U b^2 T12 Q
        P_flap  = -2 rho U b [(mu - s)(U alpha + h_dot) + b (mu (1 - a) + s (a - c)) alpha_dot
                              + mu^2 U beta / pi + b mu (1 - c) T10 beta_dot / pi]
                  - rho b^2 [-T4 h_ddot + 2 T9 b alpha_ddot - T2 b beta_ddot / pi]

    ``P`` (lift) and ``P_flap`` (normal force on the flap ``c < x < 1`` alone)
    are positive down, ``M_alpha`` nose up about ``a``, ``M_beta`` about the
    hinge, positive in the ``beta`` sense (trailing edge down); ``s`` and
    ``mu`` as in :func:`t_functions`.  ``h`` itself does not enter (no
    plunge stiffness in potential flow); it is accepted for completeness.
    ``P_flap`` is derived in section 3.4 of the theory (not in NACA 496).

    Parameters
    ----------
    alpha, alpha_dot, alpha_ddot : float or array_like
        Pitch angle, nose up [rad], and its time derivatives.
    h, h_dot, h_ddot : float or array_like
        Plunge, positive down [m], and its time derivatives.
    beta, beta_dot, beta_ddot : float or array_like
        Flap angle, trailing edge down [rad], and its time derivatives.
    U : float or array_like
        Airspeed [m/s].
    b : float
        Semichord [m].
    rho : float
        Air density [kg/m^3].
    a : float
        Pitch axis, semichords from mid-chord (aft positive).
    c : float
        Flap hinge, semichords from mid-chord, ``-1 < c < 1``.

    Returns
    -------
    dict
        ``'P', 'M_alpha', 'M_beta', 'P_flap'`` (broadcast arrays).
    """
    del h  # translation invariance: the loads do not depend on h itself
    t = t_functions(c, a)
    c = np.asarray(c, dtype=float)
    a = np.asarray(a, dtype=float)
    s = np.sqrt(1.0 - c * c)
    mu = np.arccos(c)
    pi = math.pi
    T1, T2, T3, T4, T5 = t["T1"], t["T2"], t["T3"], t["T4"], t["T5"]
    T7, T8, T9, T10, T11 = t["T7"], t["T8"], t["T9"], t["T10"], t["T11"]
    T12, T13 = t["T12"], t["T13"]
    q = (U * alpha + h_dot + b * (0.5 - a) * alpha_dot + T10 * U * beta / pi
         + b * T11 * beta_dot / (2 * pi))
    p = (-rho * b**2 * (U * pi * alpha_dot + pi * h_ddot - pi * b * a * alpha_ddot
                        - U * T4 * beta_dot - T1 * b * beta_ddot)
         - 2 * pi * rho * U * b * q)
    m_alpha = (-rho * b**2 * (pi * (0.5 - a) * U * b * alpha_dot
                              + pi * b**2 * (0.125 + a * a) * alpha_ddot
                              + (T4 + T10) * U**2 * beta
                              + (T1 - T8 - (c - a) * T4 + 0.5 * T11) * U * b * beta_dot
                              - (T7 + (c - a) * T1) * b**2 * beta_ddot
                              - a * pi * b * h_ddot)
               + 2 * pi * rho * U * b**2 * (a + 0.5) * q)
    m_beta = (-rho * b**2 * ((-2 * T9 - T1 + T4 * (a - 0.5)) * U * b * alpha_dot
                             + 2 * T13 * b**2 * alpha_ddot
                             + U**2 * beta * (T5 - T4 * T10) / pi
                             - U * b * beta_dot * T4 * T11 / (2 * pi)
                             - T3 * b**2 * beta_ddot / pi
                             - T1 * b * h_ddot)
              - rho * U * b**2 * T12 * q)
    p_flap = (-2 * rho * U * b * ((mu - s) * (U * alpha + h_dot)
                                  + b * (mu * (1 - a) + s * (a - c)) * alpha_dot
                                  + mu**2 * U * beta / pi
                                  + b * mu * (1 - c) * T10 * beta_dot / pi)
              - rho * b**2 * (-T4 * h_ddot + 2 * T9 * b * alpha_ddot - T2 * b * beta_ddot / pi))
    out = np.broadcast_arrays(p, m_alpha, m_beta, p_flap)
    return dict(zip(("P", "M_alpha", "M_beta", "P_flap"), (o[()] for o in out), strict=True))


def motion_to_theodorsen(*, alpha, alpha_rate, alpha_accel, plunge_rate, plunge_accel, delta,
                         delta_rate, delta_accel, plunge=0.0) -> dict:
    """tefcore section motion -> keyword arguments of :func:`quasi_steady_loads`.

    tefcore: ``plunge`` positive UP (``w``); Theodorsen: ``h`` positive down,
    so ``h = -plunge`` and likewise for its derivatives.  ``alpha`` (nose up)
    and ``delta`` (trailing edge down, Theodorsen's ``beta``) need no change.

    >>> motion_to_theodorsen(alpha=0.1, alpha_rate=0, alpha_accel=0, plunge_rate=2.0,
    ...                      plunge_accel=0, delta=0, delta_rate=0, delta_accel=0)["h_dot"]
    -2.0

    Parameters
    ----------
    alpha, alpha_rate, alpha_accel : float or array_like
        Angle of attack, nose up [rad], and its time derivatives.
    plunge_rate, plunge_accel : float or array_like
        Plunge velocity [m/s] and acceleration [m/s^2], positive up.
    delta, delta_rate, delta_accel : float or array_like
        Flap deflection, trailing edge down [rad], and its time derivatives.
    plunge : float or array_like, optional
        Plunge displacement [m], positive up (enters no load).

    Returns
    -------
    dict
        ``alpha, alpha_dot, alpha_ddot, h, h_dot, h_ddot, beta, beta_dot,
        beta_ddot``.
    """
    return {"alpha": alpha, "alpha_dot": alpha_rate, "alpha_ddot": alpha_accel,
            "h": -plunge, "h_dot": -plunge_rate, "h_ddot": -plunge_accel,
            "beta": delta, "beta_dot": delta_rate, "beta_ddot": delta_accel}


def loads_to_tefcore(loads: dict) -> dict:
    """Theodorsen loads -> tefcore: lift and flap lift positive UP.

    ``lift = -P``, ``flap_lift = -P_flap``; ``moment = M_alpha`` (nose up in
    both) and ``hinge_moment = M_beta`` (trailing edge down in both).

    Parameters
    ----------
    loads : dict
        ``P, M_alpha, M_beta, P_flap`` of :func:`quasi_steady_loads`.

    Returns
    -------
    dict
        ``lift, moment, hinge_moment, flap_lift`` in tefcore's signs.
    """
    return {"lift": -loads["P"], "moment": loads["M_alpha"],
            "hinge_moment": loads["M_beta"], "flap_lift": -loads["P_flap"]}


# ---------------------------------------------------------------------------
# Numerical reference: quadrature of the thin-airfoil pressure
# ---------------------------------------------------------------------------

def _tanh_sinh(step=1.0 / 24.0, zmax=3.4):
    """Tanh-sinh nodes on (0, 1): distances from both ends and weights.

    Distances are returned separately (not as 1 - x) so that logarithmic
    end-point singularities are evaluated without cancellation.
    """
    z = np.arange(-zmax, zmax + 0.5 * step, step)
    u = 0.5 * math.pi * np.sinh(z)
    left = 1.0 / (1.0 + np.exp(-2.0 * u))    # distance from the left end
    right = 1.0 / (1.0 + np.exp(2.0 * u))    # distance from the right end
    wgt = step * 0.5 * math.pi * np.cosh(z) / np.cosh(u) ** 2 / 2.0
    return left, right, wgt


_TS = _tanh_sinh()


def _segments(points):
    pts = np.unique(np.asarray(points, dtype=float))
    return list(zip(pts[:-1], pts[1:], strict=True))


def _theta_breaks(breaks):
    """Glauert angles ``theta = arccos(-x)`` of break points strictly inside (-1, 1)."""
    return [math.acos(-float(x)) for x in breaks if -1.0 < float(x) < 1.0]


def kutta_circulation(w, *, b=1.0, breaks=()) -> float:
    """Circulation ``Gamma`` of the steady Kutta solution for upwash ``w(x)``.

    ``Gamma = -2 b int_{-1}^{1} w(x) sqrt((1 + x)/(1 - x)) dx``, evaluated in
    Glauert's angle (``x = -cos theta``, integrand ``w (1 - cos theta)``) by
    tanh-sinh quadrature split at ``breaks`` (discontinuities of ``w``).
    ``w`` is a vectorised callable of ``x`` in semichords, positive UP
    (tefcore); ``Gamma > 0`` is clockwise (lift up).

    Parameters
    ----------
    w : callable
        Upwash ``w(x)`` [m/s], vectorised, ``x`` in semichords from mid-chord
        (aft positive), positive up.
    b : float, optional
        Semichord [m].
    breaks : sequence of float, optional
        Stations (semichords) where ``w`` or its derivative jumps (the flap
        hinge): the quadrature is split there.

    Returns
    -------
    float
        Gamma [m^2/s].
    """
    left, _, wgt = _TS
    total = 0.0
    for t0, t1 in _segments([0.0, math.pi, *_theta_breaks(breaks)]):
        th = t0 + (t1 - t0) * left
        total += (t1 - t0) * np.sum(wgt * w(-np.cos(th)) * (1.0 - np.cos(th)))
    return -2.0 * b * total


def apparent_mass_potential(w, x, *, b=1.0, breaks=()) -> np.ndarray:
    """Potential jump ``phi_upper - phi_lower`` of the non-circulatory flow.

    Theodorsen's source-sink representation of the flow with zero circulation
    around a plate whose surface moves with the upwash ``w(x)`` (positive up):
    ``dphi(x) = (2 b / pi) int_0^pi w(-cos t) ln|sin((theta - t)/2) / sin((theta + t)/2)|
    sin t dt`` with ``x = -cos theta``.  Evaluated by tanh-sinh quadrature on
    segments split at ``theta`` (log singularity) and at ``breaks``.  For
    ``w = 1``, ``dphi = -2 b sqrt(1 - x^2)``.

    Parameters
    ----------
    w : callable
        Upwash ``w(x)`` [m/s], vectorised, ``x`` in semichords from mid-chord
        (aft positive), positive up.
    x : float or array_like
        Stations (semichords) to evaluate at.
    b : float, optional
        Semichord [m].
    breaks : sequence of float, optional
        Stations (semichords) where ``w`` or its derivative jumps (the flap
        hinge): the quadrature is split there.

    Returns
    -------
    numpy.ndarray
        The potential jump at ``x`` [m^2/s].
    """
    left, right, wgt = _TS
    x = np.atleast_1d(np.asarray(x, dtype=float))
    out = np.empty(x.shape)
    tb = _theta_breaks(breaks)
    for k, xk in np.ndenumerate(x):
        if abs(xk) >= 1.0:
            out[k] = 0.0
            continue
        th = math.acos(-xk)
        total = 0.0
        for t0, t1 in _segments([0.0, math.pi, th, *tb]):
            span = t1 - t0
            t = t0 + span * left
            if t1 == th:
                dist = span * right           # theta - t, accurate near the singularity
            elif t0 == th:
                dist = span * left
            else:
                dist = np.abs(th - t)
            kern = np.log(np.sin(0.5 * dist)) - np.log(np.sin(0.5 * (th + t)))
            total += span * np.sum(wgt * w(-np.cos(t)) * kern * np.sin(t))
        out[k] = 2.0 * b / math.pi * total
    return out


def _x_nodes(lo, hi, breaks):
    """Nodes and weights for ``int_lo^hi f(x) dx`` in Glauert's angle (tanh-sinh)."""
    left, _, wgt = _TS
    t_lo, t_hi = math.acos(-lo), math.acos(-hi)
    inner = [t for t in _theta_breaks(breaks) if t_lo < t < t_hi]
    xs, ws = [], []
    for t0, t1 in _segments([t_lo, t_hi, *inner]):
        th = t0 + (t1 - t0) * left
        xs.append(-np.cos(th))
        ws.append((t1 - t0) * wgt * np.sin(th))
    return np.concatenate(xs), np.concatenate(ws)


def quadrature_loads(w, w_dot, *, c, a, U, b, rho, hinge=None) -> dict[str, float]:
    """Quasi-steady thin-airfoil loads of an upwash distribution, by quadrature.

    The pressure jump (lower minus upper) is
    ``dp(x) = rho U gamma_K[w](x) + rho dphi_nc[w_dot](x)``: the steady Kutta
    loading of the instantaneous upwash plus the apparent-mass pressure of its
    rate of change -- Theodorsen's loading with ``C(k) = 1``.  Moments of
    ``gamma_K`` are taken by parts through ``dphi_K = dphi_nc[w] + Gamma (1 -
    arccos(x)/pi)`` (the Kutta solution is the non-circulatory one plus the
    homogeneous ``Gamma / (pi sqrt(1 - x^2))``).

    Parameters
    ----------
    w, w_dot : callables
        Upwash ``w(x)`` [m/s] (positive UP, tefcore) and its time derivative,
        vectorised in ``x`` (semichords, -1 = leading edge); both may jump at
        ``c`` only.
    c : float
        Flap leading edge (kink of the camber line) in semichords.
    a : float
        Moment axis in semichords.
    U, b, rho : float
        Speed, semichord, density (SI).
    hinge : float, optional
        Hinge for the hinge moment, semichords (default ``c``).

    Returns
    -------
    dict with ``'lift'`` (up), ``'moment'`` (about ``a``, nose up),
    ``'flap_lift'`` (on ``c < x < 1``, up) and ``'hinge_moment'`` (about
    ``hinge``, positive trailing edge down), per unit span.
    """
    c = float(c)
    hinge = c if hinge is None else float(hinge)
    brk = (c,)
    gam = kutta_circulation(w, b=b, breaks=brk)
    x_fwd, w_fwd = _x_nodes(-1.0, c, ())
    x_flap, w_flap = _x_nodes(c, 1.0, ())
    x_all, w_all = np.concatenate([x_fwd, x_flap]), np.concatenate([w_fwd, w_flap])
    on_flap = np.arange(x_all.size) >= x_fwd.size
    nc_w = apparent_mass_potential(w, np.append(x_all, c), b=b, breaks=brk)
    nc_a = apparent_mass_potential(w_dot, x_all, b=b, breaks=brk)
    k_nodes = nc_w[:-1] + gam * (1.0 - np.arccos(x_all) / math.pi)
    k_hinge = nc_w[-1] + gam * (1.0 - math.acos(c) / math.pi)
    int_k_all = np.sum(w_all * k_nodes)
    int_k_flap = np.sum((w_all * k_nodes)[on_flap])
    nc_all = np.sum(w_all * nc_a)
    nc_all_x = np.sum(w_all * nc_a * x_all)
    nc_flap = np.sum((w_all * nc_a)[on_flap])
    nc_flap_x = np.sum((w_all * nc_a * x_all)[on_flap])
    # circulatory: rho U int gamma g dx with gamma = d(dphi_K)/dx, by parts
    lift = rho * U * gam + rho * b * nc_all
    moment = (-rho * U * b * (gam * (1.0 - a) - int_k_all)
              - rho * b**2 * (nc_all_x - a * nc_all))
    flap_lift = rho * U * (gam - k_hinge) + rho * b * nc_flap
    hinge_moment = (-rho * U * b * (gam * (1.0 - hinge) - k_hinge * (c - hinge) - int_k_flap)
                    - rho * b**2 * (nc_flap_x - hinge * nc_flap))
    return {"lift": lift, "moment": moment, "flap_lift": flap_lift,
            "hinge_moment": hinge_moment}
