"""``tefcore map``: what it writes, how it labels the plot, its estimate.

The default point function is replaced by a toy (the flap mode's growth is
``x + y^2 - 0.3``), so these tests take no solver time.
"""

import time

import pytest

import tefcore.sweeps.evaluate
import tefcore.sweeps.maps
import tefcore.sweeps.sweep
from tefcore.cli import main
from tests.sweeps.test_stability_map import Toy

MAP = ["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.2", "2", "--quiet"]


class SlowToy(Toy):
    """The toy map's point, taking `seconds` (a point function worth estimating)."""

    def __init__(self, seconds):
        super().__init__()
        self.seconds = seconds

    def __call__(self, cfg, **kw):
        time.sleep(self.seconds)
        return super().__call__(cfg)


@pytest.fixture
def toy(monkeypatch, tmp_path):
    point = Toy()
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps, tefcore.sweeps.evaluate):
        monkeypatch.setattr(module, "default_point", lambda: point)
    monkeypatch.chdir(tmp_path)
    return point


def test_png_alone_writes_no_csv(toy, tmp_path, capsys):
    """``--png`` also wrote map.csv."""
    assert main([*MAP, "--png", "m.png"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.png"]
    assert "wrote m.png:" in capsys.readouterr().out
    assert main([*MAP, "--netcdf", "m.nc"]) == 0
    assert not (tmp_path / "map.csv").exists()


def test_the_table_is_written_when_asked_or_when_nothing_else_is(toy, tmp_path):
    assert main(MAP) == 0
    assert (tmp_path / "map.csv").exists()
    assert main([*MAP, "--png", "m.png", "--csv", "t.csv"]) == 0
    assert (tmp_path / "t.csv").exists()


def _plotted(monkeypatch):
    axes = []
    plot = tefcore.sweeps.maps.MapResult.plot

    def keep(self, *a, **kw):
        ax = plot(self, *a, **kw)
        axes.append(ax)
        return ax

    monkeypatch.setattr(tefcore.sweeps.maps.MapResult, "plot", keep)
    return axes


def test_map_plot_uses_the_notebooks_axis_labels(toy, monkeypatch):
    """The PNG's axes were the raw field names (``flap.cg_offset``)."""
    from tefcore.paper.figures.plotting import FIELD_AXES

    axes = _plotted(monkeypatch)
    assert main([*MAP, "--png", "m.png"]) == 0
    assert axes[0].get_xlabel() == FIELD_AXES["flap.cg_offset"][0] \
        == "flap CG offset c_cg/c_f (positive aft)"
    assert axes[0].get_ylabel() == "flap overhang c_b/c_f"


def test_a_dimensional_axis_is_shown_in_the_notebooks_unit(toy, monkeypatch):
    axes = _plotted(monkeypatch)
    assert main(["map", "actuator.stiffness", "50 ft*lbf/rad", "100 ft*lbf/rad", "3",
                 "flap.overhang", "0", "0.2", "2", "--quiet", "--png", "m.png"]) == 0
    ax = axes[0]
    assert ax.get_xlabel() == "actuator stiffness k_a [ft-lb/rad]"
    # cells centred on 50, 75, 100 ft-lb/rad (not 67.8 ... 135.6 N m/rad): the
    # limits are the outer cell edges, 37.5 and 112.5, to round-off
    assert ax.get_xlim() == pytest.approx((37.5, 112.5), rel=1e-9)


def test_a_large_map_prints_its_estimate_before_it_starts(monkeypatch, tmp_path, capsys):
    """A 1000 x 1000 map started a day of work without a word."""
    point = SlowToy(0.05)
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps, tefcore.sweeps.evaluate):
        monkeypatch.setattr(module, "default_point", lambda: point)
    monkeypatch.chdir(tmp_path)
    started = []

    def no_map(*args, **kw):          # the estimate must come first: stop there
        started.append(capsys.readouterr().err)
        raise KeyboardInterrupt

    monkeypatch.setattr(tefcore.sweeps.maps, "stability_map", no_map)
    assert main(["map", "flap.cg_offset", "0", "0.4", "1000", "flap.overhang", "0", "0.4",
                 "1000", "--jobs", "2", "--yes"]) == 130          # --yes: past the bound
    estimate = started[0]
    assert "1000 x 1000 = 1000000 points" in estimate and "2 processes" in estimate
    # one point timed (0.05 s, more on a loaded machine) x 1e6 points / 2 processes:
    # about 7 h, printed in hours
    assert " h " in estimate and point.calls == 1


def test_a_small_map_is_not_timed(toy, capsys):
    assert main([*MAP, "--no-refine"]) == 0
    assert "points at about" not in capsys.readouterr().err
    assert toy.calls == 6            # the grid's points only: no extra timing point
