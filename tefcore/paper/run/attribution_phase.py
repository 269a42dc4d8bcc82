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
from ..attribution.packaged import PACKAGED, run_stamp, stamp_differences
from ..claims.files import reference_dir
from .outcome import what_if

__all__ = ["attribute_claims", "attribution_args", "package"]


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
    params = args.get("params") or {}
    why = "asked to search again"
    if not again:
        table, why = packaged_attribution(claims, params)
        if table is not None:
            write_attribution(table, out / "attribution.csv")
            stamp = json.loads((reference_dir() / PACKAGED[1]).read_text())
            with atomic_output(out / "attribution.json") as f:
                json.dump(stamp, f, indent=1, sort_keys=True)
                f.write("\n")
            return Attribution(table, 0.0, 0.0, 0, source=(
                "This run read the packaged attribution of the default rotor: a search made "
                f"with this code, data and settings, where every claim had the verdict it "
                f"has here ({stamp.get('cpu_seconds', 0):.0f} s of CPU then); "
                "`tefcore reproduce --attribute-again` searches anew."))
    print(f"attribution: searching ({why})", file=sys.stderr)
    result = attribute_run(out, claims, **args)
    write_stamp(out / "attribution.json", claims, params, result)
    return result


def attribution_args(attribution, params: dict, jobs) -> dict | None:
    """:func:`attribute_claims`'s arguments from ``reproduce``'s, or None to skip it."""
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
        A file is missing, or the stamp is not this code's (the code, data or
        version changed since the run), or the run was not the default one.
    """
    out = Path(out)
    src = [out / "attribution.csv", out / "attribution.json"]
    for f in src:
        if not f.is_file():
            raise ValueError(f"{f}: missing; run `tefcore reproduce --out {out} "
                             "--attribute-again` first")
    stamp = json.loads(src[1].read_text())
    now = run_stamp(stamp.get("settings", {}))
    differ = stamp_differences(stamp, now)
    if differ:
        raise ValueError(f"{src[1]}: computed with another {', '.join(differ)}; run the "
                         "reproduction again")
    params = {n: {k: v for k, v in p.items() if v is not None}
              for n, p in stamp.get("settings", {}).items()}
    changed = what_if(params, list(params))
    if changed:
        raise ValueError(f"{src[1]}: a what-if run ({changed}); only the default reproduction "
                         "is packaged")
    folder = Path(target) if target is not None else reference_dir()
    dest = (folder / PACKAGED[0], folder / PACKAGED[1])
    for s, d in zip(src, dest, strict=True):
        with atomic_output(d, mode="wb") as f:
            with open(s, "rb") as g:
                shutil.copyfileobj(g, f)
    return dest
