"""The nonlinear part of the coupled residual, station by station (docs/theory.md 6.3).

The residual of :class:`tefcore.model.coupled.CoupledModel` is linear in the modal
coordinates except through the section kinematics.  At each aerodynamic
station ``x_s`` and azimuth the nonlinear part depends only on a few *local
variables* there:

* at every station (:data:`STATION_VARIABLES`): the section pitch
  ``Theta = theta + phi`` and its two azimuth derivatives, the velocities
  ``U_T, U_P`` (units ``Omega R``) and the plunge acceleration ``w**``;
* on the flap stations also (:data:`FLAP_VARIABLES`): the flap slope
  ``w' + beta_p``, the lag deflection, slope and their rates, the flap
  slope's rate and the flap deflection ``delta`` with its two derivatives.

:func:`station_terms` returns, for every named piece of the residual, the
*station forces*: the force per station that multiplies a mode-shape field at
that station (``w``, ``w'``, ``v``, ``v'``, ``phi``) in the blade rows, or that
adds to the flap row (``flap``), quadrature weights included.  The residual is
their projection on the mode shapes (:meth:`~tefcore.model.coupled.CoupledModel.residual_pieces`)
plus the terms linear in the coordinates (structure, actuator).

Every operation is analytic in the local variables (``|U_T|`` is written
``U_T sign(Re U_T)``), so the station forces can be evaluated at complex local
variables: the exact Jacobian (:mod:`tefcore.model.jacobian`) takes their
derivatives by complex step, one perturbation per local variable for all
stations at once, and projects them on the shapes.

Examples
--------
>>> from tefcore.config.io import load_config
>>> from tefcore.model.coupled import coupled_model
>>> model = coupled_model(load_config("mdart"))
>>> n_x, n_f = model.x.size, model.flap_stations.stop - model.flap_stations.start
>>> loc = {k: np.zeros((1, n_x)) for k in STATION_VARIABLES}
>>> loc |= {k: np.zeros((1, n_f)) for k in FLAP_VARIABLES}
>>> loc["ut"], loc["theta"] = model.x[None, :], np.full((1, n_x), 0.1)
>>> terms, fz = station_terms(model, loc)
>>> [t.piece for t in terms[:3]]
['airload normal force', 'airload in-plane force', 'airload pitching moment']
>>> bool((fz > 0).all())                 # nose up at zero inflow: lift everywhere
True
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .flap import flap_moments

__all__ = ["FLAP_VARIABLES", "STATION_VARIABLES", "StationTerm", "airload_terms",
           "local_variables", "station_terms"]

#: Local variables at every aerodynamic station (rotor units, derivatives in psi).
STATION_VARIABLES = ("theta", "theta_d", "theta_dd", "ut", "up", "wdd")

#: Further local variables on the flap stations (used only with the flap dof).
FLAP_VARIABLES = ("slope", "v", "dv", "vdd", "dvd", "dwd", "dl", "dld", "dldd")


def _first_order(f, df):
    """``f`` for real input; for a complex step ``z = x + i y`` (``y`` tiny) the
    first-order expansion ``f(x) + i y f'(x)`` in real arithmetic: what the
    complex function gives (its ``O(y^2)`` rest is below round-off) at a
    fraction of the cost of complex transcendental functions."""
    def apply(z):
        if not np.iscomplexobj(z):
            return f(z)
        x = z.real
        return f(x) + 1j * (z.imag * df(x))
    return apply


_sin = _first_order(np.sin, np.cos)
_cos = _first_order(np.cos, lambda x: -np.sin(x))
_arctan = _first_order(np.arctan, lambda x: 1.0 / (1.0 + x * x))
_sqrt = _first_order(np.sqrt, lambda x: 0.5 / np.sqrt(x))


class StationTerm(NamedTuple):
    """One piece of the residual acting through one field, as forces per station.

    Attributes
    ----------
    piece : str
        The named piece of the residual (:data:`tefcore.model.coupled.RESIDUAL_PIECES`).
    field : str
        ``w, dw, v, dv, phi`` (the blade rows: the force multiplies that
        field of each mode shape at the station) or ``flap`` (the flap row).
    flap_only : bool
        True: the stations are the flap stations only; False: all stations.
    force : numpy.ndarray
        ``(..., n_psi, n_stations)``, quadrature weights included.
    """

    piece: str
    field: str
    flap_only: bool
    force: np.ndarray


def local_variables(model, kin, q, qd, qdd) -> dict:
    """The local variables of :func:`station_terms` from the kinematics.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model.
    kin : dict
        :meth:`~tefcore.model.coupled.CoupledModel.kinematics` at the model's stations.
    q, qd, qdd : numpy.ndarray
        Coordinates and their psi-derivatives, ``(n_dof, n_psi)`` (the flap
        deflection is the last coordinate).

    Returns
    -------
    dict
        :data:`STATION_VARIABLES` as ``(n_psi, n_x)`` arrays and, with the
        flap, :data:`FLAP_VARIABLES` as ``(n_psi, n_flap_stations)`` arrays.
    """
    n_psi, n_x = kin["ut"].shape
    loc = {k: np.broadcast_to(kin[k], (n_psi, n_x)) for k in STATION_VARIABLES}
    if model.has_flap:
        fs, nm = model.flap_stations, model.n_modes
        n_f = fs.stop - fs.start
        loc.update({k: kin[k][:, fs] for k in ("slope", "v", "dv", "vdd", "dvd", "dwd")})
        for name, val in (("dl", q), ("dld", qd), ("dldd", qdd)):
            loc[name] = np.broadcast_to(val[nm][:, None], (n_psi, n_f))
    return loc


def station_terms(model, loc, *, flap_only: bool = False, details: bool = False,
                  aero: bool = True, combine: bool = False):
    """Station forces of the nonlinear pieces of the residual.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model.
    loc : dict
        Local variables (:func:`local_variables`), real or complex, each
        ``(..., n_psi, n_stations)``: :data:`STATION_VARIABLES` on all the
        model's stations (or on the flap stations only, ``flap_only``), and
        :data:`FLAP_VARIABLES` on the flap stations.
    flap_only : bool, optional
        Evaluate on the flap stations only.
    details : bool, optional
        Also return what the shed-wake pieces need: the section-model inputs,
        its loads and the reverse-flow sign, as a dict.
    aero : bool, optional
        False: the flap's inertial terms only (no section loads, no hinge
        moment; only with ``flap_only``): what depends on the flap variables
        but ``delta`` and its rates.
    combine : bool, optional
        Sum the pieces acting through one field on the same stations (one
        term per field, named after its first piece): for the residual as a
        whole rather than by piece.

    Returns
    -------
    terms : list of StationTerm
        The airloads (normal force on ``w``, in-plane force on ``v``, pitching
        moment on ``phi``), the flap's reactions on the blade and the flap
        equation's station terms (actuator excluded: it is linear).
    fz : numpy.ndarray
        The normal force per station, weights included (the thrust is its sum
        times ``scale["ct_sigma"]``).
    extra : dict
        Only with ``details``: ``section``, ``loads``, ``sign``, ``speed``.
    """
    if combine:
        out = station_terms(model, loc, flap_only=flap_only, details=details, aero=aero)
        return (_combined(out[0]),) + tuple(out[1:])
    cfg, sc = model.cfg, model.scale
    fs = model.flap_stations
    if not aero:
        theta = loc["theta"]
        return _flap_terms(model, {k: loc[k] for k in FLAP_VARIABLES}, theta,
                           loc["theta_dd"], loc["wdd"], 0.0, model.x[fs], model.w[fs]), None
    stations = fs if flap_only else slice(None)
    x, wq = model.x[stations], model.w[stations]
    theta, theta_d, theta_dd, ut, up, wdd = (loc[k] for k in STATION_VARIABLES)
    shape = np.broadcast_shapes(*(np.shape(loc[k]) for k in STATION_VARIABLES))
    dtype = np.result_type(*(loc[k] for k in loc))
    # flap deflection on the flap stations, zero elsewhere
    on = slice(None) if flap_only else fs           # the flap stations among these
    dl, dld, dldd = (np.zeros(shape, dtype) for _ in range(3))
    if model.has_flap:
        for arr, name in ((dl, "dl"), (dld, "dld"), (dldd, "dldd")):
            arr[..., on] = loc[name]
    sign = np.sign(np.real(ut))                     # reverse flow flips the loads
    speed = _sqrt(ut * ut + up * up)
    r = cfg.rotor
    section = dict(alpha=theta - _arctan(up / ut), alpha_rate=theta_d * sc["omega"],
                   alpha_accel=theta_dd * sc["omega"] ** 2, plunge_rate=0.0,
                   plunge_accel=wdd * sc["accel"], delta=dl, delta_rate=dld * sc["omega"],
                   delta_accel=dldd * sc["omega"] ** 2, velocity=speed * sc["speed"],
                   density=r.air_density, chord=r.chord, axis=r.elastic_axis,
                   mach=speed * (sc["speed"] / r.speed_of_sound),
                   # a NaN here surfaces in the residual, which the trim
                   # checks; the configuration is validated
                   check_finite=False)
    out = model.aero.loads(**section)
    # cos and sin of the inflow angle without trigonometry (it lies in
    # (-pi/2, pi/2), so its cosine is positive)
    cphi, sphi = ut * sign / speed, sign * up / speed
    terms, fz = airload_terms(model, out, sign, cphi, sphi, wq, "airload", flap_only)
    if model.has_flap:
        hinge = sign[..., on] * out["hinge_moment"][..., on] / sc["moment"]
        terms += _flap_terms(model, {k: loc[k] for k in FLAP_VARIABLES},
                             theta[..., on], theta_dd[..., on], wdd[..., on], hinge,
                             x[on], model.w[fs])
    if details:
        return terms, fz, {"section": section, "loads": out, "sign": sign, "speed": speed}
    return terms, fz


def _combined(terms):
    """One term per (field, stations): the sum of the pieces acting there."""
    out: dict = {}
    for t in terms:
        key = (t.field, t.flap_only)
        out[key] = t if key not in out else out[key]._replace(force=out[key].force + t.force)
    return list(out.values())


def airload_terms(model, out, sign, cphi, sphi, wq, prefix, flap_only=False):
    """Blade-row station forces of section loads ``out`` (N/m, N): normal force, in-plane
    force and pitching moment named ``{prefix} ...``; also the normal force per station.

    Parameters
    ----------
    model : tefcore.model.coupled.CoupledModel
        The model.
    out : dict
        Section loads ``lift, drag, moment`` [SI].
    sign : numpy.ndarray
        ``sign(U_T)``: the loads of a section in reverse flow change sign.
    cphi, sphi : numpy.ndarray
        Cosine and sine of the inflow angle.
    wq : numpy.ndarray
        Quadrature weights of the stations.
    prefix : str
        ``airload`` or ``shed wake``.
    flap_only : bool, optional
        The stations are the flap stations.

    Returns
    -------
    terms : list of StationTerm
    fz : numpy.ndarray
    """
    sc = model.scale
    lift = sign * out["lift"] / sc["force"]
    drag = sign * out["drag"] / sc["force"]
    moment = sign * out["moment"] / sc["moment"]
    fz = (lift * cphi - drag * sphi) * wq
    fy = -(lift * sphi + drag * cphi) * wq
    return [StationTerm(f"{prefix} normal force", "w", flap_only, -fz),
            StationTerm(f"{prefix} in-plane force", "v", flap_only, -fy),
            StationTerm(f"{prefix} pitching moment", "phi", flap_only, -(moment * wq))], fz


def _flap_terms(model, loc, th, th_dd, wdd, hinge, x, wf):
    """The flap's reactions on the blade and its own equation (docs/theory.md 4.1, 4.2),
    per flap station (:func:`tefcore.model.flap.flap_moments`), and the aerodynamic
    hinge moment on the flap row."""
    f = model.flap
    flap_row, blade = flap_moments(
        f["inertia_hinge"], f["first_moment"], f["hinge_from_ea"], x, th, th_dd, wdd,
        loc["dl"], loc["dld"], loc["dldd"], slope=loc["slope"], v=loc["v"],
        lag_slope=loc["dv"], lag_accel=loc["vdd"], lag_slope_rate=loc["dvd"],
        slope_rate=loc["dwd"], sin=_sin, cos=_cos)
    flap_row["airload hinge moment"] = -hinge
    return ([StationTerm(piece, field, True, arr * wf) for piece, field, arr in blade]
            + [StationTerm(piece, "flap", True, arr * wf) for piece, arr in flap_row.items()])
