"""A map's stored pieces are never reused for other inputs, and a damaged one names its file.

The map's boundary file (``OUT/boundary.jsonl``) carries the header sweep
files have (configuration hash without the two mapped fields, input files,
tefcore version, model code); its crossings are keyed by the row's SI value,
the bracket and the tolerance.  A toy point function whose flutter boundary
depends on the configuration shows a stale boundary at once: the growth is
``g = x + y^2 - 0.3 + shift`` with ``shift`` from the actuator stiffness, so
the boundary of a row is at ``x = 0.3 - shift - y^2``.
"""

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tefcore.cli import main
from tefcore.errors import SweepFileError
from tefcore.sweeps.maps import stability_map
from tests.sweeps.test_stability_map import MDART

XS = [0.0, 0.1, 0.2, 0.3, 0.4]
YS = [0.0, 0.2]
#: actuator stiffness [N m/rad] of the changed configuration, and its toy shift
STIFF = 200.0


class ShiftedToy:
    """Picklable point function; the boundary moves with the actuator stiffness."""

    def __init__(self):
        self.calls = 0

    def __call__(self, cfg):
        self.calls += 1
        x, y = cfg.flap.cg_offset, cfg.flap.overhang
        shift = 0.05 if cfg.actuator.stiffness == STIFF else 0.0
        g = x + y**2 - 0.3 + shift
        modes = pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [6.0],
                              "real_part": [g], "damping_ratio": [-g / 6],
                              "share_TEF": [0.8]})
        return SimpleNamespace(modes=modes, eigenvectors=np.eye(1, dtype=complex), trim={})


def run_map(cfg, out=None, ys=YS, **kw):
    return stability_map(cfg, "flap.cg_offset", XS, "flap.overhang", ys,
                         point=kw.pop("point", ShiftedToy()), progress=False, out=out, **kw)


def boundary_lines(out):
    return [json.loads(x) for x in (Path(out) / "boundary.jsonl").read_text().splitlines()]


CHANGED = MDART.with_overrides({"actuator.stiffness": STIFF})


# ------------------------------------------------------------------ stale inputs


def test_the_boundary_file_has_the_header_of_a_sweep_file(tmp_path):
    from tefcore.provenance import model_stamp
    from tefcore.sweeps.store import config_hash

    run_map(MDART, tmp_path / "F")
    head, *crossings = boundary_lines(tmp_path / "F")
    assert head["format"] == "tefcore.map_boundary"
    assert head["x_field"] == "flap.cg_offset" and head["y_field"] == "flap.overhang"
    assert head["config_hash"] == config_hash(MDART, ["flap.cg_offset", "flap.overhang"])
    assert head["model_stamp"] == model_stamp() and head["inputs"] == {}
    assert sorted(c["y"] for c in crossings) == YS


def test_a_boundary_of_another_configuration_is_never_reused(tmp_path):
    """Rows refused, deleted as advised: the boundary of the other configuration does not
    come back."""
    out = tmp_path / "F"
    run_map(MDART, out)
    with pytest.raises(SweepFileError, match="cannot resume"):
        run_map(CHANGED, out)                       # refused before anything is computed
    for row in out.glob("row_*.jsonl"):
        row.unlink()
    # the stale boundary is refused too, naming its file ...
    toy = ShiftedToy()
    with pytest.raises(SweepFileError, match=r"boundary\.jsonl.*configuration"):
        run_map(CHANGED, out, point=toy)
    assert toy.calls == 0
    # ... and once it is deleted the boundary is the fresh one: x = 0.25 - y^2
    (out / "boundary.jsonl").unlink()
    fresh = run_map(CHANGED, out)
    # brentq's tolerance: 1e-4 of the x range (0.4), the map's default xtol
    np.testing.assert_allclose(fresh.boundary["x"], 0.25 - np.square(YS), atol=1e-4 * 0.4)
    pd.testing.assert_frame_equal(fresh.boundary, run_map(CHANGED).boundary)


@pytest.mark.parametrize("field, value, match", [
    ("model_stamp", "0123456789abcdef", "model code"),
    ("tefcore_version", "0.0.1", "tefcore version"),
    ("y_field", "flap.chord_ratio", "flap.chord_ratio"),
])
def test_a_boundary_of_other_code_or_fields_is_refused(tmp_path, field, value, match):
    out = tmp_path / "F"
    run_map(MDART, out)
    path = out / "boundary.jsonl"
    head, *rest = path.read_text().splitlines(keepends=True)
    path.write_text(json.dumps({**json.loads(head), field: value}) + "\n" + "".join(rest))
    with pytest.raises(SweepFileError, match=match):
        run_map(MDART, out)


def test_a_boundary_file_without_a_header_is_refused(tmp_path):
    # what tefcore wrote before: crossings keyed by row index, no header
    out = tmp_path / "F"
    out.mkdir()
    (out / "boundary.jsonl").write_text(json.dumps(
        {"key": "0|0.1|0.2|4e-05", "y": 0.2, "x": 0.161, "direction": "destabilising",
         "x_lo": 0.1, "x_hi": 0.2, "converged": True, "error": ""}) + "\n")
    with pytest.raises(SweepFileError, match=r"boundary\.jsonl.*header"):
        run_map(MDART, out)


def test_resume_reuses_the_crossings_of_the_rows_asked_for_again(tmp_path):
    out = tmp_path / "F"
    first = run_map(MDART, out)
    toy = ShiftedToy()
    again = run_map(MDART, out, point=toy)
    assert toy.calls == 0
    pd.testing.assert_frame_equal(first.boundary, again.boundary)
    # a new row: its points and its crossing are computed, the others reused
    toy = ShiftedToy()
    more = run_map(MDART, out, ys=[0.0, 0.2, 0.4], point=toy)
    assert 0 < toy.calls and len(more.boundary) == 3
    np.testing.assert_allclose(more.boundary["x"], 0.3 - np.square([0.0, 0.2, 0.4]),
                               atol=1e-4 * 0.4)


def test_resume_false_starts_the_boundary_anew(tmp_path):
    out = tmp_path / "F"
    run_map(MDART, out)
    path = out / "boundary.jsonl"
    lines = path.read_text().splitlines(keepends=True)
    fake = {**json.loads(lines[1]), "x": 0.123}       # a wrong crossing kept in the file
    path.write_text(lines[0] + json.dumps(fake) + "\n" + "".join(lines[2:]))
    assert 0.123 in run_map(MDART, out).boundary["x"].values   # resumed: the file's
    fresh = run_map(MDART, out, resume=False)
    assert 0.123 not in fresh.boundary["x"].values


# ------------------------------------------------------------------ damaged files


def test_a_cut_short_last_line_is_dropped_and_recomputed(tmp_path):
    out = tmp_path / "F"
    first = run_map(MDART, out)
    path = out / "boundary.jsonl"
    data = path.read_bytes()
    path.write_bytes(data[:-20])                      # a crash in the middle of a write
    toy = ShiftedToy()
    with pytest.warns(UserWarning, match=r"boundary\.jsonl: dropping an incomplete last line"):
        again = run_map(MDART, out, point=toy)
    assert toy.calls > 0                              # the lost crossing, computed again
    pd.testing.assert_frame_equal(first.boundary, again.boundary)
    assert path.read_bytes() == data                  # and stored again in full


def test_a_damaged_line_names_the_file_and_the_line(tmp_path, capsys):
    out = tmp_path / "F"
    run_map(MDART, out)
    path = out / "boundary.jsonl"
    lines = path.read_text().splitlines(keepends=True)
    lines[1] = lines[1][:40] + lines[1][41:]          # one character lost: not JSON
    path.write_text("".join(lines))
    with pytest.raises(SweepFileError, match=rf"{path}, line 2: not a JSON record"):
        run_map(MDART, out)


def test_a_damaged_boundary_is_one_line_naming_it_from_the_cli(tmp_path, monkeypatch, capsys):
    import tefcore.sweeps.maps
    import tefcore.sweeps.sweep

    toy = ShiftedToy()
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps):
        monkeypatch.setattr(module, "default_point", lambda: toy)
    out = tmp_path / "F"
    args = ["map", "flap.cg_offset", "0", "0.4", "5", "flap.overhang", "0", "0.2", "2",
            "--out", str(out), "--csv", str(tmp_path / "m.csv"), "--quiet"]
    assert main(args) == 0
    path = out / "boundary.jsonl"
    text = path.read_text()
    path.write_text(text.replace('"direction"', '"direction" 1', 1))
    capsys.readouterr()
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"tefcore: error: {path}, line 2: not a JSON record")
    assert err.count("\n") == 1
