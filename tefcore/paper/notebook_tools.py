"""Shared helpers of the numbered notebooks (``notebooks/01_*`` ... ``07_*``).

The few functions every notebook uses, so the notebooks stay short and
compute, plot, print and save the same way: ``setup_notebook``,
``figure_values``, ``run_stability_figure``, ``plot_modes``,
``mode_summary``, ``claims_table`` ...  The runner that executes the
notebooks and writes the report is :mod:`tefcore.paper.reproduce`.

Examples
--------
>>> figure_values("fig11", 3)
[0.75, 1.375, 2.0]
>>> figure_values("fig10", 3)
['150 lb/in', '475 lb/in', '800 lb/in']
"""

from __future__ import annotations

import math
import re
import warnings
from contextlib import contextmanager
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from ..safe_io import atomic_output


def _validation():
    """tefcore.paper.validation, or None where it cannot be imported."""
    try:
        from . import validation
    except ImportError:
        return None
    return validation


def deterministic_matplotlib() -> None:
    """rcParams that make saved figures byte-identical between runs."""
    import matplotlib as mpl

    mpl.rcParams.update({"svg.hashsalt": "tefcore", "pdf.compression": 6,
                         "figure.dpi": 80, "savefig.dpi": 110,
                         "figure.figsize": (6.4, 4.2), "axes.grid": True,
                         "grid.alpha": 0.3, "legend.fontsize": "small"})


def setup_notebook(output_dir) -> Path:
    """Create the output folder, fix seeds, printing and matplotlib settings."""
    import matplotlib.pyplot as plt

    np.random.seed(0)  # noqa: NPY002 -- the legacy global RNG, for user code in notebooks
    deterministic_matplotlib()
    plt.rcParams["figure.max_open_warning"] = 0
    pd.set_option("display.width", 120)
    pd.set_option("display.max_columns", 30)
    pd.set_option("display.max_colwidth", 60)
    out = Path(output_dir)
    out.mkdir(parents=True, exist_ok=True)
    return out


def savefig(fig, output_dir, stem: str) -> None:
    """Save ``fig`` as ``<output_dir>/<stem>.png`` with fixed metadata.

    Returns None, so that a notebook cell ending with it displays nothing
    extra (nbval executes cells without history, where IPython's trailing
    ``;`` does not suppress the result).
    """
    with atomic_output(Path(output_dir) / f"{stem}.png", "wb") as f:
        fig.savefig(f, format="png", metadata={"Software": None}, bbox_inches="tight")


def save_csv(df: pd.DataFrame, output_dir, stem: str) -> Path:
    """Write ``df`` as ``<output_dir>/<stem>.csv`` (10 significant digits)."""
    path = Path(output_dir) / f"{stem}.csv"
    with atomic_output(path, newline="") as f:
        df.to_csv(f, index=False, float_format="%.10g")
    return path


def base_config(aero_model: str = "thin_airfoil", overrides: dict | None = None):
    """MDART configuration with the chosen section aerodynamics.

    ``aero_model``: ``"thin_airfoil"`` (quasi-steady Theodorsen-type) or
    ``"table"`` (C81 look-up with the shipped *generated* example deck).
    """
    from ..c81 import example_deck_path
    from ..config_io import load_config

    cfg = load_config("mdart")
    if aero_model in ("table", "c81"):
        cfg = cfg.with_overrides({"model.aero_model": "c81",
                                  "model.c81_deck": str(example_deck_path())})
    elif aero_model != "thin_airfoil":
        raise ValueError(f"aero_model must be 'thin_airfoil' or 'table', got {aero_model!r}")
    return cfg.with_overrides(overrides) if overrides else cfg


def section_aero(aero_model: str, cfg=None):
    """Section model for the Fig. 5 hinge moment: ``"thin_airfoil"`` or ``"table"``
    (the shipped generated deck), with the flap geometry of ``cfg``."""
    from ..coupled import section_model

    cfg = base_config(aero_model) if cfg is None else cfg
    return section_model(base_config(aero_model).with_overrides({
        "flap.chord_ratio": cfg.flap.chord_ratio, "flap.overhang": cfg.flap.overhang}))


_NUM_UNIT = re.compile(r"^\s*([-+0-9.eE]+)\s*(.*)$")


def _split(value):
    if isinstance(value, str):
        m = _NUM_UNIT.match(value)
        if not m:
            raise ValueError(f"cannot read a number from {value!r}")
        return float(m.group(1)), m.group(2).strip()
    return float(value), ""


def figure_values(name: str, n_points: int | None = None, values=None,
                  claim_points: bool = True) -> list:
    """Sweep values of a figure: explicit ``values``, ``n_points`` evenly over the
    paper's range, or (both None) the paper's values of
    :data:`tefcore.paper.figures.FIGURES` plus (``claim_points``) the x values that
    the figure's value claims name -- the same sweep as
    :func:`tefcore.paper.validation.validate_all` runs."""
    from .figures import FIGURES

    if values is not None:
        return list(values)
    base = list(FIGURES[name].values)
    if n_points is None:
        return (_claim_sweep_values(name) if claim_points else None) or base
    n = int(n_points)
    if n < 2:
        raise ValueError(f"n_points must be at least 2, got {n_points!r}")
    (lo, unit), (hi, _) = _split(base[0]), _split(base[-1])
    grid = np.linspace(lo, hi, n)
    if unit:
        return [f"{v:.6g} {unit}" for v in grid]
    return [float(f"{v:.10g}") for v in grid]


def _claim_sweep_values(name: str):
    val = _validation()
    fn = getattr(val, "_sweep_values", None) if val is not None else None
    if fn is None:
        return None
    try:
        from .reference import load_claims

        mine = [c for c in load_claims() if c.figure == name and c.kind != "not_reproducible"]
        return fn(name, mine)
    except (ValueError, KeyError, FileNotFoundError):   # no or unusable reference data
        return None


def variant_key(overrides: dict) -> str:
    """Key of a configuration variant for :func:`claims_table` (validation's own)."""
    val = _validation()
    if val is not None and hasattr(val, "variant_key"):
        return val.variant_key(overrides)
    import json

    return json.dumps(overrides, sort_keys=True) if overrides else ""


def quiet_stability(cfg):
    """:func:`tefcore.stability.stability` with its numerical warnings counted,
    not printed (workers' stderr would otherwise reach the notebook); the count
    is the sweep column ``trim_numerical_warnings``."""
    from ..stability import stability

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = stability(cfg)
    trim = dict(res.trim)
    trim["numerical_warnings"] = len(caught)
    return SimpleNamespace(modes=res.modes, eigenvectors=res.eigenvectors, trim=trim,
                           vectors=res.vectors, periodic=res.periodic, system=res.system,
                           trim_result=res.trim_result)


def run_stability_figure(name: str, base=None, overrides: dict | None = None,
                         values=None, n_jobs: int = 1, cg_offset=None):
    """A stability figure's sweep: the caption's fixed parameters, then ``overrides``.

    Same as :func:`tefcore.paper.figures.run_figure` except that ``overrides``
    (e.g. another advance ratio) win over the caption, and warnings are
    counted instead of printed.  Returns the SweepResult.
    """
    from .figures import FIGURES, figure_config
    from ..sweep import sweep

    cfg = figure_config(name, base)
    if overrides:
        cfg = cfg.with_overrides(overrides)
    if cg_offset is not None:
        cfg = cfg.with_overrides({"flap.cg_offset": cg_offset})
    fig = FIGURES[name]
    vals = list(fig.values) if values is None else list(values)
    return sweep(cfg, fig.parameter, vals, point=quiet_stability, n_jobs=n_jobs,
                 progress=False)


#: x axis per figure: (label, function of the table's value column)
def _x_collective(v):
    return np.rad2deg(np.asarray(v, float))


AXES = {
    "fig3": ("collective pitch θ₀ [deg]", _x_collective),
    "fig4": ("collective pitch θ₀ [deg]", _x_collective),
    "fig8": ("flap overhang c_b/c_f", None),
    "fig9": ("flap CG offset c_cg/c_f (positive aft)", None),
    "fig10": ("pitch link stiffness [lb/in]", None),
    "fig11": ("torsional stiffness GJ / baseline GJ", None),
    "fig12": ("actuator stiffness / baseline (81.52 ft-lb/rad)",
              lambda v: np.array([_split(s)[0] for s in v]) / 81.52),
    "fig13": ("flap midspan location r/R", None),
    "fig14": ("flap length / R", None),
    "fig15": ("flap chord c_f/c", None),
    "fig16a": ("collective pitch θ₀ [deg]", _x_collective),
    "fig16b": ("collective pitch θ₀ [deg]", _x_collective),
    "fig17": ("advance ratio μ", None),
}


def x_values(name: str, table: pd.DataFrame) -> np.ndarray:
    """The paper's x-axis quantity for each row of a sweep table."""
    _, fn = AXES[name]
    v = table["value"].tolist()
    if fn is not None:
        return np.asarray(fn(v), float)
    return np.array([_split(s)[0] for s in v], float)


#: modes shown in the paper's damping panels
PAPER_MODES = ("TEF", "blade flap 1", "blade lag 1", "blade torsion 1")
_STYLE = {"TEF": ("C3", "o", "-"), "blade flap 1": ("C0", "s", "-"),
          "blade lag 1": ("C2", "^", "--"), "blade torsion 1": ("C1", "D", "-.")}
MEASURES = {
    "decay_rate": ("damping −Re(s)/Ω  [1/rev]  (> 0 stable)",
                   lambda t: -t["real_part"]),
    "damping_ratio": ("damping ratio ζ [%]  (> 0 stable)",
                      lambda t: 100 * t["damping_ratio"]),
}


def _base_label(s: pd.Series) -> pd.Series:
    return s.astype(str).str.removesuffix(" (locked)")


def curves(name: str, table: pd.DataFrame, labels=PAPER_MODES,
           measure: str = "decay_rate") -> pd.DataFrame:
    """One tracked curve per mode, for plotting and printing.

    ``"TEF"`` is the TEF branch of the sweep (the track of the flap mode at
    the sweep start, :func:`tefcore.sweep.sweep`); another mode ``m`` is the
    track labelled ``m`` or ``m (locked)`` that is present at the most
    points (ties: the exact label) -- the same choice as
    :mod:`tefcore.paper.validation`.  Columns ``label, track, x, frequency_per_rev``
    (continued along the track: whole /rev of a Floquet frequency are not
    allowed to jump), ``damping, same_character, certain, refinement``;
    ``same_character`` is False where the mode's own label at that point is
    another mode's (it exchanged character with it), ``certain`` is False
    from the first point where its identity could not be decided.
    """
    _, fn = MEASURES[measure]
    ok = table[table["status"] == "ok"].copy()
    ok["base"] = _base_label(ok["label"])
    parts = []
    for lab in labels:
        if lab == "TEF" and "tef_branch" in ok:
            g = ok[ok["tef_branch"].fillna(False).astype(bool)].copy()
            if g.empty:
                continue
            g["certain"] = g["tef_branch_certain"].fillna(False).astype(bool)
        else:
            sub = ok[ok["base"] == lab]
            if sub.empty:
                continue
            sizes = sub.groupby("track", sort=False).agg(n=("point", "size"),
                                                         first=("label", "first"))
            sizes = sizes.assign(exact=sizes["first"] == lab).sort_values(
                ["n", "exact"], ascending=False, kind="stable")
            g = sub[sub["track"] == sizes.index[0]].copy()
            ident = g["identity"] if "identity" in g else pd.Series("clear", index=g.index)
            g["certain"] = (ident != "ambiguous").cummin().to_numpy()
        g["label"] = lab
        parts.append(g)
    cols = ["label", "track", "x", "frequency_per_rev", "damping", "same_character",
            "certain", "refinement"]
    if not parts:
        return pd.DataFrame(columns=cols)
    cv = pd.concat(parts, ignore_index=True)
    if "frequency_tracked" in cv:
        cv["frequency_per_rev"] = cv["frequency_tracked"]
    if "refinement" not in cv:
        cv["refinement"] = 0
    cv["x"] = x_values(name, cv)
    cv["damping"] = fn(cv)
    cv["same_character"] = _base_label(cv["label_here"]) == cv["label"]
    cv = cv.sort_values(["x"], kind="stable")
    order = {lab: i for i, lab in enumerate(labels)}
    cv = cv.sort_values("label", key=lambda s: s.map(order), kind="stable")
    return cv[cols].reset_index(drop=True)


def natural_frequencies(name: str, values, base=None, overrides: dict | None = None,
                        labels=("blade flap 1", "blade lag 1", "blade torsion 1")):
    """Blade natural frequencies (:func:`tefcore.blade.blade_modes`, no aerodynamics,
    zero collective) at each sweep value: the "blade frequency" panels of
    Figs. 10a/11a, as the paper's stated frequencies (and the validation) use them."""
    from ..blade import blade_modes
    from .figures import FIGURES, figure_config

    cfg = figure_config(name, base)
    if overrides:
        cfg = cfg.with_overrides(overrides)
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


def plot_modes(ax, name: str, table: pd.DataFrame, labels=PAPER_MODES,
               quantity: str = "damping", measure: str = "decay_rate",
               reference: pd.DataFrame | None = None, label_suffix: str = "",
               style=None, natural: pd.DataFrame | None = None):
    """Frequency or damping of the tracked modes against the paper's x axis.

    Lines through every computed point (refinement points included), markers
    at the figure's own points. Hollow markers: the mode has the character of
    another mode there (it exchanged character in a coupling); a dotted line
    and grey markers: its identity is not certain there (a coalescence or an
    unresolved veering on the way).  ``natural``: plot these natural
    frequencies (:func:`natural_frequencies`) instead of the table's.
    ``reference``: digitised curves (``label, x, y``) drawn as black crosses.
    """
    xlabel, _ = AXES[name]
    cv = natural if natural is not None else curves(name, table, labels, measure)
    ycol = "frequency_per_rev" if quantity == "frequency" else "damping"
    doubt_shown = False
    for lab in labels:
        g = cv[cv["label"] == lab]
        if g.empty:
            continue
        color, marker, ls = (style or _STYLE).get(lab, ("0.3", "o", "-"))
        sure, unsure = g[g["certain"]], g[~g["certain"]]
        if not unsure.empty and not sure.empty:      # join the two parts
            unsure = pd.concat([sure.iloc[[-1]], unsure])
        ax.plot(sure["x"], sure[ycol], ls=ls, color=color, lw=1.4, label=f"{lab}{label_suffix}")
        if not unsure.empty:
            ax.plot(unsure["x"], unsure[ycol], ls=":", color=color, lw=1.4,
                    label=None if doubt_shown else "identity uncertain (dotted)")
            doubt_shown = True
        main = g[g["refinement"] == 0]
        filled = main[main["same_character"] & main["certain"]]
        hollow = main[~main["same_character"] & main["certain"]]
        grey = main[~main["certain"]]
        ax.plot(filled["x"], filled[ycol], ls="none", marker=marker, color=color, ms=5)
        ax.plot(hollow["x"], hollow[ycol], ls="none", marker=marker, ms=5,
                markerfacecolor="white", markeredgecolor=color)
        ax.plot(grey["x"], grey[ycol], ls="none", marker=marker, ms=5,
                markerfacecolor="0.85", markeredgecolor=color)
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
    axis.  Arrows point in the direction of the swept parameter; the first
    point of each curve is a square.  ``flutter``: also mark the flutter
    root of each point (the least stable root the flap takes part in) with
    black dots.
    """
    cv = curves(name, table, labels)
    for lab in labels:
        g = cv[cv["label"] == lab]
        if len(g) < 2:
            continue
        color, _, ls = (style or _STYLE).get(lab, ("0.3", "o", "-"))
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
        ax.plot(freq, fr["real_part"], "k.", ms=4, label="flutter root (each point)")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel("frequency [/rev]")
    ax.set_ylabel("real part Re(s)/Ω [1/rev]  (> 0 unstable)")
    return ax


def plot_participation(ax, name: str, table: pd.DataFrame, label: str = "TEF"):
    """Participation by kind of coordinate along one tracked mode (stacked).

    The shares are participation factors (:meth:`tefcore.floquet.FloquetResult.
    with_participation`), summing to 1 at each point: how much of the mode's
    dynamics is the flap's, the blade torsion's, flap bending's and lag's.
    """
    cv = curves(name, table, (label,))
    ok = table[table["status"] == "ok"]
    if label == "TEF" and "tef_branch" in ok:
        rows = ok[ok["tef_branch"].fillna(False).astype(bool)]
    else:
        rows = ok[ok["track"].isin(cv["track"].unique())]
    rows = rows.assign(x=x_values(name, rows)).sort_values("x")
    kinds = [k for k in ("TEF", "torsion", "flap", "lag") if f"share_{k}" in rows]
    colors = {"TEF": "C3", "torsion": "C1", "flap": "C0", "lag": "C2"}
    ax.stackplot(rows["x"], *[rows[f"share_{k}"] for k in kinds],
                 labels=[("flap (TEF)" if k == "TEF" else f"blade {k}") for k in kinds],
                 colors=[colors[k] for k in kinds], alpha=0.8)
    ax.set_ylim(0, 1)
    ax.set_ylabel(f"participation in the {label} mode")
    ax.set_xlabel(AXES[name][0])
    return ax


def mechanism_summary(cfg, x=None, name=None, root=None, knockouts=True,
                      digits: int = 3) -> pd.DataFrame:
    """:func:`tefcore.mechanism.mechanism` of one root, as a rounded table.

    ``name``/``x``: the figure's configuration at that x (its swept value);
    ``root``: the eigenvalue of the root (e.g. the TEF branch there), else
    the root the flap mode becomes (``mode="TEF"``).  Prints the kind and
    participation; returns ``term, contribution_real`` (terms with at least
    0.001 /rev, largest first) and the knockouts.
    """
    from .figures import FIGURES, figure_config
    from ..mechanism import mechanism

    if name is not None:
        cfg = figure_config(name, cfg).with_overrides({FIGURES[name].parameter: x})
    res = mechanism(cfg, mode="TEF" if root is None else "root", root=root,
                    knockouts=knockouts)
    print(f"{res.kind} at {res.eigenvalue.real:+.{digits}f} "
          f"{res.eigenvalue.imag:+.{digits}f}i /rev; participation: "
          + ", ".join(f"{k} {v:.2f}" for k, v in res.participation.items() if v >= 0.005))
    t = res.table
    terms = t[~t["term"].str.startswith(("total", "knockout"))]
    terms = terms[terms["contribution_real"].abs() >= 10 ** -digits]
    terms = terms.reindex(terms["contribution_real"].abs().sort_values(
        ascending=False, kind="stable").index)
    knock = t[t["term"].str.startswith("knockout")]
    out = pd.concat([terms, knock], ignore_index=True)[["term", "contribution_real"]]
    return clean(out.assign(contribution_real=out["contribution_real"].round(digits)))


def mode_summary(name: str, table: pd.DataFrame | None, labels=PAPER_MODES,
                 measure: str = "decay_rate", quantity: str = "damping",
                 digits: int = 3, natural: pd.DataFrame | None = None) -> pd.DataFrame:
    """Wide table (x by mode), rounded, for printing in checked cells."""
    cv = natural if natural is not None else curves(name, table, labels, measure)
    cv = cv[cv["refinement"] == 0]               # the figure's own points
    col = "frequency_per_rev" if quantity == "frequency" else "damping"
    wide = cv.pivot_table(index="x", columns="label", values=col, aggfunc="first",
                          sort=True)
    wide = wide[[c for c in labels if c in wide.columns]]
    wide.index = np.round(wide.index.to_numpy(float), 4)
    wide.index.name = AXES[name][0]
    wide.columns.name = None
    return clean(wide.round(digits))


def clean(df: pd.DataFrame) -> pd.DataFrame:
    """Replace ``-0.0`` by ``0.0`` (so printed tables do not flip sign)."""
    return df.apply(lambda c: c.mask(c == 0, 0.0) if c.dtype.kind == "f" else c)


def sign_changes(name: str, table: pd.DataFrame, label: str = "TEF",
                 measure: str = "decay_rate") -> list:
    """Where a mode's damping changes sign (:func:`tefcore.paper.curve_metrics.zero_crossings`
    of its real part, on the figure's own points), paper units."""
    from .curve_metrics import zero_crossings

    cv = curves(name, table, (label,), measure)
    cv = cv[cv["refinement"] == 0]
    out = []
    for _, g in cv.groupby("track", sort=True):
        x, y = g["x"].to_numpy(), -g["damping"].to_numpy()
        for x0, d in zero_crossings(x, y):
            out.append((round(float(x0), 3),
                        "stable -> unstable" if d == "destabilising" else "unstable -> stable"))
    return out


def report_identity(name: str, result) -> None:
    """A few deterministic lines on how the sweep's modes were identified.

    Where the TEF branch starts and how it was anchored, how many points the
    refinement added, where the branch's identity is undecided, and where
    the flutter root (least stable root the flap takes part in) is a root
    other than the TEF branch's.
    """
    t = result.table
    ok = t[t["status"] == "ok"]
    n_ref = ok.loc[ok["refinement"] > 0, "point"].nunique() if "refinement" in ok else 0
    anchor = getattr(result, "anchor", {}) or {}
    x = x_values(name, ok.assign(value=ok["value"])) if len(ok) else np.array([])
    ok = ok.assign(x=x)
    if not anchor:
        print(f"{name}: no TEF branch (no flap mode at the sweep start)")
        return
    start = ok[(ok["point"] == anchor["point"])]["x"].iloc[0]
    print(f"{name}: TEF branch anchored at x = {start:.4g} by {anchor['method']}; "
          f"{n_ref} points added where identities were ambiguous")
    branch = ok[ok["tef_branch"].fillna(False).astype(bool)]
    unsure = branch[~branch["tef_branch_certain"].fillna(False).astype(bool)]
    print("  TEF branch identity undecided from x = "
          + (f"{unsure['x'].min():.4g}" if not unsure.empty else "nowhere (decided throughout)"))
    fr = ok[ok["flutter_root"].fillna(False).astype(bool)]
    other = fr[~fr["tef_branch"].fillna(False).astype(bool) & (fr["refinement"] == 0)]
    if other.empty:
        print("  the flutter root is the TEF branch's root at every point")
    else:
        labs = sorted(set(other["label_here"].astype(str)))
        print(f"  the flutter root is another root at {len(other)} of "
              f"{int((fr['refinement'] == 0).sum())} points (labelled {', '.join(labs)})")


def explain(name: str, result, x: float, base=None, overrides: dict | None = None,
            which: str = "TEF branch", knockouts: bool = True) -> pd.DataFrame:
    """Why the TEF branch (or the flutter root) is (un)stable at the sweep point
    nearest ``x`` (paper units): :func:`mechanism_summary` of that root.

    ``which``: ``"TEF branch"`` or ``"flutter root"``.  Prints the point and
    the root's kind and participation; returns the terms' work and the
    knockouts (rounded, for checked cells).
    """
    from .figures import FIGURES, figure_config

    t = result.table
    col = "tef_branch" if which == "TEF branch" else "flutter_root"
    rows = t[(t["status"] == "ok") & t[col].fillna(False).astype(bool) & (t["refinement"] == 0)]
    if rows.empty:
        print(f"{name}: no {which} in the sweep")
        return pd.DataFrame(columns=["term", "contribution_real"])
    xs = x_values(name, rows)
    r = rows.iloc[int(np.argmin(np.abs(xs - x)))]
    cfg = figure_config(name, base)
    if overrides:
        cfg = cfg.with_overrides(overrides)
    cfg = cfg.with_overrides({FIGURES[name].parameter: r["value_si"]})
    print(f"{name}, {which} at x = {float(xs[int(np.argmin(np.abs(xs - x)))]):.4g} "
          f"(labelled {r['label_here']} there):")
    return mechanism_summary(cfg, root=complex(r["real_part"], r["frequency_per_rev"]),
                             knockouts=knockouts)


def theodorsen_c(k: float) -> complex:
    """Theodorsen's lift-deficiency function C(k) = H1(k) / (H1(k) + i H0(k))."""
    from scipy.special import hankel2

    return complex(hankel2(1, k) / (hankel2(1, k) + 1j * hankel2(0, k)))


def unsteadiness(name: str, result, base=None) -> None:
    """Print the TEF mode's reduced frequency at the flap and Theodorsen's C(k):
    how far from quasi-steady (C = 1) the flap mode of this sweep is."""
    from .figures import figure_config

    cfg = figure_config(name, base)
    t = result.table
    own = t[(t["status"] == "ok") & (_base_label(t["label_here"]) == "TEF")]
    if own.empty:
        print(f"{name}: no TEF mode in the sweep")
        return
    f = float(np.median(own["frequency_per_rev"]))   # where the mode is TEF-like itself
    # k = omega b / U with b = c/2 and U = x R Omega (hover speed at the flap midspan)
    k = f * cfg.rotor.chord / (2 * cfg.flap.midspan * cfg.rotor.radius)
    c = theodorsen_c(k)
    print(f"{name}: TEF mode at {f:.1f}/rev (median over the sweep) -> reduced frequency "
          f"k = {k:.2f} at {cfg.flap.midspan:.2f} R;")
    print(f"  Theodorsen C(k): |C| = {abs(c):.2f}, phase {np.degrees(np.angle(c)):.1f} deg "
          "(quasi-steady theory uses C = 1, phase 0)")


@contextmanager
def counted_warnings(what: str):
    """Collect the warnings of a block and print one deterministic line counting
    them by category (nothing when there are none), instead of a stderr flood."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield caught
    if caught:
        counts = pd.Series([w.category.__name__ for w in caught]).value_counts().sort_index()
        print(f"{what}: " + ", ".join(f"{n} {cat}" for cat, n in counts.items()))


def report_sweep(name: str, result) -> None:
    """One deterministic line: points, failures, points with numerical warnings."""
    t = result.table
    pts = t.drop_duplicates("point")
    n_warn = int((pts.get("trim_numerical_warnings", pd.Series(dtype=float)).fillna(0) > 0)
                 .sum())
    print(f"{name}: {len(pts)} points of {result.parameter}, "
          f"{int((pts['status'] != 'ok').sum())} failed, {n_warn} with numerical warnings")
    for row in result.failed.itertuples(index=False):
        print(f"  failed at {row.value}: {row.error}")


def claims_table(name: str, result, cfg=None, variants=None, others=None) -> pd.DataFrame:
    """:func:`tefcore.paper.validation.validate_figure` for one figure.

    ``variants``: ``{overrides dict as JSON (validation.variant_key): result}``
    of runs already made (e.g. Fig. 12's balanced flap); ``others``: figure
    name -> result, for claims comparing figures.  Anything else a claim needs
    is computed by the validation module.  Without reference data, one row
    saying so.
    """
    val = _validation()
    if val is not None:
        try:
            return val.validate_figure(name, result, cfg=cfg, variants=variants,
                                       others=others).reset_index(drop=True)
        except Exception as exc:
            if type(exc).__name__ != "ReferenceDataError":
                raise
            why = "no reference data (reference_data/claims.toml)"
    else:
        why = "tefcore.paper.validation is not installed"
    return pd.DataFrame([{"id": f"{name}-none", "figure": name, "statement": "",
                          "expected": "", "computed": "", "status": "not reproducible",
                          "reason": why, "tag": "", "recorded_status": ""}])


def reference_curves(name: str):
    """Digitised reference curves of a figure (``label, x, y``), or None."""
    val = _validation()
    fn = getattr(val, "reference_curves", None) if val is not None else None
    if fn is None:
        return None
    try:
        return fn(name)
    except (KeyError, FileNotFoundError, ValueError):
        return None


def show_claims(table: pd.DataFrame, width: int = 70) -> None:
    """Print a claims table compactly and deterministically (claim, status, computed)."""
    if table.empty:
        print("no claims for this figure")
        return
    t = table.copy()
    if "computed" in t:
        t["computed"] = [_fmt(v) for v in t["computed"]]
    cols = [c for c in ("id", "status", "computed") if c in t.columns]
    with pd.option_context("display.max_colwidth", width, "display.width", 200):
        print(t[cols or list(t.columns)].to_string(index=False))


_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])")


def _round_number(text: str) -> str:
    v = float(text)
    if abs(v) < 1e-9:          # round-off (e.g. 2.2e-16 for "unchanged"): not a result
        return "0"
    return f"{v:.4g}"


def _fmt(v) -> str:
    """A value printed with 4 significant digits; |x| < 1e-9 (round-off) as 0."""
    if isinstance(v, float | np.floating):
        return "nan" if math.isnan(v) else _round_number(repr(float(v)))
    return _NUMBER.sub(lambda m: _round_number(m.group()), str(v))
