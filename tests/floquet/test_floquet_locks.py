"""Mode identity through a Floquet frequency lock (tefcore.modes.tracking, "Floquet locks").

A complex pair of Floquet multipliers that meets the real axis becomes two
real multipliers of one sign: two roots at one frequency ``k/2`` per rev,
with different real parts, until they meet again and leave the lock.  The
tests:

* **Mathieu tongues.** ``q'' + c q' + (delta + eps cos psi) q = 0`` (beside an
  uncoupled oscillator) locks at 1/2 per rev around ``delta = 1/4`` and at
  1 per rev around ``delta = 1`` (parametric resonance), computed by
  :func:`tefcore.floquet.floquet_modes`.  Closed forms: the exponents of the
  Mathieu pair sum to ``-c`` (Liouville: ``det Phi(2 pi) = exp(-2 pi c)``),
  so outside the lock both have real part ``-c/2`` and inside one is
  ``-c/2 + s`` and the other ``-c/2 - s``.  The branch must cross the whole
  lock as one certain curve on the less stable root -- before the plane rule
  it ended (or turned ambiguous) where the lock ends.
* **Hand-made points** in which the single root's shape is in, or out of,
  the plane of the two real shapes: decided, or left ambiguous.
"""

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.floquet import floquet_modes
from tefcore.modes.matching import LOCK_TOL, is_locked, locked_pairs, plane_mac
from tefcore.modes.tracking import follow_branch, track_modes
from tefcore.sweeps.sweep import sweep

MDART = load_config("mdart")
PARAM = "flap.cg_offset"
XS = [float(x) for x in np.round(np.linspace(-1.0, 1.0, 9), 3)]

#: (delta at x = 0, d delta / dx, eps, c, locked frequency): the first tongue
#: (lock at 1/2 /rev for -0.8 < x < 0.65, measured) and the second (1 /rev,
#: -0.6 < x < 0.45), each entered and left within the sweep.
TONGUES = {"half": (0.25, 0.2, 0.3, 0.04, 0.5), "one": (1.1, 0.25, 0.8, 0.02, 1.0)}


class MathieuLock:
    """Picklable point function: the damped Mathieu oscillator ('TEF') beside an
    uncoupled one at 3.3 /rev ('blade'), ``delta = d0 + dd * flap.cg_offset``.

    Labels as the stability code gives them: of two roots at one locked
    frequency the less stable keeps the label, the other is ``(locked)``.
    """

    def __init__(self, tongue):
        self.d0, self.dd, self.eps, self.c, _ = TONGUES[tongue]

    def __call__(self, cfg):
        delta = self.d0 + self.dd * cfg.flap.cg_offset

        def a(psi):
            psi = np.atleast_1d(psi)
            out = np.zeros((psi.size, 4, 4))
            out[:, 0, 2] = out[:, 1, 3] = 1.0
            out[:, 2, 0] = -(delta + self.eps * np.cos(psi))
            out[:, 2, 2] = -self.c
            out[:, 3, 1] = -3.3 ** 2
            out[:, 3, 3] = -0.1
            return out

        r = floquet_modes(a).positive_frequency()
        # by frequency to 1e-9 /rev (a lock's two roots share it to round-off),
        # less stable first, as the stability code orders them
        order = np.lexsort((-r.exponents.real, np.round(r.exponents.imag, 9)))
        eta, vec = r.exponents[order], r.eigenvectors[:, order]
        labels, seen = [], set()
        for e in eta:
            lab = "blade" if abs(e.imag - 3.3) < 0.1 else "TEF"
            labels.append(f"{lab} (locked)" if lab in seen else lab)
            seen.add(lab)
        modes = pd.DataFrame({"mode_id": range(len(eta)), "label": labels,
                              "frequency_per_rev": eta.imag, "real_part": eta.real,
                              "damping_ratio": -eta.real / np.abs(eta)})
        return SimpleNamespace(modes=modes, vectors=vec, periodic=True, trim={})


def is_lock_row(t, f_lock):
    return np.isclose(t["frequency_per_rev"].to_numpy(float), f_lock, rtol=0, atol=LOCK_TOL)


@pytest.mark.parametrize("tongue", sorted(TONGUES))
@pytest.mark.parametrize("refine", [True, False])
def test_tef_branch_crosses_a_lock_as_one_certain_curve(tongue, refine):
    _, _, _, c, f_lock = TONGUES[tongue]
    res = sweep(MDART, PARAM, XS, point=MathieuLock(tongue), progress=False, refine=refine)
    t = res.table
    branch = t[t["tef_branch"]].sort_values("value_si")
    points = t.loc[t["status"] == "ok", "value_si"].unique()
    # one row at every point (the root the point names TEF: of a locked pair
    # the less stable), certain throughout
    assert sorted(branch["value_si"]) == sorted(points)
    assert branch["tef_branch_certain"].all()
    locked = is_lock_row(branch, f_lock)
    # the sweep enters and leaves the lock
    assert locked.any() and not locked[0] and not locked[-1]
    # tracking along the parameter decides every step through the lock (the
    # plane rule at its ends)
    assert not (t["identity"] == "ambiguous").any()
    # outside the lock the pair's real part is -c/2 (Liouville; 1e-6: the
    # Floquet solver's tolerance on the exponents)
    np.testing.assert_allclose(branch.loc[~locked, "real_part"], -c / 2, atol=1e-6)
    # inside, the branch is the less stable real root; the two sum to -c
    for x, re in branch.loc[locked, ["value_si", "real_part"]].itertuples(index=False):
        pair = t[(t["value_si"] == x) & is_lock_row(t, f_lock)]["real_part"]
        assert len(pair) == 2 and re == pair.max()
        assert re > -c / 2 + 1e-3                    # split: a real lock, not round-off
        np.testing.assert_allclose(pair.sum(), -c, atol=2e-6)


def test_lock_tables_do_not_depend_on_order_resume_or_workers(tmp_path):
    point = MathieuLock("one")
    fresh = sweep(MDART, PARAM, XS, point=point, progress=False)
    reverse = sweep(MDART, PARAM, XS[::-1], point=point, progress=False)
    out = tmp_path / "s.jsonl"
    sweep(MDART, PARAM, XS[:4], point=point, progress=False, out=out)      # interrupted
    resumed = sweep(MDART, PARAM, XS, point=point, progress=False, out=out)
    parallel = sweep(MDART, PARAM, XS, point=point, progress=False, n_jobs=2)
    ref = fresh.table.drop(columns="point").to_csv(index=False)
    for res in (reverse, resumed, parallel):
        assert res.table.drop(columns="point").to_csv(index=False) == ref
    assert fresh.table["tef_branch_certain"].sum() == len(fresh.table["value_si"].unique())


# ------------------------------------------------------------------ hand-made points

E = np.eye(4)
#: the real shapes of the locked pair and the complex shape outside the lock
#: (a + ib with a, b in their plane); the blade mode's shape is e3
REAL_HI, REAL_LO = E[0] + 0.5 * E[1], E[0] - 0.5 * E[1]
COMPLEX = E[0] + 0.3j * E[1]


def pt(roots):
    """Point from ``[(eigenvalue, shape, label)]``, Floquet (periodic)."""
    modes = pd.DataFrame({"mode_id": range(len(roots)), "label": [r[2] for r in roots],
                          "frequency_per_rev": [r[0].imag for r in roots],
                          "real_part": [r[0].real for r in roots]})
    return modes, np.array([r[1] for r in roots], complex).T, True


BLADE = (-0.2 + 3.3j, E[2], "blade")


def lock_sweep(after_shape=COMPLEX, middle=(REAL_HI, REAL_LO)):
    """Enter a lock at 2 /rev, stay, leave (to 1.98 again); the less stable real
    root is -0.45.

    The locked frequencies are 2 to round-off, as a solver gives them (below
    2 by up to 7e-8 here; 1.5e-6 measured).
    """
    return [pt([(-0.5 + 1.98j, COMPLEX, "TEF"), BLADE]),
            pt([(-0.45 + 1.99999993j, REAL_HI, "TEF"),
                (-0.55 + 1.99999997j, REAL_LO, "TEF (locked)"), BLADE]),
            pt([(-0.46 + 1.99999995j, middle[0], "TEF"),
                (-0.54 + 1.99999996j, middle[1], "TEF (locked)"), BLADE]),
            pt([(-0.5 + 1.98j, after_shape, "TEF"), BLADE])]


def rows(t, label_here):
    return t[t["label_here"] == label_here].sort_values("step")


def test_entering_staying_and_leaving_a_lock_keep_one_track():
    pts = lock_sweep()
    t = track_modes(pts)
    tef = t[t["track"] == 0].sort_values("step")
    assert tef["real_part"].tolist() == [-0.5, -0.45, -0.46, -0.5]   # the less stable root
    assert tef["identity"].tolist() == ["start", "coalescence", "clear", "coalescence"]
    # leaving the lock the prediction sits at 2 /rev, as near 1.98 as 2.02
    # but for round-off (one root up to its sign): the solver's sign is kept
    assert tef["frequency_tracked"].iloc[-1] == 1.98
    other = rows(t, "TEF (locked)")
    assert other["identity"].tolist() == ["start", "clear"] and other["track"].nunique() == 1
    path = follow_branch(t, pts, (0, 0))
    assert path["track"].eq(0).all() and path["certain"].all() and len(path) == 4
    # a branch on the more stable half ends its track where the lock ends and
    # goes on, by the convention, with the merged root: no doubt
    half = follow_branch(t, pts, (1, 1))
    assert half["track"].tolist() == [2, 2, 0] and half["certain"].all()


def test_a_shape_out_of_the_plane_leaves_the_exit_ambiguous():
    # the single root carries a large component outside the pair's plane
    # (plane MAC 0.43): the step did not resolve the exit
    shape = COMPLEX + 1.2 * E[3]
    assert plane_mac(np.stack([REAL_HI, REAL_LO], axis=1), shape) < 0.5
    pts = lock_sweep(after_shape=shape)
    t = track_modes(pts)
    last = t[(t["step"] == 3) & (t["label_here"] == "TEF")]
    assert last["identity"].tolist() == ["ambiguous"]
    # the branch goes on with that root, no longer certain
    path = follow_branch(t, pts, (0, 0))
    assert path["step"].tolist() == [0, 1, 2, 3]
    assert path["certain"].tolist() == [True, True, True, False]


class HandMade:
    """Picklable point function: point ``round(10 x)`` of :func:`lock_sweep`."""

    def __init__(self, after_shape):
        self.after_shape = after_shape

    def __call__(self, cfg):
        modes, vecs, periodic = lock_sweep(self.after_shape)[round(10 * cfg.flap.cg_offset)]
        return SimpleNamespace(modes=modes.assign(damping_ratio=0.1), vectors=vecs,
                               periodic=periodic, trim={})


def test_the_tef_role_is_certain_only_where_the_point_decided_its_name():
    # the TEF role is the row the point names TEF; it is certain where the
    # point's continuation decided that name (identity_certain), whatever the
    # tracking along the parameter says
    class Doubted(HandMade):
        def __call__(self, cfg):
            r = super().__call__(cfg)
            r.modes["identity_certain"] = cfg.flap.cg_offset < 0.25
            return r

    xs = [0.0, 0.1, 0.2, 0.3]
    res = sweep(MDART, PARAM, xs, point=Doubted(COMPLEX), progress=False, refine=False)
    branch = res.table[res.table["tef_branch"]].sort_values("value_si")
    assert branch["value_si"].tolist() == xs
    assert branch["tef_branch_certain"].tolist() == [True, True, True, False]
    res = sweep(MDART, PARAM, xs, point=HandMade(COMPLEX), progress=False, refine=False)
    assert res.table.loc[res.table["tef_branch"], "tef_branch_certain"].sum() == 4


def test_staying_in_a_lock_keeps_the_order_of_the_real_roots():
    # shapes turned 45 degrees in their plane: MAC 0.5 with either old shape,
    # so the ordinary match is undecided; the real parts decide (two real
    # multipliers cannot pass each other without leaving the lock)
    turned = ((REAL_HI + 0.8 * REAL_LO), (REAL_HI - 1.25 * REAL_LO))
    t = track_modes(lock_sweep(middle=turned))
    step2 = t[t["step"] == 2].set_index("track")
    assert step2.loc[0, "real_part"] == -0.46 and step2.loc[0, "identity"] == "coalescence"
    assert t[t["track"] == 0]["real_part"].tolist() == [-0.5, -0.45, -0.46, -0.5]


def test_a_branch_ends_only_where_no_root_continues_it():
    def p(*f):
        return pd.DataFrame({"mode_id": range(len(f)), "label": ["m"] * len(f),
                             "frequency_per_rev": f, "real_part": [-0.1] * len(f)})

    # the second point's only root clearly continues track 1: no candidate
    pts = [p(1.0, 2.0), p(1.0, 2.0), p(2.0)]
    t = track_modes(pts)
    assert t.loc[t["step"] == 2, "identity"].tolist() == ["clear"]
    assert follow_branch(t, pts, (0, 0))["step"].tolist() == [0, 1]
    with pytest.raises(ValueError, match="no row with step 0 and mode_id 5"):
        follow_branch(t, pts, (0, 5))


# ------------------------------------------------------------------ the pieces


def test_plane_mac_closed_forms_and_errors():
    pair = np.stack([REAL_HI, REAL_LO], axis=1)
    assert plane_mac(pair, COMPLEX) == pytest.approx(1.0, abs=1e-14)
    assert plane_mac(pair, E[3]) == pytest.approx(0.0, abs=1e-14)
    # |(1, 1)/sqrt 2 component|^2 of e1 + e3 over its norm: 1/2
    assert plane_mac(pair, E[0] + E[2]) == pytest.approx(0.5, abs=1e-14)
    # a pair parallel to round-off spans its line only, not an arbitrary plane
    line = np.stack([E[0], E[0] * (1 + 1e-13)], axis=1)
    assert plane_mac(line, E[0] + E[1]) == pytest.approx(0.5, abs=1e-12)
    with pytest.raises(ValueError, match="zero or non-finite"):
        plane_mac(pair, np.zeros(4))
    with pytest.raises(ValueError, match="shapes"):
        plane_mac(pair, np.ones(3))


def test_lock_detection():
    eig = np.array([-0.4 + 1j, -3 + 2.2j, -0.5 + 1j, -1 + 1.5j, -2 + 1.5j, -3 + 1.5j])
    assert is_locked(eig, 0, 2, True) and not is_locked(eig, 0, 2, False)
    assert not is_locked(eig, 0, 1, True)
    # three roots at 1.5 /rev: which two are one mode is not known
    assert locked_pairs(eig, True) == [(0, 2)]
    near = np.array([-1 + 7.0j, -1.1 + (7.0 + 3 * LOCK_TOL) * 1j])
    assert locked_pairs(near, True) == []


@pytest.mark.parametrize("overrides, label, frequency, real_part", [
    # a heavily damped root at a 1/2 /rev lock of an imbalanced, heavy flap: the
    # lift at K = 8 (chosen before solving) gives 0.4958 /rev, -7.5834 /rev; K = 4
    # and K = 16 agree on 0.49999, -7.59005 (the lifting must reach them, not
    # stop at K = 8)
    ({"flight.advance_ratio": 0.35, "flap.cg_offset": 0.4, "flap.mass": 0.6,
      "actuator.stiffness": "60 ft-lb/rad"}, "blade flap 4", 0.5, -7.59005),
    # the TEF root of an over-balanced flap at its 2 /rev lock: 2.0409, -7.0185 at
    # K = 8 against 2.000021, -6.98165 (K = 16)
    ({"flight.advance_ratio": 0.3, "flap.overhang": 0.45, "flap.cg_offset": 0.2}, "TEF",
     2.0, -6.98165),
])
def test_nearly_defective_locked_pair_gets_a_finer_lift(overrides, label, frequency,
                                                         real_part):
    # a locked pair is nearly defective: its lifted roots' condition numbers
    # (4e8 at K = 8) put their round-off far above the eps ||Z|| / |mu| the K
    # floor assumes, and step doubling cannot see round-off of the lift;
    # floquet_modes doubles K while a resolved root's first-order bound
    # eps ||Z|| kappa / |mu| exceeds LIFT_RTOL.  Gates: 1e-4 /rev in frequency and
    # 2e-3 /rev in real part, a tenth of what the K = 8 lift was off by, and
    # above the 2e-5 /rev by which the K = 16 results differ from K = 4
    from tefcore.linear.stability import stability

    # the root is the one carrying that coordinate (its participation label,
    # ``dominant``): what the lift resolves, whatever its name by continuation
    modes = stability(MDART.with_overrides(overrides)).modes
    row = modes[modes["dominant"] == label].iloc[0]
    assert abs(row["frequency_per_rev"] - frequency) < 1e-4
    assert abs(row["real_part"] - real_part) < 2e-3
