"""The attribution of failing claims: search, flips, conflicts, CSV, reproduce.

A toy point function stands in for the Floquet analysis: the TEF root's real
part is ``k (m/m0 - f0)`` with ``m/m0`` the flap-mass factor, so a claim
"the TEF is unstable at mu = 0.3" fails at the baseline (factor 1) and flips
exactly at the factor ``f0``.  The flap-mass lever of notebook 08 (0.75-1.25)
is bisected on the claim's own check (``validate_figure``).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.paper.attribution import differences as at
from tefcore.paper.attribution import search as srch
from tefcore.paper.attribution.evaluate import RunSettings, claim_values
from tefcore.paper.attribution.levers import levers
from tefcore.paper.claims.reference import load_claims, parse_claim

M0 = load_config("mdart").flap.mass


def _toy(f0):
    def point(cfg):
        growth = 0.5 * (cfg.flap.mass / M0 - f0)
        return SimpleNamespace(
            modes=pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [8.0],
                                "real_part": [growth], "damping_ratio": [-growth / 8.0]}),
            eigenvectors=np.ones((1, 1), complex), trim={})
    return point


def _claim(cid, lower=None, upper=None):
    raw = {"id": cid, "figure": "fig17", "kind": "value", "tag": "validation",
           "statement": "toy", "condition": "toy", "mode": "TEF", "quantity": "real_part",
           "x": 0.3}
    raw |= {k: v for k, v in (("lower", lower), ("upper", upper)) if v is not None}
    return parse_claim(raw)


def _attribute(f0, claims, statuses, lever="flap mass"):
    settings = RunSettings(load_config("mdart"), point=_toy(f0))
    table = pd.DataFrame({"id": [c.id for c in claims], "figure": "fig17",
                          "status": statuses, "tag": "validation"})
    lv = [x for x in levers(settings.base) if x.name == lever]
    return at.attribute(table, {"": settings}, lever_list=lv, pairs=False, reference=claims)


# ---------------------------------------------------------------- the search


def test_find_flip_bisects_to_the_step_resolution():
    flip = srch.find_flip(lambda t: t >= 0.3)
    # scanned at the end (1.0), bisected DEPTH = 3 times: the first passing
    # fraction on the grid of eighths, at most an eighth above the true flip
    assert 0.3 <= flip.t <= 0.3 + 1 / 2**srch.DEPTH
    assert srch.find_flip(lambda t: t <= -0.6).t == pytest.approx(-0.625)


def test_find_flip_finds_a_band_the_value_jumps_over():
    # a value rising through a narrow pass band [0.40, 0.45] between the scanned
    # fractions (the end 1.0 is above it): the sides say it was crossed
    def side(t):
        return -1 if t < 0.40 else (0 if t <= 0.45 else 1)
    flip = srch.find_flip(side, sides=(1,))
    assert 0.40 <= flip.t <= 0.45


def test_find_flip_none_and_beyond():
    assert srch.find_flip(lambda t: False).t is None
    flip = srch.find_flip(lambda t: t >= 1.5)     # only beyond the range (|t| > 1)
    assert 1.5 <= flip.t <= 1.5 + 1 / 2**srch.DEPTH
    assert srch.find_flip(lambda t: t >= 1.5, beyond=None).t is None
    assert srch.find_flip(lambda t: None if t > 0.5 else False).t is None   # refused


# ------------------------------------------- a synthetic claim on a toy figure


def test_bisection_finds_the_known_flip_point_of_a_claim():
    c = _claim("toy-unstable", lower=0.0)
    got = _attribute(1.1, [c], ["fail"]).table
    row = got[got["assumption"] == "flap mass"].iloc[0]
    # flips where the toy's real part crosses zero: factor 1.1 (t = 0.4 of the way
    # to 1.25); resolution an eighth of the half range, 0.25/8, above it
    assert 1.1 <= float(row["flips_at"]) <= 1.1 + 0.25 / 8 + 1e-9
    assert row["within_plausible"] is True or row["within_plausible"] == True  # noqa: E712
    assert row["confirmed"] == True and "none" not in set(got["assumption"])  # noqa: E712
    assert (row["plausible_low"], row["plausible_high"]) == (0.75, 1.25)


def test_a_claim_that_does_not_flip_is_none_within_plausible_range():
    c = _claim("toy-unstable", lower=0.0)
    beyond = _attribute(1.4, [c], ["fail"]).table     # flips at 1.4 > 1.25: beyond the range
    lever = beyond[beyond["assumption"] == "flap mass"].iloc[0]
    assert lever["within_plausible"] == False  # noqa: E712
    assert 1.4 <= float(lever["flips_at"]) <= 1.4 + 0.25 / 8 + 1e-9
    none = beyond[beyond["assumption"] == "none"].iloc[0]
    assert none["note"].startswith("none within plausible range (flips only beyond it")
    never = _attribute(3.0, [c], ["fail"]).table      # beyond even twice the range
    assert never[never["assumption"] == "flap mass"]["flips_at"].iloc[0] == ""
    assert never["assumption"].tolist() == ["flap mass", "none"]


def test_conflicts_are_the_passing_claims_a_flip_fails():
    a = _claim("toy-unstable", lower=0.0)            # fails at the baseline (real part < 0)
    b = _claim("toy-stable", upper=0.0)              # passes there, fails once unstable
    c = _claim("toy-bounded", lower=-1.0, upper=1.0)  # passes before and after
    got = _attribute(1.1, [a, b, c], ["fail", "pass", "pass"]).table
    row = got[(got["claim"] == "toy-unstable") & (got["assumption"] == "flap mass")].iloc[0]
    assert row["conflicts"] == "toy-stable (pass -> fail)"
    assert set(got["claim"]) == {"toy-unstable"}      # only failing claims are attributed


def test_csv_schema(tmp_path):
    c = _claim("toy-unstable", lower=0.0)
    res = _attribute(3.0, [c], ["fail"])
    path = at.write_attribution(res.table, tmp_path / "attribution.csv")
    back = pd.read_csv(path, dtype=str, keep_default_na=False)
    assert list(back.columns[:7]) == ["claim", "status", "assumption", "flips_at",
                                      "plausible_low", "plausible_high", "within_plausible"]
    assert list(back.columns) == at.COLUMNS + at.EXTRA_COLUMNS
    assert (back["status"] == "fail").all() and (back["claim"] == "toy-unstable").all()
    assert res.cpu_seconds > 0 and res.tasks == 1


def test_claim_values_are_the_points_that_decide_it():
    claims = {c.id: c for c in load_claims()}
    v = claim_values(claims["fig7a-power-reduced-60pct"], [0.0, 0.1, 0.2, 0.29, 0.4])
    assert v == [0.0, 0.29]                           # its x and the x it is relative to
    v = claim_values(claims["fig17-tef-weakly-unstable-hover"], [0.05, 0.1])
    assert v == [0.05]                                # not swept: the nearest above it
    assert claim_values(claims["fig9b-tef-unstable-after-0.26"], [0.0, 0.2]) == [0.0, 0.2]


def test_summary_names_what_explains_and_what_nothing_explains():
    t = pd.DataFrame({"claim": ["a", "a", "b", "c", "c"], "status": "fail",
                      "assumption": ["flap mass", "lift slope", "none", "flap mass", "x"],
                      "flips_at": ["1.1", "6", "", "0.9", "2"], "plausible_low": "",
                      "plausible_high": "", "within_plausible": [True, False, False, True,
                                                                 True],
                      "figure": ["fig9", "fig9", "fig17", "fig9", "fig9"],
                      "confirmed": [True, True, "", True, False],
                      "conflicts": ["", "", "", "d (pass -> fail)", ""], "note": ""})
    s = at.summarise(t)
    assert s["explains"] == [{"assumption": "flap mass", "claims": ["a", "c"], "conflicts": 1}]
    assert s["unexplained"] == ["b"] and (s["failing"], s["explained"]) == (3, 2)
    fig9 = {r["claim"]: r for r in s["figures"]["fig9"]}
    assert fig9["a"]["beyond"] == "lift slope at 6"
    assert fig9["c"]["beyond"] == "x at 2 (not confirmed)"


# ------------------------------------------------------------------ the report


def test_report_says_why_we_differ(tmp_path):
    from tefcore.paper.run.report import build_report, write_report
    from tefcore.paper.run.reproduce import NotebookRun
    from tests.paper.run.test_report_html import PNG, check_page

    nb = tmp_path / "07_flight_condition"
    nb.mkdir()
    (nb / "fig17.png").write_bytes(PNG)
    (nb / "fig17.json").write_text('{"figure": "fig17", "caption": "Fig. 17"}')
    claims = pd.DataFrame([{"notebook": "07_flight_condition", "id": i, "figure": "fig17",
                            "statement": "s", "expected": "x", "computed": "y", "status": "fail",
                            "reason": "r", "tag": "validation", "recorded_status": "fail"}
                           for i in ("fig17-a", "fig17-b")])
    attribution = pd.DataFrame({
        "claim": ["fig17-a", "fig17-b", "fig17-b"], "status": "fail",
        "assumption": ["dynamic inflow", "lift slope", "none"],
        "flips_at": ["dynamic", "7.5", ""], "plausible_low": ["linear", 5.5, ""],
        "plausible_high": ["dynamic", 6.28, ""], "within_plausible": [True, False, False],
        "figure": "fig17", "confirmed": [True, True, ""], "conflicts": ["fig17-c (pass -> fail)",
                                                                         "", ""],
        "note": ""})
    r = build_report(tmp_path, [NotebookRun("07_flight_condition", status="ok")], claims,
                     claims.iloc[0:0], figures_of={"07_flight_condition": ("fig17",)},
                     attribution=attribution)
    # each claim by its sentence, each lever with its range (units where the setting has one)
    assert r.why["unexplained"] == [{"id": "fig17-b", "statement": "s"}]
    assert r.sections[0].attribution[0]["plausible"] == [
        "dynamic inflow = dynamic (plausible linear to dynamic)"]
    md_path, html_path = write_report(r, tmp_path)
    page = check_page(html_path.read_text(encoding="utf-8"))
    assert "why-we-differ" in page.ids
    text = " ".join(page.text)
    assert "No plausible change explains 1 statement(s)" in text
    assert "lift slope = 7.5 (plausible 5.5 to 6.28)" in text
    md = md_path.read_text(encoding="utf-8")
    assert "## Why we differ" in md
    assert "| s (fig17-a) | dynamic inflow = dynamic (plausible linear to dynamic)" in md
    assert "but then fails: fig17-c (pass -> fail)" in md


# ------------------------------------------------- tefcore reproduce, for real


def test_reproduce_only_writes_a_row_for_every_failing_claim(tmp_path, monkeypatch):
    """``tefcore reproduce --only 04 07 --out o`` writes ``o/attribution.csv``.

    Real notebooks (three points per figure) and a real attribution, with one
    lever (dynamic inflow) to keep it to a minute or two: the rows per claim
    are the same whatever the levers.
    """
    pytest.importorskip("papermill")
    from tefcore.cli import main

    real = at.levers
    monkeypatch.setattr(at, "levers", lambda cfg: [lv for lv in real(cfg)
                                                   if lv.name == "dynamic inflow"])
    out = tmp_path / "o"
    main(["reproduce", "--only", "04", "07", "--out", str(out), "-p", "n_points", "3",
          "--no-progress"])
    claims = pd.read_csv(out / "claims.csv", dtype=str, keep_default_na=False)
    failing = claims[(claims["status"] == "fail") & (claims["tag"] == "validation")]
    got = pd.read_csv(out / "attribution.csv", dtype=str, keep_default_na=False)
    assert list(got.columns[:7]) == at.COLUMNS
    assert len(failing) and set(got["claim"]) == set(failing["id"])
    for cid, rows in got.groupby("claim"):
        assert "dynamic inflow" in set(rows["assumption"]), cid
        flipped = rows["within_plausible"].eq("True") & rows["confirmed"].eq("True")
        assert flipped.any() or "none" in set(rows["assumption"]), cid
    assert "Why we differ" in (out / "report.md").read_text(encoding="utf-8")


def test_notebooks_with_one_base_share_each_moved_configuration(tmp_path):
    # a move can be a re-calibration of the torsion (0.5 s): made once per base
    # configuration and setting, whichever notebook's claim asks (the
    # notebooks' bases are equal but distinct objects)
    moved = []
    lever = SimpleNamespace(move=lambda cfg, t: moved.append((cfg, t)) or
                            cfg.with_overrides({"flap.mass": (1 + t) * cfg.flap.mass}))
    base = load_config("mdart")
    settings = {"04": RunSettings(base.with_overrides({})),
                "05": RunSettings(base.with_overrides({})),
                "07": RunSettings(base.with_overrides({"flap.cg_offset": 0.1}))}
    task = srch._Task(lever, settings, tmp_path)
    a = task.config("04", 0.5)
    assert task.config("05", 0.5) is a and len(moved) == 1
    assert task.config("07", 0.5).flap.cg_offset == 0.1 and len(moved) == 2
    assert task.config("04", -0.5) is not a and len(moved) == 3
    assert task.config("05", None) is settings["05"].base and len(moved) == 3


def test_a_cached_sweep_of_another_model_code_is_computed_again(tmp_path):
    # the cache's sweep files are derived data: one written by another model code is
    # not resumed (the sweep would refuse it and the figure read "not computable") but
    # replaced, and the figure's values are this code's
    import json

    from tefcore.paper.attribution.evaluate import FigureCache
    from tefcore.provenance import model_stamp

    cfg = load_config("mdart")
    settings = RunSettings(base=cfg)
    first = FigureCache(tmp_path).result("fig12", cfg, settings, {}, [65.625, 131.25])
    (path,) = tmp_path.glob("fig12-*.jsonl")
    lines = path.read_text().splitlines()
    head = json.loads(lines[0])
    path.write_text("\n".join([json.dumps({**head, "model_stamp": "0" * 16})] + lines[1:])
                    + "\n")
    again = FigureCache(tmp_path).result("fig12", cfg, settings, {}, [65.625, 131.25])
    assert json.loads(path.read_text().splitlines()[0])["model_stamp"] == model_stamp()
    assert first.ok and again.ok
    assert again.table["label"].tolist() == first.table["label"].tolist()
    np.testing.assert_allclose(again.table["real_part"].astype(float),
                               first.table["real_part"].astype(float), atol=1e-9)
