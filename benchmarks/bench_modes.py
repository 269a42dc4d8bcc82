"""Median time to build the MDART modes (20 elements, 9 modes), both hub models.

Run: ``python benchmarks/bench_modes.py``. Prints the median and quartiles of
several repeats of assembly + eigenanalysis + labelling, and the split, for
the equivalent hub and the multiple-load-path hub (three joined beams, pitch
link and snubber; the pitch link couples the flap-lag and torsion blocks).
Target: median <= 20 ms for the equivalent hub.
"""

import statistics
import time

from tefcore.config.io import load_config
from tefcore.structure.blade import blade_model, blade_modes
from tefcore.structure.fem import beam_modes


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
    base = load_config("mdart").with_overrides({"model.n_elements": 20, "model.n_modes": 9})
    for hub in ("equivalent", "multiple_load_path"):
        cfg = base.with_overrides({"hub.model": hub})
        beam = blade_model(cfg)
        print(f"hub.model = {hub!r}")
        for name, fn in [("build MDART modes (assemble + eigen + label)",
                          lambda c=cfg: blade_modes(c)),
                         ("  assemble only", lambda c=cfg: blade_model(c)),
                         ("  eigen + label only", lambda b=beam: beam_modes(b, 9))]:
            med, q1, q3 = timed(fn)
            print(f"{name:48s} median {med:7.2f} ms  (IQR {q1:.2f}-{q3:.2f} ms)")


if __name__ == "__main__":
    main()
