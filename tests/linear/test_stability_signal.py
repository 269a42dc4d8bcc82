"""What a point says beside its numbers: clipped C81 inputs once, real parts below the
solver's resolution as neutral."""

import warnings

import numpy as np
import pytest

from tefcore.aero.c81 import C81RangeWarning, xfoil_deck_path
from tefcore.config.io import load_config
from tefcore.floquet import constant_coefficient_modes
from tefcore.linear.stability import stability

MDART = load_config("mdart")
#: The packaged XFOIL deck at mu = 0.3: alpha beyond its [-12, 16] deg on the retreating
#: side and Mach beyond 0.7 at the advancing tip.
XFOIL = MDART.with_overrides({"model.aero_model": "c81",
                              "model.c81_deck": str(xfoil_deck_path())})


def recorded(func, *args, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = func(*args, **kw)
    return result, [w for w in caught if issubclass(w.category, C81RangeWarning)]


def test_clipped_c81_inputs_are_one_warning_per_point():
    """One warning per point, not ~80 raw C81RangeWarning blocks."""
    _, caught = recorded(stability, XFOIL)
    assert len(caught) == 1
    clipped = caught[0].message.clipped
    assert clipped["calls"] > 1                  # many evaluations, one warning
    alpha, lo, hi = clipped["extremes"]["alpha"]
    assert (lo, hi) == (-12.0, 16.0) and abs(alpha) > 16
    assert clipped["extremes"]["mach"][0] > 0.7
    text = str(caught[0].message)
    assert f"in {clipped['calls']} evaluations" in text and "mach reached" in text


def test_a_point_inside_its_table_warns_nothing():
    # hover, C_T/sigma 0.075: every section inside the XFOIL deck's alpha and Mach
    _, caught = recorded(stability, XFOIL.with_overrides({"flight.advance_ratio": 0.0}))
    assert caught == []


def test_every_root_carries_its_resolution():
    modes = stability(MDART.with_overrides({"model.n_modes": 30})).modes
    err = modes["real_part_error"].to_numpy(float)
    assert np.isfinite(err).all() and (err > 0).all()
    assert (modes["neutral"] == (modes["real_part"].abs() <= err)).all()
    # "blade axial 1": a real part of -3.1e-5 /rev (measured), resolved to about
    # 4e-11: a small true damping, not neutral
    axial = modes[modes["label"] == "blade axial 1"].iloc[0]
    assert abs(axial["real_part"]) > 1e3 * axial["real_part_error"]
    assert not axial["neutral"]


def test_hover_roots_carry_a_roundoff_resolution():
    modes = stability(MDART.with_overrides({"flight.advance_ratio": 0.0})).modes
    assert np.isfinite(modes["real_part_error"]).all() and (modes["real_part_error"] > 0).all()


@pytest.mark.parametrize("omega", [0.5, 2.0, 30.0])
def test_an_undamped_root_is_within_its_resolution(omega):
    # x'' + omega^2 x = 0: the exponents are +-i omega exactly; what the eigensolver
    # returns for their real parts is round-off, and the estimate must cover it
    a = np.array([[0.0, 1.0], [-omega**2, 0.0]])
    res = constant_coefficient_modes(a)
    assert res.error_estimates is not None
    assert np.all(np.abs(res.exponents.real) <= res.error_estimates.real)
    # and it is a round-off bound (1e2 eps ||A|| times the condition number, ~1e-10 for
    # omega = 30), not a tolerance: far below 1e-8 /rev, while the figures resolve
    # real parts to ~1e-3 /rev
    assert np.all(res.error_estimates.real < 1e-8)
