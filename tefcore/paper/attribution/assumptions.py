"""The assumed MDART properties and their plausible ranges.

Used by :mod:`tefcore.paper.attribution.sensitivity` and the levers.

Each :class:`Assumption` names the configuration fields it changes, the low and
high ends of its range as overrides of a baseline configuration, and the
basis of that range (construction estimates, the band where soft-inplane
bearingless blades have their modes, the rounding of what the text states).
:func:`apply_assumption` applies one end, re-calibrating the first torsion
frequency to the text's four statements when the assumption moves it.

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart")
>>> heavy = apply_assumption(cfg, "flap mass", "high")
>>> round(heavy.flap.mass / cfg.flap.mass, 2)
1.25
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["ASSUMPTIONS", "Assumption", "apply_assumption", "assumption_named"]


def _times(field_name: str, factor: float) -> Callable:
    def apply(cfg):
        v = cfg.get(field_name)
        return {field_name: (np.asarray(v) * factor).tolist() if np.ndim(v) else v * factor}
    return apply


def _outboard_gj(factor: float) -> Callable:
    def apply(cfg):
        b = cfg.blade
        return {"blade.gj": np.where(np.asarray(b.stations) >= 0.5, factor, 1.0) * b.gj}
    return apply


def _section_inertia(factor: float) -> Callable:
    def apply(cfg):
        return {"blade.im_lag": cfg.blade.im_lag * factor,
                "blade.im_flap": cfg.blade.im_flap * factor}
    return apply


def _lift_slope(value: float) -> Callable:
    def apply(cfg):
        # the Lock number 9.17 is stated: a different lift slope means a blade
        # whose flapping inertia is larger by the same factor
        return {"rotor.lift_slope": value,
                "blade.mass_scale": cfg.blade.mass_scale * value / cfg.rotor.lift_slope}
    return apply


def _cg_shift(shift_in: float) -> Callable:
    def apply(cfg):
        return {"blade.cg_offset": cfg.blade.cg_offset + shift_in * 0.0254}
    return apply


def _set(field_name: str, value) -> Callable:
    return lambda cfg: {field_name: value}


@dataclass(frozen=True)
class Assumption:
    """One assumed property and the plausible range it is varied over.

    The MDART property tables are not public (Table 1 gives only rotor and
    flap data), so ``tefcore/data/mdart.toml`` assumes them; an assumption
    says how far each could plausibly be off.

    Parameters
    ----------
    name : str
        Short name used in tables and plots (``"flap mass"``), and by
        :func:`assumption_named`.
    fields : tuple of str
        Dotted configuration fields the assumption changes
        (``("flap.mass",)``).
    low, high : callable
        ``Config -> dict`` of dotted overrides giving the low and the high end
        of the range from the baseline (e.g. the flap mass times 0.75 and
        1.25); applied by :func:`apply_assumption`.
    low_label, high_label : str
        How each end is shown in the tornado table (``"x0.75"``, ``"0.23 c"``).
    basis : str
        Why the range is what it is: a construction estimate, the band where
        soft-inplane bearingless blades have their modes, the rounding of a
        value the text states.
    recalibrate : bool
        After the change, re-fit GJ scale, pitch-horn arm and pitch-link
        stiffness to the four first-torsion frequencies the text states
        (:func:`tefcore.paper.calibration.calibrate_torsion`), for
        assumptions that move them.
    """

    name: str
    fields: tuple
    low: Callable
    high: Callable
    low_label: str
    high_label: str
    basis: str
    recalibrate: bool = False


ASSUMPTIONS = (
    Assumption("flap mass", ("flap.mass",), _times("flap.mass", 0.75), _times("flap.mass", 1.25),
               "x0.75", "x1.25", "construction estimate (skins, core, fittings, balance weight) "
               "good to about a quarter; x1.25 = 0.375 lb/ft still fits in the section"),
    Assumption("flap inertia", ("flap.inertia_cg",), _times("flap.inertia_cg", 0.5),
               _times("flap.inertia_cg", 1.5), "x0.5", "x1.5",
               "radius of gyration about the hinge 0.18-0.31 c_f around the construction "
               "estimate 0.25 c_f (where the balance weight and skins sit)"),
    Assumption("section polar inertia", ("blade.im_lag", "blade.im_flap"), _section_inertia(0.9),
               _section_inertia(1.1), "x0.9", "x1.1",
               "radius of gyration 0.27-0.29 c +-5 %; torsion re-calibrated", recalibrate=True),
    Assumption("section CG", ("blade.cg_offset",), _cg_shift(-0.2), _cg_shift(0.2),
               "0.2 in aft", "0.2 in fwd", "ballast placement: section CG at the quarter chord "
               "+-2 % c"),
    Assumption("flap bending stiffness (flap modes 3-5)", ("blade.ei_flap",),
               _times("blade.ei_flap", 0.6), _times("blade.ei_flap", 1.6), "x0.6", "x1.6",
               "flap 3/4/5 at 4.46/6.75/9.68 (x0.6) to 5.03/8.06/12.3 per rev (x1.6), the band "
               "of soft-inplane hingeless and bearingless blades"),
    Assumption("lag bending stiffness (lag 2)", ("blade.ei_lag",), _times("blade.ei_lag", 0.7),
               _times("blade.ei_lag", 1.4), "x0.7", "x1.4",
               "lag 2 at 4.15 to 5.16 per rev"),
    Assumption("outboard GJ (torsion 2)", ("blade.gj",), _outboard_gj(0.7), _outboard_gj(1.4),
               "x0.7", "x1.4", "GJ outboard of 0.5 R relative to inboard; level re-calibrated, "
               "so torsion 1 stays (3.12 per rev) and torsion 2 moves (11.2 to 12.4 per rev)",
               recalibrate=True),
    Assumption("lift slope", ("rotor.lift_slope",), _lift_slope(5.5), _lift_slope(2 * math.pi),
               "5.5", "2 pi", "compressible airfoil data to thin-airfoil theory; blade mass "
               "scaled to keep the stated Lock number 9.17, torsion re-calibrated",
               recalibrate=True),
    Assumption("root flap spring", ("hub.flap_spring",), _times("hub.flap_spring", 0.5),
               _times("hub.flap_spring", 2.0), "x0.5", "x2",
               "first flap mode 1.04 to 1.06 per rev"),
    Assumption("root lag spring", ("hub.lag_spring",), _times("hub.lag_spring", 0.7),
               _times("hub.lag_spring", 1.4), "x0.7", "x1.4", "first lag mode 0.54 to 0.66 "
               "per rev (soft in-plane)"),
    Assumption("lag damper", ("hub.lag_damper",), _times("hub.lag_damper", 0.5),
               _times("hub.lag_damper", 2.0), "x0.5", "x2", "snubber placeholder (~2 % "
               "critical), halved or doubled"),
    Assumption("elastic axis", ("rotor.elastic_axis",), _set("rotor.elastic_axis", 0.23),
               _set("rotor.elastic_axis", 0.27), "0.23 c", "0.27 c",
               "quarter chord +-2 % c"),
    Assumption("modes retained", ("model.n_modes",), _set("model.n_modes", 6),
               _set("model.n_modes", 12), "6", "12",
               "the paper keeps nine coupled modes of its (unknown) blade; on this blade 6 "
               "drops flap 4, flap 5 and torsion 2 (7.3-11.8 per rev), 12 adds lag 3, flap 6 "
               "and 7"),
)


def assumption_named(name: str) -> Assumption:
    """The assumption of :data:`ASSUMPTIONS` called ``name``.

    Parameters
    ----------
    name : str
        :attr:`Assumption.name`, exactly (``"flap mass"``, ``"lift slope"``).

    Returns
    -------
    Assumption
        The assumption with that name.

    Raises
    ------
    ValueError
        No assumption has that name (the message lists the known ones).

    Examples
    --------
    >>> assumption_named("lag damper").fields
    ('hub.lag_damper',)
    """
    for a in ASSUMPTIONS:
        if a.name == name:
            return a
    known = ", ".join(a.name for a in ASSUMPTIONS)
    raise ValueError(f"unknown assumption {name!r}; known: {known}")


def apply_assumption(cfg, assumption: Assumption | str, end: str):
    """The configuration with one assumption at its ``'low'`` or ``'high'`` end.

    Re-calibrates the torsion (GJ scale, horn arm, pitch-link stiffness) when
    the assumption asks for it, so the stated first-torsion frequencies of
    Figs. 10a and 11a still hold.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        Baseline configuration (normally MDART); the end's overrides are
        computed from it.
    assumption : Assumption or str
        The assumption, or its name in :data:`ASSUMPTIONS`.
    end : {"low", "high"}
        Which end of its plausible range.

    Returns
    -------
    tefcore.config.configuration.Config
        A new configuration; ``cfg`` is unchanged.

    Raises
    ------
    ValueError
        Unknown end or assumption, or a changed configuration the data do not
        admit (e.g. a flap that no longer fits its section).
    """
    a = assumption_named(assumption) if isinstance(assumption, str) else assumption
    if end not in ("low", "high"):
        raise ValueError(f"end must be 'low' or 'high', got {end!r}")
    new = cfg.with_overrides(getattr(a, end)(cfg))
    if a.recalibrate:
        from ..calibration import calibrate_torsion

        fit = calibrate_torsion(new)
        new = new.with_overrides({"blade.gj_scale": fit["gj_scale"],
                                  "hub.pitch_horn_arm": fit["pitch_horn_arm"],
                                  "hub.pitch_link_stiffness": fit["pitch_link_stiffness"]})
    return new
