"""Floquet analysis of periodic linear systems (tefcore.floquet) against exact results.

References
----------
[F]  G. Floquet, Ann. Sci. Ec. Norm. Sup. 12 (1883) 47-88; any ODE text, e.g.
     V. A. Yakubovich, V. M. Starzhinskii, *Linear Differential Equations with
     Periodic Coefficients*, Wiley, 1975.
[PH] D. A. Peters, K. H. Hohenemser, J. Am. Helicopter Soc. 16(2) (1971) 25-33
     (frequency ambiguity of the Floquet exponents).
[BN] O. A. Bauchau, Y. G. Nikishkov, J. Am. Helicopter Soc. 46(3) (2001) 200-209.
[L]  K. Lust, Int. J. Bifurcation Chaos 11(9) (2001) 2389-2410 (lifting /
     periodic Schur for small multipliers).
[DLMF] NIST Digital Library of Mathematical Functions, ch. 28 (Mathieu):
     28.2 (Floquet solutions, characteristic exponent nu), 28.7 (a_m, b_m and
     the stability chart), 28.12 / Hill's method for a_nu(q).

Tolerances are set from the integrator's measured error (RK4 and the Magnus
scheme are both O(h^4)) or from roundoff, as each comment says.
"""

import warnings

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
import scipy.special
from numpy.testing import assert_allclose

from tefcore.floquet import (
    DEFAULT_N_STEPS,
    FloquetResult,
    characteristic_multipliers,
    constant_coefficient_modes,
    damping_ratio,
    floquet_modes,
    floquet_motions,
    monodromy,
    step_propagators,
    transition_matrices,
)

TWO_PI = 2 * np.pi


def matched(reference, computed):
    """``computed`` reordered to pair each reference value with its nearest (assignment)."""
    cost = np.abs(np.subtract.outer(reference, computed))
    rows, cols = scipy.optimize.linear_sum_assignment(cost)
    out = np.empty_like(np.asarray(computed))
    out[rows] = np.asarray(computed)[cols]
    return out


def real_form(exponents):
    """Real block-diagonal matrix with the given (conjugate-closed) eigenvalues."""
    blocks = []
    for lam in exponents:
        if lam.imag > 0:
            blocks.append([[lam.real, lam.imag], [-lam.imag, lam.real]])
        elif lam.imag == 0:
            blocks.append([[lam.real]])
    return scipy.linalg.block_diag(*blocks)


def coupled(exponents, seed=0, spread=0.5):
    """A non-normal real matrix with these eigenvalues: S D S^-1, S well conditioned."""
    d = real_form(np.asarray(exponents, complex))
    rng = np.random.default_rng(seed)
    s = np.eye(len(d)) + spread * rng.standard_normal(d.shape)
    return s @ d @ np.linalg.inv(s)


def mathieu(a, q, damping=0.0):
    """``y'' + c y' + (a - 2 q cos 2t) y = 0`` in first-order form, period pi [DLMF 28.2.1]."""
    def A(t):
        one, zero = np.ones_like(t), np.zeros_like(t)
        return np.stack([[zero, one],
                         [-(a - 2 * q * np.cos(2 * t)), -damping * one]]).transpose(2, 0, 1)
    return A


def mathieu_a_of_nu(nu, q, kmax=30):
    """Characteristic value a for exponent nu, by Hill's method [DLMF 28.12].

    ``y = exp(i nu t) sum c_k exp(2 i k t)`` gives the symmetric tridiagonal
    eigenproblem ``(nu + 2k)^2 c_k + q (c_{k-1} + c_{k+1}) = a c_k``;
    61 harmonics converge it to roundoff for q <= 1.
    """
    k = np.arange(-kmax, kmax + 1)
    hill = np.diag((nu + 2.0 * k) ** 2) + q * (np.eye(k.size, k=1) + np.eye(k.size, k=-1))
    w = np.linalg.eigvalsh(hill)
    return w[np.argmin(np.abs(w - nu**2))]


# --------------------------------------------------------------------------
# constant coefficients: lifting keeps the heavily damped modes

HEAVY = np.array([-0.05 + 0.7j, -0.05 - 0.7j, -0.2 + 2.3j, -0.2 - 2.3j,
                  -10 + 3j, -10 - 3j, -30 + 0j])


def test_heavily_damped_exponents_exact_by_lifting():
    B = coupled(HEAVY)
    # Magnus is exact for constant A (expm(h B) per step), so only the
    # eigen-solution is tested. Lifted root errors are ~ eps ||Z|| / |mu|,
    # i.e. exponent errors ~ K eps exp(|sigma| T / K) / T: with K = 16 blocks
    # the -30 mode enters each block as exp(-30 pi / 8) ~ 8e-6, giving ~1e-10;
    # the others are at roundoff.
    res = floquet_modes(B, n_sub=16, method="magnus")
    assert_allclose(matched(HEAVY, res.exponents), HEAVY, rtol=0, atol=1e-9)
    # with the default 8 blocks -10 +- 3i is still exact; -30 (block
    # multiplier 6e-11) is within the estimate 8 eps e^(30 pi/4) / 2 pi ~ 5e-6
    res8 = floquet_modes(B, method="magnus")
    got = matched(HEAVY, res8.exponents)
    assert_allclose(got[:6], HEAVY[:6], rtol=0, atol=1e-11)
    assert_allclose(got[6], HEAVY[6], rtol=0, atol=5e-5)


def test_explicit_product_loses_heavily_damped_modes():
    """Motivation for lifting: eig of the explicit product Phi(2 pi, 0).

    The multipliers exp(-20 pi) ~ 5e-28 and exp(-60 pi) ~ 4e-82 lie far below
    eps ||Phi|| ~ 1e-16, so eig returns roundoff for them: exponents near
    ln(1e-16) / 2 pi ~ -6 /rev instead of -10 and -30, while the lightly
    damped ones are fine.
    """
    B = coupled(HEAVY)
    mult = np.linalg.eigvals(monodromy(B, method="magnus"))
    eta = np.log(mult.astype(complex)) / TWO_PI
    heavy = np.sort(eta.real)[:3]
    assert np.all(np.abs(heavy - np.array([-30, -10, -10])) > 3.0)
    assert np.all(heavy > -8.0)
    light = eta[eta.real > -1]
    # the other four exponents are kept (to roundoff, modulo the frequency)
    assert_allclose(np.sort(light.real), [-0.2, -0.2, -0.05, -0.05], atol=1e-12)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_constant_coefficient_agrees_with_floquet(seed):
    rng = np.random.default_rng(seed)
    exponents = np.array([-0.02 + 0.35j, -0.02 - 0.35j, -0.3 + 1.6j, -0.3 - 1.6j,
                          -1.5 + 4.2j, -1.5 - 4.2j, -0.8 + 0j, 0.05 + 0j])
    B = coupled(exponents, seed=seed, spread=0.3 * rng.uniform(0.5, 1.5))
    ref = constant_coefficient_modes(B)
    # frequencies up to 4.2 /rev are 4 harmonics away from the principal
    # window (-0.5, 0.5]: the harmonic resolution must restore them exactly
    res = floquet_modes(B, method="magnus")
    assert_allclose(res.exponents, ref.exponents, rtol=0, atol=1e-10)   # roundoff
    assert_allclose(res.multipliers, ref.multipliers, rtol=1e-10, atol=1e-14)
    # same normalisation (unit, largest entry real positive): same vectors
    assert_allclose(res.eigenvectors, ref.eigenvectors, atol=1e-9)
    # RK4: per-step error of a mode is ~ (h lambda)^5 / 120, i.e. an exponent
    # error ~ |lambda|^5 h^4 / 120 = 1.9e3 * 3.6e-6 / 120 ~ 6e-5 for |lambda| = 4.46
    # (observed 5.6e-5)
    rk4 = floquet_modes(B)
    assert_allclose(rk4.exponents, ref.exponents, rtol=0, atol=1e-4)


@pytest.mark.parametrize("omega", [0.5, 1.0, 1.5, 3.0])
def test_repeated_multipliers_of_constant_system(omega):
    """Frequencies in multiples of 1/2 /rev make sigma +- i omega share one
    multiplier (negative real for half-integers: lifted roots exactly on the
    +-pi/K window edges). The pair must still come out as +- omega."""
    lam = np.array([-0.1 + 1j * omega, -0.1 - 1j * omega, -0.4 + 0j])
    B = coupled(lam, seed=4)
    res = floquet_modes(B, method="magnus")
    assert_allclose(matched(lam, res.exponents), lam, atol=1e-10)   # roundoff
    assert len(res.positive_frequency()) == 2


# --------------------------------------------------------------------------
# periodic systems with known exponents


def transformed(B, transform, d_transform):
    """A(psi) of x = P(psi) z, z' = B z:  A = P' P^-1 + P B P^-1 [F]."""
    def A(psi):
        p = transform(psi)
        p_inv = np.linalg.inv(p)
        return d_transform(psi) @ p_inv + p @ B @ p_inv
    return A


# B with frequencies 0.7 and 2.3 /rev: principal exponents (window
# (-0.5, 0.5]) are -0.3 and 0.3 /rev; the harmonic resolution must add 1 and 2
LAM_B = np.array([-0.02 + 0.7j, -0.02 - 0.7j, -0.05 + 2.3j, -0.05 - 2.3j])


@pytest.mark.parametrize("method", ["rk4", "magnus"])
def test_periodic_change_of_variables_diagonal(method):
    B = coupled(LAM_B, seed=1, spread=0.4)
    eps = 0.5

    def P(psi):
        return (1 + eps * np.sin(psi))[:, None, None] * np.eye(4)

    def dP(psi):
        return (eps * np.cos(psi))[:, None, None] * np.eye(4)

    res = floquet_modes(transformed(B, P, dP), method=method, shapes=True)
    # observed errors 1.4e-6 (RK4) and 4e-8 (Magnus) at 144 steps (O(h^4),
    # the 1 + 0.5 sin psi scaling makes A vary steeply); 1e-5 leaves margin
    assert_allclose(matched(LAM_B, res.exponents), LAM_B, atol=1e-5)
    # the periodic shape is P(psi) w (w: eigenvector of B) up to a constant
    # factor: p(psi) / p(0) = 1 + eps sin psi, componentwise
    ratio = res.shapes[:, 0, :] / res.shapes[0, 0, :]
    assert_allclose(ratio, (1 + eps * np.sin(res.psi))[:, None] * np.ones(4), atol=1e-5)


def general_transform_system():
    """x = P(psi) z with P = I + 0.15 (C sin psi + D cos 2 psi), z' = B z."""
    B = coupled(LAM_B, seed=1, spread=0.4)
    rng = np.random.default_rng(7)
    c, d = rng.standard_normal((2, 4, 4))
    eps = 0.15          # keeps P(psi) well conditioned (smallest singular value 0.7)

    def P(psi):
        return np.eye(4) + eps * (np.sin(psi)[:, None, None] * c
                                  + np.cos(2 * psi)[:, None, None] * d)

    def dP(psi):
        return eps * (np.cos(psi)[:, None, None] * c - 2 * np.sin(2 * psi)[:, None, None] * d)

    return transformed(B, P, dP)


def test_periodic_change_of_variables_general():
    A = general_transform_system()
    for method, tol in [("rk4", 1e-5), ("magnus", 1e-6)]:
        # observed at 144 steps: RK4 1.8e-6, Magnus 3.6e-8 (both O(h^4))
        res = floquet_modes(A, method=method)
        assert_allclose(matched(LAM_B, res.exponents), LAM_B, atol=tol)


def test_rotating_frame_shifts_frequency_by_dominant_harmonic():
    """x = R(psi) z, R a rotation by psi: the same solutions seen from a frame
    rotating at 1/rev. R(psi) w = e^{i psi} (I - iJ) w / 2 + e^{-i psi} (I + iJ) w / 2,
    so the frequency is shifted by +1 or -1, whichever part of w dominates
    [PH]; the multipliers are unchanged."""
    B = np.array([[-0.1, 1.0], [-0.5, -0.3]])
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    lam, w = np.linalg.eig(B)

    def R(psi):
        return np.cos(psi)[:, None, None] * np.eye(2) + np.sin(psi)[:, None, None] * J

    res = floquet_modes(transformed(B, R, lambda psi: J @ R(psi)), method="magnus")
    plus = np.linalg.norm((np.eye(2) - 1j * J) @ w, axis=0)
    minus = np.linalg.norm((np.eye(2) + 1j * J) @ w, axis=0)
    expected = lam + 1j * np.where(plus > minus, 1.0, -1.0)
    assert not np.allclose(plus, minus)
    # Magnus: observed error 3e-9 at 144 steps
    assert_allclose(matched(expected, res.exponents), expected, atol=1e-7)
    mult = np.exp(lam * TWO_PI)
    assert_allclose(matched(mult, res.multipliers), mult, atol=1e-7)


# --------------------------------------------------------------------------
# Mathieu's equation [DLMF 28]

MATHIEU_CASES = [(1.0, m) for m in range(4)] + [(5.0, m) for m in range(5)]


def characteristic_values(q, m_max):
    """a_0 < b_1 < a_1 < b_2 < ... for q > 0 [DLMF 28.6(i)], with the parity of m."""
    vals = [(scipy.special.mathieu_a(0, q), 0)]
    for m in range(1, m_max + 1):
        vals += [(scipy.special.mathieu_b(m, q), m), (scipy.special.mathieu_a(m, q), m)]
    return vals


@pytest.mark.parametrize("q, m", MATHIEU_CASES)
@pytest.mark.parametrize("method", ["rk4", "magnus"])
def test_mathieu_characteristic_curves(q, m, method):
    """On a_m(q), b_m(q) a solution has period pi (m even) or 2 pi (m odd):
    a multiplier (-1)^m over the period pi, double (det = 1), so trace = 2 (-1)^m."""
    for a, mm in characteristic_values(q, m):
        if mm != m:
            continue
        tr = np.trace(monodromy(mathieu(a, q), n_steps=400, period=np.pi, method=method))
        # O(h^4): observed <= 1.8e-6 (q = 5, m = 0) at 400 steps; scipy's a_m,
        # b_m are accurate to ~1e-12 (with 3200 Magnus steps |trace - 2| keeps
        # falling as h^4, to 1.3e-12 at q = 1 and 4.4e-10 at q = 5)
        assert_allclose(tr, 2 * (-1) ** m, atol=1e-5)
        # the lifted multipliers reproduce trace and det = exp(0)
        res = floquet_modes(mathieu(a, q), n_steps=400, period=np.pi, method=method)
        assert_allclose(res.multipliers.sum(), 2 * (-1) ** m, atol=1e-5)
        assert_allclose(res.multipliers.prod(), 1.0, atol=1e-9)


@pytest.mark.parametrize("q", [1.0, 5.0])
def test_mathieu_stability_chart(q):
    """Unstable (|trace| > 2) for a < a_0 and inside b_m < a < a_m; stable
    between the tongues [DLMF 28.17]. Points at the interval midpoints, where
    ||trace| - 2| >= 6e-5, far above the 400-step error (< 2e-6)."""
    vals = sorted(v for v, _ in characteristic_values(q, 3))
    points = [vals[0] - 0.5] + [0.5 * (lo + hi) for lo, hi in zip(vals[:-1], vals[1:], strict=True)]
    unstable = [True] + [i % 2 == 1 for i in range(len(vals) - 1)]
    for a, expect in zip(points, unstable, strict=True):
        tr = np.trace(monodromy(mathieu(a, q), n_steps=400, period=np.pi))
        assert (abs(tr) > 2) == expect, (a, tr)
        res = floquet_modes(mathieu(a, q), n_steps=400, period=np.pi)
        assert (res.damping_rates.max() > 1e-6) == expect


@pytest.mark.parametrize("nu", [0.7, 2.3, 3.6])
@pytest.mark.parametrize("damping", [0.0, 0.3])
def test_damped_mathieu_exponents(nu, damping):
    """Exponents -c/2 +- i nu, both known exactly.

    ``y = exp(-c t/2) u`` turns the damped equation into Mathieu's with
    ``a' = a - c^2/4``, so Re eta = -c/2 exactly (stable region); a' = a_nu(q)
    from Hill's method makes u = exp(i nu t) P(t) [DLMF 28.2]. With period pi
    the principal window of Im eta is (-1, 1]: nu = 2.3 and 3.6 need the
    harmonic resolution (shifts 2 and 4 /rad).
    """
    q = 0.4
    a = mathieu_a_of_nu(nu, q) + damping**2 / 4
    res = floquet_modes(mathieu(a, q, damping), n_steps=200, period=np.pi, method="magnus")
    # Magnus at 200 steps per pi: frequency errors observed <= 1.3e-9 (O(h^4));
    # the damping rates are exact to roundoff (the pair's |multiplier|^2 = det
    # = exp(-c pi), which the Simpson/Magnus step reproduces exactly)
    assert_allclose(res.damping_rates, -damping / 2, atol=1e-8)
    assert_allclose(np.sort(res.frequencies), [-nu, nu], atol=1e-8)
    assert_allclose(res.damping_ratios, damping_ratio(-damping / 2 + 1j * nu), atol=1e-8)


# --------------------------------------------------------------------------
# Liouville, convergence, consistency


def test_liouville_abel_jacobi():
    """det Phi(T, 0) = exp(int_0^T tr A dpsi) [F]."""
    def A(psi):
        one, zero = np.ones_like(psi), np.zeros_like(psi)
        c = 0.3 + 0.4 * np.sin(psi) ** 2 + 0.2 * np.cos(3 * psi)     # mean 0.5
        return np.stack([[zero, one, zero],
                         [-(1.2 + 0.5 * np.cos(psi)), -c, 0.1 * one],
                         [0.2 * np.sin(psi), zero, -0.7 * one]]).transpose(2, 0, 1)
    exact = np.exp(-(0.5 + 0.7) * TWO_PI)
    # RK4 at 144 steps: the relative det error is the error of int tr A,
    # observed 2e-7 (O(h^4)); Magnus (Simpson, exact for these harmonics
    # on a periodic grid, commutators traceless) reaches roundoff
    assert_allclose(np.linalg.det(monodromy(A)), exact, rtol=1e-6)
    assert_allclose(np.linalg.det(monodromy(A, method="magnus")), exact, rtol=1e-12)
    phis = transition_matrices(A, n_sub=6)
    assert_allclose(np.prod(np.linalg.det(phis)), exact, rtol=1e-6)


@pytest.mark.parametrize("method", ["rk4", "magnus"])
def test_fourth_order_convergence(method):
    A = general_transform_system()
    ref = monodromy(A, n_steps=4608, method=method)       # error 32^4 ~ 1e6 times below N=144
    err = [np.linalg.norm(monodromy(A, n, method=method) - ref) for n in (36, 72, 144)]
    order = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    # error ~ h^4: observed orders 4.04, 4.01 (RK4) and 3.96, 3.99 (Magnus)
    assert_allclose(order, 4.0, atol=0.15)


def test_samples_callable_and_constant_inputs_agree():
    B = coupled(LAM_B, seed=2)
    A = transformed(B, lambda psi: (1 + 0.3 * np.cos(psi))[:, None, None] * np.eye(4),
                    lambda psi: (-0.3 * np.sin(psi))[:, None, None] * np.eye(4))
    n = 60
    samples = A(np.arange(2 * n) * TWO_PI / (2 * n))   # periodic grid j T / (2n), j < 2n
    # same arithmetic except A(T), recomputed vs copied from A(0): roundoff
    assert_allclose(step_propagators(samples), step_propagators(A, n), rtol=0, atol=1e-13)
    const = np.broadcast_to(B, (2 * n, 4, 4))
    assert_allclose(step_propagators(B, n), step_propagators(const), rtol=0, atol=1e-15)
    assert_allclose(monodromy(B, n), monodromy(lambda psi: np.broadcast_to(B, (psi.size, 4, 4)), n),
                    rtol=0, atol=1e-13)


def test_sub_intervals_multiply_to_monodromy():
    A = mathieu(2.0, 0.7, 0.1)
    phis = transition_matrices(A, n_steps=50, n_sub=8, period=np.pi)   # uneven: 6 or 7 steps
    prod = np.linalg.multi_dot(phis[::-1])
    # different association of the same 50 step matrices: roundoff
    assert_allclose(prod, monodromy(A, n_steps=50, period=np.pi), atol=1e-13)
    even = floquet_modes(A, n_steps=48, n_sub=8, period=np.pi)
    uneven = floquet_modes(A, n_steps=50, n_sub=8, period=np.pi)
    # both RK4 at ~50 steps per pi: O(h^4) difference, observed 1e-6
    assert_allclose(uneven.exponents, even.exponents, atol=1e-5)


def test_lifted_eigenvectors_are_monodromy_eigenvectors():
    A = mathieu(3.1, 1.3, 0.05)
    phis = transition_matrices(A, period=np.pi, n_sub=5)
    mult, vec = characteristic_multipliers(phis, return_vectors=True)
    phi = np.linalg.multi_dot(phis[::-1])
    # residual at roundoff relative to ||Phi|| ~ 1
    assert_allclose(phi @ vec, vec * mult, atol=1e-12)
    assert_allclose(np.linalg.norm(vec, axis=0), 1.0)
    # single matrix: plain eigenvalues
    assert_allclose(np.sort_complex(characteristic_multipliers(phi)),
                    np.sort_complex(np.linalg.eigvals(phi)), atol=1e-12)


def test_periodic_shapes_reconstruct_the_solution():
    """x(psi_m) = exp(eta psi_m) p(psi_m) must equal the step-propagated solution."""
    A = mathieu(2.6, 0.8, 0.2)
    res = floquet_modes(A, period=np.pi, shapes=True)
    p = step_propagators(A, period=np.pi)
    x = res.eigenvectors.astype(complex)
    for m in range(len(p)):
        expected = res.shapes[m] * np.exp(res.exponents * res.psi[m])
        assert_allclose(x, expected, atol=1e-12)       # same arithmetic path up to roundoff
        x = p[m] @ x
    assert_allclose(res.shapes[0], res.eigenvectors)
    assert res.shapes.shape == (DEFAULT_N_STEPS, 2, 2)


def test_result_helpers():
    res = constant_coefficient_modes(coupled(LAM_B, seed=3))
    assert isinstance(res, FloquetResult) and len(res) == 4
    pos = res.positive_frequency()
    assert_allclose(np.sort(pos.frequencies), [0.7, 2.3], atol=1e-12)
    assert pos.eigenvectors.shape == (4, 2)
    sigma, omega = res.damping_rates, res.frequencies
    assert_allclose(res.damping_ratios, -sigma / np.hypot(sigma, omega))
    assert_allclose(res.multipliers, np.exp(res.exponents * TWO_PI))
    assert damping_ratio(0.0) == 0.0
    # conjugate pairs of a real system come out as conjugates
    assert_allclose(np.sort_complex(res.exponents.conj()), np.sort_complex(res.exponents))


def test_complex_system():
    # a complex constant A (no conjugate pairs); frequencies 1.4 and -0.6 /rev
    B = np.array([[-0.1 + 1.4j, 0.3], [0.2j, -0.2 - 0.6j]])
    ref = constant_coefficient_modes(B)
    res = floquet_modes(B, method="magnus")
    assert_allclose(res.exponents, ref.exponents, atol=1e-12)      # roundoff


# --------------------------------------------------------------------------
# input validation: clear ValueErrors, never silent NaN


def test_validation_shapes():
    with pytest.raises(ValueError, match="square"):
        monodromy(lambda psi: np.zeros((psi.size, 2, 3)))
    with pytest.raises(ValueError, match="vectorised"):
        monodromy(lambda psi: np.eye(2))                   # not vectorised
    with pytest.raises(ValueError, match="square"):
        monodromy(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="even"):
        monodromy(np.zeros((7, 2, 2)))
    with pytest.raises(ValueError, match="n_steps = 3"):
        monodromy(np.zeros((6, 2, 2)), n_steps=5)
    with pytest.raises(ValueError, match="shape"):
        monodromy(np.zeros((4, 2, 2, 2)))
    with pytest.raises(ValueError, match="n >= 1"):
        monodromy(np.zeros((0, 0)))
    with pytest.raises(ValueError, match="numeric"):
        monodromy(np.array([["a", "b"], ["c", "d"]]))
    with pytest.raises(ValueError, match="shape"):
        characteristic_multipliers(np.zeros((2, 2, 3)))
    with pytest.raises(ValueError, match="square"):
        constant_coefficient_modes(np.zeros((2, 3)))


def test_validation_non_finite():
    def A(psi):
        a = np.zeros((psi.size, 2, 2))
        a[psi > 3.0, 1, 0] = np.nan
        return a
    with pytest.raises(ValueError, match=r"non-finite.*psi = 3\.0"):
        floquet_modes(A)
    with pytest.raises(ValueError, match="non-finite"):
        monodromy(np.array([[0.0, np.inf], [0.0, 0.0]]))
    with pytest.raises(ValueError, match="non-finite"):
        characteristic_multipliers(np.full((2, 2, 2), np.nan))
    with pytest.raises(ValueError, match="non-finite"):
        constant_coefficient_modes([[np.nan]])
    with pytest.raises(ValueError, match="overflowed"):
        monodromy(np.array([[1e300]]), n_steps=1, method="magnus")


def test_validation_parameters():
    B = np.eye(2)
    for kwargs, msg in [({"n_steps": 0}, "n_steps"), ({"n_steps": 2.5}, "n_steps"),
                        ({"n_steps": True}, "n_steps"), ({"n_sub": 0}, "n_sub"),
                        ({"n_steps": 4, "n_sub": 5}, "exceeds"), ({"period": -1}, "period"),
                        ({"period": np.nan}, "period"), ({"period": "x"}, "period"),
                        ({"method": "euler"}, "method")]:
        with pytest.raises(ValueError, match=msg):
            floquet_modes(B, **kwargs)


def test_rk4_step_limit_warns():
    """h |lambda| beyond ~2.8 makes RK4 unstable: a damped mode would come out
    growing. Warn instead of returning a silently wrong stability answer."""
    B = np.diag([-100.0, -0.1])
    with pytest.warns(RuntimeWarning, match="RK4 step"):
        monodromy(B, n_steps=144)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = floquet_modes(B, method="magnus")               # no step limit
    assert_allclose(res.damping_rates.max(), -0.1, atol=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_unresolvable_modes_degrade_gracefully(seed):
    """A -1000 /rev state is far beyond the K = 8 resolution floor (block
    multiplier e^{-785}): it must come out as a finite, strongly damped
    exponent (below ~ -40 /rev) without spoiling the others or producing NaN.
    The lifting may warn that its roots do not form the K-fold pattern."""
    lam = np.array([-1000.0, -1.0, -0.1])
    B = coupled(lam, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = floquet_modes(B, method="magnus", shapes=True)
    assert np.isfinite(res.exponents).all() and np.isfinite(res.shapes).all()
    assert np.isfinite(res.damping_ratios).all()
    got = np.sort(res.damping_rates)
    assert got[0] < -40
    # the resolved two: roundoff amplified by the non-normal coupling (observed
    # <= 7e-13 over these seeds; seeds 0 and 3 take the lifting's fallback path)
    assert_allclose(got[1:], [-1.0, -0.1], atol=1e-11)


def test_positive_frequency_keeps_self_conjugate_roots():
    """A real multiplier has no conjugate partner: whatever sign of omega
    the integer shift gave it (it is arbitrary, e.g. -4 for an overdamped
    pair locked at 4/rev), positive_frequency must keep it, conjugated.
    Dropping such roots lost the MDART torsion mode from the Fig. 12 table."""
    eta = np.array([-0.1 + 1.0j, -0.1 - 1.0j, -6.1 - 4.0j, -5.6 - 4.0j, -0.3 + 0.0j])
    vec = np.eye(5, dtype=complex) + 0.1j
    res = FloquetResult(exponents=eta, multipliers=np.exp(eta * 2 * np.pi),
                        eigenvectors=vec, period=2 * np.pi)
    pos = res.positive_frequency()
    # the +-1 pair gives one mode, the two locked roots and the real root stay
    assert_allclose(np.sort(pos.frequencies), [0.0, 1.0, 4.0, 4.0])
    assert_allclose(np.sort(pos.damping_rates), [-6.1, -5.6, -0.3, -0.1])
    # conjugated with their exponent: still eigenvectors of the conjugate multiplier
    flipped = np.isclose(pos.frequencies, 4.0)
    assert_allclose(pos.eigenvectors[:, flipped], np.conj(vec[:, 2:4]))
    assert_allclose(pos.multipliers, np.exp(pos.exponents * 2 * np.pi))


def test_sub_intervals_are_raised_for_heavily_damped_roots():
    # exponents -0.05 +- 1i and -12 +- 3.5i (constant, non-normal): with
    # K = 4 the -12 root of the lift is |mu| = exp(-12 pi / 2) ~ 7e-9, below
    # MIN_ROOT (1e-6), so K goes to the power of two that lifts it above the
    # floor, chosen before the lift from the explicit product's eigenvalues
    # (K ln|mu| / ln 1e-6 ~ 5.5 -> 8); the light system keeps K = 4
    from tefcore.floquet import MIN_ROOT

    lam = np.array([-0.05 + 1j, -0.05 - 1j, -12 + 3.5j, -12 - 3.5j])
    A = coupled(lam, seed=1)
    res = floquet_modes(A, method="magnus", n_sub=4)
    assert res.n_sub == 8
    assert np.exp(-12 * TWO_PI / res.n_sub) >= MIN_ROOT > np.exp(-12 * TWO_PI / 4)
    # constant A: the exponents are exactly eig(A) up to the resolved
    # frequency shift; damping rates to Magnus/round-off accuracy
    assert_allclose(np.sort(res.damping_rates), np.sort(lam.real), atol=1e-8)
    light = floquet_modes(coupled(lam[:2], seed=1), method="magnus", n_sub=4)
    assert light.n_sub == 4
    # max_sub <= n_sub keeps K: the heavily damped root is then at the floor
    fixed = floquet_modes(A, method="magnus", n_sub=4, max_sub=4)
    assert fixed.n_sub == 4


@pytest.mark.parametrize("bad", [0, -2, 1.5, "8"])
def test_max_sub_validation(bad):
    with pytest.raises((ValueError, TypeError), match="max_sub"):
        floquet_modes(np.eye(2) * -0.1, max_sub=bad)


# --------------------------------------------------------------------------
# accuracy control

HEAVY_24 = np.array([-24.0 + 0j, -0.1 + 1.3j, -0.1 - 1.3j])


def heavy_periodic_system():
    """x = (1 + 0.3 sin psi) z, z' = B z with exponents -24 and -0.1 +- 1.3i."""
    B = coupled(HEAVY_24, seed=4, spread=0.3)

    def P(psi):
        return (1 + 0.3 * np.sin(psi))[:, None, None] * np.eye(3)

    def dP(psi):
        return (0.3 * np.cos(psi))[:, None, None] * np.eye(3)

    return transformed(B, P, dP)


def test_default_rk4_controls_its_error_on_a_heavily_damped_root():
    """RK4 at a fixed 144 steps (its default) puts a -24 /rev root at about -23.4
    (h lambda = 1.05: one-step factor 0.360 against e^-1.05 = 0.351).
    With the step-doubling control the steps double until the estimate meets
    1e-3 + 1e-3 |sigma| = 0.025 for that root."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = floquet_modes(heavy_periodic_system())
    got = matched(HEAVY_24, res.exponents)
    # RK4 error ~ |lambda|^5 h^4 / 120: 1.2e-3 at 576 steps, within the 0.025 tolerance
    assert_allclose(got.real, HEAVY_24.real, atol=0.025)
    assert res.n_steps == 4 * DEFAULT_N_STEPS
    est = res.error_estimates[np.argmin(res.exponents.real)]
    assert abs(got[0].real + 24) <= 4 * est.real          # the estimate is honest
    # without the control: the fixed-step answer, 0.6 /rev off
    old = floquet_modes(heavy_periodic_system(), atol=None)
    assert old.n_steps == DEFAULT_N_STEPS and old.error_estimates is None
    assert abs(old.exponents.real.min() + 24) > 0.5


def test_light_roots_keep_the_first_grid_and_report_their_error():
    res = floquet_modes(general_transform_system(), method="magnus")
    assert res.n_steps == DEFAULT_N_STEPS                 # estimate 1e-9: no refinement
    assert np.all(res.error_estimates.real < 1e-6)
    # the estimate follows the error: observed 3.6e-8 at 144 steps (see above)
    err = np.abs(matched(LAM_B, res.exponents) - LAM_B).max()
    assert err < 10 * np.abs(res.error_estimates).max()


def test_an_unmet_tolerance_warns_or_raises():
    from tefcore.floquet import FloquetAccuracyError, FloquetAccuracyWarning

    A = heavy_periodic_system()
    with pytest.warns(FloquetAccuracyWarning, match=r"-2\d\.\d+.*not converged at n_steps = 144"):
        floquet_modes(A, max_steps=144)
    with pytest.raises(FloquetAccuracyError, match="cannot be trusted"):
        floquet_modes(A, max_steps=144, on_inaccurate="raise")
    # periodic samples cannot be refined: the estimate still warns
    samples = A(np.arange(288) * TWO_PI / 288)
    with pytest.warns(FloquetAccuracyWarning):
        floquet_modes(samples)


def test_overflow_is_a_named_error():
    """A transition matrix that overflows at every step count is a FloquetOverflowError
    (a ValueError), not scipy's 'array must not contain infs or NaNs'."""
    from tefcore.floquet import FloquetOverflowError

    with pytest.raises(FloquetOverflowError, match="overflow.*n_steps = 4"):
        floquet_modes(np.diag([400.0, -1.0]), n_steps=2, max_steps=4, method="magnus", n_sub=1)


@pytest.mark.parametrize("kwargs, msg", [({"atol": -1.0}, "atol"), ({"rtol": np.nan}, "rtol"),
                                         ({"max_steps": 0}, "max_steps"),
                                         ({"on_inaccurate": "ignore"}, "on_inaccurate")])
def test_accuracy_parameters_are_validated(kwargs, msg):
    with pytest.raises(ValueError, match=msg):
        floquet_modes(np.eye(2) * -0.1, **kwargs)


def test_batched_exponential_matches_scipy():
    # the Magnus steps' exponential (scaling and squaring of a degree-16 Taylor
    # polynomial): within round-off of scipy's Pade expm, 1e-15 relative for small
    # norms, growing with the squarings (1e-13 at norm 30, as for any scaling and
    # squaring); exact for a rotation
    from tefcore.floquet._propagators import expm_batch

    rng = np.random.default_rng(3)
    for scale, tol in ((1e-3, 1e-15), (0.3, 1e-14), (3.0, 1e-13), (30.0, 1e-12)):
        a = rng.standard_normal((5, 12, 12)) * scale / np.sqrt(12)
        ref = np.stack([scipy.linalg.expm(x) for x in a])
        assert np.abs(expm_batch(a) - ref).max() < tol * np.abs(ref).max()
    t = 0.7
    rot = expm_batch(np.array([[[0.0, -t], [t, 0.0]]]))[0]
    assert_allclose(rot, [[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]], atol=1e-16)


def test_a_rotor_step_is_balanced_before_its_exponential():
    """An oscillator's state matrix [[0, 1], [-w^2, -c]] has entries 1 and w^2:
    its 1-norm is w^2, while exp(A h) only turns by w h.  Balanced by powers of
    two (an exact similarity), the scaling and squaring sees a norm near w h;
    the exponential is the closed form's rotation-with-decay to round-off,
    where without balancing the squarings of norm w^2 h = 140 lose a digit
    (7.3e-15 against 1.2e-15 relative, measured; gate 3e-15 between)."""
    from tefcore.floquet._propagators import _balancing, _expm, expm_batch

    w, c, h = 40.0, 0.4, 2 * np.pi / 72
    a = h * np.array([[[0.0, 1.0], [-w * w, -c]]])
    # closed form: x'' + c x' + w^2 x = 0 over h
    wd = np.sqrt(w * w - c * c / 4)
    e, co, si = np.exp(-c * h / 2), np.cos(wd * h), np.sin(wd * h)
    exact = e * np.array([[co + c / (2 * wd) * si, si / wd],
                          [-w * w / wd * si, co - c / (2 * wd) * si]])
    t = _balancing(a)
    assert t is not None and np.all(np.log2(t) == np.round(np.log2(t)))   # powers of two
    balanced = a / t[:, None] * t[None, :]
    assert np.abs(balanced).sum(axis=-2).max() < 0.1 * np.abs(a).sum(axis=-2).max()
    scale = np.abs(exact).max()
    assert np.abs(expm_batch(a)[0] - exact).max() < 3e-15 * scale
    # the unbalanced exponential misses the gate (round-off grows with the
    # squarings): the balancing is what the gate above measures
    assert np.abs(_expm(a)[0] - exact).max() > 3e-15 * scale


def test_balanced_exponential_of_odd_stacks():
    """Balancing is an exact similarity whatever the stack: a complex graded
    stack (entries from 1e-6 to 1e6) within 1e-13 of scipy's expm relative to
    its largest entry (1.3e-15 measured, 3e-11 without the balancing); a zero
    row and column (nothing to
    balance there), one 1x1 matrix and an empty stack as before; non-finite
    input, or a finite complex entry whose modulus overflows, gives NaN of the
    same shape and dtype (``|a|`` overflows there, and the balancing must not
    raise)."""
    from tefcore.floquet._propagators import expm_batch

    rng = np.random.default_rng(7)
    grade = 10.0 ** np.linspace(-3, 3, 6)
    a = (rng.standard_normal((3, 6, 6)) + 1j * rng.standard_normal((3, 6, 6))) \
        * grade[:, None] / grade[None, :] * 0.3
    ref = np.stack([scipy.linalg.expm(x) for x in a])
    assert np.abs(expm_batch(a) - ref).max() < 1e-13 * np.abs(ref).max()
    z = rng.standard_normal((2, 4, 4))
    z[:, 1, :] = 0.0
    z[:, :, 1] = 0.0
    ref = np.stack([scipy.linalg.expm(x) for x in z])
    assert np.abs(expm_batch(z) - ref).max() < 1e-14 * np.abs(ref).max()
    assert_allclose(expm_batch(np.array([[[0.5]]])), [[[np.exp(0.5)]]], rtol=1e-15)
    assert expm_batch(np.zeros((0, 3, 3))).shape == (0, 3, 3)
    for bad in (np.array([[[np.nan, 0.0], [0.0, 1.0]]]),
                np.array([[[1.5e308 + 1.5e308j, 0.0], [0.0, 1.0]]])):
        out = expm_batch(bad)
        assert out.shape == bad.shape and out.dtype == bad.dtype and np.isnan(out).all()


@pytest.mark.parametrize("kwargs", [{"min_root": 0.0}, {"min_root": 1.0}, {"root_rtol": -1e-3},
                                    {"root_rtol": float("nan")}, {"min_root": "1e-9"}])
def test_the_trust_of_the_lift_is_validated(kwargs):
    with pytest.raises(ValueError, match=next(iter(kwargs))):
        floquet_motions(np.array([[0.0, 1.0], [-0.09, 0.0]]), 72, **kwargs)


def test_sub_intervals_are_chosen_before_the_lift(monkeypatch):
    # the K that the heavily damped roots need comes from the explicit product's
    # eigenvalues before solving: one lift, not one per trial K (the -12 /rev
    # pair of the coupled system needs K = 8, found without solving K = 4 first)
    import tefcore.floquet._analysis as fm

    calls = []
    real = fm.lifted

    def counting(phis, *args, **kwargs):
        calls.append(phis.shape[0])
        return real(phis, *args, **kwargs)

    monkeypatch.setattr(fm, "lifted", counting)
    lam = np.array([-0.05 + 1j, -0.05 - 1j, -12 + 3.5j, -12 - 3.5j])
    res = floquet_modes(coupled(lam, seed=1), method="magnus", n_sub=1, atol=None)
    assert res.n_sub == 8 and calls == [8]
    # a light system: the explicit product resolves every multiplier, K = 1
    calls.clear()
    light = floquet_modes(coupled(lam[:2], seed=1), method="magnus", n_sub=1, atol=None)
    assert light.n_sub == 1 and calls == [1]
    assert_allclose(np.sort(light.damping_rates), [-0.05, -0.05], atol=1e-9)
