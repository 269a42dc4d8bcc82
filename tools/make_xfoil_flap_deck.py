"""Generate tefcore/data/naca0012_flap35_xfoil.c81 with XFOIL (viscous panel method).

A C81 flap deck (docs/c81_format.md) of a NACA 0012 with a 35 % chord
trailing-edge flap whose hinge is 29 % of the flap chord behind its nose (the
MDART flap of the paper's Table 1), computed with Drela's XFOIL 6.99:

* geometry: XFOIL's NACA 4-digit generator (``NACA 0012``), flap deflected with
  ``GDES FLAP`` about the flap NOSE (x = 0.65, mid-thickness, y/t = 0.5), then
  ``PANE`` (160 panels).  This is tefcore's idealisation of the sealed
  balanced flap (docs/theory.md 3.5): the outer contour kinks at the flap
  nose; the balance nose sits in a sealed cove, so the overhang enters through
  the moment reference of the hinge moment, not through the contour.
* flow: viscous (``VISC``), free transition (Ncrit 9), ``ITER 100``;
  Reynolds number of the 10 in (0.254 m) MDART chord at sea level (ISA),
  ``Re = 5.918e6 M``; the M = 0 row is incompressible at the Re of M = 0.2.
  Karman-Tsien compressibility (XFOIL's own) up to M = 0.7.
* C_l, C_d, C_m (quarter chord) as XFOIL prints them; C_h and C_lf by
  integrating XFOIL's surface Cp (``CPWR``) over the flap (points whose
  position rotated back by -delta about the nose lies aft of the nose):
  C_lf = normal force on the flap (perpendicular to the blade chord, up) /
  (q c), C_h = pressure moment about the hinge (the point 0.1015 c aft of the
  nose on the deflected flap's chord line), trailing edge down positive, /
  (q c^2) -- blade-chord normalisation as in tefcore.aero.thin_airfoil.
* unconverged points (XFOIL's viscous iteration) are filled by linear
  interpolation in alpha between converged neighbours of the same (M, delta),
  or by the nearest converged value at the ends of the alpha range; their
  number and places are written to the deck header.

Run (needs an XFOIL binary that does not trap floating-point exceptions; see
tools/build_xfoil.sh)::

    python tools/make_xfoil_flap_deck.py --xfoil /path/to/xfoil

Not run by the tests: the deck is generated once and committed.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import hashlib
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tefcore.aero.c81 import C81Deck, write_c81  # noqa: E402

FLAP_NOSE = 0.65            # 35 % chord flap (Table 1)
OVERHANG = 0.29             # hinge 29 % of the flap chord behind its nose (Table 1)
HINGE_ARM = OVERHANG * (1.0 - FLAP_NOSE)        # 0.1015 c
RE_PER_MACH = 1.225 * 340.294 * 0.254 / 1.7894e-5  # ISA sea level, c = 10 in: 5.918e6
ALPHAS = np.arange(-12.0, 16.0 + 1e-9, 1.0)
MACHS = np.array([0.0, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7])
DELTAS = np.array([-10.0, -6.0, -3.0, 0.0, 3.0, 6.0, 10.0])
N_PANEL = 160
NCRIT = 9.0
SWEEP_TIMEOUT = 40.0     # s per alpha sweep (a converging sweep takes < 2 s)


def _script(delta, mach, reynolds, alphas, tag):
    lines = ["PLOP", "G F", "", "NACA 0012", "PPAR", "N", str(N_PANEL), "", ""]
    if delta != 0.0:
        lines += ["GDES", "FLAP", f"{FLAP_NOSE}", "999", "0.5", f"{delta}", "", "EXEC", ""]
    lines += ["PANE", f"SAVE {tag}_geo.dat", "OPER", f"MACH {mach}", f"VISC {reynolds:.6g}",
              "VPAR", f"N {NCRIT}", "", "ITER 100", "PACC", f"{tag}_pol.txt", ""]
    for a in alphas:
        lines += [f"ALFA {a:g}", f"CPWR {tag}_{a:+06.1f}.cp"]
    lines += ["PACC", "", "QUIT"]
    return "\n".join(lines) + "\n"


def _polar(path):
    rows = {}
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if len(parts) >= 5:
            try:
                vals = [float(p) for p in parts[:5]]
            except ValueError:
                continue
            rows[round(vals[0], 3)] = vals[1:5]       # CL, CD, CDp, CM
    return rows


def _flap_loads(geo, cp, delta_deg, alpha_deg):
    """C_lf and C_h (blade chord) from surface Cp over the flap; also the pressure C_l."""
    d = math.radians(delta_deg)
    x, y = geo[:, 0], geo[:, 1]
    # position in the flap-fixed frame: rotate back by -delta (TE-down delta is clockwise)
    xb = FLAP_NOSE + (x - FLAP_NOSE) * math.cos(d) - y * math.sin(d)
    on_flap = xb > FLAP_NOSE
    xm, ym = 0.5 * (x[1:] + x[:-1]), 0.5 * (y[1:] + y[:-1])
    dx, dy = np.diff(x), np.diff(y)
    cpm = 0.5 * (cp[1:] + cp[:-1])
    fx, fy = -cpm * dy, cpm * dx               # -Cp n ds, n = (dy, -dx) outward (CCW nodes)
    panel_flap = on_flap[1:] & on_flap[:-1]
    xh = FLAP_NOSE + HINGE_ARM * math.cos(d)
    yh = -HINGE_ARM * math.sin(d)
    clf = float(np.sum(fy[panel_flap]))
    mz = np.sum(((xm - xh) * fy - (ym - yh) * fx)[panel_flap])
    a = math.radians(alpha_deg)               # lift: normal to the free stream
    return clf, float(-mz), float(np.sum(fy) * math.cos(a) - np.sum(fx) * math.sin(a))


def run_case(xfoil, delta, mach, workdir):
    reynolds = RE_PER_MACH * max(mach, 0.2)
    tag = f"d{delta:+05.1f}_m{mach:.2f}"
    out, timeouts = {}, []
    # two sweeps from alpha = 0 for continuation of the boundary-layer solution
    for part, alphas in (("up", ALPHAS[ALPHAS >= 0]), ("dn", ALPHAS[ALPHAS <= 0][::-1])):
        t = f"{tag}_{part}"
        try:
            proc = subprocess.run([xfoil], input=_script(delta, mach, reynolds, alphas, t),
                                  capture_output=True, text=True, cwd=workdir,
                                  timeout=SWEEP_TIMEOUT)
        except subprocess.TimeoutExpired:
            # XFOIL can loop without end past stall or in transonic flow: keep the
            # points it had converged and written (PACC and CPWR write as they go)
            timeouts.append(t)
        else:
            if proc.returncode != 0:
                raise RuntimeError(f"xfoil failed ({proc.returncode}) for {t}: "
                                   f"{proc.stderr[-500:]}")
        pol = _polar(workdir / f"{t}_pol.txt")
        geo = np.loadtxt(workdir / f"{t}_geo.dat", skiprows=1)
        for a in alphas:
            key = round(float(a), 3)
            if key not in pol or key in out:
                continue
            cp_file = workdir / f"{t}_{a:+06.1f}.cp"
            if not cp_file.exists():          # converged, then stopped before CPWR
                continue
            cp = np.loadtxt(cp_file, comments="#")
            if cp.shape[0] != geo.shape[0] or np.max(np.abs(cp[:, 0] - geo[:, 0])) > 1e-4:
                raise RuntimeError(f"Cp and geometry nodes differ for {t} alpha {a}")
            cl, cd, _, cm = pol[key]
            clf, ch, cl_p = _flap_loads(geo, cp[:, 1], delta, float(a))
            out[key] = (cl, cd, cm, ch, clf, cl_p)
    return out, timeouts


def _fill(values, converged):
    """Linear interpolation in alpha over unconverged points; nearest at the ends."""
    a = ALPHAS[converged]
    return np.interp(ALPHAS, a, values[converged])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--xfoil", default=os.environ.get("XFOIL", "xfoil"))
    p.add_argument("--out", default=str(ROOT / "tefcore" / "data" / "naca0012_flap35_xfoil.c81"))
    p.add_argument("--jobs", type=int, default=2, help="parallel XFOIL processes")
    args = p.parse_args(argv)
    banner = subprocess.run([args.xfoil], input="QUIT\n", capture_output=True, text=True).stdout
    version = next((ln.strip() for ln in banner.splitlines() if "XFOIL Version" in ln), "?")
    digest = hashlib.sha256(Path(args.xfoil if os.sep in args.xfoil else
                                 subprocess.run(["which", args.xfoil], capture_output=True,
                                                text=True).stdout.strip()).read_bytes())
    shape = (ALPHAS.size, MACHS.size, DELTAS.size)
    tables = {c: np.full(shape, np.nan) for c in ("cl", "cd", "cm", "ch", "clf")}
    filled, stopped, worst_cl = [], [], 0.0
    cases = [(k, j) for k in range(DELTAS.size) for j in range(MACHS.size)]
    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ProcessPoolExecutor(args.jobs) as pool:
        futures = {case: pool.submit(run_case, args.xfoil, float(DELTAS[case[0]]),
                                     float(MACHS[case[1]]), Path(tmp)) for case in cases}
        for (k, j), fut in futures.items():
            delta, mach = DELTAS[k], MACHS[j]
            res, timed_out = fut.result()
            stopped.extend(timed_out)
            conv = np.array([round(float(a), 3) in res for a in ALPHAS])
            if conv.sum() < 5:
                raise RuntimeError(f"only {conv.sum()} converged points at M={mach}, "
                                   f"delta={delta}")
            for i, name in enumerate(("cl", "cd", "cm", "ch", "clf")):
                vals = np.array([res.get(round(float(a), 3), (np.nan,) * 6)[i]
                                 for a in ALPHAS])
                tables[name][:, j, k] = _fill(vals, conv)
            for a, ok in zip(ALPHAS, conv, strict=True):
                if ok:
                    cl, cl_p = res[round(float(a), 3)][0], res[round(float(a), 3)][5]
                    worst_cl = max(worst_cl, abs(cl - cl_p))
                else:
                    filled.append(f"(M {mach:g}, d {delta:g}, a {a:g})")
            print(f"delta {delta:+5.1f} M {mach:.2f}: {conv.sum()}/{ALPHAS.size} converged",
                  flush=True)
    header = "\n".join([
        "GENERATED with XFOIL (viscous panel method, Drela) by tools/make_xfoil_flap_deck.py;",
        "computed data, NOT test data.",
        f"Solver: {version}, Debian source package xfoil 6.99.dfsg+1-3 rebuilt without the",
        "debug flags -finit-real=inf -ffpe-trap=invalid,zero (tools/build_xfoil.sh);",
        f"binary sha256 {digest.hexdigest()[:16]}.",
        "Section: NACA 0012 (XFOIL NACA generator; Abbott & von Doenhoff 1959), 160 panels.",
        "Flap: 35 % chord (nose at x/c 0.65), hinge 29 % of the flap chord behind the nose",
        "(x/c 0.7515) as the MDART flap of the paper's Table 1; contour deflected about the",
        "flap nose (GDES FLAP 0.65, y/t 0.5): sealed balance, tefcore theory 3.5.",
        f"Viscous, free transition Ncrit {NCRIT:g}; Re = {RE_PER_MACH:.4g} M (10 in chord, ISA sea",
        "level), M = 0 row incompressible at Re(M = 0.2); Karman-Tsien compressibility.",
        "C_l, C_d, C_m (1/4 chord) from XFOIL; C_lf (flap normal force) and C_h (about the",
        "hinge, TE down +) by integrating XFOIL's surface Cp over the flap; blade chord.",
        f"Cp integration reproduces XFOIL's C_l within {worst_cl:.4f} at every converged point.",
        f"Unconverged points filled ({len(filled)} of {ALPHAS.size * MACHS.size * DELTAS.size};"
        " alpha-interpolated):",
        *(" ".join(filled[i:i + 5]) for i in range(0, len(filled), 5)),
        f"Sweeps stopped after {SWEEP_TIMEOUT:g} s (XFOIL looping): "
        f"{', '.join(stopped) or 'none'}.",
        "Layout: tefcore flap deck, docs/c81_format.md.",
    ])
    deck = C81Deck("NACA0012 35%TEF XFOIL", {c: ALPHAS for c in tables},
                   {c: MACHS for c in tables}, tables, delta=DELTAS, header=header)
    out = write_c81(deck, args.out)
    print(f"wrote {out}; {len(filled)} filled points")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
