"""Both bearingless-hub models side by side, for notebook 01 (Figs. 3-4).

:func:`compare_hub_models` computes, for ``hub.model = "equivalent"`` and
``"multiple_load_path"`` (docs/theory.md sections 2.5 and 2.5a), the fan plot,
the retained modes with their structural damping and the lag damping of the
paper's Figs. 3 and 4; :func:`plot_hub_models` draws them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ...config.io import load_config
from ...structure.blade import blade_modes, fan_data
from ...structure.hub_models import HUB_MODELS
from ..figures.catalogue import run_figure

__all__ = ["HubComparison", "compare_hub_models", "plot_hub_models"]


@dataclass
class HubComparison:
    """Both hub models of one configuration (:func:`compare_hub_models`).

    Attributes
    ----------
    fan : DataFrame
        :func:`tefcore.structure.blade.fan_data` of each hub, with ``hub_model``.
    modes : DataFrame
        The retained modes at the configured rotor speed: ``hub_model, mode,
        label, frequency_per_rev, damping_ratio`` (structural, in vacuum:
        ``C_ii / (2 omega_i M_ii)``, as
        :func:`tefcore.paper.calibration.lag_damping_ratio` for lag 1).
    lag_damping : DataFrame
        Figs. 3 and 4 (no flap): ``hub_model, figure, collective_deg,
        frequency_per_rev, damping_ratio`` of the ``blade lag 1`` track.
    """

    fan: pd.DataFrame
    modes: pd.DataFrame
    lag_damping: pd.DataFrame


def _lag_track(result, hub_model, name):
    t = result.table
    t = t[(t["refinement"] == 0) & (t["status"] == "ok") & (t["label"] == "blade lag 1")]
    return pd.DataFrame({"hub_model": hub_model, "figure": name,
                         "collective_deg": np.degrees(t["value_si"].to_numpy(float)),
                         "frequency_per_rev": t["frequency_per_rev"].to_numpy(float),
                         "damping_ratio": t["damping_ratio"].to_numpy(float)})


def compare_hub_models(cfg=None, *, speed_ratios=None, figures=("fig3", "fig4"),
                       collectives_deg=None, n_jobs: int = 1) -> HubComparison:
    """Fan plots and the Figs. 3-4 lag damping of both hub models.

    Parameters
    ----------
    cfg : Config, optional
        Base configuration (default MDART); ``hub.model`` is set to each of
        :data:`HUB_MODELS` in turn.
    speed_ratios : array_like, optional
        Rotor speeds of the fan plot over the configured one (default
        0.2-1.2).
    figures : sequence of str
        Lag-damping figures to run (:data:`tefcore.paper.figures.catalogue.FIGURES`); empty
        for none (the fan plot alone takes well under a second).
    collectives_deg : array_like, optional
        Collective pitch values [deg] (default: the figures' 0-10 deg).
    n_jobs : int
        Parallel processes of the sweeps.

    Returns
    -------
    HubComparison
    """
    cfg = cfg or load_config("mdart")
    speed_ratios = np.linspace(0.2, 1.2, 26) if speed_ratios is None else speed_ratios
    values = None if collectives_deg is None else [float(np.radians(v)) for v in collectives_deg]
    fans, modes, lags = [], [], []
    for hub in HUB_MODELS:
        c = cfg.with_overrides({"hub.model": hub})
        fans.append(fan_data(c, speed_ratios).assign(hub_model=hub))
        m = blade_modes(c)
        damp = np.diag(m.modal_damping) / (2 * m.frequencies * np.diag(m.modal_mass))
        modes.append(pd.DataFrame({"hub_model": hub, "mode": np.arange(1, len(m.labels) + 1),
                                   "label": m.labels, "frequency_per_rev": m.frequencies,
                                   "damping_ratio": damp}))
        for name in figures:
            lags.append(_lag_track(run_figure(name, c, values, n_jobs=n_jobs), hub, name))
    lag = (pd.concat(lags, ignore_index=True) if lags else
           pd.DataFrame(columns=["hub_model", "figure", "collective_deg", "frequency_per_rev",
                                 "damping_ratio"]))
    return HubComparison(pd.concat(fans, ignore_index=True), pd.concat(modes, ignore_index=True),
                         lag)


def plot_hub_models(comparison: HubComparison, cfg=None):
    """Fan plots of both hubs and the lag damping of Figs. 3-4, side by side.

    Parameters
    ----------
    comparison : HubComparison
        From :func:`compare_hub_models`.
    cfg : tefcore.config.configuration.Config, optional
        Its configuration, for the nominal rotor speed (default MDART).

    Returns
    -------
    matplotlib.figure.Figure
        Two fan plots on top, the lag damping of each figure below.
    """
    import matplotlib.pyplot as plt

    cfg = cfg or load_config("mdart")
    figs = list(dict.fromkeys(comparison.lag_damping["figure"]))
    fig, axes = plt.subplots(2, max(2, len(figs)), figsize=(11, 8), squeeze=False,
                             layout="constrained")
    styles = {"flap": "-", "lag": "--", "torsion": "-.", "axial": ":"}
    nominal = cfg.rotor.rotor_speed * 30 / np.pi
    for ax, hub in zip(axes[0], HUB_MODELS, strict=False):
        df = comparison.fan[comparison.fan["hub_model"] == hub]
        for lab, g in df.groupby("label", sort=False):
            ax.plot(g["rotor_speed_rpm"], g["frequency_hz"], styles[g["family"].iloc[0]],
                    label=lab)
        rpm = np.array([0.0, df["rotor_speed_rpm"].max()])
        for k in range(1, 9):
            ax.plot(rpm, k * rpm / 60, color="0.8", lw=0.7, zorder=0)
        ax.axvline(nominal, color="0.5", lw=0.8)
        ax.set(title=f"hub.model = {hub!r}", xlabel="rotor speed [RPM]", ylabel="frequency [Hz]",
               xlim=(0, rpm[1]), ylim=(0, df["frequency_hz"].max() * 1.05))
        ax.legend(fontsize="x-small", ncol=2)
    for ax, name in zip(axes[1], figs, strict=False):
        d = comparison.lag_damping[comparison.lag_damping["figure"] == name]
        for hub, style in zip(HUB_MODELS, ("o-", "s--"), strict=True):
            g = d[d["hub_model"] == hub]
            ax.plot(g["collective_deg"], 100 * g["damping_ratio"], style, label=hub)
        ax.set(title=f"{name}: lag 1 damping", xlabel="collective [deg]",
               ylabel="damping ratio [%]")
        ax.legend(fontsize="small")
    for ax in axes[1][len(figs):]:
        ax.set_visible(False)
    return fig
