"""The packaged configuration variants, and every claim checked on each of them.

tefcore ships three configurations of the MDART rotor (``tefcore/data``):
``mdart``, the default; ``mdart-fig6``, the same rotor with the actuator's
moving parts reflected to the flap hinge fitted to Fig. 6
(:mod:`tefcore.paper.fig6_calibration`); and ``mdart-inferred``, its unknown
properties inferred from the paper's claims (:mod:`tefcore.paper.inference`).
``variants.toml`` beside this module says which is the default and why, which
claims each variant is calibrated to (``mdart-fig6``: Fig. 6's, a validation
claim of ``mdart``), each variant's recorded claim statuses (``mdart``'s are
those of the reference data), and the physics of every claim whose status
differs between them.

* :func:`apply_variant` tags and records a claims table for the variant it was
  computed on (the notebooks' claims on ``-p config mdart-fig6``);
* :func:`variant_claims` checks the claims of some figures on a variant
  (:func:`tefcore.paper.claims.validation.validate_all`), which ``tefcore reproduce``
  runs for the variant the notebooks did not
  (:mod:`tefcore.paper.run.variant_runs`);
* :func:`compare_variants` puts the variants' statuses side by side with the
  explanation of each difference.

Examples
--------
>>> v = load_variants()
>>> DEFAULT_VARIANT, sorted(v)
('mdart', ['mdart', 'mdart-fig6', 'mdart-inferred'])
>>> v["mdart-fig6"].calibration
('fig6-response-15pct-above-input',)
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from functools import cache
from importlib import resources

import pandas as pd

__all__ = ["DEFAULT_VARIANT", "Variant", "apply_variant", "compare_variants",
           "comparison_variants", "default_reason", "load_variants", "variant_claims",
           "variant_name"]

#: The configuration the notebooks, the sweeps and the CLI use unless told otherwise.
DEFAULT_VARIANT = "mdart"


@dataclass(frozen=True)
class Variant:
    """A packaged configuration and what is recorded about its claims.

    Parameters
    ----------
    config : str
        Its name in ``tefcore/data`` (``load_config(config)``).
    summary : str
        One sentence: what it is.
    calibration : tuple of str
        Claims it is calibrated to, besides the reference data's calibration
        claims: tagged ``calibration`` on it (never scored).
    recorded_status : dict
        Claim id -> its status when last recorded on this variant (empty for
        the default, whose statuses are the reference data's).
    differences : dict
        Claim id -> ``{"statuses": {variant: status}, "why": text}``: the
        physics of a status that differs between this variant and the default,
        written for that pair of statuses (:func:`compare_variants` uses it only
        for that pair).
    """

    config: str
    summary: str
    calibration: tuple = ()
    recorded_status: dict = field(default_factory=dict)
    differences: dict = field(default_factory=dict)


@cache
def _data() -> dict:
    return tomllib.loads(resources.files(__package__).joinpath("variants.toml")
                         .read_text(encoding="utf-8"))


@cache
def load_variants() -> dict:
    """The variants of ``variants.toml``, by configuration name, the default first.

    Returns
    -------
    dict of str to Variant

    Raises
    ------
    ValueError
        A variant naming no packaged configuration, an unknown status, or a
        default that is not among the variants.  (Its claim ids are those of
        the shipped reference data, which a user may replace,
        ``$TEFCORE_REFERENCE_DATA``: they are checked by the tests, not here.)
    """
    from ...config.io import available_configs
    from .reference import STATUSES

    data = _data()
    out = {}
    for raw in data["variant"]:
        v = Variant(config=raw["config"], summary=raw["summary"].strip(),
                    calibration=tuple(raw.get("calibration", ())),
                    recorded_status=dict(raw.get("recorded_status", {})),
                    differences={k: {"why": " ".join(d["why"].split()),
                                     "statuses": {n: s for n, s in d.items() if n != "why"}}
                                 for k, d in raw.get("differences", {}).items()})
        if v.config not in available_configs():
            raise ValueError(f"variants.toml: no packaged configuration {v.config!r}")
        bad = {s for s in v.recorded_status.values() if s not in STATUSES} | {
            s for d in v.differences.values() for s in d["statuses"].values()
            if s not in STATUSES}
        if bad:
            raise ValueError(f"variants.toml: variant {v.config!r}: unknown status(es) "
                             f"{sorted(bad)}")
        out[v.config] = v
    if data["default"] != DEFAULT_VARIANT or DEFAULT_VARIANT not in out:
        raise ValueError(f"variants.toml: the default must be {DEFAULT_VARIANT!r}")
    return {DEFAULT_VARIANT: out[DEFAULT_VARIANT]} | out


def default_reason() -> str:
    """Why the default variant is the default (markdown, from ``variants.toml``)."""
    return " ".join(_data()["default_reason"].split())


def variant_name(cfg) -> str | None:
    """The variant a configuration is (its ``name``), or None for another rotor.

    Parameters
    ----------
    cfg : tefcore.config.configuration.Config or str or None
        A configuration, a configuration's name, or None (the default variant).
    """
    name = DEFAULT_VARIANT if cfg is None else cfg if isinstance(cfg, str) else cfg.name
    return name if name in load_variants() else None


def apply_variant(claims: pd.DataFrame, cfg) -> pd.DataFrame:
    """A claims table as checked on ``cfg``'s variant: its calibration tags and records.

    On a variant other than the default, the claims it is calibrated to are
    tagged ``calibration`` and ``recorded_status`` is the variant's (claims
    it has no record of get ``""``: never a regression).  The default's table
    and another rotor's are returned unchanged.

    Parameters
    ----------
    claims : pandas.DataFrame
        Claims with ``id``, ``tag`` and ``recorded_status``.
    cfg : tefcore.config.configuration.Config or str or None
        What the claims were computed on.

    Returns
    -------
    pandas.DataFrame
        A copy.
    """
    name = variant_name(cfg)
    out = claims.copy()
    if name is None or name == DEFAULT_VARIANT or out.empty:
        return out
    v = load_variants()[name]
    out.loc[out["id"].isin(v.calibration), "tag"] = "calibration"
    out["recorded_status"] = out["id"].map(v.recorded_status).fillna("")
    return out


def comparison_variants(base) -> list[str]:
    """The variants a reproduction on ``base`` also checks its claims on.

    Parameters
    ----------
    base : str or None
        The notebooks' ``config`` parameter (None: the default).

    Returns
    -------
    list of str
        Every other packaged variant when ``base`` is one; ``[]`` for another
        rotor (a comparison with the MDART variants would not say what differs).
    """
    name = variant_name(base)
    return [] if name is None else [v for v in load_variants() if v != name]


def variant_claims(name: str, figures=None, n_jobs: int = 1) -> pd.DataFrame:
    """The claims of ``figures`` checked on variant ``name``, tagged and recorded for it.

    Parameters
    ----------
    name : str
        A packaged variant.
    figures : iterable of str, optional
        Paper figures whose claims to check (default all); the figures their
        comparison claims need are computed too.
    n_jobs : int
        Processes of each sweep.

    Returns
    -------
    pandas.DataFrame
        :func:`tefcore.paper.claims.validation.validate_all`'s table through
        :func:`apply_variant`, with the converged-basis columns of
        :func:`tefcore.paper.claims.truncation.mark_truncation`.
    """
    from ...config.io import load_config
    from .reference import load_claims
    from .validation import validate_all

    claims = load_claims()
    if figures is not None:
        figures = set(figures)
        claims = [c for c in claims if c.figure in figures]
    from .truncation import load_converged, mark_truncation

    cfg = load_config(name)
    table = validate_all(n_jobs=n_jobs, claims=claims, cfg=cfg)
    # each claim's verdict on its figure's converged basis, where one is stored
    # for this variant (converged_basis-<name>.csv): a differing verdict is
    # truncation-dependent
    return mark_truncation(apply_variant(table, name), load_converged(cfg))


def _why(row: dict, names) -> str:
    """The explanation of a row's statuses, if ``variants.toml`` has one for them."""
    live = {n: row[f"status {n}"] for n in names}
    written = []
    for v in load_variants().values():
        d = v.differences.get(row["id"])
        if d is None:
            continue
        if all(live.get(n) == s for n, s in d["statuses"].items()):
            return d["why"]
        written.append(", ".join(f"{n} {s}" for n, s in d["statuses"].items()))
    return "not explained" + (f" (explained for {'; '.join(written)})" if written else "")


def compare_variants(tables: dict) -> pd.DataFrame:
    """The variants' claims side by side, with the physics of every status difference.

    Parameters
    ----------
    tables : dict
        Variant name -> its claims table (``id, figure, tag, status,
        computed``), the default's first.

    Returns
    -------
    pandas.DataFrame
        One row per claim: ``id, figure``, then per variant ``status <v>``,
        ``tag <v>`` and ``computed <v>``, ``differs`` (the statuses differ) and
        ``why``: the explanation ``variants.toml`` gives for exactly these
        statuses, else ``"not explained"`` (saying for which statuses an
        explanation was written, if one was), so that a change shows.
    """
    names = list(tables)
    keep = ["id", "figure", "tag", "status", "computed"]
    out = None
    for n in names:
        t = tables[n].reindex(columns=keep).fillna("").astype(str).rename(
            columns={k: f"{k} {n}" for k in ("tag", "status", "computed")})
        out = t if out is None else out.merge(t, on=["id", "figure"], how="outer")
    status = out[[f"status {n}" for n in names]].fillna("")
    out["differs"] = status.nunique(axis=1) > 1
    out["why"] = [_why(row, names) if row["differs"] else ""
                  for row in out.to_dict("records")]
    order = {c: i for i, c in enumerate(tables[names[0]]["id"])}
    return out.sort_values("id", key=lambda s: s.map(order).fillna(len(order)),
                           ignore_index=True).fillna("")
