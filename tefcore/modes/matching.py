"""Matching modes between two points: MAC, eigenvalue distances, the match cost.

An eigen-solver returns the modes of each sweep point in its own order
(usually by frequency), so where two modes cross in frequency, "mode 3" at
one point is "mode 4" at the next.  :func:`match_modes` (and
:func:`tefcore.modes.tracking.track_modes` along a whole sweep) matches the modes of
two points with an optimal assignment
(:func:`scipy.optimize.linear_sum_assignment`) on the cost

.. math::

    C_{ij} = (1 - \\text{MAC}_{ij}) + \\min\\Big(1, \\sqrt{
        \\Big(\\frac{\\Delta\\sigma}{1/2 + (|\\hat\\sigma_i| + |\\sigma_j|)/2}\\Big)^2
      + \\Big(\\frac{\\Delta\\omega}{s_\\omega}\\Big)^2}\\Big),
    \\qquad s_\\omega = 1 + (|\\hat\\omega_i| + |\\omega_j|)/2

between track *i* (its last shape and its eigenvalue
:math:`\\hat\\lambda_i = \\hat\\sigma_i + i\\hat\\omega_i` extrapolated linearly
to the new parameter value) and mode *j* of the new point, with eigenvalues
:math:`\\lambda = \\text{real\\_part} + i\\,\\text{frequency\\_per\\_rev}` in
/rev: damping-rate and frequency differences each relative to their own
size (a damping-rate difference of 0.7 /rev between two roots near 8 and
14 /rev is large, though small against the frequencies).  For Floquet
exponents (``periodic`` points) the frequency difference is taken modulo
1/rev and up to its sign, since only the multiplier
:math:`e^{2\\pi\\lambda}` is unique, and measured against its largest
possible value, :math:`s_\\omega = 1/2` (two Floquet modes near 10.5 and
3.2 /rev can have one displacement shape at psi = 0; their frequencies
differ by 0.3 modulo 1, which is what tells them apart).  The shapes are compared in a basis
that does not change along the sweep (:meth:`tefcore.model.coupled.CoupledModel.tracking_basis`).

A match is *clear* (:func:`is_clear`) when its shape part ``1 - MAC`` is at
most :data:`CLEAR_COST` (the eigenvalue part alone when no shapes are known)
and every alternative costs at least :data:`MARGIN` more.  Two roots of one
point with the same shape and eigenvalue (:func:`is_coalesced`) are a
coalescence that no step refinement can separate; so are the two real
multipliers of a Floquet lock (:func:`is_locked`), whose plane of shapes
(:func:`plane_mac`) holds the one complex shape the pair has outside the
lock (:mod:`tefcore.modes.tracking`).

Examples
--------
>>> import numpy as np
>>> a = np.array([[1.0, 0.0], [0.0, 1.0]], complex)
>>> b = np.array([[0.0, 1.0], [1.0, 0.1]], complex)
>>> np.round(mac(a, b), 3)      # mode 0 of a is mode 1 of b, and the reverse
array([[0.  , 0.99],
       [1.  , 0.01]])
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["CLEAR_COST", "COALESCED_DISTANCE", "COALESCED_MAC", "LOCK_TOL", "MARGIN",
           "MODE_COLUMNS", "as_point", "continuous_frequency", "decide", "eigen_distance",
           "eigenvalues", "is_clear", "is_coalesced", "is_locked", "locked_pairs", "mac",
           "match_cost", "match_modes",
           "plane_mac", "relative_distance", "unwrap_frequency"]

#: Columns every modes table must have.
MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part")

#: Largest shape cost ``1 - MAC`` of a clear match: shapes sharing at least
#: half their (kinematic) norm -- a mode whose shape changed more than that in
#: one step has not been resolved by the step.  (The eigenvalue part is not
#: held to it: a flap mode at 18 /rev moves 0.25 /rev in a 0.01 c_f step of
#: the CG offset, half the range a Floquet frequency is known in, with its
#: shape unchanged, MAC 1.0 -- measured.)
CLEAR_COST = 0.5
#: Smallest lead of a clear match over every alternative.  0.25 is a MAC
#: difference of a quarter (or an eigenvalue distance of a quarter of the
#: scale): a lead that round-off or a smooth change over one step does not
#: overturn; two candidates closer than that are a coin toss and refined.
MARGIN = 0.25
#: Two roots of one point with a MAC above this ...
COALESCED_MAC = 0.9
#: ... and a :func:`relative_distance` below this are one coalesced pair.
COALESCED_DISTANCE = 0.05
#: Two Floquet roots are one locked pair (two real multipliers of one sign)
#: when their frequencies are equal and at a multiple of 1/2 per rev within
#: this [/rev].  A real multiplier's frequency is k/2 up to the round-off of
#: the lifted eigenvalues, worst for heavily damped roots: within 1.5e-6 of
#: k/2, the two of a pair within 1.3e-6 of each other (480 locked roots of
#: the paper's sweeps, measured); the complex roots nearest to a lock were
#: 1.7e-4 from k/2.  1e-5 lies between, with a factor of 7 and 17 to spare.
LOCK_TOL = 1e-5


def mac(phi_a, phi_b) -> np.ndarray:
    """Modal assurance criterion between the columns of two (complex) mode sets.

    ``MAC[i, j] = |phi_a[:, i]^H phi_b[:, j]|^2 / ((phi_a_i^H phi_a_i)(phi_b_j^H phi_b_j))``,
    which is 1 for parallel vectors (whatever their complex scaling) and 0
    for orthogonal ones.

    Parameters
    ----------
    phi_a : array_like, shape (n,) or (n, p)
        First set of mode shapes, one per column.
    phi_b : array_like, shape (n,) or (n, q)
        Second set.

    Returns
    -------
    ndarray, shape (p, q)
        (A 1-D input counts as one column.)

    Raises
    ------
    ValueError
        Different vector lengths, or a zero (or non-finite) vector.

    Examples
    --------
    >>> import numpy as np
    >>> a = np.array([[1, 0], [1j, 1], [0, 0]])
    >>> mac(a, a * (2 - 3j)).round(3)
    array([[1. , 0.5],
           [0.5, 1. ]])
    """
    a = np.asarray(phi_a)
    b = np.asarray(phi_b)
    a = a[:, None] if a.ndim == 1 else a
    b = b[:, None] if b.ndim == 1 else b
    if a.ndim != 2 or b.ndim != 2:
        raise ValueError(f"mode sets must be 1-D or 2-D, got shapes {a.shape} and {b.shape}")
    if a.shape[0] != b.shape[0]:
        raise ValueError(f"mode vectors differ in length: {a.shape[0]} and {b.shape[0]}")
    na = np.einsum("ij,ij->j", a.conj(), a).real
    nb = np.einsum("ij,ij->j", b.conj(), b).real
    for name, norms in (("phi_a", na), ("phi_b", nb)):
        bad = ~(np.isfinite(norms) & (norms > 0))
        if bad.any():
            raise ValueError(f"{name} column(s) {np.flatnonzero(bad).tolist()} are zero or "
                             "non-finite: MAC undefined")
    cross = a.conj().T @ b
    return np.abs(cross) ** 2 / np.outer(na, nb)


def eigen_distance(a, b, periodic: bool = False) -> np.ndarray:
    """Distances [1/rev] between eigenvalues ``a`` (p,) and ``b`` (q,), shape (p, q).

    ``periodic``: Floquet exponents, whose frequency is defined modulo
    1/rev and (for a real system, whose roots come in conjugate pairs) up to
    its sign; the distance is then the smallest over those.

    Parameters
    ----------
    a, b : array_like of complex
        Eigenvalues ``real_part + i frequency_per_rev`` [/rev], shapes (p,) and (q,).
    periodic : bool, optional
        Floquet exponents: the frequency is known modulo 1/rev and up to its sign.

    Returns
    -------
    numpy.ndarray
        Shape (p, q).

    Examples
    --------
    >>> float(eigen_distance([-0.1 + 2.9j], [-0.1 + 0.7j])[0, 0])
    2.2
    >>> round(float(eigen_distance([-0.1 + 2.9j], [-0.1 + 0.7j], periodic=True)[0, 0]), 12)
    0.2
    >>> float(eigen_distance([-0.1 + 2.9j], [-0.1 + 0.1j], periodic=True)[0, 0])  # conjugate
    0.0
    """
    a = np.atleast_1d(np.asarray(a, complex))
    b = np.atleast_1d(np.asarray(b, complex))
    return np.hypot(a.real[:, None] - b.real[None, :], _frequency_gap(a, b, periodic))


def _frequency_gap(a, b, periodic):
    """|frequency difference| (p, q), modulo 1/rev and sign when periodic."""
    d = np.abs(a.imag[:, None] - b.imag[None, :])
    if not periodic:
        return d

    def circ(x):
        return np.abs((x + 0.5) % 1.0 - 0.5)

    return np.minimum(circ(d), circ(a.imag[:, None] + b.imag[None, :]))


def relative_distance(a, b, periodic: bool = False) -> np.ndarray:
    """Eigenvalue distance of :func:`match_cost`: damping-rate and frequency gaps
    each relative to their size, combined (p, q).

    Parameters
    ----------
    a, b : array_like of complex
        Eigenvalues ``real_part + i frequency_per_rev`` [/rev], shapes (p,) and (q,).
    periodic : bool, optional
        Floquet exponents: the frequency is known modulo 1/rev and up to its sign.

    Returns
    -------
    numpy.ndarray
        Shape (p, q).

    Examples
    --------
    >>> round(float(relative_distance([-0.2 + 8j], [-0.9 + 14.2j], periodic=True)[0, 0]), 3)
    0.777
    """
    a = np.atleast_1d(np.asarray(a, complex))
    b = np.atleast_1d(np.asarray(b, complex))
    ds = np.abs(a.real[:, None] - b.real[None, :])
    ss = 0.5 + 0.5 * (np.abs(a.real)[:, None] + np.abs(b.real)[None, :])
    # a Floquet frequency is known modulo 1/rev: its gap lies in [0, 1/2]
    # whatever the frequencies, so it is measured against that range
    sw = 0.5 if periodic else 1.0 + 0.5 * (np.abs(a.imag)[:, None] + np.abs(b.imag)[None, :])
    return np.hypot(ds / ss, _frequency_gap(a, b, periodic) / sw)


def match_cost(pred, prev_vecs, eig, vecs, periodic: bool = False, *,
               shape_part: bool = False):
    """Assignment cost between tracks (rows) and the modes of a new point (columns).

    ``(1 - MAC)`` where both shapes are known and of one length (else 0) plus
    the :func:`relative_distance` of the eigenvalues, capped at 1.  With
    ``shape_part``, also the ``1 - MAC`` part alone (NaN where no shapes).

    Parameters
    ----------
    pred : array_like of complex, shape (p,)
        Eigenvalues expected for the tracks at the new point.
    prev_vecs : sequence of ndarray or None, length p
        The tracks' last shapes.
    eig : array_like of complex, shape (q,)
        Eigenvalues of the new point's modes [/rev].
    vecs : ndarray, shape (d, q), or None
        Their shapes.
    periodic : bool
        Floquet exponents (see :func:`eigen_distance`).
    shape_part : bool, optional
        Also return the ``1 - MAC`` part.

    Returns
    -------
    cost : numpy.ndarray
        Shape (p, q).
    shape : numpy.ndarray
        Only with ``shape_part``: the ``1 - MAC`` parts (NaN where unknown).
    """
    pred = np.asarray(pred, complex)
    eig = np.asarray(eig, complex)
    cost = np.minimum(1.0, relative_distance(pred, eig, periodic))
    shape = np.full(cost.shape, np.nan)
    if vecs is not None:
        for i, v in enumerate(prev_vecs):
            if v is not None and v.shape[0] == vecs.shape[0]:
                shape[i] = 1.0 - mac(v, vecs)[0]
                cost[i] += shape[i]
    return (cost, shape) if shape_part else cost


def is_clear(best: float, shape: float, alt: float) -> bool:
    """A match of total cost ``best`` (shape part ``shape``, NaN: unknown) with the
    best alternative at ``alt``: clear or not.

    Parameters
    ----------
    best : float
        Total cost of the match.
    shape : float
        Its ``1 - MAC`` part (NaN: shapes unknown, the total decides).
    alt : float
        Cost of the best alternative.

    Returns
    -------
    bool
        The match's own cost is at most :data:`CLEAR_COST` and it leads by at
        least :data:`MARGIN`.
    """
    own = best if np.isnan(shape) else shape
    return bool(own <= CLEAR_COST and alt - best >= MARGIN)


def decide(cost, rows, cols, shape=None):
    """Per assigned pair: clear (bool) and the best alternative's column.

    Parameters
    ----------
    cost : numpy.ndarray
        Assignment costs, tracks by modes (:func:`match_cost`).
    rows, cols : sequence of int
        The assigned pairs (:func:`scipy.optimize.linear_sum_assignment`).
    shape : numpy.ndarray, optional
        The ``1 - MAC`` parts of ``cost`` (NaN: shapes unknown).

    Returns
    -------
    clear : list of bool
        Per pair, whether the match is clear (:func:`is_clear`) against every
        alternative in its row and column.
    rival : list of int
        Per pair, the column of the next best mode for the track (-1: none).
    """
    shape = np.full(cost.shape, np.nan) if shape is None else shape
    rows, cols = np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)
    best = cost[rows, cols]
    other = np.array(cost, dtype=float)          # each pair's own entry out of the way
    other[rows, cols] = np.inf
    alt = np.minimum(other[rows].min(axis=1, initial=np.inf),
                     other[:, cols].min(axis=0, initial=np.inf))
    clear = [is_clear(b, s, a) for b, s, a in zip(best, shape[rows, cols], alt, strict=True)]
    if cost.shape[1] < 2:
        return clear, [-1] * rows.size
    # the first cheapest other column of the path's row
    return clear, np.argmin(other[rows], axis=1).tolist()


def is_coalesced(eig, vecs, j, k, periodic) -> bool:
    """Roots ``j`` and ``k`` of one point are one coalesced pair.

    Either (nearly) one shape and eigenvalue -- an exceptional point -- or,
    for Floquet exponents, the two real multipliers of one locked pair
    (:func:`is_locked`): their identities are two halves of one mode, which
    no finer step separates.

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The point's eigenvalues [/rev].
    vecs : numpy.ndarray or None
        Its mode shapes, one column per root.
    j, k : int
        The two roots.
    periodic : bool
        Floquet exponents.

    Returns
    -------
    bool
    """
    if k < 0:
        return False
    if is_locked(eig, j, k, periodic):
        return True
    if vecs is None:        # without shapes two near roots may as well be two modes
        return False
    d = relative_distance(eig[[j]], eig[[k]], periodic)[0, 0]
    return bool(mac(vecs[:, j], vecs[:, k])[0, 0] >= COALESCED_MAC and d <= COALESCED_DISTANCE)


def is_locked(eig, j, k, periodic) -> bool:
    """Floquet roots ``j`` and ``k`` of one point are the two real multipliers of
    one locked pair: equal frequencies at a multiple of 1/2 per rev (within
    :data:`LOCK_TOL`).

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The point's eigenvalues [/rev].
    j, k : int
        The two roots (distinct).
    periodic : bool
        Floquet exponents (a system with constant coefficients has no lock).

    Returns
    -------
    bool

    Examples
    --------
    >>> import numpy as np
    >>> eig = np.array([-4.062 + 7.0j, -4.065 + 7.0j, -4.059 + 7.0003j])
    >>> is_locked(eig, 0, 1, True), is_locked(eig, 0, 2, True), is_locked(eig, 0, 1, False)
    (True, False, False)
    """
    if not periodic or j == k or j < 0 or k < 0:
        return False
    f, g = eig[j].imag, eig[k].imag
    return bool(abs(f - g) <= LOCK_TOL and abs(2 * f - round(2 * f)) <= 2 * LOCK_TOL)


def locked_pairs(eig, periodic) -> list[tuple[int, int]]:
    """The locked pairs of one point (:func:`is_locked`), each ``(j, k)`` with ``j < k``.

    Only pairs: three or more roots at one frequency ``k/2`` (two locks at
    once) are left out, since which two are one mode is then not known.

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The point's eigenvalues [/rev].
    periodic : bool
        Floquet exponents.

    Returns
    -------
    list of tuple of int

    Examples
    --------
    >>> import numpy as np
    >>> locked_pairs(np.array([-0.4 + 1j, -3 + 2.2j, -0.5 + 1j]), True)
    [(0, 2)]
    """
    eig = np.asarray(eig, complex)
    groups: dict[int, list[int]] = {}
    for j in range(len(eig)):
        for g in groups.values():
            if is_locked(eig, g[0], j, periodic):
                g.append(j)
                break
        else:
            if periodic and abs(2 * eig[j].imag - round(2 * eig[j].imag)) <= 2 * LOCK_TOL:
                groups[j] = [j]
    return [(g[0], g[1]) for g in groups.values() if len(g) == 2]


def plane_mac(pair, phi) -> float:
    """MAC of a shape with a plane: the share of ``phi`` in the span of two shapes.

    ``|Q^H phi|^2 / |phi|^2`` with ``Q`` an orthonormal basis of the span
    of the columns of ``pair``: 1 when ``phi`` is a combination of them, 0
    when it is orthogonal to both.  Where a complex pair of Floquet roots
    locks into two real multipliers, its shape (a complex vector ``a + ib``)
    is such a combination of the two real shapes, whatever their share of
    each.

    Parameters
    ----------
    pair : array_like, shape (n, 2)
        The two shapes spanning the plane (linearly independent).
    phi : array_like, shape (n,)
        The shape compared.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Lengths differ, or a zero or non-finite vector.

    Examples
    --------
    >>> import numpy as np
    >>> pair = np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]])
    >>> round(plane_mac(pair, np.array([1.0, 1j, 0.0])), 12), plane_mac(pair, np.array([0, 1, 1.0]))
    (1.0, 0.5)
    """
    pair = np.asarray(pair, complex)
    phi = np.asarray(phi, complex)
    if pair.ndim != 2 or pair.shape[1] != 2 or phi.shape != (pair.shape[0],):
        raise ValueError(f"plane_mac needs shapes (n, 2) and (n,), got {pair.shape} and "
                         f"{phi.shape}")
    norm = float(np.vdot(phi, phi).real)
    if not (np.isfinite(pair).all() and np.isfinite(norm) and norm > 0):
        raise ValueError("plane_mac: zero or non-finite shape")
    size = np.linalg.norm(pair, axis=0)
    if not (size > 0).all():
        raise ValueError("plane_mac: zero shape in the pair")
    # orthonormal basis of the span; a pair parallel to round-off (the double
    # root where a lock begins) spans only its line
    u, sv, _ = np.linalg.svd(pair / size, full_matrices=False)
    q = u[:, sv > 1e-8 * sv[0]]
    return float(min(1.0, np.linalg.norm(q.conj().T @ phi) ** 2 / norm))


def match_modes(prev, curr, *, predicted=None, periodic: bool | None = None) -> np.ndarray:
    """Which mode of `curr` continues each mode of `prev`.

    Parameters
    ----------
    prev, curr
        Points: a result object with ``modes`` (DataFrame) and ``vectors``
        (or ``eigenvectors``) attributes, a ``(modes, vectors)`` tuple, a
        mapping with those keys, or a bare modes DataFrame (no vectors).
    predicted : array_like of complex, optional
        Eigenvalues of `prev` extrapolated to `curr` (default: as in `prev`).
    periodic : bool, optional
        Floquet exponents (default: either point says so).

    Returns
    -------
    ndarray of int, one per row of ``prev.modes``
        Row index in ``curr.modes``, or -1 when `curr` has fewer modes and
        this one is left unmatched.
    """
    pm, pv, pp = as_point(prev)
    cm, cv, cp = as_point(curr)
    periodic = (pp or cp) if periodic is None else periodic
    pred = eigenvalues(pm) if predicted is None else np.asarray(predicted, complex)
    vecs_prev = [None if pv is None else pv[:, i] for i in range(len(pm))]
    cost = match_cost(pred, vecs_prev, eigenvalues(cm), cv, periodic)
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, cols = linear_sum_assignment(cost)
    out = np.full(len(pm), -1)
    out[rows] = cols
    return out


def eigenvalues(modes: pd.DataFrame) -> np.ndarray:
    """Eigenvalues ``real_part + i frequency_per_rev`` of a modes table (/rev).

    Parameters
    ----------
    modes : pandas.DataFrame
        With columns ``real_part`` and ``frequency_per_rev``.

    Returns
    -------
    numpy.ndarray of complex
    """
    return modes["real_part"].to_numpy(float) + 1j * modes["frequency_per_rev"].to_numpy(float)


def as_point(p):
    """Normalise one point of a sweep to ``(modes, vectors, periodic)``.

    Parameters
    ----------
    p : pandas.DataFrame, mapping, tuple or object
        A modes table; a mapping with ``modes`` and optionally ``vectors``
        (or ``eigenvectors``) and ``periodic``; a tuple ``(modes, vectors[,
        periodic])``; or an object with those attributes (a stability
        result).

    Returns
    -------
    modes : pandas.DataFrame
        Index reset; it has the columns of :data:`MODE_COLUMNS`.
    vectors : numpy.ndarray or None
        One column per mode.
    periodic : bool
        Floquet exponents (frequencies known modulo 1/rev).

    Raises
    ------
    TypeError
        For anything else.
    ValueError
        For missing columns or vectors that do not match the modes.
    """
    import pandas as pd

    periodic = False
    if isinstance(p, pd.DataFrame):
        modes, vecs = p, None
    elif isinstance(p, Mapping):
        modes = p["modes"]
        vecs = p.get("vectors", p.get("eigenvectors"))
        periodic = bool(p.get("periodic", False))
    elif isinstance(p, tuple) and len(p) in (2, 3):
        modes, vecs = p[0], p[1]
        periodic = bool(p[2]) if len(p) == 3 else False
    elif hasattr(p, "modes"):
        modes = p.modes
        vecs = getattr(p, "vectors", None)
        if vecs is None:
            vecs = getattr(p, "eigenvectors", None)
        periodic = bool(getattr(p, "periodic", False))
    else:
        raise TypeError(f"cannot read modes from {type(p).__name__}")
    missing = [c for c in MODE_COLUMNS if c not in modes.columns]
    if missing:
        raise ValueError(f"modes table lacks column(s) {missing}")
    modes = modes.reset_index(drop=True)
    if vecs is not None:
        vecs = np.asarray(vecs)
        if vecs.ndim != 2 or vecs.shape[1] != len(modes):
            raise ValueError(f"vectors of shape {vecs.shape} do not match "
                             f"{len(modes)} modes (one column per mode)")
    return modes, vecs, periodic


def unwrap_frequency(eig, predicted, periodic: bool):
    """The frequency of a root, in the representation nearest a predicted one.

    A Floquet exponent's frequency is known modulo 1/rev and up to its sign
    (the conjugate root is the same mode): of ``f + k`` and ``-f + k`` the one
    nearest the predicted frequency.  At a lock (the prediction at a multiple
    of 1/2) the two are mirror images about it: the solver's sign is kept, not
    whichever the round-off of the locked frequency favours.  A root of
    constant coefficients has one frequency.

    Parameters
    ----------
    eig : complex or numpy.ndarray of complex
        The root, ``real_part + i frequency_per_rev`` [/rev], or roots.
    predicted : complex or numpy.ndarray of complex
        The root expected (its imaginary part: the frequency expected), one
        per root.
    periodic : bool
        Floquet exponent.

    Returns
    -------
    float or numpy.ndarray
        The frequency [/rev] (an array for arrays of roots).

    Examples
    --------
    A frequency falling from 21.77 /rev, seen by the Floquet convention as 0.32
    mirrored (-20.68 mod 1 = 0.32 ... or 0.68): continuity picks 20.68.

    >>> unwrap_frequency(-0.5 + 0.32j, -0.5 + 20.7j, True)
    20.68
    """
    f, p = np.imag(eig), np.imag(predicted)
    if periodic:
        up, down = f + np.round(p - f), -f + np.round(p + f)
        at_lock = np.abs(2 * p - np.round(2 * p)) <= 2 * LOCK_TOL
        f = np.where(at_lock | (np.abs(up - p) <= np.abs(down - p)), up, down)
    return float(f) if np.ndim(f) == 0 else np.asarray(f, float)


def continuous_frequency(x, f, *, span: int = 3, weight: float = 1.0,
                         reach: int = 2, anchor: float = 0.25, carried=None) -> np.ndarray:
    """Floquet frequencies along a curve, in the representation that makes it smoothest.

    Each point's frequency ``f`` is known modulo 1/rev and up to its sign (the
    Floquet convention writes the dominant harmonic of the mode's motion).
    The candidates at a point are its representations ``+-f + k`` within
    `span` /rev of the conventions of the points up to `reach` places on
    either side.  Each candidate is the point's own convention rewritten by
    one *offset* (the sign and the shift ``k``).  A root's frequency is
    continuous along the curve, and the convention jumps by whole /rev (two
    harmonics of nearly equal power) or to the mirror image, so what is
    priced is a change of offset between neighbours, not each point written
    otherwise: the choice at every point that minimises the curve's squared
    change of slope, plus `weight` for each change of offset between two
    neighbours, plus `anchor` for each point not in its own convention (which
    ties the curve to the convention most of its points carry), is found by
    dynamic programming over the whole curve (the change of slope measured
    over the longer of its two steps, so that a whole-/rev jump on the longer
    step costs as much on a grid refined unevenly).  So a stretch of points
    written 1/rev off or as the mirror image (``k - f``) is put back where its
    neighbours say, up to ``(4 - 2 weight) / anchor`` points (8 on an even
    grid).  A convention that changes for good with longer sides, whose points
    the anchor would keep, is joined after
    (:func:`_stitched`: a step a whole number of /rev off the slope of its
    resolved neighbours moves the rest of the curve), and the joined curve is
    written by the whole offset in which most of the parameter range keeps its
    own or its carried convention (:func:`_anchored`).  No step is left a
    whole /rev off resolved neighbours (measured on random resolved curves and
    on the reproduction, docs/theory.md 9.4); the same points give the same
    curve whatever order they came in.

    Parameters
    ----------
    x : array_like
        The parameter at the points (any order; ties keep their order).
    f : array_like
        Their frequencies by the Floquet convention [/rev] (NaN: skipped).
    span : int, optional
        How far from a neighbour's convention a candidate may lie [/rev].
    weight : float, optional
        Cost of a change of offset between two neighbouring points, against
        the squared change of slope (in /rev, the slope per local step).  A
        jump of ``J`` /rev in and out of a stretch costs about ``2 J**2`` at each
        end (4 for a 1/rev stretch): with 1, a stretch 1/rev off is put back
        (cost 2 plus its anchors), and a point a few tenths from a smooth line
        through its neighbours -- a sparse sweep of a curving frequency, or a
        root near a lock whose mirror image lies close -- is kept, the offsets
        changing twice for less than 2 of smoothness.  (Measured on Fig. 14,
        flap length 0.165-0.19 R, mu 0.3: the TEF's convention 1/rev up at
        three points running; with a cost of 2 for *each point* written
        otherwise, the earlier rule, the three were kept and the tracked
        frequency jumped +0.77 and -1.11 /rev.)
    reach : int, optional
        Neighbours on each side whose conventions place the candidates.
    anchor : float, optional
        Cost of each point written otherwise than by its own convention.  A
        whole curve rewritten by one offset changes no slope; this is what
        keeps it in the convention its points carry.  Measured on the
        reproduction's 4079 named rows in forward flight, before the jumps it
        keeps are joined (:func:`continuous_frequency`): with 0.25, 0.1 and
        0.05, 26, 16 and 12 isolated steps of a name along one track stayed a
        whole /rev off its neighbours' (49 with the earlier rule), and 8.5, 12.5
        and 16 % of the rows were written otherwise than by their dominant
        harmonic.  0.1 and 0.05 also shifted the tail of this function's
        example (a curve falling 1.3 /rev a step, a mirrored stretch and a
        shifted point in 8 points) and the whole of Fig. 9's overhang-0.1 TEF
        curve by 1/rev: a weaker anchor lets the offsets wander; 0.25 is kept.
        (Measured on Fig. 9 at overhang 0.1, 11 points: with a cost per /rev
        of departure instead, 0.1 drifted the whole curve by up to 1.35 /rev
        to straighten it.)
    carried : array_like, optional
        Per point, its frequency as continuation in the coupling carried it
        from the uncoupled root (``frequency_continued``; NaN: none).  A
        second representation the point may take without the anchor's cost
        (preferred to its own where the two make equally smooth curves):
        where the dominant harmonic changes for good, continuation says which
        way the curve goes (measured on Fig. 14's TEF at 0.1275 R: own 9.547,
        carried 10.547, continuous with 10.677 at 0.125); it is not imposed,
        since a path that passed near a lock may carry the mirror image
        (measured on Fig. 9 at overhang 0.1, c_cg 0.28: 12.09, the mirror
        of the 17.97 continuity gives).

    Returns
    -------
    numpy.ndarray
        The continuous frequencies, in the order of `x`.

    Examples
    --------
    A frequency falling 1.3 /rev per step from 21.77, written by the convention
    as the mirrored alias at two points and one 1/rev off at another:

    >>> true = 21.77 - 1.3 * np.arange(8)
    >>> seen = true.copy()
    >>> seen[[3, 4]] = 43.0 - seen[[3, 4]]     # -f + 43: the mirror
    >>> seen[6] += 1.0
    >>> bool(np.allclose(continuous_frequency(np.arange(8.0), seen), true))
    True
    """
    x = np.asarray(x, float)
    f = np.asarray(f, float)
    carried = np.full(f.shape, np.nan) if carried is None else np.asarray(carried, float)
    out = f.copy()
    good = np.flatnonzero(np.isfinite(f) & np.isfinite(x))
    if good.size < 3:
        return out
    idx = good[np.argsort(x[good], kind="stable")]
    xs, fs, cs = x[idx], f[idx], carried[idx]
    cand = _candidates(fs, span, reach, cs)
    # a representation other than the point's own convention (or the one
    # continuation carried) costs `anchor`, whatever its distance (all are the
    # same root); a change of offset between neighbours costs `weight`
    own = np.abs(cand - fs[:, None]) <= 1e-9
    kept = np.abs(cand - cs[:, None]) <= 1e-9
    # where the two make equally smooth curves, the carried one (the root
    # followed from where it comes from) is kept, not whichever the round-off
    # of the slopes favours: the own convention costs a thousandth of the
    # anchor where another was carried (measured: Fig. 13's blade flap 5 at
    # 0.756-0.761 R, own 8.70 and carried 10.70 throughout, uncoupled 10.71,
    # flipped between them with the change of the slopes' scale below)
    dev = np.where(np.isfinite(cand), np.where(kept, 0.0, np.where(
        own, np.where(np.isfinite(cs), 1e-3 * anchor, 0.0)[:, None], anchor)), np.inf)
    plus, minus = _offsets(cand, fs)
    # a point at a lock (frequency at k/2: both a shift and a mirror of itself)
    at_lock = np.isfinite(plus[:, 0]) & np.isfinite(minus[:, 0])
    cost = dev[0][:, None] + dev[1][None, :] + weight * _changes(plus, minus, at_lock, 0)
    # a second point at one parameter value has no step to be smooth over: the
    # curve is found on the first of each, and each other takes the
    # representation nearest it
    first = np.concatenate([[True], np.diff(xs) > 0])
    if not first.all():
        keep = idx[first]
        out[keep] = continuous_frequency(x[keep], f[keep], span=span, reach=reach,
                                         weight=weight, anchor=anchor, carried=carried[keep])
        at = np.searchsorted(x[keep], xs, side="right") - 1
        for i in np.flatnonzero(~first):
            # any shift: the joined curve may lie further from the conventions
            # than the candidates reach (measured: a twin 1/rev off its pair)
            out[idx[i]] = round(unwrap_frequency(1j * fs[i], 1j * out[keep[at[i]]], True), 9)
        return out
    back = []
    for i in range(2, len(xs)):
        h0, h1 = max(xs[i - 1] - xs[i - 2], 1e-300), max(xs[i] - xs[i - 1], 1e-300)
        s0 = (cand[i - 1][None, :] - cand[i - 2][:, None]) / h0          # (z, a)
        s1 = (cand[i][None, :] - cand[i - 1][:, None]) / h1              # (a, b)
        # the change of slope over the longer of the two steps: a whole-/rev
        # jump on the longer step costs J**2 here whatever the spacing, on the
        # shorter more (J**2 (h_long / h_short)**2); over their mean, a jump on
        # a 0.02 step between 0.005 steps cost a quarter of J**2 (measured on
        # Fig. 9's refined sweep: the TEF written 1/rev off at 0.08-0.10)
        curv = ((s1[None, :, :] - s0[:, :, None]) * max(h0, h1)) ** 2
        total = np.where(np.isfinite(curv), cost[:, :, None] + curv, np.inf)
        arg = np.argmin(total, axis=0)                                   # (a, b) -> z
        cost = (np.take_along_axis(total, arg[None], axis=0)[0] + dev[i][None, :]
                + weight * _changes(plus, minus, at_lock, i - 1))
        back.append(arg)
    a, b = np.unravel_index(int(np.argmin(cost)), cost.shape)
    choice = [b, a]
    for arg in reversed(back):
        choice.append(int(arg[choice[-1], choice[-2]]))
    choice = choice[::-1]
    curve = cand[np.arange(len(xs)), choice]
    out[idx] = _anchored(xs, _stitched(xs, curve, fs, at_lock), fs, cs)
    return out


def _stitched(xs, curve, fs, at_lock):
    """`curve` without its whole-/rev jumps (the same object when it has none).

    Step by step from the first: where a step departs from the slope of its
    resolved neighbours (steps under 1/2 /rev: the one before, as already
    joined, and the one after) by a whole number ``J`` of /rev, the rest of the
    curve is moved by ``-J``.  With both neighbours resolved they must agree
    within 1/4 over the step, predict under 1/2 /rev for it, and the departure
    must be within 1/4 of ``J``; at the first or last step, with its one
    neighbour, the step it predicts must be under 0.3 and the departure within
    0.15 of ``J``; a step next to one that is not resolved is left.  A jump
    the dynamic programming spread over two or three steps, writing the points
    between them otherwise than both ends (a mirror image ``k - f``, or another
    shift), is joined the same way over the span, those points rewritten by the
    representation of their own frequency (``+-f + k``) nearest the straight
    line through the ends, each within 1/4 of it; a span whose points between
    are written as an end is, is a rapid change, left as it is.  Steps next to
    a lock are left (at ``k/2`` the shifts of a root are its mirror images).
    """
    out, moved = curve.copy(), False
    h = np.diff(xs)
    n = len(xs)
    for i in range(n - 1):
        span = _jump(out, h, i, 1, at_lock)
        if span is not None:
            out[i + 1:] -= span
            moved = True
            continue
        for width in (2, 3):
            if i + width >= n or not _bridging(out, fs, i, width):
                continue
            span = _jump(out, h, i, width, at_lock)
            if span is None:
                continue
            end = out[i + width] - span
            frac = np.cumsum(h[i:i + width - 1]) / np.sum(h[i:i + width])
            line = out[i] + (end - out[i]) * frac
            best = unwrap_frequency(1j * fs[i + 1:i + width], 1j * line, True)
            if np.all(np.abs(best - line) <= 0.25):
                out[i + 1:i + width] = best
                out[i + width:] -= span
                moved = True
                break
    return out if moved else curve


def _bridging(out, fs, i, width) -> bool:
    """Whether every point strictly inside the span ``i .. i + width`` is written
    with another offset (:func:`_offsets`: shift or mirror image) than both ends."""
    plus, minus = (v[:, 0] for v in _offsets(out[i:i + width + 1, None], fs[i:i + width + 1]))

    def same(a, b):
        return plus[a] == plus[b] or minus[a] == minus[b]

    return not any(same(j, 0) or same(j, width) for j in range(1, width))


def _jump(out, h, i, width, at_lock):
    """The whole number of /rev the `width` steps from point `i` depart from their
    resolved neighbours' slope (None: none, or not decided; see :func:`_stitched`);
    over a span of two or three a departure of 0 counts (points between written
    as mirror images of a continuous curve)."""
    n = len(out)
    if at_lock[max(i - 1, 0):i + width + 2].any():
        return None
    near = [j for j in (i - 1, i + width) if 0 <= j < n - 1]
    sides = [(out[j + 1] - out[j]) / h[j] for j in near if abs(out[j + 1] - out[j]) < 0.5]
    if not sides or len(sides) < len(near):
        # a neighbour that is itself not resolved leaves the span undecided
        # (measured: notebook 10's six-point unsteady Fig. 9, blade flap 5 falling
        # 0.93 /rev a step then 0.08, was moved 1/rev at the bend)
        return None
    length = float(np.sum(h[i:i + width]))
    pred = float(np.mean(sides)) * length
    r = out[i + width] - out[i] - pred
    if len(sides) == 2:
        ok = abs(pred) < 0.5 and np.ptp(sides) * length < 0.25 and abs(r - round(r)) <= 0.25
    else:
        ok = abs(pred) < 0.3 and abs(r - round(r)) <= 0.15
    if not ok or (width == 1 and round(r) == 0):
        return None
    if width > 1 and all(abs(out[j + 1] - out[j] - pred * h[j] / length) < 0.25
                         for j in range(i, i + width)):
        return None                 # resolved steps: nothing to join
    return int(round(r))


def _anchored(xs, curve, fs, cs):
    """The continuous `curve` moved by the whole number of /rev that writes it best.

    A constant offset changes no slope.  The dynamic programming's anchor ties
    its curve to the conventions point by point; once a curve is joined (by
    :func:`_stitched`, or by the programme itself across a convention changed
    for good) that can leave the curve in the convention of a minority of the
    range -- of refined points clustered near an exceptional point.  So the
    curve is moved to the offset in which the points of most of the parameter
    range (each weighing its half-steps) are written by their own convention or
    the carried one (`cs`) when that leaves a quarter of the range or more
    fewer points otherwise written than the programme's offset; else (ties, or
    a sparse curve whose steps do not decide it: measured on notebook 10's
    six-point unsteady Fig. 9, where blade flap 5 moved 4 /rev above its
    uncoupled 10.7 /rev for 10 % of the range) `curve` is kept.
    """
    w = np.diff(np.concatenate([[xs[0]], 0.5 * (xs[1:] + xs[:-1]), [xs[-1]]]))
    shifts = np.unique(np.round(np.concatenate([fs - curve, cs - curve])))

    def missed(k):
        kept = np.abs(curve + k - cs) <= 1e-6
        hit = kept | (np.abs(curve + k - fs) <= 1e-6)
        # as in the dynamic programming: own a thousandth short of the carried one
        return float(np.sum(w[~hit]) + 1e-3 * np.sum(w[hit & ~kept & np.isfinite(cs)]))

    costs = {float(k): missed(k) for k in shifts[np.isfinite(shifts) & (shifts != 0.0)]}
    best = min(costs, key=costs.get, default=0.0)
    if best and costs[best] <= missed(0.0) - 0.25 * w.sum():
        return np.round(curve + best, 9)
    return curve


def _offsets(cand, fs):
    """Per candidate, the shift ``k`` that writes it as ``f + k`` and the one that
    writes it as ``-f + k`` (NaN where it is not such): its offset from the
    point's own convention ``f`` (at ``k/2`` a candidate is both)."""
    with np.errstate(invalid="ignore"):
        up, down = cand - fs[:, None], cand + fs[:, None]
        plus = np.where(np.abs(up - np.round(up)) <= 1e-6, np.round(up), np.nan)
        minus = np.where(np.abs(down - np.round(down)) <= 1e-6, np.round(down), np.nan)
    return plus, minus


def _changes(plus, minus, at_lock, i):
    """``(a, b)``: 1 where candidate ``a`` at point ``i`` and ``b`` at ``i + 1`` are
    written with different offsets (:func:`_offsets`), else 0.

    A point at a lock (its frequency at ``k/2``: two real multipliers) has no
    offset -- its mirror image and its shifts are the same numbers -- so no
    change is priced next to it.  (Measured on Fig. 12, mu 0.3: the locked
    TEF at 55-69 N m/rad, conventions 4.0-5.5 /rev, was otherwise written
    6.5-7.0 /rev, one mirror image ``11 - f`` being shared by most of its
    points, and fell 2 /rev where it unlocked at 72.5.)  ``at_lock``: per point,
    whether it is at a lock (its candidates both shifts and mirrors)."""
    same = ((plus[i][:, None] == plus[i + 1][None, :])
            | (minus[i][:, None] == minus[i + 1][None, :]))
    return np.where(same | at_lock[i] | at_lock[i + 1], 0.0, 1.0)


def _candidates(fs, span, reach, carried=None):
    """Per point, its representations +-f + k near its neighbours' conventions, and
    the one continuation carried if any (NaN-padded).

    A representation ``c = +-f + k`` is a candidate when it lies within
    ``span`` (+1e-9) of one of the conventions up to ``reach`` points away;
    the shifts ``k`` are searched for all points at once over the range
    that covers every neighbour (the same set as neighbour by neighbour),
    each candidate rounded to 1e-9 by Python's ``round`` (its value is
    written to the table).
    """
    fs = np.asarray(fs, float)
    n = fs.size
    # refs[i]: the conventions up to `reach` places from point i (NaN-padded)
    pos = np.arange(n)[:, None] + np.arange(-reach, reach + 1)[None, :]
    refs = np.where((pos >= 0) & (pos < n), fs[np.clip(pos, 0, n - 1)], np.nan)
    lo, hi = np.nanmin(refs, axis=1), np.nanmax(refs, axis=1)
    base = np.stack([fs, -fs], axis=1)                                   # (n, 2)
    k0 = np.floor(lo[:, None] - span - base)
    width = int(np.max(np.ceil(hi[:, None] + span - base) - k0)) + 1
    c = base[:, :, None] + (k0[:, :, None] + np.arange(width))           # (n, 2, w)
    k_end = np.ceil(hi[:, None] + span - base)[:, :, None]
    with np.errstate(invalid="ignore"):
        near = (np.abs(c[..., None] - refs[:, None, None, :]) <= span + 1e-9).any(axis=-1)
    near &= (k0[:, :, None] + np.arange(width)) <= k_end
    rows = []
    for i in range(n):
        vals = {round(v, 9) for v in c[i][near[i]].tolist()}
        if carried is not None and np.isfinite(carried[i]):
            vals.add(round(float(carried[i]), 9))
        rows.append(sorted(vals))
    width = max(len(r) for r in rows)
    return np.array([r + [np.nan] * (width - len(r)) for r in rows])
