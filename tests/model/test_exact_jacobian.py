"""Exact Jacobians of the coupled residual (docs/theory.md 6.3), the trim's Newton
matrix and the linearisation built from them.

The exact blocks are compared with central differences of the residual.  A
central difference with step ``h`` errs by ``h^2 R''' / 6`` (truncation) plus
``eps |R| / h`` (round-off); at ``h = 1e-5`` that is about 3e-11 of the largest
entry here (measured), and the error must fall as ``h^2``: tenfold steps give a
hundredfold error (checked), which only holds if the exact blocks are the limit
of the differences.  A wrong term (e.g. the ``mu cos psi`` slope part of
``U_P``, or the control columns' cosine and sine) moves entries by 1e-3 or more.
"""

import numpy as np
import pytest

from tefcore.aero.c81 import example_deck_path
from tefcore.config.io import load_config
from tefcore.linear.stability import linear_system, linearize
from tefcore.model.coupled import coupled_model
from tefcore.model.jacobian import exact_jacobian, has_exact_jacobian, jacobian_blocks
from tefcore.trimming.trim import initial_collective, trim

MDART = load_config("mdart")

CASES = {
    "thin airfoil": {},
    "C81 table": {"model.aero_model": "c81", "model.c81_deck": str(example_deck_path())},
    "dynamic inflow": {"model.inflow": "dynamic"},
    "uniform inflow, imbalanced flap": {"model.inflow": "uniform", "flap.cg_offset": 0.33},
    "no flap": {"model.tef": "none"},
    "hover": {"flight.advance_ratio": 0.0},
}


def trimmed(over):
    cfg = MDART.with_overrides({"flight.advance_ratio": 0.3, **over})
    with _quiet():
        return trim(coupled_model(cfg, collective=initial_collective(cfg)))


class _quiet:
    """Silence the C81 range warnings (reverse flow is clipped to the table)."""

    def __enter__(self):
        import warnings

        self._cm = warnings.catch_warnings()
        self._cm.__enter__()
        warnings.simplefilter("ignore")

    def __exit__(self, *exc):
        return self._cm.__exit__(*exc)


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    tr = trimmed(CASES[request.param])
    psi = tr.psi
    y, yd, ydd, inflow = tr.linear_point(psi)
    return request.param, tr, psi, (y, yd, ydd), inflow


def central(tr, psi, motion, inflow, h, pieces=False):
    with _quiet():
        return jacobian_blocks(tr.model, psi, *motion, tr.controls, inflow, step=h,
                               scheme="central", n_second=tr.model.n_dof, pieces=pieces)


def test_blocks_are_the_limit_of_central_differences(case):
    name, tr, psi, motion, inflow = case
    with _quiet():
        jac, dthr, base, _ = exact_jacobian(tr.model, psi, *motion, tr.controls, inflow)
    scale = np.abs(jac).max()
    if name == "C81 table":
        # the table is piecewise multilinear: a difference across a knot averages
        # two cells' slopes (4e-4 at h = 1e-4, 6e-8 at 1e-5: one station at one
        # azimuth, measured), the complex step takes the slope of the cell; at
        # h = 1e-6 no station crosses a knot and they agree to 5e-13
        fd, fd_thr, _ = central(tr, psi, motion, inflow, 1e-6)
        assert np.abs(jac - fd).max() < 1e-11 * scale
    else:
        errors = []
        for h in (1e-4, 1e-5):
            fd, fd_thr, _ = central(tr, psi, motion, inflow, h)
            errors.append(np.abs(jac - fd).max() / scale)
        # the h^2 law: 1e-4 -> 1e-5 divides the difference by ~100 (measured
        # 98-100; in hover the residual is nearly quadratic, round-off is reached)
        assert errors[1] < 3e-10, (name, errors)
        assert errors[1] < errors[0] / 30 or errors[1] < 1e-12, (name, errors)
    # the thrust's derivatives (the trim's C_T row) to the same standard
    assert np.abs(dthr - fd_thr).max() < 1e-8 * np.abs(fd_thr).max()
    # the unperturbed residual comes with it
    with _quiet():
        res, thrust = tr.model.evaluate(psi, *motion, tr.controls, inflow)
    assert np.abs(base[0] - res).max() < 1e-14
    assert np.allclose(base[1], thrust, rtol=1e-14, atol=1e-16)


def test_pieces_add_up_and_match_their_differences(case):
    name, tr, psi, motion, inflow = case
    with _quiet():
        parts, _, _, _ = exact_jacobian(tr.model, psi, *motion, tr.controls, inflow,
                                        pieces=True)
        whole, _, _, _ = exact_jacobian(tr.model, psi, *motion, tr.controls, inflow)
    fd, _, _ = central(tr, psi, motion, inflow, 1e-6 if name == "C81 table" else 1e-5,
                       pieces=True)
    assert set(parts) == set(fd)
    scale = np.abs(whole).max()
    assert np.abs(sum(parts.values()) - whole).max() < 1e-13 * scale
    for piece in parts:
        assert np.abs(parts[piece] - fd[piece]).max() < 3e-10 * scale, (name, piece)


def test_trim_newton_matrix_against_differences():
    # every column of the trim's Newton matrix (motion, controls, inflow) against
    # central differences of the trim equations (h = 1e-6: 1e-10 of the largest
    # entry measured); at a perturbed state, so the linear parts are not special
    for over in ({}, {"model.inflow": "dynamic"}):
        tr = trimmed(over)
        prob, x = tr._problem, tr._solution.copy()
        x[:prob.nq] += 1e-3 * np.random.default_rng(0).standard_normal(prob.nq)
        jac, _, _ = prob.jacobian(x)
        h = 1e-6
        fd = np.empty_like(jac)
        for k in range(x.size):
            e = np.zeros(x.size)
            e[k] = h
            fd[:, k] = (prob.full(x + e)[0] - prob.full(x - e)[0]) / (2 * h)
        assert np.abs(jac - fd).max() < 1e-8 * np.abs(fd).max(), over


def test_linearisation_reuses_the_trims_final_jacobian():
    tr = trimmed({})
    system = linear_system(tr)
    k, c, m = tr.final_blocks()
    assert system.k is k and system.c is c and system.m is m
    # and it is the exact linearisation about the trim on its grid
    mm, cc, kk = linearize(tr, tr.psi)
    for a, b in ((system.m, mm), (system.c, cc), (system.k, kk)):
        assert np.abs(a - b).max() < 1e-13 * np.abs(b).max()
    # a trim warm-started from it starts from that Newton matrix
    assert tr.jacobian.shape == (tr._solution.size,) * 2


def test_shed_wake_falls_back_to_differences():
    cfg = MDART.with_overrides({"flight.advance_ratio": 0.0, "model.aero": "unsteady"})
    model = coupled_model(cfg, collective=initial_collective(cfg))
    assert not has_exact_jacobian(model)
    with pytest.raises(ValueError, match="shed-wake"):
        exact_jacobian(model, np.zeros(1), *(np.zeros((model.n_dof + model.n_wake, 1)),) * 3,
                       None, None)


def test_c81_interpolation_complex_step_is_the_cell_slope():
    # inside a cell the multilinear table has the slope of that cell; beyond the
    # table (clipped) it is constant: complex step gives both exactly
    from tefcore.aero.c81 import C81FlapTable

    table = C81FlapTable(str(example_deck_path()), 0.35, 0.29)
    a, m, d = np.radians(3.0), 0.43, np.radians(1.0)
    h = 1e-30
    got = table.static_coefficients(a + 1j * h, m, d)["cl"].imag / h
    step = np.radians(1e-4)      # stays in the cell [2, 4] deg
    fd = (table.static_coefficients(a + step, m, d)["cl"]
          - table.static_coefficients(a - step, m, d)["cl"]) / (2 * step)
    assert got == pytest.approx(float(fd), rel=1e-9)
    with _quiet():
        out = table.static_coefficients(np.radians(40.0) + 1j * h, m, d)["cl"]
    assert out.imag == 0.0
