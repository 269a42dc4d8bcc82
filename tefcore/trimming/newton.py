"""Linear algebra of the trim's Newton iterations (docs/theory.md section 7).

* :func:`factor`: the factorised Newton matrix, with the shed-wake states
  eliminated first through their block-diagonal block (:class:`WakeSchur`);
* :class:`BroydenSolver`: solves with a factorised Jacobian and Broyden's
  rank-one updates, so that the chord iterations converge superlinearly without
  re-evaluating the Jacobian.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

__all__ = ["BroydenSolver", "WakeSchur", "factor"]


class BroydenSolver:
    """Solves with a factorised Jacobian and Broyden's ("good") rank-one updates.

    ``H = J0^-1`` updated as ``H += (s - H y) (H^T s)^T / (s . H y)`` after each
    step ``s`` with residual change ``y`` (Sherman-Morrison form of Broyden's
    secant update), applied as stored vectors: no refactorisation.

    Parameters
    ----------
    lu : tuple
        :func:`scipy.linalg.lu_factor` of the Jacobian.
    """

    def __init__(self, lu):
        self.lu = lu
        self.u, self.w = [], []

    def _h(self, v, trans=0):
        out = scipy.linalg.lu_solve(self.lu, v, trans=trans, check_finite=False)
        for u, w in zip(self.u, self.w, strict=True):
            out = out + (w * (u @ v) if trans else u * (w @ v))
        return out

    def solve(self, rhs):
        """``H rhs``.

        Parameters
        ----------
        rhs : numpy.ndarray
            Right-hand side.

        Returns
        -------
        numpy.ndarray
        """
        return self._h(rhs)

    def update(self, s, y):
        """Broyden's update for the step ``s`` and the residual change ``y``.

        Parameters
        ----------
        s, y : numpy.ndarray
            Step and change of the residual over it.
        """
        hy = self._h(y)
        denom = float(s @ hy)
        if not np.isfinite(denom) or abs(denom) < 1e-300:
            return
        w = self._h(s, trans=1)
        self.u.append((s - hy) / denom)
        self.w.append(w)



def factor(jac, model, n_psi):
    """LU factors of the Newton matrix; with wake states, by the Schur complement.

    Parameters
    ----------
    jac : numpy.ndarray
        The Newton matrix of the trim.
    model : tefcore.model.coupled.CoupledModel
        The model (its shed-wake states, if any).
    n_psi : int
        Collocation azimuths.

    Returns
    -------
    tuple or WakeSchur
        :func:`scipy.linalg.lu_factor` of ``jac``, or with wake states a
        :class:`WakeSchur`.
    """
    if not model.n_wake:
        return scipy.linalg.lu_factor(jac, check_finite=False)
    return WakeSchur(jac, model.n_dof * n_psi, model.wake.n_per_station * n_psi,
                      model.wake.n_stations)


class WakeSchur:
    """Newton solves that eliminate the wake states first.

    The wake rows of one station depend on its own states only, so their block
    of the Newton matrix is block diagonal (one ``N_w N`` block per station,
    ``D w + f E^-1 w``, invertible: a stable state has one periodic response).
    Its blocks are inverted and the rest solved through the Schur complement
    ``S = A - B D^-1 C`` (order ``n N + controls``: 244 instead of 1971 for MDART
    at ``N = 24``; 0.02 s instead of 0.4 s a factorisation, measured).

    Parameters
    ----------
    jac : numpy.ndarray
        The Newton matrix.
    start : int
        First row of the wake states.
    block : int
        States of one station over the azimuths.
    n_blocks : int
        Stations.
    """

    def __init__(self, jac, start, block, n_blocks):
        size = jac.shape[0]
        self.w = np.arange(start, start + block * n_blocks)
        self.o = np.concatenate([np.arange(start), np.arange(start + block * n_blocks, size)])
        self.shape = (n_blocks, block)
        d = jac[np.ix_(self.w, self.w)].reshape(n_blocks, block, n_blocks, block)
        self.d_inv = np.linalg.inv(d[np.arange(n_blocks), :, np.arange(n_blocks), :])
        self.b = jac[np.ix_(self.o, self.w)]
        self.dinv_c = self._dinv(jac[np.ix_(self.w, self.o)])
        self.lu = scipy.linalg.lu_factor(jac[np.ix_(self.o, self.o)] - self.b @ self.dinv_c,
                                         check_finite=False)

    def _dinv(self, rhs):
        n_blocks, block = self.shape
        out = self.d_inv @ rhs.reshape(n_blocks, block, -1)
        return out.reshape(rhs.shape)

    def solve(self, rhs):
        """``jac^-1 rhs``.

        Parameters
        ----------
        rhs : numpy.ndarray
            Right-hand side.

        Returns
        -------
        numpy.ndarray
        """
        y = self._dinv(rhs[self.w])
        x_o = scipy.linalg.lu_solve(self.lu, rhs[self.o] - self.b @ y, check_finite=False)
        out = np.empty_like(rhs)
        out[self.o] = x_o
        out[self.w] = y - self.dinv_c @ x_o
        return out
