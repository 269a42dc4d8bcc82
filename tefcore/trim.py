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
* momentum inflow consistent with the thrust (unknown: ``lambda_i``).

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

from .coupled import Controls, CoupledModel, jacobian_blocks
from .errors import TefcoreError
from .flap_dynamics import spectral_derivative
from .inflow import Inflow, drees_gradients, momentum_inflow
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
    inflow : tefcore.inflow.Inflow
        Trimmed inflow.
    ct_sigma : float
        Thrust coefficient over solidity reached.
    history : list
        Residual per Newton iteration.
    jacobian : numpy.ndarray or None
        Jacobian of the trim equations at the solution.
    """

    model: CoupledModel
    psi: np.ndarray
    q: np.ndarray                 # (n_dof, N) at the collocation azimuths
    controls: Controls
    inflow: Inflow
    ct_sigma: float
    history: list = field(default_factory=list)
    jacobian: np.ndarray | None = field(default=None, repr=False)

    def motion(self, psi):
        """``q, q*, q**`` at any azimuths, by Fourier interpolation."""
        return tuple(_fourier_series(self.q, psi, (0, 1, 2)))

    def summary(self) -> dict:
        """Scalars for tables: controls [deg], inflow, thrust, flap harmonics."""
        out = {"collective_deg": np.rad2deg(self.controls.collective),
               "cyclic_cos_deg": np.rad2deg(self.controls.cyclic_cos),
               "cyclic_sin_deg": np.rad2deg(self.controls.cyclic_sin),
               "inflow": self.inflow.total, "induced_inflow": self.inflow.mean_induced,
               "ct_sigma": self.ct_sigma, "iterations": len(self.history)}
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
    kx, ky = (drees_gradients(f.advance_ratio, fs + lam_i)
              if model.cfg.model.inflow == "linear" else (0.0, 0.0))
    return Inflow(mean_induced=lam_i, freestream=fs, kx=kx, ky=ky)


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
    n = model.n_dof
    free_collective = f.collective is None
    sigma = cfg.rotor.solidity
    mu, fs = f.advance_ratio, f.advance_ratio * np.tan(f.shaft_angle)
    tip = model.tip_flap                                   # tip flap of each mode

    # unknowns: Q (n x N), [theta_0], [theta_1c, theta_1s], lambda_i
    if initial is not None and initial.q.shape == (n, n_psi):
        q0, ctl, lam = initial.q.copy(), initial.controls, initial.inflow.mean_induced
    else:
        q0 = np.zeros((n, n_psi))
        ctl = Controls(collective=initial_collective(cfg))
        lam = np.sqrt(max(f.ct_sigma * sigma, 1e-6) / 2)
    ctl_names = (["collective"] if free_collective else []) + ([] if hover else
                                                               ["cyclic_cos", "cyclic_sin"])
    x = np.concatenate([q0.ravel(), [getattr(ctl, k) for k in ctl_names], [lam]])
    nq = n * n_psi

    def unpack(vec):
        c = Controls(ctl.collective, ctl.cyclic_cos, ctl.cyclic_sin)
        for k, val in zip(ctl_names, vec[nq:-1], strict=True):
            setattr(c, k, float(val))
        return vec[:nq].reshape(n, n_psi), c, float(vec[-1])

    def residuals(vec):
        q, c, li = unpack(vec)
        res, thrust = model.evaluate(psi, q, q @ d1.T, q @ d2.T, c, _inflow(model, li))
        return res, thrust, c, li

    def scalars(q, thrust, li):
        ct_s = thrust.mean()
        out = [ct_s - f.ct_sigma] if free_collective else []
        if not hover:
            w_tip = tip @ q[:model.n_modes]
            out += [2 * np.mean(w_tip * np.cos(psi)), 2 * np.mean(w_tip * np.sin(psi))]
        ct = ct_s * sigma
        out.append(li - ct / (2 * np.hypot(mu, fs + li)))
        return np.array(out)

    history = []
    lu = None
    if initial is not None and initial.jacobian is not None and \
            initial.jacobian.shape == (x.size, x.size):
        lu = scipy.linalg.lu_factor(initial.jacobian, check_finite=False)
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
                                        nq, tip, hover, free_collective, sigma, mu, fs)
        r = np.concatenate([res0.ravel(), scalars(x[:nq].reshape(n, n_psi), thrust, li)])
        norm = float(np.max(np.abs(r)))
        # no finiteness checks in the LU calls: a NaN reaches the residual,
        # and the loop below stops on it with a TrimError and its history
        lu = scipy.linalg.lu_factor(jac, check_finite=False)
        fresh = True
    else:
        r, norm, thrust, c, li = full(x)
        fresh = False
    for it in range(max_iter):
        history.append({"iteration": it, "max_residual": norm, "collective_deg":
                        np.rad2deg(c.collective), "cyclic_cos_deg": np.rad2deg(c.cyclic_cos),
                        "cyclic_sin_deg": np.rad2deg(c.cyclic_sin), "inflow": li})
        if not np.isfinite(norm):
            raise TrimError("trim residual became non-finite", history)
        if norm < tol:
            q_tr = x[:nq].reshape(n, n_psi)
            _check_flap_deflection(model, q_tr, history)
            return TrimResult(model=model, psi=psi, q=q_tr, controls=c,
                              inflow=_inflow(model, li), ct_sigma=float(thrust.mean()),
                              history=history, jacobian=jac)
        # chord method: keep the factorised Jacobian while it converges fast,
        # refresh it when the residual falls by less than 10x per iteration
        if not fresh and norm > 0.1 * prev:
            jac, _ = _jacobian(model, x, c, li, unpack, scalars, psi, d1, d2, n, n_psi, nq,
                               tip, hover, free_collective, sigma, mu, fs)
            lu = scipy.linalg.lu_factor(jac, check_finite=False)
        fresh = False
        prev = norm
        step = scipy.linalg.lu_solve(lu, -r, check_finite=False)
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
              free_collective, sigma, mu, fs):
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
        extra=[(p[1], _inflow(model, p[2])) for p in parts])
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
    denom = 2 * np.hypot(mu, fs + li)
    jac[nq + row, :nq] = -sigma * dct.ravel() / denom
    for k, (p, (res_k, thr_k)) in zip(cols, zip(parts, perturbed, strict=True), strict=True):
        rk = np.concatenate([res_k.ravel(), scalars(q, thr_k, p[2])])
        jac[:, k] = (rk - r0) / h
    assert n_s == row + 1
    return jac, (res0, thr0)
