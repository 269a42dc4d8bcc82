"""Jacobians of the coupled blade/flap residual with respect to the motion.

:func:`jacobian_blocks` differentiates the residual of
:meth:`tefcore.model.coupled.CoupledModel.evaluate` (or each of its named pieces,
:meth:`~tefcore.model.coupled.CoupledModel.residual_pieces`) with respect to the
coordinates ``q`` and their azimuth derivatives ``q*`` and ``q**``, azimuth by
azimuth: the trim's Newton steps, the linearisation about the trim and the
mechanism's term-by-term systems all use it.  The residual at one azimuth
depends only on the motion there, so all perturbed motions are stacked along
the azimuth axis and evaluated in one call.

Two ways (``scheme``):

* ``"exact"`` (the default where it is implemented): the residual is linear
  in the coordinates except through the local variables of each aerodynamic
  station (:mod:`tefcore.model.station_terms`), so its Jacobian is the projection on
  the mode shapes of the station forces' derivatives with respect to those
  variables, ``J_ij = sum_s S_i(x_s) dF_s/dv_s T_j(x_s)``; the derivatives are
  taken by complex step (``F(v + i h)``, ``h = 1e-30``: no cancellation, exact
  to round-off), one perturbation per local variable for all stations and
  azimuths at once (docs/theory.md 6.3).  Quasi-steady airloads (thin airfoil
  or C81 table), any inflow, the dynamic-inflow perturbation states.  Not
  implemented for the shed-wake states (``model.aero = "unsteady"``), which
  fall back to forward differences.
* ``"forward"``, ``"central"``: finite differences of the whole residual.
"""

from __future__ import annotations

import numpy as np

from ..aero.states import inflow_fields, rotating_inflow_damping
from .coupled import Controls, CoupledModel
from .station_kernel import covers, station_derivatives
from .station_terms import (
    FLAP_VARIABLES,
    STATION_VARIABLES,
    StationTerm,
    local_variables,
    station_terms,
)

__all__ = ["EXACT_STEP", "exact_jacobian", "has_exact_jacobian", "jacobian_blocks"]

#: Complex step of :func:`exact_jacobian`: ``Im F(v + i h) / h`` is ``F'(v)`` to
#: ``O(h^2)`` relative, with no subtraction, so any tiny ``h`` is exact.
EXACT_STEP = 1e-30


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
    inflow : tefcore.aero.inflow.Inflow
        Inflow.
    step : float, optional
        Finite-difference step (rotor units).
    scheme : {"forward", "central", "exact"}, optional
        Finite-difference scheme, or ``"exact"``: :func:`exact_jacobian` where
        :func:`has_exact_jacobian` (else forward differences).
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
    if scheme not in ("central", "forward", "exact"):
        raise ValueError(f"scheme must be 'exact', 'central' or 'forward', got {scheme!r}")
    if scheme == "exact":
        if has_exact_jacobian(model) and not extra:
            jac, dthr, base, _ = exact_jacobian(model, psi, q, qd, qdd, controls, inflow,
                                                pieces=pieces)
            return jac, dthr, base
        scheme = "forward"                 # shed-wake states: finite differences
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
        res = sum(parts.values())
        # piece by piece, each residual dropped once differenced: with the shed
        # wake the pieces and their blocks held 0.13 GiB at once (measured)
        jac = {name: _difference(parts.pop(name).reshape(n, n_blk, m), n, step, scheme, kk)[0]
               for name in list(parts)}
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


def has_exact_jacobian(model: CoupledModel) -> bool:
    """Whether :func:`exact_jacobian` covers the model (all but the shed-wake states).

    Parameters
    ----------
    model : CoupledModel
        The coupled model.

    Returns
    -------
    bool
    """
    return model.n_wake == 0


def _input_maps(model, n_cols):
    """For each local variable (station variables, then flap variables): the
    derivative order of the coordinates it reads and its map ``(n_x, n_cols)``
    from those coordinates to its value at each station."""
    sh, nm, fs = model.shapes, model.n_modes, model.flap_stations
    n_x = model.x.size

    def field(name):
        t = np.zeros((n_x, n_cols))
        t[:, :nm] = sh[name]
        return t

    flap = np.zeros((n_x, n_cols))
    if model.has_flap:
        flap[fs, nm] = 1.0
    maps = {"theta": (0, field("phi")), "theta_d": (1, field("phi")),
            "theta_dd": (2, field("phi")), "ut": (1, field("v")), "up": (1, field("w")),
            "wdd": (2, field("w")), "slope": (0, field("dw")), "v": (0, field("v")),
            "dv": (0, field("dv")), "vdd": (2, field("v")), "dvd": (1, field("dv")),
            "dwd": (1, field("dw")), "dl": (0, flap), "dld": (1, flap), "dldd": (2, flap)}
    names = STATION_VARIABLES + (("dl", "dld", "dldd") if model.has_flap else ())
    names += tuple(v for v in FLAP_VARIABLES if v not in names) if model.has_flap else ()
    return names, [maps[k] for k in names]


def _seeded(loc, names, seeds, sel, h):
    """Local variables on the stations ``sel``, one complex-step copy per seed."""
    out = {}
    k_seeds = len(seeds)
    for k in names:
        base = np.asarray(loc[k])[..., sel] if k in STATION_VARIABLES else np.asarray(loc[k])
        if k in seeds:
            arr = np.empty((k_seeds,) + base.shape, complex)
            arr[...] = base
            arr[seeds.index(k)] += 1j * h
        else:
            arr = base            # the same in every copy: broadcast
        out[k] = arr
    return out


#: Output fields of the station forces, in the order of the cached maps.
_OUT_FIELDS = ("w", "dw", "v", "dv", "phi", "flap")


def _statics(model, n_rows):
    """The per-model constants of :func:`exact_jacobian` (cached in ``model.cache``):
    the local variables, their input maps by derivative order, the output maps and
    the complex-step runs."""
    key = ("exact_jacobian", n_rows)
    if key in model.cache:
        return model.cache[key]
    nm, fs = model.n_modes, model.flap_stations
    names, maps = _input_maps(model, n_rows)
    orders = np.array([o for o, _ in maps])
    t_in = np.stack([m for _, m in maps])                     # (n_var, n_x, n_cols)
    by_order = [np.flatnonzero(orders == o) for o in range(3)]
    out_maps = np.zeros((len(_OUT_FIELDS), model.x.size, n_rows))
    for k, f in enumerate(_OUT_FIELDS[:-1]):
        out_maps[k, :, :nm] = model.shapes[f]
    if model.has_flap:
        out_maps[-1, fs, nm] = 1.0
    first_run = list(STATION_VARIABLES) + [v for v in ("dl", "dld", "dldd") if v in names]
    runs = [(first_run, slice(None), False)]
    rows = {False: slice(0, len(first_run))}          # names: first_run, then the rest
    if model.has_flap:
        rest = [v for v in FLAP_VARIABLES if v not in first_run]
        runs.append((rest, fs, True))
        rows[True] = slice(len(first_run), len(first_run) + len(rest))
    assert list(names) == first_run + (rest if model.has_flap else [])
    st = {"names": names, "n_var": len(names), "by_order": by_order, "out_maps": out_maps,
          "t_flat": [t_in[idx].reshape(-1, n_rows) for idx in by_order], "runs": runs,
          "rows": rows, "up": names.index("up")}
    model.cache[key] = st
    return st


def exact_jacobian(model: CoupledModel, psi, q, qd, qdd, controls, inflow, *,
                   pieces: bool = False, inflow_tangents=()):
    """Exact per-azimuth Jacobian blocks of the residual and thrust (complex step).

    The derivatives of the station forces (:func:`tefcore.model.station_terms.station_terms`)
    with respect to the local variables are taken by complex step, all stations
    and azimuths at once (the station variables on all stations, the flap
    variables on the flap stations), and projected on the mode shapes; the
    terms linear in the coordinates (structure, actuator, dynamic-inflow
    dynamics) add their constant matrices.

    Parameters
    ----------
    model : CoupledModel
        The coupled model, without shed-wake states (:func:`has_exact_jacobian`).
    psi : numpy.ndarray
        Azimuths [rad].
    q, qd, qdd : numpy.ndarray
        Coordinates (and, in a linearisation with dynamic inflow, the three
        inflow perturbation states after them) and their psi-derivatives,
        ``(n, n_psi)``.
    controls : Controls
        Pitch controls.
    inflow : tefcore.aero.inflow.Inflow
        Inflow (with the states: a :class:`tefcore.aero.states.InflowLinearization`).
    pieces : bool, optional
        The blocks of each named piece (a dict), whose sum is the Jacobian.
    inflow_tangents : sequence of numpy.ndarray, optional
        Derivatives ``d lambda / d p_k`` of the inflow ratio with respect to
        parameters ``p_k`` at the stations, each ``(n_psi, n_x)``: their
        residual and thrust derivatives come with those of the controls.

    Returns
    -------
    jac : numpy.ndarray or dict
        ``(3, n_psi, n, n)``: ``dR_i/dq_j``, ``dR_i/dq*_j``, ``dR_i/dq**_j``.
    dthrust : numpy.ndarray
        ``(3, n_psi, n)`` (with dynamic inflow ``(2, 3, n_psi, n)``: the blade's
        ``C_T/sigma`` and its first moment).
    base : tuple
        ``(R, thrust)`` at the motion.
    params : tuple
        ``(dR, dthrust)`` with respect to the collective, the two cyclics and
        the ``inflow_tangents`` parameters: ``(n_p, n, n_psi)`` and
        ``(..., n_p, n_psi)``.

    Raises
    ------
    ValueError
        For a model with shed-wake states.
    """
    if not has_exact_jacobian(model):
        raise ValueError("the exact Jacobian does not cover the shed-wake states "
                         "(model.aero = 'unsteady'); use finite differences")
    psi = np.atleast_1d(np.asarray(psi, float))
    n_rows, n_psi = q.shape
    nd, nm = model.n_dof, model.n_modes
    n_x = model.x.size
    nu = n_rows > nd
    if nu and n_rows != nd + model.n_inflow:
        raise ValueError(f"{n_rows} rows of coordinates and states; this model has {nd} "
                         f"coordinates and {model.n_inflow} inflow states")
    kin = model.kinematics(psi, q[:nd], qd[:nd], qdd[:nd], controls, inflow,
                           inflow_perturbation=None if not nu else
                           q[nd][:, None] + model.x[None, :] * q[nd + 1][:, None])
    loc = local_variables(model, kin, q[:nd], qd[:nd], qdd[:nd])
    st = _statics(model, n_rows)
    names = st["names"]
    motion = (psi, q, qd, qdd, controls, inflow)
    # derivatives of the station forces per output field (summed over the pieces;
    # by piece only when asked) and of the normal force: fused where the
    # compiled kernel covers the model, else by complex step on whole arrays
    fused = None if pieces else _fused(model, loc, st, motion, nu)
    if fused is None:
        total, by_piece, fz, (parts, thrust) = _complex_step(model, loc, st, motion, pieces,
                                                             nu)
    else:
        (total, fz, (parts, thrust)), by_piece = fused, {}
    out_maps, t_flat, by_order = st["out_maps"], st["t_flat"], st["by_order"]
    up = st["up"]
    mu = model.flight.advance_ratio
    # U_P = lambda + w* + mu (w' + beta_p) cos psi (+ nu_0 + x nu_R): order 0 too
    up0 = np.zeros((n_psi, n_x, n_rows))
    up0[:, :, :nm] = mu * np.cos(psi)[:, None, None] * model.shapes["dw"][None]
    if nu:
        up0[:, :, nd] = 1.0
        up0[:, :, nd + 1] = model.x[None, :]

    def project(e):
        """Output-projected derivatives ``e`` (n_var, n_psi, n_x, n_rows) -> blocks
        (3, n_psi, n_rows, n_cols): one matrix product per order."""
        jac = np.empty((3, n_psi, n_rows, n_rows))
        for o, idx in enumerate(by_order):
            lhs = e[idx].transpose(1, 3, 0, 2).reshape(n_psi, n_rows, -1)
            jac[o] = lhs @ t_flat[o]
        jac[0] += e[up].transpose(0, 2, 1) @ up0
        return jac

    def project_thrust(dfz):
        d = np.empty((3, n_psi, n_rows))
        for o, idx in enumerate(by_order):
            d[o] = dfz[idx].transpose(1, 0, 2).reshape(n_psi, -1) @ t_flat[o]
        d[0] += np.einsum("ms,msj->mj", dfz[up], up0)
        return d

    ct = model.scale["ct_sigma"]
    dthrust = project_thrust(ct * fz)
    if model.dynamic_inflow:
        dthrust = np.stack([dthrust, project_thrust(ct * fz * model.x)])
    e_total = np.einsum("fvms,fsi->vmsi", total, out_maps, optimize=True)
    if pieces:
        jac = {p: np.zeros((3, n_psi, n_rows, n_rows)) for p in parts}
        for p, d in by_piece.items():
            jac[p] += project(np.einsum("fvms,fsi->vmsi", d, out_maps, optimize=True))
    else:
        jac = {"all": project(e_total)}
    _linear_pieces(model, jac, psi, inflow, dthrust, nu)
    if not pieces:
        jac = jac["all"]
    # controls: Theta = theta_0 + theta_1c cos psi + theta_1s sin psi + ...
    c, s = np.cos(psi), np.sin(psi)
    th, th_d, th_dd = (names.index(k) for k in ("theta", "theta_d", "theta_dd"))
    e_sum = e_total.sum(axis=2)                               # (n_var, n_psi, n_rows)
    fz_sum = fz.sum(axis=-1)                                  # (n_var, n_psi)
    fzx_sum = (fz * model.x).sum(axis=-1)
    dirs = [{th: 1.0}, {th: c, th_d: -s, th_dd: -c}, {th: s, th_d: c, th_dd: -s}]
    n_p = len(dirs) + len(inflow_tangents)
    d_res = np.zeros((n_p, n_rows, n_psi))
    d_fz = np.zeros((2, n_p, n_psi))
    for k, direction in enumerate(dirs):
        for v, coef in direction.items():
            coef = np.asarray(coef)[..., None] if np.ndim(coef) else coef
            d_res[k] += (e_sum[v] * coef).T
            d_fz[0, k] += fz_sum[v] * np.squeeze(coef)
            d_fz[1, k] += fzx_sum[v] * np.squeeze(coef)
    for k, tangent in enumerate(inflow_tangents, start=len(dirs)):
        tangent = np.asarray(tangent)
        d_res[k] = np.einsum("msi,ms->im", e_total[up], tangent)
        d_fz[0, k] = (fz[up] * tangent).sum(axis=-1)
        d_fz[1, k] = (fz[up] * tangent * model.x).sum(axis=-1)
    d_thr = ct * d_fz[0]
    if model.dynamic_inflow:
        d_thr = ct * d_fz
        if nu:
            sigma, first = inflow.solidity, nd
            d_res[:, first] -= sigma * d_thr[0]
            d_res[:, first + 1] -= sigma * d_thr[1]
    return jac, dthrust, (sum(parts.values()), thrust), (d_res, d_thr)


def _residual(model, motion, nu, terms=None, fz0=None):
    """The residual's pieces and the thrust at the motion: from the real station
    forces ``terms`` and normal force ``fz0`` where given (no inflow states), else
    evaluated (:meth:`~tefcore.model.coupled.CoupledModel.residual_pieces`)."""
    psi, q, qd, qdd, controls, inflow = motion
    if nu or terms is None:
        return model.residual_pieces(psi, q, qd, qdd, controls, inflow)
    parts = model.assemble(psi, q, qd, qdd, terms)
    thrust = fz0.sum(axis=-1) * model.scale["ct_sigma"]
    if model.dynamic_inflow:
        thrust = np.stack([thrust, (fz0 * model.x).sum(axis=-1) * model.scale["ct_sigma"]])
    return parts, thrust


def _fused(model, loc, st, motion, nu):
    """The station derivatives, the residual and the thrust from the compiled kernel
    (:mod:`tefcore.model.station_kernel`); None where it does not run."""
    if not covers(model):
        return None
    out = station_derivatives(model, loc, st["n_var"], EXACT_STEP)
    if out is None:
        return None
    return out[0], out[1], _fused_residual(model, motion, out, nu)


def _fused_residual(model, motion, out, nu=False):
    """The residual's pieces and the thrust from the kernel's forces ``out``
    (:func:`~tefcore.model.station_kernel.station_derivatives`)."""
    forces, fz0 = out[2], out[3]
    # dw, dv and the flap row carry only the flap's terms
    terms = [StationTerm("station forces", f, False, forces[i])
             for i, f in enumerate(_OUT_FIELDS) if model.has_flap or f in ("w", "v", "phi")]
    return _residual(model, motion, nu, terms, fz0)


def _complex_step(model, loc, st, motion, pieces, nu):
    """The station derivatives by complex step on whole arrays (numpy): one copy per
    local variable, the station variables and the flap deflection with its rates
    on all stations at once (the copies of the flap's change only the flap
    stations' forces); the other flap variables enter only the flap's inertial
    terms, on the flap stations.  Also the residual's pieces and the thrust (the
    real part of any copy is the unperturbed one)."""
    names, n_var, fs, h = st["names"], st["n_var"], model.flap_stations, EXACT_STEP
    n_psi, n_x = loc["ut"].shape
    total = np.zeros((len(_OUT_FIELDS), n_var, n_psi, n_x))
    by_piece: dict = {}
    fz = np.zeros((n_var, n_psi, n_x))
    for seeds, sel, flap_only in st["runs"]:
        rows = st["rows"][flap_only]
        terms, fz_c = station_terms(model, _seeded(loc, names, seeds, sel, h),
                                    flap_only=flap_only, aero=not flap_only,
                                    combine=not pieces)
        if not flap_only:
            real = None if pieces else [StationTerm(t.piece, t.field, t.flap_only,
                                                    t.force[0].real) for t in terms]
            base = _residual(model, motion, nu, real, fz_c[0].real)
            fz[rows] = fz_c.imag / h
        for t in terms:
            where = fs if (t.flap_only and not flap_only) else sel
            d = t.force.imag / h
            total[_OUT_FIELDS.index(t.field), rows, :, where] += d
            if pieces:
                arr = by_piece.setdefault(t.piece, np.zeros_like(total))
                arr[_OUT_FIELDS.index(t.field), rows, :, where] += d
    return total, by_piece, fz, base


def _linear_pieces(model, jac, psi, inflow, dthrust, nu):
    """Add the terms linear in the coordinates to the blocks (``jac`` by piece, or
    ``{"all": ...}``)."""
    nm, nd = model.n_modes, model.n_dof
    one = "all" in jac

    def add(piece, order, rows, cols, mat):
        key = "all" if one else piece
        jac[key][order][:, rows, cols] += mat

    blade = slice(0, nm)
    add("blade inertia", 2, blade, blade, model.m_s)
    add("blade stiffness", 0, blade, blade, model.k_s)
    add("blade structural damping", 1, blade, blade, model.d_s)
    add("blade Coriolis", 1, blade, blade, model.g_s)
    if model.has_flap:
        add("flap inertia", 2, nm, nm, model.flap["reflected_inertia"])
        add("actuator spring", 0, nm, nm, model.flap["k_a"])
        add("actuator damper", 1, nm, nm, model.flap["c_a"])
    if nu:
        lin = inflow.perturbation
        states = slice(nd, nd + 3)
        add("inflow dynamics", 1, states, states, lin.mass)
        key = "all" if one else "inflow dynamics"
        jac[key][0][:, states, states] += rotating_inflow_damping(lin, psi)
        key = "all" if one else "inflow forcing"
        for order in range(3):
            jac[key][order][:, nd] -= inflow.solidity * dthrust[0][order]
            jac[key][order][:, nd + 1] -= inflow.solidity * dthrust[1][order]
