"""The command line: one clear line for tefcore's errors, no traceback, honest exit status,
outputs checked before computing."""

import subprocess
import sys

import pandas as pd
import pytest

import tefcore.linear.stability
import tefcore.sweeps.sweep
from tefcore.aero.c81 import example_deck_path
from tefcore.cli import main
from tefcore.trimming.trim import TrimError
from tests.sweeps.test_sweep import ToyPoint


def one_error_line(capsys):
    err = capsys.readouterr().err
    assert err.startswith("tefcore: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


@pytest.fixture
def toy_default_point(monkeypatch):
    """`tefcore sweep` evaluates the synthetic point of test_sweep instead of stability."""
    point = ToyPoint()
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    return point


# ------------------------------------------------------------------ outputs first


def test_a_bad_csv_destination_fails_before_computing(tmp_path, monkeypatch, capsys):
    """``--csv nodir/x.csv`` fails before any point is computed, not with an OSError after."""
    calls = []
    monkeypatch.setattr(tefcore.linear.stability, "stability", lambda cfg, **kw: calls.append(cfg))
    out = tmp_path / "s.jsonl"
    code = main(["sweep", "flap.cg_offset", "--values", "0.0", "0.1", "--quiet",
                 "--csv", str(tmp_path / "nodir" / "x.csv"), "--out", str(out)])
    assert code == 2 and calls == []
    err = one_error_line(capsys)
    assert "--csv" in err and "nodir" in err and "does not exist" in err
    assert not out.exists()                             # nothing started


def test_modes_csv_destination_checked_first(tmp_path, capsys):
    (tmp_path / "d.csv").mkdir()
    assert main(["modes", "--csv", str(tmp_path / "d.csv")]) == 2
    assert "is a folder" in one_error_line(capsys)


# ------------------------------------------------------------------ units


def test_a_dimensionless_field_refuses_an_angle(capsys):
    """``-s "flight.ct_sigma=5 deg"`` is refused, not read as 0.0873."""
    assert main(["modes", "-s", "flight.ct_sigma=5 deg"]) == 2
    err = one_error_line(capsys)
    assert "flight.ct_sigma" in err and "'deg' is an angle" in err and "pure number" in err


def test_a_dimensional_field_needs_its_unit_on_the_command_line(capsys):
    """``-s hub.pitch_link_stiffness=800`` is refused, not read as 800 N/m."""
    assert main(["modes", "-s", "hub.pitch_link_stiffness=800"]) == 2
    err = one_error_line(capsys)
    assert "hub.pitch_link_stiffness = 800 needs a unit" in err and "lb/in" in err
    assert main(["modes", "-s", "hub.pitch_link_stiffness=140101 N/m"]) == 0   # SI, spelled out
    assert main(["modes", "-s", "flight.shaft_angle=0.05"]) == 2                # angles too
    assert "flight.shaft_angle" in one_error_line(capsys)


def test_sweep_range_and_values_take_units(tmp_path, toy_default_point, capsys):
    csv = tmp_path / "k.csv"
    assert main(["sweep", "hub.pitch_link_stiffness", "--range", "400 lb/in", "800 lb/in",
                 "3", "--csv", str(csv), "--quiet"]) == 0
    table = pd.read_csv(csv)
    assert list(table["value"].unique()) == ["400 lb/in", "600 lb/in", "800 lb/in"]
    # 1 lb/in = 175.126835... N/m (scipy constants); printed values to 1e-9 relative
    assert table["value_si"].unique() == pytest.approx([400 * 175.12683524647636,
                                                        600 * 175.12683524647636,
                                                        800 * 175.12683524647636], rel=1e-9)
    assert main(["sweep", "hub.pitch_link_stiffness", "--values", "800", "--csv",
                 str(csv)]) == 2
    assert "needs a unit" in one_error_line(capsys)
    assert main(["sweep", "flap.cg_offset", "--range", "0", "0.2", "2", "--csv", str(csv),
                 "--quiet"]) == 0
    calls = toy_default_point.calls
    assert main(["sweep", "hub.pitch_link_stiffness", "--values", "400 lb", "--csv",
                 str(csv)]) == 2                       # a wrong unit: refused before computing
    assert "force_per_length" in one_error_line(capsys) and toy_default_point.calls == calls


# ------------------------------------------------------------------ no tracebacks


def test_a_missing_config_file_is_one_line(tmp_path, capsys):
    assert main(["modes", "--config", str(tmp_path / "missing.toml")]) == 2
    assert "missing.toml" in one_error_line(capsys)


def test_a_trim_error_is_one_line(monkeypatch, capsys):
    def no_trim(cfg, **kw):
        raise TrimError("trim did not converge in 40 iterations", [])

    monkeypatch.setattr(tefcore.linear.stability, "stability", no_trim)
    assert main(["stability"]) == 2
    assert "trim did not converge" in one_error_line(capsys)


def test_a_missing_c81_deck_is_one_line(tmp_path, capsys):
    assert main(["stability", "-s", "model.aero_model=c81", "-s",
                 f"model.c81_deck={tmp_path / 'nodeck.c81'}"]) == 2
    err = one_error_line(capsys)
    assert "model.c81_deck" in err and "no such file" in err


def test_an_override_without_equals_is_one_line(capsys):
    assert main(["modes", "-s", "flap.overhang"]) == 2
    assert "name=value" in one_error_line(capsys)


def test_c81_check_of_a_non_utf8_file_names_the_line(tmp_path, capsys):
    """A non-UTF-8 byte is one line naming the file's line, not a UnicodeDecodeError."""
    lines = example_deck_path().read_bytes().split(b"\n")
    lines[14] = lines[14][:10] + b"\xb2" + lines[14][11:]    # latin-1 superscript two
    bad = tmp_path / "bad.c81"
    bad.write_bytes(b"\n".join(lines))
    assert main(["c81", "check", str(bad)]) == 1
    err = capsys.readouterr().err
    assert f"{bad} line 15, column 11: not UTF-8 text: byte 0xb2" in err
    assert main(["c81", "check", str(tmp_path / "none.c81")]) == 2
    assert "none.c81" in one_error_line(capsys)


def test_broken_pipe_ends_quietly():
    """``tefcore modes | head -1`` ends quietly (status 141), without a BrokenPipeError."""
    proc = subprocess.Popen([sys.executable, "-m", "tefcore", "modes"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()                         # the reader went away before any output
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141 and err == ""


# ------------------------------------------------------------------ exit status


def test_sweep_exits_nonzero_when_points_failed(tmp_path, monkeypatch, capsys):
    """``tefcore sweep`` exits non-zero when points failed."""
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: ToyPoint(fail_at=[0.0, 0.1]))
    csv = tmp_path / "s.csv"
    assert main(["sweep", "flap.cg_offset", "--values", "0.0", "0.1", "0.2", "--csv", str(csv),
                 "--quiet"]) == 1
    captured = capsys.readouterr()
    assert "2 of 3 point(s) failed" in captured.err
    assert pd.read_csv(csv)["status"].tolist().count("failed") == 2     # the table is written


def test_a_sweep_value_outside_its_range_is_refused_before_computing(tmp_path, monkeypatch,
                                                                      capsys):
    """A value ``-s`` would refuse is refused by ``--values`` too, before any point runs."""
    calls = []
    monkeypatch.setattr(tefcore.linear.stability, "stability", lambda cfg, **kw: calls.append(cfg))
    csv = tmp_path / "s.csv"
    assert main(["sweep", "flap.cg_offset", "--values", "0", "2", "--csv", str(csv),
                 "--quiet"]) == 2
    err = one_error_line(capsys)
    assert "flap.cg_offset = 2.0 is outside the allowed range [-1, 1]" in err
    assert calls == [] and not csv.exists()
