"""The animation: frames that move, deterministic GIF bytes, MP4 only with ffmpeg."""

import shutil

import numpy as np
import pytest

from tefcore.config.io import load_config
from tefcore.timedomain.animation import (
    check_writer,
    gif_bytes,
    naca0012,
    render_frames,
    save_animation,
)
from tefcore.timedomain.simulate import simulate


@pytest.fixture(scope="module")
def hover():
    cfg = load_config("mdart").with_overrides({"flight.advance_ratio": 0.0,
                                               "flap.cg_offset": 0.33})
    return simulate(cfg, mode="flutter", revs=2)


def test_naca0012_thickness():
    x, y = naca0012(200)
    assert 2 * y.max() == pytest.approx(0.12, abs=2e-3)
    assert x[np.argmax(y)] == pytest.approx(0.3, abs=0.02)


def test_frames_move_and_are_deterministic(hover):
    frames = render_frames(hover, frames_per_rev=3, dpi=40)
    assert len(frames) == 7
    a, b = (np.asarray(f, float) for f in (frames[1], frames[4]))
    assert a.shape == b.shape and np.abs(a - b).mean() > 0.5      # the section moved
    first = gif_bytes(hover, frames_per_rev=3, dpi=40)
    assert first[:6] == b"GIF89a" and first == gif_bytes(hover, frames_per_rev=3, dpi=40)


def test_save_gif_atomically(hover, tmp_path):
    out = tmp_path / "a.gif"
    save_animation(hover, out, "gif", frames_per_rev=2, dpi=30)
    assert out.read_bytes()[:6] == b"GIF89a"
    assert [p.name for p in tmp_path.iterdir()] == ["a.gif"]      # no temporary left


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg not installed")
def test_save_mp4(hover, tmp_path):
    out = tmp_path / "a.mp4"
    save_animation(hover, out, "mp4", frames_per_rev=2, dpi=30)
    assert out.read_bytes()[4:8] == b"ftyp"


def test_check_writer(monkeypatch):
    with pytest.raises(ValueError, match="unknown animation format"):
        check_writer("a.avi", "avi")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(ValueError, match="needs ffmpeg"):
        check_writer("a.mp4", "mp4")
