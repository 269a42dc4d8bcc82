"""What decided a batch run's results, recorded beside them: skip, recompute, or refuse.

Each run folder ``OUT/<run>/`` holds ``batch_run.json``, written atomically
when the run starts (``"status": "running"``) and again when it ends::

    {"format": "tefcore.batch_run", "version": 1, "run": "group-overhang=0.2",
     "inputs": {...}, "environment": {...}, "status": "ok", "error": "",
     "notebooks": [{"name": "04_cg_offset", "status": "ok", "error": "", "seconds": 12.1}],
     "claims": {"passed": 2, "total": 5, "worse": 1}}

``inputs`` (:func:`run_inputs`) is everything that decides the run's
results, the same ideas as a sweep file's header
(:mod:`tefcore.sweeps.store`):

* ``notebooks`` and ``parameters`` -- the papermill parameters of each
  notebook (its output folder and the configuration's path left out);
* ``config`` -- the SHA-256 of the base configuration file's content
  (:func:`tefcore.provenance.file_digest`), and ``config_files`` the
  digests of the files that configuration reads
  (:func:`tefcore.provenance.input_digests`: a C81 deck);
* ``tefcore_version``, ``model_stamp`` (:func:`tefcore.provenance.model_stamp`,
  the solver's code) and ``paper_stamp`` (:func:`paper_stamp`, the paper
  layer's code that the notebooks run);
* ``notebook_sources`` -- a digest of each notebook's cells (their sources,
  not their stored outputs: re-executing the shipped notebooks does not
  make a run stale, editing a cell does);
* ``reference_data`` -- a digest of the paper's reference data (claims and
  digitised curves), which decides the claims' statuses.

``environment`` (:func:`tefcore.provenance.numerical_environment`: the
versions of tefcore, numpy, scipy and the BLAS) is recorded beside the
inputs, not among them: names and verdicts do not depend on it, so a run
kept from another stack is not stale, and the plan says what differs
(``RunPlan.note``).

:func:`plan_runs` compares a folder's record with the batch: unchanged and
finished -> ``skip``; unchanged but failed or cut short -> ``retry``; no
folder -> ``new``; anything else is **stale** and refused
(:class:`StaleRunError`, naming what changed) unless ``force``, which
recomputes it (``redo``).

Examples
--------
>>> changes({"tefcore_version": "0.1"}, {"tefcore_version": "0.2"})
["tefcore version ('0.1' then, '0.2' now)"]
"""

from __future__ import annotations

import functools
import hashlib
import json
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ...errors import TefcoreError
from ...provenance import (
    describe_digest,
    environment_note,
    file_digest,
    input_digests,
    model_stamp,
    numerical_environment,
)
from ...safe_io import atomic_write_text
from ..claims.files import reference_dir
from .notebook_files import notebooks_dir

__all__ = ["FORMAT", "RECORD", "RunPlan", "StaleRunError", "changes", "notebook_digest",
           "paper_stamp", "plan_runs", "read_record", "reference_digest", "run_inputs",
           "write_record"]

FORMAT = "tefcore.batch_run"
VERSION = 1
#: The record's file name inside a run folder.
RECORD = "batch_run.json"
#: Paper-layer modules that only run, compare and present batches (not in paper_stamp).
_PRESENTATION = frozenset({"run/batch", "run/batch_report", "run/batch_spec", "run/batch_state",
                           "run/commands", "run/report", "__init__"})


class StaleRunError(TefcoreError, ValueError):
    """A run folder whose recorded inputs differ from the batch's (its results would be stale)."""


@dataclass
class RunPlan:
    """What :func:`plan_runs` decided for one run.

    Parameters
    ----------
    spec : tefcore.paper.run.batch_spec.RunSpec
        The run.
    inputs : dict
        Its inputs now (:func:`run_inputs`).
    action : str
        ``"new"``, ``"skip"`` (unchanged and finished), ``"retry"``
        (unchanged, but failed or cut short) or ``"redo"`` (stale, forced).
    reason : str
        Why, for the log (what changed, for ``redo``).
    note : str
        For a run kept (``skip``, ``retry``): what differs in the numerical
        stack since it was computed (:func:`tefcore.provenance.environment_note`),
        else empty.
    """

    spec: object
    inputs: dict
    action: str
    reason: str = ""
    note: str = ""


@functools.lru_cache(maxsize=1)
def paper_stamp() -> str:
    """16 hex digits of SHA-256 over the paper layer's computing modules (what notebooks run).

    Returns
    -------
    str
        Changes with any edit of ``tefcore/paper/*.py`` except the modules
        that only run and present batches and reports.
    """
    h = hashlib.sha256()
    for name, data in _paper_sources(resources.files("tefcore.paper"), ""):
        if name.removesuffix(".py") in _PRESENTATION:
            continue
        h.update(name.encode() + b"\0" + len(data).to_bytes(8, "little") + data)
    return h.hexdigest()[:16]


def _paper_sources(folder, prefix: str):
    """``(relative path, bytes)`` of the paper layer's modules, its rooms included, sorted."""
    out = []
    for f in folder.iterdir():
        if f.is_dir() and f.name not in ("notebooks", "reference_data", "__pycache__"):
            out += _paper_sources(f, f"{prefix}{f.name}/")
        elif f.name.endswith(".py"):
            out.append((prefix + f.name, f.read_bytes()))
    return sorted(out)


def notebook_digest(path) -> str:
    """``"sha256:<hex>"`` of a notebook's cells (type and source), without their outputs.

    Parameters
    ----------
    path : path
        The ``.ipynb`` file.

    Returns
    -------
    str
    """
    import nbformat

    nb = nbformat.read(str(path), as_version=4)
    cells = [[c.cell_type, c.source] for c in nb.cells]
    kernel = nb.metadata.get("kernelspec", {}).get("name", "")
    text = json.dumps({"kernel": kernel, "cells": cells}, sort_keys=True)
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()


def reference_digest(folder=None) -> str:
    """``"sha256:<hex>"`` over the reference data's files (relative names and contents).

    Parameters
    ----------
    folder : path, optional
        Default :func:`tefcore.paper.claims.files.reference_dir`.

    Returns
    -------
    str
    """
    folder = Path(folder or reference_dir())
    h = hashlib.sha256()
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        h.update(path.relative_to(folder).as_posix().encode() + b"\0")
        h.update(file_digest(path).encode() + b"\0")
    return "sha256:" + h.hexdigest()


def _config_digest(config: str | None):
    if config is None:
        return None
    if config.endswith(".toml") or "/" in config:
        return file_digest(config)
    data = resources.files("tefcore").joinpath("data", f"{config}.toml").read_bytes()
    return "sha256:" + hashlib.sha256(data).hexdigest()


def run_inputs(spec, params: dict, nb_dir=None, cache: dict | None = None) -> dict:
    """Everything that decides a run's results (module docstring).

    Parameters
    ----------
    spec : tefcore.paper.run.batch_spec.RunSpec
        The run.
    params : dict
        ``{notebook: {name: value}}``: the papermill parameters it is
        executed with (its output folders and configuration path are left
        out: they do not change a result).
    nb_dir : path, optional
        The notebooks' folder.
    cache : dict, optional
        Digests already computed (notebooks, reference data), shared by the
        runs of one batch: each file is read once.

    Returns
    -------
    dict
        JSON-able.
    """
    from ... import __version__
    from ..figures.runs import base_config

    nb_dir = Path(nb_dir or notebooks_dir())
    cache = {} if cache is None else cache
    for nb in spec.notebooks:
        if nb not in cache:
            cache[nb] = notebook_digest(nb_dir / f"{nb}.ipynb")
    if "reference data" not in cache:
        cache["reference data"] = reference_digest()
    files = {}
    for nb in spec.notebooks:
        aero = str(params[nb].get("aero_model", "thin_airfoil"))
        files.update(input_digests(base_config(aero, config=spec.config)))
    return {
        "notebooks": list(spec.notebooks),
        "parameters": {nb: {k: v for k, v in sorted(params[nb].items())
                            if k not in ("output_dir", "config")} for nb in spec.notebooks},
        "config": _config_digest(spec.config),
        "config_files": files,
        "tefcore_version": __version__,
        "model_stamp": model_stamp(),
        "paper_stamp": paper_stamp(),
        "notebook_sources": {nb: cache[nb] for nb in spec.notebooks},
        "reference_data": cache["reference data"],
    }


def _short(value) -> str:
    text = json.dumps(value, sort_keys=True)
    return text if len(text) <= 60 else text[:57] + "..."


def changes(then: dict, now: dict) -> list[str]:
    """What differs between two runs' inputs, one phrase per difference.

    Parameters
    ----------
    then : dict
        The recorded inputs.
    now : dict
        The batch's inputs (:func:`run_inputs`).

    Returns
    -------
    list of str
        Empty when they agree.
    """
    out = []
    if then.get("notebooks") != now.get("notebooks"):
        out.append(f"notebooks ({' '.join(then.get('notebooks') or [])} then, "
                   f"{' '.join(now.get('notebooks') or [])} now)")
    p_then, p_now = then.get("parameters") or {}, now.get("parameters") or {}
    for nb in now.get("notebooks") or []:
        a, b = p_then.get(nb) or {}, p_now.get(nb) or {}
        for k in sorted(set(a) | set(b)):
            if a.get(k, "(unset)") != b.get(k, "(unset)"):
                out.append(f"parameter {nb}:{k} ({_short(a.get(k, '(unset)'))} then, "
                           f"{_short(b.get(k, '(unset)'))} now)")
    if then.get("config") != now.get("config"):
        out.append(f"configuration file ({describe_digest(then.get('config'))} then, "
                   f"{describe_digest(now.get('config'))} now)")
    f_then, f_now = then.get("config_files") or {}, now.get("config_files") or {}
    for dotted in sorted(set(f_then) | set(f_now)):
        if f_then.get(dotted) != f_now.get(dotted):
            out.append(f"the file of {dotted} ({describe_digest(f_then.get(dotted))} then, "
                       f"{describe_digest(f_now.get(dotted))} now)")
    for key, what in (("tefcore_version", "tefcore version"),
                      ("model_stamp", "solver code (model_stamp)"),
                      ("paper_stamp", "paper-layer code (paper_stamp)")):
        if then.get(key) != now.get(key):
            out.append(f"{what} ({then.get(key)!r} then, {now.get(key)!r} now)")
    s_then, s_now = then.get("notebook_sources") or {}, now.get("notebook_sources") or {}
    for nb in now.get("notebooks") or []:
        if nb in s_then and s_then.get(nb) != s_now.get(nb):
            out.append(f"the cells of notebook {nb}")
    if then.get("reference_data") != now.get("reference_data"):
        out.append("the reference data (claims, digitised curves)")
    return out


def read_record(folder) -> dict | None:
    """The run record in ``folder``, None when there is none.

    Parameters
    ----------
    folder : path
        A run folder.

    Returns
    -------
    dict or None

    Raises
    ------
    StaleRunError
        The record is not a tefcore batch record (damaged, another format).
    """
    path = Path(folder) / RECORD
    if not path.exists():
        return None
    try:
        rec = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise StaleRunError(f"{path} cannot be read ({exc}); --force recomputes the run, "
                            "or write the batch to a new --out") from None
    if not isinstance(rec, dict) or rec.get("format") != FORMAT \
            or not isinstance(rec.get("inputs"), dict):
        raise StaleRunError(f"{path} is not a tefcore batch run record; --force recomputes "
                            "the run, or write the batch to a new --out")
    return rec


def write_record(folder, run: str, inputs: dict, status: str, **more) -> Path:
    """Write ``folder/batch_run.json`` atomically.

    Parameters
    ----------
    folder : path
        The run folder (existing).
    run : str
        The run's name.
    inputs : dict
        :func:`run_inputs`.
    status : str
        ``"running"``, ``"ok"`` or ``"failed"``.
    **more
        Further fields (``error``, ``notebooks``, ``claims``).

    Returns
    -------
    pathlib.Path
        The record's path.
    """
    rec = {"format": FORMAT, "version": VERSION, "run": run, "inputs": inputs,
           "environment": numerical_environment(), "status": status, **more}
    return atomic_write_text(Path(folder) / RECORD,
                             json.dumps(rec, indent=1, sort_keys=True) + "\n")


def plan_runs(out, specs, params_of, *, force: bool = False, nb_dir=None) -> list[RunPlan]:
    """Decide for each run: new, skip, retry, or -- stale -- refuse or (``force``) redo.

    Parameters
    ----------
    out : path
        The batch's output folder.
    specs : list of tefcore.paper.run.batch_spec.RunSpec
        The runs.
    params_of : callable
        ``spec -> {notebook: {name: value}}``, the papermill parameters.
    force : bool
        Recompute stale runs instead of refusing them.
    nb_dir : path, optional
        The notebooks' folder.

    Returns
    -------
    list of RunPlan
        In the order of ``specs``.

    Raises
    ------
    StaleRunError
        Without ``force``, when any run folder's recorded inputs differ from
        the batch's (or it has files and no record): every such run is
        named with what changed, before anything runs.
    """
    out = Path(out)
    plans, stale, cache = [], [], {}
    for spec in specs:
        inputs = run_inputs(spec, params_of(spec), nb_dir, cache)
        folder = out / spec.name
        if not folder.exists() or (folder.is_dir() and not any(folder.iterdir())):
            plans.append(RunPlan(spec, inputs, "new"))
            continue
        try:
            rec = read_record(folder)
        except StaleRunError as exc:
            why = [str(exc).split(";")[0].removeprefix(f"{folder / RECORD} ")]
        else:
            why = ["it holds files but no batch record"] if rec is None \
                else changes(rec["inputs"], inputs)
        if not why:
            done = rec.get("status") == "ok"
            note = environment_note(folder / RECORD, rec.get("environment"),
                                    numerical_environment()) or ""
            plans.append(RunPlan(spec, inputs, "skip" if done else "retry",
                                 "unchanged" if done else f"unchanged, {rec.get('status')}",
                                 note))
        elif force:
            plans.append(RunPlan(spec, inputs, "redo", "; ".join(why)))
        else:
            stale.append((spec.name, why))
    if stale:
        name, why = stale[0]
        more = f" (and {len(stale) - 1} more stale run(s): " + ", ".join(
            repr(n) for n, _ in stale[1:4]) + (", ..." if len(stale) > 4 else "") + ")" \
            if len(stale) > 1 else ""
        raise StaleRunError(
            f"run {name!r} in {out} was computed with other inputs: {'; '.join(why[:3])}"
            f"{' and more' if len(why) > 3 else ''}{more}; --force recomputes the stale runs "
            "(their folders' results are replaced), or write the batch to a new --out")
    return plans
