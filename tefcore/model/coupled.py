"""Coupled blade/flap/actuator equations in rotor units (docs/theory.md section 6).

Generalised coordinates: ``N`` coupled blade modes ``q_R`` and the flap
deflection ``delta`` (``q_F``).  For any azimuths and any motion
``(q, q*, q**)`` the model returns the residual of the nonlinear equations

``R = M_s q_R** + (C_s + G_s) q_R* + K_s q_R + (flap reactions) - Q_aero``
``R_F = flap inertia/centrifugal + I_a delta** + k_a (delta - delta_a) + c_a (...)* - H_aero``

(all divided by ``m0 Omega^2 R^3``).  Trim solves ``R = 0`` for a periodic
motion, and the linearised ``M, C, K`` of the paper's eq. (5) are the
derivatives of ``R`` with respect to ``q**, q*, q`` (``linearize``).

Aerodynamics: strip theory on Gauss points over three span segments (inboard
of the flap, the flap, outboard), the section model of :mod:`tefcore.aero.thin_airfoil`
(or a C81 table model) with the flap deflection on the flap segment and zero
elsewhere.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..aero.states import ShedWake, rotating_inflow_damping
from ..structure.beam_element import gauss_legendre
from ..structure.blade import blade_modes, pitch_function, rotor_units
from ..structure.section_inertia import check_coupled_mass, check_section_inertia
from .flap import flap_properties
from .station_terms import StationTerm, airload_terms, local_variables, station_terms

__all__ = ["FLAP_PIECES", "RESIDUAL_PIECES", "TRACKING_STATIONS", "Controls",
           "CoupledModel", "coupled_model", "section_model"]


def section_model(cfg):
    """The configured section aerodynamics (thin-airfoil or C81 table).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the model section (aerodynamic model, deck,
        flap model), the flap's chord and overhang and the rotor's airfoil
        coefficients.

    Returns
    -------
    tefcore.aero.thin_airfoil.ThinAirfoilFlap or tefcore.aero.c81.C81FlapTable
        With the configured flap chord and overhang (a quasi-static 20 % flap
        without overhang when the flap is not a degree of freedom).
    """
    r, f = cfg.rotor, cfg.flap
    chord_ratio = f.chord_ratio if cfg.model.tef == "dynamic" else 0.2
    overhang = f.overhang if cfg.model.tef == "dynamic" else 0.0
    if cfg.model.aero_model == "c81":
        from ..aero.c81 import C81FlapTable, read_c81

        return C81FlapTable(read_c81(cfg.model.c81_deck), chord_ratio, overhang)
    from ..aero.thin_airfoil import ThinAirfoilFlap

    return ThinAirfoilFlap(chord_ratio, overhang, cd0=r.cd0, cd1=r.cd1, cd2=r.cd2, cm0=r.cm0,
                           lift_slope=r.lift_slope)


def _gauss_segments(edges, n):
    g, w = gauss_legendre(n)
    xs, ws = [], []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        xs.append(0.5 * (a + b) + 0.5 * (b - a) * g)
        ws.append(0.5 * (b - a) * w)
    return np.concatenate(xs), np.concatenate(ws)


#: Stations of :meth:`CoupledModel.tracking_basis` (mid-points of equal spans).
TRACKING_STATIONS = 12

#: Blade fields the aerodynamics and flap equations need, in ``shape_stack`` order.
_FIELDS = ("w", "dw", "v", "dv", "phi")


@dataclass
class Controls:
    """Blade pitch controls [rad]: ``theta = theta_0 + theta_1c cos psi + theta_1s sin psi``.

    Attributes
    ----------
    collective : float
        theta_0, at 0.75 R [rad].
    cyclic_cos, cyclic_sin : float
        theta_1c and theta_1s [rad].
    """

    collective: float = 0.0
    cyclic_cos: float = 0.0
    cyclic_sin: float = 0.0

    def as_array(self):
        return np.array([self.collective, self.cyclic_cos, self.cyclic_sin])


@dataclass
class CoupledModel:
    """Blade modes + flap dof with their aerodynamic and inertial couplings.

    Build it with :func:`coupled_model`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    modes : tefcore.structure.fem.BladeModes
        The blade modes.
    n_modes : int
        Number of blade modes.
    has_flap : bool
        Whether the flap is a degree of freedom (``model.tef = "dynamic"``).
    x, w : numpy.ndarray
        Aerodynamic stations (fractions of R) and their quadrature weights.
    flap_stations : slice
        The stations on the flap span.
    shapes : dict of str to numpy.ndarray
        Mode shapes at ``x``: ``w, dw, v, dv, phi``, each ``(n_stations, n_modes)``.
    shape_stack : numpy.ndarray
        The same side by side, ``(n_modes, 5 n_stations)``.
    tip_flap : numpy.ndarray
        Flap deflection ``w(1)`` of each mode.
    twist : numpy.ndarray
        Pretwist at ``x`` relative to 0.75 R [rad].
    m_s, c_s, k_s : numpy.ndarray
        Modal mass, damping (structural plus Coriolis) and stiffness (rotor units).
    d_s, g_s : numpy.ndarray
        The structural (lag damper) and Coriolis (skew) parts of ``c_s``.
    flap : dict
        Nondimensional flap properties.
    aero : object
        The section aerodynamics (:func:`section_model`).
    scale : dict
        The reference scales of the nondimensionalisation.
    wake : tefcore.aero.states.ShedWake or None
        Shed-wake states of the aerodynamic stations (``model.aero = "unsteady"``).
    dynamic_inflow : bool
        Pitt-Peters perturbation states in the linearisation
        (``model.inflow = "dynamic"``).
    cache : dict
        Arrays derived from the model on first use (e.g. the projection maps
        of the exact Jacobian, :mod:`tefcore.model.jacobian`).
    """

    cfg: object
    modes: object
    n_modes: int
    has_flap: bool
    x: np.ndarray                 # aerodynamic stations (fractions of R)
    w: np.ndarray                 # their quadrature weights
    flap_stations: slice          # the stations on the flap span (contiguous)
    shapes: dict                  # mode shapes at x: w, dw, v, dv, phi (n_st, n_modes)
    shape_stack: np.ndarray       # the same side by side, (n_modes, 5 n_st)
    tip_flap: np.ndarray          # flap deflection w(1) of each mode
    twist: np.ndarray             # pretwist at x relative to 0.75 R [rad]
    m_s: np.ndarray
    c_s: np.ndarray               # d_s + g_s
    k_s: np.ndarray
    d_s: np.ndarray = None        # structural (lag damper) damping
    g_s: np.ndarray = None        # Coriolis (gyroscopic, skew)
    flap: dict = field(default_factory=dict)   # nondimensional flap properties
    aero: object = None
    scale: dict = field(default_factory=dict)
    wake: ShedWake | None = None  # shed-wake states (model.aero = "unsteady")
    dynamic_inflow: bool = False  # Pitt-Peters perturbation states (model.inflow = "dynamic")
    cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def flight(self):
        """The flight condition the model is for (:class:`tefcore.config.sections.FlightConfig`)."""
        return self.cfg.flight

    @property
    def hover(self) -> bool:
        """True in hover (``advance_ratio == 0``): the coefficients are constant."""
        return self.cfg.flight.advance_ratio == 0.0

    @property
    def n_dof(self) -> int:
        """Blade modes and flap: the second-order coordinates."""
        return self.n_modes + int(self.has_flap)

    @property
    def n_wake(self) -> int:
        """Shed-wake states (first-order, after the coordinates; station-major)."""
        return 0 if self.wake is None else self.wake.n_states

    @property
    def n_inflow(self) -> int:
        """Dynamic-inflow perturbation states ``nu_0, nu_R, nu_I`` (linearisation only)."""
        return 3 if self.dynamic_inflow else 0

    @property
    def state_labels(self) -> list[str]:
        """Labels of the first-order aerodynamic states, in their order."""
        n = 0 if self.wake is None else self.wake.n_per_station
        wake = [f"wake {i // n} {i % n}" for i in range(self.n_wake)]
        return wake + (["inflow 0", "inflow R", "inflow I"] if self.dynamic_inflow else [])

    @property
    def labels(self) -> list[str]:
        """Coordinate labels: ``blade flap 1`` ..., then ``TEF``."""
        out = [f"blade {lab}" for lab in self.modes.labels]
        return out + (["TEF"] if self.has_flap else [])

    def tracking_basis(self, n_stations: int = TRACKING_STATIONS) -> np.ndarray:
        """Map from coordinates to a physical shape in which modes are compared.

        Rows: the flap and lag deflections ``w, v`` and the motion of the
        section's edges by twist ``(c/2) phi`` at ``n_stations`` mid-points
        of equal spans from the structural root to the tip, each times
        ``sqrt(dx)``, then the flap's trailing-edge motion ``c_f delta``
        times ``sqrt(b_f)`` (rotor units, lengths in R).  A kinematic norm:
        it measures how far points of the blade and flap move, so a light
        flap or a low-inertia twist is not hidden by heavy bending as in an
        energy norm.  Unlike the modal coordinates, whose blade modes change
        with the configuration, this basis is the same at every point of a
        sweep of one blade, so the shapes of different points compare (MAC).

        Returns
        -------
        ndarray, shape (3 n_stations + has_flap, n_dof)
        """
        key = ("tracking_basis", n_stations)
        if key not in self.cache:
            self.cache[key] = self._tracking_basis(n_stations)
        return self.cache[key].copy()

    def _tracking_basis(self, n_stations):
        r0 = self.cfg.rotor.root_offset
        edges = np.linspace(r0, 1.0, n_stations + 1)
        x = 0.5 * (edges[1:] + edges[:-1])
        weight = np.sqrt(np.diff(edges))[:, None]
        sh = self.modes.shapes(x)
        half_chord = 0.5 * self.cfg.rotor.chord / self.cfg.rotor.radius
        blocks = [weight * sh["w"], weight * sh["v"], half_chord * weight * sh["phi"]]
        basis = np.zeros((3 * n_stations + int(self.has_flap), self.n_dof))
        basis[:3 * n_stations, :self.n_modes] = np.concatenate(blocks, axis=0)
        if self.has_flap:
            flap_chord = self.cfg.flap.chord_ratio * self.cfg.rotor.chord / self.cfg.rotor.radius
            basis[-1, -1] = flap_chord * np.sqrt(self.flap["span"])
        return basis

    def actuator_input(self, psi):
        """Actuator base angle ``delta_a(psi)`` and its psi-derivative [rad]."""
        f = self.flight
        arg = f.actuator_harmonic * psi - f.actuator_phase
        return (f.actuator_amplitude * np.cos(arg),
                -f.actuator_amplitude * f.actuator_harmonic * np.sin(arg))

    def pitch(self, psi, controls: Controls, twist=None):
        """Geometric pitch theta(x, psi) at the stations and its psi-derivatives (columns)."""
        twist = self.twist if twist is None else np.atleast_1d(twist)
        c, s = np.cos(psi)[:, None], np.sin(psi)[:, None]
        cyc = controls.cyclic_cos * c + controls.cyclic_sin * s
        cyc_d = -controls.cyclic_cos * s + controls.cyclic_sin * c
        # the rates do not depend on x: (len(psi), 1) columns that broadcast
        return controls.collective + twist[None, :] + cyc, cyc_d, -cyc

    def kinematics(self, psi, q, qd, qdd, controls: Controls, inflow, x=None,
                   inflow_perturbation=None) -> dict:
        """Section motion and velocities at azimuths ``psi`` and stations ``x``.

        Blade fields and their psi-derivatives, the section pitch
        ``Theta = theta + phi`` and rates, and (units of Omega R)
        ``U_T = x + mu sin psi + v*``, ``U_P = lambda + w* + mu (w' + beta_p) cos psi``,
        the inflow angle ``arctan(U_P/U_T)`` (kept in (-pi/2, pi/2) for
        reverse flow) and the speed. Arrays are (len(psi), len(x)); ``x``
        defaults to the model's aerodynamic stations.  ``inflow_perturbation``
        (len(psi), len(x)) is added to ``lambda`` (the dynamic-inflow states).
        """
        if x is None:
            x, stack, twist = self.x, self.shape_stack, None
        else:
            x = np.atleast_1d(np.asarray(x, float))
            full = self.modes.shapes(x)
            stack = np.concatenate([full[f] for f in _FIELDS], axis=0).T
            twist = np.interp(x, self.x, self.twist)
        nm = self.n_modes
        psi = np.asarray(psi, float)
        # every field of q, q* and q** at every station: three products
        # with the stacked shapes (n_modes, 5 n_x), then views per field
        n_x = x.size
        k = {}
        for suffix, a in (("", q), ("d", qd), ("dd", qdd)):
            vals = a[:nm].T @ stack
            for i, f in enumerate(_FIELDS):
                k[f + suffix] = vals[:, i * n_x:(i + 1) * n_x]
        ph, phd, phdd = k.pop("phi"), k.pop("phid"), k.pop("phidd")
        theta, theta_d, theta_dd = self.pitch(psi, controls, twist)
        k["theta"], k["theta_d"], k["theta_dd"] = theta + ph, theta_d + phd, theta_dd + phdd
        mu = self.flight.advance_ratio
        k["slope"] = k["dw"] + self.cfg.rotor.precone
        k["ut"] = x[None, :] + mu * np.sin(psi)[:, None] + k["vd"]
        k["up"] = (inflow(x[None, :], psi[:, None]) + k["wd"]
                   + mu * k["slope"] * np.cos(psi)[:, None])
        if inflow_perturbation is not None:
            k["up"] = k["up"] + inflow_perturbation
        k["inflow_angle"] = np.arctan(k["up"] / k["ut"])
        k["speed"] = np.hypot(k["ut"], k["up"])
        # cos and sin of the inflow angle without trigonometry (it lies in
        # (-pi/2, pi/2), so its cosine is positive)
        k["cos_inflow"] = np.abs(k["ut"]) / k["speed"]
        k["sin_inflow"] = np.sign(k["ut"]) * k["up"] / k["speed"]
        return k

    def evaluate(self, psi, q, qd, qdd, controls: Controls, inflow):
        """Residual and section loads for motions at azimuths ``psi``.

        Parameters
        ----------
        psi : ndarray, shape (n,)
        q, qd, qdd : ndarray, shape (n_dof, n)
            Coordinates and their psi-derivatives.
        controls : Controls
        inflow : callable
            ``inflow(x, psi)`` inflow ratio (down positive).

        Returns
        -------
        residual : ndarray, shape (n_dof, n)
        thrust : ndarray, shape (n,)
            Blade vertical force per azimuth, as C_T/sigma contribution
            (its azimuthal mean is the rotor C_T/sigma).
        """
        if q.shape[0] != self.n_dof:
            pieces, thrust = self.residual_pieces(psi, q, qd, qdd, controls, inflow)
            return sum(pieces.values()), thrust
        # no aerodynamic states: the station forces summed per field, projected once
        psi = np.asarray(psi, float)
        kin = self.kinematics(psi, q, qd, qdd, controls, inflow)
        terms, fz = station_terms(self, local_variables(self, kin, q, qd, qdd), combine=True)
        nm = self.n_modes
        res = np.zeros((self.n_dof, psi.size))
        res[:nm] = self.m_s @ qdd[:nm] + self.k_s @ q[:nm] + self.c_s @ qd[:nm]
        if self.has_flap:
            da, da_d = self.actuator_input(psi)
            res[nm] = (self.flap["k_a"] * (q[nm] - da) + self.flap["c_a"] * (qd[nm] - da_d)
                       + self.flap["reflected_inertia"] * qdd[nm])
        pieces = {"all": res}
        for t in terms:
            self._project(pieces, [t._replace(piece="all")], self.n_dof, psi.size)
        thrust = fz.sum(axis=1) * self.scale["ct_sigma"]
        if self.dynamic_inflow:
            thrust = np.stack([thrust, (fz * self.x[None, :]).sum(axis=1)
                               * self.scale["ct_sigma"]])
        return res, thrust

    def residual_pieces(self, psi, q, qd, qdd, controls: Controls, inflow):
        """The residual as named physical pieces that add up to it (docs/theory.md 6.1).

        Same arguments as :meth:`evaluate`. Returns ``(pieces, thrust)`` with
        ``pieces`` a dict :data:`RESIDUAL_PIECES` -> ``(n_dof, n)`` array
        (rows: blade modes, then the flap equation); their sum is the
        residual of :meth:`evaluate`.  The mechanism diagnostics
        (:mod:`tefcore.linear.mechanism`) differentiate each piece separately.

        Aerodynamic states (docs/theory.md 6.2): with shed-wake states the
        rows of ``q`` after the ``n_dof`` coordinates are the wake states
        (``qd`` their rates; ``qdd`` is not read there), then, in a
        linearisation with an :class:`~tefcore.aero.states.InflowLinearization`,
        the three dynamic-inflow perturbations.  The pieces then have a row per
        coordinate and state: the quasi-steady airloads at the instantaneous
        angle of attack, the ``shed wake ...`` pieces (the change of the loads
        by the wake's downwash ``lambda_0``), and the state equations
        (``shed wake dynamics``, ``inflow dynamics``, ``inflow forcing``).
        With dynamic inflow ``thrust`` has two rows: the blade's ``C_T/sigma``
        and its first moment (stations weighted by ``x``).
        """
        cfg = self.cfg
        psi = np.asarray(psi, float)
        nd, n_rows = self.n_dof, q.shape[0]
        states = wake = nu = None
        if n_rows != nd:
            if n_rows not in (nd + self.n_wake, nd + self.n_wake + self.n_inflow):
                raise ValueError(f"{n_rows} rows of coordinates and states; this model has "
                                 f"{nd} coordinates, {self.n_wake} wake and {self.n_inflow} "
                                 "inflow states")
            states, rates = q[nd:], qd[nd:]
            q, qd, qdd = q[:nd], qd[:nd], qdd[:nd]
            if self.n_wake:
                wake = (self.wake.split(states[:self.n_wake]),
                        self.wake.split(rates[:self.n_wake]))
            if states.shape[0] > self.n_wake:
                nu = (states[self.n_wake:], rates[self.n_wake:])
        elif self.n_wake:
            raise ValueError(f"this model has {self.n_wake} shed-wake states: pass them after "
                             f"the {nd} coordinates")
        kin = self.kinematics(psi, q, qd, qdd, controls, inflow, inflow_perturbation=(
            None if nu is None else nu[0][0][:, None] + self.x[None, :] * nu[0][1][:, None]))
        n_psi = psi.size
        loc = local_variables(self, kin, q, qd, qdd)
        terms, fz, det = station_terms(self, loc, details=True)
        pieces = self.assemble(psi, q, qd, qdd, terms, n_rows, wake=wake is not None,
                               inflow_states=nu is not None)
        if wake is not None:
            # the wake's downwash lowers the angle of attack of the static loads
            section, out, sign, speed = (det[k] for k in ("section", "loads", "sign", "speed"))
            upwash = self.wake.airfoil.upwash(
                alpha=section["alpha"], alpha_rate=section["alpha_rate"], plunge_rate=0.0,
                delta=section["delta"], delta_rate=section["delta_rate"],
                velocity=section["velocity"], chord=cfg.rotor.chord,
                axis=cfg.rotor.elastic_axis) / self.scale["speed"]
            lam0 = self.wake.induced(upwash, wake[0])
            lagged = self.aero.loads(**{**section, "alpha": section["alpha"]
                                        - np.arctan(lam0 / speed)})
            change = {k: lagged[k] - out[k] for k in out}
            shed, fz_shed = airload_terms(self, change, sign, kin["cos_inflow"],
                                          kin["sin_inflow"], self.w, "shed wake")
            fz = fz + fz_shed
            if self.has_flap:
                fs = self.flap_stations
                shed.append(StationTerm("shed wake hinge moment", "flap", True, -(
                    sign[:, fs] * change["hinge_moment"][:, fs] / self.scale["moment"]
                    * self.w[fs])))
            self._project(pieces, shed, n_rows, n_psi)
            pieces["shed wake dynamics"][nd:nd + self.n_wake] = self.wake.join(
                self.wake.residual(wake[0], wake[1], upwash, speed))
        thrust = fz.sum(axis=1) * self.scale["ct_sigma"]
        if self.dynamic_inflow:
            moment = (fz * self.x[None, :]).sum(axis=1) * self.scale["ct_sigma"]
            if nu is not None:
                pieces.update(self._inflow_rows(psi, nu, thrust, moment, inflow, n_rows))
            thrust = np.stack([thrust, moment])
        return pieces, thrust

    def assemble(self, psi, q, qd, qdd, terms, n_rows=None, *, wake=False,
                 inflow_states=False):
        """The pieces of the residual from the station forces of its nonlinear part.

        The terms linear in the coordinates (blade structure, actuator) and the
        station forces (:func:`tefcore.model.station_terms.station_terms`) projected on
        the mode shapes, as the named pieces of :meth:`residual_pieces` (the
        shed-wake and inflow pieces zero: :meth:`residual_pieces` fills them).

        Parameters
        ----------
        psi : numpy.ndarray
            Azimuths [rad].
        q, qd, qdd : numpy.ndarray
            The coordinates (``n_dof`` rows) and their psi-derivatives.
        terms : list of tefcore.model.station_terms.StationTerm
            Real station forces at the same motion.
        n_rows : int, optional
            Rows of the residual (coordinates and states; default ``n_dof``).
        wake, inflow_states : bool, optional
            Include the (zero) shed-wake and inflow pieces.

        Returns
        -------
        dict
            Piece name -> ``(n_rows, n_psi)``, in the order of :data:`RESIDUAL_PIECES`.
        """
        nm, n_psi = self.n_modes, np.size(psi)
        n_rows = self.n_dof if n_rows is None else n_rows
        qb, qbd, qbdd = q[:nm], qd[:nm], qdd[:nm]
        names = [p for p in RESIDUAL_PIECES if (self.has_flap or p not in FLAP_PIECES)
                 and (wake or p not in WAKE_PIECES)
                 and (inflow_states or p not in INFLOW_PIECES)
                 and (self.has_flap or p != "shed wake hinge moment")]
        pieces = {p: np.zeros((n_rows, n_psi)) for p in names}
        pieces["blade inertia"][:nm] = self.m_s @ qbdd
        pieces["blade stiffness"][:nm] = self.k_s @ qb
        pieces["blade structural damping"][:nm] = self.d_s @ qbd
        pieces["blade Coriolis"][:nm] = self.g_s @ qbd
        if self.has_flap:
            da, da_d = self.actuator_input(psi)
            # the actuator's moving parts turn with the flap (docs/theory.md 4.1)
            pieces["flap inertia"][nm] = self.flap["reflected_inertia"] * qdd[nm]
            pieces["actuator spring"][nm] = self.flap["k_a"] * (q[nm] - da)
            pieces["actuator damper"][nm] = self.flap["c_a"] * (qd[nm] - da_d)
        self._project(pieces, terms, n_rows, n_psi)
        return pieces

    def _project(self, pieces, terms, n_rows, n_psi):
        """Add station forces (:func:`tefcore.model.station_terms.station_terms`) to the
        pieces: on the blade rows through the mode shapes, summed on the flap row."""
        fs, nm = self.flap_stations, self.n_modes
        for t in terms:
            if t.piece not in pieces:
                pieces[t.piece] = np.zeros((n_rows, n_psi))
            if t.field == "flap":
                pieces[t.piece][nm] += t.force.sum(axis=-1)
            else:
                shape = self.shapes[t.field][fs] if t.flap_only else self.shapes[t.field]
                pieces[t.piece][:nm] += (t.force @ shape).T

    def _inflow_rows(self, psi, nu, thrust, moment, inflow, n_rows):
        """Pieces of the dynamic-inflow perturbation equations (docs/theory.md 6.2)."""
        lin = getattr(inflow, "perturbation", None)
        if lin is None:
            raise ValueError("dynamic-inflow states need the inflow's perturbation equations "
                             "(tefcore.aero.states.InflowLinearization)")
        (state, rate), first = nu, n_rows - 3
        damping = rotating_inflow_damping(lin, psi)
        dyn, force = np.zeros((2, n_rows, psi.size))
        dyn[first:] = lin.mass @ rate + np.einsum("pij,jp->ip", damping, state)
        force[first] = -inflow.solidity * thrust
        force[first + 1] = -inflow.solidity * moment
        return {"inflow dynamics": dyn, "inflow forcing": force}



#: Pieces of the flap's own equation and of its reactions on the blade.
FLAP_PIECES = ("flap inertia", "flap inertial coupling to bending",
               "flap inertial coupling to torsion", "flap centrifugal", "flap Coriolis",
               "airload hinge moment", "actuator spring", "actuator damper")
#: Every piece of :meth:`CoupledModel.residual_pieces`, in its order.
#: Pieces of the shed wake (model.aero = "unsteady"): the change of the loads by
#: the wake's downwash, and the wake states' own equations.
WAKE_PIECES = ("shed wake normal force", "shed wake in-plane force",
               "shed wake pitching moment", "shed wake hinge moment", "shed wake dynamics")
#: Pieces of the dynamic-inflow perturbation equations (linearisation only).
INFLOW_PIECES = ("inflow dynamics", "inflow forcing")
RESIDUAL_PIECES = ("blade inertia", "blade stiffness", "blade structural damping",
                   "blade Coriolis", "airload normal force", "airload in-plane force",
                   "airload pitching moment") + FLAP_PIECES + WAKE_PIECES + INFLOW_PIECES


def coupled_model(cfg, collective: float = 0.0, modes=None) -> CoupledModel:
    """Build the coupled model of a configuration.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration (blade modes, flap, actuator, aerodynamics,
        flight condition and model choices).
    collective : float
        Pitch at 0.75 R [rad] at which the blade modes are computed (the
        structural flap-lag coupling depends on it).
    modes : BladeModes, optional
        Precomputed modes (else computed here).

    Returns
    -------
    CoupledModel

    Raises
    ------
    ValueError
        If the flap does not fit in its blade section
        (:func:`tefcore.structure.section_inertia.check_section_inertia`).
    """
    # the flap inside its section (also checked by blade_model; the blade modes
    # are cached by structure, and the flap's CG offset is not part of it)
    check_section_inertia(cfg)
    units = rotor_units(cfg.rotor, cfg.blade)
    modes = modes or blade_modes(cfg, collective=collective)
    r, fl = cfg.rotor, cfg.flap
    has_flap = cfg.model.tef == "dynamic"
    x_in, x_out = fl.midspan - fl.span / 2, fl.midspan + fl.span / 2
    edges = [r.root_cutout, x_in, x_out, 1.0]
    x, w = _gauss_segments(edges, cfg.model.n_gauss)
    n = cfg.model.n_gauss
    s = modes.shapes(np.append(x, 1.0))          # the stations and the tip
    shapes = {k: s[k][:-1] for k in ("w", "dw", "v", "dv", "phi")}
    twist = pitch_function(cfg.blade, 0.0)(x)
    om, rad, m0 = units.rotor_speed, units.radius, units.mass_per_length
    scale = {"omega": om, "speed": om * rad, "accel": om**2 * rad,
             "force": m0 * om**2 * rad, "moment": m0 * om**2 * rad**2,
             "ct_sigma": m0 / (r.air_density * r.chord * rad)}
    n_m = len(modes.frequencies)
    flap = {}
    if has_flap:
        fp = flap_properties(cfg)
        flap = {"inertia_hinge": fp.inertia_hinge / (m0 * rad**2),
                "first_moment": fp.first_moment / (m0 * rad),
                "hinge_from_ea": fp.hinge_from_ea / rad, "span": fl.span,
                "k_a": units.spring(fp.k_a), "c_a": units.damper(fp.c_a),
                "reflected_inertia": units.inertia(fp.reflected_inertia)}
    aero = section_model(cfg)
    wake = None
    if cfg.model.aero == "unsteady":
        from ..aero.unsteady import UnsteadyFlapAirfoil

        wake = ShedWake(UnsteadyFlapAirfoil(aero.chord_ratio, aero.overhang,
                                            n_states=cfg.model.wake_states,
                                            wake=cfg.model.wake, static_model=aero),
                        radius_over_semichord=2 * rad / r.chord, n_stations=x.size)
    model = CoupledModel(cfg=cfg, modes=modes, n_modes=n_m, has_flap=has_flap, x=x, w=w,
                         flap_stations=slice(n, 2 * n),
                         shape_stack=np.concatenate([shapes[f] for f in _FIELDS], axis=0).T,
                         tip_flap=s["w"][-1], shapes=shapes, twist=twist,
                         m_s=modes.modal_mass,
                         c_s=modes.modal_damping + modes.modal_gyroscopic,
                         k_s=modes.modal_stiffness, d_s=modes.modal_damping,
                         g_s=modes.modal_gyroscopic, flap=flap, aero=aero, scale=scale,
                         wake=wake, dynamic_inflow=cfg.model.inflow == "dynamic")
    check_coupled_mass(model)       # blade modes + flap: positive definite (docs/theory.md 2.7)
    return model
