"""Mode tracking along a parameter: one curve is one physical mode, or says it is not sure.

An eigen-solver returns the modes of each sweep point in its own order
(usually by frequency), so where two modes cross in frequency, "mode 3" at
one point is "mode 4" at the next.  :func:`track_modes` orders them into
continuous tracks by matching the modes of consecutive points (in the order
of the parameter, whatever order they were computed in) with an optimal
assignment (:func:`scipy.optimize.linear_sum_assignment`) on the cost

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
that does not change along the sweep (:meth:`tefcore.coupled.CoupledModel.tracking_basis`).

**Identity is decided, or flagged.**  A match is *clear* when its shape part
``1 - MAC`` is at most :data:`CLEAR_COST` (the eigenvalue part alone when no
shapes are known) and every alternative -- another mode for the track, or
another track for the mode -- costs at least :data:`MARGIN` more.
Otherwise the row's ``identity`` is ``"ambiguous"``; :func:`tefcore.sweep.sweep`
then refines the parameter step between the two points (bisection, bounded)
and tracks again.  Where two roots have the same shape and eigenvalue
(MAC >= :data:`COALESCED_MAC`, :func:`relative_distance` within
:data:`COALESCED_DISTANCE`), or are the two real multipliers of one locked
pair (equal frequency at a multiple of 1/2 per rev), no refinement can
separate them: a coalescence, and the identity is ``"coalescence"``; the
track then goes on with the less stable root of the pair (the one that
matters for stability), by convention -- the table says where.
Two tracks whose eigenvalues pass closer in a step than they move may have
crossed or veered; where their shapes exchanged (each new shape carries at
least :data:`EXCHANGE_MAC` of the other's old one), the match is
``"ambiguous"`` too and the step is refined.  A track's first row is ``"start"``.

Each track keeps the ``label`` its mode had where the track starts; the
point's own label at each point is ``label_here``, so a label that changes
along a curve (a mode that changes character, as in a veering) is visible,
and :func:`label_changes` lists it.  :func:`follow_root` is the same
continuation for one root along a homotopy (used by
:mod:`tefcore.mechanism`).

Examples
--------
Two modes whose frequencies cross; the solver lists them by frequency:

>>> import numpy as np, pandas as pd
>>> def pt(x):
...     f = {"a": 1.0 + x, "b": 2.0 - x}
...     order = sorted(f, key=f.get)
...     modes = pd.DataFrame({"mode_id": [0, 1], "label": order,
...                           "frequency_per_rev": [f[k] for k in order],
...                           "real_part": [-0.01, -0.02] if order[0] == "a" else [-0.02, -0.01]})
...     vecs = np.array([[1, 0] if k == "a" else [0, 1] for k in order], complex).T
...     return modes, vecs
>>> t = track_modes([pt(x) for x in (0.0, 0.4, 0.8)], values=[0.0, 0.4, 0.8])
>>> for label, curve in t.groupby("label"):
...     print(label, curve["frequency_per_rev"].tolist(), curve["identity"].tolist())
a [1.0, 1.4, 1.8] ['start', 'clear', 'clear']
b [2.0, 1.6, 1.2] ['start', 'clear', 'clear']
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.optimize import linear_sum_assignment

__all__ = ["CLEAR_COST", "COALESCED_DISTANCE", "EXCHANGE_MAC", "COALESCED_MAC", "MARGIN", "FollowResult",
           "ambiguous_steps", "eigen_distance", "follow_root", "label_changes", "mac",
           "relative_distance",
           "match_cost", "match_modes", "track_modes"]

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
#: Two tracks passing close in one step are a possible veering when one's new
#: shape carries at least this share of the other's old shape (MAC): a veering
#: exchanges the shapes (sin^2 of the turn, 0.13 over a step that spans the
#: veering of a 2 x 2 family), modes crossing without coupling keep theirs
#: (MAC between distinct MDART modes below 0.05, measured).
EXCHANGE_MAC = 0.1
#: Two roots of one point with a MAC above this ...
COALESCED_MAC = 0.9
#: ... and a :func:`relative_distance` below this are one coalesced pair.
COALESCED_DISTANCE = 0.05


def mac(phi_a, phi_b) -> np.ndarray:
    """Modal assurance criterion between the columns of two (complex) mode sets.

    ``MAC[i, j] = |phi_a[:, i]^H phi_b[:, j]|^2 / ((phi_a_i^H phi_a_i)(phi_b_j^H phi_b_j))``,
    which is 1 for parallel vectors (whatever their complex scaling) and 0
    for orthogonal ones.

    Parameters
    ----------
    phi_a : array_like, shape (n,) or (n, p)
    phi_b : array_like, shape (n,) or (n, q)

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
    vecs : ndarray, shape (d, q), or None
    periodic : bool
        Floquet exponents (see :func:`eigen_distance`).
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


def _is_clear(best: float, shape: float, alt: float) -> bool:
    """A match of total cost ``best`` (shape part ``shape``, NaN: unknown) with the
    best alternative at ``alt``: clear or not."""
    own = best if np.isnan(shape) else shape
    return bool(own <= CLEAR_COST and alt - best >= MARGIN)


def _decide(cost, rows, cols, shape=None):
    """Per assigned pair: clear (bool) and the best alternative's column."""
    shape = np.full(cost.shape, np.nan) if shape is None else shape
    clear, rival = [], []
    for r, c in zip(rows, cols, strict=True):
        best = cost[r, c]
        row_alt = np.delete(cost[r], c)
        col_alt = np.delete(cost[:, c], r)
        alt = min(row_alt.min(initial=np.inf), col_alt.min(initial=np.inf))
        clear.append(_is_clear(best, shape[r, c], alt))
        others = [j for j in range(cost.shape[1]) if j != c]
        rival.append(min(others, key=lambda j: cost[r, j]) if others else -1)
    return clear, rival


def _coalesced(eig, vecs, j, k, periodic) -> bool:
    """Roots ``j`` and ``k`` of one point are one coalesced pair.

    Either (nearly) one shape and eigenvalue -- an exceptional point -- or,
    for Floquet exponents, the two real multipliers of one locked pair
    (equal frequency, a multiple of 1/2 per rev): their identities are two
    halves of one mode, which no finer step separates.
    """
    if k < 0:
        return False
    if periodic and abs(eig[j].imag - eig[k].imag) <= 1e-6 and abs(
            2 * eig[j].imag - round(2 * eig[j].imag)) <= 1e-6:
        return True
    if vecs is None:        # without shapes two near roots may as well be two modes
        return False
    d = relative_distance(eig[[j]], eig[[k]], periodic)[0, 0]
    return bool(mac(vecs[:, j], vecs[:, k])[0, 0] >= COALESCED_MAC and d <= COALESCED_DISTANCE)


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
    pm, pv, pp = _as_point(prev)
    cm, cv, cp = _as_point(curr)
    periodic = (pp or cp) if periodic is None else periodic
    pred = _eig(pm) if predicted is None else np.asarray(predicted, complex)
    vecs_prev = [None if pv is None else pv[:, i] for i in range(len(pm))]
    cost = match_cost(pred, vecs_prev, _eig(cm), cv, periodic)
    rows, cols = linear_sum_assignment(cost)
    out = np.full(len(pm), -1)
    out[rows] = cols
    return out


def _eig(modes: pd.DataFrame) -> np.ndarray:
    return modes["real_part"].to_numpy(float) + 1j * modes["frequency_per_rev"].to_numpy(float)


def _as_point(p):
    """Normalise a point to (modes DataFrame, vectors ndarray or None, periodic)."""
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


@dataclass
class _Track:
    label: str
    eig: list = field(default_factory=list)  # last two (x, eigenvalue)
    vec: np.ndarray | None = None

    def predict(self, x, use: bool) -> complex:
        (x1, e1) = self.eig[-1]
        if use and len(self.eig) == 2:
            (x0, e0) = self.eig[0]
            if x1 != x0 and np.isfinite(e0) and np.isfinite(e1):
                return e1 + (e1 - e0) * (x - x1) / (x1 - x0)
        return e1

    def update(self, x, eig, vec):
        self.eig = [*self.eig[-1:], (x, eig)]
        if vec is not None:
            self.vec = vec


def track_modes(points: Sequence, values=None, *, predict: bool = True) -> pd.DataFrame:
    """Order the modes of successive sweep points into continuous tracks.

    Parameters
    ----------
    points : sequence
        One entry per sweep point, in the order of the parameter: a result
        with ``modes`` and ``vectors`` (or ``eigenvectors``) attributes
        (e.g. a ``StabilityResult``), a ``(modes, vectors[, periodic])``
        tuple, a mapping with keys ``modes``, ``vectors``, ``periodic``, or a
        bare modes DataFrame; ``None`` for a failed point (skipped; tracks
        continue across the gap).  Modes tables need the columns
        ``mode_id``, ``label``, ``frequency_per_rev`` and ``real_part``.
        Vectors (columns aligned with the rows of ``modes``) may be missing
        for some or all points; MAC is used where both sides have vectors
        of the same length.
    values : sequence of float, optional
        Parameter value of each point, for the linear extrapolation of the
        eigenvalues; default: equally spaced.
    predict : bool
        Extrapolate each track's eigenvalue linearly from its last two
        points (default) instead of comparing with its last value.

    Returns
    -------
    DataFrame
        One row per (point, mode): ``step`` (index into `points`),
        ``track`` (0, 1, ... in the order of the first point's modes; modes
        that cannot be matched start new tracks), ``label`` (the track's
        label where it starts), ``label_here`` (the point's own label),
        ``identity`` (``start``, ``clear``, ``ambiguous`` or
        ``coalescence``: how this row was matched to the track's previous
        row, module docstring), ``frequency_tracked`` (for Floquet
        exponents, the frequency shifted by whole /rev and sign to continue
        the track's: the solver's ``frequency_per_rev`` takes the dominant
        harmonic of the mode's shape, which can jump between points where
        several harmonics are strong; in hover the two are equal) and the
        remaining columns of the modes tables.  Sorted by step, track.  A
        pure function of the points and values: the same data give the same
        table.
    """
    if values is None:
        values = np.arange(len(points), dtype=float)
    values = list(values)
    if len(values) != len(points):
        raise ValueError(f"{len(values)} values for {len(points)} points")
    tracks: list[_Track] = []
    alive: list[int] = []
    frames = []
    prev_periodic = False
    for step, (p, x) in enumerate(zip(points, values, strict=True)):
        if p is None:
            continue
        modes, vecs, periodic = _as_point(p)
        try:
            x = float(x)
        except (TypeError, ValueError):
            x = float(step)
        eig = _eig(modes)
        col_vec = [None if vecs is None else vecs[:, j] for j in range(len(modes))]
        assigned = np.full(len(modes), -1)
        identity = np.full(len(modes), "start", dtype=object)
        if alive and len(modes):
            pred = np.array([tracks[t].predict(x, predict) for t in alive])
            cost, shape = match_cost(pred, [tracks[t].vec for t in alive], eig, vecs,
                                     periodic or prev_periodic, shape_part=True)
            rows, cols = linear_sum_assignment(cost)
            clear, rival = _decide(cost, rows, cols, shape)
            partner = {}
            for r, c, ok, k in zip(rows, cols, clear, rival, strict=True):
                assigned[c] = alive[r]
                if ok:
                    identity[c] = "clear"
                elif _coalesced(eig, vecs, c, k, periodic or prev_periodic):
                    identity[c] = "coalescence"
                    partner[c] = k
                else:
                    identity[c] = "ambiguous"
            # a coalesced pair is one mode split into two roots: by convention
            # the track goes on with the less stable one (the one that matters
            # for stability), the other root takes the partner's track or a new one
            for c, k in partner.items():
                if eig[k].real > eig[c].real and identity[c] == "coalescence":
                    assigned[c], assigned[k] = assigned[k], assigned[c]
                    identity[k] = "coalescence"
                    identity[c] = "coalescence" if assigned[c] >= 0 else "start"
        tracked_eig = eig.copy()
        if periodic or prev_periodic:
            for j, t in enumerate(assigned):
                if t >= 0:
                    tracked_eig[j] = _unwrap(eig[j], tracks[t].predict(x, predict))
        if alive and len(modes):
            _flag_close_passes(identity, assigned, tracked_eig, tracks, vecs,
                               periodic or prev_periodic)
        for j in np.flatnonzero(assigned < 0):
            tracks.append(_Track(label=str(modes["label"].iloc[j])))
            assigned[j] = len(tracks) - 1
        for j, t in enumerate(assigned):
            tracks[t].update(x, tracked_eig[j], col_vec[j])
        alive = [int(t) for t in assigned]
        prev_periodic = periodic
        frame = modes.drop(columns="label")
        frame.insert(frame.columns.get_loc("frequency_per_rev") + 1, "frequency_tracked",
                     tracked_eig.imag)
        frame.insert(0, "identity", identity)
        frame.insert(0, "label_here", modes["label"])
        frame.insert(0, "label", [tracks[t].label for t in assigned])
        frame.insert(0, "track", assigned)
        frame.insert(0, "step", step)
        frames.append(frame)
    if not frames:
        return pd.DataFrame(columns=["step", "track", "label", "label_here", "identity",
                                     "mode_id", "frequency_per_rev", "real_part"])
    out = pd.concat(frames, ignore_index=True)
    return out.sort_values(["step", "track"], kind="stable", ignore_index=True)


def _flag_close_passes(identity, assigned, eig, tracks, vecs, periodic=False) -> None:
    """Mark ``ambiguous`` the clear matches of two tracks that pass close in a step.

    Two roots whose eigenvalues, moving linearly over the step, come closer
    than either moved may have crossed or veered; the end points cannot tell
    which.  Modes that cross without coupling keep their own shapes; modes
    that veer exchange them, so each root's new shape carries some of the
    other's old one: where that exchange is at least :data:`EXCHANGE_MAC`
    (or no shapes are known), the step is bisected (:func:`tefcore.sweep.sweep`).
    """
    js = [j for j in range(len(assigned)) if assigned[j] >= 0 and identity[j] == "clear"]
    if len(js) < 2:
        return
    p0 = np.array([tracks[assigned[j]].eig[-1][1] for j in js])
    p1 = np.asarray([eig[j] for j in js])
    old = [tracks[assigned[j]].vec for j in js]
    known = vecs is not None and all(v is not None and v.shape[0] == vecs.shape[0] for v in old)
    exchange = np.ones((len(js), len(js)), bool)
    if known:
        cross = mac(np.stack(old, axis=1), vecs[:, js])       # old shape a vs new shape b
        exchange = (cross >= EXCHANGE_MAC) | (cross.T >= EXCHANGE_MAC)
    if periodic:
        # Floquet frequencies are known modulo 1/rev and up to sign: each
        # root's end is put next to its start, then each pair's second root
        # next to the first (the same shift and sign for both its ends), so
        # the segments below are compared in one local frame
        p1 = np.array([_unwrap(e, s) for e, s in zip(p1, p0, strict=True)])
    for a in range(len(js)):
        for b in range(a + 1, len(js)):
            if not exchange[a, b]:
                continue
            b0, b1 = p0[b], p1[b]
            if periodic:
                b0n = _unwrap(b0, p0[a])
                sign = 1.0 if np.isclose(b0n.imag % 1.0, b0.imag % 1.0) else -1.0
                b1 = complex(b1.real, sign * b1.imag + (b0n.imag - sign * b0.imag))
                b0 = b0n
            # one scale for the pair: damping rates and frequencies each
            # relative to their size (as relative_distance)
            pts = np.array([p0[a], p1[a], b0, b1])
            sc = (0.5 + 0.5 * np.abs(pts.real).mean()) + 1j * (
                0.5 if periodic else 1.0 + 0.5 * np.abs(pts.imag).mean())
            x0a, x1a, x0b, x1b = (z.real / sc.real + 1j * z.imag / sc.imag for z in pts)
            d0, dd = x0a - x0b, (x1a - x0a) - (x1b - x0b)
            t = 0.0 if dd == 0 else float(np.clip(-(d0 * np.conj(dd)).real / abs(dd) ** 2,
                                                   0.0, 1.0))
            if abs(d0 + t * dd) < max(abs(x1a - x0a), abs(x1b - x0b)):
                identity[js[a]] = identity[js[b]] = "ambiguous"


def _unwrap(eig: complex, predicted: complex) -> complex:
    """The representative of a Floquet exponent (frequency modulo 1/rev, up to
    its sign) whose frequency is closest to the predicted one."""
    f, p = eig.imag, predicted.imag
    up, down = f + round(p - f), -f + round(p + f)
    return complex(eig.real, up if abs(up - p) <= abs(down - p) else down)


def ambiguous_steps(tracked: pd.DataFrame, kinds=("ambiguous",)) -> list[int]:
    """Steps of a :func:`track_modes` table reached by an undecided match.

    The match into such a step from the previous point was not clear: the
    interval before it is where a finer parameter step is needed.
    """
    bad = tracked[tracked["identity"].isin(kinds)]
    return sorted(int(s) for s in bad["step"].unique())


def label_changes(tracked: pd.DataFrame) -> pd.DataFrame:
    """Where the point function's label of a tracked mode changes along its track.

    Parameters
    ----------
    tracked : DataFrame
        Output of :func:`track_modes` (or a sweep table), with columns
        ``track``, ``label`` and ``label_here``, in sweep order.

    Returns
    -------
    DataFrame
        One row per change: ``track``, ``label`` (the track's label),
        ``row`` (index in `tracked` where the new label first appears),
        ``from_label`` and ``to_label``.
    """
    rows = []
    valid = tracked[tracked["track"].notna()]
    for track, g in valid.groupby("track", sort=True):
        here = g["label_here"].astype(str).to_numpy()
        for k in np.flatnonzero(here[1:] != here[:-1]) + 1:
            rows.append({"track": track, "label": g["label"].iloc[k], "row": g.index[k],
                         "from_label": here[k - 1], "to_label": here[k]})
    return pd.DataFrame(rows, columns=["track", "label", "row", "from_label", "to_label"])


# ------------------------------------------------------------------ one root along a homotopy


@dataclass
class FollowResult:
    """A root followed by :func:`follow_root`.

    Attributes
    ----------
    index : int
        The root's index among the roots at the end of the path.
    eigenvalue : complex
        Its eigenvalue there.
    path : list of (float, complex)
        Parameter and eigenvalue at every accepted step.
    ambiguous : list of float
        Parameter values reached by a match that stayed ambiguous at the
        smallest step (a coalescence on the path: identity not decidable).
    """

    index: int
    eigenvalue: complex
    path: list
    ambiguous: list

    @property
    def clear(self) -> bool:
        """True when every step of the path was a clear match."""
        return not self.ambiguous


def follow_root(solve: Callable, start: float, stop: float, root: int, *,
                periodic: bool = False, n_steps: int = 8, max_halvings: int = 6,
                first=None) -> FollowResult:
    """Follow one root of a parameter-dependent eigenproblem from `start` to `stop`.

    Pseudo-arclength is not needed for eigenvalues, which are continuous in
    the parameter: the root is matched step by step (cost and decision of
    :func:`track_modes`, against its last shape and linearly extrapolated
    eigenvalue), halving a step whose match is not clear, at most
    `max_halvings` times; a match still not clear then is accepted and
    recorded in ``ambiguous``.

    Parameters
    ----------
    solve : callable
        ``solve(s) -> (eigenvalues (m,), vectors (d, m))``: all roots at
        parameter ``s``.
    start, stop : float
    root : int
        Index of the root at `start`.
    periodic : bool
        Floquet exponents (:func:`eigen_distance`).
    n_steps : int
        Initial equal steps.
    first : tuple, optional
        ``solve(start)`` if already computed.

    Returns
    -------
    FollowResult

    Examples
    --------
    Two roots that veer: ``[[1 + s, 0.1], [0.1, 2 - s]]`` on ``s`` 0 -> 1.
    The lower root rises to 1.4 at the near-crossing and turns back down to
    0.99 while its shape turns from the first coordinate to the second: the
    continuous branch, not a jump to the other one:

    >>> import numpy as np
    >>> def solve(s):
    ...     w, v = np.linalg.eigh(np.array([[1 + s, 0.1], [0.1, 2 - s]]))
    ...     return w.astype(complex), v.astype(complex)
    >>> r = follow_root(solve, 0.0, 1.0, root=0)
    >>> r.index, round(r.eigenvalue.real, 4), round(max(e.real for _, e in r.path), 4), r.clear
    (0, 0.9901, 1.4, True)
    """
    eig, vec = solve(start) if first is None else first
    eig = np.asarray(eig, complex)
    track = _Track(label="", eig=[(start, eig[root])], vec=vec[:, root])
    path = [(float(start), complex(eig[root]))]
    ambiguous = []
    s, index = float(start), int(root)
    h = (stop - start) / n_steps
    min_h = abs(h) / 2 ** max_halvings
    while (stop - s) * np.sign(h) > 1e-15 * max(1.0, abs(stop)):
        step = h if abs(h) <= abs(stop - s) else stop - s
        s_new = s + step
        eig_n, vec_n = solve(s_new)
        eig_n = np.asarray(eig_n, complex)
        cost, shape = match_cost([track.predict(s_new, True)], [track.vec], eig_n, vec_n,
                                 periodic, shape_part=True)
        j = int(np.argmin(cost[0]))
        alt = np.delete(cost[0], j).min(initial=np.inf)
        ok = _is_clear(cost[0, j], shape[0, j], alt)
        if not ok and abs(step) > min_h * (1 + 1e-12):
            h = step / 2
            continue
        if not ok:
            ambiguous.append(float(s_new))
        track.update(s_new, eig_n[j], vec_n[:, j])
        path.append((float(s_new), complex(eig_n[j])))
        s, index = s_new, j
        if ok and abs(h) < abs(stop - start) / n_steps:
            h *= 2                                   # grow back after a hard stretch
    return FollowResult(index=index, eigenvalue=path[-1][1], path=path, ambiguous=ambiguous)
