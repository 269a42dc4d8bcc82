"""Rotating finite-element beam against closed forms and published tables.

All frequencies are nondimensional: for the uniform beams below the rotor
units make ``m = 1`` and ``L = 1`` (root at the axis), so a nonrotating
frequency in "per rev" is ``omega / Omega_ref`` and the published
``omega * sqrt(m L^4 / EI)`` is recovered by multiplying by ``lambda``.
"""

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
from numpy.testing import assert_allclose

from tefcore.structure.fem import (
    RootSprings,
    _dof_owner,
    _lowest_modes,
    _uncoupled_blocks,
    assemble_beam,
    beam_modes,
    tension_from_mass,
    tension_piecewise_linear,
)

CLAMP = RootSprings(flap=np.inf, lag=np.inf, torsion=np.inf)


def uniform(mass=1.0, ei_flap=1.0, ei_lag=1.0, gj=1.0, ea=1e5, im_flap=0.0, im_lag=1e-2,
            cg_offset=0.0, tension_offset=0.0, ka=0.0):
    vals = dict(mass=mass, ei_flap=ei_flap, ei_lag=ei_lag, gj=gj, ea=ea, im_flap=im_flap,
                im_lag=im_lag, cg_offset=cg_offset, tension_offset=tension_offset, ka=ka)

    def section(x):
        x = np.asarray(x, float)
        return {k: np.full_like(x, v) for k, v in vals.items()}
    return section


def flat(x):
    return np.zeros_like(np.asarray(x, float))


def eig(beam, which="k_elastic", speed_ratio=1.0, n=8):
    """All lowest frequencies of the free dofs (per rev of the reference speed)."""
    f = beam.free
    k = beam.k_elastic if which == "k_elastic" else beam.stiffness(speed_ratio)
    # inverse form (largest 1/lambda) keeps the low modes exact beside the
    # very stiff axial ones, see tefcore.structure.fem._lowest_modes
    mu = scipy.linalg.eigh(beam.mass[np.ix_(f, f)], k[np.ix_(f, f)], eigvals_only=True)
    return np.sqrt(1.0 / mu[::-1][:n])


# Euler-Bernoulli cantilever: (beta_n L)^2 from cos(bL)cosh(bL) = -1
CANTILEVER = np.array([1.8751040687, 4.6940911330, 7.8547574382]) ** 2


def test_nonrotating_cantilever_bending_converges():
    # Hermite cubics converge as h^4 in frequency: with 20 elements the third
    # mode is within 1.6e-5 (measured), so the gate is 3e-5; the error must
    # fall by about 16x per halving of h (asserted: by more than 10x).
    errors = []
    for n_el in (5, 10, 20):
        beam = assemble_beam(np.linspace(0, 1, n_el + 1), uniform(ei_lag=4.0, gj=1e3),
                             flat, CLAMP)
        f = eig(beam, n=12)
        flap = np.sort(f)[[0, 2, 4]]     # flap (EI=1) interleaves with lag (EI=4)
        lag = 2.0 * CANTILEVER
        errors.append(np.abs(flap / CANTILEVER - 1))
        assert_allclose(f[np.isclose(f, lag[0], rtol=1e-3)], lag[0], rtol=1e-4)
    errors = np.array(errors)
    assert np.all(errors[1:, 2] < errors[:-1, 2] / 10), "third mode must converge as h^4"
    assert_allclose(flap, CANTILEVER, rtol=3e-5)


def test_nonrotating_torsion_quadratic_elements_converge():
    # omega_n = (2n-1) pi/2 sqrt(GJ/I); consistent-mass quadratic elements
    # converge as h^4 in frequency (measured: x15.6 per halving), so each
    # halving must gain more than 10x; 16 elements: 4.0e-5 on the third mode.
    exact = np.array([1, 3, 5]) * np.pi / 2 * np.sqrt(1.0 / 1e-2)
    errs = []
    for n_el in (4, 8, 16):
        beam = assemble_beam(np.linspace(0, 1, n_el + 1),
                             uniform(ei_flap=1e6, ei_lag=1e6), flat, CLAMP)
        errs.append(np.abs(eig(beam, n=3) / exact - 1))
    errs = np.array(errs)
    assert np.all(errs[1:] < errs[:-1] / 10)
    assert np.all(errs[-1] < 5e-5)


def test_torsion_root_spring_closed_form():
    # Uniform shaft, root spring k, free tip: beta tan(beta) = k L / GJ,
    # omega = beta sqrt(GJ / I).  Spring of 2 GJ/L gives beta ~ 1.0769.
    k, gj, im = 2.0, 1.0, 1e-2
    beta = scipy.optimize.brentq(lambda b: b * np.tan(b) - k / gj, 0.1, np.pi / 2 - 1e-9)
    beam = assemble_beam(np.linspace(0, 1, 21), uniform(ei_flap=1e6, ei_lag=1e6, gj=gj,
                                                        im_lag=im),
                         flat, RootSprings(flap=np.inf, lag=np.inf, torsion=k))
    # quadratic torsion elements, 20 of them: measured error 6.6e-6
    assert_allclose(eig(beam, n=1), beta * np.sqrt(gj / im), rtol=2e-5)


def test_propeller_moment_adds_one_per_rev_squared():
    # With I_m1 = 0 and zero pitch the propeller moment is Omega^2 I_m phi^2,
    # exactly proportional to the torsional inertia: nu^2 = nu0^2 + 1.
    # bending and axial stiffness moderate: far-apart stiffness scales make
    # the generalized eigenproblem ill-conditioned, which is not under test here
    beam = assemble_beam(np.linspace(0.1, 1, 21), uniform(ei_flap=1e2, ei_lag=1e2, ea=1e4),
                         flat, RootSprings(flap=np.inf, lag=np.inf, torsion=0.5))
    nu0 = eig(beam, n=1)
    nu = beam_modes(beam, n_modes=1).frequencies
    assert_allclose(nu**2, nu0**2 + 1.0, rtol=1e-9)


# Flapwise frequencies of a uniform rotating cantilever (no hub offset),
# omega sqrt(mL^4/EI) at lambda = Omega sqrt(mL^4/EI): Wright, Smith, Thresher
# & Wang, "Vibration modes of centrifugally stiffened beams", J. Appl. Mech.
# 49 (1982) 197-202, and Hodges & Rutkowski, AIAA J. 19 (1981) 1459-1466.
# The values were re-derived independently with a 400-term power series at
# 60-digit precision and agree to every printed digit.
ROTATING_TABLE = {
    0.0: [3.51602, 22.0345, 61.6972],
    3.0: [4.79728, 23.3203, 62.9850],
    6.0: [7.36037, 26.8091, 66.6839],
    9.0: [10.2257, 31.7705, 72.3867],
    12.0: [13.1702, 37.6031, 79.6145],
}


@pytest.mark.parametrize("lam", sorted(ROTATING_TABLE))
def test_rotating_uniform_beam_published_table(lam):
    # Table values carry 6 significant figures (half a unit in the last digit
    # is 1.5e-6 relative at worst); 20 Hermite elements converge to 1.6e-5
    # on the third mode (test above), so the gate is 3e-5.
    ei = 1.0
    beam = assemble_beam(np.linspace(0, 1, 21),
                         uniform(ei_flap=ei, ei_lag=1e3, gj=1e3, ea=1e6), flat, CLAMP)
    # frequencies per rev of Omega = lambda (rotor units: m = L = EI = 1);
    # at lambda = 0 use the elastic stiffness alone
    if lam == 0.0:
        nu = eig(beam, n=3)
    else:
        modes = beam_modes(beam, n_modes=3, speed_ratio=lam)
        assert modes.labels == ["flap 1", "flap 2", "flap 3"]
        nu = modes.frequencies * lam
    assert_allclose(nu, ROTATING_TABLE[lam], rtol=3e-5)


def test_rotating_lag_equals_flap_minus_one():
    # Same EI in both planes and zero pitch: K_lag = K_flap - M, so
    # nu_lag^2 = nu_flap^2 - 1 mode by mode (classical result).
    beam = assemble_beam(np.linspace(0, 1, 21), uniform(ei_flap=0.01, ei_lag=0.01, gj=1e3,
                                                        ea=1e7), flat, CLAMP)
    m = beam_modes(beam, n_modes=4)
    flap = m.frequencies[[lab.startswith("flap") for lab in m.labels]]
    lag = m.frequencies[[lab.startswith("lag") for lab in m.labels]]
    assert_allclose(lag**2, flap**2 - 1.0, rtol=1e-6)


def test_hinged_rigid_blade_with_offset():
    # Articulated uniform blade with hinge offset e: nu_flap^2 = 1 + 3e/(2(1-e)),
    # nu_lag^2 = 3e/(2(1-e)) (Johnson, Helicopter Theory).  EI = 1e4 puts the
    # first elastic mode near 400/rev, so the rigid-blade error is of order
    # (1/400)^2 ~ 1e-5; the gate is 1e-4.
    e = 0.1
    beam = assemble_beam(np.linspace(e, 1, 11), uniform(ei_flap=1e4, ei_lag=1e4, gj=1e3,
                                                        ea=1e6), flat, RootSprings())
    m = beam_modes(beam, n_modes=3)
    by = dict(zip(m.labels, m.frequencies, strict=False))
    assert_allclose(by["lag 1"] ** 2, 1.5 * e / (1 - e), rtol=1e-4)
    assert_allclose(by["flap 1"] ** 2, 1 + 1.5 * e / (1 - e), rtol=1e-4)
    # free feathering with only the propeller moment: a 1/rev rigid pitch mode
    assert_allclose(by["torsion 1"], 1.0, rtol=1e-6)


def test_pitch_90_degrees_swaps_flap_and_lag_stiffness():
    # At 90 deg pitch the flapwise stiffness acts in-plane and vice versa.
    a = assemble_beam(np.linspace(0, 1, 11), uniform(ei_flap=1.0, ei_lag=9.0, gj=1e3), flat,
                      CLAMP)
    b = assemble_beam(np.linspace(0, 1, 11), uniform(ei_flap=9.0, ei_lag=1.0, gj=1e3),
                      lambda x: np.full_like(np.asarray(x, float), np.pi / 2), CLAMP)
    assert_allclose(eig(a), eig(b), rtol=1e-10)


def test_matrices_symmetric_and_modes_orthogonal():
    sec = uniform(cg_offset=0.01, tension_offset=0.005, ka=0.01, im_flap=1e-4)
    beam = assemble_beam(np.linspace(0.05, 1, 13), sec,
                         lambda x: 0.2 - 0.15 * np.asarray(x), RootSprings(0.1, 0.2, 0.3, 0.01))
    for mat in (beam.mass, beam.k_elastic, beam.k_centrifugal):
        assert_allclose(mat, mat.T, atol=1e-14)
    assert_allclose(beam.gyroscopic, -beam.gyroscopic.T, atol=1e-14)
    m = beam_modes(beam, n_modes=6)
    mm, kk = m.modal_mass, m.modal_stiffness
    off = ~np.eye(6, dtype=bool)
    # generalized eigenvectors are M- and K-orthogonal up to round-off amplified
    # by the conditioning of K (~1e7 here): 1e-8 relative
    assert np.max(np.abs(mm[off])) < 1e-10 * np.max(np.abs(np.diag(mm)))
    assert np.max(np.abs(kk[off])) < 1e-8 * np.max(np.abs(np.diag(kk)))
    assert_allclose(np.diag(kk) / np.diag(mm), m.frequencies**2, rtol=1e-9)


def test_shapes_at_nodes_match_dofs_and_normalisation():
    beam = assemble_beam(np.linspace(0, 1, 9), uniform(ei_lag=4.0, gj=1.0), flat, CLAMP)
    m = beam_modes(beam, n_modes=4)
    s = m.shapes(beam.x_nodes)
    assert_allclose(s["w"][:, 0], m.vectors[3::6][: len(beam.x_nodes), 0], atol=1e-14)
    flap1 = m.labels.index("flap 1")
    assert_allclose(s["w"][-1, flap1], 1.0)      # tip deflection normalised to +1
    with pytest.raises(ValueError, match="stations"):
        m.shapes([1.5])


def test_tension_piecewise_linear_is_exact():
    """T(x) = int_x^1 m s ds for a piecewise-linear mass: against scipy.integrate.quad
    segment by segment (gate 1e-13: both are exact up to round-off), and the
    fine-grid Simpson fallback agrees to its own error (~h^2 at the kinks)."""
    import scipy.integrate

    xs = np.array([0.05, 0.2, 0.23, 0.5, 0.9, 1.0])
    ms = np.array([3.0, 1.5, 0.8, 1.0, 1.4, 0.6])
    exact = tension_piecewise_linear(xs, ms)
    x = np.array([0.05, 0.1, 0.2, 0.21, 0.4, 0.9, 0.95, 1.0])
    ref = [sum(scipy.integrate.quad(lambda s: np.interp(s, xs, ms) * s, max(a, xi), b)[0]
               for a, b in zip(xs[:-1], xs[1:], strict=True) if b > xi) for xi in x]
    assert_allclose(exact(x), ref, rtol=0, atol=1e-13)
    fallback = tension_from_mass(lambda s: np.interp(s, xs, ms), xs[0])
    assert_allclose(fallback(x), ref, atol=1e-6)


@pytest.mark.parametrize(("offsets", "pitch", "n_blocks"), [
    ({}, flat, 4),                                            # all four fields apart
    ({}, lambda x: 0.2 - 0.15 * np.asarray(x), 3),            # pitch couples flap and lag
    ({"cg_offset": 0.01}, flat, 2),                           # CG: flap-torsion, axial-lag
    ({"cg_offset": 0.01, "tension_offset": 0.005}, flat, 2),  # flap-torsion, axial-lag
    ({"cg_offset": 0.01}, lambda x: 0.2 - 0.15 * np.asarray(x), 1),   # and pitch: one
])
@pytest.mark.parametrize("n", [6, 40])
def test_block_eigen_solution_equals_the_dense_one(offsets, pitch, n_blocks, n):
    # the pencil is block diagonal over uncoupled fields, so solving block by
    # block (and skipping blocks by Sylvester's inertia) is exact: the same
    # eigenvalues to round-off and the same modes; with n = 40 the axial and
    # torsion blocks contribute and cannot be skipped. Round-off gate: the
    # dense inverse form (largest 1/lambda) resolves lambda to about
    # eps * lambda / lambda_min relative, plus a floor from cond(K) ~ 3e9
    # of these test beams (seen: 2e-11 between the two solutions; gate 1e-10)
    sec = uniform(im_flap=1e-4, ka=0.01, **offsets)
    beam = assemble_beam(np.linspace(0.05, 1, 13), sec, pitch, RootSprings(0.1, 0.2, 0.3, 0.01))
    f = beam.free
    k, m = beam.stiffness()[f][:, f], beam.mass[f][:, f]
    owner = _dof_owner(beam.n_elements)[f]
    assert len(_uncoupled_blocks(k, m, owner)) == n_blocks
    lam_b, vec_b = _lowest_modes(k, m, n, owner=owner)
    lam_d, vec_d = _lowest_modes(k, m, n)
    eps = np.finfo(float).eps
    assert np.all(np.abs(lam_b - lam_d) <= (10 * eps * lam_d / lam_d[0] + 1e-10) * lam_d)
    gap = np.diff(lam_d) > 1e-6 * lam_d[1:]            # distinct eigenvalues only
    mac = np.abs(np.sum(vec_b * (m @ vec_d), axis=0)) / np.sqrt(
        np.sum(vec_b * (m @ vec_b), axis=0) * np.sum(vec_d * (m @ vec_d), axis=0))
    assert_allclose(mac[np.r_[gap, True] & np.r_[True, gap]], 1.0, atol=1e-9)


def test_mdart_axial_block_is_skipped_by_inertia(monkeypatch):
    # MDART (CG and tension axis on the elastic axis): axial, torsion and
    # flap-lag separate, and the axial block (lowest ~1e5 (/rev)^2) has no
    # eigenvalue below the 9th one, so it is never solved
    import tefcore.structure.fem as structure
    from tefcore.config.io import load_config
    from tefcore.structure.blade import blade_model

    beam = blade_model(load_config("mdart"), collective=np.deg2rad(8.0))
    f = beam.free
    k, m = beam.stiffness()[f][:, f], beam.mass[f][:, f]
    owner = _dof_owner(beam.n_elements)[f]
    sizes = [np.bincount(owner[b], minlength=4) for b in _uncoupled_blocks(k, m, owner)]
    assert len(sizes) == 3
    solved = []
    original = structure._dense_lowest_modes
    monkeypatch.setattr(structure, "_dense_lowest_modes",
                        lambda kb, mb, n: solved.append(kb.shape[0]) or original(kb, mb, n))
    modes = beam_modes(beam, n_modes=9)
    axial_size = next(int(s.sum()) for s in sizes if s[0] > 0)
    assert len(solved) == 2 and axial_size not in solved
    assert not any(lab.startswith("axial") for lab in modes.labels)


def test_blade_modes_are_cached_by_the_structure():
    # one set of modes for every configuration with the same structure (a sweep
    # of the flight condition or the actuator); any structural field, the
    # collective or the mode count gives its own, equal to a fresh computation
    from tefcore.config.io import load_config
    from tefcore.structure import blade

    cfg = load_config("mdart")
    first = blade.blade_modes(cfg, collective=0.1)
    for over in ({"flight.advance_ratio": 0.3}, {"actuator.stiffness": 200.0},
                 {"model.inflow": "dynamic"}, {"model.n_azimuth": 36}):
        assert blade.blade_modes(cfg.with_overrides(over), collective=0.1) is first
    for over in ({"flap.cg_offset": 0.3}, {"hub.pitch_link_stiffness": "400 lb/in"},
                 {"blade.gj_scale": 1.5}, {"model.n_modes": 10},
                 {"model.mode_families": "flap 4, lag 2, torsion 3"}):
        other = blade.blade_modes(cfg.with_overrides(over), collective=0.1)
        assert other is not first
    assert blade.blade_modes(cfg, collective=0.12) is not first
    blade._MODES_CACHE.clear()
    again = blade.blade_modes(cfg, collective=0.1)
    assert again is not first
    np.testing.assert_array_equal(again.frequencies, first.frequencies)
    np.testing.assert_array_equal(again.modal_stiffness, first.modal_stiffness)


def test_field_blocks_are_scipy_connected_components():
    # the blade's uncoupled field blocks come from a small closure instead of
    # scipy.sparse.csgraph (not imported by `tefcore stability`); it must give
    # scipy's count and labels -- numbered by each component's lowest node,
    # the order the blocks are solved in -- on every kind of small graph
    # (empty, full, one-sided links, isolated nodes)
    import scipy.sparse.csgraph

    from tefcore.structure.fem import _connected_components

    rng = np.random.default_rng(0)
    for _ in range(3000):
        n = int(rng.integers(1, 9))
        link = rng.random((n, n)) < rng.random()
        want = scipy.sparse.csgraph.connected_components(link, directed=False)
        got = _connected_components(link)
        assert got[0] == want[0]
        np.testing.assert_array_equal(got[1], want[1])
