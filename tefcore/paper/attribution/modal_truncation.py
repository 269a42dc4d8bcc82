"""Modal truncation: how the imbalanced flap's flutter depends on the blade modes retained.

The paper keeps nine coupled blade modes of its (unknown) blade.  On the
assumed MDART blade the imbalanced flap's own frequency (10.9 /rev alone on a
rigid blade at ``c_cg/c_f = 0.33``) lies among blade flap 4, flap 5 and
torsion 2 (7.3-11.8 /rev), so which of those a truncation keeps decides the
flutter.  :func:`truncation_table` retains the lowest ``n`` modes
(``model.n_modes``); :func:`mode_additions` keeps the six lowest plus one chosen
mode (:func:`select_modes`), which shows what each of those modes does alone.

Examples
--------
>>> from tefcore.config.io import load_config
>>> from tefcore.structure.blade import blade_modes
>>> m = select_modes(blade_modes(load_config("mdart"), n_modes=12), ["flap 1", "torsion 2"])
>>> m.labels
['flap 1', 'torsion 2']
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pandas as pd

from ...linear.stability import stability
from ...model.coupled import coupled_model
from ...structure.blade import blade_modes
from ...trimming.trim import initial_collective

__all__ = ["IMBALANCED_HOVER", "MODE_COUNTS", "ADDED_MODES", "mode_additions",
           "select_modes", "truncation_table"]

#: The point of the truncation study: the paper's imbalanced flap in hover.
IMBALANCED_HOVER = {"flight.advance_ratio": 0.0, "flap.overhang": 0.29, "flap.cg_offset": 0.33}
#: Numbers of retained modes of :func:`truncation_table`.
MODE_COUNTS = (6, 7, 8, 9, 10, 12)
#: The modes between 7 and 12 /rev that :func:`mode_additions` adds one at a time.
ADDED_MODES = ("flap 4", "flap 5", "torsion 2")


def select_modes(modes, labels):
    """The blade modes of ``labels`` only, in their order of frequency.

    Parameters
    ----------
    modes : tefcore.structure.fem.BladeModes
        Modes to choose from (e.g. the twelve lowest).
    labels : sequence of str
        Structural labels (``"flap 4"``).

    Returns
    -------
    tefcore.structure.fem.BladeModes
        A new set of modes (its own shape cache); the modal matrices are the
        chosen rows and columns.

    Raises
    ------
    ValueError
        A label not among ``modes``.
    """
    missing = [lb for lb in labels if lb not in modes.labels]
    if missing:
        raise ValueError(f"no mode(s) {missing} among {modes.labels}")
    idx = np.array(sorted(modes.labels.index(lb) for lb in labels))
    sub = np.ix_(idx, idx)
    return dataclasses.replace(
        modes, frequencies=modes.frequencies[idx], vectors=modes.vectors[:, idx],
        labels=[modes.labels[i] for i in idx], fractions=modes.fractions[idx],
        modal_mass=modes.modal_mass[sub], modal_stiffness=modes.modal_stiffness[sub],
        modal_damping=modes.modal_damping[sub], modal_gyroscopic=modes.modal_gyroscopic[sub],
        cache={})


def _flutter_root(cfg, labels) -> dict:
    """The least stable flap-induced root with the blade modes ``labels`` retained."""
    theta = initial_collective(cfg)
    every = blade_modes(cfg, n_modes=max(12, len(labels)), collective=theta)
    modes = select_modes(every, labels)
    # the basis is given mode by mode: no family is held besides
    c = cfg.with_overrides({"model.n_modes": len(labels), "model.mode_families": ""})
    with warnings.catch_warnings():          # numerical warnings: the sweeps count them
        warnings.simplefilter("ignore")
        m = stability(c, model=coupled_model(c, collective=theta, modes=modes)).modes
    root = m[m["flutter_root"]] if m["flutter_root"].any() else m[m["flap_induced"]]
    row = root.loc[root["real_part"].idxmax()]
    return {"flutter root": str(row["label"]),
            "frequency /rev": round(float(row["frequency_per_rev"]), 2),
            "real part /rev": round(float(row["real_part"]), 2)}


def truncation_table(cfg, counts=MODE_COUNTS) -> pd.DataFrame:
    """The imbalanced flap's flutter root in hover versus the blade modes retained.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        Base configuration; :data:`IMBALANCED_HOVER` is applied.
    counts : sequence of int
        Numbers of modes, the lowest retained (``model.n_modes``).

    Returns
    -------
    pandas.DataFrame
        ``modes``, ``highest retained`` (label and frequency of the last
        mode kept), and the flutter root's name, frequency and real part
        [/rev], rounded to 0.01.
    """
    cfg = cfg.with_overrides(IMBALANCED_HOVER)
    every = blade_modes(cfg, n_modes=max(12, *counts), collective=initial_collective(cfg))
    rows = []
    for n in counts:
        labels = every.labels[:n]
        rows.append({"modes": n, "highest retained":
                     f"{labels[-1]} ({every.frequencies[n - 1]:.2f}/rev)",
                     **_flutter_root(cfg, labels)})
    return pd.DataFrame(rows)


def mode_additions(cfg, added=ADDED_MODES, base: int = 6) -> pd.DataFrame:
    """The six lowest blade modes, then each of ``added`` alone on top of them.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        Base configuration; :data:`IMBALANCED_HOVER` is applied.
    added : sequence of str
        Modes added one at a time.
    base : int
        The lowest modes always kept.

    Returns
    -------
    pandas.DataFrame
        ``retained`` (what is kept), ``added`` (label and frequency), and the
        flutter root's name, frequency and real part [/rev].
    """
    cfg = cfg.with_overrides(IMBALANCED_HOVER)
    every = blade_modes(cfg, n_modes=12, collective=initial_collective(cfg))
    lowest = every.labels[:base]
    rows = [{"retained": f"the {base} lowest", "added": "none", **_flutter_root(cfg, lowest)}]
    for lb in added:
        f = every.frequencies[every.labels.index(lb)]
        rows.append({"retained": f"the {base} lowest + {lb}", "added": f"{lb} ({f:.2f}/rev)",
                     **_flutter_root(cfg, [*lowest, lb])})
    return pd.DataFrame(rows)
