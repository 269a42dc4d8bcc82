"""Rotating finite-element blade: assembly, root springs and coupled modes.

The blade is a rotating Euler-Bernoulli beam with flap, lag, torsion and
axial degrees of freedom (fifteen per element, :mod:`tefcore.structure.beam_element`)
clamped at the structural root ``x = e`` with equivalent springs: the
bearingless hub (flexbeam, torque tube, pitch link) is represented by a flap
spring, a lag spring with a lag damper, and a torsion spring from the pitch
link in series with the blade's own torsional flexibility.

Global degrees of freedom: six per node ``[u, v, v', w, w', phi]`` followed by
three interior ones per element ``[u(1/3), u(2/3), phi(1/2)]``.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from .beam_element import element_matrices, field_operators

__all__ = ["FIELD_GROUPS", "BeamModel", "BladeModes", "RootSprings", "assemble_beam",
           "beam_modes", "classify", "component_matrices", "dof_owner", "dof_slopes",
           "field_rows", "tension_from_mass", "tension_piecewise_linear"]

FIELD_GROUPS = ("axial", "lag", "flap", "torsion")


@dataclass
class RootSprings:
    """Equivalent hub restraints at the structural root (rotor units).

    ``numpy.inf`` clamps the corresponding slope or twist.

    Attributes
    ----------
    flap, lag : float
        Rotational springs on the flap and lag slopes.
    torsion : float
        Torsional spring on the root twist.
    lag_damper : float
        Rotational damper on the lag slope.
    """

    flap: float = 0.0
    lag: float = 0.0
    torsion: float = 0.0
    lag_damper: float = 0.0


def _dof_map(n_el: int) -> np.ndarray:
    """Global index of each of the 15 local dofs of every element, (n_el, 15)."""
    i = np.arange(n_el)[:, None]
    a, b = 6 * i, 6 * (i + 1)
    internal = 6 * (n_el + 1) + 3 * i
    return np.hstack([a + 0, internal + 0, internal + 1, b + 0,
                      a + 1, a + 2, b + 1, b + 2,
                      a + 3, a + 4, b + 3, b + 4,
                      a + 5, internal + 2, b + 5])


def _dof_groups(n_el: int) -> dict[str, np.ndarray]:
    n_node = 6 * (n_el + 1)
    nodes = np.arange(n_node).reshape(-1, 6)
    interior = n_node + np.arange(3 * n_el).reshape(-1, 3)
    return {"axial": np.concatenate([nodes[:, 0], interior[:, :2].ravel()]),
            "lag": nodes[:, 1:3].ravel(),
            "flap": nodes[:, 3:5].ravel(),
            "torsion": np.concatenate([nodes[:, 5], interior[:, 2]])}


@functools.lru_cache(maxsize=8)
def dof_owner(n_el: int) -> np.ndarray:
    """Index into FIELD_GROUPS of every dof of an ``n_el``-element beam (read-only, cached).

    Examples
    --------
    >>> [FIELD_GROUPS[i] for i in dof_owner(1)[:6]]
    ['axial', 'lag', 'lag', 'flap', 'flap', 'torsion']
    """
    groups = _dof_groups(n_el)
    owner = np.full(6 * (n_el + 1) + 3 * n_el, -1)
    for i, kind in enumerate(FIELD_GROUPS):
        owner[groups[kind]] = i
    owner.flags.writeable = False
    return owner


_dof_owner = dof_owner


@functools.lru_cache(maxsize=8)
def dof_slopes(n_el: int) -> np.ndarray:
    """True for the slope dofs ``v', w'`` of an ``n_el``-element beam (read-only, cached).

    Examples
    --------
    >>> dof_slopes(1)[:6].tolist()
    [False, False, True, False, True, False]
    """
    slope = np.zeros(6 * (n_el + 1) + 3 * n_el, dtype=bool)
    nodes = np.arange(6 * (n_el + 1)).reshape(-1, 6)
    slope[nodes[:, [2, 4]].ravel()] = True
    slope.flags.writeable = False
    return slope


def field_rows(x_nodes, x) -> dict[str, np.ndarray]:
    """Rows mapping a beam's dof vector to its fields at stations ``x``.

    Parameters
    ----------
    x_nodes : array_like
        Node stations of the beam (increasing).
    x : array_like
        Stations within ``[x_nodes[0], x_nodes[-1]]``.

    Returns
    -------
    dict
        ``u, du, v, dv, ddv, w, dw, ddw, phi, dphi``, each ``(len(x), n_dof)``
        with ``n_dof = 6 (n_el + 1) + 3 n_el`` (the beam's own numbering).

    Examples
    --------
    >>> rows = field_rows([0.0, 0.5, 1.0], [0.5])
    >>> int(np.flatnonzero(rows["w"][0])[0]), float(rows["w"][0].sum())
    (9, 1.0)
    """
    xn = np.asarray(x_nodes, float)
    x = np.atleast_1d(np.asarray(x, float))
    if np.any(x < xn[0] - 1e-12) or np.any(x > xn[-1] + 1e-12):
        raise ValueError(f"stations must lie in [{xn[0]}, {xn[-1]}]")
    n_el = len(xn) - 1
    el = np.clip(np.searchsorted(xn, x, side="right") - 1, 0, n_el - 1)
    h = xn[el + 1] - xn[el]
    ops = field_operators((x - xn[el]) / h, h)
    dmap = _dof_map(n_el)[el]                          # (nx, 15), distinct in each row
    n_dof = 6 * (n_el + 1) + 3 * n_el
    out = {}
    row = np.arange(x.size)[:, None]
    for name, op in ops.items():
        rows = np.zeros((x.size, n_dof))
        rows[row, dmap] = op
        out[name] = rows
    return out


def tension_from_mass(mass: Callable, x_root: float, n: int = 2001) -> Callable:
    """Centrifugal tension per Omega^2, ``T(x) = int_x^1 m(s) s ds``.

    Integrated with cumulative Simpson's rule on a fine grid (exact for the
    quadratic integrand of a linearly varying mass) and interpolated.

    Parameters
    ----------
    mass : callable
        Mass per length ``m(x)`` (rotor units).
    x_root : float
        Inboard end of the integration grid, fraction of R.
    n : int, optional
        Points of the integration grid.

    Returns
    -------
    callable
        ``T(x)``.
    """
    import scipy.integrate  # only here: 0.14 s of import a blade model does not need

    s = np.linspace(x_root, 1.0, n)
    f = mass(s) * s
    cum = scipy.integrate.cumulative_simpson(f, x=s, initial=0.0)
    t = cum[-1] - cum
    return lambda x: np.interp(x, s, t)


def tension_piecewise_linear(stations, mass) -> Callable:
    """Exact centrifugal tension per Omega^2 for a piecewise-linear mass.

    ``T(x) = int_x^1 m(s) s ds`` with ``m`` linear between ``stations``
    (the last station is the tip): the integrand is quadratic on every
    segment, so Simpson's rule on each segment (and on the partial segment
    from ``x``) is exact.

    Parameters
    ----------
    stations : array_like
        Stations, fractions of R, increasing to the tip.
    mass : array_like
        Mass per length at ``stations`` (rotor units).

    Returns
    -------
    callable
        ``T(x)``.

    Examples
    --------
    >>> t = tension_piecewise_linear([0.0, 1.0], [1.0, 1.0])   # uniform: (1 - x^2)/2
    >>> round(float(t(0.5)), 12)
    0.375
    """
    xs, ms = np.asarray(stations, float), np.asarray(mass, float)
    slope = np.diff(ms) / np.diff(xs)

    def integral(a, b, i):                  # int_a^b m s ds inside segment i
        mid = 0.5 * (a + b)
        m_a, m_m, m_b = (ms[i] + slope[i] * (p - xs[i]) for p in (a, mid, b))
        return (b - a) / 6.0 * (m_a * a + 4.0 * m_m * mid + m_b * b)

    seg = np.arange(xs.size - 1)
    from_tip = np.concatenate([np.cumsum(integral(xs[:-1], xs[1:], seg)[::-1])[::-1], [0.0]])

    def tension(x):
        x = np.asarray(x, float)
        i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, xs.size - 2)
        return integral(x, xs[i + 1], i) + from_tip[i + 1]
    return tension


@dataclass
class BeamModel:
    """Assembled rotating beam in rotor units (constraints not yet applied).

    ``stiffness(r)`` gives the stiffness at rotor speed ``r * Omega_ref``
    expressed in units of the *new* speed (so eigenvalues are (/rev)^2).

    Attributes
    ----------
    x_nodes : numpy.ndarray
        Node stations, fractions of R.
    mass, k_elastic, k_centrifugal, damping_matrix, gyroscopic : numpy.ndarray
        Global mass, elastic and centrifugal stiffness (per (reference speed)^2),
        structural damping and Coriolis matrices (rotor units).
    free : numpy.ndarray of bool
        The unconstrained dofs.
    pitch : callable
        Geometric pitch ``theta(x)`` [rad] the sections were assembled at.
    """

    x_nodes: np.ndarray
    mass: np.ndarray
    k_elastic: np.ndarray
    k_centrifugal: np.ndarray
    damping_matrix: np.ndarray
    gyroscopic: np.ndarray
    free: np.ndarray
    pitch: Callable = field(repr=False)

    @property
    def n_elements(self) -> int:
        return len(self.x_nodes) - 1

    @property
    def owner(self) -> np.ndarray:
        """Field (index into FIELD_GROUPS) of every dof."""
        return dof_owner(self.n_elements)

    @property
    def slopes(self) -> np.ndarray:
        """True for the slope dofs (``v', w'``)."""
        return dof_slopes(self.n_elements)

    def stiffness(self, speed_ratio: float = 1.0) -> np.ndarray:
        return self.k_elastic / speed_ratio**2 + self.k_centrifugal

    def damping(self, speed_ratio: float = 1.0) -> np.ndarray:
        return self.damping_matrix / speed_ratio

    def evaluate(self, vectors: np.ndarray, x) -> dict[str, np.ndarray]:
        """Fields of global dof vectors at radial stations ``x``.

        Parameters
        ----------
        vectors : ndarray, shape (n_dof,) or (n_dof, k)
        x : array_like
            Stations (fractions of R) within the beam.

        Returns
        -------
        dict
            ``u, v, dv, ddv, w, dw, ddw, phi, dphi``, each (len(x), k).
        """
        x = np.atleast_1d(np.asarray(x, float))
        xn = self.x_nodes
        if np.any(x < xn[0] - 1e-12) or np.any(x > xn[-1] + 1e-12):
            raise ValueError(f"stations must lie in [{xn[0]}, {xn[-1]}]")
        vec = vectors.reshape(vectors.shape[0], -1)
        el = np.clip(np.searchsorted(xn, x, side="right") - 1, 0, self.n_elements - 1)
        h = xn[el + 1] - xn[el]
        ops = field_operators((x - xn[el]) / h, h)
        local = vec[_dof_map(self.n_elements)[el]]          # (nx, 15, k)
        values = np.einsum("fnd,ndk->fnk", np.stack(list(ops.values())), local)
        return dict(zip(ops, values, strict=True))


def component_matrices(x_nodes, section: Callable, pitch: Callable, tension: Callable):
    """Unconstrained mass, elastic, centrifugal and Coriolis matrices of one beam.

    The elements of :func:`tefcore.structure.beam_element.element_matrices` scattered
    into the beam's own dof numbering (six per node, then three interior
    per element); no supports.  :func:`assemble_beam` and the branched hub
    (:mod:`tefcore.structure.branched`) build on it.

    Parameters
    ----------
    x_nodes : array_like
        Node stations [fraction of R], strictly increasing.
    section : callable
        ``section(x) -> dict`` of nondimensional section properties.
    pitch : callable
        ``pitch(x)`` [rad].
    tension : callable
        ``tension(x)``: centrifugal tension per Omega^2 (rotor units).

    Returns
    -------
    mass, k_elastic, k_centrifugal, gyroscopic : ndarray, (n_dof, n_dof)
    """
    xn = np.asarray(x_nodes, float)
    if xn.ndim != 1 or len(xn) < 2 or np.any(np.diff(xn) <= 0):
        raise ValueError("x_nodes must be a strictly increasing 1-D array of >= 2 stations")
    n_el = len(xn) - 1
    n_dof = 6 * (n_el + 1) + 3 * n_el
    elements = element_matrices(xn[:-1], np.diff(xn), section, pitch, tension)
    dmap = _dof_map(n_el)
    flat = (dmap[:, :, None] * n_dof + dmap[:, None, :]).ravel()
    # scatter-add all four element sets at once (bincount is the fast add.at)
    return tuple(
        np.bincount(flat, weights=el.ravel(), minlength=n_dof * n_dof).reshape(n_dof, n_dof)
        for el in elements)


def assemble_beam(x_nodes, section: Callable, pitch: Callable,
                  root: RootSprings | None = None, tension: Callable | None = None) -> BeamModel:
    """Assemble a rotating beam clamped at ``x_nodes[0]`` with root springs.

    Parameters
    ----------
    x_nodes : array_like
        Node stations, increasing, in fractions of R (the rotation axis is at
        0, so ``x_nodes[0]`` is the root offset).
    section : callable
        Nondimensional section properties ``section(x) -> dict`` (see
        :func:`tefcore.structure.beam_element.element_matrices`).
    pitch : callable
        Geometric pitch (collective + pretwist) [rad] versus ``x``.
    root : RootSprings, optional
        Root restraints. ``u, v, w`` are fixed at the root; the slopes ``v'``,
        ``w'`` and the twist ``phi`` are held by these springs.
    tension : callable, optional
        Centrifugal tension per Omega^2, ``T(x)``; by default integrated from
        the section mass (:func:`tension_from_mass`).

    Returns
    -------
    BeamModel
    """
    xn = np.asarray(x_nodes, float)
    root = root or RootSprings()
    tension = tension or tension_from_mass(lambda s: section(s)["mass"], xn[0])
    mass, k_elastic, k_cf_g, gyro = component_matrices(xn, section, pitch, tension)
    n_dof = mass.shape[0]
    damp = np.zeros((n_dof, n_dof))
    fixed = [0, 1, 3]                   # u, v, w at the root
    for dof, k in ((2, root.lag), (4, root.flap), (5, root.torsion)):
        if np.isinf(k):
            fixed.append(dof)           # an infinite spring is a clamp
        else:
            k_elastic[dof, dof] += k
    damp[2, 2] += root.lag_damper
    free = np.delete(np.arange(n_dof), fixed)
    return BeamModel(xn, mass, k_elastic, k_cf_g, damp, gyro, free, pitch)


@dataclass
class BladeModes:
    """Coupled natural modes of the rotating blade and their modal matrices.

    Attributes
    ----------
    frequencies : ndarray
        Natural frequencies [/rev] at the analysis rotor speed.
    vectors : ndarray, shape (n_dof, n_modes)
        Global mode shapes (zeros at constrained dofs), each scaled so that
        its dominant field peaks at +1 (tip deflection / R for bending and
        axial modes, radians of twist for torsion).
    labels : list of str
        ``"flap 1"``, ``"lag 1"``, ``"torsion 1"``, ``"axial 1"``, ...
    fractions : ndarray, shape (n_modes, 4)
        Kinetic-energy fractions in axial, lag, flap, torsion motion.
    modal_mass, modal_stiffness, modal_damping, modal_gyroscopic : ndarray
            Generalised matrices ``Phi^T M Phi`` etc. (rotor units).
    beam : BeamModel
        The beam the modes are of (for :meth:`shapes`).
    cache : dict
        Shapes at stations asked for before (:meth:`shapes`), kept with the
        modes (which :func:`tefcore.structure.blade.blade_modes` keeps for configurations
        of one structure).
    """

    frequencies: np.ndarray
    vectors: np.ndarray
    labels: list
    fractions: np.ndarray
    modal_mass: np.ndarray
    modal_stiffness: np.ndarray
    modal_damping: np.ndarray
    modal_gyroscopic: np.ndarray
    beam: BeamModel = field(repr=False)
    cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def families(self) -> list[str]:
        """Each mode's family (``"flap"``, ``"lag"``, ``"torsion"``, ``"axial"``): the
        field carrying most of its kinetic energy, the word its label starts with."""
        return [FIELD_GROUPS[int(np.argmax(f))] for f in self.fractions]

    def shapes(self, x) -> dict[str, np.ndarray]:
        """Mode shapes (displacements, slopes, curvatures, twist) at ``x``."""
        x = np.asarray(x, float)
        key = ("shapes", x.shape, x.tobytes())
        if key not in self.cache:
            if len(self.cache) > 64:
                self.cache.clear()
            self.cache[key] = self.beam.evaluate(self.vectors, x)
        return {k: v.copy() for k, v in self.cache[key].items()}

    def table(self):
        """Tidy mode table (a pandas DataFrame): one row per mode."""
        import pandas as pd  # only where a table is built (0.18 s of import)

        df = pd.DataFrame({"mode": np.arange(1, len(self.frequencies) + 1),
                           "label": self.labels,
                           "frequency_per_rev": self.frequencies})
        for i, g in enumerate(FIELD_GROUPS):
            df[f"{g}_fraction"] = self.fractions[:, i]
        df["modal_mass"] = np.diag(self.modal_mass)
        return df


def classify(vectors: np.ndarray, mass: np.ndarray, owner):
    """Label modes by the field that carries most of their kinetic energy.

    Parameters
    ----------
    vectors : numpy.ndarray, shape (n_dof, n_modes)
        Global mode shapes, one column per mode.
    mass : numpy.ndarray, shape (n_dof, n_dof)
        The global mass matrix.
    owner : numpy.ndarray or int
        Field (index into FIELD_GROUPS) of every dof, or the number of
        elements of a single beam.

    Returns
    -------
    labels : list of str
    fractions : ndarray, shape (n_modes, 4)
        Energy fractions (axial, lag, flap, torsion); the cross terms of the
        mass matrix (CG offset) are left out so the fractions sum to one.
    """
    if np.ndim(owner) == 0:
        owner = dof_owner(int(owner))
    # the mass restricted to same-group pairs drops the cross terms, and one
    # product gives all four energies
    same = owner[:, None] == owner[None, :]
    per_dof = vectors * (np.where(same, mass, 0.0) @ vectors)
    energy = np.stack([per_dof[owner == i].sum(axis=0) for i in range(len(FIELD_GROUPS))],
                      axis=1)
    fractions = energy / energy.sum(axis=1, keepdims=True)
    counts = dict.fromkeys(FIELD_GROUPS, 0)
    labels = []
    for f in fractions:
        kind = FIELD_GROUPS[int(np.argmax(f))]
        counts[kind] += 1
        labels.append(f"{kind} {counts[kind]}")
    return labels, fractions


def _dense_lowest_modes(k, m, n):
    """Lowest ``n`` eigenpairs of ``k x = lam m x``, accurate for stiff beams.

    The axial dofs put eigenvalues of order 1e6 (/rev)^2 beside the 0.1 of a
    soft lag mode, and a direct solve then loses the low ones to round-off
    relative to the largest (seen: 1e-4).  Solving ``m x = mu k x`` for the
    largest ``mu = 1/lam`` keeps them to machine precision.  When ``k`` is
    not positive definite (a static divergence) the direct form is used.
    """
    size = k.shape[0]
    try:
        mu, vec = scipy.linalg.eigh(m, k, subset_by_index=[size - n, size - 1],
                                    driver="gvx", check_finite=False)
        return 1.0 / mu[::-1], vec[:, ::-1]
    except np.linalg.LinAlgError:
        lam, vec = scipy.linalg.eigh(k, m, driver="gvd", check_finite=False)
        return lam[:n], vec[:, :n]


def _connected_components(link) -> tuple[int, np.ndarray]:
    """Connected components of the undirected graph of a small boolean matrix.

    What :func:`scipy.sparse.csgraph.connected_components` gives with
    ``directed=False`` -- the count and each node's component, numbered in
    the order of each component's lowest node -- for the four fields of a
    blade section, without importing :mod:`scipy.sparse` (30-70 ms of the
    start-up of ``tefcore stability``, measured).

    Parameters
    ----------
    link : array_like of bool, shape (n, n)
        ``link[i, j]``: nodes ``i`` and ``j`` are joined (either direction).

    Returns
    -------
    n_components : int
    labels : numpy.ndarray of int
        Component of each node.

    Examples
    --------
    >>> n, labels = _connected_components(np.array([[0, 0, 1], [0, 0, 0], [0, 0, 0]], bool))
    >>> n, labels.tolist()
    (2, [0, 1, 0])
    """
    link = np.asarray(link, bool)
    reach = link | link.T | np.eye(link.shape[0], dtype=bool)
    while True:                     # transitive closure by squaring: log2(n) products
        wider = (reach.astype(np.int64) @ reach.astype(np.int64)) > 0
        if np.array_equal(wider, reach):
            break
        reach = wider
    lowest = reach.argmax(axis=1)   # each node's component by its lowest node
    roots, labels = np.unique(lowest, return_inverse=True)
    return int(roots.size), labels.astype(np.int32)


def _uncoupled_blocks(k, m, owner) -> list[np.ndarray]:
    """Dof sets of groups of fields that ``k`` and ``m`` do not couple.

    Fields (``owner``: axial, lag, flap, torsion) with not one nonzero
    entry between them in either matrix are separate eigenproblems.  On the
    MDART blade (CG and tension axis on the elastic axis) axial, torsion and
    flap-lag separate; a CG offset couples torsion with bending, a tension
    axis offset axial with lag, and then fewer blocks come out.
    """
    n_f = len(FIELD_GROUPS)
    ind = np.zeros((owner.size, n_f))
    ind[np.arange(owner.size), owner] = 1.0
    # |k| + |m| summed over field pairs: nonzero where any entry couples them
    link = (ind.T @ (np.abs(k) + np.abs(m)) @ ind) > 0
    n_blocks, comp = _connected_components(link)
    of_dof = comp[owner]
    blocks = [np.flatnonzero(of_dof == c) for c in range(n_blocks)]
    return [b for b in blocks if b.size]


def _lowest_modes(k, m, n, owner=None):
    """Lowest ``n`` eigenpairs of ``k x = lam m x``, block by uncoupled block.

    Exact: the pencil is block diagonal over the blocks of
    :func:`_uncoupled_blocks` (``owner``: field of every dof; without it one
    dense problem).  Blocks are solved softest first (by ``tr k / tr m``);
    a block is skipped when ``k_b - lam_n m_b`` is positive definite, with
    ``lam_n`` the n-th lowest eigenvalue so far: by Sylvester's law of
    inertia it then has no eigenvalue below ``lam_n`` (the stiff axial block
    of a rotor blade, usually).  Each solved block is smaller and better
    conditioned than the whole (MDART: 2.2-2.4 ms dense, 1.3-1.4 ms by blocks).
    """
    blocks = [np.arange(k.shape[0])] if owner is None else _uncoupled_blocks(k, m, owner)
    if len(blocks) == 1:
        return _dense_lowest_modes(k, m, n)
    dk, dm = np.diag(k), np.diag(m)
    blocks.sort(key=lambda b: dk[b].sum() / dm[b].sum())
    lams, vecs = np.empty(0), np.empty((k.shape[0], 0))
    for b in blocks:
        kb, mb = k[b][:, b], m[b][:, b]
        if lams.size >= n:
            try:
                scipy.linalg.cholesky(kb - lams[n - 1] * mb, check_finite=False)
                continue                      # nothing below the n-th eigenvalue
            except np.linalg.LinAlgError:
                pass
        lam, vec = _dense_lowest_modes(kb, mb, min(n, b.size))
        full = np.zeros((k.shape[0], lam.size))
        full[b] = vec
        lams, vecs = np.concatenate([lams, lam]), np.hstack([vecs, full])
        keep = np.argsort(lams, kind="stable")[:n]
        lams, vecs = lams[keep], vecs[:, keep]
    return lams, vecs


def _held_modes(fractions, n_modes: int, families) -> np.ndarray | None:
    """Indices (ascending) of the modes a basis holds, or None when too few were solved.

    ``fractions`` are the solved modes' energy fractions in order of
    frequency; their family is the field of the largest (:func:`classify`).
    Without ``families`` the `n_modes` lowest.
    """
    if not families:
        return np.arange(n_modes) if len(fractions) >= n_modes else None
    family = np.array([FIELD_GROUPS[int(np.argmax(fr))] for fr in fractions])
    held = []
    for name, count in families.items():
        mine = np.flatnonzero(family == name)
        if mine.size < count:
            return None
        held.extend(mine[:count].tolist())
    rest = [i for i in range(len(fractions)) if i not in held]
    short = n_modes - len(held)
    if len(rest) < short:
        return None
    return np.array(sorted(held + rest[:short]))


def beam_modes(beam: BeamModel, n_modes: int = 9, speed_ratio: float = 1.0,
               families: dict | None = None) -> BladeModes:
    """Lowest coupled modes of an assembled beam (undamped, no Coriolis).

    The Coriolis coupling (axial-lag) and the lag damper are left out of the
    eigenproblem, as usual for a modal basis, and kept in the modal damping
    and gyroscopic matrices for the coupled equations.

    Parameters
    ----------
    beam : BeamModel or tefcore.structure.branched.BranchedBeam
        Anything with ``mass, stiffness(r), damping(r), gyroscopic, free,
        owner, slopes`` and ``evaluate``.
    n_modes : int
        Number of modes kept.
    speed_ratio : float
        Rotor speed over the reference speed; frequencies are per rev of the
        new speed.
    families : dict, optional
        Family -> modes of it the basis holds (``{"flap": 5, "lag": 2,
        "torsion": 2}``, ``model.mode_families``): the lowest of each family,
        then the lowest others up to `n_modes`.  A mode whose frequency
        passes another's along a sweep stays in the basis (without: the
        `n_modes` lowest, and a torsion mode passing a lag mode leaves it).

    Returns
    -------
    BladeModes
        The modes in order of frequency, labelled by family in order of
        frequency within each (``flap 1``, ``flap 2``, ...).
    """
    f = beam.free
    k = beam.stiffness(speed_ratio)
    if n_modes > len(f):
        raise ValueError(f"n_modes = {n_modes} exceeds the {len(f)} free dofs")
    # rows then columns: two contiguous takes, ~4x faster than np.ix_ here
    owner, slopes = beam.owner, beam.slopes
    kf, mf = k[f][:, f], beam.mass[f][:, f]
    n_solved = n_modes
    while True:
        lam, vec = _lowest_modes(kf, mf, n_solved, owner=owner[f])
        full = np.zeros((k.shape[0], lam.size))
        full[f] = vec
        labels, fractions = classify(full, beam.mass, owner)
        keep = _held_modes(fractions, n_modes, families)
        if keep is not None or n_solved >= len(f):
            break
        # a family asked for lies above the modes solved so far: solve more
        n_solved = min(len(f), n_solved + max(6, n_modes))
    if keep is None:
        missing = {fam: c for fam, c in (families or {}).items()}
        raise ValueError(f"the blade has fewer modes of each family than asked "
                         f"({missing}) among its {len(f)} free dofs")
    lam, full, fractions = lam[keep], full[:, keep], fractions[keep]
    labels = [labels[i] for i in keep]
    # scale: dominant field's translational (or twist) dofs peak at +1
    for j in range(len(labels)):
        idx = np.flatnonzero((owner == int(np.argmax(fractions[j]))) & ~slopes)
        k_max = idx[np.argmax(np.abs(full[idx, j]))]
        full[:, j] /= full[k_max, j]
    mm = full.T @ beam.mass @ full
    # a negative eigenvalue is a static divergence: keep its sign, never hide it
    return BladeModes(frequencies=np.sign(lam) * np.sqrt(np.abs(lam)),
                      vectors=full, labels=labels, fractions=fractions,
                      modal_mass=mm, modal_stiffness=full.T @ k @ full,
                      modal_damping=full.T @ beam.damping(speed_ratio) @ full,
                      modal_gyroscopic=full.T @ beam.gyroscopic @ full, beam=beam)
