"""The declared parameter space: the assumed MDART properties a claim can move, with ranges.

``tefcore/data/inference/mdart-space.toml`` lists every assumed property of
``mdart.toml`` the inference moves, each with the range its construction
allows and the argument for it (its ``source``); what the paper states is not
in it.  :func:`load_space` reads it into :class:`Parameter` records;
:func:`apply_sample` turns one sample (parameter name -> value) into a
configuration, refusing one that is physically impossible
(:class:`Refused`: the flap no longer fits in its section, say), and
re-fitting the torsion level to the stated frequencies when the protocol
asks (:func:`recalibrated`).

Examples
--------
>>> space = load_space()
>>> p = space["flap mass"]
>>> p.kind, p.low, p.high, p.unit
('value', 0.2, 0.55, 'lb/ft')
>>> from tefcore.config.io import load_config
>>> cfg = apply_sample(load_config("mdart"), space, {"flap mass": 0.4})
>>> round(cfg.flap.mass / load_config("mdart").flap.mass, 3)
1.333
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache

import numpy as np

from ...config.configuration import SECTIONS, resolve_field
from ...structure.section_inertia import check_section_inertia
from ...units import parse_quantity

__all__ = ["KINDS", "Parameter", "Refused", "apply_sample", "baseline_sample", "load_space",
           "recalibrated", "sample_of"]

#: How a parameter moves its field(s) (the space file's header says each).
KINDS = ("factor", "value", "shift", "outboard", "gyration", "choice")


class Refused(ValueError):
    """A sample whose configuration tefcore refuses as physically impossible."""


@dataclass(frozen=True)
class Parameter:
    """One dimension of the space.

    Parameters
    ----------
    name : str
        Its name in tables and in the study (``"flap mass"``).
    fields : tuple of str
        Dotted configuration fields it moves.
    kind : str
        One of :data:`KINDS`.
    low, high : float
        The range (in ``unit``; a factor or fraction is dimensionless).
    unit : str
        Unit of ``low``/``high`` for a ``value`` or ``shift`` (``""``: SI or
        dimensionless).
    log : bool
        Sampled on a log scale (a factor spanning a ratio).
    choices : tuple of str
        The options of a ``choice``.
    from_station : float
        An ``outboard`` factor's inner end, a fraction of R.
    keeps : str
        ``"lock_number"``: the blade's mass level follows, keeping Table 1's
        Lock number.
    group : str
        The group the sensitivity analysis moves it with.
    source : str
        The argument for the range, from construction.
    """

    name: str
    fields: tuple
    kind: str
    low: float = 0.0
    high: float = 0.0
    unit: str = ""
    log: bool = False
    choices: tuple = ()
    from_station: float = 0.0
    keeps: str = ""
    group: str = ""
    source: str = ""

    @property
    def categorical(self) -> bool:
        """True for a choice among options."""
        return self.kind == "choice"

    def si(self, value: float) -> float:
        """`value` (in :attr:`unit`) in SI (the unit read with its field's dimension)."""
        if not self.unit:
            return float(value)
        return float(parse_quantity(f"{value!r} {self.unit}", _dimension(self.fields[0])))


def _dimension(dotted: str) -> str:
    """The dimension of a configuration field (what its unit must be)."""
    section, name = resolve_field(dotted)
    return next(p.dimension for p in SECTIONS[section].PARAMS if p.name == name)


def _parameter(raw: dict, where: str) -> Parameter:
    kind = raw.get("kind")
    if kind not in KINDS:
        raise ValueError(f"{where}: kind = {kind!r} is not one of {', '.join(KINDS)}")
    p = Parameter(name=raw["name"], fields=tuple(raw["fields"]), kind=kind,
                  low=float(raw.get("low", 0.0)), high=float(raw.get("high", 0.0)),
                  unit=raw.get("unit", ""), log=bool(raw.get("log", False)),
                  choices=tuple(raw.get("choices", ())),
                  from_station=float(raw.get("from_station", 0.0)),
                  keeps=raw.get("keeps", ""), group=raw.get("group", raw["name"]),
                  source=" ".join(raw.get("source", "").split()))
    if not p.source:
        raise ValueError(f"{where} ({p.name}): no source: every range needs its argument")
    if p.categorical and len(p.choices) < 2:
        raise ValueError(f"{where} ({p.name}): a choice needs two or more choices")
    if not p.categorical and not p.low < p.high:
        raise ValueError(f"{where} ({p.name}): low = {p.low} must be below high = {p.high}")
    if p.log and p.low <= 0:
        raise ValueError(f"{where} ({p.name}): a log-scaled range needs low > 0, got {p.low}")
    return p


@cache
def load_space(name: str = "mdart-space") -> dict[str, Parameter]:
    """The parameters of a space file, by name, in file order.

    Parameters
    ----------
    name : str
        ``tefcore/data/inference/<name>.toml``, or a ``.toml`` path.

    Returns
    -------
    dict of str to Parameter

    Raises
    ------
    ValueError
        A parameter without a source, with an unknown kind, an empty range,
        or a name used twice.
    """
    from .protocol import inference_file

    data = tomllib.loads(inference_file(name))
    out: dict[str, Parameter] = {}
    for i, raw in enumerate(data["parameter"]):
        p = _parameter(raw, f"{name}.toml parameter {i + 1}")
        if p.name in out:
            raise ValueError(f"{name}.toml: parameter {p.name!r} twice")
        out[p.name] = p
    return out


def baseline_sample(cfg, space) -> dict:
    """The sample that reproduces `cfg` (the baseline: factors 1, shifts 0, its values).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline configuration (``mdart``).
    space : dict of str to Parameter
        :func:`load_space`.

    Returns
    -------
    dict
        Parameter name -> value in its own unit.
    """
    return sample_of(cfg, cfg, space)


def sample_of(cfg, base, space) -> dict:
    """The sample of the space that makes `cfg` from the baseline `base` (inverse of
    :func:`apply_sample`).

    Parameters
    ----------
    cfg, base : tefcore.config.configuration.Config
        The configuration, and the baseline the space is about.
    space : dict of str to Parameter
        :func:`load_space`.

    Returns
    -------
    dict
        Parameter name -> value in its own unit.

    Examples
    --------
    >>> from tefcore.config.io import load_config
    >>> mdart = load_config("mdart")
    >>> space = load_space()
    >>> s = sample_of(apply_sample(mdart, space, {"outboard GJ": 1.2}), mdart, space)
    >>> round(s["outboard GJ"], 6), round(s["flap mass"], 6)
    (1.2, 0.3)
    """
    out = {}
    for p in space.values():
        now, was = (np.ravel(np.asarray(c.get(p.fields[0]), dtype=object if p.categorical
                                        else float)) for c in (cfg, base))
        if p.kind == "choice":
            out[p.name] = str(now[0])
        elif p.kind == "factor":
            k = int(np.argmax(np.abs(was)))
            out[p.name] = float(now[k] / was[k])
        elif p.kind == "shift":
            out[p.name] = float((now[0] - was[0]) / p.si(1.0))
        elif p.kind == "outboard":
            st = np.asarray(base.blade.stations, float)
            r = now / was
            out[p.name] = float(r[st >= p.from_station][0] / r[st < p.from_station][0])
        elif p.kind == "gyration":
            chord = cfg.flap.reference_chord_ratio * cfg.rotor.chord
            out[p.name] = float(np.sqrt(cfg.flap.inertia_cg / cfg.flap.mass) / chord)
        else:
            out[p.name] = float(now[0] / p.si(1.0))
    return out


def _overrides(cfg, p: Parameter, value, sample_cfg) -> dict:
    """The dotted overrides of one parameter at `value` about the baseline `cfg`."""
    if p.kind == "choice":
        return {p.fields[0]: str(value)}
    if p.kind == "factor":
        return {f: (np.asarray(cfg.get(f), float) * value).tolist() if np.ndim(cfg.get(f))
                else float(cfg.get(f)) * value for f in p.fields}
    if p.kind == "shift":
        return {f: (np.asarray(cfg.get(f), float) + p.si(value)).tolist() for f in p.fields}
    if p.kind == "outboard":
        st = np.asarray(cfg.blade.stations, float)
        return {f: (np.where(st >= p.from_station, value, 1.0) * np.asarray(cfg.get(f), float))
                .tolist() for f in p.fields}
    if p.kind == "gyration":
        chord = sample_cfg.flap.reference_chord_ratio * sample_cfg.rotor.chord
        return {"flap.inertia_cg": float(sample_cfg.flap.mass * (value * chord) ** 2)}
    over = {p.fields[0]: p.si(value)}
    if p.keeps == "lock_number":
        over["blade.mass_scale"] = cfg.blade.mass_scale * p.si(value) / float(cfg.get(p.fields[0]))
    return over


def apply_sample(cfg, space, sample: dict):
    """The configuration of one sample of the space, about the baseline `cfg`.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The baseline.
    space : dict of str to Parameter
        :func:`load_space`.
    sample : dict
        Parameter name -> value (in the parameter's unit); a parameter left
        out keeps the baseline.

    Returns
    -------
    tefcore.config.configuration.Config

    Raises
    ------
    Refused
        The configuration is physically impossible: a field out of its
        allowed range, or the flap does not fit in its section
        (:func:`tefcore.structure.section_inertia.check_section_inertia`); the
        message is tefcore's.
    ValueError
        A sample naming no parameter of the space.
    """
    unknown = sorted(set(sample) - set(space))
    if unknown:
        raise ValueError(f"sample names no parameter of the space: {', '.join(unknown)}")
    over: dict = {}
    # the flap's radius of gyration reads the sampled flap mass: apply it last
    ordered = sorted(sample, key=lambda n: space[n].kind == "gyration")
    try:
        for name in ordered:
            p = space[name]
            now = cfg.with_overrides(over) if p.kind == "gyration" else cfg
            over.update(_overrides(cfg, p, sample[name], now))
        new = cfg.with_overrides(over)
        # the flap must fit in its section (the host, section less the balanced flap,
        # keeps a positive inertia about its CG; moving the flap's CG, as Figs. 9-17
        # do, moves the lumped section's CG and does not change the host)
        check_section_inertia(new)
        return new
    except ValueError as err:
        raise Refused(str(err)) from None


def recalibrated(cfg):
    """`cfg` with GJ level, horn arm and pitch-link stiffness re-fitted to the stated frequencies.

    :func:`tefcore.paper.calibration.calibrate_torsion` (least squares on the
    four first-torsion frequencies of Figs. 10a and 11a).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        A sample's configuration.

    Returns
    -------
    tefcore.config.configuration.Config
    """
    from ..calibration import calibrate_torsion

    fit = calibrate_torsion(cfg)
    return cfg.with_overrides({"blade.gj_scale": float(fit["gj_scale"]),
                               "hub.pitch_horn_arm": float(fit["pitch_horn_arm"]),
                               "hub.pitch_link_stiffness": float(fit["pitch_link_stiffness"])})
