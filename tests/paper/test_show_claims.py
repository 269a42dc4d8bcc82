"""The notebooks' claims table: deterministic text, and a truncation-dependent verdict said."""

import pandas as pd

from tefcore.config.io import load_config
from tefcore.paper.claims.truncation import load_converged, mark_truncation
from tefcore.paper.summaries import show_claims


def test_a_truncation_dependent_claim_gets_both_verdicts(capsys):
    claims = pd.DataFrame({"id": ["a", "b"], "status": ["pass", "fail"],
                           "computed": [0.123456, "x"], "reason": ["", ""]})
    conv = pd.DataFrame({"id": ["a", "b"], "status": ["ambiguous", "fail"],
                         "n_modes": [24, 16], "computed_value": [1.0, 2.0]})
    show_claims(mark_truncation(claims, conv))
    out = capsys.readouterr().out
    assert "0.1235" in out
    assert "a: truncation-dependent, pass with the paper's 9 modes, ambiguous with 24" in out
    assert "b: truncation" not in out


def test_the_stored_converged_verdicts_are_mdarts_and_cover_every_stability_figure():
    # the converged-basis verdicts ship for the default rotor; a claim of every
    # stability figure with a checkable claim is in them, on a basis of at least 9
    conv = load_converged(load_config("mdart"))
    assert conv is not None
    assert {"fig8", "fig9", "fig10", "fig11", "fig12", "fig13", "fig14", "fig15", "fig16a",
            "fig16b", "fig17"} <= set(conv["figure"])
    assert (conv["n_modes"] >= 9).all()
    assert load_converged(load_config("mdart-fig6")) is None      # computed for mdart only


def test_each_configuration_keeps_its_own_converged_verdicts(tmp_path):
    # another configuration's verdicts sit beside mdart's under their own name and are
    # read back only for that configuration (its hash: a changed rotor has none)
    from tefcore.paper.claims.truncation import write_converged

    table = pd.DataFrame({"id": ["a"], "figure": ["fig9"], "status": ["fail"],
                          "computed_value": [1.5], "n_modes": [16]})
    fig6 = load_config("mdart-fig6")
    write_converged(table, fig6, root=tmp_path)
    assert (tmp_path / "converged_basis-mdart-fig6.csv").is_file()
    assert not (tmp_path / "converged_basis.csv").exists()
    back = load_converged(fig6, root=tmp_path)
    assert back["status"].tolist() == ["fail"] and back["n_modes"].tolist() == [16]
    assert load_converged(load_config("mdart"), root=tmp_path) is None
    moved = fig6.with_overrides({"flap.cg_offset": 0.2})
    assert load_converged(moved, root=tmp_path) is None
