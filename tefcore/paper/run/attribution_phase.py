"""The reproduction's attribution phase: read the packaged search or search.

Once the notebooks' claims are collected, :func:`attribute_claims` writes
``OUT/attribution.csv`` (the report's *Why we differ*): the package's
attribution of the default rotor where it is this run's answer
(:func:`tefcore.paper.attribution.packaged.packaged_attribution`), a search
otherwise (:func:`tefcore.paper.attribution.differences.attribute_run`),
stamped beside (``OUT/attribution.json``).  :func:`package` puts a finished
default reproduction's search into the package
(``python tools/package_attribution.py OUT``).
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import pandas as pd

from ...safe_io import atomic_output
from ..attribution.differences import failing_claims
from ..attribution.packaged import PACKAGED, run_stamp, stamp_differences, stamp_record
from ..claims.files import reference_dir
from ..claims.reference import load_claims
from .notebook_files import NOTEBOOKS, notebook_parameters, notebooks_dir
from .outcome import what_if

__all__ = ["attribute_claims", "attribution_args", "given_settings", "package"]


def attribute_claims(out: Path, claims: pd.DataFrame, attribution: dict | None):
    """The attribution of the run's failing claims, written to ``OUT/attribution.csv``.

    The one hook of :mod:`tefcore.paper.attribution.differences` in the reproduction: called
    once the notebooks' claims are collected, before the report.  Where the
    package's attribution is this run's answer (the default rotor, this code
    and data, every claim's verdict as when it was made:
    :func:`tefcore.paper.attribution.packaged.packaged_attribution`) it is
    read; otherwise, or with ``again``, the failing claims are searched and
    the search's stamp is written beside (``OUT/attribution.json``).

    Parameters
    ----------
    out : pathlib.Path
        The reproduction folder.
    claims : pandas.DataFrame
        The collected claims (:func:`collect_claims`).
    attribution : dict or None
        Keyword arguments of :func:`tefcore.paper.attribution.differences.attribute_run`
        (``params``: each notebook's parameters, ``n_jobs``, ...) and
        ``again`` (search even where the packaged attribution applies); None
        skips it, as does a run that checked no claim.

    Returns
    -------
    tefcore.paper.attribution.differences.Attribution or None
    """
    if attribution is None or claims.empty:   # nothing checked: nothing to attribute
        return None
    from ..attribution.differences import Attribution, attribute_run, write_attribution
    from ..attribution.packaged import packaged_attribution, write_stamp

    args = dict(attribution)
    again = bool(args.pop("again", False))
    settings = given_settings(args.get("params") or {})
    why = "asked to search again"
    if not again:
        table, why = packaged_attribution(claims, settings)
        if table is not None:
            write_attribution(table, out / "attribution.csv")
            stamp = json.loads((reference_dir() / PACKAGED[1]).read_text())
            # this run's stamp, marked as read: it is no search, and never packaged
            record = {**stamp_record(claims, settings), "read_from_package": True,
                      "search_cpu_seconds": stamp.get("cpu_seconds")}
            with atomic_output(out / "attribution.json") as f:
                json.dump(record, f, indent=1, sort_keys=True)
                f.write("\n")
            return Attribution(table, 0.0, 0.0, 0, source=(
                "This run read the packaged attribution of the default rotor: a search made "
                f"with this code, data and settings, where every claim had the verdict it "
                f"has here ({stamp.get('cpu_seconds', 0):.0f} s of CPU then); "
                "`tefcore reproduce --attribute-again` searches anew."))
    print(f"attribution: searching ({why})", file=sys.stderr)
    result = attribute_run(out, claims, **args)
    write_stamp(out / "attribution.json", claims, settings, result)
    return result


def given_settings(params: dict) -> dict:
    """Each notebook's parameters without those that only name its defaults.

    A value equal to the notebook's own default (its parameters cell), and
    ``config = "mdart"`` (the default rotor by name), change nothing a search
    computes: a stamp compares what is left, so ``-p config mdart`` reads the
    package as the plain command does.

    Parameters
    ----------
    params : dict
        Notebook -> its merged parameters.

    Returns
    -------
    dict

    Examples
    --------
    >>> given_settings({"04_cg_offset": {"config": "mdart", "n_points": None,
    ...                                  "overrides": {"flap.cg_offset": 0.2}}})
    {'04_cg_offset': {'overrides': {'flap.cg_offset': 0.2}}}
    """
    out = {}
    for n, p in params.items():
        try:
            defaults = notebook_parameters(notebooks_dir() / f"{n}.ipynb")
        except (OSError, ValueError, KeyError):
            defaults = {}
        out[n] = {k: v for k, v in (p or {}).items()
                  if not (k in defaults and v == defaults[k])
                  and not (k == "config" and v == "mdart")}
    return out


def attribution_args(attribution, params: dict, jobs) -> dict | None:
    """:func:`attribute_claims`'s arguments from ``reproduce``'s, or None to skip it.

    Parameters
    ----------
    attribution : bool, dict or None
        ``reproduce``'s ``attribution``: False or None skips it, True attributes,
        a dict adds its keys (``{"again": True}``: search even where the
        package applies).
    params : dict
        Notebook -> its merged parameters.
    jobs : int or None
        The run's ``--jobs`` (default: the cores).

    Returns
    -------
    dict or None
    """
    if attribution is False or attribution is None:
        return None
    extra = attribution if isinstance(attribution, dict) else {}
    return {"params": params, "n_jobs": max(1, jobs or os.cpu_count() or 1), **extra}


def package(out, target=None) -> tuple[Path, Path]:
    """Copy a default reproduction's attribution into the package, after checking it.

    Parameters
    ----------
    out : path
        A finished reproduction of the default rotor that searched
        (``tefcore reproduce --out OUT --attribute-again``): its
        ``attribution.csv`` and ``attribution.json``.
    target : path, optional
        The folder written (default the package's ``reference_data``).

    Returns
    -------
    (pathlib.Path, pathlib.Path)
        The files written.

    Raises
    ------
    ValueError
        A file is missing; the run read the package instead of searching; the
        stamp is not this code's (the code, data or version changed since the
        run); the run was not the default one (a what-if, another variant, a
        subset of the notebooks); or its rows are not every failing claim's.
    """
    out = Path(out)
    src = [out / "attribution.csv", out / "attribution.json"]
    for f in src:
        if not f.is_file():
            raise ValueError(f"{f}: missing; run `tefcore reproduce --out {out} "
                             "--attribute-again` first")
    stamp = json.loads(src[1].read_text())
    if stamp.get("read_from_package") or "tasks" not in stamp:
        raise ValueError(f"{src[1]}: that run read the packaged attribution; package a search "
                         f"(`tefcore reproduce --out {out} --attribute-again`)")
    now = run_stamp(stamp.get("settings", {}))
    differ = stamp_differences(stamp, now)
    if differ:
        raise ValueError(f"{src[1]}: made with {'; '.join(differ)}; run the reproduction "
                         "again")
    settings = stamp.get("settings", {})
    given = {n: {k: v for k, v in p.items() if v is not None} for n, p in settings.items()}
    changed = what_if(given, list(given)) or "; ".join(
        f"{n}: {k} = {v!r}" for n, p in given.items() for k, v in p.items())
    if changed:
        raise ValueError(f"{src[1]}: a what-if or another variant ({changed}); only the "
                         "default reproduction is packaged")
    if set(settings) != set(NOTEBOOKS):
        raise ValueError(f"{src[1]}: a run of {len(settings)} of the {len(NOTEBOOKS)} notebooks; "
                         "only a reproduction of all of them is packaged")
    tags = {c.id: c.tag for c in load_claims()}
    checked = pd.DataFrame([{"id": i, "notebook": nb, "status": st, "tag": tags.get(i, "")}
                            for i, (nb, st) in stamp.get("statuses", {}).items()])
    failing = set(failing_claims(checked)["id"]) if not checked.empty else set()
    rows = set(pd.read_csv(src[0], dtype=str, keep_default_na=False)["claim"])
    if rows != failing:
        raise ValueError(f"{src[0]}: attributes {len(rows)} claim(s), the run failed "
                         f"{len(failing)}; not the run's whole attribution")
    folder = Path(target) if target is not None else reference_dir()
    dest = (folder / PACKAGED[0], folder / PACKAGED[1])
    for s, d in zip(src, dest, strict=True):
        with atomic_output(d, mode="wb") as f:
            with open(s, "rb") as g:
                shutil.copyfileobj(g, f)
    return dest
