"""Why a mode is (un)stable: its growth rate as the work of named physical terms.

The linearised equations (the paper's eq. 5) are a sum of physical terms --
blade inertia and stiffness, the flap's inertial couplings, the flap's
pitching moment on the blade, the hinge moments, the actuator spring ...
(:data:`TERMS`, docs/theory.md section 10).  :func:`mechanism` takes one root
and

* **decomposes its growth rate exactly** into the terms (an energy balance:
  the net work per cycle that each term does on the mode, over twice the
  mode's energy), with the frequency apportioned by the energy each term
  stores; for a real root (divergence), the static balance of stiffnesses;
* **knocks each term out** and follows the root by continuation while the
  term is scaled from 1 to 0 (:func:`tefcore.modes.tracking.follow_root`),
  reporting the root it becomes;
* tells **flutter** (a complex pair with positive real part) from
  **divergence** (a real root crossing zero).

Which root: ``"TEF"`` is the root that the flap mode becomes when the
blade-flap coupling is switched on (:mod:`tefcore.modes.continuation`: the
uncoupled flap on its actuator, continued to the full coupling),
``"flutter"`` the least stable flap-induced root
(:func:`tefcore.modes.roles.flutter_root`), or a name of the stability table
(``"blade torsion 1"``); by default the flutter root where it is unstable.

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart").with_overrides({"flight.advance_ratio": 0.0})
>>> res = mechanism(cfg, mode="TEF", knockouts=False)
>>> bool(abs(res.closure) < 1e-8)
True
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..floquet.second_order import SecondOrderSystem, augmented_state_matrix, combine
from ..model.coupled import FLAP_PIECES
from ..modes.continuation import positive_roots, root_solver, tef_root
from ..modes.roles import FLUTTER_PARTICIPATION, flutter_root
from ..modes.tracking import FollowResult, follow_root
from ..runtime import blas_limit

__all__ = ["FLUTTER_PARTICIPATION", "NOT_REMOVABLE", "STATE_TERMS", "TERMS", "MechanismResult",
           "energy_decomposition", "flutter_root", "linearized_terms", "mechanism"]

#: Named terms of the linearised equations: name -> list of (residual piece,
#: block).  Blocks: ``R`` blade rows/columns, ``F`` the flap's, ``W`` the
#: shed-wake states', ``V`` the dynamic-inflow states', ``*`` all; ``"all"`` the
#: whole matrix.  Every (piece, block) of the residual belongs to exactly one
#: term, so the terms add up to the linearised system (tested).  The
#: aerodynamic states' terms exist only with those states (docs/theory.md 10.1).
TERMS = {
    "blade inertia": [("blade inertia", "all")],
    "blade stiffness": [("blade stiffness", "all")],
    "blade structural damping": [("blade structural damping", "all")],
    "blade Coriolis": [("blade Coriolis", "all")],
    "blade airloads": [("airload normal force", "RR"), ("airload in-plane force", "RR"),
                       ("airload pitching moment", "RR"), ("airload normal force", "F*"),
                       ("airload in-plane force", "F*"), ("airload pitching moment", "F*")],
    "flap lift on blade (C_l_delta)": [("airload normal force", "RF"),
                                       ("airload in-plane force", "RF")],
    "flap moment on blade torsion (C_m_delta)": [("airload pitching moment", "RF")],
    "hinge moment from blade motion (C_h_alpha)": [("airload hinge moment", "FR"),
                                                   ("airload hinge moment", "RR"),
                                                   ("airload hinge moment", "RF")],
    "hinge moment from flap motion (C_h_delta)": [("airload hinge moment", "FF")],
    "flap inertial coupling to bending (S_f)": [("flap inertial coupling to bending", "all")],
    "flap inertial coupling to torsion (I_h - S_f eta_h)": [
        ("flap inertial coupling to torsion", "all")],
    "flap inertia (I_h)": [("flap inertia", "all")],
    "flap propeller stiffness": [("flap centrifugal", "FF")],
    "flap centrifugal coupling": [("flap centrifugal", "RR"), ("flap centrifugal", "RF"),
                                  ("flap centrifugal", "FR")],
    "flap Coriolis": [("flap Coriolis", "all")],
    "actuator spring (k_a)": [("actuator spring", "all")],
    "actuator damper (c_a)": [("actuator damper", "all")],
    "shed wake on blade airloads (1 - C)": [("shed wake normal force", "R*"),
                                            ("shed wake in-plane force", "R*"),
                                            ("shed wake pitching moment", "R*"),
                                            ("shed wake normal force", "F*"),
                                            ("shed wake in-plane force", "F*"),
                                            ("shed wake pitching moment", "F*")],
    "shed wake on hinge moment (1 - C)": [("shed wake hinge moment", "F*"),
                                          ("shed wake hinge moment", "R*")],
    "dynamic inflow on airloads": [("airload normal force", "RV"),
                                   ("airload in-plane force", "RV"),
                                   ("airload pitching moment", "RV"),
                                   ("airload hinge moment", "FV")],
    "shed wake dynamics": [("shed wake dynamics", "all")],
    "inflow dynamics": [("inflow dynamics", "all")],
    "inflow forcing (rotor loads)": [("inflow forcing", "all")],
}
#: Terms of the aerodynamic states (present only with ``model.aero = "unsteady"``
#: or ``model.inflow = "dynamic"``).
STATE_TERMS = ("shed wake on blade airloads (1 - C)", "shed wake on hinge moment (1 - C)",
               "dynamic inflow on airloads", "shed wake dynamics", "inflow dynamics",
               "inflow forcing (rotor loads)")
#: Terms that are a coordinate's own inertia or the blade's structure:
#: knocking them out leaves no mode to follow (a singular mass matrix, or a
#: blade without stiffness), so no knockout is reported for them.
NOT_REMOVABLE = ("blade inertia", "flap inertia (I_h)", "blade stiffness",
                 "shed wake dynamics", "inflow dynamics")


def _groups(model) -> dict:
    """Row and column groups of the linearised system: R, F, W, V, *."""
    nm, nd, nw = model.n_modes, model.n_dof, model.n_wake
    return {"R": slice(0, nm), "F": slice(nm, nd), "W": slice(nd, nd + nw),
            "V": slice(nd + nw, nd + nw + model.n_inflow), "*": slice(None)}


def _block(mat, block, groups):
    """The part of ``mat`` (..., n, n) in a block, zero elsewhere."""
    out = np.zeros_like(mat)
    if block == "all":
        return mat.copy()
    r, c = groups[block[0]], groups[block[1]]
    out[..., r, c] = mat[..., r, c]
    return out


def linearized_terms(tr, psi=None) -> dict[str, SecondOrderSystem]:
    """The linearised system about a trim, term by term (:data:`TERMS`).

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim to linearise about.
    psi : array_like, optional
        Azimuths (default: one in hover, the trim grid in forward flight,
        as :func:`tefcore.linear.stability.linear_system`).

    Returns
    -------
    dict of str to SecondOrderSystem
        Terms present in the model (without a flap, the flap terms are
        absent); their sum is the linearised system.
    """
    from ..model.jacobian import jacobian_blocks

    model = tr.model
    if psi is None:
        psi = (np.zeros(1) if model.hover else
               np.linspace(0, 2 * np.pi, model.cfg.model.n_azimuth, endpoint=False))
    y, yd, ydd, inflow = tr.linear_point(psi)
    jac, _, _ = jacobian_blocks(model, psi, y, yd, ydd, tr.controls, inflow, step=1e-6,
                                scheme="exact", pieces=True, n_second=model.n_dof)
    groups = _groups(model)
    n_first = model.n_wake + model.n_inflow
    out = {}
    for name, parts in TERMS.items():
        if not model.has_flap and any(p in FLAP_PIECES for p, _ in parts):
            continue
        # the aerodynamic states' terms: only with those states
        if any(p not in jac for p, _ in parts) or any(
                g in b and groups[g].start == groups[g].stop for _, b in parts for g in "WV"):
            continue
        mats = [sum(_block(jac[p][which], b, groups) for p, b in parts) for which in (2, 1, 0)]
        out[name] = SecondOrderSystem(*mats, n_first=n_first)
    return out


# ------------------------------------------------------------------ roots


# ------------------------------------------------------------------ energy


def _herm(a):
    return 0.5 * (a + np.swapaxes(a, -1, -2).conj())


def _quad(x, a, y):
    """``x^H A y`` per azimuth: x, y (n_psi, n), A (n_psi, n, n)."""
    return np.einsum("pi,pij,pj->p", x.conj(), a, y)


def _summed(parts, psi):
    """``M, C, K`` of the whole system at ``psi``: the terms' matrices added in order."""
    m = c = k = 0
    for p in parts.values():
        with p.transient_coefficients():
            mt, ct, kt = p.matrices(psi)
        m, c, k = m + mt, c + ct, k + kt
    return m, c, k


def _term_matrices(parts, psi, periodic):
    """``(term, (M, C, K), their psi-derivatives or None)`` one term at a time: the
    matrices of all terms at once held 0.55 GiB with the shed wake (72 azimuths,
    82 coordinates and states, 20 terms, measured), the largest process of the
    reproduction.  A term's matrices are computed once the caller has dropped
    the previous term's (it holds only what it yields)."""
    for t, p in parts.items():
        # the term's Fourier coefficients for these two evaluations only
        # (SecondOrderSystem.transient_coefficients: kept, the 20 terms of the
        # shed wake's balance held 80 MiB at the peak)
        with p.transient_coefficients():
            mats = p.matrices(psi)
            dmats = p.matrices(psi, 1) if periodic else None
        yield t, mats, dmats
        del mats, dmats


def energy_decomposition(parts: dict, exponent: complex, shape, psi):
    """Contributions of each term to one root's exponent (exact, docs/theory.md section 10).

    Parameters
    ----------
    parts : dict of str to SecondOrderSystem
        The terms; their sum is the system of the root.
    exponent : complex
        The root's exponent ``eta = sigma + i omega``.
    shape : ndarray, shape (n_psi, 2 n + r)
        Its periodic state shape ``[p_q; p_v; p_z]`` at the azimuths ``psi``
        (one row: constant coefficients; ``p_z`` the ``r`` first-order states).
    psi : ndarray, shape (n_psi,)
        Equally spaced azimuths over the period (``[0]`` if constant).

    Returns
    -------
    dict of str to complex
        ``contribution_real + i contribution_imag`` per term: for an
        oscillatory root, the net work per cycle of the term over twice the
        mode's energy (real) and the frequency times the share of the energy
        the term stores (imaginary); for a real root, the static balance
        (imaginary parts 0).  The real parts add up to ``sigma``.  The energy
        is that of the blade and flap; first-order (aerodynamic) states are
        forces on them (docs/theory.md 10.1): a term's work includes the work
        of its state columns, and the state equations themselves do none.
    """
    first = next(iter(parts.values()))
    if first.n_first:
        return _energy_with_states(parts, exponent, shape, psi)
    n = first.n_dof
    psi = np.atleast_1d(np.asarray(psi, float))
    periodic = first.periodic
    m, c, k = _summed(parts, psi)
    pq, pv = shape[:, :n], shape[:, n:]
    pa = -np.linalg.solve(m, (np.einsum("pij,pj->pi", c, pv)
                              + np.einsum("pij,pj->pi", k, pq))[..., None])[..., 0]
    sigma, omega = exponent.real, exponent.imag
    if abs(omega) > 1e-9:
        denom = np.mean(_quad(pv, _herm(m), pv) + _quad(pq, _herm(k), pq)).real
        out = {}
        for t, (mt, ct, kt), dmat in _term_matrices(parts, psi, periodic):
            mn, kn = mt - _herm(mt), kt - _herm(kt)
            work = -np.real(_quad(pv, mn, pa) + _quad(pv, ct, pv) + _quad(pv, kn, pq))
            if periodic:
                dm, _, dk = dmat
                work = work + 0.5 * np.real(_quad(pv, _herm(dm), pv) + _quad(pq, _herm(dk), pq))
            stored = np.real(_quad(pv, _herm(mt), pv) + _quad(pq, _herm(kt), pq))
            out[t] = complex(np.mean(work) / denom, omega * np.mean(stored) / denom)
            del mt, ct, kt, dmat        # before the next term's matrices are made
        return out
    # real root: sigma (sigma <p M p> + <2 p M p' + p C p>) = -<p (M p'' + C p' + K p)>
    if periodic:
        dp = pv - sigma * pq
        ddp = pa - sigma**2 * pq - 2 * sigma * dp
    else:          # constant coefficients: the shape is constant, p' = p'' = 0
        dp = ddp = np.zeros_like(pq)
    denom = np.mean(sigma * _quad(pq, m, pq) + 2 * _quad(pq, m, dp) + _quad(pq, c, pq))
    return {t: complex(np.real(-np.mean(_quad(pq, mt, ddp) + _quad(pq, ct, dp)
                                        + _quad(pq, kt, pq)) / denom), 0.0)
            for t, (mt, ct, kt), _ in _term_matrices(parts, psi, False)}


def _energy_with_states(parts, exponent, shape, psi):
    """:func:`energy_decomposition` with first-order states ``z`` (docs/theory.md 10.1).

    The structural rows read ``M q** + C q* + K q + C_qz z* + K_qz z = 0``; with
    ``x = e^{eta psi} p`` the shape of the state rate is ``A p`` (``= eta p + p'``),
    which gives ``p_a`` (of ``q**``) and ``p_zd`` (of ``z*``).  The energy is the
    blade and flap's, ``E = 1/2 (q*^H M^h q* + q^H K^h q)`` over the ``q`` blocks;
    the state columns are forces whose work is each term's ``-Re q*^H (C_qz z* +
    K_qz z)``.  The balance closes exactly as in the second-order case.
    """
    sys0 = next(iter(parts.values()))
    n = sys0.n_dof
    psi = np.atleast_1d(np.asarray(psi, float))
    periodic = sys0.periodic
    m, c, k = _summed(parts, psi)
    rate = np.einsum("pij,pj->pi", augmented_state_matrix(m, c, k, n), shape)
    pq, pv, pz = shape[:, :n], shape[:, n:2 * n], shape[:, 2 * n:]
    pa, pzd = rate[:, n:2 * n], rate[:, 2 * n:]
    q = slice(0, n)
    sigma, omega = exponent.real, exponent.imag

    def state_force(ct, kt):
        return (np.einsum("pij,pj->pi", ct[:, q, n:], pzd)
                + np.einsum("pij,pj->pi", kt[:, q, n:], pz))

    if abs(omega) > 1e-9:
        mq, kq = m[:, q, q], k[:, q, q]
        denom = np.mean(_quad(pv, _herm(mq), pv) + _quad(pq, _herm(kq), pq)).real
        out = {}
        for t, (mt, ct, kt), dmat in _term_matrices(parts, psi, periodic):
            mtq, ctq, ktq = mt[:, q, q], ct[:, q, q], kt[:, q, q]
            mn, kn = mtq - _herm(mtq), ktq - _herm(ktq)
            force = (np.einsum("pij,pj->pi", mn, pa) + np.einsum("pij,pj->pi", ctq, pv)
                     + np.einsum("pij,pj->pi", kn, pq) + state_force(ct, kt))
            work = -np.real(np.einsum("pi,pi->p", pv.conj(), force))
            if periodic:
                dm, _, dk = dmat
                work = work + 0.5 * np.real(_quad(pv, _herm(dm[:, q, q]), pv)
                                            + _quad(pq, _herm(dk[:, q, q]), pq))
            stored = np.real(_quad(pv, _herm(mtq), pv) + _quad(pq, _herm(ktq), pq))
            out[t] = complex(np.mean(work) / denom, omega * np.mean(stored) / denom)
            del mt, ct, kt, dmat        # before the next term's matrices are made
        return out
    # real root: the static balance with the state forces on the right
    if periodic:
        dp = pv - sigma * pq
        ddp = pa - sigma**2 * pq - 2 * sigma * dp
    else:
        dp = ddp = np.zeros_like(pq)
    denom = np.mean(sigma * _quad(pq, m[:, q, q], pq) + 2 * _quad(pq, m[:, q, q], dp)
                    + _quad(pq, c[:, q, q], pq))
    out = {}
    for t, (mt, ct, kt), _ in _term_matrices(parts, psi, False):
        force = (np.einsum("pij,pj->pi", mt[:, q, q], ddp)
                 + np.einsum("pij,pj->pi", ct[:, q, q], dp)
                 + np.einsum("pij,pj->pi", kt[:, q, q], pq) + state_force(ct, kt))
        out[t] = complex(np.real(-np.mean(np.einsum("pi,pi->p", pq.conj(), force)) / denom), 0.0)
        del mt, ct, kt
    return out


# ------------------------------------------------------------------ the diagnosis


@dataclass
class MechanismResult:
    """Result of :func:`mechanism`.

    Attributes
    ----------
    table : DataFrame
        ``term, contribution_real, contribution_imag``: one row per term,
        then ``total`` (the root's eigenvalue) and ``knockout <term>`` (the
        root's eigenvalue with that term removed) -- the CSV of
        ``tefcore mechanism``.
    eigenvalue : complex
        The root (exponent per radian of azimuth).
    kind : str
        ``"flutter"`` (oscillatory, growing), ``"divergence"`` (real,
        growing), ``"stable oscillatory"`` or ``"stable real"``.
    closure : float
        Sum of the terms' real contributions minus the root's real part
        (numerical error of the decomposition).
    participation : dict of str to float
        The root's participation by kind of coordinate (``share_*``).
    label : str
        The root's label in the stability table.
    identification : str
        How the root was chosen, and whether its identity is certain.
    knockouts : dict of str to FollowResult
    """

    table: pd.DataFrame
    eigenvalue: complex
    kind: str
    closure: float
    participation: dict
    label: str
    identification: str
    knockouts: dict = field(default_factory=dict, repr=False)

    def summary(self) -> str:
        """A few lines for a student: what kind of instability, and who drives it."""
        terms = self.table[~self.table["term"].str.startswith(("total", "knockout"))]
        terms = terms.reindex(terms["contribution_real"].abs().sort_values(
            ascending=False, kind="stable").index)
        lines = [f"root {self.label}: {self.eigenvalue.real:+.3f} {self.eigenvalue.imag:+.3f}i "
                 f"/rev ({self.kind}); identified by {self.identification}",
                 "participation: " + ", ".join(f"{k} {v:.2f}" for k, v in
                                               self.participation.items() if v >= 0.005)]
        for row in terms.head(5).itertuples(index=False):
            lines.append(f"  {row.term}: {row.contribution_real:+.3f} /rev")
        lines.append(f"  (closure {self.closure:.1e})")
        return "\n".join(lines)


def _classify(eta: complex) -> str:
    growing = eta.real > 0
    if abs(eta.imag) <= 1e-9:
        return "divergence" if growing else "stable real"
    return "flutter" if growing else "stable oscillatory"


def _root_row(mode, res, eig_table, basis, n_steps, root):
    """Row of the stability table that `mode` names, and how it was identified."""
    table = res.modes
    named = "real_part_uncoupled" in table         # named by continuation
    if mode is None:
        row = flutter_root(table) if res.trim_result.model.has_flap else None
        if row is not None and table.at[row, "real_part"] > 0:
            return row, (f"the flutter root (no mode asked for): {_flutter_rule(named)}, "
                         f"from {table.at[row, 'label']}")
        mode = "TEF"
    if mode == "TEF":
        rows = np.flatnonzero(table["label"].to_numpy() == "TEF")
        if named and rows.size:
            return int(rows[0]), "the root the uncoupled flap mode continues into"
        eta, follow = tef_root(res.system, basis=basis, n_steps=n_steps)
        row = int(np.argmin(np.abs(eig_table - eta)))
        how = "continuation from the uncoupled flap mode"
        if not follow.clear and rows.size:
            # the flap's own root met another on the way (a coalescence):
            # which one it becomes is not decidable, so say so and take the
            # root that the flap participates in most (its label)
            row = int(rows[0])
            how = ("its label (largest flap participation): the continuation from the "
                   "uncoupled flap mode met a coalescence at coupling "
                   f"{follow.ambiguous[0]:.3g} and is ambiguous")
        return row, how
    if mode == "flutter":
        row = flutter_root(table)
        if row is None:
            raise ValueError("no flap-induced root (the configuration has no flap)")
        return row, f"{_flutter_rule(named)}, from {table.at[row, 'label']}"
    if mode == "root":
        if root is None:
            raise ValueError("mode 'root' needs the root's eigenvalue (root=...)")
        return (int(np.argmin(np.abs(eig_table - complex(root)))),
                f"the root nearest {complex(root):.4g}")
    rows = np.flatnonzero(table["label"].to_numpy() == mode)
    if rows.size == 0:
        raise ValueError(f"no mode named {mode!r}; names: {table['label'].tolist()}; "
                         "or use 'TEF' or 'flutter'")
    return int(rows[0]), ("the root continuing from that uncoupled mode" if named
                          else "its label (participation)")


def _flutter_rule(named: bool) -> str:
    if named:
        return ("the least stable flap-induced root (unstable, or much less stable, with "
                "the flap held)")
    return f"the least stable root with flap participation >= {FLUTTER_PARTICIPATION}"


@blas_limit()
def mechanism(cfg, mode: str | None = None, *, knockouts: bool = True, stability_result=None,
              n_steps: int | None = None, root: complex | None = None) -> MechanismResult:
    """Diagnose one root of a configuration: energy balance, knockouts, kind.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.
    mode : str, optional
        ``"TEF"`` (the root the uncoupled flap mode continues into),
        ``"flutter"`` (the least stable flap-induced root,
        :func:`tefcore.modes.roles.flutter_root`), ``"root"`` (the root nearest
        `root`, e.g. the TEF branch of a sweep at this point) or a name of the
        stability table (e.g. ``"blade torsion 1"``).  None (default): the
        flutter root when it is unstable, else the TEF; ``identification``
        says which.
    root : complex, optional
        Eigenvalue (/rev) for ``mode="root"``.
    knockouts : bool
        Also follow the root with each removable term knocked out.
    stability_result : StabilityResult, optional
        Of ``cfg``, if already computed.
    n_steps : int, optional
        Floquet steps (default ``cfg.model.n_floquet_steps``).

    Returns
    -------
    MechanismResult

    Raises
    ------
    ValueError
        Unknown `mode`, or the configuration has no flap for a flap mode.
    """
    from .stability import stability

    res = stability_result or stability(cfg)
    tr = res.trim_result
    model = tr.model
    n_steps = n_steps or cfg.model.n_floquet_steps
    table = res.modes
    basis = model.tracking_basis()
    eig_table = table["real_part"].to_numpy() + 1j * table["frequency_per_rev"].to_numpy()
    if mode in ("TEF", "flutter") and not model.has_flap:
        raise ValueError(f"mode {mode!r} needs the flap: model.tef is {cfg.model.tef!r}")
    if mode is None and not model.has_flap:
        raise ValueError("without the flap, name the mode (e.g. 'blade lag 1')")
    row, how = _root_row(mode, res, eig_table, basis, n_steps, root)
    parts = linearized_terms(tr)
    system = combine(parts)
    full = positive_roots(system.modes(n_steps=n_steps, n_sub=4, shapes=True,
                                  participation=False))
    j = int(np.argmin(np.abs(full.exponents - eig_table[row])))
    eta = complex(full.exponents[j])
    if full.shapes is None:
        shape, psi = full.eigenvectors[:, j][None, :], np.zeros(1)
    else:
        shape, psi = full.shapes[:, :, j], full.psi
    contrib = energy_decomposition(parts, eta, shape, psi)
    rows_out = [{"term": t, "contribution_real": v.real, "contribution_imag": v.imag}
                for t, v in contrib.items()]
    rows_out.append({"term": "total", "contribution_real": eta.real,
                     "contribution_imag": eta.imag})
    outs = {}
    if knockouts:
        n = system.n_dof
        vec0 = full.eigenvectors[:n]
        first = (full.exponents, basis @ vec0)
        for t, part in parts.items():
            if t in NOT_REMOVABLE:
                continue
            if not any(np.any(a) for a in (part.m, part.c, part.k)):
                f = FollowResult(index=j, eigenvalue=eta, path=[(1.0, eta)], ambiguous=[])
            else:
                solve = root_solver(lambda s, t=t: combine(parts, {t: s}), n, basis, n_steps)
                f = follow_root(solve, 1.0, 0.0, j, periodic=system.periodic, first=first,
                                n_steps=4, max_halvings=5)
            outs[t] = f
            rows_out.append({"term": f"knockout {t}", "contribution_real": f.eigenvalue.real,
                             "contribution_imag": f.eigenvalue.imag})
    out = pd.DataFrame(rows_out, columns=["term", "contribution_real", "contribution_imag"])
    closure = float(sum(v.real for v in contrib.values()) - eta.real)
    share = {k.removeprefix("share_"): float(table[k].iloc[row])
             for k in table.columns if k.startswith("share_")}
    return MechanismResult(table=out, eigenvalue=eta, kind=_classify(eta), closure=closure,
                           participation=share, label=str(table["label"].iloc[row]),
                           identification=how, knockouts=outs)
