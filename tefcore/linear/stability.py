"""Linearisation about the trim and Floquet stability with labelled modes.

``stability(cfg)`` is the paper's analysis in one call: coupled model, trim,
``M(psi), C(psi), K(psi)`` of eq. (5) by finite differences of the
nonlinear residual about the trimmed periodic motion
(:class:`tefcore.floquet.second_order.SecondOrderSystem`), and Floquet
eigenanalysis (direct eigenanalysis in hover, where the coefficients are
constant).  Each mode is labelled by the coordinate that carries most of its
participation (participation factors,
:meth:`tefcore.floquet.FloquetResult.with_participation`); its shares by
kind (blade flap, lag, torsion, axial, TEF) and its physical shape
(:meth:`tefcore.model.coupled.CoupledModel.tracking_basis`) go with it, so that
modes can be followed along sweeps (:mod:`tefcore.modes.tracking`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..aero.c81.range_summary import summarised_range_warnings
from ..floquet.second_order import STATE_MIN_RATE, SecondOrderSystem
from ..floquet.second_order import state_matrix as state_matrix
from ..model.coupled import coupled_model
from ..model.jacobian import jacobian_blocks
from ..modes.continuation import continue_roots
from ..modes.labels import coordinate_shares, label_modes, tracking_shapes
from ..modes.names import base_name, mode_kind
from ..modes.roles import named_columns
from ..runtime import blas_limit
from ..trimming.trim import TrimResult, initial_collective, trim

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["REMODE_DEG", "SHARE_KINDS", "StabilityResult", "linear_system", "linearize",
           "periodic_state_matrix", "stability", "state_matrix"]

#: Kinds of coordinates whose kinetic-energy shares the modes table reports.
SHARE_KINDS = ("flap", "lag", "torsion", "axial", "TEF")

#: Re-mode threshold [deg] between the modes' collective and the trimmed one.
REMODE_DEG = 2.0


def linearize(tr: TrimResult, psi, step: float = 1e-6, scheme: str = "exact"):
    """``M, C, K`` (each ``(len(psi), n, n)``) about the trimmed motion.

    Derivatives of the residual with respect to ``q**, q*, q``, vectorised
    over the azimuths (the residual at one azimuth depends only on the motion
    there).  ``scheme='exact'``: exact to round-off
    (:func:`tefcore.model.jacobian.exact_jacobian`; forward differences for
    the shed-wake states, which it does not cover).  Finite differences:
    ``'central'``, truncation error ~``step^2``, 2n evaluations per matrix;
    ``'forward'``: error ~``step`` (1e-6 relative), half the evaluations.

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim to linearise about.
    psi : array_like
        Azimuths [rad].
    step : float, optional
        Finite-difference step, relative.
    scheme : {"exact", "central", "forward"}, optional
        Exact, or the finite-difference scheme.

    Returns
    -------
    M, C, K : numpy.ndarray
        Each ``(len(psi), n, n)``.
    """
    psi = np.atleast_1d(np.asarray(psi, float))
    y, yd, ydd, inflow = tr.linear_point(psi)
    jac, _, _ = jacobian_blocks(tr.model, psi, y, yd, ydd, tr.controls, inflow,
                                step=step, scheme=scheme, n_second=tr.model.n_dof)
    return jac[2], jac[1], jac[0]


@dataclass
class StabilityResult:
    """Modes of the linearised blade/flap system and the trim they belong to.

    Attributes
    ----------
    columns : dict
        The modes table as its columns (name -> one value per mode, in the
        table's order); :attr:`modes` is the table.
    modes : DataFrame
        One row per mode, see :func:`stability`.
    eigenvectors : ndarray, shape (2 n, n_modes)
        State eigenvectors ``[q; q*]`` at psi = 0 (columns as the rows of
        ``modes``).
    trim : dict
        Trim scalars.
    trim_result : TrimResult
    vectors : ndarray, shape (2 n_phys, n_modes)
        Physical shapes of the displacements and velocities at psi = 0
        (:meth:`tefcore.model.coupled.CoupledModel.tracking_basis` times each):
        the parameter-independent basis in which modes are compared between
        sweep points.
    periodic : bool
        True for forward flight (Floquet), False for hover (constant
        coefficients).
    system : SecondOrderSystem
        The linearised ``M, C, K`` the modes belong to (with the aerodynamic
        states as first-order coordinates, if any).
    identity : tefcore.modes.continuation.ContinuedRoots or None
        How each root was named: its path from zero coupling
        (:func:`tefcore.modes.continuation.continue_roots`), where two paths
        met (``identity.meetings``); None without the flap or with
        ``identity=False``.
    aero_modes : DataFrame or None
        With aerodynamic states (docs/theory.md 6.2): the roots that belong to
        them rather than to the blade and flap (blade and flap states carry
        less than half of the root's participation), one row per root
        (positive frequency): ``kind`` (``wake`` or ``inflow``, the states with
        the larger share), ``frequency_per_rev, real_part, share_structure,
        share_TEF``.  They take no mode label and are not in ``modes``.
    """

    columns: dict
    eigenvectors: np.ndarray
    trim: dict
    trim_result: TrimResult
    vectors: np.ndarray | None = None
    periodic: bool = False
    system: SecondOrderSystem | None = None
    aero_modes: pd.DataFrame | None = None
    identity: object = None
    _modes: pd.DataFrame | None = field(default=None, repr=False, compare=False)

    @property
    def modes(self) -> pd.DataFrame:
        """The modes table, built from :attr:`columns` when first asked for.

        Built on demand: a command that prints the roots (``tefcore
        stability``) reads the columns and never imports pandas (0.15 s of
        its start, measured with ``python -X importtime``).
        """
        if self._modes is None:
            import pandas as pd

            self._modes = pd.DataFrame(self.columns)   # one construction
        return self._modes

    @modes.setter
    def modes(self, table: pd.DataFrame) -> None:
        # a table given replaces the columns too: both say the same
        self._modes = table
        self.columns = {c: table[c].to_numpy() for c in table.columns}


@blas_limit()
def stability(cfg, *, trim_result: TrimResult | None = None, n_steps: int | None = None,
              remode: bool = True, model=None,
              warm_start: TrimResult | None = None, identity: bool = True) -> StabilityResult:
    """Trim the configuration and compute its labelled stability modes.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor configuration.
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
        :func:`tefcore.model.coupled.coupled_model`, e.g. to keep one set of blade
        modes for several flight conditions; its modes are used as they are
        (no re-moding).
    warm_start : TrimResult, optional
        The trim of a neighbouring configuration as the first guess of the
        trim only: the blade modes are those of a cold start (at
        :func:`tefcore.trimming.trim.initial_collective`), so the result equals the cold
        one to the trim's tolerance (what sweeps use, :mod:`tefcore.sweeps.sweep`).
        Its Newton matrix (:meth:`tefcore.trimming.trim.TrimResult.final_blocks`) starts
        the iterations.
    identity : bool, optional
        Name each root by the uncoupled mode it continues from
        (:func:`tefcore.modes.continuation.continue_roots`; with the flap).
        False: by the coordinate it carries most (faster; no roles).

    Returns
    -------
    StabilityResult
        ``modes`` has one row per mode (positive-frequency member of each
        complex pair): ``mode_id, label, kind, coordinate_share,
        frequency_per_rev, real_part, damping_ratio, participation`` and
        ``share_flap, share_lag, share_torsion, share_axial, share_TEF``
        (participation by kind of coordinate, summing to 1) --
        ``real_part`` is the damping rate per radian of azimuth (negative:
        stable) -- and ``real_part_error``, the solver's resolution of the
        real part: the Floquet error estimate of the exponent
        (:func:`tefcore.floquet.floquet_modes`: step doubling plus the
        round-off bound of the lift; in hover the eigenvalue's round-off bound
        from its condition number), and ``neutral``, True where
        ``|real_part| <= real_part_error``: a sign below the resolution that
        means nothing (e.g. a lightly coupled axial root).

    Warns
    -----
    tefcore.aero.c81.C81RangeWarning
        Once for the point when C81 table inputs were clipped, with the
        number of evaluations clipped and the extreme inputs
        (:mod:`tefcore.aero.c81.range_summary`).

    Raises
    ------
    ValueError
        If ``model`` was built for another configuration.
    tefcore.trimming.trim.TrimError
        If the trim does not converge.
    tefcore.floquet.FloquetAccuracyError
        If the Floquet exponents do not meet the default tolerance of
        :func:`tefcore.floquet.floquet_modes` even at 32 times the steps
        (``n_steps`` is the starting value and is doubled as needed).

    References
    ----------
    .. [1] *Aeroelastic Stability of Trailing-Edge Flap Helicopter Rotors*,
       "Stability Analysis": the perturbation equations (5) about the trim
       and their Floquet eigenanalysis; docs/theory.md sections 5 and 8.

    Examples
    --------
    The MDART baseline in hover: the flap mode, well above the blade modes,
    is stable.

    >>> from tefcore.config.io import load_config
    >>> res = stability(load_config("mdart"))
    >>> tef = res.modes[res.modes["label"] == "TEF"].iloc[0]
    >>> bool(tef["real_part"] < 0), bool(tef["frequency_per_rev"] > 12)
    (True, True)
    """
    # one C81 range warning for the point, not one per airload evaluation
    with summarised_range_warnings(stacklevel=4):
        return _trimmed_stability(cfg, trim_result, n_steps, remode, model, warm_start,
                                  identity)


def _trimmed_stability(cfg, trim_result, n_steps, remode, model, warm_start, identity):
    """:func:`stability`'s trim (from the warm start or the model given) and modes."""
    if model is not None:
        if model.cfg != cfg:
            raise ValueError("model was built for another configuration than cfg")
        return _stability_of(model, trim(model, initial=trim_result or warm_start), n_steps,
                            identity)
    if warm_start is not None and trim_result is None:
        theta = initial_collective(cfg)
        model = coupled_model(cfg, collective=theta)
        tr = trim(model, initial=warm_start)
        if remode and abs(tr.controls.collective - theta) > np.deg2rad(REMODE_DEG):
            model = coupled_model(cfg, collective=tr.controls.collective)
            tr = trim(model, initial=tr)
        return _stability_of(model, tr, n_steps, identity)
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
    return _stability_of(model, tr, n_steps, identity)


def linear_system(tr: TrimResult) -> SecondOrderSystem:
    """The paper's eq. (5) linearised about a trim: ``M, C, K`` on the trim grid.

    Hover: one sample (constant coefficients).  Forward flight: the trim's
    ``cfg.model.n_azimuth`` equally spaced azimuths, interpolated by
    trigonometric series (the trim resolves harmonics below
    ``n_azimuth / 2``; twice the samples change the exponents by less than
    1e-3 /rev, measured on MDART at mu = 0.3).  The one Jacobian of the
    residual at the solution (:meth:`tefcore.trimming.trim.TrimResult.final_blocks`,
    on the trim's grid), which also gives the trim's Newton matrix there:
    exact (:func:`tefcore.model.jacobian.exact_jacobian`), with the dynamic-inflow
    states too; with the shed-wake states forward differences (step 1e-6).
    A trim without the record of its equations is linearised on its own
    (:func:`linearize`).

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim to linearise about.

    Returns
    -------
    tefcore.floquet.second_order.SecondOrderSystem
    """
    model = tr.model
    n_first = model.n_wake + model.n_inflow
    blocks = tr.final_blocks()
    if blocks is not None:
        # the Jacobian at the solution, on the trim's grid, that also gives the
        # trim's Newton matrix there (one evaluation for both)
        k, c, m = blocks
        return SecondOrderSystem(m, c, k, n_first=n_first)
    if model.hover:
        psi = np.zeros(1)
    else:
        psi = np.linspace(0, 2 * np.pi, model.cfg.model.n_azimuth, endpoint=False)
    m, c, k = linearize(tr, psi, scheme="exact")
    return SecondOrderSystem(m, c, k, n_first=n_first)


def periodic_state_matrix(tr: TrimResult):
    """State matrix ``A(psi)`` of the system linearised about a forward-flight trim.

    ``M, C, K`` are sampled on the trim's azimuth grid, interpolated by
    trigonometric series and ``A = [[0, I], [-M^-1 K, -M^-1 C]]`` formed at
    each azimuth (:meth:`SecondOrderSystem.state_matrix`).

    Parameters
    ----------
    tr : tefcore.trimming.trim.TrimResult
        The trim to linearise about.

    Returns
    -------
    a_of_psi : callable
        Vectorised ``A(psi)``, shape ``(len(psi), 2 n, 2 n)``, for
        :func:`tefcore.floquet.floquet_modes`.
    mass : ndarray, shape (n_azimuth, n, n)
        The mass matrix samples.
    """
    system = linear_system(tr)
    return system.state_matrix, system.m


def _stability_of(model, tr: TrimResult, n_steps: int | None,
                  identity: bool = True) -> StabilityResult:
    """Linearise a trimmed model, name its (Floquet) modes and their roles."""
    cfg = model.cfg
    system = linear_system(tr)
    # floquet_modes chooses the sub-intervals K from a bound of the most damped
    # root (raised for heavily damped roots, seen: -7.2 /rev torsion at Fig. 14's
    # 0.22 R span), and the steps until its error estimates meet the tolerance;
    # a result it cannot trust is an error, never a spurious (in)stability
    # the participation factors from the adjoint solutions (no inverse of the
    # shapes; within 6e-7 of it on the figures' points, measured)
    res = system.modes(n_steps=n_steps or cfg.model.n_floquet_steps, n_sub=1,
                       shapes=system.periodic, on_inaccurate="raise",
                       participation=system.periodic)
    if res.participation is None:
        res = res.with_participation()
    keep = res.positive_frequency()
    aero_modes = None
    if system.n_first:
        keep, aero_modes = _split_aero_roots(keep, model, system.periodic)
    # by frequency; the two roots of a locked pair share it exactly, so ties
    # (to 1e-9 /rev, round-off) go less damped first, not by round-off
    order = np.lexsort((-keep.damping_rates, np.round(keep.frequencies, 9)))
    keep = keep.select(order)
    columns, shapes, frac = _modes_columns(model, keep, system.periodic)
    continued = None
    if identity and model.has_flap:
        # the paths on the first grid of the Floquet steps, which divides the
        # grid the roots were resolved on (step doubling)
        continued = continue_roots(system, model.labels, keep, basis=model.tracking_basis(),
                                   final_labels=list(columns["dominant"]), final_shares=frac,
                                   n_steps=n_steps or cfg.model.n_floquet_steps)
        columns = named_columns(columns, continued, frac, model.labels)
    summary = tr.summary()
    summary["reverse_flow_fraction"] = _reverse_flow_fraction(tr)
    if aero_modes is not None:
        summary["aero_state_growth"] = (float(aero_modes["real_part"].max())
                                        if len(aero_modes) else float("nan"))
    return StabilityResult(columns=columns, eigenvectors=keep.eigenvectors, trim=summary,
                           trim_result=tr, vectors=shapes, periodic=system.periodic,
                           system=system, aero_modes=aero_modes, identity=continued)


def _modes_columns(model, keep, periodic):
    """The columns of the modes table by participation (labels: the coordinate
    each root carries most), the roots' tracking shapes and the coordinates' shares."""
    n = model.n_dof
    frac = coordinate_shares(keep.participation, n)
    shapes = tracking_shapes(model.tracking_basis(), keep, n)
    labels = label_modes(frac, model.labels, keep.frequencies, keep.damping_rates, shapes,
                         periodic=periodic)
    kinds = [mode_kind(lab) for lab in model.labels]
    columns = {
        "mode_id": np.arange(len(labels)),
        "label": np.array(labels, dtype=object),
        "dominant": np.array(labels, dtype=object),
        "kind": [mode_kind(lab) for lab in labels],
        "coordinate_share": [frac[model.labels.index(base_name(lab)), j]
                             for j, lab in enumerate(labels)],
        "frequency_per_rev": keep.frequencies,
        "real_part": keep.damping_rates,
        "damping_ratio": keep.damping_ratios,
        "participation": frac.max(axis=0),
    }
    for kind in SHARE_KINDS:
        rows = [i for i, k in enumerate(kinds) if k == kind]
        columns[f"share_{kind}"] = frac[rows].sum(axis=0) if rows else np.zeros(len(labels))
    # the resolution of each real part: its error estimate (per rad of psi, as real_part)
    err = (np.full(len(labels), np.nan) if keep.error_estimates is None
           else np.asarray(keep.error_estimates).real)
    columns["real_part_error"] = err
    columns["neutral"] = np.abs(keep.damping_rates) <= err
    return columns, shapes, frac


#: Least share of a root's participation in the blade and flap states for the
#: root to be a mode of the blade and flap rather than of the aerodynamic states.
STRUCTURAL_SHARE = 0.5


def _split_aero_roots(res, model, periodic):
    """Roots of the blade and flap, and a table of the aerodynamic-state roots.

    A root whose participation (magnitudes, over all states) lies less than
    :data:`STRUCTURAL_SHARE` in the blade and flap states ``[q, q*]`` is a root
    of the shed wake or the inflow: it gets no mode label; so does a root that
    the assignment of the coordinates' labels leaves over and that is not the
    partner of a locked pair.  In forward flight a root below
    :data:`~tefcore.floquet.second_order.STATE_MIN_RATE` is a state's too:
    the lift does not resolve it, nor its participation.
    """
    n, nw = model.n_dof, model.n_wake
    mag = np.abs(res.participation)
    total = mag.sum(axis=0)
    structural = mag[:2 * n].sum(axis=0) / total
    aero = structural < STRUCTURAL_SHARE
    if periodic:
        # below STATE_MIN_RATE a root is not resolved (the lift is not asked
        # to) and its adjoint, so its participation, is round-off: it is a
        # state's (STATE_MIN_RATE lies below every blade or flap root), never
        # a candidate for a coordinate (measured at MDART mu = 0.3, c_cg 0.1,
        # with the wake: such a root at -15.9 /rev read a structural share
        # above 1/2 once the adjoints' K was set by STATE_MIN_RATE)
        aero |= res.damping_rates < STATE_MIN_RATE
    # a root that the coordinates' labels leave over is a state's, unless it is
    # the partner of a locked pair (the same frequency as a labelled root): e.g.
    # the mean inflow root in hover, 58 % in the collective flap motion (measured)
    cand = np.flatnonzero(~aero)
    frac = coordinate_shares(res.participation[:, cand], n)
    from scipy.optimize import linear_sum_assignment  # on first use: 0.2 s
    _, cols = linear_sum_assignment(-np.log(frac + 1e-300))
    named = res.frequencies[cand[cols]]
    for j in np.setdiff1d(np.arange(cand.size), cols):
        if np.abs(named - res.frequencies[cand[j]]).min() > 1e-6:
            aero[cand[j]] = True
    wake, inflow = mag[2 * n:2 * n + nw].sum(axis=0), mag[2 * n + nw:].sum(axis=0)
    flap = (mag[n - 1] + mag[2 * n - 1]) / total if model.has_flap else np.zeros(total.size)
    import pandas as pd  # only with aerodynamic states: a point without them needs no pandas

    table = pd.DataFrame({
        "kind": np.where(wake >= inflow, "wake", "inflow")[aero],
        "frequency_per_rev": res.frequencies[aero], "real_part": res.damping_rates[aero],
        "share_structure": structural[aero], "share_TEF": flap[aero]})
    table = table.sort_values(["kind", "real_part"], ascending=[True, False],
                              ignore_index=True)
    return res.select(~aero), table


def _reverse_flow_fraction(tr: TrimResult) -> float:
    """Share of the aerodynamic stations and azimuths in reverse flow (U_T < 0)."""
    model = tr.model
    psi = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    ut = model.x[None, :] + model.flight.advance_ratio * np.sin(psi)[:, None]
    return float(np.mean(ut < 0))
