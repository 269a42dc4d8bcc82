"""Branched rotating beams: several 15-dof beams joined by multi-point constraints.

The bearingless hub (docs/theory.md section 2.5a) is three beams -- flexbeam,
torque tube and main blade -- that meet at the clevis, plus point springs and
dampers (pitch link, snubber).  Each beam is assembled in its own numbering
by :func:`tefcore.structure.fem.component_matrices`; a :class:`Joint` is the
multi-point constraint ``q_slave = q_master`` on the six node dofs
``[u, v, v', w, w', phi]`` of two nodes at the same station (a rigid clevis
with the elastic axes coincident), applied by eliminating the slave dofs
(master-slave form: the slave node's dofs are numbered as the master's), and
a :class:`Coupling` is a spring and damper on a linear combination of fields,
``1/2 k (b^T q)^2`` and ``1/2 c (b^T q*)^2``.

The result, :class:`BranchedBeam`, has the interface of
:class:`tefcore.structure.fem.BeamModel` that :func:`tefcore.structure.fem.beam_modes`
needs, so its modes are :class:`tefcore.structure.fem.BladeModes` like the
single beam's.

Examples
--------
Two equal cantilevers side by side, joined at the tip, are one cantilever of
twice the mass and stiffness: the same frequencies.

>>> import numpy as np
>>> from tefcore.structure.fem import RootSprings, assemble_beam, beam_modes
>>> def sec(x, k=1.0):
...     x = np.asarray(x, float)
...     props = dict(mass=k, ei_flap=k, ei_lag=4 * k, gj=k, ea=1e4 * k, im_flap=0.0,
...                  im_lag=1e-2 * k, cg_offset=0.0, tension_offset=0.0, ka=0.0)
...     return {n: np.full_like(x, v) for n, v in props.items()}
>>> flat = lambda x: np.zeros_like(np.asarray(x, float))
>>> free = lambda x: np.zeros_like(np.asarray(x, float))   # no tension
>>> nodes = np.linspace(0.0, 1.0, 6)
>>> twin = assemble_branched([Component("a", nodes, sec, flat, free),
...                           Component("b", nodes, sec, flat, free)],
...                          joints=[Joint("a", 5, "b", 5)], clamps=[("a", 0), ("b", 0)])
>>> one = assemble_beam(nodes, lambda x: sec(x, 2.0), flat,
...                     RootSprings(np.inf, np.inf, np.inf), tension=free)
>>> f2, f1 = beam_modes(twin, 4, 1.0).frequencies, beam_modes(one, 4, 1.0).frequencies
>>> bool(np.allclose(f2, f1, rtol=1e-9))
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from .fem import component_matrices, dof_owner, dof_slopes, field_rows

__all__ = ["BranchedBeam", "Component", "Coupling", "Joint", "assemble_branched"]


@dataclass(frozen=True)
class Component:
    """One beam of a branched structure (rotor units, stations in fractions of R).

    Parameters
    ----------
    name : str
        Name the joints and couplings refer to (``"flexbeam"``, ``"blade"``).
    x_nodes : numpy.ndarray
        Node stations [fraction of R], increasing.
    section : callable
        ``section(x) -> dict`` of nondimensional section properties, as for
        :func:`tefcore.structure.fem.assemble_beam`.
    pitch : callable
        ``pitch(x)`` [rad]: the beam's built-in and collective pitch.
    tension : callable
        ``tension(x)``: this beam's own centrifugal tension per Omega^2
        (rotor units; negative: compression).
    """

    name: str
    x_nodes: np.ndarray
    section: Callable = field(repr=False)
    pitch: Callable = field(repr=False)
    tension: Callable = field(repr=False)


@dataclass(frozen=True)
class Joint:
    """Multi-point constraint: node ``slave_node`` of ``slave`` moves with ``master_node``
    of ``master`` (all six node dofs; the two nodes must be at the same station).

    Parameters
    ----------
    master : str
        Component whose dofs are kept.
    master_node : int
        Its node index (0 = inboard end).
    slave : str
        Component whose node dofs are eliminated.
    slave_node : int
        Its node index.
    """

    master: str
    master_node: int
    slave: str
    slave_node: int


@dataclass(frozen=True)
class Coupling:
    """Spring and damper on ``b^T q = sum coefficient * field(component, station)``.

    Parameters
    ----------
    name : str
        Name of the coupling (its row is kept in :attr:`BranchedBeam.couplings`).
    terms : tuple
        ``(component, station, field, coefficient)`` with ``field`` one of
        ``u, v, dv, w, dw, phi`` (see :func:`tefcore.structure.fem.field_rows`).
    stiffness : float
        Spring on ``b^T q`` (rotor units); enters the elastic stiffness, so it
        scales as 1/Omega^2 with rotor speed.
    damping : float
        Damper on ``b^T q`` (rotor units); enters the damping matrix.
    """

    name: str
    terms: tuple
    stiffness: float = 0.0
    damping: float = 0.0


@dataclass
class BranchedBeam:
    """Assembled branched beam with its constraints (rotor units).

    The same interface as :class:`tefcore.structure.fem.BeamModel`:
    ``mass, k_elastic, k_centrifugal, damping_matrix, gyroscopic, free,
    pitch, stiffness(r), damping(r), owner, slopes, evaluate``.  Built by
    :func:`assemble_branched`.

    Parameters
    ----------
    components : dict
        Component name -> :class:`Component`.
    index : dict
        Component name -> global index of each of its dofs (after the joints).
    mass, k_elastic, k_centrifugal, damping_matrix, gyroscopic : numpy.ndarray
        Global matrices, rotor units; the stiffness at a rotor-speed ratio
        ``r`` is ``k_elastic / r**2 + k_centrifugal``.
    free : numpy.ndarray
        Global dofs not clamped.
    owner : numpy.ndarray
        Field group (index into :data:`tefcore.structure.fem.FIELD_GROUPS`) of every dof.
    slopes : numpy.ndarray
        True for the slope dofs (``dv, dw``).
    span : tuple
        Components, in order, whose stations cover the blade from the
        structural root to the tip; fields are evaluated on the first that
        contains a station.
    couplings : dict
        Coupling name -> its global row ``b``.
    pitch : callable, optional
        The blade's pitch, for the section-inertia checks.
    """

    components: dict
    index: dict                       # component name -> global index of its dofs
    mass: np.ndarray
    k_elastic: np.ndarray
    k_centrifugal: np.ndarray
    damping_matrix: np.ndarray
    gyroscopic: np.ndarray
    free: np.ndarray
    owner: np.ndarray
    slopes: np.ndarray
    span: tuple
    couplings: dict = field(default_factory=dict)     # name -> global row b
    pitch: Callable = field(default=None, repr=False)

    @property
    def n_dof(self) -> int:
        return self.mass.shape[0]

    def stiffness(self, speed_ratio: float = 1.0) -> np.ndarray:
        return self.k_elastic / speed_ratio**2 + self.k_centrifugal

    def damping(self, speed_ratio: float = 1.0) -> np.ndarray:
        return self.damping_matrix / speed_ratio

    def rows(self, component: str, x) -> dict[str, np.ndarray]:
        """Global rows of the fields of one component at stations ``x``."""
        local = field_rows(self.components[component].x_nodes, x)
        out = {}
        for name, r in local.items():
            g = np.zeros((r.shape[0], self.n_dof))
            g[:, self.index[component]] = r      # a component's global dofs are distinct
            out[name] = g
        return out

    def component_fields(self, component: str, vectors, x) -> dict[str, np.ndarray]:
        """Fields of global dof vectors on one component at ``x``, each (len(x), k)."""
        vec = np.asarray(vectors).reshape(self.n_dof, -1)
        local = vec[self.index[component]]
        return {k: r @ local for k, r in
                field_rows(self.components[component].x_nodes, x).items()}

    def evaluate(self, vectors: np.ndarray, x) -> dict[str, np.ndarray]:
        """Fields of global dof vectors at stations ``x`` along ``span``.

        Returns ``u, du, v, dv, ddv, w, dw, ddw, phi, dphi``, each (len(x), k).
        """
        x = np.atleast_1d(np.asarray(x, float))
        vec = np.asarray(vectors).reshape(self.n_dof, -1)
        owner = np.full(x.shape, -1)
        for i, name in reversed(list(enumerate(self.span))):
            xn = self.components[name].x_nodes
            owner[(x >= xn[0] - 1e-12) & (x <= xn[-1] + 1e-12)] = i
        if np.any(owner < 0):
            lo = min(self.components[n].x_nodes[0] for n in self.span)
            hi = max(self.components[n].x_nodes[-1] for n in self.span)
            raise ValueError(f"stations must lie in [{lo}, {hi}]")
        out = None
        for i, name in enumerate(self.span):
            sel = owner == i
            if not sel.any():
                continue
            part = self.component_fields(name, vec, x[sel])
            if out is None:
                out = {k: np.zeros((x.size, vec.shape[1])) for k in part}
            for k, v in part.items():
                out[k][sel] = v
        return out


def _numbering(components: Sequence[Component], joints: Sequence[Joint]) -> dict:
    """Global index of every component dof, slave nodes numbered as their masters."""
    index: dict[str, np.ndarray] = {}
    next_free = 0
    by_slave = {}
    for j in joints:
        if (j.slave, j.slave_node) in by_slave:
            raise ValueError(f"node {j.slave_node} of {j.slave!r} is constrained twice")
        by_slave[(j.slave, j.slave_node)] = j
    names = [c.name for c in components]
    for c in components:
        n_el = len(c.x_nodes) - 1
        n_dof = 6 * (n_el + 1) + 3 * n_el
        idx = np.full(n_dof, -1)
        for node in range(n_el + 1):
            j = by_slave.get((c.name, node))
            if j is None:
                continue
            if j.master not in index:
                raise ValueError(f"joint master {j.master!r} must come before {c.name!r} "
                                 f"(components: {names})")
            xm = components[names.index(j.master)].x_nodes[j.master_node]
            if abs(xm - c.x_nodes[node]) > 1e-12:
                raise ValueError(f"joint nodes at different stations: {j.master}[{j.master_node}]"
                                 f" = {xm}, {c.name}[{node}] = {c.x_nodes[node]}")
            idx[6 * node:6 * node + 6] = index[j.master][6 * j.master_node:6 * j.master_node + 6]
        own = idx < 0
        idx[own] = next_free + np.arange(own.sum())
        next_free += int(own.sum())
        index[c.name] = idx
    return index


def assemble_branched(components: Sequence[Component], joints: Sequence[Joint] = (),
                      couplings: Sequence[Coupling] = (), clamps: Sequence = (),
                      span: Sequence[str] | None = None,
                      pitch: Callable | None = None) -> BranchedBeam:
    """Assemble beams, joints, point springs/dampers and clamps.

    Parameters
    ----------
    components : sequence of Component
        Joint masters must come before their slaves.
    joints : sequence of Joint
        Multi-point constraints (the clevis).
    couplings : sequence of Coupling
        Point springs and dampers (pitch link, snubber).
    clamps : sequence of (component, node)
        Nodes whose six dofs are fixed.
    span : sequence of str, optional
        Components on which :meth:`BranchedBeam.evaluate` reads the blade
        (default: all, outboard first).
    pitch : callable, optional
        The blade's pitch for :class:`tefcore.structure.section_inertia` checks
        (default: the first component of ``span``).

    Returns
    -------
    BranchedBeam
    """
    names = [c.name for c in components]
    if len(set(names)) != len(names):
        raise ValueError(f"component names must be unique, got {names}")
    index = _numbering(components, joints)
    n = 1 + max(int(i.max()) for i in index.values())
    mats = [np.zeros((n, n)) for _ in range(4)]
    owner, slopes = np.full(n, -1), np.zeros(n, dtype=bool)
    for c in components:
        idx = index[c.name]
        n_el = len(c.x_nodes) - 1
        block = np.ix_(idx, idx)        # distinct within a component: a plain += adds
        for total, local in zip(mats, component_matrices(c.x_nodes, c.section, c.pitch,
                                                         c.tension), strict=True):
            total[block] += local
        owner[idx], slopes[idx] = dof_owner(n_el), dof_slopes(n_el)
    mass, k_el, k_cf, gyro = mats
    damp = np.zeros((n, n))
    beam = BranchedBeam({c.name: c for c in components}, index, mass, k_el, k_cf, damp, gyro,
                        np.arange(n), owner, slopes,
                        tuple(span or sorted(names, key=lambda m: -components[
                            names.index(m)].x_nodes[-1])))
    fixed = set()
    for comp, node in clamps:
        fixed.update(index[comp][6 * node:6 * node + 6].tolist())
    cache: dict = {}
    for cp in couplings:
        b = np.zeros(n)
        for comp, x, fname, coef in cp.terms:
            if (comp, x) not in cache:
                cache[(comp, x)] = beam.rows(comp, [x])
            b += coef * cache[(comp, x)][fname][0]
        beam.couplings[cp.name] = b
        k_el += cp.stiffness * np.outer(b, b)
        damp += cp.damping * np.outer(b, b)
    beam.free = np.setdiff1d(np.arange(n), sorted(fixed))
    beam.pitch = pitch or components[names.index(beam.span[0])].pitch
    return beam
