"""Running a paper figure the way the notebooks do: configuration, values, sweep.

:func:`run_config` is the configuration a notebook analyses for a figure (the
MDART baseline, the figure's caption, then the user's overrides);
the notebooks' sweeps are ``tefcore.sweep(cfg, field, values,
point=quiet_stability)`` over the values of
:func:`tefcore.paper.claims.validation.figure_values`, with numerical warnings counted, not printed
(:func:`quiet_stability`); :func:`natural_frequencies` gives the blade
frequencies of the "blade frequency" panels.

Examples
--------
>>> run_config("fig9", overrides={"flight.advance_ratio": 0.2}).flight.advance_ratio
0.2
"""

from __future__ import annotations

import warnings
from types import SimpleNamespace

import numpy as np
import pandas as pd

from ...aero.c81 import example_deck_path, xfoil_deck_path
from ...config.io import load_config
from .catalogue import FIGURES, figure_config
from .plotting import x_values

__all__ = ["AERO_MODELS", "base_config", "natural_frequencies", "quiet_stability", "run_config",
           "section_aero"]

#: Section aerodynamics a notebook can choose (``aero_model`` parameter).
AERO_MODELS = ("thin_airfoil", "table", "xfoil")


def base_config(aero_model: str = "thin_airfoil", overrides: dict | None = None,
                config=None):
    """The base configuration (MDART, or a TOML file) with the chosen section aerodynamics.

    Parameters
    ----------
    aero_model : {"thin_airfoil", "table", "xfoil"}
        Thin-airfoil theory; the C81 look-up with the shipped *generated*
        example deck (thin-airfoil theory tabulated; ``"c81"`` is accepted for
        ``"table"``); or the C81 look-up with the shipped XFOIL deck (NACA 0012
        with the MDART balanced flap, viscous: a real flapped-airfoil table).
        Unsteadiness is ``model.aero`` in ``overrides``
        (``{"model.aero": "unsteady"}``), with any of the three.
    overrides : dict, optional
        Dotted configuration fields applied last.
    config : path or str, optional
        A configuration file (TOML, :mod:`tefcore.config.io`: a complete
        rotor, e.g. a copy of ``tefcore/data/mdart.toml`` with other values)
        or the name of a shipped one; None: the shipped MDART configuration.
        The notebooks' ``config`` parameter (``tefcore batch`` sets it).

    Returns
    -------
    tefcore.config.configuration.Config
        The base configuration with the section aerodynamics set, then
        ``overrides``.
    """
    cfg = load_config("mdart" if config is None else config)
    if aero_model in ("table", "c81"):
        cfg = cfg.with_overrides({"model.aero_model": "c81",
                                  "model.c81_deck": str(example_deck_path())})
    elif aero_model == "xfoil":
        cfg = cfg.with_overrides({"model.aero_model": "c81",
                                  "model.c81_deck": str(xfoil_deck_path())})
    elif aero_model != "thin_airfoil":
        raise ValueError(f"aero_model = {aero_model!r}: expected one of "
                          f"{', '.join(AERO_MODELS)}")
    return cfg.with_overrides(overrides) if overrides else cfg


def run_config(name: str, base=None, overrides: dict | None = None):
    """The configuration a figure is computed with: base, the caption, then ``overrides``.

    Parameters
    ----------
    name : str
        Paper figure (``"fig9"``).
    base : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    overrides : dict, optional
        Dotted fields that win over the caption (e.g. another advance ratio).
    """
    cfg = figure_config(name, base)
    return cfg.with_overrides(overrides) if overrides else cfg


def section_aero(aero_model: str, cfg=None):
    """Section model of Fig. 5's hinge moment with the flap geometry of ``cfg``.

    Parameters
    ----------
    aero_model : {"thin_airfoil", "table"}
        See :func:`base_config`.
    cfg : tefcore.config.configuration.Config, optional
        Source of ``flap.chord_ratio`` and ``flap.overhang``.
    """
    from ...model.coupled import section_model

    cfg = base_config(aero_model) if cfg is None else cfg
    return section_model(base_config(aero_model).with_overrides({
        "flap.chord_ratio": cfg.flap.chord_ratio, "flap.overhang": cfg.flap.overhang}))


def quiet_stability(cfg):
    """:func:`tefcore.linear.stability.stability` with its numerical warnings counted, not printed.

    Workers' stderr would otherwise reach the notebook; the count is the
    sweep column ``trim_numerical_warnings``.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.
    """
    from ...linear.stability import stability

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = stability(cfg)
    trim = dict(res.trim)
    trim["numerical_warnings"] = len(caught)
    return SimpleNamespace(modes=res.modes, eigenvectors=res.eigenvectors, trim=trim,
                           vectors=res.vectors, periodic=res.periodic, system=res.system,
                           trim_result=res.trim_result)


def natural_frequencies(name: str, values, base=None, overrides: dict | None = None,
                        labels=("blade flap 1", "blade lag 1", "blade torsion 1")):
    """Blade natural frequencies at each sweep value (no aerodynamics, zero collective).

    The "blade frequency" panels of Figs. 10a/11a, as the paper's stated
    frequencies (and the validation) use them (:func:`tefcore.structure.blade.blade_modes`).

    Parameters
    ----------
    name : str
        Paper figure.
    values : sequence
        Sweep values.
    base : tefcore.config.configuration.Config, optional
        Base configuration.
    overrides : dict, optional
        Dotted fields applied over the caption.
    labels : tuple of str
        Modes to return.

    Returns
    -------
    DataFrame
        In the format of :func:`tefcore.paper.figures.plotting.curves`.
    """
    from ...structure.blade import blade_modes

    cfg = run_config(name, base, overrides)
    rows = []
    for v in values:
        m = blade_modes(cfg.with_overrides({FIGURES[name].parameter: v}))
        for lab, f in zip(m.labels, m.frequencies, strict=True):
            if f"blade {lab}" in labels:
                rows.append({"point": len(rows), "value": v, "label": f"blade {lab}",
                             "frequency_per_rev": float(f)})
    t = pd.DataFrame(rows)
    t["x"] = x_values(name, t)
    t["track"] = t["label"]
    t["damping"] = np.nan
    t["same_character"] = True
    t["certain"] = True
    t["refinement"] = 0
    return t[["label", "track", "x", "frequency_per_rev", "damping", "same_character",
              "certain", "refinement"]]
