"""Notebook parameters for ``tefcore reproduce``: from a YAML file and ``-p`` options.

Parameters come in layers of ``{"all"|notebook: {name: value}}``:

* a YAML file (``--params``)::

      all:                      # every notebook
        n_jobs: 2
      03_overhang:              # one notebook (also "03" or "03_overhang.ipynb")
        n_points: 8

* ``-p name value`` (all notebooks) or ``-p 03_overhang:name value`` (one);
  values are YAML (``-p n_points 5`` gives an int, ``-p overrides
  "{flight.ct_sigma: 0.08}"`` a dict).

Precedence: file ``all`` < file per notebook < ``-p`` all < ``-p`` per
notebook (:func:`merge_params`).

Examples
--------
>>> parse_cli_params([("n_jobs", "2"), ("03:n_points", "5")])
{'all': {'n_jobs': 2}, '03_overhang': {'n_points': 5}}
>>> merged = merge_params({"all": {"n_jobs": 1, "n_points": 4}},
...                       {"03_overhang": {"n_points": 6}})
>>> merged["03_overhang"], merged["04_cg_offset"]
({'n_jobs': 1, 'n_points': 6}, {'n_jobs': 1, 'n_points': 4})
"""

from __future__ import annotations

from pathlib import Path

from .notebook_files import NOTEBOOKS, resolve_notebook

__all__ = ["load_params_file", "merge_params", "parse_cli_params", "parse_value"]


def parse_value(text: str):
    """A ``-p`` value as YAML: ``"5"`` -> 5, ``"[0.1, 0.2]"`` -> list, ``"abc"`` -> 'abc'.

    Parameters
    ----------
    text : str
        The value as typed.
    """
    import yaml

    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def parse_cli_params(pairs) -> dict:
    """``[(name, value), ...]`` from ``-p`` -> ``{"all"|notebook: {name: value}}``.

    Parameters
    ----------
    pairs : iterable of (str, str)
        ``NAME`` or ``NOTEBOOK:NAME`` and the value.
    """
    out: dict[str, dict] = {}
    for name, value in pairs or ():
        target, sep, pname = str(name).rpartition(":")
        target = resolve_notebook(target) if sep else "all"
        if not pname.isidentifier():
            raise ValueError(f"-p: parameter name {pname!r} is not an identifier")
        out.setdefault(target, {})[pname] = parse_value(value) if isinstance(value, str) \
            else value
    return out


def load_params_file(path) -> dict:
    """YAML parameters file -> ``{"all"|notebook: {name: value}}`` (keys checked).

    Parameters
    ----------
    path : path
        The YAML file.
    """
    import yaml

    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8")) or {}
    except OSError as exc:
        raise ValueError(f"{path}: cannot read the parameters file "
                         f"({exc.strerror or exc})") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: the parameters file is not UTF-8 text (byte "
                         f"{exc.object[exc.start]:#04x} at offset {exc.start})") from None
    except yaml.YAMLError as exc:
        raise ValueError(f"{path}: not valid YAML ({str(exc).splitlines()[0]})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a mapping of notebook (or 'all') to parameters")
    out = {}
    for key, params in data.items():
        if params is None:
            params = {}
        if not isinstance(params, dict):
            raise ValueError(f"{path}: {key!r} must map parameter names to values")
        out["all" if str(key) == "all" else resolve_notebook(str(key))] = dict(params)
    return out


def merge_params(*layers, notebooks=NOTEBOOKS) -> dict:
    """Per-notebook parameters from layers of ``{"all"|notebook: {...}}`` (later wins).

    Parameters
    ----------
    *layers : dict
        Parameter layers, lowest precedence first.
    notebooks : sequence of str
        The notebooks to give parameters to.
    """
    merged = {nb: {} for nb in notebooks}
    for layer in layers:
        for nb in notebooks:
            merged[nb].update((layer or {}).get("all", {}))
            merged[nb].update((layer or {}).get(nb, {}))
    return merged
