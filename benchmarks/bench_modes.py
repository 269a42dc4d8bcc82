"""Median time to build the MDART modes (20 elements, 9 modes).

Run: ``python benchmarks/bench_modes.py``. Prints the median and quartiles of
several repeats of assembly + eigenanalysis + labelling, and the split.
Target (issue 2): median <= 20 ms.
"""

import statistics
import time

from tefcore.blade import blade_model, blade_modes
from tefcore.config_io import load_config
from tefcore.structure import beam_modes


def timed(fn, repeat=30):
    fn()                                    # warm-up (imports, caches)
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    q = statistics.quantiles(out, n=4)
    return 1e3 * statistics.median(out), 1e3 * q[0], 1e3 * q[2]


def main():
    cfg = load_config("mdart").with_overrides({"model.n_elements": 20, "model.n_modes": 9})
    beam = blade_model(cfg)
    for name, fn in [("build MDART modes (assemble + eigen + label)", lambda: blade_modes(cfg)),
                     ("  assemble only", lambda: blade_model(cfg)),
                     ("  eigen + label only", lambda: beam_modes(beam, 9))]:
        med, q1, q3 = timed(fn)
        print(f"{name:48s} median {med:7.2f} ms  (IQR {q1:.2f}-{q3:.2f} ms)")


if __name__ == "__main__":
    main()
