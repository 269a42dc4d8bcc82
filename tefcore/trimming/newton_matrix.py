"""The trim's Newton matrix, assembled from the residual's per-azimuth blocks.

The residual at one azimuth depends only on ``(q, q*, q**)`` there, so the
Newton matrix of the collocated trim equations (docs/theory.md section 7) is
assembled from the blocks ``dR/dq, dR/dq*, dR/dq**`` of every azimuth
(:mod:`tefcore.model.jacobian`) and the spectral derivative matrices, plus the
columns of the controls and the inflow unknowns.

:func:`newton_matrix` does it at any state of the trim, exactly
(:func:`tefcore.model.jacobian.exact_jacobian`) or by forward differences with
the shed-wake states.  At the solution one Jacobian of the residual serves
both the Newton matrix and the linearisation
(:meth:`tefcore.trimming.trim.TrimResult.final_blocks`): without aerodynamic
states the Newton matrix's blocks are the linearisation; with the
dynamic-inflow states :func:`solution_matrices` takes the Newton matrix from
the linearisation with the states.
"""

from __future__ import annotations

import numpy as np

from ..aero.inflow import drees_gradients
from ..model.jacobian import exact_jacobian, has_exact_jacobian, jacobian_blocks

__all__ = ["DIFFERENCE_STEP", "inflow_tangents", "newton_matrix", "solution_matrices"]

#: Forward-difference step of the Newton matrix with shed-wake states (rotor units).
DIFFERENCE_STEP = 1e-7


def inflow_tangents(model, li, psi):
    """``d lambda / d p`` at the stations for the inflow unknowns ``p`` of the trim,
    each ``(n_psi, n_x)`` (docs/theory.md 6.3).

    Momentum inflow with Drees' gradients,
    ``lambda = fs + l (1 + kx x cos psi + ky x sin psi)`` with ``kx`` a function of
    ``chi = atan2(mu, fs + l)``: ``d kx / d chi = 4/3 [sin^2 chi - (1 - cos chi -
    1.8 mu^2) cos chi] / sin^2 chi``, ``d chi / d l = -mu / (mu^2 + lambda^2)``.
    Pitt-Peters field ``fs + l_0 + x (l_s sin psi + l_c cos psi)``: ``1, x sin psi,
    x cos psi``.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model.
    li : float or tuple of float
        The inflow unknowns (momentum: ``lambda_i``; Pitt-Peters: three).
    psi : numpy.ndarray
        Azimuths [rad].

    Returns
    -------
    list of numpy.ndarray
    """
    x = model.x[None, :]
    c, s = np.cos(psi)[:, None], np.sin(psi)[:, None]
    if model.dynamic_inflow:
        return [np.ones((psi.size, x.size)), x * s, x * c]
    f = model.flight
    mu, fs = f.advance_ratio, f.advance_ratio * np.tan(f.shaft_angle)
    if model.cfg.model.inflow != "linear" or mu == 0.0:
        return [np.ones((psi.size, x.size))]
    kx, ky = drees_gradients(mu, fs + li)
    lam = fs + li
    chi = np.arctan2(mu, lam)
    dkx = 4.0 / 3.0 * (np.sin(chi) ** 2 - (1 - np.cos(chi) - 1.8 * mu**2) * np.cos(chi)) \
        / np.sin(chi) ** 2 * (-mu / (mu**2 + lam**2))
    return [1.0 + kx * x * c + ky * x * s + li * dkx * x * c]


def newton_matrix(prob, x, c, li, inflow):
    """Newton matrix of the trim equations at ``x``, with the residual there.

    Exact (:func:`tefcore.model.jacobian.exact_jacobian`, the control and
    inflow columns by the chain rule) where implemented, else forward
    differences with the control and inflow columns evaluated in the same
    stacked call.

    Parameters
    ----------
    prob : tefcore.trimming.trim._Problem
        The trim equations.
    x : numpy.ndarray
        The unknowns.
    c : tefcore.model.coupled.Controls
        The controls of ``x``.
    li : float or tuple of float
        The inflow unknowns of ``x``.
    inflow : tefcore.aero.inflow.Inflow or tefcore.aero.states.HarmonicInflow
        The inflow field of ``li``.

    Returns
    -------
    jac : numpy.ndarray
        The Newton matrix.
    base : tuple
        ``(R, thrust)`` at ``x``.
    blocks : list of numpy.ndarray
        ``dR/dq, dR/dq*, dR/dq**``, each ``(n_psi, n, n)``.
    """
    model, psi, nq = prob.model, prob.psi, prob.nq
    q = x[:nq].reshape(prob.n, prob.n_psi)
    qd, qdd = q @ prob.d1.T, q @ prob.d2.T
    if has_exact_jacobian(model):
        blocks, tblocks, (res0, thr0), params = exact_jacobian(
            model, psi, q, qd, qdd, c, inflow, inflow_tangents=inflow_tangents(model, li, psi))
        jac = _motion_columns(prob, li, blocks, tblocks)
        _exact_columns(prob, jac, q, li, thr0, params)
        return jac, (res0, thr0), list(blocks)
    # control and inflow columns by forward differences, evaluated at the
    # same motion in the same stacked call as the per-azimuth blocks
    h = DIFFERENCE_STEP
    cols = np.arange(nq, x.size)
    xs = np.repeat(x[None], cols.size, axis=0)
    xs[np.arange(cols.size), cols] += h
    parts = [prob.unpack(v) for v in xs]
    blocks, tblocks, (res0, thr0, perturbed) = jacobian_blocks(
        model, psi, q, qd, qdd, c, inflow, step=h, scheme="forward",
        extra=[(p[1], prob.inflow(p[2])) for p in parts], n_second=model.n_dof)
    jac = _motion_columns(prob, li, blocks, tblocks)
    r0 = np.concatenate([res0.ravel(), prob.scalars(q, thr0, li)])
    for k, (p, (res_k, thr_k)) in zip(cols, zip(parts, perturbed, strict=True), strict=True):
        rk = np.concatenate([res_k.ravel(), prob.scalars(q, thr_k, p[2])])
        jac[:, k] = (rk - r0) / h
    return jac, (res0, thr0), list(blocks)


def solution_matrices(prob, x, tr):
    """The linearisation with the dynamic-inflow states and the Newton matrix, at the solution.

    One exact Jacobian of the residual with the inflow perturbation states
    about the trim (docs/theory.md 6.2, :func:`tefcore.model.jacobian.exact_jacobian`),
    on the trim's grid: its blocks are the linearisation, and their rows and
    columns of the trim's unknowns, with the control and inflow columns of
    the same evaluation (the inflow states are zero at the trim, so the
    motion's blocks are those of the trim equations), are the Newton matrix
    at the solution.

    Parameters
    ----------
    prob : tefcore.trimming.trim._Problem
        The trim equations.
    x : numpy.ndarray
        The solution.
    tr : tefcore.trimming.trim.TrimResult
        The trim (its :meth:`~tefcore.trimming.trim.TrimResult.linear_point`).

    Returns
    -------
    jac : numpy.ndarray
        The Newton matrix at the solution.
    blocks : tuple of numpy.ndarray
        ``(K, C, M)`` of the coordinates and the inflow states, each
        ``(n_psi, n_y, n_y)``.

    Raises
    ------
    ValueError
        For a model with shed-wake states, which the exact Jacobian does not cover.
    """
    model, psi, n = prob.model, prob.psi, prob.n
    y, yd, ydd, inflow = tr.linear_point(psi)
    q, c, li = prob.unpack(x)
    lin, tblocks, (_, thr0), (d_res, d_thr) = exact_jacobian(
        model, psi, y, yd, ydd, c, inflow, inflow_tangents=inflow_tangents(model, li, psi))
    jac = _motion_columns(prob, li, [b[:, :n, :n] for b in lin], tblocks[..., :n])
    _exact_columns(prob, jac, q, li, thr0, (d_res[:, :n], d_thr))
    return jac, (lin[0], lin[1], lin[2])


def _motion_columns(prob, li, blocks, tblocks):
    """The Newton matrix with its columns of the motion filled in (the control and
    inflow columns zero): the per-azimuth blocks through the spectral derivatives,
    and the thrust's, tip flapping's and inflow equations' rows."""
    model, psi, d1, d2, n, n_psi, nq = (prob.model, prob.psi, prob.d1, prob.d2, prob.n,
                                        prob.n_psi, prob.nq)
    n_lam, sigma, mu, fs = prob.n_lam, prob.sigma, prob.mu, prob.fs
    n_s = len(prob.ctl_names) + n_lam
    # J[(i,m),(j,l)] = J0[m,i,j] I_ml + J1[m,i,j] D_ml + J2[m,i,j] D2_ml, written
    # straight into the (i, m, j, l) view of the Newton matrix
    jac = np.zeros((nq + n_s, nq + n_s))
    j4 = jac[:nq, :nq].reshape(n, n_psi, n, n_psi)
    j4[...] = np.einsum("mij,ml->imjl", blocks[1], d1) + np.einsum("mij,ml->imjl",
                                                                   blocks[2], d2)
    diag = np.arange(n_psi)
    j4[:, diag, :, diag] += blocks[0]
    # thrust derivative wrt Q (mean over azimuth)
    if n_lam == 3:
        # with dynamic inflow: the blade's C_T/sigma and its first moment
        tblocks, t_moment = tblocks
        harmonics = np.zeros((2, 1)) if prob.hover else np.array([np.sin(psi), np.cos(psi)])
        dmom = [((t_moment[0] * s).T + (t_moment[1] * s).T @ d1 + (t_moment[2] * s).T @ d2)
                / n_psi for s in harmonics[:, :, None]]
    dct = (tblocks[0].T + tblocks[1].T @ d1 + tblocks[2].T @ d2) / n_psi     # (n, N)
    row = nq
    if prob.free_collective:
        jac[row, :nq] = dct.ravel()
        row += 1
    if not prob.hover:
        w_tip = np.zeros((n, n_psi))
        w_tip[:model.n_modes] = prob.tip[:, None]
        jac[row, :nq] = (2 / n_psi * w_tip * np.cos(psi)).ravel()
        jac[row + 1, :nq] = (2 / n_psi * w_tip * np.sin(psi)).ravel()
        row += 2
    if n_lam == 3:
        denom = 2 * np.hypot(mu, fs + li[0])
        for i, d in enumerate((dct, *dmom)):
            jac[row + i, :nq] = -sigma * d.ravel() / denom
    else:
        jac[row, :nq] = -sigma * dct.ravel() / (2 * np.hypot(mu, fs + li))
    return jac


def _exact_columns(prob, jac, q, li, thr0, params):
    """The control and inflow columns of the Newton matrix from the exact Jacobian's
    parameter derivatives ``params = (dR, dthrust)`` (collective, cyclics, then the
    inflow tangents of :func:`inflow_tangents`)."""
    nq, n_lam, scalars = prob.nq, prob.n_lam, prob.scalars
    which = [("collective", "cyclic_cos", "cyclic_sin").index(k) for k in prob.ctl_names]
    which += list(range(3, 3 + n_lam))
    d_res, d_thr = params[0][which], params[1][..., which, :]
    # the trim equations are linear in the thrust: their control and inflow
    # columns are the thrust's derivatives through them (central differences
    # along the exact thrust derivative, exact for a linear function), plus the
    # inflow equations' own dependence on the inflow unknowns (central
    # differences of a scalar function: 1e-10)
    eps = 1e-6
    li_vec = np.atleast_1d(np.asarray(li, float))
    n_cols = len(which)
    for k in range(n_cols):
        dl = np.zeros(n_lam)
        if k >= n_cols - n_lam:
            dl[k - (n_cols - n_lam)] = eps
        sides = []
        for sgn in (1.0, -1.0):
            lam_k = li_vec + sgn * dl
            sides.append(scalars(q, thr0 + sgn * eps * d_thr[..., k, :],
                                 tuple(lam_k) if n_lam == 3 else float(lam_k[0])))
        jac[:nq, nq + k] = d_res[k].ravel()
        jac[nq:, nq + k] = (sides[0] - sides[1]) / (2 * eps)
