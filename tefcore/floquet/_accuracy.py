"""Floquet analysis, part 4: accuracy control of :func:`tefcore.floquet.floquet_modes`
(step-doubling error estimates per exponent, docs/theory.md section 5.6a).

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

from ._multipliers import lift, log_roots, root_cut, select_roots
from ._propagators import (
    TWO_PI,
    FloquetAccuracyError,
    FloquetAccuracyWarning,
    FloquetOverflowError,
    group,
    propagators,
    tree_product,
)

__all__ = ["DEFAULT_ATOL", "DEFAULT_RTOL", "MAX_DOUBLINGS", "ON_INACCURATE",
           "check_tolerance", "fastest_root", "coarse_exponents", "error_estimates",
           "inaccurate"]


#: Default absolute tolerance of :func:`floquet_modes` on each exponent's damping
#: rate and frequency (per radian of psi, i.e. /rev for the default period).  The
#: paper's figures resolve real parts to about 0.01 /rev; 1e-3 keeps the sign of
#: any real part beyond 1e-3 /rev right, ten times below what a plot shows.
DEFAULT_ATOL = 1e-3


#: Default relative tolerance, of |sigma| for the damping rate and of |eta| for the
#: frequency: a -24 /rev root is good to 0.025, a 15 /rev frequency to 0.016.
DEFAULT_RTOL = 1e-3


#: ``floquet_modes`` doubles the steps at most this many times by default.
MAX_DOUBLINGS = 5


#: Order of both integrators: the step-doubling estimate divides by 2^4 - 1.
_ORDER = 4


ON_INACCURATE = ("warn", "raise")


def check_tolerance(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number >= 0, got {value!r}") from None
    if not (value >= 0.0 and np.isfinite(value)):
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return value


def fastest_root(a):
    """Eigenvalue of the mean of the samples ``a`` of largest modulus."""
    ev = np.linalg.eigvals(np.mean(a, axis=0))
    return complex(ev[np.argmax(np.abs(ev))])


def coarse_exponents(a, period, k_sub, method, constant, min_rate=None):
    """Exponents (frequency modulo 2 pi / T) with the steps of the samples ``a``, or None.

    None when the coarse grid overflows: then there is no estimate, and the
    caller refines.
    """
    n_steps = (a.shape[0] - 1) // 2
    try:
        p = propagators(a, period / n_steps, constant, method)
        k = min(k_sub, n_steps)
        phis = tree_product(group(p, k)[0])
    except FloquetOverflowError:
        return None
    mu = scipy.linalg.eigvals(lift(phis))
    keep, _ = select_roots(mu, k, phis.shape[-1], root_cut(min_rate, period, k))
    return k * log_roots(mu[keep]) / period


def error_estimates(res, coarse, znorm, atol):
    """Step-doubling error estimate of each exponent, and whether it is meaningful.

    The exponents of the fine grid are matched one to one to those of the
    coarse grid (frequencies compared modulo 2 pi / T, as the integer shift
    may differ), and ``|eta_N - eta_{N/2}| / (2^4 - 1)`` estimates the error
    of ``eta_N`` for a fourth-order method (Richardson).  A root whose
    round-off bound ``(K / T) 1e2 eps ||Z|| / |mu|`` exceeds the estimate's
    use -- a tenth of the estimate or of ``atol`` -- is not "trusted" (heavily
    damped beyond resolution): refining the step cannot improve it.  The
    bound is added to every estimate.
    """
    eta = res.exponents
    unit = TWO_PI / res.period
    d = eta[:, None] - np.asarray(coarse)[None, :]
    d = np.abs(d.real) + 1j * np.abs(np.mod(d.imag + unit / 2, unit) - unit / 2)
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, cols = linear_sum_assignment(np.abs(d))
    est = np.empty(eta.shape, complex)
    est[rows] = d[rows, cols] / (2**_ORDER - 1)
    k_sub = res.n_sub
    mu_abs = np.abs(res.multipliers) ** (1.0 / k_sub)
    with np.errstate(divide="ignore"):
        roundoff = (k_sub / res.period) * 1e2 * np.finfo(float).eps * znorm / mu_abs
    trusted = roundoff <= 0.1 * np.maximum(np.abs(est), atol)
    est = est + roundoff * (1 + 1j)
    return est, trusted


def inaccurate(res, bad, tol_re, tol_im, method, on_inaccurate):
    """Warn or raise: the exponents ``bad`` missed their tolerance at the finest grid."""
    est = res.error_estimates
    excess = np.maximum(est.real / tol_re, est.imag / tol_im)
    k = int(np.flatnonzero(bad)[np.argmax(excess[bad])])
    eta = res.exponents[k]
    msg = (f"Floquet exponent {eta.real:.4g}{eta.imag:+.4g}i not converged at n_steps = "
           f"{res.n_steps} ({method}): error estimate {est[k].real:.2g} in the damping rate, "
           f"{est[k].imag:.2g} in the frequency, tolerance {tol_re[k]:.2g} / {tol_im[k]:.2g} "
           f"({int(bad.sum())} exponent(s) above); its sign and value cannot be trusted. "
           "Raise the step count (n_steps, max_steps; model.n_floquet_steps in a "
           "configuration)" + (" or use method='magnus'" if method == "rk4" else ""))
    if on_inaccurate == "raise":
        raise FloquetAccuracyError(msg)
    warnings.warn(msg, FloquetAccuracyWarning, stacklevel=3)
