"""The configured blade: finite-element model, modes and fan plot.

This module turns a :class:`tefcore.config.configuration.Config` into the rotor-unit
finite-element beam of :mod:`tefcore.structure.fem` and its coupled modes.  The
collective pitch is the geometric pitch at 0.75 R; the built-in twist is
added relative to its value there.  The hub is ``hub.model``: equivalent root
springs (docs/theory.md section 2.5) or the branched flexbeam / torque tube /
pitch link / snubber model (section 2.5a, :func:`multiple_load_path_model`).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Mapping

import numpy as np

from ..config.configuration import SECTIONS
from ..config.sections import mode_family_counts
from ..runtime import blas_limit
from .branched import BranchedBeam, Component, Coupling, Joint, assemble_branched
from .fem import (
    BeamModel,
    BladeModes,
    RootSprings,
    assemble_beam,
    beam_modes,
    tension_piecewise_linear,
)
from .scaling import RotorUnits
from .section_inertia import check_positive_definite, check_section_inertia, lumped_section

__all__ = ["MODES_CACHE_SIZE", "NON_STRUCTURAL", "blade_model", "blade_modes", "element_nodes",
           "fan_data", "fan_plot", "hub_beam_section", "multiple_load_path_model",
           "pitch_function", "root_springs", "rotor_units", "section_function",
           "structural_key"]

#: Section arrays and how each is made nondimensional.
_SECTION_SCALES = {
    "mass": "mass_per_len", "ei_flap": "bending_stiffness", "ei_lag": "bending_stiffness",
    "gj": "bending_stiffness", "ea": "axial_stiffness", "im_flap": "inertia_per_length",
    "im_lag": "inertia_per_length", "cg_offset": "length", "tension_offset": "length",
    "ka": "length",
}


def rotor_units(rotor, blade) -> RotorUnits:
    """Reference scales of a rotor and its blade (R, Omega, m0 = 3 I_b / R^3).

    Parameters
    ----------
    rotor : tefcore.config.sections.RotorConfig
        The rotor section (radius, rotor speed).
    blade : tefcore.config.sections.BladeConfig
        The blade section (its flapping inertia gives m0).

    Returns
    -------
    tefcore.structure.scaling.RotorUnits

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> units = rotor_units(cfg.rotor, cfg.blade)
    >>> units.radius == cfg.rotor.radius
    True
    """
    return RotorUnits(radius=rotor.radius, rotor_speed=rotor.rotor_speed,
                      mass_per_length=blade.reference_mass())


def section_function(cfg, units: RotorUnits | None = None):
    """Nondimensional section properties of the configured blade, ``f(x)``.

    The tables with the flap's CG offset lumped in over the flap span
    (:func:`tefcore.structure.section_inertia.lumped_section`).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade tables, the flap lumped into them
        and the rotor's chord and elastic axis that place it.
    units : tefcore.structure.scaling.RotorUnits, optional
        Reference scales (default :func:`rotor_units` of the rotor and blade).

    Returns
    -------
    callable
        ``f(x)``: the nondimensional section properties at stations ``x``.
    """
    units = units or rotor_units(cfg.rotor, cfg.blade)

    def section(x):
        p = lumped_section(cfg, np.clip(x, cfg.blade.stations[0], 1.0))
        return {k: getattr(units, how)(np.asarray(p[k], float))
                for k, how in _SECTION_SCALES.items()}
    return section


def pitch_function(blade, collective: float = 0.0):
    """Geometric pitch ``theta(x) = theta_75 + twist(x) - twist(0.75)`` [rad].

    Parameters
    ----------
    blade : tefcore.config.sections.BladeConfig
        The blade section (its stations and built-in twist).
    collective : float, optional
        theta_75 [rad].

    Returns
    -------
    callable
        ``theta(x)`` for stations ``x`` (fractions of R).
    """
    stations = np.asarray(blade.stations, float)
    twist = np.asarray(blade.twist, float)
    t75 = np.interp(0.75, stations, twist)
    return lambda x: collective + np.interp(x, stations, twist) - t75


def root_springs(hub, units: RotorUnits) -> RootSprings:
    """Equivalent bearingless-hub root restraints in rotor units.

    The torsion spring is the pitch link (stiffness times horn arm squared)
    plus any flexbeam torsion in parallel; the blade's own GJ sits in series
    with it through the finite elements.

    Parameters
    ----------
    hub : tefcore.config.sections.HubConfig
        The hub section (its springs, pitch link and lag damper).
    units : tefcore.structure.scaling.RotorUnits
        Reference scales (:func:`rotor_units`).

    Returns
    -------
    tefcore.structure.fem.RootSprings
    """
    return RootSprings(flap=units.spring(hub.flap_spring), lag=units.spring(hub.lag_spring),
                       torsion=units.spring(hub.pitch_link_torsion_stiffness
                                            + hub.torsion_spring_parallel),
                       lag_damper=units.damper(hub.lag_damper))


def blade_model(cfg, collective: float = 0.0,
                n_elements: int | None = None) -> BeamModel | BranchedBeam:
    """Assemble the finite-element blade of a configuration.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade is built from its rotor, blade,
        hub (and hub component), flap and model sections.
    collective : float
        Geometric pitch at 0.75 R [rad]; it rotates the section principal
        axes and so couples flap and lag bending.
    n_elements : int, optional
        Equal-length elements from the structural root to the tip
        (default ``cfg.model.n_elements``); with the multiple-load-path hub,
        flexbeam plus torque tube plus main blade.

    Returns
    -------
    BeamModel or tefcore.structure.branched.BranchedBeam
        A single beam on equivalent root springs (``hub.model =
        "equivalent"``) or the branched hub and blade
        (:func:`multiple_load_path_model`).

    Raises
    ------
    ValueError
        If a section, or the flap in its section, is not physical
        (:func:`tefcore.structure.section_inertia.check_section_inertia`).
    """
    check_section_inertia(cfg)
    if cfg.hub.model == "multiple_load_path":
        return multiple_load_path_model(cfg, collective, n_elements)
    n = n_elements or cfg.model.n_elements
    x_nodes = element_nodes(cfg.flap, n, cfg.rotor.root_offset)
    units = rotor_units(cfg.rotor, cfg.blade)
    section = section_function(cfg, units)
    # the section mass is linear between the blade stations: exact tension
    stations = np.asarray(cfg.blade.stations, float)
    tension = tension_piecewise_linear(stations, section(stations)["mass"])
    beam = assemble_beam(x_nodes, section, pitch_function(cfg.blade, collective),
                         root_springs(cfg.hub, units), tension=tension)
    # positive definite by construction when the sections pass
    # check_section_inertia (0.1 ms: a Cholesky of the ~180 free dofs)
    f = beam.free
    check_positive_definite(beam.mass[f][:, f], "the assembled blade mass matrix",
                            "blade.mass, blade.im_lag, blade.im_flap, blade.cg_offset and the "
                            "flap lumped into them (flap.mass, flap.inertia_cg, flap.cg_offset)")
    return beam


def hub_beam_section(sec, units: RotorUnits, ka: float = 0.0):
    """Nondimensional uniform section ``f(x)`` of a hub beam (flexbeam or torque tube).

    Elastic axis, CG and tension axis coincide.

    Parameters
    ----------
    sec : tefcore.config.hub.FlexbeamConfig or tefcore.config.hub.TorqueTubeConfig
        The beam's uniform properties (SI).
    units : RotorUnits
        Conversion to rotor units (:func:`rotor_units`).
    ka : float
        Polar radius of gyration of the tension [m] (tension-torsion stiffening).

    Returns
    -------
    callable
        ``section(x) -> dict`` of nondimensional properties, constant along x.
    """
    props = {"mass": units.mass_per_len(sec.mass), "ei_flap": units.bending_stiffness(sec.ei_flap),
             "ei_lag": units.bending_stiffness(sec.ei_lag),
             "gj": units.bending_stiffness(sec.gj), "ea": units.axial_stiffness(sec.ea),
             "im_flap": units.inertia_per_length(sec.im_flap),
             "im_lag": units.inertia_per_length(sec.im_lag), "cg_offset": 0.0,
             "tension_offset": 0.0, "ka": units.length(ka)}

    def section(x):
        x = np.asarray(x, float)
        return {k: np.full(x.shape, v) for k, v in props.items()}
    return section


def multiple_load_path_model(cfg, collective: float = 0.0, n_elements: int | None = None, *,
                             torque_tube: bool = True,
                             root: RootSprings | None = None) -> BranchedBeam:
    """The bearingless hub as flexbeam, torque tube, pitch link and snubber (docs 2.5a).

    Flexbeam (``flexbeam.n_elements``, clamped at ``rotor.root_offset``),
    torque tube (``torque_tube.n_elements`` from ``torque_tube.inboard``) and
    main blade (the rest of ``n_elements``, from the clevis to the tip, with
    nodes on the flap edges) are 15-dof beams joined at ``flexbeam.clevis``
    (:class:`tefcore.structure.branched.Joint`).  The pitch link is a spring
    ``hub.pitch_link_stiffness`` on the motion of the horn point along the
    link, the snubber springs on the relative flap, lag and pitch motion of
    torque tube and flexbeam at ``torque_tube.inboard``, with the damper of
    its complex stiffness in lag (the chordwise spring/damper).  The blade's
    centrifugal force goes through the flexbeam; the torque tube, held at
    the clevis only, carries its own in compression.  The
    flexbeam winds up elastically from ``flexbeam.precollective`` at the hub
    to the blade pitch at the clevis; the torque tube is at the clevis pitch.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the hub sections ``flexbeam``,
        ``torque_tube``, ``pitch_link`` and ``snubber`` with ``hub``,
        ``rotor``, ``blade``, ``flap`` and ``model``.
    collective : float
        Geometric pitch at 0.75 R [rad].
    n_elements : int, optional
        Flexbeam plus torque tube plus main-blade elements
        (default ``cfg.model.n_elements``).
    torque_tube : bool
        ``False``: the single-load-path limit -- no torque tube, no snubber;
        the pitch link acts on the flexbeam at the hub (with ``root`` given,
        not at all: its stiffness is then in ``root.torsion``).
    root : RootSprings, optional
        Springs at the flexbeam's root instead of the clamp (``u, v, w``
        stay fixed), as :func:`tefcore.structure.fem.assemble_beam` has them.
        With ``torque_tube=False`` and :func:`root_springs` this is the
        equivalent hub on a blade whose inboard part is the flexbeam
        (tests/structure/test_hub.py).

    Returns
    -------
    tefcore.structure.branched.BranchedBeam
        ``evaluate`` reads the main blade outboard of the clevis and the
        flexbeam inboard of it.
    """
    fb, tt, pl, sn = cfg.flexbeam, cfg.torque_tube, cfg.pitch_link, cfg.snubber
    n_hub = fb.n_elements + (tt.n_elements if torque_tube else 0)
    n_blade = (n_elements or cfg.model.n_elements) - n_hub
    if n_blade < 2:
        raise ValueError(f"n_elements = {n_elements or cfg.model.n_elements} leaves {n_blade} "
                         "main-blade element(s) after the flexbeam and torque tube; at least 2")
    units = rotor_units(cfg.rotor, cfg.blade)
    r0, xc = cfg.rotor.root_offset, fb.clevis
    xt = tt.inboard if torque_tube else r0
    blade_section = section_function(cfg, units)
    stations = np.asarray(cfg.blade.stations, float)
    blade_tension = tension_piecewise_linear(stations, blade_section(stations)["mass"])
    m_f, m_t = units.mass_per_len(fb.mass), units.mass_per_len(tt.mass)
    tube_force = 0.5 * m_t * (xc**2 - xt**2) if torque_tube else 0.0   # per Omega^2
    clevis_tension = float(blade_tension(xc)) + tube_force
    blade_pitch = pitch_function(cfg.blade, collective)
    theta_c = float(blade_pitch(xc))
    # uniform GJ: the elastic wind-up of the flexbeam is linear in x
    wind = (theta_c - fb.precollective) / (xc - r0)
    components = [
        Component("flexbeam", np.linspace(r0, xc, fb.n_elements + 1),
                  hub_beam_section(fb, units, fb.ka),
                  lambda x: fb.precollective + wind * (np.asarray(x, float) - r0),
                  lambda x: clevis_tension + 0.5 * m_f * (xc**2 - np.asarray(x, float) ** 2)),
        Component("blade", element_nodes(cfg.flap, n_blade, xc), blade_section, blade_pitch,
                  blade_tension),
    ]
    joints = [Joint("flexbeam", fb.n_elements, "blade", 0)]
    rad2 = units.radius**2
    couplings, clamps, root_fixed = [], [("flexbeam", 0)], []
    if root is not None:            # as assemble_beam: u, v, w fixed, an infinite spring clamps
        clamps, root_fixed = [], [0, 1, 3]
        for f, dof, k, c in (("dv", 2, root.lag, root.lag_damper), ("dw", 4, root.flap, 0.0),
                             ("phi", 5, root.torsion, 0.0)):
            if np.isinf(k):
                root_fixed.append(dof)
            else:
                couplings.append(Coupling(f"root {f}", (("flexbeam", r0, f, 1.0),), k, c))
    horn = "torque_tube" if torque_tube else "flexbeam"
    if torque_tube:
        components.insert(1, Component(
            "torque_tube", np.linspace(xt, xc, tt.n_elements + 1), hub_beam_section(tt, units),
            lambda x: np.full(np.shape(x), theta_c),
            lambda x: -0.5 * m_t * (np.asarray(x, float) ** 2 - xt**2)))
        joints.insert(0, Joint("flexbeam", fb.n_elements, "torque_tube", tt.n_elements))

        def snubber(name, fieldname, k_storage, scale, loss=0.0):
            c = loss * k_storage / sn.reference_frequency   # equal loss per cycle there
            return Coupling(f"snubber {name}", (("torque_tube", xt, fieldname, 1.0),
                                                ("flexbeam", xt, fieldname, -1.0)),
                            units.spring(k_storage * scale), units.damper(c * scale))

        # the damper is the chordwise restraint's; in flap and pitch the
        # elastomer centres (a viscous equivalent fixed at the lag frequency
        # would overstate its damping of the faster flap and torsion modes by
        # their frequency ratio, x5 for torsion 1)
        couplings += [snubber("flap", "w", sn.flap_stiffness, rad2),
                      snubber("lag", "v", sn.lag_stiffness, rad2, sn.loss_factor),
                      snubber("torsion", "phi", sn.torsion_stiffness, 1.0)]
    if torque_tube or root is None:
        # the horn point moves by (u - a v', v + d v', w + d w' + a phi); the
        # link (unit vector (0, sin cant, cos cant)) stretches by its
        # component along it
        a, d = units.length(pl.horn_arm), units.length(pl.radial_offset)
        ny, nz = np.sin(pl.cant), np.cos(pl.cant)
        link = tuple((horn, xt, f, c) for f, c in
                     (("w", nz), ("dw", nz * d), ("phi", nz * a), ("v", ny), ("dv", ny * d)))
        couplings.append(Coupling("pitch link", link,
                                  units.spring(cfg.hub.pitch_link_stiffness * rad2)))
    beam = assemble_branched(components, joints, couplings, clamps=clamps,
                             span=("blade", "flexbeam"), pitch=blade_pitch)
    beam.free = np.setdiff1d(beam.free, beam.index["flexbeam"][root_fixed])
    f = beam.free
    check_positive_definite(beam.mass[f][:, f], "the assembled hub and blade mass matrix",
                            "flexbeam.mass, flexbeam.im_flap, flexbeam.im_lag, "
                            "torque_tube.mass, torque_tube.im_flap, torque_tube.im_lag, and the "
                            "blade tables with the flap lumped in")
    return beam


def element_nodes(flap, n: int, start: float) -> np.ndarray:
    """``n`` elements from ``start`` to the tip, with nodes on the flap edges.

    Equal elements, except that the free interior node nearest each flap edge
    is moved onto it: the flap's CG-offset share is a step in the section
    properties at the edges, which the element quadrature integrates exactly
    only there, and the modes then vary smoothly as Figs. 13-14 move the edges.
    An edge on the root or tip is already a node; a move that would leave an
    element shorter than 5 % of the others (two edges within one element) is
    not made, and the step then lies inside that element.

    Parameters
    ----------
    flap : tefcore.config.sections.FlapConfig
        The flap section (its inboard and outboard edges).
    n : int
        Number of elements.
    start : float
        Inboard end [fraction of R]: ``rotor.root_offset`` for the blade on
        root springs, the clevis for the main blade of the
        multiple-load-path hub.

    Returns
    -------
    numpy.ndarray
        The ``n + 1`` node stations, fractions of R, from ``start`` to 1.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> nodes = element_nodes(cfg.flap, 20, cfg.rotor.root_offset)
    >>> on = [bool(np.isclose(nodes, e).any()) for e in (cfg.flap.inboard, cfg.flap.outboard)]
    >>> on
    [True, True]
    """
    nodes = np.linspace(start, 1.0, n + 1)
    h = (1.0 - start) / n
    moved: set[int] = set()
    for edge in (flap.inboard, flap.outboard):
        free = [i for i in range(1, n) if i not in moved]
        if not free or np.min(np.abs(nodes - edge)) < 1e-12:
            continue
        i = min(free, key=lambda j: abs(nodes[j] - edge))
        trial = nodes.copy()
        trial[i] = edge
        if np.min(np.diff(trial)) > 0.05 * h:
            nodes, moved = trial, moved | {i}
    return nodes


#: Configuration sections and fields that do not reach the blade's structure:
#: the flight condition, the actuator (its spring acts between flap and blade,
#: not in the blade's matrices) and the aerodynamic and solver choices of the
#: model section.  :func:`structural_key` leaves them out.
NON_STRUCTURAL = ("flight", "actuator", "model.aero_model", "model.c81_deck", "model.inflow",
                  "model.aero", "model.wake", "model.wake_states", "model.n_azimuth",
                  "model.n_floquet_steps", "model.n_gauss")

#: Blade modes kept by :func:`blade_modes` (least recently used dropped first):
#: a sweep or map over a non-structural field reuses one set.
MODES_CACHE_SIZE = 16

_MODES_CACHE: OrderedDict = OrderedDict()


def _hashable(value):
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, (list, tuple)):
        return tuple(_hashable(v) for v in value)
    if isinstance(value, Mapping):
        return tuple(sorted((k, _hashable(v)) for k, v in value.items()))
    return value


def structural_key(cfg) -> tuple:
    """The part of a configuration that the blade's modes depend on, as a hashable key.

    Every field of every section except :data:`NON_STRUCTURAL`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration (every section, the structural fields of each).

    Returns
    -------
    tuple
        Equal for two configurations whose blade structures are the same.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> cfg = load_config("mdart")
    >>> structural_key(cfg) == structural_key(cfg.with_overrides({"flight.advance_ratio": 0.3}))
    True
    >>> structural_key(cfg) == structural_key(cfg.with_overrides({"flap.cg_offset": 0.3}))
    False
    """
    out = []
    for name, cls in SECTIONS.items():
        if name in NON_STRUCTURAL:
            continue
        section = getattr(cfg, name)
        out.append((name, tuple((p.name, _hashable(getattr(section, p.name)))
                                for p in cls.PARAMS if f"{name}.{p.name}" not in NON_STRUCTURAL)))
    return tuple(out)


@blas_limit()
def blade_modes(cfg, n_modes: int | None = None, collective: float = 0.0,
                speed_ratio: float = 1.0, n_elements: int | None = None) -> BladeModes:
    """Coupled natural modes of the configured blade.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade is built from its rotor, blade,
        hub, flap and model sections (:func:`blade_model`).
    n_modes : int, optional
        Modes kept (default ``cfg.model.n_modes``).
    collective : float
        Pitch at 0.75 R [rad].
    speed_ratio : float
        Rotor speed over the configured one; frequencies are per rev of it.
    n_elements : int, optional
        Finite elements (default ``cfg.model.n_elements``).

    Returns
    -------
    BladeModes

    Examples
    --------
    The MDART blade: a soft-inplane bearingless rotor, its first lag mode
    below 1/rev and the first flap mode just above it.

    >>> from tefcore.config.io import load_config
    >>> modes = blade_modes(load_config("mdart"))
    >>> f = dict(zip(modes.labels, modes.frequencies))
    >>> bool(f["lag 1"] < 1.0 < f["flap 1"] < 1.2)
    True
    """
    families = mode_family_counts(cfg.model.mode_families) if n_modes is None else {}
    key = (structural_key(cfg), n_modes or cfg.model.n_modes, tuple(families.items()),
           float(collective), float(speed_ratio), n_elements or cfg.model.n_elements)
    modes = _MODES_CACHE.get(key)
    if modes is None:
        beam = blade_model(cfg, collective, n_elements)
        modes = beam_modes(beam, n_modes or cfg.model.n_modes, speed_ratio, families)
        _MODES_CACHE[key] = modes
        while len(_MODES_CACHE) > MODES_CACHE_SIZE:
            _MODES_CACHE.popitem(last=False)
    else:
        _MODES_CACHE.move_to_end(key)
    return modes


def fan_data(cfg, speed_ratios, n_modes: int | None = None,
             collective: float = 0.0):
    """Frequencies of the labelled modes versus rotor speed (tidy table).

    The beam is assembled once; only the stiffness is re-scaled with speed.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade is built from its rotor, blade,
        hub, flap and model sections (:func:`blade_model`).
    speed_ratios : array_like
        Rotor speeds, fractions of the configured one.
    n_modes : int, optional
        Modes kept (default ``cfg.model.n_modes``).
    collective : float, optional
        Pitch at 0.75 R [rad].

    Returns
    -------
    pandas.DataFrame
        Columns ``speed_ratio, rotor_speed_rpm, mode, label, family,
        frequency_per_rev, frequency_hz``.
    """
    beam = blade_model(cfg, collective)
    n = n_modes or cfg.model.n_modes
    rows = []
    for r in np.atleast_1d(speed_ratios):
        if not r > 0:
            raise ValueError(f"speed ratio must be positive, got {r}")
        m = beam_modes(beam, n, r)
        omega = cfg.rotor.rotor_speed * r
        for j, (lab, f) in enumerate(zip(m.labels, m.frequencies, strict=False)):
            rows.append({"speed_ratio": float(r), "rotor_speed_rpm": omega * 30 / np.pi,
                         "mode": j + 1, "label": lab, "family": m.families[j],
                         "frequency_per_rev": float(f),
                         "frequency_hz": float(f * omega / (2 * np.pi))})
    import pandas as pd  # only where the table is built

    return pd.DataFrame(rows)


def fan_plot(cfg, speed_ratios=None, n_modes: int | None = None, ax=None):
    """Fan plot: modal frequencies [Hz] versus rotor speed, with per-rev rays.

    The nominal rotor speed is marked.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The whole configuration: the blade is built from its rotor, blade,
        hub, flap and model sections (:func:`blade_model`).
    speed_ratios : array_like, optional
        Rotor speeds, fractions of the configured one (default 0.2 to 1.2).
    n_modes : int, optional
        Modes kept (default ``cfg.model.n_modes``).
    ax : matplotlib.axes.Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    import matplotlib.pyplot as plt

    if speed_ratios is None:
        speed_ratios = np.linspace(0.2, 1.2, 26)
    df = fan_data(cfg, speed_ratios, n_modes)
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 5))
    styles = {"flap": "-", "lag": "--", "torsion": "-.", "axial": ":"}
    for lab, g in df.groupby("label", sort=False):
        ax.plot(g["rotor_speed_rpm"], g["frequency_hz"], styles[g["family"].iloc[0]], label=lab)
    rpm = np.array([0.0, df["rotor_speed_rpm"].max()])
    for k in range(1, 9):
        ax.plot(rpm, k * rpm / 60, color="0.8", lw=0.7, zorder=0)
    nominal = cfg.rotor.rotor_speed * 30 / np.pi
    ax.axvline(nominal, color="0.5", lw=0.8)
    ax.set_xlabel("rotor speed [RPM]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_xlim(0, rpm[1])
    ax.set_ylim(0, df["frequency_hz"].max() * 1.05)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return ax
