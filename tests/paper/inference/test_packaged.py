"""The packaged studies: re-created by their declared commands, and mdart-inferred is their best.

The results under ``tefcore/data/inference/results/`` are what the declared
studies found; a short re-run of the Sobol study (its first trials, the real
claims' checks) must find the same parameters, statuses and margins, or the
packaged results no longer describe this code.
"""

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.paper.claims.reference import load_claims
from tefcore.paper.inference.packaged import (
    STUDIES,
    export_results,
    load_results,
    sobol_claims,
    study_command,
    trial_rows,
)
from tefcore.paper.inference.space import load_space, sample_of
from tefcore.paper.inference.study import StudySpec, run_study
from tefcore.paper.run.report_views import inference_view

from . import fakes

RESULTS = load_results()

#: The robust verdicts' value tolerance (tefcore.paper.claims.robustness): a
#: margin re-computed on another machine or BLAS kernel moves by round-off only.
MARGIN_ATOL = 1e-6

#: Trials of the Sobol study re-run: a complete one, a refused one, a complete one
#: (about 25 s of CPU).
RERUN = 3


def test_the_packaged_results_hold_every_declared_study():
    trials = RESULTS["trials"]
    for s in STUDIES:
        mine = trials[trials["study"] == s["name"]]
        finished = mine["state"].isin(["COMPLETE", "PRUNED"]).sum()
        assert finished >= s["trials"], (s["name"], finished)
    assert study_command(STUDIES[0]).startswith("tefcore infer --reading continued")


def test_the_sobol_study_is_recreated_by_its_declared_command(tmp_path):
    s = next(s for s in STUDIES if s["sampler"] == "qmc")
    study = run_study(StudySpec(reading=s["reading"], sampler=s["sampler"], seed=s["seed"],
                                storage=str(tmp_path / "s.journal")), RERUN)
    trials, claims = trial_rows(study)
    old_t = RESULTS["trials"].query("study == @s['name'] and number < @RERUN")
    assert list(trials["state"]) == list(old_t["state"])
    params = [c for c in trials.columns if c in load_space()]
    for p in params:
        a, b = trials[p].to_numpy(), old_t[p].to_numpy()
        if a.dtype.kind in "fi":
            # the CSV keeps 10 significant digits
            np.testing.assert_allclose(a, b.astype(float), rtol=1e-9, err_msg=p)
        else:
            assert list(a) == list(b), p
    old_c = RESULTS["claims"].query("study == @s['name'] and number < @RERUN")
    both = claims.merge(old_c, on=["number", "reading", "id"], suffixes=("", " packaged"),
                        how="outer", indicator=True)
    assert (both["_merge"] == "both").all(), both[both["_merge"] != "both"]
    assert (both["status"] == both["status packaged"]).all(), \
        both[both["status"] != both["status packaged"]]
    np.testing.assert_allclose(both["margin"], both["margin packaged"], atol=MARGIN_ATOL,
                               rtol=0, equal_nan=True)


def test_mdart_inferred_is_the_best_rotor_of_the_packaged_studies():
    best = RESULTS["summary"]["best"]["continued"]
    trials = RESULTS["trials"]
    row = trials[(trials["study"] == best["trial"][0])
                 & (trials["number"] == best["trial"][1])].iloc[0]
    # no trial keeping the stated frequencies has a higher objective
    calibration = {c.id for c in load_claims() if c.tag == "calibration"}
    claims = RESULTS["claims"].query("reading == 'continued'")
    broke = claims[claims["id"].isin(calibration) & (claims["status"] != "pass")]
    keeps = trials[trials["state"] == "COMPLETE"].merge(
        broke[["study", "number"]].drop_duplicates(), how="left", indicator=True)
    keeps = keeps[keeps["_merge"] == "left_only"]
    assert row["continued objective"] == pytest.approx(keeps["continued objective"].max())
    sample = sample_of(load_config("mdart-inferred"), load_config("mdart"), load_space())
    for name, v in best["params"].items():
        if isinstance(v, str):
            assert sample[name] == v, name
        else:
            # the variant's TOML and the CSV round their numbers; 1e-9 is far below
            # any parameter's resolution in the space
            assert sample[name] == pytest.approx(v, rel=1e-9), name


def test_the_report_says_what_the_studies_found():
    view = inference_view(RESULTS)
    assert [s["name"] for s in view["studies"]] == [s["name"] for s in STUDIES]
    rotors = {(r["rotor"].split(" ")[0], r["reading"]) for r in view["rotors"]}
    assert ("mdart", "continued") in rotors and ("inferred,", "flutter") in rotors
    assert view["verdict"]
    assert {p["name"] for p in view["parameters"]} == set(load_space())
    assert {x["figure"] for x in view["lofo"]} == {"fig6", "fig7", "fig8", "fig9", "fig12"}
    assert view["conflicts"] and all(float(c["rho"]) < -0.5 for c in view["conflicts"])


def test_export_writes_what_load_reads(tmp_path, fixed_protocol):
    declared = [{"name": "s", "reading": "continued", "sampler": "qmc", "seed": 0,
                 "trials": 4}]
    storage = str(tmp_path / "s.journal")
    run_study(StudySpec(storage=storage, protocol=fixed_protocol, sampler="qmc", name="s"), 4,
              evaluator=fakes.quick)
    out = load_results(export_results(storage, tmp_path / "results", check=False,
                                      studies=declared))
    assert len(out["trials"]) == 4
    assert set(out["claims"]["reading"]) == {"continued", "flutter"}
    assert isinstance(out["summary"]["pass_rates"]["continued"], list)
    assert load_results(tmp_path / "empty") == {}
    assert pd.api.types.is_float_dtype(out["claims"]["margin"])


def test_the_sobol_indices_cover_every_claim_mdart_fails_or_leaves_ambiguous():
    info, table = RESULTS["sobol_info"], RESULTS["sobol"]
    assert info["claims"] == [c.id for c in sobol_claims()]
    assert info["rotors"] == info["n"] * 8            # Saltelli, six groups, no second order
    view = inference_view(RESULTS)
    named = [x["claim"] for x in view["sobol"]]
    # every analysed claim is either indexed (its term varied) or said unmoved
    assert sorted(named + view["sobol_unmoved"]) == sorted(info["claims"])
    for x in view["sobol"]:
        mine = table[table["claim"] == x["claim"]]
        assert x["group"] == mine.loc[mine["ST"].idxmax(), "group"]
        assert set(mine["group"]) == {"flap", "actuator", "section", "blade stiffness",
                                      "aerodynamics", "hub"}


def test_the_report_says_whether_the_answer_depends_on_the_sampler_or_the_seed():
    # each reading's agreement names its studies' bests as trials.csv holds them, and
    # the report says the answer depends on them exactly when a parameter lies apart
    trials = RESULTS["trials"]
    for reading, ag in RESULTS["summary"]["agreement"].items():
        own = [s["name"] for s in STUDIES if s["reading"] == reading]
        assert [r["study"] for r in ag["studies"]] == own
        for r in ag["studies"]:
            mine = trials[(trials["study"] == r["study"]) & (trials["state"] == "COMPLETE")]
            assert r["objective"] == pytest.approx(mine[f"{reading} objective"].max())
        assert ag["same"] == (not ag["apart"])
    text = inference_view(RESULTS)["agreement"]
    for reading, label in (("continued", "continued TEF"), ("flutter", "flutter root")):
        ag = RESULTS["summary"]["agreement"].get(reading)
        said = f"as the {label}, the answer "
        if ag is None or len(ag["studies"]) < 2:
            assert said not in text          # one study cannot say whether it depends
            continue
        assert said + ("depends" if not ag["same"] else "does not depend") in text


def test_the_report_says_when_both_readings_pick_the_same_rotor():
    # the best rotor by the flutter root may be a trial of a continued-reading study;
    # where one trial is best by both objectives its rows say so, not a second rotor
    best = RESULTS["summary"]["best"]
    rows = [r["rotor"] for r in inference_view(RESULTS)["rotors"]]
    same = best["flutter"]["trial"] == best["continued"]["trial"]
    assert any("the same rotor" in r for r in rows) == same
    other = {**RESULTS, "summary": {**RESULTS["summary"], "best": {
        **best, "flutter": {**best["flutter"], "trial": ["another study", 1]}}}}
    assert not any("the same rotor" in r["rotor"] for r in inference_view(other)["rotors"])


def test_the_report_says_which_passes_of_the_inferred_rotor_hold_on_the_converged_basis():
    # the inferred rotor's converged-basis verdicts are stored for it (its config hash),
    # and the report counts its validation passes that have one and names each that is
    # lost there
    from tefcore.paper.claims.truncation import load_converged

    conv = load_converged(load_config("mdart-inferred"))
    assert conv is not None and (conv["n_modes"] >= 9).all()
    statuses = RESULTS["summary"]["checks"]["best continued"]["continued"]["statuses"]
    validation = {c.id for c in load_claims() if c.tag == "validation"}
    by_id = conv.set_index("id")["status"]
    passes = [i for i in validation if statuses.get(i) == "pass" and i in by_id.index]
    lost = sorted(i for i in passes if by_id[i] != "pass")
    text = inference_view(RESULTS)["truncation"]
    assert f"{len(lost)} of the {len(passes)} passes of its stability figures" in text
    assert all(i in text for i in lost)
