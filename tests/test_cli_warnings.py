"""The command's warnings are one line each, and what a user reads is not noise."""

import platform

import pandas as pd
import pytest

import tefcore.linear.stability
from tefcore.cli import main
from tests.linear.test_stability_signal import XFOIL


def test_clipped_c81_inputs_are_one_warning_line(capsys):
    """One line per point, not ~80 raw C81RangeWarning blocks (two lines each)."""
    deck = XFOIL.model.c81_deck
    assert main(["stability", "-s", "model.aero_model=c81", "-s",
                 f"model.c81_deck={deck}"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1, err
    assert err[0].startswith("tefcore: warning: C81RangeWarning: C81 deck "
                             "'NACA0012 35%TEF XFOIL': inputs outside the table clipped")
    assert "alpha reached" in err[0] and "mach reached" in err[0]


def test_a_real_part_below_the_resolution_is_printed_neutral(monkeypatch, capsys, tmp_path):
    """A sign that means nothing (-0.0000) is flagged neutral."""
    res = tefcore.linear.stability.stability(XFOIL.with_overrides(
        {"model.aero_model": "thin_airfoil"}))
    modes = res.modes.copy()
    modes.loc[0, ["real_part", "real_part_error"]] = [-3e-8, 1e-7]      # unresolved
    modes.loc[1, ["real_part", "real_part_error"]] = [-3.09e-5, 4e-11]  # resolved, tiny
    modes["neutral"] = modes["real_part"].abs() <= modes["real_part_error"]
    res.modes = modes
    monkeypatch.setattr(tefcore.linear.stability, "stability", lambda cfg: res)
    csv = tmp_path / "m.csv"
    assert main(["stability", "--csv", str(csv)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "-0.0000" not in "\n".join(lines)
    assert " neutral " in lines[1] and "-3.09e-05" in lines[2]
    # the stored numbers are unchanged; the flag is its own column
    stored = pd.read_csv(csv)
    assert stored.loc[0, "real_part"] == -3e-8 and bool(stored.loc[0, "neutral"])
    assert stored.loc[1, "real_part"] == -3.09e-5 and not bool(stored.loc[1, "neutral"])


@pytest.mark.skipif(platform.machine().lower() not in ("x86_64", "amd64"),
                    reason="OpenBLAS's kernel names are checked on x86-64")
@pytest.mark.parametrize("value, hint", [("garbage", "(e.g. Haswell, SkylakeX, Zen)"),
                                         ("Haswel", "(did you mean Haswell?)")])
def test_an_unknown_openblas_kernel_is_one_warning_line(value, hint, monkeypatch, capsys):
    """OpenBLAS ignores a kernel name it does not know without a word (it picks its kernels
    by the processor), so a typo in OPENBLAS_CORETYPE went unnoticed."""
    from tefcore.aero.c81 import example_deck_path

    monkeypatch.setenv("OPENBLAS_CORETYPE", value)
    assert main(["c81", "check", str(example_deck_path())]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err == [f"tefcore: warning: OPENBLAS_CORETYPE = {value!r} is not a kernel OpenBLAS "
                   f"knows {hint}; OpenBLAS ignores it and picks its kernels by the processor"]
    for known in ("Haswell", "skylakex", "ZEN", "SapphireRapids"):   # read without case
        monkeypatch.setenv("OPENBLAS_CORETYPE", known)
        assert main(["c81", "check", str(example_deck_path())]) == 0
        assert capsys.readouterr().err == ""
