"""Coupled model, wind-tunnel trim, linearisation and Floquet stability (MDART)."""

import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

from tefcore import floquet
from tefcore.config.io import load_config
from tefcore.fourier import fourier_eval
from tefcore.linear.stability import linearize, stability, state_matrix
from tefcore.model.coupled import coupled_model
from tefcore.model.flap import flap_natural_frequency, flap_properties
from tefcore.paper.calibration import mode_frequency
from tefcore.structure.blade import blade_modes
from tefcore.trimming.trim import TrimError, trim


@pytest.fixture(scope="module")
def mdart():
    return load_config("mdart")


@pytest.fixture(scope="module")
def forward(mdart):
    cfg = mdart.with_overrides({"flight.advance_ratio": 0.3})
    return trim(coupled_model(cfg))


def test_forward_flight_trim_meets_targets(forward):
    # thrust and the first-harmonic tip flapping are trim equations solved
    # to 1e-10 (rotor units); the azimuthal mean is exact on the grid
    model = forward.model
    assert_allclose(forward.ct_sigma, 0.075, atol=1e-9)
    tip = model.modes.shapes([1.0])["w"][0] @ forward.q[: model.n_modes]
    psi = forward.psi
    assert abs(2 * np.mean(tip * np.cos(psi))) < 1e-9
    assert abs(2 * np.mean(tip * np.sin(psi))) < 1e-9
    # forward flight needs forward (negative theta_1s) cyclic, and the Newton
    # iteration converged quadratically to the tolerance
    assert forward.controls.cyclic_sin < 0
    assert forward.history[-1]["max_residual"] < 1e-10
    # hinge moments exist without actuator input, so the flap deflects in trim
    assert abs(forward.summary()["delta_mean_deg"]) > 0.01


def test_harmonic_balance_converges_with_azimuth_count(mdart):
    # collocation converges spectrally: 16 -> 32 azimuths changes the controls
    # by < 0.01 deg (the response is dominated by harmonics below 5/rev)
    cfg = mdart.with_overrides({"flight.advance_ratio": 0.3})
    out = []
    for n in (16, 32):
        tr = trim(coupled_model(cfg.with_overrides({"model.n_azimuth": n})))
        out.append(tr.controls.as_array())
    assert_allclose(np.rad2deg(out[0]), np.rad2deg(out[1]), atol=1e-2)


def test_hover_collective_trim_and_prescribed_collective(mdart):
    tr = trim(coupled_model(mdart.with_overrides({"flight.advance_ratio": 0.0})))
    assert tr.q.shape[1] == 1 and tr.controls.cyclic_cos == 0.0
    theta = tr.controls.collective
    # the same collective prescribed reproduces the thrust (consistency)
    tr2 = trim(coupled_model(mdart.with_overrides(
        {"flight.advance_ratio": 0.0, "flight.collective": float(theta)})))
    assert_allclose(tr2.ct_sigma, 0.075, rtol=1e-8)


def test_non_converging_trim_raises_with_history(mdart):
    model = coupled_model(mdart.with_overrides({"flight.advance_ratio": 0.3}))
    with pytest.raises(TrimError) as err:
        trim(model, max_iter=2)
    assert len(err.value.history) == 2
    assert err.value.history[0]["max_residual"] > err.value.history[-1]["max_residual"]


def test_linearisation_matches_the_nonlinear_residual(forward):
    # [R(q + e v) - R(q - e v)] / 2 = e J v + O(e^3): the symmetric difference
    # cancels the quadratic remainder (the one-sided one was 1.9e-9 at e = 1e-5
    # on the lag row, second derivatives ~20). With e = 1e-5 the cubic remainder
    # and J's own central-difference error (step 1e-6) leave 9e-14 (measured)
    # against linear changes of 1e-6..4e-4, hence atol 1e-11 with a 1e-4
    # relative gate
    model = forward.model
    psi = np.array([0.3, 2.1, 4.4])
    m, c, k = linearize(forward, psi)
    q, qd, qdd = forward.motion(psi)
    rng = np.random.default_rng(0)
    v = [rng.standard_normal(q.shape) * 1e-5 for _ in range(3)]
    r1, _ = model.evaluate(psi, q + v[0], qd + v[1], qdd + v[2], forward.controls,
                           forward.inflow)
    r2, _ = model.evaluate(psi, q - v[0], qd - v[1], qdd - v[2], forward.controls,
                           forward.inflow)
    lin = (np.einsum("mij,jm->im", k, v[0]) + np.einsum("mij,jm->im", c, v[1])
           + np.einsum("mij,jm->im", m, v[2]))
    assert_allclose(0.5 * (r1 - r2), lin, rtol=1e-4, atol=1e-11)


def test_hover_floquet_equals_eigenanalysis(mdart):
    # constant coefficients: the Floquet machinery must reproduce the direct
    # eigenvalues (Magnus is exact for constant A; lifting keeps the damped
    # roots): 1e-8 on exponents
    tr = trim(coupled_model(mdart.with_overrides({"flight.advance_ratio": 0.0})))
    a = state_matrix(*(x[0] for x in linearize(tr, [0.0])))
    direct = floquet.constant_coefficient_modes(a)
    # 72 steps (the model default): the balanced TEF lies at 18/rev, the Nyquist
    # limit of 36 samples per rev, where the integer frequency shift is ambiguous
    per = floquet.floquet_modes(lambda p: np.broadcast_to(a, (len(p), *a.shape)), n_steps=72,
                                method="magnus", shift_states=slice(0, a.shape[0] // 2))
    assert per.exponents.size == direct.exponents.size == a.shape[0]
    gap = np.abs(per.exponents[:, None] - direct.exponents[None, :]).min(axis=1)
    assert gap.max() < 1e-8


def test_vacuum_modes_are_the_structural_modes(mdart):
    # with (almost) no air the coupled frequencies are the blade modes and the
    # flap on its actuator; damping is only the lag damper.  The flap couples
    # inertially through I_h Theta** (balanced flap), a relative shift < 1e-3
    cfg = mdart.with_overrides({"flight.advance_ratio": 0.0, "flight.collective": 0.1,
                                "rotor.air_density": 1e-9})
    res = stability(cfg)
    t = res.modes.set_index("label")
    struct = blade_modes(cfg, collective=0.1)
    for lab in ("flap 1", "lag 1", "flap 2", "torsion 1"):
        assert_allclose(t.loc[f"blade {lab}", "frequency_per_rev"],
                        mode_frequency(struct, lab), rtol=2e-3)
    flap = flap_natural_frequency(flap_properties(cfg), cfg.rotor.rotor_speed, 0.1)
    assert_allclose(t.loc["TEF", "frequency_per_rev"], flap / cfg.rotor.rotor_speed, rtol=2e-2)
    # flap damping only from the lag damper through the pretwist flap-lag
    # coupling (measured -5e-6 per rev), against -0.9 in air
    assert abs(t.loc["blade flap 1", "real_part"]) < 1e-4


def test_stability_tables_are_labelled(mdart):
    for mu in (0.0, 0.3):
        res = stability(mdart.with_overrides({"flight.advance_ratio": mu}))
        labels = set(res.modes["label"])
        assert {"blade lag 1", "blade flap 1", "blade torsion 1", "TEF"} <= labels
        assert res.eigenvectors.shape[1] == len(res.modes)
        assert np.all(np.isfinite(res.modes[["frequency_per_rev", "real_part"]].to_numpy()))
        assert "collective_deg" in res.trim


def test_stability_with_a_prebuilt_model(mdart):
    # the same modes and trim as stability() builds itself (hover does not
    # re-mode), so the tables agree exactly
    from tefcore.trimming.trim import initial_collective
    cfg = mdart.with_overrides({"flight.advance_ratio": 0.0})
    model = coupled_model(cfg, collective=initial_collective(cfg))
    own, given = stability(cfg), stability(cfg, model=model)
    assert given.modes.equals(own.modes)
    assert given.trim_result.model is model
    with pytest.raises(ValueError, match="another configuration"):
        stability(mdart, model=model)


def test_fourier_interpolation_is_exact_for_band_limited():
    psi = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    f = 1 + np.cos(psi) - 0.3 * np.sin(4 * psi)
    p = np.array([0.1, 1.7, 5.0])
    assert_allclose(fourier_eval(f, p), 1 + np.cos(p) - 0.3 * np.sin(4 * p), atol=1e-13)
    assert_allclose(fourier_eval(f, p, 1), -np.sin(p) - 1.2 * np.cos(4 * p), atol=1e-12)


def test_forward_and_central_linearisation_agree(forward):
    # forward differences err by ~step |R''| / 2: measured 2.2e-7 absolute,
    # 3.4e-7 of the largest entry (the residual is nonlinear in the motion
    # through the aerodynamics), so the gate is 1e-6 of the largest entry
    psi = np.array([0.0, 1.0])
    central = linearize(forward, psi)
    fwd = linearize(forward, psi, scheme="forward")
    for a, b in zip(central, fwd, strict=True):
        assert_allclose(b, a, rtol=1e-4, atol=1e-6 * np.abs(a).max())
    with pytest.raises(ValueError, match="scheme"):
        linearize(forward, psi, scheme="backward")


def test_sweep_gives_continuous_labelled_curves(mdart):
    # pitch-link stiffness in hover: every named mode is present at every
    # point, and the torsion frequency rises smoothly
    # (Fig. 10a's trend) while flap and lag barely move
    from tefcore.sweeps.sweep import sweep

    cfg = mdart.with_overrides({"flight.advance_ratio": 0.0})
    res = sweep(cfg, "hub.pitch_link_stiffness", ["158 lb/in", "400 lb/in", "800 lb/in"],
                progress=False)
    t = res.table
    assert (t["status"] == "ok").all()
    n_points = t["point"].nunique()          # the three asked for, and any refinement
    assert (t.drop_duplicates("point")["refinement"] == 0).sum() == 3
    # every name at every point, once; the flap mode one continuous curve (the
    # blade's names are their characters at zero flap coupling: torsion 1
    # passing flap 2 changes curve with its character, a veering of the blade)
    for lab in ("TEF", "blade lag 1", "blade flap 1", "blade torsion 1"):
        curve = t[t["label"] == lab]
        assert len(curve) == n_points and curve["value_si"].is_unique, lab
    assert t.loc[t["label"] == "TEF", "track"].nunique() == 1
    assert t.loc[t["tef_branch"], "label"].eq("TEF").all()
    torsion = t[t["label"] == "blade torsion 1"]["frequency_per_rev"].to_numpy()
    assert np.all(np.diff(torsion) > 0)
    lag = t[t["label"] == "blade lag 1"]["frequency_per_rev"].to_numpy()
    assert np.ptp(lag) / lag.mean() < 0.02


def test_c81_table_aerodynamics_runs_the_coupled_analysis(mdart):
    # the shipped deck is generated from the thin-airfoil model with a = 2 pi,
    # so the trim collective must sit close to a thin-airfoil model with the
    # same lift slope (within 0.3 deg: table interpolation and clipping)
    from tefcore.aero.c81 import C81RangeWarning, example_deck_path

    base = mdart.with_overrides({"flight.advance_ratio": 0.0,
                                 "rotor.lift_slope": float(2 * np.pi)})
    table_cfg = base.with_overrides({"model.aero_model": "c81",
                                     "model.c81_deck": str(example_deck_path())})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", C81RangeWarning)
        tab = trim(coupled_model(table_cfg))
        res = stability(table_cfg)
    thin = trim(coupled_model(base))
    assert abs(np.rad2deg(tab.controls.collective - thin.controls.collective)) < 0.3
    assert "TEF" in set(res.modes["label"])


def test_heavily_damped_root_resolved_by_raising_the_sub_intervals():
    # Fig. 13 with the flap at 0.90 R: a root near -5.0 /rev beside the
    # +3.5 /rev flutter root. Its lifted root falls below MIN_ROOT with K = 4, so
    # floquet_modes raises K (to 8). Reference: K = 16. (K = 4 is off by
    # 1.4e-4 /rev here, among the largest of the figures' extreme points, measured.)
    from tefcore.linear.stability import periodic_state_matrix
    from tefcore.paper.figures.catalogue import figure_config

    cfg = figure_config("fig13").with_overrides({"flap.midspan": 0.90})
    tr = stability(cfg).trim_result
    a_of_psi, _ = periodic_state_matrix(tr)
    n = tr.model.n_dof
    kw = dict(n_steps=72, method="magnus", shift_states=slice(0, n))
    with warnings.catch_warnings():          # K = 4 may also warn that roots do not split
        warnings.simplefilter("ignore", RuntimeWarning)
        fixed = floquet.floquet_modes(a_of_psi, n_sub=4, max_sub=4, **kw)
    adaptive = floquet.floquet_modes(a_of_psi, n_sub=4, **kw)
    eight = floquet.floquet_modes(a_of_psi, n_sub=8, max_sub=8, **kw)
    reference = floquet.floquet_modes(a_of_psi, n_sub=16, max_sub=16, **kw)
    assert fixed.n_sub == 4 and adaptive.n_sub > 4
    ref = np.sort(reference.damping_rates)
    assert ref[0] < -4.5
    err_fixed = np.abs(np.sort(fixed.damping_rates) - ref).max()
    err_adaptive = np.abs(np.sort(adaptive.damping_rates) - ref).max()
    # raising K gains three orders (1.4e-4 -> 3e-7 /rev measured): a factor 100
    # fails if the adaptive K stopped helping
    assert err_adaptive < 1e-2 * err_fixed
    # converged in K: 8 against 16 agree to 3e-7 /rev (observed); 5e-4 as before
    assert_allclose(np.sort(eight.damping_rates), ref, atol=5e-4)
    assert_allclose(np.sort(adaptive.damping_rates), ref, atol=5e-4)


def test_lightly_damped_forward_flight_keeps_four_sub_intervals(forward):
    # MDART at mu = 0.3: the most damped root (TEF, about -2 /rev) has
    # |mu| = exp(-2 pi / 2) ~ 0.04 >= MIN_ROOT, so K stays at 4 (no extra cost)
    from tefcore.linear.stability import periodic_state_matrix

    a_of_psi, _ = periodic_state_matrix(forward)
    n = forward.model.n_dof
    res = floquet.floquet_modes(a_of_psi, n_steps=72, n_sub=4, method="magnus",
                                shift_states=slice(0, n))
    assert res.n_sub == 4


def test_statically_diverged_flap_is_refused_not_trimmed(mdart):
    # MDART's flap in hover is aerodynamically over-balanced beyond ~0.59
    # overhang (its hinge-moment stiffness, actuator included, turns negative):
    # the trim then runs away to flap deflections of hundreds of degrees (215
    # deg at 0.63, measured) -- refused with the reason, not returned
    from tefcore.trimming.trim import MAX_FLAP_DEFLECTION_DEG, TrimError

    cfg = mdart.with_overrides({"flight.advance_ratio": 0.0, "flap.cg_offset": 0.0,
                                "flap.overhang": 0.63})
    with pytest.raises(TrimError, match="diverges statically") as err:
        trim(coupled_model(cfg))
    assert err.value.history                      # the Newton history is kept
    ok = trim(coupled_model(cfg.with_overrides({"flap.overhang": 0.29})))
    assert np.rad2deg(abs(ok.q[-1].mean())) < MAX_FLAP_DEFLECTION_DEG


# ------------------------------------------------------------------ stiff and damped actuators


# with damping 1e5 the TEF root (about -4.5e3 /rev) is far below the lifting's resolution:
# floquet warns that its roots do not split, which is true and not what is tested here
@pytest.mark.filterwarnings("ignore:lifted eigenvalues do not split:RuntimeWarning")
@pytest.mark.parametrize("override", [{"actuator.stiffness": 1e12}, {"actuator.damping": 1e5}])
def test_stiff_or_heavily_damped_actuator_gives_no_spurious_instability(mdart, override):
    """With a rigid actuator (stiffness 1e12 N m/rad) torsion 1 comes out at +3.249 /rev
    at a fixed 72 Magnus steps, and at +15.7 with damping 1e5; the
    step-doubling control gives a converged root (on the re-derived MDART data -0.627,
    the same at 72, 288 and 720 steps to 7e-5, measured; the tolerance
    1e-3 + 1e-3 |sigma| is 1.6e-3 for it)."""
    res = stability(mdart.with_overrides(override))
    m = res.modes.set_index("label")
    assert m.loc["blade torsion 1", "real_part"] == pytest.approx(-0.627, abs=5e-3)
    assert m["real_part"].max() < 1e-3          # nothing unstable beyond the tolerance


def test_an_untrustworthy_floquet_result_is_a_clear_error(mdart):
    """actuator.damping = 1e6 does not end in scipy's 'array must not contain infs or
    NaNs': the transition matrices' accuracy is checked and the point fails naming the
    exponent, the estimate and what to raise."""
    with pytest.raises(Exception) as info:
        stability(mdart.with_overrides({"actuator.damping": 1e6}))
    assert type(info.value).__name__ == "FloquetAccuracyError"
    assert "not converged at n_steps = 2304 (magnus)" in str(info.value)
