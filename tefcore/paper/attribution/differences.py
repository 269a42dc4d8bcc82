"""Why we differ from the paper: what would flip each failing validation claim.

A reviewer's first question about a replication is why it differs.  For every
failing validation claim of a run, :func:`attribute` moves each assumption of
notebook 08 and each model option within its plausible range
(:mod:`tefcore.paper.attribution.levers`) and finds the smallest change that
flips the claim's own verdict (:mod:`tefcore.paper.attribution.search`,
checked on the fewest points that decide it, :mod:`tefcore.paper.attribution.evaluate`):

* a continuous assumption is bisected between the baseline and the end of its
  range where the claim passes (then once beyond the range, to tell an
  implausible flip from none);
* a discrete option (modes retained 6-12, unsteady aerodynamics, dynamic
  inflow, the multiple-load-path hub, the XFOIL deck) is tried at each value;
* where no single change flips a claim, the Fig. 6 flap-system inertia held at
  its calibration (the value that gives Fig. 6's 15 %) is paired with each
  assumption that places blade flap 4/5 and torsion 2;
* every flip is checked again on refined sweeps (``confirmed``) and against
  the other claims of the figure, which passed (``conflicts``).

:func:`attribute_run` does it for a reproduction (``tefcore reproduce``) and
writes ``OUT/attribution.csv`` beside ``claims.csv`` (:data:`COLUMNS`, then
:data:`EXTRA_COLUMNS`): one row per claim and lever tried, and a row with
``assumption = none`` for a claim nothing flips within its plausible range.
:func:`summarise` reads the table for the report.

**Cost.**  The levers run in parallel (joblib, one task per lever); each task
caches its sweeps by figure and configuration hash.  On the failing claims of
a full reproduction it costs about an hour of CPU (``Attribution.cpu_seconds``
measures it); ``tefcore reproduce --no-attribution`` skips it.

References
----------
.. [1] tefcore's aim for the attribution: calibrate on what the paper
   states, and attribute every disagreement with the paper.
.. [2] The paper's assumptions and their plausible ranges: notebook 08 and
   :data:`tefcore.paper.attribution.assumptions.ASSUMPTIONS`.

Examples
--------
>>> t = pd.DataFrame({"claim": ["a", "a", "b"], "status": "fail",
...                   "assumption": ["flap mass", "lift slope", "none"],
...                   "flips_at": ["1.1", "", ""], "plausible_low": [0.75, 5.5, ""],
...                   "plausible_high": [1.25, 6.28, ""], "within_plausible": [True, False, False],
...                   "figure": ["fig9", "fig9", "fig17"], "confirmed": [True, "", ""],
...                   "conflicts": ""})
>>> s = summarise(t)
>>> s["explains"][0]["assumption"], s["unexplained"]
('flap mass', ['b'])
"""

from __future__ import annotations

import tempfile
import time
from dataclasses import dataclass, replace
from pathlib import Path

import pandas as pd

from ...safe_io import atomic_output
from .evaluate import RunSettings
from .levers import FIG6_NAME, levers, pair_lever, placement_levers
from .search import Target, lever_rows

__all__ = ["COLUMNS", "EXTRA_COLUMNS", "Attribution", "attribute", "attribute_run",
           "failing_claims", "summarise", "write_attribution"]

#: The attribution's columns, in order.
COLUMNS = ["claim", "status", "assumption", "flips_at", "plausible_low", "plausible_high",
           "within_plausible"]
#: Further columns: the figure, what the settings are and the baseline's, whether the
#: flip holds on refined sweeps, the passing claims it fails, every setting tried.
EXTRA_COLUMNS = ["figure", "setting", "baseline", "confirmed", "conflicts", "tried",
                 "evaluations", "note"]


@dataclass
class Attribution:
    """Result of :func:`attribute`.

    Attributes
    ----------
    table : pandas.DataFrame
        :data:`COLUMNS` + :data:`EXTRA_COLUMNS`, one row per claim and lever.
    cpu_seconds : float
        CPU time of the attribution, its worker processes included.
    wall_seconds : float
        Its wall-clock time.
    tasks : int
        Parallel tasks run (one per lever and pair, plus the baseline check).
    source : str
        How it was obtained, in words, for the report: ``""`` for a search
        of this run; the packaged attribution's provenance where the run read
        it (:mod:`tefcore.paper.attribution.packaged`).
    """

    table: pd.DataFrame
    cpu_seconds: float
    wall_seconds: float
    tasks: int
    source: str = ""


def failing_claims(claims: pd.DataFrame) -> pd.DataFrame:
    """The failing validation claims of a claims table.

    Parameters
    ----------
    claims : pandas.DataFrame
        ``id``, ``status``, ``tag`` (and ``figure``, ``notebook``).

    Returns
    -------
    pandas.DataFrame
        Its rows with ``status == "fail"`` and ``tag == "validation"``.
    """
    if claims.empty or "status" not in claims:
        return claims.iloc[0:0]
    return claims[(claims["status"] == "fail") & (claims.get("tag", "validation")
                                                   == "validation")]


def _targets(claims: pd.DataFrame, reference) -> tuple[list, list]:
    """The failing claims as :class:`Target` with their passing peers; and unknown ids."""
    known = {c.id: c for c in reference}
    nb = claims["notebook"] if "notebook" in claims else pd.Series("", index=claims.index)
    targets, unknown = [], []
    for i, row in failing_claims(claims).iterrows():
        c = known.get(row["id"])
        if c is None:
            unknown.append(row["id"])
            continue
        same = claims[(nb == nb[i]) & (claims["status"] == "pass")]
        peers = tuple(known[p] for p in same["id"] if p in known and known[p].figure == c.figure
                      and known[p].kind != "not_reproducible")
        targets.append(Target(c, str(nb[i]), peers))
    return targets, unknown


def _indexed(i, *args):
    return i, lever_rows(*args)


def _run(tasks, settings_of, folder: Path, n_jobs: int, progress=None):
    """Each ``(lever, targets)`` by :func:`lever_rows`, costliest first; rows and CPU seconds.

    ``progress`` (a tqdm bar, or None) grows by the tasks' estimated cost
    (:func:`_cost` times the claims each checks) and advances as each ends.
    """
    order = sorted(range(len(tasks)), key=lambda i: -_cost(tasks[i][0]))
    args = [(tasks[i][0], tasks[i][1], settings_of, folder / f"task{i}") for i in order]
    for a in args:
        a[3].mkdir(parents=True, exist_ok=True)
    weight = {i: _cost(tasks[i][0]) * max(1, len(tasks[i][1])) for i in order}
    if progress is not None:
        progress.total = (progress.total or 0) + sum(weight.values())
        progress.refresh()
    if n_jobs == 1 or len(args) <= 1:
        ends = ((i, lever_rows(*a)) for i, a in zip(order, args, strict=True))
    else:
        from joblib import Parallel, delayed

        ends = Parallel(n_jobs=n_jobs, return_as="generator_unordered")(
            delayed(_indexed)(i, *a) for i, a in zip(order, args, strict=True))
    by_task = {}
    for i, result in ends:
        by_task[i] = result
        if progress is not None:
            progress.update(weight[i])
    return [by_task[i][0] for i in range(len(tasks))], sum(d[1] for d in by_task.values())


def _cost(lever) -> float:
    if lever is None:
        return 1.0
    return lever.cost * (len(lever.options) if lever.discrete else 3.0)


def _explained(rows) -> set:
    return {r["claim"] for r in rows if r.get("within_plausible") and r.get("confirmed") is True}


def _pairs(lvs, cfg):
    """The pair levers (the Fig. 6 calibration with each placement lever), and why none."""
    fig6 = next((lv for lv in lvs if lv.name == FIG6_NAME), None)
    if fig6 is None:
        return [], "no Fig. 6 flap-system inertia lever: pairs not tried"
    placing = placement_levers(cfg, lvs)
    if not placing:
        return [], ("no assumption places blade flap 4/5 and torsion 2: the pairs with the "
                    "Fig. 6 calibration cannot be tried (an assumption is missing)")
    # the Fig. 6 lever's top is its calibration (the mdart-fig6 value)
    return [pair_lever(fig6, float(fig6.high), p) for p in placing], ""


def _none_row(target, note) -> dict:
    c = target.claim
    return {"claim": c.id, "status": "fail", "assumption": "none", "flips_at": "",
            "plausible_low": "", "plausible_high": "", "within_plausible": False,
            "figure": c.figure, "note": note}


def attribute(claims: pd.DataFrame, settings_of: dict | None = None, *, lever_list=None,
              pairs: bool = True, n_jobs: int = 1, reference=None,
              progress=None) -> Attribution:
    """What would flip each failing validation claim of a claims table.

    Parameters
    ----------
    claims : pandas.DataFrame
        The run's claims (``claims.csv``: ``id``, ``figure``, ``status``,
        ``tag``; ``notebook`` when several notebooks ran with other settings).
    settings_of : dict, optional
        Notebook -> :class:`~tefcore.paper.attribution.evaluate.RunSettings`
        (default: the notebooks' defaults for every notebook).
    lever_list : sequence of Lever, optional
        Default :func:`tefcore.paper.attribution.levers.levers` about the
        first notebook's base configuration.
    pairs : bool
        Try the Fig. 6 calibration paired with the placement of flap 4/5 and
        torsion 2 for the claims no single lever flips.
    n_jobs : int
        Parallel joblib processes (one task per lever).
    reference : sequence of Claim, optional
        The claims' definitions (default :func:`tefcore.paper.claims.reference.load_claims`).
    progress : tqdm.tqdm, optional
        A progress bar: its total grows by each stage's estimated cost (the
        pairs are known only after the single levers) and it advances as
        each task ends.

    Returns
    -------
    Attribution
    """
    from ..claims.reference import load_claims

    wall, cpu = time.perf_counter(), time.process_time()
    targets, unknown = _targets(claims, load_claims() if reference is None else reference)
    nbs = {t.notebook for t in targets}
    settings_of = {nb: (settings_of or {}).get(nb) or RunSettings.from_params() for nb in nbs}
    rows = [_none_row(Target(_Unknown(i), ""), "not in the reference data") for i in unknown]
    task_cpu, n_tasks = 0.0, 0
    if targets:
        base = next(iter(settings_of.values())).base
        lvs = list(lever_list) if lever_list is not None else levers(base)
        with tempfile.TemporaryDirectory(prefix="tefcore-attribution-") as tmp:
            targets, why, task_cpu = _baseline(targets, settings_of, Path(tmp) / "base", n_jobs,
                                               progress)
            todo = [t for t in targets if t.claim.id not in why]
            done, c1 = _run([(lv, todo) for lv in lvs], settings_of, Path(tmp), n_jobs,
                            progress)
            found = [r for part in done for r in part]
            left = [t for t in todo if t.claim.id not in _explained(found)]
            pair_levers, missing = _pairs(lvs, base) if pairs and left \
                else ([], "")
            c2 = 0.0
            if pair_levers:
                more, c2 = _run([(p, left) for p in pair_levers], settings_of,
                                Path(tmp) / "pairs", n_jobs, progress)
                found += [r for part in more for r in part]
            task_cpu += c1 + c2
            n_tasks = len(lvs) + len(pair_levers)
        rows += _finish(found, targets, why, missing)
    table = pd.DataFrame(rows).reindex(columns=COLUMNS + EXTRA_COLUMNS).astype(object).fillna("")
    return Attribution(table, time.process_time() - cpu + task_cpu,
                       time.perf_counter() - wall, n_tasks)


@dataclass(frozen=True)
class _Unknown:
    id: str
    figure: str = ""


def _baseline(targets, settings_of, folder, n_jobs, progress=None):
    """Each target checked at the baseline on its own points (one task per figure).

    Returns the targets with their side of the pass band, the claims that do not
    fail there (not attributed: the points the attribution computes do not
    reproduce the notebook's verdict) with the reason, and the CPU seconds.
    """
    groups: dict = {}
    for t in targets:
        groups.setdefault((t.notebook, t.claim.figure), []).append(t)
    done, cpu = _run([(None, g) for g in groups.values()], settings_of, folder, n_jobs,
                     progress)
    got = {r["claim"]: r for part in done for r in part}
    why = {c: f"the attribution's points give {r['status']} at the baseline: not attributed"
           for c, r in got.items() if r["status"] != "fail"}
    return [replace(t, side=got[t.claim.id]["side"] or -1) for t in targets], why, cpu


def _finish(found, targets, why, missing) -> list[dict]:
    """Rows in claim order, each claim's levers then its ``none`` row if nothing flips it."""
    out = []
    explained = _explained(found)
    for t in targets:
        mine = [r for r in found if r["claim"] == t.claim.id]
        out += mine
        if t.claim.id in why:
            out.append(_none_row(t, why[t.claim.id]))
        elif t.claim.id not in explained:
            beyond = [f"{r['assumption']} at {r['flips_at']}" for r in mine
                      if r["flips_at"] != "" and not r["within_plausible"]]
            note = "none within plausible range" + (
                f" (flips only beyond it: {'; '.join(beyond)})" if beyond else "")
            out.append(_none_row(t, note + (f"; {missing}" if missing else "")))
    return out


def write_attribution(table: pd.DataFrame, path) -> Path:
    """Write an attribution table as CSV, atomically.

    Parameters
    ----------
    table : pandas.DataFrame
        :attr:`Attribution.table`.
    path : path
        The file (``OUT/attribution.csv``).

    Returns
    -------
    pathlib.Path
    """
    path = Path(path)
    with atomic_output(path, newline="") as f:
        table.reindex(columns=COLUMNS + EXTRA_COLUMNS).to_csv(f, index=False,
                                                              float_format="%.6g")
    return path


def attribute_run(out, claims: pd.DataFrame, params: dict | None = None,
                  n_jobs: int = 1, **kwargs) -> Attribution:
    """Attribute the failing claims of a reproduction; write ``out/attribution.csv``.

    Parameters
    ----------
    out : path
        The reproduction folder.
    claims : pandas.DataFrame
        Its claims, with the ``notebook`` that checked each
        (:func:`tefcore.paper.run.reproduce.collect_claims`).
    params : dict, optional
        Notebook -> its papermill parameters (the run's base configuration,
        section aerodynamics, overrides and sweep values).
    n_jobs : int
        Parallel processes.
    **kwargs
        Passed to :func:`attribute` (``lever_list``, ``pairs``, ``progress``).

    Returns
    -------
    Attribution
    """
    settings_of = {nb: RunSettings.from_params(p) for nb, p in (params or {}).items()}
    result = attribute(claims, settings_of, n_jobs=n_jobs, **kwargs)
    write_attribution(result.table, Path(out) / "attribution.csv")
    return result


def summarise(table: pd.DataFrame, top: int = 5) -> dict:
    """What the report says about an attribution: what explains most, what nothing does.

    Parameters
    ----------
    table : pandas.DataFrame
        An attribution table (:data:`COLUMNS`, ``figure``, ``confirmed``,
        ``conflicts``, ``note``).
    top : int
        Levers listed in ``explains``.

    Returns
    -------
    dict
        ``failing`` and ``explained``: the failing claims attributed and those
        a plausible change flips; ``explains``: the levers that flip most of
        them within their plausible range (confirmed on refined sweeps), each
        ``{"assumption", "claims", "conflicts"}``, most first;
        ``unexplained``: the claims no lever flips within its range;
        ``figures``: figure -> one row per failing claim (``claim``,
        ``plausible``: what flips it, ``beyond``: what flips it only outside
        its range or unconfirmed, ``conflicts``); ``notes``: the levers'
        notes (an assumption that cannot be tried).
    """
    t = table.fillna("").astype({"flips_at": str})
    flips = t[(t["flips_at"] != "") & (t["assumption"] != "none")]
    good = flips[flips["within_plausible"].astype(str).isin(["True", "true"])
                 & (flips["confirmed"].astype(str) == "True")]
    explains = [{"assumption": a, "claims": sorted(g["claim"]),
                 "conflicts": int((g["conflicts"].astype(str) != "").sum())}
                for a, g in good.groupby("assumption", sort=False)]
    explains.sort(key=lambda e: -len(e["claims"]))
    unexplained = list(dict.fromkeys(t.loc[t["assumption"] == "none", "claim"]))
    figures: dict = {}
    for claim, g in t.groupby("claim", sort=False):
        ok = good[good["claim"] == claim]
        rest = flips[(flips["claim"] == claim) & ~flips.index.isin(ok.index)]
        figures.setdefault(str(g["figure"].iloc[0]), []).append({
            "claim": claim,
            "plausible": "; ".join(f"{r.assumption} at {r.flips_at}" for r in ok.itertuples())
            or "none within plausible range",
            "beyond": "; ".join(f"{r.assumption} at {r.flips_at}" + (
                "" if str(r.confirmed) == "True" else " (not confirmed)")
                for r in rest.itertuples()),
            "conflicts": "; ".join(c for c in ok["conflicts"].astype(str) if c)})
    notes = [n for n in dict.fromkeys(t.get("note", pd.Series(dtype=str)).astype(str))
             if "cannot be tried" in n]
    failing = t["claim"].nunique()
    return {"failing": failing, "explained": failing - len(unexplained),
            "explains": explains[:top], "unexplained": unexplained, "figures": figures,
            "notes": [n.split("; ")[-1] if "cannot be tried" in n else n for n in notes]}
