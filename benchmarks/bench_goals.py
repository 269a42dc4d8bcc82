"""The speed goals of issue 15, each measured with its verdict, and a scaling table.

Run: ``python benchmarks/bench_goals.py [--quick] [--reproduce] [--repeat N]``.

Every goal is printed with the measured median (of ``--repeat`` runs after a
warm-up, in this process unless stated), the peer measured in the same
process where the goal names one, the ratio and a verdict (met / NOT met).
The machine's load average is printed before and after: on a shared 2-core
machine the figures are only comparable when it stays low.  Speed is
measured here, never in a timed test.

The peer is scipy's ``solve_ivp`` (DOP853) integrating the monodromy matrix of
the same linearised system -- the MDART rotor at mu = 0.3, 9 blade modes and
the flap, 20 states -- all ``n^2`` columns as one vectorised ODE of 400
unknowns, ``A(psi)`` from precomputed Fourier coefficients of ``M, C, K`` (the
cheapest right-hand side), ``rtol = 1e-10``, ``atol = 1e-12``; its exponents
from the eigenvalues of the monodromy matrix.  "At matched exponent accuracy"
loosens its ``rtol`` (half decades) to the loosest whose largest exponent error
is at most that of ``floquet_modes``, both against a reference (Magnus, 32 times
the steps).

Goals (issue 15): a mu = 0.3 point <= 0.15 x the peer; hover <= 3 ms; a point
inside a sweep <= 10 ms; ``tefcore stability`` in a fresh process <= 0.4 s;
``floquet_modes`` >= 10 x the peer at matched exponent accuracy; ``tefcore
reproduce`` <= 20 s on 2 cores (only with ``--reproduce``: it runs the
notebooks); a 40 x 40 stability map <= 30 s on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.integrate

from tefcore.config.io import load_config
from tefcore.floquet import floquet_modes
from tefcore.linear.stability import linear_system, stability
from tefcore.model.coupled import coupled_model
from tefcore.runtime import apply_defaults
from tefcore.structure import blade
from tefcore.trimming.trim import initial_collective, trim

TWO_PI = 2 * np.pi


def load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def median_ms(fn, repeat, warmup=2, setup=None):
    """Median [ms] of ``repeat`` timed calls (wall), after ``warmup`` calls."""
    for _ in range(warmup):
        if setup:
            setup()
        fn()
    times = []
    for _ in range(repeat):
        if setup:
            setup()
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times)


def verdict(ok: bool) -> str:
    return "met" if ok else "NOT met"


def line(goal, measured, peer="", ratio="", ok=None):
    v = "" if ok is None else verdict(ok)
    print(f"  {goal:<46s} {measured:>18s} {peer:>16s} {ratio:>11s}  {v}", flush=True)


# ------------------------------------------------------------------ the peer


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

    def monodromy(self, rtol):
        size = 2 * self.n

        def rhs(t, y):
            return (self.a(t) @ y.reshape(size, size)).ravel()

        sol = scipy.integrate.solve_ivp(rhs, (0.0, TWO_PI), np.eye(size).ravel(),
                                        method="DOP853", rtol=rtol, atol=1e-2 * rtol)
        return sol.y[:, -1].reshape(size, size)

    def exponents(self, rtol):
        return np.log(np.linalg.eigvals(self.monodromy(rtol)).astype(complex)) / TWO_PI


def exponent_error(eta, ref):
    """Largest distance of each reference exponent to the nearest of ``eta``
    (frequencies modulo 1/rev: the integer shift is not what is compared)."""
    d = eta[:, None] - ref[None, :]
    d = np.abs(d.real) + 1j * np.abs(np.mod(d.imag + 0.5, 1.0) - 0.5)
    return float(np.abs(d).min(axis=0).max())


# ------------------------------------------------------------------ goals


def goals(args):
    repeat = args.repeat
    base = load_config("mdart")
    cfg03 = base.with_overrides({"flight.advance_ratio": 0.3})
    hover = base.with_overrides({"flight.advance_ratio": 0.0})
    print(f"issue 15 goals, MDART (9 blade modes + TEF), medians of {repeat} runs; "
          f"load average before: {load()}")
    print(f"  {'goal':<46s} {'measured':>18s} {'peer':>16s} {'ratio':>11s}  verdict")

    # the peer and the system
    tr = trim(coupled_model(cfg03, collective=initial_collective(cfg03)))
    system = linear_system(tr)
    peer = Peer(system)
    t_peer = median_ms(lambda: peer.monodromy(1e-10), max(3, repeat // 3), warmup=1)

    # 1. a mu = 0.3 point from the configuration
    t_cold = median_ms(lambda: stability(cfg03), repeat, setup=blade._MODES_CACHE.clear)
    t_cached = median_ms(lambda: stability(cfg03), repeat)
    line("mu = 0.3 point <= 0.15 x peer (modes cached)", f"{t_cached:.1f} ms",
         f"{t_peer:.0f} ms", f"{t_cached / t_peer:.3f} x", t_cached <= 0.15 * t_peer)
    line("  same, blade modes computed too", f"{t_cold:.1f} ms", f"{t_peer:.0f} ms",
         f"{t_cold / t_peer:.3f} x", t_cold <= 0.15 * t_peer)

    # 2. hover
    t_hover = median_ms(lambda: stability(hover), repeat)
    t_hover_cold = median_ms(lambda: stability(hover), repeat, setup=blade._MODES_CACHE.clear)
    line("hover point <= 3 ms (modes cached)", f"{t_hover:.1f} ms", "", "", t_hover <= 3.0)
    line("  same, blade modes computed too", f"{t_hover_cold:.1f} ms", "", "",
         t_hover_cold <= 3.0)

    # 3. a point inside a sweep: warm-started from its neighbour, as sweep() does
    values = [f"{v:.2f} ft-lb/rad" for v in np.linspace(60.0, 160.0, 9)]
    cfgs = [cfg03.with_overrides({"actuator.stiffness": v}) for v in values]

    def chain():
        warm = None
        for c in cfgs:
            warm = stability(c, warm_start=warm).trim_result

    t_chain = median_ms(chain, max(3, repeat // 3), warmup=1) / len(cfgs)
    line("point inside a sweep <= 10 ms (mu = 0.3)", f"{t_chain:.1f} ms", "", "",
         t_chain <= 10.0)
    from tefcore.sweeps.sweep import sweep

    t0 = time.perf_counter()
    sweep(cfg03, "actuator.stiffness", values, progress=False, refine=False)
    t_sweep = 1e3 * (time.perf_counter() - t0) / len(values)
    line("  sweep() per point, tracking included", f"{t_sweep:.1f} ms", "", "")

    # 4. the CLI in a fresh process
    env = dict(os.environ)
    cmd = [sys.executable, "-m", "tefcore", "stability", "--set", "flight.advance_ratio=0.3"]
    times = []
    for _ in range(max(3, repeat // 3)):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True, env=env,
                       cwd=tempfile.gettempdir())
        times.append(time.perf_counter() - t0)
    t_cli = statistics.median(times)
    imp = subprocess.run([sys.executable, "-c", "import time; t = time.perf_counter(); "
                          "import tefcore.cli, tefcore.linear.stability; "
                          "print(time.perf_counter() - t)"], capture_output=True, text=True,
                         env=env, cwd=tempfile.gettempdir(), check=True)
    line("`tefcore stability` fresh process <= 0.4 s", f"{t_cli:.2f} s", "", "",
         t_cli <= 0.4)
    line("  of which imports (cli + stability)", f"{float(imp.stdout):.2f} s", "", "")

    # 5. floquet_modes against the peer at matched exponent accuracy
    n = system.n_dof
    ref = floquet_modes(system.state_matrix, n_steps=32 * 72, method="magnus",
                        shift_states=slice(0, n), atol=None).exponents

    def ours():
        return system.modes(n_steps=72, n_sub=1, shapes=True, on_inaccurate="raise")

    err_ours = exponent_error(ours().exponents, ref)
    t_ours = median_ms(ours, repeat)
    rtol = None
    for r in 10.0 ** -np.arange(3.0, 10.5, 0.5):
        if exponent_error(peer.exponents(r), ref) <= err_ours:
            rtol = r
            break
    if rtol is None:
        line("floquet_modes >= 10 x peer (matched accuracy)", f"{t_ours:.2f} ms",
             "unreached", "", False)
    else:
        t_match = median_ms(lambda: peer.monodromy(rtol), max(3, repeat // 3), warmup=1)
        line("floquet_modes >= 10 x peer (matched accuracy)", f"{t_ours:.2f} ms",
             f"{t_match:.1f} ms", f"{t_match / t_ours:.1f} x", t_match >= 10 * t_ours)
        print(f"    exponent error: floquet_modes {err_ours:.1e} /rev, peer at rtol "
              f"{rtol:.0e} {exponent_error(peer.exponents(rtol), ref):.1e} /rev")

    # 6. reproduce
    if args.reproduce:
        out = tempfile.mkdtemp()
        t0 = time.perf_counter()
        res = subprocess.run([sys.executable, "-m", "tefcore", "reproduce", "--out", out],
                             capture_output=True, text=True, env=env)
        t_rep = time.perf_counter() - t0
        line("`tefcore reproduce` <= 20 s on 2 cores (once)", f"{t_rep:.1f} s", "", "",
             res.returncode == 0 and t_rep <= 20.0)
    else:
        line("`tefcore reproduce` <= 20 s on 2 cores", "(--reproduce)", "", "")

    # 7. the 40 x 40 map
    from tefcore.sweeps.maps import stability_map

    size = 10 if args.quick else 40
    t0 = time.perf_counter()
    m = stability_map(cfg03, "actuator.stiffness",
                      [f"{v:.3f} ft-lb/rad" for v in np.linspace(60.0, 400.0, size)],
                      "flight.advance_ratio", list(np.linspace(0.05, 0.35, size)),
                      n_jobs=2, progress=False)
    t_map = time.perf_counter() - t0
    ok = int((m.table["status"] == "ok").sum())
    line(f"{size} x {size} map (k_a x mu) <= 30 s, 2 cores (once)", f"{t_map:.1f} s", "",
         f"{ok} ok", t_map <= 30.0 * (size / 40) ** 2)
    print(f"load average after: {load()}")


def breakdown(args):
    """Where the time of a point and of the CLI goes (for the goals not met)."""
    repeat = args.repeat
    base = load_config("mdart")
    print(f"\nwhere the time goes, medians of {repeat}; load average {load()}")
    for name, cfg in (("mu = 0.3", base.with_overrides({"flight.advance_ratio": 0.3})),
                      ("hover", base.with_overrides({"flight.advance_ratio": 0.0}))):
        stability(cfg)                                     # blade modes cached
        theta = initial_collective(cfg)
        t_point = median_ms(lambda c=cfg: stability(c), repeat)
        t_model = median_ms(lambda c=cfg, th=theta: coupled_model(c, collective=th), repeat)
        model = coupled_model(cfg, collective=theta)
        t_trim = median_ms(lambda m=model: trim(m), repeat)
        tr = trim(model)
        iterations = len(tr.history)

        def linearise(m=model):
            t = trim(m)
            return linear_system(t)

        t_lin = median_ms(linearise, repeat) - t_trim      # the Jacobian at the solution
        tr.final_blocks()                                  # cached: linear_system is cheap
        steps = cfg.model.n_floquet_steps

        def floquet(t=tr, k=steps):                        # a fresh system, as in a point
            s = linear_system(t)
            return s.modes(n_steps=k, n_sub=1, shapes=s.periodic, on_inaccurate="raise",
                           participation=s.periodic)

        t_fl = median_ms(floquet, repeat) - median_ms(lambda t=tr: linear_system(t), repeat)
        rest = t_point - t_model - t_trim - t_lin - t_fl
        print(f"  {name} point {t_point:.1f} ms: model {t_model:.1f}, trim {t_trim:.1f} "
              f"({iterations} Newton iterations), linearisation {t_lin:.1f}, "
              f"Floquet {t_fl:.1f}, labels and table {rest:.1f} ms")
    env = dict(os.environ)
    print("  fresh process, imports alone (medians of 5):")
    for what in ("pass", "import numpy", "import numpy, scipy.linalg",
                 "import numpy, scipy.linalg, pandas",
                 "import numpy, scipy.linalg, scipy.optimize, scipy.interpolate, pandas",
                 "import tefcore.cli, tefcore.linear.stability"):
        times = []
        for _ in range(5):
            r = subprocess.run([sys.executable, "-c", "import time; t = time.perf_counter(); "
                                f"{what}; print(time.perf_counter() - t)"],
                               capture_output=True, text=True, env=env,
                               cwd=tempfile.gettempdir(), check=True)
            times.append(float(r.stdout))
        print(f"    {what:<72s} {statistics.median(times):.2f} s")


def scaling(args):
    base = load_config("mdart").with_overrides({"flight.advance_ratio": 0.3})
    print(f"\nscaling, mu = 0.3 point (modes cached), medians of {args.repeat}; "
          f"load average {load()}")
    print(f"  {'blade modes':>11s} {'states':>6s} {'point':>9s} {'trim':>9s} {'Floquet':>9s}")
    for n_modes in (5, 9, 15, 20):
        cfg = base.with_overrides({"model.n_modes": n_modes})
        res = stability(cfg)
        t_point = median_ms(lambda c=cfg: stability(c), args.repeat)
        model = res.trim_result.model
        t_trim = median_ms(lambda m=model: trim(m), args.repeat)
        sys_ = res.system
        t_fl = median_ms(lambda s=sys_: s.modes(n_steps=72, n_sub=1, shapes=True,
                                                on_inaccurate="raise"), args.repeat)
        print(f"  {n_modes:>11d} {2 * model.n_dof:>6d} {t_point:>7.1f} ms {t_trim:>6.1f} ms "
              f"{t_fl:>6.1f} ms", flush=True)
    from tefcore.sweeps.maps import stability_map

    print(f"\nmaps (actuator stiffness x advance ratio), 2 processes, once each; "
          f"load average {load()}")
    sizes = (5, 10, 20) if args.quick else (5, 10, 20, 40)
    for size in sizes:
        t0 = time.perf_counter()
        stability_map(base, "actuator.stiffness",
                      [f"{v:.3f} ft-lb/rad" for v in np.linspace(60.0, 400.0, size)],
                      "flight.advance_ratio", list(np.linspace(0.05, 0.35, size)),
                      n_jobs=2, progress=False)
        t = time.perf_counter() - t0
        print(f"  {size:>3d} x {size:<3d} {size * size:>5d} points {t:7.1f} s "
              f"{1e3 * t / size**2:6.1f} ms/point", flush=True)
    print(f"load average after: {load()}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=15, help="timed runs per median")
    ap.add_argument("--quick", action="store_true", help="small maps only")
    ap.add_argument("--reproduce", action="store_true", help="also time tefcore reproduce")
    ap.add_argument("--no-scaling", action="store_true", help="skip the scaling table")
    ap.add_argument("--no-breakdown", action="store_true",
                    help="skip where the time of a point and of the CLI goes")
    args = ap.parse_args()
    apply_defaults()
    goals(args)
    if not args.no_breakdown:
        breakdown(args)
    if not args.no_scaling:
        scaling(args)


if __name__ == "__main__":
    main()
