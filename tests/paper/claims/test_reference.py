"""Reference data: the shipped claims, the format checks and WebPlotDigitizer CSVs."""

import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from tefcore.paper.claims.files import ReferenceDataError, read_wpd_csv, reference_dir
from tefcore.paper.claims.reference import load_claims, parse_claim
from tefcore.paper.figures.catalogue import FIGURES
from tefcore.paper.figures.quantities import x_to_si

PAPER = Path("/work/shared/paper/000_73c128a31e609ab3.txt")

GOOD = '''
format = "tefcore.claims/1"

[[claim]]
id = "a-threshold"
figure = "fig9"
kind = "threshold"
tag = "validation"
statement = "The trailing-edge flap mode is shown to become unstable after 0.26."
condition = "mu = 0.30"
mode = "TEF"
direction = "destabilising"
expected = 0.26
tolerance = 0.04
tolerance_reason = "plot resolution"
'''


def write(tmp_path, text, name="claims.toml"):
    (tmp_path / name).write_text(text)
    return tmp_path


# ------------------------------------------------------------------ shipped data


def test_shipped_claims_cover_figures_3_to_17():
    claims = load_claims()
    assert len(claims) >= 30
    figs = {c.figure for c in claims}
    assert figs == set(FIGURES) | {"fig5", "fig6", "fig7"}
    assert {c.tag for c in claims} == {"calibration", "validation"}
    assert len({c.id for c in claims}) == len(claims)
    assert not any(c.example for c in claims)  # synthetic examples are opt-in
    # the calibration claims are exactly the four stated torsion frequencies and their trends
    cal = [c for c in claims if c.tag == "calibration"]
    assert {c.expected for c in cal if c.kind == "value"} == {2.3, 4.2, 2.96, 3.18}
    assert all(c.quantity == "natural_frequency_per_rev" for c in cal)
    # every recorded status is filled in
    assert all(c.recorded_status for c in claims)


def test_every_tolerance_has_a_reason_and_not_reproducible_a_reason():
    for c in load_claims():
        if c.tolerance is not None:
            assert c.tolerance_reason, c.id
        if c.kind == "not_reproducible":
            assert c.reason, c.id


@pytest.mark.skipif(not PAPER.exists(), reason="paper text not available")
def test_statements_are_quoted_exactly_from_the_paper():
    text = " ".join(PAPER.read_text().split())
    for c in load_claims():
        if c.kind != "curve":
            assert " ".join(c.statement.split()) in text, c.id


def test_examples_load_on_request_and_are_synthetic():
    ex = [c for c in load_claims(include_examples=True) if c.example]
    assert {c.id for c in ex} == {"example-fig8-tef", "example-fig8-blade-flap-1",
                                  "example-fig9a-tef-frequency"}
    fig9 = next(c for c in ex if c.figure == "fig9")
    # x in percent -> fraction; y in Hz -> per rev with the rotor speed (392 RPM)
    assert fig9.points["x"].tolist() == pytest.approx([0, 0.1, 0.2, 0.3, 0.4])
    assert fig9.points["y"].iloc[0] == pytest.approx(72.0 / (392 / 60))
    assert fig9.points["band"].iloc[0] == pytest.approx(2.0 / (392 / 60))
    flap = next(c for c in ex if c.id == "example-fig8-blade-flap-1")
    assert flap.points["x_band"].iloc[0] == pytest.approx(0.01)


def test_x_units_convert_to_the_sweep_units():
    assert x_to_si("fig16b", 4.0, "deg") == pytest.approx(np.deg2rad(4.0))
    assert x_to_si("fig10", 158, "lb/in") == pytest.approx(158 * 175.126835, rel=1e-6)
    assert x_to_si("fig8", 0.5, "") == 0.5
    with pytest.raises(ValueError):
        x_to_si("fig10", 1.0, "deg")


# ------------------------------------------------------------------ malformed records


def test_good_minimal_file_loads(tmp_path):
    (c,) = load_claims(write(tmp_path, GOOD))
    assert (c.id, c.quantity, c.expected) == ("a-threshold", "real_part", 0.26)


RECORD = GOOD.split('format = "tefcore.claims/1"\n')[1].replace("a-threshold", "b-threshold")


@pytest.mark.parametrize("edit, message", [
    (lambda s: s.replace('direction = "destabilising"\n', ""),
     "missing required field 'direction'"),
    (lambda s: re.sub(r"(?m)^statement = .*\n", "", s), "missing required field 'statement'"),
    (lambda s: s.replace('kind = "threshold"', 'kind = "treshold"'), "kind"),
    (lambda s: s.replace("expected = 0.26", 'expected = "0.26"'), "must be a finite number"),
    (lambda s: s.replace("expected = 0.26", "expected = nan"), "must be a finite number"),
    (lambda s: s.replace('figure = "fig9"', 'figure = "fig2"'), "figure"),
    (lambda s: s.replace('tag = "validation"', 'tag = "tuning"'), "tag"),
    (lambda s: s.replace("tolerance = 0.04\n", ""), "tolerance"),
    (lambda s: s.replace('tolerance_reason = "plot resolution"', ""), "tolerance_reason"),
    (lambda s: s + 'colour = "red"\n', "unknown field"),
    (lambda s: s.replace('mode = "TEF"', 'mode = "TEF"\nquantity = "speed"'), "quantity"),
    (lambda s: s.replace('id = "b-threshold"', 'id = "B threshold"'), "id"),
])
def test_malformed_record_names_file_and_record(tmp_path, edit, message):
    write(tmp_path, GOOD + edit(RECORD))
    with pytest.raises(ReferenceDataError) as err:
        load_claims(tmp_path)
    msg = str(err.value)
    assert str(tmp_path / "claims.toml") + ": record 2" in msg and message in msg


def test_kind_specific_checks():
    base = {"id": "x", "figure": "fig15", "tag": "validation", "statement": "s",
            "condition": "c", "mode": "TEF"}
    with pytest.raises(ReferenceDataError, match="expected_interval"):
        parse_claim({**base, "kind": "range", "state": "unstable", "tolerance": 0.1,
                     "tolerance_reason": "r", "expected_interval": [0.4, 0.15]})
    with pytest.raises(ReferenceDataError, match="second curve"):
        parse_claim({**base, "kind": "comparison", "quantity": "damping",
                     "statistic": "slope", "relation": "less"})
    with pytest.raises(ReferenceDataError, match="relation"):
        parse_claim({**base, "kind": "comparison", "quantity": "damping",
                     "statistic": "correlation", "relation": "less", "other_mode": "x"})
    with pytest.raises(ReferenceDataError, match="no modes"):
        parse_claim({**base, "figure": "fig7", "kind": "trend", "quantity": "peak_power",
                     "direction": "increasing"})
    with pytest.raises(ReferenceDataError, match="does not exist for fig15"):
        parse_claim({**base, "kind": "trend", "quantity": "peak_power",
                     "direction": "increasing"})
    with pytest.raises(ReferenceDataError, match="x_unit"):
        parse_claim({**base, "kind": "trend", "quantity": "damping", "x_unit": "lb/in",
                     "direction": "increasing"})
    with pytest.raises(ReferenceDataError, match="overrides.*flap.cgoffset"):
        parse_claim({**base, "kind": "trend", "quantity": "damping", "direction": "increasing",
                     "overrides": {"flap.cgoffset": 0.0}})
    with pytest.raises(ReferenceDataError, match="reason"):
        parse_claim({**base, "kind": "not_reproducible"})


def test_bad_toml_and_duplicate_ids(tmp_path):
    write(tmp_path, GOOD + "[[claim]\n")
    with pytest.raises(ReferenceDataError, match=r"claims.toml: not valid TOML"):
        load_claims(tmp_path)
    write(tmp_path, GOOD + RECORD.replace("b-threshold", "a-threshold"))
    with pytest.raises(ReferenceDataError, match=r"record 2 .*duplicate id 'a-threshold'"):
        load_claims(tmp_path)
    with pytest.raises(ReferenceDataError, match="no reference data"):
        load_claims(tmp_path / "nowhere")


# ------------------------------------------------------------------ WebPlotDigitizer


def test_wpd_per_dataset_without_and_with_header(tmp_path):
    (tmp_path / "a.csv").write_text("0.1,1.5\n0.2,2.5\n")
    (tmp_path / "b.csv").write_text("\ufeffx,y\n0.1, 1.5\n\n0.2, 2.5\n")
    (tmp_path / "c.csv").write_text("0.1;1.5\n0.2;2.5\n")
    for name in "abc":
        d = read_wpd_csv(tmp_path / f"{name}.csv")
        assert list(d) == [""]
        assert d[""].to_numpy().tolist() == [[0.1, 1.5], [0.2, 2.5]]


def test_wpd_export_all_with_uneven_datasets(tmp_path):
    (tmp_path / "all.csv").write_text(
        "TEF,,Blade flap,Blade flap\nX,Y,X,Y\n0,1,0,5\n1,2,,\n2,3,,\n")
    d = read_wpd_csv(tmp_path / "all.csv")
    assert list(d) == ["TEF", "Blade flap"]
    assert d["TEF"]["y"].tolist() == [1, 2, 3] and d["Blade flap"]["y"].tolist() == [5]


@pytest.mark.parametrize("text, message", [
    ("0.1,1.5\n0.2,abc\n", "row 2: 'abc' is not a number"),
    ("0.1,1.5,3\n", "row 1: expected two columns"),
    ("TEF,,,\nX,Y,X,Y\n0,1,0,\n", "row 3: dataset '' has only one|column 3 is empty"),
    ("TEF,,F,\nX,Y,X,Y\n0,1,0,\n", "row 3: dataset 'F' has only one"),
    ("TEF,,TEF,\nX,Y,X,Y\n0,1,0,1\n", "repeated"),
    ("", "no data"),
])
def test_wpd_malformed_rows_are_named(tmp_path, text, message):
    (tmp_path / "bad.csv").write_text(text)
    with pytest.raises(ReferenceDataError, match=message) as err:
        read_wpd_csv(tmp_path / "bad.csv")
    assert "bad.csv" in str(err.value)


def test_user_adds_a_curve_without_code(tmp_path):
    """Copy the example sidecar, drop `example`: the curve becomes a claim."""
    root = tmp_path / "ref"
    (root / "curves").mkdir(parents=True)
    shutil.copy(reference_dir() / "claims.toml", root)
    src = reference_dir() / "curves"
    shutil.copy(src / "SYNTHETIC_example_fig8_export_all.csv", root / "curves" / "mine.csv")
    side = (src / "SYNTHETIC_example_fig8.toml").read_text()
    side = re.sub(r"(?m)^example = true\n", "", side).replace(
        "SYNTHETIC_example_fig8_export_all.csv", "mine.csv").replace("example-fig8", "my-fig8")
    (root / "curves" / "mine.toml").write_text(side)
    claims = load_claims(root)
    mine = [c for c in claims if c.kind == "curve"]
    assert [c.id for c in mine] == ["my-fig8-tef", "my-fig8-blade-flap-1"]
    # a sidecar naming a dataset absent from the CSV is an error naming both
    (root / "curves" / "mine.toml").write_text(side.replace('name = "TEF"', 'name = "TEF2"'))
    with pytest.raises(ReferenceDataError, match=r"mine.toml: dataset 1.*'TEF2' not in mine.csv"):
        load_claims(root)


def test_claims_are_read_again_when_a_file_changes_and_never_shared_as_a_list(tmp_path):
    # load_claims keeps what it read while no file of the folder changes
    root = tmp_path / "ref"
    shutil.copytree(reference_dir(), root)
    first = load_claims(root)
    first.append("a caller's own list")                 # not the cache's
    again = load_claims(root)
    assert [c.id for c in again] == [c.id for c in first[:-1]]
    text = (root / "claims.toml").read_text(encoding="utf-8")
    old = again[0].statement
    (root / "claims.toml").write_text(text.replace(old, old + " (edited)", 1), encoding="utf-8")
    assert load_claims(root)[0].statement == old + " (edited)"
    # a curve's CSV alone edited is seen, and a dangling link is not data
    (root / "dangling").symlink_to(root / "nowhere")
    example = [c for c in load_claims(root, include_examples=True) if c.example][0]
    csv = next((root / "curves").glob("*.csv"))
    csv.write_text(csv.read_text(encoding="utf-8") + "\n", encoding="utf-8")
    assert [c for c in load_claims(root, include_examples=True) if c.example][0] is not example
    # a new curve file is seen too
    assert len(load_claims(root, include_examples=True)) > len(load_claims(root))
    shutil.copy(root / "curves" / "SYNTHETIC_example_fig8.toml", root / "curves" / "copy.toml")
    with pytest.raises(ReferenceDataError, match="duplicate id"):
        load_claims(root, include_examples=True)
