"""Mode tracking along a parameter: one curve is one physical mode, or says it is not sure.

:func:`track_modes` orders the modes of successive sweep points into
continuous tracks, matching the modes of consecutive points (in the order of
the parameter, whatever order they were computed in) by the cost of
:mod:`tefcore.modes.matching` (MAC and eigenvalue distance), each track's
eigenvalue extrapolated linearly to the new parameter value.

**Identity is decided, or flagged.**  A match is *clear* when its shape part
``1 - MAC`` is at most :data:`~tefcore.modes.matching.CLEAR_COST` (the
eigenvalue part alone when no shapes are known) and every alternative --
another mode for the track, or another track for the mode -- costs at least
:data:`~tefcore.modes.matching.MARGIN` more.
Otherwise the row's ``identity`` is ``"ambiguous"``; :func:`tefcore.sweeps.sweep.sweep`
then refines the parameter step between the two points (bisection, bounded)
and tracks again.  Where two roots have the same shape and eigenvalue
(MAC >= :data:`~tefcore.modes.matching.COALESCED_MAC`,
:func:`~tefcore.modes.matching.relative_distance` within
:data:`~tefcore.modes.matching.COALESCED_DISTANCE`), no refinement can
separate them: a coalescence, and the identity is ``"coalescence"``; the
track then goes on with the less stable root of the pair (the one that
matters for stability), by convention -- the table says where.
Two tracks whose eigenvalues pass closer in a step than they move may have
crossed or veered; where their shapes exchanged (each new shape carries at
least :data:`EXCHANGE_MAC` of the other's old one), the match is
``"ambiguous"`` too and the step is refined.  A track's first row is ``"start"``.

**Floquet locks.**  Where a complex pair of Floquet multipliers meets the
real axis it becomes two real multipliers of one sign: two roots at one
frequency ``k/2`` per rev (:func:`~tefcore.modes.matching.is_locked`) that
differ in real part, until they meet again and leave the lock as one complex
pair.  Across a lock's ends the ordinary match is not decided by a finer
step: the frequency no longer tells the roots apart, and the complex root's
shape ``a + ib`` is a combination of the two real shapes in proportions
that say nothing about identity (MAC 0.73 and 0.77 with the two of them for
the MDART flap mode leaving its 7/rev lock after GJ x 1.5, in a step of an
eighth of the figure's).
What does decide is the *plane* the two real shapes span: the complex
root's shape lies in it (:func:`~tefcore.modes.matching.plane_mac`,
1 - 4e-7 there) and in no other root's.  So a step that enters, stays in
or leaves a lock (a locked pair, :func:`~tefcore.modes.matching.locked_pairs`,
on both sides, or on one side and a complex root on the other -- a real root
alone at ``k/2`` is a lock whose partner the solver put another whole /rev
away, not a lock's end) is matched root to plane: the
cost is ``1 - plane_mac`` plus the eigenvalue distance (entering and
leaving the smaller of the two, staying the larger of the two matches in
order), and the step is decided when that is clear against every other
entry of the rows and columns involved (the ``CLEAR_COST`` and ``MARGIN``
above).  Then, by the convention above, entering, the track goes on with
the less stable real root and the other starts a track; staying, the two
real roots keep their order -- on the real axis they cannot pass each other
without meeting, which ends the lock -- so the less stable goes on with the
less stable; leaving, the merged root continues the track of the less stable
real root, which by the two rules before is the track that entered.  Rows so
decided are ``"coalescence"`` unless their ordinary match was clear too.  A
lock step the plane does not decide (another root as near, a shape out of
the plane: the step did not resolve it) keeps the ordinary decision,
``"ambiguous"``, and is refined.

:func:`follow_branch` follows one mode through a tracked table past the end
of its track (where an undecided match gave its root to another track, it
goes on with the best match and says it is no longer certain).

Each track keeps the ``label`` its mode had where the track starts; the
point's own label at each point is ``label_here``, so a label that changes
along a curve (a mode that changes character, as in a veering) is visible,
and :func:`label_changes` lists it.  :func:`follow_root` is the same
continuation for one root along a homotopy (used by
:mod:`tefcore.linear.mechanism`).

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

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .matching import (
    LOCK_TOL,
    as_point,
    decide,
    eigenvalues,
    is_clear,
    is_coalesced,
    locked_pairs,
    mac,
    match_cost,
    plane_mac,
    unwrap_frequency,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["EXCHANGE_MAC", "FollowResult", "ambiguous_steps", "follow_branch", "follow_root",
           "label_changes", "track_modes"]

#: Two tracks passing close in one step are a possible veering when one's new
#: shape carries at least this share of the other's old shape (MAC): a veering
#: exchanges the shapes (sin^2 of the turn, 0.13 over a step that spans the
#: veering of a 2 x 2 family), modes crossing without coupling keep theirs
#: (MAC between distinct MDART modes below 0.05, measured).
EXCHANGE_MAC = 0.1


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


def track_modes(points: Sequence, values=None, *, predict: bool = True,
                memo: dict | None = None) -> pd.DataFrame:
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
    memo : dict, optional
        Kept by the caller between calls on growing point sets (a sweep's
        refinement rounds, :mod:`tefcore.sweeps.table`): the march is a pass
        in the order of the points, so the state after each point is kept,
        and a later call whose first points are the very same ones resumes
        after the last of them.  The same: for a mapping point, the same
        ``modes`` and vectors objects and ``periodic``; for any other point,
        the same object; and the same value and `predict`.  Objects are
        compared by identity, so a point's data changed in place between
        calls is not seen (the sweeps give each record's point once and never
        change it).  The table is the same as without it (tested); only the
        work before the first new point is saved.

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
    import pandas as pd

    if values is None:
        values = np.arange(len(points), dtype=float)
    values = list(values)
    if len(values) != len(points):
        raise ValueError(f"{len(values)} values for {len(points)} points")
    keys = [_point_key(p, x, predict) for p, x in zip(points, values, strict=True)]
    state, start = _resume(memo, keys)
    for step in range(start, len(points)):
        if points[step] is not None:
            _track_step(state, step, points[step], values[step], predict)
        if memo is not None:
            state.saved.append(state.snapshot())
    if memo is not None:
        memo.update(keys=keys, saved=state.saved, rows=state.rows)
    if not state.rows:
        return pd.DataFrame(columns=["step", "track", "label", "label_here", "identity",
                                     "mode_id", "frequency_per_rev", "real_part"])
    return _table(state.rows).sort_values(["step", "track"], kind="stable",
                                            ignore_index=True)


class _March:
    """What :func:`track_modes` carries from one point to the next (and the rows so far)."""

    def __init__(self):
        self.tracks: list[_Track] = []
        self.alive: list[int] = []
        self.rows: list = []                               # each step's columns
        self.prev = (False, np.zeros(0, complex), None)    # periodic, eigenvalues, vectors
        self.saved: list = []                              # a snapshot after each point

    def snapshot(self):
        # a track's eig list and vec are replaced, never changed in place
        # (_Track.update): copying the tracks themselves is enough; the rows
        # only grow, so their count says which were there
        return ([_Track(t.label, t.eig, t.vec) for t in self.tracks], list(self.alive),
                len(self.rows), self.prev)

    @classmethod
    def restored(cls, saved: list, rows: list):
        """The state after the last of `saved`, the rows so far taken from `rows`."""
        out = cls()
        tracks, alive, n_rows, out.prev = saved[-1]
        out.tracks = [_Track(t.label, t.eig, t.vec) for t in tracks]
        out.alive, out.rows, out.saved = list(alive), rows[:n_rows], list(saved)
        return out


def _point_key(p, x, predict):
    """What decides a point's step of the march: its result objects (by identity),
    kind and value (a mapping's entries; any other point is itself)."""
    if isinstance(p, Mapping):
        return (p["modes"], p.get("vectors", p.get("eigenvectors")),
                bool(p.get("periodic", False)), x, predict)
    return (p, None, None, x, predict)


def _same_key(a, b) -> bool:
    return (a[0] is b[0] and a[1] is b[1] and a[2] == b[2] and a[4] == b[4]
            and (a[3] == b[3] or (a[3] != a[3] and b[3] != b[3])))


def _resume(memo, keys):
    """The march's state after the longest prefix of `keys` that `memo` holds, and
    where to go on."""
    if not memo:
        return _March(), 0
    n = 0
    for a, b in zip(memo["keys"], keys, strict=False):
        if not _same_key(a, b):
            break
        n += 1
    if n == 0:
        return _March(), 0
    return _March.restored(memo["saved"][:n], memo["rows"]), n


def _track_step(state: _March, step: int, p, x, predict: bool) -> None:
    """One point of :func:`track_modes`: its roots matched to the live tracks."""
    modes, vecs, periodic = as_point(p)
    try:
        x = float(x)
    except (TypeError, ValueError):
        x = float(step)
    tracks = state.tracks
    prev_periodic, prev_eig, prev_vecs = state.prev
    eig = eigenvalues(modes)
    col_vec = [None if vecs is None else vecs[:, j] for j in range(len(modes))]
    per = periodic or prev_periodic
    assigned, identity = _match_step(tracks, state.alive, x, predict, eig, vecs, per,
                                     (prev_eig, prev_vecs))
    tracked_eig = eig.copy()
    if per:
        for j, t in enumerate(assigned):
            if t >= 0:
                tracked_eig[j] = _unwrap(eig[j], tracks[t].predict(x, predict))
    if state.alive and len(modes):
        _flag_close_passes(identity, assigned, tracked_eig, tracks, vecs, per)
    for j in np.flatnonzero(assigned < 0):
        tracks.append(_Track(label=str(modes["label"].iloc[j])))
        assigned[j] = len(tracks) - 1
    for j, t in enumerate(assigned):
        tracks[t].update(x, tracked_eig[j], col_vec[j])
    state.alive = [int(t) for t in assigned]
    state.prev = (periodic, eig, vecs)
    state.rows.append(_step_columns(step, modes, tracked_eig, identity, assigned, tracks))


def _match_step(tracks, alive, x, predict, eig, vecs, per, prev):
    """Assign the roots of a new point to the live tracks.

    Returns ``assigned`` (a track per root, -1: none) and ``identity`` (how
    each root continues its track: ``start``, ``clear``, ``ambiguous``,
    ``coalescence``; the plane rule of a Floquet lock, :func:`_lock_steps`).
    """
    assigned = np.full(eig.size, -1)
    identity = np.full(eig.size, "start", dtype=object)
    if not (alive and eig.size):
        return assigned, identity
    pred = np.array([tracks[t].predict(x, predict) for t in alive])
    cost, shape = match_cost(pred, [tracks[t].vec for t in alive], eig, vecs,
                             per, shape_part=True)
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, cols = linear_sum_assignment(cost)
    clear, rival = decide(cost, rows, cols, shape)
    for r, c, ok in zip(rows, cols, clear, strict=True):
        assigned[c] = alive[r]
        identity[c] = "clear" if ok else "ambiguous"
    # a step into, within or out of a Floquet lock: the plane rule
    handled = _lock_steps(cost, shape, rows, cols, alive, prev, (eig, vecs), per, assigned,
                          identity)
    partner = {}
    for c, ok, k in zip(cols, clear, rival, strict=True):
        if not ok and c not in handled and k not in handled and is_coalesced(
                eig, vecs, c, k, per):
            identity[c] = "coalescence"
            partner[c] = k
    # a coalesced pair is one mode split into two roots: by convention
    # the track goes on with the less stable one (the one that matters
    # for stability), the other root takes the partner's track or a new one
    for c, k in partner.items():
        if eig[k].real > eig[c].real and identity[c] == "coalescence":
            assigned[c], assigned[k] = assigned[k], assigned[c]
            identity[k] = "coalescence"
            identity[c] = "coalescence" if assigned[c] >= 0 else "start"
    return assigned, identity


def _step_columns(step, modes, tracked_eig, identity, assigned, tracks) -> tuple:
    """One point's rows of the tracked table: ``(columns, index)``, the frame
    :func:`_table` makes of them.

    The columns are the modes table's without ``label``, ``frequency_tracked``
    after ``frequency_per_rev``, each a copy (the table, and the march a
    ``memo`` keeps, never share memory with the point): a numeric numpy
    column as an array, any other (text, objects, pandas' own dtypes) as a
    Series of its dtype, which the table keeps.  A modes table that already
    has one of the columns the tracking adds is refused, as the insertion of
    columns refused it, and so is one with a column name twice.
    """
    for name in ("frequency_tracked", "identity", "label_here", "track", "step"):
        if name in modes.columns:
            raise ValueError(f"cannot insert {name}, already exists")
    if modes.columns.has_duplicates:
        twice = sorted({str(c) for c in modes.columns[modes.columns.duplicated()]})
        raise ValueError(f"the modes table has the column(s) {twice} more than once")
    n, label = len(modes), [tracks[t].label for t in assigned]
    # step, track, label and identity as the frame of one step was given them
    # (a scalar, arrays, a list of text; their dtypes inferred), as arrays
    # where the step has rows (the joined table needs them so, and a frame
    # infers the same from them)
    cols = {"step": np.full(n, step, dtype=np.int64) if n else step,
            "track": np.array(assigned), "label": np.array(label, dtype=object) if n else label,
            "label_here": modes["label"].copy(), "identity": np.array(identity, dtype=object)}
    for name, v in modes.items():
        if name == "label":
            continue
        numeric = isinstance(v.dtype, np.dtype) and v.dtype != object
        cols[name] = v.to_numpy(copy=True) if numeric else v.copy()
        if name == "frequency_per_rev":
            cols["frequency_tracked"] = tracked_eig.imag.copy()
    return cols, modes.index


def _table(steps) -> pd.DataFrame:
    """The rows of all steps (:func:`_step_columns`) in one table, in step order.

    Where every step has rows and the same columns, each column of one kind
    (array or Series) and one dtype throughout, the columns are joined one by
    one: arrays concatenated, Series by pandas with their dtype -- the table
    that concatenating one frame per step gives, without making the frames
    (0.7 of the 1.7 s the tracking took in Fig. 15's sweep, measured at stop
    37; tested equal).  Otherwise (a dtype that changes between steps, a point
    without roots) one frame a step, concatenated as pandas resolves them.
    """
    import pandas as pd

    first = steps[0][0]
    names = list(first)

    def same(c):
        kind, dtype = type(first[c]), first[c].dtype
        return all(type(cols[c]) is kind and cols[c].dtype == dtype for cols, _ in steps)

    if all(len(idx) and list(cols) == names for cols, idx in steps) and all(map(same, names)):
        return pd.DataFrame({c: (np.concatenate([cols[c] for cols, _ in steps])
                                 if isinstance(first[c], np.ndarray)
                                 else pd.concat([cols[c] for cols, _ in steps],
                                                ignore_index=True))
                             for c in names})
    frames = [pd.DataFrame(cols, index=idx, copy=True) for cols, idx in steps]
    return pd.concat(frames, ignore_index=True)


def _lock_steps(cost, shape, rows, cols, alive, prev, new, periodic, assigned,
                identity) -> set:
    """Decide the matches of a step that enters, leaves or stays in a Floquet lock.

    The rule is in the module docstring.  `rows`, `cols`: the optimal
    assignment of `cost` (previous roots by new roots; `shape` its
    ``1 - MAC`` part); `alive`: the previous roots' tracks; `prev`, `new`:
    ``(eigenvalues, shapes)`` of the two points.  Sets `assigned` and
    `identity` in place; returns the columns decided here (no other
    coalescence convention applies to them).
    """
    if not periodic:
        return set()
    (peig, pvecs), (eig, vecs) = prev, new
    col_of = dict(zip(rows.tolist(), cols.tolist(), strict=True))
    row_of = {c: r for r, c in col_of.items()}
    eig_part = cost - np.nan_to_num(shape)
    new_pairs, old_pairs = locked_pairs(eig, True), locked_pairs(peig, True)
    handled: set = set()

    def off_plane(pair_vecs, singles):
        """Largest ``1 - plane_mac`` of the single shapes against the pair's plane."""
        if pair_vecs is None or any(v is None or v.shape[0] != pair_vecs.shape[0]
                                    for v in singles):
            return np.nan
        return max(1.0 - plane_mac(pair_vecs, v) for v in singles)

    def decided(r_idx, c_idx, own, ps):
        """Clear against every other entry of the rows and columns involved."""
        other = np.zeros(cost.shape, bool)
        other[r_idx, :] = True
        other[:, c_idx] = True
        other[np.ix_(r_idx, c_idx)] = False
        own = own + (0.0 if np.isnan(ps) else ps)
        return is_clear(own, ps, cost[other].min(initial=np.inf))

    def less_stable_first(e, i, j):
        return (i, j) if (e[i].real, -i) >= (e[j].real, -j) else (j, i)

    def old(*r):
        return None if pvecs is None else pvecs[:, list(r)]

    def now(*c):
        return None if vecs is None else vecs[:, list(c)]

    def real(e, i):
        """A real multiplier (its frequency at k/2), paired or not: a lock's
        partner may carry another whole /rev (another dominant harmonic)."""
        return abs(2 * e[i].imag - round(2 * e[i].imag)) <= 2 * LOCK_TOL

    for p, q in new_pairs:                  # entering: the root of one track -> p, q
        us = [row_of[c] for c in (p, q) if c in row_of]
        if len(us) != 1 or real(peig, us[0]):
            continue
        u = us[0]
        handled |= {p, q}
        ps = off_plane(now(p, q), [None if pvecs is None else pvecs[:, u]])
        if decided([u], [p, q], min(eig_part[u, p], eig_part[u, q]), ps):
            keep, other = less_stable_first(eig, p, q)
            assigned[keep], identity[keep] = alive[u], "coalescence"
            assigned[other], identity[other] = -1, "start"
    for a, b in old_pairs:
        cs = [col_of[r] for r in (a, b) if r in col_of]
        hi, lo = less_stable_first(peig, a, b)
        if len(cs) == 2 and tuple(sorted(cs)) in new_pairs:    # staying: a, b -> p, q
            handled |= set(cs)
            hi_n, lo_n = less_stable_first(eig, *cs)
            ps = off_plane(old(a, b), [vecs[:, hi_n], vecs[:, lo_n]] if vecs is not None
                           else [None])
            if decided([a, b], cs, max(eig_part[hi, hi_n], eig_part[lo, lo_n]), ps):
                for r, c in ((hi, hi_n), (lo, lo_n)):
                    same = assigned[c] == alive[r] and identity[c] == "clear"
                    assigned[c], identity[c] = alive[r], "clear" if same else "coalescence"
        elif cs and not any(real(eig, c) for c in cs):          # leaving: a, b -> one root
            handled |= set(cs)
            offs = [off_plane(old(a, b), [None if vecs is None else vecs[:, c]]) for c in cs]
            owns = [min(eig_part[a, c], eig_part[b, c]) for c in cs]
            i = int(np.argmin(np.add(owns, np.nan_to_num(offs))))
            if decided([a, b], [cs[i]], owns[i], offs[i]):
                for c in cs:
                    assigned[c], identity[c] = -1, "start"
                assigned[cs[i]], identity[cs[i]] = alive[hi], "coalescence"
    return handled


def _flag_close_passes(identity, assigned, eig, tracks, vecs, periodic=False) -> None:
    """Mark ``ambiguous`` the clear matches of two tracks that pass close in a step.

    Two roots whose eigenvalues, moving linearly over the step, come closer
    than either moved may have crossed or veered; the end points cannot tell
    which.  Modes that cross without coupling keep their own shapes; modes
    that veer exchange them, so each root's new shape carries some of the
    other's old one: where that exchange is at least :data:`EXCHANGE_MAC`
    (or no shapes are known), the step is bisected (:func:`tefcore.sweeps.sweep.sweep`).
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
    a, b = np.nonzero(np.triu(exchange, 1))
    if a.size:
        # every pair at once (the arithmetic of one pair, element by element:
        # the same flags; 0.4 of a 10.8 s Fig. 13 sweep in a loop over pairs)
        close = _passes_close(p0[a], p1[a], p0[b], p1[b], periodic)
        for j in np.flatnonzero(close):
            identity[js[a[j]]] = identity[js[b[j]]] = "ambiguous"


def _passes_close(a0, a1, b0, b1, periodic) -> np.ndarray:
    """Per pair: root a moving a0 -> a1 and root b moving b0 -> b1 (linearly over
    the step) come closer than either moved (:func:`_flag_close_passes`)."""
    if periodic:
        # b's start put next to a's, and b's end shifted and signed as its start
        f, b0n = b0.imag, unwrap_frequency(b0, a0, True)
        sign = np.where(np.isclose(np.mod(b0n, 1.0), np.mod(f, 1.0)), 1.0, -1.0)
        b1 = b1.real + 1j * (sign * b1.imag + (b0n - sign * f))
        b0 = b0.real + 1j * b0n
    pts = np.stack([a0, a1, b0, b1])
    # one scale for the pair: damping rates and frequencies each relative to
    # their size (as relative_distance)
    re = np.abs(pts.real)
    sr = 0.5 + 0.5 * ((((re[0] + re[1]) + re[2]) + re[3]) / 4)
    if periodic:
        si = np.full(sr.shape, 0.5)
    else:
        im = np.abs(pts.imag)
        si = 1.0 + 0.5 * ((((im[0] + im[1]) + im[2]) + im[3]) / 4)
    xr, xi = pts.real / sr, pts.imag / si
    d0r, d0i = xr[0] - xr[2], xi[0] - xi[2]
    ddr = (xr[1] - xr[0]) - (xr[3] - xr[2])
    ddi = (xi[1] - xi[0]) - (xi[3] - xi[2])
    still = (ddr == 0) & (ddi == 0)
    # |dd|^2 as the scalar code took it, libm's pow: an array's ** 2 is x * x,
    # which differs in the last bit for 0.08 % of inputs and can flip a pass
    # within an ulp of its reach
    den = np.array([math.pow(v, 2.0) for v in np.hypot(ddr, ddi).tolist()])
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        t = np.clip(-(d0r * ddr + d0i * ddi) / den, 0.0, 1.0)
    t = np.where(still, 0.0, t)
    reach = np.maximum(np.hypot(xr[1] - xr[0], xi[1] - xi[0]),
                       np.hypot(xr[3] - xr[2], xi[3] - xi[2]))
    return np.hypot(d0r + t * ddr, d0i + t * ddi) < reach


def _unwrap(eig: complex, predicted: complex) -> complex:
    """The Floquet root with its frequency in the representation nearest the predicted."""
    return complex(eig.real, unwrap_frequency(eig, predicted, True))


def follow_branch(tracked: pd.DataFrame, points: Sequence, start: tuple[int, int],
                  values=None, *, predict: bool = True) -> pd.DataFrame:
    """One mode's branch through a :func:`track_modes` table, past the end of its track.

    The branch is the track of the ``start`` row as long as the track goes
    on.  Where the track ends before the sweep does (an undecided match gave
    its root to another track, or a lock it entered as the more stable root
    ended), the branch continues with the root that matches its last row
    best (:func:`~tefcore.modes.matching.match_cost` from its extrapolated
    eigenvalue and last shape) among the next point's rows that are not a
    clear continuation of another track, and then along that root's track.
    Such a change of track is a doubt -- unless the root is the merged root
    of a lock the branch was half of (identity ``"coalescence"``), which is
    the documented convention -- and so is every ``"ambiguous"`` row; the
    branch ends only where no candidate exists.

    Parameters
    ----------
    tracked : pandas.DataFrame
        The :func:`track_modes` table of `points` (columns ``step``,
        ``track``, ``mode_id``, ``identity``, ``real_part`` and
        ``frequency_tracked``).
    points : sequence
        The points given to :func:`track_modes`.
    start : tuple of int
        ``(step, mode_id)`` of the branch's first row.
    values : sequence of float, optional
        The parameter values given to :func:`track_modes`.
    predict : bool
        Extrapolate the eigenvalue linearly from the branch's last two rows.

    Returns
    -------
    pandas.DataFrame
        One row per step from `start` while the branch goes on: ``step``,
        ``mode_id``, ``track``, ``doubt`` (this row's match into the branch
        was not decided) and ``certain`` (no doubt from the start up to here).

    Examples
    --------
    Track 0 loses its only root to track 1 in an undecided match; the
    branch goes on with it, no longer certain:

    >>> import pandas as pd
    >>> def pt(*f):
    ...     return pd.DataFrame({"mode_id": range(len(f)), "label": ["m"] * len(f),
    ...                          "frequency_per_rev": f, "real_part": [-0.1] * len(f)})
    >>> pts = [pt(1.0, 2.0), pt(1.0, 2.0), pt(1.6)]
    >>> t = track_modes(pts)
    >>> t[["step", "track", "identity"]].values.tolist()
    [[0, 0, 'start'], [0, 1, 'start'], [1, 0, 'clear'], [1, 1, 'clear'], [2, 1, 'ambiguous']]
    >>> follow_branch(t, pts, (0, 0)).values.tolist()
    [[0, 0, 0, False, True], [1, 0, 0, False, True], [2, 0, 1, True, False]]
    """
    import pandas as pd

    if values is None:
        values = np.arange(len(points), dtype=float)
    step0, mode0 = (int(v) for v in start)
    first = tracked[(tracked["step"] == step0) & (tracked["mode_id"] == mode0)]
    if first.empty:
        raise ValueError(f"no row with step {step0} and mode_id {mode0} in the table")
    track = first["track"].iloc[0]
    locked = _at_lock(first.iloc[0])
    path = [(step0, mode0, track, False)]
    branch = _Track(label="")
    branch.update(float(values[step0]), _row_eig(first.iloc[0]), _shape(points[step0], mode0))
    for step, here in tracked[tracked["step"] > step0].groupby("step", sort=True):
        mine = here[here["track"] == track]
        if mine.empty:                   # the track ended: its best match goes on
            cand = here[here["identity"] != "clear"]
            if cand.empty:
                break
            modes, vecs, periodic = as_point(points[step])
            rows = modes.index[modes["mode_id"].isin(cand["mode_id"])]
            cost = match_cost([branch.predict(float(values[step]), predict)], [branch.vec],
                              eigenvalues(modes)[rows], None if vecs is None else vecs[:, rows],
                              periodic)[0]
            best = int(modes["mode_id"].iloc[rows[int(np.argmin(cost))]])
            mine = cand[cand["mode_id"] == best]
            # no doubt only where the branch was half of a lock that ended
            # into this root (the convention); any other change of track is one
            doubt = not (mine["identity"].iloc[0] == "coalescence" and locked)
        else:
            doubt = mine["identity"].iloc[0] == "ambiguous"
        row = mine.iloc[0]
        track = row["track"]
        locked = _at_lock(row)
        path.append((int(step), int(row["mode_id"]), track, bool(doubt)))
        branch.update(float(values[step]), _row_eig(row), _shape(points[step], row["mode_id"]))
    out = pd.DataFrame(path, columns=["step", "mode_id", "track", "doubt"])
    out["certain"] = ~out["doubt"].cummax()
    return out


def _at_lock(row) -> bool:
    f = float(row["frequency_per_rev"])
    return abs(2 * f - round(2 * f)) <= 2 * LOCK_TOL


def _row_eig(row) -> complex:
    return complex(float(row["real_part"]), float(row["frequency_tracked"]))


def _shape(point, mode_id):
    modes, vecs, _ = as_point(point)
    if vecs is None:
        return None
    return vecs[:, int(np.flatnonzero(modes["mode_id"].to_numpy() == int(mode_id))[0])]


def ambiguous_steps(tracked: pd.DataFrame, kinds=("ambiguous",)) -> list[int]:
    """Steps of a :func:`track_modes` table reached by an undecided match.

    The match into such a step from the previous point was not clear: the
    interval before it is where a finer parameter step is needed.

    Parameters
    ----------
    tracked : pandas.DataFrame
        A :func:`track_modes` table.
    kinds : tuple of str, optional
        The ``identity`` values that count as undecided.

    Returns
    -------
    list of int
        The ``step`` values, sorted.
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
    import pandas as pd

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
        The parameter range.
    root : int
        Index of the root at `start`.
    periodic : bool
        Floquet exponents (:func:`eigen_distance`).
    n_steps : int
        Initial equal steps.
    first : tuple, optional
        ``solve(start)`` if already computed.
    max_halvings : int
        Halvings of a step allowed before an unclear match is accepted.

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
        ok = is_clear(cost[0, j], shape[0, j], alt)
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
