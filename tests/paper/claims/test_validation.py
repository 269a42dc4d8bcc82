"""Validation: each comparison kind on synthetic results (pass and fail), curve
masking, status bookkeeping, and one smoke test on a real 3-point Fig. 8 sweep."""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from tefcore.paper.claims.files import ReferenceDataError
from tefcore.paper.claims.reference import load_claims, parse_claim
from tefcore.paper.claims.validation import (
    claims_score,
    compare_curve,
    reference_curves,
    stability_intervals,
    update_recorded_status,
    validate_figure,
    variant_key,
    worse_than_recorded,
    zero_crossings,
)
from tefcore.paper.figures.catalogue import run_figure

X = np.round(np.arange(0.0, 0.41, 0.05), 2)  # a synthetic CG-offset sweep (fig9)


def sweep_table(x=X, **modes):
    """Tidy sweep table: mode label -> (real_part, frequency_per_rev) arrays."""
    rows = []
    for k, (label, (re_, fr)) in enumerate(modes.items()):
        for xi, r, f in zip(x, np.broadcast_to(re_, len(x)), np.broadcast_to(fr, len(x)),
                            strict=True):
            rows.append({"value": xi, "value_si": xi, "status": "ok", "track": k,
                         "label": label, "real_part": r, "frequency_per_rev": f,
                         "damping_ratio": -r / f})
    return pd.DataFrame(rows)


#: TEF goes unstable at x = 0.25 (linear), flap damping decreases, lag constant
BASE = sweep_table(**{"TEF": (4 * (X - 0.25), 10 - 5 * X),
                      "blade flap 1 (locked)": (-0.8 + X, 1.0),
                      "blade lag 1": (-0.02 + 0.001 * X, 0.6),
                      "blade torsion 1": (-0.5 - X, 3.0)})


def claim(**kw):
    raw = {"id": "t", "figure": "fig9", "tag": "validation", "statement": "s",
           "condition": "c", **kw}
    return parse_claim(raw)


def check(c, table=BASE, **kw):
    row = validate_figure(c.figure, table, [c], **kw).iloc[0]
    return row["status"], row


TOL = {"tolerance_reason": "test"}


# ------------------------------------------------------------------ primitives


def test_zero_crossings_and_intervals():
    x, y = [0, 1, 2, 3, 4], [-1.0, 1.0, 1.0, -3.0, 1.0]
    assert zero_crossings(x, y) == [(0.5, "destabilising"), (2.25, "stabilising"),
                                    (3.75, "destabilising")]
    assert stability_intervals(x, y) == [(0.5, 2.25), (3.75, 4.0)]
    assert stability_intervals(x, y, "stable") == [(0.0, 0.5), (2.25, 3.75)]
    assert stability_intervals([0, 1], [1.0, 2.0]) == [(0.0, 1.0)]
    assert zero_crossings([0, 1], [-1.0, -2.0]) == []


# ------------------------------------------------------------------ kinds


@pytest.mark.parametrize("kw, status", [
    ({"expected": 0.25, "tolerance": 0.02}, "pass"),
    ({"expected": 0.30, "tolerance": 0.02}, "fail"),                    # outside tolerance
    ({"expected": 0.25, "tolerance": 0.02, "direction": "stabilising"}, "fail"),
    ({}, "pass"),                                                         # existence only
])
def test_threshold(kw, status):
    kw = {"direction": "destabilising", **kw}
    c = claim(kind="threshold", mode="TEF", **({**TOL, **kw} if "tolerance" in kw else kw))
    got, row = check(c)
    assert got == status
    assert "destabilising at 0.25" in row["computed"]
    if kw["direction"] == "destabilising":
        assert row["computed_value"] == pytest.approx(0.25)


def test_threshold_fails_when_the_state_does_not_stay():
    t = sweep_table(TEF=(np.where(X < 0.3, 4 * (X - 0.12), -1.0), 10.0))
    got, row = check(claim(kind="threshold", mode="TEF", direction="destabilising"), t)
    assert got == "fail" and "end state" in row["reason"]


XT = np.round(np.arange(0.30, 0.605, 0.01), 2)


def _crossing_at(*points):
    """A TEF real part through (x, y) ``points`` (linear between), on :data:`XT`."""
    xs, ys = zip(*points, strict=True)
    return sweep_table(XT, TEF=(np.interp(XT, xs, ys), 10.0))


def test_threshold_fails_on_a_root_unstable_before_the_onset_and_stable_again():
    # Fig. 8's TEF root as computed: unstable from 0.43 to 0.47, stable again, unstable
    # from 0.52 -- the last onset lies within 0.5 +- 0.05, the first instability does not
    t = _crossing_at((0.30, -1.0), (0.43, 0.0), (0.45, 0.2), (0.47, 0.0), (0.50, -0.3),
                     (0.52, 0.0), (0.60, 1.0))
    c = claim(kind="threshold", mode="TEF", direction="destabilising", expected=0.5,
              tolerance=0.05, **TOL)
    got, row = check(c, t)
    assert got == "fail"
    assert "unstable on [0.43, 0.47] below the claimed onset 0.5 ± 0.05" in row["reason"]
    assert "crosses 3 times" in row["reason"] and "0.52" in row["reason"]
    assert row["computed_value"] == pytest.approx(0.52)


def test_threshold_passes_a_root_that_crosses_within_the_tolerance_and_says_so():
    t = _crossing_at((0.30, -1.0), (0.47, 0.0), (0.48, 0.1), (0.49, 0.0), (0.50, -0.1),
                     (0.52, 0.0), (0.60, 1.0))
    c = claim(kind="threshold", mode="TEF", direction="destabilising", expected=0.5,
              tolerance=0.05, **TOL)
    got, row = check(c, t)
    assert got == "pass" and "crosses 3 times" in row["reason"]
    assert row["computed_value"] == pytest.approx(0.52)


def test_threshold_with_units_and_no_crossing():
    x = np.array([100.0, 200.0, 300.0]) * 175.12683524647636  # lb/in -> N/m
    t = sweep_table(x, TEF=(np.array([1.0, -1.0, -3.0]), 5.0))
    c = parse_claim({"id": "u", "figure": "fig10", "kind": "threshold", "tag": "validation",
                     "statement": "s", "condition": "c", "mode": "TEF", "x_unit": "lb/in",
                     "direction": "stabilising", "expected": 150, "tolerance": 1, **TOL})
    status, row = validate_figure("fig10", t, [c]).iloc[0][["status", "computed_value"]]
    assert status == "pass" and row == pytest.approx(150)
    t2 = sweep_table(x, TEF=(-1.0, 5.0))
    res = validate_figure("fig10", t2, [c]).iloc[0]
    assert res["status"] == "fail" and "no stabilising crossing" in res["reason"]


def test_threshold_margin_without_a_claimed_crossing():
    # a root that never crosses: its margin is how far it stays from zero against the
    # panel's range (here always stable, 1 from zero on a range of 2: -0.5)
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    _, row = check(c, sweep_table(TEF=(np.linspace(-3.0, -1.0, len(X)), 10.0)))
    assert row["status"] == "fail" and row["margin"] == pytest.approx(-0.5)
    # a root that crosses only the other way (unstable, then stable) changes state
    # opposite to the claim: a fail by structure, margin -1, never a near tie at 0
    _, row = check(c, sweep_table(TEF=(-4 * (X - 0.25), 10.0)))
    assert row["status"] == "fail" and "no destabilising crossing" in row["reason"]
    assert row["margin"] == -1.0


@pytest.mark.parametrize("interval, tol, status", [
    ([0.25, 0.40], 0.01, "pass"), ([0.15, 0.40], 0.05, "fail"), ([0.25, 0.35], 0.02, "fail")])
def test_range(interval, tol, status):
    c = claim(kind="range", mode="TEF", state="unstable", expected_interval=interval,
              tolerance=tol, **TOL)
    assert check(c)[0] == status


def test_range_with_two_intervals_fails():
    t = sweep_table(TEF=(np.array([1, -1, -1, 1, 1, -1, 1, 1, 1.0]), 10.0))
    got, row = check(claim(kind="range", mode="TEF", state="unstable",
                           expected_interval=[0.0, 0.4], tolerance=0.1, **TOL), t)
    assert got == "fail" and "3 unstable intervals" in row["reason"]


@pytest.mark.parametrize("kw, status", [
    ({"mode": "blade flap 1", "quantity": "damping", "direction": "decreasing"}, "pass"),
    ({"mode": "blade flap 1", "quantity": "damping", "direction": "increasing"}, "fail"),
    ({"mode": "TEF", "quantity": "frequency_per_rev", "direction": "decreasing",
      "method": "net_change"}, "pass"),
    ({"mode": "blade torsion 1", "quantity": "real_part", "direction": "decreasing",
      "interval": [0.1, 0.3]}, "pass"),
    ({"mode": "blade lag 1", "quantity": "damping", "direction": "constant", "tolerance": 0.1,
      "tolerance_type": "relative_to_mode", "reference_mode": "TEF", **TOL}, "pass"),
    ({"mode": "blade flap 1", "quantity": "damping", "direction": "constant", "tolerance": 0.1,
      "tolerance_type": "relative_to_mode", "reference_mode": "TEF", **TOL}, "fail"),
    ({"mode": "blade lag 1", "quantity": "real_part", "direction": "constant",
      "tolerance": 0.05, "tolerance_type": "relative", **TOL}, "pass"),
    ({"mode": "blade torsion 1", "quantity": "real_part", "direction": "constant",
      "tolerance": 0.1, **TOL}, "fail"),
])
def test_trend(kw, status):
    assert check(claim(kind="trend", **kw))[0] == status


def test_locked_label_matches_and_missing_mode_fails_with_labels():
    got, row = check(claim(kind="trend", mode="blade flap 1", quantity="damping",
                           direction="decreasing"))
    assert got == "pass"
    got, row = check(claim(kind="trend", mode="blade flap 2", quantity="damping",
                           direction="decreasing"))
    assert got == "fail" and "no mode 'blade flap 2'" in row["reason"] and "TEF" in row["reason"]


@pytest.mark.parametrize("kw, status", [
    ({"x": 0.25, "expected": 0.0, "tolerance": 1e-9}, "pass"),
    ({"x": 0.125, "expected": -0.5, "tolerance": 0.01}, "pass"),         # interpolated
    ({"x": 0.4, "expected": 0.5, "tolerance": 0.05}, "fail"),
    ({"x": 0.4, "lower": 0.0}, "pass"),
    ({"x": 0.0, "lower": 0.0}, "fail"),
    ({"x": 0.5, "lower": 0.0}, "fail"),                                  # never extrapolated
    ({"x": 0.4, "relative_to": 0.0, "expected": -1.6, "tolerance": 0.01}, "pass"),
])
def test_value(kw, status):
    kw = {**kw, **TOL} if "tolerance" in kw else kw
    got, row = check(claim(kind="value", mode="TEF", quantity="real_part", **kw))
    assert got == status
    if kw["x"] == 0.5:
        assert "outside the computed range" in row["reason"]


def test_value_relative_tolerance_on_natural_frequency_column():
    t = BASE.assign(natural_frequency_per_rev=3.0 + BASE["value_si"])
    c = claim(kind="value", mode="TEF", quantity="natural_frequency_per_rev", x=0.2,
              expected=3.2, tolerance=0.02, tolerance_type="relative", **TOL)
    assert check(c, t)[0] == "pass"
    far = claim(kind="value", mode="TEF", quantity="natural_frequency_per_rev", x=0.2,
                expected=3.4, tolerance=0.02, tolerance_type="relative", **TOL)
    assert check(far, t)[0] == "fail"


def test_response_figures_fig6_fig7():
    fig6 = {"half_peak_to_peak_deg": 2.28, "peak_power": 1.0, "mean_power": 0.5}
    raw = {"id": "a", "figure": "fig6", "kind": "value", "tag": "validation", "statement": "s",
           "condition": "c", "quantity": "half_peak_to_peak_deg", "expected": 2.3,
           "tolerance": 0.1, **TOL}
    assert validate_figure("fig6", fig6, [parse_claim(raw)]).status.item() == "pass"
    raw["expected"] = 2.5
    assert validate_figure("fig6", fig6, [parse_claim(raw)]).status.item() == "fail"
    fig7 = pd.DataFrame({"overhang": [0.0, 0.29, 0.4, 0.5],
                         "half_peak_to_peak_deg": [1.5, 2.0, 2.5, 5.0],
                         "peak_power": [10.0, 4.0, 5.0, 20.0], "mean_power": 1.0})
    reduce = parse_claim({**raw, "figure": "fig7", "quantity": "peak_power", "x": 0.29,
                          "relative_to": 0.0, "expected": -0.6, "tolerance": 0.1})
    steeper = parse_claim({"id": "b", "figure": "fig7", "kind": "comparison", "tag": "validation",
                           "statement": "s", "condition": "c", "statistic": "slope",
                           "quantity": "half_peak_to_peak_deg", "relation": "greater",
                           "interval": [0.4, 0.5], "other_interval": [0.0, 0.4]})
    out = validate_figure("fig7", fig7, [reduce, steeper])
    assert out.status.tolist() == ["pass", "pass"]
    assert out.computed_value.iloc[0] == pytest.approx(-0.6)


def test_comparisons_variants_and_other_figures():
    balanced = sweep_table(TEF=(-1.0, 10 + 10 * X))
    imbalanced = sweep_table(TEF=(-1.0, 8 + 5 * X))
    c = claim(kind="comparison", mode="TEF", quantity="frequency_per_rev", statistic="slope",
              relation="less", other_overrides={"flap.cg_offset": 0.0})
    key = variant_key({"flap.cg_offset": 0.0})
    assert check(c, imbalanced, variants={key: balanced})[0] == "pass"
    assert check(c, balanced, variants={key: imbalanced})[0] == "fail"
    # without the variant and not allowed to compute it: not reproducible, with the reason
    got, row = check(c, imbalanced, compute_missing=False)
    assert got == "not reproducible" and "flap.cg_offset" in row["reason"]
    # another figure: peak-to-peak smaller in fig9 than in fig8
    p2p = claim(kind="comparison", mode="TEF", quantity="real_part", statistic="peak_to_peak",
                relation="less",
                other_figure="fig8")
    big = sweep_table(TEF=(10 * X, 10.0))
    assert check(p2p, BASE, others={"fig8": big})[0] == "pass"
    assert check(p2p, big, others={"fig8": BASE})[0] == "fail"


@pytest.mark.parametrize("other, relation, status", [
    ("blade flap 1", "positive", "pass"), ("blade torsion 1", "negative", "pass"),
    ("blade torsion 1", "positive", "fail"), ("blade lag 1", "negative", "fail")])
def test_correlation(other, relation, status):
    t = BASE.copy()
    lag = t["label"] == "blade lag 1"
    t.loc[lag, "real_part"] = 0.01 * np.cos(40 * t.loc[lag, "value_si"])  # unrelated wiggle
    c = claim(kind="comparison", mode="TEF", quantity="real_part", statistic="correlation",
              relation=relation, other_mode=other, tolerance=0.5, **TOL)
    assert check(c, t)[0] == status


def test_not_reproducible_is_reported_with_its_reason():
    c = claim(kind="not_reproducible", reason="no test data exists")
    got, row = check(c, None)
    assert got == "not reproducible" and row["reason"] == "no test data exists"


# ------------------------------------------------------------------ curves


def test_compare_curve_masks_outside_the_model_range_never_clamps():
    pts = pd.DataFrame({"x": [-0.1, 0.0, 0.2, 0.4, 0.5], "y": [9.0, 0.0, 2.0, 4.1, 9.0],
                        "band": 0.2})
    out = compare_curve([0.0, 0.4], [0.0, 4.0], pts)
    assert out["masked"].tolist() == [True, False, False, False, True]
    assert np.isnan(out["y_model"].iloc[0]) and np.isnan(out["y_model"].iloc[-1])
    assert out["within"].tolist()[1:4] == [True, True, True]
    assert out["within"].isna().tolist() == [True, False, False, False, True]
    # an x uncertainty widens the band by |dy/dx| dx: 10 * 0.01
    pts2 = pd.DataFrame({"x": [0.2], "y": [2.25], "band": 0.2, "x_band": 0.01})
    assert compare_curve([0.0, 0.4], [0.0, 4.0], pts2)["within"].item()


def _curve_claim(points):
    c = claim(kind="curve", mode="TEF", quantity="real_part")
    return replace(c, points=pd.DataFrame(points).assign(band=0.05, x_band=0.0))


def test_curve_claims_pass_fail_and_all_masked():
    good = _curve_claim({"x": [0.05, 0.25, 0.6], "y": [-0.8, 0.0, 99.0]})
    got, row = check(good)
    assert got == "pass" and "1 masked" in row["computed"]
    bad = _curve_claim({"x": [0.05, 0.25], "y": [-0.8, 0.3]})
    assert check(bad)[0] == "fail"
    out = _curve_claim({"x": [0.5, 0.6], "y": [0.0, 0.0]})
    got, row = check(out)
    assert got == "not reproducible" and "outside the computed range" in row["reason"]


def test_reference_curves_for_plotting():
    assert reference_curves("fig8") is None  # no real digitised curves shipped
    ex = reference_curves("fig8", include_examples=True)
    assert set(ex["label"]) == {"TEF", "blade flap 1"} and len(ex) == 13
    assert list(ex.columns) == ["id", "label", "quantity", "x", "y", "band"]


def test_synthetic_example_curves_run_against_a_synthetic_table():
    ex = [c for c in load_claims(include_examples=True) if c.id == "example-fig8-tef"]
    t = sweep_table(np.round(np.arange(0.0, 0.71, 0.1), 2), TEF=(
        np.array([-4.1, -3.6, -2.9, -2.0, -1.0, 0.1, 1.2, 2.0]), 10.0))
    row = validate_figure("fig8", t, ex).iloc[0]
    assert row["status"] == "pass" and "7/7" in row["computed"] and "1 masked" in row["computed"]


# ------------------------------------------------------------------ bookkeeping


def test_score_worse_than_recorded_and_update(tmp_path):
    t = pd.DataFrame({"id": ["a", "b", "c", "d"], "tag": ["validation"] * 3 + ["calibration"],
                      "status": ["pass", "fail", "not reproducible", "pass"],
                      "recorded_status": ["pass", "not reproducible", "", "fail"]})
    assert claims_score(t) == (1, 3)
    assert worse_than_recorded(t)["id"].tolist() == ["b"]
    path = tmp_path / "claims.toml"
    path.write_text('[[claim]]\nid = "a"\nrecorded_status = ""\n\n[[claim]]\nid = "b"\n'
                    'kind = "x"\n')
    assert update_recorded_status(t, path) == 2
    text = path.read_text()
    assert 'id = "a"\nrecorded_status = "pass"' in text
    assert 'id = "b"\nrecorded_status = "fail"\nkind = "x"' in text


def test_validate_figure_on_a_real_fig8_sweep():
    res = run_figure("fig8", values=[0.0, 0.3, 0.6])
    table = validate_figure("fig8", res)
    claims = [c for c in load_claims() if c.figure == "fig8"]
    assert table["id"].tolist() == [c.id for c in claims]
    assert set(table["status"]) <= {"pass", "fail", "not reproducible", "ambiguous"}
    checked = table[table["kind"] != "not_reproducible"]
    assert ((checked["computed"] != "") | (checked["reason"] != "")).all()


# ------------------------------------------------------------------ identity and roles


def named_table():
    """BASE with the roles a sweep gives: the TEF role is the row named TEF."""
    t = BASE.copy()
    t["identity"] = "clear"
    t["identity_certain"] = True
    t["flap_motion"] = np.where(t["label"].isin(["TEF", "blade torsion 1"]), 0.5, 1e-4)
    t["frequency_uncoupled"] = t["frequency_per_rev"]
    t["tef_branch"] = t["label"] == "TEF"
    t["tef_branch_certain"] = t["tef_branch"]
    return t


def exchanged(t, at=0.2):
    """The names TEF and blade torsion 1 exchanged on their tracks from x = `at` on
    (the uncoupled pair keeping its order): an exceptional point between."""
    t = t.copy()
    swap = (t["value_si"] >= at) & t["label"].isin(["TEF", "blade torsion 1"])
    t.loc[swap, "label"] = np.where(t.loc[swap, "label"] == "TEF", "blade torsion 1", "TEF")
    t.loc[swap, "frequency_uncoupled"] = np.where(t.loc[swap, "label"] == "TEF", 10.0, 3.0)
    t.loc[~swap & (t["label"] == "TEF"), "frequency_uncoupled"] = 10.0
    t.loc[~swap & (t["label"] == "blade torsion 1"), "frequency_uncoupled"] = 3.0
    t["tef_branch"] = t["label"] == "TEF"
    return t


def test_claims_are_decided_on_the_points_own_names():
    # the TEF role is the row each point names TEF, whichever track it lies on:
    # after the exchange the TEF rows are torsion's numbers (stable), so the
    # claim that the TEF destabilises is decided on them -- but the exchange is
    # an exceptional point inside the claim's range: no verdict, and the reason
    # names it
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    assert check(c, named_table())[0] == "pass"
    status, row = check(c, exchanged(named_table()))
    assert status == "ambiguous"
    assert "TEF / blade torsion 1" in row["reason"] and "0.15 and 0.2" in row["reason"]


def test_an_undecided_tef_stability_claim_tells_what_the_flutter_root_gives():
    # where the TEF's name has no answer the reason adds the same check on the
    # flutter root, a role every point decides; the status stays ambiguous
    t = exchanged(named_table())
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    t["flutter_root"] = t["track"] == 0          # the root that crosses zero at 0.25
    status, row = check(c, t)
    assert status == "ambiguous"
    assert "on the flutter root instead" in row["reason"]
    assert ": pass (crossings: destabilising at 0.25)" in row["reason"]
    t["flutter_root"] = t["track"] == 3          # a flutter root stable throughout
    status, row = check(c, t)
    assert status == "ambiguous" and ": fail (crossings: none" in row["reason"]
    t["flutter_root"] = False                    # no flap-induced root: says so, not "fail ()"
    status, row = check(c, t)
    assert status == "ambiguous" and ": fail (no flap-induced root in the sweep)" in row["reason"]
    # a claim on blade torsion 1 (the TEF's partner) gets no such reading
    torsion = claim(kind="threshold", mode="blade torsion 1", direction="destabilising")
    status, row = check(torsion, t)
    assert status == "ambiguous" and "flutter root" not in row["reason"]


def test_an_exceptional_point_outside_the_range_or_of_another_mode_decides():
    t = exchanged(named_table())
    # a trend before the exceptional point is decided
    trend = claim(kind="trend", mode="TEF", quantity="real_part", direction="increasing",
                  interval=[0.0, 0.15])
    assert check(trend, t)[0] == "pass"
    # a lag claim is never withheld for the TEF's identity (its scale is the
    # TEF panel's range, whichever root carries the name)
    lag = claim(kind="trend", mode="blade lag 1", quantity="damping", direction="constant",
                tolerance=0.1, tolerance_type="relative_to_mode", reference_mode="TEF", **TOL)
    assert check(lag, t)[0] == "pass"
    # the uncoupled pair changing order at the exchange: the names moved with
    # the uncoupled crossing, not an exceptional point -- decided
    crossing = t.copy()
    late = crossing["value_si"] >= 0.2
    crossing.loc[late & (crossing["label"] == "TEF"), "frequency_uncoupled"] = 2.0
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    assert check(c, crossing)[0] != "ambiguous"


def test_paths_that_meet_inside_the_range_make_the_claim_ambiguous_when_it_matters():
    # the TEF's path met blade flap 1's at the last point: taking flap 1's root
    # there (stable) the TEF does not stay unstable -- the verdict depends on
    # the choice, so no verdict, and the reason names the point and both
    t = named_table()
    t["meets"] = np.where((t["value_si"] == 0.4) & (t["label"] == "TEF"), "blade flap 1", "")
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    status, row = check(c, t)
    assert status == "ambiguous" and "TEF / blade flap 1" in row["reason"]
    assert "at x = 0.4" in row["reason"] and "paths meet" in row["reason"]
    assert "pass with the names as continued, fail with them exchanged" in row["reason"]
    # met at 0.3 instead: the crossing at 0.25 is there either way -- decided,
    # and the reason says why
    t["meets"] = np.where((t["value_si"] == 0.3) & (t["label"] == "TEF"), "blade flap 1", "")
    status, row = check(c, t)
    assert status == "pass" and "every choice gives pass" in row["reason"]
    # the same meeting outside a claim's interval does not enter
    early = claim(kind="trend", mode="TEF", quantity="real_part", direction="increasing",
                  interval=[0.0, 0.2])
    status, row = check(early, t)
    assert status == "pass" and "exceptional" not in row["reason"]


def test_mechanism_claim_fields_are_checked():
    ok = dict(kind="mechanism", mode="TEF", x=0.36, root_kind="flutter")
    assert claim(**ok).root_kind == "flutter"
    with pytest.raises(ReferenceDataError, match="unknown term"):
        claim(**ok, driving_terms=["flap lift on the blade"])
    with pytest.raises(ReferenceDataError, match="need 'tolerance'"):
        claim(**ok, knockout_terms=["flap moment on blade torsion (C_m_delta)"])
    with pytest.raises(ReferenceDataError, match="min_participation"):
        claim(**ok, min_participation={"TEF": 1.5})
    with pytest.raises(ReferenceDataError, match="needs root_kind"):
        claim(kind="mechanism", mode="TEF", x=0.3)
    with pytest.raises(ReferenceDataError, match="root_kind"):
        claim(kind="mechanism", mode="TEF", x=0.3, root_kind="wobble")


def test_mechanism_claim_on_a_real_hover_sweep():
    # Fig. 16a (hover, imbalanced flap) at 0 deg collective: the TEF branch root
    # there is decomposed; the claim passes or fails on its physics, never errs
    res = run_figure("fig16a", values=[0.0, float(np.deg2rad(4.0))])
    c = claim(kind="mechanism", figure="fig16a", mode="TEF", x=0.0,
              min_participation={"TEF": 0.1}, root_kind="flutter")
    status, row = check(c, res.table.assign(x=res.table["value_si"]))
    assert status in ("pass", "fail", "ambiguous")
    assert "participation" in row["computed"]


def test_flutter_root_claims():
    # the TEF row is stable; the flutter root of each point is the torsion
    # root, unstable above 0.2: a TEF claim fails, a flutter-root claim passes
    t = named_table()
    t["real_part"] = np.where(t["label"] == "TEF", -1.0, t["real_part"])
    t.loc[t["label"] == "blade torsion 1", "real_part"] = 2 * (t["value_si"] - 0.2)
    t["flutter_root"] = t["label"] == "blade torsion 1"
    c = claim(kind="threshold", mode="TEF", direction="destabilising")
    status, row = check(c, t)
    assert status == "fail" and "would" not in row["computed"]
    fr = claim(kind="threshold", mode="flutter root", direction="destabilising",
               expected=0.2, tolerance=0.01, tolerance_reason="test")
    status, row = check(fr, t)
    assert status == "pass" and row["computed_value"] == pytest.approx(0.2)
