"""The batch file of ``tefcore batch``: named runs, their parameters and grids, validated.

A batch file (YAML) names runs; each run is the numbered notebooks executed
with its own parameters into ``OUT/<run name>/`` (:mod:`tefcore.paper.run.batch`).
Every key is optional::

    notebooks: [03, 04]          # notebooks of every run (default: all)
    config: my_rotor.toml        # base configuration of every run (relative to this file)
    params:                      # parameters of every run, as `tefcore reproduce --params`
      all: {n_points: 6}
      04_cg_offset: {damping_measure: damping_ratio}
    grid:                        # one run per combination of the listed values
      overrides.flap.overhang: [0.2, 0.29, 0.4]
      04:overrides.flight.advance_ratio: [0.2, 0.3]
    runs:                        # the runs; each takes the keys above (its own win)
      - name: baseline
      - name: stiff-actuator
        params: {all: {overrides: {actuator.stiffness: "163.04 ft-lb/rad"}}}
    name: group                  # without `runs`: the name (prefix) of the one run

Without ``runs`` the file is one run (with its grid, one run per
combination).  A **grid** key is ``[NOTEBOOK:]PARAMETER[.KEY]``: a
notebook parameter, for all the run's notebooks or one, and for a
dictionary parameter (``overrides``, ``values``) one key of it
(``overrides.flap.overhang`` sets ``overrides["flap.overhang"]``).  A file
grid and a run's grid multiply.  Runs made from a grid are named
``<name>-<key>=<value>-...`` with the key's last part (``group-overhang=0.2``).

Parameter layers, later winning: the file's ``params``, the run's
``params``, the grid's values, then the command line's (``-p``,
``--params``).  Dictionary parameters (``overrides``, ``values``) are merged
key by key across the layers; the others are replaced.  ``config`` is set by
the ``config`` key (a path relative to the batch file, or the name of a
shipped configuration) and ``output_dir`` by the batch; neither may be given
as a parameter.

Everything is checked before anything runs (:func:`load_batch`), each
problem a :class:`BatchFileError` naming the file, the run and the field:
YAML syntax, unknown keys (with a close match), unknown notebooks,
parameters a notebook does not declare (with a close match), values of the
shared parameters (``n_points``, ``n_jobs``, ``aero_model``,
``damping_measure``, ``interactive``, ``values``), every ``overrides`` field
applied to the configuration of every figure the run computes (unknown
field, value out of range, a flap that does not fit its section), the
configuration file, a bad grid (not a mapping of non-empty lists, repeated
values, too many combinations) and run names (characters, duplicates).

Examples
--------
>>> runs = parse_batch('grid: {overrides.flap.overhang: [0.2, 0.4]}\\nnotebooks: [4]')
>>> [r.name for r in runs], runs[0].notebooks
(['overhang=0.2', 'overhang=0.4'], ('04_cg_offset',))
>>> runs[1].params["04_cg_offset"]["overrides"]
{'flap.overhang': 0.4}
>>> parse_batch("runs: [{name: a, notebook: [4]}]")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
tefcore.paper.run.batch_spec.BatchFileError: <string>: runs[0] 'a': unknown key 'notebook' (did ...
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from ...errors import TefcoreError
from .notebook_files import (
    NOTEBOOKS,
    notebook_parameters,
    notebooks_dir,
    resolve_notebook,
)
from .param_values import ParameterError, check_values, close_match
from .yaml_input import plain_problem

__all__ = ["MAX_RUNS", "RESERVED_NAMES", "BatchFileError", "RunSpec", "load_batch",
           "parse_batch"]

#: Most runs a batch file may make (a larger grid is almost always a typo).
MAX_RUNS = 500
#: Names a run cannot take: the batch's own files in its output folder.
RESERVED_NAMES = frozenset({"index.html", "index.md", "runs.csv", "headlines.csv",
                            "figures", "batch.lock", "notebooks"})
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._=+-]{0,99}\Z")
_RUN_KEYS = ("config", "grid", "name", "notebooks", "params")
_TOP_KEYS = _RUN_KEYS + ("runs",)
_SET_BY_BATCH = {"output_dir": "the batch sets each notebook's output folder",
                 "config": "give the base configuration with the 'config' key of the run "
                           "or of the file"}


class BatchFileError(ParameterError):
    """A batch file that cannot be run: its message names the file, the run and the field."""


@dataclass(frozen=True)
class RunSpec:
    """One run of a batch: notebooks, parameters and base configuration, checked.

    Parameters
    ----------
    name : str
        The run's name and folder (``OUT/<name>/``).
    notebooks : tuple of str
        The notebooks it executes, in order (full names).
    params : dict
        ``{notebook: {parameter: value}}``: what the run sets, after the
        layers (the notebooks' defaults apply to the rest).
    config : str or None
        The base configuration: an absolute path of a TOML file, the name of
        a shipped configuration, or None (the shipped MDART).
    settings : dict
        What the run sets, flattened for the comparison table:
        ``"overrides.flap.overhang" -> 0.2`` for a value every notebook of
        the run gets, ``"04_cg_offset:n_points" -> 4`` for one notebook's.
    """

    name: str
    notebooks: tuple
    params: dict
    config: str | None = None
    settings: dict = field(default_factory=dict)


def _fail(origin: str, where: str, message: str):
    raise BatchFileError(f"{origin}: {where + ': ' if where else ''}{message}")


def _check_keys(data: dict, allowed, origin: str, where: str) -> None:
    for key in data:
        if key not in allowed:
            _fail(origin, where, f"unknown key {key!r}{close_match(key, allowed)}; allowed: "
                                 f"{', '.join(sorted(allowed))}")


def _notebook(key, origin: str, where: str) -> str:
    try:
        return resolve_notebook(str(key))
    except ValueError:
        _fail(origin, where, f"unknown notebook {key!r}{close_match(key, NOTEBOOKS)}; known: "
                             f"{', '.join(NOTEBOOKS)}")


def _notebooks(value, origin: str, where: str) -> tuple:
    items = value if isinstance(value, list) else [value]
    if not items or any(isinstance(v, dict | list) or v is None for v in items):
        _fail(origin, where, "notebooks must be a notebook or a list of notebooks "
                             "(e.g. [03, 04_cg_offset])")
    names = [_notebook(v, origin, where) for v in items]
    if len(set(names)) != len(names):
        _fail(origin, where, f"a notebook is listed twice: {items}")
    return tuple(n for n in NOTEBOOKS if n in names)


def _params(value, origin: str, where: str) -> dict:
    """``params`` as in ``reproduce --params``: ``{"all"|notebook: {name: value}}``."""
    if value is None:
        return {}
    if not isinstance(value, dict):
        _fail(origin, where, "params must map 'all' or a notebook to parameters, e.g. "
                             "{all: {n_points: 6}}")
    out = {}
    for key, params in value.items():
        target = "all" if str(key) == "all" else _notebook(key, origin, f"{where}.{key}")
        if params is None:
            params = {}
        if not isinstance(params, dict):
            _fail(origin, f"{where}.{key}", "must map parameter names to values")
        for pname in params:
            if not isinstance(pname, str) or not pname.isidentifier():
                _fail(origin, f"{where}.{key}", f"parameter name {pname!r} is not an "
                                                "identifier")
            if pname in _SET_BY_BATCH:
                _fail(origin, f"{where}.{key}.{pname}", _SET_BY_BATCH[pname])
        out.setdefault(target, {}).update(params)
    return out


def _grid(value, origin: str, where: str) -> list[tuple[str, str, str, list]]:
    """``[(target, parameter, key or "", values)]`` of a grid mapping."""
    if value is None:
        return []
    if not isinstance(value, dict) or not value:
        _fail(origin, where, "a grid maps [NOTEBOOK:]PARAMETER[.KEY] to a list of values, "
                             "e.g. {overrides.flap.overhang: [0.2, 0.29]}")
    out = []
    for gkey, values in value.items():
        text = str(gkey)
        target, sep, rest = text.rpartition(":")
        target = _notebook(target, origin, f"{where}.{text}") if sep else "all"
        pname, _, sub = rest.partition(".")
        if not pname.isidentifier():
            _fail(origin, f"{where}.{text}", f"{pname!r} is not a parameter name; a grid key "
                                             "is [NOTEBOOK:]PARAMETER[.KEY]")
        if pname in _SET_BY_BATCH:
            _fail(origin, f"{where}.{text}", _SET_BY_BATCH[pname])
        if not isinstance(values, list) or not values:
            _fail(origin, f"{where}.{text}", f"must be a non-empty list of values, got "
                                             f"{values!r}")
        seen = []
        for v in values:
            if v in seen:
                _fail(origin, f"{where}.{text}", f"value {v!r} is listed twice")
            seen.append(v)
        out.append((target, pname, sub, list(values)))
    return out


def _merge(params: dict, layer: dict) -> None:
    """Lay ``layer`` over ``params`` (one notebook's), dictionaries merged key by key."""
    for k, v in layer.items():
        if isinstance(v, dict) and isinstance(params.get(k), dict):
            params[k] = {**params[k], **v}
        else:
            params[k] = dict(v) if isinstance(v, dict) else v


def _short(value) -> str:
    text = repr(value) if isinstance(value, float) else str(value)
    if isinstance(value, list | dict):
        text = re.sub(r"[\s'\"{}\[\]]", "", str(value))
    return re.sub(r"[^A-Za-z0-9.+-]+", "_", text).strip("_") or "none"


def _grid_names(axes) -> list[str]:
    """Readable name parts of the grid keys: the shortest unique tail of each."""
    parts = [[t for t in ((a[0] if a[0] != "all" else ""), a[1], *a[2].split(".")) if t]
             for a in axes]
    for n in range(1, max((len(p) for p in parts), default=1) + 1):
        names = [".".join(p[-n:]) for p in parts]
        if len(set(names)) == len(names):
            return names
    return [".".join(p) for p in parts]


def _settings(params: dict, notebooks, config) -> dict:
    """Flatten a run's parameters: shared values under their name, others per notebook."""
    flat = {}
    for nb in notebooks:
        for k, v in sorted(params[nb].items()):
            if isinstance(v, dict) and v:
                for sub, sv in sorted(v.items()):
                    flat.setdefault(f"{k}.{sub}", {})[nb] = sv
            else:
                flat.setdefault(k, {})[nb] = v
    out = {}
    if config is not None:
        out["config"] = Path(config).name if ("/" in config or config.endswith(".toml")) \
            else config
    for key, per_nb in flat.items():
        vals = list(per_nb.values())
        if len(per_nb) == len(notebooks) and all(v == vals[0] for v in vals):
            out[key] = vals[0]
        else:
            for nb, v in per_nb.items():
                out[f"{nb}:{key}"] = v
    return out


def _config_path(value, origin: str, where: str, base_dir: Path) -> str | None:
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip():
        _fail(origin, where, "config must be a path to a TOML file or a shipped "
                             "configuration's name")
    from ...config.io import available_configs

    if "/" not in value and not value.endswith(".toml"):
        if value not in available_configs():
            _fail(origin, where, f"no shipped configuration {value!r}"
                                 f"{close_match(value, available_configs())}; a file needs its "
                                 ".toml suffix")
        return value
    path = (base_dir / value).resolve()
    if not path.is_file():
        _fail(origin, where, f"configuration file {path} not found")
    from ...config.io import load_config

    try:
        load_config(path)
    except (ValueError, OSError, TefcoreError) as exc:
        _fail(origin, where, " ".join(str(exc).split()))
    return str(path)


def _run_list(data: dict, origin: str) -> list[dict]:
    runs = data.get("runs")
    if runs is None:
        if "name" in data and data["name"] is not None and not isinstance(data["name"], str):
            _fail(origin, "name", "must be a string")
        return [{"name": data.get("name") or ""}]
    if "name" in data:
        _fail(origin, "name", "a top-level name is for a file without 'runs'; name each run")
    if not isinstance(runs, list) or not runs:
        _fail(origin, "runs", "must be a non-empty list of runs, e.g. [{name: baseline}]")
    for i, r in enumerate(runs):
        if not isinstance(r, dict):
            _fail(origin, f"runs[{i}]", "a run is a mapping with a name, e.g. {name: baseline}")
    return runs


def parse_batch(text: str, *, origin: str = "<string>", base_dir=None, only=None,
                extra_params=None, nb_dir=None) -> list[RunSpec]:
    """Parse and check a batch file's text; return its runs (nothing runs).

    Parameters
    ----------
    text : str
        The YAML document (module docstring).
    origin : str
        Where it comes from, for messages (the file's path).
    base_dir : path, optional
        Folder that a relative ``config`` path is relative to (default: the
        current folder).
    only : sequence of str, optional
        Keep only these notebooks in every run (``tefcore batch --only``);
        a run left with none is dropped.
    extra_params : list of dict, optional
        Parameter layers applied over every run last (``-p``, ``--params``
        of the command line), ``{"all"|notebook: {name: value}}``.
    nb_dir : path, optional
        The notebooks' folder, whose parameters cells are checked against
        (default :func:`~tefcore.paper.run.notebook_files.notebooks_dir`).

    Returns
    -------
    list of RunSpec
        In file order, grid combinations in the order of the grid's keys.

    Raises
    ------
    BatchFileError
        Any problem (module docstring), naming the file, run and field.
    """
    data = _load_yaml(text, origin)
    batch = _Batch(data, origin, Path(base_dir or "."), Path(nb_dir or notebooks_dir()),
                   only, extra_params)
    specs, seen = [], {}
    for i, run in enumerate(_run_list(data, origin)):
        specs += batch.run_specs(i, run, len(specs), seen)
    if not specs:
        _fail(origin, "--only", "no run has any of these notebooks")
    return specs


def _load_yaml(text: str, origin: str) -> dict:
    """The batch file's top-level mapping, checked for plain data of bounded size."""
    import yaml

    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f"line {mark.line + 1}: " if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        _fail(origin, "", f"not valid YAML ({at}{problem})")
    except RecursionError:
        _fail(origin, "", "not valid YAML (nested too deeply)")
    if data is None:
        _fail(origin, "", "the file is empty; it needs runs, a grid, or one run's keys")
    if not isinstance(data, dict):
        _fail(origin, "", "the top level must be a mapping (runs:, grid:, params:, ...)")
    problem = plain_problem(data)
    if problem is not None:
        _fail(origin, *problem)
    _check_keys(data, _TOP_KEYS, origin, "")
    return data


class _Batch:
    """A batch file's top-level settings, and each run's specs from them."""

    def __init__(self, data, origin, base_dir, nb_dir, only, extra_params):
        self.data, self.origin, self.base_dir, self.nb_dir = data, origin, base_dir, nb_dir
        self.has_runs = "runs" in data
        self.notebooks = _notebooks(data["notebooks"], origin, "notebooks") \
            if data.get("notebooks") is not None else tuple(NOTEBOOKS)
        self.params = _params(data.get("params"), origin, "params")
        self.grid = _grid(data.get("grid"), origin, "grid")
        self.config = _config_path(data.get("config"), origin, "config", base_dir)
        self.extra = list(extra_params or [])
        self.keep = None if not only else {_notebook(n, origin, "--only") for n in only}
        self.declared: dict = {}

    def parameters_of(self, nb):
        """The parameters a notebook declares (its parameters cell)."""
        if nb not in self.declared:
            src = self.nb_dir / f"{nb}.ipynb"
            if not src.is_file():
                _fail(self.origin, "", f"notebook {src} not found")
            self.declared[nb] = notebook_parameters(src)
        return self.declared[nb]

    def _run_settings(self, i, run):
        """``(name, where, notebooks, config, own params, grid axes)`` of one run."""
        origin, name = self.origin, run.get("name")
        where = f"runs[{i}]" + (f" {name!r}" if name else "") if self.has_runs else ""
        _check_keys(run, _RUN_KEYS if self.has_runs else _TOP_KEYS, origin, where)
        if name is not None and not isinstance(name, str):
            _fail(origin, where, f"name must be a string, got {name!r}")
        nbs = _notebooks(run["notebooks"], origin, f"{where}.notebooks".lstrip(".")) \
            if self.has_runs and run.get("notebooks") is not None else self.notebooks
        if self.keep is not None:
            nbs = tuple(n for n in nbs if n in self.keep)
            if not nbs:                 # not in this batch: its settings are not read
                return name, where, nbs, None, {}, []
        config = _config_path(run.get("config"), origin, f"{where}.config", self.base_dir) \
            if self.has_runs and run.get("config") is not None else self.config
        own = _params(run.get("params"), origin, f"{where}.params") if self.has_runs else {}
        axes = self.grid + (_grid(run.get("grid"), origin, f"{where}.grid")
                            if self.has_runs else [])
        return name, where, nbs, config, own, axes

    def _check_axes(self, axes, nbs, where):
        """Each grid axis names a notebook of the run and one of its parameters."""
        for target, pname, sub, _ in axes:
            for nb in nbs if target == "all" else (target,):
                if target != "all" and nb not in nbs:
                    _fail(self.origin, f"{where}.grid", f"{target} is not one of the run's "
                                                        f"notebooks ({', '.join(nbs)})")
                known = self.parameters_of(nb)
                if pname not in known:
                    _fail(self.origin, f"{where}.grid", f"{nb} has no parameter {pname!r}"
                                                        f"{close_match(pname, known)}")
                if sub and not isinstance(known[pname], dict):
                    _fail(self.origin, f"{where}.grid", f"{pname} is not a mapping parameter, "
                                                        f"so {pname}.{sub} means nothing")

    def _combination_params(self, nbs, own, axes, combo):
        """Each notebook's parameters: the file's, the run's, the grid's, the command line's."""
        params = {nb: {} for nb in nbs}
        for layer in (self.params, own):
            for nb in nbs:
                _merge(params[nb], layer.get("all", {}))
                _merge(params[nb], layer.get(nb, {}))
        for (target, pname, sub, _), v in zip(axes, combo, strict=True):
            for nb in nbs if target == "all" else (target,):
                _merge(params[nb], {pname: {sub: v}} if sub else {pname: v})
        for layer in self.extra:
            for nb in nbs:
                _merge(params[nb], layer.get("all", {}))
                _merge(params[nb], layer.get(nb, {}))
        return params

    def _run_name(self, name, labels, combo, where, seen) -> str:
        """The run's name (its own, then the grid's values), checked and unique."""
        origin = self.origin
        parts = [name] if name else []
        parts += [f"{lab}={_short(v)}" for lab, v in zip(labels, combo, strict=True)]
        rname = "-".join(parts)
        if not rname:
            _fail(origin, where, "a run needs a name (or a grid to name it from)")
        if not _NAME.match(rname):
            _fail(origin, where, f"run name {rname!r} is not a folder name: letters, "
                                 "digits and . _ = + - only, starting with a letter or "
                                 "digit, at most 100 characters")
        if rname.lower() in RESERVED_NAMES:
            _fail(origin, where, f"run name {rname!r} is taken by the batch's own files")
        if rname.lower() in seen:
            _fail(origin, where, f"duplicate run name {rname!r} (also {seen[rname.lower()]})"
                                 "; name the runs apart")
        seen[rname.lower()] = where or "the file"
        return rname

    def run_specs(self, i, run, n_before, seen) -> list[RunSpec]:
        """The runs of one entry of the file (one per grid combination)."""
        name, where, nbs, config, own, axes = self._run_settings(i, run)
        if not nbs:
            return []
        self._check_axes(axes, nbs, where)
        n_comb = math.prod(len(a[3]) for a in axes)
        if n_before + n_comb > MAX_RUNS:
            _fail(self.origin, where, f"the grids make more than {MAX_RUNS} runs "
                                      f"({n_comb} combinations here); split the batch")
        labels = _grid_names(axes)
        specs = []
        for combo in itertools.product(*(a[3] for a in axes)) if axes else [()]:
            params = self._combination_params(nbs, own, axes, combo)
            rname = self._run_name(name, labels, combo, where, seen)
            for nb in nbs:
                known = self.parameters_of(nb)
                for pname in sorted(set(params[nb]) - set(known)):
                    _fail(self.origin, f"run {rname!r}", f"{nb} has no parameter {pname!r}"
                                                         f"{close_match(pname, known)}; it has "
                                                         f"{', '.join(sorted(known))}")
                try:
                    check_values(f"run {rname!r}, {nb}", nb, params[nb], known, config,
                                 self.origin)
                except ParameterError as exc:
                    raise BatchFileError(str(exc)) from None
            specs.append(RunSpec(rname, nbs, params, config, _settings(params, nbs, config)))
        return specs


def load_batch(path, *, only=None, extra_params=None, nb_dir=None) -> list[RunSpec]:
    """Read and check a batch file (:func:`parse_batch`); a relative ``config`` is relative to it.

    Parameters
    ----------
    path : path
        The YAML file.
    only : sequence of str, optional
        Keep only these notebooks in every run.
    extra_params : list of dict, optional
        Parameter layers applied over every run last.
    nb_dir : path, optional
        The notebooks' folder.

    Returns
    -------
    list of RunSpec
        The runs.

    Raises
    ------
    BatchFileError
        An unreadable file (not UTF-8, over 1 MB, missing) or any problem
        :func:`parse_batch` finds.
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise BatchFileError(f"{path}: cannot read the batch file ({exc.strerror or exc})") \
            from None
    if len(raw) > 1 << 20:
        raise BatchFileError(f"{path}: {len(raw)} bytes; a batch file is at most 1 MB")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise BatchFileError(f"{path}: not UTF-8 text (byte {exc.start})") from None
    return parse_batch(text, origin=str(path), base_dir=path.resolve().parent, only=only,
                       extra_params=extra_params, nb_dir=nb_dir)
