"""The march of continuation: every root's path along ``eps``, one step at a time.

:class:`March` holds the paths of all roots of a system along the coupling
``eps`` (:mod:`tefcore.modes.continuation`): their origins, last roots and
shapes, the meetings of two paths (exceptional points) and the frequency
locks they passed.  Each step assigns the roots of the new ``eps`` to the
paths (:meth:`March.step`): eigenvalues against each path's linear
prediction (Floquet frequencies in the representation the path carries,
unwrapped), periodic parts of the motions against each path's, the
assignment of least total cost, and whether it is decided (the regret of
every match, :func:`regrets`).

Private: the public names are those of :mod:`tefcore.modes.continuation`.
"""

from __future__ import annotations

import numpy as np

from .matching import (
    CLEAR_COST,
    COALESCED_DISTANCE,
    COALESCED_MAC,
    LOCK_TOL,
    MARGIN,
    mac,
    relative_distance,
)
from .names import base_name, is_locked, locked_name, pair_text

__all__ = ["FLAP_ACTIVE", "March", "compact_basis", "exchanges", "flap_share",
           "lock_matrix", "regrets", "same_lock"]


#: Least share of a root's kinematic motion (squared) in the flap's trailing edge
#: (the last row of :meth:`tefcore.model.coupled.CoupledModel.tracking_basis`) for
#: the root to take part in the blade-flap coupling.  Measured on MDART: the blade's
#: low modes carry 1e-8 to 1e-2 (torsion 1 at c_cg 0.33, mu 0.3: 2e-2 at full
#: coupling, 1e-4 at half), the roots the flap moves 5e-2 to 1.
FLAP_ACTIVE = 1e-2


def compact_basis(basis):
    """A tracking basis with fewer rows that compares shapes exactly as `basis` does.

    The march compares shapes only through inner products of their physical
    rows (MAC, norms) and the flap's share (the last row, :func:`flap_share`).
    ``[R; b]``, with ``R`` the triangular factor of the QR decomposition of
    all rows but the last and ``b`` the last row, has the same Gram matrix
    ``B^T B`` and the same last row: every MAC, norm and flap share is the
    same to round-off, on ``n + 1`` rows instead of one per station and
    degree of freedom (MDART: 11 instead of 37, so the shapes a path step
    stores and compares are 3.4 times shorter).

    Parameters
    ----------
    basis : numpy.ndarray
        Map from coordinates to physical shapes, shape ``(n_phys, n)``, its
        last row the flap's trailing-edge motion.

    Returns
    -------
    numpy.ndarray
        ``(n + 1, n)`` when that is fewer rows, else `basis` itself.

    Examples
    --------
    >>> import numpy as np
    >>> b = np.arange(12.0).reshape(6, 2) ** 0.5
    >>> c = compact_basis(b)
    >>> c.shape, bool(np.allclose(c.T @ c, b.T @ b)), bool(np.all(c[-1] == b[-1]))
    ((3, 2), True, True)
    """
    basis = np.asarray(basis)
    if basis.shape[0] <= basis.shape[1] + 1:
        return basis
    r = np.linalg.qr(basis[:-1], mode="r")
    return np.vstack([r, basis[-1:]])


def flap_share(vecs, n_phys):
    """Each root's kinematic share in the flap (the basis' last row) over its shape's blocks.

    Parameters
    ----------
    vecs : numpy.ndarray
        Shapes through the tracking basis, one column per root, stacked in
        blocks of `n_phys` rows (azimuths, or displacement and velocity).
    n_phys : int
        Rows of the basis; the last is the flap's trailing-edge motion.

    Returns
    -------
    numpy.ndarray
        Per root, ``sum |flap row|^2 / sum |all rows|^2``.
    """
    return _share_and_norm(vecs, n_phys)[0]


def _share_and_norm(vecs, n_phys):
    """:func:`flap_share` and each column's ``sum |.|^2``, from one pass over the shapes."""
    blocks = _modulus2(vecs.reshape(-1, n_phys, vecs.shape[-1]))
    total = np.sum(blocks, axis=(0, 1))
    return np.sum(blocks[:, -1], axis=0) / np.maximum(total, np.finfo(float).tiny), total


def _modulus2(z):
    """``|z|^2`` elementwise as ``re^2 + im^2`` (``np.abs(z) ** 2`` takes a hypot
    per element first: 0.16 against 0.04 ms for a path's 2664 x 11 shapes,
    measured; the two agree to 3e-15 relative)."""
    if not np.iscomplexobj(z):
        return z * z
    return z.real * z.real + z.imag * z.imag


#: An eigenvalue match is clear by distance alone when the predicted root is at
#: most this fraction of the way to the next nearest (and the root nearest to no
#: other path by the same ratio): the linear predictor's error would have to be
#: three times the distance it is trusted for to swap them.
NEAR_RATIO = 1.0 / 3.0

#: Cost of a path that ends or a root that appears without a lock to explain it:
#: above any match (a match costs at most 2), so the assignment drops or adds a
#: root only at a lock.
_UNEXPLAINED = 5.0


def _fold(eig) -> np.ndarray:
    """Floquet frequencies folded into [0, 1/2] (modulo 1/rev and sign)."""
    f = np.abs(np.asarray(eig, complex).imag) % 1.0
    return np.minimum(f, 1.0 - f)


def _at_half(fold) -> np.ndarray:
    """Which folded frequencies (:func:`_fold`) sit at a multiple of 1/2 /rev: within
    ten times :data:`tefcore.modes.matching.LOCK_TOL`, where a locked pair's two
    real roots sit to round-off."""
    return np.minimum(fold, 0.5 - fold) <= 10 * LOCK_TOL


def same_lock(eig, j, k) -> bool:
    """Whether Floquet roots ``j`` and ``k`` are the two real roots of one lock.

    One frequency folded into ``[0, 1/2]`` (modulo 1/rev and sign), at ``k/2``:
    a pair of real multipliers on the negative axis may carry 3.5 and 4.5 /rev
    by their dominant harmonics (:func:`tefcore.modes.matching.is_locked`
    compares the frequencies as they are).

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The roots [/rev].
    j, k : int
        Two of them.

    Returns
    -------
    bool

    Examples
    --------
    >>> import numpy as np
    >>> same_lock(np.array([-6.2 + 3.5j, -5.4 + 4.5j, -0.5 + 4.4j]), 0, 1)
    True
    """
    return j != k and bool(lock_matrix(np.asarray(eig, complex)[[j, k]])[0, 1])


def lock_matrix(eig) -> np.ndarray:
    """:func:`same_lock` of every two roots at once: ``(m, m)``, False on the diagonal.

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The roots [/rev].

    Returns
    -------
    numpy.ndarray of bool

    Examples
    --------
    >>> import numpy as np
    >>> lock_matrix(np.array([-6.2 + 3.5j, -5.4 + 4.5j, -0.5 + 4.4j])).astype(int)
    array([[0, 1, 0],
           [1, 0, 0],
           [0, 0, 0]])
    """
    fold = _fold(eig)
    out = _at_half(fold)[:, None] & (np.abs(fold[:, None] - fold[None, :]) <= 10 * LOCK_TOL)
    np.fill_diagonal(out, False)
    return out


def _near_lock(eig, periodic) -> np.ndarray:
    """Which roots are one of a locked pair: at a multiple of 1/2 /rev, with another
    root at the same frequency (both within :data:`tefcore.modes.matching.LOCK_TOL`
    ten times over; Floquet only).

    Only such a pair can merge into one complex root (a path ends) or split
    from one (a root appears).
    """
    eig = np.asarray(eig, complex)
    if not periodic:
        return np.zeros(eig.size, bool)
    return lock_matrix(eig).any(axis=1)


def _padded(cost, path_lock, root_lock):
    """The square cost matrix of the assignment: where the counts differ (a pair
    entering or leaving a lock at ``k/2``), a path near a lock ends for free and
    only a root near one appears for free (:data:`_UNEXPLAINED` otherwise)."""
    p, r = cost.shape
    n = max(p, r)
    full = np.zeros((n, n))
    full[:p, :r] = cost
    if r < p:
        full[:p, r:] = np.where(path_lock, 0.0, _UNEXPLAINED)[:, None]
    elif p < r:
        full[p:, :r] = np.where(root_lock, 0.0, _UNEXPLAINED)[None, :]
    return full


def _assign(full, p, r):
    """Least-cost assignment of the padded matrix `full` (:func:`_padded`): the
    permutation of all its rows, and the pairs of the `p` paths and `r` roots."""
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, perm = linear_sum_assignment(full)
    keep = (rows < p) & (perm < r)
    return perm, rows[keep], perm[keep]


def regrets(full, perm, rows):
    """Per assigned path: how much dearer the best assignment without its match is.

    The match of a path is decided by the whole step, not by its row and
    column alone: a veering pair whose two matches are each near their rivals
    (costs 0.07 and 0.28 against 0.10 and 0.40, measured on Fig. 9's c_cg
    0.12 at eps 0.53) can still have a swap that costs 0.5 more.  The least
    assignment in which path ``i`` leaves its root differs from the optimum
    ``perm`` by one cycle of paths each taking the next one's root (other
    cycles only add cost: the optimum has no cheaper one), so the regret is
    the cheapest cycle through ``i`` in the graph of exchanges ``i -> j``
    (``i`` takes ``j``'s root, at ``full[i, perm[j]] - full[i, perm[i]]``),
    by Floyd-Warshall: exact, and no solver (scipy.optimize stays unimported).

    Parameters
    ----------
    full : numpy.ndarray
        The padded square cost matrix (:func:`_padded`).
    perm : numpy.ndarray
        Its optimal assignment, the column of each row.
    rows : sequence of int
        The paths asked about.

    Returns
    -------
    numpy.ndarray
        One regret per row asked (inf where the path has no other root).

    Examples
    --------
    Two paths and two roots, a swap dearer by 0.5:

    >>> import numpy as np
    >>> regrets(np.array([[0.1, 0.4], [0.3, 0.1]]), np.array([0, 1]), [0, 1]).round(6)
    array([0.5, 0.5])
    """
    return exchanges(full, perm, rows)[0]


def exchanges(full, perm, rows):
    """Per assigned path: its regret (:func:`regrets`) and the root it would take instead.

    The rival of a match is the root the path takes in the cheapest
    assignment without it -- the other end of the exchange the regret
    prices -- not the next cheapest entry of its row: two paths that swap
    roots at a veering are each other's rivals even where a third root,
    alone, is nearer one of them in cost (measured on Fig. 14's flap length
    0.0775 R at mu 0.3: the TEF path's row had a flap-free root next, while
    its exchange was with blade torsion 2's root).

    Parameters
    ----------
    full, perm, rows
        As :func:`regrets`.

    Returns
    -------
    regret : numpy.ndarray
        One per row asked (inf where the path has no other root).
    rival : numpy.ndarray of int
        The column the path takes in that assignment (-1: none, or a padded
        column -- the path ending at a lock).

    Examples
    --------
    Three paths; path 0's cheapest exchange is with path 2's root:

    >>> import numpy as np
    >>> full = np.array([[0.1, 0.3, 0.2], [0.9, 0.1, 0.9], [0.2, 0.9, 0.1]])
    >>> regret, rival = exchanges(full, np.array([0, 1, 2]), [0])
    >>> regret.round(6).tolist(), rival.tolist()
    ([0.2], [2])
    """
    own = full[np.arange(full.shape[0]), perm]
    w = full[:, perm] - own[:, None]                 # w[i, j]: i takes j's root
    n = w.shape[0]
    d = w.copy()
    np.fill_diagonal(d, 0.0)
    for k in range(n):                               # shortest exchanges j -> ... -> i
        d = np.minimum(d, d[:, k:k + 1] + d[k:k + 1, :])
    out, rival = [], []
    for i in rows:
        alt = w[i] + d[:, i]                          # i takes j's root, j's chain back to i
        alt[i] = np.inf
        j = int(np.argmin(alt)) if n > 1 else i
        out.append(float(alt[j]) if n > 1 else np.inf)
        rival.append(int(perm[j]) if n > 1 else -1)
    return np.maximum(np.array(out), 0.0), np.array(rival, int)


def _nearest_clear(dist, rows, cols):
    """Per assigned pair: the root is the path's nearest by :data:`NEAR_RATIO`, and back.

    ``dist`` is the absolute distance [/rev] from each path's predicted root
    to each root (in the representation the path sees).
    """
    rows, cols = np.asarray(rows, int), np.asarray(cols, int)
    own = dist[rows, cols]
    other = dist.astype(float)                  # a copy
    other[rows, cols] = np.inf
    row_alt = other[rows].min(axis=1, initial=np.inf)
    col_alt = other[:, cols].min(axis=0, initial=np.inf)
    return (own <= NEAR_RATIO * np.minimum(row_alt, col_alt)).tolist()


def _lock_partner(eig, c, assigned, periodic):
    """The assigned root whose second root ``c`` is, or None.

    Floquet: a root at the same frequency folded into ``[0, 1/2]`` (within
    ten times :data:`tefcore.modes.matching.LOCK_TOL`: the two of a lock share
    ``k/2`` to round-off), the
    nearest in real part.  Constant coefficients: two real roots of one
    overdamped pair, the nearest real root.
    """
    eig = np.asarray(eig, complex)
    fold = _fold(eig)
    if periodic:
        ok = assigned & (np.abs(fold - fold[c]) <= 10 * LOCK_TOL)
    else:
        ok = assigned & (np.abs(eig.imag) <= 1e-9) & (abs(eig[c].imag) <= 1e-9)
    if not ok.any():
        return None
    return int(np.argmin(np.where(ok, np.abs(eig.real - eig[c].real), np.inf)))


class March:
    """The paths of all roots along ``eps``: their origins, last roots and doubts.

    ``doubt``: the path met another mode's (an exceptional point); ``lock``:
    the path passed an undecided match among roots the flap takes no part in
    (a frequency lock of the blade, named by participation at the end).

    Parameters
    ----------
    eig : numpy.ndarray of complex
        The roots at ``eps = 0``, one path each [/rev].
    vecs : numpy.ndarray
        Their shapes (:func:`tefcore.modes.continuation.path_shapes`), one
        column per root.
    names : list of str
        Their names (the uncoupled modes).
    n_phys : int
        Rows of the tracking basis (the flap's motion last).
    periodic : bool
        Floquet exponents (frequencies known modulo 1/rev and up to the sign).
    """

    def __init__(self, eig, vecs, names, n_phys, periodic):
        self.eig, self.vecs = np.asarray(eig, complex), vecs
        # each path's flap share and sum |shape|^2, as self.vecs
        self.share, self.norm = _share_and_norm(vecs, n_phys)
        self.n_phys, self.periodic = n_phys, periodic
        self.origin = [str(x) for x in names]
        self.start = self.eig.copy()
        self.before = None                # (eps, each path's eigenvalue) at the step before
        self.eps = 0.0
        self.doubt = np.zeros(self.eig.size, bool)
        self.lock = np.zeros(self.eig.size, bool)
        self.pid = np.arange(self.eig.size)       # each path's id, carried along
        self.next_pid = self.eig.size
        self.meetings: list[dict] = []
        self.last_clear = True

    def _base(self, i):
        return base_name(self.origin[i])

    def _predicted(self, eps):
        """Each path's eigenvalue extrapolated linearly from its last two steps."""
        if self.before is None:
            return self.eig
        e0, eig0 = self.before
        return self.eig + (self.eig - eig0) * (eps - self.eps) / (self.eps - e0)

    def _distance(self, pred, seen):
        """Eigenvalue part of the cost of each path (rows) to each root as it sees it."""
        a = pred[:, None]
        ds = np.abs(a.real - seen.real)
        ss = 0.5 + 0.5 * (np.abs(a.real) + np.abs(seen.real))
        sw = 1.0 + 0.5 * (np.abs(a.imag) + np.abs(seen.imag))
        return np.hypot(ds / ss, np.abs(a.imag - seen.imag) / sw)

    def _costs(self, pred, eig, vecs, norm=None):
        """Match costs (paths, roots), their ``1 - MAC`` parts, the roots as each path sees them.

        Constant coefficients: eigenvalue distance (:meth:`_distance`) plus
        ``1 - MAC`` of the shapes, against the path's shape and its conjugate
        (the sign of the imaginary part is the pair's convention).

        Floquet: a root's frequency is known modulo 1/rev and up to the sign.
        Each root is taken in the representation a path would carry it in
        unwrapped: the integer shift nearest the path's predicted frequency,
        of the root (``up``) or of its conjugate (``down``, whose motion is the
        conjugate).  The shapes compared are the motions over the revolution
        with each one's own frequency taken out -- the periodic parts
        ``p(psi)`` in that representation -- so the drift ``exp(i (f' - f) psi)``
        of a frequency that moves along ``eps`` does not read as a change of
        shape, and a representation that is near in frequency but not the
        root's own (a root near ``k/2``: ``f`` and ``k - f`` both near the
        path) shows in the shape.  Of the two, the one of least cost.
        (Measured on Fig. 9's point c_cg 0.04: comparing the motions
        themselves, the TEF root at 18.6 /rev kept MAC 0.25 with itself over
        the step to eps = 0.5, and steps were halved to 1/64 where no two
        roots met.)
        """
        if not self.periodic:
            seen = np.broadcast_to(eig[None, :], (pred.size, eig.size))
            shape = 1.0 - np.maximum(mac(self.vecs, vecs), mac(self.vecs.conj(), vecs))
            return np.minimum(1.0, self._distance(pred, seen)) + shape, shape, seen, \
                np.zeros(seen.shape, bool)
        f, q = eig.imag[None, :], pred.imag[:, None]
        n_phys = self.n_phys
        samples = vecs.shape[0] // n_phys
        psi = 2 * np.pi * np.arange(samples) / samples
        # conj(path motion) exp(i f_path psi) and root motion exp(-i f_root psi):
        # what is left of exp(i (f_path - f_seen) psi) is exp(-i j psi) for the
        # integer shift j of the representation -- harmonic j of the product,
        # read from its FFT over the samples
        # (the path's factor applied after the product: forming conj(path)
        # exp(i f psi) first, a strided copy, took 0.4 of the 0.86 ms of a
        # step's costs, measured with 11 roots at 72 azimuths)
        path_h = np.swapaxes(self.vecs.reshape(samples, n_phys, -1).conj(), 1, 2)
        spin = np.exp(1j * np.outer(psi, self.eig.imag))[:, :, None]
        bt = vecs.reshape(samples, n_phys, -1) * np.exp(-1j * np.outer(psi, eig.imag))[:, None, :]
        if norm is None:                   # each root's sum |shape|^2
            norm = _share_and_norm(vecs, n_phys)[1]
        norm = self.norm[:, None] * norm[None, :]
        rows, cols = np.indices(norm.shape)
        # the root (f + j, its motion) and its conjugate (-f + j', the conjugate
        # motion) side by side: one product and one FFT for both
        # (harmonics, paths, 2 roots)
        harm = np.fft.fft((path_h @ np.concatenate([bt, bt.conj()], axis=-1)) * spin, axis=0)
        out = []
        for half, sign in enumerate((1.0, -1.0)):
            shift = np.round(q - sign * f)
            num = _modulus2(harm[shift.astype(int) % samples, rows, cols + half * eig.size])
            seen = eig.real[None, :] + 1j * (sign * f + shift)
            shape = 1.0 - num / norm
            out.append((np.minimum(1.0, self._distance(pred, seen)) + shape, shape, seen))
        flip = out[1][0] < out[0][0]
        cost, shape, seen = (np.where(flip, dn, up)
                             for up, dn in zip(out[0], out[1], strict=True))
        return cost, shape, seen, flip

    def step(self, eps, eig, vecs, final_step) -> bool:
        """Assign the roots at `eps` to the paths; False when the step must be halved."""
        eig = np.asarray(eig, complex)
        pred = self._predicted(eps)
        share, norm = _share_and_norm(vecs, self.n_phys)
        cost, shape, seen, flip = self._costs(pred, eig, vecs, norm)
        full = _padded(cost, _near_lock(pred, self.periodic), _near_lock(eig, self.periodic))
        perm, rows, cols = _assign(full, *cost.shape)
        # clear: the root's shape is resolved by the step (its own 1 - MAC at
        # most CLEAR_COST) and no rearrangement of the step is within MARGIN of
        # the assignment (tefcore.modes.matching: a quarter of a MAC)
        regret, rival = exchanges(full, perm, rows)
        rival = np.where(rival < cost.shape[1], rival, -1)     # a padded column: none
        clear = [bool(shape[r, c] <= CLEAR_COST and g >= MARGIN)
                 for r, c, g in zip(rows, cols, regret, strict=True)]
        near = _nearest_clear(np.abs(seen - pred[:, None]), rows, cols)
        clear = [a or b for a, b in zip(clear, near, strict=True)]
        active = share >= FLAP_ACTIVE
        moved = self.share >= FLAP_ACTIVE
        path_of = dict(zip(cols, rows, strict=True))
        # the two real roots of a lock forming at this step: a path that
        # reaches either has reached its mode, and the other root is its
        # partner (named as a pair by the caller, never by which of the two
        # the assignment chose): an exchange with the appearing partner is not
        # undecided (measured on Fig. 14's 0.14 R: the TEF touches the lock at
        # 8.5 /rev near eps 0.984 and leaves it a step later; counted as a
        # rival, the appearing root's regret, equal to round-off, flags the
        # TEF's name undecided)
        partner = None                  # lock_matrix(eig), on the first undecided row
        meet, lock = [], []
        for r, c, ok, k in zip(rows, cols, clear, rival, strict=True):
            other = path_of.get(k)
            if ok or (other is not None and self._base(other) == self._base(r)):
                continue
            if other is None and k >= 0 and self.periodic:
                if partner is None:
                    partner = lock_matrix(eig)
                if partner[c, k]:
                    continue
            mine = moved[r] or active[c]
            theirs = (k >= 0 and active[k]) or (other is not None and moved[other])
            unresolved = shape[r, c] > CLEAR_COST
            if self.periodic and not (mine and (theirs or unresolved)):
                # an exchange that does not move the flap on both sides: not
                # refined.  The coupling moves a root in proportion to its
                # motion of the flap, so a root that does not move it is the
                # blade's own and is named by participation at the end, which
                # also gives a moving root the name left when the two swapped
                # here (final_names.flap_free_by_participation); only an
                # exchange between two paths or roots that move the flap needs
                # the step resolved.
                # The rival is the other end of the exchange the regret prices
                # (:func:`exchanges`), and a side moves the flap when its path
                # did or its root does (measured: with the matched root and the
                # row's next root alone, the TEF path of mdart-fig6's Fig. 14
                # point 0.22 R took a flap-free root at 1 - MAC 1.00 at the
                # first step, against flap 4's path and a root moving the flap,
                # and ended on blade flap 3's root).  (Measured on Fig. 9's
                # sweep: 312 eigenproblems on the paths with every undecided
                # pair refined, 132 without.)
                lock.append((r, other))
            else:
                meet.append((r, other))
        self.last_clear = not meet
        if meet and not final_step:
            return False
        self._accept(eps, seen, flip, vecs, rows, cols, meet, lock, eig, share)
        self.norm = norm
        return True

    def _accept(self, eps, seen, flip, vecs, rows, cols, meet, lock, raw, share):
        # each root as the path it continues sees it (its frequency unwrapped),
        # its motion in the same orientation (the conjugate where the sign flipped)
        eig = seen[0].copy()
        turn = flip[0].copy()
        for r, c in zip(rows, cols, strict=True):
            eig[c], turn[c] = seen[r, c], flip[r, c]
        vecs = np.where(turn[None, :], vecs.conj(), vecs)
        origin = [""] * eig.size
        start = np.full(eig.size, np.nan, complex)
        last = np.full(eig.size, np.nan, complex)     # each path's eigenvalue a step back
        doubt = np.zeros(eig.size, bool)
        locked = np.zeros(eig.size, bool)
        pid = np.full(eig.size, -1)
        for r, c in zip(rows, cols, strict=True):
            origin[c], start[c], last[c] = self.origin[r], self.start[r], self.eig[r]
            doubt[c], locked[c], pid[c] = self.doubt[r], self.lock[r], self.pid[r]
        col_of = dict(zip(rows, cols, strict=True))
        for r, other in lock:
            locked[[col_of[x] for x in (r, other) if x is not None]] = True
        for r, other in meet:
            doubt[[col_of[x] for x in (r, other) if x is not None]] = True
            pair = sorted({self._base(r), self._base(other) if other is not None else "?"})
            if len(pair) < 2 or other is None:
                continue
            a, b = col_of[r], col_of[other]
            # Floquet: the multipliers coalesce (frequencies modulo 1/rev and
            # up to the sign, a combination resonance among them)
            gap = float(relative_distance(eig[a:a + 1], eig[b:b + 1], self.periodic)[0, 0])
            shape = float(max(mac(vecs[:, a], vecs[:, b])[0, 0],
                              mac(vecs[:, a].conj(), vecs[:, b])[0, 0]))
            # a meeting is an exceptional point only where the two roots
            # coalesce, one eigenvalue and one shape; two roots still apart
            # whose match no step decided keep the assignment of least cost,
            # uncertain but not a coalescence (measured on the paper's
            # figures: undecided pairs at MAC 0.18-0.8 or 0.1-0.6 apart, and
            # coalescing pairs at MAC 0.97, 0.03 apart)
            if shape >= COALESCED_MAC and gap <= COALESCED_DISTANCE:
                self.meetings.append({"eps": eps, "origins": pair_text(*pair),
                                      "gap": gap, "mac": shape,
                                      "paths": {self._base(r): int(self.pid[r]),
                                                self._base(other): int(self.pid[other])}})
        # a lock that dissolves: its two real roots become one complex root
        # again, and one of the two paths ends; the root left is the mode
        # itself, whichever path it continues (measured on Fig. 13 at 0.725 R:
        # the TEF path ended where its lock closed, and 'TEF (locked)' went on)
        names = set(origin)
        for c in cols:
            if is_locked(origin[c]) and base_name(origin[c]) not in names:
                names.add(base_name(origin[c]))
                origin[c] = base_name(origin[c])
        assigned = np.isin(np.arange(eig.size), cols)
        for c in np.flatnonzero(~assigned):
            pid[c], self.next_pid = self.next_pid, self.next_pid + 1
            # a root that appears: a pair became two real roots (a lock at k/2,
            # or an overdamped pair): it is the second root of its partner,
            # the assigned root at its frequency (folded into [0, 1/2])
            near = _lock_partner(raw, c, assigned, self.periodic)
            if near is None or not origin[near]:
                # unexplained: no partner, or a partner no path explains either
                # (measured: A changed by 1e-13 at Fig. 14's 0.2175 R lost the
                # TEF path where its lock formed, and the appearing root was
                # named ' (locked)', which no later pass renamed: a root named '')
                origin[c], doubt[c], last[c] = "", True, eig[c]
                continue
            origin[c] = locked_name(origin[near])
            start[c], doubt[c], last[c] = start[near], doubt[near], eig[c]
            locked[[c, near]] = True
        self.before = (self.eps, last)
        self.eps, self.eig, self.vecs = eps, eig, vecs
        self.share = share              # flap_share(vecs): a conjugate's is the same
        self.origin, self.start, self.doubt, self.lock = origin, start, doubt, locked
        self.pid = pid
