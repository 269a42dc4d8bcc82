"""Tests of tefcore.sweeps.maps: grid, boundary refinement, resume, dask, CLI.

A toy point function with a known flutter boundary: the flap mode's growth
is ``g = cg_offset + overhang^2 - 0.3`` (flutter where g >= 0), so along a
row (fixed overhang y) the boundary is at ``x = 0.3 - y^2`` exactly.
"""

import subprocess
import sys
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.sweeps.maps import stability_map

MDART = load_config("mdart")
XS = [0.0, 0.1, 0.2, 0.3, 0.4]
YS = [0.0, 0.2, 0.4]


class Toy:
    """Picklable point function: flap mode + a stable blade mode."""

    def __init__(self):
        self.calls = 0

    def __call__(self, cfg):
        self.calls += 1
        x, y = cfg.flap.cg_offset, cfg.flap.overhang
        g = x + y**2 - 0.3
        modes = pd.DataFrame({"mode_id": [0, 1], "label": ["blade flap 1", "TEF"],
                              "frequency_per_rev": [1.0, 6.0 - 2 * x],
                              "real_part": [-0.3, g], "damping_ratio": [0.3, -g / 6],
                              "share_TEF": [0.01, 0.8]})
        return SimpleNamespace(modes=modes, eigenvectors=np.eye(2, dtype=complex), trim={})


def test_grid_dataset_and_refined_boundary():
    m = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=Toy(),
                      progress=False)
    ds = m.dataset
    assert ds["flutter_growth"].shape == (3, 5)
    np.testing.assert_allclose(ds["x"], XS)
    np.testing.assert_allclose(ds["y"], YS)
    expected = np.add.outer(np.square(YS), XS) - 0.3
    np.testing.assert_allclose(ds["flutter_growth"], expected, atol=1e-12)
    # the flap mode is the flutter root (share >= 0.1), never the blade mode
    assert (m.table["flutter_label"] == "TEF").all()
    b = m.boundary
    assert len(b) == 3 and b["converged"].all()
    # refined beyond the grid: x = 0.3 - y^2 to brentq's tolerance (1e-4 of the range)
    np.testing.assert_allclose(b["x"], 0.3 - np.square(b["y"]), atol=1e-4 * 0.4)
    assert (b["direction"] == "destabilising").all()


def test_resume_reuses_every_point(tmp_path):
    out = tmp_path / "map"
    first = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=Toy(),
                          progress=False, out=out)
    toy = Toy()
    again = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=toy,
                          progress=False, out=out)
    assert toy.calls == 0                      # grid and boundary all from the files
    pd.testing.assert_frame_equal(first.table, again.table)
    pd.testing.assert_frame_equal(first.boundary, again.boundary)


def test_parallel_joblib_and_dask_local_cluster_agree():
    distributed = pytest.importorskip("distributed")
    serial = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=Toy(),
                           progress=False)
    par = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=Toy(),
                        progress=False, n_jobs=2)
    pd.testing.assert_frame_equal(serial.table, par.table)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = stability_map(MDART, "flap.cg_offset", XS, "flap.overhang", YS, point=Toy(),
                             progress=False, backend="dask", client=client)
    pd.testing.assert_frame_equal(serial.table, dask.table)
    pd.testing.assert_frame_equal(serial.boundary, dask.boundary)


def test_failed_points_are_nan_with_their_error():
    m = stability_map(MDART, "flap.cg_offset", [0.0, 1.5], "flap.overhang", [0.1],
                      point=Toy(), progress=False)
    bad = m.table[m.table["status"] != "ok"]
    assert len(bad) == 1 and "outside the allowed range" in bad["error"].iloc[0]
    assert np.isnan(bad["flutter_growth"].iloc[0])


def test_bad_arguments():
    with pytest.raises(ValueError, match="same"):
        stability_map(MDART, "flap.cg_offset", XS, "flap.cg_offset", YS, point=Toy())
    with pytest.raises(ValueError, match="at least one"):
        stability_map(MDART, "flap.cg_offset", [], "flap.overhang", YS, point=Toy())


def test_real_hover_map_has_a_physical_flutter_root():
    # a tiny hover map of the real model: every point has a flutter root (the
    # least stable flap-induced root, named after where it comes from): the
    # balanced flap's is stable, the imbalanced flap's flutters
    cfg = MDART.with_overrides({"flight.advance_ratio": 0.0})
    m = stability_map(cfg, "flap.cg_offset", [0.0, 0.3], "flap.overhang", [0.29],
                      progress=False)
    ok = m.table[m.table["status"] == "ok"]
    assert len(ok) == 2
    assert (ok["flutter_label"] != "").all()
    assert ok["flutter_growth"].iloc[0] < 0 < ok["flutter_growth"].iloc[1]
    # the mass-imbalanced flap is less stable than the balanced one (paper, Fig. 9)
    assert ok["flutter_growth"].iloc[1] > ok["flutter_growth"].iloc[0]


def test_cli_map(tmp_path):
    csv, png = tmp_path / "m.csv", tmp_path / "m.png"
    run = subprocess.run(
        [sys.executable, "-m", "tefcore", "map", "flap.cg_offset", "0", "0.3", "2",
         "flap.overhang", "0.29", "0.29", "1", "-s", "flight.advance_ratio=0",
         "--csv", str(csv), "--png", str(png), "--quiet"],
        capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    t = pd.read_csv(csv)
    assert len(t) == 2 and {"flutter_growth", "tef_growth", "x", "y"} <= set(t.columns)
    assert png.stat().st_size > 1000


def test_real_map_is_the_same_serial_parallel_and_on_dask():
    # the real point function takes warm starts: each row is cut into the same
    # fixed chains (tefcore.sweeps.evaluate.WARM_CHAIN) whichever backend runs it -- rows
    # side by side in joblib workers, chains as dask tasks, or row by row here --
    # so the tables (and refined boundaries) are identical, not merely close.
    # mu = 0.1, a collective sweep in x: the warm start must not carry the
    # previous point's prescribed collective over
    distributed = pytest.importorskip("distributed")
    cfg = MDART.with_overrides({"flight.advance_ratio": 0.1})
    args = (cfg, "flight.collective", [0.08, 0.1, 0.12], "flap.cg_offset", [0.0, 0.33])
    serial = stability_map(*args, progress=False, refine_boundary=False)
    par = stability_map(*args, progress=False, refine_boundary=False, n_jobs=2)
    pd.testing.assert_frame_equal(serial.table, par.table)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = stability_map(*args, progress=False, refine_boundary=False, backend="dask",
                             client=client)
    pd.testing.assert_frame_equal(serial.table, dask.table)
    # and each point is its own: equal to the same point computed cold, to the
    # trim's tolerance (4e-9 /rev measured); with the collective carried over,
    # points of one chain came out equal to its first (off by 1e-4 to 1e-3 /rev)
    from tefcore.linear.stability import stability

    ok = serial.table[serial.table["status"] == "ok"]
    assert len(ok) == 6
    for row in ok.itertuples():
        modes = stability(cfg.with_overrides({"flight.collective": row.x,
                                              "flap.cg_offset": row.y})).modes
        cold = modes[modes["flutter_root"]].iloc[0]
        assert abs(row.flutter_growth - cold["real_part"]) < 1e-7, (row.x, row.y)
        assert row.flutter_label == cold["label"]
