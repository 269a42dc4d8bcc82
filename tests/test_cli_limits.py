"""Nothing typed on the command line can take the machine: worker processes capped by the
cores and the work, long runs estimated and refused past a stated bound without ``--yes``,
the marched and animated revolutions bounded.

Every test here stops before any large amount of work could start: the pools
are replaced by recorders that refuse more than a few workers, and the
computations by stand-ins that record how they were called.
"""

from __future__ import annotations

import math

import pytest

import tefcore.linear.stability
import tefcore.sweeps.evaluate
import tefcore.sweeps.maps
import tefcore.sweeps.sweep
import tefcore.timedomain.simulate
from tefcore import runtime
from tefcore.cli import estimate, main
from tefcore.sweeps import evaluate
from tefcore.timedomain.limits import MAX_ANIMATED_REVS, MAX_REVS
from tefcore.timedomain.simulate import simulate
from tests.sweeps.test_map_cli import SlowToy
from tests.sweeps.test_stability_map import MDART, Toy
from tests.sweeps.test_sweep import ToyPoint

#: The cores the tests pretend the process may use.
CORES = 2


class Started(Exception):
    """Raised by a stand-in: the work would have started here."""


@pytest.fixture
def two_cores(monkeypatch):
    monkeypatch.setattr(runtime, "usable_cores", lambda: CORES)


@pytest.fixture
def pools(monkeypatch):
    """The worker counts asked of the command's pool; more than the cores is refused
    (never started) so that a missing cap fails here instead of forking thousands."""
    asked = []
    real = evaluate.worker_pool

    def recorder(n_workers):
        asked.append(n_workers)
        if n_workers > CORES:
            raise Started(f"{n_workers} worker processes asked for")
        return real(n_workers)

    monkeypatch.setattr(evaluate, "worker_pool", recorder)
    monkeypatch.setattr(tefcore.sweeps.maps, "worker_pool", recorder)
    yield asked
    evaluate.close_pool()


@pytest.fixture
def toy_points(monkeypatch, tmp_path):
    """The commands' default point is a toy (no solver time); files go to tmp_path."""
    point = Toy()
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps, tefcore.sweeps.evaluate):
        monkeypatch.setattr(module, "default_point", lambda: point)
    monkeypatch.chdir(tmp_path)
    return point


# ------------------------------------------------------------------ worker processes


def test_process_count_is_capped_by_the_cores_and_the_work(two_cores):
    assert runtime.process_count(100000, 10**6) == CORES
    assert runtime.process_count(64, 1) == 1              # one chain: one process
    assert runtime.process_count(-1, 10**6) == CORES      # negative: all the cores
    assert runtime.process_count(1, 10**6) == 1
    assert runtime.process_count(2) == 2
    n, line = runtime.process_cap(100000, 40, "chain of points")
    assert n == CORES and line == "--jobs 100000: 2 processes, the 2 cores this process may use"
    assert runtime.process_cap(-1, 40) == (CORES, None)   # all the cores were asked for
    assert runtime.process_cap(2, 40) == (2, None)


def test_usable_cores_follow_the_affinity_mask(monkeypatch):
    import os

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0}, raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 64)
    assert runtime.usable_cores() == 1


def test_sweep_jobs_100000_starts_no_more_workers_than_cores(two_cores, pools, tmp_path,
                                                           monkeypatch, capsys):
    # the command once asked the pool for 99999 forked workers: ~5200 started
    # before the machine ran out of memory
    point = ToyPoint()
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    code = main(["sweep", "flap.cg_offset", "--range", "-1", "1", "40", "--quiet",
                 "--csv", str(tmp_path / "s.csv"), "--jobs", "100000"])
    err = capsys.readouterr().err
    assert code == 0, err
    assert pools and max(pools) <= CORES - 1              # the caller computes too
    assert "tefcore sweep: --jobs 100000: 2 processes, the 2 cores this process may use" in err


def test_sweep_jobs_64_for_a_few_points_says_so(two_cores, pools, tmp_path, monkeypatch,
                                                capsys):
    # 64 processes for 5 points (one warm-start chain; the refinement's midpoints
    # may use a second process later, never more than the cores)
    point = ToyPoint()
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    assert main(["sweep", "flap.cg_offset", "--values", "0", "0.1", "0.2", "0.3", "0.4",
                 "--quiet", "--csv", str(tmp_path / "s.csv"), "--jobs", "64"]) == 0
    assert max(pools, default=0) <= CORES - 1
    assert "--jobs 64: 1 process, one per chain of points (there is 1)" \
        in capsys.readouterr().err


def test_map_jobs_64_for_five_rows_starts_no_more_workers_than_cores(two_cores, pools,
                                                                     toy_points, capsys):
    # 64 forked workers for the 5 rows of a map (63 were idle)
    code = main(["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.4", "5",
                 "--quiet", "--jobs", "64"])
    err = capsys.readouterr().err
    assert code == 0, err
    assert pools and max(pools) <= CORES
    assert "tefcore map: --jobs 64: 2 processes, the 2 cores this process may use" in err


def test_map_rows_in_joblib_processes_are_capped_too(two_cores, monkeypatch):
    # a script's map (spawned loky workers, not the command's forked pool)
    asked = []

    class Parallel:
        def __init__(self, n_jobs, **kw):
            asked.append(n_jobs)
            if n_jobs > CORES:
                raise Started(f"{n_jobs} loky workers asked for")

        def __call__(self, tasks):
            return [f(*a, **kw) for f, a, kw in tasks]

    import joblib

    monkeypatch.setattr(joblib, "Parallel", Parallel)
    m = tefcore.sweeps.maps.stability_map(MDART, "flap.cg_offset", [0.0, 0.2, 0.4],
                                          "flap.overhang", [0.0, 0.2, 0.4], point=Toy(),
                                          n_jobs=64, progress=False)
    assert len(m.table) == 9 and asked and max(asked) <= CORES


def test_a_local_dask_cluster_is_capped(two_cores, monkeypatch):
    distributed = pytest.importorskip("distributed")
    asked = []

    def cluster(n_workers, **kw):
        asked.append(n_workers)
        raise Started(f"{n_workers} dask workers")

    monkeypatch.setattr(distributed, "LocalCluster", cluster)
    with pytest.raises(Started):
        evaluate.dask_client(100000, None, n_tasks=40)
    with pytest.raises(Started):
        evaluate.dask_client(64, None, n_tasks=1)
    assert asked == [CORES, 1]


# ------------------------------------------------------------------ estimates


def _stop_before(monkeypatch, module, name, calls):
    def stand_in(*args, **kw):
        calls.append((args, kw))
        raise Started(name)

    monkeypatch.setattr(module, name, stand_in)


def test_a_huge_map_is_refused_without_yes(monkeypatch, tmp_path, capsys):
    # a map estimated at about 300686 h printed its estimate and started
    point = SlowToy(0.05)
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps, tefcore.sweeps.evaluate):
        monkeypatch.setattr(module, "default_point", lambda: point)
    monkeypatch.chdir(tmp_path)
    calls = []
    _stop_before(monkeypatch, tefcore.sweeps.maps, "stability_map", calls)
    argv = ["map", "flap.cg_offset", "0", "0.4", "1000", "flap.overhang", "0", "0.4", "1000"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert calls == [] and point.calls == 1               # one point timed, nothing started
    assert err.startswith("tefcore: error: map: ") and err.count("\n") == 1, err
    assert "1000 x 1000 = 1000000 points" in err and " h" in err
    assert f"more than {estimate.LIMIT_TEXT}" in err and "--yes" in err
    assert not list(tmp_path.iterdir())                   # no file written
    with pytest.raises(Started):                          # --yes: it starts
        main([*argv, "--yes"])
    assert len(calls) == 1


def test_a_huge_sweep_states_its_estimate_and_is_refused_without_yes(monkeypatch, tmp_path,
                                                                     capsys):
    # a 100000-point sweep started without a word
    point = SlowToy(0.05)
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    monkeypatch.setattr(tefcore.sweeps.evaluate, "default_point", lambda: point)
    calls = []
    _stop_before(monkeypatch, tefcore.sweeps.sweep, "sweep", calls)
    argv = ["sweep", "flap.cg_offset", "--range", "0", "0.4", "100000", "--quiet",
            "--csv", str(tmp_path / "s.csv")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert calls == [] and err.startswith("tefcore: error: sweep: 100000 points at about")
    assert "--yes" in err and not (tmp_path / "s.csv").exists()
    with pytest.raises(Started):
        main([*argv, "--yes"])
    err = capsys.readouterr().err
    assert "tefcore sweep: 100000 points at about" in err      # the estimate, stated
    assert len(calls) == 1


def test_a_sweep_under_the_bound_states_its_estimate_and_starts(monkeypatch, tmp_path,
                                                                capsys):
    point = SlowToy(0.05)
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    monkeypatch.setattr(tefcore.sweeps.evaluate, "default_point", lambda: point)
    calls = []
    _stop_before(monkeypatch, tefcore.sweeps.sweep, "sweep", calls)
    # 0.05 s x 5000 points = 250 s: over ESTIMATE_ABOVE_S, under the bound
    with pytest.raises(Started):
        main(["sweep", "flap.cg_offset", "--range", "0", "0.4", "5000", "--quiet",
              "--csv", str(tmp_path / "s.csv")])
    assert "tefcore sweep: 5000 points at about" in capsys.readouterr().err
    assert len(calls) == 1


def test_the_bound_is_stated_in_the_help():
    import io
    from contextlib import redirect_stdout

    for command in ("sweep", "map"):
        out = io.StringIO()
        with redirect_stdout(out), pytest.raises(SystemExit):
            main([command, "--help"])
        assert f"more than {estimate.LIMIT_TEXT}" in " ".join(out.getvalue().split())


# ------------------------------------------------------------------ revolutions


@pytest.mark.parametrize("revs", ["inf", "1e9", "nan", str(MAX_REVS + 1), "-1", "0"])
def test_simulate_revs_are_bounded_before_anything_is_computed(revs, monkeypatch, capsys):
    # --revs inf or 1e9 marched on, the memory growing without bound
    calls = []
    _stop_before(monkeypatch, tefcore.timedomain.simulate, "simulate", calls)
    assert main(["simulate", "--revs", revs]) == 2
    err = capsys.readouterr().err
    assert calls == [] and err.count("\n") == 1
    assert f"argument --revs: must be a number in (0, {MAX_REVS}] revolutions, got '{revs}'" \
        in err


@pytest.mark.parametrize("revs", ["inf", "1e9", str(MAX_ANIMATED_REVS + 1)])
def test_animated_revs_are_bounded_before_anything_is_computed(revs, monkeypatch, capsys):
    # --anim-revs inf was accepted (about 0.35 GB a revolution animated)
    calls = []
    _stop_before(monkeypatch, tefcore.timedomain.simulate, "simulate", calls)
    assert main(["simulate", "--anim-revs", revs, "--gif", "never.gif"]) == 2
    err = capsys.readouterr().err
    assert calls == []
    assert f"argument --anim-revs: must be a number in (0, {MAX_ANIMATED_REVS}] revolutions, " \
           f"got '{revs}'" in err


@pytest.mark.parametrize("kw", [{"revs": math.inf}, {"revs": 1e9}, {"revs": math.nan},
                                {"amplitude": math.nan}, {"amplitude": math.inf}])
def test_the_library_refuses_unbounded_revolutions_before_computing(kw, monkeypatch):
    calls = []
    _stop_before(monkeypatch, tefcore.linear.stability, "stability", calls)
    name = next(iter(kw))
    with pytest.raises(ValueError, match=f"^{name} = "):
        simulate(MDART, **kw)
    assert calls == []


def test_the_animation_refuses_unbounded_revolutions():
    from tefcore.timedomain.animation import render_frames

    with pytest.raises(ValueError, match=rf"revs = inf.*\(0, {MAX_ANIMATED_REVS}\]"):
        render_frames(object(), revs=math.inf)
