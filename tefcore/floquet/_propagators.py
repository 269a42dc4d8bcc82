"""Floquet analysis, part 1: step propagators and transition matrices (the implementation
of :func:`tefcore.floquet.step_propagators`, :func:`~tefcore.floquet.transition_matrices`
and :func:`~tefcore.floquet.monodromy`; input checks and the errors of the Floquet
modules).

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

import numbers
import warnings

import numpy as np
import scipy.linalg

from ..errors import TefcoreError
from ..runtime import blas_limit

__all__ = ["DEFAULT_N_STEPS", "DEFAULT_N_SUB", "TWO_PI", "FloquetAccuracyError",
           "FloquetOverflowError", "FloquetAccuracyWarning", "check_int", "check_period",
           "check_method", "as_numeric", "sample", "rk4_step_warning",
           "step_propagators", "propagators", "group", "tree_product",
           "transition_matrices", "check_sub", "monodromy", "expm_batch"]


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


_METHODS = ("rk4", "magnus")


TWO_PI = 2.0 * np.pi


class FloquetAccuracyError(TefcoreError, RuntimeError):
    """The Floquet exponents could not be computed to the requested accuracy."""


class FloquetOverflowError(FloquetAccuracyError, ValueError):
    """A transition matrix overflowed: the step is too long for the system."""


class FloquetAccuracyWarning(RuntimeWarning):
    """The Floquet exponents did not meet the requested accuracy (see the message)."""


def check_int(name, value, minimum):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def check_period(period):
    try:
        period = float(period)
    except (TypeError, ValueError):
        raise ValueError(f"period must be a positive real number, got {period!r}") from None
    if not (np.isfinite(period) and period > 0.0):
        raise ValueError(f"period must be a positive finite number, got {period!r}")
    return period


def check_method(method):
    if method not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
    return method


def as_numeric(a, what):
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


def sample(A, n_steps, period):
    """A at the step ends and midpoints ``psi_j = j h / 2``, j = 0..2N: (2N+1, n, n).

    Returns the samples, the number of steps and whether A is constant.
    """
    period = check_period(period)
    if callable(A):
        n = DEFAULT_N_STEPS if n_steps is None else check_int("n_steps", n_steps, 1)
        psi = np.linspace(0.0, period, 2 * n + 1)
        a = np.asarray(A(psi))
        if a.ndim != 3 or a.shape[0] != psi.size:
            raise ValueError(
                f"A(psi) must be vectorised: for an array of {psi.size} azimuths it must return "
                f"shape ({psi.size}, n, n), got {a.shape}. Build the matrices with numpy "
                "broadcasting, e.g. A0 + np.cos(psi)[:, None, None] * A1.")
        a = as_numeric(a, "A(psi)")
        what, constant = "A(psi)", False
    else:
        a = as_numeric(np.asarray(A), "A")
        if a.ndim == 2:
            n = DEFAULT_N_STEPS if n_steps is None else check_int("n_steps", n_steps, 1)
            a = np.broadcast_to(a, (2 * n + 1, *a.shape))
            psi = np.linspace(0.0, period, 2 * n + 1)
            what, constant = "A", True
        elif a.ndim == 3:
            m = a.shape[0]
            if m < 2 or m % 2:
                raise ValueError(
                    "samples of A must lie on the periodic grid psi_j = j*period/M, j = 0..M-1, "
                    f"with M = 2*n_steps (step ends and midpoints): M must be even, got M = {m}")
            if n_steps is not None and check_int("n_steps", n_steps, 1) != m // 2:
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


def rk4_step_warning(a, h, n_steps):
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


def step_propagators(A, n_steps=None, period=TWO_PI, method="rk4"):
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
    method = check_method(method)
    a, n_steps, constant = sample(A, n_steps, period)
    h = check_period(period) / n_steps
    if method == "rk4":
        rk4_step_warning(a[:3] if constant else a, h, n_steps)
    return propagators(a, h, constant, method)


def propagators(a, h, constant, method):
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
            p = expm_batch(omega)
    if not np.isfinite(p).all():
        raise FloquetOverflowError(f"step propagator overflowed (h = {h:.4g}); A is too "
                                   "large for this step: increase n_steps")
    if constant:
        p = np.broadcast_to(p, (n_steps, *p.shape[1:]))
    return p


#: Scaled 1-norm of :func:`expm_batch`'s Taylor polynomial: the truncation after
#: degree 16 is ``sum_{k > 16} 0.5^k / k! < 3e-20`` relative, below round-off.
_TAYLOR_NORM = 0.5

#: 1/k!, k = 0..16.
_INV_FACT = 1.0 / np.cumprod(np.concatenate([[1.0], np.arange(1.0, 17.0)]))


def expm_batch(a):
    """``exp(a)`` of a stack of matrices ``(..., n, n)`` by scaling and squaring.

    ``a / 2^s`` with the largest 1-norm of the stack at most 1/2, its Taylor
    polynomial of degree 16 by Paterson-Stockmeyer (six batched products),
    then ``s`` squarings: batched matrix products only, no solve (about a
    third of the cost of :func:`scipy.linalg.expm` on the Magnus steps of a
    20-state rotor, 72 steps); agrees with it to round-off (tested).  The
    stack is balanced first by a diagonal similarity of powers of two
    (:func:`_balancing`), which lowers the norm and so the squarings.

    Parameters
    ----------
    a : numpy.ndarray
        Real or complex, ``(..., n, n)``.

    Returns
    -------
    numpy.ndarray
        ``exp(a)``, same shape; non-finite input gives non-finite output.
    """
    a = np.asarray(a)
    with np.errstate(over="ignore", invalid="ignore"):
        if a.size and not np.isfinite(a).all():
            return np.full(a.shape, np.nan, dtype=a.dtype)
        t = _balancing(a)
        if t is not None:
            # exp(a) = T exp(T^-1 a T) T^-1, T diagonal powers of two: exact
            # similarity, a smaller norm, fewer squarings
            return _expm(a / t[:, None] * t[None, :]) * t[:, None] / t[None, :]
        return _expm(a)


def _balancing(a):
    """Powers of two ``t`` that balance the rows and columns of the stack's
    largest entries (LAPACK's ``gebal`` on ``max |a|``), or None when they do
    not lower the largest 1-norm by half.

    A rotor's state matrix ``[[0, I], [-M^-1 K, -M^-1 C]]`` has entries of 1
    and of ``omega^2``: balanced, the 1-norm of the 72 Magnus steps fell from
    39 to 2.8 on MDART at mu 0.3 (0.66 against 0.62 ms, medians of 300) and
    from 997 to 3.7 on Fig. 9's c_cg 0.36 (0.81 against 0.64 ms); at that
    point's half coupling (a path step) 4e-15 against 2e-13 from
    :func:`scipy.linalg.expm` (measured).  None also where ``|a|`` overflows
    (a finite complex entry near the largest float): the stack is then
    exponentiated as it is.
    """
    if a.ndim < 2 or a.shape[-1] < 2 or not a.size:
        return None
    with np.errstate(over="ignore"):
        big = np.abs(a).reshape(-1, *a.shape[-2:]).max(axis=0)
    if not np.isfinite(big).all():
        return None
    _, (t, _) = scipy.linalg.matrix_balance(big, permute=False, separate=True)
    if np.all(t == 1.0):
        return None
    balanced = big / t[:, None] * t[None, :]
    if balanced.sum(axis=0).max() > 0.5 * big.sum(axis=0).max():
        return None
    return t


def _expm(a):
    """:func:`expm_batch` of a finite stack, without balancing."""
    n = a.shape[-1]
    with np.errstate(over="ignore", invalid="ignore"):
        norm = float(np.abs(a).sum(axis=-2).max()) if a.size else 0.0
        if not np.isfinite(norm):
            return np.full(a.shape, np.nan, dtype=a.dtype)
        s = max(0, int(np.ceil(np.log2(norm / _TAYLOR_NORM)))) if norm > 0 else 0
        x = a / 2.0**s
        eye = np.eye(n, dtype=x.dtype)
        x2 = x @ x
        x3 = x2 @ x
        x4 = x2 @ x2
        powers = np.stack(np.broadcast_arrays(eye, x, x2, x3))
        # sum_k x^k / k!, k = 0..16, as Horner in x4 over blocks of four terms
        blocks = np.tensordot(_INV_FACT[:16].reshape(4, 4), powers, axes=1)
        out = _INV_FACT[16] * x4 + blocks[3]
        for j in (2, 1, 0):
            out = out @ x4 + blocks[j]
        for _ in range(s):
            out = out @ out
    return out


def group(p, n_sub):
    """Consecutive steps in ``n_sub`` groups, padded with I: (K, L, n, n), bounds."""
    n_steps, n = p.shape[0], p.shape[-1]
    bounds = (np.arange(n_sub + 1) * n_steps) // n_sub       # lengths differ by <= 1
    lengths = np.diff(bounds)
    idx = bounds[:-1, None] + np.arange(lengths.max())
    valid = idx < bounds[1:, None]
    stack = p[np.minimum(idx, n_steps - 1)]
    stack[~valid] = np.eye(n)               # padding at the end of a group: no effect
    return stack, bounds, valid


def tree_product(stack):
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


@blas_limit()
def transition_matrices(A, n_steps=None, n_sub=DEFAULT_N_SUB, period=TWO_PI, method="rk4"):
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
    n_sub = check_sub(n_sub, len(p))
    return tree_product(group(p, n_sub)[0])


def check_sub(n_sub, n_steps):
    n_sub = check_int("n_sub", n_sub, 1)
    if n_sub > n_steps:
        raise ValueError(f"n_sub = {n_sub} exceeds n_steps = {n_steps}")
    return n_sub


def monodromy(A, n_steps=None, period=TWO_PI, method="rk4"):
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
