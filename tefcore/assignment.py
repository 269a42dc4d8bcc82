"""The linear sum assignment, without importing :mod:`scipy.optimize` when it is plain.

:func:`linear_sum_assignment` returns what
:func:`scipy.optimize.linear_sum_assignment` returns.  Most assignments tefcore
solves (mode labels, exponents matched between step sizes) are *plain*: every
row of the (wide) cost matrix has a strict minimum, in a column of its own.
Choosing those minima then costs the sum of the row minima, a lower bound of
every assignment, and any other assignment costs strictly more: it is the
unique optimum, the one scipy finds too.  Only when the certificate fails is
scipy's solver imported and called (importing :mod:`scipy.optimize` costs
0.15 s, a third of a ``tefcore stability`` command's wall time, measured).

Examples
--------
>>> import numpy as np
>>> rows, cols = linear_sum_assignment(np.array([[1.0, 5.0], [4.0, 2.0], [0.5, 9.0]]))
>>> rows.tolist(), cols.tolist()
([1, 2], [1, 0])
"""

from __future__ import annotations

import numpy as np

__all__ = ["linear_sum_assignment", "plain_assignment"]


def plain_assignment(cost) -> np.ndarray | None:
    """The optimum of a wide cost matrix when each row's strict minimum is its own column.

    Parameters
    ----------
    cost : numpy.ndarray
        ``(n_rows, n_cols)`` with ``n_rows <= n_cols``, finite.

    Returns
    -------
    numpy.ndarray or None
        The column of each row (the unique optimal assignment), or None when
        the certificate fails: a row's minimum is tied, or two rows share
        their minimum's column.
    """
    n_rows, n_cols = cost.shape
    if n_rows == 0:
        return np.zeros(0, dtype=np.intp)
    if n_cols == 1:
        return np.zeros(1, dtype=np.intp)
    best = np.argmin(cost, axis=1)
    if np.unique(best).size != n_rows:
        return None
    two = np.partition(cost, 1, axis=1)[:, :2]
    if not (two[:, 0] < two[:, 1]).all():          # a tie: the optimum may not be unique
        return None
    return best.astype(np.intp)


def linear_sum_assignment(cost):
    """The least-cost assignment, as :func:`scipy.optimize.linear_sum_assignment` gives it.

    Parameters
    ----------
    cost : array_like
        The cost matrix, ``(n_rows, n_cols)``.

    Returns
    -------
    row_ind, col_ind : numpy.ndarray
        The assigned pairs, ``row_ind`` increasing; ``min(n_rows, n_cols)`` of
        them.  Identical to scipy's: where the certificate of
        :func:`plain_assignment` holds the optimum is unique, and otherwise
        scipy's solver is called.
    """
    cost = np.asarray(cost)
    if cost.ndim == 2 and np.isrealobj(cost) and np.isfinite(cost).all():
        wide = cost.shape[0] <= cost.shape[1]
        cols = plain_assignment(cost if wide else cost.T)
        if cols is not None:
            if wide:
                return np.arange(cost.shape[0]), cols
            order = np.argsort(cols)
            return cols[order], order.astype(np.intp)
    import scipy.optimize  # the general solver: only when the assignment is not plain

    return scipy.optimize.linear_sum_assignment(cost)
