"""Cost of the process settings of :mod:`tefcore.runtime` in a fresh process.

Run: ``python benchmarks/bench_runtime.py [--repeat N] [--path DIR]``.  Each
of ``N`` fresh interpreters (``--path`` prepended to ``PYTHONPATH``: compare
two checkouts) times

* ``import tefcore`` alone,
* the first ``tefcore.linear.stability.stability`` call of the process (MDART,
  mu = 0.3, configuration loaded beforehand), and
* the median of the next 10 calls,

each as wall time and as CPU time of the process (``first_cpu``,
``next_cpu``: all threads; less sensitive than wall time to other work on a
shared machine),

once as a user's script would (``import tefcore`` and nothing else) and once
after ``tefcore.runtime.apply_defaults()`` (what the CLI, the sweep workers
and the notebooks do).  It prints the medians over the interpreters, with
min and max.  Speed is measured here, not in a timed test.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

CODE = r"""
import json, statistics, sys, time
t0 = time.perf_counter()
import tefcore
t_import = time.perf_counter() - t0
if sys.argv[1] == "defaults":
    from tefcore.runtime import apply_defaults
    apply_defaults()
from tefcore.config.io import load_config
from tefcore.linear.stability import stability
cfg = load_config("mdart").with_overrides({"flight.advance_ratio": 0.3})
t0, c0 = time.perf_counter(), time.process_time()
stability(cfg)
t_first, c_first = time.perf_counter() - t0, time.process_time() - c0
times, cpu = [], []
for _ in range(10):
    t0, c0 = time.perf_counter(), time.process_time()
    stability(cfg)
    times.append(time.perf_counter() - t0)
    cpu.append(time.process_time() - c0)
print(json.dumps({"import": t_import, "first": t_first, "next": statistics.median(times),
                  "first_cpu": c_first, "next_cpu": statistics.median(cpu)}))
"""

# the checkout of 84ceab7 (settings applied by `import tefcore`) has no
# config_io.load_config at the top, nor runtime.apply_defaults to call again
CODE_OLD = CODE.replace("from tefcore.config.io import", "from tefcore.config.sections import")


def run(mode: str, repeat: int, path: str | None, old: bool) -> dict[str, list[float]]:
    env = dict(os.environ)
    if path:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [path, env.get("PYTHONPATH")]))
    out: dict[str, list[float]] = {"import": [], "first": [], "next": [], "first_cpu": [],
                                   "next_cpu": []}
    empty = tempfile.mkdtemp()     # the working directory is first on sys.path: no checkout
    for _ in range(repeat):
        res = subprocess.run([sys.executable, "-c", CODE_OLD if old else CODE, mode], env=env,
                             capture_output=True, text=True, check=True, cwd=empty)
        for k, v in json.loads(res.stdout.strip().splitlines()[-1]).items():
            out[k].append(1e3 * v)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=7, help="fresh interpreters per case")
    ap.add_argument("--path", default=None, help="checkout to put first on PYTHONPATH")
    ap.add_argument("--old", action="store_true",
                    help="the checkout applies the settings at import (tefcore <= 84ceab7)")
    args = ap.parse_args()
    modes = ("plain",) if args.old else ("plain", "defaults")
    print(f"MDART mu = 0.3, {args.repeat} fresh interpreters: median (min - max) [ms]; "
          f"load average {os.getloadavg()[0]:.2f}", flush=True)
    for mode in modes:
        res = run(mode, args.repeat, args.path, args.old)
        print(f"  {mode}:", flush=True)
        for k, v in res.items():
            print(f"    {k:<8s}{statistics.median(v):8.1f}  ({min(v):.1f} - {max(v):.1f})")


if __name__ == "__main__":
    main()
