"""What the report says in words, made from the run's tables.

* :func:`headline` -- the report's first paragraph, three sentences made
  from the claims table: what reproduces, what does not, the key finding
  (where the paper's TEF mode goes unstable, what the computed roots do);
* :func:`why_view` -- "why we differ" for a first-time reader: each failing
  claim with its sentence, each lever with what it sets, its units and its
  plausible range;
* :func:`shared_notes` -- the sentences every stability figure's caption
  repeats (how to read the lines and markers), said once;
* :func:`check_rows` -- the stated blade frequencies with named columns and
  units;
* :func:`notebook_title` -- a notebook's own title (its first heading);
* :func:`inference_view` -- "what the paper's rotor must have been": the
  packaged inference studies, the inferred rotor against the assumed one, the
  fitted and held-out pass rates.

Examples
--------
>>> claims = pd.DataFrame({"id": ["a", "b"], "figure": ["fig10", "fig9"],
...                        "tag": ["validation"] * 2, "status": ["pass", "fail"],
...                        "mode": ["", ""], "kind": ["trend", "trend"],
...                        "statement": ["s", "t"], "computed": ["", ""],
...                        "computed_value": ["", ""], "reason": ["", ""]})
>>> print(headline(claims))  # doctest: +NORMALIZE_WHITESPACE
1 of the paper's 2 validation claims reproduce, among them every statement on Fig. 10.
1 does not (on Fig. 9).
"""

from __future__ import annotations

import json
import re
from functools import cache
from pathlib import Path

import pandas as pd

__all__ = ["CHECK_COLUMNS", "check_rows", "headline", "inference_view", "notebook_title",
           "setting_unit", "shared_notes", "why_view"]

#: The stated blade frequencies' columns as the report names them.
CHECK_COLUMNS = {"case": "case", "stated_per_rev": "stated torsion 1 [/rev]",
                 "computed_per_rev": "model torsion 1 [/rev]",
                 "error_percent": "model − stated [%]", "flap1_per_rev": "model flap 1 [/rev]",
                 "lag1_per_rev": "model lag 1 [/rev]"}


def _figs(keys) -> str:
    """``["fig9", "fig16a"]`` as ``"Figs. 9 and 16a"``."""
    nums = [str(k).replace("fig", "") for k in dict.fromkeys(keys)]
    if not nums:
        return ""
    if len(nums) == 1:
        return f"Fig. {nums[0]}"
    return "Figs. " + ", ".join(nums[:-1]) + " and " + nums[-1]


def _fig_order(key: str) -> tuple:
    m = re.match(r"fig(\d+)(\w*)", str(key))
    return (int(m.group(1)), m.group(2)) if m else (999, str(key))


def _stays_stable(row) -> bool:
    """Whether a claim's computed TEF root is stable everywhere it was checked."""
    text = str(row["computed"])
    if "unstable on none" in text:
        return True
    m = re.search(r"real part (-?[\d.]+(?:e[+-]?\d+)?)(?: to (-?[\d.]+(?:e[+-]?\d+)?))? 1/rev",
                  text)
    return m is not None and float(m.group(2) or m.group(1)) < 0


def _key_finding(v: pd.DataFrame) -> str:
    """The key finding: where the paper's TEF mode goes unstable, what the computation gives."""
    col = v["mode"].astype(str)
    onset = v[(col == "TEF") & v["kind"].isin(["threshold", "range", "value"])
              & v["statement"].str.contains("unstable", case=False)]
    decided = onset[onset["status"].isin(["pass", "fail"])]
    stable = decided[(decided["status"] == "fail") & decided.apply(_stays_stable, axis=1)]
    root = v[(col == "flutter root") & (v["computed_value"].astype(str) != "")]
    if decided.empty:
        return ""
    text = (f"The key finding: of the {len(decided)} "
            f"{'statement' if len(decided) == 1 else 'statements'} that the TEF mode becomes "
            f"unstable which tefcore can decide, {len(stable)} "
            f"{'finds' if len(stable) == 1 else 'find'} the computed TEF root stable "
            f"throughout ({_figs(sorted(stable['figure'], key=_fig_order))})")
    growth = pd.to_numeric(root["computed_value"], errors="coerce")
    if growth.notna().any():
        top = root.loc[growth.idxmax()]
        shares = dict(re.findall(r"(\w+) participation ([\d.]+)", str(top["computed"])))
        share = (f", blade torsion {shares['torsion']} of its motion and the flap "
                 f"{shares['TEF']}" if {"torsion", "TEF"} <= set(shares) else "")
        text += (f"; the root that does go unstable, the flutter root, grows at "
                 f"{growth.max():+.1f} /rev in {_figs([top['figure']])}{share}: a fast "
                 "coupled flutter where the paper describes a weak instability of the flap")
    return text + "."


def headline(claims: pd.DataFrame, what_if: str = "") -> str:
    """The report's first paragraph: what reproduces, what does not, the key finding.

    Parameters
    ----------
    claims : pandas.DataFrame
        The run's claims (``id``, ``figure``, ``tag``, ``status``, ``mode``,
        ``kind``, ``statement``, ``computed``, ``computed_value``, ``reason``).
    what_if : str
        The changed parameters of a what-if run (said first).

    Returns
    -------
    str
        Markdown, three sentences (four for a what-if).
    """
    v = claims[claims["tag"] == "validation"] if "tag" in claims else claims
    if v.empty or "status" not in v:
        return "No validation claim of the paper was checked in this run."
    needed = ["figure", "mode", "kind", "statement", "computed", "computed_value", "reason"]
    v = v.assign(**{c: "" for c in needed if c not in v}).fillna("")
    by = {s: v[v["status"] == s] for s in ("pass", "fail", "ambiguous", "not reproducible")}
    figures = sorted(v["figure"].unique(), key=_fig_order)
    whole = [f for f in figures if (v.loc[v["figure"] == f, "status"] == "pass").all()]
    first = (f"{len(by['pass'])} of the paper's {len(v)} validation claims reproduce"
             + (f", among them every statement on {_figs(whole)}" if whole else "") + ".")
    failing = sorted(by["fail"]["figure"].unique(), key=_fig_order)
    second = (f"{len(by['fail'])} {'does' if len(by['fail']) == 1 else 'do'} not "
              f"(on {_figs(failing)})" if failing else "None fails")
    undecided = len(by["ambiguous"]) + len(by["not reproducible"])
    if undecided:
        second += (f", and {undecided} cannot be decided: {len(by['ambiguous'])} ambiguous "
                   f"(two roots meet inside the claim's range), {len(by['not reproducible'])} "
                   "needing data tefcore does not have")
    parts = [first, second + ".", _key_finding(v)]
    if what_if:
        parts.insert(0, f"**A what-if**: the notebooks ran with {what_if}; the claims say what "
                        "the paper's statements become for that rotor, and none is compared "
                        "with the statuses recorded for the default one.")
    return " ".join(p for p in parts if p)


@cache
def _params_by_field() -> dict:
    """``{"section.field": Param}`` of the shipped configuration's sections."""
    from ...config.io import load_config

    cfg = load_config("mdart")
    out = {}
    for name in dir(cfg):
        section = getattr(cfg, name, None)
        for p in getattr(type(section), "PARAMS", ()):
            out[f"{name}.{p.name}"] = p
    return out


def setting_unit(setting: str) -> str:
    """The unit of a lever's setting (``"factor on flap.mass"`` -> ``"× baseline"``).

    Parameters
    ----------
    setting : str
        What a lever's numbers are (:class:`tefcore.paper.attribution.levers.Lever`).

    Returns
    -------
    str
        SI unit, ``"× baseline"`` for a factor, ``""`` when dimensionless or
        an option.

    Examples
    --------
    >>> setting_unit("factor on flap.mass"), setting_unit("rotor.radius")
    ('× baseline', 'm')
    """
    if setting.startswith("factor on "):
        return "× baseline"
    m = re.fullmatch(r"shift of ([\w.]+)(?: \[SI\])?", setting)
    p = _params_by_field().get(m.group(1) if m else setting)
    unit = p.unit if p is not None and p.kind != "str" else ""
    return unit.replace("^2", "²").replace("^3", "³").replace("*", " ")


def _value(v, unit: str) -> str:
    try:
        x = float(v)
    except (TypeError, ValueError):
        return str(v)
    return f"{x:.3g}" + (f" {unit}" if unit and unit != "× baseline" else
                         " × baseline" if unit else "")


def _lever_text(row) -> str:
    """``"elastic axis = 0.255 (rotor.elastic_axis: plausible 0.23 to 0.27; baseline 0.25)"``,
    units included; the parts the table lacks are left out."""
    setting = str(row.get("setting", "") or "")
    unit = setting_unit(setting) if setting else ""
    parts = []
    if str(row.get("plausible_low", "")) != "" and str(row.get("plausible_high", "")) != "":
        parts.append(f"plausible {_value(row['plausible_low'], unit)} to "
                     f"{_value(row['plausible_high'], unit)}")
    if str(row.get("baseline", "")) != "":
        parts.append(f"baseline {_value(row['baseline'], unit)}")
    what = setting.removeprefix("factor on ").removesuffix(" [SI]")
    inner = "; ".join(parts)
    inner = f"{what}: {inner}" if what and inner else what or inner
    return f"{row['assumption']} = {_value(row['flips_at'], unit)}" + (
        f" ({inner})" if inner else "")


def why_view(table: pd.DataFrame, claims: pd.DataFrame) -> dict:
    """"Why we differ" in words: claims by their sentence, levers with units and ranges.

    Parameters
    ----------
    table : pandas.DataFrame
        The run's attribution (``OUT/attribution.csv``).
    claims : pandas.DataFrame
        The run's claims (their statements).

    Returns
    -------
    dict
        ``failing``, ``explained`` (counts); ``explains``: each lever that
        flips failing claims within its plausible range (``assumption``,
        ``what``: the setting and its range, ``claims``: ``id`` and
        ``statement``); ``unexplained`` (``id``, ``statement``); ``figures``:
        figure -> one row per failing claim (``claim``, ``statement``,
        ``plausible`` and ``beyond``: lists of lever settings in words,
        ``breaks``: the passing claims the flipping change makes fail);
        ``notes``.
    """
    from ..attribution.differences import summarise

    said = dict(zip(claims.get("id", []), claims.get("statement", []), strict=False))
    base = summarise(table)
    t = table.fillna("").astype(str)
    flips = t[(t["flips_at"] != "") & (t["assumption"] != "none")]
    good = flips[flips["within_plausible"].isin(["True", "true"])
                 & (flips["confirmed"] == "True")]

    def claim(cid):
        return {"id": cid, "statement": said.get(cid, "")}

    explains = []
    for e in base["explains"]:
        rows = good[good["assumption"] == e["assumption"]]
        r = rows.iloc[0]
        setting = str(r.get("setting", "") or "")
        unit = setting_unit(setting) if setting else ""
        explains.append({
            "assumption": e["assumption"],
            "what": (f"{setting}, " if setting else "")
            + f"plausible {_value(r['plausible_low'], unit)} to "
              f"{_value(r['plausible_high'], unit)}",
            "claims": [claim(c) for c in e["claims"]]})
    figures: dict = {}
    for cid, g in t.groupby("claim", sort=False):
        ok = good[good["claim"] == cid]
        rest = flips[(flips["claim"] == cid) & ~flips.index.isin(ok.index)]
        figures.setdefault(str(g["figure"].iloc[0]), []).append({
            **claim(cid), "plausible": [_lever_text(r) for _, r in ok.iterrows()],
            "beyond": [_lever_text(r) + ("" if r["confirmed"] == "True" else ", not confirmed")
                       for _, r in rest.iterrows()],
            "breaks": "; ".join(c for c in ok["conflicts"] if c)})
    return {"failing": base["failing"], "explained": base["explained"], "explains": explains,
            "unexplained": [claim(c) for c in base["unexplained"]], "figures": figures,
            "notes": base["notes"]}


def _sentences(caption: str) -> list[str]:
    return [s for s in re.split(r"(?<=[.)])\s+(?=[A-Z(\"])", caption.strip()) if s]


def shared_notes(captions, least: int = 3) -> tuple[list[str], dict]:
    """The sentences at least ``least`` captions repeat, and each caption without them.

    Parameters
    ----------
    captions : iterable of str
        The figures' captions.
    least : int
        How many captions must repeat a sentence for it to be said once.

    Returns
    -------
    tuple
        ``(notes, short)``: the shared sentences in the order they first
        appear, and ``{caption: caption without them}``.

    Examples
    --------
    >>> caps = ["Fig. 8: a. Lines join points.", "Fig. 9: b. Lines join points.",
    ...         "Fig. 10: c. Lines join points.", "Fig. 7: d."]
    >>> notes, short = shared_notes(caps)
    >>> notes, short["Fig. 9: b. Lines join points."]
    (['Lines join points.'], 'Fig. 9: b.')
    """
    captions = list(dict.fromkeys(captions))
    count: dict = {}
    for c in captions:
        for s in dict.fromkeys(_sentences(c)):
            count[s] = count.get(s, 0) + 1
    notes = [s for s, n in count.items() if n >= least]
    short = {c: " ".join(s for s in _sentences(c) if s not in notes) for c in captions}
    return notes, short


def check_rows(checks: pd.DataFrame | None) -> list[dict]:
    """The stated blade frequencies as rows with the report's column names (rounded).

    Parameters
    ----------
    checks : pandas.DataFrame or None
        :func:`tefcore.paper.calibration.frequency_checks`.

    Returns
    -------
    list of dict
    """
    if checks is None:
        return []
    table = checks.drop(columns="source", errors="ignore").round(3)
    return table.rename(columns=CHECK_COLUMNS).astype(str).to_dict("records")


def notebook_title(out, name: str) -> str:
    """The first heading of the executed notebook ``out/notebooks/<name>.ipynb``.

    Parameters
    ----------
    out : path
        The reproduction folder.
    name : str
        The notebook.

    Returns
    -------
    str
        ``"11 -- Watch it flutter: ..."``, or ``"Further results of <name>"``.
    """
    path = Path(out) / "notebooks" / f"{name}.ipynb"
    try:
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    except (OSError, ValueError, KeyError):
        cells = []
    for c in cells:
        src = "".join(c.get("source", "")) if c.get("cell_type") == "markdown" else ""
        m = re.match(r"\s*#\s+(.+)", src)
        if m:
            return m.group(1).strip().replace(" -- ", " — ")
    return f"Further results of {name}"


def _passes(counts: dict, part: str) -> str:
    n, of = counts[part]
    return f"{n} of {of}"


def _rotor_rows(checks: dict, best: dict | None = None) -> list[dict]:
    """Each checked rotor's validation passes by each reading: fitted, held out, all.

    The best rotor by the flutter root is said to be the same rotor as the best by the
    continued TEF where one trial is best by both objectives.
    """
    best = best or {}
    same = "trial" in best.get("flutter", {}) and \
        best.get("flutter", {}).get("trial") == best.get("continued", {}).get("trial")
    names = {"baseline": "mdart (assumed; its sample of the space)",
             "best continued": "inferred, by the continued TEF",
             "best flutter": "inferred, by the flutter root" + (
                 " (the same rotor: best by both objectives)" if same else "")}
    return [{"rotor": names.get(k, k), "reading": r, "fitted": _passes(v[r], "fitted"),
             "held_out": _passes(v[r], "held out"), "all": _passes(v[r], "all")}
            for k, v in checks.items() for r in ("continued", "flutter") if r in v]


def _parameter_rows(best: dict, baseline: dict, space: dict) -> list[dict]:
    """The inferred value of each parameter of the space against mdart's, with its spread."""
    def show(v, unit):
        return str(v) if isinstance(v, str) else f"{v:.3g}" + (f" {unit}" if unit else "")

    rows = []
    for name, v in best["params"].items():
        p = space.get(name)
        unit = p.unit if p is not None else ""
        lo_hi = best["spread"].get(name, [])
        spread = (", ".join(map(str, lo_hi)) if isinstance(v, str)
                  else f"{lo_hi[0]:.3g} to {lo_hi[1]:.3g}" if len(lo_hi) == 2 else "")
        rows.append({"name": name, "assumed": show(baseline[name], unit) if name in baseline
                     else "", "inferred": show(v, unit), "spread": spread})
    return rows


def inference_view(results: dict) -> dict | None:
    """"What the paper's rotor must have been": the packaged studies in words and tables.

    Parameters
    ----------
    results : dict
        :func:`tefcore.paper.inference.packaged.load_results` (empty: no section).

    Returns
    -------
    dict or None
        ``studies`` (name, command, trials, refused, not computable), ``rotors``
        (each checked rotor's validation passes by reading: fitted, held out,
        all), ``parameters`` (inferred against assumed, with the spread of the
        trials within one claim of the best), ``lofo`` (leave-one-figure-out on
        the Sobol sample), ``unreached`` (fitted claims no sampled rotor
        passes), ``conflicts`` (fitted claims that pull against each other over
        the Sobol sample), ``sobol`` (per failing or ambiguous claim of mdart:
        the group of the largest total Sobol index, with its interval, and the
        next), ``sobol_info``, ``sobol_unmoved`` (analysed claims no rotor of
        the design moved), ``best`` (study and trial of the inferred rotor),
        ``agreement`` (:func:`agreement_text`: do the studies of the continued
        reading end at the same rotor?), ``truncation`` (:func:`truncation_text`
        of the inferred rotor; empty where its converged-basis verdicts are
        not stored).
    """
    if not results:
        return None
    from ..figures.runs import base_config
    from ..inference.packaged import study_command
    from ..inference.protocol import load_protocol
    from ..inference.space import baseline_sample, load_space

    summary = results["summary"]
    space = load_space(load_protocol().space)
    trials = results["trials"]
    studies = []
    for s in summary["studies"]:
        mine = trials[trials["study"] == s["name"]]
        f = summary["failures"].get(s["name"], {})
        studies.append({"name": s["name"], "command": study_command(s),
                        "trials": int((mine["state"] == "COMPLETE").sum()),
                        "refused": int(f.get("refused", 0)),
                        "not_computable": ", ".join(f"{k} {v}" for k, v in
                                                    sorted(f.get("not_computable", {}).items()))
                        or "none"})
    best = summary["best"].get("continued", {})
    qmc = next((s["name"] for s in summary["studies"] if s["sampler"] == "qmc"), None)
    lofo = summary["lofo"].get(f"{qmc}:continued", []) if qmc else []
    rates = summary["pass_rates"].get("continued", [])
    return {
        "verdict": _inference_verdict(summary.get("checks", {})),
        "studies": studies,
        "rotors": _rotor_rows(summary.get("checks", {}), summary.get("best", {})),
        "parameters": (_parameter_rows(best, baseline_sample(base_config("thin_airfoil"),
                                                             space), space)
                       if "params" in best else []),
        "best": f"{best['trial'][0]} trial {best['trial'][1]}" if "trial" in best else "",
        "lofo": [{"figure": r["figure"], "claims": r["claims"],
                  "without": r["passes there"], "with": r["passes at best"]} for r in lofo],
        "unreached": [r["id"] for r in rates if r["passes"] == 0],
        "conflicts": [{"a": c["a"], "b": c["b"], "rho": f"{c['rho']:.2f}"}
                      for c in summary.get("conflicts", {}).get(qmc, [])] if qmc else [],
        "sobol": _sobol_rows(results.get("sobol")),
        "sobol_info": results.get("sobol_info", {}),
        "sobol_unmoved": _sobol_unmoved(results),
        "agreement": _agreement_paragraph(summary.get("agreement", {})),
        "truncation": truncation_text(
            _validation(summary.get("checks", {}).get("best continued", {})
                        .get("continued", {}).get("statuses", {})), _inferred_converged()),
    }


def _agreement_paragraph(agreement: dict) -> str:
    """Both readings' :func:`agreement_text`, and what their pass counts count."""
    text = " ".join(t for t in (
        agreement_text(agreement.get(r), label)
        for r, label in (("continued", "continued TEF"), ("flutter", "flutter root"))) if t)
    return text + (" (The fitted passes there count every fitted claim, the calibration ones "
                   "included, as the study checked it, without refinement; the table above "
                   "counts validation claims checked with refinement.)" if text else "")


def agreement_text(agreement: dict | None, reading: str = "") -> str:
    """One sentence: do the studies of a reading end at the same rotor?

    Parameters
    ----------
    agreement : dict or None
        :func:`tefcore.paper.inference.analysis.agreement`.
    reading : str, optional
        The reading's name, said first (``"flutter root"``: "Reading the
        paper's TEF mode as the flutter root, ..."); ``""``: not said.

    Returns
    -------
    str
        Empty without one, or with fewer than two studies.

    Examples
    --------
    >>> print(agreement_text({"studies": [
    ...     {"study": "a", "trial": 3, "objective": 12.9, "passes": 17},
    ...     {"study": "b", "trial": 9, "objective": 11.2, "passes": 15}],
    ...     "apart": [{"parameter": "flap mass", "values": {"a": 0.1, "b": 0.8}}],
    ...     "objective_spread": 1.7, "same": False}))  # doctest: +NORMALIZE_WHITESPACE
    The answer depends on the sampler and the seed: the best rotors of a (objective 12.9,
    17 fitted passes) and b (objective 11.2, 15 fitted passes) lie more than a quarter of
    their ranges apart in flap mass (0.1, 0.8 of the range).
    """
    if not agreement or len(agreement.get("studies", [])) < 2:
        return ""
    bests = " and ".join(f"{r['study']} (objective {r['objective']:.1f}, {r['passes']} fitted "
                         "passes)" for r in agreement["studies"])
    lead = f"Reading the paper's TEF mode as the {reading}, the" if reading else "The"
    varied = _what_varies([r["study"] for r in agreement["studies"]])
    if agreement["same"]:
        return (f"{lead} answer does not depend on {varied.replace(' and ', ' or ')}: the best "
                f"rotors of {bests} lie within a quarter of every range of each other.")
    def where(a):
        values = list(a["values"].values())
        numbers = all(isinstance(v, (int, float)) for v in values)
        return (f"{a['parameter']} ({', '.join(str(v) for v in values)}"
                f"{' of the range' if numbers else ''})")

    apart = "; ".join(where(a) for a in agreement["apart"])
    return (f"{lead} answer depends on {varied}: the best rotors of {bests} "
            f"lie more than a quarter of their ranges apart in {apart}.")


def _what_varies(names) -> str:
    """What differs among the packaged studies named: "the sampler", "the seed" or both
    (both where a study is not a packaged one)."""
    from ..inference.packaged import STUDIES

    known = {s["name"]: s for s in STUDIES}
    if not all(n in known for n in names):
        return "the sampler and the seed"
    parts = [f"the {k}" for k in ("sampler", "seed") if len({known[n][k] for n in names}) > 1]
    return " and ".join(parts) or "the sampler and the seed"


def _validation(statuses: dict) -> dict:
    """The validation claims' entries of a claim id -> status table (the counts the
    report gives are of the 58 validation statements)."""
    from ..claims.reference import load_claims

    keep = {c.id for c in load_claims() if c.tag == "validation"}
    return {k: v for k, v in statuses.items() if k in keep}


def _inferred_converged():
    """The stored converged-basis verdicts of ``mdart-inferred``, or None."""
    from ...config.io import load_config
    from ..claims.truncation import load_converged

    return load_converged(load_config("mdart-inferred"))


def truncation_text(statuses: dict, converged) -> str:
    """One sentence: which of a rotor's verdicts hold on its figures' converged bases.

    Only the claims with a converged verdict count (those of the stability
    figures; Figs. 6 and 7 have no modal basis to converge).

    Parameters
    ----------
    statuses : dict
        Claim id -> status with the paper's nine modes (validation claims).
    converged : pandas.DataFrame or None
        :func:`tefcore.paper.claims.truncation.load_converged` of the rotor.

    Returns
    -------
    str
        Empty without either.

    Examples
    --------
    >>> import pandas as pd
    >>> conv = pd.DataFrame({"id": ["a", "b", "c"], "status": ["pass", "fail", "pass"],
    ...                      "n_modes": [16, 24, 16]})
    >>> print(truncation_text({"a": "pass", "b": "pass", "c": "fail"}, conv))
    ... # doctest: +NORMALIZE_WHITESPACE
    On its figures' converged bases (16-24 modes) 1 of the 2 passes of its stability
    figures with the paper's nine modes is truncation-dependent: b (fail with 24); and 1
    verdict that is not a pass becomes one: c (fail with nine, pass with 16).
    """
    if not statuses or converged is None or converged.empty:
        return ""
    conv = converged.set_index("id")
    ids = [i for i in statuses if i in conv.index]
    passes = [i for i in ids if statuses[i] == "pass"]
    lost = [i for i in passes if conv.at[i, "status"] != "pass"]
    won = [i for i in ids if statuses[i] != "pass" and conv.at[i, "status"] == "pass"]
    modes = sorted({int(n) for n in conv["n_modes"]})
    span = f"{modes[0]}-{modes[-1]}" if len(modes) > 1 else f"{modes[0]}"
    out = (f"On its figures' converged bases ({span} modes) {len(lost)} of the "
           f"{len(passes)} passes of its stability figures with the paper's nine modes "
           f"{'is' if len(lost) == 1 else 'are'} truncation-dependent")
    out += (": " + ", ".join(f"{i} ({conv.at[i, 'status']} with {int(conv.at[i, 'n_modes'])})"
                             for i in lost)) if lost else ""
    if won:
        out += (f"; and {len(won)} verdict{'' if len(won) == 1 else 's'} that "
                f"{'is' if len(won) == 1 else 'are'} not a pass "
                f"become{'s' if len(won) == 1 else ''} one: "
                + ", ".join(f"{i} ({statuses[i]} with nine, pass with "
                            f"{int(conv.at[i, 'n_modes'])})" for i in won))
    return out + "."


def _sobol_unmoved(results: dict) -> list[str]:
    """The analysed claims whose term did not vary over the Sobol design: nothing moves them."""
    info, table = results.get("sobol_info"), results.get("sobol")
    if not info or table is None:
        return []
    return [c for c in info.get("claims", []) if c not in set(table["claim"])]


def _sobol_rows(table) -> list[dict]:
    """Per claim: the groups by total Sobol index, largest first, with its 95 % interval.

    ``above``: whether the largest total index's interval stays above zero
    (``ST - ST_conf > 0``).
    """
    if table is None or table.empty:
        return []
    rows = []
    for cid, t in table.groupby("claim", sort=False):
        t = t.sort_values("ST", ascending=False)
        top = t.iloc[0]
        rows.append({"claim": cid, "group": top["group"],
                     "st": f"{top['ST']:.2f} ± {top['ST_conf']:.2f}",
                     "above": "yes" if top["ST"] - top["ST_conf"] > 0 else "no",
                     "next": f"{t.iloc[1]['group']} {t.iloc[1]['ST']:.2f}" if len(t) > 1
                     else ""})
    return rows


def _inference_verdict(checks: dict) -> str:
    """One sentence: does the fit carry over to the claims it did not see?"""
    base, best = checks.get("baseline"), checks.get("best continued")
    if not base or not best:
        return ""
    fb, hb = base["continued"]["fitted"][0], base["continued"]["held out"][0]
    fi, hi = best["continued"]["fitted"][0], best["continued"]["held out"][0]
    if fi > fb and hi < hb:
        return (f"The inferred rotor passes more of the fitted claims than mdart ({fi} against "
                f"{fb}) and fewer of the held-out ones ({hi} against {hb}): the fit does not "
                "carry over to the figures it did not see, so the data of these studies do not "
                "pin the unknown properties, and mdart stays the default.")
    if hi > hb:
        return (f"The inferred rotor passes {hi} of the held-out claims against mdart's {hb}: "
                "the fit carries over to figures it did not see.")
    return (f"The inferred rotor passes {fi} fitted and {hi} held-out claims against mdart's "
            f"{fb} and {hb}.")
