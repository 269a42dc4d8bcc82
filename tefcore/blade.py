"""The configured blade: finite-element model, modes and fan plot.

This module turns a :class:`tefcore.config.Config` into the rotor-unit
finite-element beam of :mod:`tefcore.structure` and its coupled modes.  The
collective pitch is the geometric pitch at 0.75 R; the built-in twist is
added relative to its value there.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .runtime import blas_limit
from .scaling import RotorUnits
from .section_inertia import check_positive_definite, lumped_section
from .structure import (
    BeamModel,
    BladeModes,
    RootSprings,
    assemble_beam,
    beam_modes,
    tension_piecewise_linear,
)

__all__ = ["blade_model", "blade_modes", "element_nodes", "fan_data", "fan_plot",
           "pitch_function", "root_springs", "rotor_units", "section_function"]

#: Section arrays and how each is made nondimensional.
_SECTION_SCALES = {
    "mass": "mass_per_len", "ei_flap": "bending_stiffness", "ei_lag": "bending_stiffness",
    "gj": "bending_stiffness", "ea": "axial_stiffness", "im_flap": "inertia_per_length",
    "im_lag": "inertia_per_length", "cg_offset": "length", "tension_offset": "length",
    "ka": "length",
}


def rotor_units(cfg) -> RotorUnits:
    """Reference scales of a configuration (R, Omega, m0 = 3 I_b / R^3).

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.

    Returns
    -------
    tefcore.scaling.RotorUnits
    """
    return RotorUnits(radius=cfg.rotor.radius, rotor_speed=cfg.rotor.rotor_speed,
                      mass_per_length=cfg.blade.reference_mass())


def section_function(cfg, units: RotorUnits | None = None):
    """Nondimensional section properties of the configured blade, ``f(x)``.

    The tables with the flap's CG offset lumped in over the flap span
    (:func:`tefcore.section_inertia.lumped_section`).

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    units : tefcore.scaling.RotorUnits, optional
        Reference scales (default :func:`rotor_units` of ``cfg``).

    Returns
    -------
    callable
        ``f(x)``: the nondimensional section properties at stations ``x``.
    """
    units = units or rotor_units(cfg)

    def section(x):
        p = lumped_section(cfg, np.clip(x, cfg.blade.stations[0], 1.0))
        return {k: getattr(units, how)(np.asarray(p[k], float))
                for k, how in _SECTION_SCALES.items()}
    return section


def pitch_function(cfg, collective: float = 0.0):
    """Geometric pitch ``theta(x) = theta_75 + twist(x) - twist(0.75)`` [rad].

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    collective : float, optional
        theta_75 [rad].

    Returns
    -------
    callable
        ``theta(x)`` for stations ``x`` (fractions of R).
    """
    stations = np.asarray(cfg.blade.stations, float)
    twist = np.asarray(cfg.blade.twist, float)
    t75 = np.interp(0.75, stations, twist)
    return lambda x: collective + np.interp(x, stations, twist) - t75


def root_springs(cfg, units: RotorUnits | None = None) -> RootSprings:
    """Equivalent bearingless-hub root restraints in rotor units.

    The torsion spring is the pitch link (stiffness times horn arm squared)
    plus any flexbeam torsion in parallel; the blade's own GJ sits in series
    with it through the finite elements.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    units : tefcore.scaling.RotorUnits, optional
        Reference scales (default :func:`rotor_units` of ``cfg``).

    Returns
    -------
    tefcore.structure.RootSprings
    """
    units, hub = units or rotor_units(cfg), cfg.hub
    return RootSprings(flap=units.spring(hub.flap_spring), lag=units.spring(hub.lag_spring),
                       torsion=units.spring(hub.pitch_link_torsion_stiffness
                                            + hub.torsion_spring_parallel),
                       lag_damper=units.damper(hub.lag_damper))


def blade_model(cfg, collective: float = 0.0, n_elements: int | None = None) -> BeamModel:
    """Assemble the finite-element blade of a configuration.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    collective : float
        Geometric pitch at 0.75 R [rad]; it rotates the section principal
        axes and so couples flap and lag bending.
    n_elements : int, optional
        Equal-length elements from the structural root to the tip
        (default ``cfg.model.n_elements``).

    Returns
    -------
    BeamModel
    """
    n = n_elements or cfg.model.n_elements
    x_nodes = element_nodes(cfg, n)
    units = rotor_units(cfg)
    section = section_function(cfg, units)
    # the section mass is linear between the blade stations: exact tension
    stations = np.asarray(cfg.blade.stations, float)
    tension = tension_piecewise_linear(stations, section(stations)["mass"])
    beam = assemble_beam(x_nodes, section, pitch_function(cfg, collective),
                         root_springs(cfg, units), tension=tension)
    # positive definite by construction when the sections pass
    # check_section_inertia (0.1 ms: a Cholesky of the ~180 free dofs)
    f = beam.free
    check_positive_definite(beam.mass[f][:, f], "the assembled blade mass matrix",
                            "blade.mass, blade.im_lag, blade.im_flap, blade.cg_offset and the "
                            "flap lumped into them (flap.mass, flap.inertia_cg, flap.cg_offset)")
    return beam


def element_nodes(cfg, n: int) -> np.ndarray:
    """``n`` elements from the structural root to the tip, with nodes on the flap edges.

    Equal elements, except that the free interior node nearest each flap edge
    is moved onto it: the flap's CG-offset share is a step in the section
    properties at the edges, which the element quadrature integrates exactly
    only there, and the modes then vary smoothly as Figs. 13-14 move the edges.
    An edge on the root or tip is already a node; a move that would leave an
    element shorter than 5 % of the others (two edges within one element) is
    not made, and the step then lies inside that element.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    n : int
        Number of elements.

    Returns
    -------
    numpy.ndarray
        The ``n + 1`` node stations, fractions of R, from
        ``rotor.root_offset`` to 1.

    Examples
    --------
    >>> from tefcore.config_io import load_config
    >>> cfg = load_config("mdart")
    >>> nodes = element_nodes(cfg, 20)
    >>> on = [bool(np.isclose(nodes, e).any()) for e in (cfg.flap.inboard, cfg.flap.outboard)]
    >>> on
    [True, True]
    """
    x0 = cfg.rotor.root_offset
    nodes = np.linspace(x0, 1.0, n + 1)
    h = (1.0 - x0) / n
    moved: set[int] = set()
    for edge in (cfg.flap.inboard, cfg.flap.outboard):
        free = [i for i in range(1, n) if i not in moved]
        if not free or np.min(np.abs(nodes - edge)) < 1e-12:
            continue
        i = min(free, key=lambda j: abs(nodes[j] - edge))
        trial = nodes.copy()
        trial[i] = edge
        if np.min(np.diff(trial)) > 0.05 * h:
            nodes, moved = trial, moved | {i}
    return nodes


@blas_limit()
def blade_modes(cfg, n_modes: int | None = None, collective: float = 0.0,
                speed_ratio: float = 1.0, n_elements: int | None = None) -> BladeModes:
    """Coupled natural modes of the configured blade.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
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

    >>> from tefcore.config_io import load_config
    >>> modes = blade_modes(load_config("mdart"))
    >>> f = dict(zip(modes.labels, modes.frequencies))
    >>> bool(f["lag 1"] < 1.0 < f["flap 1"] < 1.2)
    True
    """
    beam = blade_model(cfg, collective, n_elements)
    return beam_modes(beam, n_modes or cfg.model.n_modes, speed_ratio)


def fan_data(cfg, speed_ratios, n_modes: int | None = None,
             collective: float = 0.0) -> pd.DataFrame:
    """Frequencies of the labelled modes versus rotor speed (tidy table).

    The beam is assembled once; only the stiffness is re-scaled with speed.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
    speed_ratios : array_like
        Rotor speeds, fractions of the configured one.
    n_modes : int, optional
        Modes kept (default ``cfg.model.n_modes``).
    collective : float, optional
        Pitch at 0.75 R [rad].

    Returns
    -------
    pandas.DataFrame
        Columns ``speed_ratio, rotor_speed_rpm, mode, label,
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
                         "mode": j + 1, "label": lab, "frequency_per_rev": float(f),
                         "frequency_hz": float(f * omega / (2 * np.pi))})
    return pd.DataFrame(rows)


def fan_plot(cfg, speed_ratios=None, n_modes: int | None = None, ax=None):
    """Fan plot: modal frequencies [Hz] versus rotor speed, with per-rev rays.

    The nominal rotor speed is marked.

    Parameters
    ----------
    cfg : tefcore.config.Config
        The rotor configuration.
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
        ax.plot(g["rotor_speed_rpm"], g["frequency_hz"], styles[lab.split()[0]], label=lab)
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
