"""Mode identity along sweeps: synthetic families with known answers.

* **Veering** ``A(x) = [[1 + 2x, g], [g, 2 - x]]``: the two eigenvalues come
  within ``2g`` of each other at ``x = 1/3`` and exchange shapes.  The
  continuous branches are the lower and the upper eigenvalue; a coarse sweep
  is ambiguous across the veering, refinement (bisection) resolves it, and
  the characters (labels) change along the branches.
* **Crossing** (``g = 0``): the eigenvalues cross, the shapes do not change;
  each track keeps its shape (and label) through the crossing.
* **Coalescence**: the pair ``s^2 + 2 z s + 1`` as ``z`` passes 1 becomes two
  real roots with one shape at ``z = 1``: no step separates them.

The tables are pure functions of the points: the order the values are
given (and computed), resuming, and parallel workers do not change them.
"""

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.modes.tracking import track_modes
from tefcore.sweeps.sweep import sweep

MDART = load_config("mdart")
PARAM = "flap.cg_offset"


class Veering:
    """Picklable point function: the 2 x 2 veering family at x = flap.cg_offset."""

    def __init__(self, g=0.05):
        self.g = g

    def __call__(self, cfg):
        x = cfg.flap.cg_offset
        w, v = np.linalg.eigh(np.array([[1 + 2 * x, self.g], [self.g, 2 - x]]))
        labels = ["first" if abs(v[0, j]) >= abs(v[1, j]) else "second" for j in range(2)]
        modes = pd.DataFrame({"mode_id": [0, 1], "label": labels, "frequency_per_rev": w,
                              "real_part": [-0.01, -0.01], "damping_ratio": [0.01, 0.01]})
        # a sign/phase per point, as a solver gives: MAC must not care
        return SimpleNamespace(modes=modes, vectors=v * np.exp(1j * 3.0 * x), trim={})


XS = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]


def branch(table, track):
    return table[table["track"] == track].sort_values("value_si")


def test_veering_followed_as_continuous_branches_after_refinement():
    res = sweep(MDART, PARAM, XS, point=Veering(), progress=False)
    t = res.table
    # the coarse step across the veering was ambiguous and got bisected
    assert (t["refinement"] > 0).any()
    assert t["identity"].isin(["start", "clear"]).all()
    lower = branch(t, 0)
    w = lower["frequency_per_rev"].to_numpy()
    x = lower["value_si"].to_numpy()
    exact = [np.linalg.eigvalsh([[1 + 2 * xi, 0.05], [0.05, 2 - xi]])[0] for xi in x]
    np.testing.assert_allclose(w, exact, rtol=1e-12)          # always the lower root
    # its character changes at the veering, once: first -> second
    names = lower["label"].tolist()
    assert names[0] == "first" and names[-1] == "second"
    assert sum(a != b for a, b in zip(names, names[1:], strict=False)) == 1


def test_without_refinement_the_coarse_veering_is_flagged_ambiguous():
    res = sweep(MDART, PARAM, XS, point=Veering(), progress=False, refine=False)
    t = res.table
    assert (t["refinement"] == 0).all()
    assert (t["identity"] == "ambiguous").any()


def test_crossing_without_coupling_keeps_shapes():
    res = sweep(MDART, PARAM, XS, point=Veering(g=0.0), progress=False)
    t = res.table
    assert t["identity"].isin(["start", "clear"]).all()
    for track, g in t.groupby("track"):
        assert g["label"].nunique() == 1, track        # shape (label) kept
    first = t[t["label"] == "first"].sort_values("value_si")
    np.testing.assert_allclose(first["frequency_per_rev"], 1 + 2 * first["value_si"])


def coalescing(z):
    """Roots of s^2 + 2 z s + 1 with shapes [1, s] (first-order state)."""
    roots = np.roots([1.0, 2 * z, 1.0]).astype(complex)
    roots = roots[roots.imag >= -1e-12]
    roots = roots[np.argsort(roots.real)]
    vecs = np.array([np.ones_like(roots), roots])
    modes = pd.DataFrame({"mode_id": range(len(roots)), "label": ["m"] * len(roots),
                          "frequency_per_rev": np.abs(roots.imag), "real_part": roots.real})
    return modes, vecs


def test_coalescence_is_flagged():
    # z = 0.9 (complex pair) -> 1.0 (double root) -> 1.1 (two real roots)
    t = track_modes([coalescing(z) for z in (0.8, 0.9, 1.0, 1.1)], values=[0.8, 0.9, 1.0, 1.1])
    assert (t["identity"] == "coalescence").any()


# ------------------------------------------------------------------ invariance


def csv_bytes(res, tmp_path, name):
    path = tmp_path / name
    res.table.drop(columns="point").to_csv(path, index=False)
    return path.read_bytes()


def test_order_of_values_does_not_change_the_table(tmp_path):
    a = sweep(MDART, PARAM, XS, point=Veering(), progress=False)
    b = sweep(MDART, PARAM, XS[::-1], point=Veering(), progress=False)
    c = sweep(MDART, PARAM, [XS[i] for i in (3, 0, 5, 1, 4, 2)], point=Veering(),
              progress=False)
    ref = csv_bytes(a, tmp_path, "a.csv")
    assert csv_bytes(b, tmp_path, "b.csv") == ref
    assert csv_bytes(c, tmp_path, "c.csv") == ref


def test_resumed_and_parallel_sweeps_write_identical_csv(tmp_path):
    fresh = sweep(MDART, PARAM, XS, point=Veering(), progress=False)
    out = tmp_path / "s.jsonl"
    sweep(MDART, PARAM, XS[:3], point=Veering(), progress=False, out=out)   # interrupted
    resumed = sweep(MDART, PARAM, XS, point=Veering(), progress=False, out=out)
    again = sweep(MDART, PARAM, XS, point=Veering(), progress=False, out=out)
    assert again.n_computed == 0 and again.n_refined == 0      # all reused, refinements too
    parallel = sweep(MDART, PARAM, XS, point=Veering(), progress=False, n_jobs=2)
    paths = [tmp_path / f"{k}.csv" for k in ("f", "r", "a", "p")]
    for res, path in zip((fresh, resumed, again, parallel), paths, strict=True):
        res.to_csv(path)
    ref = paths[0].read_bytes()
    assert all(p.read_bytes() == ref for p in paths[1:])


class Labelled(Veering):
    """The toy with the point's names: the 'first' character is the TEF."""

    def __call__(self, cfg):
        r = super().__call__(cfg)
        r.modes["label"] = ["TEF" if lab == "first" else "blade torsion 1"
                            for lab in r.modes["label"]]
        return r


def test_the_tef_role_is_the_root_named_tef_at_every_point_whatever_the_start():
    # the TEF role is a point's own name for its root -- not a track followed
    # from wherever the sweep starts: two sweeps starting on either side of
    # the veering give the same TEF rows where they overlap
    full = sweep(MDART, PARAM, XS, point=Labelled(), progress=False).table
    half = sweep(MDART, PARAM, [x for x in XS if x >= 0.4], point=Labelled(),
                 progress=False).table
    for t in (full, half):
        rows = t[t["tef_branch"]]
        points = t.loc[t["status"] == "ok", "value_si"].unique()
        assert sorted(rows["value_si"]) == sorted(points)       # one row per point
        assert (rows["label"] == "TEF").all()
    a = full[full["tef_branch"] & (full["value_si"] >= 0.4)].sort_values("value_si")
    b = half[half["tef_branch"]].sort_values("value_si")
    np.testing.assert_array_equal(a["value_si"].to_numpy(), b["value_si"].to_numpy())
    np.testing.assert_array_equal(a["frequency_per_rev"].to_numpy(),
                                  b["frequency_per_rev"].to_numpy())
    # the TEF row crosses the veering from the lower root to the upper one
    # (its character, 'first', goes with it): not one track
    assert full[full["tef_branch"]]["track"].nunique() == 2


def test_warm_started_sweep_is_the_same_in_every_run(tmp_path):
    # stability() takes warm_start: the sweep cuts the values (sorted) into fixed
    # chains in which each point starts its trim from the previous one.  Fresh,
    # resumed (interrupted after two points), order-reversed and parallel sweeps
    # compute every point from the same start: byte-identical tables.  Against
    # cold starts the points agree to the trim's tolerance (residual 1e-10:
    # measured 4e-9 /rev in the real parts), far below what tracking or a figure
    # resolves; a warm start that changed the model (e.g. the blade modes at the
    # neighbour's collective) would move them by 1e-4 or more
    from tefcore.linear.stability import stability
    from tefcore.sweeps import evaluate as sweep_module

    cfg = MDART.with_overrides({"flight.advance_ratio": 0.3})
    param, xs = "actuator.stiffness", ["70 ft-lb/rad", "90 ft-lb/rad", "110 ft-lb/rad",
                                       "130 ft-lb/rad", "150 ft-lb/rad"]
    kw = dict(progress=False, refine=False)
    assert sweep_module.takes_warm_start(stability)
    fresh = sweep(cfg, param, xs, **kw)
    out = tmp_path / "s.jsonl"
    sweep(cfg, param, xs[:2], out=out, **kw)                           # interrupted
    resumed = sweep(cfg, param, xs, out=out, **kw)
    backwards = sweep(cfg, param, xs[::-1], **kw)
    parallel = sweep(cfg, param, xs, n_jobs=2, **kw)
    ref = csv_bytes(fresh, tmp_path, "f.csv")
    for name, res in (("resumed", resumed), ("backwards", backwards), ("parallel", parallel)):
        assert csv_bytes(res, tmp_path, f"{name}.csv") == ref, name
    cold = sweep(cfg, param, xs, point=lambda c: stability(c), **kw).table
    warm = fresh.table
    assert (warm["trim_iterations"].iloc[len(warm) // 2:] <
            cold["trim_iterations"].iloc[len(cold) // 2:]).all()
    for col in ("real_part", "frequency_per_rev"):
        assert np.abs(warm[col].to_numpy() - cold[col].to_numpy()).max() < 1e-7


@pytest.mark.parametrize("base, param, xs", [
    # a prescribed collective is not a trim unknown: a warm start that carried the
    # previous point's controls over would keep the neighbour's collective (Fig.
    # 16's hover sweep would come out flat, every point equal to the first)
    ({"flight.advance_ratio": 0.0, "flight.collective": 0.0}, "flight.collective",
     [0.0, 0.05, 0.1, 0.15]),
    ({"flight.advance_ratio": 0.3, "flight.collective": 0.1}, "flight.collective",
     [0.1, 0.14]),
    # the trim targets and the flight condition themselves
    ({"flight.advance_ratio": 0.3}, "flight.ct_sigma", [0.06, 0.08]),
    ({}, "flight.advance_ratio", [0.25, 0.3]),
])
def test_warm_starts_take_every_trim_input_from_their_own_point(base, param, xs):
    # each point of a warm-started sweep against the same point computed cold:
    # equal to the trim's tolerance (4e-9 /rev measured above), whatever field
    # the sweep varies -- a warm start may change the starting guess only
    from tefcore.linear.stability import stability

    cfg = MDART.with_overrides(base)
    kw = dict(progress=False, refine=False)
    warm = sweep(cfg, param, xs, **kw).table
    cold = sweep(cfg, param, xs, point=lambda c: stability(c), **kw).table
    assert len(warm) == len(cold)
    assert np.abs(warm["trim_collective_deg"].to_numpy()
                  - cold["trim_collective_deg"].to_numpy()).max() < 1e-6
    for col in ("real_part", "frequency_per_rev"):
        assert np.abs(warm[col].to_numpy() - cold[col].to_numpy()).max() < 1e-7
    if param == "flight.collective":
        got = np.deg2rad(warm.groupby("value_si")["trim_collective_deg"].first().to_numpy())
        assert np.allclose(got, sorted(xs), atol=1e-12)


def _moves_reference(table, x, kind):
    """The moves of names along tracks as pandas groups them (the reference
    :func:`tefcore.modes.roles._moves` reads from columns)."""
    from tefcore.modes.march import base_name
    from tefcore.modes.roles import _ROW_COLUMNS

    out = []
    t = table.sort_values([x, "track"], kind="stable")
    base = t["label"].map(base_name)
    at = {(float(v), n): r for v, n, r in zip(t[x], base, t.index, strict=True)}
    for _, g in t.groupby("track", sort=False):
        names = g["label"].map(base_name).to_numpy()
        xs = g[x].to_numpy(float)
        for i in np.flatnonzero(names[1:] != names[:-1]):
            a, b = names[i], names[i + 1]
            rows = [at.get((xs[i], a)), at.get((xs[i], b)), at.get((xs[i + 1], a)),
                    at.get((xs[i + 1], b))]
            if None in rows:
                continue
            sel = t.loc[rows]
            if kind({c: sel[c].to_numpy() for c in _ROW_COLUMNS if c in sel}):
                out.append((xs[i], xs[i + 1], a, b))
    return out


@pytest.mark.parametrize("track_kind", ["int", "str"])
def test_name_moves_read_from_columns_are_the_moves_of_the_grouped_table(track_kind):
    # exchanges of names along tracks (exceptional or undecided), found from the
    # table's columns read once, are those of the table grouped by track:
    # random names swapping between two tracks, tracks as numbers or strings,
    # rows without a track (left out as groupby leaves them), missing flags
    from tefcore.modes.roles import _is_exceptional, _is_undecided, _moves

    rng = np.random.default_rng(5)
    rows = []
    names = ["TEF", "blade flap 5", "blade torsion 2 (locked)", "blade flap 1"]
    for j, x in enumerate(np.round(np.linspace(0.0, 1.0, 30), 6)):
        perm = rng.permutation(4) if rng.random() < 0.4 else np.arange(4)
        for tr in range(4):
            rows.append({"x": x, "track": tr, "label": names[perm[tr]],
                         "identity_certain": [True, False, None, np.nan][rng.integers(0, 4)]
                         if rng.random() < 0.3 else True,
                         "named_by_path": bool(rng.random() < 0.9),
                         "flap_motion": rng.uniform(0, 0.05),
                         "frequency_uncoupled": rng.uniform(10, 18),
                         "meets": ["", "TEF", "blade flap 5, TEF", np.nan][rng.integers(0, 4)]})
        if j % 7 == 3:
            rows.append({**rows[-1], "track": np.nan, "label": "blade flap 1"})
    table = pd.DataFrame(rows).sample(frac=1.0, random_state=1).reset_index(drop=True)
    if track_kind == "str":
        table["track"] = [t if pd.isna(t) else f"track {int(t)}" for t in table["track"]]
    found = []
    for kind in (_is_exceptional, _is_undecided):
        got = _moves(table, "x", kind)
        assert all(m[4] is True for m in got)             # the kind's own verdict
        assert [m[:4] for m in got] == _moves_reference(table, "x", kind)
        found.append(len(got))
    assert min(found) > 0                                 # both kinds of move drawn


def test_flags_read_missing_as_false_as_pandas_fillna_does():
    # the name-move predicates read identity_certain / named_by_path from
    # column values; missing (None, NaN, pd.NA) is False, as
    # Series.fillna(False).astype(bool) made it
    from tefcore.modes.roles import _flags

    for values in ([True, False, None, np.nan], [1.0, 0.0, np.nan, 2.0],
                   pd.array([True, None, False, True], dtype="boolean"),
                   np.array([True, False, True, False])):
        series = pd.Series(values)
        want = series.astype(object).fillna(False).astype(bool).to_numpy()
        np.testing.assert_array_equal(_flags(series.to_numpy()), want)
