"""Cost of identity by continuation: a point and a sweep, with and without.

Run: ``python benchmarks/bench_identity.py [--repeat N]``.

``stability(cfg)`` names every root by continuation in the blade-flap coupling
(:func:`tefcore.modes.continuation.continue_roots`); ``stability(cfg,
identity=False)`` names them by participation only.  Measured here, in one
process, as medians of ``--repeat`` runs of each, interleaved, after a warm-up: one point in hover
and at mu = 0.3 (the paper's imbalanced flap), with the eigenproblems the
continuation solved; and Fig. 9's sweep (11 points, mu = 0.3, no refinement)
both ways.  The goal: a sweep with identity by continuation costs at most 2x
one without.  The load average is printed before and after (2 shared cores:
compare only when it stays low).
"""

from __future__ import annotations

import argparse
import functools
import os
import statistics
import time

import numpy as np

from tefcore.linear.stability import stability
from tefcore.paper.figures.catalogue import figure_config
from tefcore.runtime import apply_defaults
from tefcore.sweeps.sweep import sweep


def load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def paired_medians(on_fn, off_fn, repeat):
    """Medians of `repeat` runs of each, interleaved (on, off, on, off, ...) so a
    change of the machine's load falls on both alike; one warm-up each first.
    Also the spread of the ratios of each adjacent pair (min, median, max): a
    load that moves during the run shows there, not as a shifted median."""
    on_fn()
    off_fn()
    on, off = [], []
    for _ in range(repeat):
        for fn, times in ((on_fn, on), (off_fn, off)):
            t0 = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t0)
    pairs = sorted(a / b for a, b in zip(on, off, strict=True))
    return statistics.median(on), statistics.median(off), (pairs[0], statistics.median(pairs),
                                                          pairs[-1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    apply_defaults()
    print(f"load average before: {load()}")
    cases = {"hover, c_cg 0.33": figure_config("fig16a").with_overrides(
                 {"flight.collective": 0.0}),
             "mu 0.3, c_cg 0.33 (Fig. 10's flap)": figure_config("fig10").with_overrides(
                 {"hub.pitch_link_stiffness": "400 lb/in"})}
    for name, cfg in cases.items():
        on, off, _ = paired_medians(lambda cfg=cfg: stability(cfg),
                                    lambda cfg=cfg: stability(cfg, identity=False), args.repeat)
        n = stability(cfg).identity.n_solves
        print(f"{name:38s} point with identity {1e3 * on:7.1f} ms, without {1e3 * off:7.1f} ms,"
              f" ratio {on / off:4.2f} ({n} eigenproblems on the path)")
    cfg = figure_config("fig9")
    values = list(np.round(np.arange(0.0, 0.41, 0.04), 2))
    kw = dict(progress=False, refine=False)
    on, off, spread = paired_medians(
        lambda: sweep(cfg, "flap.cg_offset", values, **kw),
        lambda: sweep(cfg, "flap.cg_offset", values,
                      point=functools.partial(stability, identity=False), **kw),
        args.repeat)
    ratio = on / off
    solves = [stability(cfg.with_overrides({"flap.cg_offset": float(v)})).identity.n_solves
              for v in values]
    print(f"{'Fig. 9 sweep, 11 points, mu 0.3':38s} with identity {on:6.2f} s, without "
          f"{off:6.2f} s, ratio {ratio:4.2f}: goal <= 2x {'met' if ratio <= 2 else 'NOT met'}")
    print(f"{'':38s} ratios of adjacent pairs: {spread[0]:.2f} / {spread[1]:.2f} / "
          f"{spread[2]:.2f} (min / median / max)")
    print(f"{'':38s} eigenproblems for the paths: {sum(solves)} ({min(solves)} to "
          f"{max(solves)} per point, eps = 0 included); continuation "
          f"{1e3 * (on - off) / len(values):.1f} ms per point")
    print(f"load average after: {load()}")


if __name__ == "__main__":
    main()
