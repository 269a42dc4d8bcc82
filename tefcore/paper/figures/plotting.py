"""Plots of the paper's figures: tracked modes, root loci, participation, captions.

Every stability figure of the notebooks is drawn by these functions, so the
curves, markers and captions mean the same thing everywhere:

* :func:`curves` -- one tracked curve per mode of a sweep table (the TEF
  branch for ``"TEF"``), with the paper's x axis (:data:`AXES`);
* :func:`plot_modes`, :func:`plot_root_locus`, :func:`plot_participation`;
* :func:`legend_below` -- a legend that cannot cover a curve;
* :func:`savefig` -- a PNG with fixed metadata (byte-identical between runs)
  and a JSON caption beside it that the report reads (captions:
  :mod:`tefcore.paper.figures.captions`).

Examples
--------
>>> split_value("0.5 ft-lbf/rad")
(0.5, 'ft-lbf/rad')
"""

from __future__ import annotations

import io
import json
import re
import textwrap
from pathlib import Path

import numpy as np
import pandas as pd

from ...modes.names import base_name
from ...safe_io import atomic_output, atomic_write_text
from ...units import from_si

__all__ = ["AXES", "FIELD_AXES", "MEASURES", "PAPER_MODES", "STYLE", "curves",
           "deterministic_matplotlib", "field_axis", "flutter_legend",
           "legend_below", "locus_figure",
           "plot_modes", "plot_participation", "plot_root_locus", "savefig", "show_saved",
           "split_value",
           "x_values"]

_NUM_UNIT = re.compile(r"^\s*([-+0-9.eE]+)\s*(.*)$")


def split_value(value) -> tuple[float, str]:
    """A swept value as ``(number, unit)``: ``"150 lb/in"`` -> ``(150.0, "lb/in")``.

    Parameters
    ----------
    value : str or float
        A figure's swept value: a number (SI or a fraction) or a ``"value
        unit"`` string as in :data:`tefcore.paper.figures.catalogue.FIGURES` (Figs. 10
        and 12 give the pitch-link and actuator stiffness in lb/in and
        ft-lb/rad, the paper's units).

    Returns
    -------
    tuple of (float, str)
        The number, and the unit as written (``""`` for a number).

    Raises
    ------
    ValueError
        A string that does not start with a number.

    Examples
    --------
    >>> split_value("150 lb/in"), split_value(0.25)
    ((150.0, 'lb/in'), (0.25, ''))
    """
    if isinstance(value, str):
        m = _NUM_UNIT.match(value)
        if not m:
            raise ValueError(f"cannot read a number from {value!r}")
        return float(m.group(1)), m.group(2).strip()
    return float(value), ""


def _degrees(v):
    return np.rad2deg(np.asarray(v, float))


#: Axis of a configuration field in the figures and maps: (label, unit shown or None
#: for the stored value); the notebooks' labels, reused by ``tefcore map``
#: (:func:`field_axis`).
FIELD_AXES = {
    "flight.collective": ("collective pitch θ₀ [deg]", "deg"),
    "flap.overhang": ("flap overhang c_b/c_f", None),
    "flap.cg_offset": ("flap CG offset c_cg/c_f (positive aft)", None),
    "hub.pitch_link_stiffness": ("pitch link stiffness [lb/in]", "lb/in"),
    "blade.gj_scale": ("torsional stiffness GJ / baseline GJ", None),
    "actuator.stiffness": ("actuator stiffness k_a [ft-lb/rad]", "ft-lbf/rad"),
    "flap.midspan": ("flap midspan location r/R", None),
    "flap.span": ("flap length / R", None),
    "flap.chord_ratio": ("flap chord c_f/c", None),
    "flight.advance_ratio": ("advance ratio μ", None),
}


def field_axis(field: str) -> tuple[str, str | None]:
    """Axis label and display unit of a configuration field, as the notebooks show it.

    The fields of the paper's figures have the notebooks' labels
    (:data:`FIELD_AXES`); any other field is named by its description, its
    dotted name and its SI unit.

    Parameters
    ----------
    field : str
        A dotted configuration field.

    Returns
    -------
    label : str
    unit : str or None
        The unit to show values in (None: the stored value).

    Raises
    ------
    ValueError
        For an unknown field.

    Examples
    --------
    >>> field_axis("actuator.stiffness")
    ('actuator stiffness k_a [ft-lb/rad]', 'ft-lbf/rad')
    >>> field_axis("rotor.radius")
    ('Rotor radius R (rotor.radius) [m]', None)
    """
    if field in FIELD_AXES:
        return FIELD_AXES[field]
    from ...config.text_input import field_param

    p = field_param(field)
    doc = p.doc.rstrip(".") if p is not None else field
    return f"{doc} ({field})" + (f" [{p.unit}]" if p is not None and p.unit else ""), None


#: x axis per figure: (label, function of the table's ``value`` column or None)
AXES = {
    "fig3": (FIELD_AXES["flight.collective"][0], _degrees),
    "fig4": (FIELD_AXES["flight.collective"][0], _degrees),
    "fig8": (FIELD_AXES["flap.overhang"][0], None),
    "fig9": (FIELD_AXES["flap.cg_offset"][0], None),
    "fig10": (FIELD_AXES["hub.pitch_link_stiffness"][0], None),
    "fig11": (FIELD_AXES["blade.gj_scale"][0], None),
    "fig12": ("actuator stiffness / baseline (81.52 ft-lb/rad)",
              lambda v: np.array([split_value(s)[0] for s in v]) / 81.52),
    "fig13": (FIELD_AXES["flap.midspan"][0], None),
    "fig14": (FIELD_AXES["flap.span"][0], None),
    "fig15": (FIELD_AXES["flap.chord_ratio"][0], None),
    "fig16a": (FIELD_AXES["flight.collective"][0], _degrees),
    "fig16b": (FIELD_AXES["flight.collective"][0], _degrees),
    "fig17": (FIELD_AXES["flight.advance_ratio"][0], None),
}

#: modes shown in the paper's damping panels
PAPER_MODES = ("TEF", "blade flap 1", "blade lag 1", "blade torsion 1")
#: colour, marker and line style of each mode
STYLE = {"TEF": ("C3", "o", "-"), "blade flap 1": ("C0", "s", "-"),
         "blade lag 1": ("C2", "^", "--"), "blade torsion 1": ("C1", "D", "-.")}
#: damping measures: (axis label, function of a curves table)
MEASURES = {
    "decay_rate": ("damping −Re(s)/Ω  [1/rev]  (> 0 stable)",
                   lambda t: -t["real_part"]),
    "damping_ratio": ("damping ratio ζ [%]  (> 0 stable)",
                      lambda t: 100 * t["damping_ratio"]),
}
_CURVE_COLUMNS = ["label", "track", "x", "frequency_per_rev", "damping", "same_character",
                  "certain", "refinement"]


def deterministic_matplotlib() -> None:
    """Set the matplotlib rcParams that make saved figures byte-identical between runs."""
    import matplotlib as mpl

    mpl.rcParams.update({"svg.hashsalt": "tefcore", "pdf.compression": 6,
                         "figure.dpi": 80, "savefig.dpi": 110,
                         "figure.figsize": (6.4, 4.2), "axes.grid": True,
                         "grid.alpha": 0.3, "legend.fontsize": "small",
                         # titles, panel titles and legends below the axes never overlap
                         "figure.constrained_layout.use": True})


def savefig(fig, output_dir, stem: str, figure: str = "", caption: str = "") -> None:
    """Save ``fig`` as ``<output_dir>/<stem>.png`` with fixed metadata.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    output_dir : path
        Existing folder to write into.
    stem : str
        File name without suffix.
    figure : str
        The paper figure it belongs to (``"fig9"``), for the report; several
        separated by spaces when one figure shows them all (``"fig16a
        fig16b"``), the first owning it.
    caption : str
        Caption for the report (:func:`tefcore.paper.figures.captions.figure_caption`);
        written with ``figure`` to ``<stem>.json`` beside the PNG when either
        is given.

    Notes
    -----
    Returns None, so that a notebook cell ending with it displays nothing
    extra (nbval executes cells without history, where IPython's trailing
    ``;`` does not suppress the result).  Both files are written atomically.

    In a notebook (matplotlib's inline backend) the cell shows the PNG just
    written, at the size and with the text the backend would show the figure
    with, and the figure is closed so that the backend does not draw it a
    second time at the end of the cell (:func:`show_saved`).
    """
    out = Path(output_dir)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None}, bbox_inches="tight")
    png = buf.getvalue()
    with atomic_output(out / f"{stem}.png", "wb") as f:
        f.write(png)
    if figure or caption:
        atomic_write_text(out / f"{stem}.json", json.dumps(
            {"figure": figure, "caption": caption}, sort_keys=True, ensure_ascii=False) + "\n")
    show_saved(fig, png)


def show_saved(fig, png: bytes) -> bool:
    """Show `png`, the figure as saved, as a notebook's output of `fig`, and close `fig`.

    Only in a Jupyter kernel under matplotlib's inline backend: there the
    backend draws every open figure again when the cell ends (at the
    figure's dpi, ``bbox_inches="tight"``), which is the work this saves --
    0.15-0.7 s a figure in the notebooks (0.5-0.7 s a root-locus figure,
    measured), about once for each of their 29 saved figures.  The output
    is the saved file, drawn at ``savefig.dpi`` (110 in the notebooks,
    :func:`deterministic_matplotlib`), shown at the size the backend's own
    picture had (``figure.dpi``, 80: width and height in the output's
    metadata), so the cell looks as before, sharper; its ``text/plain`` is
    the backend's (``repr(fig)``, ``<Figure size 880x352 with 2 Axes>``),
    which nbval compares.  Closed, the figure is no longer pyplot's (a
    pyplot call after it in the same cell starts a new figure, as in the
    next cell), but it can still be saved or drawn.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure `png` was drawn from.
    png : bytes
        The PNG file.

    Returns
    -------
    bool
        Whether it was shown (False outside a kernel with the inline backend:
        nothing done; e.g. a script started from a notebook, which inherits
        the backend through ``MPLBACKEND`` but has no kernel to show it).
    """
    import sys

    if "matplotlib_inline.backend_inline" not in sys.modules:
        return False
    import matplotlib
    from IPython import get_ipython

    if "inline" not in matplotlib.get_backend() or \
            getattr(get_ipython(), "kernel", None) is None:
        return False
    import base64

    import matplotlib.pyplot as plt
    from IPython.display import display

    saved_dpi = matplotlib.rcParams["savefig.dpi"]
    scale = 1.0 if saved_dpi == "figure" else fig.dpi / float(saved_dpi)
    # the PNG's size in pixels: its IHDR chunk (bytes 16-24, big-endian)
    width, height = (int.from_bytes(png[i:i + 4], "big") for i in (16, 20))
    display({"image/png": base64.b64encode(png).decode("ascii"), "text/plain": repr(fig)},
            metadata={"image/png": {"width": round(width * scale),
                                    "height": round(height * scale)}}, raw=True)
    plt.close(fig)
    return True


def legend_below(ax, ncol: int = 3, **kw):
    """A legend under the axes, where it cannot cover a curve.

    The paper's damping panels have curves everywhere between the modes, so a
    legend inside the axes would hide a crossing of zero damping.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose labelled artists are listed.
    ncol : int
        Columns of legend entries.
    **kw
        Passed to :meth:`matplotlib.axes.Axes.legend` (``fontsize`` defaults
        to ``"x-small"``).

    Returns
    -------
    matplotlib.legend.Legend or None
        The legend, or None when nothing in ``ax`` is labelled.
    """
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    kw.setdefault("fontsize", "x-small")
    return ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.16),
                     ncol=ncol, frameon=False, **kw)


def x_values(name: str, table: pd.DataFrame) -> np.ndarray:
    """The paper's x-axis quantity for each row of a sweep table.

    Dimensional values are read from ``value_si`` in the unit of the figure's
    own values (points added by refinement carry only SI values), else from
    ``value``.

    Parameters
    ----------
    name : str
        Paper figure.
    table : DataFrame
        Rows with ``value`` (and ``value_si``).
    """
    from .catalogue import FIGURES
    from .quantities import swept_dimension

    _, fn = AXES[name]
    unit = split_value(FIGURES[name].values[0])[1] if name in FIGURES else ""
    if unit and "value_si" in table:
        own = from_si(table["value_si"].to_numpy(float), unit.replace("ft-lb/", "ft-lbf/"),
                      swept_dimension(name))
        v = [f"{float(x)!r} {unit}" for x in np.atleast_1d(own)]
    else:
        v = table["value"].tolist()
    if fn is not None:
        return np.asarray(fn(v), float)
    return np.array([split_value(s)[0] for s in v], float)


def _base_label(s: pd.Series) -> pd.Series:
    return s.map(base_name)


def curves(name: str, table: pd.DataFrame, labels=PAPER_MODES,
           measure: str = "decay_rate") -> pd.DataFrame:
    """One curve per mode, for plotting and printing: the root of that name at each point.

    A root's name is the uncoupled mode it continues from
    (:mod:`tefcore.modes.continuation`): ``"TEF"`` is the root the flap's own
    mode continues into (the TEF branch), ``"blade torsion 1"`` the one the
    blade's first torsion mode does -- whatever its character there, in
    whatever order the points were computed.  The same choice as
    :mod:`tefcore.paper.claims.validation`.

    Parameters
    ----------
    name : str
        Paper figure (sets the x axis).
    table : DataFrame
        Sweep table (:attr:`tefcore.sweeps.sweep.SweepResult.table`).
    labels : tuple of str
        Modes to return.
    measure : {"decay_rate", "damping_ratio"}
        Damping measure (:data:`MEASURES`).

    Returns
    -------
    DataFrame
        Columns ``label, track, x, frequency_per_rev`` (continuous along the
        name: whole /rev of a Floquet frequency are not allowed to jump, nor
        its sign to mirror), ``damping, same_character, certain,
        refinement``; ``same_character`` is False where the root carries
        another coordinate most (it exchanged character in a veering),
        ``certain`` is False where its path from zero coupling met another's.
    """
    _, fn = MEASURES[measure]
    ok = table[table["status"] == "ok"].copy()
    parts = []
    for lab in labels:
        g = ok[ok["label"].astype(str) == lab].drop_duplicates("point").copy()
        if g.empty:
            continue
        g["certain"] = (g["identity_certain"].fillna(False).astype(bool)
                        if "identity_certain" in g else True)
        parts.append(g)
    if not parts:
        return pd.DataFrame(columns=_CURVE_COLUMNS)
    cv = pd.concat(parts, ignore_index=True)
    if "frequency_tracked" in cv:
        cv["frequency_per_rev"] = cv["frequency_tracked"]
    if "refinement" not in cv:
        cv["refinement"] = 0
    cv["x"] = x_values(name, cv)
    cv["damping"] = fn(cv)
    character = cv["dominant"] if "dominant" in cv else cv["label"]
    cv["same_character"] = _base_label(character) == _base_label(cv["label"])
    cv = cv.sort_values(["x"], kind="stable")
    order = {lab: i for i, lab in enumerate(labels)}
    cv = cv.sort_values("label", key=lambda s: s.map(order), kind="stable")
    return cv[_CURVE_COLUMNS].reset_index(drop=True)


def _runs(g: pd.DataFrame):
    """A name's curve (rows in the order of x) as the pieces a line may join.

    A line joins neighbouring points of one root only: where the name moves
    to another root (``track`` changes: an exceptional point between the two
    points) the line stops, and the next root's piece starts at its own point
    -- a line across would draw one root turning into another, which is what
    no root does.  Within a root, a segment is solid where both its points'
    identity is certain and dotted where either's is not; consecutive
    segments of one style make one run.  A root seen at one point only is a
    run of that point (its marker, if it is a sweep point, shows it).

    Yields
    ------
    (DataFrame, bool)
        The rows of a run and whether it is drawn solid (identity certain).
    """
    # a row no tracking linked (no track) is a piece of its own: NaN equals nothing
    track = pd.to_numeric(g["track"], errors="coerce").to_numpy(float)
    certain = g["certain"].to_numpy(bool)
    piece = np.concatenate([[0], np.cumsum(~(track[1:] == track[:-1]))])
    for r in range(piece[-1] + 1 if len(g) else 0):
        idx = np.flatnonzero(piece == r)
        if idx.size == 1:
            yield g.iloc[idx], bool(certain[idx[0]])
            continue
        solid = certain[idx[:-1]] & certain[idx[1:]]            # per segment
        cuts = np.flatnonzero(solid[1:] != solid[:-1]) + 1
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, solid.size], strict=True):
            yield g.iloc[idx[a]:idx[b] + 1], bool(solid[a])


def plot_modes(ax, name: str, table: pd.DataFrame, labels=PAPER_MODES,
               quantity: str = "damping", measure: str = "decay_rate",
               reference: pd.DataFrame | None = None, label_suffix: str = "",
               style=None, natural: pd.DataFrame | None = None, flutter: bool = True):
    """Frequency or damping of the tracked modes against the paper's x axis.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes to draw in.
    name : str
        Paper figure.
    table : DataFrame
        Sweep table.
    labels : tuple of str
        Modes to draw.
    quantity : {"damping", "frequency"}
        What to draw.
    measure : {"decay_rate", "damping_ratio"}
        Damping measure.
    reference : DataFrame, optional
        Digitised curves (``label, x, y``) drawn as black crosses.
    label_suffix : str
        Appended to each legend entry (to compare variants in one axes).
    style : dict, optional
        ``label -> (colour, marker, line style)``; default :data:`STYLE`.
    natural : DataFrame, optional
        Draw these natural frequencies (:func:`tefcore.paper.figures.runs.natural_frequencies`)
        instead of the table's.
    flutter : bool
        In a damping panel with the TEF, also mark the flutter root of each of
        the figure's points (the least stable root the flap takes part in,
        whichever mode it is) with black dots: where the flutter root is not
        the TEF branch, this is the root that goes unstable.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``. What the markers mean: :data:`tefcore.paper.figures.captions.MARKERS`.
    """
    xlabel, _ = AXES[name]
    cv = natural if natural is not None else curves(name, table, labels, measure)
    ycol = "frequency_per_rev" if quantity == "frequency" else "damping"
    doubt_shown = False
    for lab in labels:
        g = cv[cv["label"] == lab]
        if g.empty:
            continue
        color, marker, ls = (style or STYLE).get(lab, ("0.3", "o", "-"))
        ax.plot([], [], ls=ls, color=color, lw=1.4, label=f"{lab}{label_suffix}")
        for run, certain in _runs(g):
            if not certain and not doubt_shown:
                ax.plot([], [], ls=":", color=color, lw=1.4,
                        label="identity undecided (dotted)")
                doubt_shown = True
            ax.plot(run["x"], run[ycol], ls=ls if certain else ":", color=color, lw=1.4)
        main = g[g["refinement"] == 0]
        filled = main[main["same_character"] & main["certain"]]
        hollow = main[~main["same_character"] & main["certain"]]
        grey = main[~main["certain"]]
        ax.plot(filled["x"], filled[ycol], ls="none", marker=marker, color=color, ms=5)
        ax.plot(hollow["x"], hollow[ycol], ls="none", marker=marker, ms=5,
                markerfacecolor="white", markeredgecolor=color)
        ax.plot(grey["x"], grey[ycol], ls="none", marker=marker, ms=5,
                markerfacecolor="0.85", markeredgecolor=color)
    if flutter and quantity == "damping" and "TEF" in labels and table is not None \
            and "flutter_root" in table:
        fr = table[(table["status"] == "ok") & table["flutter_root"].fillna(False).astype(bool)
                   & (table["refinement"] == 0)]
        if not fr.empty:
            ax.plot(x_values(name, fr), MEASURES[measure][1](fr), "k.", ms=5, zorder=5,
                    label=flutter_legend(fr) + label_suffix)
    if reference is not None and not reference.empty:
        for lab, g in reference.groupby("label", sort=True):
            ax.plot(g["x"], g["y"], ls="none", marker="x", color="k", ms=6,
                    label=f"paper: {lab}")
    if quantity == "damping":
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel(MEASURES[measure][0])
    else:
        ax.set_ylabel("natural frequency [/rev]" if natural is not None
                      else "frequency [/rev]")
    ax.set_xlabel(xlabel)
    return ax


def plot_root_locus(ax, name: str, table: pd.DataFrame, labels=PAPER_MODES,
                    flutter: bool = True, style=None):
    """Root locus: real part against frequency of the tracked modes along the sweep.

    The classic picture of coalescence flutter: two roots approach in
    frequency and one of them turns towards (and across) the imaginary
    axis.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes to draw in.
    name : str
        Paper figure.
    table : DataFrame
        Sweep table.
    labels : tuple of str
        Modes to draw; arrows point in the direction of the swept parameter,
        the first point of each curve is a square.
    flutter : bool
        Also mark the flutter root of each point (the least stable root the
        flap takes part in) with black dots.
    style : dict, optional
        ``label -> (colour, marker, line style)``.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    cv = curves(name, table, labels)
    for lab in labels:
        g = cv[cv["label"] == lab]
        if len(g) < 2:
            continue
        color, _, ls = (style or STYLE).get(lab, ("0.3", "o", "-"))
        x, y = g["frequency_per_rev"].to_numpy(float), -g["damping"].to_numpy(float)
        ax.plot(x, y, ls=ls, color=color, lw=1.3, label=lab)
        ax.plot(x[0], y[0], "s", color=color, ms=5)
        step = max(1, len(x) // 5)
        for i in range(0, len(x) - 1, step):
            ax.annotate("", xy=(x[i + 1], y[i + 1]), xytext=(x[i], y[i]),
                        arrowprops={"arrowstyle": "->", "color": color, "lw": 1.2})
    if flutter and "flutter_root" in table:
        fr = table[(table["status"] == "ok") & table["flutter_root"].fillna(False).astype(bool)]
        freq = fr["frequency_tracked"] if "frequency_tracked" in fr else fr["frequency_per_rev"]
        ax.plot(freq, fr["real_part"], "k.", ms=4, label=flutter_legend(fr))
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel("frequency [/rev]")
    ax.set_ylabel("real part Re(s)/Ω [1/rev]  (> 0 unstable)")
    return ax


def flutter_legend(rows: pd.DataFrame) -> str:
    """The flutter root's legend entry, naming the modes it continues from.

    Parameters
    ----------
    rows : pandas.DataFrame
        The flutter root's rows (one per point), with ``label`` (the name: the
        uncoupled mode the root continues from).

    Returns
    -------
    str
        E.g. ``"flutter root (from blade torsion 2)"``; several names in order
        of the number of points, most first.

    Examples
    --------
    >>> flutter_legend(pd.DataFrame({"label": ["blade torsion 2"] * 3 + ["TEF"]}))
    'flutter root (from blade torsion 2, TEF)'
    """
    if "label" not in rows or rows.empty:
        return "flutter root"
    names = _base_label(rows["label"]).value_counts(sort=False)
    names = names.sort_values(ascending=False, kind="stable")
    return "flutter root (from " + ", ".join(names.index.astype(str)) + ")"


def plot_participation(ax, name: str, table: pd.DataFrame, label: str = "TEF"):
    """Participation by kind of coordinate along one mode (stacked).

    The shares are participation factors
    (:meth:`tefcore.floquet.FloquetResult.with_participation`), summing to 1
    at each point: how much of the mode's dynamics is the flap's, the blade
    torsion's, flap bending's and lag's.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes to draw in.
    name : str
        Paper figure.
    table : DataFrame
        Sweep table.
    label : str
        The mode (``"TEF"``: the TEF branch; ``"flutter root"``: the flutter
        root of each point; else a name).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    ok = table[table["status"] == "ok"]
    if label == "flutter root":
        rows = ok[ok["flutter_root"].fillna(False).astype(bool)]
    else:
        rows = ok[ok["label"].astype(str) == label].drop_duplicates("point")
    if "refinement" in rows:
        rows = rows[rows["refinement"] == 0]
    rows = rows.assign(x=x_values(name, rows)).sort_values("x")
    kinds = [k for k in ("TEF", "torsion", "flap", "lag") if f"share_{k}" in rows]
    colors = {"TEF": "C3", "torsion": "C1", "flap": "C0", "lag": "C2"}
    ax.stackplot(rows["x"], *[rows[f"share_{k}"] for k in kinds],
                 labels=[("flap (TEF)" if k == "TEF" else f"blade {k}") for k in kinds],
                 colors=[colors[k] for k in kinds], alpha=0.8)
    ax.set_ylim(0, 1)
    ax.set_ylabel(f"participation in the {label}" if label == "flutter root"
                  else f"participation in the {label} mode")
    ax.set_xlabel(AXES[name][0])
    return ax


def locus_figure(name: str, table: pd.DataFrame, labels=PAPER_MODES):
    """Root locus beside the participation in the TEF branch and in the flutter root.

    The classic picture of coalescence flutter, one per stability figure of
    the notebooks: :func:`plot_root_locus` (left), :func:`plot_participation`
    of the TEF branch (middle) and of the flutter root (right, titled with the
    modes it continues from), legends below.

    Parameters
    ----------
    name : str
        Paper figure.
    table : DataFrame
        Sweep table.
    labels : tuple of str
        Modes in the root locus.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    fig, (ax_l, ax_p, ax_f) = plt.subplots(1, 3, figsize=(15, 4.2))
    plot_root_locus(ax_l, name, table, labels=labels)
    ax_l.set_title("root locus (square: start, arrows: increasing x)", fontsize="medium")
    legend_below(ax_l)
    plot_participation(ax_p, name, table)
    ax_p.set_title("participation in the TEF branch", fontsize="medium")
    legend_below(ax_p, ncol=2)
    if "flutter_root" in table and table["flutter_root"].fillna(False).astype(bool).any():
        ok = table[(table["status"] == "ok") & table["flutter_root"].fillna(False).astype(bool)]
        plot_participation(ax_f, name, table, "flutter root")
        # wrapped to its axes' width: the modes it continues from made the title run
        # into the middle one's
        ax_f.set_title(textwrap.fill(flutter_legend(ok).replace(
            "flutter root", "participation in the flutter root", 1), 45), fontsize="medium")
        legend_below(ax_f, ncol=2)
    else:
        ax_f.set_axis_off()
    return fig
