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
# # 05 -- Control system, blade torsion and actuator stiffness (Figs. 10-12)
#
# From here on the flap is deliberately **mass-imbalanced** (CG offset 0.33
# c_f, overhang 0.29 c_f) and the rotor flies at mu = 0.30: a configuration
# prone to TEF/torsion flutter (notebook 04), used to see which stiffnesses
# make it better or worse. Three stiffnesses set the frequencies of the two
# modes that flutter together:
#
# * **pitch-link stiffness** (rotor control system) -- mostly sets the blade's
#   first torsion frequency (2.3/rev at 158 lb/in to 4.2/rev at 800 lb/in);
# * **blade torsional stiffness GJ** -- also raises torsion, but much less here
#   (2.96/rev at 0.75 GJ to 3.18/rev at 2 GJ), since the soft root dominates;
# * **actuator stiffness** -- sets the TEF frequency (sqrt(k_a / I_f)).
#
# Flutter from inertial coupling is strongest when the two coupled frequencies
# approach each other, and the sign of the energy exchange depends on their
# order and phase -- so stiffening one side can stabilise or destabilise.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/05_stiffness"
n_jobs = 1                 # processes for the stability sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied over each figure's caption,
                           # e.g. {"flight.ct_sigma": 0.08, "flight.advance_ratio": 0.2}
n_points = None            # None: the paper's sweep values; int: that many, evenly, same range
values = {}                # explicit sweep values per figure, e.g. {"fig8": [0.0, 0.25, 0.5]}
damping_measure = "decay_rate"  # "decay_rate" (-Re(s)/Omega) or "damping_ratio" (%)

# %% tags=["nbval-ignore-output"]
# %matplotlib inline
import matplotlib.pyplot as plt
import pandas as pd

import tefcore
from tefcore.paper import notebook_tools as nt

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, config=config)
claims_cfg = base.with_overrides(overrides) if overrides else base  # for runs validation adds
results, variants = {}, {}

# %% [markdown]
# ## Figure 10: pitch-link stiffness
#
# Paper: torsion frequency 2.3 -> 4.2/rev, flap and lag frequencies
# unchanged; the **TEF mode becomes gradually more unstable** with stiffer
# pitch links; blade flap damping increases strongly, torsion damping
# decreases slightly, lag varies little.

# %%
modes_fig10 = ("blade flap 1", "blade lag 1", "blade torsion 1", "TEF")
blade_modes_a = ("blade flap 1", "blade lag 1", "blade torsion 1")
vals_fig10 = nt.figure_values("fig10", n_points, values.get("fig10"))
cfg_fig10 = nt.run_config("fig10", base, overrides)
res_fig10 = tefcore.sweep(cfg_fig10, "hub.pitch_link_stiffness", vals_fig10,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
nat_fig10 = nt.natural_frequencies("fig10", vals_fig10, base, overrides)
results["fig10"] = res_fig10
nt.report_sweep("fig10", res_fig10)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "fig10", res_fig10.table, quantity="frequency", labels=blade_modes_a,
              natural=nat_fig10)
ax_a.set_title("(a) blade natural frequencies", fontsize="medium")
nt.legend_below(ax_a)
nt.plot_modes(ax_b, "fig10", res_fig10.table, measure=damping_measure, labels=modes_fig10,
              reference=nt.reference_curves("fig10"))
ax_b.set_title("(b) blade and TEF damping", fontsize="medium")
nt.legend_below(ax_b)
fig.suptitle(nt.figure_title("fig10", cfg_fig10, width=110), fontsize="medium")
nt.savefig(fig, out, "fig10", figure="fig10",
           caption=nt.figure_caption("fig10", cfg_fig10,
                                     "(a) blade natural frequencies; (b) damping of the blade "
                                     "modes and the TEF branch"));

# %% [markdown]
# **Which root is which**: the TEF branch and the flutter root, as defined in
# [notebook 03, *Which root is which*](03_overhang.ipynb#Which-root-is-which).

# %%
nt.which_root("fig10", res_fig10, cfg_fig10, out, labels=modes_fig10)

# %%
nt.damping_summary("fig10", res_fig10, measure=damping_measure, labels=modes_fig10)

# %% [markdown]
# ## Figure 11: blade torsional stiffness (GJ factor)
#
# Paper: torsion frequency 2.96 -> 3.18/rev; the **TEF mode is unstable over
# the whole range** 0.75-2.0 GJ with little variation; torsion damping
# decreases slightly and flap damping increases with GJ.

# %%
modes_fig11 = ("blade flap 1", "blade lag 1", "blade torsion 1", "TEF")
blade_modes_a = ("blade flap 1", "blade lag 1", "blade torsion 1")
vals_fig11 = nt.figure_values("fig11", n_points, values.get("fig11"))
cfg_fig11 = nt.run_config("fig11", base, overrides)
res_fig11 = tefcore.sweep(cfg_fig11, "blade.gj_scale", vals_fig11,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
nat_fig11 = nt.natural_frequencies("fig11", vals_fig11, base, overrides)
results["fig11"] = res_fig11
nt.report_sweep("fig11", res_fig11)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "fig11", res_fig11.table, quantity="frequency", labels=blade_modes_a,
              natural=nat_fig11)
ax_a.set_title("(a) blade natural frequencies", fontsize="medium")
nt.legend_below(ax_a)
nt.plot_modes(ax_b, "fig11", res_fig11.table, measure=damping_measure, labels=modes_fig11,
              reference=nt.reference_curves("fig11"))
ax_b.set_title("(b) blade and TEF damping", fontsize="medium")
nt.legend_below(ax_b)
fig.suptitle(nt.figure_title("fig11", cfg_fig11, width=110), fontsize="medium")
nt.savefig(fig, out, "fig11", figure="fig11",
           caption=nt.figure_caption("fig11", cfg_fig11,
                                     "(a) blade natural frequencies; (b) damping of the blade "
                                     "modes and the TEF branch"));

# %%
nt.which_root("fig11", res_fig11, cfg_fig11, out, labels=modes_fig11)

# %%
nt.damping_summary("fig11", res_fig11, measure=damping_measure, labels=modes_fig11)

# %%
for name, nat in (("fig10", nat_fig10), ("fig11", nat_fig11)):
    print(f"{name} (a): blade natural frequencies [/rev]")
    print(nt.mode_summary(name, None, labels=("blade flap 1", "blade lag 1", "blade torsion 1"),
                          quantity="frequency", natural=nat).to_string())

# %% [markdown]
# Panel (a) of Figs. 10 and 11 shows the blade's *natural* frequencies (the
# structure in vacuum, rotating, at zero collective), which is what the stated
# 2.3-4.2/rev and 2.96-3.18/rev refer to and what the assumed properties were
# calibrated to. The aeroelastic (Floquet) frequencies of the coupled
# system differ from them -- strongly for the torsion mode, which the
# imbalanced flap's inertia and the aerodynamic stiffness both load.

# %% [markdown]
# ## Figure 12: actuator stiffness
#
# Panel (a) compares the TEF frequency of a mass-balanced flap (c_cg = 0) and
# the mass-imbalanced one (c_cg = 0.33 c_f): both rise with actuator
# stiffness, the imbalanced one more slowly because of its larger inertia
# about the hinge. Panel (b), for the imbalanced flap: the paper finds the
# **TEF mode unstable with a soft actuator and stable above 1.5 times the
# baseline stiffness**: raising the flap frequency moves it away from the blade
# modes it exchanges energy with. Blade flap damping increases with actuator
# stiffness, torsion damping decreases, lag is unaffected.

# %%
vals_fig12 = nt.figure_values("fig12", n_points, values.get("fig12"))
cfg_fig12 = nt.run_config("fig12", base, overrides)
res_fig12 = tefcore.sweep(cfg_fig12, "actuator.stiffness", vals_fig12,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
cfg_fig12_balanced = cfg_fig12.with_overrides({"flap.cg_offset": 0.0})   # Fig. 12(a)
res_fig12_balanced = tefcore.sweep(cfg_fig12_balanced, "actuator.stiffness", vals_fig12,
                                   point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig12"] = res_fig12
variants["fig12"] = {nt.variant_key({"flap.cg_offset": 0.0}): res_fig12_balanced}
nt.report_sweep("fig12", res_fig12)
nt.report_sweep("fig12 (balanced)", res_fig12_balanced)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "fig12", res_fig12_balanced.table, labels=("TEF",), quantity="frequency",
              label_suffix=", c_cg/c_f = 0", style={"TEF": ("C0", "s", "--")})
nt.plot_modes(ax_a, "fig12", res_fig12.table, labels=("TEF",), quantity="frequency",
              label_suffix=", c_cg/c_f = 0.33")
ax_a.set_title("(a) trailing-edge flap frequency", fontsize="medium")
nt.legend_below(ax_a)
nt.plot_modes(ax_b, "fig12", res_fig12.table, measure=damping_measure,
              labels=("blade flap 1", "blade lag 1", "blade torsion 1", "TEF"),
              reference=nt.reference_curves("fig12"))
ax_b.set_title("(b) blade and TEF damping, c_cg/c_f = 0.33", fontsize="medium")
nt.legend_below(ax_b)
fig.suptitle(nt.figure_title("fig12", cfg_fig12, width=110), fontsize="medium")
nt.savefig(fig, out, "fig12", figure="fig12",
           caption=nt.figure_caption("fig12", cfg_fig12,
                                     "(a) TEF frequency; (b) damping of the blade modes and the "
                                     "TEF branch, mass-imbalanced and balanced flap"));

# %%
print("TEF frequency [/rev]: balanced (c_cg = 0) and imbalanced (c_cg = 0.33)")
print(pd.concat({"balanced": nt.mode_summary("fig12", res_fig12_balanced.table, labels=("TEF",),
                                             quantity="frequency")["TEF"],
                 "imbalanced": nt.mode_summary("fig12", res_fig12.table, labels=("TEF",),
                                               quantity="frequency")["TEF"]}, axis=1).to_string())
print("damping (" + damping_measure + "), imbalanced flap:")
print(nt.mode_summary("fig12", res_fig12.table, measure=damping_measure).to_string())
print("TEF damping changes sign at:", nt.sign_changes("fig12", res_fig12.table,
                                                      measure=damping_measure) or "nowhere")

# %% [markdown]
# **What the paper concludes:** increasing rotor control stiffness with a
# mass-imbalanced flap *may destabilise* the TEF mode (conclusion 3);
# increasing the actuator stiffness *stabilises* it (conclusion 4). Blade GJ
# matters little in the range studied.

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper checked against these results, as in
# [notebook 03](03_overhang.ipynb#Validation:-the-paper's-claims-for-these-figures);
# the tables, the figures and `claims.csv` are in `output_dir`.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig10_modes": res_fig10.table,
    "fig11_modes": res_fig11.table,
    "fig12_modes": res_fig12.table,
    "fig12_balanced_modes": res_fig12_balanced.table,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig10", "fig11", "fig12")

# %%
for name in ["fig10", "fig12"]:
    nt.unsteadiness(name, results[name], base)
