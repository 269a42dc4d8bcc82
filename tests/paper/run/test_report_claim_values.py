"""Claims print their values with the quantity's name and the unit of the plot beside them
(Fig. 17's claim, a damping ratio, must not print as "0 1" -- unit "1" -- next to a
panel in 1/rev)."""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from tefcore.paper.claims.reference import load_claims, parse_claim
from tefcore.paper.claims.validation import validate_figure
from tefcore.paper.figures.quantities import QUANTITIES, QUANTITY_NAMES, quantity_unit

MU = np.round(np.arange(0.0, 0.31, 0.05), 2)


def fig17_table(tef_real):
    """A Fig. 17 sweep (advance ratio): the TEF at 10 /rev with the given real part."""
    rows = []
    for k, (label, real, freq) in enumerate((("TEF", tef_real, 10.0),
                                              ("blade lag 1", -0.02 + 0 * MU, 0.6))):
        for x, r in zip(MU, np.broadcast_to(real, len(MU)), strict=True):
            rows.append({"value": x, "value_si": x, "status": "ok", "track": k, "label": label,
                         "real_part": r, "frequency_per_rev": freq,
                         "damping_ratio": -r / np.hypot(r, freq)})
    return pd.DataFrame(rows)


def fig17_claim():
    (c,) = [c for c in load_claims() if c.id == "fig17-tef-weakly-unstable-hover"]
    return c


def test_every_quantity_has_a_name():
    assert set(QUANTITY_NAMES) == set(QUANTITIES)
    assert quantity_unit("damping_ratio") == "" and quantity_unit("real_part") == "1/rev"


@pytest.mark.parametrize("real0, status", [(0.05, "pass"), (-0.05, "fail")])
def test_fig17_damping_ratio_is_printed_with_its_name_and_its_real_part(real0, status):
    c = fig17_claim()
    assert c.quantity == "damping_ratio" and c.kind == "value" and c.x == 0.0
    row = validate_figure("fig17", fig17_table(real0 + 0.1 * MU), [c]).iloc[0]
    # the status is the check's, unchanged: a damping ratio in [-0.02, 0] at hover passes
    zeta = -real0 / np.hypot(real0, 10.0)
    assert row["status"] == status and row["computed_value"] == pytest.approx(zeta)
    assert row["expected"] == "-0.02 <= damping ratio <= 0 at x = 0"
    # the ratio by name, and the real part the panel's 1/rev axis shows beside it
    assert row["computed"] == f"damping ratio {zeta:.4g} (real part {real0:.4g} 1/rev)"
    assert not row["computed"].endswith(" 1") and " 1 " not in row["computed"]


def test_values_in_1_per_rev_name_their_quantity():
    c = parse_claim({"id": "t", "figure": "fig17", "tag": "validation", "statement": "s",
                     "condition": "c", "kind": "value", "mode": "TEF", "quantity": "real_part",
                     "x": 0.1, "expected": 0.06, "tolerance": 0.01, "tolerance_reason": "test"})
    row = validate_figure("fig17", fig17_table(0.05 + 0.1 * MU), [c]).iloc[0]
    assert row["status"] == "pass"
    assert row["expected"] == "real part 0.06 ± 0.01 1/rev at x = 0.1"
    assert row["computed"] == "real part 0.06 1/rev"          # no damping-ratio companion


def test_a_dimensionless_trend_says_what_it_is_not_1():
    c = replace(fig17_claim(), kind="trend", direction="increasing", method="slope", x=None,
                lower=None, upper=None)
    row = validate_figure("fig17", fig17_table(0.05 - 0.1 * MU), [c]).iloc[0]
    assert row["computed"].endswith("(damping ratio)")
