"""Command line: modes table, configuration errors, the reproduce command."""

import subprocess
import sys

import pandas as pd

from tefcore.cli import main


def test_modes_with_override_writes_csv(tmp_path, capsys):
    out = tmp_path / "modes.csv"
    # Fig. 10 is for the mass-imbalanced flap, whose CG offset is part of the
    # blade section (tefcore.section_inertia)
    assert main(["modes", "-s", "hub.pitch_link_stiffness=800 lb/in", "-s", "flap.cg_offset=0.33",
                 "--csv", str(out)]) == 0
    df = pd.read_csv(out)
    torsion = df.loc[df.label == "torsion 1", "frequency_per_rev"].item()
    assert abs(torsion / 4.2 - 1) < 0.02          # Fig. 10a statement, 2 % gate
    assert "torsion 1" in capsys.readouterr().out


def test_bad_override_is_a_clear_error_not_a_traceback(capsys):
    assert main(["modes", "-s", "flap.overhang=1.2"]) == 2
    err = capsys.readouterr().err
    assert "flap.overhang" in err and "[0, 1)" in err and "Traceback" not in err


def test_python_m_entry_point():
    r = subprocess.run([sys.executable, "-m", "tefcore", "--help"], capture_output=True,
                       text=True, check=True)
    assert "reproduce" in r.stdout
