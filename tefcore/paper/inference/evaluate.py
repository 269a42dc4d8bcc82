"""One rotor of the space checked against a set of claims, surviving figures that fail.

:func:`evaluate_rotor` computes only the figures the given claims read (at the
points that decide them: :func:`tefcore.paper.attribution.evaluate.claim_needs`,
cached by configuration in a :class:`~tefcore.paper.attribution.evaluate.FigureCache`),
then checks the claims under each reading of the mode names with their own
checks (:func:`tefcore.paper.claims.checks.validate_figure`).  A figure that
cannot be computed (the trim does not converge, the configuration is refused
at the figure's own parameters) gives its claims the status ``not
computable`` with the reason; the other figures are still checked.  Claims
that read only the blade's natural frequencies (the stated torsion
frequencies) need no Floquet sweep: their figure is given as its x values.
:func:`objective` turns a checked table into the number a study maximises.

Examples
--------
>>> import numpy as np, pandas as pd
>>> t = pd.DataFrame({"status": ["pass", "fail", "ambiguous", "not computable", "fail"],
...                   "margin": [2.0, -0.5, np.nan, np.nan, -0.0]})
>>> round(objective(t), 4)
-1.4981
>>> round(float(np.tanh(2.0) + np.tanh(-0.5) - 1 - 1), 4)
-1.4981
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...errors import TefcoreError
from ..attribution.evaluate import FigureCache, RunSettings, checked_claims, claim_needs
from ..figures.catalogue import FIGURES, variant_key
from ..figures.quantities import swept_dimension
from .protocol import read_claims

__all__ = ["COMPUTE_ERRORS", "FigureCache", "RunSettings", "evaluate_rotor", "objective",
           "pass_count"]

#: What a figure that cannot be computed raises: tefcore's own errors (a trim that does
#: not converge, Floquet accuracy), a configuration refused at the figure's
#: parameters (ValueError) and a singular system.
COMPUTE_ERRORS = (TefcoreError, ValueError, ArithmeticError, np.linalg.LinAlgError)

#: Quantities read from the blade's natural frequencies alone (no Floquet sweep).
NATURAL = "natural_frequency_per_rev"


def _needs(claims, settings) -> dict:
    """``(figure, variant key) -> [overrides, values, natural only]`` of all the claims."""
    out: dict = {}
    for c in claims:
        if c.kind == "not_reproducible":        # no check: nothing to compute
            continue
        for fig, over, values in claim_needs(c, settings):
            key = (fig, variant_key(over))
            entry = out.setdefault(key, [over, [], True])
            entry[1] += [v for v in values if str(v) not in map(str, entry[1])]
            entry[2] = entry[2] and c.quantity == NATURAL and fig == c.figure
    return out


def _natural_only(figure, values) -> pd.DataFrame:
    """A figure's x values as a result table: what a natural-frequency claim reads of it."""
    from ...units import parse_quantity

    si = [parse_quantity(v, swept_dimension(figure)) if isinstance(v, str) else float(v)
          for v in values]
    return pd.DataFrame({"value_si": si, "value": si, "label": "", "status": "ok",
                         "real_part": np.nan})


def _results(cfg, claims, settings, cache):
    """Results by (figure, variant key), and the reason of each figure that failed."""
    results, broken = {}, {}
    for key, (over, values, natural) in _needs(claims, settings).items():
        fig = key[0]
        if fig in broken:
            continue
        try:
            if natural and fig in FIGURES:
                results[key] = _natural_only(fig, values)
            else:
                results[key] = cache.result(fig, cfg, settings, over, values)
        except COMPUTE_ERRORS as err:
            what = f"{fig} with {key[1]}" if key[1] else fig
            broken[fig] = f"{what} cannot be computed: {type(err).__name__}: {err}"
    return results, broken


def evaluate_rotor(cfg, claims, readings=("continued",), *, settings=None, cache=None,
                   flutter_quantities=("real_part", "damping", "damping_ratio")) -> dict:
    """Check `claims` on the rotor `cfg` under each reading, computing only what they read.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        The rotor (a sample of the space).
    claims : list of Claim
        The claims to check (a study passes only its fitted claims).
    readings : tuple of str
        Readings of the mode names (:func:`tefcore.paper.inference.protocol.read_claims`);
        the figures are computed once for all of them.
    settings : RunSettings, optional
        Sweep values and refinement; default the paper's values and the
        claims' x, without refinement, on :func:`tefcore.paper.figures.runs.base_config`'s
        section aerodynamics with `cfg` as the base.
    cache : FigureCache, optional
        Where the figures are kept (default: a fresh one in memory only is
        not possible -- a folder is needed; see :class:`FigureCache`).
    flutter_quantities : tuple of str
        Quantities of the flutter reading.

    Returns
    -------
    dict
        Reading -> table (columns of :func:`tefcore.paper.claims.checks.validate_figure`),
        plus ``"broken"`` -> {figure: reason} of the figures not computable.
    """
    settings = settings or RunSettings(base=cfg)
    if cache is None:
        raise ValueError("evaluate_rotor needs a FigureCache (a folder for its sweeps)")
    results, broken = _results(cfg, claims, settings, cache)
    out: dict = {"broken": broken}
    for r in readings:
        out[r] = checked_claims(read_claims(claims, r, flutter_quantities), cfg, results, broken)
    return out


def objective(table: pd.DataFrame, ambiguous: float = 0.0, no_margin_fail: float = -1.0) -> float:
    """Sum over the claims of ``tanh(margin)``: the number a study maximises.

    A pass adds up to +1 and a fail down to -1 (about the pass count minus the
    fail count when the margins are large), a claim far outside its threshold
    cannot outweigh the others, and a failing claim moved toward its threshold
    still raises the sum.  A claim without a measured margin adds +1 when it
    passes (a range claim with no tolerance), `ambiguous` when it is
    ambiguous, `no_margin_fail` when it failed (a fail whose margin is exactly
    zero has none: its check measured no distance) or its figure is not
    computable, nothing when it is not reproducible.

    Parameters
    ----------
    table : pandas.DataFrame
        ``status`` and ``margin`` columns (a checked claims table).
    ambiguous, no_margin_fail : float
        The protocol's values for claims without a margin.

    Returns
    -------
    float
    """
    m = table["margin"].to_numpy(float)
    s = table["status"].to_numpy(object)
    measured = np.isfinite(m) & ~((s == "fail") & (m == 0))
    value = np.where(measured, np.tanh(np.where(measured, m, 0.0)), np.nan)
    for status, v in (("pass", 1.0), ("ambiguous", ambiguous), ("fail", no_margin_fail),
                      ("not computable", no_margin_fail)):
        value = np.where(np.isnan(value) & (s == status), v, value)
    return float(np.nansum(value))


def pass_count(table: pd.DataFrame, tag: str | None = None) -> int:
    """Claims of `table` (of one `tag`, if given) whose status is ``pass``.

    Parameters
    ----------
    table : pandas.DataFrame
        A checked claims table (``status``, ``tag``).
    tag : str, optional
        ``"validation"`` or ``"calibration"``; None: every claim.

    Returns
    -------
    int
    """
    t = table if tag is None else table[table["tag"] == tag]
    return int((t["status"] == "pass").sum())
