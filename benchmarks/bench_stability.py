"""Median time of one stability point (trim + linearisation + Floquet), MDART.

Run: ``python benchmarks/bench_stability.py``. Prints medians of 15 runs
(after one second of warm-up runs) for a hover point and a mu = 0.3 point (9 blade modes
+ TEF), each from scratch: finite-element blade modes, coupled model, trim,
linearisation and Floquet (eigen)analysis; with the time of the first two
parts alone. Targets (issue 4): hover <= 10 ms, mu = 0.3 <= 50 ms.
The monodromy against a naive solve_ivp is in ``bench_floquet.py``.
"""

import statistics
import time

from tefcore.config import load_config
from tefcore.coupled import coupled_model
from tefcore.stability import stability
from tefcore.trim import initial_collective, trim


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


def main():
    base = load_config("mdart")
    for mu in (0.0, 0.3):
        cfg = base.with_overrides({"flight.advance_ratio": mu})
        full = median_ms(lambda c=cfg: stability(c))
        warm_start = stability(cfg).trim_result
        warm = median_ms(lambda c=cfg, w=warm_start: stability(c, trim_result=w))
        model = coupled_model(cfg, collective=initial_collective(cfg))
        modes = median_ms(lambda c=cfg: coupled_model(c, collective=initial_collective(c)))
        only_trim = median_ms(lambda m=model: trim(m))
        print(f"mu = {mu:.1f}: stability point median {full[0]:5.1f} ms "
              f"(min {full[1]:.1f}, max {full[2]:.1f}) = FE blade modes + coupled model "
              f"{modes[0]:.1f} ms + trim {only_trim[0]:.1f} ms + linearisation/Floquet; "
              f"warm-started (sweep) {warm[0]:.1f} ms")


if __name__ == "__main__":
    main()
