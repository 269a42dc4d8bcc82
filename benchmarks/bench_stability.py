"""Median time of one stability point (trim + linearisation + Floquet), MDART.

Run: ``python benchmarks/bench_stability.py``. Prints medians of several runs
for a hover point and a mu = 0.3 point (9 blade modes + TEF), split into
trim and the rest. Targets (issue 4): hover <= 10 ms, mu = 0.3 <= 50 ms.
The monodromy against a naive solve_ivp is in ``bench_floquet.py``.
"""

import statistics
import time

from tefcore.config import load_config
from tefcore.coupled import coupled_model
from tefcore.stability import stability
from tefcore.trim import trim


def median_ms(fn, repeat=7):
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times), 1e3 * min(times), 1e3 * max(times)


def main():
    base = load_config("mdart")
    for mu in (0.0, 0.3):
        cfg = base.with_overrides({"flight.advance_ratio": mu})
        full = median_ms(lambda c=cfg: stability(c))
        warm_start = stability(cfg).trim_result
        warm = median_ms(lambda c=cfg, w=warm_start: stability(c, trim_result=w))
        model = coupled_model(cfg)
        only_trim = median_ms(lambda m=model: trim(m))
        print(f"mu = {mu:.1f}: stability point median {full[0]:7.1f} ms "
              f"(min {full[1]:.1f}, max {full[2]:.1f}); warm-started (sweep) "
              f"{warm[0]:.1f} ms; trim alone {only_trim[0]:.1f} ms")


if __name__ == "__main__":
    main()
