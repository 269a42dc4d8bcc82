"""The sweep's worker pool: set up once, chains shared with the caller, small jobs serial."""

from __future__ import annotations

import os
import time
from types import SimpleNamespace

import pandas as pd
import pytest

from tefcore.runtime import defaults_applied
from tefcore.sweeps import evaluate
from tefcore.sweeps.sweep import sweep
from tests.sweeps.test_sweep import MDART, PARAM, XS, ToyPoint, toy_result


class PidPoint(ToyPoint):
    """ToyPoint that records the process it ran in (trim column ``pid``) after a pause,
    so that a ready worker takes chains while the caller works."""

    def __call__(self, cfg):
        time.sleep(0.02)
        res = toy_result(cfg.flap.cg_offset)
        return SimpleNamespace(modes=res.modes, eigenvectors=res.eigenvectors,
                               trim={**res.trim, "pid": float(os.getpid())})


@pytest.fixture
def ready_pool():
    pool = evaluate.worker_pool(1)
    deadline = time.monotonic() + 120
    while not evaluate.pool_ready():          # a worker started and imported the solver
        assert time.monotonic() < deadline, "the pool's worker did not start"
        time.sleep(0.05)
    yield pool
    evaluate.close_pool()


def test_a_worker_applies_the_settings_and_imports_once(ready_pool):
    assert ready_pool.submit(defaults_applied).result() is True
    modules = ready_pool.submit(_loaded, "tefcore.linear.stability").result()
    assert modules is True


def _loaded(name):
    import sys

    return name in sys.modules


def test_chains_shared_between_caller_and_worker_give_the_serial_table(ready_pool):
    serial = sweep(MDART, PARAM, XS, point=PidPoint(), progress=False)
    par = sweep(MDART, PARAM, XS, point=PidPoint(), progress=False, n_jobs=2)
    pids = set(par.table["trim_pid"])
    assert float(os.getpid()) in pids and len(pids) == 2       # both did some of the work
    cols = [c for c in serial.table.columns if c != "trim_pid"]
    pd.testing.assert_frame_equal(par.table[cols], serial.table[cols])
    assert par.timing["processes"] == 2 and par.timing["point_s"] > 0


def test_small_jobs_stay_serial_without_starting_a_pool():
    evaluate.close_pool()
    res = sweep(MDART, PARAM, XS[:evaluate.MIN_COLD_CHAINS - 1], point=ToyPoint(),
                progress=False, n_jobs=2)
    assert not evaluate.pool_started()
    assert res.timing["processes"] == 1


def test_forked_workers_take_chains_at_once_and_give_the_serial_table():
    # the command line's pool: workers forked from the caller, ready at once,
    # so that two chains are worth them (a spawned pool needs MIN_COLD_CHAINS)
    evaluate.close_pool()
    if not evaluate.fork_workers():
        pytest.skip("no fork start method on this platform")
    try:
        assert evaluate.min_chains() == 2 < evaluate.MIN_COLD_CHAINS
        xs = XS[:2 * evaluate.WARM_CHAIN]                  # two chains
        serial = sweep(MDART, PARAM, xs, point=PidPoint(), progress=False)
        par = sweep(MDART, PARAM, xs, point=PidPoint(), progress=False, n_jobs=2)
        assert evaluate.pool_started()
        pids = set(par.table["trim_pid"])
        assert float(os.getpid()) in pids and len(pids) == 2   # the fork did a chain
        cols = [c for c in serial.table.columns if c != "trim_pid"]
        pd.testing.assert_frame_equal(par.table[cols], serial.table[cols])
    finally:
        evaluate.close_pool()
        evaluate.fork_workers(False)
    assert not evaluate.pool_started() and evaluate.min_chains() == evaluate.MIN_COLD_CHAINS


def test_the_command_with_two_jobs_writes_the_serial_table(tmp_path):
    # tefcore sweep --jobs 2 (forked workers) against --jobs 1: the same bytes
    import subprocess
    import sys

    out = {}
    for jobs in ("1", "2"):
        path = tmp_path / f"s{jobs}.csv"
        run = subprocess.run([sys.executable, "-m", "tefcore", "sweep", "actuator.stiffness",
                              "--range", "70 ft-lb/rad", "100 ft-lb/rad", "16", "--quiet",
                              "-s", "flight.advance_ratio=0", "--csv", str(path), "--jobs", jobs],
                             check=True, capture_output=True, text=True)
        assert f"on {jobs} process(es)" in run.stdout            # the pool did take chains
        out[jobs] = path.read_bytes()
    assert out["1"] == out["2"]


@pytest.mark.parametrize("n", [0, 1, 7, 8, 9, 16, 17, 24, 40, 41, 100])
def test_chains_are_an_even_number_of_runs_of_near_equal_length(n):
    # two processes share an even number of chains evenly; five chains of 8
    # (the cut before) left one process three and the other two.  Each run is
    # at most WARM_CHAIN long, the runs are consecutive and cover every value
    # once, and their lengths differ by one at most.
    order = list(range(n))
    runs = evaluate._even_chains(order, evaluate.WARM_CHAIN)
    assert [i for r in runs for i in r] == order
    assert all(0 < len(r) <= evaluate.WARM_CHAIN for r in runs)
    if n > evaluate.WARM_CHAIN:
        assert len(runs) % 2 == 0
        assert max(map(len, runs)) - min(map(len, runs)) <= 1
        # no more chains than needed, rounded up to even: each extra chain is a cold start
        assert len(runs) <= -(-n // evaluate.WARM_CHAIN) + 1
    else:
        assert len(runs) == (1 if n else 0)
    # a point function without warm starts: every value a chain of its own
    assert evaluate._even_chains(order, 1) == [[i] for i in order]


def test_a_sweeps_chains_are_the_even_cut_of_its_values_fresh_or_resumed():
    # chains() itself: 40 values (given in reverse) are six chains of 6-7 in SI
    # order, whatever order they came in; with records present (a resumed
    # sweep) each chain is a prefix of the same cut, its recorded points
    # recomputed only as warm starts (keep False), and a chain with nothing
    # missing is no job.  With five chains of 8 (the cut before) or a cut that
    # followed the given order, this fails.
    xs = [0.01 * k for k in range(40)][::-1]
    keys = [f"k{i}" for i in range(len(xs))]
    jobs = evaluate.chains(MDART, PARAM, xs, keys, {}, lambda i: ("args", i))
    assert [len(j) for j in jobs] == [6, 7, 7, 6, 7, 7]
    by_value = [[xs[i] for i, _, _ in j] for j in jobs]
    assert [x for j in by_value for x in j] == sorted(xs)
    assert all(keep for j in jobs for _, _, keep in j)
    # resumed: the first chain done, the second done up to its 4th point
    done = {keys[i]: {} for i, _, _ in jobs[0]} | {keys[i]: {} for i, _, _ in jobs[1][:4]}
    again = evaluate.chains(MDART, PARAM, xs, keys, done, lambda i: ("args", i))
    assert [[i for i, _, _ in j] for j in again] == [[i for i, _, _ in j] for j in jobs[1:]]
    assert [keep for _, _, keep in again[0]] == [False] * 4 + [True] * 3
