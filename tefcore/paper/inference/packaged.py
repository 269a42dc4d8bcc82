"""The packaged studies: the declared studies behind ``mdart-inferred``, their results as files.

The studies themselves live in optuna's storage; what the package carries is
what they found, as plain tables under version control
(``tefcore/data/inference/results/``), so that the reproduction report shows
them without running a study:

* ``trials.csv``: one row per trial of every packaged study (its study, number,
  state, parameters, each reading's objective and passes, the figures that
  could not be computed, why a sample was refused);
* ``claims.csv``: every completed trial's fitted claims, each reading's status
  and margin (long form);
* ``sobol.csv``, ``sobol.json``: the Sobol indices of every claim that fails
  or is ambiguous on mdart, per group of the space (:data:`SOBOL`);
* ``summary.json``: what :mod:`tefcore.paper.inference.analysis` reads from
  them -- the failures met, the pass rates of the fitted claims, the
  leave-one-figure-out table of each study, the best rotor of each reading,
  the fitted claims that pull against each other over the Sobol sample --
  and the check after the studies: the baseline (mdart's sample of the space)
  and each reading's best rotor checked with refinement on every claim, fitted
  and held out, by both readings (:func:`tefcore.paper.inference.analysis.check_rotor`).

:data:`STUDIES` declares them: ``tefcore infer`` with these arguments re-creates
each one exactly (a test re-runs the first trials of one and compares them
with ``trials.csv`` and ``claims.csv``).

Examples
--------
>>> [s["name"] for s in STUDIES][:2]
['protocol-continued-qmc-seed0', 'protocol-continued-tpe-seed0']
>>> study_command(STUDIES[0])
'tefcore infer --reading continued --sampler qmc --seed 0 --trials 32'
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["RESULTS", "SOBOL", "STUDIES", "export_results", "export_sobol", "load_results",
           "sobol_claims", "study_command", "trial_rows"]

#: The packaged studies, in the order they are run: a Sobol sample (independent of
#: the objective: its leave-one-figure-out is exact), TPE on each reading with seed
#: 0, and TPE on each reading with another seed (does the answer depend on it?).
STUDIES = (
    {"name": "protocol-continued-qmc-seed0", "reading": "continued", "sampler": "qmc",
     "seed": 0, "trials": 32},
    {"name": "protocol-continued-tpe-seed0", "reading": "continued", "sampler": "tpe",
     "seed": 0, "trials": 60},
    {"name": "protocol-flutter-tpe-seed0", "reading": "flutter", "sampler": "tpe",
     "seed": 0, "trials": 60},
    {"name": "protocol-continued-tpe-seed1", "reading": "continued", "sampler": "tpe",
     "seed": 1, "trials": 60},
    {"name": "protocol-flutter-tpe-seed1", "reading": "flutter", "sampler": "tpe",
     "seed": 1, "trials": 60},
)

#: The packaged Sobol analysis: every validation claim that fails or is ambiguous on
#: mdart (its recorded status), the space's six groups, Saltelli's design of base
#: size ``n`` (``n * 8`` rotors), seeded.
SOBOL = {"n": 8, "seed": 0, "reading": "continued"}

#: Where the packaged results are.
RESULTS = Path(__file__).resolve().parents[2] / "data" / "inference" / "results"

_READINGS = ("continued", "flutter")

#: Fitted claims whose terms of the objective have a rank correlation below this
#: over a sample independent of the objective pull against each other: as one
#: rises toward passing the other falls (Spearman; -0.5 is a strong opposition
#: over 25 rotors, where chance correlations stay within about +-0.4).
CONFLICT_RHO = -0.5


def study_command(study: dict) -> str:
    """The ``tefcore infer`` command that runs a packaged study.

    Parameters
    ----------
    study : dict
        One of :data:`STUDIES`.

    Returns
    -------
    str
    """
    return (f"tefcore infer --reading {study['reading']} --sampler {study['sampler']} "
            f"--seed {study['seed']} --trials {study['trials']}")


def trial_rows(study) -> tuple[pd.DataFrame, pd.DataFrame]:
    """A study's trials (every state) and its completed trials' claims, as tables.

    Parameters
    ----------
    study : optuna.Study
        The study.

    Returns
    -------
    trials, claims : pandas.DataFrame
        ``trials``: ``study``, ``number``, ``state``, the parameters, ``<reading>
        objective`` and ``<reading> passes``, ``broken``, ``refused``.  ``claims``:
        ``study``, ``number``, ``reading``, ``id``, ``status``, ``margin``.
    """
    trows, crows = [], []
    for t in sorted(study.get_trials(deepcopy=False), key=lambda t: t.number):
        row = {"study": study.study_name, "number": t.number, "state": t.state.name,
               **t.params}
        for r in _READINGS:
            row[f"{r} objective"] = t.user_attrs.get(f"{r}:objective", np.nan)
            row[f"{r} passes"] = t.user_attrs.get(f"{r}:passes", np.nan)
            statuses = t.user_attrs.get(f"{r}:statuses", {})
            margins = t.user_attrs.get(f"{r}:margins", {})
            crows += [{"study": study.study_name, "number": t.number, "reading": r, "id": cid,
                       "status": st, "margin": np.nan if margins.get(cid) is None
                       else margins[cid]} for cid, st in statuses.items()]
        row["broken"] = "; ".join(sorted(t.user_attrs.get("broken", {})))
        row["refused"] = t.user_attrs.get("refused", "")
        trows.append(row)
    return pd.DataFrame(trows), pd.DataFrame(
        crows, columns=["study", "number", "reading", "id", "status", "margin"])


def _summary(studies, declared, protocol) -> dict:
    from .analysis import agreement, conflicts, failures, leave_one_figure_out, pass_rates
    from .inferred import inferred_rotor
    from .space import load_space

    out: dict = {"studies": [dict(s) for s in declared], "failures": {}, "lofo": {},
                 "pass_rates": {}, "best": {}, "conflicts": {}, "agreement": {}}
    space = load_space(protocol.space)
    for s, d in zip(studies, declared, strict=True):
        out["failures"][s.study_name] = failures(s)
        if d["sampler"] in ("qmc", "random"):     # a sample the objective did not steer
            out["conflicts"][s.study_name] = conflicts(s, "continued", CONFLICT_RHO) \
                .to_dict("records")
        for r in _READINGS:
            lofo = leave_one_figure_out(s, r, protocol.fit_figures)
            out["lofo"][f"{s.study_name}:{r}"] = lofo.to_dict("records")
    for r in _READINGS:
        # does the answer depend on the sampler or the seed? the studies run on this
        # reading, each one's best and where the bests lie apart
        own = [s for s, d in zip(studies, declared, strict=True) if d["reading"] == r]
        out["agreement"][r] = agreement(own, r, space)
        out["pass_rates"][r] = pass_rates(studies, r).replace(-np.inf, None) \
            .to_dict("records")
        try:
            best = inferred_rotor(studies, r)
        except ValueError as err:         # no trial keeps the stated frequencies
            out["best"][r] = {"error": str(err)}
            continue
        out["best"][r] = {**best, "spread": {k: list(v) for k, v in best["spread"].items()},
                          "trial": list(best["trial"])}
    return out


def _counts(table: pd.DataFrame, fitted: set) -> dict:
    """Validation passes of a checked rotor: fitted, held out, all (each ``[passes, of]``)."""
    v = table[table["tag"] == "validation"]
    fit = v["id"].isin(fitted)
    ok = v["status"] == "pass"
    return {"fitted": [int((ok & fit).sum()), int(fit.sum())],
            "held out": [int((ok & ~fit).sum()), int((~fit).sum())],
            "all": [int(ok.sum()), len(v)]}


def _checks(summary: dict, cache_folder) -> dict:
    """The baseline and each reading's best rotor on every claim, refined, both readings."""
    from ..attribution.evaluate import FigureCache
    from ..claims.reference import load_claims
    from ..figures.runs import base_config
    from .analysis import check_rotor
    from .protocol import load_protocol
    from .space import baseline_sample, load_space

    protocol = load_protocol()
    claims = load_claims()
    fitted = {c.id for c in protocol.split(claims)[0]}
    rotors = {"baseline": baseline_sample(base_config("thin_airfoil"), load_space(protocol.space))}
    rotors |= {f"best {r}": b["params"] for r, b in summary["best"].items() if "params" in b}
    out = {}
    for name, params in rotors.items():
        res = check_rotor(params, claims, _READINGS, cache=FigureCache(cache_folder))
        out[name] = {"broken": dict(res["broken"]),
                     **{r: {**_counts(res[r], fitted),
                            "statuses": dict(zip(res[r]["id"], res[r]["status"], strict=True))}
                        for r in _READINGS}}
    return out


def export_results(storage: str, folder=RESULTS, *, check: bool = True,
                   cache_folder=None, studies=STUDIES) -> Path:
    """Write the packaged studies' results from `storage` into `folder` (atomically).

    Parameters
    ----------
    storage : str
        The journal file or RDB URL holding the studies of :data:`STUDIES`.
    folder : path
        Where ``trials.csv``, ``claims.csv`` and ``summary.json`` go.
    check : bool
        Check the baseline and the best rotors on every claim (a few minutes
        of CPU each); without it the summary has no ``checks``.
    cache_folder : path, optional
        Where those checks keep their figures (default ``<storage>.checks``).
    studies : sequence of dict
        The studies exported (default :data:`STUDIES`).

    Returns
    -------
    pathlib.Path
        The folder.
    """
    import optuna

    from ...safe_io import atomic_write_text
    from .protocol import load_protocol
    from .study import open_storage

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    store = open_storage(storage)
    declared = list(studies)
    studies = [optuna.load_study(study_name=s["name"], storage=store) for s in declared]
    frames = [trial_rows(s) for s in studies]
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    trials = pd.concat([f[0] for f in frames], ignore_index=True)
    claims = pd.concat([f[1] for f in frames], ignore_index=True)
    atomic_write_text(folder / "trials.csv", trials.to_csv(index=False, float_format="%.10g"))
    atomic_write_text(folder / "claims.csv", claims.to_csv(index=False, float_format="%.10g"))
    summary = _summary(studies, declared, load_protocol())
    if check:
        base = storage.split("///", 1)[-1] if "://" in storage else storage
        summary["checks"] = _checks(summary, cache_folder or f"{base}.checks")
    atomic_write_text(folder / "summary.json",
                      json.dumps(summary, indent=1, default=_plain) + "\n")
    return folder


def _plain(v):
    """JSON for numpy scalars (the summary's counts and margins)."""
    if isinstance(v, np.generic):
        return v.item()
    raise TypeError(f"{type(v).__name__} is not JSON")


def sobol_claims() -> list:
    """The claims of the packaged Sobol analysis: mdart's failing and ambiguous validation claims.

    Returns
    -------
    list of Claim
    """
    from ..claims.reference import load_claims

    return [c for c in load_claims() if c.tag == "validation"
            and c.recorded_status in ("fail", "ambiguous")]


def export_sobol(folder=RESULTS, *, cache_folder, n_jobs: int = 1) -> Path:
    """Run the packaged Sobol analysis (:data:`SOBOL`) and write ``sobol.csv`` and ``sobol.json``.

    Parameters
    ----------
    folder : path
        Where the files go.
    cache_folder : path
        Where its rotors' figures are kept.
    n_jobs : int
        Processes over the design.

    Returns
    -------
    pathlib.Path
        The folder.
    """
    from ...safe_io import atomic_write_text
    from ..attribution.evaluate import FigureCache
    from .sensitivity import sobol_indices

    claims = sobol_claims()
    table, info = sobol_indices(claims, SOBOL["n"], seed=SOBOL["seed"],
                                cache=FigureCache(cache_folder), reading=SOBOL["reading"],
                                n_jobs=n_jobs)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    atomic_write_text(folder / "sobol.csv", table.to_csv(index=False, float_format="%.6g"))
    atomic_write_text(folder / "sobol.json", json.dumps(
        {**SOBOL, **info, "claims": [c.id for c in claims]}, indent=1, default=_plain) + "\n")
    return folder


def load_results(folder=RESULTS) -> dict:
    """The packaged results: ``trials``, ``claims`` (DataFrames) and ``summary`` (dict).

    Parameters
    ----------
    folder : path
        Default :data:`RESULTS`.

    Returns
    -------
    dict
        ``trials``, ``claims``, ``summary`` and, where the Sobol analysis is
        stored, ``sobol`` and ``sobol_info``; empty when the folder holds no
        results.
    """
    folder = Path(folder)
    if not (folder / "summary.json").exists():
        return {}
    out = {"trials": pd.read_csv(folder / "trials.csv"),
           "claims": pd.read_csv(folder / "claims.csv"),
           "summary": json.loads((folder / "summary.json").read_text())}
    if (folder / "sobol.json").exists():
        out["sobol"] = pd.read_csv(folder / "sobol.csv")
        out["sobol_info"] = json.loads((folder / "sobol.json").read_text())
    return out
