"""Median time of one stability point (trim + linearisation + Floquet), MDART.

Run: ``python benchmarks/bench_stability.py``. For a hover point and a
mu = 0.3 point (9 blade modes + TEF) it prints medians of 15 runs (after one
second of warm-up runs), with min and max, of

* trim + Floquet: trim, linearisation and Floquet (eigen)analysis of a coupled
  model built beforehand -- what the targets name (hover <= 10 ms,
  mu = 0.3 <= 50 ms);
* the cold point: the same from the configuration alone, i.e. with the
  finite-element blade modes and the coupled model built first (what a
  single ``tefcore stability`` call costs), and its two first parts;
* a warm-started point (the previous trim as initial guess, as in a sweep).

The monodromy against a naive solve_ivp is in ``bench_floquet.py``.
"""

import statistics
import time

from tefcore.config.io import load_config
from tefcore.linear.stability import stability
from tefcore.model.coupled import coupled_model
from tefcore.trimming.trim import initial_collective, trim

TARGET_MS = {0.0: 10.0, 0.3: 50.0}


def median_ms(fn, repeat=15, warmup_s=1.0):
    # the first calls in a process run slower for about the first second
    # (measured: 6.3 against 4.6 ms for the FE modes on this VM), as in any
    # benchmark harness: warm up for a fixed time, at least three calls
    t_end, calls = time.perf_counter() + warmup_s, 0
    while calls < 3 or time.perf_counter() < t_end:
        fn()
        calls += 1
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times), 1e3 * min(times), 1e3 * max(times)


def line(text, timing, target=None):
    verdict = "" if target is None else (
        f"   target <= {target:g} ms: {'met' if timing[0] <= target else 'NOT met'}")
    print(f"  {text:<58s}{timing[0]:6.1f} ms  ({timing[1]:.1f} - {timing[2]:.1f}){verdict}")


def main():
    base = load_config("mdart")
    print("MDART, 9 blade modes + TEF: median of 15 runs (min - max)")
    for mu, target in TARGET_MS.items():
        cfg = base.with_overrides({"flight.advance_ratio": mu})
        model = coupled_model(cfg, collective=initial_collective(cfg))
        warm_start = stability(cfg).trim_result
        print(f"mu = {mu:.1f}")
        line("trim + Floquet (blade modes and coupled model built)",
             median_ms(lambda c=cfg, m=model: stability(c, model=m)), target)
        line("cold point (FE blade modes included)",
             median_ms(lambda c=cfg: stability(c)), target)
        line("  of which FE blade modes + coupled model",
             median_ms(lambda c=cfg: coupled_model(c, collective=initial_collective(c))))
        line("  of which trim", median_ms(lambda m=model: trim(m)))
        line("warm-started point (previous trim, as in a sweep)",
             median_ms(lambda c=cfg, w=warm_start: stability(c, trim_result=w)))


if __name__ == "__main__":
    main()
