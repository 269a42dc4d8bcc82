"""``tefcore reproduce`` on both variants: the other variant's claims beside the notebooks'.

The notebooks run on one configuration (their ``config`` parameter, default
``mdart``).  While they run, :func:`start_variant_runs` checks the claims of
the same figures on every other packaged variant (:mod:`tefcore.paper.claims.variants`),
each in a process of its own (``python -m tefcore.paper.run.variant_runs claims ...``),
and measures the conflict of Fig. 6's calibration
(:func:`tefcore.paper.fig6_calibration.conflict_table`); :func:`finish_variant_runs`
waits for them and puts the statuses side by side.  Files::

    OUT/variants/claims-<variant>.csv   the variant's claims (same columns as claims.csv)
    OUT/variants/conflict.csv           Fig. 6 and the stability points on each variant
    OUT/variants/<run>.log              what each process printed (its errors)
    OUT/claims-variants.csv             every claim's status on each variant, and why
                                        a status differs

The other variant's claims are checked with the paper's sweep values and no
notebook parameter but ``config`` (:func:`tefcore.paper.claims.validation.validate_all`):
a reproduction with ``-p overrides ...`` or ``-p n_points ...`` compares its
notebooks with the variant's paper-value claims, and the report says so.
"""

from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from ...safe_io import atomic_output
from ..claims.validation import claims_score, worse_than_recorded
from ..claims.variants import (
    compare_variants,
    comparison_variants,
    default_reason,
    load_variants,
    variant_claims,
    variant_name,
)

__all__ = ["VariantRun", "base_variant", "finish_variant_runs", "start_variant_runs",
           "stop_variant_runs"]


@dataclass
class VariantRun:
    """One process of :func:`start_variant_runs`.

    Parameters
    ----------
    name : str
        ``claims-<variant>`` or ``conflict``.
    variant : str
        The variant whose claims it checks (``""`` for the conflict).
    csv : pathlib.Path
        What it writes.
    log : pathlib.Path
        Its standard output and error.
    process : subprocess.Popen
        The running process.
    """

    name: str
    variant: str
    csv: Path
    log: Path
    process: subprocess.Popen


def base_variant(params: dict, names) -> tuple[bool, str | None]:
    """The configuration every notebook of a run uses, from their parameters.

    Parameters
    ----------
    params : dict
        ``{notebook: {parameter: value}}`` (merged).
    names : sequence of str
        The notebooks run.

    Returns
    -------
    tuple
        ``(same, config)``: whether they all use one configuration, and it
        (None: the default).
    """
    configs = {params.get(n, {}).get("config") for n in names}
    return len(configs) <= 1, (next(iter(configs)) if configs else None)


def _paths(out: Path, name: str) -> tuple[Path, Path]:
    folder = out / "variants"
    folder.mkdir(parents=True, exist_ok=True)
    return folder / f"{name}.csv", folder / f"{name}.log"


def _launch(name: str, variant: str, csv: Path, log: Path, args) -> VariantRun:
    """``python -m tefcore.paper.run.variant_runs ARGS`` with its output in ``log``."""
    csv.unlink(missing_ok=True)
    with open(log, "w", encoding="utf-8") as f:     # the child keeps its own handle
        proc = subprocess.Popen([sys.executable, "-m", "tefcore.paper.run.variant_runs", *args],
                                stdout=f, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    return VariantRun(name, variant, csv, log, proc)


def start_variant_runs(out: Path, base, figures) -> list[VariantRun]:
    """Start checking the claims of ``figures`` on the variants other than ``base``.

    Parameters
    ----------
    out : pathlib.Path
        The reproduction folder (it exists).
    base : str or None
        The notebooks' configuration (None: the default).
    figures : sequence of str
        The paper figures the notebooks reproduce; none: nothing is started.

    Returns
    -------
    list of VariantRun
        One per other variant, and the conflict measurement; empty when
        ``base`` is not a packaged variant (a comparison would not say what
        differs) or there are no figures.
    """
    runs = []
    for v in comparison_variants(base) if figures else []:
        csv, log = _paths(out, f"claims-{v}")
        runs.append(_launch(f"claims-{v}", v, csv, log, ["claims", v, str(csv), *figures]))
    if runs:
        csv, log = _paths(out, "conflict")
        runs.append(_launch("conflict", "", csv, log, ["conflict", str(csv)]))
    return runs


def stop_variant_runs(runs) -> None:
    """Kill the processes of ``runs`` that still run (Ctrl-C, a failure).

    Parameters
    ----------
    runs : list of VariantRun
        From :func:`start_variant_runs`.
    """
    for r in runs:
        if r.process.poll() is None:
            r.process.kill()
            r.process.wait()


def _read(run: VariantRun) -> tuple[pd.DataFrame | None, str]:
    code = run.process.wait()
    if code == 0 and run.csv.exists():
        return pd.read_csv(run.csv, dtype=str, keep_default_na=False), ""
    lines = run.log.read_text(encoding="utf-8", errors="replace").strip().splitlines()
    return None, f"{run.name} exited with status {code}: {lines[-1] if lines else 'no output'}"


def finish_variant_runs(runs, out: Path, base_claims: pd.DataFrame, base,
                        done=None) -> dict | None:
    """Wait for ``runs`` and compare the variants' claims; write ``OUT/claims-variants.csv``.

    Parameters
    ----------
    runs : list of VariantRun
        From :func:`start_variant_runs` (none: returns None).
    out : pathlib.Path
        The reproduction folder.
    base_claims : pandas.DataFrame
        The notebooks' claims (on ``base``).
    base : str or None
        The notebooks' configuration.
    done : callable, optional
        Called with each run once it has ended (a progress bar's step).

    Returns
    -------
    dict or None
        ``base``, ``names`` (the variants, the notebooks' first), ``reason``
        (why the default is the default), ``summaries``, ``scores`` (variant
        -> (passed, total) validation claims), ``worse`` (the other variants'
        claims worse than their recorded status), ``comparison`` (the
        :func:`~tefcore.paper.claims.variants.compare_variants` table), ``conflict``
        (DataFrame or None) and ``errors`` (what failed).
    """
    if not runs:
        return None
    variants = load_variants()
    base = base or next(iter(variants))
    tables = {base: base_claims.drop(columns=["notebook"], errors="ignore")}
    conflict, errors, worse = None, [], []
    for r in runs:
        table, err = _read(r)
        if done is not None:
            done(r)
        errors += [err] if err else []
        if table is not None and r.variant:
            tables[r.variant] = table
            worse += [table.assign(variant=r.variant).pipe(worse_than_recorded)]
        elif table is not None:
            conflict = table
    comparison = compare_variants(tables)
    with atomic_output(out / "claims-variants.csv", newline="") as f:
        comparison.to_csv(f, index=False)
    return {"base": base, "names": list(tables), "reason": default_reason(),
            "summaries": {n: variants[n].summary for n in tables},
            "scores": {n: tuple(int(x) for x in claims_score(t)) if not t.empty else (0, 0)
                       for n, t in tables.items()},
            "worse": pd.concat(worse, ignore_index=True) if worse else pd.DataFrame(),
            "comparison": comparison, "conflict": conflict, "errors": errors}


USAGE = ("usage: python -m tefcore.paper.run.variant_runs claims CONFIG OUT.csv [FIGURE ...] | "
         "conflict OUT.csv")


def _exit_with_parent() -> None:
    """End this process when the one that started it ends (``kill -9`` of a reproduction)."""
    import os
    import threading
    import time

    parent = os.getppid()

    def watch():
        while os.getppid() == parent:
            time.sleep(1.0)
        os._exit(1)

    threading.Thread(target=watch, daemon=True).start()


def _main(argv) -> int:
    """``claims CONFIG OUT.csv [FIGURE ...]`` or ``conflict OUT.csv`` (module docstring)."""
    from ...runtime import apply_defaults
    from ...safe_io import atomic_output

    # the process is tefcore's (started by `tefcore reproduce`): its settings
    # (tefcore.runtime).  Without them the mdart-fig6 claims took 56 s of CPU,
    # 11 s of it the kernel's (the heap trimmed and faulted back in at every
    # point), against 42 s with 0.2 s system time; the same CSV, byte for byte
    apply_defaults()
    _exit_with_parent()

    if argv[:1] == ["conflict"] and len(argv) == 2:
        from ..fig6_calibration import conflict_table

        table, out = conflict_table(), argv[1]
    elif argv[:1] == ["claims"] and len(argv) >= 3:
        name, out, figures = argv[1], argv[2], argv[3:]
        if variant_name(name) is None:
            raise ValueError(f"{name!r} is not a packaged variant; known: "
                             f"{', '.join(load_variants())}")
        table = variant_claims(name, figures or None)
    else:
        raise ValueError(USAGE)
    with atomic_output(out, newline="") as f:
        table.to_csv(f, index=False)
    return 0


if __name__ == "__main__":
    from ...errors import run_command

    raise SystemExit(run_command(_main, sys.argv[1:],
                                 prog="python -m tefcore.paper.run.variant_runs"))
