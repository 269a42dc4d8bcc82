"""Command line: modes table, configuration errors, the reproduce command."""

import subprocess
import sys

import pandas as pd
import pytest

from tefcore.cli import main


def test_modes_with_override_writes_csv(tmp_path, capsys):
    out = tmp_path / "modes.csv"
    # Fig. 10 is for the mass-imbalanced flap, whose CG offset is part of the
    # blade section (tefcore.structure.section_inertia)
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


# ------------------------------------------------------------------ help and version


def _help(*args) -> str:
    r = subprocess.run([sys.executable, "-m", "tefcore", *args, "--help"], capture_output=True,
                       text=True, check=True, env={**__import__("os").environ, "COLUMNS": "80"})
    return r.stdout


def test_version_is_the_package_version():
    import tefcore

    r = subprocess.run([sys.executable, "-m", "tefcore", "--version"], capture_output=True,
                       text=True, check=True)
    assert r.stdout.strip() == f"tefcore {tefcore.__version__}"


SUBCOMMANDS = ("modes", "fanplot", "stability", "sweep", "map", "mechanism", "c81", "reproduce",
               "batch")


def test_help_lists_each_subcommand_on_one_line_without_markup():
    text = _help()
    for markup in ("``", ":mod:", ":func:", ":class:", ":data:"):
        assert markup not in text, markup
    lines = text.splitlines()
    for name in SUBCOMMANDS:
        # "    name   help text" on one line (argparse wraps long names otherwise)
        line = next(li for li in lines if li.strip().split(" ")[0] == name)
        assert len(line.split()) > 2, line
    assert "exit status" in text and "examples:" in text


@pytest.mark.parametrize("name", SUBCOMMANDS)
def test_every_subcommand_has_help(name):
    # (map's --help failed with a ValueError: argparse and tuple metavars)
    text = _help(name)
    assert text.startswith(f"usage: tefcore {name}")


def test_every_subcommand_has_a_description():
    from tefcore.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")  # noqa: SLF001 (argparse)
    for name, p in sub.choices.items():
        assert p.description and "``" not in p.description, name
    text = _help("c81")
    assert "check" in text and "example" in text


def test_c81_check_reports_each_deck(tmp_path, capsys):
    from tefcore.aero.c81 import example_deck_path

    bad = tmp_path / "bad.c81"
    bad.write_text("not a deck\n")
    assert main(["c81", "check", str(example_deck_path()), str(bad)]) == 1
    out, err = capsys.readouterr()
    assert "flap deck, 7 deltas" in out and f"{bad} line 1" in err
