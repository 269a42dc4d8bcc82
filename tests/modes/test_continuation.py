"""Identity by continuation in the coupling (tefcore.modes.continuation), on known answers.

The coupling between the blade and the flap is scaled by ``eps`` from 0 to 1
(:func:`coupling_homotopy`); each root of the coupled system is named by the
uncoupled mode it continues from.  The cases:

* **Coalescence flutter of a typical section with a flap** (undamped, two
  modes, aerodynamic -- unsymmetric -- coupling ``eps a``, ``eps b`` with
  ``a b < 0``): ``lambda = (k1 + k2)/2 +- sqrt(((k1 - k2)/2)**2 + eps**2 a b)``
  coalesce at the exceptional point ``eps* = |k1 - k2| / (2 sqrt(-a b))``,
  beyond which one root flutters.  Continuation must meet it there, name
  both roots, and leave them uncertain; short of it, name them plainly.
* **A veering pair** (symmetric coupling ``eps g``): no exceptional point on
  real ``eps``; the flap's name goes to the lower root while its uncoupled
  frequency is the lower, to the upper when it is the upper -- the name moves
  across the veering gap with the uncoupled crossing, which is not an
  exceptional point.
* **A Floquet blade mode in a 1/2 /rev lock** (a Mathieu oscillator in its
  first tongue) beside the flap: the lock's two real-multiplier roots keep the
  blade's name (``X``, ``X (locked)``), the flap's root its own, decided.
* **MDART at mu = 0.3 against a fine march**: where a coarse step of the
  adaptive march was decided wrongly (a match by the row's next root, a flap
  path accepted with its shape lost), the names must equal those of a march
  in 256 equal steps, which 1024 steps do not change (measured).
"""

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from tefcore.config.io import load_config
from tefcore.floquet.second_order import SecondOrderSystem
from tefcore.modes.continuation import MIN_STEP, continue_roots, positive_roots
from tefcore.modes.matching import continuous_frequency
from tefcore.modes.roles import exceptional_points, name_roots
from tefcore.sweeps.sweep import sweep

LABELS = ["blade flap 1", "TEF"]


def _section(k1, k2, a, b, c=0.0):
    """``q'' + c q' + K q = 0`` with K = [[k1, a], [b, k2]] (constant coefficients)."""
    m = np.eye(2)[None]
    k = np.array([[[k1, a], [b, k2]]], float)
    return SecondOrderSystem(m, c * np.eye(2)[None], k)


# ------------------------------------------------------------------ coalescence


@pytest.mark.parametrize("k2", [6.0, 9.0, 11.0])
def test_typical_section_meets_its_exceptional_point_where_the_closed_form_puts_it(k2):
    """Coalescence flutter: the paths meet at eps* = |k1 - k2| / (2 sqrt(-a b))."""
    k1, a, b = 4.0, 4.0, -4.0                  # sqrt(-ab) = 4
    eps_star = abs(k1 - k2) / (2 * np.sqrt(-a * b))
    assert 0.0 < eps_star < 1.0
    out = continue_roots(_section(k1, k2, a, b), LABELS)
    assert len(out.meetings) == 1
    met = out.meetings.iloc[0]
    assert met["origins"] == "TEF / blade flap 1"
    # the step is halved down to MIN_STEP around the meeting: the recorded eps
    # is within two smallest steps of the exact coalescence (the undecided
    # step may end either side of it)
    assert abs(met["eps"] - eps_star) <= 2 * MIN_STEP
    # the two roots that met have no certain name, and both carry them
    assert sorted(out.origin) == ["TEF", "blade flap 1"]
    assert not out.certain.any()
    # a wrong model: no coupling -- nothing meets, both names certain
    plain = continue_roots(_section(k1, k2, 0.0, 0.0), LABELS)
    assert plain.meetings.empty and plain.certain.all()


def test_typical_section_short_of_its_exceptional_point_is_named_plainly():
    """eps* = 1.25 > 1: the coupled roots are still two frequencies; the flap is the upper."""
    k1, k2, a, b = 4.0, 14.0, 4.0, -4.0         # eps* = 10 / 8
    out = continue_roots(_section(k1, k2, a, b), LABELS)
    assert out.meetings.empty and out.certain.all()
    res = positive_roots(_section(k1, k2, a, b).modes())
    # closed form: lambda = 9 +- sqrt(25 - 16); frequencies sqrt(12), sqrt(6)
    assert np.allclose(np.sort(res.frequencies), np.sqrt([6.0, 12.0]), atol=1e-9)
    assert out.origin[int(np.argmax(res.frequencies))] == "TEF"


# ------------------------------------------------------------------ veering


class Veering:
    """Picklable point function: blade at 2 rad/rev, flap stiffness ``4 + 4 flap.cg_offset``,
    symmetric coupling ``g`` -- a veering pair as the flap passes the blade mode."""

    def __init__(self, g=0.4, c=0.04):
        self.g, self.c = g, c

    def __call__(self, cfg):
        k2 = 4.0 + 4.0 * cfg.flap.cg_offset
        system = _section(4.0, k2, self.g, self.g, self.c)
        res = positive_roots(system.modes())
        cont = continue_roots(system, LABELS, res)
        eta = res.exponents
        modes = pd.DataFrame({"mode_id": range(eta.size), "label": cont.origin,
                              "frequency_per_rev": eta.imag, "real_part": eta.real,
                              "damping_ratio": -eta.real / np.abs(eta)})
        modes = name_roots(modes, cont)
        return SimpleNamespace(modes=modes, vectors=res.eigenvectors[:2], periodic=False,
                               trim={})


def test_veering_pair_moves_the_flap_name_across_the_gap_without_an_exceptional_point():
    # not through x = 0 itself: there the uncoupled pair is degenerate (a
    # diabolic point at eps = 0) and no name is certain -- rightly
    xs = [float(x) for x in np.linspace(-0.45, 0.55, 11)]
    res = sweep(load_config("mdart"), "flap.cg_offset", xs, point=Veering(), progress=False,
                refine=False)
    t = res.table
    tef = t[t["label"] == "TEF"].sort_values("value_si")
    blade = t[t["label"] == "blade flap 1"].sort_values("value_si")
    assert len(tef) == len(xs) == len(blade)
    assert tef["identity_certain"].all() and blade["identity_certain"].all()
    below = tef["value_si"] < 0          # uncoupled flap frequency below the blade's (2)
    f_tef, f_blade = tef["frequency_per_rev"].to_numpy(), blade["frequency_per_rev"].to_numpy()
    assert (f_tef[below.to_numpy()] < f_blade[below.to_numpy()]).all()
    assert (f_tef[~below.to_numpy()] > f_blade[~below.to_numpy()]).all()
    # the coupled pair never coalesces: the gap at the crossing is the
    # veering's (2 g / (2 * 2) = 0.2 rad/rev in frequency, closed form to
    # first order; 0.19 with the damping), not zero
    gap = np.min(np.abs(f_tef - f_blade))
    assert 0.15 < gap < 0.25
    # the name moved across the gap: along the lower curve the names
    # exchanged at the uncoupled crossing -- which is not an exceptional point
    assert exceptional_points(t[t["status"] == "ok"], x="value_si").empty


def test_an_exchange_away_from_an_uncoupled_crossing_is_an_exceptional_point():
    """The same exchange with the uncoupled frequencies kept in order is reported."""
    rows = []
    for x, names in [(0.0, ["blade flap 1", "TEF"]), (1.0, ["TEF", "blade flap 1"])]:
        for track, name in enumerate(names):
            rows.append({"x": x, "track": track, "label": name, "identity_certain": True,
                         "flap_motion": 0.5,
                         "frequency_uncoupled": 3.0 if name == "TEF" else 2.0})
    ep = exceptional_points(pd.DataFrame(rows))
    assert ep["modes"].tolist() == ["TEF / blade flap 1"]
    assert ep[["x_low", "x_high"]].to_numpy().tolist() == [[0.0, 1.0]]
    # the uncoupled pair changing order between the points: no exceptional point
    for r in rows:
        if r["x"] == 1.0:
            r["frequency_uncoupled"] = 5.0 - r["frequency_uncoupled"]
    assert exceptional_points(pd.DataFrame(rows)).empty


def _exchange_rows(certain_at_1=(True, True), crossed=False, by_path_at_0=(True, True),
                   motion=0.5):
    """The TEF and blade flap 3 exchange tracks between x = 0 and 1; at x = 1 the
    two names' certainty as given, at x = 0 whether each name is its path's
    (``named_by_path``); the uncoupled frequencies keep their order unless
    `crossed`; blade flap 3's roots move the flap by `motion`."""
    rows = []
    for x, names in [(0.0, ["blade flap 3", "TEF"]), (1.0, ["TEF", "blade flap 3"])]:
        for track, name in enumerate(names):
            sure = True if x == 0.0 else certain_at_1[name == "TEF"]
            own = by_path_at_0[name == "TEF"] if x == 0.0 else True
            f = 3.0 if name == "TEF" else 2.0
            if crossed and x == 1.0:
                f = 5.0 - f
            rows.append({"x": x, "track": track, "label": name, "identity_certain": sure,
                         "flap_motion": 0.5 if name == "TEF" else motion,
                         "frequency_uncoupled": f, "named_by_path": own})
    return pd.DataFrame(rows)


def test_paths_that_met_are_an_exceptional_point_not_an_undecided_step():
    """Where two paths met (a coalescence located on the way from zero coupling)
    both names are undecided at that point; the names' move into it is that
    exceptional point ('paths meet'), not listed again as undecided (the same
    pair must not print under both)."""
    from tefcore.modes.roles import undecided_steps

    table = _exchange_rows((False, False))
    at_1 = table["x"] == 1.0
    table["meets"] = ""
    table.loc[at_1, "meets"] = np.where(table.loc[at_1, "label"] == "TEF", "blade flap 3", "TEF")
    assert exceptional_points(table)["kind"].tolist() == ["paths meet"]
    assert undecided_steps(table).empty


@pytest.mark.parametrize("certain_at_1, crossed, by_path_at_0, motion, kind", [
    ((True, True), False, (True, True), 0.5, "names exchange"),  # decided both sides: an EP
    ((True, False), False, (True, True), 0.5, "identity undecided"),  # the TEF undecided at 1
    ((False, True), False, (True, True), 0.5, "identity undecided"),  # flap 3 undecided
    ((True, False), True, (True, True), 0.5, None),  # the uncoupled modes crossed: no jump
    # blade flap 3's name at x = 0 given by participation (its root's path was
    # another's): the paths did not exchange, so no exceptional point
    ((True, True), False, (False, True), 0.5, "identity undecided"),
    # decided on both sides, but blade flap 3's roots do not move the flap
    # (Fig. 12's balanced flap: flap 5 and torsion 2, 2e-3 to 5e-3): not an
    # exceptional point of the coupling, a move of names by participation --
    # listed, not silent
    ((True, True), False, (True, True), 3e-3, "named by participation"),
])
def test_a_name_that_moves_is_an_exceptional_point_or_an_undecided_step(
        certain_at_1, crossed, by_path_at_0, motion, kind):
    """A label moves to another track in one of four ways, and is never silent:
    through an exceptional point (both names decided by their paths:
    :func:`exceptional_points`), with a name undecided on a side or given by
    participation, or two decided names of roots the flap does not move
    exchanged (:func:`undecided_steps`: not an EP, since no coalescence was
    located, but the jump is listed), or with the uncoupled modes changing
    places (the names follow them: neither)."""
    from tefcore.modes.roles import undecided_steps

    table = _exchange_rows(certain_at_1, crossed, by_path_at_0, motion)
    ep, moved = exceptional_points(table), undecided_steps(table)
    assert (ep["kind"].tolist() + moved["kind"].tolist()) == ([kind] if kind else [])
    for found in (ep, moved):
        if len(found):
            assert found[["modes", "x_low", "x_high"]].values.tolist() == [
                ["TEF / blade flap 3", 0.0, 1.0]]


def _lock_rows(at_0, at_1):
    """Three tracks at x = 0 and 1 carrying the names given; track 0's name
    undecided at x = 0, every other decided; all roots move the flap."""
    return pd.DataFrame([
        {"x": x, "track": k, "label": n, "identity_certain": not (x == 0.0 and k == 0),
         "named_by_path": True, "flap_motion": 0.5,
         "frequency_uncoupled": 11.3 if "torsion" in n else 2.7}
        for x, names in ((0.0, at_0), (1.0, at_1)) for k, n in enumerate(names)])


def test_a_move_is_judged_on_the_track_s_own_rows_beside_a_lock():
    """Where the moving name is also a lock's second root at a point ("X" and "X
    (locked)"), the move is judged on the row of the track that moves, not on
    whichever row of the name came last (Fig. 12 at 186.5 ft-lb/rad: blade
    torsion 2's undecided root moves to blade flap 3; judged on its decided
    locked partner, it would be neither an exceptional point nor listed)."""
    from tefcore.modes.roles import undecided_steps

    table = _lock_rows(["blade torsion 2", "blade torsion 2 (locked)", "blade flap 3"],
                       ["blade flap 3", "blade torsion 2 (locked)", "blade torsion 2"])
    moved = undecided_steps(table)
    assert moved[["modes", "x_low", "x_high", "kind"]].values.tolist() == [
        ["blade flap 3 / blade torsion 2", 0.0, 1.0, "identity undecided"]]
    assert exceptional_points(table).empty
    # the lock's second root is the one that moves, its plain partner stays on
    # its track: both tracks of the exchange judge it on the same rows (read
    # from the plain torsion 2 of the track that never moved, decided, the flap
    # 3 track would call the same step an exceptional point)
    table = _lock_rows(["blade torsion 2 (locked)", "blade torsion 2", "blade flap 3"],
                       ["blade flap 3", "blade torsion 2", "blade torsion 2 (locked)"])
    assert undecided_steps(table)["kind"].tolist() == ["identity undecided"]
    assert exceptional_points(table).empty


# ------------------------------------------------------------------ Floquet lock


def _mathieu_with_flap(delta, eps_m=0.3, g=0.3, n_psi=64):
    """Blade: Mathieu oscillator ``delta + eps_m cos psi`` (1/2 /rev lock for delta ~ 1/4);
    flap at 3.3 /rev; coupled by ``g`` (stiffness)."""
    psi = np.linspace(0, 2 * np.pi, n_psi, endpoint=False)
    k = np.zeros((n_psi, 2, 2))
    k[:, 0, 0] = delta + eps_m * np.cos(psi)
    k[:, 1, 1] = 3.3 ** 2
    k[:, 0, 1] = k[:, 1, 0] = g
    m = np.broadcast_to(np.eye(2), (n_psi, 2, 2)).copy()
    c = np.broadcast_to(np.diag([0.04, 0.3]), (n_psi, 2, 2)).copy()
    return SecondOrderSystem(m, c, k)


def test_floquet_lock_keeps_the_blade_name_and_the_flap_root_is_decided():
    system = _mathieu_with_flap(0.25)
    res = positive_roots(system.modes(shapes=True))
    out = continue_roots(system, LABELS, res)
    names = dict(zip(out.origin, res.exponents, strict=True))
    assert sorted(names) == ["TEF", "blade flap 1", "blade flap 1 (locked)"]
    # the lock: both blade roots at 1/2 /rev (modulo 1), real multipliers
    for n in ("blade flap 1", "blade flap 1 (locked)"):
        f = names[n].imag % 1.0
        assert min(abs(f - 0.5), abs(f + 0.5 - 1.0)) < 1e-6
    # the plain name to the less stable of the pair
    assert names["blade flap 1"].real > names["blade flap 1 (locked)"].real
    tef = out.origin.index("TEF")
    assert out.certain[tef] and out.meetings.empty
    # the flap root stays near its uncoupled self: 3.3 /rev (modulo 1 and sign),
    # damping -0.15 /rev, moved by the weak coupling by less than 0.05
    f = res.exponents[tef].imag
    assert min(abs(((s * f) - 3.3 + 0.5) % 1.0 - 0.5) for s in (1, -1)) < 0.05
    assert abs(res.exponents[tef].real + 0.15) < 0.05


# ------------------------------------------------------------------ unwrapping


def test_continuous_frequency_recovers_a_falling_curve_from_its_floquet_convention():
    """Known answer: a frequency falling 1.3 /rev per step from 21.77 (the overhang-0.1
    TEF of Fig. 9), written by the convention as mirror images ``k - f`` at some
    points and shifted by 1/rev at others; in any order of the points."""
    x = np.linspace(0.0, 0.4, 11)
    true = 21.77 - 31.1 * x
    seen = true.copy()
    seen[[3, 4]] = 43.0 - seen[[3, 4]]
    seen[6] += 1.0
    seen[8] = 35.0 - seen[8]
    assert np.allclose(continuous_frequency(x, seen), true)
    order = np.random.default_rng(0).permutation(x.size)
    assert np.allclose(continuous_frequency(x[order], seen[order]), true[order])
    # a wrong model: the curve as seen is not monotonic, the recovered one is
    assert np.any(np.diff(seen) > 0) and np.all(np.diff(continuous_frequency(x, seen)) < 0)


def test_the_tef_frequency_of_a_real_sweep_falls_without_shifts_or_mirrors():
    """Fig. 9 at overhang 0.1 (mu 0.3).  The flap's uncoupled
    frequency falls with the CG offset, so the TEF's does too: 21.77 -> 9.32 /rev
    (measured).  Without continuation the tracked frequency *rises* to 33.68 (the
    mirror of the root, shifted) and the point values jump by 1 /rev; a wrong
    unwrapping or a TEF name on another root breaks the monotonic fall."""
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig9").with_overrides({"flap.overhang": 0.1})
    xs = [float(x) for x in np.round(np.linspace(0.0, 0.4, 11), 2)]
    t = sweep(cfg, "flap.cg_offset", xs, progress=False, refine=False).table
    tef = t[t["tef_branch"]].sort_values("value_si")
    assert len(tef) == len(xs)
    f = tef["frequency_tracked"].to_numpy()
    assert np.all(np.diff(f) < 0)
    # the ends, where the flap alone decides (0.05 /rev: the Floquet exponents'
    # tolerance is 1e-3; the configuration's, not the unwrapping's, numbers)
    assert abs(f[0] - 21.77) < 0.05 and abs(f[-1] - 9.32) < 0.05
    # the point values keep the Floquet convention: within 1/2 /rev of the
    # continuous curve at a k/2 lock's mirror image, never a whole /rev off
    assert np.all(np.abs(tef["frequency_per_rev"].to_numpy() - f) < 0.5)


def test_a_root_that_does_not_move_the_flap_keeps_its_own_coordinate():
    """mdart-fig6 (the flap system fitted to Fig. 6), Fig. 14's flap of 0.22 R:
    the blade torsion 1 root (3.63 /rev, -0.78 /rev; torsion 1 coordinate 0.41,
    flap 3 0.35) moves the flap by less than FLAP_ACTIVE, but the assignment
    over all roots had given torsion 1 to the TEF root, so it was named blade
    flap 3, torsion 1's track ended at 0.20 R and the flap 3 root (6.29 /rev)
    took 'blade flap 4 (locked)' beside the flutter root's 'blade flap 4'
    (measured).  The names must run on from 0.20 R, each given once."""
    from tefcore.linear.stability import stability
    from tefcore.paper.figures.catalogue import figure_config

    base = figure_config("fig14", load_config("mdart-fig6"))
    named = {}
    for span in (0.20, 0.22):
        m = stability(base.with_overrides({"flap.span": span})).modes
        named[span] = dict(zip(m["label"], zip(m["frequency_per_rev"], m["real_part"],
                                               strict=True), strict=True))
        assert m["label"].is_unique
        assert not any(x.endswith("(locked)") for x in m["label"] if "flap 1" not in x)
    for name, (f, r) in named[0.20].items():
        # a name follows its root: a 10 % longer flap moves each root by at most
        # 0.33 /rev in frequency and 0.32 /rev in real part here (the TEF's,
        # measured); the wrong names sat on roots 2.5 /rev away (flap 3 named
        # on the root at 3.63 /rev, it was at 6.09) or were missing
        assert name in named[0.22], name
        f2, r2 = named[0.22][name]
        assert abs(f2 - f) < 0.5 and abs(r2 - r) < 0.5, name


def _named(cfg, first_steps=None, monkeypatch=None):
    from tefcore.linear.stability import stability
    if first_steps is not None:
        monkeypatch.setitem(continue_roots.__kwdefaults__, "first_steps", first_steps)
    m = stability(cfg).modes
    if first_steps is not None:
        monkeypatch.undo()
    return m


@pytest.mark.parametrize(("figure", "field", "value", "tef"), [
    # the TEF path's row had a flap-free root next while its exchange was with
    # blade torsion 2's: the step to eps = 1 was taken at 1 - MAC 0.93 and the
    # TEF named the 11.6 /rev root
    ("fig14", "flap.span", 0.0775, (15.20, -0.477)),
    # the TEF path's match at the step to eps = 1 had MAC 0.00, its exchange
    # rival a flap-free root (blade torsion 1): with the rival taken from the
    # exchange but a lost shape not refined, the step was taken and the TEF
    # named on the root at 12.5 /rev, -1.57 /rev (measured)
    ("fig15", "flap.chord_ratio", 0.1875, (22.42, -0.34)),
])
def test_the_adaptive_march_names_the_roots_as_a_fine_march_does(figure, field, value, tef,
                                                                 monkeypatch):
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config(figure).with_overrides({field: value})
    coarse = _named(cfg)
    fine = _named(cfg, 256, monkeypatch)
    assert coarse["label"].tolist() == fine["label"].tolist()
    row = coarse[coarse["label"] == "TEF"].iloc[0]
    # the point's own roots to 0.01 /rev (printed to two places when measured)
    assert abs(row["frequency_per_rev"] - tef[0]) < 0.01
    assert abs(row["real_part"] - tef[1]) < 0.01


def test_a_root_that_does_not_move_the_flap_is_never_the_flap_mode():
    """Fig. 12 (mu 0.3) at an actuator stiffness of 56 ft-lb/rad: the flap's
    own root is a locked pair at 5 /rev (-5.6 and -5.3 /rev) that the one-to-one
    participation labels gave 'TEF (locked)' and 'blade flap 4 (locked)',
    leaving 'TEF' to the second real root of blade flap 1's lock at 1 /rev
    (flap motion 1e-4), which kept it as a root that does not move the flap
    (measured).  The flap mode is the pair that moves the flap.  Which of the
    pair's two roots is named what round-off decides: with OpenBLAS's SkylakeX
    kernels the march decides both ('TEF', 'TEF (locked)'); with its Haswell
    kernels (pinned by tefcore.runtime) it leaves both undecided and names the
    second 'blade flap 4 (locked)' -- both roots move the flap, 0.49 of their
    motion (measured).  Either way the TEF is the pair's."""
    from tefcore.linear.stability import stability
    from tefcore.modes.continuation import FLAP_ACTIVE
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig12").with_overrides(
        {"actuator.stiffness": "75.98681691423332 N*m/rad"})
    res = stability(cfg)
    m = res.modes
    motion = res.identity.flap_motion
    labels = m["label"].to_numpy()
    tef = np.flatnonzero([x.startswith("TEF") for x in labels])
    assert tef.size >= 1
    assert np.all(motion[tef] >= FLAP_ACTIVE)
    assert np.all(np.round(m["frequency_per_rev"].to_numpy()[tef], 6) == 5.0)
    # the root that took 'TEF' before: flap 1's lock at 1 /rev, which does not move the flap
    lock = np.flatnonzero(labels == "blade flap 1 (locked)")
    assert lock.size == 1 and motion[lock[0]] < FLAP_ACTIVE


def test_continuous_frequency_puts_back_a_stretch_written_one_per_rev_off():
    """Measured case: Fig. 14's TEF (mu 0.3, flap length 0.165-0.19 R), the
    point's own convention (its dominant harmonic) 1/rev up at three points
    running, 0.175-0.18 R.  A Floquet frequency is continuous along a root;
    the known answer is the curve with those three shifted down, which falls
    smoothly (steps -0.09 to -0.23 /rev).  The rule that priced each point
    written otherwise kept the stretch (jumps +0.77 and -1.11 /rev)."""
    x = 0.165 + 0.0025 * np.arange(11)
    own = np.array([7.834818, 7.726080, 7.604256, 7.442463, 8.208709, 8.021819, 7.893596,
                    6.786041, 6.686840, 6.591755, 6.5])
    true = own.copy()
    true[4:7] -= 1.0
    got = continuous_frequency(x, own)
    np.testing.assert_allclose(got, true, atol=1e-9)
    assert np.all(np.diff(got) < 0)
    # a stretch of two points is put back; with six of the eleven 1/rev up the
    # curve is the same one, written as most of its points write it (1/rev up
    # everywhere); the whole curve 1/rev off stays as its points write it
    seen = true.copy()
    seen[4:6] += 1.0
    np.testing.assert_allclose(continuous_frequency(x, seen), true, atol=1e-9)
    seen = true.copy()
    seen[2:8] += 1.0
    np.testing.assert_allclose(continuous_frequency(x, seen), true + 1.0, atol=1e-9)
    np.testing.assert_allclose(continuous_frequency(x, true + 1.0), true + 1.0, atol=1e-9)
    # in any order
    order = np.random.default_rng(1).permutation(x.size)
    np.testing.assert_allclose(continuous_frequency(x[order], own[order]), true[order],
                               atol=1e-9)


def test_continuous_frequency_takes_the_carried_curve_where_the_convention_changes_for_good():
    """Measured case: Fig. 16b's blade torsion 2 (mu 0.3, collective 0-7.5 deg):
    its dominant harmonic 12.07, 12.08, 12.11 at the first three points and
    11.14-11.16 from the fourth on, the frequency as continuation carried it
    11.07-11.16 throughout (the same roots: whole /rev apart).  A Floquet
    frequency is continuous along a root: the known answer is the carried
    curve.  Without it the curve is continuous too, a whole number of /rev
    from it (the for-good change, 3 points on one side and 5 on the other, is
    not kept as a jump of 0.97 /rev, as an anchor pricing each point written
    otherwise would keep it)."""
    x = np.array([0.0, 0.034907, 0.069813, 0.10472, 0.122173, 0.126536, 0.128718, 0.129809])
    own = np.array([12.07097, 12.083995, 12.10925, 11.13705, 11.149683, 11.152629, 11.154067,
                    11.154778])
    carried = own.copy()
    carried[:3] -= 1.0
    np.testing.assert_allclose(continuous_frequency(x, own, carried=carried), carried,
                               atol=1e-9)
    alone = continuous_frequency(x, own)
    assert np.ptp(np.diff(alone)) < 0.05                               # no jump left
    shift = alone - carried
    assert np.allclose(shift, np.round(shift[0]), atol=1e-9)
    # only an option: a carried mirror image at one point (a path that passed
    # near a lock) is not taken where the neighbours say otherwise
    true = 21.77 - 31.1 * np.linspace(0.0, 0.4, 11)
    odd = np.full(11, np.nan)
    odd[7] = 30.0 - true[7]
    np.testing.assert_allclose(continuous_frequency(np.linspace(0.0, 0.4, 11), true,
                                                    carried=odd), true, atol=1e-9)


def test_the_carried_frequency_is_the_same_root_continued_across_a_harmonic_switch():
    """Fig. 14 (mu 0.3), flap length 0.125 and 0.1275 R: the TEF's dominant
    harmonic drops from 10.68 to 9.55 /rev between the two (measured) while
    the root moves 0.13 /rev.  ``frequency_continued`` is a representation of
    the root's own exponent (a whole number of /rev from ``frequency_per_rev``,
    to round-off) and continuous across the switch (within 0.2 /rev: the
    neighbours' steps are 0.13)."""
    from tefcore.linear.stability import stability
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig14")
    rows = []
    for span in (0.125, 0.1275):
        t = stability(cfg.with_overrides({"flap.span": span})).modes
        rows.append(t[t["label"] == "TEF"].iloc[0])
    own = np.array([r["frequency_per_rev"] for r in rows])
    carried = np.array([r["frequency_continued"] for r in rows])
    shift = carried - own
    assert np.allclose(shift, np.round(shift), atol=1e-6)
    assert abs(own[1] - own[0]) > 1.0 and abs(carried[1] - carried[0]) < 0.2


def test_continuous_frequency_keeps_a_locked_stretch_beside_where_it_unlocks():
    """Measured case: Fig. 12's TEF (mu 0.3, imbalanced flap), actuator stiffness
    55-97 N m/rad: locked (two real multipliers, frequency at k/2, written 4.0
    to 5.5 /rev) up to 69 N m/rad, unlocking at 4.80 /rev and rising to 6.27.
    At a lock the mirror image and the shifts are the same numbers, so the
    lock's points are as continuous at 4.5-5.0 as anywhere; they must stay
    within 1/2 /rev of 4.80 where the root unlocks (a rule pricing offsets
    next to a lock wrote them 6.5-7.0 through the mirror image 11 - f, and the
    curve fell 2 /rev at 72.5)."""
    x = np.array([55.2631, 56.1266, 56.9901, 58.7171, 62.171, 65.625, 69.0789, 72.5329,
                  75.9868, 82.8947, 96.7105])
    own = np.array([4.5, 4.5, 4.0, 5.0, 5.0, 4.5, 5.5, 4.80127724, 5.0, 5.5, 6.26508076])
    got = continuous_frequency(x, own)
    assert np.all(np.abs(got[:7] - 4.80127724) <= 0.5 + 1e-9)
    np.testing.assert_allclose(got[7:], own[7:], atol=1e-9)     # unlocked: as written


def test_continuous_frequency_takes_a_repeated_parameter_value_without_a_jump():
    # two rows of one name at one value (a lock's two roots, once, before the
    # names were made unique) made every step through them infinitely curved,
    # and the whole curve came out shifted by 3 /rev (measured: [2, 2.1, ...])
    x = np.array([0.0, 1.0, 1.0, 2.0, 3.0])
    true = np.array([5.0, 5.1, 5.2, 5.3, 5.4])
    seen = true.copy()
    seen[2] = 11.0 - seen[2]                   # the mirror, 1/rev shifted
    np.testing.assert_allclose(continuous_frequency(x, seen), true, atol=1e-9)



# Fig. 9's TEF (mu 0.3, overhang 0.29) as notebook 04's refined sweep computes it
# (stored): c_cg/c_f, the dominant-harmonic convention and the frequency the
# continuation in eps carried, at 60 points 0.005-0.04 apart
_FIG9_X = np.array([
    0, 0.005, 0.01, 0.015, 0.02, 0.04, 0.045, 0.05, 0.055, 0.06, 0.08, 0.085, 0.0875, 0.08875,
    0.09, 0.095, 0.1, 0.11, 0.115, 0.12, 0.125, 0.13, 0.14, 0.16, 0.17, 0.18, 0.185, 0.19, 0.195,
    0.2, 0.205, 0.21, 0.215, 0.22, 0.23, 0.235, 0.2375, 0.23875, 0.24, 0.25, 0.26, 0.28, 0.285,
    0.28625, 0.2875, 0.29, 0.3, 0.32, 0.325, 0.32625, 0.326562, 0.326875, 0.3275, 0.33, 0.345,
    0.36, 0.37, 0.38, 0.39, 0.4])
_FIG9_OWN = np.array([
    18.281098, 18.130302, 17.971648, 17.804812, 17.629407, 16.832059, 16.606223, 16.369626,
    16.123671, 15.871242, 13.870020, 13.634197, 13.519134, 13.462263, 13.405791, 13.182919,
    12.961386, 13.499250, 13.262836, 13.043404, 12.846419, 12.667335, 12.345430, 11.801398,
    11.563880, 11.330542, 11.212278, 11.092781, 10.972439, 10.851733, 10.731111, 10.610944,
    10.491523, 10.373067, 9.139665, 9.024924, 8.968073, 8.939780, 8.911577, 8.689198, 8.472621,
    8.055805, 7.954507, 7.929325, 7.904193, 7.854067, 7.654733, 7.250528, 7.145160, 7.118445,
    7.111744, 7.105034, 7.091588, 7.037474, 6.713543, 6.424244, 6.254969, 6.099446, 5.958580,
    5.820013])
# the carried frequency is the same root a whole number of /rev up (to 1e-15):
# the path from zero coupling wound 1-5 /rev above the convention at some points
_FIG9_CARRIED = _FIG9_OWN + np.array([
    0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 5, 5, 5, 5, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 1, 2, 2, 1, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0])


def test_continuous_frequency_joins_fig9s_tef_across_its_harmonic_switches():
    """Known answer, the paper's Fig. 9a: the TEF's frequency falls with the CG
    offset (the flap's inertia grows, the actuator stays).  Its dominant harmonic
    is 1/rev below the falling curve at 0.08-0.10 and from 0.23 on (the steps
    there are -2.0 over 0.02 and -1.23 over 0.01 where the neighbouring steps
    give -1.0 and -0.24).  The continuous curve is the convention 1/rev up
    there and falls at every step, in any order of the points.  Measuring the
    change of slope over the mean of its two steps, and without the stitching,
    three whole-/rev steps stay (13.87 at 0.08, 12.96 -> 13.50 at 0.10 -> 0.11,
    10.37 -> 9.14 at 0.22 -> 0.23): a 1/rev jump over a 0.02 step between 0.005
    steps costs a quarter of what it costs on a uniform grid, and a convention
    changed for good on long sides stays a jump (docs/theory.md 9.4)."""
    up = ((_FIG9_X >= 0.08) & (_FIG9_X <= 0.1)) | (_FIG9_X >= 0.23)
    true = _FIG9_OWN + up
    got = continuous_frequency(_FIG9_X, _FIG9_OWN, carried=_FIG9_CARRIED)
    # the whole curve may be written a whole number of /rev off (a constant
    # offset changes no slope); its shape is the known one
    offset = got[0] - true[0]
    assert offset == pytest.approx(round(offset), abs=1e-9)
    np.testing.assert_allclose(got - offset, true, atol=1e-9)
    assert np.all(np.diff(got) < 0)
    order = np.random.default_rng(2).permutation(_FIG9_X.size)
    np.testing.assert_allclose(continuous_frequency(_FIG9_X[order], _FIG9_OWN[order],
                                                    carried=_FIG9_CARRIED[order]),
                               got[order], atol=1e-9)


def test_continuous_frequency_joins_a_convention_changed_for_good_on_long_sides():
    """A frequency falling from 10.3 to 10.05 /rev over 21 points whose dominant
    harmonic drops by 1/rev for good at the eleventh (10 points on each side):
    one root, so one continuous curve -- not a jump kept because either side is
    long."""
    x = np.linspace(0.0, 1.0, 21)
    true = 10.3 - 0.25 * x
    own = true - (x > 0.5)
    got = continuous_frequency(x, own)
    np.testing.assert_allclose(np.diff(got), np.diff(true), atol=1e-9)
    assert got[0] - true[0] == pytest.approx(round(got[0] - true[0]), abs=1e-9)
    # the check of the invariant below finds the jump as written, none after
    assert _whole_steps(x, own) == [10] and _whole_steps(x, got) == []


def _resolved_curve(band, where, total, bend, falling, n, gaps, switches):
    """A frequency moving ``total`` /rev over `n` points inside one half-/rev band
    (a complex root's frequency does not cross ``k/2`` without locking: there
    its conjugate meets it), on a grid whose steps are `gaps` (relative sizes, as
    a refined sweep's), and the same written with its dominant harmonic
    switching by whole /rev from each ``(x, k)`` of `switches` on."""
    g = np.asarray(gaps[:n - 1], float)
    x = np.concatenate([[0.0], np.cumsum(g)]) / g.sum()
    w = (1.0 + bend * (x[1:] + x[:-1] - 1.0)) * g
    steps = total * w / w.sum() * (-1 if falling else 1)
    start = band / 2 + 0.04 + where * (0.42 - total) + (total if falling else 0.0)
    true = start + np.concatenate([[0.0], np.cumsum(steps)])
    own = true.copy()
    for at, k in switches:
        own[x >= at] += k
    return x, true, own


# steps from even to four times their neighbours (a refined sweep's 0.005-0.02)
_CURVES = dict(band=st.integers(4, 40), where=st.floats(0.0, 1.0), total=st.floats(0.1, 0.38),
               bend=st.floats(-0.5, 0.5), falling=st.booleans(), n=st.integers(12, 40),
               gaps=st.lists(st.floats(1.0, 4.0), min_size=39, max_size=39))


@settings(max_examples=80, deadline=None, derandomize=True)
@given(**_CURVES, switch=st.tuples(st.floats(0.05, 0.95), st.sampled_from([-2, -1, 1, 2])))
def test_continuous_frequency_recovers_a_curve_whose_harmonic_switches_once(switch, **curve):
    """Invariant: a resolved frequency (steps under 0.04 /rev) whose dominant
    harmonic switches by one or two /rev for good anywhere along it comes back
    as the same curve up to one whole offset -- every step the true one.
    (Measured: 4000 such curves, none missed.)"""
    x, true, own = _resolved_curve(**curve, switches=[switch])
    got = continuous_frequency(x, own)
    np.testing.assert_allclose(np.diff(got), np.diff(true), atol=1e-9)


def _whole_steps(x, f):
    """Steps of `f` that depart from both resolved neighbours' slope by a whole /rev."""
    h, d = np.diff(x), np.diff(f)
    out = []
    for i in range(1, d.size - 1):
        sides = [d[j] / h[j] for j in (i - 1, i + 1) if abs(d[j]) < 0.5]
        r = d[i] - np.mean(sides) * h[i] if len(sides) == 2 else 0.0
        if round(r) != 0 and abs(r - round(r)) <= 0.25 and np.ptp(sides) * h[i] < 0.25:
            out.append(i)
    return out


@settings(max_examples=80, deadline=None, derandomize=True)
@given(**_CURVES, switches=st.lists(st.tuples(st.floats(0.05, 0.95),
                                              st.sampled_from([-2, -1, 1, 2])), max_size=3))
def test_continuous_frequency_leaves_no_whole_per_rev_step(switches, **curve):
    """Invariant: with up to three switches, anywhere (even at one point), no step
    of the curve is left a whole /rev off its resolved neighbours (measured:
    one in 12,000 such curves).  Not exact: where switches come close the
    curve may come back otherwise than the truth in a stretch between them
    (measured: about 1 % of them), almost never with a whole-/rev step."""
    x, true, own = _resolved_curve(**curve, switches=switches)
    assume(np.all(np.abs(own - true) <= 2))
    assert _whole_steps(x, continuous_frequency(x, own)) == []


def test_continuous_frequency_leaves_a_rapid_change_and_a_repeated_value():
    """Wrong-model checks of the joins.  A real rapid change (two steps of -0.4 /rev
    between steps of +0.1, each point written by its own convention) is not a
    jump spread over two steps: it stays (an earlier version of the join took
    it for one and wrote the point between as its mirror image).  A second row at
    one parameter value follows its twin wherever the joined curve lies (four
    switches move this one 4 /rev from the first point's convention; the twin
    was left 1/rev off)."""
    seen = np.array([10.13, 10.23, 9.83, 9.43, 9.53, 9.63, 9.73])
    np.testing.assert_allclose(continuous_frequency(np.arange(7.0), seen), seen, atol=1e-9)
    x = np.arange(21.0)
    own = 10.33 - 0.05 * x
    for at in (4, 8, 12, 16):
        own[at:] += 1.0
    got = continuous_frequency(np.insert(x, 1, 0.0), np.insert(own, 1, own[0]))
    assert got[0] == pytest.approx(got[1], abs=1e-9)
    np.testing.assert_allclose(np.diff(got[1:]), -0.05, atol=1e-9)


def test_continuous_frequency_writes_the_joined_curve_as_most_of_the_range_does():
    """The whole offset of a joined curve: 10 points over 80 % of the range in one
    convention, 12 refined points over the last 20 % 1/rev up (a cluster at an
    exceptional point must not outvote the rest).  The curve is written as the
    10 are -- also where the dynamic programming joins it itself, without a
    step to stitch (an earlier version wrote it as the 12, by their count)."""
    x = np.r_[np.linspace(0.0, 0.8, 10), 0.8 + np.linspace(0.02, 0.2, 12)]
    own = 10.33 - 0.5 * x + (x > 0.8)
    np.testing.assert_allclose(continuous_frequency(x, own), 10.33 - 0.5 * x, atol=1e-9)


def test_the_second_roots_of_two_locks_are_named_once_each():
    """Fig. 12 at 41.4 ft-lb/rad (56.13 N m/rad): the flap's heavily damped mode
    is a pair of real multipliers on the negative axis (3.5 and 4.5 /rev by
    their dominant harmonics, -6.2 and -5.4 /rev) whose path ended where it
    locked, beside blade flap 1's lock at 1 /rev.  The fallback labels had
    named both roots at 1 /rev and the flap's second root 'blade flap 1
    (locked)' (measured); each name is given once, the flap's pair TEF."""
    from tefcore.linear.stability import stability
    from tefcore.paper.figures.catalogue import figure_config

    m = stability(figure_config("fig12").with_overrides(
        {"actuator.stiffness": "56.12662612983142 N*m/rad"})).modes
    assert m["label"].is_unique
    f = dict(zip(m["label"], m["frequency_per_rev"].to_numpy(), strict=True))

    def off(name, target):
        # distance modulo 1/rev: a root at k /rev can read k - 1e-14 (measured
        # with numpy 2.4.6, scipy 1.17.1), which `% 1` puts at 1, not 0
        return abs((f[name] - target + 0.5) % 1.0 - 0.5)

    # a locked pair sits at k/2 to the lock tolerance (3.500002 measured)
    assert max(off("TEF", 0.5), off("TEF (locked)", 0.5)) <= 1e-4
    assert max(off("blade flap 1", 0.0), off("blade flap 1 (locked)", 0.0)) <= 1e-4


@pytest.mark.parametrize("figure, field, value", [("fig14", "flap.span", 0.2175),
                                                  ("fig13", "flap.midspan", 0.885)])
def test_the_names_do_not_depend_on_round_off_where_a_lock_forms(monkeypatch, figure, field,
                                                                 value):
    """The flap's own root locks at 5.5 /rev at these points (mu 0.3).  With
    ``A(psi)`` of every path step changed by 1e-13 (relative, seeded), the
    march lost the TEF path there and named the root appearing beside it
    ' (locked)' -- a root left named '' at the end (measured).  A name must
    not hang on round-off: the same names either way.  (Across the 261
    points of Figs. 9, 12-15 no name changes under this perturbation,
    measured.)"""
    from tefcore.floquet import floquet_motions
    from tefcore.linear.stability import stability
    from tefcore.modes import continuation
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config(figure).with_overrides({field: value})
    plain = stability(cfg).modes

    def perturbed(homotopy, eps, basis):
        rng = np.random.default_rng(int(eps * 1e6))
        a = homotopy(eps)
        a = a * (1 + 1e-13 * rng.standard_normal(a.shape))
        eta, x = floquet_motions(a, n_steps=homotopy.n_steps, n_sub=1, method="magnus")
        order = np.lexsort((-eta.real, np.round(eta.imag, 9)))
        return eta[order], (basis @ x[:, :homotopy.n, order]).reshape(-1, order.size)

    monkeypatch.setattr(continuation, "_path_step", perturbed)
    shaken = stability(cfg).modes
    assert all(str(x).strip() and not str(x).startswith(" ") for x in shaken["label"])
    assert list(shaken["label"]) == list(plain["label"])
    # and the certainty of each name: at 0.2175 R the lock's two real roots were
    # both dropped at one path step or both kept, as round-off decided (their
    # multipliers' angles 1.5e-4 off the axis against a fixed 1e-8), and three
    # blade names lost their certainty with it
    assert list(shaken["identity_certain"]) == list(plain["identity_certain"])


def test_a_lock_the_flap_touches_on_the_way_leaves_its_name_certain():
    """At Fig. 14's 0.14 R the TEF reaches 8.5 /rev near eps 0.984, locks there
    for a step and leaves: a root appears beside it and goes.  Which of the
    lock's two real roots the path took is a tie by construction (one mode's
    pair, named as a pair); it is not an undecided match, and the TEF's name
    stays certain (it was flagged undecided by the tie, measured)."""
    from tefcore.linear.stability import stability
    from tefcore.paper.figures.catalogue import figure_config

    modes = stability(figure_config("fig14").with_overrides({"flap.span": 0.14})).modes
    tef = modes[modes["label"] == "TEF"].iloc[0]
    assert bool(tef["identity_certain"])
    assert abs(tef["frequency_per_rev"] - 8.913) < 0.01     # past the lock, as continued


def test_a_lock_at_zero_coupling_is_named_from_its_own_mode():
    """Fig. 12 (mu 0.3) at 110 ft-lb/rad, zero coupling: blade flap 1 is locked
    (two real roots, -1.48 /rev at 0.5 and -0.44 /rev written at 2.5 /rev by
    its dominant harmonic) and blade flap 2's own root is at 2.497 /rev.  The
    one-to-one labels gave the lock's second root 'blade flap 2' and flap 2's
    root 'blade flap 2 (locked)' (measured), so the coupled flap 2 was
    compared with the lock's root (real_part_uncoupled -0.44 instead of its own
    -0.48).  At zero coupling blade and flap are apart: a lock is one mode's,
    and the names there are exact."""
    from tefcore.linear.stability import stability
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig12").with_overrides({"actuator.stiffness": "110 ft-lb/rad"})
    m = stability(cfg).modes.set_index("label")
    # flap 2's uncoupled root is its own, off the lock's 1/2 /rev (folded) by
    # 2.6e-3 /rev -- 26 times the lock tolerance -- and -0.480 /rev
    assert abs(m.loc["blade flap 2", "frequency_uncoupled"] - 2.4974) < 1e-3
    assert abs(m.loc["blade flap 2", "real_part_uncoupled"] + 0.480) < 1e-3
    # the lock's two roots both continue blade flap 1, at 1/2 /rev folded
    for name in ("blade flap 1", "blade flap 1 (locked)"):
        f = m.loc[name, "frequency_uncoupled"] % 1.0
        assert abs(min(f, 1.0 - f) - 0.5) < 1e-6


def test_zero_coupling_names_follow_the_roots_not_their_order():
    """MDART at mu 0.3, c_cg 0.33, zero coupling: four roots at 1/2 /rev folded
    -- blade flap 1's lock (0.5 and 2.5 /rev) and blade flap 2's (both at
    2.5) -- and pairing them in index order would name a flap 2 root 'blade
    flap 1' in 16 of the 24 orders of those four.  Pairs are
    the most alike roots (shape MAC plus overlap of coordinate shares), so
    every order of the roots gives each root the same name."""
    from tefcore.linear.stability import stability
    from tefcore.model.coupled import coupled_model
    from tefcore.modes import continuation
    from tefcore.modes.labels import coordinate_shares
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig9").with_overrides({"flap.cg_offset": 0.33})
    system = stability(cfg).system
    n = system.n_dof
    basis = coupled_model(cfg).tracking_basis()
    res0 = continuation._solve(system, n, 0.0, 72, participation=True)
    frac = coordinate_shares(res0.participation, n)
    shapes = continuation.path_shapes(basis, res0, n, True, 72)
    labels = coupled_model(cfg).labels
    f, r = res0.frequencies, res0.damping_rates
    base = continuation.zero_coupling_names(frac, labels, f, r, shapes, periodic=True)
    assert base.count("blade flap 1") == 1 and base.count("blade flap 1 (locked)") == 1
    assert base.count("blade flap 2") == 1 and base.count("blade flap 2 (locked)") == 1
    rng = np.random.default_rng(3)
    for _ in range(12):
        p = rng.permutation(f.size)
        got = continuation.zero_coupling_names(frac[:, p], labels, f[p], r[p], shapes[:, p],
                                               periodic=True)
        assert [got[list(p).index(j)] for j in range(f.size)] == base


def test_a_root_no_path_explains_keeps_the_coordinate_it_carries():
    # a root the march could not place (origin '') where no final naming
    # runs (constant coefficients) would keep the empty name and read as kind
    # 'TEF': it takes the coordinate it carries, uncertain
    table = pd.DataFrame({"mode_id": [0, 1], "label": ["blade flap 1", "blade lag 1"],
                          "frequency_per_rev": [1.1, 0.7], "real_part": [-0.3, -0.05]})
    continued = SimpleNamespace(origin=["blade flap 1", ""], certain=np.array([True, False]),
                                uncoupled=np.array([-0.3 + 1.1j, np.nan]),
                                meetings=pd.DataFrame(columns=["eps", "origins"]),
                                flap_motion=np.array([0.0, 0.0]),
                                frequency=np.full(2, np.nan))
    out = name_roots(table, continued)
    assert out["label"].tolist() == ["blade flap 1", "blade lag 1"]
    assert out["kind"].tolist() == ["flap", "lag"]
    assert out["identity_certain"].tolist() == [True, False]
    assert out["named_by_path"].tolist() == [True, False]


@pytest.mark.parametrize("eps", [0.0, 0.3, 0.77, 1.0])
def test_the_homotopy_by_block_elimination_is_the_homotopy(eps):
    """:class:`HomotopySamples` inverts ``M(eps)`` by eliminating the blade block
    once (the flap is one coordinate: a scalar Schur complement); its ``A`` at
    every sample must be that of :func:`coupling_homotopy` sampled and solved
    directly.  MDART at mu 0.3, Fig. 9's c_cg 0.36: agreement 1e-15 relative
    (measured); gate 1e-12, far below any difference a wrong block (a factor
    eps missing on a coupling term moves A by 7e-2 relative or more, measured)
    could hide."""
    from tefcore.linear.stability import stability
    from tefcore.modes.continuation import HomotopySamples, coupling_homotopy
    from tefcore.paper.figures.catalogue import figure_config

    system = stability(figure_config("fig9").with_overrides({"flap.cg_offset": 0.36})).system
    samples = HomotopySamples(system, 72)
    direct = coupling_homotopy(system, system.n_dof - 1, eps).state_matrix(
        np.arange(144) * np.pi / 72)
    got = samples(eps)
    assert got.shape == direct.shape
    assert np.abs(got - direct).max() <= 1e-12 * np.abs(direct).max()


def test_the_homotopy_samples_refuse_a_system_they_cannot_split():
    """Aerodynamic states (first-order) or constant coefficients: not the
    periodic second-order system the block elimination is written for."""
    from tefcore.floquet.second_order import SecondOrderSystem
    from tefcore.modes.continuation import HomotopySamples

    m = np.eye(2)[None]
    with pytest.raises(ValueError, match="periodic second-order"):
        HomotopySamples(SecondOrderSystem(m, 0.1 * m, m), 36)


def test_a_root_named_by_participation_carries_no_other_path_s_frequency():
    """Fig. 13 at 0.71875 R (mu 0.3): the flap-free root at 3.30 /rev carries
    blade torsion 1 (its participation) while its path was the TEF's; it had
    been given the TEF path's continued frequency, 10.30 /rev (measured).  Its
    name is not its path's (``named_by_path`` False) and it has no continued
    frequency; the roots named by their own paths keep theirs."""
    from tefcore.linear.stability import stability
    from tefcore.modes.names import is_locked
    from tefcore.paper.figures.catalogue import figure_config

    res = stability(figure_config("fig13").with_overrides({"flap.midspan": 0.71875}))
    m = res.modes
    torsion = m[m["label"] == "blade torsion 1"].iloc[0]
    assert abs(torsion["frequency_per_rev"] - 3.30) < 0.01    # the flap-free root (3.3014)
    assert not torsion["named_by_path"] and np.isnan(torsion["frequency_continued"])
    own = m["named_by_path"].to_numpy(bool)
    assert own.sum() >= len(m) // 2                     # most roots keep their paths' names
    for j in np.flatnonzero(own & m["identity_certain"].to_numpy(bool)):
        f, g = m["frequency_per_rev"].iloc[j], m["frequency_continued"].iloc[j]
        # a path's own frequency: the root's, modulo 1/rev and the sign; of a
        # locked pair, which root the path reached is round-off (the pair is
        # named as a pair), and only that root carries it
        if not is_locked(m["label"].iloc[j]) and np.isfinite(g):
            assert min(abs((f - g + 0.5) % 1 - 0.5), abs((f + g + 0.5) % 1 - 0.5)) < 1e-6


def test_an_exceptional_point_says_how_near_its_uncoupled_modes_lie():
    """An exceptional point grows out of two roots near each other at zero
    coupling: in hover two frequencies, in forward flight two Floquet
    frequencies equal modulo 1/rev and up to the sign.  Fig. 15's TEF at
    16.48 /rev and blade flap 5 at 10.71 /rev (mu 0.3): the sum, 27.19, lies
    0.19 from 27 /rev, nearer an integer than the difference 5.77 (0.23): the
    mirror (``f`` and ``1 - f`` modulo 1/rev) -- measured between 0.2719 and
    0.275 c, where the two exchange names.  In hover the plain difference."""
    from tefcore.modes.roles import uncoupled_relation

    floquet = pd.DataFrame({"x": [0.27, 0.275], "label": ["TEF", "blade flap 5"],
                            "frequency_uncoupled": [16.48, 10.71],
                            "frequency_continued": [16.1, np.nan]})
    assert uncoupled_relation(floquet, "TEF / blade flap 5", 0.27, 0.275).endswith(
        "TEF + blade flap 5 = 27 /rev to 0.19")
    hover = floquet.assign(frequency_continued=np.nan, frequency_uncoupled=[3.3, 3.1])
    assert uncoupled_relation(hover, "TEF / blade flap 5", 0.27, 0.275).endswith(
        "TEF - blade flap 5 = 0.20 /rev")
    # the exchange table: the note rides along with the point, and says nothing
    # where a frequency is not known
    ep = exceptional_points(_exchange_rows())
    assert ep["uncoupled"].tolist() == [
        "uncoupled TEF 3.00, blade flap 3 2.00 /rev: TEF - blade flap 3 = 1.00 /rev"]
    assert uncoupled_relation(floquet.drop(columns="frequency_uncoupled"),
                              "TEF / blade flap 5", 0.27, 0.275) == ""


@pytest.mark.parametrize("field, rel", [("blade.mass_scale", 1e-12),
                                        ("rotor.air_density", -1e-12)])
def test_a_nudge_leaves_every_name_and_its_certainty_where_a_lock_forms(field, rel):
    """Fig. 14's 0.2175 R, where the TEF's lock at 5.5 /rev forms near eps 0.994:
    a relative nudge of 1e-12 (no engineering meaning; the round-off of another
    BLAS kernel) left the names but flipped the certainty of three of them
    (measured while a fixed angle threshold decided whether the lock's roots
    were real, and the lock's appearing root counted as a rival of the path
    that reached its partner; either rule alone keeps them here)."""
    from tefcore.paper.claims.robustness import nudge
    from tefcore.paper.figures.frames import compute_figure

    cfg = load_config("mdart")
    plain = compute_figure("fig14", cfg, [0.2175]).table.sort_values("label")
    shaken = compute_figure("fig14", nudge(cfg, field, rel), [0.2175]).table.sort_values("label")
    assert list(shaken["label"]) == list(plain["label"])
    assert list(shaken["identity_certain"]) == list(plain["identity_certain"])
