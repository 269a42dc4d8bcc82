"""Floquet analysis, part 2: characteristic multipliers from the factors of the monodromy
matrix by lifting to a block-cyclic matrix (the implementation of
:func:`tefcore.floquet.characteristic_multipliers`).

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

from ..runtime import blas_limit
from ._propagators import TWO_PI, as_numeric

__all__ = ["lifted", "lift", "select_roots", "root_cut", "warn_unsplit", "log_roots",
           "characteristic_multipliers"]


def lifted(phis, cut=0.0, left=False):
    """Eigen-decomposition of the block-cyclic lift, one root per multiplier.

    Returns the selected roots ``mu`` (``mu**K`` are the multipliers), the
    eigenvector blocks ``v_k`` of shape (K, n, n) (``v_0`` is the monodromy
    eigenvector at psi = 0 and ``v_k = Phi_k ... Phi_1 v_0 / mu**k``) and
    whether the roots split into one per multiplier (False: some are at
    round-off level and unreliable); with ``cut > 0`` only the roots with
    ``|mu| >= cut`` are judged (:func:`select_roots`).  ``left``: also the
    blocks ``u_k`` of the left eigenvectors (``u_k = Phi_k^H u_{k+1} / conj(mu)``,
    the adjoint solution at the start of sub-interval ``k``), as a fourth item.
    """
    k_sub, n = phis.shape[0], phis.shape[1]
    if left:
        mu, lvec, vec = scipy.linalg.eig(lift(phis), left=True)
    else:
        mu, vec = scipy.linalg.eig(lift(phis))
    keep, split = select_roots(mu, k_sub, n, cut)
    blocks = vec[:, keep].reshape(k_sub, n, n)
    if left:
        return mu[keep], blocks, split, lvec[:, keep].reshape(k_sub, n, n)
    return mu[keep], blocks, split


def lift(phis):
    """The block-cyclic matrix ``Z`` of the sub-interval transition matrices."""
    k_sub, n = phis.shape[0], phis.shape[1]
    z = np.zeros((k_sub * n, k_sub * n), dtype=phis.dtype)
    z4 = z.reshape(k_sub, n, k_sub, n)
    z4[(np.arange(k_sub) + 1) % k_sub, :, np.arange(k_sub), :] = phis   # Phi_k below diag
    return z


def select_roots(mu, k_sub, n, cut=0.0):
    """Mask of one root ``mu`` per multiplier among the ``K n`` roots of the lift.

    ``cut > 0``: roots with ``|mu| < cut`` need not be resolved (``min_rate`` of
    :func:`tefcore.floquet.floquet_modes`); the window and the splitting are
    decided by the others, and the deep ones fill the selection up to ``n``.
    """
    if cut > 0.0:
        return _select_resolved(mu, k_sub, n, cut)
    # The K n eigenvalues are the K K-th roots mu w^j (w = exp(2 pi i / K)) of
    # every multiplier, so modulo 2 pi / K their angles collapse to n points.
    # Any half-open window of width 2 pi / K holds one root per multiplier;
    # starting it in the widest gap between those points (>= 2 pi / (K n))
    # keeps roundoff from putting two roots of one multiplier in it, or none,
    # e.g. for the pair of roots at +-pi/K of a negative real multiplier.
    sector = TWO_PI / k_sub
    theta = np.angle(mu)
    s = np.sort(np.mod(theta, sector))
    gaps = np.diff(np.append(s, s[0] + sector))
    start = s[np.argmax(gaps)] + 0.5 * gaps.max()
    keep = np.mod(theta - start, TWO_PI) < sector
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
    """:func:`select_roots` judged on the roots with ``|mu| >= cut`` only."""
    big = np.abs(mu) >= cut
    sector = TWO_PI / k_sub
    theta = np.angle(mu)
    if big.any():
        s = np.sort(np.mod(theta[big], sector))
        gaps = np.diff(np.append(s, s[0] + sector))
        start = s[np.argmax(gaps)] + 0.5 * gaps.max()
    else:
        start = 0.0
    window = np.mod(theta - start, TWO_PI) < sector
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


def root_cut(min_rate, period, k_sub):
    """``|mu|`` of a root at ``min_rate`` with ``K`` sub-intervals (0: no cut)."""
    return 0.0 if min_rate is None else float(np.exp(min_rate * period / k_sub))


def warn_unsplit(stacklevel=3):
    warnings.warn("lifted eigenvalues do not split into one root per multiplier; "
                  "multipliers near roundoff level are unreliable", RuntimeWarning,
                  stacklevel=stacklevel)


def log_roots(mu):
    # a root that underflowed to 0 (a mode decaying faster than ~ -700 K / T)
    # gets the smallest normal modulus instead of log(0) = -inf
    tiny = np.finfo(float).tiny
    return np.log(np.maximum(np.abs(mu), tiny)) + 1j * np.angle(mu)


@blas_limit()
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
    phis = as_numeric(np.asarray(phis), "phis")
    if phis.ndim == 2:
        phis = phis[None]
    if phis.ndim != 3 or phis.shape[1] != phis.shape[2] or 0 in phis.shape:
        raise ValueError(f"phis must have shape (K, n, n) with K, n >= 1, got {phis.shape}")
    if not np.isfinite(phis).all():
        raise ValueError("phis has non-finite entries (NaN or inf)")
    mu, blocks, split = lifted(phis)
    if not split:
        warn_unsplit()
    multipliers = np.exp(phis.shape[0] * log_roots(mu))
    if not return_vectors:
        return multipliers
    v = blocks[0]
    return multipliers, v / np.linalg.norm(v, axis=0)
