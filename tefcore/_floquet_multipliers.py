"""Floquet analysis, part 2: characteristic multipliers from the factors of the monodromy
matrix by lifting to a block-cyclic matrix (the implementation of
:func:`tefcore.floquet.characteristic_multipliers`).

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

from ._floquet_propagators import TWO_PI, as_numeric
from .runtime import blas_limit

__all__ = ["lifted", "lift", "select_roots", "warn_unsplit", "log_roots",
           "characteristic_multipliers"]


def lifted(phis):
    """Eigen-decomposition of the block-cyclic lift, one root per multiplier.

    Returns the selected roots ``mu`` (``mu**K`` are the multipliers), the
    eigenvector blocks ``v_k`` of shape (K, n, n) (``v_0`` is the monodromy
    eigenvector at psi = 0 and ``v_k = Phi_k ... Phi_1 v_0 / mu**k``) and
    whether the roots split into one per multiplier (False: some are at
    round-off level and unreliable).
    """
    k_sub, n = phis.shape[0], phis.shape[1]
    mu, vec = scipy.linalg.eig(lift(phis))
    keep, split = select_roots(mu, k_sub, n)
    blocks = vec[:, keep].reshape(k_sub, n, n)
    return mu[keep], blocks, split


def lift(phis):
    """The block-cyclic matrix ``Z`` of the sub-interval transition matrices."""
    k_sub, n = phis.shape[0], phis.shape[1]
    z = np.zeros((k_sub * n, k_sub * n), dtype=phis.dtype)
    z4 = z.reshape(k_sub, n, k_sub, n)
    z4[(np.arange(k_sub) + 1) % k_sub, :, np.arange(k_sub), :] = phis   # Phi_k below diag
    return z


def select_roots(mu, k_sub, n):
    """Mask of one root ``mu`` per multiplier among the ``K n`` roots of the lift."""
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
