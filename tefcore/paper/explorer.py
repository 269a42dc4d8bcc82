"""An interactive root map of the bladed rotor with a flap, for teaching.

:func:`explore` shows, for one configuration, every root of the Floquet
analysis in the s-plane (frequency against real part, coloured by how much
the flap takes part in it), the TEF root (the root the flap's own mode
becomes when the coupling is switched on, :mod:`tefcore.modes.continuation`)
and the flutter root (the least stable root the flap takes part in), beside
the damping of the paper's modes.  With ipywidgets in a live notebook,
sliders for the flap CG offset, the overhang, the actuator stiffness and the
advance ratio redraw it, leaving the previous roots as a grey trail: moving
one slider draws the root locus of that parameter.  Without a widget frontend
(papermill, nbval, an HTML export) it draws the same figure once, statically.

Examples
--------
>>> cfg = explorer_config(cg_offset=0.0, overhang=0.29, actuator_scale=1.0,
...                       advance_ratio=0.0)
>>> cfg.flap.cg_offset, cfg.flight.advance_ratio
(0.0, 0.0)
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass

import pandas as pd

from ..modes.names import base_name
from ..modes.roles import flutter_root
from .figures.plotting import PAPER_MODES, STYLE, legend_below
from .figures.runs import base_config

__all__ = ["SLIDERS", "RootMap", "draw_root_map", "explore", "explorer_config", "explorer_state",
           "root_map"]

#: The sliders: parameter -> (label, minimum, maximum, step, default).
SLIDERS = {
    "cg_offset": ("flap CG offset c_cg/c_f", -0.1, 0.45, 0.01, 0.33),
    "overhang": ("overhang c_b/c_f", 0.0, 0.6, 0.01, 0.29),
    "actuator_scale": ("actuator stiffness / 81.52 ft-lb/rad", 0.25, 3.0, 0.05, 1.0),
    "advance_ratio": ("advance ratio μ", 0.0, 0.35, 0.01, 0.30),
}
#: Highest frequency shown in the root map [/rev].
MAX_FREQUENCY = 20.0
#: Previous states kept as the grey trail.
TRAIL = 12


def explorer_config(base=None, *, cg_offset: float, overhang: float, actuator_scale: float,
                    advance_ratio: float):
    """The configuration of one explorer state.

    Parameters
    ----------
    base : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART, thin-airfoil aerodynamics).
    cg_offset, overhang : float
        Flap CG offset and overhang, fractions of the flap chord.
    actuator_scale : float
        Actuator stiffness as a factor on the base configuration's.
    advance_ratio : float
        Forward flight (0: hover).
    """
    base = base_config() if base is None else base
    return base.with_overrides({
        "flap.cg_offset": float(cg_offset), "flap.overhang": float(overhang),
        "actuator.stiffness": float(base.actuator.stiffness * actuator_scale),
        "flight.advance_ratio": float(advance_ratio)})


@dataclass
class RootMap:
    """The roots of one configuration: ``modes`` table, TEF root and flutter root.

    Parameters
    ----------
    modes : pandas.DataFrame
        The Floquet roots (:attr:`tefcore.linear.stability.StabilityResult.modes`):
        ``label``, ``frequency_per_rev``, ``real_part`` [1/rev, > 0
        unstable], ``share_TEF`` (flap participation) ...; empty when the
        configuration has no roots (``error`` says why).
    tef : complex or None
        The TEF root, ``real_part + 1j * frequency_per_rev`` [1/rev]: the root
        the flap's own mode becomes when its coupling to the blade is switched
        on (:mod:`tefcore.modes.continuation`); None without a flap.
    flutter : int or None
        Index in ``modes`` of the flutter root, the least stable flap-induced
        root (:func:`tefcore.modes.roles.flutter_root`); None without a flap.
    error : str
        Why there are no roots (a refused configuration, a failed trim);
        ``""`` when there are.
    """

    modes: pd.DataFrame
    tef: complex | None
    flutter: int | None
    error: str = ""


def root_map(cfg) -> RootMap:
    """Floquet roots of ``cfg`` with the TEF root and the flutter root.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration.

    Returns
    -------
    RootMap
        ``error`` says why there are no roots (e.g. the flap diverged
        statically, so there is no trim to linearise about).
    """
    from ..errors import TefcoreError
    from ..linear.stability import stability

    try:
        res = stability(cfg)
    except (TefcoreError, ValueError) as exc:
        return RootMap(pd.DataFrame(), None, None, f"{type(exc).__name__}: {exc}")
    tef = None
    rows = res.modes[res.modes["label"] == "TEF"]
    if cfg.model.tef != "none" and not rows.empty:
        tef = complex(rows["real_part"].iloc[0], rows["frequency_per_rev"].iloc[0])
    return RootMap(res.modes, tef, flutter_root(res.modes), "")


def explorer_state(base=None, **values) -> RootMap:
    """:func:`root_map` of :func:`explorer_config`, or why there is none.

    A configuration the model refuses (e.g. a flap whose inertia no longer
    fits in its section at that overhang) or cannot trim (a statically
    diverged flap) gives an empty :class:`RootMap` with the reason, which the
    explorer shows instead of the roots.

    Parameters
    ----------
    base : tefcore.config.configuration.Config, optional
        Base configuration.
    **values
        The :data:`SLIDERS` values.
    """
    try:
        cfg = explorer_config(base, **values)
    except ValueError as exc:
        return RootMap(pd.DataFrame(), None, None, f"refused: {exc}")
    return root_map(cfg)


def draw_root_map(fig, state: RootMap, trail=(), title: str = ""):
    """Draw a :class:`RootMap` into ``fig`` (two axes: roots, damping of the paper's modes).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Cleared and drawn into.
    state : RootMap
        The current roots.
    trail : sequence of RootMap
        Earlier states, drawn as small grey dots (the root locus so far).
    title : str
        Figure title.
    """
    fig.clear()
    ax, bx = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1]})
    for old in trail:
        m = old.modes
        if not m.empty:
            keep = m["frequency_per_rev"].between(0, MAX_FREQUENCY)
            ax.plot(m.loc[keep, "frequency_per_rev"], m.loc[keep, "real_part"], ".",
                    color="0.75", ms=3)
            if old.tef is not None:
                ax.plot(old.tef.imag, old.tef.real, ".", color="C3", alpha=0.35, ms=4)
    m = state.modes
    if m.empty:
        ax.text(0.5, 0.5, "\n".join(textwrap.wrap(state.error or "no roots", 60)),
                transform=ax.transAxes, ha="center", va="center", fontsize="small")
    else:
        keep = m[m["frequency_per_rev"].between(0, MAX_FREQUENCY)]
        sc = ax.scatter(keep["frequency_per_rev"], keep["real_part"], c=keep["share_TEF"],
                        cmap="viridis", vmin=0, vmax=1, s=28, zorder=3)
        fig.colorbar(sc, ax=ax, label="flap participation")
        if state.tef is not None:
            ax.plot(state.tef.imag, state.tef.real, "o", ms=13, mfc="none", mec="C3",
                    mew=2, zorder=4, label="TEF root")
        if state.flutter is not None:
            r = m.loc[state.flutter]
            ax.plot(r["frequency_per_rev"], r["real_part"], "kx", ms=11, mew=2, zorder=5,
                    label=f"flutter root (from {r['label']})")
        legend_below(ax, ncol=2)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlim(0, MAX_FREQUENCY)
    ax.set_xlabel("frequency [/rev]")
    ax.set_ylabel("real part Re(s)/Ω [1/rev]  (> 0 unstable)")
    names, values, colors = [], [], []
    if not m.empty:
        base = m["label"].map(base_name)
        for lab in PAPER_MODES:
            if lab == "TEF" and state.tef is not None:
                names.append("TEF root")
                values.append(-state.tef.real)
            elif lab != "TEF" and (base == lab).any():
                names.append(lab)
                values.append(-float(m.loc[base == lab, "real_part"].max()))
            else:
                continue
            colors.append(STYLE[lab][0])
        if state.flutter is not None:
            names.append("flutter root")
            values.append(-float(m.loc[state.flutter, "real_part"]))
            colors.append("k")
    bx.barh(names[::-1], values[::-1], color=colors[::-1])
    bx.axvline(0.0, color="k", lw=0.8)
    bx.set_xlabel("damping −Re(s)/Ω [1/rev]  (< 0 unstable)")
    bx.tick_params(axis="y", labelsize="small")
    if title:
        fig.suptitle(title, fontsize="medium")
    return fig


def _title(values: dict) -> str:
    return (f"c_cg/c_f = {values['cg_offset']:.2f}, c_b/c_f = {values['overhang']:.2f}, "
            f"actuator × {values['actuator_scale']:.2f}, μ = {values['advance_ratio']:.2f}")


def explore(base=None, interactive: bool = True, **start):
    """The root-map explorer: sliders in a live notebook, a static figure otherwise.

    Parameters
    ----------
    base : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART, thin-airfoil aerodynamics).
    interactive : bool
        Show ipywidgets sliders (when ipywidgets is installed); False draws the
        figure for ``start`` once (what papermill and nbval run).
    **start
        Starting values of the :data:`SLIDERS` (defaults: the paper's
        mass-imbalanced flap at μ = 0.3).

    Returns
    -------
    matplotlib.figure.Figure or ipywidgets.Widget
        The static figure (shown by the notebook's inline backend at the end of
        the cell), or the widget box (sliders and the figure's output), already
        displayed.
    """
    import matplotlib.pyplot as plt

    unknown = sorted(set(start) - set(SLIDERS))
    if unknown:
        raise TypeError(f"explore: unknown parameter(s) {unknown}; known: {sorted(SLIDERS)}")
    values = {k: float(start.get(k, spec[4])) for k, spec in SLIDERS.items()}
    try:
        import ipywidgets as widgets
    except ImportError:
        interactive = False
    if not interactive:
        fig = plt.figure(figsize=(11.5, 4.6), layout="constrained")
        return draw_root_map(fig, explorer_state(base, **values), title=_title(values))
    out = widgets.Output()
    trail: list[RootMap] = []
    sliders = {k: widgets.FloatSlider(value=values[k], min=lo, max=hi, step=step,
                                      description=label, continuous_update=False,
                                      style={"description_width": "initial"},
                                      layout=widgets.Layout(width="420px"))
               for k, (label, lo, hi, step, _) in SLIDERS.items()}
    clear = widgets.Button(description="clear trail")

    def redraw(_change=None):
        now = {k: s.value for k, s in sliders.items()}
        state = explorer_state(base, **now)
        with out:
            out.clear_output(wait=True)
            fig = plt.figure(figsize=(11.5, 4.6), layout="constrained")
            draw_root_map(fig, state, trail[-TRAIL:], _title(now))
            plt.show()
        trail.append(state)

    def reset(_button):
        trail.clear()
        redraw()

    for s in sliders.values():
        s.observe(redraw, names="value")
    clear.on_click(reset)
    redraw()
    box = widgets.VBox([widgets.HBox([widgets.VBox(list(sliders.values())[:2]),
                                       widgets.VBox(list(sliders.values())[2:])]), clear, out])
    from IPython.display import display

    display(box)
    return box
