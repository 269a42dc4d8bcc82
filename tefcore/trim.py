"""Wind-tunnel trim: periodic blade/flap response and controls together.

Harmonic balance by Fourier collocation (docs/theory.md section 7): the
coupled equations are enforced at ``N`` equally spaced azimuths, with the
azimuth derivatives given by the Fourier differentiation matrix, together
with the trim targets

* ``C_T/sigma`` equal to the target (unknown: collective; dropped when the
  collective is prescribed),
* zero first-harmonic tip flap deflection ``beta_1c = beta_1s = 0``
  (unknowns: cyclic pitch; forward flight only — in hover the solution is
  axisymmetric and ``N = 1``),
* momentum inflow consistent with the thrust (unknown: ``lambda_i``), or with
  ``model.inflow = "dynamic"`` the steady Pitt-Peters equations (unknowns: the
  mean, sine and cosine inflow).

With ``model.aero = "unsteady"`` the shed-wake states of every aerodynamic
station are periodic unknowns too, collocated with the blade equations
(docs/theory.md section 7).

Newton's method with the exact block structure: the residual at one azimuth
depends only on ``(q, q*, q**)`` there, so its Jacobian is found for all
azimuths at once from ``3 n`` perturbed evaluations.  Convergence is
quadratic; a trim that does not converge raises :class:`TrimError` with its
residual history.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from .aero_states import HarmonicInflow, InflowLinearization, steady_inflow_residual
from .coupled import Controls, CoupledModel
from .dynamic_inflow import SteadyInflow, mass_flow, perturbation_matrices, wake_skew
from .errors import TefcoreError
from .flap_dynamics import spectral_derivative
from .inflow import Inflow, drees_gradients, momentum_inflow
from .residual_jacobian import jacobian_blocks
from .runtime import blas_limit

__all__ = ["MAX_FLAP_DEFLECTION_DEG", "TrimError", "TrimResult", "fourier_coefficients",
           "fourier_eval", "initial_collective", "trim"]


class TrimError(TefcoreError, RuntimeError):
    """The trim did not converge, or converged to a state beyond the model (a flap
    diverged statically); ``history`` holds the residual per iteration.

    Parameters
    ----------
    message : str
        What went wrong.
    history : list of dict, optional
        The residual of each Newton iteration.
    """

    def __init__(self, message: str, history: list[dict] | None = None):
        super().__init__(message)
        self.history = [] if history is None else history


def fourier_coefficients(samples: np.ndarray) -> np.ndarray:
    """Complex Fourier coefficients (last axis = equally spaced azimuths).

    Parameters
    ----------
    samples : numpy.ndarray
        Periodic samples; the last axis is ``N`` equally spaced azimuths
        from 0.

    Returns
    -------
    numpy.ndarray
        ``numpy.fft.rfft(samples) / N``: the coefficients ``c_k``, k = 0 .. N/2,
        of ``x(psi) = c_0 + 2 Re sum_k c_k exp(i k psi)`` (below the Nyquist
        term).
    """
    return np.fft.rfft(samples, axis=-1) / samples.shape[-1]


def fourier_eval(samples: np.ndarray, psi, derivative: int = 0) -> np.ndarray:
    """Trigonometric interpolation of periodic samples (and its derivatives).

    Exact for trigonometric polynomials of degree below ``N/2``; the Nyquist
    term is kept as a cosine in the value and dropped from derivatives (as in
    :func:`tefcore.flap_dynamics.spectral_derivative`).

    Parameters
    ----------
    samples : numpy.ndarray
        Periodic samples; the last axis is ``N`` equally spaced azimuths from 0.
    psi : array_like
        Azimuths to evaluate at [rad].
    derivative : int, optional
        Order of the psi-derivative.

    Returns
    -------
    numpy.ndarray
        Shape ``samples.shape[:-1] + (len(psi),)``.

    Examples
    --------
    >>> grid = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> round(float(fourier_eval(np.sin(2 * grid), np.array([0.3]))[0]), 12)
    0.564642473395
    """
    return _fourier_series(samples, psi, (derivative,))[0]


def _fourier_series(samples, psi, derivatives):
    """:func:`fourier_eval` for several derivatives from one FFT."""
    n = samples.shape[-1]
    c = fourier_coefficients(samples)
    k = np.arange(c.shape[-1])
    weight = np.where((k == 0) | ((n % 2 == 0) & (k == n // 2)), 1.0, 2.0)
    psi = np.atleast_1d(np.asarray(psi, float))
    basis = np.exp(1j * np.outer(k, psi))                # (n_k, n_psi)
    out = []
    for derivative in derivatives:
        ik = (1j * k) ** derivative
        if derivative and n % 2 == 0:
            ik = np.where(k == n // 2, 0.0, ik)
        out.append(np.real((c * weight * ik) @ basis))
    return out


@dataclass
class TrimResult:
    """Converged trim: controls, inflow and the periodic response.

    Attributes
    ----------
    model : tefcore.coupled.CoupledModel
        The model trimmed.
    psi : numpy.ndarray
        Collocation azimuths [rad].
    q : numpy.ndarray
        Periodic response, ``(n_dof, len(psi))`` (modal coordinates, then the
        flap deflection [rad]).
    controls : tefcore.coupled.Controls
        Trimmed pitch controls.
    inflow : tefcore.inflow.Inflow or tefcore.aero_states.HarmonicInflow
        Trimmed inflow: with ``model.inflow = "dynamic"``, the steady
        Pitt-Peters field.
    ct_sigma : float
        Thrust coefficient over solidity reached.
    history : list
        Residual per Newton iteration.
    jacobian : numpy.ndarray or None
        Jacobian of the trim equations at the solution.
    states : numpy.ndarray or None
        The shed-wake states (``model.aero = "unsteady"``; rows as
        :attr:`CoupledModel.state_labels`), None otherwise.
    """

    model: CoupledModel
    psi: np.ndarray
    q: np.ndarray                 # (n_dof, N) at the collocation azimuths
    controls: Controls
    inflow: Inflow
    ct_sigma: float
    history: list = field(default_factory=list)
    jacobian: np.ndarray | None = field(default=None, repr=False)
    states: np.ndarray | None = None     # shed-wake states (n_wake, N)

    def motion(self, psi):
        """``q, q*, q**`` at any azimuths, by Fourier interpolation."""
        return tuple(_fourier_series(self.q, psi, (0, 1, 2)))

    def linear_point(self, psi):
        """What the linearisation differentiates about, at azimuths ``psi``.

        Returns ``(y, y*, y**, inflow)``: the coordinates followed by the
        aerodynamic states (shed wake from the trim, dynamic-inflow
        perturbations zero), and the inflow to evaluate with (with dynamic
        inflow an :class:`~tefcore.aero_states.InflowLinearization` that holds
        the perturbation equations about this trim, docs/theory.md 6.2).
        Without aerodynamic states this is :meth:`motion` and the trim's inflow.
        """
        model = self.model
        y = list(self.motion(psi))
        if model.n_wake:
            w, wd = _fourier_series(self.states, psi, (0, 1))
            y = [np.vstack([a, b]) for a, b in zip(y, (w, wd, np.zeros_like(w)), strict=True)]
        inflow = self.inflow
        if model.n_inflow:
            y = [np.vstack([a, np.zeros((3, a.shape[1]))]) for a in y]
            inflow = InflowLinearization(inflow, perturbation_matrices(_steady_inflow(
                model, inflow)), model.cfg.rotor.solidity)
        return (*y, inflow)

    def summary(self) -> dict:
        """Scalars for tables: controls [deg], inflow, thrust, flap harmonics."""
        out = {"collective_deg": np.rad2deg(self.controls.collective),
               "cyclic_cos_deg": np.rad2deg(self.controls.cyclic_cos),
               "cyclic_sin_deg": np.rad2deg(self.controls.cyclic_sin),
               "inflow": self.inflow.total, "induced_inflow": self.inflow.mean_induced,
               "ct_sigma": self.ct_sigma, "iterations": len(self.history)}
        if isinstance(self.inflow, HarmonicInflow):
            out["inflow_sine"], out["inflow_cosine"] = self.inflow.sine, self.inflow.cosine
        if self.model.has_flap:
            c = fourier_coefficients(self.q[-1])
            out["delta_mean_deg"] = float(np.rad2deg(np.real(c[0])))
            for k in range(1, min(6, c.size)):
                out[f"delta_{k}c_deg"] = float(np.rad2deg(2 * np.real(c[k])))
                out[f"delta_{k}s_deg"] = float(np.rad2deg(-2 * np.imag(c[k])))
        return out


def _inflow(model, lam_i):
    f = model.cfg.flight
    fs = f.advance_ratio * np.tan(f.shaft_angle)
    if model.dynamic_inflow:
        mean, sine, cosine = lam_i
        return HarmonicInflow(mean=mean, freestream=fs, sine=sine, cosine=cosine)
    kx, ky = (drees_gradients(f.advance_ratio, fs + lam_i)
              if model.cfg.model.inflow == "linear" else (0.0, 0.0))
    return Inflow(mean_induced=lam_i, freestream=fs, kx=kx, ky=ky)


def _steady_inflow(model, inflow: HarmonicInflow) -> SteadyInflow:
    """The trimmed Pitt-Peters field as a :class:`~tefcore.dynamic_inflow.SteadyInflow`."""
    mu = model.cfg.flight.advance_ratio
    lam = inflow.freestream + inflow.mean
    vt, v = mass_flow(mu, lam, inflow.mean)
    return SteadyInflow(mean=inflow.mean, sine=inflow.sine, cosine=inflow.cosine,
                        freestream=inflow.freestream, chi=wake_skew(mu, lam), v_total=vt,
                        v_mass=v, advance_ratio=mu)


def initial_collective(cfg) -> float:
    """First estimate of the collective [rad]: the prescribed one, or blade
    element momentum theory for a linearly twisted blade,
    ``C_T/sigma = a/6 [theta_75 (1 + 3/2 mu^2) - 3/2 lambda]`` with momentum
    inflow (Johnson, *Helicopter Theory*, ch. 5).

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.

    Returns
    -------
    float
    """
    f = cfg.flight
    if f.collective is not None:
        return float(f.collective)
    sigma = cfg.rotor.solidity
    lam = (momentum_inflow(f.ct_sigma * sigma, f.advance_ratio, f.shaft_angle)
           + f.advance_ratio * np.tan(f.shaft_angle))
    mu2 = f.advance_ratio**2
    # C_T/sigma = a/6 [theta_75 (1 + 3/2 mu^2) - 3/2 lambda] (Johnson, eq. 5.x)
    return float((6 * f.ct_sigma / cfg.rotor.lift_slope + 1.5 * lam) / (1 + 1.5 * mu2))


@blas_limit()
def trim(model: CoupledModel, *, tol: float = 1e-10, max_iter: int = 40,
         initial: TrimResult | None = None) -> TrimResult:
    """Trim the coupled model (wind-tunnel trim in forward flight).

    Parameters
    ----------
    model : CoupledModel
        The coupled model (:func:`tefcore.coupled.coupled_model`).
    tol : float
        Convergence on the largest residual (rotor units) and the largest
        Newton update.
    max_iter : int
        Newton iterations allowed.
    initial : TrimResult, optional
        Warm start (e.g. the previous point of a sweep).

    Returns
    -------
    TrimResult

    Raises
    ------
    TrimError
        If Newton's method does not converge in ``max_iter`` iterations or
        the residual becomes non-finite.
    """
    cfg = model.cfg
    f = cfg.flight
    hover = f.advance_ratio == 0.0
    n_psi = 1 if hover else cfg.model.n_azimuth
    psi = np.linspace(0, 2 * np.pi, n_psi, endpoint=False)
    d1 = spectral_derivative(n_psi)
    d2 = d1 @ d1
    n = model.n_dof + model.n_wake                         # coordinates and wake states
    n_lam = 3 if model.dynamic_inflow else 1               # inflow unknowns
    # sin and cos psi of the collocation points, for the rotor's first moments;
    # in hover the loads are axisymmetric (one point) and the moments vanish
    harmonics = (np.zeros((2, 1)) if hover else np.array([np.sin(psi), np.cos(psi)]))
    free_collective = f.collective is None
    sigma = cfg.rotor.solidity
    mu, fs = f.advance_ratio, f.advance_ratio * np.tan(f.shaft_angle)
    tip = model.tip_flap                                   # tip flap of each mode

    # unknowns: Q (n x N; wake states after the coordinates), [theta_0],
    # [theta_1c, theta_1s], lambda_i (dynamic inflow: lambda_0, lambda_s, lambda_c)
    if _warm(initial, model, n_psi):
        q0, ctl = initial.q.copy(), initial.controls
        if model.n_wake:
            q0 = np.vstack([q0, initial.states])
        lam = ([initial.inflow.mean, initial.inflow.sine, initial.inflow.cosine]
               if model.dynamic_inflow else [initial.inflow.mean_induced])
    else:
        q0 = np.zeros((n, n_psi))
        ctl = Controls(collective=initial_collective(cfg))
        lam = [np.sqrt(max(f.ct_sigma * sigma, 1e-6) / 2)] + [0.0] * (n_lam - 1)
    ctl_names = (["collective"] if free_collective else []) + ([] if hover else
                                                               ["cyclic_cos", "cyclic_sin"])
    x = np.concatenate([q0.ravel(), [getattr(ctl, k) for k in ctl_names], lam])
    nq = n * n_psi

    def unpack(vec):
        c = Controls(ctl.collective, ctl.cyclic_cos, ctl.cyclic_sin)
        for k, val in zip(ctl_names, vec[nq:x.size - n_lam], strict=True):
            setattr(c, k, float(val))
        li = tuple(float(v) for v in vec[-3:]) if n_lam == 3 else float(vec[-1])
        return vec[:nq].reshape(n, n_psi), c, li

    def residuals(vec):
        q, c, li = unpack(vec)
        res, thrust = model.evaluate(psi, q, q @ d1.T, q @ d2.T, c, _inflow(model, li))
        return res, thrust, c, li

    def scalars(q, thrust, li):
        ct_s = thrust.mean() if n_lam == 1 else thrust[0].mean()
        out = [ct_s - f.ct_sigma] if free_collective else []
        if not hover:
            w_tip = tip @ q[:model.n_modes]
            out += [2 * np.mean(w_tip * np.cos(psi)), 2 * np.mean(w_tip * np.sin(psi))]
        ct = ct_s * sigma
        if n_lam == 3:
            # steady Pitt-Peters, divided by 2 v_T: in hover the mean row is
            # the momentum row below, lambda_0 - C_T / (2 lambda_0)
            loads = sigma * (harmonics @ thrust[1]) / n_psi
            res = steady_inflow_residual(li, ct, *loads, advance_ratio=mu, freestream=fs)
            return np.concatenate([out, res / (2 * np.hypot(mu, fs + li[0]))])
        out.append(li - ct / (2 * np.hypot(mu, fs + li)))
        return np.array(out)

    history = []
    lu = None
    if initial is not None and initial.jacobian is not None and \
            initial.jacobian.shape == (x.size, x.size):
        lu = _factor(initial.jacobian, model, n_psi)
        jac = initial.jacobian
    def full(vec):
        res, thrust, c, li = residuals(vec)
        q = vec[:nq].reshape(n, n_psi)
        r = np.concatenate([res.ravel(), scalars(q, thrust, li)])
        return r, float(np.max(np.abs(r))), thrust, c, li

    prev = np.inf
    if lu is None:
        # cold start: the residual comes with the first Jacobian (its
        # unperturbed block), not from a separate evaluation
        _, c, li = unpack(x)
        jac, (res0, thrust) = _jacobian(model, x, c, li, unpack, scalars, psi, d1, d2, n, n_psi,
                                        nq, tip, hover, free_collective, sigma, mu, fs, n_lam)
        r = np.concatenate([res0.ravel(), scalars(x[:nq].reshape(n, n_psi), thrust, li)])
        norm = float(np.max(np.abs(r)))
        # no finiteness checks in the LU calls: a NaN reaches the residual,
        # and the loop below stops on it with a TrimError and its history
        lu = _factor(jac, model, n_psi)
        fresh = True
    else:
        r, norm, thrust, c, li = full(x)
        fresh = False
    for it in range(max_iter):
        history.append({"iteration": it, "max_residual": norm, "collective_deg":
                        np.rad2deg(c.collective), "cyclic_cos_deg": np.rad2deg(c.cyclic_cos),
                        "cyclic_sin_deg": np.rad2deg(c.cyclic_sin),
                        "inflow": li if n_lam == 1 else li[0]})
        if not np.isfinite(norm):
            raise TrimError("trim residual became non-finite", history)
        if norm < tol:
            q_tr = x[:nq].reshape(n, n_psi)
            nd = model.n_dof
            _check_flap_deflection(model, q_tr[:nd], history)
            return TrimResult(model=model, psi=psi, q=q_tr[:nd], controls=c,
                              inflow=_inflow(model, li),
                              ct_sigma=float(thrust.mean() if n_lam == 1 else thrust[0].mean()),
                              history=history, jacobian=jac,
                              states=q_tr[nd:] if model.n_wake else None)
        # chord method: keep the factorised Jacobian while it converges fast,
        # refresh it when the residual falls by less than 10x per iteration
        if not fresh and norm > 0.1 * prev:
            jac, _ = _jacobian(model, x, c, li, unpack, scalars, psi, d1, d2, n, n_psi, nq,
                               tip, hover, free_collective, sigma, mu, fs, n_lam)
            lu = _factor(jac, model, n_psi)
        fresh = False
        prev = norm
        step = lu.solve(-r) if isinstance(lu, _WakeSchur) else scipy.linalg.lu_solve(
            lu, -r, check_finite=False)
        # damped Newton: halve the step while the residual grows; the accepted
        # trial's residual is the next iteration's (no re-evaluation)
        alpha = 1.0
        for _ in range(8):
            trial = full(x + alpha * step)
            if trial[1] <= norm or norm < 1e-6:
                break
            alpha *= 0.5
        x = x + alpha * step
        r, norm, thrust, c, li = trial
    raise TrimError(f"trim did not converge in {max_iter} iterations "
                    f"(last max residual {history[-1]['max_residual']:.3e})", history)


#: Largest mean trimmed flap deflection [deg] accepted as a result.  A
#: trailing-edge flap travels a few degrees, and the linear flap aerodynamics
#: (attached flow on the flap) end about here; a trim whose *mean* deflection
#: needs more is a flap that diverges statically -- an aerodynamically
#: over-balanced flap in hover trims at 5.6 deg mean at overhang 0.55, 17.9 deg
#: at 0.60, 180 deg at 0.63 with the collective running away, and at -14 deg
#: at 0.70 on the other side (MDART, measured): equilibria of a diverged flap
#: held only by the model's nonlinear kinematics, not results.  The
#: oscillating part is not limited: a near-resonant response to the actuator
#: (Fig. 7 at 0.5 overhang: 21 deg half peak-to-peak, measured) is the paper's
#: own result, out of the linear range as it is.
MAX_FLAP_DEFLECTION_DEG = 10.0


def _factor(jac, model, n_psi):
    """LU factors of the Newton matrix; with wake states, by the Schur complement."""
    if not model.n_wake:
        return scipy.linalg.lu_factor(jac, check_finite=False)
    return _WakeSchur(jac, model.n_dof * n_psi, model.wake.n_per_station * n_psi,
                      model.wake.n_stations)


class _WakeSchur:
    """Newton solves that eliminate the wake states first.

    The wake rows of one station depend on its own states only, so their block
    of the Newton matrix is block diagonal (one ``N_w N`` block per station,
    ``D w + f E^-1 w``, invertible: a stable state has one periodic response).
    Its blocks are inverted and the rest solved through the Schur complement
    ``S = A - B D^-1 C`` (order ``n N + controls``: 244 instead of 1971 for MDART
    at ``N = 24``; 0.02 s instead of 0.4 s a factorisation, measured).
    """

    def __init__(self, jac, start, block, n_blocks):
        size = jac.shape[0]
        self.w = np.arange(start, start + block * n_blocks)
        self.o = np.concatenate([np.arange(start), np.arange(start + block * n_blocks, size)])
        self.shape = (n_blocks, block)
        d = jac[np.ix_(self.w, self.w)].reshape(n_blocks, block, n_blocks, block)
        self.d_inv = np.linalg.inv(d[np.arange(n_blocks), :, np.arange(n_blocks), :])
        self.b = jac[np.ix_(self.o, self.w)]
        self.dinv_c = self._dinv(jac[np.ix_(self.w, self.o)])
        self.lu = scipy.linalg.lu_factor(jac[np.ix_(self.o, self.o)] - self.b @ self.dinv_c,
                                         check_finite=False)

    def _dinv(self, rhs):
        n_blocks, block = self.shape
        out = self.d_inv @ rhs.reshape(n_blocks, block, -1)
        return out.reshape(rhs.shape)

    def solve(self, rhs):
        y = self._dinv(rhs[self.w])
        x_o = scipy.linalg.lu_solve(self.lu, rhs[self.o] - self.b @ y, check_finite=False)
        out = np.empty_like(rhs)
        out[self.o] = x_o
        out[self.w] = y - self.dinv_c @ x_o
        return out


def _warm(initial, model, n_psi) -> bool:
    """Whether a previous trim can start this one (same unknowns)."""
    if initial is None or initial.q.shape != (model.n_dof, n_psi):
        return False
    if model.n_wake and (initial.states is None
                         or initial.states.shape != (model.n_wake, n_psi)):
        return False
    return isinstance(initial.inflow, HarmonicInflow) == model.dynamic_inflow


def _check_flap_deflection(model, q, history) -> None:
    """Refuse a trim whose mean flap deflection is beyond :data:`MAX_FLAP_DEFLECTION_DEG`."""
    if not model.has_flap:
        return
    mean = float(np.rad2deg(abs(q[-1].mean())))
    if mean > MAX_FLAP_DEFLECTION_DEG:
        raise TrimError(
            f"the mean trimmed flap deflection is {mean:.3g} deg, beyond "
            f"{MAX_FLAP_DEFLECTION_DEG:g} deg where the flap model holds: the flap diverges "
            f"statically (its hinge-moment stiffness, actuator included, is near zero or "
            f"negative: an aerodynamically over-balanced flap, flap.overhang = "
            f"{model.cfg.flap.overhang:g})", history)


def _jacobian(model, x, c, li, unpack, scalars, psi, d1, d2, n, n_psi, nq, tip, hover,
              free_collective, sigma, mu, fs, n_lam=1):
    """Newton Jacobian using the per-azimuth block structure.

    Returns the Jacobian and ``(R, thrust)`` at ``x`` (its unperturbed block).
    """
    q = x[:nq].reshape(n, n_psi)
    qd, qdd = q @ d1.T, q @ d2.T
    infl = _inflow(model, li)
    # control and inflow columns by forward differences, evaluated at the
    # same motion in the same stacked call as the per-azimuth blocks
    h = 1e-7
    cols = np.arange(nq, x.size)
    xs = np.repeat(x[None], cols.size, axis=0)
    xs[np.arange(cols.size), cols] += h
    parts = [unpack(v) for v in xs]
    (jq, jqd, jqdd), tblocks, (res0, thr0, perturbed) = jacobian_blocks(
        model, psi, q, qd, qdd, c, infl, step=1e-7, scheme="forward",
        extra=[(p[1], _inflow(model, p[2])) for p in parts], n_second=model.n_dof)
    r0 = np.concatenate([res0.ravel(), scalars(q, thr0, li)])
    blocks = [jq, jqd, jqdd]
    eye = np.eye(n_psi)
    # J[(i,m),(j,l)] = J0[m,i,j] I_ml + J1[m,i,j] D_ml + J2[m,i,j] D2_ml
    j4 = (blocks[0][:, None] * eye[:, :, None, None] + blocks[1][:, None] * d1[:, :, None, None]
          + blocks[2][:, None] * d2[:, :, None, None])          # (m, l, i, j)
    jqq = j4.transpose(2, 0, 3, 1).reshape(nq, nq)
    n_s = r0.size - nq
    jac = np.zeros((r0.size, r0.size))
    jac[:nq, :nq] = jqq
    # thrust derivative wrt Q (mean over azimuth)
    if n_lam == 3:
        # with dynamic inflow: the blade's C_T/sigma and its first moment
        tblocks, t_moment = tblocks
        harmonics = np.zeros((2, 1)) if hover else np.array([np.sin(psi), np.cos(psi)])
        dmom = [((t_moment[0] * s).T + (t_moment[1] * s).T @ d1 + (t_moment[2] * s).T @ d2)
                / n_psi for s in harmonics[:, :, None]]
    dct = (tblocks[0].T + tblocks[1].T @ d1 + tblocks[2].T @ d2) / n_psi     # (n, N)
    row = 0
    if free_collective:
        jac[nq, :nq] = dct.ravel()
        row += 1
    if not hover:
        w_tip = np.zeros((n, n_psi))
        w_tip[:model.n_modes] = tip[:, None]
        jac[nq + row, :nq] = (2 / n_psi * w_tip * np.cos(psi)).ravel()
        jac[nq + row + 1, :nq] = (2 / n_psi * w_tip * np.sin(psi)).ravel()
        row += 2
    if n_lam == 3:
        denom = 2 * np.hypot(mu, fs + li[0])
        for i, d in enumerate((dct, *dmom)):
            jac[nq + row + i, :nq] = -sigma * d.ravel() / denom
        row += 2
    else:
        denom = 2 * np.hypot(mu, fs + li)
        jac[nq + row, :nq] = -sigma * dct.ravel() / denom
    for k, (p, (res_k, thr_k)) in zip(cols, zip(parts, perturbed, strict=True), strict=True):
        rk = np.concatenate([res_k.ravel(), scalars(q, thr_k, p[2])])
        jac[:, k] = (rk - r0) / h
    assert n_s == row + 1
    return jac, (res0, thr0)
