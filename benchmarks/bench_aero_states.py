"""Cost of a stability point with each aerodynamic option, MDART.

Run: ``python benchmarks/bench_aero_states.py [repeats]``.  For hover and
mu = 0.3 with the imbalanced flap (``c_cg/c_f = 0.33``) it prints, per option
(quasi-steady, unsteady airloads, dynamic inflow, both), the median, min and
max over ``repeats`` runs (default 7, after one warm-up run) of a cold
stability point (``stability(cfg)``: blade modes, trim, linearisation,
Floquet), the number of states of the Floquet analysis, and the trim and
Floquet parts at mu = 0.3.  ``time.perf_counter``; the load average of the
machine is printed before and after, since the VM is shared.
"""

import os
import statistics
import sys
import time

from tefcore.config.io import load_config
from tefcore.linear.stability import linear_system, stability
from tefcore.model.coupled import coupled_model
from tefcore.trimming.trim import initial_collective, trim

OPTIONS = {
    "quasi-steady": {},
    "unsteady": {"model.aero": "unsteady"},
    "dynamic inflow": {"model.inflow": "dynamic"},
    "unsteady + dynamic": {"model.aero": "unsteady", "model.inflow": "dynamic"},
}


def timed(fn, repeat):
    fn()                                                  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times), max(times)


def main(repeat=7):
    print(f"load average before: {os.getloadavg()}")
    base = load_config("mdart").with_overrides({"flap.cg_offset": 0.33})
    for mu in (0.0, 0.3):
        print(f"mu = {mu}: median (min - max) of {repeat} cold stability points")
        for name, over in OPTIONS.items():
            cfg = base.with_overrides({"flight.advance_ratio": mu, **over})
            med, lo, hi = timed(lambda c=cfg: stability(c), repeat)
            res = stability(cfg)
            n = res.system.n_states
            line = (f"  {name:<20s} {1e3 * med:8.1f} ms ({1e3 * lo:.1f} - {1e3 * hi:.1f}), "
                    f"{n} states")
            if mu:
                model = coupled_model(cfg, collective=initial_collective(cfg))
                t_trim = timed(lambda m=model: trim(m), max(3, repeat // 2))[0]
                tr = trim(model)
                system = linear_system(tr)
                t_floq = timed(lambda s=system: s.modes(n_steps=72, n_sub=4, shapes=True,
                                                        on_inaccurate="raise"),
                               max(3, repeat // 2))[0]
                line += f"; trim {1e3 * t_trim:.0f} ms, Floquet {1e3 * t_floq:.0f} ms"
            print(line, flush=True)
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
