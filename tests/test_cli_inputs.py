"""Numbers typed on the command line: NaN, infinities and out-of-range values get one line
naming the option, its value and its range, before anything is computed; and what the
commands say of the flutter root agrees between them."""

from __future__ import annotations

import pytest

import tefcore.structure.blade
import tefcore.timedomain.simulate
from tefcore.cli import main
from tefcore.timedomain.limits import MAX_AMPLITUDE


class Started(Exception):
    """Raised by a stand-in: the computation would have started here."""


@pytest.fixture
def nothing_computed(monkeypatch):
    calls = []

    def stand_in(*a, **kw):
        calls.append(a)
        raise Started

    monkeypatch.setattr(tefcore.timedomain.simulate, "simulate", stand_in)
    monkeypatch.setattr(tefcore.structure.blade, "blade_modes", stand_in)
    monkeypatch.setattr(tefcore.structure.blade, "fan_plot", stand_in)
    return calls


@pytest.mark.parametrize("argv, expected", [
    # --amplitude nan: "the initial state is zero: nothing to march"
    (["simulate", "--amplitude", "nan"], f"argument --amplitude: must be a number in "
                                         f"(0, {MAX_AMPLITUDE:g}] chords, got 'nan'"),
    (["simulate", "--amplitude", "inf"], "argument --amplitude: must be a number in (0, 1]"),
    (["simulate", "--anim-revs", "nan"], "argument --anim-revs: must be a number in (0, 6]"),
    # --collective nan: "the assembled blade mass matrix is not positive definite"
    (["modes", "--collective", "nan"], "argument --collective: must be a number in [-90, 90] "
                                       "deg, got 'nan'"),
    (["modes", "--collective=-inf"], "argument --collective: must be a number in [-90, 90]"),
    # --n-modes -3: an IndexError traceback
    (["modes", "--n-modes", "-3"], "argument --n-modes: must be a whole number in [1, inf), "
                                   "got '-3'"),
    (["fanplot", "--n-modes", "0"], "argument --n-modes: must be a whole number in [1, inf)"),
    # --jobs 0: "n_jobs must be a non-zero integer" (the library's name, not the option's)
    (["sweep", "flap.cg_offset", "--values", "0", "--jobs", "0"],
     "argument --jobs: must be a whole number of processes other than 0"),
    (["map", "flap.cg_offset", "0", "1", "2", "flap.overhang", "0", "1", "2", "--jobs", "x"],
     "argument --jobs: must be a whole number of processes other than 0"),
])
def test_a_bad_number_is_one_line_naming_the_option(argv, expected, nothing_computed, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"tefcore: error: {argv[0]}: ") and err.count("\n") == 1, err
    assert expected in err and "Traceback" not in err
    assert nothing_computed == []


def test_the_flutter_root_is_named_alike_by_stability_and_simulate(capsys):
    # at the MDART point the least stable flap-induced root is stable: `stability` said
    # "no flutter root" while `simulate --mode flutter` said it started from "the flutter root"
    assert main(["stability"]) == 0
    said = capsys.readouterr().out
    assert "no flutter root: the least stable flap-induced root, blade torsion 2, is stable" \
        in said
    assert main(["simulate", "--mode", "flutter", "--revs", "2", "--no-work"]) == 0
    out = capsys.readouterr().out
    assert "flutter root (" not in out
    assert ("started from the least stable flap-induced root, blade torsion 2, at 0.001 chord "
            "(no flutter root: it is stable)") in " ".join(out.split())
