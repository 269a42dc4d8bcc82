"""What the command imports before it computes, and the table it prints without pandas.

Start-up is most of a one-point command's time: ``tefcore --version`` and
``--help`` import no numerics at all, and ``tefcore stability`` imports what a
point needs (numpy, scipy.linalg) but not pandas (a table is built only where
one is read or written), scipy.constants (the unit factors are written out),
scipy.integrate (only the tension integral of a tabulated mass uses it) nor,
in hover, scipy.optimize (only the forward-flight momentum inflow's root).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from tefcore.cli import table_text

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


def test_stability_imports_only_what_a_point_needs():
    loaded = _modules_after(["stability", "--set", "flight.advance_ratio=0"])
    assert {"numpy", "scipy.linalg", "tefcore.linear.stability"} <= loaded
    for name in ("pandas", "scipy.constants", "scipy.integrate", "scipy.optimize",
                 "matplotlib"):
        assert name not in loaded, name


def _result_columns(mu):
    from tefcore.config.io import load_config
    from tefcore.linear.stability import stability

    res = stability(load_config("mdart").with_overrides({"flight.advance_ratio": mu}))
    return res.columns


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_table_text_is_pandas_to_string(mu):
    # the command's table (no pandas) is the one pandas prints, character for character
    columns = _result_columns(mu)
    expected = pd.DataFrame(columns).to_string(index=False, float_format=lambda v: f"{v:.4f}")
    assert table_text(columns) == expected


def test_table_text_edge_cases_are_pandas_to_string():
    # short names under wide values, negative integers, NaN, a lone string column
    columns = {"a": [1, 22, -3], "x": [0.5, -12.25, 3.0], "long_name": [1.0, 2.0, 3.0],
               "s": ["ab", "c", "longer str"], "t": ["A", "bb", "c"],
               "b": [np.nan, 1.0, -0.0], "i": np.arange(3)}
    expected = pd.DataFrame(columns).to_string(index=False, float_format=lambda v: f"{v:.4f}")
    assert table_text(columns) == expected
