"""What the command imports before it computes.

Start-up is most of a one-point command's time: ``tefcore --version`` and
``--help`` import no numerics at all, and ``tefcore stability`` imports what a
point needs (numpy, scipy.linalg) but not pandas (the roots are named on
the table's columns, and the command words the columns, tefcore.cli.text;
the table itself is built on first use, for ``--csv``), scipy.constants (the
unit factors are written out), scipy.integrate (only the tension integral of
a tabulated mass uses it), scipy.interpolate (only a C81 deck read),
scipy.sparse (the blade's uncoupled field blocks are the components of a 4 x 4
graph, found without it; a Floquet lift imports it only for repeated
multipliers) nor scipy.optimize (the momentum
inflow's root is a safeguarded Newton iteration, and tefcore.assignment
solves the continuation's small assignments itself where their optimum is
unique -- at the default point, mu = 0.3, it is).
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
    for name in ("pandas", "scipy.constants", "scipy.integrate", "scipy.interpolate",
                 "scipy.optimize", "scipy.sparse", "matplotlib"):
        assert name not in loaded, name
