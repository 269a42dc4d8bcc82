"""Tests of tefcore.linear.mechanism: the energy balance closes, knockouts are recomputations,
the flap mode is found by continuation from zero coupling, and the CLI contract.

Closed forms: a damped oscillator ``m q'' + c q' + k q = 0`` has
``sigma = -c / 2m`` and ``|lambda|^2 = k / m``, so its damper does all the
work (``-c/2m``) and its mass and spring store equal energy (``omega/2``
each); a negative spring gives a real root ``lambda`` with
``lambda (lambda m + c) = -k`` (divergence).
"""

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from tefcore.config.io import load_config
from tefcore.floquet.second_order import SecondOrderSystem, combine
from tefcore.linear.mechanism import (
    NOT_REMOVABLE,
    STATE_TERMS,
    TERMS,
    energy_decomposition,
    linearized_terms,
    mechanism,
)
from tefcore.linear.stability import stability
from tefcore.modes.continuation import coupling_homotopy, tef_root


def constant(m, c, k):
    return SecondOrderSystem(*(np.asarray(a, float)[None] for a in (m, c, k)))


def root_shape(system, j=None, shapes=False, n_steps=72):
    res = system.modes(n_steps=n_steps, n_sub=4, shapes=shapes).positive_frequency()
    j = int(np.argmax(res.damping_rates)) if j is None else j
    if res.shapes is None:
        return res.exponents[j], res.eigenvectors[:, j][None, :], np.zeros(1)
    return res.exponents[j], res.shapes[:, :, j], res.psi


# ------------------------------------------------------------------ closed forms


def test_damped_oscillator_damper_does_all_the_work():
    m, c, k = 2.0, 0.3, 8.0
    parts = {"mass": constant([[m]], [[0]], [[0]]), "damper": constant([[0]], [[c]], [[0]]),
             "spring": constant([[0]], [[0]], [[k]])}
    eta, shape, psi = root_shape(combine(parts))
    out = energy_decomposition(parts, eta, shape, psi)
    assert out["damper"].real == pytest.approx(-c / (2 * m), rel=1e-12)
    assert out["mass"].real == pytest.approx(0.0, abs=1e-14)
    assert out["spring"].real == pytest.approx(0.0, abs=1e-14)
    # |lambda|^2 m = k: mass and spring store the same energy, half the frequency each
    assert out["mass"].imag == pytest.approx(eta.imag / 2, rel=1e-12)
    assert out["spring"].imag == pytest.approx(eta.imag / 2, rel=1e-12)


def test_divergence_is_a_real_root_driven_by_the_negative_spring():
    m, c, k = 1.0, 0.2, -4.0
    parts = {"mass": constant([[m]], [[0]], [[0]]), "damper": constant([[0]], [[c]], [[0]]),
             "spring": constant([[0]], [[0]], [[k]])}
    eta, shape, psi = root_shape(combine(parts))
    assert eta.imag == 0 and eta.real > 0
    out = energy_decomposition(parts, eta, shape, psi)
    lam = eta.real
    assert out["spring"].real == pytest.approx(-k / (lam * m + c), rel=1e-12)
    assert out["spring"].real == pytest.approx(lam, rel=1e-12)
    assert out["mass"].real == 0 and out["damper"].real == 0


def random_parts(rng, n, n_parts, n_psi=1, amplitude=0.3):
    """Random named parts of a system with a positive definite total mass."""
    psi = np.linspace(0, 2 * np.pi, n_psi, endpoint=False)
    parts = {}
    for p in range(n_parts):
        def rnd(scale, p=p):
            base = rng.normal(size=(n, n)) * scale
            var = rng.normal(size=(n, n)) * scale * amplitude
            return base[None] + np.sin(psi + p)[:, None, None] * var[None]
        m = rnd(0.1)
        if p == 0:
            a = rng.normal(size=(n, n))
            m = m + (a @ a.T + n * np.eye(n))[None]
        parts[f"t{p}"] = SecondOrderSystem(m, rnd(0.5), rnd(3.0))
    return parts


@pytest.mark.parametrize("seed", range(6))
def test_closure_on_random_constant_systems(seed):
    # every root, oscillatory or real: the terms add up to its real part
    rng = np.random.default_rng(seed)
    parts = random_parts(rng, n=4, n_parts=5)
    res = combine(parts).modes().positive_frequency()
    for j in range(len(res)):
        eta = res.exponents[j]
        out = energy_decomposition(parts, eta, res.eigenvectors[:, j][None, :], np.zeros(1))
        total = sum(v.real for v in out.values())
        assert total == pytest.approx(eta.real, abs=1e-9 * (1 + abs(eta)))
        if abs(eta.imag) > 1e-9:
            assert sum(v.imag for v in out.values()) == pytest.approx(eta.imag, rel=1e-9)


@pytest.mark.parametrize("seed", range(4))
def test_closure_on_random_periodic_systems_converges_with_the_steps(seed):
    # periodic coefficients: the balance holds up to the integration error of
    # the Floquet shapes (Magnus, O(h^4)): it shrinks as the steps are refined
    rng = np.random.default_rng(10 + seed)
    parts = random_parts(rng, n=3, n_parts=4, n_psi=8)
    system = combine(parts)
    errors = []
    for n_steps in (36, 144):
        res = system.modes(n_steps=n_steps, n_sub=4, shapes=True).positive_frequency()
        err = 0.0
        for j in range(len(res)):
            eta = res.exponents[j]
            out = energy_decomposition(parts, eta, res.shapes[:, :, j], res.psi)
            err = max(err, abs(sum(v.real for v in out.values()) - eta.real) / (1 + abs(eta)))
        errors.append(err)
    # 144 Magnus steps: closure to 1e-5 of the root's size (measured 1e-8 ... 1e-6);
    # and better than at 36 steps
    assert errors[1] < 1e-5
    assert errors[1] < errors[0]


# ------------------------------------------------------------------ the rotor


@pytest.fixture(scope="module")
def hover_imbalanced():
    cfg = load_config("mdart").with_overrides(
        {"flap.cg_offset": 0.33, "flight.advance_ratio": 0.0})
    return cfg, stability(cfg)


def test_terms_add_up_to_the_linearised_system(hover_imbalanced):
    _, res = hover_imbalanced
    parts = linearized_terms(res.trim_result)
    assert set(parts) == set(TERMS) - set(STATE_TERMS)
    total = combine(parts)
    for a, b in zip((total.m, total.c, total.k), (res.system.m, res.system.c, res.system.k),
                    strict=True):
        np.testing.assert_allclose(a, b, atol=1e-9 * np.abs(b).max())


def test_knockout_equals_recomputation(hover_imbalanced):
    cfg, res = hover_imbalanced
    out = mechanism(cfg, stability_result=res)
    parts = linearized_terms(res.trim_result)
    assert not set(out.knockouts) & set(NOT_REMOVABLE)
    clear = {t: f for t, f in out.knockouts.items() if f.clear}
    # a knockout may pass a coalescence (e.g. the flap without its actuator
    # spring becomes two real roots): flagged, not compared; most are clear
    assert len(clear) >= len(out.knockouts) - 2
    for term, follow in clear.items():
        direct = combine(parts, {term: 0.0}).modes().positive_frequency().exponents
        # the followed root is one of the roots of the system without the term
        assert np.abs(direct - follow.eigenvalue).min() < 1e-9, term
        row = out.table[out.table["term"] == f"knockout {term}"].iloc[0]
        assert row["contribution_real"] == follow.eigenvalue.real


def test_decomposition_closes_on_the_rotor(hover_imbalanced):
    cfg, res = hover_imbalanced
    out = mechanism(cfg, stability_result=res, knockouts=False)
    assert abs(out.closure) < 1e-10
    terms = out.table[~out.table["term"].str.startswith(("total", "knockout"))]
    total = out.table.set_index("term").loc["total"]
    assert terms["contribution_real"].sum() == pytest.approx(total["contribution_real"],
                                                             abs=1e-10)
    assert terms["contribution_imag"].sum() == pytest.approx(total["contribution_imag"],
                                                             rel=1e-10)


def test_forward_flight_decomposition_closes():
    cfg = load_config("mdart").with_overrides({"flap.cg_offset": 0.33})
    out = mechanism(cfg, knockouts=False)
    # periodic shapes from 72 Magnus steps: closure measured 9e-4 /rev on a
    # +3 /rev root; 1 % of the root's real part bounds it with room
    assert abs(out.closure) < 0.01 * abs(out.eigenvalue.real)


def test_tef_root_of_an_uncoupled_flap_is_the_flap_itself(hover_imbalanced):
    _, res = hover_imbalanced
    n = res.system.n_dof
    uncoupled = coupling_homotopy(res.system, n - 1, 0.0)
    eta, follow = tef_root(uncoupled)
    assert follow.clear
    flap = constant(uncoupled.m[0, -1:, -1:], uncoupled.c[0, -1:, -1:],
                    uncoupled.k[0, -1:, -1:]).modes().positive_frequency().exponents
    assert np.abs(flap - eta).min() < 1e-10


def test_imbalanced_flap_root_is_found_and_classified(hover_imbalanced):
    cfg, res = hover_imbalanced
    # no mode asked for: the flutter root when the point has an unstable one
    out = mechanism(cfg, stability_result=res, knockouts=False)
    fr = res.modes[res.modes["flutter_root"]].iloc[0]
    assert fr["real_part"] > 0                 # the imbalanced flap flutters in hover
    assert out.identification.startswith("the flutter root (no mode asked for)")
    assert out.eigenvalue.real == pytest.approx(fr["real_part"], abs=1e-9)
    assert out.kind == "flutter"
    # freeing the flap is what makes it unstable: held, its root is stable
    assert fr["real_part_uncoupled"] < 0 and fr["flap_induced"]
    # asked for the TEF: the root the uncoupled flap mode continues into
    tef = mechanism(cfg, mode="TEF", stability_result=res, knockouts=False)
    assert tef.identification == "the root the uncoupled flap mode continues into"
    row = res.modes[res.modes["label"] == "TEF"].iloc[0]
    assert tef.eigenvalue.real == pytest.approx(row["real_part"], abs=1e-9)
    assert tef.kind in ("flutter", "stable oscillatory", "divergence", "stable real")


def test_unknown_mode_and_no_flap_are_clear_errors(hover_imbalanced):
    cfg, res = hover_imbalanced
    with pytest.raises(ValueError, match="no mode named 'blade flap 9'"):
        mechanism(cfg, mode="blade flap 9", stability_result=res)
    with pytest.raises(ValueError, match="needs the flap"):
        mechanism(cfg.with_overrides({"model.tef": "none"}), mode="TEF")


def test_cli_contract(tmp_path):
    out = tmp_path / "m.csv"
    run = subprocess.run(
        [sys.executable, "-m", "tefcore", "mechanism", "--mode", "TEF", "-s",
         "flap.cg_offset=0.33", "-s", "flight.advance_ratio=0", "--csv", str(out)],
        capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    table = pd.read_csv(out)
    assert list(table.columns) == ["term", "contribution_real", "contribution_imag"]
    terms = table[~table["term"].str.startswith(("total", "knockout"))]
    assert set(terms["term"]) == set(TERMS) - set(STATE_TERMS)
    total = table[table["term"] == "total"].iloc[0]
    # the terms close to the real part (CSV round trip with 10 digits)
    assert terms["contribution_real"].sum() == pytest.approx(total["contribution_real"],
                                                             abs=1e-8)
    knock = table[table["term"].str.startswith("knockout ")]
    assert knock["term"].str.contains("inertial").any()
