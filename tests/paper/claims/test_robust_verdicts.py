"""Verdicts that round-off cannot tip: Figs. 12 and 15 under nudges of the inputs.

Figs. 12 and 15 hold the reproduction's k/2 locks: at a soft actuator the
imbalanced flap's heavily damped root locks on the negative real axis (its two
real roots read 3.5 and 4.5 /rev), and Fig. 15's TEF locks at 5 /rev beside
blade lag 2.  Which of a lock's two real roots a path reached is decided by
round-off, and so was a name, its certainty and Fig. 12a's slope (0.0876
against 0.0824) before locked pairs were named as pairs.  A relative nudge of
1e-12 or 1e-9 of the blade's mass, the rotor speed, the air density or the
radius changes the round-off as another BLAS kernel does: every claim's
status, every computed value (to 1e-6 relative), every root's name and its
certainty must stay as they are (docs/theory.md 9.5).
"""

from __future__ import annotations

import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.paper.claims.robustness import NUDGES, NudgedRun, differences, nudged_runs

FIGURES = ("fig12", "fig15")


@pytest.fixture(scope="module")
def runs():
    return nudged_runs(load_config("mdart"), FIGURES, NUDGES)


@pytest.mark.parametrize("k", range(1, len(NUDGES) + 1))
def test_a_nudge_moves_no_status_value_or_name(runs, k):
    base, other = runs[0], runs[k]
    assert len(base.claims) >= 10          # the figures' claims were checked
    found = differences(base, other)
    assert not found, "\n".join(found[:40])


def test_the_comparison_sees_a_flipped_name_a_status_and_a_jumped_value(runs):
    # the check can fail: a lock's reading moved by 1/rev, a status and a name changed
    base = runs[0]
    claims = base.claims.copy()
    row = claims.index[claims["id"] == "fig12a-imbalanced-smaller-slope"][0]
    claims.loc[row, "computed_value"] = claims.loc[row, "computed_value"] * 1.06
    claims.loc[row, "status"] = "fail"
    tables = {k: v.copy() for k, v in base.tables.items()}
    t = tables["fig12"]
    i = t.index[t["label"] == "TEF"][0]
    t.loc[i, "label"] = "TEF (locked)"
    t.loc[i + 1, "identity_certain"] = not t.loc[i + 1, "identity_certain"]
    found = differences(base, NudgedRun("planted", claims, tables))
    assert any("identity_certain" in d for d in found)
    assert not any("identity_certain" in d for d in differences(
        base, NudgedRun("planted", claims, tables), certainty=False))
    assert any("fig12a-imbalanced-smaller-slope pass -> fail" in d for d in found)
    assert any("fig12a-imbalanced-smaller-slope value" in d for d in found)
    assert any("label TEF -> TEF (locked)" in d for d in found)


def test_a_near_zero_slope_is_compared_to_the_change_its_claim_measures():
    # Fig. 10b's slope (4.96e-6 /rev per lb/in) is a small difference of growth
    # rates: its verdict is its sign against the panel's change (margin 0.028, a
    # scale of 1.8e-4), and so is its agreement under a nudge -- 1e-6 of that
    # scale, not of the slope, and not an absolute 1e-8 (two thousandths of it)
    claims = pd.DataFrame({"id": ["fig10b-tef-more-unstable"], "kind": ["trend"],
                           "expected": ["increasing (slope)"],
                           "computed_value": [4.9649e-6], "margin": [0.027700],
                           "status": ["pass"]})
    base = NudgedRun("base", claims, {})

    def moved(by):
        other = claims.copy()
        other["computed_value"] = claims["computed_value"] + by
        return differences(base, NudgedRun("nudged", other, {}))

    assert not moved(-7.5e-11)         # measured under a radius nudge: 4e-7 of the scale
    assert moved(5e-10)                # 3e-6 of the scale: round-off does not do that
    constant = claims.assign(expected="constant: peak-to-peak <= 0.1", kind="trend")
    # a statistic without a signed margin keeps the absolute floor
    assert not differences(NudgedRun("b", constant, {}), NudgedRun(
        "n", constant.assign(computed_value=4.9649e-6 + 5e-9), {}))
