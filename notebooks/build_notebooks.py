"""Write (and optionally execute in place) the numbered notebooks 01-08.

The notebooks are the product; this script is their source so that all eight
share one structure. Run from anywhere:

    python notebooks/build_notebooks.py            # write the .ipynb files (no outputs)
    python notebooks/build_notebooks.py --execute  # ... and execute them in place

The committed notebooks carry their executed outputs (nbval compares them),
so re-run with ``--execute`` whenever the model or a notebook changes.
Execution uses nbclient with the notebook's folder as working directory,
like nbval does.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

COMMON_PARAMS = '''\
# Parameters (papermill: `tefcore reproduce -p NAME VALUE`, `papermill -p NAME VALUE`).
# output folder for the CSV and PNG results, relative to the working directory
output_dir = "../output/{stem}"
n_jobs = 1                 # processes for the stability sweeps (joblib); 2 on 2 cores
aero_model = "thin_airfoil"  # "thin_airfoil" (quasi-steady) or "table" (C81, shipped deck)
overrides = {{}}             # dotted configuration fields applied over each figure's caption,
                           # e.g. {{"flight.ct_sigma": 0.08, "flight.advance_ratio": 0.2}}
n_points = None            # None: the paper's sweep values; int: that many, evenly, same range
values = {{}}                # explicit sweep values per figure, e.g. {{"fig8": [0.0, 0.25, 0.5]}}
damping_measure = "{measure}"  # "decay_rate" (-Re(s)/Omega) or "damping_ratio" (%)
'''

SETUP = '''\
%matplotlib inline
import matplotlib.pyplot as plt
import pandas as pd

from tefcore.paper import notebook_tools as nt

out = nt.setup_notebook(output_dir)
base = nt.base_config(aero_model)
claims_cfg = base.with_overrides(overrides) if overrides else base  # for runs validation adds
results, variants = {}, {}
'''

DEPARTURES_COMMON = '''\
## Where the compact model departs from UMARC, and what that may shift

The paper's numbers come from UMARC; tefcore is a compact re-derivation. The
differences are deliberate (the inputs UMARC used are not public) but they
are real, and a student should read every figure above with them in mind:

* **Equivalent root springs instead of multiple load paths.** UMARC models
  the MDART flexbeam, torque tube, pitch link, viscoelastic snubber and
  control kinematics as separate beams and linkages. tefcore lumps them into
  flap, lag and torsion springs (and a lag damper) at 5 % R, calibrated only
  to the torsion frequencies the text states. Frequencies can be matched
  this way; the *mode shapes* near the root and the kinematic pitch-flap and
  pitch-lag couplings of the real hub cannot. Anything that relies on those
  couplings -- lag damping, the torsion participation in flap modes -- may
  shift.
* **Linear inflow instead of the Bagai-Leishman free wake.** Uniform momentum
  inflow in hover and the Drees linear distribution in forward flight give
  the right thrust but not the tip-vortex induced velocities near the flap
  (at 74-92 % R). The local angle of attack, hence the trimmed flap
  deflection and the hinge-moment level, can differ by a few tenths of a
  degree; the stability derivatives themselves change less.
* **Quasi-steady aerodynamics.** The flap mode oscillates at several /rev,
  where the reduced frequency at the flap, k = f c / (2 x R), is a few tenths
  -- far from quasi-steady: Theodorsen's lift deficiency C(k) there has a
  magnitude near 0.7 and some 15 deg of phase lag (computed below for the
  sweeps of this notebook where there is a flap). Quasi-steady theory (C = 1)
  over-predicts the circulatory lift and damping of the flap motion and
  misses its phase lag, so the TEF damping levels, and where they cross
  zero, are the least certain numbers here. Compressibility enters only
  through a Prandtl-Glauert factor.
* **Assumed properties.** Blade mass and inertia distributions, flap mass and
  inertia, the snubber damping and the pitch-horn geometry are assumptions
  (`tefcore/data/mdart.toml` gives the source or reason for each). Inertial
  couplings scale with the assumed flap mass; thresholds in CG offset and
  actuator stiffness scale with it too.
'''

MECHANISM_NOTE = '''\
### Why: the growth rate as work done by each term

`tefcore.mechanism` writes the root's real part as an exact energy balance:
each term of the linearised equations (blade inertia and stiffness, the
blade's own airloads, the flap's lift and pitching moment on the blade, the
hinge moments, the flap's inertial couplings, the actuator ...) does some net
work on the mode per cycle; divided by twice the mode's energy, these add up
to the real part (positive: the term feeds the mode). Conservative terms --
the inertial couplings among them -- do no net work themselves: they shape
the mode so that the aerodynamic terms can. That is what the **knockouts**
show: the same root followed while one term is switched off.'''

LOCUS_NOTE = '''\
**Which root is which.** "The TEF mode" is the *TEF branch*: the root that the
flap's own mode (the flap on its actuator spring, uncoupled from the blade)
becomes when the coupling is switched on, at the start of the sweep, followed
continuously along the sweep (by eigenvalue and shape; where a step is too
coarse to tell, tefcore bisects it). Its character can change along the way
-- it can turn into a torsion-like root, while another root becomes
flap-dominated -- so the plots also show the *flutter root* at each point
(the least stable root in which the flap participates by at least 10 %) and
the participation of flap, torsion, bending and lag in the TEF branch. Two
roots approaching in frequency while one turns towards the unstable side is
the classic picture of coalescence flutter.'''

SAVE_NOTE = '''\
The results of this notebook are in `output_dir`: the tidy sweep tables
(`*_modes.csv`: one row per point and tracked mode, with the trim), the
figures (`*.png`) and the claims table (`claims.csv`), which
`tefcore reproduce` collects into its report.
'''


def pystr(text, indent, width=96):
    """A string literal wrapped as implicit concatenation, lines <= width."""
    import textwrap

    room = max(20, width - indent - 2)
    parts = textwrap.wrap(text, room, drop_whitespace=False) or [""]
    sep = "\n" + " " * indent
    return sep.join(f'"{p}"' for p in parts)


def md(text):
    return ("markdown", text.strip("\n"), ())


def code(text, *tags):
    return ("code", text.strip("\n"), tuple(tags))


def params_cell(stem, measure="decay_rate", extra=""):
    return code(COMMON_PARAMS.format(stem=stem, measure=measure) + extra, "parameters")


def locus_cells(fig, var, stem_png, lab=""):
    """Root locus and TEF participation along the sweep, and how modes were identified."""
    return [code(f'''\
nt.report_identity("{fig}", {var})
fig, (ax_l, ax_p) = plt.subplots(1, 2, figsize=(11, 4.2))
nt.plot_root_locus(ax_l, "{fig}", {var}.table{lab})
ax_l.set_title("root locus (square: start, arrows: increasing x)", fontsize="medium")
ax_l.legend(fontsize="x-small")
nt.plot_participation(ax_p, "{fig}", {var}.table)
ax_p.set_title("participation in the TEF branch", fontsize="medium")
ax_p.legend(fontsize="x-small", loc="upper right")
nt.savefig(fig, out, "{stem_png}_locus");
''')]


def stability_block(fig, stem_png, title, *, labels=None, panels=("damping",),
                    var=None, natural=False, freq_labels=None, locus=True):
    """Compute, plot, tabulate one stability figure (natural: panel (a) shows the
    blade natural frequencies)."""
    var = var or f"res_{fig}"
    setup = []
    lab = flab = ""
    if labels is not None:
        setup.append(f"modes_{fig} = {tuple(labels)!r}".replace("'", '"'))
        lab = flab = f", labels=modes_{fig}"
    if natural:
        setup.append('blade_modes_a = ("blade flap 1", "blade lag 1", "blade torsion 1")')
        flab = ", labels=blade_modes_a"
    elif freq_labels is not None:
        flab = f", labels={tuple(freq_labels)!r}".replace("'", '"')
    nat = (f'\nnat_{fig} = nt.natural_frequencies("{fig}", vals_{fig}, base, overrides)'
           if natural else "")
    nat_kw = f",\n              natural=nat_{fig}" if natural else ""
    pre = "".join(line + "\n" for line in setup)
    cells = [code(f'''\
{pre}vals_{fig} = nt.figure_values("{fig}", n_points, values.get("{fig}"))
{var} = nt.run_stability_figure("{fig}", base, overrides, vals_{fig}, n_jobs){nat}
results["{fig}"] = {var}
nt.report_sweep("{fig}", {var})
''')]
    if panels == ("damping",):
        cells.append(code(f'''\
fig, ax = plt.subplots(figsize=(6.4, 4.4))
nt.plot_modes(ax, "{fig}", {var}.table, measure=damping_measure{lab},
              reference=nt.reference_curves("{fig}"))
ax.set_title({pystr(title, 13)},
             fontsize="medium")
ax.legend()
nt.savefig(fig, out, "{stem_png}");
'''))
    else:
        cells.append(code(f'''\
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "{fig}", {var}.table, quantity="frequency"{flab}{nat_kw})
ax_a.set_title("(a) {panels[0]}", fontsize="medium")
ax_a.legend()
nt.plot_modes(ax_b, "{fig}", {var}.table, measure=damping_measure{lab},
              reference=nt.reference_curves("{fig}"))
ax_b.set_title("(b) blade and TEF damping", fontsize="medium")
ax_b.legend()
fig.suptitle({pystr(title, 13)},
             fontsize="medium")
nt.savefig(fig, out, "{stem_png}");
'''))
    if locus:
        cells.append(md(LOCUS_NOTE))
        cells.extend(locus_cells(fig, var, stem_png, lab))
    cells.append(code(f'''\
print("damping (" + damping_measure + ") of the tracked modes "
      "(NaN: that track is absent at this x, e.g. after a locked pair unlocks):")
summary = nt.mode_summary("{fig}", {var}.table, measure=damping_measure{lab})
print(summary.to_string())
changes = nt.sign_changes("{fig}", {var}.table, measure=damping_measure)
print("TEF damping changes sign at:", changes or "nowhere in the range")
'''))
    return cells


def claims_cells(figs, saved):
    figs_list = ", ".join(f'"{f}"' for f in figs)
    saves = "\n".join(f'written.append(nt.save_csv({expr}, out, "{name}"))'
                      for name, expr in saved)
    return [
        md('''\
## Validation: the paper's claims for these figures

Each row is one statement of the paper, checked against the computed
results by `tefcore.paper.validation` (`pass`, `fail`, or `not reproducible` when
the statement needs data we do not have). The full table, with the
statement, the expected and computed values and the reason, is saved to
`claims.csv`.'''),
        code(f'''\
claims = pd.concat([nt.claims_table(name, results[name], cfg=claims_cfg, others=results,
                                   variants=variants.get(name))
                    for name in [{figs_list}]], ignore_index=True)
nt.show_claims(claims)
'''),
        md(SAVE_NOTE),
        code(f'''\
written = [nt.save_csv(claims, out, "claims")]
{saves}
print(sorted(p.name for p in written + sorted(out.glob("*.png"))))
'''),
    ]


# ----------------------------------------------------------------- notebooks


def nb01():
    stem = "01_baseline_mdart_correlation"
    return stem, [
        md('''\
# 01 -- Baseline MDART rotor: blade modes and lag stability (Figs. 3-4)

Before adding a trailing-edge flap (TEF), the paper checks that its analysis
predicts the stability of the bare rotor: the **McDonnell-Douglas Advanced
Rotor Technology (MDART)** rotor, a five-bladed *bearingless* rotor (a
pre-production MD900), tested in the NASA Ames 40- by 80-foot wind tunnel in
1994. Figure 3 shows the lag damping ratio against collective pitch in
hover, Figure 4 at advance ratio 0.25 with the shaft tilted 7.3 deg forward.
The paper reports that UMARC "agrees well" with the test data in hover and
"fairly well" in forward flight.

**No MDART test data is available to us.** The wind-tunnel measurements
(the paper's Ref. 20) are not published in a form we can obtain, and we do
not digitise them from the paper's plots. This notebook therefore shows
tefcore's *prediction* of lag damping versus collective, without a
correlation, and says so on every plot.

What couples to what: the first lag mode of a soft-inplane rotor sits below
1/rev (about 0.6/rev here). Lag motion produces almost no aerodynamic damping
(only drag and induced-drag changes), so the lag damping comes from the
flexbeam/snubber structural damping plus **flap-lag coupling**: Coriolis
forces from flapping and the tilt of the lift vector with inflow. Both grow
with thrust, which is why lag damping is plotted against collective pitch.'''),
        params_cell(stem, measure="damping_ratio"),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## The blade: coupled modes, fan plot and the stated frequencies

The MDART property tables are not public; `tefcore/data/mdart.toml` assumes
them (each value with its source) and calibrates the torsion stiffness, the
pitch-horn arm and the baseline pitch-link stiffness to the four first-torsion
frequencies the text states (Figs. 10a and 11a). The flap and lag
frequencies are typical bearingless values, not stated by the paper.'''),
        code('''\
import numpy as np

from tefcore.blade import blade_modes, fan_plot
from tefcore.paper.calibration import frequency_checks

modes = blade_modes(base).table()
modes["frequency_hz"] = modes["frequency_per_rev"] * base.rotor.rotor_speed / (2 * np.pi)
cols = ["mode", "label", "frequency_per_rev", "frequency_hz", "flap_fraction", "lag_fraction",
        "torsion_fraction"]
print("coupled blade modes at 392 RPM, zero collective (fractions: share of kinetic energy)")
print(nt.clean(modes[cols].round(3)).to_string(index=False))
'''),
        code('''\
ax = fan_plot(base)
ax.set_title("MDART blade (assumed properties): coupled modes vs rotor speed", fontsize="medium")
nt.savefig(ax.figure, out, "blade_fanplot");
'''),
        code('''\
checks = frequency_checks(base)
print(nt.clean(checks.drop(columns="source").round(3)).to_string(index=False))
print("largest error against the stated frequencies: "
      f"{checks['error_percent'].abs().max():.2f} %")
'''),
        md('''\
The fan plot shows how each frequency grows with rotor speed as centrifugal
stiffening adds to the elastic stiffness; the grey rays are 1/rev, 2/rev,
... Crossings of a ray at the operating speed (vertical line) would mean
resonance with the periodic airloads. The table above is the check of the
assumed structure: first torsion at 2.3/rev and 4.2/rev for pitch-link
stiffnesses of 158 and 800 lb/in, and 2.96/rev and 3.18/rev at 0.75 and 2.0
times the baseline GJ.

## Figure 3: lag damping versus collective in hover

The rotor here has **no** trailing-edge flap (`model.tef = none`), as in
the paper's correlation.'''),
        *stability_block_lag("fig3", "fig03", "Fig. 3: blade in-plane (lag) stability in hover, "
                             "no TEF -- prediction only, no test data"),
        md('''\
## Figure 4: lag damping versus collective at mu = 0.25

Same rotor in forward flight, shaft tilted 7.3 deg forward (a steady level
flight attitude). In forward flight the equations have periodic
coefficients and the Floquet method gives the damping.'''),
        *stability_block_lag("fig4", "fig04", "Fig. 4: blade in-plane stability, mu = 0.25, "
                             "7.3 deg forward shaft tilt -- prediction only"),
        md('''\
**What the paper concludes:** UMARC's lag damping agrees well with the MDART
hover data and fairly well at mu = 0.25, which gives confidence in the
baseline analysis before the flap is added. **What we can say:** only the
trend of the prediction. The level at zero collective is set mostly by the
assumed snubber damper (`hub.lag_damper`, a placeholder chosen for about 2 %
critical damping), so it is an input, not a result; the change with collective
comes from the flap-lag coupling of the model.'''),
        *claims_cells(["fig3", "fig4"], [("fig03_modes", 'res_fig3.table'),
                                          ("fig04_modes", 'res_fig4.table'),
                                          ("blade_modes", 'modes'),
                                          ("blade_frequency_checks", 'checks')]),
        md(DEPARTURES_COMMON + '''
For Figs. 3-4 in particular: the lag damping of a bearingless rotor is
dominated by the snubber and by the pitch-lag coupling of the flexbeam and
torque tube -- exactly what the equivalent root springs leave out. A real
correlation would need the MDART hub properties and the test data.'''),
    ]


def stability_block_lag(fig, png, title):
    var = f"res_{fig}"
    return [
        code(f'''\
{var} = nt.run_stability_figure("{fig}", base, overrides,
                                nt.figure_values("{fig}", n_points, values.get("{fig}")), n_jobs)
results["{fig}"] = {var}
nt.report_sweep("{fig}", {var})
'''),
        code(f'''\
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.2))
nt.plot_modes(ax_a, "{fig}", {var}.table, labels=("blade lag 1",), measure=damping_measure)
ax_a.set_title("lag damping (tefcore prediction; no MDART test data)", fontsize="medium")
ax_a.set_ylim(bottom=0)
nt.plot_modes(ax_b, "{fig}", {var}.table, labels=("blade lag 1",), quantity="frequency")
ax_b.set_title("lag frequency", fontsize="medium")
fig.suptitle({pystr(title, 13)},
             fontsize="medium")
nt.savefig(fig, out, "{png}");
'''),
        code(f'''\
print(nt.mode_summary("{fig}", {var}.table, labels=("blade lag 1",), measure=damping_measure)
      .rename(columns={{"blade lag 1": "lag damping"}}).to_string())
'''),
    ]


def nb02():
    stem = "02_hinge_moments_and_flap_response"
    extra = '''\
n_psi = 72                # azimuth points of the Fig. 5 hinge-moment history
'''
    return stem, [
        md('''\
# 02 -- Flap hinge moments and the flap response (Figs. 5-6)

The **hinge moment** is the aerodynamic moment about the flap hinge. It is
what the actuator has to fight, and it is what couples the blade to the
flap: blade flapping and twisting change the flap's angle of attack, which
changes the hinge moment, which moves the flap through the compliant
actuator. Its prediction is therefore the first thing to get right.

Figure 5 prescribes the flap motion delta_f = 2 deg cos(4 psi - 240 deg) on
the trimmed rotor (mu = 0.2, C_T/sigma = 0.0774, overhang 0.29 c_f, mass-
balanced flap) and plots the hinge moment over one revolution. The paper
compares three predictions: UMARC with **table look-up** of C_h and C_lf,
UMARC with the **Theodorsen-type** analytical flap model, and CAMRAD II
(also table look-up). Table look-up agrees with CAMRAD II; the analytical
model agrees qualitatively but **under-predicts the magnitude in the first
quadrant**.

**What we can and cannot compare.** The paper's tables came from wind-tunnel
test data of the MD900 flap airfoil, which we do not have. tefcore ships a
C81 deck, `example_flap_generated.c81`, that is **generated from the same
thin-airfoil theory** (with the lift-slope and Prandtl-Glauert corrections)
-- so our "table look-up" curve is a check of the table machinery, not an
independent aerodynamic model, and the two curves are expected to be close.
The CAMRAD II curve is not available either.'''),
        params_cell(stem, extra=extra),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## Figure 5: hinge moment over one revolution, thin airfoil versus table look-up'''),
        code('''\
from tefcore.paper.figures import hinge_moment_figure

cfg5 = base.with_overrides(overrides) if overrides else base
with nt.counted_warnings("warnings (e.g. table inputs clipped to its edges)"):
    hm_thin = hinge_moment_figure(cfg5, aero=nt.section_aero("thin_airfoil", cfg5), n_psi=n_psi)
    hm_table = hinge_moment_figure(cfg5, aero=nt.section_aero("table", cfg5), n_psi=n_psi)
fig5 = hm_thin.rename(columns={"hinge_moment": "thin_airfoil"}).assign(
    table_lookup=hm_table["hinge_moment"].to_numpy())
results["fig5"] = fig5
print(nt.clean(fig5[["thin_airfoil", "table_lookup"]].describe().loc[["mean", "min", "max"]]
               .round(3)).to_string())
'''),
        code('''\
fig, ax = plt.subplots(figsize=(6.4, 4.4))
ax.plot(fig5["psi_deg"], fig5["thin_airfoil"], "-", color="C0", label="thin airfoil (quasi-steady)")
ax.plot(fig5["psi_deg"], fig5["table_lookup"], "--", color="C3",
        label="table look-up (generated deck)")
ref = nt.reference_curves("fig5")
if ref is not None:
    for lab, g in ref.groupby("label"):
        ax.plot(g["x"], g["y"], "kx", label=f"paper: {lab}")
ax.set_xlabel("azimuth psi [deg]")
ax.set_ylabel("flap hinge moment [N m]")
ax.set_xticks(range(0, 361, 90))
ax.set_title("Fig. 5: hinge moment, delta_f = 2 deg cos(4 psi - 240 deg), mu = 0.2",
             fontsize="medium")
ax.legend()
nt.savefig(fig, out, "fig05");
'''),
        md('''\
The mean (negative) hinge moment comes from the steady angle of attack and
camber-like loading of the trimmed section; the 4/rev ripple from the
prescribed flap motion; the 1/rev content from the advancing/retreating
dynamic pressure. Because our deck is generated from thin-airfoil theory,
the two curves differ only by the deck's corrections and interpolation; the
paper's first-quadrant under-prediction (test-data tables versus Theodorsen)
**cannot be reproduced** without the test-data tables.

## Figure 6: flap response to the actuator input

Now the flap is free: the actuator base moves with delta_a = 2 deg
cos(4 psi - 240 deg), and the flap follows through the actuator's torsional
spring (81.52 ft-lb/rad) and damper, loaded by the hinge moment and the flap
inertia. An infinitely stiff actuator would give delta_f = delta_a. The paper
finds a **half peak-to-peak flap response 15 % larger than the input**: the
aerodynamically balanced flap has a small *negative* aerodynamic spring
(overhang puts the centre of pressure near the hinge), which softens the
actuator, and the 4/rev input is below the flap's natural frequency, so the
response is amplified in phase.'''),
        code('''\
from tefcore.paper.figures import flap_response_figure

with nt.counted_warnings("warnings (e.g. table inputs clipped to its edges)"):
    fig6 = flap_response_figure(base, **overrides)
results["fig6"] = fig6
ratio = fig6["half_peak_to_peak_deg"] / fig6["input_half_peak_to_peak_deg"]
print(f"half peak-to-peak: input {fig6['input_half_peak_to_peak_deg']:.2f} deg, "
      f"flap {fig6['half_peak_to_peak_deg']:.3f} deg, ratio {ratio:.3f} (paper: 1.15)")
print(f"trimmed mean flap deflection {fig6['trim']['delta_mean_deg']:.3f} deg "
      "(non-zero with zero actuator input, as the paper notes)")
'''),
        code('''\
t6 = fig6["table"]
fig, ax = plt.subplots(figsize=(6.4, 4.4))
ax.plot(t6["psi_deg"], t6["delta_a_deg"], "--", color="0.4", label="actuator input delta_a")
ax.plot(t6["psi_deg"], t6["delta_f_deg"], "-", color="C3", label="flap response delta_f")
ref = nt.reference_curves("fig6")
if ref is not None:
    for lab, g in ref.groupby("label"):
        ax.plot(g["x"], g["y"], "kx", label=f"paper: {lab}")
ax.set_xlabel("azimuth psi [deg]")
ax.set_ylabel("deflection [deg] (positive flap down)")
ax.set_xticks(range(0, 361, 90))
ax.set_title("Fig. 6: flap response, delta_a = 2 deg cos(4 psi - 240 deg), mu = 0.2",
             fontsize="medium")
ax.legend()
nt.savefig(fig, out, "fig06");
'''),
        md('''\
**What the paper concludes:** the flap does not simply follow the actuator;
"this demonstrates the importance of including actuator dynamics in the
model". The same compliance is what lets the flap take part in the
aeroelastic modes studied in notebooks 03-07.'''),
        *claims_cells(["fig5", "fig6"], [("fig05_hinge_moment", "fig5"),
                                          ("fig06_flap_response", 't6')]),
        md(DEPARTURES_COMMON + '''
For Figs. 5-6 in particular: the hinge moment depends directly on the local
angle of attack at the flap (free wake versus linear inflow) and on the
section's C_h tables (test data versus thin-airfoil theory). Thin-airfoil
theory is known to over-predict flap effectiveness and hinge-moment
derivatives on real, thick airfoils with gaps; the paper's under-prediction
in the first quadrant is the sign of that.'''),
    ]


def nb03():
    stem = "03_overhang"
    extra = '''\
fig7_overhangs = [0.0, 0.1, 0.2, 0.29, 0.35, 0.4, 0.45, 0.5]  # Fig. 7 overhangs c_b/c_f
'''
    return stem, [
        md('''\
# 03 -- Aerodynamic balance: flap overhang (Figs. 7-8)

A plain flap hinged at its nose needs a large actuator moment: all the flap's
lift acts aft of the hinge. Moving the hinge aft into the flap -- a **nose
overhang** c_b (Figure 2 of the paper) -- puts part of the flap's area ahead
of the hinge, so its pressure partly balances the rest: the **aerodynamic
hinge moment shrinks**, and with it the actuation power. The MD900 flap has
its hinge 10 % chord behind the flap nose: c_b/c_f = 0.29.

The price: the hinge moment's *stiffness* (how much it pushes the flap back
when it deflects) also shrinks, changes sign when the hinge passes the
flap's aerodynamic centre, and then the aerodynamic moment *helps* the flap
deflect further -- the flap becomes **aerodynamically over-balanced**. The
actuator spring must then carry the flap alone against a negative aerodynamic
spring, and beyond some overhang the flap mode diverges.

In this notebook the flap is **mass-balanced** (c_cg/c_f = 0): flap and blade
couple only through aerodynamics.'''),
        params_cell(stem, extra=extra),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## Figure 7: actuation power and flap response versus overhang

Same conditions as Fig. 6 (mu = 0.2, C_T/sigma = 0.0774, delta_a = 2 deg
cos(4 psi - 240 deg)). The power is the actuator torque times the actuator
rate; we show its peak over a revolution and the mean of its magnitude.'''),
        code('''\
from tefcore.paper.figures import overhang_actuation_figure

with nt.counted_warnings("warnings (e.g. table inputs clipped to its edges)"):
    fig7 = overhang_actuation_figure(base.with_overrides(overrides) if overrides else base,
                                     overhangs=tuple(fig7_overhangs))
results["fig7"] = fig7
fig7 = fig7.assign(peak_power_rel=fig7["peak_power"] / fig7["peak_power"].iloc[0],
                   mean_power_rel=fig7["mean_power"] / fig7["mean_power"].iloc[0])
print(nt.clean(fig7.round(3)).to_string(index=False))
'''),
        code('''\
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
fig.suptitle("Fig. 7: actuation power and flap response vs overhang, mu = 0.2", fontsize="medium")
nt.savefig(fig, out, "fig07");
'''),
        md('''\
**Paper:** the actuation power drops by 60 % at c_b/c_f = 0.29 compared with
no overhang; the half peak-to-peak response grows with overhang, "more
dramatically above 40 % flap chord" -- the softening negative aerodynamic
spring brings the flap's natural frequency down towards the 4/rev input.
Beyond the point where the power starts to rise again the actuator is
driving a nearly resonant flap.

## Figure 8: stability versus overhang, in hover

What to look for (paper): the **TEF mode damping decreases** with overhang and
the mode becomes **unstable above about 50 % flap chord** (over-balance, the
flap mode diverges). Because the flap is mass-balanced, it couples to the
blade only aerodynamically: a flap-down deflection adds lift, so the flap
motion is **in phase with blade flap bending** -- blade flap damping
*decreases* with overhang; it produces a nose-down pitching moment, so it is
**out of phase with blade torsion** -- torsion damping *increases*. Lag
damping stays about constant.'''),
        *stability_block("fig8", "fig08", "Fig. 8: effect of overhang on stability in hover, "
                         "c_cg/c_f = 0"),
        md(MECHANISM_NOTE + '''
For the over-balanced flap the paper's explanation is that "the flap becomes
aerodynamically over-balanced ... and the flap mode diverges": a divergence
would be a *real* root crossing zero, driven by the flap's own hinge moment
(C_h_delta, a negative spring beyond the balance point). Here is the TEF
branch at an overhang of 0.6, term by term:'''),
        code('''\
print(nt.explain("fig8", res_fig8, 0.6, base, overrides).to_string(index=False))
'''),
        md('''\
**What the paper concludes** (conclusion 1): aerodynamic balance is the key to
small actuation requirements, but excessive overhang may lead to
blade/trailing-edge-flap instability. The design sits at 0.29, where the
power is already much reduced and the flap mode is still well damped.'''),
        *claims_cells(["fig7", "fig8"], [("fig07_actuation", "fig7"),
                                          ("fig08_modes", "res_fig8.table")]),
        md(DEPARTURES_COMMON + '''
For Figs. 7-8 in particular: the over-balance boundary is set by where the
hinge passes the flap's aerodynamic centre, which quasi-steady thin-airfoil
theory places differently from a real airfoil with a gap and a thick nose;
the overhang at which the TEF damping crosses zero is sensitive to exactly
that. Try `aero_model = "table"` to see how sensitive: the generated deck
comes from the same thin-airfoil theory, but tabulated (angle of attack only
within +-10 deg, clipped beyond; its own Mach corrections), and that alone
moves this boundary noticeably -- a measure of how much the paper's
test-data tables could move it.'''),
        code('''\
for name in ["fig8"]:
    nt.unsteadiness(name, results[name], base)
'''),
    ]


def nb04():
    stem = "04_cg_offset"
    return stem, [
        md('''\
# 04 -- Mass balance: flap CG offset (Fig. 9)

A flap whose centre of gravity lies **behind its hinge** (c_cg > 0) is
*mass-unbalanced*: when the blade section accelerates up or down (flap
bending) or twists (torsion), the flap's inertia lags behind and the flap
rotates about its hinge -- and a flap rotation in turn shakes the blade.
This **inertial coupling** is the mechanism of classic aileron flutter on
fixed wings (Broadbent, Fung, Theodorsen in the paper's references), and the
cure there is the same as here: mass balance, stiffer (irreversible) controls,
more damping.

Two effects of moving the CG aft, at constant actuator stiffness:

1. the flap's moment of inertia about the hinge grows (I_cg + m d^2), so the
   **TEF frequency decreases**;
2. the inertial coupling with blade torsion grows, and with it the energy the
   two modes can exchange per cycle: past some offset the aerodynamic work
   of the flap on the twisting blade is positive and the **TEF mode becomes
   unstable** -- trailing-edge flap / blade torsion flutter.

Conditions: forward flight, mu = 0.30, overhang 0.29 c_f.'''),
        params_cell(stem),
        code(SETUP, "nbval-ignore-output"),
        md('## Figure 9: (a) TEF frequency and (b) blade and TEF damping versus CG offset'),
        *stability_block("fig9", "fig09", "Fig. 9: effect of flap CG offset, mu = 0.30, "
                         "c_b/c_f = 0.29", panels=("trailing-edge flap frequency",),
                         freq_labels=("TEF",)),
        code('''\
print("TEF frequency [/rev] versus CG offset:")
print(nt.mode_summary("fig9", res_fig9.table, labels=("TEF",), quantity="frequency").to_string())
'''),
        md(MECHANISM_NOTE + '''
The paper calls the instability of the mass-unbalanced flap "typical
trailing-edge flap-blade torsion flutter", resulting "from the energy transfer
between the trailing-edge flap mode and blade torsion mode". Here is the TEF
branch and the flutter root at c_cg = 0.33 c_f (the paper's imbalanced flap), term by term: which terms do
the destabilising work, and what happens when the flap-torsion couplings are
knocked out:'''),
        code('''\
print(nt.explain("fig9", res_fig9, 0.33, base, overrides).to_string(index=False))
'''),
        code('''\
print(nt.explain("fig9", res_fig9, 0.33, base, overrides, which="flutter root",
                 knockouts=False).to_string(index=False))
'''),
        md('''\
**What the paper concludes:** the TEF frequency falls with CG offset; the TEF
mode becomes unstable after an offset of **0.26 flap chord** (flap/torsion
flutter from energy transfer between the TEF and blade torsion modes); blade
flap damping decreases with offset and lag damping is unaffected. Conclusion
2: large flap CG offsets cause torsion-flap flutter, especially at high
advance ratios. Notebooks 05-07 use a deliberately mass-imbalanced flap
(c_cg = 0.33 c_f) to study what makes that flutter better or worse.

Where the mode labels swap (hollow markers), TEF and torsion motion are
strongly mixed in one eigenvector -- the signature of the coupling that
drives the flutter.'''),
        *claims_cells(["fig9"], [("fig09_modes", "res_fig9.table")]),
        md(DEPARTURES_COMMON + '''
For Fig. 9 in particular: the inertial coupling is proportional to the flap
mass times its CG offset, and the flap mass and inertia are assumed
(0.30 lb/ft with a nose balance weight, from the flap's construction); the
critical offset moves with them (notebook 08). The torsion mode shape at the
flap (set by the assumed GJ and the equivalent pitch-link spring) sets how
much the flap "sees" of the twist.'''),
        code('''\
for name in ["fig9"]:
    nt.unsteadiness(name, results[name], base)
'''),
    ]


def nb05():
    stem = "05_stiffness"
    return stem, [
        md('''\
# 05 -- Control system, blade torsion and actuator stiffness (Figs. 10-12)

From here on the flap is deliberately **mass-imbalanced** (CG offset 0.33
c_f, overhang 0.29 c_f) and the rotor flies at mu = 0.30: a configuration
prone to TEF/torsion flutter (notebook 04), used to see which stiffnesses
make it better or worse. Three stiffnesses set the frequencies of the two
modes that flutter together:

* **pitch-link stiffness** (rotor control system) -- mostly sets the blade's
  first torsion frequency (2.3/rev at 158 lb/in to 4.2/rev at 800 lb/in);
* **blade torsional stiffness GJ** -- also raises torsion, but much less here
  (2.96/rev at 0.75 GJ to 3.18/rev at 2 GJ), since the soft root dominates;
* **actuator stiffness** -- sets the TEF frequency (sqrt(k_a / I_f)).

Flutter from inertial coupling is strongest when the two coupled frequencies
approach each other, and the sign of the energy exchange depends on their
order and phase -- so stiffening one side can stabilise or destabilise.'''),
        params_cell(stem),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## Figure 10: pitch-link stiffness

Paper: torsion frequency 2.3 -> 4.2/rev, flap and lag frequencies
unchanged; the **TEF mode becomes gradually more unstable** with stiffer
pitch links; blade flap damping increases strongly, torsion damping
decreases slightly, lag varies little.'''),
        *stability_block("fig10", "fig10", "Fig. 10: effect of pitch link stiffness, mu = 0.30, "
                         "c_b/c_f = 0.29, c_cg/c_f = 0.33",
                         labels=("blade flap 1", "blade lag 1", "blade torsion 1", "TEF"),
                         panels=("blade natural frequencies",), natural=True),
        md('''\
## Figure 11: blade torsional stiffness (GJ factor)

Paper: torsion frequency 2.96 -> 3.18/rev; the **TEF mode is unstable over
the whole range** 0.75-2.0 GJ with little variation; torsion damping
decreases slightly and flap damping increases with GJ.'''),
        *stability_block("fig11", "fig11", "Fig. 11: effect of blade torsional stiffness, "
                         "mu = 0.30, c_b/c_f = 0.29, c_cg/c_f = 0.33",
                         labels=("blade flap 1", "blade lag 1", "blade torsion 1", "TEF"),
                         panels=("blade natural frequencies",), natural=True),
        code('''\
for name, nat in (("fig10", nat_fig10), ("fig11", nat_fig11)):
    print(f"{name} (a): blade natural frequencies [/rev]")
    print(nt.mode_summary(name, None, labels=("blade flap 1", "blade lag 1", "blade torsion 1"),
                          quantity="frequency", natural=nat).to_string())
'''),
        md('''\
Panel (a) of Figs. 10 and 11 shows the blade's *natural* frequencies (the
structure in vacuum, rotating, at zero collective), which is what the stated
2.3-4.2/rev and 2.96-3.18/rev refer to and what the assumed properties were
calibrated to. The aeroelastic (Floquet) frequencies of the coupled
system differ from them -- strongly for the torsion mode, which the
imbalanced flap's inertia and the aerodynamic stiffness both load.'''),
        md('''\
## Figure 12: actuator stiffness

Panel (a) compares the TEF frequency of a mass-balanced flap (c_cg = 0) and
the mass-imbalanced one (c_cg = 0.33 c_f): both rise with actuator
stiffness, the imbalanced one more slowly because of its larger inertia
about the hinge. Panel (b), for the imbalanced flap: the paper finds the
**TEF mode unstable with a soft actuator and stable above 1.5 times the
baseline stiffness**: raising the flap frequency moves it away from the blade
modes it exchanges energy with. Blade flap damping increases with actuator
stiffness, torsion damping decreases, lag is unaffected.'''),
        code('''\
vals_fig12 = nt.figure_values("fig12", n_points, values.get("fig12"))
res_fig12 = nt.run_stability_figure("fig12", base, overrides, vals_fig12, n_jobs)
res_fig12_balanced = nt.run_stability_figure("fig12", base, overrides, vals_fig12, n_jobs,
                                             cg_offset=0.0)
results["fig12"] = res_fig12
variants["fig12"] = {nt.variant_key({"flap.cg_offset": 0.0}): res_fig12_balanced}
nt.report_sweep("fig12", res_fig12)
nt.report_sweep("fig12 (balanced)", res_fig12_balanced)
'''),
        code('''\
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
nt.plot_modes(ax_a, "fig12", res_fig12_balanced.table, labels=("TEF",), quantity="frequency",
              label_suffix=", c_cg/c_f = 0", style={"TEF": ("C0", "s", "--")})
nt.plot_modes(ax_a, "fig12", res_fig12.table, labels=("TEF",), quantity="frequency",
              label_suffix=", c_cg/c_f = 0.33")
ax_a.set_title("(a) trailing-edge flap frequency", fontsize="medium")
ax_a.legend()
nt.plot_modes(ax_b, "fig12", res_fig12.table, measure=damping_measure,
              labels=("blade flap 1", "blade lag 1", "blade torsion 1", "TEF"),
              reference=nt.reference_curves("fig12"))
ax_b.set_title("(b) blade and TEF damping, c_cg/c_f = 0.33", fontsize="medium")
ax_b.legend()
fig.suptitle("Fig. 12: effect of actuator stiffness, mu = 0.30, c_b/c_f = 0.29", fontsize="medium")
nt.savefig(fig, out, "fig12");
'''),
        code('''\
print("TEF frequency [/rev]: balanced (c_cg = 0) and imbalanced (c_cg = 0.33)")
print(pd.concat({"balanced": nt.mode_summary("fig12", res_fig12_balanced.table, labels=("TEF",),
                                             quantity="frequency")["TEF"],
                 "imbalanced": nt.mode_summary("fig12", res_fig12.table, labels=("TEF",),
                                               quantity="frequency")["TEF"]}, axis=1).to_string())
print("damping (" + damping_measure + "), imbalanced flap:")
print(nt.mode_summary("fig12", res_fig12.table, measure=damping_measure).to_string())
print("TEF damping changes sign at:", nt.sign_changes("fig12", res_fig12.table,
                                                      measure=damping_measure) or "nowhere")
'''),
        md('''\
**What the paper concludes:** increasing rotor control stiffness with a
mass-imbalanced flap *may destabilise* the TEF mode (conclusion 3);
increasing the actuator stiffness *stabilises* it (conclusion 4). Blade GJ
matters little in the range studied.'''),
        *claims_cells(["fig10", "fig11", "fig12"],
                      [("fig10_modes", "res_fig10.table"), ("fig11_modes", "res_fig11.table"),
                       ("fig12_modes", "res_fig12.table"),
                       ("fig12_balanced_modes", "res_fig12_balanced.table")]),
        md(DEPARTURES_COMMON + '''
For Figs. 10-12 in particular: in UMARC the pitch link is one of several
load paths (flexbeam, torque tube, snubber), so changing its stiffness also
changes the torsion mode *shape* and the pitch-flap/pitch-lag couplings; in
tefcore it changes one equivalent root torsion spring. The calibration
matches the two stated torsion frequencies, but the flap-mode damping trend
of Fig. 10, which the paper attributes to those couplings, may differ.'''),
        code('''\
for name in ["fig10", "fig12"]:
    nt.unsteadiness(name, results[name], base)
'''),
    ]


def nb06():
    stem = "06_size_and_location"
    return stem, [
        md('''\
# 06 -- Flap size and spanwise location (Figs. 13-15)

Mass-imbalanced flap (c_cg = 0.33 c_f, c_b = 0.29 c_f), mu = 0.30. Where the
flap sits and how big it is changes two things at once:

* the **dynamic pressure** it sees (proportional to (r/R)^2 in hover, more
  outboard) and the size of its aerodynamic and inertial loads;
* the **modal amplitude** of blade flap bending and torsion at the flap:
  both grow towards the tip, so an outboard flap couples more strongly to the
  blade modes -- for better (more authority for vibration control) and for
  worse (more flutter-prone).

A larger flap chord also changes the section aerodynamics of the flap
itself: the flap's pitching moment peaks near c_f/c = 0.26 while the flap
lift grows monotonically (the paper's Ref. 21).'''),
        params_cell(stem),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## Figure 13: flap midspan location

Paper: the **TEF mode becomes unstable as the flap moves towards the tip**;
blade flap damping decreases slightly, torsion damping increases, lag is
unchanged.'''),
        *stability_block("fig13", "fig13", "Fig. 13: effect of flap spanwise location, mu = 0.30, "
                         "c_b/c_f = 0.29, c_cg/c_f = 0.33"),
        md('''\
## Figure 14: flap length

Paper: the **TEF mode becomes unstable for flap lengths above 14 % R**; blade
flap damping decreases with length, torsion damping increases (both stay
well damped). Length acts like location, but more strongly.'''),
        *stability_block("fig14", "fig14", "Fig. 14: effect of flap length, mu = 0.30, "
                         "c_b/c_f = 0.29, c_cg/c_f = 0.33"),
        md('''\
## Figure 15: flap chord

Paper: the **TEF mode is unstable for flap chords between 0.15 and 0.40 of
the airfoil chord** and stable outside; blade flap damping follows the TEF
mode (positive aerodynamic coupling), torsion damping does the opposite
(negative coupling).'''),
        *stability_block("fig15", "fig15", "Fig. 15: effect of flap chord, mu = 0.30, "
                         "c_b/c_f = 0.29, c_cg/c_f = 0.33"),
        md('''\
**What the paper concludes** (conclusion 5): with a mass-imbalanced flap,
increasing the flap length or moving the flap towards the tip destabilises
the TEF mode. Note that in these sweeps the flap is built the same way at
every size (`flap.scaling = "construction"`): its mass per unit span is kept
as it grows longer and grows with its chord (its inertia with the chord
cubed), so a longer or wider flap is also a heavier flap with a larger
imbalance moment -- the inertial and aerodynamic effects grow together.'''),
        *claims_cells(["fig13", "fig14", "fig15"],
                      [("fig13_modes", "res_fig13.table"), ("fig14_modes", "res_fig14.table"),
                       ("fig15_modes", "res_fig15.table")]),
        md(DEPARTURES_COMMON + '''
For Figs. 13-15 in particular: near the tip the free wake (tip vortices)
changes the local inflow most, and the assumed blade properties (smooth
between a few stations) make the torsion mode shape a smooth curve, while the
real MD900 blade has a swept tip and detailed sections; the location and
length thresholds depend on both. How the flap's mass and inertia scale with
its chord is an assumption (`flap.scaling`: mass per span ~ chord, inertia ~
chord^3; `"fixed"` keeps them).'''),
        code('''\
for name in ["fig13", "fig15"]:
    nt.unsteadiness(name, results[name], base)
'''),
    ]


def nb07():
    stem = "07_flight_condition"
    return stem, [
        md('''\
# 07 -- Flight condition: collective pitch and forward speed (Figs. 16-17)

Mass-imbalanced flap (c_cg = 0.33 c_f, c_b = 0.29 c_f). The structural and
inertial couplings do not depend on the flight condition; the aerodynamic
ones do:

* **collective pitch** raises the blade's steady lift and the trimmed flap
  deflection and hinge moment, changing the aerodynamic stiffness around
  which the flap oscillates;
* **forward speed** makes the dynamic pressure periodic (advancing side high,
  retreating side low) and couples the modes through periodic coefficients,
  which is why the Floquet method is needed; on the advancing side the flap
  sees up to (0.83 + mu)^2 of the hover dynamic pressure at the flap.

Here the collective is prescribed (not trimmed to a thrust).'''),
        params_cell(stem),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## Figure 16: collective pitch, (a) hover and (b) mu = 0.30

Paper: in hover the **TEF mode becomes unstable at large collective**, though
the variation is very small; at mu = 0.30 it is **unstable from 4 to 12 deg
collective and increasingly so** with larger collective.'''),
        code('''\
res_fig16a = nt.run_stability_figure("fig16a", base, overrides,
                                     nt.figure_values("fig16a", n_points, values.get("fig16a")),
                                     n_jobs)
res_fig16b = nt.run_stability_figure("fig16b", base, overrides,
                                     nt.figure_values("fig16b", n_points, values.get("fig16b")),
                                     n_jobs)
results.update(fig16a=res_fig16a, fig16b=res_fig16b)
nt.report_sweep("fig16a", res_fig16a)
nt.report_sweep("fig16b", res_fig16b)
'''),
        code('''\
fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
nt.plot_modes(ax_a, "fig16a", res_fig16a.table, measure=damping_measure,
              reference=nt.reference_curves("fig16a"))
ax_a.set_title("(a) hover", fontsize="medium")
nt.plot_modes(ax_b, "fig16b", res_fig16b.table, measure=damping_measure,
              reference=nt.reference_curves("fig16b"))
ax_b.set_title("(b) forward flight, mu = 0.30", fontsize="medium")
ax_b.legend()
fig.suptitle("Fig. 16: effect of collective pitch, c_b/c_f = 0.29, c_cg/c_f = 0.33",
             fontsize="medium")
nt.savefig(fig, out, "fig16");
'''),
        code('''\
for name in ("fig16a", "fig16b"):
    print(f"{name}: damping (" + damping_measure + ")")
    print(nt.mode_summary(name, results[name].table, measure=damping_measure).to_string())
    print("TEF damping changes sign at:",
          nt.sign_changes(name, results[name].table, measure=damping_measure) or "nowhere")
'''),
        md('''\
## Figure 17: forward speed

Paper: the **TEF mode is weakly unstable in hover and becomes more unstable
with forward speed**.'''),
        *stability_block("fig17", "fig17", "Fig. 17: effect of forward speed, c_b/c_f = 0.29, "
                         "c_cg/c_f = 0.33"),
        md('''\
**What the paper concludes** (conclusions 2 and 6): torsion-flap flutter of a
mass-unbalanced flap is worse at high advance ratio, and increasing
collective pitch makes the TEF mode more unstable. Combined with notebooks
03-06, the design message is: mass-balance the flap, keep the overhang
moderate, and keep the actuator stiff.'''),
        *claims_cells(["fig16a", "fig16b", "fig17"],
                      [("fig16a_modes", "res_fig16a.table"), ("fig16b_modes", "res_fig16b.table"),
                       ("fig17_modes", "res_fig17.table")]),
        md(DEPARTURES_COMMON + '''
For Figs. 16-17 in particular: these are the figures most affected by the
aerodynamic model -- the free wake changes the inflow distribution with
collective and advance ratio, the reverse-flow region grows with mu, and the
unsteady (non-quasi-steady) flap aerodynamics matter most at high dynamic
pressure. The paper's own statement that the hover variation is "very small"
means the sign of the hover TEF damping is within the uncertainty of any of
these models.'''),
        code('''\
for name in ["fig16b", "fig17"]:
    nt.unsteadiness(name, results[name], base)
'''),
    ]


def nb08():
    stem = "08_assumptions"
    extra = '''\
assumptions = None         # None: every assumption of tefcore.paper.sensitivity.ASSUMPTIONS, or a
                           # list of their names, e.g. ["flap mass", "flap inertia"]
'''
    return stem, [
        md('''\
# 08 -- What each assumption does

tefcore replicates the paper with **assumed** blade and flap data: the MDART
property tables are not public, and the paper gives only Table 1 and a few
frequencies. A reviewer judging such a replication must know which assumption
moves which result, and by how much. This notebook

1. shows how the flap sits **inside** its blade section (the paper lumps it
   there) and what the inertia checks refuse;
2. shows the assumed blade (frequencies where soft-inplane bearingless blades
   have them, torsion calibrated to the four frequencies the text states);
3. computes four **headline results** and re-computes them with every assumed
   property at the two ends of its plausible range (`tefcore.paper.sensitivity`):

* `fig9_onset`: the flap CG offset c_cg/c_f where the TEF flutter root turns
  unstable, mu = 0.3, c_b/c_f = 0.29 (paper: 0.26);
* `growth_hover`: the growth rate (real part, 1/rev) of the TEF flutter root at
  the imbalanced baseline (c_cg/c_f = 0.33, c_b/c_f = 0.29) in hover (paper:
  "weakly unstable");
* `growth_mu03`: the same at mu = 0.3 (paper: "more unstable with forward
  speed");
* `fig8_onset`: the overhang c_b/c_f at which the TEF flutter root turns
  unstable in hover with the mass-balanced flap (paper: "larger than 50 %").

**Which root is the TEF.** Where the flap frequency meets a blade mode the two
roots *coalesce*: they share the flap's motion, one is destabilised and the
other stabilised, and a name attached to one root is ambiguous. The *flutter
root* here is the least stable root in which the flap takes part materially:
its TEF kinetic-energy share is at least 0.15 of the largest share among all
roots (measured on MDART: the unstable flap-involved root carries 0.19-1.0 of
it at every point of Figs. 8-17, roots without the flap below 1e-3). This rule
is `tefcore.paper.sensitivity.flutter_root`; every function takes an `identify`
argument, so the mode tracking of `tefcore.tracking` can replace it.'''),
        params_cell(stem, extra=extra),
        code(SETUP, "nbval-ignore-output"),
        md('''\
## 1. The flap inside its blade section

The blade tables are whole sections with the mass-balanced flap inside
(docs/theory.md section 2.7). Over the flap span the flap's share is its mass,
its first moment and its polar inertia about the elastic axis; the rest, the
*host* (spar, skins, nose ballast, actuator), must be a real body: positive mass
and positive inertia about its own CG. That bounds the flap mass. Moving the
flap CG aft (c_cg > 0) moves its share: the section CG goes aft and its torsion
inertia grows.'''),
        code('''\
import numpy as np

from tefcore import section_inertia as si
from tefcore.units import from_si

cfg = base.with_overrides(overrides) if overrides else base
x = np.array([cfg.flap.midspan])
rows = []
for cg in (0.0, 0.33):
    c = cfg.with_overrides({"flap.cg_offset": cg})
    share, host, sec = si.flap_share(c), si.host_section(c, x), si.lumped_section(c, x)
    rows.append({"c_cg/c_f": cg,
                 "flap mass [lb/ft]": from_si(share.mass, "lb/ft", "mass_per_length"),
                 "flap I_theta [lb in^2/ft]": from_si(share.inertia, "lb*in^2/ft",
                                                      "inertia_per_length"),
                 "section I_theta [lb in^2/ft]": from_si(sec["im_lag"][0] + sec["im_flap"][0],
                                                         "lb*in^2/ft", "inertia_per_length"),
                 "section CG [in ahead of EA]": from_si(sec["cg_offset"][0], "in", "length"),
                 "host I about own CG [lb in^2/ft]": from_si(host["inertia_cg"][0],
                                                             "lb*in^2/ft", "inertia_per_length")})
print(nt.clean(pd.DataFrame(rows).round(3)).to_string(index=False))
limit = si.flap_mass_limit(cfg)
print(f"largest flap mass the section holds: "
      f"{from_si(limit, 'lb/ft', 'mass_per_length'):.3f} lb/ft (configured "
      f"{from_si(cfg.flap.mass_per_span, 'lb/ft', 'mass_per_length'):.3f} lb/ft)")
try:
    cfg.with_overrides({"flap.mass": "1.0 lb/ft"})
except ValueError as err:
    print("flap.mass = 1.0 lb/ft is refused:")
    print(str(err).replace("). ", ").\\n"))
'''),
        md('''\
## 2. The assumed blade

Non-uniform sections (pitchcase region, root joint, inboard blade, the outboard
active-flap section, tip weight), the flap's share inside; flapwise stiffness of
a 10 in chord composite blade, which places the higher flap modes where
soft-inplane hingeless and bearingless blades have them; the GJ level, horn arm
and pitch-link stiffness fitted to the four stated torsion frequencies at the
figures' mass-imbalanced flap. `tefcore/data/mdart.toml` gives the reason for
every number.'''),
        code('''\
from tefcore.blade import blade_modes
from tefcore.paper.calibration import frequency_checks
from tefcore.flap_dynamics import flap_natural_frequency, flap_properties

fan = []
for cg in (0.0, 0.33):
    m = blade_modes(cfg.with_overrides({"flap.cg_offset": cg}), n_modes=12)
    fan.append(pd.Series(m.frequencies, index=m.labels, name=f"c_cg/c_f = {cg}"))
print("blade natural frequencies [/rev] at 392 RPM, zero collective (first 9 retained):")
print(pd.concat(fan, axis=1).round(2).to_string())
checks = frequency_checks(cfg)
print(nt.clean(checks[["case", "stated_per_rev", "computed_per_rev", "error_percent"]]
               .round(3)).to_string(index=False))
for cg in (0.0, 0.33):
    c = cfg.with_overrides({"flap.cg_offset": cg})
    f = flap_natural_frequency(flap_properties(c), c.rotor.rotor_speed) / c.rotor.rotor_speed
    print(f"flap alone on a rigid blade, in vacuum, c_cg/c_f = {cg}: {f:.2f} /rev")
'''),
        md('''\
## 3. Headline results and what each assumption does

Each assumption is set to the low and the high end of its plausible range, one
at a time; the basis of each range is in the table below. Assumptions that move
the stated torsion frequencies (section inertia, the GJ distribution, the lift
slope through the blade inertia that the stated Lock number then needs) are
re-calibrated first: the sensitivity is that of the whole derivation with what
the text states held fixed.'''),
        code('''\
from tefcore.paper import sensitivity as sens

chosen = [a for a in sens.ASSUMPTIONS if assumptions is None or a.name in assumptions]
pd.set_option("display.max_colwidth", 110)
print(pd.DataFrame([{"assumption": a.name, "low": a.low_label, "high": a.high_label,
                     "basis": a.basis} for a in chosen]).to_string(index=False))
table = sens.sensitivity(cfg, chosen, n_jobs=n_jobs)
base_rows = table[table["end"] == "baseline"].set_index("headline")
paper = {h.name: h.paper for h in sens.HEADLINES}
print()
print("baseline headline results (paper in brackets):")
for h, row in base_rows.iterrows():
    print(f"  {h:13s} {row['value']:+.3f} {row['unit']:9s} ({paper[h]}) {row['status']}")
'''),
        code('''\
wide = sens.tornado_table(table)
print("low / high end of each assumption (rows: largest relative change first):")
print(nt.clean(wide).to_string())
odd = table[(table["status"] != "ok") & (table["end"] != "baseline")]
if len(odd):
    print("missing values (onset outside the scanned range, or data not admitted):")
    print(odd[["assumption", "end", "headline", "status"]].to_string(index=False))
'''),
        code('''\
fig, axes = plt.subplots(2, 2, figsize=(13, 9))
for ax, h in zip(axes.ravel(), [h.name for h in sens.HEADLINES], strict=True):
    sens.tornado_plot(table, h, ax)
    ax.set_title(h, fontsize="medium")
fig.suptitle("What each assumption does: headline results at the low (blue) and high (red) "
             "end of its range", fontsize="medium")
fig.tight_layout()
nt.savefig(fig, out, "tornado");
'''),
        md('''\
## What the data can and cannot explain

* **The flap fits in its section.** The first-draft flap (0.51 lb/ft, its polar
  inertia about the elastic axis 1.04 times the whole section's) is refused by
  the checks of section 1; the re-derived flap (0.30 lb/ft, from its
  construction) takes about half of the outboard section's polar inertia.
* **The flutter stays violent.** At the imbalanced baseline the flutter root
  grows at about +3 /rev in hover and at mu = 0.3 (damping ratio about -0.3);
  the paper calls the hover case "weakly unstable". No assumed *property* moves
  this by more than about a fifth within its plausible range: it is set by the
  coalescence of the flap mode (falling from 17.5 /rev as its CG moves aft) with
  blade torsion 2 and flap 5 at 10.8-11.8 /rev, which a plausible blade has
  somewhere in that band.
* **The retained modes decide it.** Keeping six modes (dropping flap 4, flap 5
  and torsion 2) gives the paper's picture: onset near c_cg/c_f = 0.25 and a
  weak hover instability that grows with forward speed; twelve modes agree with
  nine. The paper keeps nine modes of its own blade; which modes those are, and
  where the imbalanced flap's frequency lies relative to them, is exactly what
  it does not state. Quasi-steady aerodynamics (no lift deficiency C(k), see
  notebooks 03-07) are the other candidate: at the flutter frequency the
  reduced frequency at the flap is about 0.3.
* **The onsets move with the flap.** The Fig. 8 and Fig. 9 onsets depend most on
  the flap's own inertia and mass (they set its frequency and its inertial
  coupling), then on the lag-2 placement and the section CG; the root springs,
  the lag damper and the lift slope hardly matter.'''),
        code('''\
flat = wide.copy()
flat.columns = [f"{h}_{e}" for h, e in wide.columns]
written = [nt.save_csv(table, out, "sensitivity"),
           nt.save_csv(flat.rename_axis("assumption").reset_index(), out, "sensitivity_wide")]
print(sorted(p.name for p in written + sorted(out.glob("*.png"))))
'''),
    ]


BUILDERS = (nb01, nb02, nb03, nb04, nb05, nb06, nb07, nb08)


def build(stem_cells):
    import nbformat

    stem, cells = stem_cells
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nb.metadata["language_info"] = {"name": "python"}
    for i, (kind, text, tags) in enumerate(cells):
        cell = (nbformat.v4.new_markdown_cell(text) if kind == "markdown"
                else nbformat.v4.new_code_cell(text))
        cell["id"] = f"{stem[:2]}-{i:02d}"
        if tags:
            cell.metadata["tags"] = list(tags)
        nb.cells.append(cell)
    return stem, nb


def execute(nb, timeout=1200):
    from nbclient import NotebookClient

    NotebookClient(nb, timeout=timeout, kernel_name="python3",
                   resources={"metadata": {"path": str(HERE)}}).execute()
    # the kernel may flush one print in several stream messages; merge them so
    # the stored outputs do not depend on the flush timing
    for cell in nb.cells:
        merged = []
        for out in cell.get("outputs", []):
            if (out.output_type == "stream" and merged and merged[-1].output_type == "stream"
                    and merged[-1].name == out.name):
                merged[-1].text += out.text
            else:
                merged.append(out)
        if "outputs" in cell:
            cell.outputs = merged
    return nb


def main(argv=None) -> int:
    import nbformat

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--execute", action="store_true", help="execute and store the outputs")
    ap.add_argument("--only", nargs="+", default=None, help="notebook numbers, e.g. 03 04")
    args = ap.parse_args(argv)
    for builder in BUILDERS:
        stem, nb = build(builder())
        if args.only and stem[:2] not in args.only:
            continue
        if args.execute:
            execute(nb)
            nb.metadata.pop("widgets", None)
        nbformat.validate(nb)
        path = HERE / f"{stem}.ipynb"
        nbformat.write(nb, str(path))
        print(f"wrote {path.relative_to(HERE.parent)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
