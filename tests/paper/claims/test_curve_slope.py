"""The slope a trend claim reads is the curve's, not the sampling's.

A sweep's refinement points cluster where names exchange; the slope of the
least-squares line to the curve over its range (not to its points) is
unchanged by a point added on a straight stretch, equals an exact line's slope,
and is the limit of an unweighted fit to a uniform, ever finer sampling.
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from tefcore.paper.claims.kinds import curve_slope

_points = st.lists(st.floats(-5, 5, allow_nan=False), min_size=3, max_size=12)


@settings(max_examples=60, deadline=None)
@given(ys=_points, where=st.floats(0.01, 0.99), seed=st.integers(0, 2**16))
def test_a_point_on_a_straight_stretch_changes_nothing(ys, where, seed):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0, 10, len(ys)))
    if np.min(np.diff(x)) < 1e-3:
        x = np.linspace(0, 10, len(ys))
    y = np.array(ys)
    k = int(rng.integers(0, len(x) - 1))
    xm = x[k] + where * (x[k + 1] - x[k])
    ym = np.interp(xm, x, y)
    xx, yy = np.insert(x, k + 1, xm), np.insert(y, k + 1, ym)
    # round-off of sums of order 10^2 x 5: 1e-9 of the slopes' scale
    np.testing.assert_allclose(curve_slope(xx, yy), curve_slope(x, y), atol=1e-9)


def test_an_exact_line_and_the_limit_of_a_fine_uniform_fit():
    x = np.array([0.0, 0.3, 1.7, 2.0, 5.0])
    assert abs(curve_slope(x, 2.5 * x - 1.0) - 2.5) < 1e-12
    y = np.array([0.0, 1.0, -0.5, 2.0, 0.7])
    fine = np.linspace(0, 5, 200001)
    # an unweighted fit to a uniform sampling converges to the curve's slope as
    # the step falls: its error is of the order of the step (the sum counts each
    # end once, the integral by half a step), 5e-7 at the step 2.5e-5; the fit to
    # the five points themselves is 0.1 away
    np.testing.assert_allclose(curve_slope(x, y), np.polyfit(fine, np.interp(fine, x, y), 1)[0],
                               atol=2e-6)
    assert abs(curve_slope(x, y) - np.polyfit(x, y, 1)[0]) > 0.05


def test_clustered_points_do_not_weigh_their_stretch():
    # a curve rising on [0, 1] and flat on [1, 10]: its slope is set by the whole
    # range, and ten points crowded into the rise do not make it steeper (an
    # unweighted fit of the points does)
    x = np.r_[np.linspace(0, 1, 11), [5.0, 10.0]]
    y = np.minimum(x, 1.0)
    plain = curve_slope([0.0, 1.0, 10.0], [0.0, 1.0, 1.0])
    assert abs(curve_slope(x, y) - plain) < 1e-12
    assert np.polyfit(x, y, 1)[0] > 1.5 * plain
