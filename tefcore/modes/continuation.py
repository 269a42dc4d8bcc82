"""Identity by continuation: the root a mode of the uncoupled system becomes.

A root's name is where it comes from.  With the blade-flap coupling scaled by
``s`` (:func:`coupling_homotopy`: the flap row and column of ``M, C, K``),
``s = 0`` is the uncoupled blade (its modes named by their structural
labels) and the flap on its actuator; following each root by continuation
(:func:`tefcore.modes.tracking.follow_root`) to ``s = 1`` names the roots of
the coupled system.  :func:`tef_root` is the root the uncoupled flap mode
becomes: "the TEF mode", a definition that depends on no label,
participation or sweep.
"""

from __future__ import annotations

import numpy as np

from ..floquet.second_order import SecondOrderSystem
from .tracking import follow_root

__all__ = ["coupling_homotopy", "positive_roots", "root_solver", "tef_root", "visible_roots"]


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
