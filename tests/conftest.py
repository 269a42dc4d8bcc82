"""Fixtures of every test: each test leaves the process environment as it found it."""

import os

import pytest


@pytest.fixture(autouse=True)
def _restore_environment():
    # a dask LocalCluster started by a test writes its workers' settings
    # (OMP_NUM_THREADS=1, ...) into os.environ and leaves them: a later test that
    # starts a subprocess would inherit them (seen: tests/test_runtime.py failing
    # after tests/sweeps/test_stability_map.py)
    saved = dict(os.environ)
    yield
    if os.environ != saved:
        os.environ.clear()
        os.environ.update(saved)
