"""The XFOIL flap deck (tefcore/data/naca0012_flap35_xfoil.c81): loads and is physical.

Generated once by tools/make_xfoil_flap_deck.py (XFOIL 6.99, viscous); these
tests read the committed file only.  Each bound is thin-airfoil theory
(section 3 of the theory, Prandtl-Glauert) with the margin a real, viscous,
12 %-thick section is known to need, and fails for a wrong sign, a wrong
normalisation (flap vs blade chord: x 8) or a wrong moment reference.
"""

import math
from importlib import resources

import numpy as np
import pytest

from tefcore.aero.c81 import C81FlapTable, read_c81
from tefcore.aero.thin_airfoil import ThinAirfoilFlap, prandtl_glauert

PATH = resources.files("tefcore") / "data" / "naca0012_flap35_xfoil.c81"
HINGE_ARM = 0.29 * 0.35          # hinge behind the flap nose, blade chords


@pytest.fixture(scope="module")
def deck():
    return read_c81(str(PATH))


def _table(deck, coef):
    return deck.tables[coef], deck.alpha[coef], deck.mach[coef], deck.delta


def _slope(y, x):
    return np.polyfit(x, y, 1)[0]


def test_deck_loads_with_provenance(deck):
    assert deck.is_flap
    assert "XFOIL Version 6.99" in deck.header and "make_xfoil_flap_deck.py" in deck.header
    table = C81FlapTable(deck, chord_ratio=0.35, overhang=0.29, out_of_range="raise")
    st = table.static_coefficients(np.radians(2.0), 0.4, np.radians(3.0))
    assert set(st) == {"cl", "cd", "cm", "ch", "clf"}
    assert all(np.isfinite(v) for v in st.values())


@pytest.mark.parametrize("mach", [0.0, 0.3, 0.5])
def test_lift_slope_and_flap_effectiveness(deck, mach):
    cl, alpha, machs, delta = _table(deck, "cl")
    j, k0 = list(machs).index(mach), list(delta).index(0.0)
    pg = float(prandtl_glauert(mach))
    lin = np.abs(alpha) <= 4
    a_slope = _slope(cl[lin, j, k0], np.radians(alpha[lin]))
    # NACA 0012, Re 1-3e6: measured 6.5-7.3 /rad x PG; thin airfoil 2 pi PG.
    # Thickness raises, the boundary layer lowers it: within [0.9, 1.25] x 2 pi PG.
    assert 0.9 < a_slope / (2 * math.pi * pg) < 1.25
    # flap effectiveness at alpha = 0 over delta in [-3, 3] against thin airfoil
    # 2 T10 PG: thickness raises it as it raises the lift slope (~1 + 0.8 t/c),
    # viscous decambering lowers it; measured 1.06-1.09 (M 0-0.5)
    i0 = list(alpha).index(0.0)
    ks = [list(delta).index(d) for d in (-3.0, 0.0, 3.0)]
    d_slope = _slope(cl[i0, j, ks], np.radians([-3.0, 0.0, 3.0]))
    thin = ThinAirfoilFlap(0.35, 0.29, compressibility=False).derivatives["cl_delta"] * pg
    assert 0.7 < d_slope / thin < 1.25


def test_symmetric_section(deck):
    # NACA 0012: C_l(-alpha, -delta) = -C_l(alpha, delta), C_h likewise; XFOIL's
    # free transition is symmetric too. Where both points converged the mismatch
    # is round-off of the F7 fields and the iteration (measured <= 1.3e-3 in C_l
    # for |alpha| <= 6, M <= 0.5); an alpha-interpolated (unconverged) point
    # reaches 0.018 (M 0.5, delta -10, alpha -5).  A sign error is off by ~1.
    cl, alpha, machs, delta = _table(deck, "cl")
    pos = [list(alpha).index(a) for a in range(-6, 7)]
    neg = [list(alpha).index(-a) for a in range(-6, 7)]
    assert np.array_equal(delta, -delta[::-1])
    for j, m in enumerate(machs):
        if m > 0.5:
            continue
        assert np.max(np.abs(cl[pos, j, :] + cl[neg, j, ::-1])) < 0.02


@pytest.mark.parametrize("mach", [0.3, 0.5])
def test_hinge_moment_sign_magnitude_and_balance(deck, mach):
    ch, alpha, machs, delta = _table(deck, "ch")
    clf = deck.tables["clf"]
    j, i0 = list(machs).index(mach), list(alpha).index(0.0)
    ks = [list(delta).index(d) for d in (-3.0, 0.0, 3.0)]
    drad = np.radians([-3.0, 0.0, 3.0])
    pg = float(prandtl_glauert(mach))
    hinge = _slope(ch[i0, j, ks], drad)
    nose = _slope(ch[i0, j, ks] - HINGE_ARM * clf[i0, j, ks], drad)   # plain flap (o = 0)
    thin_nose = ThinAirfoilFlap(0.35, 0.0, compressibility=False).derivatives["ch_delta"] * pg
    # about the nose: restoring (negative), and real hinge moments are smaller than
    # thin-airfoil ones (viscous decambering): 0.4-1.0 of -0.121 PG per rad
    assert nose < 0
    assert 0.4 < nose / thin_nose < 1.0
    # the 29 % overhang removes most of it: thin airfoil leaves 14 %; XFOIL less
    assert abs(hinge) < 0.3 * abs(nose)
    # flap lift: thin airfoil 2 mu^2/pi per rad (PG); viscous 0.6-1.05 of it
    thin_clf = ThinAirfoilFlap(0.35, 0.0, compressibility=False).derivatives["clf_delta"] * pg
    assert 0.6 < _slope(clf[i0, j, ks], drad) / thin_clf < 1.05


def test_stall_and_drag(deck):
    cl, alpha, machs, delta = _table(deck, "cl")
    cd = deck.tables["cd"]
    j, k0 = list(machs).index(0.2), list(delta).index(0.0)
    # low Mach, no flap: the lift curve bends over (stall) inside the table:
    # the slope over the last 3 degrees is less than half the linear slope
    lin = _slope(cl[np.abs(alpha) <= 4, j, k0], alpha[np.abs(alpha) <= 4])
    top = _slope(cl[alpha >= alpha[-1] - 3, j, k0], alpha[alpha >= alpha[-1] - 3])
    assert top < 0.5 * lin
    assert 1.1 < cl[:, j, k0].max() < 1.8               # NACA 0012 c_l,max at Re ~1e6
    i0 = list(alpha).index(0.0)
    assert 0.004 < cd[i0, j, k0] < 0.012                 # NACA 0012 minimum drag
    assert np.all(cd > 0)
