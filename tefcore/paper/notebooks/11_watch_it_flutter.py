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
# # 11 -- Watch it flutter: the Floquet growth in the time domain
#
# The stability table says the paper's mass-imbalanced flap (c_cg/c_f = 0.33,
# overhang 0.29 c_f, mu = 0.3) has a root at **+3 /rev**. What does that mean
# for the blade? A real part sigma per radian of azimuth means the motion grows
# by e^(2 pi sigma) each revolution -- here about 10^8. Nothing in the Floquet
# analysis *shows* that: it is an eigenvalue of the monodromy matrix.
#
# Here we do what a wind-tunnel engineer would: give the blade a small nudge
# and watch. `tefcore.simulate` integrates the same linearised periodic
# equations M(psi) q'' + C q' + K q = 0 that the Floquet analysis uses, with
# `scipy.integrate.solve_ivp`, from a small perturbation of the trim (the
# root's own periodic shape), and fits the growth to the response: least
# squares on the logarithm of the largest flap deflection in each whole
# revolution (docs/theory.md section 12). Two flaps side by side:
#
# * the **mass-balanced** flap (CG on the hinge): the root decays;
# * the paper's **imbalanced** flap (CG 0.33 c_f behind the hinge): the same
#   root -- blade torsion 2, the least stable flap-induced root -- grows.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and GIF results, relative to the working directory
output_dir = "output/11_watch_it_flutter"
n_jobs = 1                 # unused here (no sweeps); kept for the common parameters
n_points = 0               # unused here (no sweeps); kept for the common parameters
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file; None: the shipped MDART
overrides = {}             # dotted configuration fields applied to both flaps
revs = 4                   # revolutions marched for the growth fit
animate = True             # draw the animations (the slowest cells)

# %% tags=["nbval-ignore-output"]
# %matplotlib inline
import base64
import warnings

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from IPython.display import HTML

import tefcore
from tefcore.paper import notebook_tools as nt
from tefcore.timedomain.animation import gif_bytes

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, overrides, config=config)
flaps = {"mass-balanced": base.with_overrides({"flight.advance_ratio": 0.3,
                                               "flap.overhang": 0.29, "flap.cg_offset": 0.0}),
         "imbalanced": base.with_overrides({"flight.advance_ratio": 0.3,
                                            "flap.overhang": 0.29, "flap.cg_offset": 0.33})}
if overrides:
    flaps = {k: c.with_overrides(overrides) for k, c in flaps.items()}

# %% [markdown]
# ## The same root, two flaps: marched growth against Floquet
#
# `mode="flutter"` starts each march from the least stable flap-induced root
# (the root the imbalanced flap makes flutter). The perturbation is a
# thousandth of a chord; the equations are linear, so its size does not
# matter here.

# %%
sims = {name: tefcore.simulate(cfg, mode="flutter", revs=revs) for name, cfg in flaps.items()}
rows = []
for name, sim in sims.items():
    s = sim.summary
    rows.append({"flap": name, "root": s["mode"],
                 "Floquet [/rev]": round(s["growth_floquet_per_rev"], 3),
                 "marched [/rev]": round(s["growth_time_domain_per_rev"], 3),
                 "agrees (2 % + 0.01)": s["agrees"],
                 "growth per revolution": f"x{s['growth_factor_per_revolution']:.2g}"})
print(pd.DataFrame(rows).to_string(index=False))

# %% [markdown]
# The marched growth is the Floquet real part to a few thousandths: the
# eigenvalue is the motion. Per revolution the imbalanced flap's motion grows
# a hundred million times; the balanced flap's decays to a tenth.
#
# ## The motion itself
#
# Left: the flap deflection on a log scale with the Floquet slope; right: the
# first revolution of the flap deflection and of the twist at the flap's
# midspan, each divided by its largest value (their phase is the mechanism:
# the flap lags the twist).

# %%
fig, axs = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
for (name, sim), color in zip(sims.items(), ("C0", "C3"), strict=True):
    h, s = sim.history, sim.summary
    axs[0].semilogy(h["psi_rev"], np.abs(h["flap_deflection_deg"]), color=color, lw=0.8,
                    label=f"{name}: |flap deflection|")
    start = np.abs(h["flap_deflection_deg"]).iloc[0]
    axs[0].semilogy(h["psi_rev"], start * np.exp(2 * np.pi * s["growth_floquet_per_rev"]
                                                 * h["psi_rev"]), "k--", lw=0.8)
first = sims["imbalanced"].history.query("psi_rev <= 1")
for col, style in (("flap_deflection_deg", "C3-"), ("twist_flap_midspan_deg", "C2-")):
    axs[1].plot(first["psi_rev"], first[col] / np.abs(first[col]).max(), style,
                label=col.replace("_deg", "").replace("_", " "))
axs[0].set(xlabel="revolutions", ylabel="deg", title="flap deflection (dashed: Floquet)")
axs[1].set(xlabel="revolutions", ylabel="normalised", title="imbalanced flap, first revolution")
for ax in axs:
    ax.legend(fontsize="small")

# %% [markdown]
# ## Who does the work
#
# Along the marched motion each named term of the equations does work on the
# blade and flap; weighted by the growth, its work over a revolution divided
# by twice the energy is its share of the growth rate, and the shares add up
# to the energy's growth (docs/theory.md 12.3). Beside it, the Floquet
# decomposition of the same root (`tefcore mechanism`): the motion and the
# eigenvector tell the same story -- the flap's lift does the work that the
# blade's own airloads cannot absorb.

# %%
sim = sims["imbalanced"]
last = sim.work.iloc[-1]
terms = sorted(sim.floquet_work, key=lambda t: -abs(sim.floquet_work[t]))[:5]
table = pd.DataFrame({"term": terms,
                      "marched, last revolution [/rev]": [round(last[t], 3) for t in terms],
                      "Floquet [/rev]": [round(sim.floquet_work[t], 3) for t in terms]})
print(table.to_string(index=False))
print(f"sum of all terms {last['sum']:+.3f} /rev, energy growth "
      f"{last['energy_growth']:+.3f} /rev")

# %% [markdown]
# ## Watch it
#
# The section at the flap midspan (to scale: NACA 0012, the 35 % flap turning
# about its hinge 29 % behind its nose), a side view of the blade, the
# amplitude and the work of the terms, for two revolutions. The motion is
# normalised -- one gain for all components, so their ratios are true -- and
# the growth is slowed to a factor 4 over the clip (the title says by how
# much it really grows).

# %% tags=["nbval-ignore-output"]
def show(sim, name):
    """A short animation of a simulation as an embedded GIF."""
    short = tefcore.simulate(sim.stability.trim_result.model.cfg, mode="flutter", revs=2,
                             stability_result=sim.stability)
    data = gif_bytes(short, dpi=56, figsize=(10.0, 6.4))
    (out / f"{name}.gif").write_bytes(data)
    return HTML(f'<img src="data:image/gif;base64,{base64.b64encode(data).decode()}" '
                f'alt="{name} flap" style="max-width: 100%">')


show(sims["imbalanced"], "imbalanced") if animate else None

# %% tags=["nbval-ignore-output"]
show(sims["mass-balanced"], "mass-balanced") if animate else None

# %% [markdown]
# ## Where the linearisation holds
#
# The Floquet analysis is linear. `nonlinear=True` also marches the full
# nonlinear equations (the coupled model's residual, the one the trim solves)
# from the trim plus the same perturbation, and compares the two.

# %%
with warnings.catch_warnings():
    warnings.simplefilter("ignore", RuntimeWarning)    # large-amplitude trigonometry
    nl = tefcore.simulate(flaps["imbalanced"], mode="flutter", revs=1, amplitude=1e-6,
                          nonlinear=True, work=False)
n = nl.summary["nonlinear"]
print(f"nonlinear march reached {n['reached_rev']:.2f} rev: {n['stopped'] or 'all of it'}")
print(f"largest departure from the linear march: {n['largest_relative_departure']:.1%} "
      "of the linear amplitude")
print(f"growth over windows of {n['fit_window_rev']:g} rev: nonlinear "
      f"{n['growth_nonlinear_per_rev']:+.2f} /rev, linear {n['growth_linear_same_window']:+.2f} /rev")

# %% [markdown]
# Starting from a millionth of a chord, the flap reaches 90 degrees within
# half a revolution, and the nonlinear motion stays within a percent of the
# linear one all the way: the model's nonlinearities (the inflow angle's
# arctangent, the flap's trigonometry in its inertial couplings) are weak,
# and nothing in it -- no stall, no actuator stop, no flap limit --
# saturates the motion. There is no limit cycle to find: a real flap would
# stall or hit its stops long before. Within the model, the Floquet root is
# the whole story until the motion is far beyond what the model describes.

# %%
for name, sim in sims.items():
    nt.save_csv(sim.history, out, f"history_{name.replace('-', '_')}")
nt.save_csv(sims["imbalanced"].work, out, "work_imbalanced")
print(sorted(p.name for p in out.glob("*.csv")))
