"""A figure that cannot be computed: its claims say so, the rest are still checked."""

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.paper.attribution.evaluate import FigureCache
from tefcore.paper.claims import validation
from tefcore.paper.claims.reference import STATUSES, load_claims
from tefcore.paper.inference.evaluate import evaluate_rotor, objective
from tefcore.trimming.trim import TrimError

CLAIMS = [c for c in load_claims() if c.figure in ("fig6", "fig7")]


class TrimFailsAtFig7(FigureCache):
    def result(self, figure, cfg, settings, overrides, values):
        if figure == "fig7":
            raise TrimError("trim did not converge in 40 iterations (planted)")
        return super().result(figure, cfg, settings, overrides, values)


def test_not_computable_is_a_status_between_not_reproducible_and_fail():
    assert STATUSES.index("not reproducible") < STATUSES.index("not computable") \
        < STATUSES.index("fail")


def test_evaluate_rotor_survives_a_figure_that_cannot_be_computed(tmp_path):
    calibration = [c for c in load_claims() if c.tag == "calibration"]
    out = evaluate_rotor(load_config("mdart"), CLAIMS + calibration,
                         ("continued", "flutter"), cache=TrimFailsAtFig7(tmp_path))
    assert set(out["broken"]) == {"fig7"} and "TrimError" in out["broken"]["fig7"]
    for reading in ("continued", "flutter"):
        t = out[reading].set_index("id")
        fig7 = t[t["figure"] == "fig7"]
        assert len(fig7) == 3 and (fig7["status"] == "not computable").all()
        assert fig7["reason"].str.contains("fig7 cannot be computed: TrimError").all()
        # the rest are checked as ever: Fig. 6's response (0.97 x on mdart, the claim
        # wants 1.15 +- 0.1) fails with its margin, the stated frequencies pass
        assert t.loc["fig6-response-15pct-above-input", "status"] == "fail"
        assert t.loc["fig6-response-15pct-above-input", "margin"] < -1
        assert (t.loc[[c.id for c in calibration], "status"] == "pass").all()


def test_validate_all_survives_a_figure_that_cannot_be_computed(monkeypatch):
    real = validation.compute_figure

    def compute(name, *args, **kw):
        if name == "fig7":
            raise TrimError("trim did not converge (planted)")
        return real(name, *args, **kw)

    monkeypatch.setattr(validation, "compute_figure", compute)
    t = validation.validate_all(claims=CLAIMS).set_index("id")
    fig7 = t[t["figure"] == "fig7"]
    assert (fig7["status"] == "not computable").all()
    assert fig7["reason"].str.startswith("fig7 cannot be computed: TrimError").all()
    assert np.isnan(fig7["margin"]).all()
    assert t.loc["fig6-response-15pct-above-input", "status"] == "fail"
    # not computable is worse than a recorded pass (fig7b), not than a recorded fail (fig7a)
    assert validation.worse_than_recorded(t.reset_index())["id"].tolist() == [
        "fig7b-response-increases-with-overhang", "fig7b-steeper-above-0.40"]


def test_an_error_that_is_a_bug_is_not_swallowed(monkeypatch):
    def compute(name, *args, **kw):
        raise KeyError("a bug")

    monkeypatch.setattr(validation, "compute_figure", compute)
    with pytest.raises(KeyError):
        validation.validate_all(claims=CLAIMS)


@pytest.mark.parametrize(("status", "margin", "term"), [
    ("pass", 0.5, np.tanh(0.5)), ("fail", -3.0, np.tanh(-3.0)), ("pass", np.nan, 1.0),
    ("ambiguous", np.nan, 0.0), ("fail", -0.0, -1.0), ("fail", np.nan, -1.0),
    ("not computable", np.nan, -1.0), ("not reproducible", np.nan, 0.0)])
def test_each_claims_term_of_the_objective(status, margin, term):
    assert objective(pd.DataFrame({"status": [status], "margin": [margin]})) == \
        pytest.approx(term, abs=1e-12)
