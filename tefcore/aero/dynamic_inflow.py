"""Pitt-Peters dynamic inflow: three inflow states (mean, sine, cosine).

docs/theory.md section 3.10.  The induced inflow over the disk (positive down,
units of the tip speed ``Omega R``, ``x = r/R``) is

    lambda_i(x, psi) = lambda_0 + x (lambda_s sin psi + lambda_c cos psi)

and the states obey, in the azimuth ``psi = Omega t`` (``*`` = d/dpsi),

    M lam* + V L^-1 lam = C,        lam = (lambda_0, lambda_s, lambda_c)

with the aerodynamic load coefficients of all blades (``rho pi R^2 (Omega R)^2``
and ``R``; lift up)::

    C_T = sum_blades int F_z dr / (rho pi R^2 (Omega R)^2)
    C_s = sum_blades int F_z r sin psi dr / (rho pi R^2 (Omega R)^2 R)   (advancing side up)
    C_c = sum_blades int F_z r cos psi dr / (rho pi R^2 (Omega R)^2 R)   (rear of the disk up)

Signs: every component is positive where it adds downwash or lift at the
azimuth where its harmonic is positive (Pitt & Peters wrote the moments with
the opposite sign, which makes their ``L22, L33, M22, M33`` negative).  ``L``
depends on the wake skew angle ``chi = atan(mu / lambda)`` through
``X = tan(chi/2)`` (Peters & HaQuang 1988)::

        [ 1/2               0           -15 pi X / 64 ]
    L = [ 0            2 (1 + X^2)       0            ]
        [ 15 pi X / 64      0           2 (1 - X^2)   ]

(a thrust raises the downwash at the rear, ``L31 > 0``; load at the rear adds
less mean inflow than load at the front, ``L13 < 0``).  ``V = diag(v_T, v, v)``
for the steady solution, ``V = v I`` for perturbations, with the total flow
``v_T = sqrt(mu^2 + lambda^2)`` and the mass-flow parameter
``v = (mu^2 + lambda (lambda + lambda_0)) / v_T``; ``M = diag(m0, 16/(45 pi),
16/(45 pi))`` with ``m0 = 128/(75 pi)`` (Pitt & Peters 1981) or ``8/(3 pi)``
(apparent mass of the impermeable disk, Peters & HaQuang 1988).

The steady mean equation is Glauert's momentum theory (:mod:`tefcore.aero.inflow`);
the harmonics give the Pitt-Peters longitudinal gradient
``lambda_c / lambda_0 = (15 pi / 32) tan(chi/2)``.

Examples
--------
>>> st = steady_inflow(0.008, advance_ratio=0.0)
>>> round(st.mean, 10), st.sine, st.cosine          # hover: momentum theory
(0.0632455532, 0.0, 0.0)
>>> lin = perturbation_matrices(st)
>>> [round(float(t), 4) for t in lin.time_constants]   # rad: m0/(4 lambda_0), 32/(45 pi 2 lambda_0)
[2.1474, 1.7895, 1.7895]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .inflow import Inflow, momentum_inflow

__all__ = [
    "APPARENT_MASS",
    "InflowPerturbation",
    "SteadyInflow",
    "apparent_mass",
    "l_matrix",
    "mass_flow",
    "perturbation_matrices",
    "steady_inflow",
    "wake_skew",
]

#: Mean-inflow apparent mass ``M11`` by source: Pitt & Peters (1981) from the
#: actuator-disk pressure distribution; Peters & HaQuang (1988) the impermeable disk.
APPARENT_MASS = {"pitt_peters": 128.0 / (75.0 * math.pi), "peters_haquang": 8.0 / (3.0 * math.pi)}


def _finite(name, value):
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value}")
    return v


def wake_skew(advance_ratio: float, total_inflow: float) -> float:
    """Wake skew angle ``chi = atan2(mu, lambda)`` [rad]: 0 in hover, pi/2 edgewise.

    >>> round(math.degrees(wake_skew(0.3, 0.03)), 4)
    84.2894

    Parameters
    ----------
    advance_ratio : float
        mu.
    total_inflow : float
        lambda, the total inflow ratio (positive down through the disk).

    Returns
    -------
    float
    """
    mu = _finite("advance_ratio", advance_ratio)
    lam = _finite("total_inflow", total_inflow)
    if mu < 0:
        raise ValueError(f"advance_ratio must be >= 0, got {mu}")
    if lam <= 0 and mu == 0:
        raise ValueError(f"hover needs a positive inflow, got total_inflow={lam}")
    return math.atan2(mu, lam)


def l_matrix(chi: float) -> np.ndarray:
    """Pitt-Peters ``L`` (per unit flow parameter) at wake skew ``chi`` in [0, pi/2] rad.

    Parameters
    ----------
    chi : float
        Wake skew angle [rad] in [0, pi/2].

    Returns
    -------
    numpy.ndarray
        3 x 3, rows and columns (mean, sine, cosine).

    References
    ----------
    Pitt, D. M. & Peters, D. A., "Theoretical prediction of dynamic-inflow
    derivatives", Vertica 5(1), 21-34, 1981; Peters, D. A. & HaQuang, N.,
    "Dynamic inflow for practical applications", J. American Helicopter
    Society 33(4), 64-68, 1988 (the ``X = tan(chi/2)`` form).

    >>> l_matrix(0.0).tolist()
    [[0.5, 0.0, -0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]
    """
    chi = _finite("chi", chi)
    if not (0.0 <= chi <= 0.5 * math.pi):
        raise ValueError(f"wake skew angle chi must lie in [0, pi/2] rad, got {chi}")
    x = math.tan(0.5 * chi)
    k = 15.0 * math.pi / 64.0 * x
    return np.array([[0.5, 0.0, -k], [0.0, 2.0 * (1.0 + x * x), 0.0],
                     [k, 0.0, 2.0 * (1.0 - x * x)]])


def apparent_mass(kind: str = "pitt_peters") -> np.ndarray:
    """``M = diag(m0, 16/(45 pi), 16/(45 pi))`` with ``m0 = APPARENT_MASS[kind]``.

    Parameters
    ----------
    kind : {"pitt_peters", "peters_haquang"}, optional
        Source of the mean-inflow apparent mass (:data:`APPARENT_MASS`).

    Returns
    -------
    numpy.ndarray
        3 x 3 diagonal.
    """
    if kind not in APPARENT_MASS:
        raise ValueError(f"apparent mass must be one of {sorted(APPARENT_MASS)}, got {kind!r}")
    m1 = 16.0 / (45.0 * math.pi)
    return np.diag([APPARENT_MASS[kind], m1, m1])


def mass_flow(advance_ratio: float, total_inflow: float, induced: float) -> tuple[float, float]:
    """``(v_T, v)``: total flow ``sqrt(mu^2 + lambda^2)`` and mass-flow parameter
    ``(mu^2 + lambda (lambda + lambda_0)) / v_T`` (Peters & HaQuang 1988).

    Parameters
    ----------
    advance_ratio : float
        mu.
    total_inflow : float
        lambda, the total inflow ratio (positive down through the disk).
    induced : float
        lambda_0, the induced part of the inflow.

    Returns
    -------
    v_total, v_mass : float
    """
    mu, lam, li = (_finite(n, v) for n, v in (("advance_ratio", advance_ratio),
                                              ("total_inflow", total_inflow),
                                              ("induced", induced)))
    vt = math.hypot(mu, lam)
    if vt == 0.0:
        raise ValueError("no flow through the disk (mu = lambda = 0): zero thrust has no "
                         "dynamic inflow time constant")
    return vt, (mu * mu + lam * (lam + li)) / vt


@dataclass(frozen=True)
class SteadyInflow:
    """Steady Pitt-Peters inflow: ``mean, sine, cosine`` (``lambda_0, lambda_s, lambda_c``).

    ``freestream`` is ``mu tan(alpha_s)``, ``chi`` the wake skew angle, ``v_total``
    and ``v_mass`` the flow parameters, ``advance_ratio`` the flight condition.

    Attributes
    ----------
    mean, sine, cosine : float
        lambda_0, lambda_s, lambda_c (induced, positive down).
    freestream : float
        mu tan(alpha_s).
    chi : float
        Wake skew angle [rad].
    v_total, v_mass : float
        Total flow and mass-flow parameters (:func:`mass_flow`).
    advance_ratio : float
        mu.
    """

    mean: float
    sine: float
    cosine: float
    freestream: float
    chi: float
    v_total: float
    v_mass: float
    advance_ratio: float

    def to_inflow(self) -> Inflow:
        """The same field as a :class:`tefcore.aero.inflow.Inflow` (``kx = lambda_c/lambda_0``,
        ``ky = lambda_s/lambda_0``), for the existing trim."""
        if self.mean == 0.0:
            return Inflow(mean_induced=0.0, freestream=self.freestream)
        return Inflow(mean_induced=self.mean, freestream=self.freestream,
                      kx=self.cosine / self.mean, ky=self.sine / self.mean)


def steady_inflow(ct: float, cs: float = 0.0, cc: float = 0.0, *, advance_ratio: float,
                  shaft_angle: float = 0.0) -> SteadyInflow:
    """Steady inflow states for the load coefficients ``(C_T, C_s, C_c)``.

    ``lam = L V^-1 C`` with ``V = diag(v_T, v, v)``: the mean is Glauert's
    momentum solution ``lambda_0 = C_T / (2 v_T)`` (:func:`tefcore.aero.inflow.momentum_inflow`),
    the harmonics follow from ``L``.  ``shaft_angle`` forward tilt [rad].

    Parameters
    ----------
    ct, cs, cc : float
        Thrust, sine and cosine moment coefficients C_T, C_s, C_c.
    advance_ratio : float
        mu.
    shaft_angle : float, optional
        Forward shaft tilt alpha_s [rad].

    Returns
    -------
    SteadyInflow
    """
    ct, cs, cc = (_finite(n, v) for n, v in (("ct", ct), ("cs", cs), ("cc", cc)))
    mu = _finite("advance_ratio", advance_ratio)
    if mu < 0:
        raise ValueError(f"advance_ratio must be >= 0, got {mu}")
    fs = mu * math.tan(_finite("shaft_angle", shaft_angle))
    li = momentum_inflow(ct, mu, shaft_angle)
    lam = fs + li
    if ct <= 0.0 and mu == 0.0:
        raise ValueError(f"hover needs a positive thrust coefficient, got ct={ct}")
    chi = wake_skew(mu, lam)
    vt, v = mass_flow(mu, lam, li)
    ell = l_matrix(chi)
    states = ell @ np.array([ct / vt, cs / v, cc / v])
    return SteadyInflow(mean=li, sine=float(states[1]), cosine=float(states[2]), freestream=fs,
                        chi=chi, v_total=vt, v_mass=v, advance_ratio=mu)


@dataclass(frozen=True)
class InflowPerturbation:
    """Linear dynamic-inflow equations ``mass dlam/dpsi + damping dlam = dC``.

    ``damping = v L^-1`` (``v`` the mass-flow parameter); ``time_constants`` are
    the reciprocal eigenvalues of ``mass^-1 damping`` [rad of azimuth], sorted
    as (mean, sine, cosine) in hover.

    Attributes
    ----------
    mass : numpy.ndarray
        Apparent mass ``M`` (3 x 3).
    damping : numpy.ndarray
        ``v L^-1`` (3 x 3).
    l : numpy.ndarray
        The ``L`` matrix at the steady skew angle (per unit flow parameter).
    v_mass : float
        The mass-flow parameter ``v``.
    """

    mass: np.ndarray
    damping: np.ndarray
    l: np.ndarray
    v_mass: float

    @property
    def time_constants(self) -> np.ndarray:
        """``1 / eig(M^-1 V L^-1)`` (real parts), in radians of azimuth."""
        ev = np.linalg.eigvals(np.linalg.solve(self.mass, self.damping))
        return np.sort(1.0 / ev.real)[::-1]

    def state_matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """``(A, B)`` of ``dlam/dpsi = A dlam + B dC``."""
        minv = np.linalg.inv(self.mass)
        return -minv @ self.damping, minv


def perturbation_matrices(steady: SteadyInflow, kind: str = "pitt_peters") -> InflowPerturbation:
    """Perturbation equations about a steady inflow (Peters & HaQuang 1988).

    ``M dlam* + v L^-1 dlam = dC`` with the mass-flow parameter ``v`` for all three
    states; the mean row is the linearised momentum equation,
    ``d C_T / d lambda_0 = 2 v`` at fixed ``mu`` and shaft angle.  ``L`` is frozen at
    the steady skew angle.

    Parameters
    ----------
    steady : SteadyInflow
        The steady inflow to linearise about (:func:`steady_inflow`).
    kind : {"pitt_peters", "peters_haquang"}, optional
        Source of the mean-inflow apparent mass (:data:`APPARENT_MASS`).

    Returns
    -------
    InflowPerturbation
    """
    ell = l_matrix(steady.chi)
    return InflowPerturbation(mass=apparent_mass(kind),
                              damping=steady.v_mass * np.linalg.inv(ell), l=ell,
                              v_mass=steady.v_mass)
