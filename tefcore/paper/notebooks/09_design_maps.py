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
# # 09 -- Design maps: where the flap flutters, over two parameters at once
#
# The paper varies one parameter at a time (Figs. 8-17). A flap designer needs
# the other view: for a pair of design parameters, which combinations are
# stable? A **stability map** answers it: over a grid of two configuration
# fields, the growth rate of the **flutter root** -- the least stable
# flap-induced root (unstable, or much less stable, with the flap held than
# free), whichever mode it comes from -- as a colour map (red: growing, unstable; blue: decaying), with the
# **flutter boundary** where it crosses zero: the black contour, and black dots
# where tefcore located the zero between grid points (Brent's method on the
# growth rate along each row).
#
# Two maps here:
#
# 1. **Mass balance against aerodynamic balance, in hover**: flap CG offset
#    c_cg/c_f against overhang c_b/c_f -- the two parameters of Figs. 8 and 9
#    together.
# 2. **Actuator stiffness against forward speed**, for the paper's
#    mass-imbalanced flap (c_cg/c_f = 0.33, c_b/c_f = 0.29) -- Figs. 12 and 17
#    together.
#
# Each map is `tefcore.sweeps.maps.stability_map` (the command line has it as
# `tefcore map`); every row is a resumable sweep, and the points run in
# parallel on local processes or, with a `dask.distributed` client, on a
# cluster: `stability_map(..., client=distributed.Client("tcp://scheduler:8786"))`.

# %% tags=["parameters"]
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "output/09_design_maps"
n_jobs = 1                 # processes for the map's points (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
config = None              # base configuration: a TOML file (a complete rotor, e.g. an edited
                           # copy of tefcore/data/mdart.toml); None: the shipped MDART
overrides = {}             # dotted configuration fields applied to both maps
n_points = None            # None: the grids below; int: that many values on every axis
n_cg, n_overhang = 9, 7    # grid of map 1 (flap CG offset x overhang)
n_actuator, n_mu = 8, 4    # grid of map 2 (actuator stiffness x advance ratio)
scheduler = None           # a dask.distributed scheduler address, e.g. "tcp://10.0.0.5:8786"

# %% tags=["nbval-ignore-output"]
# %matplotlib inline
import textwrap
import warnings

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from tefcore.paper import notebook_tools as nt
from tefcore.sweeps.maps import stability_map

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model, overrides, config=config)
if n_points is not None:
    n_cg = n_overhang = n_actuator = n_mu = int(n_points)
client = None
if scheduler:
    from distributed import Client

    client = Client(scheduler)


def run_map(cfg, x_field, xs, y_field, ys):
    """The map, with the solver's numerical warnings counted, not printed."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        m = stability_map(cfg, x_field, xs, y_field, ys, n_jobs=n_jobs, client=client,
                          progress=False)
    failed = m.table[m.table["status"] != "ok"]
    print(f"{len(m.table)} points, {len(failed)} without a result, "
          f"{len(m.boundary)} boundary points located, {len(caught)} numerical warnings")
    # the reasons, with their numbers left out so that alike failures count together
    reasons = failed["error"].str.replace(r"-?\d+(\.\d+)?(e-?\d+)?", "#", regex=True)
    for text, n in reasons.str.slice(0, 110).value_counts().sort_index().items():
        print(f"  {n} x {text}")
    return m


def growth_grid(m, x_name, y_name, x_scale=1.0, digits=2):
    """The flutter growth as an x-by-y table, rounded (paper units)."""
    g = m.table.pivot_table(index="y", columns="x", values="flutter_growth", dropna=False)
    g.index = np.round(g.index.to_numpy(float), 3)
    g.columns = np.round(g.columns.to_numpy(float) * x_scale, 3)
    g.index.name, g.columns.name = y_name, x_name
    return nt.clean(g.round(digits))


# %% [markdown]
# ## Map 1: flap CG offset against overhang, in hover
#
# Moving the flap's CG aft of its hinge couples the flap inertially to the
# blade's bending and torsion (notebook 04); moving the hinge aft (a longer
# overhang, the balanced flap's nose) shrinks the aerodynamic spring that
# holds the flap at zero deflection (notebook 03). Both lower the frequency of
# the flap's own mode (about 24/rev for a balanced, un-overhung flap) towards
# the blade's second torsion and fifth flap modes near 11-13/rev, and both
# strengthen the coupling that lets the flap and the blade exchange energy.

# %%
cfg1 = base.with_overrides({"flight.advance_ratio": 0.0})
xs1 = list(np.round(np.linspace(0.0, 0.4, n_cg), 4))
ys1 = list(np.round(np.linspace(0.0, 0.6, n_overhang), 4))
map1 = run_map(cfg1, "flap.cg_offset", xs1, "flap.overhang", ys1)

# %%
print("flutter root growth Re(s)/Omega [1/rev] (> 0: unstable; NaN: no result):")
print(growth_grid(map1, "c_cg/c_f", "c_b/c_f").to_string())
print()
print("flutter boundary: the least CG offset that flutters, at each overhang")
b1 = map1.boundary[["y", "x", "direction"]].rename(
    columns={"y": "c_b/c_f", "x": "c_cg/c_f at the boundary"})
print(nt.clean(b1.round(3)).to_string(index=False))

# %%
fig, ax = plt.subplots(figsize=(7.5, 5.0))
map1.plot(ax, x_label="flap CG offset c_cg/c_f (positive aft)",
          y_label="flap overhang c_b/c_f")
title1 = "Design map: flap CG offset and overhang (" + nt.conditions(
    cfg1, exclude=("flap.cg_offset", "flap.overhang")) + ")"
ax.set_title("\n".join(textwrap.wrap(title1, 80)), fontsize="medium")
nt.savefig(fig, out, "map_cg_overhang",
           caption=title1 + ". Colour: growth rate of the flutter root (the least stable "
                   "flap-induced root; red unstable). Black line: "
                   "the zero contour of the grid; black dots: the boundary located between "
                   "grid points. Blank cells: configurations without a result (see the "
                   "notebook).");

# %% [markdown]
# **Reading the map.** The boundary runs from c_cg/c_f of about 0.31 with no
# overhang down to almost zero at c_b/c_f = 0.4: **aerodynamic balance costs
# mass balance**. An overhung flap needs its CG further forward -- a nose
# balance weight -- to stay stable, because its own aerodynamic spring, which
# keeps its frequency away from the blade's, is weaker. Reading the row
# c_b/c_f = 0.3 gives the onset of Fig. 9's kind (the paper: 0.26 at 0.29
# overhang, mu = 0.3); reading the column c_cg/c_f = 0 gives Fig. 8 (the paper:
# the mass-balanced flap becomes unstable beyond 50 % overhang). The flutter
# root changes identity across the map -- the flap's own mode at small
# offsets, a torsion- or bending-dominated root that the flap drives at large
# ones -- which is why the map follows the flutter root and not one labelled
# mode. Blank cells have no result: there the flap **diverges statically** --
# the trim finds a mean flap deflection beyond 10 deg, because with the hinge
# far enough aft the aerodynamic moment about it grows with deflection faster
# than the actuator's spring can hold it (the over-balance the paper warns of
# in Figs. 7-8), and there is no trimmed state to linearise about.

# %% [markdown]
# ## Map 2: actuator stiffness against advance ratio, mass-imbalanced flap
#
# The actuator is the flap's spring. A stiffer actuator raises the flap's
# frequency; for the mass-imbalanced flap that moves it away from the blade
# modes it couples with, and the energy exchange weakens. Forward flight
# raises the dynamic pressure on the advancing side and with it the
# aerodynamic coupling.

# %%
k0 = 81.52                  # the baseline actuator stiffness [ft-lb/rad] (Table 1)
factors = list(np.round(np.geomspace(0.5, 12.0, n_actuator), 3))
cfg2 = base.with_overrides({"flap.cg_offset": 0.33, "flap.overhang": 0.29})
xs2 = [f"{k0 * f:.4f} ft-lbf/rad" for f in factors]
ys2 = list(np.round(np.linspace(0.0, 0.3, n_mu), 4))
map2 = run_map(cfg2, "actuator.stiffness", xs2, "flight.advance_ratio", ys2)

# %%
k0_si = 110.52627904                # 81.52 ft-lbf/rad in N m/rad
print("flutter root growth Re(s)/Omega [1/rev]; columns: actuator stiffness / 81.52 ft-lb/rad")
print(growth_grid(map2, "k_a / baseline", "mu", x_scale=1 / k0_si).to_string())
print()
print("flutter boundary: the actuator stiffness above which the flap is stable")
b2 = map2.boundary.assign(factor=map2.boundary["x"] / k0_si)[["y", "factor", "direction"]]
b2 = b2.rename(columns={"y": "mu", "factor": "k_a / baseline at the boundary"})
print(nt.clean(b2.round(3)).to_string(index=False))

# %%
fig, ax = plt.subplots(figsize=(7.5, 5.0))
map2.plot(ax, x_unit="ft-lbf/rad", x_label="actuator stiffness k_a [ft-lb/rad]",
          y_label="advance ratio μ")
ax.set_xscale("log")
title2 = "Design map: actuator stiffness and advance ratio (" + nt.conditions(
    cfg2, exclude=("actuator.stiffness", "flight.advance_ratio")) + ")"
ax.set_title("\n".join(textwrap.wrap(title2, 80)), fontsize="medium")
nt.savefig(fig, out, "map_actuator_mu",
           caption=title2 + ". Colour: growth rate of the flutter root (red unstable); "
                   "black line and dots: the flutter boundary. Logarithmic stiffness axis.");

# %% [markdown]
# **Reading the map.** With the paper's imbalanced flap (c_cg/c_f = 0.33),
# tefcore's flap flutters at the baseline actuator stiffness at every speed and
# becomes stable only when the actuator is about 3.6 times stiffer in hover and
# 5 times at mu = 0.3: forward speed moves the boundary towards stiffer
# actuators, as the paper's Figs. 12 and 17 say in their own terms.
# The paper finds the flap stable above 1.5 times the baseline at mu = 0.3;
# tefcore needs far more. The growth rates of the flutter root here are large
# (several /rev), larger than the paper's curves suggest -- the assumed flap
# inertia and the quasi-steady aerodynamics (no lift deficiency at the flap's
# reduced frequency, notebook 04) are the first suspects (notebook 08 shows
# what each assumption does). The map is a design tool for this model; with
# your own blade and flap data (`overrides`, or a configuration file) it is
# one for your rotor.

# %%
written = [nt.save_csv(map1.table, out, "map_cg_overhang"),
           nt.save_csv(map1.boundary, out, "map_cg_overhang_boundary"),
           nt.save_csv(map2.table, out, "map_actuator_mu"),
           nt.save_csv(map2.boundary, out, "map_actuator_mu_boundary")]
print(sorted(p.name for p in written + sorted(out.glob("*.png"))))
