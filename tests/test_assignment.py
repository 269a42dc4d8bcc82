"""tefcore.assignment gives scipy's assignment, plain or not (it calls scipy when not)."""

from __future__ import annotations

import numpy as np
import scipy.optimize
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from tefcore.assignment import linear_sum_assignment, plain_assignment

# costs drawn from few values produce ties (the certificate must refuse them),
# wide ranges produce plain assignments; -log(share + 1e-300) is what the mode
# labels assign, with shares of exactly zero
costs = st.integers(1, 7).flatmap(lambda r: st.integers(1, 7).flatmap(
    lambda c: arrays(np.float64, (r, c), elements=st.one_of(
        st.sampled_from([0.0, 1.0, 2.0, 690.7755278982137]),
        st.floats(-1e6, 1e6, allow_nan=False)))))


@given(costs)
def test_same_pairs_as_scipy(cost):
    rows, cols = linear_sum_assignment(cost)
    want_rows, want_cols = scipy.optimize.linear_sum_assignment(cost)
    np.testing.assert_array_equal(rows, want_rows)
    np.testing.assert_array_equal(cols, want_cols)


def test_random_share_matrices_match_scipy():
    rng = np.random.default_rng(1)
    plain = 0
    for _ in range(3000):
        shape = rng.integers(1, 12, 2)
        share = np.where(rng.random(shape) < 0.2, 0.0, rng.random(shape))
        cost = -np.log(share + 1e-300)
        plain += plain_assignment(cost if shape[0] <= shape[1] else cost.T) is not None
        for got, want in zip(linear_sum_assignment(cost),
                             scipy.optimize.linear_sum_assignment(cost), strict=True):
            np.testing.assert_array_equal(got, want)
    assert plain > 300          # the fast path is exercised, not only the fallback


def test_certificate_refuses_a_tie_and_a_shared_column():
    assert plain_assignment(np.array([[1.0, 1.0], [0.0, 5.0]])) is None    # tied minimum
    assert plain_assignment(np.array([[0.0, 1.0], [0.0, 5.0]])) is None    # one column twice
    np.testing.assert_array_equal(plain_assignment(np.array([[0.0, 1.0], [3.0, 2.0]])), [0, 1])
