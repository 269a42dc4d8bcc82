"""Floquet analysis, part 5: :func:`tefcore.floquet.floquet_modes` -- exponents with the
frequency ambiguity resolved from the dominant harmonic of each periodic mode shape.

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg

from ..runtime import blas_limit
from ._accuracy import (
    DEFAULT_ATOL,
    DEFAULT_RTOL,
    MAX_DOUBLINGS,
    ON_INACCURATE,
    check_tolerance,
    coarse_exponents,
    error_estimates,
    fastest_root,
    inaccurate,
)
from ._multipliers import lifted, log_roots, root_cut, warn_unsplit
from ._propagators import (
    DEFAULT_N_SUB,
    TWO_PI,
    FloquetOverflowError,
    check_int,
    check_method,
    check_period,
    check_sub,
    group,
    propagators,
    rk4_step_warning,
    sample,
    tree_product,
)
from ._result import sorted_result

__all__ = ["LIFT_RTOL", "MIN_ROOT", "MAX_SUB", "ROOT_RTOL", "STATE_ROOT_RTOL", "choose_sub",
           "floquet_modes", "floquet_motions",
           "sub_products"]


#: Smallest modulus ``|mu| = |lambda|^(1/K)`` of a lifted root that
#: :func:`floquet_modes` accepts: below it ``n_sub`` is raised (see there).
#: The floor ``1e6 eps max ||Phi_k||`` carries the non-normality of the lift;
#: this one only keeps roots off the round-off level of a normal lift.  It was
#: 1e-3: against K = 16 on the 30 forward-flight end and middle points of the
#: paper's figures, 1e-6 changes the chosen K at 9 of them (K = 2 or 4 instead
#: of 4 or 8) and the largest exponent error from 4e-7 to 1.2e-6 /rev
#: (docs/theory.md 5.3), a thousandth of the default tolerance.
MIN_ROOT = 1e-6

#: Largest relative round-off ``eps max ||Phi_k|| / |mu|`` of a trusted root of
#: the lift (the floor ``1e6 eps max ||Phi_k||``).
ROOT_RTOL = 1e-6

#: :data:`ROOT_RTOL` of :func:`floquet_modes` with ``min_rate`` (fast states whose
#: deep roots are not wanted: the shed wake).  At 1e-6 the most damped wanted
#: root (at ``min_rate``, -8 /rev) drove MDART's 92-state shed-wake system at
#: mu 0.3 to K = 8 (a 736 x 736 lift, 0.24 s of a 0.86 s point) at c_cg 0.2 and
#: 0.33; at 1e-4 K = 4 (0.53 s a point), the blade and flap roots within
#: 7.5e-7 /rev of K = 8 and every label the same (measured at c_cg 0.1, 0.2,
#: 0.33, hover and mu 0.3).  The wanted roots' own accuracy is the step-doubling
#: error control's, unchanged.
STATE_ROOT_RTOL = 1e-4


#: Largest number of sub-intervals :func:`floquet_modes` raises ``n_sub`` to.
MAX_SUB = 16

#: Largest first-order round-off bound ``eps ||Z|| kappa_i / |mu_i|`` of a
#: resolved lifted root (``kappa_i`` its eigenvalue condition number, from the
#: left and right eigenvectors, known when the adjoint solutions are wanted)
#: that :func:`floquet_modes` accepts below :data:`MAX_SUB`; above it ``K`` is
#: doubled.  A locked pair (two real multipliers at ``k/2`` /rev) is nearly
#: defective: ``kappa`` 4e8 at ``K = 8`` for a -7.6 /rev root of an imbalanced
#: flap at mu = 0.35 (bound 40), whose frequency came out 0.4958 instead of
#: 0.5 /rev; ``K = 16`` (bound 0.1) gives 0.49999.  The bound is pessimistic by
#: orders of magnitude (the paper's imbalanced baseline: 2e-4 at ``K = 8``, its
#: roots within 1e-6 /rev of ``K = 16``; ordinary points 1e-11), so it is
#: acted on only where it says the root may be off by a percent (measured:
#: 3e-4 at most on ordinary and imbalanced points, 0.7 to 40 where the lift
#: gave a wrong root; docs/theory.md 5.3).  Not applied with ``min_rate``
#: (aerodynamic states, whose deep roots need not be resolved).
LIFT_RTOL = 1e-2


def _clusters(mu, scale):
    """Index arrays of the groups of (numerically) equal roots, two or more each."""
    # semisimple repeated roots agree to roundoff, eps ||Z|| absolutely
    tol = 1e-8 * np.abs(mu) + 1e3 * np.finfo(float).eps * scale
    close = np.abs(mu[:, None] - mu[None, :]) <= np.maximum.outer(tol, tol)
    if np.count_nonzero(close) == mu.size:         # only the diagonal: no group (usual)
        return []
    import scipy.sparse.csgraph  # deferred: rare (repeated roots), and 30-70 ms to import

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


@blas_limit()
def floquet_modes(A, n_steps=None, n_sub=DEFAULT_N_SUB, period=TWO_PI, method="rk4",
                  shapes=False, shift_states=None, max_sub=MAX_SUB, atol=DEFAULT_ATOL,
                  rtol=DEFAULT_RTOL, max_steps=None, on_inaccurate="warn", min_rate=None,
                  participation=False, root_rtol=None):
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
        root has ``|mu|`` below :data:`MIN_ROOT` (1e-6) or below
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
    root_rtol : float, optional
        Largest relative round-off ``eps max ||Phi_k|| / |mu|`` of the lift's
        most damped wanted root: ``K`` is raised until it holds.  Default:
        :data:`ROOT_RTOL` (1e-6), or :data:`STATE_ROOT_RTOL` (1e-4) with
        ``min_rate``.

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
    period = check_period(period)
    method = check_method(method)
    if on_inaccurate not in ON_INACCURATE:
        raise ValueError(f"on_inaccurate must be one of {ON_INACCURATE}, got {on_inaccurate!r}")
    if atol is not None:
        atol, rtol = (check_tolerance(name, v) for name, v in (("atol", atol), ("rtol", rtol)))
    if min_rate is not None and not (np.isfinite(min_rate) and min_rate < 0):
        raise ValueError(f"min_rate must be a negative damping rate or None, got {min_rate!r}")
    if root_rtol is None:
        root_rtol = ROOT_RTOL if min_rate is None else STATE_ROOT_RTOL
    _check_trust("root_rtol", root_rtol)
    a, n_steps, constant = sample(A, n_steps, period)
    k_sub = check_sub(n_sub, n_steps)
    problem = _Problem(A, period, constant, method, check_int("max_sub", max_sub, 1), shapes,
                       shift_states, min_rate, participation, root_rtol)
    if max_steps is None:
        max_steps = n_steps * 2**MAX_DOUBLINGS
    max_steps = check_int("max_steps", max_steps, 1)
    if atol is None:
        return _one_grid(problem, a, n_steps, k_sub)
    return _step_doubling(problem, a, n_steps, k_sub, max_steps, (atol, rtol), on_inaccurate)


@dataclass(frozen=True)
class _Problem:
    """What every grid of :func:`floquet_modes` solves: ``A`` and the options of the lift."""

    A: object
    period: float
    constant: bool
    method: str
    max_sub: int
    shapes: bool
    shift_states: object
    min_rate: float | None
    participation: bool
    root_rtol: float

    @property
    def refinable(self) -> bool:
        """Whether ``A`` can be sampled on a finer grid (not periodic samples)."""
        return callable(self.A) or self.constant

    def resample(self, n_steps):
        """The samples of ``A`` for ``n_steps`` steps per period."""
        return sample(self.A, n_steps, self.period)[0]

    def solve(self, a, n_steps, k_sub):
        """``(result, max ||Phi_k||, split)`` on the grid of the samples ``a``."""
        p = propagators(a, self.period / n_steps, self.constant, self.method)
        return _modes(p, self.period, k_sub, self.max_sub, self.shapes, self.shift_states,
                      self.min_rate, self.participation, _frozen(a), self.root_rtol)


def _one_grid(problem, a, n_steps, k_sub):
    """The modes on one grid, without error control (``atol=None``): the RK4 step-limit
    warning of :func:`step_propagators` instead."""
    if problem.method == "rk4":
        rk4_step_warning(a[:3] if problem.constant else a, problem.period / n_steps, n_steps)
    res, _, split = problem.solve(a, n_steps, k_sub)
    return _returned(res, split)


def _step_doubling(problem, a, n_steps, k_sub, max_steps, tolerance, on_inaccurate):
    """The accuracy loop (docs/theory.md 5.6a): the exponents of ``N`` steps against
    those of ``N / 2``, the steps doubled while a trusted exponent misses its
    tolerance (or a transition matrix overflows), up to ``max_steps``; there
    :func:`inaccurate` warns or raises.  ``tolerance``: ``(atol, rtol)``."""
    coarse = None                  # exponents on the grid with half the steps
    while True:
        try:
            res, znorm, split = problem.solve(a, n_steps, k_sub)
        except FloquetOverflowError as err:
            if problem.refinable and 2 * n_steps <= max_steps:   # shorter steps may not overflow
                n_steps, coarse = 2 * n_steps, None
                a = problem.resample(n_steps)
                continue
            raise FloquetOverflowError(f"{err} (at n_steps = {n_steps} with method = "
                                       f"{problem.method!r}; the fastest root of the mean A "
                                       f"is {fastest_root(a):.3g} per unit of psi)") from None
        k_sub = res.n_sub
        if coarse is None and n_steps % 2 == 0:
            coarse = coarse_exponents(a[::2], problem.period, k_sub, problem.method,
                                      problem.constant, problem.min_rate)
        if coarse is None:                                  # odd step count: compare 2N
            if not problem.refinable or 2 * n_steps > max_steps:
                return _returned(res, split)
            coarse, n_steps = res.exponents, 2 * n_steps
            a = problem.resample(n_steps)
            continue
        res, bad, tol_re, tol_im = _misses(res, coarse, znorm, tolerance, problem.min_rate)
        if not bad.any() or not problem.refinable or 2 * n_steps > max_steps:
            if bad.any():      # an untrusted result is an error first (on_inaccurate="raise")
                inaccurate(res, bad, tol_re, tol_im, problem.method, on_inaccurate)
            return _returned(res, split)
        coarse, n_steps = res.exponents, 2 * n_steps
        a = problem.resample(n_steps)


def _misses(res, coarse, znorm, tolerance, min_rate):
    """The exponents that miss their tolerance (docs/theory.md 5.6a).

    Returns the result with its error estimates (:func:`error_estimates`), the
    trusted exponents above ``atol + rtol |sigma|`` in the damping rate or
    ``atol + rtol |eta|`` in the frequency, and those two tolerances.  Roots
    below ``min_rate`` are not held to them.
    """
    atol, rtol = tolerance
    est, trusted = error_estimates(res, coarse, znorm, atol)
    if min_rate is not None:            # roots below min_rate are not held to it
        trusted &= res.exponents.real >= min_rate
    tol_re = atol + rtol * np.abs(res.exponents.real)
    tol_im = atol + rtol * np.abs(res.exponents)   # |eta|: see floquet_modes
    bad = trusted & ((est.real > tol_re) | (est.imag > tol_im))
    return replace(res, error_estimates=est), bad, tol_re, tol_im


def _returned(res, split):
    """`res`, after the RuntimeWarning when the lifted roots did not split."""
    if not split:
        warn_unsplit()
    return res


def _check_trust(name, value):
    """``ValueError`` unless `value` (``min_root``, ``root_rtol``) is a number in (0, 1)."""
    if isinstance(value, bool) or not (isinstance(value, (int, float, np.floating))
                                       and 0.0 < value < 1.0):
        raise ValueError(f"{name} must be a number in (0, 1), got {value!r}")


def _frozen(a):
    """The least real part of the eigenvalues of the mean of the samples ``a``, lazily
    and once: :func:`choose_sub` may ask twice (the adjoints' ``K``, then the
    smallest multiplier's estimate), and each asking was an eigenvalue problem
    (0.26 ms for MDART's 20 states; measured at mu = 0.3, twice in each of the
    point's two solves with participation)."""
    held: list = []

    def rate():
        if not held:
            with np.errstate(all="ignore"):
                ev = np.linalg.eigvals(np.mean(a, axis=0))
            held.append(float(ev.real.min()) if np.isfinite(ev).all() else float("nan"))
        return held[0]
    return rate


def _lift(p, period, k_sub, max_sub, min_rate=None, duals=False, frozen_rate=None,
          min_root=MIN_ROOT, root_rtol=ROOT_RTOL):
    """The lifted roots: ``K`` chosen and raised until they are resolved.

    Returns ``K``, the roots ``mu``, the right (and with ``duals`` left)
    eigenvector blocks, the steps grouped by sub-interval (``stack, bounds,
    valid``, :func:`group`), ``max ||Phi_k||`` and whether the roots split.
    """
    n_steps = p.shape[0]
    k_sub = check_sub(k_sub, n_steps)
    max_sub = min(max(max_sub, k_sub), n_steps)
    eps = np.finfo(float).eps
    # K before solving, from a cheap bound of the smallest multiplier
    levels: dict = {}
    k_sub = choose_sub(p, period, k_sub, max_sub, min_rate, frozen_rate, duals, levels,
                       min_root, root_rtol)
    while True:
        stack, bounds, valid = group(p, k_sub)
        phis = sub_products(p, k_sub, levels)
        cut = root_cut(min_rate, period, k_sub)
        mu, blocks, split, *lblocks = lifted(phis, cut, left=duals)
        # with min_rate, the roots below the cut need not be resolved
        smallest = max(np.abs(mu).min(), cut)
        # a root is trusted when it is above MIN_ROOT and its round-off,
        # eps ||Z|| / |mu| relative (||Z|| = the largest ||Phi_k||), is <= root_rtol
        # (1e-6 by default)
        with np.errstate(over="ignore"):     # an inf norm: no K resolves it (below)
            znorm = float(np.linalg.norm(phis, axis=(1, 2)).max())
            floor = max(min_root, eps * znorm / root_rtol)
        if k_sub >= max_sub:
            break
        if split and smallest >= floor:
            # the conditioning check where every root is to be resolved: with
            # min_rate (aerodynamic states) the shed wake's nearly repeated roots
            # are ill-conditioned by nature and unwanted; doubling K for them cost
            # 3.3 s instead of 0.85 s at MDART mu = 0.3, c_cg 0.33, for the same
            # roots to 1e-6 /rev (measured)
            if not (duals and min_rate is None
                    and _ill_conditioned(mu, blocks, lblocks[0], znorm, cut)):
                break
            k_sub = min(max_sub, 2 * k_sub)      # a nearly defective root: a finer lift
            continue
        # |mu| = |lambda|^(1/K): the K that lifts the most damped root to the
        # floor (from the computed root even when it is garbage: then it is
        # below round-off, and the true one smaller still)
        if floor >= 1.0:        # ||Phi_k|| beyond root_rtol / eps: no K resolves it
            k_sub = max_sub
            continue
        need = k_sub * np.log(max(smallest, np.finfo(float).tiny)) / np.log(floor)
        if not (floor < 1.0 and np.isfinite(need) and need > 0):
            need = 2 * k_sub                     # round-off above 1: just halve the blocks
        k_sub = int(min(max_sub, max(2 * k_sub, 2 ** np.ceil(np.log2(need)))))
    return k_sub, mu, blocks, lblocks, (stack, bounds, valid), phis, znorm, split


def _solutions(blocks, stack, valid):
    """The solutions on the step grid, each sub-interval from its lifted block:
    ``x(psi) = Phi(psi, psi_k) v_k`` in sub-interval ``k`` (without ``mu^k``),
    ``(n_steps, n, m)`` in time order."""
    n, m = blocks.shape[1], blocks.shape[2]
    if np.iscomplexobj(stack):
        x = np.empty((*valid.shape, n, m), dtype=complex)
        cur = blocks.astype(complex)
        for step in range(valid.shape[1]):
            x[:, step] = cur
            cur = stack[:, step] @ cur
        return x[valid]
    # real propagators (a real system): the real and imaginary parts side by
    # side in one real product a step, not a complex product that first casts
    # the propagator (measured with 20 states, 72 steps: 10 roots 0.19 against
    # 0.25 ms; 20 roots 0.79 against 0.77 ms -- the products' size, not their
    # type, is what costs there)
    x = np.empty((*valid.shape, n, 2 * m))
    cur = np.concatenate([blocks.real, blocks.imag], axis=-1)
    for step in range(valid.shape[1]):
        x[:, step] = cur
        cur = stack[:, step] @ cur
    x = x[valid]
    return x[..., :m] + 1j * x[..., m:]


def floquet_motions(A, n_steps, n_sub=4, period=TWO_PI, method="magnus", max_sub=MAX_SUB,
                    min_root=MIN_ROOT, root_rtol=ROOT_RTOL):
    """Characteristic exponents and each root's motion over the period, on one grid.

    What continuation needs of a Floquet system at each step, and no more:
    the exponents on the principal branch (``|Im eta| <= pi / T``; no
    integer frequency shift is chosen), one of each conjugate pair, and the
    motion ``exp(-sigma psi) x(psi)`` of each root's solution on the step grid
    -- the solution without its decay, which no frequency convention changes
    (``exp(i omega psi) p(psi)`` for every choice of ``omega``; compare
    :func:`tefcore.modes.labels.trajectory_shapes`).  The lift is chosen as in
    :func:`floquet_modes` (``K`` raised until the most damped root is
    resolved); there is no error control, no Fourier analysis of the
    periodic shapes and no participation: about half the cost of
    :func:`floquet_modes` with ``shapes=True`` (measured: 3.6 against 6.6 ms
    for MDART's 20 states at mu = 0.3, 72 Magnus steps).

    Parameters
    ----------
    A : callable
        Vectorised ``A(psi)`` of a real system (see :func:`step_propagators`).
    n_steps : int
        Steps per period.
    n_sub : int, optional
        The first ``K`` tried (as in :func:`floquet_modes`).
    period : float, optional
        Period ``T``.
    method : {'magnus', 'rk4'}, optional
        Step integrator.
    max_sub : int, optional
        Largest ``K``.
    min_root : float, optional
        Least modulus of a lifted root that is trusted: ``K`` is raised until
        the most damped root's ``|mu|`` is above it (and above the round-off
        floor ``eps max ||Phi_k|| / root_rtol``).  Default :data:`MIN_ROOT`;
        a caller that needs the roots told apart rather than converged may
        pass less (the continuation's path steps,
        :mod:`tefcore.modes.continuation`).
    root_rtol : float, optional
        Largest relative round-off ``eps max ||Phi_k|| / |mu|`` of a trusted
        root; default :data:`ROOT_RTOL` (1e-6, the floor ``1e6 eps max
        ||Phi_k||``).

    Returns
    -------
    exponents : numpy.ndarray of complex
        One per kept root [per unit of psi]: the root of each conjugate pair
        of multipliers with ``0 < Im eta < pi / T``, and every real multiplier
        (``Im eta`` 0 or ``pi / T``).
    motions : numpy.ndarray of complex
        ``(n_steps, n, m)``: ``exp(-sigma psi) x(psi)`` of each kept root.

    Examples
    --------
    An undamped oscillator at 0.3 /rev: one root, its motion ``exp(0.3 i psi)``
    times its eigenvector.

    >>> import numpy as np
    >>> a = np.array([[0.0, 1.0], [-0.09, 0.0]])
    >>> eta, x = floquet_motions(lambda psi: np.broadcast_to(a, (len(psi), 2, 2)), 72)
    >>> np.round(eta, 6), x.shape
    (array([0.+0.3j]), (72, 2, 1))
    """
    period = check_period(period)
    method = check_method(method)
    for name, value in (("min_root", min_root), ("root_rtol", root_rtol)):
        _check_trust(name, value)
    a, n_steps, constant = sample(A, n_steps, period)
    p = propagators(a, period / n_steps, constant, method)
    k_sub, mu, blocks, _, (stack, bounds, valid), _, znorm, split = _lift(
        p, period, n_sub, check_int("max_sub", max_sub, 1), frozen_rate=_frozen(a),
        min_root=min_root, root_rtol=root_rtol)
    if not split:
        warn_unsplit()
    log_mu = log_roots(mu)
    # the multiplier's angle, K arg(mu), on the principal branch: the lift's
    # roots of a conjugate pair of multipliers need not be conjugates, their
    # multipliers are (to round-off)
    angle = np.angle(np.exp(1j * k_sub * log_mu.imag))
    # a real multiplier (a frequency locked to k/2 /rev, or no oscillation) is
    # its own conjugate: kept, snapped onto the real axis (angle 0 or pi
    # exactly; the two of a locked pair both).  Whether a root is on the axis
    # is decided within its accuracy, the angle its multiplier can have by
    # round-off: a lifted root carries a relative error of about
    # eps ||Z|| / |mu| (``||Z||`` = max ||Phi_k||), and where two real roots
    # meet (the roots of a lock at k/2 just formed) the error is its square
    # root -- K times that in the multiplier's angle.  A fixed threshold below
    # that error leaves the decision to round-off: measured on Fig. 14's 0.2175 R
    # at eps 0.99414 (TEF pair at 5.5 /rev, -4.96 /rev, |mu| = 4e-4, ||Z|| =
    # 2.3e6), the two real multipliers of the lock read |sin| 1.5e-4 and 8e-7;
    # against 1e-8 both are dropped as the negative member of a complex pair,
    # or one is kept, as a relative nudge of 1e-12 of the blade mass decides;
    # the bound there is 4.5e-3.  Real roots elsewhere read |sin| at most 7e-14 and complex ones
    # at least 0.04 (Fig. 9's points, c_cg 0-0.36, eps 0.25-0.75); the floor
    # 1e-8 keeps well-resolved roots decided as before.
    with np.errstate(divide="ignore"):
        near_axis = np.maximum(1e-8, k_sub * np.sqrt(np.finfo(float).eps * znorm
                                                     / np.abs(mu)))
    real = np.abs(np.sin(angle)) <= near_axis
    angle = np.where(real, np.where(np.cos(angle) < 0.0, np.pi, 0.0), angle)
    keep = real | (angle > 0)
    # only the kept roots' motions are propagated: half the columns (measured
    # with 20 states, 72 steps: 0.19 ms for the 10 kept against 0.77 for all 20)
    log_mu, angle = log_mu[keep], angle[keep]
    x = _solutions(blocks[:, :, keep], stack, valid)
    h = period / n_steps
    psi = np.arange(n_steps) * h
    k_of = np.repeat(np.arange(k_sub), np.diff(bounds))
    psi_k = bounds[k_of] * h
    # x(psi) = mu^k Phi(psi, psi_k) v_k; exp(-sigma psi) mu^k = exp(-sigma (psi - psi_k)
    # + i Im(log mu) k) for equal sub-intervals: bounded factors only
    rate = k_sub * log_mu.real / period
    expo = (-rate[None, :] * (psi - psi_k)[:, None]
            + 1j * log_mu.imag[None, :] * k_of[:, None]
            + log_mu.real[None, :] * (k_of - k_sub * psi_k / period)[:, None])
    with np.errstate(over="ignore", invalid="ignore"):
        x = np.exp(np.minimum(expo.real, 700.0) + 1j * expo.imag)[:, None, :] * x
    x[~np.isfinite(x)] = 0.0                       # only for unresolvable (garbage) roots
    return rate + 1j * angle / period, x


def _modes(p, period, k_sub, max_sub, shapes, shift_states, min_rate=None, duals=False,
           frozen_rate=None, root_rtol=ROOT_RTOL):
    """Floquet modes from the step propagators ``p``; also ``max ||Phi_k||`` and whether
    the lifted roots split one per multiplier.  ``duals``: with the participation
    factors from the adjoint solutions (:func:`_adjoint_participation`)."""
    n_steps, n = p.shape[0], p.shape[-1]
    k_sub, mu, blocks, lblocks, (stack, bounds, valid), phis, znorm, split = _lift(
        p, period, k_sub, max_sub, min_rate, duals, frozen_rate, root_rtol=root_rtol)
    log_mu = log_roots(mu)
    eta = k_sub * log_mu / period                  # the branch of the selected roots

    # solution on the step grid, each sub-interval from its lifted block:
    # x(psi) = mu^k Phi(psi, psi_k) v_k for psi in sub-interval k
    x = _solutions(blocks, stack, valid)           # (n_steps, n, m), in time order
    if duals:
        # adjoint solutions on the same grid, carried backwards from the start of
        # the next sub-interval, y(psi_m) = P_m^H y(psi_m+1) (u_k = Phi_k^H u_k+1
        # / conj(mu)): no inverse, and backwards is the adjoint's stable direction
        # (it decays where the solution grows); scalar factors cancel below
        y = np.empty((*valid.shape, n, n), dtype=complex)
        stack_h = np.swapaxes(stack, -1, -2).conj()
        cur = np.roll(lblocks[0], -1, axis=0).astype(complex)     # u_k+1 for block k
        for step in range(valid.shape[1] - 1, -1, -1):
            cur = stack_h[:, step] @ cur
            # keep the columns of order one (a decaying adjoint, backwards)
            cur /= np.maximum(np.abs(cur).max(axis=1, keepdims=True), np.finfo(float).tiny)
            y[:, step] = cur
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
    unit = TWO_PI / period
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
    return (sorted_result(eta, multipliers, per[0], period, psi if shapes else None,
                          per if shapes else None, n_sub=k_sub, n_steps=n_steps,
                          participation=part),
            znorm, split)


def sub_products(p, k, levels):
    """The ``k`` sub-interval transition matrices of the step propagators ``p``.

    ``levels`` (a dict, ``K -> (K, n, n)``) keeps what was computed: ``K = 8`` by
    tree products over its groups, the coarser levels whose bounds nest in a finer
    one by pairwise products of that one (three small products for 4, 2, 1).

    Parameters
    ----------
    p : numpy.ndarray
        Step propagators ``(n_steps, n, n)``.
    k : int
        Sub-intervals.
    levels : dict
        Cache of the levels.

    Returns
    -------
    numpy.ndarray
        ``(k, n, n)``.
    """
    if k in levels:
        return levels[k]
    n_steps = p.shape[0]

    def bounds(kk):
        return (np.arange(kk + 1) * n_steps) // kk

    finer = 2 * k
    if finer <= min(8, n_steps) and np.array_equal(bounds(finer)[::2], bounds(k)):
        fine = sub_products(p, finer, levels)
        with np.errstate(over="ignore", invalid="ignore"):
            out = fine[1::2] @ fine[0::2]
        if not np.isfinite(out).all():
            raise FloquetOverflowError("the transition matrices overflow: the system is too "
                                       "stiff for this step (increase n_steps, or use "
                                       "method='magnus')")
    else:
        out = tree_product(group(p, k)[0])
    levels[k] = out
    return out


def _ill_conditioned(mu, right, left, znorm, cut):
    """Whether a resolved root (``|mu| >= cut``) of the lift has a first-order
    round-off bound ``eps ||Z|| kappa / |mu|`` (``||Z|| = znorm``) above :data:`LIFT_RTOL`
    (``kappa = |u| |v| / |u^H v|`` of its stacked left and right eigenvectors)."""
    k_sub, n, m = right.shape
    v = right.reshape(k_sub * n, m)
    u = left.reshape(k_sub * n, m)
    with np.errstate(all="ignore"):
        kappa = (np.linalg.norm(u, axis=0) * np.linalg.norm(v, axis=0)
                 / np.abs(np.einsum("ij,ij->j", u.conj(), v)))
        bound = np.finfo(float).eps * znorm * kappa / np.abs(mu)
    resolved = np.abs(mu) >= cut
    return bool(np.any(resolved & ~(bound <= LIFT_RTOL)))


def choose_sub(p, period, k_min, max_sub, min_rate=None, frozen_rate=None, duals=False,
               levels=None, min_root=MIN_ROOT, root_rtol=ROOT_RTOL):
    """Sub-intervals ``K`` for the lift, chosen before solving it.

    The explicit product ``Phi`` (cheap: ``n x n`` eigenvalues) gives the
    moduli of the multipliers down to its round-off ``1e3 eps ||Phi_2|| ||Phi_1||``
    (``Phi_1, Phi_2`` its halves).  When every multiplier is above that, the
    smallest one is known; otherwise it is estimated from the most damped
    root of the mean ``A``, ``frozen_rate``, less 1/2 per rev (the lift then
    checks it, :func:`floquet_modes`).  ``K`` is the least power of two, at
    least ``k_min`` and at most ``max_sub``, that lifts it (or
    ``exp(min_rate T)``, if larger) to the floor ``max(min_root, eps
    max ||Phi_k|| / root_rtol)`` (``1e6 eps max ||Phi_k||`` by default).

    Parameters
    ----------
    p : numpy.ndarray
        Step propagators ``(n_steps, n, n)``.
    period : float
        The period ``T``.
    k_min, max_sub : int
        Least and largest ``K``.
    min_rate : float, optional
        Roots below this damping rate need not be resolved.
    frozen_rate : float or callable, optional
        Least real part of the eigenvalues of the mean ``A`` (per unit of psi),
        or a function returning it (called only when needed).
    duals : bool, optional
        The adjoint solutions will be propagated (participation factors): the
        adjoint of a root damped at ``sigma`` loses ``exp(|sigma| T / K)`` of
        its relative accuracy over a sub-interval, so ``K`` is at least
        ``|sigma| T / ln(1/eps)`` for the most damped root wanted: the mean
        ``A``'s (``frozen_rate``), or ``min_rate`` when that is higher (the
        roots below it are not wanted, and each root's adjoint is carried on
        its own).
    levels : dict, optional
        Sub-interval products computed on the way (:func:`sub_products`), for
        the lift to reuse.
    min_root : float, optional
        Least modulus of a lifted root that is trusted (:data:`MIN_ROOT`).
    root_rtol : float, optional
        Largest relative round-off of a trusted root (:data:`ROOT_RTOL`).

    Returns
    -------
    int
    """
    eps = np.finfo(float).eps
    n_steps = p.shape[0]
    if duals and frozen_rate is not None:
        rate = frozen_rate() if callable(frozen_rate) else frozen_rate
        if min_rate is not None and np.isfinite(rate):
            # the adjoints of roots below min_rate are not wanted: only theirs
            # lose accuracy (measured with the shed wake, MDART mu = 0.3, c_cg
            # 0.1 and 0.33: K 8 -> 2-4, every exponent, share and flap motion
            # of the point within 3e-12 of the K the wake's -31 /rev forced,
            # the same names; 1.66 -> 0.75 s a point)
            rate = max(rate, min_rate)
        need = -rate * period / np.log(1.0 / eps) if np.isfinite(rate) else max_sub
        if need > 1:
            k_min = max(k_min, int(2 ** np.ceil(np.log2(need))))
    levels = {} if levels is None else levels
    if n_steps < 2 or max_sub <= k_min:
        return int(min(max(k_min, 1), max_sub))
    halves = sub_products(p, 2, levels)
    phi = sub_products(p, 1, levels)[0]
    with np.errstate(over="ignore", invalid="ignore"):
        noise = 1e3 * eps * float(np.prod(np.linalg.norm(halves, axis=(1, 2))))
        if not (np.isfinite(phi).all() and np.isfinite(noise)):
            return int(max_sub)
        lam = np.abs(scipy.linalg.eigvals(phi, check_finite=False))
    if lam.min() >= 1e3 * noise:
        log_min = float(np.log(lam.min()))
    elif frozen_rate is not None:
        rate = frozen_rate() if callable(frozen_rate) else frozen_rate
        if not np.isfinite(rate):
            return int(max_sub)
        log_min = (rate - 0.5 * TWO_PI / period) * period
    else:
        return int(max_sub)
    if min_rate is not None:
        log_min = max(log_min, min_rate * period)
    k = max(1, int(k_min))
    while k < max_sub:
        phis = sub_products(p, k, levels)
        with np.errstate(over="ignore"):
            floor = max(min_root, eps * np.linalg.norm(phis, axis=(1, 2)).max() / root_rtol)
        if floor < 1.0 and log_min / k >= np.log(floor):
            break
        k *= 2
    return int(min(k, max_sub))


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
