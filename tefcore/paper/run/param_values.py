"""The values of a notebook's parameters, checked before anything runs.

``tefcore reproduce -p`` and ``tefcore batch`` give notebooks parameters; each
value is checked here, in the process that starts the run, so a typo is one
line naming the notebook, the parameter, its value and what is allowed --
never a notebook that fails minutes later:

* the scalar settings (``n_points``, ``n_jobs``, ``aero_model``,
  ``damping_measure``, ``interactive``);
* ``values`` (the sweep values of a notebook's figures: numbers, or
  quantities with their units) and ``fig7_overhangs``;
* ``config`` (a shipped name or a TOML file that loads) and every override on
  every stability figure the notebook computes (a field that exists, a value
  in its range, a flap that fits its section).
"""

from __future__ import annotations

import difflib
import functools
import math

from ...errors import TefcoreError
from ...structure.section_inertia import check_section_inertia
from .notebook_files import NOTEBOOK_FIGURES

__all__ = ["ParameterError", "check_notebook_values", "check_values", "close_match"]


class ParameterError(TefcoreError, ValueError):
    """A notebook parameter's value that cannot run: the message names the notebook, the
    parameter, its value and what is allowed."""


def _fail(origin: str, where: str, message: str):
    raise ParameterError(f"{origin}: {where + ': ' if where else ''}{message}")


def close_match(word: str, options) -> str:
    """`` (did you mean 'x'?)`` for the closest of `options` to `word`, or ``""``.

    Parameters
    ----------
    word : str
        What was given.
    options : iterable
        What is allowed.

    Returns
    -------
    str

    Examples
    --------
    >>> close_match("n_pints", ["n_points", "n_jobs"])
    " (did you mean 'n_points'?)"
    """
    near = difflib.get_close_matches(str(word), [str(o) for o in options], n=1, cutoff=0.6)
    return f" (did you mean {near[0]!r}?)" if near else ""


@functools.lru_cache(maxsize=32)
def _base_config(config: str | None, aero_model: str):
    from ..figures.runs import base_config

    return base_config(aero_model, config=config)


def check_notebook_values(nb: str, params: dict, defaults: dict, origin: str) -> None:
    """A notebook's parameters' values, checked before anything runs.

    The scalar settings (``n_points``, ``aero_model``, ...), ``values``, the
    ``config`` (a shipped name or a TOML file that loads) and every override on
    every stability figure the notebook computes (a field that exists, a value
    in its range, a flap that fits its section).

    Parameters
    ----------
    nb : str
        The notebook's full name.
    params : dict
        The parameters given for it.
    defaults : dict
        Its parameters cell's values.
    origin : str
        Where the parameters came from, for the message.

    Raises
    ------
    ParameterError
        One line naming the notebook, the parameter, its value and what is allowed.

    Examples
    --------
    >>> from tefcore.paper.run.notebook_files import notebook_parameters, notebooks_dir
    >>> nb = "04_cg_offset"
    >>> defaults = notebook_parameters(notebooks_dir() / f"{nb}.ipynb")
    >>> check_notebook_values(nb, {"n_points": -2}, defaults, "-p")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    tefcore.paper.run.param_values.ParameterError: -p: 04_cg_offset: n_points = -2; allowed: ...
    """
    config = {**defaults, **params}.get("config")
    check_values(nb, nb, params, defaults, config, origin)


def check_values(where: str, nb: str, params: dict, defaults: dict, config,
                 origin: str) -> None:
    """The given parameters' values, and every override on every figure the notebook runs.

    Parameters
    ----------
    where : str
        What the message names after `origin` (a batch's run and notebook).
    nb : str
        The notebook's full name.
    params : dict
        The parameters given for it.
    defaults : dict
        Its parameters cell's values.
    config : str or None
        The base configuration the overrides apply to (None: the shipped MDART).
    origin : str
        Where the parameters came from (a file, ``-p/--params``).

    Raises
    ------
    ParameterError
        One line naming `origin`, `where`, the parameter, its value and what is allowed.
    """
    p = {**defaults, **params}
    for name, allowed in _scalar_problems(p, params):
        _fail(origin, where, f"{name} = {p[name]!r}; allowed: {allowed}")
    if "values" in params:
        _check_sweep_values(p["values"], nb, where, origin)
    if "fig7_overhangs" in params:
        o = p["fig7_overhangs"]
        if not isinstance(o, list) or not o:
            _fail(origin, where, f"fig7_overhangs = {o!r}; allowed: a non-empty list of "
                                 "overhangs c_b/c_f")
        for v in o:
            _check_sweep_value(v, "fig7", "fig7_overhangs", where, origin)
    _check_overrides(p, nb, config, where, origin)


def _scalar_problems(p: dict, given: dict):
    """``(name, what is allowed)`` of each scalar parameter set in ``given`` with a bad value."""
    from ..figures.plotting import MEASURES
    from ..figures.runs import AERO_MODELS

    def integer(v):
        return isinstance(v, int) and not isinstance(v, bool)

    rules = {
        "n_points": (lambda v: v is None or (integer(v) and v >= 2),
                     "null (the paper's values) or an integer >= 2"),
        "n_jobs": (lambda v: integer(v) and v >= 1, "an integer >= 1"),
        "aero_model": (lambda v: v in (*AERO_MODELS, "c81"), ", ".join(AERO_MODELS)),
        "damping_measure": (lambda v: v in MEASURES, ", ".join(MEASURES)),
        "interactive": (lambda v: isinstance(v, bool), "true or false"),
    }
    for name, (ok, allowed) in rules.items():
        if name in given and not ok(p[name]):
            yield name, allowed


def _check_sweep_values(values, nb: str, where: str, origin: str) -> None:
    """``values``: a mapping of the notebook's figures to non-empty lists of sweep values."""
    if not isinstance(values, dict):
        _fail(origin, where, f"values = {values!r}; allowed: a mapping of figure to sweep "
                             "values, e.g. {fig9: [0.0, 0.2]}")
    for fig, vals in values.items():
        fig = str(fig)
        if fig not in NOTEBOOK_FIGURES[nb]:
            _fail(origin, where, f"values: {nb} computes no figure {fig!r}"
                                 f"{close_match(fig, NOTEBOOK_FIGURES[nb])}; its figures: "
                                 f"{', '.join(NOTEBOOK_FIGURES[nb]) or 'none'}")
        if not isinstance(vals, list) or not vals:
            _fail(origin, where, f"values.{fig} must be a non-empty list")
        for v in vals:
            _check_sweep_value(v, fig, f"values.{fig}", where, origin)


def _check_sweep_value(v, fig: str, name: str, where: str, origin: str) -> None:
    """One swept value: a finite number, or (a stability figure's) a quantity with its unit."""
    from ...units import parse_quantity
    from ..figures.catalogue import FIGURES
    from ..figures.quantities import swept_dimension

    if isinstance(v, str) and fig in FIGURES:
        try:
            parse_quantity(v, swept_dimension(fig))
            return
        except ValueError as exc:
            _fail(origin, where, f"{name}: {' '.join(str(exc).split())}")
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        _fail(origin, where, f"{name}: {v!r} is not a number"
                             + (" or a quantity with its unit" if fig in FIGURES else ""))


def _check_overrides(p: dict, nb: str, config, where: str, origin: str) -> None:
    """The overrides name configuration fields, and the flap fits its section with them on
    the base configuration and on every stability figure's the notebook runs."""
    from ..figures.catalogue import FIGURES
    from ..figures.runs import run_config

    overrides = p.get("overrides") or {}
    if not isinstance(overrides, dict) or not all(isinstance(k, str) for k in overrides):
        _fail(origin, where, f"overrides = {p.get('overrides')!r}; allowed: a mapping of "
                             "dotted configuration fields to values")
    fig = None
    try:
        base = _base_config(config, str(p.get("aero_model", "thin_airfoil")))
        check_section_inertia(base.with_overrides(overrides))   # the flap fits its section
        for fig in (f for f in NOTEBOOK_FIGURES[nb] if f in FIGURES):   # stability figures
            check_section_inertia(run_config(fig, base, overrides))
    except (ValueError, OSError, TefcoreError) as exc:
        text = " ".join(str(exc).split())
        _fail(origin, where, f"{'overrides: ' if overrides else ''}{text}"
                             + (f" (on the configuration of {fig})" if fig else ""))
