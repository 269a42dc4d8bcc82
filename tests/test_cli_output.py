"""What the command prints fits 100 columns and says which root matters.

``tefcore stability``: one row per root with a note marking the unstable
roots and the flutter root, a legend, a sentence naming the flutter root;
``tefcore mechanism`` without ``--mode`` takes the flutter root when it is
unstable and says so; ``tefcore sweep`` ends with one summary per role (the
TEF mode, the flutter root): onset, largest growth, exceptional points.
"""

import contextlib
import io
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import tefcore.linear.stability
import tefcore.sweeps.sweep
from tefcore.cli import main
from tefcore.cli.text import LEGEND, LOCKED_LEGEND, UNCERTAIN_LEGEND, WIDTH, onset, sweep_summary
from tests.sweeps.test_sweep import MODES, ToyPoint

#: A flutter point: MDART in forward flight with an imbalanced flap
#: (measured: one flap-induced root at about +3 /rev).
FLUTTER = ["-s", "flight.advance_ratio=0.3", "-s", "flap.overhang=0.29",
           "-s", "flap.cg_offset=0.36"]
#: Hover with the mass-balanced flap: every root stable (measured).
BALANCED = ["-s", "flight.advance_ratio=0", "-s", "flap.cg_offset=0"]


def stability_output(capsys, tmp_path, args):
    """Run ``tefcore stability``; return its lines, its table rows and the CSV."""
    csv = tmp_path / "modes.csv"
    assert main(["stability", *args, "--csv", str(csv)]) == 0
    lines = capsys.readouterr().out.splitlines()
    table = pd.read_csv(csv)
    rows = lines[1:1 + len(table)]          # a header, then one line per root in table order
    for line, name in zip(rows, table["label"], strict=True):
        assert line.startswith(name + " "), (line, name)
    return lines, rows, table


def fits(lines):
    return max(map(len, lines)) <= WIDTH


# ------------------------------------------------------------------ tefcore stability


@pytest.fixture(scope="module")
def flutter_point(tmp_path_factory):
    """The flutter point's output, computed once (about 2 s; capsys is per test)."""
    out = io.StringIO()
    csv = tmp_path_factory.mktemp("flutter") / "modes.csv"
    with contextlib.redirect_stdout(out):
        assert main(["stability", *FLUTTER, "--csv", str(csv)]) == 0
    lines = out.getvalue().splitlines()
    table = pd.read_csv(csv)
    return lines, lines[1:1 + len(table)], table


def test_stability_fits_100_columns_and_marks_the_flutter_root(flutter_point):
    """No line is longer than 100 columns (unwrapped, the table's lines take 178 and the
    trim's 413)."""
    lines, rows, table = flutter_point
    assert fits(lines), max(lines, key=len)
    flutter = table[table["flutter_root"] & (table["real_part"] > 0)]
    # the point is a flutter point (else every assertion below is vacuous)
    assert len(flutter) == 1 and flutter["real_part"].iloc[0] > 1.0
    bad = (table["real_part"] > 0) & ~table["neutral"]
    for line, (_, r), b in zip(rows, table.iterrows(), bad, strict=True):
        if r["flutter_root"] and b:
            assert line.rstrip().endswith("FLUTTER ROOT"), line
        elif b:
            assert "UNSTABLE" in line and "FLUTTER ROOT" not in line, line
        else:
            assert "UNSTABLE" not in line and "FLUTTER ROOT" not in line, line
    assert sum("FLUTTER ROOT" in line for line in rows) == 1
    # the useful content is kept: name, frequency, signed real part, damping ratio
    r = flutter.iloc[0]
    line = rows[flutter.index[0]]
    for text in (r["label"], f"{r['frequency_per_rev']:.4f}", f"{r['real_part']:+.4f}",
                 f"{r['damping_ratio']:.4f}"):
        assert text in line, (text, line)


def test_stability_legend_flutter_sentence_and_wrapped_trim(flutter_point):
    lines, rows, table = flutter_point
    after = lines[1 + len(table):]
    assert after[0] == LEGEND
    r = table[table["flutter_root"]].iloc[0]
    name = r["label"].removesuffix(" (locked)")
    # the legend of a locked pair follows when one is listed (this point has blade flap 1's);
    # a "name uncertain" line may come between, when a root has that note
    assert (after[1] == LOCKED_LEGEND) == table["label"].str.endswith(" (locked)").any()
    sentence = next(ln for ln in after[1:4] if ln.startswith("flutter root:"))
    assert sentence == (f"flutter root: {r['label']} at {r['real_part']:+.3f} /rev (continues "
                        f"from {name}), frequency {r['frequency_per_rev']:.3f} /rev")
    trim = [ln for ln in after if ln.startswith(("trim:", "flap deflection", "  "))]
    joined = " ".join(trim)
    # the key scalars are all still printed, over several short lines
    for key in ("collective_deg=", "cyclic_cos_deg=", "cyclic_sin_deg=", "ct_sigma=", "mean=",
                "1c=", "1s="):
        assert key in joined, key
    assert len(trim) >= 3


def test_a_stable_balanced_point_marks_no_flutter_root(capsys, tmp_path):
    lines, rows, table = stability_output(capsys, tmp_path, BALANCED)
    assert fits(lines)
    assert (table["real_part"] < 0).all()            # the point is stable
    # the table has a least stable flap-induced root, but it is stable: not called flutter
    least = table[table["flutter_root"]]
    assert len(least) == 1
    assert not any("FLUTTER ROOT" in ln or "UNSTABLE" in ln for ln in rows)
    assert not any(ln.startswith("flutter root:") for ln in lines)
    assert (f"no flutter root: the least stable flap-induced root, {least['label'].iloc[0]}, "
            "is stable") in "\n".join(lines)


def fake_point(monkeypatch, modes: pd.DataFrame):
    """`tefcore stability` prints `modes` (the trim of a real command's length)."""
    trim = {"collective_deg": 6.1, "cyclic_cos_deg": 2.5, "cyclic_sin_deg": -3.6,
            "inflow": 0.0097, "induced_inflow": 0.0097, "ct_sigma": 0.075, "iterations": 11,
            **{f"delta_{h}_deg": 0.123456 for h in ("mean", "1c", "1s", "2c", "2s", "3c", "3s",
                                                   "4c", "4s", "5c", "5s")},
            "reverse_flow_fraction": 0.017}
    res = SimpleNamespace(modes=modes, trim=trim, aero_modes=None)
    monkeypatch.setattr(tefcore.linear.stability, "stability", lambda cfg: res)


def test_unstable_neutral_and_uncertain_rows_with_long_names(monkeypatch, capsys):
    """An unstable root that is not the flap's is UNSTABLE; a neutral one is not; 24-character
    names in two columns still fit (the 'carries most' column gives way)."""
    long = "blade torsion 2 (locked)"
    modes = pd.DataFrame({
        "label": ["blade lag 1", long, "TEF", "blade flap 5", "blade axial 1"],
        "dominant": [long, "blade flap 1 (locked)", "TEF", "blade torsion 1 (locked)",
                     "blade axial 1"],
        "identity_certain": [True, False, True, True, True],
        "frequency_per_rev": [0.59, 11.5, 6.4, 9.8, 12.5],
        "real_part": [0.05, -0.1, -4.7, 2.98, 1e-9],
        "real_part_error": [1e-9, 1e-9, 1e-9, 1e-9, 1e-7],
        "neutral": [False, False, False, False, True],
        "damping_ratio": [-0.08, 0.01, 0.6, -0.29, 0.0],
        "flutter_root": [False, False, False, True, False]})
    fake_point(monkeypatch, modes)
    assert main(["stability"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert fits(lines), max(lines, key=len)
    rows = lines[1:6]
    assert "UNSTABLE" in rows[0] and "FLUTTER ROOT" not in rows[0]
    assert "name uncertain" in rows[1] and "UNSTABLE" not in rows[1]
    assert "UNSTABLE" not in rows[2] and "FLUTTER ROOT" not in rows[2]
    assert rows[3].rstrip().endswith("FLUTTER ROOT")
    assert " neutral" in rows[4] and "UNSTABLE" not in rows[4]
    assert lines[6:9] == [LEGEND, LOCKED_LEGEND, UNCERTAIN_LEGEND]
    assert lines[9].startswith("flutter root: blade flap 5 at +2.980 /rev")


def test_a_neutral_flutter_root_is_not_called_flutter(monkeypatch, capsys):
    modes = pd.DataFrame({"label": ["TEF", "blade torsion 2"], "dominant": ["TEF", "x"],
                          "frequency_per_rev": [6.4, 11.5], "real_part": [-4.7, 2e-9],
                          "neutral": [False, True], "damping_ratio": [0.6, 0.0],
                          "flutter_root": [False, True]})
    fake_point(monkeypatch, modes)
    assert main(["stability"]) == 0
    out = capsys.readouterr().out
    assert "FLUTTER ROOT" not in out.split(LEGEND)[0] and "\nflutter root:" not in out
    assert "no flutter root: the least stable flap-induced root, blade torsion 2, is neutral" in out


# ------------------------------------------------------------------ tefcore mechanism


def mechanism_run(capsys, tmp_path, args):
    csv = tmp_path / "m.csv"
    assert main(["mechanism", "--no-knockouts", *args, "--csv", str(csv)]) == 0
    lines = capsys.readouterr().out.splitlines()
    total = pd.read_csv(csv).set_index("term").loc["total", "contribution_real"]
    return lines, float(total)


def test_mechanism_defaults_to_the_unstable_flutter_root(capsys, tmp_path, flutter_point):
    _, _, table = flutter_point
    r = table[table["flutter_root"]].iloc[0]
    lines, total = mechanism_run(capsys, tmp_path, FLUTTER)
    assert fits(lines)
    assert lines[0] == (f"decomposing the flutter root ({r['label']}, {total:+.2f} /rev); "
                        "--mode TEF for the flap mode")
    assert lines[1].startswith(f"root {r['label']}: ")
    # the root decomposed is the table's flutter root: the mechanism recomputes it with its
    # own Floquet steps (4 sub-intervals), the exponents agree to the solver's 1e-3 /rev
    assert total == pytest.approx(r["real_part"], abs=1e-3)


def test_mechanism_mode_flutter_and_tef_are_kept(capsys, tmp_path):
    """--mode flutter decomposes the unstable root (about +3 /rev)."""
    lines, total = mechanism_run(capsys, tmp_path, ["--mode", "flutter", *FLUTTER])
    assert not lines[0].startswith("decomposing")        # asked for: nothing to announce
    assert 2.0 < total < 4.0
    lines, total = mechanism_run(capsys, tmp_path, ["--mode", "TEF", *FLUTTER])
    assert lines[0].startswith("root TEF: ") and total < 0


def test_mechanism_defaults_to_the_tef_mode_without_flutter(capsys, tmp_path):
    lines, total = mechanism_run(capsys, tmp_path, BALANCED)
    assert lines[0].startswith(f"decomposing the TEF mode ({total:+.2f} /rev): no flutter root "
                               "is unstable")
    assert lines[1].startswith("root TEF: ") and total < 0


# ------------------------------------------------------------------ tefcore sweep


def tef_real(x):
    return MODES["TEF"][1](x)


@pytest.fixture
def toy_default_point(monkeypatch):
    """`tefcore sweep` evaluates the synthetic point of test_sweep (TEF unstable above 0.2)."""
    point = ToyPoint()
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    return point


def sweep_lines(capsys, tmp_path, values):
    assert main(["sweep", "flap.cg_offset", "--values", *values, "--quiet",
                 "--csv", str(tmp_path / "s.csv")]) == 0
    return capsys.readouterr().out.splitlines()


def test_sweep_summary_interpolates_the_onset(toy_default_point, capsys, tmp_path):
    lines = sweep_lines(capsys, tmp_path, ["-0.3", "0.0", "0.3", "0.6"])
    assert fits(lines)
    # the TEF real part changes sign between 0.0 and 0.3 (it is 0 at 0.2, cubic): the onset is
    # the linear interpolation between those two points asked for, not 0.2
    y0, y1 = tef_real(0.0), tef_real(0.3)
    x_on = 0.3 * -y0 / (y1 - y0)
    assert abs(x_on - 0.2) > 1e-3                   # the interpolation is what is tested
    tef = next(ln for ln in lines if ln.startswith("TEF mode:"))
    assert tef == (f"TEF mode: onset at {x_on:.4g}; largest real part {tef_real(0.6):+.3f} "
                   "/rev at 0.6")
    # the toy's flutter root is the least stable root of each point: the torsion root at
    # -0.3 (-0.03 against the TEF's -0.075), the TEF from 0.0 on
    fr = next(ln for ln in lines if ln.startswith("flutter root:"))
    assert fr == (f"flutter root: onset at {x_on:.4g}; largest real part {tef_real(0.6):+.3f} "
                  "/rev at 0.6 (TEF)")


@pytest.mark.parametrize("values, text", [(["-0.6", "-0.3"], "stable throughout"),
                                          (["0.4", "0.6"], "unstable throughout")])
def test_sweep_summary_without_a_sign_change(toy_default_point, capsys, tmp_path, values, text):
    lines = sweep_lines(capsys, tmp_path, values)
    assert next(ln for ln in lines if ln.startswith("TEF mode:")).startswith(f"TEF mode: {text};")


def test_onset_cases():
    assert onset([0, 1, 2], [0.1, -0.1, -0.2]) == ("unstable from the first point (1 later "
                                                   "sign change)", 0.0)
    text, x = onset([0, 1, 2, 3], [-1.0, 1.0, -1.0, 1.0])
    assert x == 0.5 and text == "onset at 0.5 (2 later sign changes)"
    # a neutral positive real part is stable: the onset is after it
    assert onset([0, 1, 2], [1e-9, -0.1, 0.1], neutral=[True, False, False])[1] == 1.5


def fake_sweep(eps=()):
    """A sweep of the pitch-link stiffness given in lb/in, with exceptional points."""
    lb_in = 175.126835                                   # N/m per lb/in
    rows = []
    for i, k in enumerate([400.0, 600.0, 800.0]):
        for label, real, tef, fr in (("TEF", [-1.0, 0.5, 1.5][i], True, i > 0),
                                     ("blade torsion 2", [0.2, 0.1, -0.3][i], False, i == 0)):
            rows.append({"point": i, "value": f"{k:g} lb/in", "value_si": k * lb_in,
                         "refinement": 0, "status": "ok", "label": label, "real_part": real,
                         "tef_branch": tef, "flutter_root": fr})
    columns = ["modes", "x_low", "x_high", "kind"]
    return SimpleNamespace(table=pd.DataFrame(rows), parameter="hub.pitch_link_stiffness",
                           exceptional_points=pd.DataFrame(
                               [e for e in eps if e[3] not in MOVED], columns=columns),
                           undecided_steps=pd.DataFrame(
                               [e for e in eps if e[3] in MOVED], columns=columns))


#: The kinds of :func:`tefcore.modes.roles.undecided_steps`.
MOVED = ("identity undecided", "named by participation")


def test_sweep_summary_in_the_given_unit_with_exceptional_points():
    lb_in = 175.126835
    res = fake_sweep([("TEF / blade flap 3", 650 * lb_in, 660 * lb_in, "names exchange"),
                      ("blade flap 1 / blade lag 1", 500 * lb_in, 500 * lb_in, "paths meet")])
    lines = sweep_summary(res)
    assert fits(lines)
    assert lines[0] == "along hub.pitch_link_stiffness in lb/in:"
    text = " ".join(" ".join(lines).split())        # wrapped lines read as one text
    # TEF: -1 at 400, +0.5 at 600 -> onset 400 + 200 * 1/1.5 = 533.3 lb/in
    assert "TEF mode: onset at 533.3; largest real part +1.500 /rev at 800 lb/in" in text
    assert "exceptional points: TEF / blade flap 3 between 650 and 660" in text
    assert "blade flap 1 / blade lag 1" not in text        # not a mode of either role
    # the flutter root: torsion (+0.2) then the TEF (+0.5, +1.5): unstable throughout
    assert "flutter root: unstable throughout; largest real part +1.500 /rev at 800 lb/in (TEF)" \
        in text
    # its names include the TEF: the TEF's exceptional point is one of its names'
    assert "exceptional points of its names: TEF / blade flap 3" in text
    assert "exceptional points" not in sweep_summary(fake_sweep())[1]


def test_sweep_summary_names_a_step_where_a_role_s_name_moved_undecided():
    """A name that moved to another root with no located exceptional point is
    said on its role's line (never a silent jump), apart from the exceptional
    points; a pair of other modes is not."""
    lb_in = 175.126835
    res = fake_sweep([("TEF / blade flap 3", 650 * lb_in, 660 * lb_in, "identity undecided"),
                      ("blade flap 1 / blade lag 1", 500 * lb_in, 510 * lb_in,
                       "identity undecided")])
    lines = sweep_summary(res)
    assert fits(lines)
    text = " ".join(" ".join(lines).split())
    assert "TEF mode: onset at 533.3; largest real part +1.500 /rev at 800 lb/in; identity " \
        "undecided: TEF / blade flap 3 between 650 and 660" in text
    assert "exceptional points" not in text
    assert "blade flap 1 / blade lag 1" not in text
    # a move of names by participation is said under its own kind
    res = fake_sweep([("blade torsion 2 / blade flap 5", 450 * lb_in, 460 * lb_in,
                       "named by participation")])
    text = " ".join(" ".join(sweep_summary(res)).split())
    assert ("flutter root: unstable throughout; largest real part +1.500 /rev at 800 lb/in "
            "(TEF); named by participation of its names: blade torsion 2 / blade flap 5 "
            "between 450 and 460") in text
    assert "identity undecided" not in text


def test_a_real_hover_sweep_summary(capsys, tmp_path):
    """Three hover points (about 1 s): the flutter root's onset is where its real part, read
    back from the CSV, changes sign between the points asked for."""
    csv = tmp_path / "s.csv"
    assert main(["sweep", "flap.cg_offset", "--values", "0", "0.1", "0.2", "--quiet",
                 "-s", "flight.advance_ratio=0", "--csv", str(csv)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert fits(lines)
    t = pd.read_csv(csv)
    fr = t[t["flutter_root"] & (t["refinement"] == 0)].sort_values("value_si")
    x, y = fr["value_si"].to_numpy(), fr["real_part"].to_numpy()
    line = next(ln for ln in lines if ln.startswith("flutter root:"))
    text, value = onset(x, y)
    assert line.startswith(f"flutter root: {text};")
    if np.isfinite(value) and value > x[0]:
        i = int(np.searchsorted(x, value))
        assert y[i - 1] <= 0 < y[i]
