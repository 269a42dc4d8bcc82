"""What the command imports before it computes.

Start-up is most of a one-point command's time: ``tefcore --version`` and
``--help`` import no numerics at all, and ``tefcore stability`` imports what a
point needs: numpy, scipy.linalg, and scipy.optimize for the assignments that
name the modes (it brings scipy.constants, scipy.sparse, scipy.spatial and
scipy.special with it), but not pandas (the roots are named on the table's
columns, and the command words the columns, tefcore.cli.text; the table
itself is built on first use, for ``--csv``), scipy.integrate (only the
tension integral of a tabulated mass uses it) nor scipy.interpolate (only a
C81 deck read).  Importing the solver imports no scipy.optimize: the modules
that assign import :func:`scipy.optimize.linear_sum_assignment` where they
call it.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

HEAVY = ("numpy", "scipy", "pandas", "matplotlib", "tefcore.config", "tefcore.structure")


def _modules_after(argv: list[str]) -> set[str]:
    """The modules loaded by ``tefcore ARGV`` in a fresh process (its output discarded)."""
    code = ("import io, sys, contextlib\n"
            "from tefcore.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    try:\n"
            f"        main({argv!r})\n"
            "    except SystemExit:\n"
            "        pass\n"
            "print('\\n'.join(sorted(sys.modules)))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    return set(out.stdout.split())


@pytest.mark.parametrize("argv", [["--version"], ["--help"], ["stability", "--help"]])
def test_version_and_help_import_no_numerics(argv):
    loaded = _modules_after(argv)
    assert not {m for m in loaded if m.startswith(HEAVY)}


@pytest.mark.parametrize("argv", [["stability", "--set", "flight.advance_ratio=0"],
                                  ["stability"]])
def test_stability_imports_only_what_a_point_needs(argv):
    loaded = _modules_after(argv)
    assert {"numpy", "scipy.linalg", "tefcore.linear.stability"} <= loaded
    for name in ("pandas", "scipy.integrate", "scipy.interpolate", "matplotlib"):
        assert name not in loaded, name


def test_importing_the_solver_leaves_scipy_optimize_to_the_first_assignment():
    # the modules that label and match modes import scipy's assignment where
    # they call it: a program that imports the solver and never names a mode
    # does not pay for scipy.optimize (0.15-0.2 s of import)
    code = ("import sys, tefcore.linear.stability; "
            "print('scipy.optimize' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"


def _program(prelude: str) -> subprocess.CompletedProcess:
    """``python -m tefcore stability`` (hover) in a fresh process, after `prelude`."""
    code = ("import runpy, sys\n" + prelude +
            "sys.argv = ['tefcore', 'stability', '--set', 'flight.advance_ratio=0']\n"
            "runpy.run_module('tefcore', run_name='__main__', alter_sys=True)\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)


def test_the_program_exits_without_the_final_collection():
    # `python -m tefcore` (and the installed script) end in gc.freeze(): the
    # interpreter's last collections would walk every object numpy, scipy and
    # pandas made (0.1-0.2 s, tefcore.cli.entry_point).  The exit handlers
    # still run -- this one reports the frozen count -- and the output is whole.
    out = _program("import atexit, gc\n"
                   "atexit.register(lambda: sys.stderr.write("
                   "f'frozen {gc.get_freeze_count()}\\n'))\n")
    assert out.returncode == 0, out.stderr
    frozen = int(out.stderr.split("frozen")[-1])
    assert frozen > 10_000          # numpy and scipy alone leave ~10^5 tracked objects
    assert "TEF" in out.stdout and out.stdout.endswith("\n")


def test_main_leaves_the_collector_alone(tmp_path):
    # main() is what tests and programs call in their own process: freezing
    # there would keep their cyclic garbage for good
    import gc

    from tefcore.cli import main

    before = gc.get_freeze_count()
    assert main(["c81", "example", "--out", str(tmp_path / "deck.c81")]) == 0
    assert gc.get_freeze_count() == before


def test_the_installed_script_is_the_program():
    import tomllib
    from pathlib import Path

    pyproject = Path(__file__).resolve().parents[1] / "pyproject.toml"
    scripts = tomllib.loads(pyproject.read_text())["project"]["scripts"]
    assert scripts["tefcore"] == "tefcore.cli:entry_point"


def test_the_program_runs_without_a_stderr():
    # pythonw and some launchers start a process with sys.stderr None: the exit
    # must not fail on flushing it
    out = _program("sys.stderr = None\n")
    assert out.returncode == 0, out.stderr
    assert "TEF" in out.stdout
