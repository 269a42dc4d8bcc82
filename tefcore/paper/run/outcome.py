"""What a reproduction's claims are measured against: the recorded statuses, or its own last run.

The statuses recorded in the reference data (``claims.toml``; a packaged
variant's in ``variants.toml``) are those of the packaged configurations
computed with the notebooks' own parameter values.  Only a run that changes
nothing but how the work is spread (:data:`NEUTRAL_PARAMETERS`) and, at
most, names a packaged configuration is compared with them: a claim worse
than recorded is then a regression (exit status 1).

Any other run is a *what-if* (:func:`what_if`): another rotor
(``-p config my.toml``), other flight conditions (``-p overrides ...``),
coarser sweeps (``-p n_points 4``).  Its statuses say what the paper's
statements become for that rotor; none is a regression.  It is compared
instead with the previous run of the same parameters in the folder it
replaces, if there is one (:func:`status_changes`), and the differences are
printed as a short list (:func:`change_lines`).

Examples
--------
>>> what_if({"04_cg_offset": {"n_jobs": 2, "interactive": False}}, ["04_cg_offset"])
''
>>> what_if({"04_cg_offset": {"overrides": {"flight.advance_ratio": 0.2}}}, ["04_cg_offset"])
"overrides = {'flight.advance_ratio': 0.2}"
"""

from __future__ import annotations

import json
import sys
import textwrap
from pathlib import Path

import pandas as pd

from ..claims.reference import STATUSES
from ..claims.variants import variant_name

__all__ = ["NEUTRAL_PARAMETERS", "change_lines", "previous_claims", "print_summary", "run_record",
           "same_parameters", "status_changes", "what_if"]

#: Notebook parameters that change how the work is done, never its results.
NEUTRAL_PARAMETERS = frozenset({"n_jobs", "interactive", "output_dir"})


def what_if(params: dict, names) -> str:
    """What makes a run a what-if (``name = value`` pairs), or ``""`` when the records apply.

    Parameters
    ----------
    params : dict
        ``{notebook: {name: value}}`` (merged).
    names : sequence of str
        The notebooks run.

    Returns
    -------
    str
        The parameters that differ from the recorded computation, each once.
    """
    seen: dict = {}
    for n in names:
        for k, v in sorted(params.get(n, {}).items()):
            if k in NEUTRAL_PARAMETERS or (k == "config" and (
                    v is None or (isinstance(v, str) and variant_name(v) is not None))):
                continue
            seen.setdefault(f"{k} = {v!r}", None)
    return ", ".join(seen)


def _comparable(params: dict) -> dict:
    """Parameters as JSON would keep them, the neutral ones left out."""
    kept = {n: {k: v for k, v in p.items() if k not in NEUTRAL_PARAMETERS}
            for n, p in params.items()}
    return json.loads(json.dumps(kept, sort_keys=True, default=str))


def run_record(names, params: dict, version: str, change: str) -> dict:
    """What a run was, for its folder's marker (:mod:`tefcore.paper.run.output_folder`).

    Parameters
    ----------
    names : sequence of str
        The notebooks run.
    params : dict
        Their parameters.
    version : str
        tefcore's version.
    change : str
        :func:`what_if` of the run.

    Returns
    -------
    dict
    """
    return {"tefcore": version, "notebooks": list(names),
            "parameters": _comparable({n: params.get(n, {}) for n in names}),
            "what_if": change}


def same_parameters(previous: dict | None, record: dict) -> bool:
    """Whether a previous run's record (its marker) ran with the same parameters.

    Parameters
    ----------
    previous : dict or None
        The previous run's record (``{}``: a folder without one).
    record : dict
        This run's (:func:`run_record`).
    """
    if not previous or "parameters" not in previous:
        return False
    before, now = previous["parameters"], record["parameters"]
    common = set(before) & set(now)
    return bool(common) and all(before[n] == now[n] for n in common)


def previous_claims(out) -> pd.DataFrame | None:
    """The claims table of the reproduction in ``out`` (its ``claims.csv``), or None.

    Parameters
    ----------
    out : path
        The folder being replaced.
    """
    path = Path(out) / "claims.csv"
    if not path.is_file() or path.is_symlink() or not path.stat().st_size:
        return None
    try:
        table = pd.read_csv(path, dtype=str, keep_default_na=False)
    except (OSError, ValueError, pd.errors.ParserError):
        return None
    return table if {"id", "status"} <= set(table.columns) else None


def status_changes(claims: pd.DataFrame, before: pd.DataFrame | None) -> list[dict]:
    """The claims whose status differs from ``before`` (ids in both), worse ones first.

    Parameters
    ----------
    claims : pandas.DataFrame
        This run's claims (``id``, ``figure``, ``status``, ``reason``).
    before : pandas.DataFrame or None
        The previous run's.

    Returns
    -------
    list of dict
        ``id``, ``figure``, ``before``, ``now``, ``worse`` (bool) and ``reason``.

    Examples
    --------
    >>> now = pd.DataFrame({"id": ["a", "b"], "figure": ["fig8", "fig9"],
    ...                     "status": ["fail", "pass"], "reason": ["r", ""]})
    >>> old = pd.DataFrame({"id": ["a", "b"], "status": ["pass", "pass"]})
    >>> [(c["id"], c["before"], c["now"], c["worse"]) for c in status_changes(now, old)]
    [('a', 'pass', 'fail', True)]
    """
    if before is None or claims.empty:
        return []
    rank = {s: i for i, s in enumerate(STATUSES)}
    old = dict(zip(before["id"], before["status"], strict=False))
    rows = []
    for r in claims.to_dict("records"):
        was = old.get(r["id"])
        if was is None or was == r["status"]:
            continue
        rows.append({"id": r["id"], "figure": r.get("figure", ""), "before": was,
                     "now": r["status"], "reason": str(r.get("reason", "")),
                     "worse": rank.get(r["status"], 0) > rank.get(was, 0)})
    return sorted(rows, key=lambda c: (not c["worse"], c["id"]))


def change_lines(rows, before: str = "before", limit: int = 12, width: int = 110) -> list[str]:
    """A short list of status changes, one line each: ``- id (Fig. 8): pass -> fail: reason``.

    Parameters
    ----------
    rows : list of dict
        ``id``, ``figure``, ``now``, ``reason`` and the earlier status under
        the key ``before`` names.
    before : str
        The key of the earlier status (``"before"``, ``"recorded_status"``).
    limit : int
        Most lines; the rest counted on a last line.
    width : int
        Longest line (the reason is cut to fit).

    Returns
    -------
    list of str
    """
    lines = []
    for r in list(rows)[:limit]:
        fig = str(r.get("figure", "")).replace("fig", "Fig. ")
        head = f"  - {r['id']}" + (f" ({fig})" if fig else "") + \
            f": {r[before]} -> {r['status'] if 'status' in r else r['now']}"
        reason = " ".join(str(r.get("reason", "")).split())
        room = width - len(head) - 2
        if reason and room > 20:
            head += ": " + (reason if len(reason) <= room else reason[:room - 3] + "...")
        lines.append(head)
    if len(rows) > limit:
        lines.append(f"  ... and {len(rows) - limit} more (claims.csv)")
    return lines


def print_summary(runs, done, elapsed, out, *, what_if: str = "", changes=None) -> bool:
    """Print the run's summary; True when something is not clean (exit status 1).

    The notebooks' outcomes, the claims' score (against the recorded statuses,
    or, for a what-if, only counted), the other variants' scores and the
    attribution's source, each statement wrapped to 100 columns; on stderr the
    failed notebooks and every claim worse than recorded.

    Parameters
    ----------
    runs : list of tefcore.paper.run.reproduce.NotebookRun
        The notebooks' outcomes.
    done : dict
        :func:`tefcore.paper.run.reproduce.finish_report`'s result (claims,
        worse, passed, total, variants, attribution).
    elapsed : float
        Seconds the run took.
    out : pathlib.Path
        The output folder.
    what_if : str, optional
        What makes the run a what-if (:func:`what_if`); empty for the default.
    changes : list of dict or None, optional
        The status changes since the previous run of the same parameters
        (:func:`status_changes`); None when there was none to compare with.

    Returns
    -------
    bool
    """
    claims, worse, passed, total = (done[k] for k in ("claims", "worse", "passed", "total"))

    def say(text: str) -> None:   # one statement, wrapped to the terminal's 100 columns
        print(textwrap.fill(text, 100, subsequent_indent="  ", break_long_words=False,
                            break_on_hyphens=False))

    for r in runs:
        print(f"{r.name:38s} {r.status:7s} {r.seconds:6.1f} s  {r.error}")
    if what_if:
        say(f"claims: {passed} validation claims pass of {total} on this what-if "
              f"({what_if}); the recorded statuses are the default rotor's, so none is "
              "compared with them")
    else:
        say(f"claims: {passed} validation claims passed of {total} ({len(claims)} checked "
              f"in all); worse than recorded: {len(worse)}")
    if changes is not None:
        say(f"since the previous run of these parameters in {out}: "
              + (f"{len(changes)} claim(s) changed" if changes else "no claim changed"))
        print("\n".join(change_lines(changes)) if changes else "", end="\n" if changes else "")
    v = done.get("variants")
    if v:
        say("on each variant: " + "; ".join(
            f"{'this what-if' if what_if and n == v['base'] else n} {a} of {b} validation claims"
            for n, (a, b) in v["scores"].items())
            + f"; other variants worse than recorded: {len(v['worse'])}")
    if done.get("attribution") is not None:
        a = done["attribution"]
        if a.source:
            say(f"attribution: {a.table['claim'].nunique()} failing claim(s), read from the "
                  f"package (the same code, data and verdicts) -> {out / 'attribution.csv'}")
        else:
            say(f"attribution: {a.table['claim'].nunique()} failing claim(s), {a.tasks} "
                  f"levers, {a.cpu_seconds:.0f} CPU s ({a.wall_seconds:.0f} s wall) -> "
                  f"{out / 'attribution.csv'}")
    say(f"wrote {out / 'report.md'} and {out / 'report.html'} in {elapsed:.1f} s")
    failed = [r.name for r in runs if r.status != "ok"]
    if failed:
        print(f"tefcore reproduce: notebook(s) failed: {', '.join(failed)}", file=sys.stderr)
    if not worse.empty:
        print(f"tefcore reproduce: {len(worse)} claim(s) worse than recorded (a regression):\n"
              + "\n".join(change_lines(worse.to_dict("records"), before="recorded_status")),
              file=sys.stderr)
    bad_variants = bool(v and (v["errors"] or not v["worse"].empty))
    if v and v["errors"]:
        print("tefcore reproduce: " + "; ".join(v["errors"]), file=sys.stderr)
    if v and not v["worse"].empty:
        rows = [{**r, "id": f"{r['id']} on {r['variant']}"}
                for r in v["worse"].to_dict("records")]
        print("tefcore reproduce: claim(s) worse than recorded on another variant:\n"
              + "\n".join(change_lines(rows, before="recorded_status")), file=sys.stderr)
    return bool(failed) or not worse.empty or bad_variants
