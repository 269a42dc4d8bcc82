"""The packaged variant ``mdart-inferred``, written from a study's best rotor.

:func:`inferred_rotor` takes a study's best trial by one reading's objective
and the spread of each parameter over the trials within one claim of it (an
objective no more than 1 below the best: as good, to one claim's worth);
:func:`inferred_config` makes the configuration, each inferred field's
source saying ``inferred: from claims ..., study ..., spread [lo, hi]``;
:func:`write_inferred` writes it as ``tefcore/data/mdart-inferred.toml``
(``load_config("mdart-inferred")``).  The default ``mdart`` is never
changed.

Examples
--------
>>> spread_text(0.3, 0.41, "lb/ft")
'spread [0.3, 0.41] lb/ft'
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["WITHIN", "inferred_config", "inferred_rotor", "spread_text", "write_inferred"]

#: Trials whose objective is within this of the best make a parameter's spread: one
#: claim's worth of the sum of tanh(margin).
WITHIN = 1.0


def spread_text(lo: float, hi: float, unit: str = "") -> str:
    """``"spread [lo, hi] unit"`` with 3 significant digits.

    Parameters
    ----------
    lo, hi : float
        The ends.
    unit : str
        Written after them.

    Returns
    -------
    str
    """
    return f"spread [{lo:.3g}, {hi:.3g}]" + (f" {unit}" if unit else "")


def _claims_text(fitted_ids) -> str:
    """``"the 28 fitted claims (6 calibration, Figs. 10a, 11a; 22 of Figs. 6, 7, ...)"``."""
    from ..claims.reference import load_claims

    tags = {c.id: (c.tag, c.figure, c.panel) for c in load_claims()}
    cal = [tags[i] for i in fitted_ids if tags[i][0] == "calibration"]
    val = [tags[i] for i in fitted_ids if tags[i][0] != "calibration"]

    def figs(rows, panel):
        names = {f.removeprefix("fig") + (p if panel else "") for _, f, p in rows}
        return ", ".join(sorted(names, key=lambda n: (int(n.rstrip("ab")), n)))
    return (f"the {len(fitted_ids)} fitted claims ({len(cal)} calibration, Figs. "
            f"{figs(cal, True)}; {len(val)} of Figs. {figs(val, False)})")


def inferred_rotor(studies, reading: str, within: float = WITHIN) -> dict:
    """The best rotor of one or more studies by `reading`, and each parameter's spread.

    Only a rotor whose calibration claims pass (the four stated torsion
    frequencies and their trends: facts of the paper, not fitted preferences)
    can be the inferred rotor; the torsion re-fit leaves some samples outside
    their 2 % tolerance.

    Parameters
    ----------
    studies : sequence of optuna.Study
        Studies of one protocol (their trials are pooled).
    reading : str
        The reading whose objective ranks the trials.
    within : float
        The spread is taken over the trials whose objective is within this of
        the best.

    Returns
    -------
    dict
        ``params`` (the best trial's), ``spread`` (name -> (lo, hi), or the
        choices seen for a choice), ``trial`` (study name, number),
        ``objective``, ``passes``, ``near`` (how many trials make the spread).
    """
    from optuna.trial import TrialState

    from ..claims.reference import load_claims

    stated = [c.id for c in load_claims() if c.tag == "calibration"]

    def keeps_stated(t):
        st = t.user_attrs[f"{reading}:statuses"]
        return all(st.get(i) == "pass" for i in stated if i in st)

    pooled = [(s.study_name, t) for s in studies
              for t in s.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))
              if f"{reading}:objective" in t.user_attrs and keeps_stated(t)]
    if not pooled:
        raise ValueError(f"no completed trial with the {reading} reading passes the "
                         "calibration claims")
    key = f"{reading}:objective"
    name, best = max(pooled, key=lambda p: p[1].user_attrs[key])
    top = best.user_attrs[key]
    near = [t for _, t in pooled if t.user_attrs[key] >= top - within]
    spread = {}
    for p, v in best.params.items():
        seen = [t.params[p] for t in near if p in t.params]
        spread[p] = (sorted(set(seen)) if isinstance(v, str)
                     else (float(np.min(seen)), float(np.max(seen))))
    return {"params": dict(best.params), "spread": spread, "trial": (name, best.number),
            "objective": float(top), "passes": int(best.user_attrs[f"{reading}:passes"]),
            "near": len(near)}


def inferred_config(rotor: dict, fitted_ids, *, name: str = "mdart-inferred",
                    protocol=None):
    """The configuration of an inferred rotor, every inferred field's source saying how.

    Parameters
    ----------
    rotor : dict
        :func:`inferred_rotor`.
    fitted_ids : sequence of str
        The claims the study fitted (named in each source).
    name : str
        The configuration's name.
    protocol : Protocol, optional
        Default the packaged one.

    Returns
    -------
    tefcore.config.configuration.Config
    """
    from ..figures.runs import base_config
    from .protocol import load_protocol
    from .space import apply_sample, load_space, recalibrated

    protocol = protocol or load_protocol()
    space = load_space(protocol.space)
    base = base_config("thin_airfoil")
    cfg = apply_sample(base, space, rotor["params"])
    if protocol.torsion == "recalibrated":
        cfg = recalibrated(cfg)
    study, number = rotor["trial"]
    claims = _claims_text(fitted_ids)
    sources = dict(cfg.sources)
    for pname, p in space.items():
        v, s = rotor["params"][pname], rotor["spread"][pname]
        where = (f"choices within one claim of the best: {', '.join(s)}" if p.categorical
                 else spread_text(*s, p.unit))
        shown = v if p.categorical else f"{v:.4g}" + (f" {p.unit}" if p.unit else "")
        for f in p.fields + (("blade.mass_scale",) if p.keeps else ()):
            sources[f] = (f"inferred: {pname} = {shown} (the space's range {p.low:g}-"
                          f"{p.high:g}{' ' + p.unit if p.unit else ''}: {p.kind}) from {claims}, "
                          f"study {study} trial {number}, {where}; the range's argument: "
                          f"{p.source}") if not p.categorical else (
                          f"inferred: {pname} = {shown} from {claims}, study {study} trial "
                          f"{number}, {where}")
    for f in ("blade.gj_scale", "hub.pitch_horn_arm", "hub.pitch_link_stiffness"):
        sources[f] = ("inferred: re-fitted (python -m tefcore.paper.calibration, least squares) "
                      "to the four stated first-torsion frequencies of Figs. 10a/11a with the "
                      f"inferred section and flap, study {study} trial {number}")
    return dataclasses.replace(cfg, name=name, sources=sources,
                               description="MDART with its unknown properties inferred from "
                                           "the paper's claims (tefcore infer)")


def write_inferred(cfg, path, header: str) -> None:
    """Write the configuration as TOML with a `header` comment (atomically).

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config
        :func:`inferred_config`.
    path : path
        The file written.
    header : str
        Lines of text put first as ``#`` comments.
    """
    from ...config.io import dumps_config
    from ...safe_io import atomic_write_text

    lines = "".join(f"# {h}".rstrip() + "\n" for h in header.splitlines())
    atomic_write_text(path, lines + dumps_config(cfg))
