"""The packaged attribution: the default rotor's search, shipped as its result.

Attributing the failing claims of the default reproduction (moving every
assumption and model option, :mod:`tefcore.paper.attribution.differences`)
costs about four times the rest of ``tefcore reproduce``, and for the default
rotor its answer is a function of things that do not change between runs:
the code, the input data, the run's settings and the claims' verdicts.  The
package carries that answer (``reference_data/attribution-mdart.csv``) with
what it was computed from (``attribution-mdart.json``: :func:`run_stamp` and
every claim's status); the reproduction reads it instead of searching again
when all of that is the same:

* :func:`code_stamp` -- the model code (:func:`tefcore.provenance.model_stamp`),
  the paper layer's code that computes figures, checks claims, calibrates and
  searches levers (all of it but running, reporting, the notebooks and the
  inference studies), the claims' reference data and the package's input
  data files;
* the notebooks' settings the attribution reads (:data:`SETTINGS`) and the
  digests of the files the base configuration refers to;
* each claim's status as the run checked it, in the notebook that checked it
  (a claim's attribution reads its peers: the passing claims of its figure).

Anything else -- a what-if, another variant, edited code or data, a claim
whose verdict moved -- and the run searches (``tefcore reproduce``), as it
does when asked to (``--attribute-again``).  A search of the default run
writes its stamp beside ``attribution.csv`` (``attribution.json``);
:func:`tefcore.paper.run.attribution_phase.package` copies a finished
default reproduction's pair into the package after checking the stamp against
this code, and a test checks that the packaged pair is this code's.

Examples
--------
>>> stamp = run_stamp({"04_cg_offset": {"config": None}})
>>> sorted(stamp)
['code_stamp', 'inputs', 'settings', 'tefcore_version']
>>> stamp["settings"]["04_cg_offset"]["config"] is None
True
"""

from __future__ import annotations

import hashlib
import json
from importlib import resources
from pathlib import Path

import pandas as pd

from ...safe_io import atomic_output

__all__ = ["DATA_FILES", "PACKAGED", "SETTINGS", "UNSTAMPED_FOLDERS", "code_stamp",
           "packaged_attribution", "run_stamp", "stamp_differences", "stamp_record",
           "write_stamp"]

#: The packaged pair: the default reproduction's attribution and its stamp.
PACKAGED = ("attribution-mdart.csv", "attribution-mdart.json")

#: The notebook parameters :class:`~tefcore.paper.attribution.evaluate.RunSettings`
#: reads (``RunSettings.from_params``): what the attribution computes with.
SETTINGS = ("aero_model", "config", "overrides", "n_points", "values", "fig7_overhangs")

#: The paper layer's folders whose code cannot change an attribution (below
#: ``tefcore/paper``): running and reporting, the notebooks, the inference studies.
#: Every other source of the paper layer is stamped (the claims, the figures, the
#: attribution, the torsion calibration the levers re-run, ...).
UNSTAMPED_FOLDERS = ("run", "notebooks", "inference")

#: The package's data files the levers and figures load (``tefcore/data``).
DATA_FILES = ("*.toml", "*.c81")


def _reference_dir() -> Path:
    from ..claims.files import reference_dir

    return reference_dir()


def code_stamp() -> str:
    """16 hex digits of SHA-256 over everything an attribution's rows depend on in code.

    The model code (:func:`tefcore.provenance.model_stamp`); every source of
    the paper layer but those of :data:`UNSTAMPED_FOLDERS` and this module
    (which only stores and reads the result); the claims' definitions as
    :func:`tefcore.paper.claims.reference.load_claims` reads them
    (``reference_data/claims.toml`` and ``reference_data/curves/``); the
    package's data files (``tefcore/data``, :data:`DATA_FILES`: the
    configurations and aerofoil decks the levers load).  Any change to one of
    them, a comment included, changes the stamp.

    Returns
    -------
    str
    """
    from ...provenance import model_stamp

    h = hashlib.sha256(model_stamp().encode())
    files = [(f"paper/{name}", path) for name, path in _paper_sources()
             if name.split("/")[0] not in UNSTAMPED_FOLDERS and name != "attribution/packaged.py"]
    ref = _reference_dir()
    files.append(("paper/reference_data/claims.toml", ref / "claims.toml"))
    if (ref / "curves").is_dir():
        files += [(f"paper/reference_data/curves/{e.name}", e)
                  for e in (ref / "curves").iterdir() if e.is_file()]
    data = Path(str(resources.files("tefcore").joinpath("data")))
    files += [(f"data/{e.name}", e) for pattern in DATA_FILES for e in data.glob(pattern)]
    for name, entry in sorted(files, key=lambda f: f[0]):
        data = entry.read_bytes()
        h.update(name.encode() + b"\0" + len(data).to_bytes(8, "little") + data)
    return h.hexdigest()[:16]


def _paper_sources(folder=None, prefix: str = "") -> list[tuple[str, object]]:
    """``(path below tefcore/paper, file)`` of every Python source of the paper layer."""
    folder = folder if folder is not None else resources.files("tefcore.paper")
    out = []
    for e in folder.iterdir():
        if e.is_dir() and e.joinpath("__init__.py").is_file():
            out += _paper_sources(e, f"{prefix}{e.name}/")
        elif e.name.endswith(".py"):
            out.append((f"{prefix}{e.name}", e))
    return out


def _settings(params: dict) -> dict:
    """Per notebook: the parameters of :data:`SETTINGS`, as JSON keeps them (missing: None)."""
    kept = {n: {k: (p or {}).get(k) for k in SETTINGS} for n, p in params.items()}
    return json.loads(json.dumps(kept, sort_keys=True, default=str))


def run_stamp(params: dict) -> dict:
    """What a run's attribution is computed from, except the claims' statuses.

    Parameters
    ----------
    params : dict
        Notebook -> its papermill parameters (the reproduction's, merged).

    Returns
    -------
    dict
        ``tefcore_version``, ``code_stamp`` (:func:`code_stamp`), ``settings``
        (per notebook, :data:`SETTINGS`), ``inputs`` (digests of the files
        each distinct base configuration refers to,
        :func:`tefcore.provenance.input_digests`).
    """
    from ... import __version__
    from ...provenance import input_digests
    from .evaluate import RunSettings

    settings = _settings(params)
    inputs = {}
    for p in settings.values():
        key = f"{p['config'] or 'mdart'} / {p['aero_model'] or 'thin_airfoil'}"
        if key not in inputs:
            inputs[key] = input_digests(RunSettings.from_params(p).base)
    return {"tefcore_version": __version__, "code_stamp": code_stamp(),
            "settings": settings, "inputs": inputs}


def _statuses(claims: pd.DataFrame) -> dict:
    """Claim id -> [notebook, status] of a reproduction's claims table."""
    if claims.empty or "id" not in claims:
        return {}
    nb = claims["notebook"] if "notebook" in claims else pd.Series("", index=claims.index)
    return {str(i): [str(n), str(s)] for i, n, s in zip(claims["id"], nb, claims["status"],
                                                          strict=True)}


def stamp_record(claims: pd.DataFrame, params: dict, attribution=None) -> dict:
    """The stamp of an attribution: :func:`run_stamp`, the claims' statuses, its cost.

    Parameters
    ----------
    claims : pandas.DataFrame
        The run's claims (``id``, ``status``, ``notebook``).
    params : dict
        Notebook -> parameters.
    attribution : tefcore.paper.attribution.differences.Attribution, optional
        Its cost is recorded (``cpu_seconds``, ``wall_seconds``, ``tasks``).

    Returns
    -------
    dict
    """
    rec = {**run_stamp(params), "statuses": _statuses(claims)}
    if attribution is not None:
        rec.update(cpu_seconds=round(float(attribution.cpu_seconds), 1),
                   wall_seconds=round(float(attribution.wall_seconds), 1),
                   tasks=int(attribution.tasks))
    return rec


def write_stamp(path, claims: pd.DataFrame, params: dict, attribution) -> Path:
    """Write an attribution's stamp (:func:`stamp_record`) as JSON, atomically.

    Parameters
    ----------
    path : path
        The file (``OUT/attribution.json``).
    claims, params, attribution
        As :func:`stamp_record`.

    Returns
    -------
    pathlib.Path
    """
    path = Path(path)
    with atomic_output(path) as f:
        json.dump(stamp_record(claims, params, attribution), f, indent=1, sort_keys=True)
        f.write("\n")
    return path


def stamp_differences(stamp: dict, now: dict) -> list[str]:
    """What differs between a packaged stamp and this run's, in words.

    Parameters
    ----------
    stamp : dict
        The packaged attribution's stamp (:func:`stamp_record`).
    now : dict
        This run's :func:`run_stamp`.

    Returns
    -------
    list of str
        One phrase per difference (empty: the same code, data, inputs and
        settings).
    """
    out = [what for key, what in (("tefcore_version", "another tefcore version"),
                                   ("code_stamp", "other code or data (code_stamp)"))
           if stamp.get(key) != now.get(key)]
    inputs = stamp.get("inputs", {})
    if any(inputs.get(k) != v for k, v in now["inputs"].items()):
        out.append("other input files")
    settings = stamp.get("settings", {})
    for what, names in (
            ("other settings of", [n for n, s in now["settings"].items()
                                   if n in settings and settings[n] != s]),
            ("notebooks it was not made with:", [n for n in now["settings"]
                                                 if n not in settings])):
        if names:
            more = f" and {len(names) - 2} more" if len(names) > 2 else ""
            out.append(f"{what} {', '.join(names[:2])}{more}")
    return out


def packaged_attribution(claims: pd.DataFrame, params: dict):
    """The packaged attribution where it is this run's answer, else why not.

    It applies when the stamp's code, data, version and settings are this
    run's (:func:`run_stamp`) for every notebook run, and every claim of the
    run has the status, in the same notebook, it had when the package was
    made; then its rows of the run's failing validation claims are the ones a
    search would give (each claim's rows depend on its own verdict, its
    figure's passing peers and the settings only).

    Parameters
    ----------
    claims : pandas.DataFrame
        The run's claims (``id``, ``status``, ``tag``, ``notebook``).
    params : dict
        Notebook -> parameters of the run (merged).

    Returns
    -------
    (pandas.DataFrame or None, str)
        The attribution table (the run's failing claims' rows) and ``""``;
        or None and the reason it does not apply.
    """
    from .differences import COLUMNS, EXTRA_COLUMNS, failing_claims

    ref = _reference_dir()
    csv, meta = ref / PACKAGED[0], ref / PACKAGED[1]
    if not (csv.is_file() and meta.is_file()):
        return None, "the package has no attribution"
    stamp = json.loads(meta.read_text())
    run_notebooks = {n for n in claims.get("notebook", pd.Series(dtype=str)).astype(str)}
    now = run_stamp({n: p for n, p in params.items() if n in run_notebooks})
    differ = stamp_differences(stamp, now)
    if differ:
        return None, "the packaged attribution was made with " + "; ".join(differ)
    packaged = stamp.get("statuses", {})
    moved = [i for i, (nb, s) in _statuses(claims).items() if packaged.get(i) != [nb, s]]
    if moved:
        more = " ..." if len(moved) > 3 else ""
        return None, (f"{len(moved)} claim(s) checked otherwise than when the attribution was "
                      f"packaged ({', '.join(sorted(moved)[:3])}{more})")
    table = pd.read_csv(csv, dtype=str, keep_default_na=False)
    failing = set(failing_claims(claims)["id"])
    table = table[table["claim"].isin(failing)].reset_index(drop=True)
    return table.reindex(columns=COLUMNS + EXTRA_COLUMNS).fillna(""), ""
