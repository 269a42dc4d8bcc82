"""The fused station kernel (tefcore.model.station_kernel) against the numpy complex step.

The kernel repeats the arithmetic of ``station_terms`` station by station; the
numpy path takes the same complex steps on whole arrays.  Both are exact to
round-off, so they agree to round-off: measured 3e-16 of the largest entry
(jacobian, thrust, parameter columns) on MDART; 1e-13 leaves room for
another machine's libm and is far below any wrong term (a dropped term of the
flap's equation or the apparent mass moves entries by 1e-4 or more).  The
kernel runs compiled (numba, where installed) and as plain Python on a few
azimuths (always): the formulas are checked with or without numba.
"""

import numpy as np
import pytest

from tefcore.config.io import load_config
from tefcore.model import jacobian as jac_module
from tefcore.model import station_kernel as sk
from tefcore.model.coupled import coupled_model
from tefcore.model.station_terms import local_variables
from tefcore.trimming.newton_matrix import inflow_tangents
from tefcore.trimming.trim import initial_collective, trim

MDART = load_config("mdart")
KERNELS = ["python"] + (["numba"] if sk._numba_available() else [])
CASES = {
    "imbalanced flap, mu 0.3": {"flap.cg_offset": 0.33},
    "no flap": {"model.tef": "none"},
    "dynamic inflow": {"model.inflow": "dynamic"},
    "incompressible, no overhang": {"flap.overhang": 0.0},
    "hover": {"flight.advance_ratio": 0.0},
}


@pytest.fixture(scope="module", params=list(CASES))
def point(request):
    cfg = MDART.with_overrides({"flight.advance_ratio": 0.3, **CASES[request.param]})
    tr = trim(coupled_model(cfg, collective=initial_collective(cfg)))
    y, yd, ydd, inflow = tr.linear_point(tr.psi)
    return tr, (tr.psi, y, yd, ydd, tr.controls, inflow)


def rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.mark.parametrize("kernel", KERNELS)
def test_kernel_agrees_with_the_numpy_complex_step(point, kernel):
    tr, motion = point
    model = tr.model
    psi, y, yd, ydd = motion[:4]
    if kernel == "python":             # a few azimuths: Python is slow
        keep = slice(0, 3)
        psi, y, yd, ydd = psi[keep], y[:, keep], yd[:, keep], ydd[:, keep]
        motion = (psi, y, yd, ydd, *motion[4:])
    kin = model.kinematics(psi, y, yd, ydd, motion[4], motion[5])
    loc = local_variables(model, kin, y, yd, ydd)
    st = jac_module._statics(model, y.shape[0])
    total, _, dfz, (parts, thrust) = jac_module._complex_step(model, loc, st, motion, False,
                                                              False)
    got = sk.station_derivatives(model, loc, st["n_var"], jac_module.EXACT_STEP,
                                 kernel=kernel)
    assert rel(got[0], total) < 1e-13
    assert rel(got[1], dfz) < 1e-13
    # the forces themselves: the residual and thrust built from them
    parts_k, thrust_k = jac_module._fused_residual(model, motion, got)
    scale = max(np.abs(p).max() for p in parts.values())
    assert np.abs(sum(parts_k.values()) - sum(parts.values())).max() < 1e-13 * scale
    assert rel(thrust_k, thrust) < 1e-13


@pytest.mark.skipif(not sk._numba_available(), reason="numba is not installed")
def test_the_compiled_path_is_the_exact_jacobian(point, monkeypatch):
    tr, motion = point
    model = tr.model
    li = ((tr.inflow.mean, tr.inflow.sine, tr.inflow.cosine) if model.dynamic_inflow
          else tr.inflow.mean_induced)
    tang = inflow_tangents(model, li, tr.psi)
    out = {}
    for kernel in ("numpy", "numba"):
        monkeypatch.setenv(sk.KERNEL_ENV, kernel)
        out[kernel] = jac_module.exact_jacobian(model, *motion, inflow_tangents=tang)
    a, b = out["numba"], out["numpy"]
    assert rel(a[0], b[0]) < 1e-13 and rel(a[1], b[1]) < 1e-13
    assert rel(a[3][0], b[3][0]) < 1e-13 and rel(a[3][1], b[3][1]) < 1e-13
    assert rel(a[2][1], b[2][1]) < 1e-13


def test_without_numba_the_numpy_path_runs(monkeypatch):
    monkeypatch.setattr(sk, "_numba_available", lambda: False)
    monkeypatch.delenv(sk.KERNEL_ENV, raising=False)
    assert sk.kernel_name() == "numpy"
    assert sk.kernel_name("auto") == "numpy"
    assert sk.station_derivatives(None, {}, 6, 1e-30) is None
    with pytest.raises(ValueError, match=r"numba is not installed.*tefcore\[fast\]"):
        sk.kernel_name("numba")


def test_an_unknown_kernel_is_named(monkeypatch):
    monkeypatch.setenv(sk.KERNEL_ENV, "fortran")
    with pytest.raises(ValueError, match="TEFCORE_STATION_KERNEL = 'fortran' is not one of "
                                         "auto, numba, numpy"):
        sk.kernel_name()


def test_the_c81_table_takes_the_numpy_path():
    from tefcore.aero.c81 import example_deck_path

    cfg = MDART.with_overrides({"model.aero_model": "c81",
                                "model.c81_deck": str(example_deck_path())})
    assert not sk.covers(coupled_model(cfg))
    assert sk.covers(coupled_model(MDART))
