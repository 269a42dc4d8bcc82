"""Watch a root grow: march the linearised rotor from a small perturbation, check Floquet.

:func:`simulate` trims the configuration, linearises it (the
:class:`~tefcore.floquet.second_order.SecondOrderSystem` of
:func:`tefcore.linear.stability.stability`), starts from a small perturbation
-- by default the periodic shape of the flutter root when it is unstable,
else the TEF mode's; a named root; or a flap impulse -- marches it with
:func:`tefcore.timedomain.march.march`, fits the growth rate of the response's
dominant physical component and compares it with the Floquet real part of
the root it started from.  Optionally the full nonlinear residual is marched
from the same perturbation of the trim (:mod:`tefcore.timedomain.nonlinear`),
and the work of the mechanism's named terms is counted revolution by
revolution (:mod:`tefcore.timedomain.work`).  docs/theory.md section 12.

Growth rates are per radian of azimuth, as the Floquet real part ("/rev" in
the tables): the envelope grows by ``exp(2 pi rate)`` each revolution.

Examples
--------
In hover the balanced flap's TEF mode decays at -3.4 /rev (a factor 3e-10 a
revolution); the envelope fit finds it:

>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart").with_overrides({"flight.advance_ratio": 0.0})
>>> res = simulate(cfg, revs=3, work=False)
>>> res.summary["mode"], res.summary["agrees"]
('TEF', True)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..modes.roles import flutter_root
from .limits import MAX_AMPLITUDE, MAX_REVS, check_bounded
from .march import DEFAULT_RTOL, RESOLVED_DECAY, GrowthFit, Trajectory, fit_growth, march
from .nonlinear import check_nonlinear, flap_limit_event, nonlinear_rhs

__all__ = ["COMPONENTS", "FIT_SAMPLES", "LEAST_STABLE", "REL_TOLERANCE", "ABS_TOLERANCE",
           "SimulationResult", "check_march", "physical_map", "simulate"]

#: Physical components of the response: name -> (column of the history, unit).
COMPONENTS = {"tip_flap_bending": ("tip_flap_bending_m", "m"),
              "twist_flap_midspan": ("twist_flap_midspan_deg", "deg"),
              "flap_deflection": ("flap_deflection_deg", "deg"),
              "plunge_flap_midspan": ("plunge_flap_midspan_m", "m")}
#: Samples per revolution for the envelope: the peaks of a 12 /rev oscillation
#: are found to 1 - cos(pi 12 / 2048) = 1.7e-4 (in the log, far below the fit).
FIT_SAMPLES = 2048
#: The time-domain growth agrees with Floquet within REL_TOLERANCE |sigma| + ABS_TOLERANCE.
REL_TOLERANCE = 0.02
ABS_TOLERANCE = 0.01
#: How the start is named when ``mode="flutter"`` and that root is not unstable:
#: the flutter root is the least stable flap-induced root only when it is
#: unstable (as ``tefcore stability`` says).
LEAST_STABLE = "least stable flap-induced root"


@dataclass
class SimulationResult:
    """A marched response and its growth against the Floquet root.

    Attributes
    ----------
    history : pandas.DataFrame
        ``psi_rev`` (azimuth in revolutions), the generalised coordinates
        (``q:<name>``) and the physical components (:data:`COMPONENTS`, the
        perturbation about the trim), and with ``nonlinear`` the same
        physical columns of the nonlinear march (``nonlinear_...``; NaN after
        it stopped).
    summary : dict
        The JSON summary: ``growth_time_domain_per_rev``,
        ``growth_floquet_per_rev``, ``mode`` ... (see :func:`simulate`).
    run : Trajectory
        The linear march.
    fit : GrowthFit
        The growth fitted to the dominant component.
    stability : tefcore.linear.stability.StabilityResult
        The point's Floquet analysis.
    work : pandas.DataFrame or None
        :func:`tefcore.timedomain.work.work_per_revolution` of the linear march.
    floquet_work : dict
        The Floquet decomposition of the root (term -> contribution to its
        real part, :func:`tefcore.linear.mechanism.mechanism`); empty without
        ``work``.
    physical : numpy.ndarray
        Map from the coordinates ``q`` to the physical components, rows in
        :data:`COMPONENTS` order (SI: m and rad).
    nonlinear_run : Trajectory or None
        The nonlinear march of the perturbation.
    """

    history: pd.DataFrame
    summary: dict
    run: Trajectory
    fit: GrowthFit
    stability: object
    work: pd.DataFrame | None = None
    floquet_work: dict = field(default_factory=dict)
    physical: np.ndarray | None = None
    nonlinear_run: Trajectory | None = None


def physical_map(model) -> np.ndarray:
    """Map from the coordinates to tip flap bending, twist and plunge at the flap midspan, flap.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model.

    Returns
    -------
    numpy.ndarray
        ``(4, n_dof)``, rows in :data:`COMPONENTS` order: tip flap bending [m],
        twist at the flap midspan [rad], flap deflection [rad], plunge (flap
        bending) at the flap midspan [m].
    """
    radius = model.cfg.rotor.radius
    mid = model.modes.shapes(np.array([model.cfg.flap.midspan]))
    out = np.zeros((4, model.n_dof))
    nm = model.n_modes
    out[0, :nm] = model.tip_flap * radius
    out[1, :nm] = mid["phi"][0]
    out[3, :nm] = mid["w"][0] * radius
    if model.has_flap:
        out[2, nm] = 1.0
    return out


def _kinematic_weights(cfg) -> np.ndarray:
    """Metres moved per unit of each component: bending 1, twist c/2, flap c_f, plunge 1."""
    chord = cfg.rotor.chord
    return np.array([1.0, 0.5 * chord, cfg.flap.chord_ratio * chord, 1.0])


def _unstable(table, row) -> bool:
    """Whether a root is unstable: real part above zero and not within its error."""
    neutral = "neutral" in table.columns and table.at[row, "neutral"] in (True, 1)
    return bool(table.at[row, "real_part"] > 0) and not neutral


def _choose_root(table, mode, has_flap):
    """Row of the modes table to start from, and how it was chosen."""
    if mode is None:
        if not has_flap:
            raise ValueError("without the flap, name the mode to start from (e.g. 'blade lag 1')")
        row = flutter_root(table)
        if row is not None and _unstable(table, row):
            return row, "flutter root"
        mode = "TEF"
    if mode == "flutter":
        row = flutter_root(table) if has_flap else None
        if row is None:
            raise ValueError("no flap-induced root (the configuration has no flap)")
        return row, "flutter root" if _unstable(table, row) else LEAST_STABLE
    rows = np.flatnonzero(table["label"].to_numpy() == mode)
    if rows.size == 0:
        raise ValueError(f"no mode named {mode!r}; names: {', '.join(table['label'])}; "
                         "or 'TEF' or 'flutter'")
    return int(table.index[rows[0]]), ("TEF mode" if mode == "TEF" else "named mode")


def _initial_state(res, row, impulse, amplitude, phys, weights, has_flap):
    """The perturbation: the root's shape at psi = 0 (its dominant motion at its peak,
    ``amplitude`` chords), or a flap impulse (flap rate ``amplitude / E``)."""
    cfg = res.trim_result.model.cfg
    n = res.system.n_dof
    x0 = np.zeros(res.system.n_states)
    if impulse:
        if not has_flap:
            raise ValueError("a flap impulse needs the flap (model.tef = 'dynamic')")
        x0[2 * n - 1] = amplitude / cfg.flap.chord_ratio
        return x0
    v = np.asarray(res.eigenvectors[:, int(np.flatnonzero(res.modes.index == row)[0])])
    motion = weights[:3] * (phys[:3] @ v[:n])
    big = motion[np.argmax(np.abs(motion))]
    x0 = np.real(v * (abs(big) / big))
    size = np.abs(weights[:3] * (phys[:3] @ x0[:n])).max()
    return x0 * (amplitude * cfg.rotor.chord / size)


def _reference(table, row, impulse):
    """The Floquet root to compare with: the start's, or for an impulse the least stable."""
    if impulse:
        row = int(table["real_part"].idxmax())
    return row, float(table.at[row, "real_part"]), float(table.at[row, "frequency_per_rev"])


def _components(run, phys, n, psi):
    """Physical components (rows of :data:`COMPONENTS`, SI) of a march at ``psi``."""
    return phys @ run.at(psi)[:n]


def _fit(run, phys, weights, n, first, floor, window=2 * np.pi):
    """Fit the growth of the dominant component (largest kinematic peak) of a march."""
    revs = run.psi_end / (2 * np.pi)
    psi = np.linspace(0.0, run.psi_end, int(np.ceil(FIT_SAMPLES * revs)) + 1)
    comp = _components(run, phys, n, psi)
    peaks = np.nanmax(np.abs(comp[:3]), axis=1) * weights[:3]
    dominant = int(np.argmax(peaks))
    fit = fit_growth(psi, comp[dominant], first=first, period=window, floor=floor)
    return fit, dominant, psi, comp


def _history(res, run, phys, samples_per_rev, revs):
    """The time history: azimuth, coordinates, physical components (deg for angles)."""
    model = res.trim_result.model
    n = model.n_dof
    psi = np.linspace(0.0, 2 * np.pi * revs, int(round(samples_per_rev * revs)) + 1)
    x = run.at(psi)
    cols = {"psi_rev": psi / (2 * np.pi)}
    cols.update({f"q:{lab}": x[i] for i, lab in enumerate(model.labels)})
    cols.update(_physical_columns(phys @ x[:n], ""))
    return pd.DataFrame(cols), psi


def _physical_columns(comp, prefix):
    out = {}
    for i, (name, unit) in enumerate(COMPONENTS.values()):
        out[prefix + name] = np.rad2deg(comp[i]) if unit == "deg" else comp[i]
    return out


def simulate(cfg, mode: str | None = None, *, impulse: bool = False, revs: float = 6,
             amplitude: float = 1e-3, nonlinear: bool = False, samples_per_rev: int = 72,
             stability_result=None, rtol: float = DEFAULT_RTOL, work: bool = True,
             fit_from: int | None = None) -> SimulationResult:
    """March the linearised rotor from a small perturbation and fit its growth rate.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.
    mode : str, optional
        The root whose periodic shape starts the march: ``"TEF"``,
        ``"flutter"`` (the least stable flap-induced root) or a name of the
        stability table; None: the flutter root when it is unstable, else the
        TEF mode.
    impulse : bool, optional
        Start from a flap impulse instead (flap rate ``amplitude / E`` per
        radian, everything else at rest); compared with the least stable root.
    revs : float, optional
        Revolutions marched.
    amplitude : float, optional
        Size of the perturbation: the largest kinematic displacement (tip
        bending, twist times half the chord, flap times its chord) at
        ``psi = 0``, in chords.
    nonlinear : bool, optional
        Also march the full nonlinear equations from the trim plus the same
        perturbation (:mod:`tefcore.timedomain.nonlinear`).
    samples_per_rev : int, optional
        Rows of the history per revolution.
    stability_result : tefcore.linear.stability.StabilityResult, optional
        Of ``cfg``, if already computed.
    rtol : float, optional
        Relative tolerance of the march.
    work : bool, optional
        Count the work of the named terms per revolution, with the Floquet
        decomposition of the root beside it.
    fit_from : int, optional
        First revolution of the fit (default 0; 1 after an impulse, whose
        first revolution holds the decay of the other roots).

    Returns
    -------
    SimulationResult
        ``summary``: ``mode`` (the root's name, or ``"flap impulse"``),
        ``start``, ``growth_time_domain_per_rev``, ``growth_floquet_per_rev``,
        ``frequency_floquet_per_rev``, ``difference``, ``tolerance``,
        ``agrees`` (within 2 % + 0.01 /rev), ``component`` (the dominant
        component fitted), ``growth_per_revolution``, ``fit_revolutions``,
        ``growth_factor_per_revolution``, with ``work`` the ``work_closure``,
        with ``nonlinear`` a ``nonlinear`` entry (:func:`_compare_nonlinear`).

    Raises
    ------
    ValueError
        Unknown ``mode``; no flap for a flap mode or impulse; ``revs`` or
        ``amplitude`` outside their ranges (:func:`check_march`), before
        anything is computed; with ``nonlinear``, aerodynamic states.
    """
    from ..linear.stability import stability

    check_march(revs, amplitude)                  # before anything is computed
    if nonlinear:
        check_nonlinear(cfg)
    res = stability_result or stability(cfg)
    model = res.trim_result.model
    table = res.modes
    row, start = ((None, "flap impulse") if impulse
                  else _choose_root(table, mode, model.has_flap))
    ref_row, sigma, freq = _reference(table, row, impulse)
    phys, weights, n = physical_map(model), _kinematic_weights(cfg), model.n_dof
    x0 = _initial_state(res, row, impulse, amplitude, phys, weights, model.has_flap)
    run = march(res.system, x0, revs, rtol=rtol)
    first = fit_from if fit_from is not None else (1 if impulse and revs >= 3 else 0)
    floor = RESOLVED_DECAY["periodic" if res.periodic else "constant"]
    fit, dominant, _, _ = _fit(run, phys, weights, n, first, floor)
    history, psi = _history(res, run, phys, samples_per_rev, revs)
    summary = _summary(cfg, table, row, ref_row, start, sigma, freq, fit, dominant, amplitude,
                       revs, impulse)
    out = SimulationResult(history=history, summary=summary, run=run, fit=fit, stability=res,
                           physical=phys)
    if work:
        _add_work(out, res, ref_row, sigma, freq)
    if nonlinear:
        _compare_nonlinear(out, res, x0, revs, phys, weights, psi, rtol)
    return out


def check_march(revs: float, amplitude: float) -> None:
    """Refuse revolutions or an amplitude :func:`simulate` cannot march: one line each.

    Parameters
    ----------
    revs : float
        Revolutions, in (0, :data:`~tefcore.timedomain.limits.MAX_REVS`].
    amplitude : float
        Perturbation in chords, in (0, :data:`~tefcore.timedomain.limits.MAX_AMPLITUDE`].

    Raises
    ------
    ValueError
        Naming the argument, its value and its range (NaN and infinities too).

    Examples
    --------
    >>> check_march(6, 1e-3)
    >>> check_march(6, float("nan"))
    Traceback (most recent call last):
    ...
    ValueError: amplitude = nan: must be a number in (0, 1] (chords)
    """
    check_bounded("revs", revs, MAX_REVS, "revolutions marched")
    check_bounded("amplitude", amplitude, MAX_AMPLITUDE, "chords")


def _summary(cfg, table, row, ref_row, start, sigma, freq, fit, dominant, amplitude, revs,
             impulse):
    tol = REL_TOLERANCE * abs(sigma) + ABS_TOLERANCE
    name = "flap impulse" if impulse else str(table.at[row, "label"])
    resolved = bool(np.isfinite(fit.rate))
    if resolved:
        note = ""
    elif revs < 2:
        note = "no growth fitted: the fit needs two whole revolutions (--revs 2 or more)"
    else:
        note = ("no growth fitted: the response decayed below the resolved fraction of its "
                "start (the accuracy of the root's shape) within the first revolution: a root "
                "this damped is gone in one revolution")
    return {
        "configuration": cfg.name, "mode": name, "start": start,
        "compared_with": str(table.at[ref_row, "label"]),
        "growth_time_domain_per_rev": fit.rate, "growth_floquet_per_rev": sigma,
        "frequency_floquet_per_rev": freq, "difference": fit.rate - sigma,
        "tolerance": tol, "agrees": bool(abs(fit.rate - sigma) <= tol) if resolved else None,
        "note": note,
        "component": list(COMPONENTS)[dominant],
        "growth_factor_per_revolution": float(np.exp(2 * np.pi * fit.rate)),
        "growth_per_revolution": [float(v) for v in fit.per_window],
        "fit_revolutions": [int(fit.revolutions[0]), int(fit.revolutions[-1])]
        if fit.revolutions.size else [], "fit_scatter": fit.scatter,
        "amplitude_chord": amplitude, "revolutions": revs,
        "units": "growth rates per radian of azimuth (the Floquet real part, '/rev' in the "
                 "tables): the envelope grows by exp(2 pi rate) each revolution"}


def _add_work(out, res, ref_row, sigma, freq):
    """The per-revolution work of the named terms and the Floquet decomposition beside it."""
    from ..linear.mechanism import linearized_terms, mechanism
    from .work import work_per_revolution

    parts = linearized_terms(res.trim_result)
    out.work = work_per_revolution(parts, out.run, rate=out.fit.rate)
    mech = mechanism(res.trim_result.model.cfg, mode="root", root=complex(sigma, freq),
                     knockouts=False, stability_result=res)
    terms = mech.table[~mech.table["term"].str.startswith(("total", "knockout"))]
    out.floquet_work = dict(zip(terms["term"], terms["contribution_real"].astype(float),
                                strict=True))
    closure = (out.work["sum"] - out.work["energy_growth"]).abs()
    out.summary["work_closure"] = float(closure.max()) if len(closure) else float("nan")


#: Relative departures of the nonlinear response from the linear one that are reported.
DEPARTURES = (0.01, 0.1)


def _compare_nonlinear(out, res, x0, revs, phys, weights, psi_hist, rtol):
    """March the nonlinear equations from the same perturbation; compare with the linear march.

    Adds the ``nonlinear_...`` history columns and ``summary["nonlinear"]``:
    ``growth_nonlinear_per_rev`` and ``growth_linear_same_window`` (the same
    fit on both marches, over the azimuths the nonlinear one reached: whole
    revolutions when it reached two, else eighths of a revolution,
    ``fit_window_rev``), ``stopped`` (why it ended early, or ""), ``reached_rev``,
    and ``departures``: where the dominant component first differs from the
    linear one by 1 % and 10 % of the linear amplitude so far, with the
    amplitudes of the physical components there.
    """
    tr = res.trim_result
    n = tr.model.n_dof
    run = march(None, x0[:2 * n], revs, rtol=rtol, rhs=nonlinear_rhs(tr),
                events=flap_limit_event(tr), piece=2 * np.pi / 8)
    out.nonlinear_run = run
    x = run.at(psi_hist)
    out.history = out.history.assign(**_physical_columns(phys @ x[:n], "nonlinear_"))
    window = 2 * np.pi if run.psi_end >= 4 * np.pi - 1e-9 else 2 * np.pi / 8
    floor = RESOLVED_DECAY["periodic" if res.periodic else "constant"]
    fit_nl, dom, psi, comp_nl = _fit(run, phys, weights, n, 0, floor, window)
    comp_lin = _components(out.run, phys, n, psi)
    fit_lin = fit_growth(psi, comp_lin[dom], period=window, floor=floor)
    scale = np.maximum.accumulate(np.abs(comp_lin[dom]))
    rel = np.abs(comp_nl[dom] - comp_lin[dom]) / np.where(scale > 0, scale, np.inf)
    departures = {}
    for level in DEPARTURES:
        hit = np.flatnonzero(rel > level)
        if hit.size == 0:
            departures[f"{level:g}"] = None
            continue
        j = hit[0]
        amp = np.max(np.abs(comp_nl[:, :j + 1]), axis=1)
        departures[f"{level:g}"] = {"psi_rev": float(psi[j] / (2 * np.pi)), **{
            col: float(np.rad2deg(a) if unit == "deg" else a)
            for (col, unit), a in zip(COMPONENTS.values(), amp, strict=True)}}
    out.summary["nonlinear"] = {
        "growth_nonlinear_per_rev": fit_nl.rate, "growth_linear_same_window": fit_lin.rate,
        "fit_window_rev": window / (2 * np.pi), "component": list(COMPONENTS)[dom],
        "reached_rev": run.psi_end / (2 * np.pi), "stopped": run.stopped,
        "departures": departures, "largest_relative_departure": float(np.nanmax(rel))}
