"""Tests of tefcore.modes.tracking: MAC and mode tracking along a sweep."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from tefcore.modes.matching import mac, match_modes
from tefcore.modes.tracking import ambiguous_steps, label_changes, track_modes

# ------------------------------------------------------------------ MAC


def test_mac_identity_scaling_and_phase_invariance():
    rng = np.random.default_rng(0)
    a = rng.normal(size=(6, 3)) + 1j * rng.normal(size=(6, 3))
    scaled = a * np.array([2.0, -1j, 0.3 * np.exp(0.7j)])
    np.testing.assert_allclose(np.diag(mac(a, scaled)), 1.0, rtol=1e-14)
    q, _ = np.linalg.qr(a)  # orthonormal columns: MAC is the identity
    np.testing.assert_allclose(mac(q, q), np.eye(3), atol=1e-14)


def test_mac_is_vectorised_and_matches_the_definition():
    rng = np.random.default_rng(1)
    a = rng.normal(size=(5, 4)) + 1j * rng.normal(size=(5, 4))
    b = rng.normal(size=(5, 2)) + 1j * rng.normal(size=(5, 2))
    m = mac(a, b)
    assert m.shape == (4, 2)
    for i in range(4):
        for j in range(2):
            x, y = a[:, i], b[:, j]
            ref = abs(np.vdot(x, y)) ** 2 / (np.vdot(x, x).real * np.vdot(y, y).real)
            assert m[i, j] == pytest.approx(ref, rel=1e-13)
    assert mac(a[:, 0], b[:, 1]).shape == (1, 1)  # 1-D input is one column


def test_mac_complex_conjugation_matters():
    # phi and conj(phi) are different modes when phi is genuinely complex
    phi = np.array([1.0, 1j])
    assert mac(phi, phi.conj())[0, 0] == pytest.approx(0.0, abs=1e-15)


def test_mac_errors():
    with pytest.raises(ValueError, match="differ in length"):
        mac(np.ones(3), np.ones(4))
    with pytest.raises(ValueError, match=r"phi_b column\(s\) \[1\] are zero"):
        mac(np.ones((2, 1)), np.array([[1.0, 0.0], [0.0, 0.0]]))
    with pytest.raises(ValueError, match="non-finite"):
        mac(np.array([np.nan, 1.0]), np.ones(2))


# Gaussian-integer entries (scaled): exact zero columns occur, underflow does not.
complex_arrays = hnp.arrays(
    complex, (4, 3), elements=st.builds(lambda re, im: complex(re, im) / 8,
                                        st.integers(-40, 40), st.integers(-40, 40)))


@settings(max_examples=80, deadline=None)
@given(complex_arrays, complex_arrays)
def test_mac_bounded_and_symmetric(a, b):
    if (np.abs(np.hstack([a, b])).sum(axis=0) == 0).any():
        with pytest.raises(ValueError):
            mac(a, b)
        return
    m = mac(a, b)
    assert ((m >= 0) & (m <= 1 + 1e-9)).all()
    np.testing.assert_allclose(m, mac(b, a).T, rtol=1e-12, atol=1e-15)


# ------------------------------------------------------------------ tracking

# Two modes A (f = 1 + x) and B (f = 2 - x) that cross at x = 0.5; a third,
# C (f = 3), stays apart.  The "solver" lists them by frequency.
LAWS = {"A": (lambda x: 1.0 + x, 0), "B": (lambda x: 2.0 - x, 1), "C": (lambda x: 3.0, 2)}
XS = np.linspace(0.0, 1.0, 11)


def point(x, *, by_order=False, vectors=True, phase=True):
    names = sorted(LAWS, key=lambda k: LAWS[k][0](x))
    modes = pd.DataFrame({
        "mode_id": range(3),
        "label": [f"mode {j + 1}" for j in range(3)] if by_order else names,
        "frequency_per_rev": [LAWS[k][0](x) for k in names],
        "real_part": [-0.01 * (1 + LAWS[k][1]) for k in names],
        "damping_ratio": 0.0,
    })
    if not vectors:
        return modes
    vecs = np.zeros((3, 3), complex)
    for j, k in enumerate(names):
        vecs[LAWS[k][1], j] = 1.0
        vecs[(LAWS[k][1] + 1) % 3, j] = 0.3
        if phase:
            vecs[:, j] *= np.exp(1j * (5 * x + 2 * j))
    return modes, vecs


def assert_follows_laws(t, xs=XS, key="label"):
    for name, (law, _) in LAWS.items():
        c = t[t[key] == name]
        assert c["track"].nunique() == 1 and len(c) == len(xs)
        np.testing.assert_allclose(c["frequency_per_rev"], law(xs[c["step"]]), atol=1e-12)


def test_tracks_follow_modes_through_the_crossing():
    t = track_modes([point(x) for x in XS], values=XS)
    assert list(t.columns[:6]) == ["step", "track", "label", "label_here", "identity",
                                   "mode_id"]
    assert t["identity"].isin(["start", "clear"]).all()
    assert len(t) == 3 * len(XS)
    assert_follows_laws(t)
    assert (t["label"] == t["label_here"]).all()
    assert t.loc[t["label"] == "A", "mode_id"].tolist() == [0] * 6 + [1] * 5  # reordered


def test_first_label_is_kept_and_label_changes_are_reported():
    t = track_modes([point(x, by_order=True) for x in XS], values=XS)
    start = t[t["step"] == 0].set_index("track")["label"]
    assert start.tolist() == ["mode 1", "mode 2", "mode 3"]
    # track 0 is mode A all along; the solver's frequency-order label switches
    a = t[t["track"] == 0]
    np.testing.assert_allclose(a["frequency_per_rev"], 1.0 + XS, atol=1e-12)
    assert (a["label"] == "mode 1").all()
    assert a["label_here"].tolist() == ["mode 1"] * 6 + ["mode 2"] * 5
    changes = label_changes(t)
    assert changes[["track", "from_label", "to_label"]].values.tolist() == [
        [0, "mode 1", "mode 2"], [1, "mode 2", "mode 1"]]
    assert t.loc[changes["row"], "step"].tolist() == [6, 6]


def test_mac_decides_at_the_crossing_without_prediction():
    # at x = 0.5 both modes have one frequency: only the shapes tell them apart
    t = track_modes([point(x) for x in XS], predict=False)
    assert_follows_laws(t)
    assert t["identity"].isin(["start", "clear"]).all()


def test_extrapolated_eigenvalues_alone_track_a_straight_crossing():
    t = track_modes([point(x, vectors=False) for x in XS], values=XS)
    assert_follows_laws(t)


def test_nearest_eigenvalue_without_prediction_or_mac_would_swap():
    # documents why both MAC and extrapolation are used: the nearest eigenvalue
    # follows the frequency-ordered branch and swaps the modes at the crossing
    xs = np.linspace(0.0, 1.0, 6)  # steps straddle the crossing
    t = track_modes([point(x, vectors=False) for x in xs], values=xs, predict=False)
    a = t[t["track"] == 0]
    np.testing.assert_allclose(a["frequency_per_rev"], np.minimum(1 + xs, 2 - xs))
    assert_follows_laws(track_modes([point(x) for x in xs], values=xs, predict=False),
                        xs=xs)


def test_uneven_steps_use_the_values_for_extrapolation():
    xs = np.array([0.0, 0.1, 0.2, 0.45, 0.9, 1.0])
    assert_follows_laws(track_modes([point(x, vectors=False) for x in xs], values=xs), xs=xs)


def test_failed_points_are_skipped_and_tracks_continue():
    pts = [point(x) for x in XS]
    pts[5] = None
    t = track_modes(pts, values=XS)
    assert 5 not in set(t["step"])
    for name, (law, _) in LAWS.items():
        c = t[t["label"] == name]
        assert c["track"].nunique() == 1 and len(c) == len(XS) - 1
        np.testing.assert_allclose(c["frequency_per_rev"], law(XS[c["step"]]))


def test_appearing_and_disappearing_modes():
    m0, v0 = point(0.0)
    m1, v1 = point(0.1)
    fewer = (m1.iloc[:2].reset_index(drop=True), v1[:, :2])  # mode C absent
    t = track_modes([(m0.iloc[:2], v0[:, :2]), point(0.05), fewer, point(0.15)])
    # C appears at step 1 (a new track), is absent at step 2 and comes back at
    # step 3 as another new track: a mode is not revived across a point where
    # it was missing -- its identity there is unknown
    assert sorted(t["track"].unique()) == [0, 1, 2, 3]
    assert t.loc[t["track"] == 2, "step"].tolist() == [1]
    assert t.loc[t["track"] == 3, "step"].tolist() == [3]
    assert t.loc[t["track"].isin([2, 3]), "identity"].eq("start").all()


def test_missing_or_mismatched_eigenvectors_fall_back_to_eigenvalues():
    pts = [point(x) for x in XS]
    pts[3] = point(XS[3], vectors=False)
    m, v = pts[7]
    pts[7] = (m, np.vstack([v, np.ones((1, 3))]))  # other state size: no MAC there
    assert_follows_laws(track_modes(pts, values=XS))


def test_point_formats_and_errors():
    m, v = point(0.2)
    as_obj = type("R", (), {"modes": m, "eigenvectors": v})()
    t1 = track_modes([as_obj, {"modes": m, "eigenvectors": v}, (m, v), m])
    assert len(t1) == 12 and t1.groupby("track").size().tolist() == [4, 4, 4]
    with pytest.raises(ValueError, match="lacks column"):
        track_modes([m.drop(columns="real_part")])
    with pytest.raises(ValueError, match="do not match 3 modes"):
        track_modes([(m, v[:, :2])])
    with pytest.raises(TypeError, match="cannot read modes"):
        track_modes([42])
    with pytest.raises(ValueError, match="2 values for 1 points"):
        track_modes([m], values=[0, 1])
    assert track_modes([None, None]).empty


def test_match_modes():
    a, b = point(0.4), point(0.6)  # across the crossing: A and B swap order
    assert match_modes(a, b).tolist() == [1, 0, 2]
    fewer = (b[0].iloc[:2], b[1][:, :2])
    assert match_modes(a, fewer).tolist() == [1, 0, -1]


def test_undecidable_match_is_flagged_not_silently_swapped():
    # two modes coalesce: at the third point both roots lie as far from either
    # extrapolated eigenvalue and there are no shapes; the match cannot be
    # decided, and the table says so instead of passing it off as a track
    def pt(lam_a, lam_b):
        return pd.DataFrame({"mode_id": [0, 1], "label": ["TEF", "torsion"],
                             "frequency_per_rev": [lam_a.imag, lam_b.imag],
                             "real_part": [lam_a.real, lam_b.real]})

    pts = [pt(-1 + 9j, -1 + 4j), pt(-0.5 + 7j, -2 + 5j), pt(-1.4 + 5.5j, -1.6 + 5.5j)]
    t = track_modes(pts, values=[0, 1, 2])
    assert t.loc[t["step"] == 2, "identity"].eq("ambiguous").all()
    # roots on the extrapolated paths of the tracks, which stay apart, are
    # clear continuations ...
    apart = [pt(-1 + 9j, -1 + 2j), pt(-0.5 + 8j, -2 + 2.5j), pt(0.02 + 7.01j, -3.0 + 3.0j)]
    clear = track_modes(apart, values=[0, 1, 2])
    assert clear.loc[clear["step"] == 2, "identity"].eq("clear").all()
    # ... but two tracks that cross within the step, with no shapes to show
    # whether they crossed or veered, are not
    crossing = [pt(-1 + 9j, -1.2 + 3j), pt(-1 + 7j, -1.2 + 5j), pt(-1 + 5.02j, -1.2 + 6.98j)]
    cross = track_modes(crossing, values=[0, 1, 2])
    assert cross.loc[cross["step"] == 2, "identity"].eq("ambiguous").all()
    assert 2 in ambiguous_steps(t)


def test_track_table_is_a_pure_function_of_the_points():
    # the same points give the same table, row for row
    pts = [point(x) for x in XS]
    a = track_modes(pts, values=XS)
    b = track_modes([point(x) for x in XS], values=XS)
    pd.testing.assert_frame_equal(a, b)


def test_a_resumed_march_is_the_march_from_scratch(monkeypatch):
    # a sweep's refinement rounds add midpoints; the march resumes after the
    # points before the first one added (memo) and must give, row for row,
    # the table of a march from the first point -- also when the new point is
    # the first, the last, or replaces a result by an equal copy
    import tefcore.modes.tracking as tr

    xs = list(XS)
    built = {x: point(x) for x in np.linspace(0.0, 1.0, 41)}

    def pts(values):
        return [{"modes": built[x][0], "vectors": built[x][1]} for x in values]

    rounds = [xs, sorted(xs + [0.55, 0.65]), sorted(xs + [0.55, 0.65, 0.025]),
              sorted(xs + [0.55, 0.65, 0.025, 0.975]), sorted(xs + [0.55, 0.65, 0.025, 0.975])]
    rounds = [[float(x) for x in r] for r in rounds]
    for r in rounds:
        for x in r:
            built.setdefault(x, point(x))
    memo: dict = {}
    stepped = []
    real = tr._track_step
    monkeypatch.setattr(tr, "_track_step", lambda st, step, *a: stepped.append(step)
                        or real(st, step, *a))
    for r in rounds:
        stepped.clear()
        resumed = track_modes(pts(r), values=r, memo=memo)
        pd.testing.assert_frame_equal(resumed, track_modes(pts(r), values=r), check_exact=True)
        assert_follows_laws(resumed, xs=np.array(r))
    # the last round's points were all seen: nothing marched again (steps
    # stepped in the fresh comparison run only)
    assert stepped == list(range(len(rounds[-1])))
    # an equal copy of a point's result is not the same result: marched from it
    memo2: dict = {}
    track_modes(pts(xs), values=xs, memo=memo2)
    copies = pts(xs)
    copies[6] = {"modes": built[xs[6]][0].copy(), "vectors": built[xs[6]][1].copy()}
    stepped.clear()
    again = track_modes(copies, values=xs, memo=memo2)
    assert stepped[:len(xs) - 6] == list(range(6, len(xs)))
    pd.testing.assert_frame_equal(again, track_modes(pts(xs), values=xs), check_exact=True)


def _pair_close_reference(a0, a1, b0, b1, periodic):
    """One pair of _flag_close_passes as a loop computes it (the scalar reference)."""
    from tefcore.modes.tracking import _unwrap

    if periodic:
        b0n = _unwrap(b0, a0)
        sign = 1.0 if np.isclose(b0n.imag % 1.0, b0.imag % 1.0) else -1.0
        b1 = complex(b1.real, sign * b1.imag + (b0n.imag - sign * b0.imag))
        b0 = b0n
    pts = np.array([a0, a1, b0, b1])
    sc = (0.5 + 0.5 * np.abs(pts.real).mean()) + 1j * (
        0.5 if periodic else 1.0 + 0.5 * np.abs(pts.imag).mean())
    x0a, x1a, x0b, x1b = (z.real / sc.real + 1j * z.imag / sc.imag for z in pts)
    d0, dd = x0a - x0b, (x1a - x0a) - (x1b - x0b)
    t = 0.0 if dd == 0 else float(np.clip(-(d0 * np.conj(dd)).real / abs(dd) ** 2, 0.0, 1.0))
    return abs(d0 + t * dd) < max(abs(x1a - x0a), abs(x1b - x0b))


@pytest.mark.parametrize("periodic", [False, True])
def test_close_passes_of_all_pairs_at_once_are_the_pairs_one_by_one(periodic):
    # the vectorised test of two roots passing close in a step gives, pair for
    # pair, the flags of the scalar arithmetic it replaced -- on random steps,
    # crossings built to pass close, Floquet frequencies mirrored, shifted by
    # whole /rev and sitting on a k/2 lock, and a root that does not move
    from tefcore.modes.tracking import _passes_close

    rng = np.random.default_rng(11)
    n = 4000
    a0 = rng.normal(-1, 1, n) + 1j * rng.uniform(0, 20, n)
    a1 = a0 + rng.normal(0, 0.3, n) + 1j * rng.normal(0, 0.5, n)
    b0 = a1 + rng.normal(0, 0.3, n) + 1j * rng.normal(0, 0.5, n)     # starts near a's end
    b1 = a0 + rng.normal(0, 0.3, n) + 1j * rng.normal(0, 0.5, n)     # ... and ends near its start
    apart = rng.random(n) < 0.5                     # half: a root elsewhere, moving a little
    b0 = np.where(apart, rng.normal(-1, 1, n) + 1j * rng.uniform(0, 20, n), b0)
    b1 = np.where(apart, b0 + rng.normal(0, 0.3, n) + 1j * rng.normal(0, 0.5, n), b1)
    if periodic:
        k = rng.integers(-3, 4, n)
        b0 = np.where(rng.random(n) < 0.3, b0.real - 1j * b0.imag, b0) + 1j * k
        lock = rng.random(n) < 0.1
        b0 = np.where(lock, b0.real + 0.5j * np.round(2 * b0.imag), b0)
        a0 = np.where(rng.random(n) < 0.1, a0.real + 0.5j * np.round(2 * a0.imag), a0)
    b1[:50] = b0[:50]                               # b does not move
    a1[50:100] = a0[50:100] + (b1[50:100] - b0[50:100])   # parallel: dd = 0
    if periodic:
        # |dd|^2 as x * x instead of pow(x, 2) moves t by an ulp and flips
        # this pair, whose closest approach is within an ulp of its reach
        a0[100], a1[100] = -1.6787109375 + 0.1015625j, -1.509765625 + 0.0035856833447920275j
        b0[100], b1[100] = -2.078125 + 0.0595703125j, -1.771484375 + 0.07487474584479203j
    got = _passes_close(a0, a1, b0, b1, periodic)
    want = np.array([_pair_close_reference(*z, periodic) for z in zip(a0, a1, b0, b1,
                                                                       strict=True)])
    assert got.dtype == bool and min(want.sum(), (~want).sum()) >= 100   # both drawn
    np.testing.assert_array_equal(got, want)


def test_a_steps_rows_keep_the_points_dtypes_and_share_no_memory():
    # the tracked rows are a copy of the point's table with its dtypes; a
    # column the tracking adds is refused where the point already has it
    modes = pd.DataFrame({"mode_id": pd.array([0, 1], dtype="Int64"),
                          "label": pd.Categorical(["A", "B"]),
                          "frequency_per_rev": [1.0, 2.0], "real_part": [-0.1, -0.2],
                          "flag": pd.array([True, None], dtype="boolean"),
                          "note": pd.Series(["x", None], dtype=object)})
    t = track_modes([modes])
    assert str(t["mode_id"].dtype) == "Int64" and str(t["flag"].dtype) == "boolean"
    assert isinstance(t["label_here"].dtype, pd.CategoricalDtype)
    assert t["note"].dtype == object and t["note"].iloc[1] is None
    modes.loc[0, "real_part"] = 123.0
    assert t["real_part"].tolist() == [-0.1, -0.2]
    for name in ("identity", "step", "frequency_tracked"):
        with pytest.raises(ValueError, match=f"cannot insert {name}"):
            track_modes([modes.assign(**{name: 1})])


def _step_frame_reference(step, modes, tracked_eig, identity, assigned, tracks):
    """One step's rows as a frame per step: the reference the joined columns must equal."""
    cols = {"step": step, "track": assigned, "label": [tracks[t].label for t in assigned],
            "label_here": modes["label"], "identity": identity}
    for name in modes.columns:
        if name == "label":
            continue
        cols[name] = modes[name]
        if name == "frequency_per_rev":
            cols["frequency_tracked"] = tracked_eig.imag
    return pd.DataFrame(cols, index=modes.index, copy=True)


@pytest.mark.parametrize("case", ["numpy and text", "object column", "pandas dtypes",
                                  "dtype changes", "a point without roots"])
def test_the_joined_table_is_the_concatenation_of_one_frame_per_step(case):
    # _table joins the steps' columns instead of making a frame per step; it
    # must give what one frame per step concatenated gives -- values, dtypes
    # (text inferred from the labels as a frame infers it, a column's own
    # dtype kept) and index -- also where it falls back to frames (a column's
    # dtype changes between steps, a step has no rows)
    from tefcore.modes.tracking import _step_columns, _table, _Track

    rng = np.random.default_rng(11)
    tracks = [_Track(label=f"mode {k}") for k in range(6)]
    steps, frames = [], []
    for step in range(7):
        n = 0 if case == "a point without roots" and step == 3 else int(rng.integers(2, 6))
        modes = pd.DataFrame({
            "mode_id": np.arange(n), "label": [f"mode {k}" for k in range(n)],
            "dominant": pd.Series(rng.choice(["flap", "torsion", None], n), dtype="str"),
            "frequency_per_rev": rng.random(n), "real_part": -rng.random(n),
            "neutral": rng.random(n) < 0.5})
        if case == "object column":
            modes["note"] = pd.Series([None if k % 2 else "x" for k in range(n)], dtype=object)
        if case == "pandas dtypes":
            modes["flag"] = pd.array([True, None, False, True, None][:n], dtype="boolean")
        if case == "dtype changes":
            modes["neutral"] = modes["neutral"].astype(float if step % 2 else bool)
        eig = modes["real_part"].to_numpy() + 1j * modes["frequency_per_rev"].to_numpy()
        assigned = rng.permutation(6)[:n]
        identity = np.array(rng.choice(["clear", "start", "ambiguous"], n), dtype=object)
        args = (step, modes, eig + 0.5j, identity, assigned, tracks)
        steps.append(_step_columns(*args))
        frames.append(_step_frame_reference(*args))
    got = _table(steps)
    pd.testing.assert_frame_equal(got, pd.concat(frames, ignore_index=True), check_exact=True)
    assert got["frequency_tracked"].iloc[0] == steps[0][0]["frequency_tracked"][0]


def test_review_cases_a_memo_shares_nothing_empty_points_and_repeated_columns():
    # three cases: (1) a memo must not keep the points' text columns
    # themselves, or a write into an earlier point shows in a resumed table;
    # (2) points without roots give 'label' the dtype one frame per step gives;
    # (3) a column name twice fails, as the frames do, and is not dropped
    def point(f):
        return pd.DataFrame({"mode_id": [0], "label": ["a"], "frequency_per_rev": [f],
                             "real_part": [-0.1], "note": pd.Series(["x"], dtype="str")})

    pts, memo = [point(1.0), point(1.1), point(1.2)], {}
    track_modes(pts[:2], memo=memo)
    pts[0]["note"].array[0] = "CHANGED"
    assert track_modes(pts, memo=memo)["note"].tolist() == ["x", "x", "x"]

    empty = point(1.0).iloc[:0]
    from tefcore.modes.tracking import _Track

    want = pd.concat([_step_frame_reference(s, empty, np.zeros(0, complex),
                                            np.zeros(0, object), np.zeros(0, int),
                                            [_Track(label="a")]) for s in (0, 1)],
                     ignore_index=True)
    got = track_modes([empty, empty])
    assert got["label"].dtype == want["label"].dtype and got["step"].dtype == want["step"].dtype

    twice = point(1.0)
    twice.insert(4, "x", [1])
    twice.insert(5, "x", [2.0], allow_duplicates=True)
    with pytest.raises(ValueError, match=r"column\(s\) \['x'\] more than once"):
        track_modes([twice])
