"""Aerodynamic states of the rotor model: shed wake per station, dynamic inflow.

docs/theory.md section 6.2.  Two kinds of first-order states are appended to
the blade and flap coordinates when the configuration asks for them:

* **Shed-wake states** (``model.aero = "unsteady"``), ``N = model.wake_states``
  per aerodynamic station, in the *lagged-upwash* form of the finite-state
  wake of :mod:`tefcore.aero.unsteady`.  With the wake ``E lam' + lam = c Q'``
  (reduced time) and ``kappa = E^-1 c``, the states ``w = kappa Q - lam``
  obey, in the azimuth ``psi``,

  ``w* = (U R / b) E^-1 (kappa Q - w)``,     ``lambda_0 = g.kappa Q - g.w``

  (``U`` the section speed in ``Omega R``, ``R/b`` radius over semichord):
  an exact change of variables that removes ``Q'`` (no accelerations drive
  the wake) and holds for a time-varying ``U`` (reduced time).  The section
  loads are the quasi-steady ones at ``alpha - arctan(lambda_0 / U)`` (the lag
  angle ``lambda_0 / U`` of the linear theory, kept within 90 deg where ``U``
  vanishes at the reverse-flow boundary).  For the fitted
  wake ``kappa = 1`` and ``g.kappa = 1/2`` (``C(inf) = 1/2``).
* **Dynamic-inflow states** (``model.inflow = "dynamic"``), the Pitt-Peters
  perturbations of :mod:`tefcore.aero.dynamic_inflow` written in the reference
  blade's rotating frame, ``nu = (nu_0, nu_R, nu_I)`` with
  ``nu_R = nu_s sin psi + nu_c cos psi`` (the gradient the blade sees: it
  adds ``nu_0 + x nu_R`` to its inflow) and ``nu_I = nu_s cos psi - nu_c sin psi``:

  ``M nu* + (M J + v R(psi) L^-1 R(psi)) nu = (C_T, C_R, 0)``

  with ``R = diag(1, [[sin, cos], [cos, -sin]])``, ``J = diag(0, [[0, -1], [1, 0]])``
  and the rotor loads of N_b blades that each carry the reference blade's
  loads at its own azimuth: ``C_T = sigma * (C_T/sigma of the blade)`` and
  ``C_R`` the same with each station weighted by ``x``.  For the mean (and
  every collective motion) this is exact; for the cyclic components it keeps
  the fixed-frame mean and leaves a 2/rev error (the exact treatment is a
  multiblade model).  In hover ``R L^-1 R = L^-1`` and the equations have
  constant coefficients.

Examples
--------
>>> from tefcore.aero.unsteady import UnsteadyFlapAirfoil
>>> wake = ShedWake(UnsteadyFlapAirfoil(0.35, 0.29, n_states=4), radius_over_semichord=40.8,
...                 n_stations=2)
>>> wake.n_states, round(wake.g_kappa, 12)
(8, 0.5)
>>> q = np.array([[0.1, 0.2]])            # steady upwash: the wake settles at w = kappa Q
>>> w = q[..., None] * wake.kappa
>>> float(np.abs(wake.induced(q, w)).max()) < 1e-15
True
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .dynamic_inflow import InflowPerturbation, l_matrix, mass_flow, wake_skew

__all__ = ["HarmonicInflow", "InflowLinearization", "ShedWake", "inflow_fields",
           "rotating_inflow_damping", "steady_inflow_residual"]


class ShedWake:
    """Shed-wake states of the aerodynamic stations, lagged-upwash form.

    Parameters
    ----------
    airfoil : tefcore.aero.unsteady.UnsteadyFlapAirfoil
        Gives the wake (``E, c, g``) and the 3/4-chord upwash ``Q`` of the
        section (:meth:`~tefcore.aero.unsteady.UnsteadyFlapAirfoil.upwash`).
    radius_over_semichord : float
        ``R / b``: a station at speed ``U`` (units ``Omega R``) advances
        ``U R / b`` semichords per radian of azimuth.
    n_stations : int
        Number of aerodynamic stations, each with its own ``N`` wake states.

    Attributes
    ----------
    kappa : ndarray (N,)
        ``E^-1 c``: the steady states per unit upwash.
    rate : ndarray (N, N)
        ``E^-1``.
    g : ndarray (N,)
    g_kappa : float
        ``g . kappa = 1 - C(inf)`` (1/2 for a wake with the exact impulsive lift).
    n_per_station, n_states : int
        ``N`` and ``N * n_stations`` (state order: station-major).
    """

    def __init__(self, airfoil, radius_over_semichord: float, n_stations: int):
        wake = airfoil.wake
        self.airfoil = airfoil
        self.rate = np.linalg.inv(wake.E)
        self.kappa = self.rate @ wake.cvec
        self.g = np.asarray(wake.g, float)
        self.g_kappa = float(self.g @ self.kappa)
        self.radius_over_semichord = float(radius_over_semichord)
        self.n_per_station = wake.n_states
        self.n_stations = int(n_stations)

    @property
    def n_states(self) -> int:
        return self.n_per_station * self.n_stations

    def __repr__(self):
        return (f"ShedWake({self.airfoil!r}, radius_over_semichord="
                f"{self.radius_over_semichord:g}, n_stations={self.n_stations})")

    def split(self, rows):
        """States as rows ``(n_states, n_psi)`` -> ``(n_psi, n_stations, N)``."""
        rows = np.asarray(rows)
        return rows.T.reshape(rows.shape[1], self.n_stations, self.n_per_station)

    def join(self, arr):
        """Inverse of :meth:`split`."""
        return arr.reshape(arr.shape[0], self.n_states).T

    def induced(self, upwash, states):
        """``lambda_0 = g.kappa Q - g.w`` (units of ``Q``); ``states`` (..., N)."""
        return self.g_kappa * upwash - states @ self.g

    def residual(self, states, states_d, upwash, speed):
        """``w* - (U R/b) E^-1 (kappa Q - w)``, shape (n_psi, n_stations, N)."""
        drive = upwash[..., None] * self.kappa - states
        return states_d - (speed * self.radius_over_semichord)[..., None] * (drive @ self.rate.T)


# ------------------------------------------------------------------ inflow


@dataclass(frozen=True)
class HarmonicInflow:
    """Inflow ratio ``mu tan(alpha_s) + lambda_0 + x (lambda_s sin psi + lambda_c cos psi)``.

    The steady Pitt-Peters field of a trim with ``model.inflow = "dynamic"``
    (units ``Omega R``, positive down).  ``mean_induced`` and ``total`` as in
    :class:`tefcore.aero.inflow.Inflow`.

    Parameters
    ----------
    mean : float
        ``lambda_0``, the mean induced inflow.
    freestream : float
        ``mu tan(alpha_s)``, the free stream through the disc.
    sine, cosine : float
        ``lambda_s`` and ``lambda_c``, the first-harmonic gradients along the
        blade (per unit ``x = r/R``).

    Examples
    --------
    >>> f = HarmonicInflow(freestream=0.01, mean=0.05, sine=-0.01, cosine=0.02)
    >>> round(float(f(1.0, 0.0)), 12), f.total
    (0.08, 0.060000000000000005)
    """

    mean: float
    freestream: float = 0.0
    sine: float = 0.0
    cosine: float = 0.0

    @property
    def mean_induced(self) -> float:
        return self.mean

    @property
    def total(self) -> float:
        return self.freestream + self.mean

    def __call__(self, x, psi):
        x, psi = np.asarray(x, float), np.asarray(psi, float)
        shape = np.broadcast_shapes(x.shape, psi.shape)
        out = self.freestream + self.mean + x * (self.sine * np.sin(psi)
                                                 + self.cosine * np.cos(psi))
        return out if np.shape(out) == shape else np.broadcast_to(out, shape).copy()


@dataclass(frozen=True)
class InflowLinearization:
    """The trimmed inflow field and its perturbation equations (linearisation only).

    Parameters
    ----------
    steady : object
        The trimmed inflow field, called like any inflow (``steady(x, psi)``).
    perturbation : tefcore.aero.dynamic_inflow.InflowPerturbation
        ``M`` and ``v L^-1`` of the perturbation states
        (:func:`tefcore.aero.dynamic_inflow.perturbation_matrices`).
    solidity : float
        Rotor solidity: turns the blade's ``C_T/sigma`` into the rotor's ``C_T``.
    """

    steady: object
    perturbation: InflowPerturbation
    solidity: float

    def __call__(self, x, psi):
        return self.steady(x, psi)

    @property
    def mean_induced(self) -> float:
        return self.steady.mean_induced

    @property
    def total(self) -> float:
        return self.steady.total


def inflow_fields(inflow) -> tuple[str, ...]:
    """The dataclass fields of an inflow object, for per-azimuth stacking.

    Parameters
    ----------
    inflow : dataclass instance
        An inflow field (:class:`tefcore.aero.inflow.Inflow`, :class:`HarmonicInflow`).

    Returns
    -------
    tuple of str
    """
    return tuple(f.name for f in dataclasses.fields(inflow))


def rotating_inflow_damping(perturbation: InflowPerturbation, psi) -> np.ndarray:
    """``M J + v R(psi) L^-1 R(psi)`` of the rotating-frame states, (len(psi), 3, 3).

    Parameters
    ----------
    perturbation : tefcore.aero.dynamic_inflow.InflowPerturbation
        ``M`` and ``v L^-1`` of the fixed-frame perturbation states.
    psi : array_like
        Azimuths of the reference blade [rad].

    Returns
    -------
    numpy.ndarray
        The damping matrix of the states in the blade's rotating frame.

    Examples
    --------
    Hover: ``L^-1 = diag(2, 1/2, 1/2)`` commutes with ``R``; only ``M J`` couples
    ``nu_R`` and ``nu_I`` (the 1/rev of the frame).

    >>> from tefcore.aero.dynamic_inflow import perturbation_matrices, steady_inflow
    >>> lin = perturbation_matrices(steady_inflow(0.008, advance_ratio=0.0))
    >>> d = rotating_inflow_damping(lin, [0.0, 1.0])
    >>> bool(np.allclose(d[0], d[1])), bool(np.isclose(d[0, 2, 1], lin.mass[1, 1]))
    (True, True)
    """
    psi = np.atleast_1d(np.asarray(psi, float))
    s, c = np.sin(psi), np.cos(psi)
    rot = np.zeros((psi.size, 3, 3))
    rot[:, 0, 0] = 1.0
    rot[:, 1, 1], rot[:, 1, 2], rot[:, 2, 1], rot[:, 2, 2] = s, c, c, -s
    frame = np.zeros((3, 3))
    frame[1, 2], frame[2, 1] = -1.0, 1.0
    return perturbation.mass @ frame + rot @ perturbation.damping @ rot


def steady_inflow_residual(states, ct, cs, cc, *, advance_ratio, freestream):
    """Steady Pitt-Peters equations ``V L^-1 lambda - C`` for the trim.

    ``states = (lambda_0, lambda_s, lambda_c)``, ``C = (C_T, C_s, C_c)`` the rotor's
    load coefficients, ``V = diag(v_T, v, v)``, ``L`` at the wake skew of
    ``lambda = freestream + lambda_0`` (:func:`tefcore.aero.dynamic_inflow.l_matrix`).  In
    hover the mean row is Glauert's ``2 lambda_0^2 = C_T`` exactly; in forward flight
    it keeps ``L13`` (the mean inflow of a pitching moment) where
    :func:`tefcore.aero.dynamic_inflow.steady_inflow` uses momentum theory alone.

    Parameters
    ----------
    states : sequence of float
        ``(lambda_0, lambda_s, lambda_c)``.
    ct, cs, cc : float
        The rotor's thrust and its first-harmonic (sine, cosine) moment coefficients.
    advance_ratio : float
        ``mu``.
    freestream : float
        ``mu tan(alpha_s)``.

    Returns
    -------
    numpy.ndarray
        The three residuals.

    Examples
    --------
    >>> lam0 = np.sqrt(0.008 / 2)
    >>> bool(np.abs(steady_inflow_residual([lam0, 0, 0], 0.008, 0, 0, advance_ratio=0.0,
    ...                                    freestream=0.0)).max() < 1e-17)
    True
    """
    lam0, lam_s, lam_c = (float(v) for v in states)
    lam = freestream + lam0
    vt, v = mass_flow(advance_ratio, lam, lam0)
    ell = l_matrix(wake_skew(advance_ratio, lam))
    out = np.array([vt, v, v]) * np.linalg.solve(ell, np.array([lam0, lam_s, lam_c]))
    return out - np.array([ct, cs, cc], float)
