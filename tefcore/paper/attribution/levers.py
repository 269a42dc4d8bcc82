"""What the attribution moves: assumptions and model options, each within its plausible range.

A :class:`Lever` is one thing that could explain a disagreement with the
paper, with the range over which it is plausible:

* every assumption of notebook 08 (:data:`tefcore.paper.attribution.assumptions.ASSUMPTIONS`),
  *continuous*: moved a fraction ``t`` of the way from the baseline to the
  low (``t < 0``) or the high end (``t > 0``) of its range, each field
  interpolated linearly and the torsion re-calibrated where the assumption
  asks for it; an integer field (``model.n_modes``) is *discrete*: each
  value of its range is tried;
* the Fig. 6 flap-system inertia (:func:`fig6_lever`), the one hook for the
  flap-system calibration to Fig. 6: ``actuator.reflected_inertia`` from 0
  to the ``mdart-fig6`` value;
* the model options of :data:`MODEL_OPTIONS` (unsteady aerodynamics, dynamic
  inflow, the multiple-load-path hub, the XFOIL C81 deck), discrete.

A new assumption is one entry: an :class:`~tefcore.paper.attribution.assumptions.Assumption`
in ``ASSUMPTIONS`` or a :class:`ModelOption` in :data:`MODEL_OPTIONS`.
:func:`placement_levers` finds, by their effect on the blade's modes, the
levers that place blade flap 4, flap 5 and torsion 2 (paired with the Fig. 6
calibration by :func:`pair_lever`).

Examples
--------
>>> from tefcore.config.io import load_config
>>> cfg = load_config("mdart")
>>> mass = next(lv for lv in levers(cfg) if lv.name == "flap mass")
>>> mass.setting, mass.low, mass.base, mass.high
('factor on flap.mass', 0.75, 1.0, 1.25)
>>> round(mass.value(0.4), 3), round(mass.move(cfg, 0.4).flap.mass / cfg.flap.mass, 3)
(1.1, 1.1)
>>> [lv.name for lv in levers(cfg) if lv.discrete]  # doctest: +NORMALIZE_WHITESPACE
['modes retained', 'unsteady aerodynamics', 'dynamic inflow', 'multiple-load-path hub',
 'XFOIL C81 deck']
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ...config.configuration import SECTIONS, resolve_field
from .assumptions import ASSUMPTIONS, Assumption

__all__ = ["FIG6_CONFIG", "FIG6_FIELD", "FIG6_NAME", "Lever", "MODEL_OPTIONS",
           "ModelOption", "PLACEMENT_MODES", "PLACEMENT_SHIFT", "assumption_lever",
           "fig6_lever", "levers", "option_lever", "pair_lever",
           "placement_levers"]

#: The field of the flap system's reflected actuator inertia (the Fig. 6 calibration).
FIG6_FIELD = "actuator.reflected_inertia"
#: The packaged configuration whose ``FIG6_FIELD`` reproduces Fig. 6: the top of its range.
FIG6_CONFIG = "mdart-fig6"
#: Name of the Fig. 6 flap-system inertia lever in tables and the report.
FIG6_NAME = "Fig. 6 flap-system inertia"
#: Blade modes whose placement the paired levers move (:func:`placement_levers`).
PLACEMENT_MODES = ("flap 4", "flap 5", "torsion 2")
#: Least relative shift of one of :data:`PLACEMENT_MODES` at an end of a lever's range
#: for it to count as placing them: the flap-bending and outboard-GJ assumptions move
#: them by 5-14 %, every other assumption of notebook 08 by at most 2.3 % (lift slope).
PLACEMENT_SHIFT = 0.04


@dataclass(frozen=True)
class Lever:
    """One assumption or model option, and its plausible range.

    Parameters
    ----------
    name : str
        Name in the attribution table (an assumption's own name).
    setting : str
        What its numbers are (``"factor on flap.mass"``, ``"model.n_modes"``).
    base, low, high : float or str
        The baseline setting and the ends of the plausible range.
    move : callable
        ``(cfg, where) -> Config``: ``where`` is the fraction ``t`` of the
        way to the high (``t > 0``) or low (``t < 0``) end for a continuous
        lever (beyond the range for ``|t| > 1``), an option for a discrete one.
    options : tuple
        A discrete lever's settings to try (nearest the baseline first);
        empty for a continuous lever.
    basis : str
        Why the range is what it is.
    note : str
        What the reader must know (e.g. a field it cannot move).
    cost : float
        Relative cost of a point with the lever moved (scheduling only).
    """

    name: str
    setting: str
    base: object
    low: object
    high: object
    move: Callable = field(repr=False, compare=False)
    options: tuple = ()
    basis: str = ""
    note: str = ""
    cost: float = 1.0

    @property
    def discrete(self) -> bool:
        """True when the lever has options to try instead of a range to bisect."""
        return bool(self.options)

    def value(self, t: float) -> float:
        """The setting a fraction ``t`` of the way to an end (``t < 0``: the low end).

        Parameters
        ----------
        t : float
            Signed fraction of the way from the baseline; ``|t| > 1`` is beyond.
        """
        end = self.high if t > 0 else self.low
        return float(self.base + abs(t) * (end - self.base))

    def fraction(self, setting: float) -> float:
        """Inverse of :meth:`value`: the signed fraction at which the lever has `setting`.

        Parameters
        ----------
        setting : float
            A setting on either side of the baseline.
        """
        end = self.high if setting >= self.base else self.low
        return float(np.sign(setting - self.base) * (setting - self.base) / (end - self.base))


def _lerp(base, end, s: float):
    b, e = np.asarray(base, float), np.asarray(end, float)
    v = b + s * (e - b)
    return v.tolist() if v.ndim else float(v)


def _interpolating(assumption: Assumption) -> Callable:
    def move(cfg, t):
        if t == 0:
            return cfg
        end = (assumption.high if t > 0 else assumption.low)(cfg)
        new = cfg.with_overrides({k: _lerp(cfg.get(k), v, abs(t)) for k, v in end.items()})
        if not assumption.recalibrate:
            return new
        from ..calibration import calibrate_torsion

        fit = calibrate_torsion(new)
        return new.with_overrides({"blade.gj_scale": fit["gj_scale"],
                                   "hub.pitch_horn_arm": fit["pitch_horn_arm"],
                                   "hub.pitch_link_stiffness": fit["pitch_link_stiffness"]})
    return move


def _coordinate(cfg, a: Assumption) -> tuple[str, float, float, float]:
    """(setting, base, low, high) of an assumption, in the terms of its labels.

    A factor when its labels are factors (``"x0.75"``); otherwise the value of a
    scalar field, or the shift of an array field where it moves most.
    """
    key = a.fields[0]
    base = np.asarray(cfg.get(key), float)
    lo, hi = (np.asarray(end(cfg)[key], float) for end in (a.low, a.high))
    i = int(np.argmax(np.abs(np.ravel(hi - base)))) if base.ndim else ()
    b, lo, hi = (np.ravel(v)[i] if base.ndim else float(v) for v in (base, lo, hi))
    if a.low_label.startswith("x") and a.high_label.startswith("x") and b:
        return f"factor on {key}", 1.0, float(lo / b), float(hi / b)
    if base.ndim == 0:
        return key, float(b), float(lo), float(hi)
    return f"shift of {key} [SI]", 0.0, float(lo - b), float(hi - b)


def assumption_lever(cfg, a: Assumption) -> Lever:
    """The lever of one assumption of notebook 08, about the configuration `cfg`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline the range is taken about.
    a : tefcore.paper.attribution.assumptions.Assumption
        The assumption; an integer field makes a discrete lever (every
        value between its ends), any other a continuous one.

    Returns
    -------
    Lever
    """
    section, name = resolve_field(a.fields[0])
    kind = next(p.kind for p in SECTIONS[section].PARAMS if p.name == name)
    if kind == "int":
        base, lo, hi = (int(v) for v in (cfg.get(a.fields[0]), a.low(cfg)[a.fields[0]],
                                          a.high(cfg)[a.fields[0]]))
        opts = sorted((n for n in range(lo, hi + 1) if n != base),
                      key=lambda n: (abs(n - base), n))
        return Lever(a.name, a.fields[0], base, lo, hi,
                     lambda c, n, key=a.fields[0]: c.with_overrides({key: int(n)}),
                     tuple(opts), a.basis)
    setting, base, lo, hi = _coordinate(cfg, a)
    return Lever(a.name, setting, base, lo, hi, _interpolating(a), basis=a.basis)


@dataclass(frozen=True)
class ModelOption:
    """A model option the paper's analysis may differ in, tried switched on.

    Parameters
    ----------
    name : str
        Name in the attribution table.
    overrides : callable
        ``() -> dict`` of dotted fields that switch it on.
    basis : str
        Why it is a plausible difference from the paper's analysis.
    cost : float
        Relative cost of a point with it (scheduling only).
    """

    name: str
    overrides: Callable
    basis: str
    cost: float = 1.0


def _xfoil():
    from ...aero.c81 import xfoil_deck_path

    return {"model.aero_model": "c81", "model.c81_deck": str(xfoil_deck_path())}


#: The model options tried switched on, one entry each.
MODEL_OPTIONS = (
    ModelOption("unsteady aerodynamics", lambda: {"model.aero": "unsteady"},
                "the paper's UMARC airloads are quasi-steady; the shed wake adds the lift "
                "deficiency C(k) (reduced frequency ~0.3 at the flap)", 6.0),
    ModelOption("dynamic inflow", lambda: {"model.inflow": "dynamic"},
                "Pitt-Peters inflow states in the stability analysis instead of a frozen "
                "inflow", 1.0),
    ModelOption("multiple-load-path hub", lambda: {"hub.model": "multiple_load_path"},
                "the bearingless hub's flexbeam, torque tube, pitch link and snubber instead "
                "of equivalent root springs, calibrated to the same frequencies", 1.5),
    ModelOption("XFOIL C81 deck", _xfoil, "a viscous NACA 0012 flapped-airfoil table (XFOIL) "
                "instead of thin-airfoil theory; the paper uses test-based tables", 5.0),
)


def option_lever(cfg, option: ModelOption) -> Lever | None:
    """The discrete lever of a model option; None when `cfg` already has it.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline.
    option : ModelOption
        The option.

    Returns
    -------
    Lever or None
    """
    over = option.overrides()
    key, on = next(iter(over.items()))
    if all(cfg.get(k) == v for k, v in over.items()):
        return None
    shown = on if key != "model.aero_model" else f"c81 deck {str(over['model.c81_deck'])}"
    shown = shown.rsplit("/", 1)[-1]
    return Lever(option.name, key, str(cfg.get(key)), str(cfg.get(key)), shown,
                 lambda c, _, over=over: c.with_overrides(over), (shown,), option.basis,
                 cost=option.cost)


def _field_lever(name, key, base, low, high, factor: bool, basis, note) -> Lever:
    """A continuous lever moving one scalar field (a factor on its baseline, or its value)."""
    def move(cfg, t, key=key):
        v = (1.0 + abs(t) * ((high if t > 0 else low) - 1.0)) * cfg.get(key) if factor \
            else base + abs(t) * ((high if t > 0 else low) - base)
        return cfg if t == 0 else cfg.with_overrides({key: float(v)})
    return Lever(name, f"factor on {key}" if factor else key, base, low, high, move,
                 basis=basis, note=note)


def fig6_lever(cfg) -> Lever:
    """The Fig. 6 flap-system inertia: the reflected actuator inertia, from none to its calibration.

    :data:`FIG6_FIELD` from 0 to its value in the packaged :data:`FIG6_CONFIG`
    (the calibration to Fig. 6's 15 %).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline.

    Returns
    -------
    Lever
    """
    from ...config.io import load_config

    top = float(load_config(FIG6_CONFIG).get(FIG6_FIELD))
    return _field_lever(FIG6_NAME, FIG6_FIELD, float(cfg.get(FIG6_FIELD)), 0.0, top, False,
                        f"the actuator's moving parts reflected through the linkage: from "
                        f"none to the {FIG6_CONFIG} calibration to Fig. 6", "")


def levers(cfg, assumptions=ASSUMPTIONS, options=MODEL_OPTIONS) -> list[Lever]:
    """Every lever of the attribution about `cfg`: assumptions, the Fig. 6 hook, options.

    An assumption that changes :data:`FIG6_FIELD` is replaced by :func:`fig6_lever`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline.
    assumptions : sequence of Assumption
        Default: notebook 08's.
    options : sequence of ModelOption
        Default: :data:`MODEL_OPTIONS`.

    Returns
    -------
    list of Lever
        The assumptions in their order, then the Fig. 6 inertia, then the
        model options (those `cfg` does not already have).
    """
    out = [assumption_lever(cfg, a) for a in assumptions if FIG6_FIELD not in a.fields]
    out.append(fig6_lever(cfg))
    out += [lv for lv in (option_lever(cfg, o) for o in options) if lv is not None]
    return out


def placement_levers(cfg, candidates) -> list[Lever]:
    """The continuous levers that move blade flap 4, flap 5 or torsion 2.

    A lever places them when one of :data:`PLACEMENT_MODES` moves by at least
    :data:`PLACEMENT_SHIFT` (relative) at an end of its range
    (:func:`tefcore.structure.blade.blade_modes`, in vacuum, twelve modes so
    that none of them drops out of the set).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline.
    candidates : sequence of Lever
        The levers to look at (the Fig. 6 lever is never one).

    Returns
    -------
    list of Lever
        Empty when no assumption places those modes: the pairs then cannot be tried.
    """
    from ...structure.blade import blade_modes

    def freqs(c):
        m = blade_modes(c, n_modes=12)
        return {lab: f for lab, f in zip(m.labels, m.frequencies, strict=True)
                if lab in PLACEMENT_MODES}

    base, out = freqs(cfg), []
    for lv in candidates:
        if lv.discrete or lv.name == FIG6_NAME:
            continue
        for t in (-1.0, 1.0):
            try:
                moved = freqs(lv.move(cfg, t))
            except ValueError:
                continue
            if any(abs(moved.get(k, f) / f - 1) >= PLACEMENT_SHIFT for k, f in base.items()):
                out.append(lv)
                break
    return out


def pair_lever(anchor: Lever, at: float, partner: Lever) -> Lever:
    """`partner` moved with `anchor` held at the setting `at` (e.g. the Fig. 6 calibration).

    Parameters
    ----------
    anchor : Lever
        A continuous lever, held fixed.
    at : float
        Its setting (in ``anchor.setting`` terms).
    partner : Lever
        The continuous lever moved; the pair's settings and range are its.

    Returns
    -------
    Lever
        Named ``"<anchor> at <at> + <partner>"``.
    """
    t_anchor = anchor.fraction(at)

    def move(cfg, t):
        return partner.move(anchor.move(cfg, t_anchor), t)

    return Lever(f"{anchor.name} at {at:.3g} + {partner.name}", partner.setting, partner.base,
                 partner.low, partner.high, move, basis=partner.basis,
                 note="; ".join(n for n in (anchor.note, partner.note) if n),
                 cost=anchor.cost * partner.cost)
