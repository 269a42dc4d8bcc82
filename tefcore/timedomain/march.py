"""March the linearised periodic equations in azimuth and fit the growth of the response.

The paper's eq. (5), ``M(psi) q** + C(psi) q* + K(psi) q = 0`` (the
:class:`~tefcore.floquet.second_order.SecondOrderSystem` that the Floquet
analysis uses, aerodynamic states included), in first-order form
``x* = A(psi) x``, integrated with :func:`scipy.integrate.solve_ivp` (DOP853,
tight ``rtol``) revolution by revolution.  Each revolution starts from the
state divided by its largest element; the scales are kept, so the response
is exact while its size changes by many orders of magnitude (a +3 /rev root
grows ``e^{2 pi 3} = 1.5e8`` times a revolution) and the error control stays
relative (docs/theory.md section 12).

:func:`fit_growth` is the time-domain estimate of a growth rate: least
squares on the logarithm of the per-revolution envelope (the largest
``|signal|`` in each whole revolution), in the units of the Floquet real part
(per radian of azimuth, "/rev" in the tables).

Examples
--------
A damped oscillator ``q** + 0.2 q* + 4 q = 0`` decays at ``-0.1``:

>>> import numpy as np
>>> from tefcore.floquet.second_order import SecondOrderSystem
>>> one = np.ones((1, 1, 1))
>>> run = march(SecondOrderSystem(one, 0.2 * one, 4 * one), [1.0, 0.0], revs=4)
>>> psi = np.linspace(0, 4 * 2 * np.pi, 4001)
>>> round(fit_growth(psi, run.at(psi)[0]).rate, 3)
-0.1
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.integrate

__all__ = ["DEFAULT_RTOL", "RESOLVED_DECAY", "GrowthFit", "Trajectory", "envelope", "fit_growth",
           "march"]

#: Relative tolerance of the march: the exponents it checks are resolved to
#: about 1e-3 /rev; 1e-10 keeps the integration error far below that.
DEFAULT_RTOL = 1e-10

#: Absolute tolerance relative to the state's largest element at the start of
#: each revolution (the states are renormalised there).
RELATIVE_ATOL = 1e-13

TWO_PI = 2.0 * np.pi

#: Largest decay of a marched root that is resolved, relative to its start, in
#: forward flight: a root's periodic shape from the Floquet analysis is
#: accurate to about 1e-6 (measured: the balanced flap's TEF mode, -3.6 /rev,
#: levels off at 1e-6 of its start within a third of a revolution at mu = 0.3,
#: where the other roots take over); below 1e-5 of the start the response is
#: no longer the root's.  In hover the eigenvector is exact to round-off: 1e-12.
RESOLVED_DECAY = {"periodic": 1e-5, "constant": 1e-12}


@dataclass
class Trajectory:
    """A marched response: dense in azimuth, one piece per revolution.

    Attributes
    ----------
    pieces : list of tuple
        ``(psi_start, psi_end, log_scale, solution)``: the state on the piece
        is ``exp(log_scale) * solution(psi)``.
    n_states : int
        Length of the state.
    stopped : str
        Why the march ended before ``psi_end`` ("" when it did not).
    nfev : int
        Evaluations of the right-hand side.
    """

    pieces: list = field(default_factory=list)
    n_states: int = 0
    stopped: str = ""
    nfev: int = 0

    @property
    def psi_end(self) -> float:
        """Last azimuth reached [rad]."""
        return self.pieces[-1][1] if self.pieces else 0.0

    def at(self, psi) -> np.ndarray:
        """The state at azimuths within the march.

        Parameters
        ----------
        psi : array_like
            Azimuths [rad], between 0 and :attr:`psi_end`.

        Returns
        -------
        numpy.ndarray
            ``(n_states, len(psi))``.
        """
        psi = np.atleast_1d(np.asarray(psi, float))
        out = np.full((self.n_states, psi.size), np.nan)
        for k, (a, b, log_scale, sol) in enumerate(self.pieces):
            last = k == len(self.pieces) - 1
            sel = (psi >= a) & ((psi <= b) if last else (psi < b))
            if sel.any():
                out[:, sel] = np.exp(log_scale) * sol(psi[sel])
        return out


def march(system, x0, revs: float, *, rtol: float = DEFAULT_RTOL, rhs=None, events=None,
          piece: float = TWO_PI) -> Trajectory:
    """Integrate ``x* = A(psi) x`` from ``x(0) = x0`` for ``revs`` revolutions.

    Parameters
    ----------
    system : tefcore.floquet.second_order.SecondOrderSystem or None
        The linearised equations (``A(psi)``: :meth:`state_matrix`); None
        with ``rhs``.
    x0 : array_like
        Initial state ``[q, q*, z]`` (real).
    revs : float
        Revolutions (``psi`` from 0 to ``2 pi revs``); > 0.
    rtol : float, optional
        Relative tolerance of DOP853.
    rhs : callable, optional
        ``rhs(psi, x) -> x*`` instead of the linear system (a nonlinear
        march: no renormalisation).
    events : callable, optional
        A terminal event of :func:`scipy.integrate.solve_ivp` with a
        ``reason`` attribute (the text of ``stopped``).
    piece : float, optional
        Length of the pieces [rad]: at most this much of a march is lost
        when the right-hand side refuses a state.

    Returns
    -------
    Trajectory
        ``stopped`` says why a march ended early (the right-hand side
        refused a state with a ``ValueError``, or the integrator failed).
    """
    if not revs > 0:
        raise ValueError(f"revs must be positive, got {revs}")
    x = np.asarray(x0, float).copy()
    if rhs is None:
        rhs = system.rate_function()
        renormalise = True
    else:
        renormalise = False
    run = Trajectory(n_states=x.size)
    log_scale, end, start = 0.0, TWO_PI * revs, 0.0
    while start < end - 1e-12:
        stop = min(start + piece, end)
        scale = float(np.abs(x).max()) if renormalise else 1.0
        if not scale > 0:
            raise ValueError("the initial state is zero: nothing to march")
        y0 = x / scale
        log_scale += np.log(scale)
        try:
            sol = scipy.integrate.solve_ivp(rhs, (start, stop), y0, method="DOP853", rtol=rtol,
                                            atol=RELATIVE_ATOL * np.abs(y0).max(),
                                            dense_output=True, events=events)
        except ValueError as exc:           # a state the model refuses (Mach beyond range)
            run.stopped = f"the model refused a state after {start / TWO_PI:.3f} rev: {exc}"
            break
        run.nfev += sol.nfev
        if sol.status != 0:
            run.stopped = (f"{getattr(events, 'reason', 'event')} at {sol.t[-1] / TWO_PI:.3f} "
                           "rev" if sol.status == 1 else
                           f"integration failed at {sol.t[-1] / TWO_PI:.3f} rev: {sol.message}")
            if sol.t[-1] > start:
                run.pieces.append((start, float(sol.t[-1]), log_scale, sol.sol))
            break
        run.pieces.append((start, stop, log_scale, sol.sol))
        x = sol.y[:, -1]            # in this piece's units: the next one rescales
        start = stop
    if not run.pieces:
        raise ValueError(run.stopped or "the march made no step")
    return run


def envelope(psi, signal, period: float = TWO_PI):
    """Largest ``|signal|`` in each whole period.

    Parameters
    ----------
    psi : array_like
        Equally spaced azimuths from 0 [rad] (a partial last period is dropped).
    signal : array_like
        Values at ``psi``.
    period : float, optional
        Window [rad] (one revolution).

    Returns
    -------
    index : numpy.ndarray
        Window number ``k`` (``psi`` in ``[k period, (k + 1) period]``).
    values : numpy.ndarray
        The envelope of each window.
    """
    psi, signal = np.asarray(psi, float), np.abs(np.asarray(signal, float))
    n = int(np.floor(psi[-1] / period + 1e-9))
    index = np.arange(n)
    values = np.array([signal[(psi >= k * period - 1e-12) & (psi <= (k + 1) * period + 1e-12)]
                       .max() for k in index])
    return index, values


@dataclass
class GrowthFit:
    """A growth rate fitted to a response's per-revolution envelope.

    Attributes
    ----------
    rate : float
        Slope of ``ln(envelope)`` per radian of azimuth (the units of the
        Floquet real part, "/rev" in the tables); nan with fewer than two
        windows.
    revolutions : numpy.ndarray
        Window numbers used.
    log_envelope : numpy.ndarray
        ``ln`` of the envelope of each window.
    per_window : numpy.ndarray
        Growth between consecutive windows, same units.
    scatter : float
        Largest distance of ``ln(envelope)`` from the fitted line.
    """

    rate: float
    revolutions: np.ndarray
    log_envelope: np.ndarray
    per_window: np.ndarray
    scatter: float


def fit_growth(psi, signal, *, first: int = 0, period: float = TWO_PI,
               floor: float = 0.0) -> GrowthFit:
    """Least squares on ``ln`` of the per-revolution envelope: the growth rate.

    Parameters
    ----------
    psi : array_like
        Equally spaced azimuths from 0 [rad], fine enough to resolve the
        oscillation's peaks.
    signal : array_like
        The response at ``psi`` (e.g. the flap deflection).
    first : int, optional
        First window used (skip transients).
    period : float, optional
        Window [rad]: one revolution (whole revolutions, so the periodic
        coefficients' variation within a revolution averages out).
    floor : float, optional
        The fit ends before the first window whose envelope is below ``floor``
        times the first window's: what is left there is the error of the
        initial state, not the root (:data:`RESOLVED_DECAY`); 0: no limit.

    Returns
    -------
    GrowthFit
    """
    index, values = envelope(psi, signal, period)
    keep = (index >= first) & (values > 0) & np.isfinite(values)
    if floor > 0 and keep.any():
        low = np.flatnonzero(keep & (values < floor * values[np.argmax(keep)]))
        if low.size:
            keep &= index < index[low[0]]
    k, logv = index[keep], np.log(values[keep])
    if k.size < 2:
        return GrowthFit(float("nan"), k, logv, np.array([]), float("nan"))
    slope, intercept = np.polyfit(k, logv, 1)
    scatter = float(np.abs(logv - (slope * k + intercept)).max())
    return GrowthFit(float(slope / period), k, logv, np.diff(logv) / period, scatter)
