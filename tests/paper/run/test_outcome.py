"""A what-if is not a regression; a regression is a short readable list.

``reproduce -p overrides "{flight.advance_ratio: 0.2}"`` exited 1 as "claims
worse than recorded" and printed a 953-character pandas table: the recorded
statuses are the default rotor's, and another rotor is not a regression.  A
what-if is compared with the previous run of the same parameters in the
folder it replaces.  The notebooks are replaced by a fake that writes the
claims a test gives.
"""

import pandas as pd
import pytest

from tefcore.paper.run import outcome
from tefcore.paper.run import reproduce as rp

pytest.importorskip("papermill")

WHAT_IF = {"all": {"overrides": {"flight.advance_ratio": 0.2}}}


def _claim(status, recorded="pass", cid="fig9b-x"):
    return {"id": cid, "figure": "fig9", "panel": "b", "kind": "trend", "tag": "validation",
            "statement": "s", "expected": "e", "computed": "c", "status": status,
            "reason": "the TEF root crosses at 0.43 " + "and more words " * 20,
            "recorded_status": recorded}


@pytest.fixture
def claims_written(monkeypatch):
    rows = []

    def run(out, params, names, progress=True, nb_dir=None, kernel_name="python3", jobs=None,
            stop=None):
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame(rows).to_csv(out / name / "claims.csv", index=False)
        return [rp.NotebookRun(name, status="ok") for name in names]

    monkeypatch.setattr(rp, "run_notebooks", run)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])
    return rows


def test_a_what_if_is_not_a_regression(tmp_path, claims_written, capsys):
    claims_written[:] = [_claim("fail", "pass")]
    code = rp.reproduce(tmp_path / "out", params=WHAT_IF, notebooks=["04"], progress=False,
                        attribution=False)
    out, err = capsys.readouterr()
    assert code == 0
    assert "worse than recorded" not in err and "regression" not in err
    assert "what-if (overrides = {'flight.advance_ratio': 0.2})" in out
    md = (tmp_path / "out" / "report.md").read_text()
    assert "flight.advance_ratio" in md and "Worse than recorded: 1" not in md


@pytest.mark.parametrize("params", [
    {"config": "my.toml"}, {"n_points": 4}, {"aero_model": "table"},
    {"values": {"fig9": [0.0, 0.3]}}])
def test_any_parameter_of_the_results_makes_a_what_if(params):
    assert outcome.what_if({"04_cg_offset": params}, ["04_cg_offset"]) != ""


@pytest.mark.parametrize("params", [
    {}, {"n_jobs": 2, "interactive": False}, {"config": "mdart-fig6"}, {"config": "mdart"},
    {"config": None}])
def test_the_recorded_computation_is_no_what_if(params):
    assert outcome.what_if({"04_cg_offset": params}, ["04_cg_offset"]) == ""


def test_a_what_if_is_compared_with_its_own_previous_run(tmp_path, claims_written, capsys):
    out = tmp_path / "out"
    claims_written[:] = [_claim("pass"), _claim("pass", cid="fig9b-y")]
    assert rp.reproduce(out, params=WHAT_IF, notebooks=["04"], progress=False,
                        attribution=False) == 0
    capsys.readouterr()
    claims_written[:] = [_claim("fail"), _claim("pass", cid="fig9b-y")]
    assert rp.reproduce(out, params=WHAT_IF, notebooks=["04"], progress=False,
                        attribution=False) == 0
    printed = capsys.readouterr().out
    assert "since the previous run of these parameters" in printed
    assert "  - fig9b-x (Fig. 9): pass -> fail: the TEF root crosses at 0.43" in printed
    assert "fig9b-y" not in printed
    # another configuration's previous run is not compared with
    claims_written[:] = [_claim("pass"), _claim("pass", cid="fig9b-y")]
    rp.reproduce(out, params={"all": {"n_points": 3}}, notebooks=["04"], progress=False,
                 attribution=False)
    assert "since the previous run" not in capsys.readouterr().out


def test_a_regression_is_a_short_list(tmp_path, claims_written, capsys):
    claims_written[:] = [_claim("fail", "pass"), _claim("pass", "pass", cid="fig9b-y")]
    assert rp.reproduce(tmp_path / "out", notebooks=["04"], progress=False,
                        attribution=False) == 1
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert lines[0] == "tefcore reproduce: 1 claim(s) worse than recorded (a regression):"
    assert lines[1].startswith("  - fig9b-x (Fig. 9): pass -> fail: the TEF root crosses")
    assert len(lines) == 2 and max(len(x) for x in lines) <= 110
    assert "recorded_status" not in err          # no table header
