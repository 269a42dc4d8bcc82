"""Unsteady airloads of a thin airfoil with a balanced trailing-edge flap (finite-state wake).

docs/theory.md section 3.9.  The quasi-steady section model of section 3
(:mod:`tefcore.aero.thin_airfoil`, Theodorsen with ``C(k) = 1``) plus the shed wake,
represented by ``N`` aerodynamic states: a state-space form of Theodorsen's
theory that holds for any hinge position (overhang ``o = c_b/c_f`` in [0, 1)).

Physics.  In Theodorsen's theory the wake changes only the circulatory
loading, and only through its flat-plate (Kutta) part: the loads are the
quasi-steady ones with the 3/4-chord upwash ``Q`` of the circulation replaced
by ``Q - lambda_0``, where ``lambda_0`` is the wake-induced downwash, uniform
over the chord (Peters, Karunamoorthy & Cao 1995).  For harmonic motion
``lambda_0 = (1 - C(k)) Q``.  For the balanced flap ``Q`` carries the hinge
kinematics (``delta_rate`` turns the flap about its hinge, section 3.2)::

    Q = U alpha - h_dot + b (1/2 - a) alpha_dot + (T10/pi)(U delta - b d delta_dot)
        + b T11 delta_dot / (2 pi)

and the wake loads follow from the quasi-steady model at the angle of attack
``alpha - lambda_0 / U`` (the flat-plate loading of ``-lambda_0``: lift,
quarter-chord moment, flap lift and hinge moment about the hinge, with the
model's Prandtl-Glauert factor and lift-slope scaling).  ``lambda_0`` comes
from ``N`` states ``lam`` (velocities, m/s)::

    E lam_dot + (U/b) lam = cvec Q_dot,        lambda_0 = g . lam

a rational approximation of ``1 - C(k)`` (:class:`WakeModel`): either
Peters' published constants (``wake="peters"``) or a least-squares fit of
``1 - C(k)`` by ``N`` real poles (``wake="fitted"``, the default: a
generalised R. T. Jones / Wagner-exponential form, which converges with
``N`` where Peters' constants stop converging at N ~ 10).

Examples
--------
>>> model = UnsteadyFlapAirfoil(0.35, 0.29, n_states=8, compressibility=False)
>>> bool(abs(model.wake.lift_deficiency(0.26) - theodorsen_function(0.26)) < 2e-4)
True
>>> round(float(theodorsen_function(0.26).real), 4), round(float(theodorsen_function(0.26).imag), 4)
(0.6865, -0.1842)
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.integrate
import scipy.linalg
import scipy.optimize
from scipy.special import hankel2

from .theodorsen import t_functions
from .thin_airfoil import ThinAirfoilFlap, section_loads

__all__ = [
    "MAX_STATES",
    "SectionMatrices",
    "UnsteadyFlapAirfoil",
    "WakeModel",
    "fitted_wake",
    "peters_wake",
    "theodorsen_function",
    "wagner_function",
]

#: Largest number of wake states.  Peters' constants stop converging beyond ~10
#: (measured: max |C_N - C| over k <= 2 is 8.5e-3 at N = 10, 3.2e-2 at N = 12,
#: and the N = 16 system is unstable even in 80-digit arithmetic); the fitted
#: wake reaches 2.7e-5 at N = 10, below what a rotor model can use.
MAX_STATES = 10

_MOTION = ("plunge", "alpha", "delta")
_LOADS = ("lift", "moment", "flap_lift", "hinge_moment")


# ---------------------------------------------------------------------------
# Theodorsen and Wagner functions (exact references)
# ---------------------------------------------------------------------------

def theodorsen_function(k) -> np.ndarray:
    """Theodorsen's lift-deficiency function ``C(k) = H1(k) / (H1(k) + i H0(k))``.

    ``H_n = H_n^(2)`` are Hankel functions of the second kind (``scipy.special.hankel2``),
    ``k = omega b / U >= 0`` the reduced frequency; ``C(0) = 1`` (the limit).

    Parameters
    ----------
    k : float or array_like
        Reduced frequency ``omega b / U >= 0``.

    Returns
    -------
    numpy.ndarray of complex

    References
    ----------
    Theodorsen, T., "General theory of aerodynamic instability and the mechanism
    of flutter", NACA Report 496, 1935.

    >>> c = theodorsen_function([0.0, 0.1, 1.0])
    >>> [round(float(v), 4) for v in c.real], [round(float(v), 4) for v in c.imag]
    ([1.0, 0.8319, 0.5394], [0.0, -0.1723, -0.1003])
    """
    k = np.asarray(k, dtype=float)
    if not np.all(np.isfinite(k)) or np.any(k < 0.0):
        raise ValueError(f"reduced frequency k must be finite and >= 0, got {k}")
    out = np.ones(k.shape, dtype=complex)
    pos = k > 0.0
    h1, h0 = hankel2(1, k[pos]), hankel2(0, k[pos])
    out[pos] = h1 / (h1 + 1j * h0)
    return out[()]


def _imag_c_over_k(k):
    return float(theodorsen_function(k).imag) / k


def wagner_function(s) -> np.ndarray:
    """Wagner's indicial lift function ``phi(s)`` by quadrature of ``C(k)``.

    ``phi(s) = 1 + (2/pi) int_0^inf (Im C(k) / k) cos(k s) dk`` for reduced time
    ``s = U t / b >= 0`` (lift after a step in angle of attack over its final
    value): ``phi(0) = 1/2``, ``phi -> 1``.  Adaptive quadrature
    (``scipy.integrate.quad``, a cosine-weighted Fourier integral on the tail);
    about 1e-7 absolute.

    Parameters
    ----------
    s : float or array_like
        Reduced time ``U t / b >= 0``.

    Returns
    -------
    numpy.ndarray

    References
    ----------
    Wagner, H., "Ueber die Entstehung des dynamischen Auftriebes von
    Tragfluegeln", ZAMM 5(1), 1925; Bisplinghoff, Ashley & Halfman,
    *Aeroelasticity*, 1955, sec. 5-6 (the Fourier relation to ``C(k)``).

    >>> [round(float(v), 4) for v in wagner_function([0.0, 2.0, 10.0])]
    [0.5, 0.6693, 0.875]
    """
    s = np.asarray(s, dtype=float)
    if not np.all(np.isfinite(s)) or np.any(s < 0.0):
        raise ValueError(f"reduced time s must be finite and >= 0, got {s}")
    out = np.empty(s.shape)
    tail = 20.0
    for idx, si in np.ndenumerate(s):
        total = 0.0
        # Im C / k ~ ln k at k -> 0 (integrable), ~ -1/(8 k^2) at large k
        for lo, hi in ((1e-300, 1e-6), (1e-6, 1e-3), (1e-3, 1.0), (1.0, tail)):
            if si * hi < 50.0:
                total += scipy.integrate.quad(lambda k, s_=si: _imag_c_over_k(k) * math.cos(k * s_),
                                              lo, hi, limit=200)[0]
            else:
                total += scipy.integrate.quad(_imag_c_over_k, lo, hi, weight="cos", wvar=si,
                                              limit=400)[0]
        if si > 0.0:
            total += scipy.integrate.quad(_imag_c_over_k, tail, np.inf, weight="cos", wvar=si,
                                          limlst=200)[0]
        else:
            total += scipy.integrate.quad(_imag_c_over_k, tail, np.inf, limit=200)[0]
        out[idx] = 1.0 + 2.0 / math.pi * total
    return out[()]


# ---------------------------------------------------------------------------
# Wake models
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class WakeModel:
    """Finite-state shed wake in reduced time ``s = int U dt / b``.

    ``E dlam/ds + lam = cvec dQ/ds`` and ``lambda_0 = g . lam``; in physical time
    ``E lam_dot + (U/b) lam = cvec Q_dot``.  For harmonic motion at reduced
    frequency ``k`` this gives ``lambda_0 = (1 - C_N(k)) Q`` with
    ``C_N(k) = 1 - g . (i k E + I)^-1 cvec i k`` (:meth:`lift_deficiency`).

    Attributes
    ----------
    name : str
        ``"peters"`` or ``"fitted"``.
    E : ndarray (N, N)
    cvec, g : ndarray (N,)
    """

    name: str
    E: np.ndarray
    cvec: np.ndarray
    g: np.ndarray

    @property
    def n_states(self) -> int:
        """Number of states ``N``."""
        return int(self.g.size)

    def lift_deficiency(self, k) -> np.ndarray:
        """The model's ``C_N(k)`` at reduced frequencies ``k >= 0`` (broadcast)."""
        k = np.asarray(k, dtype=float)
        if not np.all(np.isfinite(k)) or np.any(k < 0.0):
            raise ValueError(f"reduced frequency k must be finite and >= 0, got {k}")
        kk = k.reshape(-1)
        eye = np.eye(self.n_states)
        lhs = 1j * kk[:, None, None] * self.E[None] + eye[None]
        rhs = np.broadcast_to((1j * kk[:, None] * self.cvec[None])[..., None],
                              (kk.size, self.n_states, 1))
        lam = np.linalg.solve(lhs, rhs)[..., 0]
        return (1.0 - lam @ self.g).reshape(k.shape)[()]

    def indicial(self, s) -> np.ndarray:
        """Circulatory lift after a unit step of ``Q`` at ``s = 0``: ``1 - lambda_0(s)``.

        The step's ``dQ/ds`` is an impulse, so ``lam(0+) = E^-1 cvec`` and then
        ``lam(s) = expm(-E^-1 s) E^-1 cvec``.  Compare :func:`wagner_function`.
        """
        s = np.asarray(s, dtype=float)
        if not np.all(np.isfinite(s)) or np.any(s < 0.0):
            raise ValueError(f"reduced time s must be finite and >= 0, got {s}")
        einv = np.linalg.inv(self.E)
        lam0 = einv @ self.cvec
        vals, vecs = np.linalg.eig(-einv)
        coef = np.linalg.solve(vecs, lam0)
        ss = s.reshape(-1)
        lam = (vecs[None] * np.exp(np.outer(ss, vals))[:, None, :]) @ coef
        return (1.0 - (lam @ self.g).real).reshape(s.shape)[()]


def _check_n(n_states) -> int:
    if isinstance(n_states, bool) or int(n_states) != n_states or not (
            1 <= int(n_states) <= MAX_STATES):
        raise ValueError(f"n_states must be an integer in [1, {MAX_STATES}], got {n_states!r}")
    return int(n_states)


@functools.cache
def peters_wake(n_states: int) -> WakeModel:
    """Peters' finite-state wake with his published constants.

    ``E = D + d b^T + c d^T + (1/2) c b^T``, ``D[n, n-1] = 1/(2n)``,
    ``D[n, n+1] = -1/(2n)``, ``b_n = (-1)^(n-1) (N+n-1)! / ((N-n-1)! (n!)^2)``
    (``n < N``), ``b_N = (-1)^(N-1)``, ``c_n = 2/n``, ``d = (1/2, 0, ...)``,
    ``lambda_0 = (1/2) b . lam`` (``n, m = 1..N``).  Accuracy (max |C_N - C|,
    k <= 2): 3.4e-2 (N = 4), 1.6e-2 (6), 9.7e-3 (8), 8.5e-3 (10); largest at
    k ~ 0.04.

    References
    ----------
    Peters, D. A., Karunamoorthy, S. & Cao, W.-M., "Finite state induced flow
    models, Part I: two-dimensional thin airfoil", J. Aircraft 32(2), 313-322,
    1995; Hodges, D. H. & Pierce, G. A., *Introduction to Structural Dynamics
    and Aeroelasticity*, Cambridge, 2002, sec. 5.5.

    >>> w = peters_wake(4)
    >>> [round(float(v), 3) for v in w.g * 2]
    [12.0, -30.0, 20.0, -1.0]
    """
    n = _check_n(n_states)
    idx = np.arange(1, n + 1)
    b = np.array([(-1) ** (i - 1) * math.factorial(n + i - 1)
                  / (math.factorial(n - i - 1) * math.factorial(i) ** 2) if i < n
                  else (-1) ** (n - 1) for i in idx], dtype=float)
    c = 2.0 / idx
    d = np.zeros(n)
    d[0] = 0.5
    dm = np.zeros((n, n))
    for i in range(n):
        if i >= 1:
            dm[i, i - 1] = 1.0 / (2 * (i + 1))
        if i + 1 < n:
            dm[i, i + 1] = -1.0 / (2 * (i + 1))
    e = dm + np.outer(d, b) + np.outer(c, d) + 0.5 * np.outer(c, b)
    for arr in (e, c, b):
        arr.setflags(write=False)
    g = 0.5 * b
    g.setflags(write=False)
    return WakeModel("peters", e, c, g)


# reduced frequencies of the least-squares fit: the k ln k behaviour of C at
# small k needs a logarithmic grid down to 1e-5; the tail to 100 pins C -> 1/2
_FIT_K = np.concatenate([np.geomspace(1e-5, 1e-2, 60, endpoint=False),
                         np.linspace(1e-2, 2.0, 200), np.geomspace(2.0, 100.0, 40)[1:]])


def _fit_residues(poles):
    """Residues for fixed poles by linear least squares with ``sum r = 1/2`` (C(inf) = 1/2)."""
    n = poles.size
    basis = (1j * _FIT_K[:, None]) / (1j * _FIT_K[:, None] + poles[None, :])
    target = 1.0 - theodorsen_function(_FIT_K)
    a = np.vstack([basis.real, basis.imag])
    y = np.concatenate([target.real, target.imag])
    r0 = np.zeros(n)
    r0[-1] = 0.5
    if n == 1:
        return a @ r0 - y, r0
    z = np.vstack([np.eye(n - 1), -np.ones((1, n - 1))])     # null space of sum r
    sol = np.linalg.lstsq(a @ z, y - a @ r0, rcond=None)[0]
    r = r0 + z @ sol
    return a @ r - y, r


@functools.cache
def fitted_wake(n_states: int) -> WakeModel:
    """Wake of ``N`` real poles fitted to ``1 - C(k)`` by least squares.

    ``1 - C_N(k) = sum_j r_j i k / (i k + p_j)``, i.e. ``lam_j`` obeys
    ``dlam_j/ds + p_j lam_j = dQ/ds`` (``E = diag(1/p)``, ``cvec = 1/p``,
    ``g = r``), and the indicial function is ``1 - sum_j r_j exp(-p_j s)`` (R. T.
    Jones' two-exponential Wagner approximation is the case N = 2).  Poles by
    variable projection (``scipy.optimize.least_squares``, Levenberg-Marquardt
    on ``ln p``) with the residues solved linearly under ``sum r = 1/2``
    (exact impulsive lift ``C(inf) = 1/2``; ``C_N(0) = 1`` holds by
    construction), on ``k`` from 1e-5 to 100.  Measured max |C_N - C| over
    k in [0, 2]: 2.3e-3 (N = 4), 3.8e-4 (6), 9.1e-5 (8), 2.7e-5 (10); all
    poles and residues positive (monotone indicial response).

    References
    ----------
    Jones, R. T., "The unsteady lift of a wing of finite aspect ratio", NACA
    Report 681, 1940 (exponential approximation of Wagner's function);
    Golub, G. & Pereyra, V., "The differentiation of pseudo-inverses and
    nonlinear least squares problems whose variables separate", SIAM J.
    Numer. Anal. 10(2), 1973 (variable projection).

    >>> w = fitted_wake(2)
    >>> bool(np.all(w.g > 0)), round(float(w.g.sum()), 12)
    (True, 0.5)
    """
    n = _check_n(n_states)
    x0 = np.log(np.geomspace(10.0 ** (-(1.0 + n / 3.0)), 2.0, n)) if n > 1 else np.log([0.2])
    sol = scipy.optimize.least_squares(lambda lp: _fit_residues(np.exp(lp))[0], x0,
                                       method="lm", xtol=1e-12, ftol=1e-12, max_nfev=4000)
    poles = np.exp(sol.x)
    order = np.argsort(poles)
    poles = poles[order]
    _, res = _fit_residues(poles)
    if not (np.all(np.isfinite(poles)) and np.all(poles > 0) and poles.max() < 1e3
            and np.all(np.diff(poles) > 1e-6 * poles[1:])):
        raise RuntimeError(f"wake fit with {n} states degenerated: poles {poles}")
    e = np.diag(1.0 / poles)
    c = 1.0 / poles
    for arr in (e, c, res):
        arr.setflags(write=False)
    return WakeModel("fitted", e, c, res)


# ---------------------------------------------------------------------------
# The section model
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class SectionMatrices:
    """Linear unsteady section model at one flow condition (constant ``U``).

    Motion ``x = (h, alpha, delta)`` (plunge of the axis point UP [m], pitch
    nose up, flap TE down [rad]); loads ``y = (L, M, L_f, H)`` per unit span
    (lift up, moment about the axis nose up, flap lift up, hinge moment about
    the hinge TE down)::

        y = Mx x_ddot + Cx x_dot + Kx x + D lam
        E lam_dot + F lam = cvec (q0 . x_dot + q1 . x_ddot)      (Q = q0 . x + q1 . x_dot)

    ``F = (U/b) I``.  The rows of ``(Mx, Cx, Kx)`` for ``(L, M, H)`` are the
    generalised forces of ``(h, alpha, delta)``: ``-Mx[[0, 1, 3]]`` is the
    apparent-mass matrix, symmetric positive definite.

    Attributes
    ----------
    Mx, Cx, Kx : numpy.ndarray
        Load per motion acceleration, rate and displacement, ``(4, 3)``.
    D : numpy.ndarray
        Load per wake state, ``(4, N)``.
    E, F : numpy.ndarray
        Wake-state equations, ``(N, N)``.
    cvec : numpy.ndarray
        Input vector of the wake states, ``(N,)``.
    q0, q1 : numpy.ndarray
        The circulatory downwash ``Q`` per motion and per motion rate, ``(3,)``.
    """

    Mx: np.ndarray
    Cx: np.ndarray
    Kx: np.ndarray
    D: np.ndarray
    E: np.ndarray
    F: np.ndarray
    cvec: np.ndarray
    q0: np.ndarray
    q1: np.ndarray

    def frequency_response(self, omega) -> np.ndarray:
        """Complex loads per unit harmonic motion: ``y_hat = H(omega) x_hat``, shape (..., 4, 3)."""
        w = np.asarray(omega, dtype=float)
        if not np.all(np.isfinite(w)):
            raise ValueError(f"omega must be finite, got {omega}")
        ww = w.reshape(-1)
        s = 1j * ww
        h = (self.Kx[None] + s[:, None, None] * self.Cx[None]
             + (s * s)[:, None, None] * self.Mx[None])
        n = self.E.shape[0]
        lhs = s[:, None, None] * self.E[None] + self.F[None]
        drive = s[:, None] * (self.q0[None] + s[:, None] * self.q1[None])          # Q_dot / x
        lam = np.linalg.solve(lhs, np.broadcast_to(self.cvec[None, :, None], (ww.size, n, 1)))
        h = h + (self.D[None] @ lam) * drive[:, None, :]
        return h.reshape(w.shape + (4, 3))


class UnsteadyFlapAirfoil:
    """Thin airfoil with a balanced trailing-edge flap and a finite-state shed wake.

    Parameters
    ----------
    chord_ratio, overhang : float
        Flap chord / blade chord ``E`` in (0, 1); hinge behind the flap nose /
        flap chord ``o`` in [0, 1) (section 3.5).
    n_states : int
        Wake states ``N``, 1 .. :data:`MAX_STATES` (default 6: max |C_N - C|
        3.8e-4 with the fitted wake).
    wake : {"fitted", "peters"}
        :func:`fitted_wake` or :func:`peters_wake`.
    static_model : optional
        The quasi-steady model whose ``static_coefficients`` give the loads
        (default ``ThinAirfoilFlap(chord_ratio, overhang, **quasi_steady)``); a
        :class:`tefcore.aero.c81.C81FlapTable` of the same geometry works for
        :meth:`loads` (the wake then lags the table's angle of attack).
    **quasi_steady
        Keyword arguments of :class:`~tefcore.aero.thin_airfoil.ThinAirfoilFlap`
        (``compressibility``, ``lift_slope``, ``cd0``, ...).

    References
    ----------
    Theodorsen, NACA Report 496, 1935; Peters, Karunamoorthy & Cao, J. Aircraft
    32(2), 1995; docs/theory.md sections 3.2-3.5 and 3.9.
    """

    def __init__(self, chord_ratio: float, overhang: float, *, n_states: int = 6,
                 wake: str = "fitted", static_model=None, **quasi_steady):
        if wake not in ("fitted", "peters"):
            raise ValueError(f"wake must be 'fitted' or 'peters', got {wake!r}")
        if static_model is None:
            static_model = ThinAirfoilFlap(chord_ratio, overhang, **quasi_steady)
        elif quasi_steady:
            raise TypeError("give either static_model or ThinAirfoilFlap keyword arguments")
        if not (math.isclose(static_model.chord_ratio, chord_ratio)
                and math.isclose(static_model.overhang, overhang)):
            raise ValueError(f"static_model geometry (chord_ratio={static_model.chord_ratio}, "
                             f"overhang={static_model.overhang}) differs from ({chord_ratio}, "
                             f"{overhang})")
        self.static_model = static_model
        self.chord_ratio = float(static_model.chord_ratio)
        self.overhang = float(static_model.overhang)
        self.wake = (fitted_wake if wake == "fitted" else peters_wake)(n_states)
        c = 1.0 - 2.0 * self.chord_ratio
        t = t_functions(c)
        self._c, self._d = c, 2.0 * self.overhang * self.chord_ratio
        self._t10, self._t11 = float(t["T10"]), float(t["T11"])

    def __repr__(self):
        return (f"UnsteadyFlapAirfoil(chord_ratio={self.chord_ratio:g}, overhang="
                f"{self.overhang:g}, n_states={self.wake.n_states}, wake={self.wake.name!r})")

    @property
    def n_states(self) -> int:
        """Number of wake states ``N``."""
        return self.wake.n_states

    def _q_coefficients(self, velocity, chord, axis):
        """``Q = q0 . (h, alpha, delta) + q1 . (h_dot, alpha_dot, delta_dot)`` (constant U)."""
        b = 0.5 * chord
        a = 2.0 * axis - 1.0
        pi = math.pi
        q0 = np.array([0.0, velocity, self._t10 * velocity / pi])
        q1 = np.array([-1.0, b * (0.5 - a),
                       b * (self._t11 / (2 * pi) - self._t10 * self._d / pi)])
        return q0, q1

    def upwash(self, *, alpha, alpha_rate, plunge_rate, delta, delta_rate, velocity, chord,
               axis=0.25) -> np.ndarray:
        """The 3/4-chord upwash ``Q`` [m/s]: circulation ``Gamma = 2 pi b Q`` (section 3.2)."""
        b = 0.5 * np.asarray(chord, dtype=float)
        a = 2.0 * np.asarray(axis, dtype=float) - 1.0
        u = np.asarray(velocity, dtype=float)
        return (u * alpha - plunge_rate + b * (0.5 - a) * alpha_rate
                + self._t10 / math.pi * (u * delta - b * self._d * delta_rate)
                + b * self._t11 / (2 * math.pi) * delta_rate)

    def upwash_rate(self, *, alpha, alpha_rate, alpha_accel, plunge_accel, delta, delta_rate,
                    delta_accel, velocity, chord, axis=0.25, velocity_rate=0.0) -> np.ndarray:
        """``Q_dot`` [m/s^2], the input of the wake states (``velocity_rate`` = dU/dt)."""
        b = 0.5 * np.asarray(chord, dtype=float)
        a = 2.0 * np.asarray(axis, dtype=float) - 1.0
        u = np.asarray(velocity, dtype=float)
        return (velocity_rate * alpha + u * alpha_rate - plunge_accel + b * (0.5 - a) * alpha_accel
                + self._t10 / math.pi * (velocity_rate * delta + u * delta_rate
                                         - b * self._d * delta_accel)
                + b * self._t11 / (2 * math.pi) * delta_accel)

    def induced_velocity(self, states) -> np.ndarray:
        """Wake-induced downwash ``lambda_0 = g . lam`` [m/s]; ``states`` shape (..., N)."""
        lam = np.asarray(states, dtype=float)
        if lam.shape[-1:] != (self.n_states,):
            raise ValueError(f"states must have last dimension {self.n_states}, got {lam.shape}")
        return lam @ self.wake.g

    def state_rate(self, states, *, upwash_rate, velocity, chord) -> np.ndarray:
        """``lam_dot = E^-1 (cvec Q_dot - (U/b) lam)`` in physical time; shape (..., N)."""
        lam = np.asarray(states, dtype=float)
        if lam.shape[-1:] != (self.n_states,):
            raise ValueError(f"states must have last dimension {self.n_states}, got {lam.shape}")
        u = np.asarray(velocity, dtype=float)[..., None]
        b = 0.5 * np.asarray(chord, dtype=float)[..., None]
        rhs = self.wake.cvec * np.asarray(upwash_rate, dtype=float)[..., None] - (u / b) * lam
        return np.linalg.solve(self.wake.E, rhs[..., None])[..., 0]

    def loads(self, *, states, alpha, alpha_rate, alpha_accel, plunge_rate, plunge_accel, delta,
              delta_rate, delta_accel, velocity, density, chord, axis=0.25, mach=0.0,
              check_finite=True) -> dict[str, np.ndarray]:
        """Section loads with the wake: the quasi-steady loads at ``alpha - lambda_0 / U``.

        Same inputs and outputs as :func:`tefcore.aero.thin_airfoil.section_loads`, plus the
        wake ``states`` (shape (..., N), m/s).  ``lambda_0`` lowers the 3/4-chord
        angle of attack, so the static coefficients (thin airfoil or table) see
        the lagged angle while the apparent-mass terms stay instantaneous.
        """
        lam0 = self.induced_velocity(states)
        return section_loads(self.static_model, alpha=np.asarray(alpha, dtype=float)
                             - lam0 / np.asarray(velocity, dtype=float),
                             alpha_rate=alpha_rate, alpha_accel=alpha_accel,
                             plunge_rate=plunge_rate, plunge_accel=plunge_accel, delta=delta,
                             delta_rate=delta_rate, delta_accel=delta_accel, velocity=velocity,
                             density=density, chord=chord, axis=axis, mach=mach,
                             check_finite=check_finite)

    def matrices(self, *, velocity, density, chord, axis=0.25, mach=0.0) -> SectionMatrices:
        """The linear state-space model at one flow condition (:class:`SectionMatrices`).

        Needs a static model linear in ``alpha`` and ``delta`` (the thin airfoil):
        the columns are the loads of unit motions, so ``k -> 0`` reproduces
        :meth:`ThinAirfoilFlap.loads` exactly.
        """
        for name, v in (("velocity", velocity), ("density", density), ("chord", chord)):
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be positive and finite, got {v}")
        if not (0.0 < axis < 1.0):
            raise ValueError(f"axis must lie in (0, 1) (chord fraction from the LE), got {axis}")
        if not isinstance(self.static_model, ThinAirfoilFlap):
            raise TypeError("matrices() needs the linear thin-airfoil static model; linearise a "
                            "table model about its operating point instead")
        zero = {k: 0.0 for k in ("alpha", "alpha_rate", "alpha_accel", "plunge_rate",
                                 "plunge_accel", "delta", "delta_rate", "delta_accel")}
        flow = dict(velocity=velocity, density=density, chord=chord, axis=axis, mach=mach)

        def column(**unit):
            base = self.static_model.loads(**zero, **flow)
            out = self.static_model.loads(**{**zero, **unit}, **flow)
            return np.array([out[k] - base[k] for k in _LOADS])

        kx = np.column_stack([np.zeros(4), column(alpha=1.0), column(delta=1.0)])
        cx = np.column_stack([column(plunge_rate=1.0), column(alpha_rate=1.0),
                              column(delta_rate=1.0)])
        mx = np.column_stack([column(plunge_accel=1.0), column(alpha_accel=1.0),
                              column(delta_accel=1.0)])
        # lambda_0 acts as -lambda_0/U on the static angle of attack
        d = np.outer(-kx[:, 1] / velocity, self.wake.g)
        q0, q1 = self._q_coefficients(velocity, chord, axis)
        n = self.n_states
        return SectionMatrices(Mx=mx, Cx=cx, Kx=kx, D=d, E=np.array(self.wake.E),
                               F=(2.0 * velocity / chord) * np.eye(n),
                               cvec=np.array(self.wake.cvec), q0=q0, q1=q1)

    def frequency_response(self, reduced_frequency, *, velocity, density, chord, axis=0.25,
                           mach=0.0) -> np.ndarray:
        """Complex loads per unit harmonic motion at ``k = omega b / U``: shape (..., 4, 3).

        Rows ``(L, M, L_f, H)``, columns ``(h, alpha, delta)`` (see
        :class:`SectionMatrices`); ``y(t) = Re(y_hat e^{i omega t})``.
        """
        k = np.asarray(reduced_frequency, dtype=float)
        if not np.all(np.isfinite(k)) or np.any(k < 0.0):
            raise ValueError(f"reduced frequency must be finite and >= 0, "
                             f"got {reduced_frequency}")
        mats = self.matrices(velocity=velocity, density=density, chord=chord, axis=axis, mach=mach)
        return mats.frequency_response(k * velocity / (0.5 * chord))
