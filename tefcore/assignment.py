"""The linear sum assignment, without importing :mod:`scipy.optimize` when it is plain.

:func:`linear_sum_assignment` returns what
:func:`scipy.optimize.linear_sum_assignment` returns.  Most assignments tefcore
solves (mode labels, exponents matched between step sizes) are *plain*: every
row of the (wide) cost matrix has a strict minimum, in a column of its own.
Choosing those minima then costs the sum of the row minima, a lower bound of
every assignment, and any other assignment costs strictly more: it is the
unique optimum, the one scipy finds too.  When the certificate fails on a
small square matrix and :mod:`scipy.optimize` is not imported yet, the
optimum is found by shortest augmenting paths (:func:`augmenting_assignment`)
and kept only when it is unique by a margin (:func:`unique_margin`: every
other assignment costs more by more than round-off), so that it is the one
scipy finds too.  Only otherwise is scipy's solver imported and called
(importing :mod:`scipy.optimize` costs 0.15-0.2 s, a fifth of a ``tefcore
stability`` command's wall time, measured).

Examples
--------
>>> import numpy as np
>>> rows, cols = linear_sum_assignment(np.array([[1.0, 5.0], [4.0, 2.0], [0.5, 9.0]]))
>>> rows.tolist(), cols.tolist()
([1, 2], [1, 0])
"""

from __future__ import annotations

import sys

import numpy as np

__all__ = ["augmenting_assignment", "linear_sum_assignment", "plain_assignment",
           "unique_margin"]

#: Largest square matrix solved here rather than by scipy (the augmenting
#: paths cost ~n^3 Python-level numpy operations: ~0.3 ms at n = 11).
OWN_SOLVER_MAX = 24


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
        n = cost.shape[0]
        if cost.shape[1] == n and n <= OWN_SOLVER_MAX and not _scipy_solver_loaded():
            cols = augmenting_assignment(cost)
            scale = max(1.0, float(np.abs(cost).max()))
            if unique_margin(cost, cols) > 1e-9 * scale:    # far above round-off
                return np.arange(n), cols
    import scipy.optimize  # the general solver: only when the assignment is not plain

    return scipy.optimize.linear_sum_assignment(cost)


def _scipy_solver_loaded() -> bool:
    """Whether scipy's solver is imported already (then it is the cheaper call)."""
    return "scipy.optimize" in sys.modules


def augmenting_assignment(cost) -> np.ndarray:
    """The least-cost assignment of a square cost matrix by shortest augmenting paths.

    The Hungarian method in its shortest-path form (Kuhn-Munkres with
    potentials, as in Jonker and Volgenant): rows enter one at a time, each by
    a Dijkstra search over reduced costs from it to a free column.

    Parameters
    ----------
    cost : numpy.ndarray
        ``(n, n)``, finite.

    Returns
    -------
    numpy.ndarray
        The column of each row.

    References
    ----------
    R. Jonker and A. Volgenant, "A shortest augmenting path algorithm for
    dense and sparse linear assignment problems", *Computing* 38 (1987).

    Examples
    --------
    >>> augmenting_assignment(np.array([[4.0, 1.0, 3.0], [2.0, 0.0, 5.0], [3.0, 2.0, 2.0]]))
    array([1, 0, 2])
    """
    cost = np.asarray(cost, float)
    n = cost.shape[0]
    u, v = np.zeros(n + 1), np.zeros(n + 1)      # potentials; index 0 is the virtual start
    row_of = np.zeros(n + 1, dtype=np.intp)      # row (1-based) assigned to column j, 0: free
    way = np.zeros(n + 1, dtype=np.intp)
    for i in range(1, n + 1):
        row_of[0] = i
        j0 = 0
        dist = np.full(n + 1, np.inf)
        used = np.zeros(n + 1, bool)
        while True:
            used[j0] = True
            i0 = row_of[j0]
            reduced = cost[i0 - 1] - u[i0] - v[1:]
            better = ~used[1:] & (reduced < dist[1:])
            dist[1:][better] = reduced[better]
            way[1:][better] = j0
            free = np.where(used[1:], np.inf, dist[1:])
            j1 = int(np.argmin(free)) + 1
            delta = free[j1 - 1]
            u[row_of[used]] += delta
            v[used] -= delta
            dist[~used] -= delta
            j0 = j1
            if row_of[j0] == 0:
                break
        while j0:                                 # augment along the path back
            j1 = way[j0]
            row_of[j0] = row_of[j1]
            j0 = j1
    cols = np.empty(n, dtype=np.intp)
    cols[row_of[1:] - 1] = np.arange(n)
    return cols


def unique_margin(cost, cols) -> float:
    """How much dearer the cheapest other assignment is than ``cols``.

    Any other assignment differs from ``cols`` by cycles of rows each taking
    the next one's column; the cheapest cycle (by Floyd-Warshall over the
    exchange costs ``cost[i, cols[j]] - cost[i, cols[i]]``) is the margin.
    Positive when ``cols`` is the unique optimum, 0 at a tie, negative when
    ``cols`` is not optimal.

    Parameters
    ----------
    cost : numpy.ndarray
        ``(n, n)``.
    cols : numpy.ndarray
        The column of each row.

    Returns
    -------
    float
        inf for one row.

    Examples
    --------
    >>> round(unique_margin(np.array([[0.1, 0.4], [0.3, 0.1]]), np.array([0, 1])), 12)
    0.5
    """
    cost = np.asarray(cost, float)
    own = cost[np.arange(len(cols)), cols]
    dist = cost[:, cols] - own[:, None]
    np.fill_diagonal(dist, np.inf)
    for k in range(len(cols)):
        dist = np.minimum(dist, dist[:, k, None] + dist[None, k, :])
    return float(np.min(np.diag(dist))) if len(cols) > 1 else float("inf")
