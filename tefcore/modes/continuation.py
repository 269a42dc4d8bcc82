"""Identity by continuation: the root a mode of the uncoupled system becomes.

A root's name is where it comes from.  With the blade-flap coupling scaled by
``eps`` (:func:`coupling_homotopy`: the flap row and column of ``M, C, K``),
``eps = 0`` is the uncoupled system -- the blade with the flap held at its
trimmed motion, whose roots carry the structural labels of their modal
coordinates (``blade flap 1`` ...), and the flap alone on its actuator
(``TEF``) -- where identity is exact.  :func:`continue_roots` follows every
root from ``eps = 0`` to ``eps = 1`` (the coupled system), halving a step of
``eps`` wherever a match between its ends is not decided
(:func:`tefcore.modes.tracking.track_modes`: eigenvalues compared modulo
1/rev for Floquet exponents, with the shapes), and so names each root of the
coupled system by the uncoupled mode it continues from.  The one thing
continuation cannot decide is a root that meets another on the way
(coalescence: an *exceptional point* of the two-parameter family in the
design parameter and ``eps``); such a path is reported with where it met,
never guessed.

:func:`tef_root` is the one root the uncoupled flap mode becomes: "the TEF
mode", a definition that depends on no label, participation or sweep.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..assignment import linear_sum_assignment
from ..floquet.second_order import SecondOrderSystem
from .labels import coordinate_shares, label_modes, tracking_shapes, trajectory_shapes
from .matching import (
    CLEAR_COST,
    COALESCED_DISTANCE,
    COALESCED_MAC,
    LOCK_TOL,
    MARGIN,
    mac,
    relative_distance,
)
from .tracking import follow_root

__all__ = ["FIRST_STEPS", "FLAP_ACTIVE", "MIN_STEP", "ContinuedRoots", "continue_roots",
           "coupling_homotopy", "path_shapes", "positive_roots", "root_solver", "tef_root",
           "visible_roots"]

#: Equal steps of ``eps`` the continuation starts with (each step's end is one
#: eigenproblem); a step whose matches are not all decided is halved.
FIRST_STEPS = 2

#: Smallest step of ``eps``: 1/256 (7 halvings of the first 1/2).  A match still
#: undecided at this step is a coalescence on the path (an exceptional point
#: within ~1/256 of the coupling), reported rather than refined further.
MIN_STEP = 1.0 / 4096


def positive_roots(res):
    """Positive-frequency roots, ordered like the stability table.

    Parameters
    ----------
    res : tefcore.floquet.FloquetResult
        All roots of a system.

    Returns
    -------
    tefcore.floquet.FloquetResult
        The positive-frequency member of each pair (and the real roots), by
        frequency, less damped first where two share it (a locked pair).
    """
    keep = res.positive_frequency()
    order = np.lexsort((-keep.damping_rates, np.round(keep.frequencies, 9)))
    return keep.select(order)


def visible_roots(res, n, basis):
    """Roots and displacement shapes to follow.

    With first-order (aerodynamic) states, only the roots that move the blade
    or the flap: a state decoupled from them, e.g. by a knockout, has no shape
    to compare.

    Parameters
    ----------
    res : tefcore.floquet.FloquetResult
        Roots with their eigenvectors (displacements first).
    n : int
        Number of coordinates (blade and flap).
    basis : numpy.ndarray or None
        Map from coordinates to the physical shapes compared between steps
        (:meth:`tefcore.model.coupled.CoupledModel.tracking_basis`); None:
        the coordinates themselves.

    Returns
    -------
    res : tefcore.floquet.FloquetResult
        The roots kept.
    shapes : numpy.ndarray
        Their displacement shapes, one column per root.
    """
    vec = res.eigenvectors[:n]
    shapes = vec if basis is None else basis @ vec
    if res.eigenvectors.shape[0] > 2 * n:
        size = np.linalg.norm(shapes, axis=0)
        keep = size > 1e-12 * size.max()
        res, shapes = res.select(keep), shapes[:, keep]
    return res, shapes


def root_solver(system_of_s, n, basis, n_steps):
    """``solve(s)`` for :func:`tefcore.modes.tracking.follow_root` along a homotopy.

    Parameters
    ----------
    system_of_s : callable
        ``s -> SecondOrderSystem``.
    n : int
        Number of coordinates (blade and flap).
    basis : numpy.ndarray or None
        See :func:`visible_roots`.
    n_steps : int
        Floquet steps per period of each eigenproblem.

    Returns
    -------
    callable
        ``solve(s) -> (exponents, shapes)``: the positive roots at ``s``
        (:func:`positive_roots`, :func:`visible_roots`).
    """
    def solve(s):
        res = positive_roots(system_of_s(s).modes(n_steps=n_steps, n_sub=4, participation=False))
        res, shapes = visible_roots(res, n, basis)
        return res.exponents, shapes
    return solve


def coupling_homotopy(system: SecondOrderSystem, n_blade: int, s: float) -> SecondOrderSystem:
    """``system`` with every blade-flap coupling block scaled by ``s``.

    ``s = 0`` is the uncoupled blade and the flap on its actuator (with its
    own aerodynamic and centrifugal springs); ``s = 1`` the coupled system.

    Aerodynamic states (first-order, after the flap) go with the blade: their
    couplings with the flap are scaled too, so at ``s = 0`` the flap has its
    instantaneous airloads only (docs/theory.md 10.1).

    Parameters
    ----------
    system : tefcore.floquet.second_order.SecondOrderSystem
        Blade coordinates first, the flap last.
    n_blade : int
        Number of blade coordinates.
    s : float
        Coupling scale, 0 (uncoupled) to 1 (coupled).

    Returns
    -------
    tefcore.floquet.second_order.SecondOrderSystem
    """
    nd = system.n_dof
    mats = []
    for a in (system.m, system.c, system.k):
        b = a.copy()
        b[..., :n_blade, n_blade:nd] *= s
        b[..., n_blade:nd, :n_blade] *= s
        if system.n_first:
            b[..., nd:, n_blade:nd] *= s
            b[..., n_blade:nd, nd:] *= s
        mats.append(b)
    return SecondOrderSystem(*mats, n_first=system.n_first)


def tef_root(system: SecondOrderSystem, *, basis=None, n_steps: int = 72):
    """The root that the uncoupled flap mode becomes in the coupled system.

    At zero coupling (:func:`coupling_homotopy`) the flap's roots are the
    ones whose shape is the flap alone; the least damped of them (a locked
    pair has two) is followed by continuation to the full coupling.  This is
    the anchor of "the TEF mode": a definition that does not depend on
    labels, participations or a sweep.

    Parameters
    ----------
    system : SecondOrderSystem
        Blade coordinates first, the flap last.
    basis : ndarray, optional
        Map from coordinates to the shapes compared between steps
        (:meth:`tefcore.model.coupled.CoupledModel.tracking_basis`).
    n_steps : int, optional
        Floquet steps per period of each eigenproblem on the path.

    Returns
    -------
    eigenvalue : complex
        The TEF root of ``system`` (positive frequency).
    follow : FollowResult
        The continuation (``follow.clear`` False where it met a coalescence).
    """
    n = system.n_dof
    solve = root_solver(lambda s: coupling_homotopy(system, n - 1, s), n, basis, n_steps)
    raw, vec0 = visible_roots(positive_roots(coupling_homotopy(system, n - 1, 0.0).modes(
        n_steps=n_steps, n_sub=4, participation=False)), n, basis)
    eig0 = raw.exponents
    share = np.abs(raw.eigenvectors[n - 1]) ** 2 + np.abs(raw.eigenvectors[2 * n - 1]) ** 2
    share = share / np.sum(np.abs(raw.eigenvectors) ** 2, axis=0)
    flap = np.flatnonzero(share >= 0.5 * share.max())
    start = int(flap[np.argmax(eig0[flap].real)])
    follow = follow_root(solve, 0.0, 1.0, start, periodic=system.periodic, first=(eig0, vec0))
    return follow.eigenvalue, follow


# ------------------------------------------------------------------ all roots


#: Least share of a root's kinematic motion (squared) in the flap's trailing edge
#: (the last row of :meth:`tefcore.model.coupled.CoupledModel.tracking_basis`) for
#: the root to take part in the blade-flap coupling.  Measured on MDART: the blade's
#: low modes carry 1e-8 to 1e-2 (torsion 1 at c_cg 0.33, mu 0.3: 2e-2 at full
#: coupling, 1e-4 at half), the roots the flap moves 5e-2 to 1.
FLAP_ACTIVE = 1e-2


def path_shapes(basis, res, n, periodic, samples=72):
    """The shapes paths are matched by.

    Floquet roots: their motion over the revolution
    (:func:`tefcore.modes.labels.trajectory_shapes`), free of the frequency
    convention; constant coefficients: displacement and velocity shapes
    (:func:`tefcore.modes.labels.tracking_shapes`).

    Parameters
    ----------
    basis : numpy.ndarray
        Map from coordinates to physical shapes.
    res : tefcore.floquet.FloquetResult
        The roots (with their periodic shapes when `periodic`).
    n : int
        Number of coordinates.
    periodic : bool
        Floquet exponents.
    samples : int, optional
        Azimuths sampled (Floquet): the path's grid, which must divide the
        grid of every result compared.

    Returns
    -------
    numpy.ndarray
        One column per root.
    """
    if not periodic:
        return tracking_shapes(basis, res, n)
    # every azimuth of the path's grid (72 by default; a grid refined by
    # step doubling is sampled at the same azimuths): the motion of a root at
    # 16 /rev sampled at 8 azimuths aliased to that of one at 3 /rev (MAC 0.93
    # between MDART's TEF and first torsion roots at Fig. 14's 0.08 span,
    # measured), at 72 it is resolved up to 36 /rev
    return trajectory_shapes(basis, res, n, samples=samples)


def _flap_share(vecs, n_phys):
    """Each root's kinematic share in the flap (the basis' last row) over its shape's blocks."""
    blocks = vecs.reshape(-1, n_phys, vecs.shape[-1])
    total = np.sum(np.abs(blocks) ** 2, axis=(0, 1))
    return np.sum(np.abs(blocks[:, -1]) ** 2, axis=0) / np.maximum(total, np.finfo(float).tiny)


def _solve(system, n, eps, periodic, n_steps, participation=False):
    """Positive roots of the system at coupling `eps` (Floquet: one grid, shapes)."""
    s = coupling_homotopy(system, n - 1, eps)
    if periodic:
        # n_sub=1: the lift's K chosen as for the point's own roots (raised
        # until the most damped root is resolved)
        res = s.modes(n_steps=n_steps, n_sub=1, shapes=True, participation=participation,
                      atol=None)
    else:
        res = s.modes()
    if participation and res.participation is None:
        res = res.with_participation()
    return positive_roots(res)


def _path_step(system, n, eps, n_steps, basis):
    """The roots at coupling `eps` as a path step compares them: exponents and shapes.

    Floquet: :meth:`~tefcore.floquet.second_order.SecondOrderSystem.motions`
    on one grid of `n_steps` -- the exponents on the principal branch (the
    march unwraps them along each path) and each root's motion over the
    revolution through `basis`, the shapes :func:`path_shapes` gives a full
    result, without the harmonic analysis and participation a path step does
    not use (3.6 against 6.6 ms an eigenproblem, measured on MDART at mu = 0.3).
    Constant coefficients: the positive roots and :func:`path_shapes`.
    """
    if not system.periodic:
        res = _solve(system, n, eps, False, n_steps)
        return res.exponents, path_shapes(basis, res, n, False, n_steps)
    eta, x = coupling_homotopy(system, n - 1, eps).motions(n_steps=n_steps, n_sub=1)
    order = np.lexsort((-eta.real, np.round(eta.imag, 9)))
    shapes = basis @ x[:, :n, order]                     # (azimuths, n_phys, roots)
    return eta[order], shapes.reshape(-1, order.size)


@dataclass
class ContinuedRoots:
    """The identity of a coupled system's roots by continuation from zero coupling.

    Attributes
    ----------
    origin : list of str
        Per root (in the order given to :func:`continue_roots`): the
        uncoupled mode it continues from.
    certain : numpy.ndarray of bool
        Per root: every step of its path was decided (and, in forward flight,
        its match to the guide's root).
    uncoupled : numpy.ndarray of complex
        Per root: the root of the uncoupled system it continues from (for a
        blade root, the root of the blade with the flap held at its trimmed
        motion; for the TEF, the flap alone) [/rev]; NaN where there is none.
    meetings : pandas.DataFrame
        Where two paths of different uncoupled modes met and could not be
        told apart at the smallest step (:data:`MIN_STEP`): ``eps`` and the two
        ``origins`` -- an exceptional point of the family within that step.
    n_solves : int
        Eigenproblems solved for the path: ``eps = 0`` and each step's end
        once (a step halved and retried reuses its end; the coupled system's
        roots count only when they were not given, ``final``).
    flap_motion : numpy.ndarray
        Per root: the share of its kinematic motion (squared) in the flap's
        trailing edge (:data:`FLAP_ACTIVE`).
    """

    origin: list
    certain: np.ndarray
    uncoupled: np.ndarray
    meetings: pd.DataFrame
    n_solves: int
    flap_motion: np.ndarray


def continue_roots(system: SecondOrderSystem, labels, final=None, *, basis=None,
                   final_labels=None, final_shares=None, first_steps: int = FIRST_STEPS,
                   min_step: float = MIN_STEP, n_steps: int = 72) -> ContinuedRoots:
    """Name every root of the coupled system by the uncoupled mode it continues from.

    **Constant coefficients (hover).**  The roots at ``eps = 0`` are named
    by the coordinates they carry (:func:`tefcore.modes.labels.label_modes`:
    the blade's by their structural labels, the flap's ``TEF`` -- exact, the
    two blocks being decoupled) and marched to ``eps = 1``: at each step all
    roots of the new ``eps`` are assigned to the paths (shapes by MAC,
    eigenvalues extrapolated linearly along each path; the assignment of
    least total cost).  A step whose assignment is not decided for some path
    (its shape changed by more than :data:`tefcore.modes.matching.CLEAR_COST`
    over the step, or an assignment without its match within
    :data:`tefcore.modes.matching.MARGIN` of the best, :func:`_regrets`;
    or, where the eigenvalues alone decide, :func:`_nearest_clear`) is
    halved, down to `min_step`; a
    decided step lets the next one double, up to ``1 / first_steps``.  A
    rival that continues the *same* uncoupled mode (``X`` and ``X (locked)``,
    the two real roots of an overdamped pair) does not make a step undecided.
    A match still undecided at `min_step` between two different uncoupled
    modes is two paths meeting -- an exceptional point of the family -- and
    goes into ``meetings``; the roots there keep the assignment of least cost
    and are not ``certain``.

    **Periodic coefficients (forward flight).**  The same march on the
    Floquet roots, with two differences.  Their frequencies are known modulo
    1/rev and up to the sign, so the shapes compared are the roots' motion
    over the revolution (:func:`path_shapes`), which no convention changes.
    And the blade's low modes sit in frequency locks (pairs of real
    multipliers at ``k/2`` /rev) whose roots meet and part along ``eps``
    although the flap takes no part in them: an undecided match in which a
    root carries less than :data:`FLAP_ACTIVE` of its motion in the flap is
    not refined; at the end the roots that do not move the flap are named by
    the coordinate they carry (their participation, ``final_labels``) --
    what the coupling through the flap cannot have changed -- and the moving
    roots keep their paths' names, or take the names left.

    Parameters
    ----------
    system : tefcore.floquet.second_order.SecondOrderSystem
        The coupled system, blade coordinates first and the flap last.
    labels : list of str
        The coordinates' labels (blade modes, then ``TEF``).
    final : tefcore.floquet.FloquetResult, optional
        The coupled system's roots as solved elsewhere (positive frequency,
        in the order of the modes table; with their periodic shapes in
        forward flight): the result is per root of it.  Default: the positive
        roots of `system`, solved here.
    basis : numpy.ndarray, optional
        Map from coordinates to physical shapes (default: the coordinates;
        its last row the flap's motion, as in
        :meth:`tefcore.model.coupled.CoupledModel.tracking_basis`).
    final_labels : list of str, optional
        The coordinate each root of `final` carries most (its participation
        label): the name of a root that passed through a lock of the blade.
    final_shares : numpy.ndarray, optional
        The coordinates' shares of participation in each root of `final`
        (coordinates x roots, :func:`tefcore.modes.labels.coordinate_shares`).
        Given, the roots that do not move the flap are named among themselves
        by the blade coordinate they carry (:func:`_free_labels`), not by
        `final_labels`' assignment over all roots, in which a root sharing a
        coordinate with a flap root can be left the second one it carries.
    first_steps : int, optional
        ``1 / first_steps`` is the first and the longest step of ``eps``.
    min_step : float, optional
        Smallest step of ``eps``.
    n_steps : int, optional
        Floquet steps per period of each eigenproblem on the path (forward
        flight; no error control: identity needs the roots told apart, not
        converged).

    Returns
    -------
    ContinuedRoots

    Examples
    --------
    Two oscillators, 1 and 2 rad/rev, coupled through the second ("flap")
    coordinate: the coupled roots keep their origins.

    >>> import numpy as np
    >>> from tefcore.floquet.second_order import SecondOrderSystem
    >>> m = np.eye(2)[None]
    >>> c = 0.02 * np.eye(2)[None]
    >>> k = np.array([[[1.0, 0.3], [0.3, 4.0]]])
    >>> out = continue_roots(SecondOrderSystem(m, c, k), ["blade flap 1", "TEF"])
    >>> out.origin, out.certain.tolist()
    (['blade flap 1', 'TEF'], [True, True])
    """
    n = system.n_dof
    basis = np.eye(n) if basis is None else basis
    per = system.periodic
    res0 = _solve(system, n, 0.0, per, n_steps, participation=True)
    if system.n_first:
        return _by_participation(res0, n, labels, basis, final, final_labels)
    frac0 = coordinate_shares(res0.participation, n)
    vec0 = path_shapes(basis, res0, n, per, n_steps)
    names0 = label_modes(frac0, labels, res0.frequencies, res0.damping_rates, vec0,
                         periodic=per)
    march = _March(res0.exponents, vec0, names0, basis.shape[0], per)
    h_max, eps, h, n_solves = 1.0 / first_steps, 0.0, 1.0 / first_steps, 1
    solved: dict = {}                  # eps -> the roots there, for steps retried
    streak = 2                         # clear steps since the last halving
    while eps < 1.0 - 1e-12:
        h = min(h, 1.0 - eps)
        if eps + h == 1.0 and final is not None:
            eig, vecs = final.exponents, path_shapes(basis, final, n, per, n_steps)
        elif eps + h in solved:
            eig, vecs = solved[eps + h]
        else:
            # a step that was halved comes back to its end: solved once (ends
            # are dyadic, so equal as floats; measured on Fig. 9's sweep: 45
            # eigenproblems on the paths instead of 66 over 11 points)
            eig, vecs = solved[eps + h] = _path_step(system, n, eps + h, n_steps, basis)
            n_solves += 1
        if march.step(eps + h, eig, vecs, final_step=h <= min_step * (1 + 1e-9)):
            eps += h
            streak = streak + 1 if march.last_clear else 0
            if streak >= 2:            # a step that had to be halved is not doubled at once
                h = min(2 * h, h_max)
        else:
            h *= 0.5
            streak = 0
    origin, uncoupled, certain = list(march.origin), march.start.copy(), ~march.doubt
    motion = _flap_share(march.vecs, basis.shape[0])
    if final_labels is not None and per:
        carried = list(final_labels)
        if final_shares is not None:
            carried = _free_labels(carried, motion, final_shares, labels)
        origin, changed = _flap_free_by_participation(origin, motion, carried)
        certain = certain & ~changed
        held = dict(zip(names0, res0.exponents, strict=True))
        uncoupled = np.array([held.get(o, held.get(_base_name(o), np.nan)) for o in origin],
                             complex)
    meetings = _renamed_meetings(march, origin)
    return ContinuedRoots(origin=origin, certain=certain, uncoupled=uncoupled,
                          meetings=meetings, n_solves=n_solves, flap_motion=motion)


#: Least share of a root's participation in the blade and flap states for it to
#: be a root of the blade and flap, not of the aerodynamic states (as in
#: :func:`tefcore.linear.stability.stability`).
_STRUCTURAL = 0.5


def _base_name(name: str) -> str:
    """A name without its locked-partner suffix."""
    return name.removesuffix(" (locked)")


def _renamed_meetings(march, names) -> pd.DataFrame:
    """The march's meetings between the roots the two paths end on, by their final names.

    A path that passed a flap-free root (not refined, put right by
    :func:`_flap_free_by_participation`) carries another name than its root
    gets; the meeting is between the roots, so it takes their names.  Two
    roots that end as one mode's pair (``X``, ``X (locked)``: a lock entered
    there) did not meet another mode.
    """
    final = {int(p): _base_name(n) for p, n in zip(march.pid, names, strict=True)}
    rows = []
    for m in march.meetings:
        a, b = (final.get(p, n) for n, p in m["paths"].items())
        if a != b:
            rows.append({"eps": m["eps"], "origins": " / ".join(sorted((a, b))),
                         "gap": m["gap"], "mac": m["mac"]})
    meetings = pd.DataFrame(rows, columns=["eps", "origins", "gap", "mac"])
    return meetings.drop_duplicates("origins", keep="first").reset_index(drop=True)


def _free_labels(carried, motion, shares, labels):
    """Participation labels in which a root that does not move the flap keeps its own coordinate.

    The one-to-one assignment over all roots (:func:`label_modes`) gives
    every coordinate to one root; where a flap root carries a blade
    coordinate too, a flap-free root can be left its second coordinate
    (measured: mdart-fig6, Fig. 14 at a flap length of 0.22 R, the blade
    torsion 1 root -- torsion 1 coordinate 0.41, flap 3 0.35 -- was named
    blade flap 3 because the TEF root took torsion 1).  The flap-free roots
    are the blade's own roots: one whose largest blade coordinate went to a
    root that moves the flap takes it back (the moving roots are named by
    their paths).  Lock partners (``(locked)``) keep their labels.
    """
    free = np.asarray(motion) < FLAP_ACTIVE
    out = list(carried)
    holder = {name: j for j, name in enumerate(out)}
    blade = list(labels[:-1])                   # the flap is the last coordinate
    for j in np.flatnonzero(free):
        own = blade[int(np.argmax(shares[:len(blade), j]))]
        k = holder.get(own)
        if out[j] == own or out[j].endswith("(locked)") or k is None or free[k]:
            continue
        out[j], out[k] = own, out[j]            # the moving root's label only a fallback
        holder[own], holder[out[k]] = j, k
    return out


def _flap_free_by_participation(origin, motion, carried):
    """Floquet roots that do not move the flap named by their coordinate; the rest by path.

    The coupling moves a root in proportion to its motion of the flap: a root
    of the coupled system that does not move it (``motion <``
    :data:`FLAP_ACTIVE`) is the blade's own root of the coordinate it carries
    (its participation label), whatever path the march took among the
    blade's locks and near-degenerate roots, where the Floquet frequencies of
    roots far apart in /rev coincide modulo 1/rev.  The roots that move the
    flap keep the names their paths brought; one whose name a flap-free root
    took gets, of the names left, its own coordinate's or the first.

    Parameters
    ----------
    origin : list of str
        Each root's name by its path.
    motion : numpy.ndarray
        Each root's kinematic share of the flap.
    carried : list of str
        Each root's participation label.

    Returns
    -------
    names : list of str
    changed : numpy.ndarray of bool
        The roots that move the flap whose path's name was taken.
    """
    free = np.asarray(motion) < FLAP_ACTIVE
    names = [str(c) if f else o for o, c, f in zip(origin, carried, free, strict=True)]
    # the names left for the moving roots: not a mode a flap-free root already
    # is (nor its lock partner's name: the pair that left its lock is one root)
    taken = {_base_name(names[i]) for i in np.flatnonzero(free)}
    left = [o for o in origin if o and _base_name(o) not in taken]   # "": unexplained
    changed = np.zeros(len(origin), bool)
    active = np.flatnonzero(~free)
    if not active.size:
        return names, changed
    # names of the moving roots: its own path's (0), its own coordinate's (1),
    # any other left (2) -- the assignment of least total cost
    # each name once (a moving root's coordinate can be another's path name:
    # given twice, two roots took it -- measured on mdart-fig6, Fig. 14 at
    # 0.22 R); the repeats stay at the end, dearest, so it is never short of names
    offered = left + [str(carried[i]) for i in active]
    pool = list(dict.fromkeys(offered))
    repeat = len(pool)
    pool += [n for k, n in enumerate(offered) if n in offered[:k]]
    cost = np.array([[3.0 if k >= repeat else 0.0 if n and n == origin[i] else 1.0
                      if _base_name(n) == _base_name(str(carried[i])) else 2.0
                      for k, n in enumerate(pool)] for i in active])
    rows, cols = linear_sum_assignment(cost)
    for r, c in zip(rows, cols, strict=True):
        i = active[r]
        names[i] = pool[c]
        changed[i] = pool[c] != origin[i]
    return names, changed


def _by_participation(res0, n, labels, basis, final, final_labels) -> ContinuedRoots:
    """Names with aerodynamic states: the coordinate each root carries, compared by name.

    The shed wake's roots come in near-repeated families that no continuation
    step separates; with them, the roots keep their participation labels
    (``final_labels``) and are compared with the uncoupled root of the same
    name (the flap held: the blade's roots with their aerodynamic states).
    """
    mag = np.abs(res0.participation)
    keep = mag[:2 * n].sum(axis=0) >= _STRUCTURAL * mag.sum(axis=0)
    res0 = res0.select(keep)
    names0 = label_modes(coordinate_shares(res0.participation, n), labels, res0.frequencies,
                         res0.damping_rates, tracking_shapes(basis, res0, n),
                         periodic=res0.shapes is not None)
    held = dict(zip(names0, res0.exponents, strict=True))
    names = [str(x) for x in final_labels]
    uncoupled = np.array([held.get(x, held.get(x.removesuffix(" (locked)"), np.nan))
                          for x in names], complex)
    return ContinuedRoots(origin=names, certain=np.zeros(len(names), bool),
                          uncoupled=uncoupled,
                          meetings=pd.DataFrame(columns=["eps", "origins"]), n_solves=1,
                          flap_motion=_flap_share(tracking_shapes(basis, final, n),
                                                  basis.shape[0]))


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
    fold = _fold(eig)
    tol = 10 * LOCK_TOL
    at_half = np.minimum(fold, 0.5 - fold) <= tol
    pair = np.abs(fold[:, None] - fold[None, :]) <= tol
    np.fill_diagonal(pair, False)
    return at_half & pair.any(axis=1)


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


def _assign(cost, path_lock, root_lock):
    """Least-cost assignment of paths (rows) to roots (columns).

    Where the counts differ (a pair entering or leaving a lock at ``k/2``),
    only a path near a lock ends and only a root near one appears.
    """
    p, r = cost.shape
    if p == r:
        return linear_sum_assignment(cost)
    rows, cols = linear_sum_assignment(_padded(cost, path_lock, root_lock))
    keep = (rows < p) & (cols < r)
    return rows[keep], cols[keep]


def _regrets(cost, path_lock, root_lock, rows, cols):
    """Per assigned pair: how much dearer the best assignment without it is.

    The match of path ``r`` to root ``c`` is decided by the whole step, not
    by its row and column alone: a veering pair whose two matches are each
    near their rivals (costs 0.07 and 0.28 against 0.10 and 0.40, measured on
    Fig. 9's c_cg 0.12 at eps 0.53) can still have a swap that costs 0.5
    more.  The regret is the least-cost assignment with ``(r, c)`` forbidden,
    less the optimum (every rearrangement: swaps, rotations of three, a path
    ending at a lock).
    """
    full = _padded(cost, path_lock, root_lock)
    best = full[linear_sum_assignment(full)].sum()
    out = []
    for r, c in zip(rows, cols, strict=True):
        alt = full.copy()
        alt[r, c] = _FORBIDDEN
        out.append(float(alt[linear_sum_assignment(alt)].sum() - best))
    return np.array(out)


#: A cost no assignment takes (above any sum of :data:`_UNEXPLAINED`).
_FORBIDDEN = 1e6


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


def _rivals(cost, rows, cols):
    """Per assigned pair: the column of the path's next best root (-1: none)."""
    rows, cols = np.asarray(rows, int), np.asarray(cols, int)
    if cost.shape[1] < 2:
        return [-1] * rows.size
    other = cost.astype(float)
    other[rows, cols] = np.inf
    return np.argmin(other[rows], axis=1).tolist()


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


class _March:
    """The paths of all roots along ``eps``: their origins, last roots and doubts.

    ``doubt``: the path met another mode's (an exceptional point); ``lock``:
    the path passed an undecided match among roots the flap takes no part in
    (a frequency lock of the blade, named by participation at the end).
    """

    def __init__(self, eig, vecs, names, n_phys, periodic):
        self.eig, self.vecs = np.asarray(eig, complex), vecs
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
        return _base_name(self.origin[i])

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

    def _costs(self, pred, eig, vecs):
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
        a = (np.swapaxes(self.vecs.reshape(samples, n_phys, -1), 1, 2).conj()
             * np.exp(1j * np.outer(psi, self.eig.imag))[:, :, None])
        b = vecs.reshape(samples, n_phys, -1)
        turn = np.exp(-1j * np.outer(psi, eig.imag))[:, None, :]
        norm = (np.sum(np.abs(self.vecs) ** 2, axis=0)[:, None]
                * np.sum(np.abs(vecs) ** 2, axis=0)[None, :])
        rows, cols = np.indices(norm.shape)
        out = []
        # the root (f + j, its motion) and its conjugate (-f + j', the conjugate motion)
        for sign, other in ((1.0, b * turn), (-1.0, b.conj() * turn.conj())):
            shift = np.round(q - sign * f)
            harm = np.fft.fft(a @ other, axis=0)          # (harmonics, paths, roots)
            num = np.abs(harm[shift.astype(int) % samples, rows, cols]) ** 2
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
        cost, shape, seen, flip = self._costs(pred, eig, vecs)
        path_lock, root_lock = _near_lock(pred, self.periodic), _near_lock(eig, self.periodic)
        rows, cols = _assign(cost, path_lock, root_lock)
        rival = _rivals(cost, rows, cols)
        # clear: the root's shape is resolved by the step (its own 1 - MAC at
        # most CLEAR_COST) and no rearrangement of the step is within MARGIN of
        # the assignment (tefcore.modes.matching: a quarter of a MAC)
        regret = _regrets(cost, path_lock, root_lock, rows, cols)
        clear = [bool(shape[r, c] <= CLEAR_COST and g >= MARGIN)
                 for r, c, g in zip(rows, cols, regret, strict=True)]
        near = _nearest_clear(np.abs(seen - pred[:, None]), rows, cols)
        clear = [a or b for a, b in zip(clear, near, strict=True)]
        path_of = dict(zip(cols, rows, strict=True))
        active = _flap_share(vecs, self.n_phys) >= FLAP_ACTIVE
        meet, lock = [], []
        for r, c, ok, k in zip(rows, cols, clear, rival, strict=True):
            other = path_of.get(k)
            if ok or (other is not None and self._base(other) == self._base(r)):
                continue
            if self.periodic and not (active[c] and k >= 0 and active[k]):
                # two roots that do not both move the flap: not refined.  The
                # coupling moves a root in proportion to its motion of the flap,
                # so a root that does not move it is the blade's own and is named
                # by participation at the end, which also gives a moving root
                # the name left when the two swapped here
                # (_flap_free_by_participation); only two moving roots need the
                # step resolved.  (Measured on Fig. 9's sweep: 312 eigenproblems
                # on the paths with every such pair refined, 132 without; the
                # names of the moving roots unchanged.)
                lock.append((r, other))
            else:
                meet.append((r, other))
        self.last_clear = not meet
        if meet and not final_step:
            return False
        self._accept(eps, seen, flip, vecs, rows, cols, meet, lock, eig)
        return True

    def _accept(self, eps, seen, flip, vecs, rows, cols, meet, lock, raw):
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
                self.meetings.append({"eps": eps, "origins": " / ".join(pair),
                                      "gap": gap, "mac": shape,
                                      "paths": {self._base(r): int(self.pid[r]),
                                                self._base(other): int(self.pid[other])}})
        assigned = np.isin(np.arange(eig.size), cols)
        for c in np.flatnonzero(~assigned):
            pid[c], self.next_pid = self.next_pid, self.next_pid + 1
            # a root that appears: a pair became two real roots (a lock at k/2,
            # or an overdamped pair): it is the second root of its partner,
            # the assigned root at its frequency (folded into [0, 1/2])
            near = _lock_partner(raw, c, assigned, self.periodic)
            if near is None:
                origin[c], doubt[c], last[c] = "", True, eig[c]     # unexplained
                continue
            origin[c] = _base_name(origin[near]) + " (locked)"
            start[c], doubt[c], last[c] = start[near], doubt[near], eig[c]
            locked[[c, near]] = True
        self.before = (self.eps, last)
        self.eps, self.eig, self.vecs = eps, eig, vecs
        self.origin, self.start, self.doubt, self.lock = origin, start, doubt, locked
        self.pid = pid
