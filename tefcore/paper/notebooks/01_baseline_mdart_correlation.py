# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 01 -- Baseline MDART rotor: blade modes and lag stability (Figs. 3-4)
#
# Before adding a trailing-edge flap (TEF), the paper checks that its analysis
# predicts the stability of the bare rotor: the **McDonnell-Douglas Advanced
# Rotor Technology (MDART)** rotor, a five-bladed *bearingless* rotor (a
# pre-production MD900), tested in the NASA Ames 40- by 80-foot wind tunnel in
# 1994. Figure 3 shows the lag damping ratio against collective pitch in
# hover, Figure 4 at advance ratio 0.25 with the shaft tilted 7.3 deg forward.
# The paper reports that UMARC "agrees well" with the test data in hover and
# "fairly well" in forward flight.
#
# **No MDART test data is available to us.** The wind-tunnel measurements
# (the paper's Ref. 20) are not published in a form we can obtain, and we do
# not digitise them from the paper's plots. This notebook therefore shows
# tefcore's *prediction* of lag damping versus collective, without a
# correlation, and says so on every plot.
#
# What couples to what: the first lag mode of a soft-inplane rotor sits below
# 1/rev (about 0.6/rev here). Lag motion produces almost no aerodynamic damping
# (only drag and induced-drag changes), so the lag damping comes from the
# flexbeam/snubber structural damping plus **flap-lag coupling**: Coriolis
# forces from flapping and the tilt of the lift vector with inflow. Both grow
# with thrust, which is why lag damping is plotted against collective pitch.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/01_baseline_mdart_correlation"
n_jobs = 1                 # processes for the stability sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied over each figure's caption,
                           # e.g. {"flight.ct_sigma": 0.08, "flight.advance_ratio": 0.2}
n_points = None            # None: the paper's sweep values; int: that many, evenly, same range
values = {}                # explicit sweep values per figure, e.g. {"fig8": [0.0, 0.25, 0.5]}
damping_measure = "damping_ratio"  # "decay_rate" (-Re(s)/Omega) or "damping_ratio" (%)

# %% tags=["nbval-ignore-output"]
# %matplotlib inline
import matplotlib.pyplot as plt

import tefcore
from tefcore.paper import notebook_tools as nt

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, config=config)
claims_cfg = base.with_overrides(overrides) if overrides else base  # for runs validation adds
results, variants = {}, {}

# %% [markdown]
# ## The blade: coupled modes, fan plot and the stated frequencies
#
# The MDART property tables are not public; `tefcore/data/mdart.toml` assumes
# them (each value with its source) and calibrates the torsion stiffness, the
# pitch-horn arm and the baseline pitch-link stiffness to the four first-torsion
# frequencies the text states (Figs. 10a and 11a). The flap and lag
# frequencies are typical bearingless values, not stated by the paper.

# %%
import numpy as np

from tefcore.structure.blade import blade_modes, fan_plot
from tefcore.paper.calibration import frequency_checks

modes = blade_modes(base).table()
modes["frequency_hz"] = modes["frequency_per_rev"] * base.rotor.rotor_speed / (2 * np.pi)
cols = ["mode", "label", "frequency_per_rev", "frequency_hz", "flap_fraction", "lag_fraction",
        "torsion_fraction"]
print("coupled blade modes at 392 RPM, zero collective (fractions: share of kinetic energy)")
print(nt.clean(modes[cols].round(3)).to_string(index=False))

# %%
ax = fan_plot(base)
ax.set_title("MDART blade (assumed properties): coupled modes vs rotor speed", fontsize="medium")
nt.savefig(ax.figure, out, "blade_fanplot");

# %%
checks = frequency_checks(base)
print(nt.clean(checks.drop(columns="source").round(3)).to_string(index=False))
print("largest error against the stated frequencies: "
      f"{checks['error_percent'].abs().max():.2f} %")

# %% [markdown]
# The fan plot shows how each frequency grows with rotor speed as centrifugal
# stiffening adds to the elastic stiffness; the grey rays are 1/rev, 2/rev,
# ... Crossings of a ray at the operating speed (vertical line) would mean
# resonance with the periodic airloads. The table above is the check of the
# assumed structure: first torsion at 2.3/rev and 4.2/rev for pitch-link
# stiffnesses of 158 and 800 lb/in, and 2.96/rev and 3.18/rev at 0.75 and 2.0
# times the baseline GJ.
#
# ## Figure 3: lag damping versus collective in hover
#
# The rotor here has **no** trailing-edge flap (`model.tef = none`), as in
# the paper's correlation.

# %%
cfg_fig3 = nt.run_config("fig3", base, overrides)
vals_fig3 = nt.figure_values("fig3", n_points, values.get("fig3"))
res_fig3 = tefcore.sweep(cfg_fig3, "flight.collective", vals_fig3,
                         point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig3"] = res_fig3
nt.report_sweep("fig3", res_fig3)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.2))
nt.plot_modes(ax_a, "fig3", res_fig3.table, labels=("blade lag 1",), measure=damping_measure)
ax_a.set_title("lag damping (tefcore prediction; no MDART test data)", fontsize="medium")
ax_a.set_ylim(bottom=0)
nt.plot_modes(ax_b, "fig3", res_fig3.table, labels=("blade lag 1",), quantity="frequency")
ax_b.set_title("lag frequency", fontsize="medium")
fig.suptitle(nt.figure_title("fig3", cfg_fig3, width=110) + " -- prediction only, no test data",
             fontsize="medium")
nt.savefig(fig, out, "fig03", figure="fig3",
           caption=nt.figure_caption("fig3", cfg_fig3,
                                     "(a) lag damping (tefcore prediction; no MDART test data); "
                                     "(b) lag frequency"));

# %%
print(nt.mode_summary("fig3", res_fig3.table, labels=("blade lag 1",), measure=damping_measure)
      .rename(columns={"blade lag 1": "lag damping"}).to_string())

# %% [markdown]
# ## Figure 4: lag damping versus collective at mu = 0.25
#
# Same rotor in forward flight, shaft tilted 7.3 deg forward (a steady level
# flight attitude). In forward flight the equations have periodic
# coefficients and the Floquet method gives the damping.

# %%
cfg_fig4 = nt.run_config("fig4", base, overrides)
vals_fig4 = nt.figure_values("fig4", n_points, values.get("fig4"))
res_fig4 = tefcore.sweep(cfg_fig4, "flight.collective", vals_fig4,
                         point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig4"] = res_fig4
nt.report_sweep("fig4", res_fig4)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.2))
nt.plot_modes(ax_a, "fig4", res_fig4.table, labels=("blade lag 1",), measure=damping_measure)
ax_a.set_title("lag damping (tefcore prediction; no MDART test data)", fontsize="medium")
ax_a.set_ylim(bottom=0)
nt.plot_modes(ax_b, "fig4", res_fig4.table, labels=("blade lag 1",), quantity="frequency")
ax_b.set_title("lag frequency", fontsize="medium")
fig.suptitle(nt.figure_title("fig4", cfg_fig4, width=110), fontsize="medium")
nt.savefig(fig, out, "fig04", figure="fig4",
           caption=nt.figure_caption("fig4", cfg_fig4,
                                     "(a) lag damping (tefcore prediction; no MDART test data); "
                                     "(b) lag frequency"));

# %%
print(nt.mode_summary("fig4", res_fig4.table, labels=("blade lag 1",), measure=damping_measure)
      .rename(columns={"blade lag 1": "lag damping"}).to_string())

# %% [markdown]
# ## Two models of the bearingless hub
#
# The MDART hub is a flexbeam (carrying flap, lag and the centrifugal force)
# inside a torque tube (carrying the pitch input from the pitch link), joined
# to the blade at the clevis, with an elastomeric snubber/damper at the hub --
# the "multiple load paths" of the paper's UMARC model. tefcore's default lumps
# the hub into equivalent root springs and a lag damper
# (`hub.model = "equivalent"`); `hub.model = "multiple_load_path"` builds the
# branched beams (docs/theory.md section 2.5a). Both are calibrated to the same
# four torsion frequencies the text states, and the branched hub's flexbeam
# bending and snubber stiffness place flap 1, lag 1 and its structural damping
# where the equivalent hub has them -- so the two differ in mode *shapes* and
# kinematic couplings, not in where the fundamental modes sit. The lag damping
# of Figs. 3 and 4 is nearly the same for both: with no pitch-link cant (none
# is stated), the branched hub adds little pitch-lag coupling.

# %%
from tefcore.paper.attribution.hub_comparison import compare_hub_models, plot_hub_models

hubs = compare_hub_models(base, n_jobs=n_jobs)
wide = hubs.modes.pivot_table(index="mode", columns="hub_model", values="frequency_per_rev",
                              aggfunc="first")
wide.insert(0, "label (equivalent)", hubs.modes[hubs.modes["hub_model"] == "equivalent"]
            .set_index("mode")["label"])
wide.insert(2, "label (multiple load path)",
            hubs.modes[hubs.modes["hub_model"] == "multiple_load_path"]
            .set_index("mode")["label"])
print("retained modes at 392 RPM [/rev]:")
print(nt.clean(wide.round(3)).to_string())
lag = hubs.lag_damping.assign(damping_percent=lambda d: (100 * d["damping_ratio"]).round(2))
print("lag 1 damping [%] against collective [deg]:")
print(lag.pivot_table(index=["figure", "collective_deg"], columns="hub_model",
                      values="damping_percent").round(2).to_string())

# %%
fig = plot_hub_models(hubs, base)
nt.savefig(fig, out, "hub_models",
           caption="The two hub models: fan plots (top; grey rays 1-8/rev, vertical line "
                   "392 RPM) and the lag damping of Figs. 3 and 4 (bottom) with equivalent "
                   "root springs and with multiple load paths (flexbeam, torque tube, pitch "
                   "link, snubber).");

# %% [markdown]
# **What the paper concludes:** UMARC's lag damping agrees well with the MDART
# hover data and fairly well at mu = 0.25, which gives confidence in the
# baseline analysis before the flap is added. **What we can say:** only the
# trend of the prediction. The level at zero collective is set mostly by the
# assumed snubber damper (`hub.lag_damper`, a placeholder chosen for about 2 %
# critical damping), so it is an input, not a result; the change with collective
# comes from the flap-lag coupling of the model.

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper checked against these results, as in
# [notebook 03](03_overhang.ipynb#Validation:-the-paper's-claims-for-these-figures);
# the tables, the figures and `claims.csv` are in `output_dir`.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig03_modes": res_fig3.table,
    "fig04_modes": res_fig4.table,
    "blade_modes": modes,
    "blade_frequency_checks": checks,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig3", "fig4")
