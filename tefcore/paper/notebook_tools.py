"""Everything the numbered notebooks use, under one short name (``nt``).

The notebooks (``tefcore notebooks --copy DIR`` gives editable copies) import
this module as ``nt`` so that a reader sees one vocabulary; the functions live
where they belong and are re-exported here:

* running a figure -- :mod:`tefcore.paper.figures.runs` (:func:`base_config`,
  :func:`run_config`, :func:`quiet_stability` -- the point
  function the notebooks' sweeps use --,
  :func:`natural_frequencies`, :func:`section_aero`);
* plotting -- :mod:`tefcore.paper.figures.plotting` (:func:`plot_modes`,
  :func:`plot_root_locus`, :func:`plot_participation`, :func:`legend_below`,
  :func:`savefig`) and :mod:`tefcore.paper.figures.captions` (:func:`figure_title`,
  :func:`figure_caption`, :func:`conditions`);
* printed summaries for checked cells -- :mod:`tefcore.paper.summaries`
  (:func:`mode_summary`, :func:`sign_changes`, :func:`report_identity`,
  :func:`explain`, :func:`unsteadiness`, :func:`claims_table`, ...);
* the shared departures text -- :func:`show_departures`;
* the interactive root map -- :func:`explore`.

Defined here are the notebook's own frame -- :func:`setup_notebook` (its
first cell), :func:`save_csv` and :func:`check_and_save` (its last: the
paper's claims checked, printed and saved with the notebook's tables) -- and
the three views every stability figure gets after its sweep:
:func:`damping_figure` (the paper's damping panel), :func:`which_root` (the
identity report and the root locus) and :func:`damping_summary` (the printed
table and where the TEF branch changes sign).

Examples
--------
>>> figure_values("fig11", 3)
[0.75, 1.375, 2.0]
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ..runtime import apply_defaults
from ..safe_io import atomic_output
from .attribution.departures import departures_text, show_departures
from .claims.truncation import load_converged, mark_truncation
from .claims.validation import figure_values
from .claims.variants import apply_variant
from .explorer import explore
from .figures.captions import (
    LOCUS_CAPTION,
    MARKERS,
    conditions,
    figure_caption,
    figure_title,
    flight_condition,
)
from .figures.catalogue import variant_key
from .figures.plotting import (
    AXES,
    MEASURES,
    PAPER_MODES,
    STYLE,
    curves,
    deterministic_matplotlib,
    legend_below,
    locus_figure,
    plot_modes,
    plot_participation,
    plot_root_locus,
    savefig,
    x_values,
)
from .figures.runs import (
    base_config,
    natural_frequencies,
    quiet_stability,
    run_config,
    section_aero,
)
from .summaries import (
    claims_table,
    clean,
    counted_warnings,
    explain,
    format_value,
    mechanism_summary,
    mode_summary,
    reference_curves,
    report_identity,
    report_sweep,
    show_claims,
    sign_changes,
    unsteadiness,
)

__all__ = ["AXES", "LOCUS_CAPTION", "MARKERS", "MEASURES", "PAPER_MODES", "STYLE", "base_config",
           "check_and_save", "claims_table", "clean", "conditions", "counted_warnings", "curves",
           "damping_figure", "damping_summary",
           "departures_text", "deterministic_matplotlib", "explain", "explore",
           "figure_caption", "figure_title", "figure_values", "flight_condition",
           "format_value", "legend_below", "locus_figure",
           "mechanism_summary", "mode_summary", "natural_frequencies", "plot_modes",
           "plot_participation", "plot_root_locus", "quiet_stability", "reference_curves",
           "report_identity", "report_sweep", "run_config",
           "save_csv", "savefig", "section_aero", "setup_notebook", "show_claims",
           "show_departures", "sign_changes", "unsteadiness", "variant_key", "which_root",
           "x_values"]


def setup_notebook(output_dir) -> Path:
    """Prepare a notebook run: process settings, seeds, printing, matplotlib, output folder.

    Applies tefcore's process settings (:func:`tefcore.runtime.apply_defaults`:
    the notebook's kernel is a process tefcore owns), seeds numpy's legacy
    global generator, makes saved figures byte-identical
    (:func:`deterministic_matplotlib`) and creates ``output_dir``.

    Parameters
    ----------
    output_dir : path
        Folder for the notebook's CSV, PNG and claims files.

    Returns
    -------
    pathlib.Path
        ``output_dir``.
    """
    import matplotlib.pyplot as plt

    apply_defaults()
    np.random.seed(0)  # noqa: NPY002 -- the legacy global RNG, for user code in notebooks
    deterministic_matplotlib()
    plt.rcParams["figure.max_open_warning"] = 0
    pd.set_option("display.width", 120)
    pd.set_option("display.max_columns", 30)
    pd.set_option("display.max_colwidth", 60)
    out = Path(output_dir)
    out.mkdir(parents=True, exist_ok=True)
    return out


def save_csv(df: pd.DataFrame, output_dir, stem: str) -> Path:
    """Write ``df`` as ``<output_dir>/<stem>.csv`` (10 significant digits), atomically.

    Parameters
    ----------
    df : DataFrame
        The table.
    output_dir : path
        Existing folder.
    stem : str
        File name without suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(output_dir) / f"{stem}.csv"
    with atomic_output(path, newline="") as f:
        df.to_csv(f, index=False, float_format="%.10g")
    return path


def check_and_save(out, results: dict, *, cfg=None, variants=None, tables=None) -> pd.DataFrame:
    """A notebook's tail: the paper's claims about its figures checked, printed, saved.

    Checks the claims of every figure in `results` (:func:`claims_table`,
    each with the others' results for claims that compare figures), prints
    them (:func:`show_claims`), writes ``claims.csv`` and each of `tables`
    into `out` (:func:`save_csv`), and prints the names of the files the
    notebook wrote there (those and its figures).

    Parameters
    ----------
    out : pathlib.Path
        The notebook's output folder (:func:`setup_notebook`).
    results : dict
        Paper figure -> its result, in the notebook's order.
    cfg : tefcore.config.configuration.Config, optional
        Base configuration of runs the validation adds; on a packaged variant
        other than the default (``mdart-fig6``) its calibration claims are
        tagged and its recorded statuses used (:func:`tefcore.paper.claims.variants.apply_variant`).
    variants : dict, optional
        Figure -> ``{variant_key(overrides): result}`` of runs already made.
    tables : dict, optional
        File stem -> DataFrame: the notebook's result tables.

    Returns
    -------
    pandas.DataFrame
        The claims, as saved.
    """
    variants = variants or {}
    claims = pd.concat([claims_table(name, result, cfg=cfg, others=results,
                                     variants=variants.get(name))
                        for name, result in results.items()], ignore_index=True)
    # on a packaged variant, its calibration claims and recorded statuses
    claims = apply_variant(claims, cfg)
    # each claim's verdict on its figure's converged basis, where one is stored
    # for this configuration: a verdict that differs is truncation-dependent
    claims = mark_truncation(claims, load_converged(cfg if cfg is not None else base_config()))
    show_claims(claims)
    written = [save_csv(claims, out, "claims")]
    written += [save_csv(df, out, stem) for stem, df in (tables or {}).items()]
    print(sorted(p.name for p in written + sorted(Path(out).glob("*.png"))))
    return claims


def _stem(name: str) -> str:
    """The file stem of a figure's PNG: ``fig08`` for ``fig8``, ``fig16a`` kept."""
    number = name.removeprefix("fig")
    digits = "".join(ch for ch in number if ch.isdigit())
    return f"fig{int(digits):02d}{number[len(digits):]}"


def damping_figure(name: str, result, cfg, output_dir, measure: str,
                   what: str = "Damping of the blade modes and the TEF branch") -> None:
    """The paper's damping panel of a stability figure, saved as ``OUTPUT/figNN.png``.

    The tracked modes' damping against the swept field on the paper's axes, the
    paper's digitised curves where the reference data has them, the figure's
    title and caption written from ``cfg``.

    Parameters
    ----------
    name : str
        The paper figure (``"fig15"``).
    result : tefcore.sweeps.sweep.SweepResult
        Its sweep.
    cfg : tefcore.config.configuration.Config
        The configuration it ran (:func:`run_config`).
    output_dir : path
        The notebook's output folder.
    measure : str
        ``"decay_rate"`` or ``"damping_ratio"``.
    what : str, optional
        What the panel shows, for the caption.
    """
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    plot_modes(ax, name, result.table, measure=measure, reference=reference_curves(name))
    ax.set_title(figure_title(name, cfg, width=110), fontsize="medium")
    legend_below(ax)
    savefig(fig, output_dir, _stem(name), figure=name,
            caption=figure_caption(name, cfg, what))


def which_root(name: str, result, cfg, output_dir, labels=PAPER_MODES) -> None:
    """Which root is which along a figure's sweep: the identity report and the root locus.

    Prints :func:`report_identity` (the TEF branch and the flutter root, where
    names exchange) and saves :func:`locus_figure` of the modes ``labels`` as
    ``OUTPUT/figNN_locus.png``.

    Parameters
    ----------
    name : str
        The paper figure.
    result : tefcore.sweeps.sweep.SweepResult
        Its sweep.
    cfg : tefcore.config.configuration.Config
        The configuration it ran.
    output_dir : path
        The notebook's output folder.
    labels : sequence of str, optional
        The modes drawn (default: the paper's).
    """
    report_identity(name, result)
    fig = locus_figure(name, result.table, labels=labels)
    savefig(fig, output_dir, _stem(name) + "_locus", figure=name,
            caption=figure_caption(name, cfg, LOCUS_CAPTION, markers=False))


def damping_summary(name: str, result, measure: str, labels=None) -> None:
    """Print the tracked modes' damping along a sweep and where the TEF branch changes sign.

    Parameters
    ----------
    name : str
        The paper figure.
    result : tefcore.sweeps.sweep.SweepResult
        Its sweep.
    measure : str
        ``"decay_rate"`` or ``"damping_ratio"``.
    labels : sequence of str, optional
        The modes of the table (default: :func:`mode_summary`'s).
    """
    print("damping (" + measure + ") of the tracked modes "
          "(NaN: that track is absent at this x, e.g. after a locked pair unlocks):")
    more = {} if labels is None else {"labels": labels}
    print(mode_summary(name, result.table, measure=measure, **more).to_string())
    changes = sign_changes(name, result.table, measure=measure)
    print("TEF damping changes sign at:", changes or "nowhere in the range")
