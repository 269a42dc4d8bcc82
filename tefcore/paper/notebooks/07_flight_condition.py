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
# # 07 -- Flight condition: collective pitch and forward speed (Figs. 16-17)
#
# Mass-imbalanced flap (c_cg = 0.33 c_f, c_b = 0.29 c_f). The structural and
# inertial couplings do not depend on the flight condition; the aerodynamic
# ones do:
#
# * **collective pitch** raises the blade's steady lift and the trimmed flap
#   deflection and hinge moment, changing the aerodynamic stiffness around
#   which the flap oscillates;
# * **forward speed** makes the dynamic pressure periodic (advancing side high,
#   retreating side low) and couples the modes through periodic coefficients,
#   which is why the Floquet method is needed; on the advancing side the flap
#   sees up to (0.83 + mu)^2 of the hover dynamic pressure at the flap.
#
# Here the collective is prescribed (not trimmed to a thrust).

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/07_flight_condition"
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
# ## Figure 16: collective pitch, (a) hover and (b) mu = 0.30
#
# Paper: in hover the **TEF mode becomes unstable at large collective**, though
# the variation is very small; at mu = 0.30 it is **unstable from 4 to 12 deg
# collective and increasingly so** with larger collective.

# %%
cfg_fig16a = nt.run_config("fig16a", base, overrides)
vals_fig16a = nt.figure_values("fig16a", n_points, values.get("fig16a"))
res_fig16a = tefcore.sweep(cfg_fig16a, "flight.collective", vals_fig16a,
                           point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
cfg_fig16b = nt.run_config("fig16b", base, overrides)
vals_fig16b = nt.figure_values("fig16b", n_points, values.get("fig16b"))
res_fig16b = tefcore.sweep(cfg_fig16b, "flight.collective", vals_fig16b,
                           point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results.update(fig16a=res_fig16a, fig16b=res_fig16b)
nt.report_sweep("fig16a", res_fig16a)
nt.report_sweep("fig16b", res_fig16b)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
nt.plot_modes(ax_a, "fig16a", res_fig16a.table, measure=damping_measure,
              reference=nt.reference_curves("fig16a"))
ax_a.set_title("(a) " + nt.flight_condition(cfg_fig16a), fontsize="medium")
nt.plot_modes(ax_b, "fig16b", res_fig16b.table, measure=damping_measure,
              reference=nt.reference_curves("fig16b"))
ax_b.set_title("(b) " + nt.flight_condition(cfg_fig16b), fontsize="medium")
nt.legend_below(ax_b)
title16 = ("Fig. 16: effect of collective pitch ("
           + nt.conditions(cfg_fig16b, exclude=("flight.collective", "flight.advance_ratio"))
           + ")")
fig.suptitle(title16, fontsize="medium")
nt.savefig(fig, out, "fig16", figure="fig16a fig16b",
           caption=f"{title16}. Damping of the blade modes and the TEF branch: (a) "
                   f"{nt.flight_condition(cfg_fig16a)}, (b) {nt.flight_condition(cfg_fig16b)}. "
                   + nt.MARKERS);

# %%
for name in ("fig16a", "fig16b"):
    print(f"{name}: damping (" + damping_measure + ")")
    print(nt.mode_summary(name, results[name].table, measure=damping_measure).to_string())
    print("TEF damping changes sign at:",
          nt.sign_changes(name, results[name].table, measure=damping_measure) or "nowhere")

# %% [markdown]
# ## Figure 17: forward speed
#
# Paper: the **TEF mode is weakly unstable in hover and becomes more unstable
# with forward speed**.

# %%
vals_fig17 = nt.figure_values("fig17", n_points, values.get("fig17"))
cfg_fig17 = nt.run_config("fig17", base, overrides)
res_fig17 = tefcore.sweep(cfg_fig17, "flight.advance_ratio", vals_fig17,
                          point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig17"] = res_fig17
nt.report_sweep("fig17", res_fig17)

# %%
nt.damping_figure("fig17", res_fig17, cfg_fig17, out, measure=damping_measure)

# %% [markdown]
# **Which root is which**: the TEF branch and the flutter root, as defined in
# [notebook 03, *Which root is which*](03_overhang.ipynb#Which-root-is-which).

# %%
nt.which_root("fig17", res_fig17, cfg_fig17, out)

# %%
nt.damping_summary("fig17", res_fig17, measure=damping_measure)

# %% [markdown]
# **What the paper concludes** (conclusions 2 and 6): torsion-flap flutter of a
# mass-unbalanced flap is worse at high advance ratio, and increasing
# collective pitch makes the TEF mode more unstable. Combined with notebooks
# 03-06, the design message is: mass-balance the flap, keep the overhang
# moderate, and keep the actuator stiff.

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper checked against these results, as in
# [notebook 03](03_overhang.ipynb#Validation:-the-paper's-claims-for-these-figures);
# the tables, the figures and `claims.csv` are in `output_dir`.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig16a_modes": res_fig16a.table,
    "fig16b_modes": res_fig16b.table,
    "fig17_modes": res_fig17.table,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig16a", "fig16b", "fig17")

# %%
for name in ["fig16b", "fig17"]:
    nt.unsteadiness(name, results[name], base)
