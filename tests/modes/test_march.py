"""The march of continuation (tefcore.modes.march): what decides a step.

* :func:`regrets` -- the cost of the best assignment without a match -- is
  checked against its definition: the assignment solved again with the
  match forbidden (scipy's solver), on random cost matrices, square and with
  a path ending at a lock (padded).  Exact equality to round-off: both are
  the same minimum, found two ways.
* :func:`exchanges` names, beside each regret, the root the path takes in
  that cheapest other assignment: checked the same way (the forbidden
  assignment solved again gives the path's new root).
* A Floquet root whose frequency moves along ``eps`` with its shape fixed is
  compared by its periodic part: a path sees it at MAC 1 whatever the
  frequency drift over the step (compared as whole motions, a drift of
  1/2 /rev over a revolution costs most of the MAC).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from tefcore.modes.march import March, _padded, compact_basis, exchanges, flap_share, regrets


def _forbidden(full, r, c):
    alt = full.copy()
    alt[r, c] = 1e6
    i, j = linear_sum_assignment(alt)
    k, m = linear_sum_assignment(full)
    return alt[i, j].sum() - full[k, m].sum()


@pytest.mark.parametrize("seed", range(20))
def test_regret_is_the_best_assignment_without_the_match(seed):
    rng = np.random.default_rng(seed)
    p, r = rng.integers(2, 9), rng.integers(2, 9)
    cost = rng.uniform(0.0, 2.0, (p, r))
    full = _padded(cost, rng.random(p) < 0.5, rng.random(r) < 0.5)
    rows, perm = linear_sum_assignment(full)
    got = regrets(full, perm, rows)
    want = [_forbidden(full, i, perm[i]) for i in rows]
    # both are the same minimum over assignments (sums of at most 9 costs
    # of order 1): equal to round-off
    np.testing.assert_allclose(got, want, atol=1e-9)


def _forbidden_root(full, r, c):
    alt = full.copy()
    alt[r, c] = 1e6
    i, j = linear_sum_assignment(alt)
    return int(j[list(i).index(r)])


@pytest.mark.parametrize("seed", range(20))
def test_the_rival_is_the_root_taken_in_the_best_assignment_without_the_match(seed):
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(3, 9))
    # distinct sums (continuous costs): the best other assignment is unique
    full = rng.uniform(0.0, 2.0, (n, n))
    rows, perm = linear_sum_assignment(full)
    regret, rival = exchanges(full, perm, rows)
    want = [_forbidden_root(full, i, perm[i]) for i in rows]
    assert rival.tolist() == want
    np.testing.assert_allclose(regret, regrets(full, perm, rows), atol=0)


def test_the_rival_of_a_veering_pair_is_its_partner_not_the_next_in_its_row():
    # the row of path 0 has root 2 next (0.30), but the cheapest exchange is
    # with path 1 (0.20 + 0.25 - 0.10 - 0.10 = 0.25 < 0.30 + 0.9 - 0.1 - 0.1):
    # the shape of Fig. 14's TEF path at 0.0775 R, whose row had a flap-free
    # root next while its exchange was with blade torsion 2's
    full = np.array([[0.10, 0.20, 0.30],
                     [0.25, 0.10, 0.95],
                     [0.90, 0.90, 0.10]])
    regret, rival = exchanges(full, np.array([0, 1, 2]), [0])
    assert rival.tolist() == [1]
    np.testing.assert_allclose(regret, [0.25], atol=1e-12)


def test_a_veering_swap_dearer_than_its_rows_show_is_decided():
    # measured on Fig. 9's c_cg 0.12 at eps 0.53: each match near its rival in
    # its row (0.104 vs 0.404, 0.074 vs 0.277), the swap 0.5 dearer
    full = np.array([[0.104, 0.404], [0.277, 0.074]])
    got = regrets(full, np.array([0, 1]), [0, 1])
    np.testing.assert_allclose(got, [0.503, 0.503], atol=1e-12)


def _motion(freq, shape, samples=72):
    """A root's motion over the revolution: exp(i f psi) times a fixed shape."""
    psi = 2 * np.pi * np.arange(samples) / samples
    return (np.exp(1j * freq * psi)[:, None] * shape[None, :]).reshape(-1, 1)


@pytest.mark.parametrize("drift", [0.05, 0.3, 0.49])
def test_a_drifting_frequency_is_not_a_change_of_shape(drift):
    shape = np.array([1.0, 0.4 - 0.2j, 0.1])
    other = np.array([0.1, 1.0, -0.5j])
    f0 = 7.2
    march = March(np.array([-0.1 + 1j * f0]), _motion(f0, shape), ["TEF"], 3, True)
    # at the next eps: the root moved by `drift` /rev (seen modulo 1, as the
    # principal branch gives it), a second root elsewhere with another shape
    eig = np.array([-0.1 + 1j * ((f0 + drift) % 1.0), -0.2 + 0.9j])
    vecs = np.hstack([_motion(f0 + drift, shape), _motion(3.9, other)])
    cost, shape_cost, seen, _ = march._costs(march._predicted(0.5), eig, vecs)
    # the same shape: MAC 1 to round-off; the frequency unwrapped to the path's
    assert shape_cost[0, 0] == pytest.approx(0.0, abs=1e-12)
    assert seen[0, 0].imag == pytest.approx(f0 + drift, abs=1e-12)
    # compared as whole motions the drift alone costs MAC: |mean exp(i d psi)|^2
    # = (sin(pi d) / (pi d))^2 over the revolution (0.74 at d = 0.3, 0.42 at
    # 0.49); the 72 samples agree with the integral to 1e-3
    a, b = _motion(f0, shape)[:, 0], vecs[:, 0]
    whole = abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real)
    assert whole == pytest.approx(np.sinc(drift) ** 2, abs=1e-3)
    assert shape_cost[0, 1] > 0.5                 # the other root stays another


def test_the_second_root_of_a_lock_no_path_explains_is_unexplained_too():
    # a lock forming on a root that no path explains (its path was lost at an
    # earlier step): the root that appears beside it has no mode to be the
    # second root of, so it is unexplained ('') like its partner, for the
    # final naming to place (final_names.second_roots_of_locks) -- not
    # ' (locked)', the suffix on an empty name (measured at Fig. 14's 0.2175 R
    # with A changed by 1e-13: a root left named '')
    a = np.array([1.0, 0.3, 0.0])
    b = np.array([0.1, 0.5, 1.0])
    march = March(np.array([-0.2 + 0.3j, -5.0 + 0.45j]),
                  np.hstack([_motion(0.3, a), _motion(0.45, b)]), ["blade flap 1", "TEF"], 3,
                  True)
    march.origin[1] = ""                          # the TEF path lost before this step
    eig = np.array([-0.2 + 0.3j, -5.0 + 0.5j, -5.3 + 0.5j])     # the pair locked at 1/2 /rev
    vecs = np.hstack([_motion(0.3, a), _motion(0.5, b), _motion(0.5, b * (1 + 0.01j))])
    assert march.step(0.5, eig, vecs, final_step=True)
    assert march.origin[0] == "blade flap 1"
    assert sorted(march.origin[1:]) == ["", ""]


def test_compact_basis_keeps_every_mac_norm_and_flap_share():
    """The march compares shapes through inner products of the physical rows and
    the flap's row alone; ``[R; b]`` (R of the QR of the other rows) keeps the
    Gram matrix and that row, so MAC, norms and flap shares of any coordinate
    vectors are the same to round-off (1e-12: a few hundred flops of 1e-16 each)
    on 11 rows instead of MDART's 37.  Q instead of R, or the flap row dropped
    from the factorisation's complement, fails it."""
    from tefcore.modes.matching import mac

    rng = np.random.default_rng(7)
    basis = rng.normal(size=(37, 10))
    basis[-1] *= 1e-3                          # the flap's row small, as in MDART's
    small = compact_basis(basis)
    assert small.shape == (11, 10)
    x = rng.normal(size=(10, 6)) + 1j * rng.normal(size=(10, 6))
    big_s, small_s = basis @ x, small @ x
    np.testing.assert_allclose(mac(small_s, small_s), mac(big_s, big_s), atol=1e-12)
    np.testing.assert_allclose(np.sum(np.abs(small_s) ** 2, axis=0),
                               np.sum(np.abs(big_s) ** 2, axis=0), rtol=1e-12)
    np.testing.assert_allclose(flap_share(small_s, 11), flap_share(big_s, 37), rtol=1e-10)
    # a basis with no more rows than n + 1 is kept as it is
    assert compact_basis(np.eye(3)).shape == (3, 3)
