"""Rotor inflow: uniform momentum (hover, forward flight) and Drees linear inflow.

Inflow ratios are positive down through the disk, in units of the tip speed
``Omega R``. The shaft angle ``alpha_s`` is positive for forward tilt, which
makes the free stream pass down through the disk: ``lambda = mu tan(alpha_s)
+ lambda_i`` (Leishman, *Principles of Helicopter Aerodynamics*, ch. 2).
The paper uses the Bagai-Leishman free wake; a compact model cannot, and the
linear inflow misses the wake's local peaks (notebooks discuss what that
shifts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Inflow", "drees_gradients", "momentum_inflow", "rotor_inflow"]


@dataclass(frozen=True)
class Inflow:
    """Inflow ratio field over the disk.

    ``lambda(x, psi) = mu tan(alpha_s) + lambda_0 (1 + kx x cos psi + ky x sin psi)``.

    Attributes
    ----------
    mean_induced : float
        lambda_0, the momentum-theory induced inflow.
    freestream : float
        ``mu tan(alpha_s)``, the free-stream part.
    kx, ky : float
        Drees longitudinal and lateral gradients (zero for uniform inflow).
    """

    mean_induced: float
    freestream: float = 0.0
    kx: float = 0.0
    ky: float = 0.0

    @property
    def total(self) -> float:
        """Mean total inflow ratio."""
        return self.freestream + self.mean_induced

    def __call__(self, x, psi):
        x, psi = np.asarray(x, float), np.asarray(psi, float)
        shape = np.broadcast_shapes(x.shape, psi.shape)
        # trigonometry on psi's own shape, then broadcast against x
        out = self.freestream + self.mean_induced * (
            1.0 + self.kx * x * np.cos(psi) + self.ky * x * np.sin(psi))
        return out if np.shape(out) == shape else np.broadcast_to(out, shape).copy()


def momentum_inflow(ct: float, advance_ratio: float, shaft_angle: float = 0.0) -> float:
    """Mean induced inflow from momentum theory (Glauert), ``lambda_i``.

    Solves ``lambda_i = C_T / (2 sqrt(mu^2 + lambda^2))`` with
    ``lambda = mu tan(alpha_s) + lambda_i``; in hover ``sqrt(C_T / 2)``.

    Parameters
    ----------
    ct : float
        Thrust coefficient (negative thrust gives negative inflow).
    advance_ratio : float
        mu.
    shaft_angle : float
        Forward tilt [rad].

    Returns
    -------
    float

    Examples
    --------
    >>> round(momentum_inflow(0.008, 0.0), 10)
    0.0632455532
    """
    if not np.isfinite(ct):
        raise ValueError(f"thrust coefficient must be finite, got {ct}")
    mu = advance_ratio
    lam_fs = mu * np.tan(shaft_angle)
    if ct == 0.0:
        return 0.0
    if mu == 0.0 and lam_fs == 0.0:
        return float(np.sign(ct) * np.sqrt(abs(ct) / 2.0))

    hover = np.sqrt(abs(ct) / 2.0)
    lo, hi = (1e-12, 2 * hover) if ct > 0 else (-2 * hover, -1e-12)
    return _momentum_root(float(ct), float(mu), float(lam_fs), lo, hi)


def _momentum_root(ct: float, mu: float, lam_fs: float, lo: float, hi: float,
                   xtol: float = 1e-14, max_iter: int = 200) -> float:
    """The root of ``g(l) = l - C_T / (2 sqrt(mu^2 + (lam_fs + l)^2))`` in ``[lo, hi]``.

    Newton's iteration on ``g`` with its exact slope ``g' = 1 + C_T lam / (2 r^3)``
    (the usual way of solving the momentum equation, Johnson, *Helicopter
    Theory*, sec. 4.1.1), kept inside a bracket that shrinks by the sign of
    ``g`` and bisected whenever a Newton step would leave it: the same root a
    bracketing solver finds (``scipy.optimize.brentq`` agrees to 1e-14;
    tests/aero/test_inflow.py compares the two), without importing
    :mod:`scipy.optimize` (0.15-0.2 s of a one-point command, measured with
    ``python -X importtime``).  ``ValueError`` when ``g`` has one sign at both
    ends.
    """
    def g(li):
        lam = lam_fs + li
        r = math.hypot(mu, lam)
        return li - ct / (2.0 * r), 1.0 + ct * lam / (2.0 * r**3)

    g_lo, g_hi = g(lo)[0], g(hi)[0]
    if g_lo == 0.0 or g_hi == 0.0:
        return lo if g_lo == 0.0 else hi
    if (g_lo > 0.0) == (g_hi > 0.0):
        raise ValueError(f"momentum inflow: no root between {lo:.6g} and {hi:.6g} "
                         f"(C_T = {ct:.6g}, mu = {mu:.6g}, mu tan(alpha_s) = {lam_fs:.6g})")
    rising = g_hi > 0.0
    x = min(max(ct / (2.0 * math.hypot(mu, lam_fs + 0.5 * (lo + hi))), lo), hi)
    for _ in range(max_iter):
        gx, slope = g(x)
        if gx == 0.0:
            return x
        if (gx > 0.0) == rising:
            hi = x
        else:
            lo = x
        step = gx / slope if slope != 0.0 else math.inf
        x_new = x - step
        if not lo < x_new < hi:          # Newton would leave the bracket: bisect
            x_new = 0.5 * (lo + hi)
        if abs(x_new - x) <= xtol or hi - lo <= xtol:
            return x_new
        x = x_new
    raise ValueError(f"momentum inflow: no convergence in {max_iter} iterations "
                     f"(C_T = {ct:.6g}, mu = {mu:.6g})")


def drees_gradients(advance_ratio: float, total_inflow: float) -> tuple[float, float]:
    """Drees (1949) linear inflow gradients ``(kx, ky)``.

    ``kx = 4/3 (1 - cos chi - 1.8 mu^2) / sin chi``, ``ky = -2 mu``, with the
    wake skew angle ``chi = atan(mu / lambda)``; zero in hover.

    Parameters
    ----------
    advance_ratio : float
        mu.
    total_inflow : float
        lambda, the total inflow ratio.

    Returns
    -------
    kx, ky : float
    """
    mu = advance_ratio
    if mu == 0.0:
        return 0.0, 0.0
    chi = np.arctan2(mu, total_inflow)
    return float(4.0 / 3.0 * (1.0 - np.cos(chi) - 1.8 * mu**2) / np.sin(chi)), -2.0 * mu


def rotor_inflow(ct: float, advance_ratio: float, shaft_angle: float = 0.0,
                 model: str = "linear") -> Inflow:
    """Inflow field for a thrust coefficient and flight condition.

    Parameters
    ----------
    model : {'linear', 'uniform'}
        'linear' adds the Drees gradients in forward flight.
    ct : float
        Thrust coefficient C_T.
    advance_ratio : float
        mu.
    shaft_angle : float, optional
        Forward shaft tilt [rad].

    Returns
    -------
    Inflow
    """
    if model not in ("linear", "uniform"):
        raise ValueError(f"inflow model must be 'linear' or 'uniform', got {model!r}")
    li = momentum_inflow(ct, advance_ratio, shaft_angle)
    fs = advance_ratio * np.tan(shaft_angle)
    kx, ky = (drees_gradients(advance_ratio, fs + li) if model == "linear" else (0.0, 0.0))
    return Inflow(mean_induced=li, freestream=fs, kx=kx, ky=ky)
