"""Count whole-/rev steps of tracked frequencies in a reproduction's figure tables.

Run: ``python tools/frequency_jumps.py OUT [OUT2 ...]`` (folders written by
``tefcore reproduce``).

A Floquet frequency is continuous along a root, so a step of a name's
``frequency_tracked`` between neighbouring points of one ``track`` that lies
within 0.3 of a whole number of /rev (and is not 0), while both neighbouring
steps on the track are under half of it, is a convention jump left in the
curve (an *isolated* step: a steep curve has large neighbouring steps too).
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
    """(name, x, f before, f after) of each isolated whole-/rev step in one table."""
    if "frequency_tracked" not in table or table["frequency_per_rev"].isna().all():
        return []
    t = table[(table["status"] == "ok") & table["label"].notna()]
    out = []
    for name, g in t.groupby("label"):
        g = g.sort_values("value_si")
        track = g["track"].to_numpy()
        f = g["frequency_tracked"].to_numpy(float)
        x = g["value_si"].to_numpy(float)
        steps = np.diff(f)
        same = track[1:] == track[:-1]
        for i, step in enumerate(steps):
            k = round(step)
            if not same[i] or k == 0 or abs(step - k) > 0.3:
                continue
            near = [abs(steps[j]) for j in (i - 1, i + 1) if 0 <= j < len(steps) and same[j]]
            if near and max(near) < 0.5 * abs(step):
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
