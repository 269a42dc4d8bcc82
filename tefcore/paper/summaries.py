"""Printed summaries of a figure's results, for notebook cells that nbval checks.

Every function prints (or returns) rounded, deterministic text: the tracked
modes' damping and frequency tables (:func:`mode_summary`), where damping
changes sign (:func:`sign_changes`), how the modes were identified
(:func:`report_identity`), why a root is (un)stable (:func:`explain`, an
energy balance by :mod:`tefcore.linear.mechanism`), how unsteady the flap mode is
(:func:`unsteadiness`), and the paper's claims checked against the results
(:func:`claims_table`, :func:`show_claims`).

Examples
--------
>>> format_value(2.2e-16), format_value(0.123456), format_value("at 0.3333333 c_f")
('0', '0.1235', 'at 0.3333 c_f')
"""

from __future__ import annotations

import math
import re
import warnings
from contextlib import contextmanager

import numpy as np
import pandas as pd

from ..aero.unsteady import theodorsen_function
from ..linear.mechanism import mechanism
from ..modes.names import base_name
from ..modes.roles import exceptional_points, undecided_steps
from .claims import validation
from .claims.curves import zero_crossings
from .claims.exceptional import where
from .figures.catalogue import FIGURES, figure_config
from .figures.plotting import AXES, PAPER_MODES, curves, x_values
from .figures.runs import run_config

__all__ = ["claims_table", "clean", "counted_warnings", "explain", "format_value",
           "mechanism_summary", "mode_summary", "reference_curves", "report_identity",
           "report_sweep", "show_claims", "sign_changes", "unsteadiness"]


def mechanism_summary(cfg, x=None, name=None, root=None, knockouts=True,
                      digits: int = 3) -> pd.DataFrame:
    """:func:`tefcore.linear.mechanism.mechanism` of one root, as a rounded table.

    Why a root is (un)stable: the work each term of the linearised equations
    does on it over a period (its contribution to the real part), and what
    knocking a term out does to the root.  Prints the root's kind
    (flutter, divergence, stable) and participation.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config or None
        The configuration; with ``name``, the base configuration of the
        figure (None: MDART).
    x : float or str, optional
        With ``name``: the value of the figure's swept field, SI or a ``"value
        unit"`` string (a flap CG offset 0.33 for Fig. 9, ``"400 lb/in"``
        for Fig. 10).
    name : str, optional
        Stability figure; the root is analysed at its caption's configuration
        with the swept field at ``x``.
    root : complex, optional
        Eigenvalue of the root to analyse, ``real_part + 1j *
        frequency_per_rev`` [1/rev] (e.g. the TEF branch of a sweep there);
        default: the root the flap mode becomes (``mode="TEF"``).
    knockouts : bool
        Also follow the root with each removable term knocked out.
    digits : int
        Decimals printed and kept; terms smaller than ``10**-digits`` /rev
        are left out.

    Returns
    -------
    pandas.DataFrame
        ``term, contribution_real`` [1/rev]: the terms, largest first, then
        the knockouts (the root's real part with that term removed).
    """
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
    """Wide table (x by mode), rounded, for printing in checked cells.

    Parameters
    ----------
    name : str
        Stability figure (sets the x axis and its label, :data:`AXES`).
    table : pandas.DataFrame or None
        Sweep table (:attr:`tefcore.sweeps.sweep.SweepResult.table`); may be None
        when ``natural`` is given.
    labels : tuple of str
        Modes (columns), in order: ``"TEF"`` is the TEF branch.
    measure : {"decay_rate", "damping_ratio"}
        Damping measure: ``-Re(s)/Omega`` [1/rev] or ``zeta`` [%]
        (:data:`tefcore.paper.figures.plotting.MEASURES`).
    quantity : {"damping", "frequency"}
        Which value fills the table (frequency in /rev).
    digits : int
        Decimals kept.
    natural : pandas.DataFrame, optional
        Curves of blade natural frequencies
        (:func:`tefcore.paper.figures.runs.natural_frequencies`) to tabulate
        instead of the sweep's roots.

    Returns
    -------
    pandas.DataFrame
        Index: the figure's own x values in the paper's units, named by the
        axis label; one column per mode present.
    """
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
    """Replace ``-0.0`` by ``0.0`` (so printed tables do not flip sign).

    Parameters
    ----------
    df : pandas.DataFrame
        A rounded table; only its float columns change.

    Returns
    -------
    pandas.DataFrame
        A copy with every zero of a float column a positive zero.

    Examples
    --------
    >>> clean(pd.DataFrame({"d": [-0.0, -0.5]}))["d"].tolist()
    [0.0, -0.5]
    """
    return df.apply(lambda c: c.mask(c == 0, 0.0) if c.dtype.kind == "f" else c)


def sign_changes(name: str, table: pd.DataFrame, label: str = "TEF",
                 measure: str = "decay_rate") -> list:
    """Where a mode's damping changes sign, in the paper's x units.

    The zero crossings (:func:`tefcore.paper.claims.curves.zero_crossings`)
    of the mode's real part, linearly interpolated between the figure's own
    points (points added by refinement left out): e.g. Fig. 9b's TEF mode
    "becomes unstable after a flap CG offset of 0.26 flap chord".

    Parameters
    ----------
    name : str
        Stability figure (sets the x axis).
    table : pandas.DataFrame
        Sweep table.
    label : str
        The mode (``"TEF"``: the TEF branch; ``"blade torsion 1"``, ...).
    measure : {"decay_rate", "damping_ratio"}
        Damping measure whose sign is followed (both change sign together).

    Returns
    -------
    list of tuple of (float, str)
        ``(x, "stable -> unstable" | "unstable -> stable")``, x rounded to
        3 decimals, in order along each track.
    """
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
    """A few deterministic lines on which root is which along the sweep.

    Every root is named by the uncoupled mode it continues from (at every
    point, by continuation in the blade-flap coupling); printed: the
    exceptional points where two names exchange (none: every root keeps its
    name over the range), the steps where a name moves to another root with
    no exceptional point located there
    (:func:`tefcore.modes.roles.undecided_steps`: its identity undecided, or
    the names by participation of roots the flap does not move), how many
    points the refinement added to locate the exceptional points, and the
    modes the flutter root continues from.  Nothing is returned.

    Parameters
    ----------
    name : str
        Stability figure (sets the x axis of the printed positions).
    result : tefcore.sweeps.sweep.SweepResult
        The figure's sweep.
    """
    t = result.table
    ok = t[t["status"] == "ok"]
    if ok.empty:
        print(f"{name}: no point computed")
        return
    n_ref = ok.loc[ok["refinement"] > 0, "point"].nunique() if "refinement" in ok else 0
    ok = ok.assign(x=x_values(name, ok))
    eps = exceptional_points(ok, x="x")
    print(f"{name}: roots named by the uncoupled mode they continue from; "
          f"{n_ref} points added to locate exceptional points")
    if eps.empty:
        print("  no exceptional point in the range: every root keeps its name")
    for _, e in eps.iterrows():
        print(f"  exceptional point of {e['modes']} {where(e)} ({e['kind']})")
    moved = undecided_steps(ok, x="x")
    if not moved.empty:
        print("  names that move to another root with no exceptional point located there "
              "(the identity undecided, or names by participation of roots the flap does "
              "not move):")
    for (modes, kind), g in moved.groupby(["modes", "kind"], sort=False):
        steps = ", ".join(f"{lo:.4g}-{hi:.4g}" for lo, hi in zip(g["x_low"], g["x_high"],
                                                                 strict=True))
        print(f"    {modes} at x = {steps}" + ("" if kind == "identity undecided"
                                                 else f" ({kind})"))
    fr = ok[ok["flutter_root"].fillna(False).astype(bool)]
    if "refinement" in fr:
        fr = fr[fr["refinement"] == 0]
    if fr.empty:
        print("  no flutter root (no flap-induced root)")
        return
    counts = fr["label"].map(base_name).value_counts()
    counts = counts.sort_index().sort_values(ascending=False, kind="stable")
    print("  the flutter root continues from "
          + ", ".join(f"{lab} ({n} of {len(fr)} points)" for lab, n in counts.items()))


def explain(name: str, result, x: float, base=None, overrides: dict | None = None,
            which: str = "TEF branch", knockouts: bool = True) -> pd.DataFrame:
    """Why the TEF branch (or the flutter root) is (un)stable near ``x``.

    :func:`mechanism_summary` of that root at the sweep point nearest ``x``
    (in the paper's units).  Prints the point, the root's label there, kind
    and participation.

    Parameters
    ----------
    name : str
        Stability figure.
    result : tefcore.sweeps.sweep.SweepResult
        The figure's sweep.
    x : float
        Where to look, in the paper's x units (deg of collective, lb/in,
        fractions of c_f, ...); the nearest point of the figure's own is used.
    base : tefcore.config.configuration.Config, optional
        Base configuration the sweep was run with (default: MDART).
    overrides : dict, optional
        Dotted fields the sweep was run with over the caption.
    which : {"TEF branch", "flutter root"}
        The root to explain: the continuation of the flap's own mode, or the
        least stable root the flap takes part in.
    knockouts : bool
        Also follow the root with each removable term knocked out.

    Returns
    -------
    pandas.DataFrame
        ``term, contribution_real`` [1/rev], rounded, for checked cells; empty
        when the sweep has no such root.
    """
    t = result.table
    col = "tef_branch" if which == "TEF branch" else "flutter_root"
    rows = t[(t["status"] == "ok") & t[col].fillna(False).astype(bool) & (t["refinement"] == 0)]
    if rows.empty:
        print(f"{name}: no {which} in the sweep")
        return pd.DataFrame(columns=["term", "contribution_real"])
    xs = x_values(name, rows)
    r = rows.iloc[int(np.argmin(np.abs(xs - x)))]
    cfg = run_config(name, base, overrides).with_overrides(
        {FIGURES[name].parameter: r["value_si"]})
    character = r["dominant"] if "dominant" in r else r["label"]
    print(f"{name}, {which} at x = {float(xs[int(np.argmin(np.abs(xs - x)))]):.4g} "
          f"(from {r['label']}; carries {character} most there):")
    return mechanism_summary(cfg, root=complex(r["real_part"], r["frequency_per_rev"]),
                             knockouts=knockouts)


def unsteadiness(name: str, result, base=None) -> None:
    """Print the TEF mode's reduced frequency at the flap and Theodorsen's C(k).

    How far from quasi-steady (C = 1) the flap mode of this sweep is: the
    paper's flap aerodynamics are quasi-steady (adapted from Theodorsen's
    theory, or table look-up).  ``k = omega b / U`` with the median frequency of the roots
    labelled TEF, ``b = c/2`` and ``U`` the rotational speed at the flap
    midspan (hover).

    Parameters
    ----------
    name : str
        Stability figure (its caption's flap and rotor).
    result : tefcore.sweeps.sweep.SweepResult
        The figure's sweep.
    base : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART).
    """
    cfg = figure_config(name, base)
    t = result.table
    own_label = t["dominant" if "dominant" in t else "label"].map(base_name)
    own = t[(t["status"] == "ok") & (own_label == "TEF")]
    if own.empty:
        print(f"{name}: no TEF mode in the sweep")
        return
    f = float(np.median(own["frequency_per_rev"]))   # where the mode is TEF-like itself
    # k = omega b / U with b = c/2 and U = x R Omega (hover speed at the flap midspan)
    k = f * cfg.rotor.chord / (2 * cfg.flap.midspan * cfg.rotor.radius)
    c = complex(theodorsen_function(k))
    print(f"{name}: TEF mode at {f:.1f}/rev (median over the sweep) -> reduced frequency "
          f"k = {k:.2f} at {cfg.flap.midspan:.2f} R;")
    print(f"  Theodorsen C(k): |C| = {abs(c):.2f}, phase {np.degrees(np.angle(c)):.1f} deg "
          "(quasi-steady theory uses C = 1, phase 0)")


@contextmanager
def counted_warnings(what: str):
    """Collect the warnings of a block and print one line counting them by category.

    Instead of a stderr flood (which nbval would compare), one deterministic
    line such as ``"fig9: 3 RuntimeWarning"``; nothing when there are none.

    Parameters
    ----------
    what : str
        What the block computes, the start of the printed line.

    Yields
    ------
    list of warnings.WarningMessage
        The warnings caught so far, for a block that wants to look at them.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield caught
    if caught:
        counts = pd.Series([w.category.__name__ for w in caught]).value_counts().sort_index()
        print(f"{what}: " + ", ".join(f"{n} {cat}" for cat, n in counts.items()))


def report_sweep(name: str, result) -> None:
    """One deterministic line: points, failures, points with numerical warnings.

    Then one line per failed point with its value and error.

    Parameters
    ----------
    name : str
        The figure, the start of the line.
    result : tefcore.sweeps.sweep.SweepResult
        The sweep (its ``table``, ``parameter`` and ``failed`` points).
    """
    t = result.table
    pts = t.drop_duplicates("point")
    n_warn = int((pts.get("trim_numerical_warnings", pd.Series(dtype=float)).fillna(0) > 0)
                 .sum())
    print(f"{name}: {len(pts)} points of {result.parameter}, "
          f"{int((pts['status'] != 'ok').sum())} failed, {n_warn} with numerical warnings")
    for row in result.failed.itertuples(index=False):
        print(f"  failed at {row.value}: {row.error}")


def claims_table(name: str, result, cfg=None, variants=None, others=None) -> pd.DataFrame:
    """The paper's claims about one figure, checked against its result.

    :func:`tefcore.paper.claims.validation.validate_figure`, with a fresh index.

    Parameters
    ----------
    name : str
        Paper figure.
    result : SweepResult or dict
        The figure's result.
    cfg : tefcore.config.configuration.Config, optional
        Base configuration of runs the validation adds.
    variants : dict, optional
        ``{variant_key(overrides): result}`` of runs already made (e.g. Fig.
        12's balanced flap); anything else a claim needs is computed.
    others : dict, optional
        Figure name -> result, for claims comparing figures.

    Raises
    ------
    tefcore.paper.claims.files.ReferenceDataError
        Without usable reference data (never an empty "0 of 0" table).
    """
    return validation.validate_figure(name, result, cfg=cfg, variants=variants,
                                      others=others).reset_index(drop=True)


def reference_curves(name: str):
    """Digitised curves of the paper for a figure (``label, x, y``), or None.

    Parameters
    ----------
    name : str
        Paper figure.
    """
    return validation.reference_curves(name)


def show_claims(table: pd.DataFrame, width: int = 70) -> None:
    """Print a claims table compactly and deterministically (claim, status, computed).

    A claim whose verdict depends on the modal basis (column ``truncation``,
    :func:`tefcore.paper.claims.truncation.mark_truncation`) gets a line saying
    both verdicts.

    Parameters
    ----------
    table : pandas.DataFrame
        Claims checked (:func:`claims_table`); the computed values are
        printed with 4 significant digits (:func:`format_value`).
    width : int
        Widest column shown, in characters.
    """
    if table.empty:
        print("no claims for this figure")
        return
    t = table.copy()
    if "computed" in t:
        t["computed"] = [format_value(v) for v in t["computed"]]
    cols = [c for c in ("id", "status", "computed") if c in t.columns]
    with pd.option_context("display.max_colwidth", width, "display.width", 200):
        print(t[cols or list(t.columns)].to_string(index=False))
    if "truncation" in t:
        # a verdict the paper's nine modes decide otherwise than a converged basis
        for _, r in t[t["truncation"].fillna("").astype(str) == "truncation-dependent"].iterrows():
            print(f"{r['id']}: truncation-dependent, {r['status']} with the paper's 9 modes, "
                  f"{r['converged_status']} with {int(r['converged_modes'])} (converged basis)")


_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])")


def _round_number(text: str) -> str:
    v = float(text)
    if abs(v) < 1e-9:          # round-off (e.g. 2.2e-16 for "unchanged"): not a result
        return "0"
    return f"{v:.4g}"


def format_value(v) -> str:
    """A value printed with 4 significant digits; |x| < 1e-9 (round-off) as 0.

    Parameters
    ----------
    v : float or str
        A number, or text with numbers in it (each is rounded).

    Returns
    -------
    str
        The value as printed in checked cells (``"nan"`` for NaN).
    """
    if isinstance(v, float | np.floating):
        return "nan" if math.isnan(v) else _round_number(repr(float(v)))
    return _NUMBER.sub(lambda m: _round_number(m.group()), str(v))
