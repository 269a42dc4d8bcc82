"""Compare tefcore results with the reference claims of the paper.

:func:`validate_all` runs every figure that has a checkable claim (through
:mod:`tefcore.paper.figures.catalogue`, adding the x values that value claims need to the
sweeps) and returns one tidy row per claim; :func:`validate_figure` checks
the claims of one figure against its result.  The claims are loaded by
:mod:`tefcore.paper.claims.reference` (format: ``reference_data/README.md``).

How each kind of claim is compared is in :mod:`tefcore.paper.claims.checks`
(specified in ``reference_data/README.md``, kinds table), with the
curve primitives in :mod:`tefcore.paper.claims.curves` and the figure results as
tables in :mod:`tefcore.paper.figures.frames`; their public names are re-exported
here.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd

from ...errors import TefcoreError
from ...safe_io import atomic_write_text
from ...units import parse_quantity
from ..figures.catalogue import FIGURES, KNOWN_FIGURES, variant_key
from ..figures.frames import FIG7_OVERHANGS, compute_figure, figure_frame
from ..figures.plotting import split_value
from ..figures.quantities import swept_dimension, x_to_si
from .checks import COLUMNS, validate_figure
from .curves import X_SLACK, compare_curve, stability_intervals, zero_crossings
from .files import ReferenceDataError, reference_dir
from .reference import STATUSES, load_claims

__all__ = ["COLUMNS", "FIGURE_ERRORS", "claim_values", "claims_score", "compare_curve",
           "figure_frame", "figure_values", "not_computable_rows", "reference_curves",
           "stability_intervals", "sweep_values", "update_recorded_status", "validate_all",
           "validate_figure", "worse_than_recorded", "zero_crossings"]

#: What a figure that cannot be computed raises: tefcore's own errors (a trim that
#: does not converge, Floquet accuracy), a configuration refused at the figure's own
#: parameters (ValueError), a singular or overflowing system.
FIGURE_ERRORS = (TefcoreError, ValueError, ArithmeticError, np.linalg.LinAlgError)


def _value_si(name: str, v) -> float:
    if isinstance(v, str):
        return parse_quantity(v, swept_dimension(name))
    return float(v)


def sweep_values(name: str, claims) -> list:
    """A stability figure's sweep values plus the x its value and mechanism claims name.

    Sorted, without duplicates (equal within :data:`~tefcore.paper.claims.curves.X_SLACK`),
    in the figure's own value format; the sweep :func:`validate_all` runs, so
    a value claim is read at a computed point, not between two.

    Parameters
    ----------
    name : str
        Stability figure, a key of :data:`tefcore.paper.figures.catalogue.FIGURES`.
    claims : iterable of Claim
        The figure's claims; the ``x`` and ``relative_to`` of its value and
        mechanism claims without overrides are added.

    Returns
    -------
    list
        The sweep values: numbers (SI) or ``"value unit"`` strings like the
        paper's (``"400 lb/in"``) for a dimensional axis.
    """
    values = list(FIGURES[name].values)
    have = [_value_si(name, v) for v in values]
    strings = isinstance(values[0], str)
    for c in claims:
        for xv in ((c.x, c.relative_to) if c.kind in ("value", "mechanism")
                   and not c.overrides else ()):
            if xv is None:
                continue
            si = float(x_to_si(name, xv, c.x_unit))
            if any(abs(si - h) <= X_SLACK * max(abs(h), 1e-300) for h in have):
                continue
            values.append(f"{xv:g} {c.x_unit}" if strings and c.x_unit else si)
            have.append(si)
    return [v for _, v in sorted(zip(have, values, strict=True), key=lambda p: p[0])]


def _claim_sweep_values(name: str):
    try:
        mine = [c for c in load_claims() if c.figure == name and c.kind != "not_reproducible"]
    except (ReferenceDataError, FileNotFoundError):
        return None
    return sweep_values(name, mine)


def figure_values(name: str, n_points: int | None = None, values=None,
                  claim_points: bool = True) -> list:
    """Sweep values of a figure.

    Parameters
    ----------
    name : str
        Paper figure.
    n_points : int, optional
        That many values, evenly over the paper's range.
    values : sequence, optional
        Explicit values (win over ``n_points``).
    claim_points : bool
        With neither: add the x values the figure's value claims name to the
        paper's values -- the same sweep as
        :func:`validate_all` runs.

    Returns
    -------
    list
        Numbers, or strings with units where the paper's values have them.
    """
    if values is not None:
        return list(values)
    base = list(FIGURES[name].values)
    if n_points is None:
        return (_claim_sweep_values(name) if claim_points else None) or base
    n = int(n_points)
    if n < 2:
        raise ValueError(f"n_points must be at least 2, got {n_points!r}")
    (lo, unit), (hi, _) = split_value(base[0]), split_value(base[-1])
    grid = np.linspace(lo, hi, n)
    if unit:
        return [f"{v:.6g} {unit}" for v in grid]
    return [float(f"{v:.10g}") for v in grid]


def claim_values(claims) -> dict:
    """Each figure the claims read, with its sweep values (None: the figure's own).

    Parameters
    ----------
    claims : sequence of Claim
        The checkable claims.

    Returns
    -------
    dict
        Figure -> its values: the paper's and the claims' x for a stability
        figure (:func:`sweep_values`), Fig. 7's overhangs with the claims'.
    """
    need = {c.figure for c in claims} | {c.other_figure for c in claims if c.other_figure}
    values: dict = {}
    for name in (n for n in KNOWN_FIGURES if n in need):
        mine = [c for c in claims if c.figure == name]
        values[name] = None
        if name in FIGURES:
            values[name] = sweep_values(name, mine)
        elif name == "fig7":
            xs = {float(v) for c in mine for v in (c.x, c.relative_to) if v is not None}
            values[name] = sorted(set(FIG7_OVERHANGS) | xs)
    return values


def validate_all(n_jobs: int = 1, progress: bool = False, *, claims=None, cfg=None,
                 results=None, include_examples: bool = False) -> pd.DataFrame:
    """Run every figure that has a checkable claim and check all claims.

    Parameters
    ----------
    n_jobs : int
        Processes of each sweep (:func:`tefcore.paper.figures.catalogue.run_figure`);
        1 runs serially.
    progress : bool
        Show the sweeps' progress bars.
    claims : list of Claim, optional
        Default :func:`tefcore.paper.claims.reference.load_claims`.
    cfg : Config, optional
        Base configuration (default MDART).
    results : dict, optional
        Figure name -> precomputed result, used instead of running it.
    include_examples : bool
        Also check the synthetic example curves.

    Returns
    -------
    DataFrame
        One row per claim (columns :data:`COLUMNS`), in reference-data order.  A
        figure that cannot be computed (:data:`FIGURE_ERRORS`) gives its claims
        (and the comparisons that read it) the status ``not computable`` with
        the reason; the other figures are still checked.
    """
    claims = load_claims(include_examples=include_examples) if claims is None else list(claims)
    results = dict(results or {})
    active = [c for c in claims if c.kind != "not_reproducible"]
    values = claim_values(active)
    broken: dict = {}
    for name in values:
        if name not in results:
            _survive(broken, name, name, lambda n=name: results.__setitem__(n, compute_figure(
                n, cfg, values[n], None, n_jobs, progress)))
    variants = _variants(active, cfg, values, broken, n_jobs, progress)
    tables = []
    for name in dict.fromkeys(c.figure for c in claims):
        mine = [c for c in claims if c.figure == name]
        dead = sorted({f for c in mine if c.kind != "not_reproducible"
                       for f in (c.figure, c.other_figure) if f in broken})
        tables.append(not_computable_rows(mine, "; ".join(broken[f] for f in dead)) if dead
                      else validate_figure(
                          name, results.get(name), mine, cfg=cfg, others=results,
                          variants={k: v for (f, k), v in variants.items() if f == name}))
    order = {c.id: i for i, c in enumerate(claims)}
    table = pd.concat(tables, ignore_index=True)
    return table.sort_values("id", key=lambda s: s.map(order), ignore_index=True)


def _variants(active, cfg, values, broken, n_jobs, progress) -> dict:
    """The claims' configuration variants of their figures, by (figure, variant key)."""
    variants: dict = {}
    for c in active:
        for fig, ov in ((c.figure, c.overrides), (c.other_figure or c.figure, c.other_overrides)):
            key = (fig, variant_key(ov))
            if ov and key not in variants and fig not in broken:
                _survive(broken, fig, f"{fig} with {key[1]}", lambda f=fig, o=ov, k=key:
                         variants.__setitem__(k, compute_figure(f, cfg, values.get(f), o,
                                                                n_jobs, progress)))
    return variants


def _survive(broken: dict, figure: str, label: str, compute) -> None:
    """Run `compute`; a figure that cannot be computed is recorded in `broken` with why."""
    try:
        compute()
    except FIGURE_ERRORS as err:
        broken[figure] = f"{label} cannot be computed: {type(err).__name__}: {err}"


def not_computable_rows(claims, reason: str) -> pd.DataFrame:
    """Rows of claims whose figure cannot be computed: status ``not computable``, the reason.

    A ``not_reproducible`` claim keeps its own status and reason (it has no check).

    Parameters
    ----------
    claims : list of Claim
        The claims of the figure (or figures) that could not be computed.
    reason : str
        What failed (the figure and the error).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS`.
    """
    rows = [{"id": c.id, "figure": c.figure, "panel": c.panel, "kind": c.kind, "tag": c.tag,
             "mode": c.mode, "quantity": c.quantity, "statement": c.statement,
             "expected": "", "computed": "", "computed_value": np.nan, "margin": np.nan,
             "status": "not reproducible" if c.kind == "not_reproducible" else "not computable",
             "reason": c.reason if c.kind == "not_reproducible" else reason,
             "recorded_status": c.recorded_status} for c in claims]
    return pd.DataFrame(rows, columns=COLUMNS)


def reference_curves(name: str, include_examples: bool = False) -> pd.DataFrame | None:
    """Digitised curves of a figure for plotting, or None when there are none.

    Parameters
    ----------
    name : str
        The figure (``"fig8"``).
    include_examples : bool
        Also the synthetic demonstration curves (``example = true``), never
        data of the paper.

    Returns
    -------
    pandas.DataFrame or None
        ``id, label`` (the mode, or the claim id for Figs. 5-7),
        ``quantity, x, y, band``: x in the units of the figure's result table
        (:func:`figure_frame`), y and its half-width ``band`` in the
        canonical unit of the quantity; None when the figure has no curves.
    """
    curves = [c for c in load_claims(include_examples=include_examples)
              if c.kind == "curve" and c.figure == name]
    if not curves:
        return None
    return pd.concat([c.points[["x", "y", "band"]].assign(
        id=c.id, label=c.mode or c.id, quantity=c.quantity) for c in curves], ignore_index=True)[
        ["id", "label", "quantity", "x", "y", "band"]]


def claims_score(table: pd.DataFrame) -> tuple[int, int]:
    """(passed, total) over the ``validation`` claims of a validation table.

    Calibration targets (the four stated torsion frequencies that set the
    assumed properties) are not scored.

    Parameters
    ----------
    table : pandas.DataFrame
        Result of :func:`validate_all` (``tag`` and ``status`` columns).

    Returns
    -------
    tuple of (int, int)
        Validation claims with status ``"pass"``, and all validation claims.
    """
    v = table[table["tag"] == "validation"]
    return int((v["status"] == "pass").sum()), len(v)


def worse_than_recorded(table: pd.DataFrame) -> pd.DataFrame:
    """Rows whose status is worse than their ``recorded_status``.

    Best to worst: pass, ambiguous, not reproducible, fail
    (:data:`tefcore.paper.claims.reference.STATUSES`).  A claim without a recorded
    status is never a regression.

    Parameters
    ----------
    table : pandas.DataFrame
        Result of :func:`validate_all` (``status`` and ``recorded_status``).

    Returns
    -------
    pandas.DataFrame
        The regressed rows, with all their columns.

    Examples
    --------
    >>> t = pd.DataFrame({"id": ["a", "b", "c"], "status": ["fail", "pass", "fail"],
    ...                   "recorded_status": ["pass", "fail", ""]})
    >>> worse_than_recorded(t)["id"].tolist()
    ['a']
    """
    rank = {s: i for i, s in enumerate(STATUSES)}
    rec = table["recorded_status"].map(rank)
    now = table["status"].map(rank)
    return table[rec.notna() & (now > rec)]


def update_recorded_status(table: pd.DataFrame, path=None) -> int:
    """Write the statuses of `table` as ``recorded_status`` into a claims file.

    Edits the ``recorded_status = "..."`` line of each ``[[claim]]`` (adding
    it after the ``id`` line when absent), keeping everything else; the file
    is rewritten atomically.  Run after a reviewed full validation: later
    runs are compared with what it records (:func:`worse_than_recorded`).

    Parameters
    ----------
    table : pandas.DataFrame
        Result of :func:`validate_all` (``id`` and ``status``); claims not in
        it keep their recorded status.
    path : path, optional
        The claims file (default ``claims.toml`` of
        :func:`tefcore.paper.claims.files.reference_dir`).

    Returns
    -------
    int
        The number of records changed.
    """
    path = Path(path) if path is not None else reference_dir() / "claims.toml"
    status = dict(zip(table["id"], table["status"], strict=True))
    blocks = re.split(r"(?m)^(?=\[\[claim\]\])", path.read_text())
    changed = 0
    for i, b in enumerate(blocks):
        m = re.search(r'(?m)^id\s*=\s*"([^"]+)"\s*$', b)
        if not m or m.group(1) not in status:
            continue
        line = f'recorded_status = "{status[m.group(1)]}"'
        if re.search(r"(?m)^recorded_status\s*=.*$", b):
            new = re.sub(r"(?m)^recorded_status\s*=.*$", line, b)
        else:
            new = b[:m.end()] + "\n" + line + b[m.end():]
        changed += new != b
        blocks[i] = new
    atomic_write_text(path, "".join(blocks))
    return changed
