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

from ..aero.dynamic_inflow import SteadyInflow, mass_flow, perturbation_matrices, wake_skew
from ..aero.inflow import Inflow, drees_gradients, momentum_inflow
from ..aero.states import HarmonicInflow, InflowLinearization, steady_inflow_residual
from ..errors import TefcoreError
from ..fourier import fourier_coefficients, fourier_series, spectral_derivative
from ..model.coupled import Controls, CoupledModel
from ..runtime import blas_limit
from .newton import BroydenSolver, WakeSchur, factor
from .newton_matrix import newton_matrix, solution_matrices

__all__ = ["MAX_FLAP_DEFLECTION_DEG", "TrimError", "TrimResult", "initial_collective", "trim"]


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


@dataclass
class TrimResult:
    """Converged trim: controls, inflow and the periodic response.

    Attributes
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model trimmed.
    psi : numpy.ndarray
        Collocation azimuths [rad].
    q : numpy.ndarray
        Periodic response, ``(n_dof, len(psi))`` (modal coordinates, then the
        flap deflection [rad]).
    controls : tefcore.model.coupled.Controls
        Trimmed pitch controls.
    inflow : tefcore.aero.inflow.Inflow or tefcore.aero.states.HarmonicInflow
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
    _problem: object = field(default=None, repr=False, compare=False)
    _solution: np.ndarray | None = field(default=None, repr=False, compare=False)
    _blocks: tuple | None = field(default=None, repr=False, compare=False)

    def final_blocks(self):
        """``dR/dq, dR/dq*, dR/dq**`` at the trimmed motion on the trim grid: the linearisation.

        One Jacobian of the residual at the solution, cached, serves both the
        linearisation and the next trim: its per-azimuth blocks are the
        linearisation about the trim (:func:`tefcore.linear.stability.linear_system`
        takes them as they are), and the Newton matrix built from the same
        evaluation replaces :attr:`jacobian`, so a trim warm-started from this
        one starts from the Jacobian at this solution.  Without aerodynamic
        states it is the trim's exact Newton Jacobian at the solution
        (:func:`tefcore.trimming.newton_matrix.newton_matrix`); with the
        dynamic-inflow states the exact linearisation with the states, whose
        rows and columns of the trim's unknowns are the Newton matrix
        (:func:`tefcore.trimming.newton_matrix.solution_matrices`).

        None with the shed-wake states: the linearisation is then
        :func:`tefcore.linear.stability.linearize`'s forward differences, once,
        and the Newton matrix stays the trim's last (measured on MDART at
        mu = 0.3: a warm-started trim with the wake re-evaluates its matrix
        after one chord step whichever it starts from, and the control columns
        at the solution would cost six more evaluations of the residual).  None
        too without a record of the trim equations.

        Returns
        -------
        tuple of numpy.ndarray or None
            ``(K, C, M)`` blocks, each ``(n_psi, n_y, n_y)`` (the coordinates,
            then the aerodynamic states of :meth:`linear_point`).
        """
        if self._blocks is None and self._problem is not None and not self.model.n_wake:
            if not self.model.n_inflow:
                jac, _, blocks = self._problem.jacobian(self._solution)
            else:
                jac, blocks = solution_matrices(self._problem, self._solution, self)
            self.jacobian = jac
            self._blocks = tuple(blocks)
        return self._blocks

    def motion(self, psi):
        """``q, q*, q**`` at any azimuths, by Fourier interpolation."""
        return tuple(fourier_series(self.q, psi, (0, 1, 2)))

    def linear_point(self, psi):
        """What the linearisation differentiates about, at azimuths ``psi``.

        Returns ``(y, y*, y**, inflow)``: the coordinates followed by the
        aerodynamic states (shed wake from the trim, dynamic-inflow
        perturbations zero), and the inflow to evaluate with (with dynamic
        inflow an :class:`~tefcore.aero.states.InflowLinearization` that holds
        the perturbation equations about this trim, docs/theory.md 6.2).
        Without aerodynamic states this is :meth:`motion` and the trim's inflow.
        """
        model = self.model
        y = list(self.motion(psi))
        if model.n_wake:
            w, wd = fourier_series(self.states, psi, (0, 1))
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
    f = model.flight
    fs = f.advance_ratio * np.tan(f.shaft_angle)
    if model.dynamic_inflow:
        mean, sine, cosine = lam_i
        return HarmonicInflow(mean=mean, freestream=fs, sine=sine, cosine=cosine)
    kx, ky = (drees_gradients(f.advance_ratio, fs + lam_i)
              if model.cfg.model.inflow == "linear" else (0.0, 0.0))
    return Inflow(mean_induced=lam_i, freestream=fs, kx=kx, ky=ky)


def _steady_inflow(model, inflow: HarmonicInflow) -> SteadyInflow:
    """The trimmed Pitt-Peters field as a :class:`~tefcore.aero.dynamic_inflow.SteadyInflow`."""
    mu = model.flight.advance_ratio
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
    cfg : tefcore.config.configuration.Config
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
        The coupled model (:func:`tefcore.model.coupled.coupled_model`).
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
    prob = _Problem(model)
    x = _initial_guess(prob, initial)
    newton = _Newton(prob, x, initial)
    history = []
    for it in range(max_iter):
        r, norm, thrust, c, li = newton.state
        history.append({"iteration": it, "max_residual": norm, "collective_deg":
                        np.rad2deg(c.collective), "cyclic_cos_deg": np.rad2deg(c.cyclic_cos),
                        "cyclic_sin_deg": np.rad2deg(c.cyclic_sin),
                        "inflow": li if prob.n_lam == 1 else li[0]})
        if not np.isfinite(norm):
            raise TrimError("trim residual became non-finite", history)
        if norm < tol:
            return _result(prob, newton, history)
        if not newton.step():
            raise TrimError("the trim left the range of the models (a section "
                            "model refused the state)", history)
    raise TrimError(f"trim did not converge in {max_iter} iterations "
                    f"(last max residual {history[-1]['max_residual']:.3e})", history)


def _initial_guess(prob, initial: TrimResult | None) -> np.ndarray:
    """The unknowns' first guess: a warm start's solution, or rest at the first
    collective estimate; sets ``prob.base``.

    Unknowns: Q (n x N; wake states after the coordinates), [theta_0],
    [theta_1c, theta_1s], lambda_i (dynamic inflow: lambda_0, lambda_s, lambda_c).
    """
    model, cfg, n, n_psi, n_lam = prob.model, prob.model.cfg, prob.n, prob.n_psi, prob.n_lam
    if _warm(initial, model, n_psi):
        q0, ctl = initial.q.copy(), initial.controls
        if model.n_wake:
            q0 = np.vstack([q0, initial.states])
        lam = ([initial.inflow.mean, initial.inflow.sine, initial.inflow.cosine]
               if model.dynamic_inflow else [initial.inflow.mean_induced])
        # the controls not solved for are this configuration's, never the warm
        # start's: a prescribed collective (a collective sweep) would otherwise
        # stay at the previous point's value
        ctl = Controls(collective=(ctl.collective if prob.free_collective
                                   else initial_collective(cfg)),
                       cyclic_cos=0.0 if prob.hover else ctl.cyclic_cos,
                       cyclic_sin=0.0 if prob.hover else ctl.cyclic_sin)
    else:
        q0 = np.zeros((n, n_psi))
        ctl = Controls(collective=initial_collective(cfg))
        f = model.flight
        # the mean induced inflow of momentum theory at the target thrust
        # (Glauert in forward flight; with a prescribed collective at the
        # ct_sigma field all the same): what a uniform inflow converges to, and
        # close to the mean of the Pitt-Peters states.  Measured on MDART at
        # mu 0.02-0.4 against the hover value sqrt(C_T/2): 0-4 fewer Newton
        # iterations with uniform, linear or Pitt-Peters inflow (one more once:
        # Pitt-Peters at mu 0.1); the default model at mu 0.3: 11 -> 8, trim
        # 9.9 -> 7.8 ms
        lam = ([np.sqrt(max(f.ct_sigma * prob.sigma, 1e-6) / 2) if prob.hover
                else momentum_inflow(f.ct_sigma * prob.sigma, f.advance_ratio, f.shaft_angle)]
               + [0.0] * (n_lam - 1))
    prob.base = ctl
    return np.concatenate([q0.ravel(), [getattr(ctl, k) for k in prob.ctl_names], lam])


class _Newton:
    """Damped chord-Newton iterations with Broyden's updates on the trim equations.

    ``state`` is ``(r, norm, thrust, controls, inflow)`` at ``x``; :meth:`step`
    moves ``x`` by one damped step.
    """

    def __init__(self, prob, x, initial):
        self.prob, self.x = prob, x
        model, n_psi = prob.model, prob.n_psi
        self.lu = None
        if initial is not None and initial.jacobian is not None and \
                initial.jacobian.shape == (x.size, x.size):
            self.lu = factor(initial.jacobian, model, n_psi)
            self.jac = initial.jacobian
        if self.lu is None:
            # cold start: the residual comes with the first Jacobian (its
            # unperturbed block), not from a separate evaluation
            self.jac, self.state, _ = prob.jacobian(x)
            # no finiteness checks in the LU calls: a NaN reaches the residual,
            # and the loop of trim() stops on it with a TrimError and its history
            self.lu = factor(self.jac, model, n_psi)
            self.fresh = True
        else:
            self.state = prob.full(x)
            self.fresh = False
        self.broyden = None if isinstance(self.lu, WakeSchur) else BroydenSolver(self.lu)
        self.prev = np.inf
        self.last = None

    def _refresh_or_update(self, r, norm) -> None:
        """Chord method with Broyden's updates: keep the factorised Jacobian while
        it converges fast, refresh it when the residual falls by less than
        REFRESH_RATIO per iteration."""
        ratio = REFRESH_RATIO if self.broyden is not None else CHORD_REFRESH_RATIO
        if not self.fresh and norm > ratio * self.prev:
            self.jac = self.prob.jacobian(self.x)[0]
            self.lu = factor(self.jac, self.prob.model, self.prob.n_psi)
            self.broyden = None if isinstance(self.lu, WakeSchur) else BroydenSolver(self.lu)
        elif not self.fresh and self.broyden is not None and self.last is not None:
            self.broyden.update(self.x - self.last[0], r - self.last[1])

    def step(self) -> bool:
        """One damped step; False when the models refused every trial state."""
        r, norm = self.state[0], self.state[1]
        self._refresh_or_update(r, norm)
        self.fresh = False
        self.prev = norm
        self.last = (self.x, r)
        lu, broyden = self.lu, self.broyden
        step = lu.solve(-r) if broyden is None else broyden.solve(-r)
        # damped Newton: halve the step while the residual grows; the accepted
        # trial's residual is the next iteration's (no re-evaluation)
        alpha = 1.0
        for _ in range(8):
            try:
                trial = self.prob.full(self.x + alpha * step)
            except ValueError:      # a state beyond the models (e.g. Mach > 0.99)
                trial = None
            if trial is not None and (trial[1] <= norm or norm < 1e-6):
                break
            if alpha == 1.0 and broyden is not None and broyden.u:
                # a secant step that does not reduce the residual: back to the
                # factorised Jacobian alone before halving
                broyden = self.broyden = BroydenSolver(lu)
                step = broyden.solve(-r)
                continue
            alpha *= 0.5
        if trial is None:
            return False
        self.x = self.x + alpha * step
        self.state = trial
        return True


def _result(prob, newton, history) -> TrimResult:
    """The converged trim: the periodic motion, controls and inflow."""
    model, x = prob.model, newton.x
    _, _, thrust, c, li = newton.state
    q_tr = x[:prob.nq].reshape(prob.n, prob.n_psi)
    nd = model.n_dof
    _check_flap_deflection(model, q_tr[:nd], history)
    return TrimResult(model=model, psi=prob.psi, q=q_tr[:nd], controls=c,
                      inflow=_inflow(model, li),
                      ct_sigma=float(thrust.mean() if prob.n_lam == 1 else thrust[0].mean()),
                      history=history, jacobian=newton.jac,
                      states=q_tr[nd:] if model.n_wake else None,
                      _problem=prob, _solution=x)


#: The factorised Newton matrix is re-evaluated when the residual falls by less
#: than this factor in an iteration (Broyden's updates in between).  Measured on
#: MDART, mu = 0.1 .. 0.35, balanced and imbalanced flap, momentum and dynamic
#: inflow: a cold trim took one Jacobian and 9-11 residuals (two and 6-8 with
#: 0.1 and no updates), 15 % less time -- from the hover inflow; from the
#: momentum inflow one Jacobian and 7 residuals at mu = 0.3.
REFRESH_RATIO = 0.5

#: The same without Broyden's updates (the shed-wake states' Schur-complement
#: solves): the plain chord iteration needs the stricter 0.1.
CHORD_REFRESH_RATIO = 0.1


class _Problem:
    """The trim equations of a model: unknowns, residual and Newton Jacobian."""

    def __init__(self, model):
        cfg = model.cfg
        f = model.flight
        self.model = model
        self.hover = f.advance_ratio == 0.0
        self.n_psi = 1 if self.hover else cfg.model.n_azimuth
        self.psi = np.linspace(0, 2 * np.pi, self.n_psi, endpoint=False)
        self.d1 = spectral_derivative(self.n_psi)
        self.d2 = self.d1 @ self.d1
        self.n = model.n_dof + model.n_wake                # coordinates and wake states
        self.n_lam = 3 if model.dynamic_inflow else 1      # inflow unknowns
        # sin and cos psi of the collocation points, for the rotor's first moments;
        # in hover the loads are axisymmetric (one point) and the moments vanish
        self.harmonics = (np.zeros((2, 1)) if self.hover
                          else np.array([np.sin(self.psi), np.cos(self.psi)]))
        self.free_collective = f.collective is None
        self.sigma = cfg.rotor.solidity
        self.mu, self.fs = f.advance_ratio, f.advance_ratio * np.tan(f.shaft_angle)
        self.tip = model.tip_flap                          # tip flap of each mode
        self.ctl_names = ((["collective"] if self.free_collective else [])
                          + ([] if self.hover else ["cyclic_cos", "cyclic_sin"]))
        self.nq = self.n * self.n_psi
        self.base = Controls()                             # the controls not solved for

    def unpack(self, vec):
        """``(Q, controls, inflow unknowns)`` of an unknown vector."""
        b, n_lam = self.base, self.n_lam
        c = Controls(b.collective, b.cyclic_cos, b.cyclic_sin)
        for k, val in zip(self.ctl_names, vec[self.nq:vec.size - n_lam], strict=True):
            setattr(c, k, float(val))
        li = tuple(float(v) for v in vec[-3:]) if n_lam == 3 else float(vec[-1])
        return vec[:self.nq].reshape(self.n, self.n_psi), c, li

    def scalars(self, q, thrust, li):
        """The trim targets and the inflow equations."""
        n_lam, mu, fs, sigma = self.n_lam, self.mu, self.fs, self.sigma
        f = self.model.flight
        ct_s = thrust.mean() if n_lam == 1 else thrust[0].mean()
        out = [ct_s - f.ct_sigma] if self.free_collective else []
        if not self.hover:
            w_tip = self.tip @ q[:self.model.n_modes]
            out += [2 * np.mean(w_tip * np.cos(self.psi)),
                    2 * np.mean(w_tip * np.sin(self.psi))]
        ct = ct_s * sigma
        if n_lam == 3:
            # steady Pitt-Peters, divided by 2 v_T: in hover the mean row is
            # the momentum row below, lambda_0 - C_T / (2 lambda_0)
            loads = sigma * (self.harmonics @ thrust[1]) / self.n_psi
            res = steady_inflow_residual(li, ct, *loads, advance_ratio=mu, freestream=fs)
            return np.concatenate([out, res / (2 * np.hypot(mu, fs + li[0]))])
        out.append(li - ct / (2 * np.hypot(mu, fs + li)))
        return np.array(out)

    def full(self, vec):
        """Residual, its largest entry, thrust, controls and inflow at ``vec``."""
        q, c, li = self.unpack(vec)
        res, thrust = self.model.evaluate(self.psi, q, q @ self.d1.T, q @ self.d2.T, c,
                                          _inflow(self.model, li))
        r = np.concatenate([res.ravel(), self.scalars(q, thrust, li)])
        return r, float(np.max(np.abs(r))), thrust, c, li

    def inflow(self, li):
        """The inflow field of the inflow unknowns ``li``."""
        return _inflow(self.model, li)

    def jacobian(self, vec):
        """Newton matrix at ``vec``, ``full(vec)`` and the per-azimuth blocks."""
        q, c, li = self.unpack(vec)
        jac, (res0, thrust), blocks = newton_matrix(self, vec, c, li, _inflow(self.model, li))
        r = np.concatenate([res0.ravel(), self.scalars(q, thrust, li)])
        return jac, (r, float(np.max(np.abs(r))), thrust, c, li), blocks


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
