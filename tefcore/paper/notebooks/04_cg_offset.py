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
# # 04 -- Mass balance: flap CG offset (Fig. 9)
#
# A flap whose centre of gravity lies **behind its hinge** (c_cg > 0) is
# *mass-unbalanced*: when the blade section accelerates up or down (flap
# bending) or twists (torsion), the flap's inertia lags behind and the flap
# rotates about its hinge -- and a flap rotation in turn shakes the blade.
# This **inertial coupling** is the mechanism of classic aileron flutter on
# fixed wings (Broadbent, Fung, Theodorsen in the paper's references), and the
# cure there is the same as here: mass balance, stiffer (irreversible) controls,
# more damping.
#
# Two effects of moving the CG aft, at constant actuator stiffness:
#
# 1. the flap's moment of inertia about the hinge grows (I_cg + m d^2), so the
#    **TEF frequency decreases**;
# 2. the inertial coupling with blade torsion grows, and with it the energy the
#    two modes can exchange per cycle: past some offset the aerodynamic work
#    of the flap on the twisting blade is positive and the **TEF mode becomes
#    unstable** -- trailing-edge flap / blade torsion flutter.
#
# Conditions: forward flight, mu = 0.30, overhang 0.29 c_f.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/04_cg_offset"
n_jobs = 1                 # processes for the stability sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied over each figure's caption,
                           # e.g. {"flight.ct_sigma": 0.08, "flight.advance_ratio": 0.2}
n_points = None            # None: the paper's sweep values; int: that many, evenly, same range
values = {}                # explicit sweep values per figure, e.g. {"fig8": [0.0, 0.25, 0.5]}
damping_measure = "decay_rate"  # "decay_rate" (-Re(s)/Omega) or "damping_ratio" (%)
interactive = True         # the explorer's sliders (ipywidgets); False: a static figure

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
# ## Figure 9: (a) TEF frequency and (b) blade and TEF damping versus CG offset

# %%
vals_fig9 = nt.figure_values("fig9", n_points, values.get("fig9"))
cfg_fig9 = nt.run_config("fig9", base, overrides)
res_fig9 = tefcore.sweep(cfg_fig9, "flap.cg_offset", vals_fig9,
                         point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig9"] = res_fig9
nt.report_sweep("fig9", res_fig9)

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "fig9", res_fig9.table, quantity="frequency", labels=("TEF",))
ax_a.set_title("(a) trailing-edge flap frequency", fontsize="medium")
nt.legend_below(ax_a)
nt.plot_modes(ax_b, "fig9", res_fig9.table, measure=damping_measure,
              reference=nt.reference_curves("fig9"))
ax_b.set_title("(b) blade and TEF damping", fontsize="medium")
nt.legend_below(ax_b)
fig.suptitle(nt.figure_title("fig9", cfg_fig9, width=110), fontsize="medium")
nt.savefig(fig, out, "fig09", figure="fig9",
           caption=nt.figure_caption("fig9", cfg_fig9,
                                     "(a) TEF frequency; (b) damping of the blade modes and the "
                                     "TEF branch"));

# %% [markdown]
# **Which root is which**: the TEF branch and the flutter root, as defined in
# [notebook 03, *Which root is which*](03_overhang.ipynb#Which-root-is-which).

# %%
nt.which_root("fig9", res_fig9, cfg_fig9, out)

# %%
nt.damping_summary("fig9", res_fig9, measure=damping_measure)

# %%
print("TEF frequency [/rev] versus CG offset:")
print(nt.mode_summary("fig9", res_fig9.table, labels=("TEF",), quantity="frequency").to_string())

# %% [markdown]
# ### Why: the growth rate as work done by each term
#
# `tefcore.linear.mechanism` writes the root's real part as an exact energy balance:
# each term of the linearised equations (blade inertia and stiffness, the
# blade's own airloads, the flap's lift and pitching moment on the blade, the
# hinge moments, the flap's inertial couplings, the actuator ...) does some net
# work on the mode per cycle; divided by twice the mode's energy, these add up
# to the real part (positive: the term feeds the mode). Conservative terms --
# the inertial couplings among them -- do no net work themselves: they shape
# the mode so that the aerodynamic terms can. That is what the **knockouts**
# show: the same root followed while one term is switched off.
# The paper calls the instability of the mass-unbalanced flap "typical
# trailing-edge flap-blade torsion flutter", resulting "from the energy transfer
# between the trailing-edge flap mode and blade torsion mode". Here is the TEF
# branch and the flutter root at c_cg = 0.33 c_f (the paper's imbalanced flap),
# term by term: which terms do the destabilising work, and what happens when the
# flap-torsion couplings are knocked out:

# %%
print(nt.explain("fig9", res_fig9, 0.33, base, overrides).to_string(index=False))

# %%
print(nt.explain("fig9", res_fig9, 0.33, base, overrides, which="flutter root",
                 knockouts=False).to_string(index=False))

# %% [markdown]
# **What the paper concludes:** the TEF frequency falls with CG offset; the TEF
# mode becomes unstable after an offset of **0.26 flap chord** (flap/torsion
# flutter from energy transfer between the TEF and blade torsion modes); blade
# flap damping decreases with offset and lag damping is unaffected. Conclusion
# 2: large flap CG offsets cause torsion-flap flutter, especially at high
# advance ratios. Notebooks 05-07 use a deliberately mass-imbalanced flap
# (c_cg = 0.33 c_f) to study what makes that flutter better or worse.
#
# Where the mode labels swap (hollow markers), TEF and torsion motion are
# strongly mixed in one eigenvector -- the signature of the coupling that
# drives the flutter.

# %% [markdown]
# ## Explore: move the flap's CG, overhang, actuator stiffness and forward speed
#
# Every root of the Floquet analysis at one configuration, in the s-plane
# (frequency against real part; above the line: unstable), coloured by how
# much the flap takes part in it. The red ring is the TEF root (the flap's own
# mode followed as the coupling is switched on), the black cross the flutter
# root (the least stable root the flap takes part in); on the right the damping
# of the paper's modes. In Jupyter the sliders redraw it and leave the earlier
# roots as a grey trail: drag one slider and the trail is that parameter's root
# locus. Try moving the CG forward of the hinge (negative c_cg: a nose balance
# weight), or halving the actuator stiffness. Each redraw is one trim and one
# Floquet analysis, a fraction of a second. Run non-interactively (papermill,
# `tefcore reproduce`, an HTML export) it draws the starting point once.

# %% tags=["nbval-ignore-output"]
explorer = nt.explore(base, interactive=interactive, cg_offset=0.33, overhang=0.29,
                      actuator_scale=1.0, advance_ratio=0.30)

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper checked against these results, as in
# [notebook 03](03_overhang.ipynb#Validation:-the-paper's-claims-for-these-figures);
# the tables, the figures and `claims.csv` are in `output_dir`.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig09_modes": res_fig9.table,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig9")

# %%
for name in ["fig9"]:
    nt.unsteadiness(name, results[name], base)
