"""Count whole-/rev steps of tracked frequencies in a reproduction's figure tables.

Run: ``python tools/frequency_jumps.py OUT [OUT2 ...]`` (folders written by
``tefcore reproduce``).

A Floquet frequency is continuous along a root, so a step of a name's
``frequency_tracked`` between neighbouring points of one ``track`` that departs
from the slope of the steps on either side (each under 1/2 /rev, on the same
track, agreeing within 1/4 over the step and predicting under 1/2 /rev for it)
by a whole number of /rev (within 0.3, not 0) is a convention jump left in the
curve.  The slope is per unit of
the parameter, so an unevenly refined grid does not read a steep stretch as a
jump (comparing a step with its neighbours' sizes would count Fig. 9's TEF
falling 0.8 /rev over a 0.02 step between 0.005 steps).
Printed per figure table and in total, one column per folder, with the first
few steps of the last folder.  Used to measure the rule of
:func:`tefcore.modes.matching.continuous_frequency` (docs/theory.md 9.4).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd


def isolated_steps(table: pd.DataFrame) -> list[tuple]:
    """(name, x, f before, f after) of each whole-/rev step in one table."""
    if "frequency_tracked" not in table or table["frequency_per_rev"].isna().all():
        return []
    t = table[(table["status"] == "ok") & table["label"].notna()]
    out = []
    for name, g in t.groupby("label"):
        g = g.sort_values("value_si")
        track = g["track"].to_numpy()
        f = g["frequency_tracked"].to_numpy(float)
        x = g["value_si"].to_numpy(float)
        h, d = np.diff(x), np.diff(f)
        same = track[1:] == track[:-1]
        for i in range(d.size):
            if not same[i] or h[i] <= 0:
                continue
            sides = [d[j] / h[j] for j in (i - 1, i + 1)
                     if 0 <= j < d.size and same[j] and h[j] > 0 and abs(d[j]) < 0.5]
            # a step whose neighbours predict 1/2 /rev or more is not resolved:
            # which whole number it is off cannot be told
            if (len(sides) < 2 or np.ptp(sides) * h[i] >= 0.25
                    or abs(np.mean(sides) * h[i]) >= 0.5):
                continue
            r = d[i] - np.mean(sides) * h[i]
            if round(r) != 0 and abs(r - round(r)) <= 0.3:
                out.append((name, x[i], round(f[i], 3), round(f[i + 1], 3)))
    return out


def main(argv=None) -> int:
    folders = [Path(a) for a in (argv if argv is not None else sys.argv[1:])]
    if not folders:
        print(__doc__.splitlines()[2].strip(), file=sys.stderr)
        return 2
    files = sorted(p.relative_to(folders[0]) for p in folders[0].glob("*/*_modes.csv"))
    totals = [0] * len(folders)
    for rel in files:
        found = [isolated_steps(pd.read_csv(f / rel)) if (f / rel).exists() else []
                 for f in folders]
        for i, steps in enumerate(found):
            totals[i] += len(steps)
        print(f"{rel.name:28s} " + " ".join(f"{len(s):4d}" for s in found),
              found[-1][:3] if found[-1] else "")
    print(f"{'total':28s} " + " ".join(f"{t:4d}" for t in totals))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
