"""Everything the numbered notebooks use, under one short name (``nt``).

The notebooks (``tefcore notebooks --copy DIR`` gives editable copies) import
this module as ``nt`` so that a reader sees one vocabulary; the functions live
where they belong and are re-exported here:

* running a figure -- :mod:`tefcore.paper.figure_runs` (:func:`base_config`,
  :func:`run_config`, :func:`figure_values`, :func:`run_stability_figure`,
  :func:`natural_frequencies`, :func:`section_aero`);
* plotting -- :mod:`tefcore.paper.plotting` (:func:`plot_modes`,
  :func:`plot_root_locus`, :func:`plot_participation`, :func:`legend_below`,
  :func:`savefig`) and :mod:`tefcore.paper.captions` (:func:`figure_title`,
  :func:`figure_caption`, :func:`conditions`);
* printed summaries for checked cells -- :mod:`tefcore.paper.summaries`
  (:func:`mode_summary`, :func:`sign_changes`, :func:`report_identity`,
  :func:`explain`, :func:`unsteadiness`, :func:`claims_table`, ...);
* the shared departures text -- :func:`show_departures`;
* the interactive root map -- :func:`explore`.

Only :func:`setup_notebook` and :func:`save_csv` are defined here.

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
from .captions import (
    LOCUS_CAPTION,
    MARKERS,
    conditions,
    figure_caption,
    figure_title,
    flight_condition,
)
from .departures import departures_text, show_departures
from .explorer import explore
from .figure_runs import (
    base_config,
    figure_values,
    natural_frequencies,
    quiet_stability,
    run_config,
    run_stability_figure,
    section_aero,
    variant_key,
)
from .plotting import (
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
           "claims_table", "clean", "conditions", "counted_warnings", "curves",
           "departures_text", "deterministic_matplotlib", "explain", "explore",
           "figure_caption", "figure_title", "figure_values", "flight_condition",
           "format_value", "legend_below", "locus_figure",
           "mechanism_summary", "mode_summary", "natural_frequencies", "plot_modes",
           "plot_participation", "plot_root_locus", "quiet_stability", "reference_curves",
           "report_identity", "report_sweep", "run_config", "run_stability_figure",
           "save_csv", "savefig", "section_aero", "setup_notebook", "show_claims",
           "show_departures", "sign_changes", "unsteadiness", "variant_key", "x_values"]


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
