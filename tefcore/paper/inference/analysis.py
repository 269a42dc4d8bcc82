"""What a study says: best rotors, failures met, held-out checks, leave-one-figure-out, conflicts.

Every trial of a study records, for every reading, each fitted claim's status
and margin (:class:`tefcore.paper.inference.study.Objective`), so these
functions read the trials without computing anything, except
:func:`check_rotor`, which checks a rotor on any claims (the held-out ones
after the study: never inside it).

* :func:`trials_frame`: one row per completed trial, its parameters and each
  reading's objective and pass count;
* :func:`failures`: refused samples, failed trials, figures not computable;
* :func:`leave_one_figure_out`: for each fitted figure F, the best trial by
  the objective without F's claims, and how F's claims fare there.  On a
  sampler independent of the objective (``qmc``, ``random``) this is exactly a
  fit without F over that sample; on TPE the sampling itself was guided by F
  too, which the result says;
* :func:`conflicts` and :func:`pareto_front`: claims whose margins pull against
  each other over the trials, and the trials no other beats on all of them;
* :func:`agreement`: whether the studies of one reading (other samplers, other
  seeds) end at the same rotor -- each study's best, and the parameters on
  which the bests lie further apart than :data:`AGREE` of their range.

Examples
--------
>>> scores = claim_scores({"a": "pass", "b": "fail", "c": "ambiguous"},
...                       {"a": 0.5, "b": None, "c": None})
>>> [round(v, 3) for v in scores.values()]
[0.462, -1.0, 0.0]
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .evaluate import objective

__all__ = ["AGREE", "agreement", "check_rotor", "claim_scores", "conflicts", "failures",
           "leave_one_figure_out", "pareto_front", "pass_rates", "trial_claims",
           "trials_frame"]

#: Two studies' best rotors agree on a parameter when they lie within this share of
#: its declared range (a log range measured in its logarithm; a choice: the same
#: one).  A quarter: the spread of the trials within one claim of the best is
#: itself a third to a half of most ranges (the packaged studies), so a closer
#: agreement would ask more of the bests than the landscape can say.
AGREE = 0.25


def claim_scores(statuses: dict, margins: dict, ambiguous: float = 0.0,
                 no_margin_fail: float = -1.0) -> dict:
    """Each claim's share of the objective (:func:`~tefcore.paper.inference.evaluate.objective`).

    Parameters
    ----------
    statuses, margins : dict
        Claim id -> status, and -> margin (None where there is none).
    ambiguous, no_margin_fail : float
        The protocol's values for claims without a margin.

    Returns
    -------
    dict
        Claim id -> its term of the sum.
    """
    out = {}
    for cid, status in statuses.items():
        m = margins.get(cid)
        t = pd.DataFrame({"status": [status], "margin": [np.nan if m is None else m]})
        out[cid] = objective(t, ambiguous, no_margin_fail)
    return out


def _completed(study):
    from optuna.trial import TrialState

    return study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))


def trials_frame(study, readings=("continued", "flutter")) -> pd.DataFrame:
    """One row per completed trial: number, parameters, each reading's objective and passes.

    Parameters
    ----------
    study : optuna.Study
        The study.
    readings : tuple of str
        The readings whose columns are wanted.

    Returns
    -------
    pandas.DataFrame
        ``number``, the parameters, ``<reading> objective``, ``<reading> passes``,
        ``cpu_s`` and ``broken`` (figures not computable).
    """
    rows = []
    for t in _completed(study):
        row = {"number": t.number, **t.params}
        for r in readings:
            if f"{r}:objective" in t.user_attrs:
                row[f"{r} objective"] = t.user_attrs[f"{r}:objective"]
                row[f"{r} passes"] = t.user_attrs[f"{r}:passes"]
        row["cpu_s"] = t.user_attrs.get("cpu_s", np.nan)
        row["broken"] = ", ".join(sorted(t.user_attrs.get("broken", {})))
        rows.append(row)
    return pd.DataFrame(rows)


def trial_claims(trial, reading: str) -> pd.DataFrame:
    """A trial's fitted claims under `reading`: ``id``, ``status``, ``margin``, ``score``.

    Parameters
    ----------
    trial : optuna.trial.FrozenTrial
        A completed trial of a study.
    reading : str
        The reading.

    Returns
    -------
    pandas.DataFrame
    """
    st = trial.user_attrs[f"{reading}:statuses"]
    mg = trial.user_attrs[f"{reading}:margins"]
    sc = claim_scores(st, mg)
    return pd.DataFrame({"id": list(st), "status": list(st.values()),
                         "margin": [np.nan if mg.get(i) is None else mg[i] for i in st],
                         "score": [sc[i] for i in st]})


def failures(study) -> dict:
    """What the study met in the space: refused samples, failed trials, figures not computable.

    Parameters
    ----------
    study : optuna.Study
        The study.

    Returns
    -------
    dict
        ``refused`` (pruned: physically impossible samples) with their
        reasons' first words counted, ``failed`` (trials that raised or whose
        worker died), ``not_computable`` (figure -> trials where it could not
        be computed) and ``completed``.
    """
    from collections import Counter

    from optuna.trial import TrialState

    trials = study.get_trials(deepcopy=False)
    refused = [t for t in trials if t.state == TrialState.PRUNED]
    reasons = Counter(t.user_attrs.get("refused", "")[:60] for t in refused)
    broken = Counter(f for t in trials for f in t.user_attrs.get("broken", {}))
    return {"completed": sum(t.state == TrialState.COMPLETE for t in trials),
            "refused": len(refused), "refused_reasons": dict(reasons),
            "failed": sum(t.state == TrialState.FAIL for t in trials),
            "not_computable": dict(broken)}


def _figure_of(cid: str) -> str:
    """The figure of a claim id (``fig12b-...`` -> ``fig12``, ``fig16a-...`` -> ``fig16a``)."""
    head = cid.split("-", 1)[0]
    return head if head in ("fig16a", "fig16b") else head.rstrip("ab")


def leave_one_figure_out(study, reading: str, figures) -> pd.DataFrame:
    """For each fitted figure F: the best trial without F's claims, and F's claims there.

    Parameters
    ----------
    study : optuna.Study
        The study.
    reading : str
        The reading the objective is read under.
    figures : iterable of str
        The fitted figures (the protocol's ``fit_figures``).

    Returns
    -------
    pandas.DataFrame
        ``figure``, ``claims`` (F's fitted claims), ``best trial without``,
        ``passes there`` (F's claims that pass at that trial), ``passes at best``
        (at the best trial with every fitted claim), ``guided`` (True when the
        sampler read F's claims while sampling: TPE, NSGA-II).
    """
    trials = _completed(study)
    guided = study.user_attrs.get("sampler", "tpe") in ("tpe", "nsga2")
    scored = [(t, trial_claims(t, reading)) for t in trials
              if f"{reading}:statuses" in t.user_attrs]
    if not scored:
        return pd.DataFrame()
    full = max(scored, key=lambda p: p[1]["score"].sum())
    rows = []
    for f in figures:
        def mine(table, f=f):
            return table["id"].map(_figure_of) == f
        best = max(scored, key=lambda p: p[1].loc[~mine(p[1]), "score"].sum())
        tb, tf = best[1], full[1]
        rows.append({"figure": f, "claims": int(mine(tb).sum()),
                     "best trial without": best[0].number,
                     "passes there": int((tb.loc[mine(tb), "status"] == "pass").sum()),
                     "passes at best": int((tf.loc[mine(tf), "status"] == "pass").sum()),
                     "guided": guided})
    return pd.DataFrame(rows)


def conflicts(study, reading: str, threshold: float = -0.3) -> pd.DataFrame:
    """Pairs of fitted claims whose scores fall as the other's rise, over the trials.

    Spearman's rank correlation of the two claims' terms of the objective over
    the completed trials; pairs below `threshold` (and where both vary).

    Parameters
    ----------
    study : optuna.Study
        The study (a sample independent of the objective, QMC, reads best).
    reading : str
        The reading.
    threshold : float
        The largest rank correlation reported.

    Returns
    -------
    pandas.DataFrame
        ``a``, ``b``, ``rho``, sorted most negative first.
    """
    scored = pd.DataFrame({t.number: trial_claims(t, reading).set_index("id")["score"]
                           for t in _completed(study)
                           if f"{reading}:statuses" in t.user_attrs}).T
    scored = scored.loc[:, scored.std() > 1e-9]
    if scored.shape[0] < 4 or scored.shape[1] < 2:
        return pd.DataFrame(columns=["a", "b", "rho"])
    rho = scored.corr(method="spearman")
    cols = list(rho.columns)
    rows = [{"a": a, "b": b, "rho": float(rho.loc[a, b])}
            for i, a in enumerate(cols) for b in cols[i + 1:] if rho.loc[a, b] < threshold]
    return pd.DataFrame(rows, columns=["a", "b", "rho"]).sort_values("rho", ignore_index=True)


def pass_rates(studies, reading: str) -> pd.DataFrame:
    """How often each fitted claim passes over the completed trials, and its best margin.

    A claim no sampled rotor passes is out of reach of the space as far as the
    sample shows: no buildable choice of the assumed properties fixes it.

    Parameters
    ----------
    studies : sequence of optuna.Study
        Studies of one protocol (their trials are pooled).
    reading : str
        The reading.

    Returns
    -------
    pandas.DataFrame
        ``id``, ``passes``, ``trials``, ``best margin``; the rarest passes first.
    """
    rows: dict = {}
    for s in studies:
        for t in _completed(s):
            if f"{reading}:statuses" not in t.user_attrs:
                continue
            for _, r in trial_claims(t, reading).iterrows():
                e = rows.setdefault(r["id"], {"id": r["id"], "passes": 0, "trials": 0,
                                              "best margin": -np.inf})
                e["passes"] += r["status"] == "pass"
                e["trials"] += 1
                if np.isfinite(r["margin"]):
                    e["best margin"] = max(e["best margin"], float(r["margin"]))
    out = pd.DataFrame(list(rows.values()), columns=["id", "passes", "trials", "best margin"])
    return out.sort_values(["passes", "best margin"], ignore_index=True)


def pareto_front(study, reading: str, claim_ids) -> pd.DataFrame:
    """The trials no other trial beats on every one of `claim_ids` (their objective terms).

    Parameters
    ----------
    study : optuna.Study
        The study.
    reading : str
        The reading.
    claim_ids : sequence of str
        The claims whose terms are compared.

    Returns
    -------
    pandas.DataFrame
        ``number`` and one column per claim (its term), the non-dominated
        trials only, sorted by the first claim.
    """
    ids = list(claim_ids)
    rows = []
    for t in _completed(study):
        if f"{reading}:statuses" not in t.user_attrs:
            continue
        sc = trial_claims(t, reading).set_index("id")["score"]
        rows.append({"number": t.number, **{i: float(sc.get(i, np.nan)) for i in ids}})
    frame = pd.DataFrame(rows)
    if frame.empty:
        return frame
    v = frame[ids].to_numpy(float)
    keep = [not any(np.all(o >= p) and np.any(o > p) for o in v) for p in v]
    return frame[keep].sort_values(ids[0], ignore_index=True)


def check_rotor(params: dict, claims, readings=("continued", "flutter"), *, cache,
                protocol=None, refine: bool = True) -> dict:
    """Check a rotor of the space (a trial's parameters) on `claims`, with refinement.

    The check after a study: every claim a table reports (fitted and held
    out), with the sweeps' mode identity refined between points as the
    notebooks do.

    Parameters
    ----------
    params : dict
        Parameter name -> value (a trial's ``params``).
    claims : list of Claim
        Every claim to check.
    readings : tuple of str
        The readings of the mode names.
    cache : tefcore.paper.attribution.evaluate.FigureCache
        Where the figures are kept.
    protocol : Protocol, optional
        Default the packaged one.
    refine : bool
        Refine the mode identity between sweep points (the notebooks' way).

    Returns
    -------
    dict
        As :func:`tefcore.paper.inference.evaluate.evaluate_rotor`.
    """
    from ..attribution.evaluate import RunSettings
    from ..figures.runs import base_config
    from .evaluate import evaluate_rotor
    from .protocol import load_protocol
    from .space import apply_sample, load_space, recalibrated

    protocol = protocol or load_protocol()
    cfg = apply_sample(base_config("thin_airfoil"), load_space(protocol.space), params)
    if protocol.torsion == "recalibrated":
        cfg = recalibrated(cfg)
    return evaluate_rotor(cfg, claims, readings, cache=cache,
                          settings=RunSettings(base=cfg, refine=refine),
                          flutter_quantities=protocol.flutter_quantities)


def _position(p, v) -> float:
    """Where `v` lies in parameter `p`'s declared range, 0 at ``low`` and 1 at ``high``."""
    if p.log:
        return float((np.log(v) - np.log(p.low)) / (np.log(p.high) - np.log(p.low)))
    return float((v - p.low) / (p.high - p.low))


def agreement(studies, reading: str, space, within: float = AGREE) -> dict:
    """Do the studies of one reading, by other samplers and seeds, end at the same rotor?

    Parameters
    ----------
    studies : sequence of optuna.Study
        The studies (those without a completed trial of `reading` are left out).
    reading : str
        The reading whose objective ranks the trials.
    space : dict
        :func:`tefcore.paper.inference.space.load_space` (the declared ranges).
    within : float
        Share of a range within which two bests agree (:data:`AGREE`).

    Returns
    -------
    dict
        ``studies``: per study its name, best trial, objective and fitted
        passes; ``apart``: per parameter on which the bests disagree, the
        parameter and each study's value there (its position in the range
        for a number); ``objective_spread``: the best objective's range over
        the studies; ``same``: True when no parameter is apart.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> import optuna
    >>> optuna.logging.set_verbosity(optuna.logging.WARNING)
    >>> from tefcore.paper.inference.space import Parameter
    >>> space = {"m": Parameter("m", "value", ("flap.mass",), low=0.0, high=1.0)}
    >>> def study(name, m, obj):
    ...     s = optuna.create_study(study_name=name, direction="maximize")
    ...     t = optuna.trial.create_trial(params={"m": m}, value=obj,
    ...         distributions={"m": optuna.distributions.FloatDistribution(0, 1)},
    ...         user_attrs={"continued:objective": obj, "continued:passes": 3})
    ...     s.add_trial(t)
    ...     return s
    >>> a = agreement([study("a", 0.2, 5.0), study("b", 0.7, 4.0)], "continued", space)
    >>> a["same"], a["apart"][0]["parameter"], a["objective_spread"]
    (False, 'm', 1.0)
    """
    bests = []
    for s in studies:
        done = [t for t in _completed(s) if f"{reading}:objective" in t.user_attrs]
        if done:
            best = max(done, key=lambda t: t.user_attrs[f"{reading}:objective"])
            bests.append((s.study_name, best))
    rows = [{"study": n, "trial": t.number, "objective": t.user_attrs[f"{reading}:objective"],
             "passes": t.user_attrs[f"{reading}:passes"]} for n, t in bests]
    apart = []
    for name, p in space.items():
        values = [t.params.get(name) for _, t in bests]
        if len(values) < 2 or any(v is None for v in values):
            continue
        if p.categorical:
            far = len(set(values)) > 1
            shown = [str(v) for v in values]
        else:
            pos = [_position(p, float(v)) for v in values]
            far = max(pos) - min(pos) > within
            shown = [round(x, 2) for x in pos]
        if far:
            apart.append({"parameter": name, "values": dict(zip([n for n, _ in bests], shown,
                                                                 strict=True))})
    objs = [r["objective"] for r in rows]
    return {"studies": rows, "apart": apart,
            "objective_spread": float(max(objs) - min(objs)) if objs else 0.0,
            "same": not apart}
