"""What each assumption does: flutter-root identification, headlines, tornado table."""

import math

import matplotlib
import numpy as np
import pandas as pd
import pytest
from numpy.testing import assert_allclose

from tefcore.config.io import load_config
from tefcore.linear.stability import stability
from tefcore.paper.attribution.sensitivity import (
    ASSUMPTIONS,
    HEADLINES,
    Headline,
    apply_assumption,
    flutter_root,
    headline_results,
    sensitivity,
    tornado_plot,
    tornado_table,
)
from tefcore.paper.calibration import frequency_checks

matplotlib.use("Agg")
MDART = load_config("mdart")
HOVER_IMBALANCED = {"flap.cg_offset": 0.33, "flap.overhang": 0.29, "flight.advance_ratio": 0.0}


def test_no_flap_no_flutter_root():
    bare = stability(MDART.with_overrides({"model.tef": "none", "flight.advance_ratio": 0.0}))
    with pytest.raises(ValueError, match="no root carries the flap"):
        flutter_root(bare)


def test_flutter_root_of_the_balanced_flap_is_the_root_the_flap_destabilises_most():
    # mass-balanced flap in hover: nothing flutters; the flutter root is the
    # least stable flap-induced root -- blade torsion 2, which freeing the flap
    # makes less stable (-0.58 -> -0.45 /rev, measured), not the heavily damped
    # flap mode (-3.45 /rev) that a flap-share rule picked
    res = stability(MDART.with_overrides({**HOVER_IMBALANCED, "flap.cg_offset": 0.0}))
    row = flutter_root(res)
    tef = res.modes[res.modes["label"] == "TEF"].iloc[0]
    assert row["real_part"] < 0 and row["label"] == "blade torsion 2"
    # the flap's doing: raised by more than the plot resolution (0.01 /rev)
    assert row["real_part"] > row["real_part_uncoupled"] + 0.01
    assert tef["real_part"] < row["real_part"]


def test_flutter_root_is_the_least_stable_flap_root():
    res = stability(MDART.with_overrides(HOVER_IMBALANCED))
    row = flutter_root(res)
    share = res.modes["share_TEF"].to_numpy()
    involved = share >= 0.1
    assert row["real_part"] == res.modes["real_part"][involved].max()
    # the imbalanced flap flutters (+3.0 /rev in hover, docs/theory.md 2.8)
    assert row["real_part"] > 0
    # a root without the flap never qualifies, however unstable: a fake one
    res.modes.loc[int(np.argmin(share)), "real_part"] = 99.0
    assert flutter_root(res)["real_part"] < 99.0


def test_onset_brackets_a_zero_crossing():
    # a coarse Fig. 8 scan: the onset lies between the grid points where the
    # flutter root changes sign and the root's real part vanishes there
    # (0.55, not 0.6: beyond ~0.59 the over-balanced flap diverges statically and
    # its trim is refused, tefcore.trimming.trim.MAX_FLAP_DEFLECTION_DEG)
    h = Headline("fig8", "", {"flight.advance_ratio": 0.0, "flap.cg_offset": 0.0},
                 "flap.overhang", (0.0, 0.2, 0.4, 0.55))
    out = headline_results(MDART, headlines=[h], xtol=1e-6)
    x = float(out["value"].iloc[0])
    assert out["status"].iloc[0] == "ok" and 0.4 < x < 0.55
    cfg = MDART.with_overrides({**h.fixed, "flap.overhang": x})
    near = [flutter_root(stability(cfg.with_overrides({"flap.overhang": x + d})))["real_part"]
            for d in (-1e-4, 1e-4)]
    assert near[0] < 0 < near[1]


def test_onset_outside_the_range_is_reported_not_invented():
    h = Headline("fig8", "", {"flight.advance_ratio": 0.0, "flap.cg_offset": 0.0},
                 "flap.overhang", (0.0, 0.1, 0.2))
    out = headline_results(MDART, headlines=[h])
    assert math.isnan(out["value"].iloc[0]) and out["status"].iloc[0].startswith("stable up to")
    g = Headline("g", "", {"flight.advance_ratio": 0.0, "flap.cg_offset": 0.33},
                 "flap.overhang", (0.29, 0.3))
    out = headline_results(MDART, headlines=[g])
    assert out["status"].iloc[0].startswith("unstable already at")


def test_growth_headline_is_the_flutter_root():
    h = [x for x in HEADLINES if x.name == "growth_hover"]
    out = headline_results(MDART, headlines=h)
    res = stability(MDART.with_overrides(h[0].fixed))
    assert out["value"].iloc[0] == flutter_root(res)["real_part"]


def test_recalibrated_assumption_keeps_the_stated_frequencies():
    # changing the section inertia re-fits GJ, horn arm and pitch link: the four
    # stated torsion frequencies stay within the 2 % gate
    for end in ("low", "high"):
        cfg = apply_assumption(MDART, "section polar inertia", end)
        assert cfg.blade.im_lag[10] == pytest.approx(
            MDART.blade.im_lag[10] * (0.9 if end == "low" else 1.1), rel=1e-12)
        assert frequency_checks(cfg)["error_percent"].abs().max() < 2.0
    with pytest.raises(ValueError, match="unknown assumption"):
        apply_assumption(MDART, "flap colour", "low")
    with pytest.raises(ValueError, match="end must be"):
        apply_assumption(MDART, "flap mass", "middle")


def test_lift_slope_assumption_keeps_the_stated_lock_number():
    for end in ("low", "high"):
        cfg = apply_assumption(MDART, "lift slope", end)
        assert cfg.lock_number == pytest.approx(MDART.lock_number, rel=1e-12)


def test_every_assumption_names_real_fields_and_a_basis():
    for a in ASSUMPTIONS:
        assert a.basis and a.low_label and a.high_label
        for f in a.fields:
            MDART.get(f)
        lo, hi = a.low(MDART), a.high(MDART)
        assert set(lo) == set(hi) and set(a.fields) <= set(lo) | {"blade.mass_scale"}


def test_sensitivity_table_and_tornado():
    subset = [a for a in ASSUMPTIONS if a.name in ("flap mass", "lag damper")]
    heads = [h for h in HEADLINES if h.name == "growth_hover"]
    t = sensitivity(MDART, subset, headlines=heads)
    assert len(t) == 5 and set(t["end"]) == {"baseline", "low", "high"}
    base = t[t["end"] == "baseline"]["value"].iloc[0]
    assert_allclose(t["change"], t["value"] - base, rtol=0, atol=0)
    # the heavier flap is the more unstable one (inertial coupling ~ S_f)
    mass = t[t["assumption"] == "flap mass"].set_index("end")["value"]
    assert mass["low"] < base < mass["high"]
    wide = tornado_table(t)
    assert list(wide.index) == ["flap mass", "lag damper", "baseline"]   # by spread
    assert wide.loc["baseline", ("growth_hover", "low")] == round(base, 3)
    ax = tornado_plot(t, "growth_hover")
    assert len(ax.patches) >= 4
    # a configuration the data do not admit is a row with its reason, not a crash
    huge = [a for a in ASSUMPTIONS if a.name == "flap mass"][0]
    bad = type(huge)(**{**huge.__dict__, "high": lambda c: {"flap.mass": "2 lb/ft"}})
    t2 = sensitivity(MDART, [bad], headlines=heads)
    row = t2[t2["end"] == "high"].iloc[0]
    assert math.isnan(row["value"]) and "does not fit" in row["status"]
    assert isinstance(t2, pd.DataFrame)
