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
# # 10 -- Unsteady airloads and dynamic inflow: what quasi-steady theory misses
#
# The paper's aerodynamics are quasi-steady: the airloads follow the motion
# instantly, as Theodorsen's theory with his lift-deficiency function
# C(k) = 1. Its authors say why: the one unsteady flap model they had assumed
# the hinge at the flap's nose and could not describe an aerodynamically
# *balanced* flap. But the flap mode oscillates at several times the rotor
# speed: at the flap (0.74-0.92 R) its **reduced frequency** k = omega b / U is
# 0.3-0.4, where Theodorsen's |C| is about 0.65 with some 15 deg of phase lag --
# the circulatory lift of the flap's motion is a third smaller and late.
#
# tefcore has two options beyond the paper, both states of the Floquet
# analysis (no p-k iteration, the stability stays exact):
#
# * `model.aero = "unsteady"`: the **shed wake** of the balanced flap, a
#   finite-state wake per aerodynamic station (docs/theory.md 3.9 and 6.2);
# * `model.inflow = "dynamic"`: **Pitt-Peters dynamic inflow**, three states of
#   the rotor's induced flow (3.10).
#
# Every notebook runs with them: pass `overrides = {"model.aero": "unsteady"}`
# (or `tefcore reproduce -p overrides "{model.aero: unsteady}"`). This notebook
# compares the options for the paper's mass-imbalanced flap (c_cg/c_f = 0.33,
# c_b/c_f = 0.29).

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/10_unsteady"
n_jobs = 1                 # processes for the sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil", "table" (generated deck) or "xfoil" (XFOIL deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied to every option
n_points = 6               # CG offsets of the Fig. 9 comparison (the paper's range)
onset = True               # also find the Fig. 9 onset under each option (a minute)
refine = False             # locate the exceptional points along the Fig. 9 comparison
                           # (bisection, as the figure notebooks do: 62 more points,
                           # 25 s of CPU, mostly unsteady ones)

# %% tags=["nbval-ignore-output"]
# %matplotlib inline
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import tefcore
from tefcore.paper import notebook_tools as nt
from tefcore.paper.attribution.model_comparison import OPTIONS, compare_models
from tefcore.aero.unsteady import fitted_wake, theodorsen_function

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, overrides, config=config)

# %% [markdown]
# ## The section: Theodorsen's C(k) and the finite-state wake
#
# A finite-state wake replaces the wake's integral over the shed vorticity by a
# few states with fitted time constants; its transfer function from the
# upwash to the circulatory lift approximates C(k). With four states (the
# default, `model.wake_states`) it matches C(k) closely at the flap's reduced
# frequencies:

# %%
ks = np.array([0.05, 0.1, 0.2, 0.3, 0.4, 0.6, 1.0])
exact = theodorsen_function(ks)
wake = fitted_wake(4)
approx = wake.lift_deficiency(ks)
table_c = pd.DataFrame({"k": ks, "|C| Theodorsen": np.abs(exact),
                        "phase [deg]": np.degrees(np.angle(exact)),
                        "|C| 4 states": np.abs(approx),
                        "phase 4 states [deg]": np.degrees(np.angle(approx)),
                        "|error|": np.abs(approx - exact)})
print(nt.clean(table_c.round(4)).to_string(index=False))

# %% [markdown]
# ## The imbalanced flap under each option
#
# `tefcore.paper.attribution.model_comparison.compare_models` finds, for each option, the
# Fig. 9 onset (the CG offset where the flutter root turns unstable at
# mu = 0.3) and the flutter root's growth rate at the imbalanced baseline in
# hover and at mu = 0.3, and breaks the mu = 0.3 growth rate into the work of
# each term of the equations (`tefcore.linear.mechanism`, as in notebook 04).

# %%
with nt.counted_warnings("numerical warnings"):
    comp = compare_models(base, onset=onset)
print("headline results (growth: real part of the flutter root, 1/rev; paper onset 0.26):")
print(nt.clean(comp.headlines.round(4)).to_string(index=False))
print()
print("the flutter root at the imbalanced baseline:")
print(nt.clean(comp.roots.round(3)).to_string(index=False))

# %%
print("growth rate of the flutter root at mu = 0.3, term by term [1/rev]:")
mech = comp.mechanism.copy()
mech = mech[mech.abs().max(axis=1) >= 0.005]      # terms that do at least 0.005 /rev
print(nt.clean(mech.round(3)).to_string())

# %% [markdown]
# **What the states change.** The shed wake takes a third or more off the
# growth rate in hover and about a fifth at mu = 0.3, through the flap's lift
# on the blade: with the wake, the flap's circulatory lift is smaller and lags
# the flap's motion, so it feeds less energy into the blade mode it drives (the
# row "shed wake on blade airloads" is the work of the lift deficiency 1 - C
# itself). The onset of Fig. 9 barely moves: where the flutter root turns
# unstable is set by when the flap's frequency meets the blade's modes, which
# the wake hardly shifts. Dynamic inflow changes little at the flap's
# frequencies -- the induced flow cannot follow a 10/rev motion -- but it does
# change the low blade modes (notebook 01's lag damping; see docs/theory.md
# 6.2 for how far a single reference blade can represent the inflow states).
# The flutter stays far more violent than the paper's curves: the assumed flap
# inertia (notebook 08) weighs more than the unsteadiness.

# %% [markdown]
# ## Fig. 9 with and without the shed wake
#
# The TEF branch and the flutter root along the CG offset, quasi-steady and
# unsteady, on the same axes, at the sweep's points only (`refine = False`):
# with the shed wake a root's name is its participation label (the wake's
# near-repeated families leave no continuation in the coupling to follow,
# `tefcore.modes.continuation`), so bisecting where a name changes would
# locate a change of label, not an exceptional point. Notebook 04 locates
# those of the quasi-steady Fig. 9.

# %%
vals = nt.figure_values("fig9", n_points)
runs = {}
for name in ("quasi-steady", "unsteady"):
    cfg_fig9 = nt.run_config("fig9", base, OPTIONS[name])   # Fig. 9's caption, this model
    with nt.counted_warnings(f"{name}: numerical warnings"):
        runs[name] = tefcore.sweep(cfg_fig9, "flap.cg_offset", vals, point=nt.quiet_stability,
                                   n_jobs=n_jobs, progress=False, refine=refine)
    nt.report_sweep("fig9", runs[name])
    fr = runs[name].table
    fr = fr[(fr["status"] == "ok") & fr["flutter_root"].fillna(False).astype(bool)
            & (fr["refinement"] == 0)]
    print(f"  {name}: flutter root growth at c_cg/c_f = "
          + ", ".join(f"{x:.2f}: {g:+.2f}" for x, g in zip(nt.x_values("fig9", fr),
                                                           fr["real_part"], strict=True)))

# %%
fig, ax = plt.subplots(figsize=(8, 4.8))
styles = {"quasi-steady": "-", "unsteady": "--"}
for name, res in runs.items():
    t = res.table
    nt.plot_modes(ax, "fig9", t, labels=("TEF", "blade torsion 1"), label_suffix=f" ({name})",
                  style={"TEF": ("C3", "o", styles[name]),
                         "blade torsion 1": ("C1", "D", styles[name])}, flutter=False)
    fr = t[(t["status"] == "ok") & t["flutter_root"].fillna(False).astype(bool)
           & (t["refinement"] == 0)]
    ax.plot(nt.x_values("fig9", fr), -fr["real_part"], "k" + {"quasi-steady": "o",
            "unsteady": "s"}[name], ms=4, mfc="none" if name == "unsteady" else "k",
            label=f"flutter root ({name})")
cfg9 = nt.run_config("fig9", base)
title = nt.figure_title("fig9", cfg9, width=90).replace("quasi-steady thin-airfoil",
                                                          "thin-airfoil")
ax.set_title(title + "\nquasi-steady (solid) and with the shed wake (dashed)",
             fontsize="medium")
nt.legend_below(ax, ncol=2)
nt.savefig(fig, out, "fig09_unsteady",
           caption=title + ". Damping of the TEF branch and blade torsion 1, quasi-steady "
                   "(solid) and with the shed wake of the balanced flap (dashed); black "
                   "markers: the flutter root of each point (filled: quasi-steady, hollow: "
                   "unsteady).");

# %%
written = [nt.save_csv(comp.headlines, out, "headlines"),
           nt.save_csv(comp.roots, out, "flutter_roots"),
           nt.save_csv(comp.mechanism.reset_index(), out, "mechanism_mu03")]
written += [nt.save_csv(r.table, out, f"fig09_{n.replace('-', '_')}") for n, r in runs.items()]
print(sorted(p.name for p in written + sorted(out.glob("*.png"))))
