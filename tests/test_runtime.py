"""Process settings of tefcore.runtime: never at import; in the CLI, the workers, the solver."""

import json
import os
import platform
import subprocess
import sys
import textwrap

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tefcore import runtime


def _parses_as_int(text):
    try:
        int(text)
    except ValueError:
        return False
    return True


GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


BLAS_THREADS = """
from threadpoolctl import threadpool_info
def blas_threads():
    return sorted({lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"})
"""


def run_python(code: str, **env) -> dict:
    """Run ``code`` (after :data:`BLAS_THREADS`) in a fresh interpreter; it prints
    one JSON line, returned parsed."""
    out = subprocess.run([sys.executable, "-c", BLAS_THREADS + textwrap.dedent(code)],
                         env=dict(os.environ, **env), capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


# the BLAS thread counts of a fresh process that never imported tefcore
UNTOUCHED = run_python("""
import json, numpy, scipy.linalg
print(json.dumps(blas_threads()))
""")
SEVERAL_THREADS = UNTOUCHED != [1]
needs_threads = pytest.mark.skipif(not SEVERAL_THREADS,
                                   reason="BLAS has one thread here: a limit cannot be seen")


@needs_threads
def test_import_changes_no_process_setting():
    # importing the package and the whole solver leaves BLAS as it was
    got = run_python("""
    import json, numpy, scipy.linalg
    import tefcore, tefcore.linear.stability, tefcore.sweeps.sweep
    import tefcore.linear.mechanism, tefcore.structure.blade
    print(json.dumps(blas_threads()))
    """)
    assert got == UNTOUCHED


@needs_threads
def test_solver_limits_blas_only_during_the_call():
    # floquet_modes calls A(psi) inside its limit: the count seen there is 1,
    # and the process has its own count back afterwards
    got = run_python("""
    import json
    import numpy as np
    from tefcore.floquet import floquet_modes
    seen = []
    def A(psi):
        seen.append(blas_threads())
        return np.broadcast_to(np.array([[0.0, 1.0], [-1.0, -0.1]]), (psi.size, 2, 2))
    floquet_modes(A)
    print(json.dumps({"inside": seen[0], "after": blas_threads()}))
    """)
    assert got == {"inside": [1], "after": UNTOUCHED}


@needs_threads
def test_apply_defaults_sets_the_process():
    got = run_python("""
    import json
    from tefcore.runtime import apply_defaults
    apply_defaults()
    print(json.dumps(blas_threads()))
    """)
    assert got == [1]


@needs_threads
def test_the_command_applies_the_settings():
    # the CLI's body runs after apply_defaults: seen from a subcommand
    got = run_python("""
    import json, tefcore.cli
    seen = []
    tefcore.cli.c81.run_check = lambda args: seen.append(blas_threads()) or 0
    tefcore.cli.main(["c81", "check", "x.c81"])
    print(json.dumps(seen[0]))
    """)
    assert got == [1]


@pytest.mark.parametrize("module, argv", [
    # the process `tefcore reproduce` starts for the other variant's claims: a
    # usage error stops it right after the settings (without them the heap was
    # trimmed and faulted back at every point: 56 s of CPU, 11 s of it system
    # time, against 42 s and 0.2 s for the same claims)
    ("tefcore.paper.run.variant_runs", ["no-such-command"]),
    # the calibration scripts, stopped at their first configuration
    ("tefcore.paper.calibration", []),
    ("tefcore.paper.fig6_calibration", []),
])
def test_the_solver_processes_tefcore_starts_apply_the_settings(module, argv):
    got = run_python(f"""
    import json, runpy, sys
    import tefcore.config.io as io
    def refuse(*args, **kw):
        raise ValueError("stopped by the test")
    io.loads_config = refuse
    sys.argv = ["{module}", *{argv!r}]
    try:
        runpy.run_module("{module}", run_name="__main__", alter_sys=True)
    except SystemExit as stop:
        code = stop.code
    from tefcore.runtime import defaults_applied
    print(json.dumps([code, defaults_applied()]))
    """)
    assert got == [2, True]


def test_blas_thread_setting_is_validated():
    for bad in ("0", "-2", "many"):
        with pytest.raises(ValueError, match="TEFCORE_BLAS_THREADS"):
            runtime.limit_blas_threads(bad)


def test_sweep_workers_apply_the_settings():
    # (loky limits BLAS threads in its workers by itself, so the BLAS count
    # would not tell whether tefcore's worker entry ran); the pool's worker,
    # asked directly: a two-point sweep stays in the caller
    from tefcore.runtime import defaults_applied
    from tefcore.sweeps.evaluate import close_pool, worker_pool

    try:
        assert worker_pool(1).submit(defaults_applied).result() is True
    finally:
        close_pool()


@pytest.mark.skipif(not GLIBC, reason="mallopt is glibc's")
def test_trim_threshold_applied_on_glibc():
    assert runtime.keep_freed_memory(str(64 * 2**20)) is True
    runtime.keep_freed_memory(str(128 * 2**20))        # back to apply_defaults' value


def test_default_leaves_the_allocator_alone():
    assert runtime.keep_freed_memory("default") is False


@pytest.mark.parametrize("bad", ["-1", str(2**31), "lots"])
def test_bad_trim_threshold_is_a_clear_error(bad):
    if not GLIBC:
        pytest.skip("the value is only read on glibc")
    with pytest.raises(ValueError):
        runtime.keep_freed_memory(bad)


@pytest.mark.skipif(not GLIBC, reason="the value is only read on glibc")
@given(st.one_of(st.integers(max_value=-1).map(str),
                 st.integers(min_value=2**31).map(str),
                 st.text().filter(lambda t: t != "default" and not _parses_as_int(t))))
def test_any_out_of_range_or_non_numeric_threshold_is_rejected(bad):
    # rejected before mallopt is called, so the allocator keeps its settings
    with pytest.raises(ValueError, match="TEFCORE_MALLOC_TRIM"):
        runtime.keep_freed_memory(bad)


@needs_threads
def test_both_settings_can_be_turned_off():
    got = run_python("""
    import json
    import numpy as np
    from tefcore.floquet import floquet_modes
    from tefcore.runtime import apply_defaults
    apply_defaults()
    seen = []
    def A(psi):
        seen.append(blas_threads())
        return np.broadcast_to(np.array([[0.0, 1.0], [-1.0, -0.1]]), (psi.size, 2, 2))
    floquet_modes(A)
    print(json.dumps({"inside": seen[0], "after": blas_threads()}))
    """, TEFCORE_BLAS_THREADS="default", TEFCORE_MALLOC_TRIM="default")
    assert got == {"inside": UNTOUCHED, "after": UNTOUCHED}


# --------------------------------------------------------------- the kernels

BLAS_KERNELS = """
from threadpoolctl import threadpool_info
def blas_kernels():
    return sorted({lib.get("architecture") or "" for lib in threadpool_info()
                   if lib["internal_api"] == "openblas"})
"""


def kernels_in(code: str, **env) -> dict:
    """``code`` in a fresh interpreter without an ``OPENBLAS_CORETYPE`` of its own
    (unless given): it prints one JSON line, returned parsed."""
    base = {k: v for k, v in os.environ.items() if k != "OPENBLAS_CORETYPE"}
    out = subprocess.run([sys.executable, "-c", BLAS_KERNELS + textwrap.dedent(code)],
                         env=dict(base, **env), capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_the_command_leaves_the_kernels_to_openblas_and_the_user():
    # what `tefcore ...` does first (apply_defaults before it imports numpy):
    # OpenBLAS loads the kernels it picks for this processor, the same as a
    # plain interpreter does, and a process it starts inherits no setting
    code = """
    import json, os, subprocess, sys
    from tefcore.runtime import apply_defaults
    apply_defaults()
    import numpy, scipy.linalg
    child = subprocess.run([sys.executable, "-c", "import os; print(os.environ.get("
                            "'OPENBLAS_CORETYPE'))"], capture_output=True, text=True).stdout
    print(json.dumps([blas_kernels(), child.strip()]))
    """
    plain = kernels_in("""
    import json
    import numpy, scipy.linalg
    print(json.dumps(blas_kernels()))
    """)
    assert kernels_in(code) == [plain, "None"]
    # a user's own choice is respected (Sandybridge runs on every x86-64 with AVX)
    if plain:
        chosen = kernels_in(code, OPENBLAS_CORETYPE="Sandybridge")
        assert chosen[1] == "Sandybridge"


def test_nothing_in_the_package_or_its_tools_sets_the_kernel():
    # the product never chooses a user's BLAS kernel: no assignment to the
    # variable anywhere in the package, the test set-up or the tools
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    files = [*root.joinpath("tefcore").rglob("*.py"), root / "conftest.py",
             *root.joinpath("tools").glob("*.py"), *root.joinpath("benchmarks").glob("*.py")]
    setting = [str(f.relative_to(root)) for f in files
               if "environ[\"OPENBLAS_CORETYPE\"] =" in f.read_text(encoding="utf-8")
               or "setdefault(\"OPENBLAS_CORETYPE\"" in f.read_text(encoding="utf-8")]
    assert not setting
