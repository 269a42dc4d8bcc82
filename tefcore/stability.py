"""Linearisation about the trim and Floquet stability with labelled modes.

``stability(cfg)`` is the paper's analysis in one call: coupled model, trim,
``M(psi), C(psi), K(psi)`` of eq. (5) by central differences of the
nonlinear residual about the trimmed periodic motion, and Floquet
eigenanalysis (direct eigenanalysis in hover, where the coefficients are
constant).  Each mode is labelled by the coordinate that carries most of its
modal kinetic energy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
import scipy.optimize

from . import floquet
from .coupled import coupled_model, jacobian_blocks
from .trim import TrimResult, fourier_eval, initial_collective, trim

#: Re-mode threshold [deg] between the modes' collective and the trimmed one.
REMODE_DEG = 2.0


def linearize(tr: TrimResult, psi, step: float = 1e-6, scheme: str = "central"):
    """``M, C, K`` (each ``(len(psi), n, n)``) about the trimmed motion.

    Finite differences of the residual with respect to ``q**, q*, q``,
    vectorised over the azimuths (the residual at one azimuth depends only on
    the motion there). ``scheme='central'``: truncation error ~``step^2``,
    2n evaluations per matrix; ``'forward'``: error ~``step`` (1e-6 relative,
    far below what moves a damping value), half the evaluations.
    """
    psi = np.atleast_1d(np.asarray(psi, float))
    q, qd, qdd = tr.motion(psi)
    jac, _, _ = jacobian_blocks(tr.model, psi, q, qd, qdd, tr.controls, tr.inflow,
                                step=step, scheme=scheme)
    return jac[2], jac[1], jac[0]


def state_matrix(m, c, k):
    """First-order ``A = [[0, I], [-M^-1 K, -M^-1 C]]`` for stacked matrices."""
    n = m.shape[-1]
    minv_k = np.linalg.solve(m, k)
    minv_c = np.linalg.solve(m, c)
    top = np.concatenate([np.zeros_like(m), np.broadcast_to(np.eye(n), m.shape)], axis=-1)
    return np.concatenate([top, np.concatenate([-minv_k, -minv_c], axis=-1)], axis=-2)


@dataclass
class StabilityResult:
    """Modes of the linearised blade/flap system and the trim they belong to."""

    modes: pd.DataFrame
    eigenvectors: np.ndarray
    trim: dict
    trim_result: TrimResult


def _label_modes(vectors, mass_diag, labels, freqs, rates):
    """Label modes by the coordinate they carry, one coordinate per mode.

    Kinetic-energy fractions ``|q_k|^2 M_kk`` of each eigenvector's
    displacements give a participation matrix; the labels are the
    assignment (``scipy.optimize.linear_sum_assignment``) that maximises the
    summed participation, so every coordinate names exactly one mode. A pure
    "largest share" rule fails where aerodynamics couples modes strongly: the
    MDART torsion mode in hover carries more flap than torsion kinetic energy
    (torsion's modal inertia is tiny), yet it is the only mode with torsion.
    A complex pair whose multipliers have become two real ones (frequency
    locked to a multiple of 1/2 per rev, or overdamped) gives one mode more
    than coordinates: the pair shares its coordinate's label, the less damped
    root carrying it plainly and the other with ``(locked)`` appended (the
    partner is the assigned mode at the closest frequency, ties by the
    energy-weighted MAC).
    """
    n = len(labels)
    disp = vectors[:n] * np.sqrt(mass_diag)[:, None]
    energy = np.abs(disp) ** 2
    frac = energy / energy.sum(axis=0, keepdims=True)          # (coords, modes)
    # maximise the product of the shares (sum of logs): a coordinate must
    # participate materially in the mode that carries its name.  Maximising
    # the plain sum can hand a coordinate a mode where its share is 1e-4
    # (seen: the TEF label on a flap mode while the TEF flutter mode took a
    # blade label)
    rows, cols = scipy.optimize.linear_sum_assignment(-np.log(frac + 1e-300))
    out = [None] * frac.shape[1]
    for r, c in zip(rows, cols, strict=True):
        out[c] = labels[r]
    unit = disp / np.linalg.norm(disp, axis=0, keepdims=True)
    mac = np.abs(unit.conj().T @ unit) ** 2
    for j, lab in enumerate(out):
        if lab is None:
            best = min(cols, key=lambda i: (round(abs(freqs[i] - freqs[j]), 6), -mac[i, j]))
            # the two roots of a locked pair have nearly the same shape, so
            # which one the assignment named is decided by round-off; name the
            # less damped root (the one that matters for stability) after the
            # coordinate, deterministically
            if rates[j] > rates[best]:
                out[j], out[best] = out[best], out[best] + " (locked)"
            else:
                out[j] = out[best] + " (locked)"
    return out, frac


def stability(cfg, *, trim_result: TrimResult | None = None, n_steps: int | None = None,
              remode: bool = True, model=None) -> StabilityResult:
    """Trim the configuration and compute its labelled stability modes.

    Parameters
    ----------
    cfg : tefcore.config.Config
    trim_result : TrimResult, optional
        Warm start for the trim (e.g. the previous sweep point).
    n_steps : int, optional
        RK4 steps per revolution for Floquet (default ``cfg.model.n_floquet_steps``).
    remode : bool
        Recompute the blade modes at the trimmed collective and trim again
        when it differs from the modes' collective by more than
        ``REMODE_DEG`` (the structural flap-lag coupling depends on pitch).
    model : CoupledModel, optional
        A model of ``cfg`` built beforehand with
        :func:`tefcore.coupled.coupled_model`, e.g. to keep one set of blade
        modes for several flight conditions; its modes are used as they are
        (no re-moding).

    Returns
    -------
    StabilityResult
        ``modes`` has one row per mode (positive-frequency member of each
        complex pair): ``mode_id, label, kind, frequency_per_rev, real_part,
        damping_ratio, participation`` — ``real_part`` is the damping rate
        per radian of azimuth (negative: stable).

    Raises
    ------
    ValueError
        If ``model`` was built for another configuration.
    tefcore.trim.TrimError
        If the trim does not converge.
    tefcore.floquet.FloquetAccuracyError
        If the Floquet exponents do not meet the default tolerance of
        :func:`tefcore.floquet.floquet_modes` even at 32 times the steps
        (``n_steps`` is the starting value and is doubled as needed).
    """
    if model is not None:
        if model.cfg != cfg:
            raise ValueError("model was built for another configuration than cfg")
        return _stability_of(model, trim(model, initial=trim_result), n_steps)
    # modes at the collective of the warm start (or the first estimate);
    # re-mode and re-trim only when the trim lands far from it: the MDART
    # frequencies move < 0.3 % per degree of collective (measured)
    theta_modes = (trim_result.controls.collective if trim_result is not None
                   else initial_collective(cfg))
    model = coupled_model(cfg, collective=theta_modes)
    tr = trim(model, initial=trim_result)
    if remode and abs(tr.controls.collective - theta_modes) > np.deg2rad(REMODE_DEG):
        model = coupled_model(cfg, collective=tr.controls.collective)
        tr = trim(model, initial=tr)
    return _stability_of(model, tr, n_steps)


def periodic_state_matrix(tr: TrimResult):
    """State matrix ``A(psi)`` of the system linearised about a forward-flight trim.

    ``A`` is sampled on the trim's azimuth grid (``cfg.model.n_azimuth``) and
    interpolated by Fourier series: the trim resolves harmonics below
    ``n_azimuth / 2``, and twice the samples change the exponents by less
    than 1e-3 /rev (measured on MDART at mu = 0.3).

    Returns
    -------
    a_of_psi : callable
        Vectorised ``A(psi)``, shape ``(len(psi), 2 n, 2 n)``, for
        :func:`tefcore.floquet.floquet_modes`.
    mass : ndarray, shape (n_azimuth, n, n)
        The mass matrix samples.
    """
    n = tr.model.n_dof
    n_lin = tr.model.cfg.model.n_azimuth
    psi_lin = np.linspace(0, 2 * np.pi, n_lin, endpoint=False)
    m, c, k = linearize(tr, psi_lin, scheme="forward")
    a_flat = state_matrix(m, c, k).reshape(n_lin, -1).T

    def a_of_psi(psi):
        return fourier_eval(a_flat, psi).T.reshape(-1, 2 * n, 2 * n)

    return a_of_psi, m


def _stability_of(model, tr: TrimResult, n_steps: int | None) -> StabilityResult:
    """Linearise a trimmed model and label its (Floquet) modes."""
    cfg = model.cfg
    n = model.n_dof
    hover = cfg.flight.advance_ratio == 0.0
    if hover:
        m, c, k = (a[0] for a in linearize(tr, [0.0], scheme="forward"))
        res = floquet.constant_coefficient_modes(state_matrix(m, c, k))
        mass_diag = np.abs(np.diag(m))
    else:
        a_of_psi, m = periodic_state_matrix(tr)
        # K = 4 sub-intervals to start with; floquet_modes raises K for
        # heavily damped roots (seen: -7.2 /rev torsion at Fig. 14's 0.22 R span),
        # and the steps until its error estimates meet the tolerance; a result
        # it cannot trust is an error, never a spurious (in)stability
        res = floquet.floquet_modes(a_of_psi, n_steps=n_steps or cfg.model.n_floquet_steps,
                                    n_sub=4, method="magnus", shift_states=slice(0, n),
                                    on_inaccurate="raise")
        mass_diag = np.abs(np.einsum("mii->i", m)) / m.shape[0]
    keep = res.positive_frequency()
    # by frequency; the two roots of a locked pair share it exactly, so ties
    # (to 1e-9 /rev, round-off) go less damped first, not by round-off
    order = np.lexsort((-keep.damping_rates, np.round(keep.frequencies, 9)))
    vec = keep.eigenvectors[:, order]
    labels, frac = _label_modes(vec, mass_diag, model.labels, keep.frequencies[order],
                                keep.damping_rates[order])
    table = pd.DataFrame({
        "mode_id": np.arange(len(labels)),
        "label": labels,
        "kind": [lab.split()[1] if lab.startswith("blade") else "TEF" for lab in labels],
        "coordinate_share": [frac[model.labels.index(lab.split(" (")[0]), j]
                             for j, lab in enumerate(labels)],
        "frequency_per_rev": keep.frequencies[order],
        "real_part": keep.damping_rates[order],
        "damping_ratio": keep.damping_ratios[order],
        "participation": frac.max(axis=0),
    })
    summary = tr.summary()
    summary["reverse_flow_fraction"] = _reverse_flow_fraction(tr)
    return StabilityResult(modes=table, eigenvectors=vec, trim=summary,
                           trim_result=tr)


def _reverse_flow_fraction(tr: TrimResult) -> float:
    """Share of the aerodynamic stations and azimuths in reverse flow (U_T < 0)."""
    model = tr.model
    psi = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    ut = model.x[None, :] + model.cfg.flight.advance_ratio * np.sin(psi)[:, None]
    return float(np.mean(ut < 0))
