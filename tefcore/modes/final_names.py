"""Names at full coupling for the roots the march does not decide (Floquet).

Private to :mod:`tefcore.modes.continuation`.  The coupling moves a root in
proportion to its motion of the flap: a root of the coupled system that does
not move it is the blade's own root of the coordinate it carries, named by
participation (:func:`free_labels`, :func:`flap_free_by_participation`); the
roots that move the flap keep their paths' names.  A lock's second root no
path explains is named beside its partner (:func:`second_roots_of_locks`),
and every locked pair is named as one mode's pair (:func:`name_lock_pairs`).
"""

from __future__ import annotations

import numpy as np

from .march import FLAP_ACTIVE, lock_matrix, same_lock
from .names import TEF_NAME, base_name, is_locked, is_tef, locked_name

__all__ = ["flap_free_by_participation", "free_labels", "name_lock_pairs",
           "second_roots_of_locks"]


def free_labels(carried, motion, shares, labels, eig=None):
    """Participation labels in which a root that does not move the flap keeps its own coordinate.

    The one-to-one assignment over all roots (:func:`tefcore.modes.labels.label_modes`) gives
    every coordinate to one root; where a flap root carries a blade
    coordinate too, a flap-free root can be left its second coordinate
    (measured: mdart-fig6, Fig. 14 at a flap length of 0.22 R, the blade
    torsion 1 root -- torsion 1 coordinate 0.41, flap 3 0.35 -- was named
    blade flap 3 because the TEF root took torsion 1).  The flap-free roots
    are the blade's own roots: one whose largest blade coordinate went to a
    root that moves the flap takes it back (the moving roots are named by
    their paths).  Lock partners (``(locked)``) keep their labels.  A root
    that does not move the flap is never the flap's mode: one the assignment
    left the flap's label (the flap's own root split into a locked pair that
    took two labels) is the second root of its blade coordinate's lock when
    the root holding that coordinate is its lock partner (`eig`; measured on
    Fig. 12 at 56 ft-lb/rad: the second real root of blade flap 1's lock at
    1 /rev, flap motion 1e-4, had been named TEF).

    Parameters
    ----------
    carried : list of str
        Each root's participation label
        (:func:`tefcore.modes.labels.label_modes`).
    motion : numpy.ndarray
        Each root's kinematic share of the flap
        (:func:`tefcore.modes.march.flap_share`).
    shares : numpy.ndarray
        The coordinates' shares of participation in each root (coordinates
        x roots, the flap last).
    labels : list of str
        The coordinates' labels (blade modes, then the flap's).
    eig : numpy.ndarray of complex, optional
        The roots' exponents [/rev], to tell a lock's partner.

    Returns
    -------
    list of str
        The labels, each root's.
    """
    free = np.asarray(motion) < FLAP_ACTIVE
    out = list(carried)
    holder = {name: j for j, name in enumerate(out)}
    blade = list(labels[:-1])                   # the flap is the last coordinate
    for j in np.flatnonzero(free):
        own = blade[int(np.argmax(shares[:len(blade), j]))]
        k = holder.get(own)
        if is_tef(out[j]) and k is not None and free[k]:
            second = locked_name(own)
            if eig is not None and same_lock(eig, j, k) and second not in holder:
                holder.pop(out[j], None)
                out[j] = second
                holder[second] = j
            continue
        if out[j] == own or is_locked(out[j]) or k is None or free[k]:
            continue
        out[j], out[k] = own, out[j]            # the moving root's label only a fallback
        holder[own], holder[out[k]] = j, k
    return _one_plain_per_lock(out, free, eig)


def _one_plain_per_lock(out, free, eig):
    """Two flap-free roots left one lock label ``X (locked)``: the less damped is ``X``.

    The one-to-one participation labels can give ``X`` to a root that moves
    the flap (it carries X too) and ``X (locked)`` to both real roots of X's
    own lock (measured on Fig. 12 at 41.4 ft-lb/rad: the two roots at 1 /rev
    both 'blade flap 1 (locked)', the flutter root 'blade flap 1').  A root
    that moves the flap is named by its path, its label only a fallback, so
    it takes the lock label and the lock's less damped root (the convention
    of :func:`tefcore.modes.labels.label_modes`) the plain one.
    """
    for name in sorted(set(out)):
        same = [j for j in np.flatnonzero(free) if out[j] == name]
        if len(same) < 2 or not is_locked(name):
            continue
        plain = base_name(name)
        k = next((i for i, x in enumerate(out) if x == plain), None)
        if k is not None and free[k]:
            continue
        j = max(same, key=lambda i: eig[i].real) if eig is not None else same[0]
        if k is not None:
            out[k] = name
        out[j] = plain
    return out


def second_roots_of_locks(names, paths, eig):
    """A root no path explains, or named twice, beside its lock partner: ``X (locked)``.

    A lock whose two real roots both came without a path (the path of their
    mode ended where the pair locked, e.g. the heavily damped flap mode at a
    soft actuator) leaves the second root to the fallback labels, which can
    repeat a name (measured on Fig. 12 at 41.4 ft-lb/rad: the TEF's two real
    roots at 3.5 and 4.5 /rev -- one multiplier pair on the negative axis --
    named TEF and 'blade flap 1 (locked)' beside the two roots of blade flap
    1's own lock).  Such a root, at the frequency (modulo 1/rev and sign) of
    a root named ``X`` at ``k/2``, is ``X (locked)`` when that name is free.

    Parameters
    ----------
    names : list of str
        The roots' names.
    paths : list of str
        Their paths' names (``""``: a root no path explains).
    eig : numpy.ndarray of complex
        Their exponents [/rev].

    Returns
    -------
    names : list of str
    renamed : numpy.ndarray of bool
    """
    eig = np.asarray(eig, complex)
    names = list(names)
    renamed = np.zeros(len(names), bool)
    for i, name in enumerate(names):
        if names.count(name) == 1 and paths[i]:
            continue
        partners = [p for p in range(len(names)) if same_lock(eig, i, p)
                    and not is_locked(names[p]) and names[p] != name]
        if not partners:
            continue
        p = min(partners, key=lambda q: abs(eig[q].real - eig[i].real))
        second = locked_name(names[p])
        if second not in names:
            names[i] = second
            renamed[i] = True
    return names, renamed


def _lock_pairs(members, names, eig):
    """The pairs of one lock class: roots of one name first, the rest by real part.

    A class is the real roots at one ``k/2`` (multipliers of one sign); each
    complex pair that locked gave two of them.  Two roots already of one name
    are a pair; the others are paired in order of their real parts (the two
    of a pair share the complex root's decay before it split, so they lie
    next to each other), which depends on no eigensolver's order.
    """
    members = sorted(members, key=lambda i: (eig[i].real, i))
    pairs, left = [], []
    for base in dict.fromkeys(base_name(names[i]) for i in members):
        same = [i for i in members if base and base_name(names[i]) == base]
        while len(same) >= 2:
            pairs.append((same.pop(0), same.pop(0)))
        left += same
    left += [i for i in members if not base_name(names[i])]
    left.sort(key=lambda i: (eig[i].real, i))
    pairs += [(left[k], left[k + 1]) for k in range(0, len(left) - 1, 2)]
    return pairs


def name_lock_pairs(names, eig, motion):
    """Every locked pair named as one mode's pair, ``X`` and ``X (locked)``.

    The two real roots of a lock at ``k/2`` are one complex pair of the
    coupled system that locked: one mode.  Which of the two a path reached is
    decided by round-off (both lie at the same distance from the complex root
    they split from), so a pair is named as a pair, never root by root: the
    name ``X`` both its roots' paths agree on; where they disagree (one path
    ended at the lock and the other root took a name from elsewhere), the one
    of their two names that no other root of the point carries -- every
    uncoupled mode continues into exactly one complex root or one locked pair
    (completeness).  Which root of the pair is written ``X`` and which
    ``X (locked)`` is the roles' rule (the plain name to the less stable).

    Parameters
    ----------
    names : list of str
        The roots' names after the final naming (``""``: none).
    eig : numpy.ndarray of complex
        Their Floquet exponents [/rev].
    motion : numpy.ndarray
        Their flap motion shares (:data:`FLAP_ACTIVE`): where both names are
        free, a pair that moves the flap is the TEF's.

    Returns
    -------
    names : list of str
    decided : numpy.ndarray of bool
        Per root of a pair: its name followed from its paths or from
        completeness; False where the rule had to choose (both names free or
        neither); True for roots in no pair.

    Examples
    --------
    The TEF's pair locked at 4.5 /rev (3.5 by one root's dominant harmonic),
    its second root given blade flap 3's name while blade flap 3 itself is
    the complex root at 5.8 /rev:

    >>> import numpy as np
    >>> eig = np.array([-6.40 + 3.5j, -5.31 + 4.5j, -0.51 + 5.80j])
    >>> names, decided = name_lock_pairs(["TEF", "blade flap 3 (locked)", "blade flap 3"],
    ...                                  eig, np.array([0.9, 0.9, 0.1]))
    >>> sorted(names[:2]), decided.tolist()
    (['TEF', 'TEF (locked)'], [True, True, True])
    """
    eig = np.asarray(eig, complex)
    names = list(names)
    decided = np.ones(len(names), bool)
    lock = lock_matrix(eig)
    seen: set = set()
    for i in range(len(names)):
        if i in seen or not lock[i].any():
            continue
        members = [i, *np.flatnonzero(lock[i]).tolist()]
        seen.update(members)
        for a, b in _lock_pairs(members, names, eig):
            na, nb = base_name(names[a]), base_name(names[b])
            if na and na == nb:
                x, sure = na, True
            else:
                others = {base_name(names[k]) for k in range(len(names)) if k not in (a, b)}
                free = [n for n in dict.fromkeys((na, nb)) if n and n not in others]
                if len(free) == 1:
                    x, sure = free[0], True
                elif (len(free) == 2 and TEF_NAME in free
                      and max(motion[a], motion[b]) >= FLAP_ACTIVE):
                    x, sure = TEF_NAME, False
                else:
                    # the less stable root's own name (the one a claim reads)
                    x = (na, nb)[int(eig[b].real > eig[a].real)] or na or nb
                    sure = False
            if x:
                names[a], names[b] = x, locked_name(x)
            decided[[a, b]] = sure
    return names, decided


def flap_free_by_participation(origin, motion, carried):
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
    taken = {base_name(names[i]) for i in np.flatnonzero(free)}
    left = [o for o in origin if o and base_name(o) not in taken]   # "": unexplained
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
                      if base_name(n) == base_name(str(carried[i])) else 2.0
                      for k, n in enumerate(pool)] for i in active])
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    rows, cols = linear_sum_assignment(cost)
    for r, c in zip(rows, cols, strict=True):
        i = active[r]
        names[i] = pool[c]
        changed[i] = pool[c] != origin[i]
    return names, changed
