"""Sobol sensitivity of each claim over the declared space (SALib).

First-order (S1) and total (ST) Sobol indices of each claim's term of the
objective (``tanh`` of its margin, :func:`tefcore.paper.inference.analysis.claim_scores`:
bounded, and defined where the check measured no margin) over the numeric
parameters of the space, moved in their groups (the space file's ``group``:
flap, actuator, section, blade stiffness, aerodynamics, hub) with Saltelli's
design (:func:`SALib.sample.sobol.sample`, no second order): ``N * (G + 2)``
rotors for ``G`` groups, each checked on the chosen claims.  The confidence
intervals are SALib's bootstrap (95 %).  Choices (the flap's chord scaling)
stay at the baseline.

It is expensive: with the six groups, N = 8 is 64 rotors -- about 2 min of CPU
on the claims of Figs. 6-8 (2 s each), 17 min on every fitted figure (16 s
each).  A sample tefcore refuses (the flap no longer fits its section) cannot
be left out of the design; its claims take the mean of the others' values,
and the count is reported.

Examples
--------
>>> problem, groups = sobol_problem(load_space())
>>> problem["num_vars"], len(set(groups))
(14, 6)
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .space import Refused, apply_sample, load_space, recalibrated

__all__ = ["load_space", "sobol_design", "sobol_indices", "sobol_problem"]


def sobol_problem(space) -> tuple[dict, list]:
    """SALib's problem over the numeric parameters (log-scaled ones in log), and their groups.

    Parameters
    ----------
    space : dict of str to Parameter
        :func:`load_space`.

    Returns
    -------
    tuple of (dict, list)
        The problem (``num_vars``, ``names``, ``bounds``, ``groups``) and the groups.
    """
    numeric = [p for p in space.values() if not p.categorical]
    bounds = [[np.log(p.low), np.log(p.high)] if p.log else [p.low, p.high] for p in numeric]
    groups = [p.group for p in numeric]
    return ({"num_vars": len(numeric), "names": [p.name for p in numeric], "bounds": bounds,
             "groups": groups}, groups)


def sobol_design(space, n: int, seed: int = 0) -> list[dict]:
    """Saltelli's design: the samples (parameter name -> value) to evaluate, in order.

    Parameters
    ----------
    space : dict of str to Parameter
        :func:`load_space`.
    n : int
        SALib's base sample size N (a power of 2): ``N * (groups + 2)`` samples.
    seed : int
        The design's scrambling seed.

    Returns
    -------
    list of dict
    """
    from SALib.sample import sobol

    problem, _ = sobol_problem(space)
    x = sobol.sample(problem, n, calc_second_order=False, scramble=True, seed=seed)
    numeric = [p for p in space.values() if not p.categorical]
    return [{p.name: float(np.exp(v) if p.log else v) for p, v in zip(numeric, row, strict=True)}
            for row in x]


def _scores(sample, space, base, claims, reading, cache, evaluate):
    """One rotor of the design: each claim's term of the objective; None if refused."""
    from ..attribution.evaluate import RunSettings
    from .analysis import claim_scores
    from .evaluate import evaluate_rotor

    try:
        cfg = recalibrated(apply_sample(base, space, sample))
    except Refused:
        return None
    if evaluate is None:
        t = evaluate_rotor(cfg, claims, (reading,), cache=cache,
                           settings=RunSettings(base=cfg))[reading]
    else:
        t = evaluate(cfg, claims)
    return claim_scores(dict(zip(t["id"], t["status"], strict=True)),
                        {i: (None if not np.isfinite(m) else m)
                         for i, m in zip(t["id"], t["margin"].to_numpy(float), strict=True)})


def sobol_indices(claims, n: int = 8, *, seed: int = 0, cache, evaluate=None,
                  reading: str = "continued", progress: bool = False,
                  n_jobs: int = 1) -> tuple[pd.DataFrame, dict]:
    """S1 and ST of each claim's term of the objective, per group of parameters.

    Parameters
    ----------
    claims : list of Claim
        The claims (a cheap subset for a small budget).
    n : int
        SALib's base sample size (a power of 2).
    seed : int
        The design's and the bootstrap's seed.
    cache : tefcore.paper.attribution.evaluate.FigureCache
        Where the figures are kept.
    evaluate : callable, optional
        ``(cfg, claims) -> table`` (status, margin, id); default the claims'
        own checks without refinement.
    reading : str
        The reading of the mode names.
    progress : bool
        Show a progress bar over the design.
    n_jobs : int
        Processes over the design's rotors (joblib; bounded by the machine,
        :func:`tefcore.runtime.process_cap`); 1 runs them here, in order.

    Returns
    -------
    tuple of (pandas.DataFrame, dict)
        ``claim, group, S1, S1_conf, ST, ST_conf``; and ``{"rotors", "refused",
        "n"}``.
    """
    from SALib.analyze import sobol as analyze

    from ..figures.runs import base_config

    space = load_space()
    problem, _ = sobol_problem(space)
    samples = sobol_design(space, n, seed)
    base = base_config("thin_airfoil")
    args = (space, base, claims, reading, cache, evaluate)
    if n_jobs > 1:
        from joblib import Parallel, delayed

        from ...runtime import process_cap

        jobs = Parallel(n_jobs=process_cap(n_jobs, len(samples), "rotor")[0],
                        return_as="generator")(
            delayed(_scores)(s, *args) for s in samples)
    else:
        jobs = (_scores(s, *args) for s in samples)
    if progress:
        from tqdm.auto import tqdm

        jobs = tqdm(jobs, total=len(samples), unit="rotor", desc="Sobol design")
    rows = list(jobs)
    refused = sum(r is None for r in rows)
    ids = [c.id for c in claims]
    y = pd.DataFrame([r if r is not None else {} for r in rows], columns=ids, dtype=float)
    y = y.fillna(y.mean())
    out = []
    for cid in ids:
        v = y[cid].to_numpy(float)
        if not np.all(np.isfinite(v)) or np.ptp(v) == 0:
            continue
        res = analyze.analyze(problem, v, calc_second_order=False, conf_level=0.95,
                              num_resamples=200, seed=seed)
        names = sorted(set(problem["groups"]), key=problem["groups"].index)
        for i, g in enumerate(names):
            out.append({"claim": cid, "group": g, "S1": res["S1"][i],
                        "S1_conf": res["S1_conf"][i], "ST": res["ST"][i],
                        "ST_conf": res["ST_conf"][i]})
    return pd.DataFrame(out), {"rotors": len(samples), "refused": refused, "n": n}
