"""Floquet analysis, part 3: the result (:class:`tefcore.floquet.FloquetResult`), the
damping ratio and the constant-coefficient case
(:func:`~tefcore.floquet.constant_coefficient_modes`).

Private: the public names are those of :mod:`tefcore.floquet`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg

from ..runtime import blas_limit
from ._propagators import TWO_PI, as_numeric, check_period

__all__ = ["damping_ratio", "eigenvalue_roundoff", "FloquetResult", "sorted_result",
           "constant_coefficient_modes"]


def damping_ratio(exponents):
    """Damping ratio ``zeta = -sigma / sqrt(sigma^2 + omega^2)`` of ``eta = sigma + i omega``.

    Positive for a decaying mode; 0 for ``eta = 0``.

    Parameters
    ----------
    exponents : complex or array_like
        Characteristic exponents ``eta``.

    Returns
    -------
    numpy.ndarray

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
    period: float = TWO_PI
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


def sorted_result(eta, multipliers, vectors, period, psi=None, shapes=None, n_sub=None,
                  n_steps=None, participation=None):
    order = np.lexsort((eta.real, np.round(eta.imag, 9)))   # frequency ties: by damping
    scale = _normalise(vectors)[order]
    return FloquetResult(
        exponents=eta[order], multipliers=multipliers[order],
        eigenvectors=vectors[:, order] * scale, period=period, psi=psi,
        shapes=None if shapes is None else shapes[..., order] * scale, n_sub=n_sub,
        n_steps=n_steps, participation=None if participation is None
        else participation[:, order])


@blas_limit()
def constant_coefficient_modes(A, period=TWO_PI):
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
    period = check_period(period)
    a = as_numeric(np.asarray(A), "A")
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] == 0:
        raise ValueError(f"A must be a square n x n matrix with n >= 1, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError("A has non-finite entries (NaN or inf)")
    eta, vectors = scipy.linalg.eig(a)
    # a real A with real eigenvalues gives real vectors: complex, like every result
    res = sorted_result(eta, np.exp(eta * period), vectors.astype(complex), period)
    return replace(res, error_estimates=eigenvalue_roundoff(a, res.eigenvectors))


def eigenvalue_roundoff(a, vectors) -> np.ndarray:
    """Round-off bound of each eigenvalue of ``a`` (the error estimate of a direct analysis).

    First-order perturbation theory: an eigenvalue moves by at most
    ``||E|| kappa_i`` under a perturbation ``E`` of ``a``, with ``kappa_i =
    ||x_i|| ||y_i|| / |y_i^H x_i|`` its condition number (right and left
    eigenvectors; the left ones are the rows of ``inv(X)``, normalised so that
    ``y_i^H x_i = 1``).  ``||E||`` is taken as ``1e2 eps ||a||``, the factor of
    the lift's round-off bound in :func:`tefcore.floquet.floquet_modes`.

    Parameters
    ----------
    a : ndarray, shape (n, n)
        The matrix.
    vectors : ndarray, shape (n, n)
        Its right eigenvectors (columns, any scaling).

    Returns
    -------
    ndarray of complex, shape (n,)
        The bound as ``b + 1j b`` (real part: the damping rate's, imaginary
        part: the frequency's); infinite for a defective matrix.

    Examples
    --------
    >>> a = np.array([[0.0, 1.0], [-4.0, 0.0]])     # undamped: exponents +-2i
    >>> res = constant_coefficient_modes(a)
    >>> bool(np.all(np.abs(res.exponents.real) <= res.error_estimates.real))
    True
    """
    try:
        left = np.linalg.inv(vectors)
    except np.linalg.LinAlgError:
        return np.full(vectors.shape[1], np.inf + 1j * np.inf)
    kappa = np.linalg.norm(vectors, axis=0) * np.linalg.norm(left, axis=1)
    bound = 1e2 * np.finfo(float).eps * np.linalg.norm(a, 2) * kappa
    return bound * (1 + 1j)
