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

from dataclasses import InitVar, dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..floquet import floquet_motions
from ..floquet.second_order import STATE_MIN_RATE, SecondOrderSystem, periodic_modes
from .final_names import (
    flap_free_by_participation,
    free_labels,
    name_lock_pairs,
    second_roots_of_locks,
)
from .labels import coordinate_shares, label_modes, tracking_shapes, trajectory_shapes
from .march import FLAP_ACTIVE, March, compact_basis, flap_share, lock_matrix
from .names import base_name, is_locked, locked_name, pair_text
from .tracking import follow_root

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["FIRST_STEPS", "FIRST_STEPS_CONSTANT", "FLAP_ACTIVE", "MIN_STEP", "PATH_MIN_ROOT",
           "PATH_RTOL", "ContinuedRoots", "HomotopySamples", "MeetingRows", "continue_roots",
           "coupling_homotopy", "path_shapes", "positive_roots", "root_solver", "tef_root",
           "visible_roots", "zero_coupling_names"]

#: Equal steps of ``eps`` the continuation starts with in forward flight (each
#: step's end is one eigenproblem); a step whose matches are not all decided is
#: halved.  (One step of the whole coupling was measured no faster there: at mu
#: 0.3 the first step is halved anyway, the roots near k/2 and the TEF mixing
#: with the blade modes near its frequency.)
FIRST_STEPS = 2

#: The same with constant coefficients (hover): the whole coupling in one
#: step, halved where it is not decided.  MDART's hover point is decided in one
#: step: one step of the march and no eigenproblem on the path instead of two
#: and one, 7.4 against 8.2 ms a point (interleaved medians of 15).  Where the
#: step is halved, it costs one step of the march more and saves nothing:
#: measured on the hover figures' sweeps with their refinement points (Figs. 8
#: and 16a, 37 points), 61 eigenproblems on the paths against 72 and 155 steps
#: of the march against 143 -- about even -- and the same tables, row for row.
FIRST_STEPS_CONSTANT = 1

#: The lift of a path step trusts a root down to ``|mu| = 1e-9`` and a relative
#: round-off of 1e-3 (:func:`tefcore.floquet.floquet_motions`; the point's own
#: roots: 1e-6 and 1e-6).  A path step must tell the roots apart, not converge
#: them: measured on Fig. 9's sweep (mu 0.3, 78 path steps), the lift's K fell
#: from 1/2/4/8 at 24/38/15/1 steps to 55/13/10/0, the exponents moved by at
#: most 1.5e-6 /rev, and no name, certainty or role changed on 21 points of
#: Figs. 9, 12, 13 and 14 (1.7 ms a point less; K = 4 stays where a root grows
#: at +3 /rev and another decays at -4.5 /rev: ``||Phi|| ~ 1e10``).  (The
#: balanced exponentials of the same stop changed the round-off, and with it
#: the certainty of a few locked TEF pairs at k/2: docs/theory.md 9.1.)
PATH_MIN_ROOT = 1e-9
PATH_RTOL = 1e-3

#: Smallest step of ``eps``: 1/4096 (11 halvings of the first 1/2).  A match still
#: undecided at this step is a coalescence on the path (an exceptional point
#: within ~1/4096 of the coupling), reported rather than refined further.
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


def _solve(system, n, eps, n_steps, participation=False, homotopy=None):
    """Positive roots of the system at coupling `eps` (Floquet: one grid, shapes;
    ``A`` from `homotopy`'s samples when given, a :class:`HomotopySamples`)."""
    if not system.periodic:
        res = coupling_homotopy(system, n - 1, eps).modes()
    else:
        a = (homotopy(eps) if homotopy is not None
             else coupling_homotopy(system, n - 1, eps).state_matrix)
        # n_sub=1: the lift's K chosen as for the point's own roots (raised
        # until the most damped root is resolved)
        res = periodic_modes(a, n, system.n_first, n_steps=n_steps, n_sub=1, shapes=True,
                             participation=participation, atol=None)
    if participation and res.participation is None:
        res = res.with_participation()
    return positive_roots(res)


def zero_coupling_names(frac, labels, freqs, rates, shapes, periodic=False):
    """The roots' names at zero coupling: by coordinate, a lock's two roots from its one mode.

    :func:`tefcore.modes.labels.label_modes` gives each coordinate to one
    root.  A lock's two real roots are one mode and one root more than the
    coordinates, and that assignment can hand the second of them another
    coordinate (measured on Fig. 12, mu = 0.3: at 29 of 42 points blade flap
    1's second real root, which its dominant harmonic writes at 2.5 /rev, was
    'blade flap 2', and flap 2's own root at 2.498 /rev 'blade flap 2
    (locked)'; the flap 2 path then started from the lock, and the uncoupled
    root of the coupled flap 2 was the lock's).  At zero coupling blade and
    flap are apart, so a lock (:func:`tefcore.modes.march.same_lock`) is one
    mode's: its two roots take one column of the assignment, their shares
    summed; the less damped is named plainly, the other ``X (locked)``.

    Parameters
    ----------
    frac : numpy.ndarray
        Coordinate shares, coordinates x roots (:func:`coordinate_shares`).
    labels : list of str
        The coordinates' labels.
    freqs, rates : numpy.ndarray
        The roots' frequencies and damping rates [/rev].
    shapes : numpy.ndarray
        Their physical shapes, one column each (for
        :func:`tefcore.modes.labels.label_modes`).
    periodic : bool, optional
        Floquet roots (constant coefficients: :func:`label_modes` as it is).

    Returns
    -------
    list of str

    Examples
    --------
    Two coordinates, three roots: a lock at 1/2 /rev (two real roots) that
    carries some of the second coordinate, and the second coordinate's own
    root near the lock's folded frequency.

    >>> import numpy as np
    >>> frac = np.array([[0.6, 0.55, 0.1], [0.4, 0.45, 0.9]])
    >>> zero_coupling_names(frac, ["blade flap 1", "blade flap 2"],
    ...                     np.array([0.5, 2.5, 2.498]), np.array([-1.5, -0.4, -0.5]),
    ...                     np.eye(3), periodic=True)
    ['blade flap 1 (locked)', 'blade flap 1', 'blade flap 2']
    """
    freqs, rates = np.asarray(freqs, float), np.asarray(rates, float)
    locks = np.triu(lock_matrix(rates + 1j * freqs), 1) if periodic else None
    if locks is None or not locks.any():
        return label_modes(frac, labels, freqs, rates, shapes, periodic)
    # the pairs: roots at one k/2 (folded), the most alike in shape first --
    # two locks can share a folded frequency (measured on MDART at mu 0.3,
    # c_cg 0.33: blade flap 1's at 0.5 / 2.5 /rev and flap 2's at 2.5 /rev;
    # MAC 1.00 within flap 2's pair, 0.17 within flap 1's, 0.007 across), and
    # pairing in index order would make the names depend on the roots' order;
    # alike: MAC of the shapes plus the overlap of the coordinate shares (a
    # lock's two roots carry one coordinate), each in [0, 1]
    unit = shapes / np.maximum(np.linalg.norm(shapes, axis=0, keepdims=True), 1e-300)
    share = np.asarray(frac, float) / np.maximum(np.sum(frac, axis=0), 1e-300)
    alike = (np.abs(unit.conj().T @ unit) ** 2
             + np.minimum(share[:, :, None], share[:, None, :]).sum(axis=0))
    pairs = sorted(((alike[j, k], j, k) for j, k in np.argwhere(locks).tolist()),
                   key=lambda t: (-round(t[0], 9), t[1], t[2]))
    second: dict = {}                      # the more damped root of a lock -> its partner
    paired: set = set()
    for _, j, k in pairs:
        if j in paired or k in paired:
            continue
        a, b = (j, k) if (rates[j], -j) >= (rates[k], -k) else (k, j)
        second[b] = a
        paired |= {j, k}
    keep = [j for j in range(freqs.size) if j not in second]
    col = {j: i for i, j in enumerate(keep)}
    sub = np.array(frac, float)[:, keep]
    for b, a in second.items():
        sub[:, col[a]] += frac[:, b]
    named = label_modes(sub, labels, freqs[keep], rates[keep], shapes[:, keep], periodic)
    out = [named[col[j]] if j in col else "" for j in range(freqs.size)]
    fallback = None
    for b, a in second.items():
        name = locked_name(out[a])
        if name in out:
            # more roots than coordinates: the pair's plain root is itself a
            # '(locked)' extra; the second root keeps the labels' own name
            fallback = fallback or label_modes(frac, labels, freqs, rates, shapes, periodic)
            name = fallback[b]
        out[b] = name
    return out


class HomotopySamples:
    """``A(psi)`` of :func:`coupling_homotopy` on one Floquet grid, for any ``eps``.

    The flap is one coordinate (the last), so the mass matrix of the
    homotopy, ``M(eps) = [[M_bb, eps m_bf], [eps m_fb, m_ff]]``, is inverted by
    eliminating the blade block once: with ``G = M_bb^-1 [K_b, C_b]`` (the
    blade rows of ``[K, C]``) and ``u = M_bb^-1 m_bf`` at every azimuth, the
    flap row of ``M(eps)^-1 [K(eps), C(eps)]`` is
    ``x_f = (r_f(eps) - eps m_fb G d(eps)) / (m_ff - eps^2 m_fb u)`` and the
    blade rows ``G d(eps) - eps u x_f``, where ``d(eps)`` scales the flap
    columns by ``eps`` and ``r_f(eps)`` is the flap row of ``[K, C]`` with its
    blade columns scaled (docs/theory.md 9.1).  Each ``eps`` then costs a few
    products instead of sampling the trigonometric interpolation and
    factorising ``M`` at every azimuth (0.5 of a path step's 3.6 ms, measured
    on MDART at mu = 0.3); equal to
    ``coupling_homotopy(system, n - 1, eps).state_matrix(psi)`` to round-off
    (tested).

    Parameters
    ----------
    system : tefcore.floquet.second_order.SecondOrderSystem
        Periodic, blade coordinates first and the flap last, no first-order states.
    n_steps : int
        Floquet steps per period: the samples are the step ends and midpoints,
        ``psi_j = j pi / n_steps``, ``j = 0 .. 2 n_steps - 1``.

    Examples
    --------
    >>> import numpy as np
    >>> from tefcore.floquet.second_order import SecondOrderSystem
    >>> psi = 2 * np.pi * np.arange(8) / 8
    >>> m = np.eye(2) + 0.1 * np.cos(psi)[:, None, None] * np.array([[0, 1], [1, 0]])
    >>> k = np.array([[1.0, 0.3], [0.3, 4.0]]) + 0.0 * m
    >>> system = SecondOrderSystem(m, 0.02 * m, k)
    >>> a = HomotopySamples(system, 4)(0.5)
    >>> direct = coupling_homotopy(system, 1, 0.5).state_matrix(np.arange(8) * np.pi / 4)
    >>> bool(np.allclose(a, direct, rtol=1e-12, atol=1e-14))
    True
    """

    def __init__(self, system: SecondOrderSystem, n_steps: int):
        if not system.periodic or system.n_first:
            raise ValueError("HomotopySamples: for a periodic second-order system without "
                             "first-order states")
        n = self.n = system.n_dof
        nb = n - 1
        self.n_steps = n_steps
        m, c, k = system.matrices(np.arange(2 * n_steps) * np.pi / n_steps)
        rhs = np.concatenate([k, c], axis=-1)                      # (N, n, 2n)
        both = np.linalg.solve(m[:, :nb, :nb], np.concatenate(
            [rhs[:, :nb], m[:, :nb, nb:]], axis=-1))               # one factorisation
        self._g, self._u = both[..., :2 * n], both[..., 2 * n]
        self._w = np.einsum("pb,pbj->pj", m[:, nb, :nb], self._g)  # m_fb G
        self._z = np.einsum("pb,pb->p", m[:, nb, :nb], self._u)    # m_fb u
        self._mff, self._rf = m[:, nb, nb], rhs[:, nb]
        self._flap_col = np.zeros(2 * n, bool)
        self._flap_col[[nb, n + nb]] = True

    def __call__(self, eps: float) -> np.ndarray:
        """``A`` at the samples, ``(2 n_steps, 2n, 2n)``, with the coupling scaled by `eps`."""
        n = self.n
        d = np.where(self._flap_col, eps, 1.0)                     # blade rows' columns
        x_f = ((self._rf * np.where(self._flap_col, 1.0, eps) - eps * self._w * d)
               / (self._mff - eps * eps * self._z)[:, None])
        x_b = self._g * d - eps * self._u[..., None] * x_f[:, None, :]
        out = np.zeros((x_f.shape[0], 2 * n, 2 * n))
        out[:, :n, n:] = np.eye(n)
        out[:, n:-1] = -x_b
        out[:, -1] = -x_f
        return out


def _path_step(homotopy, eps, basis):
    """The roots at coupling `eps` as a Floquet path step compares them (`homotopy` a
    :class:`HomotopySamples`): exponents and shapes.

    :func:`tefcore.floquet.floquet_motions` on its grid -- the exponents on
    the principal branch (the march unwraps them along each path) and each
    root's motion over the revolution through `basis`, the shapes
    :func:`path_shapes` gives a full result, without the harmonic analysis and
    participation a path step does not use (3.6 against 6.6 ms an
    eigenproblem, measured on MDART at mu = 0.3).
    """
    eta, x = floquet_motions(homotopy(eps), n_steps=homotopy.n_steps, n_sub=1,
                             min_root=PATH_MIN_ROOT, root_rtol=PATH_RTOL)
    order = np.lexsort((-eta.real, np.round(eta.imag, 9)))
    shapes = basis @ x[:, :homotopy.n, order]            # (azimuths, n_phys, roots)
    return eta[order], shapes.reshape(-1, order.size)


def _constant_step(system, eps, basis):
    """The roots at coupling `eps` of a constant-coefficient system (hover): the
    positive roots and :func:`path_shapes`."""
    n = system.n_dof
    res = _solve(system, n, eps, None)
    return res.exponents, path_shapes(basis, res, n, False)


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
    frequency : numpy.ndarray
        Per root (Floquet): its frequency [/rev] in the representation its
        path carried from the uncoupled root (the 1/rev shift and the sign
        chosen step by step nearest the path's prediction): continuous in
        ``eps``, and so in the design parameter wherever no exceptional point
        intervenes, the uncoupled root's convention being continuous in it.
        NaN where the path did not decide the root's name (not ``certain``, a
        root named by participation at the end, a lock's second root) and
        with constant coefficients (the frequency itself is continuous).
    by_path : numpy.ndarray of bool or None
        Per root: its name is the one its path brought from zero coupling --
        False where the final naming (forward flight) gave it another: a root
        that does not move the flap named by the coordinate it carries, a
        moving root given a name left, a lock's second root.  None: every
        root with a path (``origin`` not empty).
    """

    origin: list
    certain: np.ndarray
    uncoupled: np.ndarray
    meetings: InitVar[object]
    n_solves: int
    flap_motion: np.ndarray
    frequency: np.ndarray
    by_path: np.ndarray | None = None
    _meetings: object = field(init=False, repr=False, compare=False)

    def __post_init__(self, meetings):
        self._meetings = meetings

    def meeting_origins(self) -> list[str]:
        """The ``origins`` of :attr:`meetings` (``"A / B"``), without building the table.

        Returns
        -------
        list of str
        """
        m = self._meetings
        return list(m.data.get("origins", [])) if isinstance(m, MeetingRows) \
            else [str(x) for x in m["origins"]]


class MeetingRows(NamedTuple):
    """:attr:`ContinuedRoots.meetings` before it is asked for: its columns and their
    values (a point's naming needs no pandas; the table is built on first use).

    Parameters
    ----------
    columns : list of str
        The table's columns, in order (those of an empty table too).
    data : dict
        Column -> list of values, one per meeting; empty for no meeting.
    """

    columns: list
    data: dict


def _meetings_table(self) -> pd.DataFrame:
    m = self._meetings
    if isinstance(m, MeetingRows):
        import pandas as pd

        m = (pd.DataFrame(m.data) if m.data.get(m.columns[0])
             else pd.DataFrame([], columns=m.columns))
        self._meetings = m
    return m


# a property set after the class is made: ``meetings`` is also the
# constructor's argument (an InitVar), which a property in the class body
# would turn into a default
ContinuedRoots.meetings = property(_meetings_table, doc=(
    "pandas.DataFrame: where two paths met (``eps``, ``origins``, ``gap``, ``mac``), "
    "built on first use."))


def continue_roots(system: SecondOrderSystem, labels, final=None, *, basis=None,
                   final_labels=None, final_shares=None, first_steps: int | None = None,
                   min_step: float = MIN_STEP, n_steps: int = 72) -> ContinuedRoots:
    """Name every root of the coupled system by the uncoupled mode it continues from.

    **Constant coefficients (hover).**  The roots at ``eps = 0`` are named
    by the coordinates they carry (:func:`tefcore.modes.labels.label_modes`:
    the blade's by their structural labels, the flap's ``TEF`` -- exact, the
    two blocks being decoupled) and marched to ``eps = 1``: at each step all
    roots of the new ``eps`` are assigned to the paths (shapes by MAC,
    eigenvalues extrapolated linearly along each path; the assignment of
    least total cost; :class:`tefcore.modes.march.March`).  A step whose
    assignment is not decided for some path (its shape changed by more than
    :data:`tefcore.modes.matching.CLEAR_COST` over the step, or an assignment
    without its match within :data:`tefcore.modes.matching.MARGIN` of the
    best, :func:`tefcore.modes.march.regrets`; unless the eigenvalues alone
    decide it) is halved, down to `min_step`; a decided step lets the next
    one double, up to ``1 / first_steps``; an end solved once is reused.  A
    rival that continues the *same* uncoupled mode (``X`` and ``X (locked)``,
    the two real roots of an overdamped pair) does not make a step undecided.
    A match still undecided at `min_step` between two different uncoupled
    modes is two paths meeting -- an exceptional point of the family -- and
    goes into ``meetings``; the roots there keep the assignment of least cost
    and are not ``certain``.

    **Periodic coefficients (forward flight).**  The same march on the
    Floquet roots, with two differences.  Their frequencies are known modulo
    1/rev and up to the sign: each step's roots come on the principal branch
    (:func:`tefcore.floquet.floquet_motions`), a path sees each root in the
    representation nearest its own unwrapped frequency (the root's or its
    conjugate's), and the shapes compared are the periodic parts of the
    roots' motions over the revolution in that representation, which a
    frequency drifting along ``eps`` does not change.
    And the blade's low modes sit in frequency locks (pairs of real
    multipliers at ``k/2`` /rev) whose roots meet and part along ``eps``
    although the flap takes no part in them: an undecided match is refined
    only when the exchange it belongs to moves the flap on both sides (the
    path or its root carries :data:`FLAP_ACTIVE` of its motion in the flap,
    and so does the rival root or its path, :func:`tefcore.modes.march.exchanges`),
    or when a path or root that moves the flap lost its shape over the step;
    at the end the roots that do not move the flap are named by the
    coordinate they carry (their participation, ``final_labels``) -- what the
    coupling through the flap cannot have changed, and never the flap's own
    label -- and the moving roots keep their paths' names, or take the names
    left; a lock's second root no path explains is ``X (locked)`` beside its
    partner.

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
        by the blade coordinate they carry (:func:`tefcore.modes.final_names.free_labels`), not by
        `final_labels`' assignment over all roots, in which a root sharing a
        coordinate with a flap root can be left the second one it carries.
    first_steps : int, optional
        ``1 / first_steps`` is the first and the longest step of ``eps``
        (default :data:`FIRST_STEPS` for Floquet roots,
        :data:`FIRST_STEPS_CONSTANT` with constant coefficients).
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
    # the same MACs, norms and flap shares on n + 1 rows (march.compact_basis:
    # measured on Fig. 9's sweep, MDART's 37 rows made the march's costs and
    # the path steps' shapes a third of the continuation)
    basis = compact_basis(np.eye(n) if basis is None else basis)
    per = system.periodic
    if system.n_first:
        res0 = _solve(system, n, 0.0, n_steps, participation=True)
        return _by_participation(res0, n, labels, basis, final, final_labels)
    homotopy = HomotopySamples(system, n_steps) if per else None
    if first_steps is None:
        first_steps = FIRST_STEPS if per else FIRST_STEPS_CONSTANT
    res0 = _solve(system, n, 0.0, n_steps, participation=True, homotopy=homotopy)
    frac0 = coordinate_shares(res0.participation, n)
    vec0 = path_shapes(basis, res0, n, per, n_steps)
    names0 = zero_coupling_names(frac0, labels, res0.frequencies, res0.damping_rates, vec0,
                                 periodic=per)
    march = March(res0.exponents, vec0, names0, basis.shape[0], per)
    h_max, eps, h, n_solves = 1.0 / first_steps, 0.0, 1.0 / first_steps, 1
    solved: dict = {}                  # eps -> the roots there, for steps retried
    streak = 2                         # clear steps since the last halving
    while eps < 1.0 - 1e-12:
        h = min(h, 1.0 - eps)
        if eps + h == 1.0 and final is not None and 1.0 not in solved:
            eig, vecs = solved[1.0] = final.exponents, path_shapes(basis, final, n, per, n_steps)
        elif eps + h in solved:
            eig, vecs = solved[eps + h]
        else:
            # a step that was halved comes back to its end: solved once (ends
            # are dyadic, so equal as floats; measured on Fig. 9's sweep: 45
            # eigenproblems on the paths instead of 66 over 11 points)
            eig, vecs = solved[eps + h] = (_path_step(homotopy, eps + h, basis) if per
                                           else _constant_step(system, eps + h, basis))
            n_solves += 1
        if march.step(eps + h, eig, vecs, final_step=h <= min_step * (1 + 1e-9)):
            eps += h
            streak = streak + 1 if march.last_clear else 0
            if streak >= 2:            # a step that had to be halved is not doubled at once
                h = min(2 * h, h_max)
        else:
            h *= 0.5
            streak = 0
    paths = list(march.origin)
    origin, uncoupled, certain = list(paths), march.start.copy(), ~march.doubt
    motion = march.share                   # flap_share of its last roots
    if final_labels is not None and per:
        carried = list(final_labels)
        if final_shares is not None:
            carried = free_labels(carried, motion, final_shares, labels, final.exponents)
        origin, changed = flap_free_by_participation(origin, motion, carried)
        eig_final = final.exponents if final is not None else march.eig
        origin, renamed = second_roots_of_locks(origin, list(march.origin), eig_final)
        certain = certain & ~changed & ~renamed
        # a locked pair is one mode's pair: named as a pair, and decided by its
        # paths or by completeness whatever its paths' step-by-step certainty
        origin, decided = name_lock_pairs(origin, eig_final, motion)
        paired = lock_matrix(eig_final).any(axis=1)
        certain = np.where(paired, decided, certain)
        held = dict(zip(names0, res0.exponents, strict=True))
        uncoupled = np.array([held.get(o, held.get(base_name(o), np.nan)) for o in origin],
                             complex)
    by_path, carried = _own_paths(origin, paths, certain, march.eig, per)
    return ContinuedRoots(origin=origin, certain=certain, uncoupled=uncoupled,
                          meetings=_renamed_meetings(march, origin), n_solves=n_solves,
                          flap_motion=motion, frequency=carried, by_path=by_path)


def _own_paths(origin, paths, certain, eig, periodic):
    """Per root: its name is its own path's (``by_path``), and the frequency that
    path carried where it decided the name (Floquet; NaN otherwise).

    A flap-free root renamed by participation carries another path's frequency
    (measured on Fig. 13 at 0.71875 R: blade torsion 1's root, whose path was
    the TEF's, had been given the TEF's continued 10.30 /rev).
    """
    by_path = np.array([bool(p) and base_name(o) == base_name(p)
                        for o, p in zip(origin, paths, strict=True)])
    carried = np.full(len(origin), np.nan)
    if periodic:
        own = certain & by_path & np.array([not is_locked(o) for o in origin])
        carried[own] = eig.imag[own]
    return by_path, carried


#: Least share of a root's participation in the blade and flap states for it to
#: be a root of the blade and flap, not of the aerodynamic states (as in
#: :func:`tefcore.linear.stability.stability`).
_STRUCTURAL = 0.5


def _renamed_meetings(march, names) -> MeetingRows:
    """The march's meetings between the roots the two paths end on, by their final names.

    A path that passed a flap-free root (not refined, put right by
    :func:`tefcore.modes.final_names.flap_free_by_participation`) carries another name than its root
    gets; the meeting is between the roots, so it takes their names.  Two
    roots that end as one mode's pair (``X``, ``X (locked)``: a lock entered
    there) did not meet another mode.
    """
    final = {int(p): base_name(n) for p, n in zip(march.pid, names, strict=True)}
    rows: dict = {}                        # the first meeting of each pair
    for m in march.meetings:
        a, b = (final.get(p, n) for n, p in m["paths"].items())
        pair = pair_text(a, b)
        if a != b and pair not in rows:
            rows[pair] = (m["eps"], pair, m["gap"], m["mac"])
    # from columns, not records: a third of the cost (0.2 against 0.7 ms a point)
    columns = ["eps", "origins", "gap", "mac"]
    if not rows:
        return MeetingRows(columns, {})
    return MeetingRows(columns, dict(zip(columns, map(list, zip(*rows.values(), strict=True)),
                                         strict=True)))


def _by_participation(res0, n, labels, basis, final, final_labels) -> ContinuedRoots:
    """Names with aerodynamic states: the coordinate each root carries, compared by name.

    The shed wake's roots come in near-repeated families that no continuation
    step separates; with them, the roots keep their participation labels
    (``final_labels``) and are compared with the uncoupled root of the same
    name (the flap held: the blade's roots with their aerodynamic states).
    """
    mag = np.abs(res0.participation)
    keep = mag[:2 * n].sum(axis=0) >= _STRUCTURAL * mag.sum(axis=0)
    if res0.shapes is not None:
        # a Floquet root below STATE_MIN_RATE is not resolved and its
        # participation is round-off: a state's (as in
        # tefcore.linear.stability, which splits the point's own roots so)
        keep &= res0.damping_rates >= STATE_MIN_RATE
    res0 = res0.select(keep)
    names0 = zero_coupling_names(coordinate_shares(res0.participation, n), labels,
                                 res0.frequencies, res0.damping_rates,
                                 tracking_shapes(basis, res0, n),
                                 periodic=res0.shapes is not None)
    held = dict(zip(names0, res0.exponents, strict=True))
    names = [str(x) for x in final_labels]
    uncoupled = np.array([held.get(x, held.get(base_name(x), np.nan))
                          for x in names], complex)
    return ContinuedRoots(origin=names, certain=np.zeros(len(names), bool),
                          uncoupled=uncoupled,
                          meetings=MeetingRows(["eps", "origins"], {}), n_solves=1,
                          flap_motion=flap_share(tracking_shapes(basis, final, n),
                                                  basis.shape[0]),
                          frequency=np.full(len(names), np.nan),
                          by_path=np.zeros(len(names), bool))
