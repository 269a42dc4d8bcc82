"""Tests of tefcore.aero.theodorsen: T-functions, quasi-steady loads, flap lift.

Every closed form is checked against an independent computation:

* T-functions against quadrature of the integrals they stand for (scipy quad,
  and the apparent-mass potential computed from Theodorsen's source-sink
  representation by tanh-sinh quadrature) and against published numbers;
* the quasi-steady loads, motion term by motion term, against quadrature of
  the thin-airfoil pressure (``theodorsen.quadrature_loads``);
* the steady parts against Glauert's solution for the kinked camber line.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from tefcore.aero.theodorsen import (
    T_NAMES,
    apparent_mass_potential,
    kutta_circulation,
    loads_to_tefcore,
    motion_to_theodorsen,
    quadrature_loads,
    quasi_steady_loads,
    t_functions,
)

HINGES = [-0.8, -0.3, 0.0, 0.3, 0.6, 0.9]
ZERO_MOTION = dict(alpha=0.0, alpha_dot=0.0, alpha_ddot=0.0, h=0.0, h_dot=0.0, h_ddot=0.0,
                   beta=0.0, beta_dot=0.0, beta_ddot=0.0)
# scipy quad on smooth (or end-point sqrt/log) integrands reaches ~1e-13 absolute
# on these O(1) integrals; 1e-10 leaves a wide margin.
QUAD_TOL = dict(rtol=1e-10, atol=1e-10)


def _quad(f, lo, hi, **kw):
    return quad(f, lo, hi, epsabs=1e-13, epsrel=1e-12, limit=200, **kw)[0]


def _sq(x):
    return math.sqrt(1.0 - x * x)


@pytest.mark.parametrize("c", HINGES)
def test_t_functions_match_their_defining_integrals(c):
    a = -0.35
    t = t_functions(c, a)
    # sqrt((1+x)/(1-x)) over (c, 1): quad's algebraic weight (1 - x)^(-1/2) takes the
    # end-point singularity, the rest is smooth
    w_half = dict(weight="alg", wvar=(0.0, -0.5))
    assert_allclose(t["T10"], _quad(lambda x: math.sqrt(1 + x), c, 1, **w_half), **QUAD_TOL)
    assert_allclose(t["T11"], 2 * _quad(lambda x: (x - c) * math.sqrt(1 + x), c, 1, **w_half),
                    **QUAD_TOL)
    # T12: circulatory hinge moment of the flat plate, 2 int (x - c) sqrt((1-x)/(1+x))
    assert_allclose(t["T12"], 2 * _quad(lambda x: (x - c) * (1 - x) / math.sqrt(1 + x), c, 1,
                                        **w_half), **QUAD_TOL)
    assert_allclose(t["T4"], -2 * _quad(_sq, c, 1), **QUAD_TOL)
    assert_allclose(t["T1"], -2 * _quad(lambda x: (x - c) * _sq(x), c, 1), **QUAD_TOL)
    s3 = _quad(lambda x: x * _sq(x), c, 1)                       # = s^3 / 3
    assert_allclose(t["T8"], -s3 - c * t["T4"], **QUAD_TOL)
    assert_allclose(t["T9"], 0.5 * (s3 + a * t["T4"]), **QUAD_TOL)
    assert_allclose(t["T7"] + c * t["T1"], -_quad(lambda x: x * (x - c) * _sq(x), c, 1),
                    **QUAD_TOL)
    # T13 and T14 are defined algebraically from the others
    assert_allclose(t["T13"], 0.5 * (-t["T7"] - (c - a) * t["T1"]), rtol=1e-15)
    assert_allclose(t["T14"], 1 / 16 + a * c / 2, rtol=1e-15)


def _flap(c):
    return lambda x: np.where(np.asarray(x) > c, 1.0, 0.0)


def _flap_ramp(c):
    return lambda x: np.where(np.asarray(x) > c, np.asarray(x) - c, 0.0)


@pytest.mark.parametrize("c", [-0.5, 0.3, 0.7])
def test_apparent_mass_t_functions_by_quadrature_of_the_potential(c):
    # dphi for w = H (flap translating) and w = (x - c) H (flap rotating about c),
    # from the source-sink integral; T5, T2, T3 are its flap moments times pi.
    t = t_functions(c)

    def pot_h(x):
        return apparent_mass_potential(_flap(c), x, breaks=(c,))[0]

    def pot_r(x):
        return apparent_mass_potential(_flap_ramp(c), x, breaks=(c,))[0]

    # Nested quadrature: inner tanh-sinh ~1e-13, outer quad ~1e-12 on an O(1) value.
    tol = dict(rtol=1e-9, atol=1e-10)
    assert_allclose(math.pi * _quad(pot_h, c, 1), t["T5"], **tol)
    assert_allclose(math.pi * _quad(pot_r, c, 1), t["T2"], **tol)
    assert_allclose(math.pi * _quad(lambda x: pot_r(x) * (x - c), c, 1), t["T3"], **tol)


def test_numerical_reference_reproduces_the_flat_plate():
    # w = 1: dphi = -2 sqrt(1 - x^2), Gamma = -2 pi; w = x: dphi = -x sqrt(1 - x^2),
    # Gamma = -pi.  Tanh-sinh on analytic integrands: ~1e-13.
    x = np.linspace(-0.99, 0.99, 9)
    assert_allclose(apparent_mass_potential(lambda s: 1 + 0 * s, x), -2 * np.sqrt(1 - x * x),
                    atol=1e-12)
    assert_allclose(apparent_mass_potential(lambda s: s, x), -x * np.sqrt(1 - x * x),
                    atol=1e-12)
    assert_allclose(kutta_circulation(lambda s: 1 + 0 * s), -2 * math.pi, rtol=1e-13)
    assert_allclose(kutta_circulation(lambda s: s), -math.pi, rtol=1e-13)


def test_published_numbers_twenty_percent_flap():
    # 20 % flap, hinge at c = 0.6; values quoted to 5 decimals, so atol 5e-6.
    e = 0.2
    t = t_functions(0.6)
    assert_allclose(2 * t["T10"], 3.45459, atol=5e-6)
    ch_alpha = -t["T12"] / 2 / e**2
    ch_delta = -(t["T5"] - t["T4"] * t["T10"] + t["T10"] * t["T12"]) / (2 * math.pi) / e**2
    assert_allclose(ch_alpha, -0.49938, atol=5e-6)
    assert_allclose(ch_delta, -0.92288, atol=5e-6)


@pytest.mark.parametrize("f", [0.05, 0.1, 0.2, 0.3, 0.35, 0.5, 0.7, 0.9])
def test_hinge_moment_slope_against_glauert_textbook(f):
    # Houghton & Carpenter / Glauert: b2 = [(1 - cos 2phi) - 2 (pi - phi)^2 (1 - 2 cos phi)
    # + 4 (pi - phi) sin phi] / (4 pi F^2), cos phi = 2F - 1: the magnitude of the flap-chord
    # hinge-moment slope.  Two closed forms evaluated in double precision: rtol 1e-12.
    phi = math.acos(2 * f - 1)
    b2 = ((1 - math.cos(2 * phi)) - 2 * (math.pi - phi) ** 2 * (1 - 2 * math.cos(phi))
          + 4 * (math.pi - phi) * math.sin(phi)) / (4 * math.pi * f * f)
    loads = loads_to_tefcore(quasi_steady_loads(**{**ZERO_MOTION, "beta": 1.0}, U=1.0, b=1.0,
                                                rho=1.0, a=0.0, c=1 - 2 * f))
    # C_h on the flap chord: H / (q c_f^2) with q = 1/2, c_f = 2 f (b = 1)
    ch_flap = loads["hinge_moment"] / (0.5 * (2 * f) ** 2)
    assert_allclose(ch_flap, -b2, rtol=1e-12)


def test_t_functions_broadcast_and_validate():
    t = t_functions(np.array([[0.1], [0.5]]), np.array([-0.5, 0.0, 0.25]))
    assert set(t) == set(T_NAMES)
    assert all(np.shape(v) == (2, 3) for v in t.values())
    assert np.ndim(t_functions(0.2)["T1"]) == 0
    for bad in (1.0, -1.0, 1.5, float("nan")):
        with pytest.raises(ValueError, match="hinge location c"):
            t_functions(bad)


# ---------------------------------------------------------------------------
# quasi-steady loads, term by term, against quadrature of the pressure
# ---------------------------------------------------------------------------

U, B, RHO = 60.0, 0.15, 1.1


def _upwash(term, value, c, a):
    """(theodorsen kwargs, w(x), w_dot(x)) for one motion term (tefcore upwash, h down)."""
    h = _flap(c)

    def z(x):
        return 0.0 * np.asarray(x)

    table = {
        "alpha": (lambda x: -U * value + z(x), z),
        "beta": (lambda x: -U * value * h(x), z),
        "h_dot": (lambda x: -value + z(x), z),                    # h down: upwash -h_dot
        "alpha_dot": (lambda x: -B * (x - a) * value, lambda x: -U * value + z(x)),
        "beta_dot": (lambda x: -B * (x - c) * value * h(x), lambda x: -U * value * h(x)),
        "h_ddot": (z, lambda x: -value + z(x)),
        "alpha_ddot": (z, lambda x: -B * (x - a) * value),
        "beta_ddot": (z, lambda x: -B * (x - c) * value * h(x)),
    }
    w, w_dot = table[term]
    return {**ZERO_MOTION, term: value}, w, w_dot


TERMS = ["alpha", "beta", "h_dot", "alpha_dot", "beta_dot", "h_ddot", "alpha_ddot",
         "beta_ddot"]


@pytest.mark.parametrize("term", TERMS)
@pytest.mark.parametrize(("c", "a"), [(0.6, -0.5), (0.3, -0.2), (-0.4, 0.3)])
def test_quasi_steady_loads_match_pressure_quadrature(term, c, a):
    kw, w, w_dot = _upwash(term, 0.7, c, a)
    closed = loads_to_tefcore(quasi_steady_loads(**kw, U=U, b=B, rho=RHO, a=a, c=c))
    numeric = quadrature_loads(w, w_dot, c=c, a=a, U=U, b=B, rho=RHO)
    # The quadrature is good to ~1e-13 relative; moments can be small differences of
    # O(force * b) terms, so the absolute floor is 1e-10 of the force (times b) scale.
    force = max(abs(numeric["lift"]), abs(numeric["flap_lift"]))
    for key in ("lift", "flap_lift"):
        assert_allclose(closed[key], numeric[key], rtol=1e-10, atol=1e-10 * force, err_msg=key)
    for key in ("moment", "hinge_moment"):
        assert_allclose(closed[key], numeric[key], rtol=1e-10, atol=1e-10 * force * B,
                        err_msg=key)


def _glauert_gamma_sin(theta, alpha, delta, c):
    """gamma(theta) sin(theta) / U of Glauert's solution for a flat plate at alpha with a
    flap deflected delta about x = c (camber line kinked there).

    A0 = alpha + delta mu / pi, A_n = (2 delta / pi) sin(n theta_c) / n, theta_c = pi - mu,
    and sum sin(n theta_c) sin(n theta) / n = ln|sin((theta + theta_c)/2) / sin((theta -
    theta_c)/2)| / 2.
    """
    mu = math.acos(c)
    tc = math.pi - mu
    a0 = alpha + delta * mu / math.pi
    log = math.log(abs(math.sin(0.5 * (theta + tc)) / math.sin(0.5 * (theta - tc))))
    return 2 * (a0 * (1 + math.cos(theta)) + delta / math.pi * log * math.sin(theta))


def test_glauert_series_closed_sum():
    # the log form of the Fourier series, checked against 200000 terms at one angle
    # (series tail ~ 1/N: rtol 1e-4)
    c, th = 0.3, 1.0
    tc = math.pi - math.acos(c)
    n = np.arange(1, 200001)
    series = np.sum(np.sin(n * tc) * np.sin(n * th) / n)
    closed = 0.5 * math.log(abs(math.sin(0.5 * (th + tc)) / math.sin(0.5 * (th - tc))))
    assert_allclose(series, closed, rtol=1e-4)


@pytest.mark.parametrize("c", [-0.5, 0.3, 0.6, 0.9])
@pytest.mark.parametrize(("alpha", "delta"), [(1.0, 0.0), (0.0, 1.0)])
def test_steady_loads_against_glauert_kinked_camber_line(c, alpha, delta):
    a = -0.1
    tc = math.pi - math.acos(c)
    q = RHO * U * U * B   # rho U^2 b

    def g(th):
        return _glauert_gamma_sin(th, alpha, delta, c)

    lift = q * _quad(g, 0, math.pi, points=[tc])
    moment = -q * B * _quad(lambda th: g(th) * (-math.cos(th) - a), 0, math.pi, points=[tc])
    flap_lift = q * _quad(g, tc, math.pi)
    hinge = -q * B * _quad(lambda th: g(th) * (-math.cos(th) - c), tc, math.pi)
    closed = loads_to_tefcore(quasi_steady_loads(**{**ZERO_MOTION, "alpha": alpha,
                                                    "beta": delta},
                                                 U=U, b=B, rho=RHO, a=a, c=c))
    # quad with the log singularity split off: ~1e-12 relative
    assert_allclose(closed["lift"], lift, rtol=1e-10)
    assert_allclose(closed["flap_lift"], flap_lift, rtol=1e-10)
    assert_allclose(closed["moment"], moment, rtol=1e-10, atol=1e-12 * q * B)
    assert_allclose(closed["hinge_moment"], hinge, rtol=1e-10, atol=1e-12 * q * B)
    # and the flap-lift closed forms L_f / (rho U^2 b) = 2 (mu - s) alpha + 2 mu^2 / pi delta
    mu, s = math.acos(c), math.sqrt(1 - c * c)
    assert_allclose(flap_lift / q, 2 * (mu - s) * alpha + 2 * mu**2 / math.pi * delta,
                    rtol=1e-10)


@pytest.mark.parametrize(("c", "a"), [(0.6, -0.5), (0.0, 0.2), (-0.7, -0.3)])
def test_apparent_mass_matrix_is_symmetric_positive_definite(c, a):
    # Generalised forces (lift, M_alpha, M_beta) of the coordinates (z up, alpha, beta):
    # the acceleration terms are -M q**, M the fluid's kinetic-energy matrix.  Round-off
    # only: rtol 1e-13.
    cols = []
    for name, scale in (("h_ddot", -1.0), ("alpha_ddot", 1.0), ("beta_ddot", 1.0)):
        ld = loads_to_tefcore(quasi_steady_loads(**{**ZERO_MOTION, name: scale}, U=U, b=B,
                                                 rho=RHO, a=a, c=c))
        cols.append([-ld["lift"], -ld["moment"], -ld["hinge_moment"]])
    m = np.array(cols).T
    assert_allclose(m, m.T, rtol=1e-13, atol=1e-13 * np.abs(m).max())
    assert np.all(np.linalg.eigvalsh(0.5 * (m + m.T)) > 0)


@pytest.mark.parametrize("term", TERMS)
def test_flap_over_whole_chord_is_the_airfoil(term):
    # c -> -1: the flap is the airfoil (P_flap -> P) and a hinge at the leading edge makes
    # beta another pitch about x = -1 (M_beta -> M_alpha at a = -1).  Leading error is
    # O(sqrt(1 - c^2)) ~ 1.4e-7 at 1 + c = 1e-14; rtol 1e-5.
    c = -1 + 1e-14
    kw = {**ZERO_MOTION, term: 0.9}
    out = quasi_steady_loads(**kw, U=U, b=B, rho=RHO, a=c, c=c)
    scale = max(abs(out["P"]), 1e-300)
    assert_allclose(out["P_flap"], out["P"], rtol=1e-5, atol=1e-6 * scale)
    assert_allclose(out["M_beta"], out["M_alpha"], rtol=1e-5, atol=1e-6 * scale * B)


def test_beta_equals_alpha_when_hinged_at_leading_edge():
    # with c = a = -1 (limit), beta motions act exactly like alpha motions
    c = -1 + 1e-14
    for al, be in (("alpha", "beta"), ("alpha_dot", "beta_dot"), ("alpha_ddot", "beta_ddot")):
        pa = quasi_steady_loads(**{**ZERO_MOTION, al: 1.0}, U=U, b=B, rho=RHO, a=c, c=c)
        pb = quasi_steady_loads(**{**ZERO_MOTION, be: 1.0}, U=U, b=B, rho=RHO, a=c, c=c)
        for key in ("P", "M_alpha", "M_beta", "P_flap"):
            # O(sqrt(1 - c^2)) ~ 1.4e-7 relative to the force scale
            assert_allclose(pb[key], pa[key], rtol=1e-5, atol=1e-6 * abs(pa["P"]) * B)


def test_sign_conventions_and_converters():
    kw = motion_to_theodorsen(alpha=0.0, alpha_rate=0.0, alpha_accel=0.0, plunge=0.3,
                              plunge_rate=-2.0, plunge_accel=4.0, delta=0.1, delta_rate=0.2,
                              delta_accel=0.3)
    assert (kw["h"], kw["h_dot"], kw["h_ddot"]) == (-0.3, 2.0, -4.0)
    assert (kw["beta"], kw["beta_dot"], kw["beta_ddot"]) == (0.1, 0.2, 0.3)
    # nose up alpha: Theodorsen P < 0 (down positive), tefcore lift > 0
    out = quasi_steady_loads(**{**ZERO_MOTION, "alpha": 0.1}, U=U, b=B, rho=RHO, a=-0.5, c=0.5)
    assert out["P"] < 0 and out["P_flap"] < 0
    tef = loads_to_tefcore(out)
    assert tef["lift"] == -out["P"] and tef["flap_lift"] == -out["P_flap"]
    assert tef["moment"] == out["M_alpha"] and tef["hinge_moment"] == out["M_beta"]
    # descending plate (tefcore plunge_rate < 0) sees more angle of attack: more lift
    desc = quasi_steady_loads(**{**ZERO_MOTION, "h_dot": 1.0}, U=U, b=B, rho=RHO, a=0, c=0.5)
    assert -desc["P"] > 0
    # flap down: positive lift, nose-down quarter-chord moment, TE-up hinge moment
    fl = loads_to_tefcore(quasi_steady_loads(**{**ZERO_MOTION, "beta": 0.1}, U=U, b=B,
                                             rho=RHO, a=-0.5, c=0.5))
    assert fl["lift"] > 0 and fl["moment"] < 0 and fl["hinge_moment"] < 0 and fl["flap_lift"] > 0
