"""Names at full coupling for the roots the march does not decide (Floquet).

Private to :mod:`tefcore.modes.continuation`.  The coupling moves a root in
proportion to its motion of the flap: a root of the coupled system that does
not move it is the blade's own root of the coordinate it carries, named by
participation (:func:`free_labels`, :func:`flap_free_by_participation`); the
roots that move the flap keep their paths' names.  A lock's second root no
path explains is named beside its partner (:func:`second_roots_of_locks`).
"""

from __future__ import annotations

import numpy as np

from .march import FLAP_ACTIVE, base_name, same_lock

__all__ = ["flap_free_by_participation", "free_labels", "second_roots_of_locks"]


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
        if base_name(out[j]) == labels[-1] and k is not None and free[k]:
            second = f"{own} (locked)"
            if eig is not None and same_lock(eig, j, k) and second not in holder:
                holder.pop(out[j], None)
                out[j] = second
                holder[second] = j
            continue
        if out[j] == own or out[j].endswith("(locked)") or k is None or free[k]:
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
        if len(same) < 2 or not name.endswith(" (locked)"):
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
                    and not names[p].endswith("(locked)") and names[p] != name]
        if not partners:
            continue
        p = min(partners, key=lambda q: abs(eig[q].real - eig[i].real))
        second = f"{base_name(names[p])} (locked)"
        if second not in names:
            names[i] = second
            renamed[i] = True
    return names, renamed


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
