"""The explorer web page (``tefcore explore``): built and driven without a browser.

The page-building code runs with ipywidgets alone (the ``notebooks`` extra);
serving it needs voila (the ``app`` extra) and is tested only where voila is
installed; a headless browser drives it only with ``TEFCORE_BROWSER=1`` and
Playwright with a Chromium (``tools/check_explorer.py``, which those tests run).
"""

import importlib.util
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import nbformat
import pytest

from tefcore.cli import main
from tefcore.paper import explorer_app as app
from tefcore.paper.explorer import SLIDERS

REPO = Path(__file__).resolve().parents[2]
HAS_VOILA = importlib.util.find_spec("voila") is not None


def test_mechanism_bars_rank_by_magnitude():
    names, values = app.mechanism_bars({"a": 0.1, "b": -2.0, "c": 0.5, "d": 0.0}, top=3)
    assert names == ["b", "c", "a"] and values == [-2.0, 0.5, 0.1]


def test_mechanism_figure_without_a_root_says_why():
    fig = app.mechanism_figure({}, None, "no flap-induced root")
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert texts == ["no flap-induced root"]
    png = app.figure_png(app.mechanism_figure({"flap lift": 1.0, "airloads": -0.5}, 0.5, "x"))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_notebook_is_one_cell_calling_the_page():
    nb = nbformat.reads(app.notebook_json("rotor.toml", ["flap.cg_offset=0.2"]), as_version=4)
    nbformat.validate(nb)
    (cell,) = nb.cells
    assert "page(config='rotor.toml', overrides=['flap.cg_offset=0.2'])" in cell.source
    # the page is assigned, not the cell's value: displayed once, not twice
    assert cell.source.splitlines()[-1].startswith("_page = ")


@pytest.fixture(scope="module")
def built_page():
    pytest.importorskip("ipywidgets")
    return app.page(display=False)


def test_page_has_the_sliders_figures_and_button(built_page):
    w = built_page.tefcore
    assert list(w["sliders"]) == list(SLIDERS)
    for key, (_, lo, hi, step, default) in SLIDERS.items():
        s = w["sliders"][key]
        assert (s.min, s.max, s.step, s.value) == (lo, hi, step, default)
        assert s.continuous_update is False        # a point costs seconds: on release
    assert w["roots"].value[:4] == b"\x89PNG" and w["mechanism"].value[:4] == b"\x89PNG"
    assert w["animate"].disabled is False           # the paper's flap has a flutter root
    assert w["animation"].layout.display == "none"  # no broken image before an animation


def test_moving_a_slider_redraws(built_page):
    w = built_page.tefcore
    before = (w["roots"].value, w["mechanism"].value)
    w["sliders"]["cg_offset"].value = 0.0           # mass-balanced: the flutter root decays
    assert w["roots"].value != before[0] and w["mechanism"].value != before[1]
    assert w["status"].value == ""
    w["sliders"]["cg_offset"].value = SLIDERS["cg_offset"][4]


def test_animation_on_request(built_page):
    w = built_page.tefcore
    w["run_animation"]()
    assert w["animation"].value[:6] == b"GIF89a" and w["animation"].layout.display == "block"
    assert "marched" in w["status"].value and "Floquet" in w["status"].value


def test_page_state_of_a_refused_point_says_why():
    state = app.page_state(cg_offset=0.33, overhang=0.95, actuator_scale=1.0,
                           advance_ratio=0.3)
    assert state.roots.modes.empty and state.roots.error and state.contributions == {}


def test_explore_without_voila_is_one_line(monkeypatch, capsys):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "voila" else real(name, *a))
    code = main(["explore", "--port", "0"])
    err = capsys.readouterr().err
    assert code == 2 and "pip install 'tefcore[app]'" in err and len(err.splitlines()) == 1


@pytest.mark.skipif(not HAS_VOILA, reason="voila not installed (pip install 'tefcore[app]')")
def test_explore_serves_the_page():
    port = app.free_port()
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(REPO), *filter(None, [os.environ.get("PYTHONPATH")])])}
    proc = subprocess.Popen([sys.executable, "-m", "tefcore", "explore", "--port", str(port)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        for _ in range(120):
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=120) as r:
                    page = r.read().decode(errors="replace")
                    break
            except OSError:
                if proc.poll() is not None:
                    pytest.fail(proc.stdout.read().decode(errors="replace"))
                time.sleep(1)
        else:
            pytest.fail("the server did not answer")
        assert "voila" in page.lower()
        assert "jupyterlab-jupytext" not in page      # the editors' extension is not loaded
    finally:
        proc.terminate()
        proc.wait(timeout=30)


@pytest.mark.skipif(os.environ.get("TEFCORE_BROWSER") != "1" or not HAS_VOILA
                    or importlib.util.find_spec("playwright") is None
                    or not any(shutil.which(n) for n in ("chromium", "chromium-browser")),
                    reason="a browser test: set TEFCORE_BROWSER=1, with voila, playwright "
                           "and chromium installed")
def test_headless_browser_drives_the_page(tmp_path):
    proc = subprocess.run([sys.executable, str(REPO / "tools" / "check_explorer.py"), "--out",
                           str(tmp_path), "--widths", "800", "--no-animation", "--brief"],
                          capture_output=True, text=True, timeout=900)
    report = json.loads(proc.stdout)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert report[0]["overflow_px"] <= 0 and not report[0]["errors"]
