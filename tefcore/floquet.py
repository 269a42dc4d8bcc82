"""Floquet stability of linear periodic systems ``x' = A(psi) x`` (docs/theory.md section 5).

General tools, independent of the rotor model: any real or complex system
whose matrix is periodic in the azimuth ``psi`` with period ``period``
(default ``2 pi``, so rates and frequencies come out per rev).

* :func:`step_propagators`, :func:`transition_matrices`, :func:`monodromy` --
  the state transition matrix, all columns at once, by classical RK4 written
  as a matrix polynomial (or a fourth-order Magnus exponential), grouped into
  ``n_sub`` sub-interval matrices ``Phi_k``.
* :func:`characteristic_multipliers` -- eigenvalues of the product
  ``Phi_K ... Phi_1`` *without forming it*, by lifting to a block-cyclic
  matrix, so heavily damped modes are not lost.
* :func:`floquet_modes` -- characteristic exponents with the frequency
  ambiguity (integer multiples of ``2 pi / period``) resolved from the
  dominant harmonic of the periodic mode shape; :class:`FloquetResult`.
* :func:`constant_coefficient_modes` -- the same result for a constant
  ``A`` (hover) by direct eigenanalysis.

Default grid: ``n_steps = 144`` RK4 steps per period (2.5 deg) in
``n_sub = 8`` sub-intervals of 45 deg, raised up to :data:`MAX_SUB` for
heavily damped roots (:data:`MIN_ROOT`); see :data:`DEFAULT_N_STEPS`,
:data:`DEFAULT_N_SUB` and the theory notes for why.  :func:`floquet_modes`
controls its own accuracy: a step-doubling error estimate per exponent, and
the steps doubled until every exponent meets ``atol + rtol |sigma|`` in its
damping rate and ``atol + rtol |eta|`` in its frequency
(:data:`DEFAULT_ATOL`, :data:`DEFAULT_RTOL`);
if it cannot, :class:`FloquetAccuracyWarning` or :class:`FloquetAccuracyError`
(docs/theory.md section 5.6a).

Longer than ~400 lines because it is one algorithm, kept with its verification-oriented docs.

Examples
--------
A damped oscillator (frequency 0.7/rev, damping rate -0.05/rev) seen through
the periodic change of variables ``x = (1 + 0.3 sin psi) z``:

>>> import numpy as np
>>> from tefcore.floquet import floquet_modes
>>> B = np.array([[0.0, 1.0], [-(0.05**2 + 0.7**2), -0.1]])
>>> def A(psi):
...     s = 1 + 0.3 * np.sin(psi)
...     return B + (0.3 * np.cos(psi) / s)[:, None, None] * np.eye(2)
>>> res = floquet_modes(A).positive_frequency()
>>> np.round(res.frequencies, 6), np.round(res.damping_rates, 6)
(array([0.7]), array([-0.05]))
"""

from __future__ import annotations

import numbers
import warnings
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.sparse.csgraph

from .errors import TefcoreError

__all__ = [
    "DEFAULT_ATOL",
    "DEFAULT_N_STEPS",
    "DEFAULT_N_SUB",
    "DEFAULT_RTOL",
    "MAX_DOUBLINGS",
    "MAX_SUB",
    "MIN_ROOT",
    "FloquetAccuracyError",
    "FloquetAccuracyWarning",
    "FloquetOverflowError",
    "FloquetResult",
    "characteristic_multipliers",
    "constant_coefficient_modes",
    "damping_ratio",
    "floquet_modes",
    "monodromy",
    "step_propagators",
    "transition_matrices",
]

#: RK4 steps per period. 2.5 deg steps: the RK4 damping error of a frozen mode
#: of frequency w is about ``w**6 h**5 / 144`` per rad, < 2e-5 /rev up to 5/rev
#: (lag, flap, first torsion), ~1e-3 /rev at 10/rev; the frequency error
#: ``w**5 h**4 / 120`` is ~1e-4 /rev at 5/rev. 144 = 8 x 18.
DEFAULT_N_STEPS = 144
#: Sub-intervals (lifting blocks). Each ``Phi_k`` spans 45 deg, so a mode of
#: rate sigma enters it as ``exp(sigma pi / 4)``: exponents down to -10/rev
#: keep ~1e-12 accuracy and down to about -45/rev stay resolved, while the
#: lifted eigenproblem (size 8 n) costs ~12 ms for n = 20.
DEFAULT_N_SUB = 8
#: Smallest modulus ``|mu| = |lambda|^(1/K)`` of a lifted root that
#: :func:`floquet_modes` accepts: below it ``n_sub`` is raised (see there).
MIN_ROOT = 1e-3
#: Largest number of sub-intervals :func:`floquet_modes` raises ``n_sub`` to.
MAX_SUB = 16

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

_METHODS = ("rk4", "magnus")
_TWO_PI = 2.0 * np.pi
_ON_INACCURATE = ("warn", "raise")


class FloquetAccuracyError(TefcoreError, RuntimeError):
    """The Floquet exponents could not be computed to the requested accuracy."""


class FloquetOverflowError(FloquetAccuracyError, ValueError):
    """A transition matrix overflowed: the step is too long for the system."""


class FloquetAccuracyWarning(RuntimeWarning):
    """The Floquet exponents did not meet the requested accuracy (see the message)."""


# --------------------------------------------------------------------------
# input checks


def _check_int(name, value, minimum):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _check_period(period):
    try:
        period = float(period)
    except (TypeError, ValueError):
        raise ValueError(f"period must be a positive real number, got {period!r}") from None
    if not (np.isfinite(period) and period > 0.0):
        raise ValueError(f"period must be a positive finite number, got {period!r}")
    return period


def _check_method(method):
    if method not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
    return method


def _as_numeric(a, what):
    """Float or complex copy-free view of ``a``; anything else is refused."""
    if a.dtype.kind in "biu":
        return a.astype(float)
    if a.dtype.kind not in "fc":
        raise ValueError(f"{what} must be a real or complex numeric array, got dtype {a.dtype}")
    return a


def _check_finite(a, psi, what):
    bad = ~np.isfinite(a).all(axis=(1, 2))
    if bad.any():
        first = int(np.argmax(bad))
        raise ValueError(f"{what} has non-finite entries (NaN or inf) at psi = {psi[first]:.6g}"
                         f" (sample {first} of {len(psi)})")


def _sample(A, n_steps, period):
    """A at the step ends and midpoints ``psi_j = j h / 2``, j = 0..2N: (2N+1, n, n).

    Returns the samples, the number of steps and whether A is constant.
    """
    period = _check_period(period)
    if callable(A):
        n = DEFAULT_N_STEPS if n_steps is None else _check_int("n_steps", n_steps, 1)
        psi = np.linspace(0.0, period, 2 * n + 1)
        a = np.asarray(A(psi))
        if a.ndim != 3 or a.shape[0] != psi.size:
            raise ValueError(
                f"A(psi) must be vectorised: for an array of {psi.size} azimuths it must return "
                f"shape ({psi.size}, n, n), got {a.shape}. Build the matrices with numpy "
                "broadcasting, e.g. A0 + np.cos(psi)[:, None, None] * A1.")
        a = _as_numeric(a, "A(psi)")
        what, constant = "A(psi)", False
    else:
        a = _as_numeric(np.asarray(A), "A")
        if a.ndim == 2:
            n = DEFAULT_N_STEPS if n_steps is None else _check_int("n_steps", n_steps, 1)
            a = np.broadcast_to(a, (2 * n + 1, *a.shape))
            psi = np.linspace(0.0, period, 2 * n + 1)
            what, constant = "A", True
        elif a.ndim == 3:
            m = a.shape[0]
            if m < 2 or m % 2:
                raise ValueError(
                    "samples of A must lie on the periodic grid psi_j = j*period/M, j = 0..M-1, "
                    f"with M = 2*n_steps (step ends and midpoints): M must be even, got M = {m}")
            if n_steps is not None and _check_int("n_steps", n_steps, 1) != m // 2:
                raise ValueError(f"{m} samples of A give n_steps = {m // 2}, got n_steps = "
                                 f"{n_steps}; pass n_steps=None or resample A")
            n = m // 2
            a = np.concatenate([a, a[:1]])          # A(period) = A(0): A is periodic
            psi = np.linspace(0.0, period, 2 * n + 1)
            what, constant = "samples of A", False
        else:
            raise ValueError("A must be a callable A(psi), an (n, n) constant matrix or "
                             f"(2*n_steps, n, n) periodic samples, got an array of shape {a.shape}")
    if a.shape[1] != a.shape[2] or a.shape[1] == 0:
        raise ValueError(f"{what} must be square n x n with n >= 1, got {a.shape[1:]} matrices")
    _check_finite(a[:1] if constant else a, psi, what)
    return a, n, constant


def _rk4_step_warning(a, h, n_steps):
    """Warn when the frozen-coefficient RK4 step leaves its reliable range.

    RK4 is stable only for ``|h lambda| < ~2.8``; beyond it a damped mode
    can come out neutral or unstable, a silent wrong answer in a stability code.
    """
    z = h * np.linalg.eigvals(a.mean(axis=0))
    worst = float(np.abs(z).max())
    if worst > 2.5:
        warnings.warn(
            f"RK4 step h = {h:.4g} times the largest eigenvalue of the mean A is {worst:.3g} "
            "(stability limit ~2.8): results are unreliable; increase n_steps to at least "
            f"{int(np.ceil(n_steps * worst / 1.5))} or use method='magnus'",
            RuntimeWarning, stacklevel=3)


# --------------------------------------------------------------------------
# transition matrices


def step_propagators(A, n_steps=None, period=_TWO_PI, method="rk4"):
    """One-step transition matrices of ``x' = A(psi) x`` on a uniform grid.

    All steps are evaluated at once: ``A`` is sampled at the ``2 n_steps + 1``
    step ends and midpoints in one call, and the step propagators are built
    with batched matrix products, acting on all columns of the state at once.

    Parameters
    ----------
    A : callable or array_like
        Either a vectorised callable ``A(psi)`` that takes an array of
        azimuths and returns an array of shape ``(len(psi), n, n)``; or a
        constant ``(n, n)`` matrix; or samples of shape ``(2 n_steps, n, n)``
        on the periodic grid ``psi_j = j period / (2 n_steps)``,
        ``j = 0 .. 2 n_steps - 1`` (step ends and midpoints; ``A(period)``
        is taken equal to ``A(0)``). Real or complex.
    n_steps : int, optional
        Number of steps per period. Default :data:`DEFAULT_N_STEPS` (144);
        for samples it is implied by their number.
    period : float, optional
        Period ``T`` of ``A`` in the units of ``psi`` (default ``2 pi``).
    method : {'rk4', 'magnus'}, optional
        ``'rk4'``: classical Runge-Kutta as the matrix polynomial
        ``P = I + h/6 (K1 + 2 K2 + 2 K3 + K4)`` with ``K1 = A(psi)``,
        ``K2 = A(psi + h/2)(I + h/2 K1)``, ``K3 = A(psi + h/2)(I + h/2 K2)``,
        ``K4 = A(psi + h)(I + h K3)``.
        ``'magnus'``: fourth-order Magnus exponential with Simpson nodes,
        ``P = expm(h/6 (A0 + 4 Am + A1) + h^2/12 [A1, A0])``: same samples,
        2-3x the cost per step, exact for constant ``A``, error set by the
        variation of ``A`` rather than by the mode frequencies, and free of
        the RK4 step limit ``|h lambda| < 2.8``: preferred for stiff or
        heavily damped states, and usually more accurate per unit time.

    Returns
    -------
    P : ndarray, shape (n_steps, n, n)
        ``P[m]`` maps ``x(m h)`` to ``x((m + 1) h)``, ``h = period / n_steps``.

    Raises
    ------
    ValueError
        If ``A`` is not square, has the wrong shape, or has non-finite
        entries; if a parameter is invalid; or if a propagator overflows.

    Warns
    -----
    RuntimeWarning
        With ``method='rk4'``, if ``h |lambda|`` of the mean ``A`` exceeds 2.5.

    References
    ----------
    .. [1] E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary
       Differential Equations I*, 2nd ed., Springer, 1993, sec. II.1.
    .. [2] S. Blanes, F. Casas, J. A. Oteo, J. Ros, "The Magnus expansion and
       some of its applications", Phys. Rep. 470 (2009) 151-238.

    Examples
    --------
    >>> import numpy as np
    >>> P = step_propagators(np.array([[0.0, 1.0], [-1.0, 0.0]]), n_steps=72)
    >>> P.shape
    (72, 2, 2)
    >>> h = 2 * np.pi / 72                     # exact step: a rotation by h
    >>> bool(np.allclose(P[0], [[np.cos(h), np.sin(h)], [-np.sin(h), np.cos(h)]], atol=1e-7))
    True
    """
    method = _check_method(method)
    a, n_steps, constant = _sample(A, n_steps, period)
    h = _check_period(period) / n_steps
    if method == "rk4":
        _rk4_step_warning(a[:3] if constant else a, h, n_steps)
    return _propagators(a, h, constant, method)


def _propagators(a, h, constant, method):
    """Step propagators from the samples ``a`` (2N + 1, n, n) of step ends and midpoints."""
    n_steps = (a.shape[0] - 1) // 2
    if constant:                            # every step is the same: compute one
        a = a[:3]
    a0, am, a1 = a[0:-1:2], a[1::2], a[2::2]
    eye = np.eye(a.shape[-1])
    with np.errstate(over="ignore", invalid="ignore"):
        if method == "rk4":                 # in place: few temporaries of (N, n, n)
            k2 = am @ a0
            k2 *= h / 2
            k2 += am
            k3 = am @ k2
            k3 *= h / 2
            k3 += am
            k4 = a1 @ k3
            k4 *= h
            k4 += a1
            p = k2
            p += k3
            p *= 2
            p += a0
            p += k4
            p *= h / 6
            p += eye
        else:
            omega = (h / 6) * (a0 + 4 * am + a1) + (h * h / 12) * (a1 @ a0 - a0 @ a1)
            p = scipy.linalg.expm(omega)
    if not np.isfinite(p).all():
        raise FloquetOverflowError(f"step propagator overflowed (h = {h:.4g}); A is too "
                                   "large for this step: increase n_steps")
    if constant:
        p = np.broadcast_to(p, (n_steps, *p.shape[1:]))
    return p


def _group(p, n_sub):
    """Consecutive steps in ``n_sub`` groups, padded with I: (K, L, n, n), bounds."""
    n_steps, n = p.shape[0], p.shape[-1]
    bounds = (np.arange(n_sub + 1) * n_steps) // n_sub       # lengths differ by <= 1
    lengths = np.diff(bounds)
    idx = bounds[:-1, None] + np.arange(lengths.max())
    valid = idx < bounds[1:, None]
    stack = p[np.minimum(idx, n_steps - 1)]
    stack[~valid] = np.eye(n)               # padding at the end of a group: no effect
    return stack, bounds, valid


def _tree_product(stack):
    """Ordered products ``S[:, L-1] ... S[:, 0]`` by pairwise (tree) reduction.

    Raises :class:`FloquetOverflowError` if a product overflows.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        while stack.shape[1] > 1:
            if stack.shape[1] % 2:
                eye = np.broadcast_to(np.eye(stack.shape[-1]),
                                      (stack.shape[0], 1, *stack.shape[2:]))
                stack = np.concatenate([stack, eye], axis=1)
            stack = stack[:, 1::2] @ stack[:, 0::2]
    if not np.isfinite(stack).all():
        raise FloquetOverflowError("the transition matrices overflow: the system is too stiff "
                                   "for this step (increase n_steps, or use method='magnus')")
    return stack[:, 0]


def transition_matrices(A, n_steps=None, n_sub=DEFAULT_N_SUB, period=_TWO_PI, method="rk4"):
    """Transition matrices ``Phi_k`` of ``n_sub`` consecutive sub-intervals.

    ``Phi_k = Phi(psi_k, psi_{k-1})`` over ``[psi_{k-1}, psi_k]``, where the
    ``n_steps`` steps are split into ``n_sub`` groups of consecutive steps
    (equal when ``n_sub`` divides ``n_steps``, otherwise differing by one
    step). Their product ``Phi_K ... Phi_1`` is the monodromy matrix; keeping
    the factors lets :func:`characteristic_multipliers` find its eigenvalues
    without the cancellation of the explicit product.

    Parameters
    ----------
    A, n_steps, period, method
        As in :func:`step_propagators`.
    n_sub : int, optional
        Number of sub-intervals ``K``, ``1 <= K <= n_steps``. Default
        :data:`DEFAULT_N_SUB` (8).

    Returns
    -------
    Phi : ndarray, shape (n_sub, n, n)

    Raises
    ------
    ValueError
        As :func:`step_propagators`, or if ``n_sub`` is not in ``1..n_steps``.

    Examples
    --------
    >>> import numpy as np
    >>> Phi = transition_matrices(-np.eye(1), n_steps=8, n_sub=4, method="magnus")
    >>> np.allclose(Phi[:, 0, 0], np.exp(-np.pi / 2))
    True
    """
    p = step_propagators(A, n_steps, period, method)
    n_sub = _check_sub(n_sub, len(p))
    return _tree_product(_group(p, n_sub)[0])


def _check_sub(n_sub, n_steps):
    n_sub = _check_int("n_sub", n_sub, 1)
    if n_sub > n_steps:
        raise ValueError(f"n_sub = {n_sub} exceeds n_steps = {n_steps}")
    return n_sub


def monodromy(A, n_steps=None, period=_TWO_PI, method="rk4"):
    """Monodromy (Floquet transition) matrix ``Phi(period, 0)`` as one explicit product.

    For users and tests. Its eigenvalues lose the multipliers below about
    ``eps ||Phi||`` (heavily damped modes); use :func:`floquet_modes` or
    :func:`characteristic_multipliers` for those.

    Parameters
    ----------
    A, n_steps, period, method
        As in :func:`step_propagators`.

    Returns
    -------
    Phi : ndarray, shape (n, n)

    Raises
    ------
    ValueError
        As :func:`step_propagators`.

    References
    ----------
    .. [1] D. A. Peters, K. H. Hohenemser, "Application of the Floquet
       transition matrix to problems of lifting rotor stability", J. Am.
       Helicopter Soc. 16(2) (1971) 25-33.

    Examples
    --------
    Liouville's formula, ``det Phi = exp(int_0^T tr A)``:

    >>> import numpy as np
    >>> def A(psi):
    ...     one, zero = np.ones_like(psi), np.zeros_like(psi)
    ...     return np.stack([[zero, one], [-one, -0.2 - 0.1 * np.sin(psi)]]).transpose(2, 0, 1)
    >>> Phi = monodromy(A)
    >>> bool(np.isclose(np.linalg.det(Phi), np.exp(-0.2 * 2 * np.pi), rtol=1e-6))
    True
    """
    return transition_matrices(A, n_steps, 1, period, method)[0]


# --------------------------------------------------------------------------
# characteristic multipliers by lifting


def _lifted(phis, cut=0.0, left=False):
    """Eigen-decomposition of the block-cyclic lift, one root per multiplier.

    Returns the selected roots ``mu`` (``mu**K`` are the multipliers), the
    eigenvector blocks ``v_k`` of shape (K, n, n) (``v_0`` is the monodromy
    eigenvector at psi = 0 and ``v_k = Phi_k ... Phi_1 v_0 / mu**k``) and
    whether the roots split into one per multiplier (False: some are at
    round-off level and unreliable); with ``cut > 0`` only the roots with
    ``|mu| >= cut`` are judged (:func:`_select_roots`).  ``left``: also the
    blocks ``u_k`` of the left eigenvectors (``u_k = Phi_k^H u_{k+1} / conj(mu)``,
    the adjoint solution at the start of sub-interval ``k``), as a fourth item.
    """
    k_sub, n = phis.shape[0], phis.shape[1]
    if left:
        mu, lvec, vec = scipy.linalg.eig(_lift(phis), left=True)
    else:
        mu, vec = scipy.linalg.eig(_lift(phis))
    keep, split = _select_roots(mu, k_sub, n, cut)
    blocks = vec[:, keep].reshape(k_sub, n, n)
    if left:
        return mu[keep], blocks, split, lvec[:, keep].reshape(k_sub, n, n)
    return mu[keep], blocks, split


def _lift(phis):
    """The block-cyclic matrix ``Z`` of the sub-interval transition matrices."""
    k_sub, n = phis.shape[0], phis.shape[1]
    z = np.zeros((k_sub * n, k_sub * n), dtype=phis.dtype)
    z4 = z.reshape(k_sub, n, k_sub, n)
    z4[(np.arange(k_sub) + 1) % k_sub, :, np.arange(k_sub), :] = phis   # Phi_k below diag
    return z


def _select_roots(mu, k_sub, n, cut=0.0):
    """Mask of one root ``mu`` per multiplier among the ``K n`` roots of the lift.

    ``cut > 0``: roots with ``|mu| < cut`` need not be resolved (``min_rate`` of
    :func:`floquet_modes`); the window and the splitting are decided by the
    others, and the deep ones fill the selection up to ``n``.
    """
    if cut > 0.0:
        return _select_resolved(mu, k_sub, n, cut)
    # The K n eigenvalues are the K K-th roots mu w^j (w = exp(2 pi i / K)) of
    # every multiplier, so modulo 2 pi / K their angles collapse to n points.
    # Any half-open window of width 2 pi / K holds one root per multiplier;
    # starting it in the widest gap between those points (>= 2 pi / (K n))
    # keeps roundoff from putting two roots of one multiplier in it, or none,
    # e.g. for the pair of roots at +-pi/K of a negative real multiplier.
    sector = _TWO_PI / k_sub
    theta = np.angle(mu)
    s = np.sort(np.mod(theta, sector))
    gaps = np.diff(np.append(s, s[0] + sector))
    start = s[np.argmax(gaps)] + 0.5 * gaps.max()
    keep = np.mod(theta - start, _TWO_PI) < sector
    split = keep.sum() == n
    if not split:
        # only if roots at roundoff level (unresolvable, |mu^K| < ~eps) break
        # the K-fold pattern: keep the largest in the window, fill with the smallest
        inside = np.flatnonzero(keep)[np.argsort(-np.abs(mu[keep]))][:n]
        outside = np.flatnonzero(~keep)[np.argsort(np.abs(mu[~keep]))][:n - inside.size]
        keep = np.zeros_like(keep)
        keep[np.concatenate([inside, outside])] = True
    return keep, split


def _select_resolved(mu, k_sub, n, cut):
    """:func:`_select_roots` judged on the roots with ``|mu| >= cut`` only."""
    big = np.abs(mu) >= cut
    sector = _TWO_PI / k_sub
    theta = np.angle(mu)
    if big.any():
        s = np.sort(np.mod(theta[big], sector))
        gaps = np.diff(np.append(s, s[0] + sector))
        start = s[np.argmax(gaps)] + 0.5 * gaps.max()
    else:
        start = 0.0
    window = np.mod(theta - start, _TWO_PI) < sector
    keep = window & big
    split = keep.sum() * k_sub == big.sum() and keep.sum() <= n
    # fill with the deep roots: the largest in the window first, then the others
    deep = np.flatnonzero(~big & window)[np.argsort(-np.abs(mu[~big & window]))]
    rest = np.flatnonzero(~big & ~window)[np.argsort(-np.abs(mu[~big & ~window]))]
    fill = np.concatenate([deep, rest])[:max(n - keep.sum(), 0)]
    keep[fill] = True
    if keep.sum() > n:                      # not split: keep the n largest of them
        idx = np.flatnonzero(keep)[np.argsort(-np.abs(mu[keep]))][:n]
        keep = np.zeros_like(keep)
        keep[idx] = True
    return keep, bool(split)


def _warn_unsplit(stacklevel=3):
    warnings.warn("lifted eigenvalues do not split into one root per multiplier; "
                  "multipliers near roundoff level are unreliable", RuntimeWarning,
                  stacklevel=stacklevel)


def _log_roots(mu):
    # a root that underflowed to 0 (a mode decaying faster than ~ -700 K / T)
    # gets the smallest normal modulus instead of log(0) = -inf
    tiny = np.finfo(float).tiny
    return np.log(np.maximum(np.abs(mu), tiny)) + 1j * np.angle(mu)


def characteristic_multipliers(phis, return_vectors=False):
    """Eigenvalues of ``Phi_K ... Phi_1`` from its factors, by lifting.

    The block-cyclic matrix ``Z`` (``K n x K n``) with ``Phi_1 .. Phi_{K-1}``
    on its block sub-diagonal and ``Phi_K`` in the top-right corner has the
    eigenvalues ``mu`` with ``mu**K`` = the multipliers, and the first block of
    its eigenvector is the monodromy eigenvector. Unlike the explicit product,
    whose eigenvalues carry absolute errors of about ``eps ||Phi||``, each root
    has a relative error of about ``eps ||Z|| / |mu|`` with ``|mu| = |lambda|^(1/K)``:
    a heavily damped multiplier such as ``exp(-20 pi)`` is found to full accuracy.

    Parameters
    ----------
    phis : array_like, shape (K, n, n) or (n, n)
        Sub-interval transition matrices in time order, e.g. from
        :func:`transition_matrices`; a single matrix is its own product.
    return_vectors : bool, optional
        Also return the eigenvectors of the product (at the start of the
        first sub-interval) as unit columns.

    Returns
    -------
    multipliers : ndarray, shape (n,)
        Characteristic multipliers (complex), unsorted.
    vectors : ndarray, shape (n, n)
        Only if ``return_vectors``.

    Raises
    ------
    ValueError
        If ``phis`` is not a stack of square matrices or is not finite.

    References
    ----------
    .. [1] T. F. Fairgrieve, A. D. Jepson, "O.K. Floquet multipliers", SIAM
       J. Numer. Anal. 28(5) (1991) 1446-1462.
    .. [2] K. Lust, "Improved numerical Floquet multipliers", Int. J.
       Bifurcation Chaos 11(9) (2001) 2389-2410.
    .. [3] A. Bojanczyk, G. Golub, P. Van Dooren, "The periodic Schur
       decomposition. Algorithms and applications", Proc. SPIE 1770 (1992)
       31-42.

    Examples
    --------
    Two factors whose product has eigenvalues 1 and 1e-30:

    >>> import numpy as np
    >>> phis = np.array([np.diag([1.0, 1e-15]), np.array([[1.0, 1.0], [0.0, 1e-15]])])
    >>> sorted(np.abs(characteristic_multipliers(phis)))  # doctest: +ELLIPSIS
    [np.float64(1.0...e-30), np.float64(1.0...)]
    """
    phis = _as_numeric(np.asarray(phis), "phis")
    if phis.ndim == 2:
        phis = phis[None]
    if phis.ndim != 3 or phis.shape[1] != phis.shape[2] or 0 in phis.shape:
        raise ValueError(f"phis must have shape (K, n, n) with K, n >= 1, got {phis.shape}")
    if not np.isfinite(phis).all():
        raise ValueError("phis has non-finite entries (NaN or inf)")
    mu, blocks, split = _lifted(phis)
    if not split:
        _warn_unsplit()
    multipliers = np.exp(phis.shape[0] * _log_roots(mu))
    if not return_vectors:
        return multipliers
    v = blocks[0]
    return multipliers, v / np.linalg.norm(v, axis=0)


# --------------------------------------------------------------------------
# results


def damping_ratio(exponents):
    """Damping ratio ``zeta = -sigma / sqrt(sigma^2 + omega^2)`` of ``eta = sigma + i omega``.

    Positive for a decaying mode; 0 for ``eta = 0``.

    Examples
    --------
    >>> float(damping_ratio(-0.6 + 0.8j))
    0.6
    """
    eta = np.asarray(exponents, dtype=complex)
    mag = np.abs(eta)
    return np.divide(-eta.real, mag, out=np.zeros(eta.shape), where=mag > 0)


@dataclass(frozen=True)
class FloquetResult:
    """Floquet modes of ``x' = A(psi) x``: one entry per characteristic exponent.

    A mode is ``x(psi) = exp(eta psi) p(psi)`` with ``p`` periodic. Entries
    are sorted by frequency, then damping rate; for real ``A`` conjugate
    pairs are both kept (see :meth:`positive_frequency`).

    Attributes
    ----------
    exponents : ndarray, shape (m,)
        Characteristic exponents ``eta = sigma + i omega`` per radian of psi,
        frequency ambiguity resolved (see :func:`floquet_modes`).
    multipliers : ndarray, shape (m,)
        Characteristic multipliers ``exp(eta period)``.
    eigenvectors : ndarray, shape (n, m)
        Unit eigenvectors of the monodromy matrix at psi = 0 (columns), phase
        set so that the largest entry is real positive.
    period : float
        Period of ``A``.
    psi : ndarray, shape (n_steps,) or None
        Azimuths of ``shapes``.
    shapes : ndarray, shape (n_steps, n, m) or None
        Periodic mode shapes ``p(psi)`` (``shapes[0] == eigenvectors``), if
        requested.
    n_sub : int or None
        Sub-intervals of the lifting that gave the result (``floquet_modes``
        raises it for heavily damped modes); None for direct eigenanalysis.
    participation : ndarray, shape (n, m) or None
        Participation factors of the states in the modes, if computed
        (:meth:`with_participation`).
    n_steps : int or None
        Steps per period that gave the result (``floquet_modes`` raises it
        until the error estimates meet the tolerance); None for direct
        eigenanalysis.
    error_estimates : ndarray, shape (m,), or None
        Estimated error of each exponent: real part for the damping rate,
        imaginary part for the frequency (both >= 0, per radian of psi):
        the step-doubling estimate plus a round-off bound, large (up to inf)
        for a root below round-off (heavily damped beyond resolution).  None
        when not estimated.
    """

    exponents: np.ndarray
    multipliers: np.ndarray
    eigenvectors: np.ndarray
    period: float = _TWO_PI
    psi: np.ndarray | None = None
    shapes: np.ndarray | None = None
    n_sub: int | None = None
    participation: np.ndarray | None = None
    n_steps: int | None = None
    error_estimates: np.ndarray | None = None

    @property
    def damping_rates(self):
        """Real parts ``sigma`` of the exponents (per rad; negative = decaying)."""
        return self.exponents.real

    @property
    def frequencies(self):
        """Imaginary parts ``omega`` of the exponents (rad per rad of psi: /rev)."""
        return self.exponents.imag

    @property
    def damping_ratios(self):
        """``-sigma / sqrt(sigma^2 + omega^2)``, positive when stable."""
        return damping_ratio(self.exponents)

    def __len__(self):
        return len(self.exponents)

    def select(self, mask):
        """Result restricted to the entries ``mask`` (boolean or integer index)."""
        pf = self.participation
        return replace(self, exponents=self.exponents[mask], multipliers=self.multipliers[mask],
                       eigenvectors=self.eigenvectors[:, mask],
                       shapes=None if self.shapes is None else self.shapes[..., mask],
                       participation=None if pf is None else pf[:, mask],
                       error_estimates=None if self.error_estimates is None
                       else self.error_estimates[mask])

    def with_participation(self):
        """The result with the participation factors of the states filled in.

        The participation of state ``k`` in mode ``i`` is
        ``p_ki = <y_ik(psi)* x_ik(psi)>``, the azimuthal mean of the product of
        the mode's periodic shape and its dual (adjoint) shape, normalised so
        that ``y_i(psi)^H x_i(psi) = 1`` [1]_ [2]_.  The duals are the rows of
        the inverse of the matrix of all periodic shapes (Floquet solutions
        and adjoint solutions are biorthogonal at every azimuth); for constant
        coefficients the shapes are the eigenvectors and ``p_ki`` are the
        classical participation factors ``l_ik r_ki / l_i^T r_i``.  Each
        column sums to 1; unlike energy shares they do not depend on how the
        coordinates are scaled, so a light flap coordinate is not hidden by
        heavy blade modes.  Needs all modes and, for a periodic system, the
        shapes (``floquet_modes(..., shapes=True)``).

        References
        ----------
        .. [1] I. J. Perez-Arriaga, G. C. Verghese, F. C. Schweppe, "Selective
           modal analysis with applications to electric power systems, part I",
           IEEE Trans. Power App. Syst. PAS-101(9) (1982) 3117-3125.
        .. [2] G. C. Verghese, I. J. Perez-Arriaga, F. C. Schweppe, "Selective
           modal analysis ... part II", ibid. 3126-3134.

        Examples
        --------
        >>> import numpy as np
        >>> res = constant_coefficient_modes(np.diag([-1.0, -2.0])).with_participation()
        >>> np.abs(res.participation).round(6).tolist()
        [[0.0, 1.0], [1.0, 0.0]]
        """
        per = self.shapes if self.shapes is not None else self.eigenvectors[None]
        if per.shape[-1] != per.shape[-2]:
            raise ValueError("participation factors need every mode of the system "
                             f"({per.shape[-2]} states, {per.shape[-1]} modes)")
        try:
            dual = np.linalg.inv(per)                   # (n_psi, modes, states)
        except np.linalg.LinAlgError:
            # a root beyond the lifting's resolution leaves a zero or repeated
            # shape: the pseudo-inverse keeps the duals of the resolved modes
            dual = np.linalg.pinv(per)
        pf = np.einsum("pik,pki->ki", dual, per) / per.shape[0]
        return replace(self, participation=pf)

    def positive_frequency(self, tol=1e-9):
        """One mode of each conjugate pair: those with ``omega >= -tol``.

        Meant for real ``A``, whose exponents come in pairs ``sigma +- i omega``;
        non-oscillatory modes (``omega = 0``) are all kept. A root with
        ``omega < -tol`` and no conjugate partner is kept too, conjugated
        (``omega -> |omega|``): a real multiplier (a frequency locked to a
        multiple of 1/2 per rev) is its own conjugate, and the sign the
        integer shift gives it is arbitrary — dropping it would lose a mode.

        Examples
        --------
        >>> import numpy as np
        >>> res = constant_coefficient_modes(np.array([[0.0, 1.0], [-4.0, -0.2]]))
        >>> [round(float(w), 6) for w in res.positive_frequency().frequencies]
        [1.997498]
        """
        eta = self.exponents
        keep = eta.imag >= -tol
        pos = np.flatnonzero(keep)
        partnered = np.zeros(pos.size, bool)
        flip = np.zeros(eta.size, bool)
        for i in np.flatnonzero(~keep):
            dist = np.where(partnered, np.inf, np.abs(eta[pos] - np.conj(eta[i])))
            j = int(np.argmin(dist)) if pos.size else -1
            if j >= 0 and dist[j] <= 1e-6 * max(1.0, abs(eta[i])):
                partnered[j] = True             # its partner is kept
            else:
                flip[i] = True
        out = self.select(keep | flip)
        conj = flip[keep | flip]

        def fix(a):
            return np.where(conj, np.conj(a), a)
        return replace(out, exponents=fix(out.exponents), multipliers=fix(out.multipliers),
                       eigenvectors=fix(out.eigenvectors),
                       shapes=None if out.shapes is None else fix(out.shapes),
                       participation=None if out.participation is None
                       else fix(out.participation))


def _normalise(v):
    """Unit columns with the largest entry real positive (conjugate pairs stay conjugate)."""
    big = v[np.argmax(np.abs(v), axis=0), np.arange(v.shape[1])]
    size = np.abs(big) * np.linalg.norm(v, axis=0)
    return np.divide(np.conj(big), size, out=np.ones(size.shape, complex), where=size > 0)


def _sorted_result(eta, multipliers, vectors, period, psi=None, shapes=None, n_sub=None,
                   n_steps=None, participation=None):
    order = np.lexsort((eta.real, np.round(eta.imag, 9)))   # frequency ties: by damping
    scale = _normalise(vectors)[order]
    return FloquetResult(
        exponents=eta[order], multipliers=multipliers[order],
        eigenvectors=vectors[:, order] * scale, period=period, psi=psi,
        shapes=None if shapes is None else shapes[..., order] * scale, n_sub=n_sub,
        n_steps=n_steps, participation=None if participation is None
        else participation[:, order])


# --------------------------------------------------------------------------
# Floquet analysis


def _clusters(mu, scale):
    """Index arrays of the groups of (numerically) equal roots, two or more each."""
    # semisimple repeated roots agree to roundoff, eps ||Z|| absolutely
    tol = 1e-8 * np.abs(mu) + 1e3 * np.finfo(float).eps * scale
    close = np.abs(mu[:, None] - mu[None, :]) <= np.maximum.outer(tol, tol)
    n_groups, label = scipy.sparse.csgraph.connected_components(close, directed=False)
    groups = [np.flatnonzero(label == g) for g in range(n_groups)]
    return [g for g in groups if g.size > 1]


def _harmonic_basis(per, omega):
    """Recombine periodic parts of one multiplier into harmonically pure modes.

    Returns ``per @ C`` (:func:`_harmonic_combination`).
    """
    coef = _harmonic_combination(per, omega)
    return per if coef is None else per @ coef


def _harmonic_combination(per, omega):
    """The combination ``C`` of :func:`_harmonic_basis` (None: left as they are).

    Solves ``F c = kappa G c`` with ``G`` the Gram matrix of the periodic parts
    ``per`` (n_steps, n, d) over the period and ``F`` the same weighted by the
    frequency ``omega`` of each harmonic: its eigenvectors are the
    combinations of stationary mean frequency, the pure modes when their
    harmonic contents are disjoint (exact for a constant ``A``). A defective
    multiplier (Jordan block, e.g. on a Mathieu stability boundary) has
    (nearly) parallel vectors; they are left as they are.
    """
    f = np.fft.fft(per, axis=0)
    g = np.einsum("hia,hib->ab", f.conj(), f)
    w = np.linalg.eigvalsh(g)
    if w[0] <= 1e-8 * w[-1]:
        return None
    fm = np.einsum("h,hia,hib->ab", omega, f.conj(), f)
    return scipy.linalg.eigh(fm, g)[1]


def floquet_modes(A, n_steps=None, n_sub=DEFAULT_N_SUB, period=_TWO_PI, method="rk4",
                  shapes=False, shift_states=None, max_sub=MAX_SUB, atol=DEFAULT_ATOL,
                  rtol=DEFAULT_RTOL, max_steps=None, on_inaccurate="warn", min_rate=None,
                  participation=False):
    """Characteristic exponents, multipliers and modes of ``x' = A(psi) x``.

    The step propagators are grouped into ``n_sub`` transition matrices
    ``Phi_k``, whose product's eigenvalues (the multipliers ``lambda``) are
    found by lifting (:func:`characteristic_multipliers`). The exponents are
    ``eta = ln(lambda) / T``, defined only up to ``i j 2 pi / T`` (integer
    ``j``): ``exp(eta psi) p(psi)`` is the same solution as
    ``exp((eta + i j 2 pi/T) psi) exp(-i j 2 pi psi/T) p(psi)``. The
    ambiguity is resolved as in Peters & Hohenemser [1]_ and Bauchau &
    Nikishkov [2]_: each eigenvector is propagated over the period on the
    step grid (from the lifted eigenvector, one sub-interval at a time, so a
    decaying mode is never swamped), its periodic part ``p`` is Fourier
    analysed, and the frequency is shifted so that the dominant harmonic of
    ``p`` becomes the mean: ``omega = Im eta + j 2 pi / T``, with ``j`` the
    harmonic of largest energy (ties: smallest ``|omega|``, then positive).

    Parameters
    ----------
    A : callable or array_like
        Vectorised ``A(psi)``, constant matrix or periodic samples; see
        :func:`step_propagators`.
    n_steps : int, optional
        Steps per period (default :data:`DEFAULT_N_STEPS`, 144).
    n_sub : int, optional
        Sub-intervals for the lifting (default :data:`DEFAULT_N_SUB`, 8), the
        first ``K`` tried. A root of the lift has the modulus
        ``|mu| = exp(sigma T / K)``, and its relative error is about
        ``eps ||Z|| / |mu|``, where the transition matrices of a rotor are
        far from normal (``||Phi_k||`` up to 1e7 seen). So when the most damped
        root has ``|mu|`` below :data:`MIN_ROOT` (1e-3) or below
        ``1e6 eps max ||Phi_k||`` (a relative round-off above 1e-6), or the
        roots do not split one per multiplier, ``K`` is raised to the power
        of two that lifts that root above this floor (at most ``max_sub``),
        and the lift is solved again from the same step propagators (cost
        ``O((K n)^3)``).
        Seen on MDART sweeps: damping-rate errors of 1.4 /rev at ``K = 4`` for
        a -7.2 /rev torsion root, 2e-4 at ``K = 8``.
    max_sub : int, optional
        Largest ``K`` (default :data:`MAX_SUB`, 16; at most ``n_steps``);
        ``max_sub <= n_sub`` keeps ``K = n_sub``. If the roots still do not
        split, a RuntimeWarning says so.
    period : float, optional
        Period ``T`` (default ``2 pi``).
    method : {'rk4', 'magnus'}, optional
        Step integrator, see :func:`step_propagators`.
    shapes : bool, optional
        Also return the periodic mode shapes on the step grid.

    shift_states : slice or index array, optional
        States whose periodic part decides the integer frequency shift
        (default: all). For a second-order system ``x = [q, q*]`` pass the
        displacements ``slice(0, n)``: the velocities weight harmonic ``k`` by
        ``k^2`` and would pull a heavily damped, harmonically rich mode to a
        higher branch.
    atol, rtol : float or None, optional
        Accuracy asked of every exponent, separately for the damping rate
        (``atol + rtol |sigma|``, the stability answer) and the frequency
        (``atol + rtol |eta|``: the frequency of a heavily damped root, e.g.
        near a frequency lock, is ill-conditioned and matters little, so it
        is held to the size of the whole exponent), per radian of psi
        (default :data:`DEFAULT_ATOL`, :data:`DEFAULT_RTOL`, both 1e-3).
        The error is estimated by step doubling: the exponents of
        ``N`` steps against those of ``N / 2`` steps (every other sample, no
        new evaluations of ``A``), ``|eta_N - eta_{N/2}| / 15`` for these
        fourth-order methods. While some exponent misses its tolerance the
        steps are doubled (``A`` resampled; not possible for periodic
        samples). ``atol=None`` switches the control off: one grid, and the
        RK4 step-limit warning of :func:`step_propagators`.
    max_steps : int, optional
        Most steps per period the control may reach (default ``32 n_steps``).
    on_inaccurate : {'warn', 'raise'}, optional
        Still above the tolerance at ``max_steps``:
        :class:`FloquetAccuracyWarning` and the result, or
        :class:`FloquetAccuracyError`.
    min_rate : float, optional
        Damping rate (negative, per unit of psi) below which roots need not be
        resolved: ``K`` is raised only until ``exp(min_rate T / K)`` reaches the
        floor, and whether the roots split is judged on the roots above that
        modulus.  For systems with fast, heavily damped states that no
        ``K <= max_sub`` can resolve (the shed wake of a rotor blade, down to
        -30 /rev): without it they drive ``K`` to ``max_sub`` at a cost
        ``O((K n)^3)``.  Such roots are reported somewhere below the cut and
        are not held to the tolerance (they do not drive the step
        refinement).  Default None: every root counts.
    participation : bool, optional
        Also the participation factors (:meth:`FloquetResult.with_participation`),
        from the adjoint solutions: the left eigenvectors of the lift, carried
        over each sub-interval by ``(P^-1)^H`` of the step propagators.  Unlike
        the inverse of the matrix of all periodic shapes, this needs only the
        root itself, so the factors of the resolved roots hold when roots below
        ``min_rate`` are not resolved (theirs are then meaningless).

    Returns
    -------
    FloquetResult
        One entry per exponent (``n``), conjugate pairs both kept, with the
        ``n_steps`` reached and the ``error_estimates``.

    Raises
    ------
    ValueError
        For invalid ``A`` or parameters, see :func:`step_propagators`.
    FloquetOverflowError
        A transition matrix overflows even at ``max_steps`` (a ``ValueError``
        and a :class:`FloquetAccuracyError`).
    FloquetAccuracyError
        With ``on_inaccurate="raise"``, see above.

    Warns
    -----
    FloquetAccuracyWarning
        See `on_inaccurate`.
    RuntimeWarning
        The lifted roots do not split (roots at round-off level).

    References
    ----------
    .. [1] D. A. Peters, K. H. Hohenemser, "Application of the Floquet
       transition matrix to problems of lifting rotor stability", J. Am.
       Helicopter Soc. 16(2) (1971) 25-33.
    .. [2] O. A. Bauchau, Y. G. Nikishkov, "An implicit Floquet analysis for
       rotorcraft stability evaluation", J. Am. Helicopter Soc. 46(3) (2001)
       200-209.
    .. [3] P. P. Friedmann, C. E. Hammond, T.-H. Woo, "Efficient numerical
       treatment of periodic systems with application to stability
       problems", Int. J. Numer. Methods Eng. 11(7) (1977) 1117-1136.

    Examples
    --------
    Mathieu's equation ``y'' + (a - 2 q cos 2t) y = 0`` (period pi) is
    unstable inside the first tongue, ``b_1(q) < a < a_1(q)``:

    >>> import numpy as np
    >>> def mathieu(a, q):
    ...     return lambda t: np.stack([[0 * t, 1 + 0 * t],
    ...                                [-(a - 2 * q * np.cos(2 * t)), 0 * t]]).transpose(2, 0, 1)
    >>> res = floquet_modes(mathieu(1.0, 0.2), period=np.pi)
    >>> bool(res.damping_rates.max() > 0)
    True
    >>> res = floquet_modes(mathieu(2.0, 0.2), period=np.pi)
    >>> bool(abs(res.damping_rates).max() < 1e-6)
    True
    """
    period = _check_period(period)
    method = _check_method(method)
    if on_inaccurate not in _ON_INACCURATE:
        raise ValueError(f"on_inaccurate must be one of {_ON_INACCURATE}, got {on_inaccurate!r}")
    check = atol is not None
    if check:
        atol, rtol = (_check_tolerance(name, v) for name, v in (("atol", atol), ("rtol", rtol)))
    if min_rate is not None and not (np.isfinite(min_rate) and min_rate < 0):
        raise ValueError(f"min_rate must be a negative damping rate or None, got {min_rate!r}")
    a, n_steps, constant = _sample(A, n_steps, period)
    k_sub = _check_sub(n_sub, n_steps)
    max_sub = _check_int("max_sub", max_sub, 1)
    refinable = callable(A) or constant
    if max_steps is None:
        max_steps = n_steps * 2**MAX_DOUBLINGS
    max_steps = _check_int("max_steps", max_steps, 1)
    if not check:
        if method == "rk4":
            _rk4_step_warning(a[:3] if constant else a, period / n_steps, n_steps)
        p = _propagators(a, period / n_steps, constant, method)
        res, _, split = _modes(p, period, k_sub, max_sub, shapes, shift_states, min_rate,
                               participation)
        if not split:
            _warn_unsplit()
        return res

    coarse = None                  # exponents on the grid with half the steps
    while True:
        try:
            p = _propagators(a, period / n_steps, constant, method)
            res, znorm, split = _modes(p, period, k_sub, max_sub, shapes, shift_states,
                                       min_rate, participation)
        except FloquetOverflowError as err:
            if refinable and 2 * n_steps <= max_steps:      # shorter steps may not overflow
                n_steps, coarse = 2 * n_steps, None
                a = _sample(A, n_steps, period)[0]
                continue
            raise FloquetOverflowError(f"{err} (at n_steps = {n_steps} with method = "
                                       f"{method!r}; the fastest root of the mean A is "
                                       f"{_fastest_root(a):.3g} per unit of psi)") from None
        k_sub = res.n_sub
        if coarse is None and n_steps % 2 == 0:
            coarse = _coarse_exponents(a[::2], period, k_sub, method, constant, min_rate)
        if coarse is None:                                  # odd step count: compare 2N
            if not refinable or 2 * n_steps > max_steps:
                if not split:
                    _warn_unsplit()
                return res
            coarse, n_steps = res.exponents, 2 * n_steps
            a = _sample(A, n_steps, period)[0]
            continue
        est, trusted = _error_estimates(res, coarse, znorm, atol)
        if min_rate is not None:            # roots below min_rate are not held to it
            trusted &= res.exponents.real >= min_rate
        tol_re = atol + rtol * np.abs(res.exponents.real)
        tol_im = atol + rtol * np.abs(res.exponents)   # |eta|: see the docstring
        bad = trusted & ((est.real > tol_re) | (est.imag > tol_im))
        res = replace(res, error_estimates=est)
        if not bad.any() or not refinable or 2 * n_steps > max_steps:
            if bad.any():      # an untrusted result is an error first (on_inaccurate="raise")
                _inaccurate(res, bad, tol_re, tol_im, method, on_inaccurate)
            if not split:
                _warn_unsplit()
            return res
        coarse, n_steps = res.exponents, 2 * n_steps
        a = _sample(A, n_steps, period)[0]


def _check_tolerance(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number >= 0, got {value!r}") from None
    if not (value >= 0.0 and np.isfinite(value)):
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return value


def _fastest_root(a):
    """Eigenvalue of the mean of the samples ``a`` of largest modulus."""
    ev = np.linalg.eigvals(np.mean(a, axis=0))
    return complex(ev[np.argmax(np.abs(ev))])


def _coarse_exponents(a, period, k_sub, method, constant, min_rate=None):
    """Exponents (frequency modulo 2 pi / T) with the steps of the samples ``a``, or None.

    None when the coarse grid overflows: then there is no estimate, and the
    caller refines.
    """
    n_steps = (a.shape[0] - 1) // 2
    try:
        p = _propagators(a, period / n_steps, constant, method)
        k = min(k_sub, n_steps)
        phis = _tree_product(_group(p, k)[0])
    except FloquetOverflowError:
        return None
    mu = scipy.linalg.eigvals(_lift(phis))
    keep, _ = _select_roots(mu, k, phis.shape[-1], _cut(min_rate, period, k))
    return k * _log_roots(mu[keep]) / period


def _error_estimates(res, coarse, znorm, atol):
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
    unit = _TWO_PI / res.period
    d = eta[:, None] - np.asarray(coarse)[None, :]
    d = np.abs(d.real) + 1j * np.abs(np.mod(d.imag + unit / 2, unit) - unit / 2)
    rows, cols = scipy.optimize.linear_sum_assignment(np.abs(d))
    est = np.empty(eta.shape, complex)
    est[rows] = d[rows, cols] / (2**_ORDER - 1)
    k_sub = res.n_sub
    mu_abs = np.abs(res.multipliers) ** (1.0 / k_sub)
    with np.errstate(divide="ignore"):
        roundoff = (k_sub / res.period) * 1e2 * np.finfo(float).eps * znorm / mu_abs
    trusted = roundoff <= 0.1 * np.maximum(np.abs(est), atol)
    est = est + roundoff * (1 + 1j)
    return est, trusted


def _inaccurate(res, bad, tol_re, tol_im, method, on_inaccurate):
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


def _cut(min_rate, period, k_sub):
    """``|mu|`` of a root at ``min_rate`` with ``K`` sub-intervals (0: no cut)."""
    return 0.0 if min_rate is None else float(np.exp(min_rate * period / k_sub))


def _modes(p, period, k_sub, max_sub, shapes, shift_states, min_rate=None, duals=False):
    """Floquet modes from the step propagators ``p``; also ``max ||Phi_k||`` and whether
    the lifted roots split one per multiplier.  ``duals``: with the participation
    factors from the adjoint solutions (:func:`_adjoint_participation`)."""
    n_steps, n = p.shape[0], p.shape[-1]
    k_sub = _check_sub(k_sub, n_steps)
    max_sub = min(max(max_sub, k_sub), n_steps)
    eps = np.finfo(float).eps
    while True:
        stack, bounds, valid = _group(p, k_sub)
        phis = _tree_product(stack)
        cut = _cut(min_rate, period, k_sub)
        mu, blocks, split, *lblocks = _lifted(phis, cut, left=duals)
        # with min_rate, the roots below the cut need not be resolved
        smallest = max(np.abs(mu).min(), cut)
        # a root is trusted when it is above MIN_ROOT and its round-off,
        # eps ||Z|| / |mu| relative (||Z|| = the largest ||Phi_k||), is <= 1e-6
        with np.errstate(over="ignore"):     # an inf norm: no K resolves it (below)
            floor = max(MIN_ROOT, 1e6 * eps * np.linalg.norm(phis, axis=(1, 2)).max())
        if (split and smallest >= floor) or k_sub >= max_sub:
            break
        # |mu| = |lambda|^(1/K): the K that lifts the most damped root to the
        # floor (from the computed root even when it is garbage: then it is
        # below round-off, and the true one smaller still)
        if floor >= 1.0:        # ||Phi_k|| beyond 1/(1e6 eps): no K resolves it
            k_sub = max_sub
            continue
        need = k_sub * np.log(max(smallest, np.finfo(float).tiny)) / np.log(floor)
        if not (floor < 1.0 and np.isfinite(need) and need > 0):
            need = 2 * k_sub                     # round-off above 1: just halve the blocks
        k_sub = int(min(max_sub, max(2 * k_sub, 2 ** np.ceil(np.log2(need)))))
    log_mu = _log_roots(mu)
    eta = k_sub * log_mu / period                  # the branch of the selected roots

    # solution on the step grid, each sub-interval from its lifted block:
    # x(psi) = mu^k Phi(psi, psi_k) v_k for psi in sub-interval k
    x = np.empty((*valid.shape, n, n), dtype=complex)
    cur = blocks.astype(complex)
    for step in range(valid.shape[1]):
        x[:, step] = cur
        cur = stack[:, step] @ cur
    x = x[valid]                                   # (n_steps, n, m), in time order
    if duals:
        # adjoint solutions y = Phi(psi, psi_k)^-H u_k on the same grid
        y = np.empty((*valid.shape, n, n), dtype=complex)
        inv_h = np.swapaxes(np.linalg.inv(stack), -1, -2).conj()
        cur = lblocks[0].astype(complex)
        for step in range(valid.shape[1]):
            y[:, step] = cur
            cur = inv_h[:, step] @ cur
        y = y[valid]
    h = period / n_steps
    psi = np.arange(n_steps) * h
    k_of = np.repeat(np.arange(k_sub), np.diff(bounds))
    psi_k = bounds[k_of] * h
    # periodic part p = exp(-eta psi) x = exp(-eta (psi - psi_k)) c_k x_k with
    # c_k = mu^k exp(-eta psi_k) (= 1 for equal sub-intervals): bounded factors only
    expo = (-eta[None, :] * (psi - psi_k)[:, None]
            + log_mu[None, :] * (k_of - k_sub * psi_k / period)[:, None])
    with np.errstate(over="ignore", invalid="ignore"):
        per = np.exp(np.minimum(expo.real, 700.0) + 1j * expo.imag)[:, None, :] * x
    per[~np.isfinite(per)] = 0.0                   # only for unresolvable (garbage) modes

    harm = np.fft.fftfreq(n_steps, 1.0 / n_steps)
    unit = _TWO_PI / period
    # equal multipliers (e.g. sigma +- 3i of a constant A: exp(+-3i 2 pi) = 1)
    # leave eig an arbitrary basis of their eigenspace, mixing harmonics: pick
    # the basis of harmonically pure modes instead
    for idx in _clusters(mu, np.abs(phis).max()):
        eta[idx] = eta[idx].mean()
        if not duals:
            per[..., idx] = _harmonic_basis(per[..., idx], eta[idx[0]].imag + harm * unit)
            continue
        coef = _harmonic_combination(per[..., idx], eta[idx[0]].imag + harm * unit)
        if coef is not None:
            per[..., idx] = per[..., idx] @ coef
            y[..., idx] = y[..., idx] @ np.linalg.inv(coef).conj().T
    part = _adjoint_participation(y, per) if duals else None

    # dominant harmonic of the periodic part fixes the integer shift
    sel = slice(None) if shift_states is None else shift_states
    power = (np.abs(np.fft.fft(per[:, sel], axis=0)) ** 2).sum(axis=1)  # (n_steps, m)
    omega = eta.imag[None, :] + harm[:, None] * unit
    tied = power >= (1.0 - 1e-9) * power.max(axis=0)
    score = np.where(tied, np.abs(omega) - 1e-9 * unit * (omega > 0), np.inf)
    j = harm[np.argmin(score, axis=0)]
    eta = eta + 1j * j * unit
    per *= np.exp(-1j * np.outer(psi, j) * unit)[:, None, :]

    with np.errstate(over="ignore"):   # a garbage root beyond resolution: inf, judged below
        multipliers = np.exp(k_sub * log_mu)
    return (_sorted_result(eta, multipliers, per[0], period, psi if shapes else None,
                           per if shapes else None, n_sub=k_sub, n_steps=n_steps,
                           participation=part),
            float(np.linalg.norm(phis, axis=(1, 2)).max()), split)


def _adjoint_participation(y, x):
    """Participation factors ``<conj(y_k) x_k / y^H x>_psi`` of solutions ``x`` and
    their adjoints ``y`` (n_steps, n, m).  ``y^H x`` is constant along a solution;
    normalising at every step makes the result independent of any scalar factor
    of either.  A root beyond resolution (a zero or overflowed shape) gets zeros."""
    prod = y.conj() * x
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        pf = (prod / prod.sum(axis=1, keepdims=True)).mean(axis=0)
    pf[:, ~np.isfinite(pf).all(axis=0)] = 0.0
    return pf




def constant_coefficient_modes(A, period=_TWO_PI):
    """Modes of a constant-coefficient system ``x' = A x`` (e.g. hover).

    Direct eigenanalysis: the exponents are the eigenvalues of ``A``, with no
    frequency ambiguity; returned as a :class:`FloquetResult` for the
    ``period`` given, so it compares entry by entry with :func:`floquet_modes`.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Real or complex system matrix.
    period : float, optional
        Period used for the multipliers ``exp(eta period)`` (default ``2 pi``).

    Returns
    -------
    FloquetResult

    Raises
    ------
    ValueError
        If ``A`` is not a finite square matrix.

    Examples
    --------
    >>> import numpy as np
    >>> res = constant_coefficient_modes([[0.0, 1.0], [-4.0, -0.4]])
    >>> res.exponents
    array([-0.2-1.98997487j, -0.2+1.98997487j])
    >>> np.round(res.damping_ratios, 3)
    array([0.1, 0.1])
    """
    period = _check_period(period)
    a = _as_numeric(np.asarray(A), "A")
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] == 0:
        raise ValueError(f"A must be a square n x n matrix with n >= 1, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError("A has non-finite entries (NaN or inf)")
    eta, vectors = scipy.linalg.eig(a)
    # a real A with real eigenvalues gives real vectors: complex, like every result
    return _sorted_result(eta, np.exp(eta * period), vectors.astype(complex), period)

