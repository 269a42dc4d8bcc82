"""One Jacobian of the residual at the trimmed motion per point.

The trim's Newton matrix at its solution and the linearisation about the trim
are the same derivatives; a point evaluates them once (docs/theory.md 6.3,
:meth:`tefcore.trimming.trim.TrimResult.final_blocks`).  Every evaluation of
the Jacobian is recorded with the motion it was taken at; an evaluation at the
solution is one whose coordinates equal the trimmed motion to 1e-9 (the
linearisation takes them by Fourier interpolation of the trim: the same,
round-off apart).  The trim's own Newton matrices are evaluated at its first
guess (rest, or the neighbouring point's solution) and where its iterations
stall, farther from the solution than that.
"""

import warnings

import numpy as np
import pytest

import tefcore.linear.stability as stability_module
import tefcore.trimming.newton_matrix as newton_module
from tefcore.config.io import load_config
from tefcore.linear.stability import stability

BASE = load_config("mdart").with_overrides({"flight.advance_ratio": 0.3,
                                            "flap.cg_offset": 0.33})


@pytest.fixture
def evaluations(monkeypatch):
    """The motions ``q`` (coordinates only) of every Jacobian evaluation."""
    seen = []

    def counted(module, name):
        inner = getattr(module, name)

        def wrapper(model, psi, q, *args, **kwargs):
            seen.append(np.array(q[:model.n_dof]))
            return inner(model, psi, q, *args, **kwargs)

        monkeypatch.setattr(module, name, wrapper)

    counted(newton_module, "exact_jacobian")
    counted(newton_module, "jacobian_blocks")
    counted(stability_module, "jacobian_blocks")
    return seen


def at_solution(seen, tr):
    return sum(np.abs(q - tr.q).max() <= 1e-9 * max(np.abs(tr.q).max(), 1.0) for q in seen)


@pytest.mark.parametrize("over", [{}, {"model.inflow": "dynamic"}],
                         ids=["quasi-steady", "dynamic inflow"])
def test_a_point_evaluates_the_jacobian_at_its_solution_once(evaluations, over):
    cfg = BASE.with_overrides(over)
    first = stability(cfg).trim_result
    # cold: the Newton matrix at the first guess, then one at the solution
    assert at_solution(evaluations, first) == 1
    assert len(evaluations) == 2
    # warm-started from it, a neighbouring point starts from that Newton
    # matrix and evaluates only the one at its own solution
    evaluations.clear()
    nxt = stability(cfg.with_overrides({"flight.advance_ratio": 0.31}),
                    warm_start=first).trim_result
    assert at_solution(evaluations, nxt) == 1
    assert len(evaluations) == 1
    # the linearisation is that evaluation: asking again evaluates nothing
    stability_module.linear_system(nxt)
    assert len(evaluations) == 1


def test_with_the_shed_wake_the_linearisation_is_evaluated_once(evaluations):
    cfg = BASE.with_overrides({"model.aero": "unsteady", "flight.advance_ratio": 0.0})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tr = stability(cfg).trim_result
    assert at_solution(evaluations, tr) == 1
