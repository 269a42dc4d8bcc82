"""The speed goals, each measured with its peer in one run, with the load and a verdict.

Run: ``python benchmarks/bench_goals.py [--repeat N] [--reproduce] [--kernel K]``.

Goals:

(a) one mu = 0.3 stability point (MDART, flap CG offset 0.33 chord: 9 blade
    modes and the flap, 20 states; trim, linearisation, Floquet analysis and
    the naming of its roots) <= 0.5 x the peer: scipy's ``solve_ivp`` (DOP853,
    ``rtol = 1e-8``) integrating the monodromy matrix of the same linearised
    system, all ``n^2`` columns as one vectorised ODE, ``A(psi)`` from
    precomputed Fourier coefficients of ``M, C, K``;
(b) a hover point <= 3 ms;
(c) every claim on the default rotor (``tefcore.paper.claims.validate_all()``
    in a fresh process, one job, imports included) <= 7 s CPU (stretch 5 s);
(d) ``tefcore reproduce --out DIR`` as the README runs it <= 240 s CPU and
    <= 600 MiB peak memory over its process tree (opt-in, ``--reproduce``:
    minutes);
(e) ``tefcore stability`` <= 1.6 x the wall time of
    ``python -c "import numpy, scipy.linalg"`` (fresh processes, interleaved).

Times are CPU time of this process (``time.process_time``) for (a), (b),
medians of ``--repeat`` runs after a warm-up, the peer measured in the same
process between the same warm-ups; whole commands are medians of interleaved
fresh processes (their CPU from ``RUSAGE_CHILDREN``).  The machine's load
(``/proc/loadavg``, 1/5/15 min) is printed before and after every goal: on a
shared 2-core machine a figure is only comparable with one measured at a
similar load.  Speed is measured here, never in a timed test.

``--kernel`` sets ``TEFCORE_STATION_KERNEL`` (:mod:`tefcore.model.station_kernel`)
for this process and the commands it times; the Jacobian line compares the
kernels where numba is installed.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import scipy.integrate

from tefcore.config.io import load_config  # noqa: E402
from tefcore.linear.stability import linear_system, stability  # noqa: E402
from tefcore.model.coupled import coupled_model  # noqa: E402
from tefcore.runtime import apply_defaults  # noqa: E402
from tefcore.trimming.trim import initial_collective, trim  # noqa: E402

TWO_PI = 2 * np.pi
POINT = {"flight.advance_ratio": 0.3, "flap.cg_offset": 0.33}


def load() -> str:
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def median_cpu_ms(fn, repeat, warmup=2):
    """Median CPU time [ms] of ``repeat`` calls after ``warmup`` calls."""
    for _ in range(warmup):
        fn()
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return 1e3 * statistics.median(times)


def line(goal, measured, peer="", ok=None, before=""):
    v = "" if ok is None else ("met" if ok else "NOT met")
    print(f"  {goal:<46s} {measured:>12s} {peer:>24s}  load {before} -> {load()}  {v}",
          flush=True)


class Peer:
    """``solve_ivp`` (DOP853) monodromy of a :class:`SecondOrderSystem`, vectorised."""

    def __init__(self, system):
        samples = np.stack([system.m, system.c, system.k], axis=1)      # (N, 3, n, n)
        n_az = samples.shape[0]
        c = np.fft.rfft(samples, axis=0) / n_az
        k = np.arange(c.shape[0])
        w = np.where((k == 0) | ((n_az % 2 == 0) & (k == n_az // 2)), 1.0, 2.0)
        self.coef = (c * w[:, None, None, None]).reshape(c.shape[0], -1)
        self.k = k
        self.n = system.m.shape[-1]

    def a(self, psi):
        n = self.n
        m, c, kk = np.real(np.exp(1j * self.k * psi) @ self.coef).reshape(3, n, n)
        lower = -np.linalg.solve(m, np.concatenate([kk, c], axis=1))
        top = np.concatenate([np.zeros((n, n)), np.eye(n)], axis=1)
        return np.concatenate([top, lower], axis=0)

    def monodromy(self, rtol=1e-8):
        size = 2 * self.n

        def rhs(t, y):
            return (self.a(t) @ y.reshape(size, size)).ravel()

        sol = scipy.integrate.solve_ivp(rhs, (0.0, TWO_PI), np.eye(size).ravel(),
                                        method="DOP853", rtol=rtol, atol=1e-2 * rtol)
        return sol.y[:, -1].reshape(size, size)


def point_goals(args):
    base = load_config("mdart")
    cfg = base.with_overrides(POINT)
    hover = base.with_overrides({"flight.advance_ratio": 0.0})
    print(f"\n(a), (b): points, CPU medians of {args.repeat} (the peer of "
          f"{max(5, args.repeat // 3)})")
    before = load()
    system = stability(cfg).system
    peer = Peer(system)
    t_peer = median_cpu_ms(peer.monodromy, max(5, args.repeat // 3), warmup=1)
    t_point = median_cpu_ms(lambda: stability(cfg), args.repeat)
    line("(a) mu = 0.3 point <= 0.5 x peer (naming in)", f"{t_point:.1f} ms",
         f"{t_peer:.0f} ms ({t_point / t_peer:.3f} x)", t_point <= 0.5 * t_peer, before)
    before = load()
    t_plain = median_cpu_ms(lambda: stability(cfg, identity=False), args.repeat)
    line("    the same without the naming", f"{t_plain:.1f} ms",
         f"{t_peer:.0f} ms ({t_plain / t_peer:.3f} x)", None, before)
    before = load()
    stability(hover)
    t_hover = median_cpu_ms(lambda: stability(hover), args.repeat)
    line("(b) hover point <= 3 ms", f"{t_hover:.1f} ms", "", t_hover <= 3.0, before)
    return t_point


def breakdown(args):
    """Where a mu = 0.3 point goes, and the Jacobian by kernel."""
    from tefcore.model import station_kernel
    from tefcore.model.jacobian import exact_jacobian
    from tefcore.trimming.newton_matrix import inflow_tangents

    cfg = load_config("mdart").with_overrides(POINT)
    model = coupled_model(cfg, collective=initial_collective(cfg))
    tr = trim(model)
    print(f"\nwhere a mu = 0.3 point goes (CPU medians of {args.repeat})")
    before = load()
    t_trim = median_cpu_ms(lambda: trim(model), args.repeat)
    line("trim (its Newton matrix at the first guess in)", f"{t_trim:.1f} ms", "", None, before)
    before = load()
    t_lin = median_cpu_ms(lambda: linear_system(trim(model)), args.repeat) - t_trim
    line("linearisation (the Jacobian at the solution)", f"{t_lin:.1f} ms", "", None, before)

    def floquet():
        s = linear_system(tr)
        return s.modes(n_steps=cfg.model.n_floquet_steps, n_sub=1, shapes=True,
                       on_inaccurate="raise", participation=True)

    before = load()
    t_fl = median_cpu_ms(floquet, args.repeat)
    line("Floquet analysis with participation", f"{t_fl:.1f} ms", "", None, before)
    y, yd, ydd, inflow = tr.linear_point(tr.psi)
    tang = inflow_tangents(model, tr.inflow.mean_induced, tr.psi)
    kernels = ["numpy"] + (["numba"] if station_kernel._numba_available() else [])
    saved = os.environ.get(station_kernel.KERNEL_ENV)
    times = {}
    for kernel in kernels:
        os.environ[station_kernel.KERNEL_ENV] = kernel
        before = load()
        times[kernel] = median_cpu_ms(lambda: exact_jacobian(
            model, tr.psi, y, yd, ydd, tr.controls, inflow, inflow_tangents=tang),
            3 * args.repeat)
        peer = "" if kernel == "numpy" else f"numpy {times['numpy'] / times[kernel]:.2f} x"
        line(f"one exact Jacobian, {kernel} station kernel", f"{times[kernel]:.2f} ms", peer,
             None, before)
    if saved is None:
        os.environ.pop(station_kernel.KERNEL_ENV, None)
    else:
        os.environ[station_kernel.KERNEL_ENV] = saved


def _run(cmd, env=None):
    """Wall and CPU [s] of a whole command (with its children)."""
    import resource

    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, cwd=tempfile.gettempdir(), env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def command_goals(args):
    py = sys.executable
    before = load()
    print(f"\n(c), (e): whole commands in fresh processes (medians of {args.runs}, interleaved)")
    claims = [py, "-c", "from tefcore.runtime import apply_defaults; apply_defaults(); "
              "from tefcore.paper.claims.validation import validate_all; validate_all(n_jobs=1)"]
    cpu = [_run(claims)[1] for _ in range(args.runs)]
    t_claims = statistics.median(cpu)
    line("(c) every claim, one job: <= 7 s CPU (5 s)", f"{t_claims:.1f} s CPU",
         f"runs {min(cpu):.1f}-{max(cpu):.1f} s", t_claims <= 7.0, before)
    before = load()
    cmd, peer = [py, "-m", "tefcore", "stability"], [py, "-c", "import numpy, scipy.linalg"]
    _run(cmd), _run(peer)                                   # warm the file caches
    ta, tb = [], []
    for _ in range(args.runs):
        ta.append(_run(cmd)[0])
        tb.append(_run(peer)[0])
    ratio = statistics.median([a / b for a, b in zip(ta, tb, strict=True)])
    line("(e) `tefcore stability` <= 1.6 x peer (wall)", f"{statistics.median(ta):.2f} s",
         f"{statistics.median(tb):.2f} s ({ratio:.2f} x)", ratio <= 1.6, before)


def _tree_peak(proc, out):
    """Largest sum of the resident memory of ``proc`` and its descendants [bytes],
    sampled every 50 ms until it ends (psutil)."""
    import psutil

    try:
        root = psutil.Process(proc.pid)
    except psutil.NoSuchProcess:
        return
    while proc.poll() is None:
        total = 0
        try:
            for p in [root, *root.children(recursive=True)]:
                try:
                    total += p.memory_info().rss
                except psutil.NoSuchProcess:
                    pass
        except psutil.NoSuchProcess:
            break
        out[0] = max(out[0], total)
        time.sleep(0.05)


def reproduce_goal():
    import resource

    before = load()
    print("\n(d) `tefcore reproduce --out DIR` as the README runs it (once)")
    out = os.path.join(tempfile.mkdtemp(), "out")
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "tefcore", "reproduce", "--out", out],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            cwd=tempfile.gettempdir())
    peak = [0]
    watcher = threading.Thread(target=_tree_peak, args=(proc, peak))
    watcher.start()
    rc = proc.wait()
    watcher.join()
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    largest = r1.ru_maxrss / 1024
    line("reproduce <= 240 s CPU", f"{cpu:.0f} s CPU", f"{wall:.0f} s wall, exit {rc}",
         rc == 0 and cpu <= 240, before)
    line("  peak memory of the tree <= 600 MiB", f"{peak[0] / 2**20:.0f} MiB",
         f"largest process {largest:.0f} MiB", peak[0] <= 600 * 2**20, before)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=15, help="timed calls per median (a, b)")
    ap.add_argument("--runs", type=int, default=5, help="fresh processes per median (c, e)")
    ap.add_argument("--reproduce", action="store_true",
                    help="also time `tefcore reproduce` (d; minutes)")
    ap.add_argument("--kernel", choices=("numpy", "numba", "auto"),
                    help="TEFCORE_STATION_KERNEL for this run and its commands")
    ap.add_argument("--no-breakdown", action="store_true", help="skip where a point goes")
    args = ap.parse_args()
    if args.kernel:
        os.environ["TEFCORE_STATION_KERNEL"] = args.kernel
    apply_defaults()
    kernel = os.environ.get("TEFCORE_STATION_KERNEL", "numpy")
    print(f"tefcore speed goals; station kernel {kernel}; load {load()}")
    point_goals(args)
    if not args.no_breakdown:
        breakdown(args)
    command_goals(args)
    if args.reproduce:
        reproduce_goal()
    else:
        print("\n((d) `tefcore reproduce`: --reproduce)")
    print(f"\nload at the end {load()}")


if __name__ == "__main__":
    main()
