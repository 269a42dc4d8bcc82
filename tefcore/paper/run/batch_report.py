"""The comparison report of a batch: the runs side by side, per figure.

What a teacher or reviewer looks at after ``tefcore batch``
(:mod:`tefcore.paper.run.batch`): one row per run with what it set, whether it
ran, its claims score, and for every stability figure the **headline
results** read from the sweep tables the notebooks wrote
(``OUT/<run>/<notebook>/figNN_modes.csv``); then, per figure, the runs'
curves overlaid.

Headline results (:func:`headlines`), for two roots of each figure's sweep:

* the **flutter root** (the sweep tables' ``flutter_root`` rows: at each
  point the least stable flap-induced root, the root that goes unstable
  whichever mode it comes from), and
* the **TEF branch** (``tef_branch`` rows where ``tef_branch_certain``: the
  root each point names TEF, the flap's own mode continued from zero
  coupling, where that name is certain);

each gives ``onset``, the x of its first stable-to-unstable crossing
(:func:`tefcore.paper.claims.curves.zero_crossings`, linear between the
computed points, refinement points included), ``state`` (``"stable"`` or
``"unstable"`` throughout, ``"crosses"`` from stable, ``"unstable at
start"``: it crosses, starting unstable) and ``max_growth``, its largest
growth rate Re(s)/Omega [1/rev] (positive: unstable) with the x where it
occurs.  x is the paper's axis of the figure
(:data:`tefcore.paper.figures.plotting.AXES`).

Files: ``OUT/index.html`` (self-contained, figures embedded, responsive),
``OUT/index.md``, ``OUT/runs.csv`` (one row per run: ``run``, ``status``,
``error``, ``notebooks``, the settings, ``passed``, ``total``, ``worse``,
then ``<figure>.<root>_<result>`` columns), ``OUT/headlines.csv`` (tidy: one
row per run, figure and root) and ``OUT/figures/<figure>.png``.  Everything
is deterministic: run times are not written.

Examples
--------
>>> import pandas as pd
>>> t = pd.DataFrame({"status": "ok", "value": [0.0, 0.1, 0.2], "real_part": [-1., 1., 2.],
...                   "flutter_root": True, "tef_branch": False,
...                   "tef_branch_certain": False})
>>> h = headlines("fig9", t)
>>> h["flutter root"]["onset"], h["flutter root"]["max_growth"], h["TEF branch"]["state"]
(0.05, 2.0, 'no data')
"""

from __future__ import annotations

import base64
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ...safe_io import atomic_output, atomic_write_text, check_output_folder
from ..claims.curves import stability_intervals, zero_crossings
from ..figures.plotting import (
    AXES,
    MEASURES,
    deterministic_matplotlib,
    savefig,
    x_values,
)
from .report import FIGURE_TITLES, template_environment

__all__ = ["ROOTS", "Comparison", "FigurePanel", "comparison", "headlines", "render_comparison",
           "run_curves", "write_comparison"]

#: The roots whose headline results are compared: name -> sweep-table role column.
ROOTS = {"flutter root": "flutter_root", "TEF branch": "tef_branch"}
_TABLE = re.compile(r"fig(\d+[ab]?)_modes\.csv\Z")
_PAPER_ORDER = list(FIGURE_TITLES)
#: Columns of headlines.csv.
_LONG = ("run", "figure", "x_axis", "root", "onset", "state", "max_growth", "max_growth_at",
         "points", "stable_in")


def _rows(name: str, table: pd.DataFrame, root: str) -> pd.DataFrame:
    """x (the paper's axis) and real part of one root along a sweep, sorted by x."""
    col = ROOTS[root]
    if col not in table or "real_part" not in table:
        return pd.DataFrame(columns=["x", "real_part"])
    ok = table[(table["status"] == "ok") & table[col].fillna(False).astype(bool)]
    if root == "TEF branch" and "tef_branch_certain" in ok:
        ok = ok[ok["tef_branch_certain"].fillna(False).astype(bool)]
    if ok.empty:
        return pd.DataFrame(columns=["x", "real_part"])
    out = pd.DataFrame({"x": x_values(name, ok), "real_part": ok["real_part"].to_numpy(float)})
    out = out[np.isfinite(out["x"]) & np.isfinite(out["real_part"])]
    return out.drop_duplicates("x").sort_values("x", kind="stable").reset_index(drop=True)


def _interval(a: float, b: float) -> str:
    fa, fb = f"{a:.3g}", f"{b:.3g}"
    return f"near {fa}" if fa == fb else f"{fa} to {fb}"


def headlines(name: str, table: pd.DataFrame) -> dict:
    """Onset and largest growth of the flutter root and the TEF branch along one sweep.

    Parameters
    ----------
    name : str
        The paper figure (``"fig9"``): its x axis.
    table : DataFrame
        Its sweep table (``figNN_modes.csv``: ``status``, ``value``
        (``value_si``), ``real_part``, ``flutter_root``, ``tef_branch``,
        ``tef_branch_certain``).

    Returns
    -------
    dict
        ``{root: {"onset", "state", "max_growth", "max_growth_at", "points",
        "stable_in"}}`` for each of :data:`ROOTS` (module docstring; ``stable_in``
        the x intervals where the root is stable, as text); NaN where there is
        no such value, ``state = "no data"`` without rows.
    """
    out = {}
    for root in ROOTS:
        r = _rows(name, table, root)
        if r.empty:
            out[root] = {"onset": np.nan, "state": "no data", "max_growth": np.nan,
                         "max_growth_at": np.nan, "points": 0, "stable_in": ""}
            continue
        x, y = r["x"].to_numpy(float), r["real_part"].to_numpy(float)
        onset = next((x0 for x0, d in zero_crossings(x, y) if d == "destabilising"), np.nan)
        state = "stable" if (y < 0).all() else "unstable" if (y >= 0).all() else \
            "unstable at start" if y[0] >= 0 else "crosses"
        k = int(np.argmax(y))
        stable = "; ".join(_interval(a, b) for a, b in stability_intervals(x, y, "stable"))
        out[root] = {"onset": float(onset), "state": state, "max_growth": float(y[k]),
                     "max_growth_at": float(x[k]), "points": len(x), "stable_in": stable}
    return out


def run_curves(folder, notebooks) -> dict:
    """The sweep tables a run's notebooks wrote, by paper figure.

    Parameters
    ----------
    folder : path
        The run's folder (``<notebook>/figNN_modes.csv`` in it).
    notebooks : sequence of str
        Its notebooks.

    Returns
    -------
    dict
        ``{figure: DataFrame}`` for every readable ``figNN_modes.csv``
        (``fig09_modes.csv`` -> ``"fig9"``), in the paper's order.
    """
    found = {}
    for nb in notebooks:
        sub = Path(folder) / nb
        for path in sorted(sub.glob("fig*_modes.csv")) if sub.is_dir() else []:
            m = _TABLE.match(path.name)
            if not m:
                continue
            fig = "fig" + m.group(1).lstrip("0")
            try:
                found[fig] = pd.read_csv(path)
            except (OSError, ValueError, pd.errors.ParserError):
                continue
    order = {f: i for i, f in enumerate(_PAPER_ORDER)}
    return dict(sorted(found.items(), key=lambda kv: order.get(kv[0], len(order))))


@dataclass
class FigurePanel:
    """One paper figure in the comparison: the runs' curves overlaid, and their headlines.

    Parameters
    ----------
    key : str
        The paper figure (``"fig9"``), also the HTML anchor.
    title : str
        The paper's caption of it.
    xlabel : str
        Its x axis.
    image : str
        The overlay PNG, base64 (embedded in the HTML page).
    src : str
        The PNG's path relative to the report (``figures/fig9.png``).
    caption : str
        What the panels show.
    rows : list of dict
        One per run that computed the figure: ``run``, ``link`` and, for
        each root, its onset and largest growth as text.
    """

    key: str
    title: str
    xlabel: str
    image: str
    src: str
    caption: str
    rows: list = field(default_factory=list)


@dataclass
class Comparison:
    """What the comparison report shows (rendered by :func:`render_comparison`).

    Parameters
    ----------
    title : str
        Page title.
    intro : str
        What the page shows (plain text).
    version : str
        tefcore's version.
    counts : dict
        Runs by status (``{"ok": n, "failed": n}``).
    common : list of tuple
        Settings every run shares: ``(name, value text)``.
    columns : list of str
        Settings that differ between runs (the run table's columns).
    runs : list of dict
        One per run: ``name``, ``link`` (its report), ``status``, ``css``,
        ``error``, ``notebooks``, ``settings`` (text per column of
        ``columns``), ``score`` (``"2 / 5"``) and ``worse``.
    panels : list of FigurePanel
        One per paper figure any run computed, in the paper's order.
    """

    title: str
    intro: str
    version: str
    counts: dict
    common: list
    columns: list
    runs: list
    panels: list


def _text(value) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _onset_text(h: dict) -> str:
    if h["state"] == "no data":
        return "–"
    if h["state"] == "unstable at start":
        return f"unstable except {h['stable_in']}"
    if np.isfinite(h["onset"]):
        return f"{h['onset']:.3g}"
    return "stable throughout" if h["state"] == "stable" else "unstable throughout"


def _growth_text(h: dict) -> str:
    if h["state"] == "no data":
        return "–"
    return f"{h['max_growth']:+.3f} at {h['max_growth_at']:.3g}"


def _short_setting(key: str, value) -> str:
    """``overrides.flap.overhang`` = 0.2 -> ``overhang=0.2`` (as in the grid's run names)."""
    return f"{key.rpartition(':')[2].rpartition('.')[2]}={_text(value)}"


def _groups(fig: str, curves: list[tuple[str, pd.DataFrame]], settings: dict, varying) -> list:
    """Runs whose two curves are identical, drawn once: ``[(label, [runs], table)]``.

    Runs that differ only in what the figure does not depend on (in a grid,
    the swept field itself: Fig. 9 sweeps the CG offset, so the runs'
    CG offsets do not change it) give identical curves, which would hide one
    another.  A group is labelled with the settings its runs share, e.g.
    ``overhang=0.2 (3 runs)``.
    """
    groups: dict[bytes, list] = {}
    for run, table in curves:
        key = b"|".join(_rows(fig, table, root).to_numpy(float).tobytes() for root in ROOTS)
        groups.setdefault(key, []).append((run, table))
    out = []
    for members in groups.values():
        runs = [r for r, _ in members]
        if len(runs) == 1:
            label = runs[0]
        else:
            shared = [_short_setting(k, settings[runs[0]].get(k)) for k in varying
                      if len({repr(settings[r].get(k)) for r in runs}) == 1]
            label = (", ".join(shared) if shared else f"{runs[0]}, ...") + \
                f" ({len(runs)} runs)"
        out.append((label, runs, members[0][1]))
    return out


def _overlay(out: Path, fig: str, groups: list) -> Path:
    """The runs' flutter root and TEF branch damping against the figure's x, overlaid."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deterministic_matplotlib()
    n = len(groups)
    colours = plt.get_cmap("tab10")(np.arange(n) % 10) if n <= 10 else \
        plt.get_cmap("viridis")(np.linspace(0, 0.92, n))
    fig_, axes = plt.subplots(1, 2, figsize=(9.0, 3.9), sharex=True, sharey=True)
    for ax, root in zip(axes, ROOTS, strict=True):
        for (label, _, table), colour in zip(groups, colours, strict=True):
            r = _rows(fig, table, root)
            if r.empty:
                continue
            ax.plot(r["x"], -r["real_part"], "-", marker=".", ms=3, color=colour, lw=1.2,
                    label=label if root == "flutter root" else None)
            h = headlines(fig, table)[root]
            if np.isfinite(h["onset"]):
                ax.plot([h["onset"]], [0.0], "v", color=colour, ms=7, mec="k", mew=0.5)
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_title(root, fontsize="medium")
        ax.set_xlabel(AXES.get(fig, (fig,))[0])
    axes[0].set_ylabel(MEASURES["decay_rate"][0])
    fig_.legend(loc="outside lower center", ncol=min(3, max(1, n)), frameon=False,
                fontsize="small")
    fig_.suptitle(FIGURE_TITLES.get(fig, fig), fontsize="medium")
    folder = out / "figures"
    check_output_folder(folder, "batch figures", create=True)
    savefig(fig_, folder, fig, figure=fig)
    plt.close(fig_)
    return folder / f"{fig}.png"


def comparison(out, outcomes, title: str = "tefcore batch comparison") -> tuple:
    """The comparison model, the run table and the tidy headline table of a batch.

    Writes the overlay PNGs (``out/figures/<figure>.png``).

    Parameters
    ----------
    out : path
        The batch's output folder.
    outcomes : list of tefcore.paper.run.batch.RunOutcome
        The runs, in the batch file's order (``spec``, ``status``,
        ``error``, ``claims``).
    title : str
        The page title.

    Returns
    -------
    tuple
        ``(Comparison, runs DataFrame, headlines DataFrame)``.
    """
    from ... import __version__

    out = Path(out)
    keys = []
    for o in outcomes:
        keys += [k for k in o.spec.settings if k not in keys]
    varying = [k for k in keys if len({repr(o.spec.settings.get(k, "(unset)"))
                                       for o in outcomes}) > 1]
    common = [(k, _text(outcomes[0].spec.settings[k])) for k in keys if k not in varying]
    tables = {o.spec.name: run_curves(out / o.spec.name, o.spec.notebooks) for o in outcomes}
    rows, long, view = [], [], []
    for o in outcomes:
        row, headline_rows = _run_row(o, keys, tables[o.spec.name])
        rows.append(row)
        long += headline_rows
        view.append(_run_view(o, varying))
    figs = [f for f in _PAPER_ORDER if any(f in t for t in tables.values())]
    panels = [_figure_panel(out, fig, outcomes, tables, varying) for fig in figs]
    counts = {s: sum(o.status == s for o in outcomes) for s in ("ok", "failed")}
    model = Comparison(
        title=title,
        intro=("Each row is one run of the batch: the notebooks executed with that run's "
               "parameters (its own report is linked). Headline results come from the sweep "
               "tables the notebooks wrote: for each figure, the x at which the flutter root "
               "and the TEF branch turn unstable (onset) and their largest growth rate "
               "Re(s)/Ω in 1/rev (positive: unstable) with the x where it occurs. The claims "
               "score counts the paper's validation claims that still pass; a batch changes "
               "the rotor on purpose, so a lower score is a result, not a failure."),
        version=__version__, counts=counts, common=common, columns=varying, runs=view,
        panels=panels)
    runs_df = pd.DataFrame(rows)
    long_df = pd.DataFrame(long, columns=list(_LONG))
    return model, runs_df, long_df


def _run_row(o, keys, tables: dict) -> tuple[dict, list]:
    """One run's row of ``runs.csv`` (settings, score, each figure's headlines) and its rows
    of the tidy ``headlines.csv``."""
    claims = o.claims or {}
    row = {"run": o.spec.name, "status": o.status, "error": o.error,
           "notebooks": " ".join(o.spec.notebooks),
           **{k: o.spec.settings.get(k) for k in keys},
           "passed": claims.get("passed"), "total": claims.get("total"),
           "worse": claims.get("worse")}
    long = []
    for fig, table in tables.items():
        for root, h in headlines(fig, table).items():
            tag = "flutter" if root == "flutter root" else "tef"
            row.update({f"{fig}.{tag}_onset": h["onset"], f"{fig}.{tag}_state": h["state"],
                        f"{fig}.{tag}_max_growth": h["max_growth"],
                        f"{fig}.{tag}_max_growth_at": h["max_growth_at"]})
            long.append({"run": o.spec.name, "figure": fig,
                         "x_axis": AXES.get(fig, (fig,))[0], "root": root,
                         **{k: h[k] for k in _LONG[4:]}})
    return row, long


def _run_view(o, varying) -> dict:
    """One run's row of the comparison page: link, status, the settings that vary, score."""
    claims = o.claims or {}
    return {"name": o.spec.name, "link": f"{o.spec.name}/report.html",
            "status": o.status, "css": "pass" if o.status == "ok" else "fail",
            "error": o.error, "notebooks": " ".join(n[:2] for n in o.spec.notebooks),
            "settings": [_text(o.spec.settings.get(k, "–")) for k in varying],
            "score": f"{claims['passed']} / {claims['total']}" if claims else "–",
            "worse": claims.get("worse", "–")}


def _figure_panel(out: Path, fig: str, outcomes, tables: dict, varying) -> FigurePanel:
    """One figure's overlay of every run's curves (its PNG written) and its headline rows."""
    curves = [(o.spec.name, tables[o.spec.name][fig]) for o in outcomes
              if fig in tables[o.spec.name]]
    groups = _groups(fig, curves, {o.spec.name: o.spec.settings for o in outcomes}, varying)
    png = _overlay(out, fig, groups)
    label_of = {run: label for label, runs, _ in groups for run in runs}
    prow = []
    for run, table in curves:
        h = headlines(fig, table)
        prow.append({"run": run, "link": f"{run}/report.html#{fig}",
                     "curve": label_of[run] if len(groups) < len(curves) else "",
                     **{f"{tag}_{what}": fn(h[root]) for root, tag in
                        (("flutter root", "flutter"), ("TEF branch", "tef"))
                        for what, fn in (("onset", _onset_text), ("growth", _growth_text))}})
    return FigurePanel(
        key=fig, title=FIGURE_TITLES.get(fig, fig), xlabel=AXES.get(fig, (fig,))[0],
        image=base64.b64encode(png.read_bytes()).decode("ascii"),
        src=png.relative_to(out).as_posix(),
        caption=(f"Damping −Re(s)/Ω [1/rev] of the flutter root (left: at each point the "
                 f"least stable flap-induced root, so the curve jumps where another root "
                 f"becomes the least stable) and of the TEF mode (right: the root the "
                 f"flap's own mode continues into, where that name is certain) against "
                 f"{AXES.get(fig, (fig,))[0]}, one colour per run"
                 + (" (runs with identical curves drawn once, labelled with the settings "
                    "they share)" if len(groups) < len(curves) else "")
                 + "; a triangle on the zero line marks where the root turns unstable "
                   "(onset)."),
        rows=prow)


def _breakable(text: str):
    """A dotted name that may wrap after each dot (table headers at 800 px)."""
    from markupsafe import Markup, escape

    return Markup("<wbr>").join(escape(part) for part in re.split(r"(?<=[.:])", str(text)))


def render_comparison(model: Comparison, fmt: str = "html") -> str:
    """The comparison as ``"html"`` (self-contained, responsive) or ``"md"``.

    Parameters
    ----------
    model : Comparison
        What to show.
    fmt : {"html", "md"}
        Output format.

    Returns
    -------
    str
        The page (jinja2 templates ``batch.html.j2``, ``batch.md.j2``).

    Raises
    ------
    ValueError
        Another format.
    """
    if fmt not in ("html", "md"):
        raise ValueError(f"format must be 'html' or 'md', got {fmt!r}")
    return template_environment(breakable=_breakable).get_template(
        f"batch.{fmt}.j2").render(c=model)


def write_comparison(out, outcomes, title: str = "tefcore batch comparison") -> tuple:
    """Write ``index.md``, ``index.html``, ``runs.csv``, ``headlines.csv`` and the figures.

    Parameters
    ----------
    out : path
        The batch's output folder.
    outcomes : list of tefcore.paper.run.batch.RunOutcome
        The runs.
    title : str
        The page title.

    Returns
    -------
    tuple of pathlib.Path
        ``(index.md, index.html, runs.csv)``.
    """
    out = Path(out)
    model, runs_df, long_df = comparison(out, outcomes, title)
    paths = out / "index.md", out / "index.html", out / "runs.csv"
    atomic_write_text(paths[0], render_comparison(model, "md"))
    atomic_write_text(paths[1], render_comparison(model, "html"))
    for df, path in ((runs_df, paths[2]), (long_df, out / "headlines.csv")):
        with atomic_output(path, newline="") as f:
            df.to_csv(f, index=False, float_format="%.6g")
    return paths
