"""Check the claims of one figure against its result (:func:`validate_figure`).

Each claim is judged by its kind's check (:mod:`tefcore.paper.claims.kinds`) on
the series it reads (:mod:`tefcore.paper.claims.context`).  A verdict that a
near tie could tip is checked under every reading the tie allows: the names
on either side of each exceptional point in the claim's range, the readings
of each locked root's frequency; it stands where every reading gives it and
is ``ambiguous`` otherwise, with the readings in its reason.  Running every
figure is :func:`tefcore.paper.claims.validation.validate_all`.
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

from ...modes.names import pair_labels
from .context import Ambiguous, ClaimFailed, Context, NotEvaluated, g4
from .exceptional import flutter_reading, where
from .kinds import CHECKS
from .reference import Claim, load_claims

__all__ = ["COLUMNS", "MAX_CHOICES", "MAX_LOCK_READINGS", "validate_figure"]


COLUMNS = ["id", "figure", "panel", "kind", "tag", "mode", "quantity", "statement", "expected",
           "computed", "computed_value", "margin", "status", "reason", "recorded_status"]


def _row(c: Claim, expected="", computed="", value=np.nan, status="", reason="",
         margin=np.nan):
    return {"id": c.id, "figure": c.figure, "panel": c.panel, "kind": c.kind, "tag": c.tag,
            "mode": c.mode, "quantity": c.quantity, "statement": c.statement,
            "expected": expected, "computed": computed, "computed_value": value,
            "margin": margin, "status": status, "reason": reason,
            "recorded_status": c.recorded_status}


def validate_figure(name: str, result, claims=None, *, cfg=None, variants=None, others=None,
                    compute_missing: bool = True) -> pd.DataFrame:
    """Check the claims of one figure against its result.

    Parameters
    ----------
    name : str
        ``"fig3"`` ... ``"fig17"`` (stability figures of
        :data:`tefcore.paper.figures.catalogue.FIGURES`) or ``"fig5"``, ``"fig6"``, ``"fig7"``.
    result : tefcore.sweeps.sweep.SweepResult, DataFrame, dict or None
        The figure's output: SweepResult (or its table), the DataFrame of
        figs. 5 and 7, or the dict of fig. 6.  ``None``: computed when needed.
    claims : list of Claim, optional
        Default: the claims of `name` in the reference data.
    cfg : Config, optional
        Base configuration (default MDART) for anything computed here.
    variants : dict, optional
        :func:`variant_key` of overrides -> result of the figure with them.
    others : dict, optional
        Figure name -> result, for comparisons with another figure.
    compute_missing : bool
        Compute a missing variant/other figure; if False such a claim is
        ``not reproducible``.

    Returns
    -------
    DataFrame
        One row per claim, columns :data:`COLUMNS`.
    """
    if claims is None:
        claims = [c for c in load_claims() if c.figure == name]
    ctx = Context(name, result, cfg, variants, others, compute_missing)
    rows = []
    for c in claims:
        if c.figure != name:
            raise ValueError(f"claim {c.id} is about {c.figure}, not {name}")
        if c.kind == "not_reproducible":
            rows.append(_row(c, status="not reproducible", reason=c.reason))
            continue
        ctx.locks, ctx.margin = [], np.nan
        try:
            expected, computed, value, ok, why = CHECKS[c.kind](c, ctx)
        except ClaimFailed as err:
            rows.append(_row(c, status="fail", reason=str(err)))
            continue
        except NotEvaluated as err:
            rows.append(_row(c, status="not reproducible", reason=str(err)))
            continue
        except Ambiguous as err:
            rows.append(_across_exceptional_points(c, ctx, err))
            continue
        status = "not reproducible" if ok is None else ("pass" if ok else "fail")
        row = _row(c, expected, computed, value, status, why, _signed(ctx.margin, ok))
        rows.append(_across_readings(c, ctx, row) if ctx.locks else row)
    return pd.DataFrame(rows, columns=COLUMNS)


#: Locked points of one claim whose every combination of readings is checked
#: (3**5 = 243 checks on the tables already computed); with more, the claim
#: stands on the readings continuity gives and its reason says so.
MAX_LOCK_READINGS = 5


def _across_readings(c: Claim, ctx: Context, row: dict) -> dict:
    """A claim that reads a locked root's frequency, checked with every possible reading.

    Its verdict stands where every combination of the locked points' readings
    (:func:`lock_readings`) gives it; otherwise the claim is ``ambiguous`` and
    the reason names the points and what each reading gives.  The computed
    value stays the one of the readings continuity gives (the point's own).
    """
    locks = list(dict.fromkeys((w, cand) for w, cand in ctx.locks))
    where = ", ".join(f"{g4(w[2])} ({' or '.join(g4(v) for v in cand)} /rev)"
                      for w, cand in locks)
    if len(locks) > MAX_LOCK_READINGS:
        note = (f"{len(locks)} locked points in its range ({where}): checked with the "
                "readings continuity gives")
        row["reason"] = f"{row['reason']}; {note}" if row["reason"] else note
        return row
    statuses = []
    for combo in itertools.product(*(cand for _, cand in locks)):
        alt = Context.__new__(Context)
        alt.__dict__.update(ctx.__dict__)
        alt.locks = []
        alt.reading = {w: v for (w, _), v in zip(locks, combo, strict=True)}
        statuses.append(_checked(c, alt)["status"])
    if len(set(statuses)) == 1 and statuses[0] == row["status"]:
        note = (f"decided for every reading of the locked root(s) at {where}: a real "
                "multiplier's frequency is known only modulo 1/rev and up to its sign")
        row["reason"] = f"{row['reason']}; {note}" if row["reason"] else note
        return row
    seen = ", ".join(sorted(set(statuses)))
    return _row(c, status="ambiguous",
                reason=f"the verdict depends on the reading of a locked root's frequency "
                       f"({where}): {seen} among the readings")


#: Exceptional points in one claim's range whose every choice of names is tried
#: (2**7 = 128 checks of the claim on the tables already computed); with more
#: the claim is left undecided without its verdicts.  Fig. 14's and Fig. 15's
#: TEF claims hold 6 each (the imbalanced flap's TEF, flap 5 and torsion 2
#: cluster at mu = 0.3, measured); with 7 the reproduction's notebooks 05 and
#: 06 took 50 s of wall time together, their claims among them.
MAX_CHOICES = 7


def _checked(c: Claim, ctx: Context) -> dict:
    """One claim's row (a dict of :func:`_row`) under the context's choice of names."""
    ctx.margin = np.nan
    try:
        expected, computed, value, ok, why = CHECKS[c.kind](c, ctx)
    except ClaimFailed as err:
        return _row(c, status="fail", reason=str(err))
    except NotEvaluated as err:
        return _row(c, status="not reproducible", reason=str(err))
    except Ambiguous as err:
        return _row(c, status="ambiguous", reason=str(err))
    status = "not reproducible" if ok is None else ("pass" if ok else "fail")
    return _row(c, expected, computed, value, status, why, _signed(ctx.margin, ok))


def _across_exceptional_points(c: Claim, ctx: Context, err: Ambiguous) -> dict:
    """A claim whose range holds exceptional points: decided when no choice matters.

    At an exceptional point which root carries a name has no answer.  The
    claim is checked with the names as continuation gives them and with the
    pair's names exchanged beyond each point (every combination, up to
    :data:`MAX_CHOICES` points, until two disagree); when every choice gives
    the same verdict it stands (its reason says so), otherwise the claim is
    ``ambiguous`` and the reason names the point and what the names as
    continued and the first choice that disagrees give.
    """
    points = err.points
    if not points or len(points) > MAX_CHOICES:
        why = str(err) + (f" ({len(points)} exceptional points)" if points else "")
        return _row(c, status="ambiguous", reason=why)
    outcomes = []
    for mask in np.ndindex(*(2,) * len(points)):
        alt = Context.__new__(Context)
        alt.__dict__.update(ctx.__dict__)
        alt.strict = False
        alt.swaps = {}
        for (key, p), take in zip(points, mask, strict=True):
            if take:
                alt.swaps.setdefault(key, []).append(p)
        outcomes.append(_checked(c, alt))
        if outcomes[-1]["status"] != outcomes[0]["status"]:
            # two choices disagree: the claim is undecided whatever the rest
            # give (the reason names the first choice and this one), so the
            # rest are not checked (measured: 2^6 choices of Figs. 14 and 15
            # took 5 of notebook 06's 48 s)
            break
    statuses = [o["status"] for o in outcomes]
    places = "; ".join(f"{p['modes']} {where(p)} ({p['kind']})" for _, p in points)
    # the names whose roots meet there (a claim about blade flap 1 relative to
    # the TEF depends on the TEF's name, not on blade flap 1's)
    met = list(dict.fromkeys(m for _, p in points for m in pair_labels(p["modes"])))
    named = " or ".join(repr(m) for m in met) if met else repr(c.mode)
    if len(set(statuses)) == 1 and statuses[0] != "ambiguous":
        row = outcomes[0]
        note = (f"decided whichever root carries {named} at the exceptional point(s) "
                f"inside its range ({places}): every choice gives {statuses[0]}")
        row["reason"] = f"{row['reason']}; {note}" if row["reason"] else note
        return row
    other = next(s for s in statuses if s != statuses[0])
    seen = f"{statuses[0]} with the names as continued, {other} with them exchanged"
    return _row(c, status="ambiguous",
                reason=f"an exceptional point lies inside the claim's range ({places}): which "
                       f"root is {named} has no answer there, and the verdict depends on "
                       f"it ({seen}){flutter_reading(c, lambda alt: _checked(alt, ctx))}")


def _signed(margin, ok) -> float:
    """A check's margin with the sign of its verdict: inside its threshold (pass) > 0.

    The margins are measured against each claim's own tolerance or the panel's
    scale (dimensionless: +1 at the centre of a tolerance band, 0 on its edge);
    a pass with a margin rounded to zero or below, or a fail above, keeps the
    verdict's sign (the slack of the threshold's comparison).
    """
    if ok is None or not np.isfinite(margin):
        return np.nan
    return abs(margin) if ok else -abs(margin)
