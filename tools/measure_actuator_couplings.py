"""Measure the cross-couplings of the actuator's moving parts that tefcore leaves out.

tefcore models the actuator's moving parts (output, push rod, horn) by their
inertia reflected to the flap hinge, ``actuator.reflected_inertia`` ``I_a``,
which adds to the flap's ``delta**`` term only (docs/theory.md 4.1).  What the
real parts add beyond that depends on the linkage, which the paper does not
give.  This script measures each left-out term at a size the linkage could
give it, on ``mdart-fig6`` (``I_a`` = 2.66 lb in^2), by adding it to the flap's
equation and its blade reactions for the run (a patch of
``tefcore.model.station_terms.flap_moments``, so that the residual and its
exact Jacobian both see it) and recomputing Fig. 6 and the conflict points of
:data:`tefcore.paper.fig6_calibration.CONFLICT_POINTS`:

* centrifugal moment of the parts: ``-I_a Omega^2`` (parts sliding in the plane
  of the section) to ``+I_a Omega^2`` (parts turning about a spanwise axis);
* coupling to the section's pitch acceleration, ``kappa I_a (Theta** on the
  flap, delta** on blade torsion)``: ``kappa = zeta / l`` for a part sliding
  chordwise ``l`` per radian at ``zeta`` above the elastic axis (|kappa| <~ 0.5
  in a 1.2 in thick section), ``kappa = 1/n`` for a part turning ``n`` times as
  fast as the flap (``kappa = 1``: turning with it, as if the flap itself were
  heavier -- :data:`tefcore.paper.fig6_calibration.FLAP_INERTIA_SCALE`);
* first moment of parts sliding chordwise, ``S_a = I_a / l``: couples the flap
  with the lag (``cos Theta``) and flap (``sin Theta``) accelerations and, through
  the centrifugal field, with lag displacement (zero for a push-pull pair).

Run: ``PYTHONPATH=. python tools/measure_actuator_couplings.py`` (about 30 s).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

import tefcore.model.station_terms as st
from tefcore.config.io import load_config
from tefcore.paper.fig6_calibration import CONFLICT_POINTS, _least_stable, fig6_ratio
from tefcore.structure.blade import rotor_units

ORIGINAL = st.flap_moments


def patch(kappa: float = 0.0, first_moment: float = 0.0, per_span: float = 0.0):
    """Add the torsion coupling ``kappa`` and the chordwise first moment to the flap terms.

    ``per_span``: ``I_a / b_f`` in rotor units (``m0 R^2``); ``first_moment``:
    ``S_a / b_f`` in rotor units (``m0 R``).
    """
    def flap_moments(ih, sf, eta, x, th, th_dd, wdd, dl, dld, dldd, *, slope, v=0.0,
                     lag_slope=0.0, lag_accel=0.0, lag_slope_rate=0.0, slope_rate=0.0,
                     omega=None, sin=np.sin, cos=np.cos):
        row, blade = ORIGINAL(ih, sf, eta, x, th, th_dd, wdd, dl, dld, dldd, slope=slope, v=v,
                              lag_slope=lag_slope, lag_accel=lag_accel,
                              lag_slope_rate=lag_slope_rate, slope_rate=slope_rate,
                              omega=omega, sin=sin, cos=cos)
        c, s = cos(th), sin(th)
        c_t, s_a = kappa * per_span, first_moment
        row["flap inertial coupling to torsion"] = \
            row["flap inertial coupling to torsion"] + c_t * th_dd
        row["flap inertial coupling to bending"] = \
            row["flap inertial coupling to bending"] - s_a * (lag_accel * c + wdd * s)
        row["flap centrifugal"] = row["flap centrifugal"] + s_a * c * v
        blade = blade + [("flap inertial coupling to torsion", "phi", c_t * dldd),
                         ("flap inertial coupling to bending", "v", -s_a * c * dldd),
                         ("flap inertial coupling to bending", "w", -s_a * s * dldd),
                         ("flap centrifugal", "v", s_a * c * dl)]
        return row, blade
    return flap_moments


def measure(cfg, name, **kw):
    st.flap_moments = patch(**kw)
    try:
        row = {"case": name, "Fig. 6 / input": round(fig6_ratio(cfg), 3)}
        for point, over in CONFLICT_POINTS.items():
            r = _least_stable(cfg.with_overrides(over))
            row[point] = f"{r['real part /rev']:+.2f} ({r['least stable root']}, " \
                         f"{r['frequency /rev']:.1f}/rev)"
        return row
    finally:
        st.flap_moments = ORIGINAL


def main():
    cfg = load_config("mdart-fig6")
    units = rotor_units(cfg.rotor, cfg.blade)
    i_a, span = cfg.actuator.reflected_inertia, cfg.flap.span * cfg.rotor.radius
    per_span = units.inertia(i_a) / cfg.flap.span
    shift = i_a * cfg.rotor.rotor_speed**2
    rows = [measure(cfg, "as modelled (I_a on delta** only)")]
    for sign, what in ((-1, "sliding parts"), (1, "turning parts")):
        c = cfg.with_overrides({"actuator.stiffness": cfg.actuator.stiffness + sign * shift})
        rows.append(measure(c, f"centrifugal {sign * 100 * shift / cfg.actuator.stiffness:+.1f} % "
                               f"of k_a ({what})"))
    for kappa in (-0.5, 0.5, 1.0):
        rows.append(measure(cfg, f"torsion coupling kappa = {kappa:+.1f}", kappa=kappa,
                            per_span=per_span))
    for arm_in in (0.6,):
        s_a = i_a / (arm_in * 0.0254)                      # kg m, whole flap
        s_rotor = s_a / (units.mass_per_length * units.radius**2) / cfg.flap.span
        for sign in (-1, 1):
            rows.append(measure(cfg, f"chordwise first moment {sign * s_a / span * 1e3:+.1f} g "
                                     f"(per span, arm {arm_in} in)",
                                first_moment=sign * s_rotor))
    scaled = load_config("mdart").with_overrides({"flap.inertia_cg": 3.5 * 0.24 * 0.0254**2
                                                  / 0.3048 * 0.45359237})
    rows.append(measure(scaled, "mdart with flap.inertia_cg x 3.5 (reaches Fig. 6 too)"))
    with pd.option_context("display.width", 250, "display.max_colwidth", 60):
        print(pd.DataFrame(rows).to_string(index=False))


if __name__ == "__main__":
    main()
