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


# ------------------------------------------------------------------ serving safely


class _Started(Exception):
    """A stand-in for starting voila: what it was started with."""


@pytest.fixture
def voila_command(monkeypatch):
    """Serving stops where voila would start; the command line and notebook are kept."""
    seen = {}

    def popen(cmd, **kw):
        seen["cmd"], seen["kw"] = cmd, kw
        seen["notebook"] = Path(cmd[3]).read_text(encoding="utf-8")
        raise _Started

    monkeypatch.setattr(app, "check_voila", lambda: None)
    monkeypatch.setattr(subprocess, "Popen", popen)
    return seen


@pytest.mark.parametrize("port", ["99999", "-1", "http"])
def test_a_port_out_of_range_is_one_line(port, voila_command, capsys):
    # --port 99999 was accepted and --port -1 ended in a traceback
    assert main(["explore", "--port", port]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert f"argument --port: must be a whole number in [0, 65535], got '{port}'" in err
    assert voila_command == {}                              # voila never started


def test_a_port_in_use_is_refused_naming_it(voila_command, capsys):
    # a busy port made voila serve on the next one, while the command printed the busy one
    import socket

    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        assert main(["explore", "--port", str(port)]) == 2
    err = capsys.readouterr().err
    assert f"--port {port}: cannot serve on it" in err and "--port 0" in err
    assert voila_command == {}                              # voila never started


def test_voila_serves_the_port_it_is_given_or_fails(voila_command):
    with pytest.raises(_Started):
        app.serve(port=0)
    cmd = voila_command["cmd"]
    assert "--Voila.port_retries=0" in cmd                  # no other port behind our back
    # traitlets' list syntax is deprecated (a DeprecationWarning reached the user)
    assert "--VoilaConfiguration.extension_denylist=jupyterlab-jupytext" in cmd
    assert not any("=[" in c for c in cmd)
    assert voila_command["kw"]["env"]["PYTHONWARNINGS"] == "ignore"


def test_a_relative_config_is_read_from_the_callers_folder(voila_command, tmp_path,
                                                           monkeypatch):
    # a relative --config was looked for in the kernel's temporary folder
    from tefcore.config.io import load_config, save_config

    monkeypatch.chdir(tmp_path)
    save_config(load_config("mdart"), tmp_path / "rotor.toml")
    with pytest.raises(_Started):
        main(["explore", "--config", "rotor.toml", "--port", "0"])
    (cell,) = nbformat.reads(voila_command["notebook"], as_version=4).cells
    assert f"config={str(tmp_path / 'rotor.toml')!r}" in cell.source
    assert f"os.chdir({str(tmp_path)!r})" in cell.source   # and the --set files with it


def test_the_temporary_folder_goes_when_voila_cannot_start(voila_command, tmp_path,
                                                           monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", None)         # TMPDIR read again
    with pytest.raises(_Started):
        app.serve(port=0)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not HAS_VOILA, reason="voila not installed (pip install 'tefcore[app]')")
@pytest.mark.parametrize("signame", ["SIGTERM", "SIGINT"])
def test_a_signal_stops_the_server_its_kernel_and_removes_its_folder(signame, tmp_path):
    # SIGTERM left voila serving (and its temporary folder) after the command had gone
    import re
    import signal

    psutil = pytest.importorskip("psutil")
    env = {**os.environ, "TMPDIR": str(tmp_path), "PYTHONPATH": os.pathsep.join(
        [str(REPO), *filter(None, [os.environ.get("PYTHONPATH")])])}
    env.pop("PYTHONWARNINGS", None)
    log = tmp_path / "log.txt"
    with open(log, "w") as out:
        proc = subprocess.Popen([sys.executable, "-m", "tefcore", "explore", "--port", "0"],
                                env=env, stdout=out, stderr=subprocess.STDOUT)
    started = []
    try:
        deadline = time.monotonic() + 120
        while "serving" not in log.read_text() and time.monotonic() < deadline:
            assert proc.poll() is None, log.read_text()
            time.sleep(0.2)
        port = int(re.search(r"http://127\.0\.0\.1:(\d+)/", log.read_text()).group(1))
        # the port printed is the port that answers; the page starts its kernel
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=120) as r:
            assert "voila" in r.read().decode(errors="replace").lower()
        started = psutil.Process(proc.pid).children(recursive=True)
        assert len(started) >= 2                             # voila and the page's kernel
        os.kill(proc.pid, getattr(signal, signame))
        code = proc.wait(timeout=60)
    finally:
        for p in psutil.Process(proc.pid).children(recursive=True) if proc.poll() is None \
                else []:
            p.kill()
        if proc.poll() is None:
            proc.kill()
    assert code == (143 if signame == "SIGTERM" else 130)
    gone, alive = psutil.wait_procs(started, timeout=20)
    for p in alive:                                          # never leave one behind
        p.kill()
    assert not alive, alive
    assert sorted(p.name for p in tmp_path.iterdir()) == ["log.txt"]
    text = log.read_text()
    assert "Warning" not in text and "[Voila]" not in text, text   # no third-party noise
