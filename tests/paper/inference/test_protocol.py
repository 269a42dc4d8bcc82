"""The protocol: what is fitted and held out, the readings, and that the study never reads a
held-out claim."""

import optuna
import pandas as pd
import pytest

from tefcore.modes.roles import FLUTTER_ROOT
from tefcore.paper.attribution import evaluate as attribution_evaluate
from tefcore.paper.attribution.evaluate import FigureCache
from tefcore.paper.claims.reference import load_claims
from tefcore.paper.figures.runs import base_config
from tefcore.paper.inference.protocol import load_protocol, read_claims
from tefcore.paper.inference.space import baseline_sample, load_space
from tefcore.paper.inference.study import Objective, StudySpec

PROTOCOL = load_protocol()
FIT, HELD = PROTOCOL.split(load_claims())


def test_fitted_are_calibration_and_whole_declared_figures():
    assert {c.id for c in FIT} | {c.id for c in HELD} == {c.id for c in load_claims()}
    assert not {c.id for c in FIT} & {c.id for c in HELD}
    assert all(c.tag == "calibration" or c.figure in PROTOCOL.fit_figures for c in FIT)
    assert sum(c.tag == "calibration" for c in FIT) == 6
    # whole figures: every checkable validation claim of a fitted figure is fitted
    for c in HELD:
        assert c.figure not in PROTOCOL.fit_figures or c.kind == "not_reproducible"
    assert not any(c.kind == "not_reproducible" for c in FIT)


def test_leaving_a_figure_out_holds_its_claims_out():
    fit, held = PROTOCOL.split(load_claims(), without=["fig9"])
    assert not any(c.figure == "fig9" for c in fit)
    assert {c.id for c in held} - {c.id for c in HELD} == {c.id for c in FIT
                                                          if c.figure == "fig9"}


def test_the_flutter_reading_puts_the_flutter_root_in_the_tefs_place_on_stability_only():
    read = {c.id: c for c in read_claims(load_claims(), "flutter")}
    assert read["fig9b-tef-unstable-after-0.26"].mode == FLUTTER_ROOT
    assert read["fig17-tef-weakly-unstable-hover"].mode == FLUTTER_ROOT   # damping ratio
    # the TEF's frequency keeps the continued root
    assert read["fig9a-tef-frequency-decreases"].mode == "TEF"
    # the other curve of a comparison too
    assert read["fig15-flap-same-trend-as-tef"].other_mode == FLUTTER_ROOT
    assert read["fig15-flap-same-trend-as-tef"].mode == "blade flap 1"
    assert read_claims(load_claims(), "continued") == load_claims()
    with pytest.raises(ValueError, match="reading = 'both'"):
        read_claims(load_claims(), "both")


def test_the_objective_never_evaluates_a_held_out_claim(monkeypatch, tmp_path):
    # spies on what a trial computes (the figures asked of the cache) and checks
    # (the claims handed to their check); the figures themselves are stubs
    asked, checked = [], []

    def result(self, figure, cfg, settings, overrides, values):
        asked.append(figure)

    def validate_figure(name, res, claims, **kw):
        checked.extend(c.id for c in claims)
        return pd.DataFrame({"id": [c.id for c in claims], "status": "pass", "margin": 1.0,
                             "figure": name, "tag": [c.tag for c in claims]})

    monkeypatch.setattr(FigureCache, "result", result)
    # the claims are checked where every rotor's are (attribution.evaluate.checked_claims)
    monkeypatch.setattr(attribution_evaluate, "validate_figure", validate_figure)
    spec = StudySpec(storage=str(tmp_path / "s.journal"))
    study = optuna.create_study(direction="maximize")
    study.enqueue_trial(baseline_sample(base_config(), load_space()))
    study.optimize(Objective(spec), n_trials=1)
    assert study.trials[0].state == optuna.trial.TrialState.COMPLETE
    held = {c.id for c in HELD}
    assert set(checked) == {c.id for c in FIT}       # twice: one per reading
    assert not set(checked) & held
    # only the fitted figures' sweeps (the torsion claims of Figs. 10a/11a read the
    # blade's natural frequencies, without a sweep)
    assert set(asked) == set(PROTOCOL.fit_figures)
