"""Which verdicts the paper's nine-mode basis decides and a converged basis would not.

The paper reduces the blade to "nine blade coupled natural vibration modes";
tefcore does the same by default (``model.n_modes = 9``, the families of the
baseline's nine lowest held along every sweep).  The flap's flutter needs
more: checked against a full-order model of the same blade, the growth of the
flutter root converges only at 25-30 modes.  So each figure's *converged
basis* is found -- the fewest modes (of :data:`MODE_COUNTS`) beyond which the
least stable flap-induced root's growth anywhere on the figure's sweep changes
by less than :data:`GROWTH_TOL` -- and every claim is checked on it.  A claim
whose verdict differs between the paper's basis and the converged one is
*truncation-dependent*: the reproduction reports both verdicts
(:func:`mark_truncation`).

The converged verdicts cost many times the claims themselves (Figs. 10-11
take 7 s of CPU with 9 modes, 132 s with 30), so they are computed once by
``python -m tefcore.paper.claims.truncation`` and stored with the reference
data (:data:`CONVERGED_FILE`; another packaged configuration's, such as the
inferred rotor's, as ``converged_basis-<name>.csv``), with the tefcore version
and the configuration they were computed for; a reproduction of a
configuration without them says that it has none.

Examples
--------
>>> import pandas as pd
>>> claims = pd.DataFrame({"id": ["a", "b"], "status": ["pass", "fail"], "reason": ["", "x"]})
>>> conv = pd.DataFrame({"id": ["a", "b"], "status": ["fail", "fail"], "n_modes": [30, 24],
...                      "computed_value": [1.0, 2.0]})
>>> marked = mark_truncation(claims, conv)
>>> marked["truncation"].tolist()
['truncation-dependent', '']
>>> print(marked.loc[0, "reason"])
truncation-dependent: pass with the paper's 9 modes, fail with 30 (converged basis)
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from ...safe_io import atomic_write_text
from ..figures.catalogue import FIGURES
from ..figures.frames import compute_figure
from .files import reference_dir
from .reference import load_claims
from .validation import sweep_values, validate_all

__all__ = ["CONVERGED_FILE", "GROWTH_TOL", "MODE_COUNTS", "converged_count",
           "converged_verdicts", "flutter_growth", "load_converged", "mark_truncation",
           "write_converged"]

#: The bases tried, in order: the paper's nine, then more of the lowest modes
#: (the nine's families always held).
MODE_COUNTS = (9, 16, 24, 30, 36)

#: Change of the flutter root's largest growth [/rev] below which a basis is
#: converged: the resolution of the paper's damping plots (about 0.01 /rev).
GROWTH_TOL = 0.01

#: The stored converged verdicts of the default rotor (beside the claims) and what they
#: were computed for; another configuration's are ``converged_basis-<name>.csv``.
CONVERGED_FILE = "converged_basis.csv"
_META = "converged_basis.json"


def _files(root, name: str):
    """The verdicts' table and its record for configuration ``name`` in ``root``."""
    if name in ("mdart", ""):
        return root / CONVERGED_FILE, root / _META
    return root / f"converged_basis-{name}.csv", root / f"converged_basis-{name}.json"


def flutter_growth(table: pd.DataFrame) -> float:
    """The largest real part [/rev] of a sweep's flutter roots (the points asked for).

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep's table (``flutter_root``, ``real_part``, ``refinement``).

    Returns
    -------
    float
        NaN where no point has a flutter root.
    """
    t = table[table["status"] == "ok"] if "status" in table else table
    if "refinement" in t:
        t = t[t["refinement"] == 0]
    rows = t[t["flutter_root"].fillna(False).astype(bool)] if "flutter_root" in t else t[:0]
    return float(rows["real_part"].max()) if len(rows) else float("nan")


def converged_count(cfg, figure: str, values=None, counts=MODE_COUNTS,
                    tol: float = GROWTH_TOL) -> tuple[int, dict]:
    """The converged basis of one figure and the results on each basis tried.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The base configuration.
    figure : str
        A stability figure.
    values : list, optional
        Its sweep values (default: the paper's and the claims' x).
    counts : sequence of int
        The bases to try, in order.
    tol : float
        :data:`GROWTH_TOL`.

    Returns
    -------
    n_modes : int
        The first count whose flutter growth differs from the next one's by
        less than `tol` (the last tried when none does).
    results : dict
        Count -> the figure's sweep result on that basis.
    """
    results, growth = {}, {}
    for n in counts:
        results[n] = compute_figure(figure, cfg.with_overrides({"model.n_modes": n}), values)
        growth[n] = flutter_growth(results[n].table)
        done = [m for m in results if m < n]
        if done:
            prev = done[-1]
            both_nan = np.isnan(growth[prev]) and np.isnan(growth[n])
            if both_nan or abs(growth[n] - growth[prev]) < tol:
                return prev, results
    return counts[-1], results


def converged_verdicts(cfg, figures=None, counts=MODE_COUNTS) -> pd.DataFrame:
    """Every claim of ``figures`` checked on its figure's converged basis.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The base configuration.
    figures : sequence of str, optional
        Stability figures (default: every one with a claim).
    counts : sequence of int
        The bases to try (:data:`MODE_COUNTS`).

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`tefcore.paper.claims.validation.validate_all`
        with ``n_modes``, the converged basis of the claim's figure.
    """
    claims = [c for c in load_claims() if c.kind != "not_reproducible"]
    figures = [f for f in (figures or FIGURES) if f in FIGURES
               and any(c.figure == f for c in claims)]
    rows = []
    for fig in figures:
        mine = [c for c in claims if c.figure == fig]
        # a claim reading a variant or another figure gets it on the same basis
        # (validate_all computes it from the converged configuration)
        n, results = converged_count(cfg, fig, sweep_values(fig, mine), counts)
        conv = cfg.with_overrides({"model.n_modes": n})
        table = validate_all(cfg=conv, results={fig: results[n]}, claims=mine)
        rows.append(table.assign(n_modes=n))
    return pd.concat(rows, ignore_index=True) if rows else pd.DataFrame()


def write_converged(table: pd.DataFrame, cfg, root=None) -> None:
    """Store converged verdicts beside the claims, with what they were computed for.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`converged_verdicts`.
    cfg : tefcore.config.configuration.Config
        The configuration they were computed on (its name and hash are kept).
    root : path, optional
        The reference-data folder (default: the package's).
    """
    from ..._version import __version__
    from ...sweeps.store import config_hash

    root = reference_dir() if root is None else root
    data, meta = _files(root, cfg.name)
    atomic_write_text(data, table[["id", "figure", "status", "computed_value", "n_modes"]]
                      .to_csv(index=False, float_format="%.10g"))
    atomic_write_text(meta, json.dumps({
        "tefcore_version": __version__, "config": cfg.name, "config_hash": config_hash(cfg),
        "mode_counts": sorted(set(int(n) for n in table["n_modes"]))}, indent=1) + "\n")


def load_converged(cfg, root=None) -> pd.DataFrame | None:
    """The stored converged verdicts, where they were computed for ``cfg``; else None.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The configuration a reproduction runs.
    root : path, optional
        The reference-data folder (default: the package's).

    Returns
    -------
    pandas.DataFrame or None
        ``id, figure, status, computed_value, n_modes``; None where none were
        stored or they were computed for another configuration.
    """
    from ...sweeps.store import config_hash

    root = reference_dir() if root is None else root
    data, meta = _files(root, cfg.name)
    if not (meta.is_file() and data.is_file()):
        return None
    info = json.loads(meta.read_text())
    if info.get("config_hash") != config_hash(cfg):
        return None
    return pd.read_csv(data)


def mark_truncation(claims: pd.DataFrame, converged: pd.DataFrame | None) -> pd.DataFrame:
    """Claims with their converged-basis verdict, and which are truncation-dependent.

    Parameters
    ----------
    claims : pandas.DataFrame
        A claims table (``id``, ``status``, ``reason``).
    converged : pandas.DataFrame or None
        :func:`converged_verdicts` (``id``, ``status``, ``n_modes``); None:
        none for this configuration (the columns are empty).

    Returns
    -------
    pandas.DataFrame
        `claims` with ``converged_status``, ``converged_modes`` and
        ``truncation`` (``"truncation-dependent"`` where the verdicts differ);
        such a claim's reason says both.
    """
    out = claims.copy()
    if converged is None or converged.empty:
        out["converged_status"], out["converged_modes"], out["truncation"] = "", "", ""
        return out
    conv = converged.set_index("id")
    status = out["id"].map(conv["status"]).fillna("")
    modes = out["id"].map(conv["n_modes"])
    out["converged_status"] = status
    out["converged_modes"] = modes.map(lambda v: "" if pd.isna(v) else str(int(v)))
    differs = (status != "") & (status != out["status"])
    out["truncation"] = np.where(differs, "truncation-dependent", "")
    for i in np.flatnonzero(differs.to_numpy()):
        note = (f"truncation-dependent: {out['status'].iloc[i]} with the paper's 9 modes, "
                f"{status.iloc[i]} with {int(modes.iloc[i])} (converged basis)")
        r = out["reason"].iloc[i]
        out.iloc[i, out.columns.get_loc("reason")] = f"{r}; {note}" if r else note
    return out


def _main(argv) -> int:
    """``python -m tefcore.paper.claims.truncation [--config NAME] [FIGURE ...]``: compute
    and store.

    With figures named, their verdicts replace theirs in the stored table and
    the other figures' stay (one figure at a time fits a short session).
    ``--config`` names a packaged configuration (default ``mdart``); its
    verdicts are stored as ``converged_basis-<name>.csv``.
    """
    import argparse

    from ...config.io import load_config
    from ...runtime import apply_defaults

    ap = argparse.ArgumentParser(prog="python -m tefcore.paper.claims.truncation")
    ap.add_argument("--config", default="mdart")
    ap.add_argument("figures", nargs="*")
    args = ap.parse_args(argv)
    argv = args.figures
    apply_defaults()
    cfg = load_config(args.config)
    table = converged_verdicts(cfg, argv or None)
    stored = load_converged(cfg) if argv else None
    if stored is not None:
        kept = stored[~stored["figure"].isin(set(table["figure"]))]
        table = pd.concat([kept, table[list(stored.columns)]], ignore_index=True)
    write_converged(table, cfg)
    for fig, n in table.groupby("figure")["n_modes"].first().items():
        print(f"{fig}: converged with {n} modes")
    return 0


if __name__ == "__main__":
    import sys

    from ...errors import run_command

    raise SystemExit(run_command(_main, sys.argv[1:],
                                 prog="python -m tefcore.paper.claims.truncation"))
