"""tefcore.assignment gives scipy's assignment, plain or not: its own augmenting paths
when the optimum is unique by a margin, scipy's solver otherwise."""

from __future__ import annotations

from unittest import mock

import numpy as np
import pytest
import scipy.optimize
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from tefcore import assignment
from tefcore.assignment import (
    augmenting_assignment,
    linear_sum_assignment,
    plain_assignment,
    unique_margin,
)

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


def _own_solver():
    """linear_sum_assignment as in a process without scipy.optimize (a command's)."""
    return mock.patch.object(assignment, "_scipy_solver_loaded", lambda: False)


@settings(deadline=None)
@given(costs)
def test_same_pairs_as_scipy_without_scipy_imported(cost):
    with _own_solver():
        rows, cols = linear_sum_assignment(cost)
    want_rows, want_cols = scipy.optimize.linear_sum_assignment(cost)
    np.testing.assert_array_equal(rows, want_rows)
    np.testing.assert_array_equal(cols, want_cols)


@pytest.mark.parametrize("values", ["continuous", "integers"])
def test_augmenting_paths_find_an_optimum_and_the_margin_says_when_it_is_unique(values):
    # integer costs tie often: there the optimum's cost must still be scipy's,
    # the margin 0 (so linear_sum_assignment hands the tie to scipy); with
    # continuous costs ties do not occur and the pairs are scipy's
    rng = np.random.default_rng(7)
    unique = 0
    for _ in range(600):
        n = int(rng.integers(1, 16))
        cost = (rng.normal(size=(n, n)) if values == "continuous"
                else rng.integers(0, 4, (n, n)).astype(float))
        cols = augmenting_assignment(cost)
        r, c = scipy.optimize.linear_sum_assignment(cost)
        assert sorted(cols) == list(range(n))                     # a permutation
        assert abs(cost[np.arange(n), cols].sum() - cost[r, c].sum()) <= 1e-9
        margin = unique_margin(cost, cols)
        assert margin >= -1e-9                                    # nothing cheaper
        if margin > 1e-9:
            unique += 1
            np.testing.assert_array_equal(cols, c)
        else:
            # a tie: another assignment of the same cost exists
            assert n > 1 and values == "integers"
    assert unique > (500 if values == "continuous" else 30)


def test_a_tie_goes_to_scipy_and_the_pairs_are_scipys():
    cost = np.array([[1.0, 1.0, 5.0], [1.0, 1.0, 5.0], [5.0, 5.0, 0.0]])
    assert unique_margin(cost, augmenting_assignment(cost)) == 0.0
    with _own_solver():
        got = linear_sum_assignment(cost)
    for a, b in zip(got, scipy.optimize.linear_sum_assignment(cost), strict=True):
        np.testing.assert_array_equal(a, b)


def test_the_margin_of_a_known_swap():
    # two rows, the swap dearer by (0.4 + 0.3) - (0.1 + 0.1) = 0.5; a worse
    # assignment has a negative margin (a negative cycle: Floyd-Warshall may
    # go round it more than once, so only its sign is asserted)
    cost = np.array([[0.1, 0.4], [0.3, 0.1]])
    assert unique_margin(cost, np.array([0, 1])) == pytest.approx(0.5, abs=1e-15)
    assert unique_margin(cost, np.array([1, 0])) < 0.0
