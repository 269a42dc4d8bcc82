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
# # 03 -- Aerodynamic balance: flap overhang (Figs. 7-8)
#
# A plain flap hinged at its nose needs a large actuator moment: all the flap's
# lift acts aft of the hinge. Moving the hinge aft into the flap -- a **nose
# overhang** c_b (Figure 2 of the paper) -- puts part of the flap's area ahead
# of the hinge, so its pressure partly balances the rest: the **aerodynamic
# hinge moment shrinks**, and with it the actuation power. The MD900 flap has
# its hinge 10 % chord behind the flap nose: c_b/c_f = 0.29.
#
# The price: the hinge moment's *stiffness* (how much it pushes the flap back
# when it deflects) also shrinks, changes sign when the hinge passes the
# flap's aerodynamic centre, and then the aerodynamic moment *helps* the flap
# deflect further -- the flap becomes **aerodynamically over-balanced**. The
# actuator spring must then carry the flap alone against a negative aerodynamic
# spring, and beyond some overhang the flap mode diverges.
#
# In this notebook the flap is **mass-balanced** (c_cg/c_f = 0): flap and blade
# couple only through aerodynamics.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/03_overhang"
n_jobs = 1                 # processes for the stability sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied over each figure's caption,
                           # e.g. {"flight.ct_sigma": 0.08, "flight.advance_ratio": 0.2}
n_points = None            # None: the paper's sweep values; int: that many, evenly, same range
values = {}                # explicit sweep values per figure, e.g. {"fig8": [0.0, 0.25, 0.5]}
damping_measure = "decay_rate"  # "decay_rate" (-Re(s)/Omega) or "damping_ratio" (%)
fig7_overhangs = [0.0, 0.1, 0.2, 0.29, 0.35, 0.4, 0.45, 0.5]  # Fig. 7 overhangs c_b/c_f

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
# ## Figure 7: actuation power and flap response versus overhang
#
# Same conditions as Fig. 6 (mu = 0.2, C_T/sigma = 0.0774, delta_a = 2 deg
# cos(4 psi - 240 deg)). The power is the actuator torque times the actuator
# rate; we show its peak over a revolution and the mean of its magnitude.

# %%
from tefcore.paper.figures import overhang_actuation_figure, response_config

with nt.counted_warnings("warnings (e.g. table inputs clipped to its edges)"):
    fig7 = overhang_actuation_figure(base, overhangs=tuple(fig7_overhangs), **overrides)
results["fig7"] = fig7
fig7 = fig7.assign(peak_power_rel=fig7["peak_power"] / fig7["peak_power"].iloc[0],
                   mean_power_rel=fig7["mean_power"] / fig7["mean_power"].iloc[0])
print(nt.clean(fig7.round(3)).to_string(index=False))

# %%
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.2))
ax_a.plot(fig7["overhang"], fig7["peak_power"], "o-", color="C3", label="peak power")
ax_a.plot(fig7["overhang"], fig7["mean_power"], "s--", color="C0", label="mean |power|")
ax_a.set_xlabel("flap overhang c_b/c_f")
ax_a.set_ylabel("actuation power [W]")
ax_a.set_title("(a) actuation requirement", fontsize="medium")
ax_a.legend()
ax_b.plot(fig7["overhang"], fig7["half_peak_to_peak_deg"], "o-", color="C3", label="flap response")
ax_b.axhline(2.0, color="0.4", ls="--", lw=1, label="actuator input (2 deg)")
ax_b.set_xlabel("flap overhang c_b/c_f")
ax_b.set_ylabel("half peak-to-peak flap deflection [deg]")
ax_b.set_title("(b) trailing-edge flap response", fontsize="medium")
ax_b.legend()
for ax, name in ((ax_a, "fig7a"), (ax_b, "fig7b")):
    ref = nt.reference_curves(name)
    if ref is not None:
        ax.plot(ref["x"], ref["y"], "kx", label="paper")
cfg7 = response_config(base, **overrides)
fig.suptitle(nt.figure_title("fig7", cfg7, width=110), fontsize="medium")
nt.savefig(fig, out, "fig07", figure="fig7",
           caption=nt.figure_caption("fig7", cfg7, "(a) peak and mean actuation power; (b) half "
                                     "peak-to-peak flap response against the 2 deg input",
                                     markers=False));

# %% [markdown]
# **Paper:** the actuation power drops by 60 % at c_b/c_f = 0.29 compared with
# no overhang; the half peak-to-peak response grows with overhang, "more
# dramatically above 40 % flap chord" -- the softening negative aerodynamic
# spring brings the flap's natural frequency down towards the 4/rev input.
# Beyond the point where the power starts to rise again the actuator is
# driving a nearly resonant flap.
#
# ## Figure 8: stability versus overhang, in hover
#
# What to look for (paper): the **TEF mode damping decreases** with overhang and
# the mode becomes **unstable above about 50 % flap chord** (over-balance, the
# flap mode diverges). Because the flap is mass-balanced, it couples to the
# blade only aerodynamically: a flap-down deflection adds lift, so the flap
# motion is **in phase with blade flap bending** -- blade flap damping
# *decreases* with overhang; it produces a nose-down pitching moment, so it is
# **out of phase with blade torsion** -- torsion damping *increases*. Lag
# damping stays about constant.

# %%
vals_fig8 = nt.figure_values("fig8", n_points, values.get("fig8"))
cfg_fig8 = nt.run_config("fig8", base, overrides)
res_fig8 = tefcore.sweep(cfg_fig8, "flap.overhang", vals_fig8,
                         point=nt.quiet_stability, n_jobs=n_jobs, progress=False)
results["fig8"] = res_fig8
nt.report_sweep("fig8", res_fig8)

# %%
nt.damping_figure("fig8", res_fig8, cfg_fig8, out, measure=damping_measure)

# %% [markdown]
# ### Which root is which
#
# A root's name is where it comes from. Switch the blade-flap coupling off
# (every mass, damping and stiffness term between the blade and the flap
# scaled by a factor eps = 0): the blade with its flap held has its own modes,
# named by their structure (blade flap 1, blade torsion 1, ...), and the flap
# on its actuator spring has its own mode, "TEF". Turn the coupling back on
# step by step (eps from 0 to 1) and follow every root: each root of the real
# rotor is named by the uncoupled mode it continues from
# (`tefcore.modes.continuation`). "The TEF mode" is the root the flap's own
# mode becomes, at every point on its own -- no sweep order or participation
# share enters. Its character can change along a sweep: where the flap's
# frequency passes a blade mode, the name moves across the pair's veering gap
# with it.
#
# The *flutter root* of a point is its least stable **flap-induced** root: one
# that freeing the flap makes unstable (or much less stable) than it is with
# the flap held. The legends say where it comes from, e.g. "flutter root (from
# blade torsion 2)". Which root carries a name has no answer only at an
# *exceptional point*, where two roots coalesce in the plane of the swept
# parameter and the coupling; tefcore locates them (listed below) and a claim
# whose verdict depends on one is left without a verdict (its reason says what
# the same check gives on the flutter root, which every point decides).

# %%
nt.which_root("fig8", res_fig8, cfg_fig8, out)

# %%
nt.damping_summary("fig8", res_fig8, measure=damping_measure)

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
# For the over-balanced flap the paper's explanation is that "the flap becomes
# aerodynamically over-balanced ... and the flap mode diverges": a divergence
# would be a *real* root crossing zero, driven by the flap's own hinge moment
# (C_h_delta, a negative spring beyond the balance point). Here is the TEF
# branch at an overhang of 0.6, term by term:

# %%
print(nt.explain("fig8", res_fig8, 0.6, base, overrides).to_string(index=False))

# %% [markdown]
# **What the paper concludes** (conclusion 1): aerodynamic balance is the key to
# small actuation requirements, but excessive overhang may lead to
# blade/trailing-edge-flap instability. The design sits at 0.29, where the
# power is already much reduced and the flap mode is still well damped.

# %% [markdown]
# ## Validation: the paper's claims for these figures
#
# Each row is one statement of the paper, checked against the computed
# results by `tefcore.paper.claims.validation` (`pass`, `fail`, or `not reproducible` when
# the statement needs data we do not have). The full table, with the
# statement, the expected and computed values and the reason, is saved to
# `claims.csv`.
#
# The results of this notebook are in `output_dir`: the tidy sweep tables
# (`*_modes.csv`: one row per point and tracked mode, with the trim), the
# figures (`*.png`) and the claims table (`claims.csv`), which
# `tefcore reproduce` collects into its report.

# %%
claims = nt.check_and_save(out, results, cfg=claims_cfg, variants=variants, tables={
    "fig07_actuation": fig7,
    "fig08_modes": res_fig8.table,
})

# %% [markdown]
# ## Where the compact model departs from UMARC, and what that may shift
#
# One text for all notebooks (`tefcore/paper/attribution/departures.toml`): what holds for every
# figure, then what matters most for this notebook's.

# %%
nt.show_departures("fig7", "fig8")

# %%
for name in ["fig8"]:
    nt.unsteadiness(name, results[name], base)
