"""The two packaged variants: Fig. 6's calibration, their claims, the report on both."""

import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.paper import fig6_calibration as f6
from tefcore.paper.claims.reference import load_claims
from tefcore.paper.claims.variants import (
    DEFAULT_VARIANT,
    apply_variant,
    compare_variants,
    comparison_variants,
    load_variants,
)
from tefcore.paper.run import reproduce as rp
from tefcore.paper.run.report import Report, render, variants_view
from tefcore.units import from_si


def test_mdart_fig6_reproduces_fig6_and_mdart_does_not():
    target = f6.fig6_target()
    fit = 2 * f6.fig6_ratio(load_config("mdart-fig6"))
    # the claim's own tolerance (0.1 deg) ...
    assert abs(fit - target["expected_deg"]) <= target["tolerance_deg"]
    # ... and the fit's: the stored 2.661 lb in^2 is rounded to 4 digits (+-0.0005),
    # and the response moves 0.08 x the input per lb in^2 there: < 1e-4 deg
    assert fit == pytest.approx(2.3, abs=2e-3)
    base = 2 * f6.fig6_ratio(load_config("mdart"))
    assert abs(base - target["expected_deg"]) > target["tolerance_deg"]   # 1.944 deg


def test_bisection_recovers_the_stored_value():
    fit = f6.calibrate_reflected_inertia()
    stored = load_config("mdart-fig6").actuator.reflected_inertia
    # 4-digit rounding of the stored value (0.0005 lb in^2 = 1.5e-7 kg m^2) plus xtol
    assert fit["reflected_inertia"] == pytest.approx(stored, abs=2e-7)
    assert fit["ratio"] == pytest.approx(1.15, abs=1e-6)
    assert 4.0 < fit["inertia_ratio"] < 5.0          # the flap system 4.6 x the flap's own
    assert fit["evaluations"] <= 20


def test_fitted_value_is_outside_its_construction_range():
    # the data file argues 0.05-0.7 lb in^2; the fit is ~4 x its upper end
    lb = from_si(load_config("mdart-fig6").actuator.reflected_inertia, "lb*in^2", "inertia")
    assert 3 * 0.7 < lb < 5 * 0.7


def test_registry_default_and_comparisons():
    v = load_variants()
    assert list(v)[0] == DEFAULT_VARIANT == "mdart"
    assert v["mdart"].calibration == () and v["mdart"].recorded_status == {}
    assert v["mdart-fig6"].calibration == (f6.FIG6_CLAIM,)
    assert comparison_variants(None) == ["mdart-fig6", "mdart-inferred"]
    assert comparison_variants("mdart-fig6") == ["mdart", "mdart-inferred"]
    assert comparison_variants("rotor.toml") == []


def test_every_recorded_difference_is_explained():
    # mdart-fig6 has a recorded status for every claim; each explanation is written
    # for mdart-fig6's recorded status and a different one on mdart, and says more
    # than a phrase
    fig6 = load_variants()["mdart-fig6"]
    assert {c.id for c in load_claims()} == set(fig6.recorded_status)
    assert set(fig6.calibration) <= set(fig6.recorded_status)
    assert fig6.differences
    for cid, d in fig6.differences.items():
        assert d["statuses"]["mdart-fig6"] == fig6.recorded_status[cid]
        assert d["statuses"]["mdart"] != d["statuses"]["mdart-fig6"]
        assert len(d["why"]) > 80, cid
    assert fig6.differences[f6.FIG6_CLAIM]["statuses"] == {"mdart": "fail", "mdart-fig6": "pass"}


def test_apply_variant_retags_calibration_and_records():
    table = pd.DataFrame({"id": [f6.FIG6_CLAIM, "fig9b-tef-unstable-after-0.26"],
                          "tag": ["validation", "validation"],
                          "recorded_status": ["fail", "x"], "status": ["pass", "fail"]})
    on_fig6 = apply_variant(table, load_config("mdart-fig6"))
    assert on_fig6["tag"].tolist() == ["calibration", "validation"]
    rec = load_variants()["mdart-fig6"].recorded_status
    assert on_fig6["recorded_status"].tolist() == [rec[i] for i in table["id"]]
    pd.testing.assert_frame_equal(apply_variant(table, load_config("mdart")), table)
    pd.testing.assert_frame_equal(apply_variant(table, None), table)


def test_compare_variants_shows_unexplained_differences():
    a = pd.DataFrame({"id": ["x", "y"], "figure": ["fig8", "fig9"], "tag": "validation",
                      "status": ["pass", "fail"], "computed": ["1", "2"]})
    b = a.assign(status=["pass", "pass"])
    cmp = compare_variants({"mdart": a, "mdart-fig6": b})
    assert cmp["differs"].tolist() == [False, True]
    assert cmp["why"].tolist() == ["", "not explained"]
    # an explanation is used for the statuses it was written for only
    fig6 = a.assign(id=f6.FIG6_CLAIM, figure="fig6")
    ok = compare_variants({"mdart": fig6.assign(status="fail"),
                           "mdart-fig6": fig6.assign(status="pass")})
    assert ok["why"].iloc[0].startswith("The calibration target of mdart-fig6")
    stale = compare_variants({"mdart": fig6.assign(status="ambiguous"),
                              "mdart-fig6": fig6.assign(status="pass")})
    assert stale["why"].iloc[0] == ("not explained (explained for mdart fail, "
                                    "mdart-fig6 pass)")


def _conflict():
    rows = []
    for v, ratio, grow in (("mdart", 0.972, (3.04, 3.01, -0.02)),
                           ("mdart-fig6", 1.15, (1.91, 2.19, -0.02)),
                           ("heavy", 1.156, (2.21, 2.58, 0.10))):
        for point, g in zip(f6.CONFLICT_POINTS, grow, strict=True):
            rows.append({"variant": v, "reflected inertia [lb in^2]": 0,
                         "flap-system inertia / mdart's": 4.62,
                         "Fig. 6 response / input": ratio, "point": point,
                         "least stable root": "blade lag 1", "frequency /rev": 0.58,
                         "real part /rev": -0.02, "flap-induced root": "blade torsion 2",
                         "its frequency /rev": 11.2, "its real part /rev": g})
    return pd.DataFrame(rows).astype(str)


def test_conflict_text_states_the_numbers_and_the_verdict():
    text = f6.conflict_text(_conflict())
    assert "0.972 x the input on mdart, 1.150 x on mdart-fig6" in text
    assert "+1.91 and +2.19 on mdart-fig6" in text
    assert "hold together on mdart-fig6" in text and "but do not on heavy" in text
    assert "blade torsion 2 at 11.20/rev, +0.10/rev (unstable)" in text


def test_report_renders_both_variants():
    cmp = compare_variants({
        "mdart": pd.DataFrame({"id": ["x"], "figure": ["fig6"], "tag": "validation",
                               "status": "fail", "computed": "1"}),
        "mdart-fig6": pd.DataFrame({"id": ["x"], "figure": ["fig6"], "tag": "calibration",
                                    "status": "pass", "computed": "2"})})
    v = {"base": "mdart", "names": ["mdart", "mdart-fig6"], "reason": "because **so**",
         "summaries": {"mdart": "a", "mdart-fig6": "b"},
         "scores": {"mdart": (1, 2), "mdart-fig6": (2, 2)}, "worse": pd.DataFrame(),
         "comparison": cmp, "conflict": _conflict(), "errors": []}
    r = Report(title="t", intro="i", passed=1, total=2, counts={"pass": 1}, worse=[],
               notebooks=[], sections=[], checks=[], version="0", variants=variants_view(v))
    md, page = render(r, "md"), render(r, "html")
    for text in (md, page):
        assert "The claims on both variants" in text and "pass (calibration)" in text
        assert "not explained" in text and "because so" in text
        assert "hold together on mdart-fig6" in text
    assert "| x | fig6 | fail | pass (calibration) | not explained |" in md


def test_reproduce_runs_the_other_variant_beside_the_notebooks(tmp_path, monkeypatch):
    # fake notebooks (a fig6 claim as mdart's notebook 02 writes it), real variant
    # processes: Fig. 6's claims on mdart-fig6 and the conflict (~15 s)
    row = {"id": f6.FIG6_CLAIM, "figure": "fig6", "panel": "", "kind": "value",
           "tag": "validation", "statement": "s", "expected": "e", "computed": "1.944",
           "status": "fail", "reason": "", "recorded_status": "fail"}

    def run(out, params, names, progress=True, nb_dir=None, kernel_name="python3", jobs=None,
            stop=None):
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame([row]).to_csv(out / name / "claims.csv", index=False)
        return [rp.NotebookRun(n, status="ok") for n in names]

    monkeypatch.setattr(rp, "run_notebooks", run)
    assert rp.reproduce(tmp_path, notebooks=["02"], progress=False) == 0
    cmp = pd.read_csv(tmp_path / "claims-variants.csv", dtype=str, keep_default_na=False)
    fig6 = cmp[cmp["id"] == f6.FIG6_CLAIM].iloc[0]
    assert (fig6["status mdart"], fig6["status mdart-fig6"]) == ("fail", "pass")
    assert fig6["tag mdart-fig6"] == "calibration" and len(fig6["why"]) > 40
    md = (tmp_path / "report.md").read_text()
    assert "The claims on both variants" in md and "mdart-fig6" in md
    assert (tmp_path / "variants" / "conflict.csv").exists()
