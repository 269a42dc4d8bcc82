"""Process settings applied by ``import tefcore`` (tefcore.runtime)."""

import os
import platform
import subprocess
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st
from threadpoolctl import threadpool_info

from tefcore import runtime


def _parses_as_int(text):
    try:
        int(text)
    except ValueError:
        return False
    return True


GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


def test_import_limits_blas_to_one_thread():
    blas = [lib for lib in threadpool_info() if lib["user_api"] == "blas"]
    assert blas, "numpy/scipy BLAS not found by threadpoolctl"
    assert all(lib["num_threads"] == 1 for lib in blas)


@pytest.mark.skipif(not GLIBC, reason="mallopt is glibc's")
def test_trim_threshold_applied_on_glibc():
    assert runtime.keep_freed_memory(str(64 * 2**20)) is True
    runtime.keep_freed_memory(str(128 * 2**20))        # restore the import's value


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


def test_both_settings_can_be_turned_off_before_import():
    env = dict(os.environ, TEFCORE_BLAS_THREADS="default", TEFCORE_MALLOC_TRIM="default")
    out = subprocess.run([sys.executable, "-c", "import tefcore; print(tefcore.__version__)"],
                         env=env, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == __import__("tefcore").__version__
