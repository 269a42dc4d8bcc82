"""Jacobians of the coupled blade/flap residual with respect to the motion.

:func:`jacobian_blocks` differentiates the residual of
:meth:`tefcore.coupled.CoupledModel.evaluate` (or each of its named pieces,
:meth:`~tefcore.coupled.CoupledModel.residual_pieces`) with respect to the
coordinates ``q`` and their azimuth derivatives ``q*`` and ``q**``, azimuth by
azimuth: the trim's Newton steps, the linearisation about the trim and the
mechanism's term-by-term systems all use it.  The residual at one azimuth
depends only on the motion there, so all perturbed motions are stacked along
the azimuth axis and evaluated in one call.
"""

from __future__ import annotations

import numpy as np

from .aero_states import inflow_fields
from .coupled import Controls, CoupledModel

__all__ = ["jacobian_blocks"]


def _stack_fields(objs, cls, names, n_psi):
    """One ``cls`` whose fields are per-azimuth columns, block after block."""
    return cls(*(np.repeat(np.array([getattr(o, f) for o in objs], float), n_psi)[:, None]
                 for f in names))


def jacobian_blocks(model: CoupledModel, psi, q, qd, qdd, controls, inflow, *,
                    step: float = 1e-7, scheme: str = "forward", extra=(), pieces=False,
                    n_second: int | None = None):
    """Per-azimuth derivatives of the residual and thrust w.r.t. ``q, q*, q**``.

    The residual at one azimuth depends only on the motion there, so every
    perturbed motion is stacked along the azimuth axis and the model is
    evaluated once for all of them (numpy overhead paid once, not 3n times).

    Parameters
    ----------
    extra : sequence of (Controls, Inflow), optional
        Further controls and inflows to evaluate at the unperturbed motion in
        the same stacked call (the trim's control columns).
    pieces : bool
        Differentiate each named piece of the residual
        (:meth:`CoupledModel.residual_pieces`) separately: ``jac`` is then a
        dict piece -> array, whose sum is the Jacobian of the residual.
    model : CoupledModel
        The coupled model.
    psi : numpy.ndarray
        Azimuths [rad].
    q, qd, qdd : numpy.ndarray
        Coordinates and their psi-derivatives at ``psi``, ``(n_dof, n_psi)``.
    controls : Controls
        Pitch controls.
    inflow : tefcore.inflow.Inflow
        Inflow.
    step : float, optional
        Finite-difference step (rotor units).
    scheme : {"forward", "central"}, optional
        Finite-difference scheme.
    n_second : int, optional
        Rows of ``q`` from ``n_second`` on are first-order states (the
        aerodynamic states, docs/theory.md 6.2): their second derivatives are
        not perturbed and their ``q**`` columns are zero.  Default: all rows
        are second-order coordinates.

    Returns
    -------
    jac : ndarray, shape (3, n_psi, n, n), or dict of them
        ``d R_i / d q_j`` for ``q`` (0), ``q*`` (1), ``q**`` (2) at each azimuth.
    dthrust : ndarray, shape (3, n_psi, n) or (k, 3, n_psi, n)
        The same for the thrust contribution (for each of its ``k`` rows,
        when the model returns several).
    base : tuple
        ``(R, thrust)`` at the unperturbed motion (forward scheme) or None;
        with ``extra``, a third item: the list of ``(R, thrust)`` for each
        (residuals summed over the pieces).
    """
    if scheme not in ("central", "forward"):
        raise ValueError(f"scheme must be 'central' or 'forward', got {scheme!r}")
    psi = np.atleast_1d(np.asarray(psi, float))
    n, m = q.shape
    n_second = n if n_second is None else int(n_second)
    signs = (1.0,) if scheme == "forward" else (1.0, -1.0)
    # perturbations per sign: q, q* of every row, q** of the second-order rows
    kk = 2 * n + n_second
    n_pert = kk * len(signs)
    n_base = int(scheme == "forward") + len(extra)
    n_blk = n_pert + n_base
    motion = [np.tile(a, (1, n_blk)) for a in (q, qd, qdd)]
    # block (s, which, j) = s * kk + which * n + j perturbs coordinate j of
    # q, q* or q** by sign s: its m columns in row j
    for s_i, sgn in enumerate(signs):
        for which in range(3):
            rows = np.arange(n if which < 2 else n_second)[:, None]
            cols = ((s_i * kk + which * n) + rows) * m + np.arange(m)
            motion[which][rows, cols] += sgn * step
    if extra:
        # controls and inflow become per-azimuth columns (they broadcast in
        # evaluate): the base values for the perturbed motions, then extras
        base_pairs = [(controls, inflow)] * (n_pert + int(scheme == "forward"))
        pairs = base_pairs + list(extra)
        controls = _stack_fields([p[0] for p in pairs], Controls,
                                 ("collective", "cyclic_cos", "cyclic_sin"), m)
        inflow = _stack_fields([p[1] for p in pairs], type(inflow), inflow_fields(inflow), m)
    args = (np.tile(psi, n_blk), *motion, controls, inflow)
    if pieces:
        parts, thr = model.residual_pieces(*args)
        jac = {name: _difference(r.reshape(n, n_blk, m), n, step, scheme, kk)[0]
               for name, r in parts.items()}
        res = sum(parts.values())
    else:
        res, thr = model.evaluate(*args)
    res = res.reshape(n, n_blk, m)
    thr = np.asarray(thr)
    lead = thr.shape[:-1]
    thr = thr.reshape(lead + (n_blk, m))
    if not pieces:
        jac, r0 = _difference(res, n, step, scheme, kk)
    else:
        r0 = res[:, kk] if scheme == "forward" else None
    if scheme == "forward":
        t0 = thr[..., kk, :]
        dthr = (thr[..., :kk, :] - t0[..., None, :]) / step
        base = (r0, t0)
    else:
        dthr = (thr[..., :kk, :] - thr[..., kk:n_pert, :]) / (2 * step)
        base = None
    if kk < 3 * n:
        dthr = np.concatenate([dthr, np.zeros(lead + (3 * n - kk, m))], axis=-2)
    if extra:
        first = n_blk - len(extra)
        base = (base or (None, None)) + ([(res[:, b], thr[..., b, :])
                                          for b in range(first, n_blk)],)
    return jac, np.swapaxes(dthr.reshape(lead + (3, n, m)), -1, -2), base


def _difference(res, n, step, scheme, kk=None):
    """Finite-difference Jacobian blocks (3, n_psi, n, n) from stacked residuals
    ``res`` (n, n_blocks, n_psi); also the unperturbed residual (forward).
    ``kk`` perturbations per sign (default ``3 n``; fewer: the ``q**`` of the
    last rows were not perturbed, their columns are zero)."""
    m = res.shape[-1]
    k = 3 * n if kk is None else kk
    if scheme == "forward":
        r0 = res[:, k]
        dres = (res[:, :k] - r0[:, None]) / step
    else:
        r0 = None
        dres = (res[:, :k] - res[:, k:2 * k]) / (2 * step)
    if k < 3 * n:
        dres = np.concatenate([dres, np.zeros((n, 3 * n - k, m))], axis=1)
    return dres.reshape(n, 3, n, m).transpose(1, 3, 0, 2), r0
