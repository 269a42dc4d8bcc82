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
# # 06 -- Flap size and spanwise location (Figs. 13-15)
#
# Mass-imbalanced flap (c_cg = 0.33 c_f, c_b = 0.29 c_f), mu = 0.30. Where the
# flap sits and how big it is changes two things at once:
#
# * the **dynamic pressure** it sees (proportional to (r/R)^2 in hover, more
#   outboard) and the size of its aerodynamic and inertial loads;
# * the **modal amplitude** of blade flap bending and torsion at the flap:
#   both grow towards the tip, so an outboard flap couples more strongly to the
#   blade modes -- for better (more authority for vibration control) and for
#   worse (more flutter-prone).
#
# A larger flap chord also changes the section aerodynamics of the flap
# itself: the flap's pitching moment peaks near c_f/c = 0.26 while the flap
# lift grows monotonically (the paper's Ref. 21).

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/06_size_and_location"
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

import tefcore
from tefcore.paper import notebook_tools as nt

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, config=config)
claims_cfg = base.with_overrides(overrides) if overrides else base  # for runs validation adds
results, variants = {}, {}

# %% [markdown]
# ## Figure 13: flap midspan location
#
# Paper: the **TEF mode becomes unstable as the flap moves towards the tip**;
# blade flap damping decreases slightly, torsion damping increases, lag is
# unchanged.

# %%
vals_fig13 = nt.figure_values("fig13", n_points, values.get("fig13"))
cfg_fig13 = nt.run_config("fig13", base, overrides)
res_fig13 = tefcore.sweep(cfg_fig13, "flap.midspan", vals_fig13,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig13"] = res_fig13
nt.report_sweep("fig13", res_fig13)

# %%
nt.damping_figure("fig13", res_fig13, cfg_fig13, out, measure=damping_measure)

# %% [markdown]
# **Which root is which**: the TEF branch and the flutter root, as defined in
# [notebook 03, *Which root is which*](03_overhang.ipynb#Which-root-is-which).

# %%
nt.which_root("fig13", res_fig13, cfg_fig13, out)

# %%
nt.damping_summary("fig13", res_fig13, measure=damping_measure)

# %% [markdown]
# ## Figure 14: flap length
#
# Paper: the **TEF mode becomes unstable for flap lengths above 14 % R**; blade
# flap damping decreases with length, torsion damping increases (both stay
# well damped). Length acts like location, but more strongly.

# %%
vals_fig14 = nt.figure_values("fig14", n_points, values.get("fig14"))
cfg_fig14 = nt.run_config("fig14", base, overrides)
res_fig14 = tefcore.sweep(cfg_fig14, "flap.span", vals_fig14,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig14"] = res_fig14
nt.report_sweep("fig14", res_fig14)

# %%
nt.damping_figure("fig14", res_fig14, cfg_fig14, out, measure=damping_measure)

# %%
nt.which_root("fig14", res_fig14, cfg_fig14, out)

# %%
nt.damping_summary("fig14", res_fig14, measure=damping_measure)

# %% [markdown]
# ## Figure 15: flap chord
#
# Paper: the **TEF mode is unstable for flap chords between 0.15 and 0.40 of
# the airfoil chord** and stable outside; blade flap damping follows the TEF
# mode (positive aerodynamic coupling), torsion damping does the opposite
# (negative coupling).

# %%
vals_fig15 = nt.figure_values("fig15", n_points, values.get("fig15"))
cfg_fig15 = nt.run_config("fig15", base, overrides)
res_fig15 = tefcore.sweep(cfg_fig15, "flap.chord_ratio", vals_fig15,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig15"] = res_fig15
nt.report_sweep("fig15", res_fig15)

# %%
nt.damping_figure("fig15", res_fig15, cfg_fig15, out, measure=damping_measure)

# %%
nt.which_root("fig15", res_fig15, cfg_fig15, out)

# %%
nt.damping_summary("fig15", res_fig15, measure=damping_measure)

# %% [markdown]
# **What the paper concludes** (conclusion 5): with a mass-imbalanced flap,
# increasing the flap length or moving the flap towards the tip destabilises
# the TEF mode. Note that in these sweeps the flap is built the same way at
# every size (`flap.scaling = "construction"`): its mass per unit span is kept
# as it grows longer and grows with its chord (its inertia with the chord
# cubed), so a longer or wider flap is also a heavier flap with a larger
# imbalance moment -- the inertial and aerodynamic effects grow together.

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper checked against these results, as in
# [notebook 03](03_overhang.ipynb#Validation:-the-paper's-claims-for-these-figures);
# the tables, the figures and `claims.csv` are in `output_dir`.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig13_modes": res_fig13.table,
    "fig14_modes": res_fig14.table,
    "fig15_modes": res_fig15.table,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig13", "fig14", "fig15")

# %%
for name in ["fig13", "fig15"]:
    nt.unsteadiness(name, results[name], base)
