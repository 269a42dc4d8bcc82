"""Section aerodynamics of an airfoil with a balanced trailing-edge flap.

docs/theory.md section 3.  Quasi-steady thin-airfoil theory (Theodorsen with
``C(k) = 1``) for a flap of chord ratio ``E = c_f/c`` whose hinge lies
``overhang * c_f`` behind the flap nose (aerodynamic balance, paper Fig. 2).

Conventions (tefcore): ``alpha`` nose up, ``delta`` (the paper's delta_f)
trailing edge down, plunge positive UP, lift and flap lift positive up,
moments nose up / trailing edge down.  All coefficients are normalised by the
BLADE chord ``c`` and ``q = rho U^2 / 2``::

    C_l  = L / (q c)          C_m = M / (q c^2)   (about ``axis``; static: 1/4 chord)
    C_lf = L_f / (q c)        C_h = H / (q c^2)   (about the hinge)
    C_d  = cd0 + cd1 alpha + cd2 alpha^2

so that the flap-chord hinge-moment coefficient is ``C_h / E^2`` and the
flap lift on the flap chord ``C_lf / E``.

Model (section 3.5 of the theory):

* The flap nose ``x_n = 1 - E`` (chord fraction from the leading edge) is the
  kink of the mean line: the balance nose is sealed inside the blade contour,
  so the stream sees the plain flap deflected about its nose (Theodorsen hinge
  ``c = 2 x_n - 1``).
* The flap is a rigid body rotating about the hinge ``x_h = x_n + overhang E``:
  the surface velocity of the ``delta_rate`` motion is that of rotation about
  the hinge, and the hinge moment is taken about it,
  ``H_h = H_n + c_b L_f`` (``c_b = overhang E c``).  Then ``H_h`` is the
  generalised force of ``delta`` and the apparent-mass matrix is symmetric.
* :func:`section_loads` splits the loads into the STATIC coefficients of the
  model at the quasi-steady angle of attack
  ``alpha_eff = alpha - plunge_rate/U + (b/U)(1/2 - a) alpha_rate``
  (3/4-chord upwash) and ``delta``, plus thin-airfoil increments: the
  zero-lift pitch-rate loading, the ``delta_rate`` circulatory loading
  (circulatory, Prandtl-Glauert scaled) and all apparent-mass terms (not
  scaled).  A C81 table model reuses it with its own static coefficients.

Examples
--------
>>> m = ThinAirfoilFlap(0.35, 0.29, compressibility=False)
>>> st = m.static_coefficients(0.0, 0.0, np.radians(1.0))
>>> round(float(st["cl"] / np.radians(1.0)), 4)     # dC_l/d delta = 2 T10
4.4401
>>> out = m.loads(alpha=0.05, alpha_rate=0.0, alpha_accel=0.0, plunge_rate=0.0,
...               plunge_accel=0.0, delta=0.0, delta_rate=0.0, delta_accel=0.0,
...               velocity=100.0, density=1.2, chord=0.254)
>>> round(float(out["cl"]), 6) == round(2 * np.pi * 0.05, 6)
True
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ..config.sections import MACH_MAX
from .theodorsen import t_functions

__all__ = ["MACH_CLIP", "MACH_MAX", "ThinAirfoilFlap", "prandtl_glauert", "section_loads"]

#: Mach numbers above this are clipped in the Prandtl-Glauert factor (max 2.294).
MACH_CLIP = 0.9
# MACH_MAX (0.99): Mach numbers above it are rejected (ValueError); it lives with
# the configuration's checks, which hold the advancing tip below it


def prandtl_glauert(mach) -> np.ndarray:
    """Prandtl-Glauert factor ``1 / sqrt(1 - M^2)`` with ``M`` clipped at ``MACH_CLIP``.

    ``0 <= M <= MACH_MAX`` (0.99), else ValueError; ``M`` in (0.9, 0.99] gives
    the factor at 0.9 (linear theory is meaningless there anyway).

    >>> round(float(prandtl_glauert(0.6)), 12)
    1.25
    >>> float(prandtl_glauert(0.95)) == float(prandtl_glauert(0.9))
    True

    Parameters
    ----------
    mach : float or array_like
        Mach number.

    Returns
    -------
    numpy.ndarray
    """
    m = _numeric(mach)
    if np.iscomplexobj(m):
        # a complex-step derivative (tefcore.model.jacobian): the range is
        # that of the real part, and the clipped factor is constant
        x = m.real
        pg = prandtl_glauert(x)
        # first order in the imaginary part, real arithmetic: d pg / dM = M pg^3
        return (pg + 1j * np.where(x > MACH_CLIP, 0.0, m.imag * x * pg**3))[()]
    # min/max propagate NaN, and every comparison with NaN is False
    if m.size and not (m.min() >= 0.0 and m.max() <= MACH_MAX):
        bad = ~((m >= 0.0) & (m <= MACH_MAX))
        worst = m[bad][np.argmax(np.abs(np.nan_to_num(m[bad], nan=np.inf)))]
        raise ValueError(f"mach must lie in [0, {MACH_MAX}], got {worst:.6g}"
                         + (f" ({int(bad.sum())} of {m.size} values outside)" if m.size > 1
                            else ""))
    m = np.minimum(m, MACH_CLIP)
    return (1.0 / np.sqrt(1.0 - m * m))[()]


def _numeric(value):
    """A float array, or a complex one for complex input (complex-step derivatives:
    every load is analytic in its inputs)."""
    v = np.asarray(value)
    return v if v.dtype.kind == "c" else np.asarray(v, dtype=float)


def _geometry(chord_ratio, overhang):
    """Validated (E, overhang, c, d): Theodorsen nose ``c`` and hinge offset ``d`` (semichords)."""
    e = float(chord_ratio)
    o = float(overhang)
    if not (0.0 < e < 1.0):
        raise ValueError(f"chord_ratio must lie in (0, 1) (flap chord / blade chord), got {e}")
    if not (0.0 <= o < 1.0):
        raise ValueError(f"overhang must lie in [0, 1) (hinge offset behind the flap nose / "
                         f"flap chord), got {o}")
    return e, o, 1.0 - 2.0 * e, 2.0 * o * e


@functools.lru_cache(maxsize=64)
def _influence(c: float):
    """Steady (``S``) and apparent-mass (``N``) influence matrices for a kink at ``c``.

    Upwash basis ``e = (1, x, H, (x - c) H)`` (``H`` = 1 on the flap ``x > c``),
    weight basis the same.  For ``w = W_i e_i`` (velocity) and the semichord ``b``:
    ``int gamma_K[w] e_k dx = b W_i S[i, k]`` and
    ``int dphi_nc[w] e_k dx = b^2 W_i N[i, k]`` (``x`` in semichords, section 3.3).
    """
    t = t_functions(c)
    s, mu, pi = math.sqrt(1.0 - c * c), math.acos(c), math.pi
    T1, T2, T3, T4, T5 = (float(t[k]) for k in ("T1", "T2", "T3", "T4", "T5"))
    T7, T10, T11 = float(t["T7"]), float(t["T10"]), float(t["T11"])
    n = np.array([
        [-pi, 0.0, T4, T1],
        [0.0, -pi / 8.0, -s**3 / 3.0, T7 + c * T1],
        [T4, -s**3 / 3.0, T5 / pi, T2 / pi],
        [T1, T7 + c * T1, T2 / pi, T3 / pi],
    ])
    gamma = np.array([-2.0 * pi, -pi, -2.0 * T10, -T11])        # Kutta circulation / b
    at_hinge = np.array([-2.0 * s, -c * s, -2.0 * mu * s / pi, -s * (s - c * mu) / pi])
    sm = np.empty((4, 4))
    sm[:, 0] = gamma
    sm[:, 1] = -n[:, 0]
    sm[:, 2] = gamma * mu / pi - at_hinge
    sm[:, 3] = gamma * (s - c * mu) / pi - n[:, 2]
    sm.setflags(write=False)
    n.setflags(write=False)
    return sm, n


def _finite(name, value, positive=False):
    v = _numeric(value)
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} contains NaN or infinite values")
    if positive and np.any(v <= 0.0):
        raise ValueError(f"{name} must be positive, got {value}")
    return v


class ThinAirfoilFlap:
    """Quasi-steady thin-airfoil (Theodorsen, C(k)=1) airfoil with a balanced TEF.

    Parameters
    ----------
    chord_ratio : float
        Flap chord / blade chord ``E``, in (0, 1).
    overhang : float
        Hinge offset behind the flap nose / flap chord (``c_b / c_f``), in [0, 1);
        0 is a plain flap hinged at its nose (Theodorsen).
    cd0, cd1, cd2 : float
        Drag polar ``C_d = cd0 + cd1 alpha + cd2 alpha^2`` (alpha in rad).  No
        ``delta`` term: thin-airfoil theory has no drag and the profile drag
        increment of a few degrees of flap is second order; use a C81 table
        model for it.
    cm0 : float
        Zero-lift pitching moment about the quarter chord (not scaled with Mach).
    compressibility : bool
        Prandtl-Glauert factor on the circulatory loads (:func:`prandtl_glauert`).
    lift_slope : float
        Section lift-curve slope [1/rad]. Thin-airfoil theory gives 2 pi; a
        real airfoil has less (viscous decambering). Every circulatory load
        (lift, moment, flap lift, hinge moment, rate terms) is scaled by
        ``lift_slope / (2 pi)`` — the usual empirical correction — while the
        apparent-mass loads are not. Default 2 pi.

    Attributes
    ----------
    flap_nose, hinge : float
        Chord fractions from the leading edge of the flap nose and hinge.
    derivatives : dict
        Incompressible static derivatives (per rad): ``cl_alpha`` (2 pi),
        ``cl_delta`` (2 T10), ``cm_delta`` (1/4 chord), ``clf_alpha``,
        ``clf_delta``, ``ch_alpha``, ``ch_delta`` (blade-chord normalisation).
    """

    def __init__(self, chord_ratio: float, overhang: float, *, cd0=0.01, cd1=0.0, cd2=0.0,
                 cm0=0.0, compressibility: bool = True, lift_slope: float = 2 * np.pi):
        e, o, c, d = _geometry(chord_ratio, overhang)
        if not (np.isfinite(lift_slope) and 0 < lift_slope <= 8.0):
            raise ValueError(f"lift_slope = {lift_slope} is outside the allowed range (0, 8] 1/rad")
        self.circulatory_scale = float(lift_slope) / (2 * np.pi)
        self.chord_ratio = e
        self.overhang = o
        self.cd0, self.cd1, self.cd2, self.cm0 = float(cd0), float(cd1), float(cd2), float(cm0)
        self.compressibility = bool(compressibility)
        self.flap_nose = 1.0 - e
        self.hinge = 1.0 - e + o * e
        sm, _ = _influence(c)
        # static loads of W = (-U alpha, 0, -U delta, 0): rows 0 (alpha) and 2 (delta)
        der = {}
        for name, i in (("alpha", 0), ("delta", 2)):
            der[f"cl_{name}"] = -sm[i, 0]
            der[f"cm_{name}"] = 0.5 * (sm[i, 1] + 0.5 * sm[i, 0])
            der[f"clf_{name}"] = -sm[i, 2]
            der[f"ch_{name}"] = 0.5 * (sm[i, 3] - d * sm[i, 2])
        self.derivatives = {k: float(v) for k, v in der.items()}

    def influence(self):
        """The flap's geometry in the loads' formulas (:func:`section_loads`).

        Returns
        -------
        d : float
            Hinge offset behind the flap nose [semichords], ``2 overhang E``.
        steady, apparent_mass : numpy.ndarray
            The ``(4, 4)`` influence matrices ``S`` and ``N`` of the kink at the
            flap nose (module docstring; read-only).
        """
        _, _, c, d = _geometry(self.chord_ratio, self.overhang)
        sm, nm = _influence(c)
        return d, sm, nm

    def __repr__(self):
        return (f"ThinAirfoilFlap(chord_ratio={self.chord_ratio:g}, overhang={self.overhang:g}, "
                f"compressibility={self.compressibility})")

    def static_coefficients(self, alpha, mach, delta) -> dict[str, np.ndarray]:
        """Steady coefficients, keys exactly 'cl','cd','cm','ch','clf'; broadcast over inputs (rad).

        ``cm`` about the quarter chord, ``ch`` about the hinge; normalised by the
        blade chord (``C_h / E^2`` on the flap chord).  The Prandtl-Glauert
        factor (if ``compressibility``) scales the thin-airfoil terms, not
        ``cd`` or ``cm0``.  ``mach`` is validated (0..0.99) even without
        compressibility.
        """
        a, m, dl = np.broadcast_arrays(_finite("alpha", alpha), _numeric(mach),
                                       _finite("delta", delta))
        pg = prandtl_glauert(m)
        if not self.compressibility:
            pg = np.ones_like(a)
        pg = pg * self.circulatory_scale
        dv = self.derivatives
        out = {
            "cl": pg * (dv["cl_alpha"] * a + dv["cl_delta"] * dl),
            "cd": self.cd0 + self.cd1 * a + self.cd2 * a * a,
            "cm": self.cm0 + pg * (dv["cm_alpha"] * a + dv["cm_delta"] * dl),
            "ch": pg * (dv["ch_alpha"] * a + dv["ch_delta"] * dl),
            "clf": pg * (dv["clf_alpha"] * a + dv["clf_delta"] * dl),
        }
        return {k: _numeric(v)[()] for k, v in out.items()}

    def loads(self, *, alpha, alpha_rate, alpha_accel, plunge_rate, plunge_accel, delta,
              delta_rate, delta_accel, velocity, density, chord, axis=0.25,
              mach=0.0, check_finite=True) -> dict[str, np.ndarray]:
        """Per unit span (SI): 'lift','drag','moment' (about `axis`, fraction of chord
        from LE, nose-up +), 'flap_lift','hinge_moment' (about the hinge, positive in the
        delta-positive sense, TE down) and the coefficients 'cl','cd','cm','clf','ch'.

        See :func:`section_loads` (this is ``section_loads(self, ...)``).
        """
        return section_loads(self, alpha=alpha, alpha_rate=alpha_rate, alpha_accel=alpha_accel,
                             plunge_rate=plunge_rate, plunge_accel=plunge_accel, delta=delta,
                             delta_rate=delta_rate, delta_accel=delta_accel, velocity=velocity,
                             density=density, chord=chord, axis=axis, mach=mach,
                             check_finite=check_finite)


def section_loads(static_model, *, alpha, alpha_rate, alpha_accel, plunge_rate, plunge_accel,
                  delta, delta_rate, delta_accel, velocity, density, chord, axis=0.25,
                  mach=0.0, check_finite=True) -> dict[str, np.ndarray]:
    """Quasi-steady section loads from a static model plus thin-airfoil rate terms.

    ``static_model`` needs ``static_coefficients(alpha, mach, delta)`` (keys
    ``cl, cd, cm, ch, clf``; ``cm`` about the quarter chord, ``ch`` about the
    hinge, blade-chord normalisation) and the flap geometry attributes
    ``chord_ratio`` and ``overhang``; an optional ``compressibility``
    attribute (default True) switches the Prandtl-Glauert factor of the
    circulatory increments.

    Inputs (SI, rad, broadcast together): ``alpha`` nose up, its time
    derivatives ``alpha_rate``, ``alpha_accel``, about the pitch axis
    ``axis`` (chord fraction from the leading edge, also the moment
    reference); ``plunge_rate``, ``plunge_accel`` of that axis point, positive
    UP; flap ``delta`` (TE down) and its derivatives; ``velocity`` U > 0;
    ``density``; blade ``chord``; ``mach`` (0..0.99).

    The loads are the sum of

    1. the static coefficients at ``alpha_eff = alpha - plunge_rate/U +
       (b/U)(1/2 - a) alpha_rate`` and ``delta`` (``b`` semichord, ``a = 2 axis - 1``),
       with ``cm`` transferred from the quarter chord to ``axis``;
    2. circulatory thin-airfoil increments, times the Prandtl-Glauert factor:
       the zero-lift loading of the upwash ``-b alpha_rate (x - 1/2)`` (pitch
       rate about the 3/4 chord, what ``alpha_eff`` leaves out) and the loading
       of the ``delta_rate`` upwash (flap rotating about its hinge);
    3. the apparent-mass (non-circulatory) loads ``rho d/dt dphi_nc`` of all
       motions, including the ``U alpha_rate`` and ``U delta_rate`` terms.

    For :class:`ThinAirfoilFlap` the sum is exactly Theodorsen's loading with
    ``C(k) = 1`` (circulatory part scaled by Prandtl-Glauert).  The drag is
    ``q chord C_d(alpha_eff)`` along ``U``; lift is normal to ``U``.

    ``check_finite=False`` skips the finiteness test of every input and the
    positivity test of ``velocity``, ``density`` and ``chord`` (as in
    scipy.linalg): for callers that check their own results, such as the
    coupled model, whose trim stops on a non-finite residual.  The Mach
    range is always checked.

    Parameters
    ----------
    static_model : object
        The static coefficients and flap geometry (see above).
    alpha, alpha_rate, alpha_accel : float or array_like
        Angle of attack [rad], nose up, and its time derivatives.
    plunge_rate, plunge_accel : float or array_like
        Velocity [m/s] and acceleration [m/s^2] of the axis point, up.
    delta, delta_rate, delta_accel : float or array_like
        Flap deflection [rad], trailing edge down, and its time derivatives.
    velocity : float or array_like
        Airspeed U [m/s], positive.
    density : float or array_like
        Air density [kg/m^3].
    chord : float
        Blade chord [m].
    axis : float, optional
        Pitch axis and moment reference, chord fraction from the leading edge.
    mach : float or array_like, optional
        Mach number, 0 .. 0.99.
    check_finite : bool, optional
        Check the inputs (see above).

    Returns
    -------
    dict
        ``'lift', 'drag', 'moment', 'flap_lift', 'hinge_moment'`` per unit span
        and ``'cl', 'cd', 'cm', 'clf', 'ch'`` (``cm`` about ``axis``; all on the
        blade chord, ``q = rho U^2 / 2``).

    Raises
    ------
    ValueError
        A non-finite input, a non-positive ``velocity``, ``density`` or
        ``chord`` (unless ``check_finite=False``), or a Mach number outside
        [0, 0.99].
    """
    _, _, c, d = _geometry(static_model.chord_ratio, static_model.overhang)
    names = ("alpha", "alpha_rate", "alpha_accel", "plunge_rate", "plunge_accel", "delta",
             "delta_rate", "delta_accel", "axis")
    vals = dict(zip(names, (alpha, alpha_rate, alpha_accel, plunge_rate, plunge_accel, delta,
                            delta_rate, delta_accel, axis), strict=True))
    vals.update(velocity=velocity, density=density, chord=chord, mach=mach)
    vals = {k: _numeric(v) for k, v in vals.items()}
    shape = np.broadcast_shapes(*(v.shape for v in vals.values()))
    # one finiteness test for all inputs (this sits in the trim's inner loop):
    # NaN or inf anywhere makes the sum non-finite; the per-name checks run
    # only to word the error. Scalars stay scalars (no broadcast copies).
    if check_finite:
        if not np.isfinite(sum(v.sum() for v in vals.values())):
            for k, v in vals.items():
                _finite(k, v)
        for k in ("velocity", "density", "chord"):
            if np.any(vals[k] <= 0.0):
                _finite(k, vals[k], positive=True)
    pg = prandtl_glauert(vals["mach"])
    al, ar, aa, pr, pa, dl, dr, da, ax, u, rho, chd, m = vals.values()
    if not getattr(static_model, "compressibility", True):
        pg = 1.0
    b = 0.5 * chd
    a = 2.0 * ax - 1.0
    q = 0.5 * rho * u * u

    # 1. static coefficients at the 3/4-chord angle of attack
    alpha_eff = al - pr / u + (b * (0.5 - a)) * ar / u
    st = static_model.static_coefficients(alpha_eff, m, dl)
    qc, qcc = q * chd, q * (chd * chd)
    lift = qc * st["cl"]
    moment = qcc * (st["cm"] + st["cl"] * (ax - 0.25))
    flap_lift = qc * st["clf"]
    hinge = qcc * st["ch"]
    drag = qc * st["cd"]

    # 2./3. thin-airfoil increments. Upwash components on e = (1, x, H, (x-c)H):
    # circulatory W = b (ar/2, -ar, d dr, -dr), apparent-mass
    # W* = (pa + a b aa - u ar, -b aa, -u dr + b d da, -b da); the loads are
    # the projections sum_i W_i S[i, k] (resp. N), written out per rate so
    # that no (4, ...) stacks are built in the trim's inner loop
    sm, nm = _influence(c)
    circ = pg * getattr(static_model, "circulatory_scale", 1.0) * rho * u * b * b
    pc = [circ * (ar * (0.5 * sm[0, k] - sm[1, k]) + dr * (d * sm[2, k] - sm[3, k]))
          for k in range(4)]
    rb2 = rho * b * b
    pn = [rb2 * ((pa - u * ar) * nm[0, k] + aa * (b * (a * nm[0, k] - nm[1, k]))
                 + (b * d * nm[2, k] - b * nm[3, k]) * da - u * dr * nm[2, k])
          for k in range(4)]
    lift = lift + pc[0] + pn[0]
    moment = moment - b * (pc[1] - a * pc[0]) - b * (pn[1] - a * pn[0])
    flap_lift = flap_lift + pc[2] + pn[2]
    hinge = hinge - b * (pc[3] - d * pc[2]) - b * (pn[3] - d * pn[2])
    lift, drag, moment, flap_lift, hinge = (
        v if np.shape(v) == shape else np.broadcast_to(v, shape).copy()
        for v in (lift, drag, moment, flap_lift, hinge))

    out = {"lift": lift, "drag": drag, "moment": moment, "flap_lift": flap_lift,
           "hinge_moment": hinge}
    out.update(cl=lift / qc, cd=drag / qc, cm=moment / qcc, clf=flap_lift / qc, ch=hinge / qcc)
    return {k: _numeric(v)[()] for k, v in out.items()}
