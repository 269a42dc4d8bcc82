"""Two-parameter stability maps: the flap designer's chart.

:func:`stability_map` evaluates the stability over a grid of two
configuration fields -- e.g. flap CG offset and overhang, or actuator
stiffness and advance ratio -- as one :func:`tefcore.sweeps.sweep.sweep` of the
first field per value of the second (each resumable in its own sweep file,
run on joblib or a dask cluster), and refines where the flutter root's
growth rate changes sign along a row (:func:`scipy.optimize.brentq`), so the
flutter boundary is located beyond the grid's resolution.

The mapped quantity is the **flutter root** of each point: the least stable
flap-induced root (:func:`tefcore.modes.roles.flutter_root`: unstable, or much
less stable, with the flap held at its trimmed motion; a property of the point
alone, no tracking needed), with its frequency, flap participation and the
mode it continues from; the **TEF branch** (the root the uncoupled flap
continues into) is kept too.  Results come as a tidy table and an :class:`xarray.Dataset`.

Examples
--------
>>> import numpy as np, pandas as pd
>>> from types import SimpleNamespace
>>> from tefcore.config.io import load_config
>>> def toy(cfg):   # flutter where cg_offset + overhang > 0.5
...     g = cfg.flap.cg_offset + cfg.flap.overhang - 0.5
...     modes = pd.DataFrame({"mode_id": [0], "label": ["TEF"], "frequency_per_rev": [5.0],
...                           "real_part": [g], "damping_ratio": [-g / 5.0], "share_TEF": [0.9]})
...     return SimpleNamespace(modes=modes, eigenvectors=np.ones((1, 1), complex), trim={})
>>> m = stability_map(load_config("mdart"), "flap.cg_offset", [0.0, 0.2, 0.4],
...                   "flap.overhang", [0.1, 0.3], point=toy, progress=False)
>>> m.dataset["flutter_growth"].shape
(2, 3)
>>> m.boundary[["y", "x"]].round(6).values.tolist()   # flutter where x >= 0.5 - y
[[0.1, 0.4], [0.3, 0.2]]
"""

from __future__ import annotations

import numbers
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.optimize import brentq

from ..aero.c81.range_summary import (
    collected_range_warnings,
    describe_clipped,
    merge_clipped,
    range_warning,
)
from ..config.configuration import Config
from ..modes.roles import flutter_root
from ..runtime import process_count, worker_init
from .evaluate import (
    check_result,
    default_point,
    forked_workers,
    point_name,
    takes_warm_start,
    warn_clipped,
    worker_pool,
)
from .map_store import BoundaryFile, boundary_header, crossing_key
from .sweep import SweepResult, sweep

__all__ = ["MapResult", "map_files", "stability_map"]


@dataclass
class MapResult:
    """Result of :func:`stability_map`.

    Attributes
    ----------
    x_field, y_field : str
    table : DataFrame
        One row per grid point (``x_index, y_index, x, y`` in SI,
        ``x_value, y_value`` as given, ``status``, ``error``, ``warning``:
        C81 table inputs clipped at the point, or None) with the flutter
        root's ``flutter_growth`` (real part, /rev), ``flutter_frequency``,
        ``flutter_share_TEF`` and ``flutter_label``, and the row's TEF branch
        ``tef_growth``, ``tef_frequency``, ``tef_certain``.  Failed points
        carry NaN and their error.
    boundary : DataFrame
        ``y, x, direction`` (``destabilising``: flutter above ``x``), the
        refined zero of the flutter growth between two grid points of a row,
        and ``x_lo, x_hi`` (the bracket), ``converged``.
    rows : list of SweepResult
        The sweep of each row (``y`` value).
    """

    x_field: str
    y_field: str
    table: pd.DataFrame
    boundary: pd.DataFrame
    rows: list = field(default_factory=list, repr=False)

    @property
    def dataset(self):
        """The map as an :class:`xarray.Dataset` (dims ``y``, ``x``; SI coordinates)."""
        import xarray as xr

        t = self.table.sort_values(["y_index", "x_index"])
        ny, nx = t["y_index"].max() + 1, t["x_index"].max() + 1
        xs = t.drop_duplicates("x_index").sort_values("x_index")["x"].to_numpy(float)
        ys = t.drop_duplicates("y_index").sort_values("y_index")["y"].to_numpy(float)
        variables = {}
        for col in ("flutter_growth", "flutter_frequency", "flutter_share_TEF", "tef_growth",
                    "tef_frequency"):
            grid = np.full((ny, nx), np.nan)
            grid[t["y_index"].to_numpy(), t["x_index"].to_numpy()] = t[col].to_numpy(float)
            variables[col] = (("y", "x"), grid)
        ds = xr.Dataset(variables, coords={"x": xs, "y": ys})
        ds.attrs.update(x_field=self.x_field, y_field=self.y_field,
                        description="flutter root: least stable flap-induced root "
                                    "(tefcore.modes.roles.flutter_root); growth in 1/rev")
        return ds

    def plot(self, ax=None, levels=None, x_unit: str | None = None,
             y_unit: str | None = None, x_label: str | None = None,
             y_label: str | None = None):
        """Colour map of the flutter growth with the flutter boundary.

        The zero contour of the grid and the refined boundary points.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw in (default: a new figure).
        levels : sequence, optional
            Unused; kept for the signature of earlier versions.
        x_unit, y_unit : str, optional
            Show a dimensional axis in this unit (e.g. ``"ft-lbf/rad"``)
            instead of SI.
        x_label, y_label : str, optional
            Axis labels (default: the field names, with the unit).

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        ds = self.dataset
        if ax is None:
            _, ax = plt.subplots(figsize=(6.4, 4.8))
        x = _in_unit(ds["x"].values, self.x_field, x_unit)
        y = _in_unit(ds["y"].values, self.y_field, y_unit)
        g = ds["flutter_growth"]
        lim = float(np.nanmax(np.abs(g.values))) if np.isfinite(g.values).any() else 1.0
        mesh = ax.pcolormesh(x, y, g, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
        ax.figure.colorbar(mesh, ax=ax, label="flutter root growth Re(s)/Ω [1/rev]")
        if np.isnan(g.values).any():          # points without a result: grey
            from matplotlib.patches import Patch

            ax.set_facecolor("0.75")
            ax.add_artist(ax.legend(handles=[Patch(facecolor="0.75", edgecolor="0.4",
                                                   label="no result")],
                                    loc="upper left", fontsize="small"))
        if min(g.shape) >= 2 and np.nanmin(g.values) < 0 < np.nanmax(g.values):
            ax.contour(x, y, g, levels=[0.0], colors="k", linewidths=1.2)
        if not self.boundary.empty:
            ax.plot(_in_unit(self.boundary["x"].to_numpy(float), self.x_field, x_unit),
                    _in_unit(self.boundary["y"].to_numpy(float), self.y_field, y_unit),
                    "k.", ms=5, label="boundary (refined)")
            ax.legend(loc="best", fontsize="small")
        ax.set_xlabel(x_label or self.x_field + (f" [{x_unit}]" if x_unit else ""))
        ax.set_ylabel(y_label or self.y_field + (f" [{y_unit}]" if y_unit else ""))
        return ax


def _in_unit(values, field_name: str, unit: str | None):
    """SI ``values`` of a field in ``unit`` (unchanged without one)."""
    if not unit:
        return np.asarray(values, float)
    from ..config.text_input import field_param
    from ..units import from_si

    return np.asarray(from_si(np.asarray(values, float), unit,
                              field_param(field_name).dimension), float)


def _si(cfg: Config, name: str, v) -> float:
    si = cfg.with_overrides({name: v}).get(name)
    if not isinstance(si, numbers.Real):
        raise ValueError(f"{name} is not a numeric field (value {si!r})")
    return float(si)


def _row_frame(res: SweepResult, y_index: int, y_si: float, y_value) -> pd.DataFrame:
    """One row of the map from its sweep: flutter root and TEF branch per x."""
    t = res.table
    main = t[t["refinement"] == 0] if "refinement" in t else t
    rows = []
    for point, g in main.groupby("point", sort=True):
        first = g.iloc[0]
        rec = {"x_index": int(point), "y_index": y_index, "x": first["value_si"], "y": y_si,
               "x_value": first["value"], "y_value": y_value, "status": first["status"],
               "error": first["error"], "warning": first.get("warning"),
               "flutter_growth": np.nan, "flutter_frequency": np.nan,
               "flutter_share_TEF": np.nan, "flutter_label": "", "tef_growth": np.nan,
               "tef_frequency": np.nan, "tef_certain": False}
        if first["status"] == "ok":
            fr = g[g["flutter_root"].fillna(False).astype(bool)]
            if not fr.empty:
                r = fr.iloc[0]
                rec.update(flutter_growth=r["real_part"], flutter_frequency=r["frequency_per_rev"],
                           flutter_share_TEF=r.get("share_TEF", np.nan),
                           flutter_label=str(r["label"]))
            br = g[g["tef_branch"].fillna(False).astype(bool)]
            if not br.empty:
                r = br.iloc[0]
                rec.update(tef_growth=r["real_part"], tef_frequency=r["frequency_per_rev"],
                           tef_certain=bool(r["tef_branch_certain"]))
        rows.append(rec)
    return pd.DataFrame(rows)


def _flutter_growth(point, cfg, x_field, x, warm=None) -> float:
    """Flutter-root growth at one x (NaN when no root has the flap's participation).

    ``warm``: a dict holding the previous evaluation's trim, for a point function
    that takes ``warm_start`` (the brentq iterations of one bracket, in order)."""
    cfg_x = cfg.with_overrides({x_field: float(x)})
    result = None
    if warm is not None and warm.get("trim") is not None:
        try:
            result = point(cfg_x, warm_start=warm["trim"])
        except Exception:  # astray from the warm start: cold below
            result = None
    if result is None:
        result = point(cfg_x)
    if warm is not None:
        warm["trim"] = getattr(result, "trim_result", None)
    modes, _, _ = check_result(result)
    row = flutter_root(modes)
    return float(modes.loc[row, "real_part"]) if row is not None else np.nan


def _row_in_worker(cfg, x_field, x_values, point, out, resume):
    """One row of the map as a serial sweep in a worker process."""
    worker_init()
    return sweep(cfg, x_field, x_values, point=point, n_jobs=1, out=out, resume=resume,
                 refine=False, progress=False, warn=False)


def _in_workers(fn, args, n_jobs):
    """``[fn(*a) for a in args]`` in `n_jobs` worker processes, in order: the
    forked pool of a command (:func:`tefcore.sweeps.evaluate.fork_workers`,
    ready at once), else joblib's loky processes; never more processes than
    cores or tasks (:func:`tefcore.runtime.process_count`)."""
    workers = process_count(n_jobs, len(args))
    if forked_workers():
        return list(worker_pool(workers).map(fn, *zip(*args, strict=True)))
    from joblib import Parallel, delayed

    return Parallel(n_jobs=workers, backend="loky")(delayed(fn)(*a) for a in args)


def _refine_in_worker(*args):
    """The task of a worker process: the process settings first (tefcore.runtime)."""
    worker_init()
    return _refine(*args)


def _refine(point, cfg, x_field, y_si, a, b, direction, xtol):
    """Zero of the flutter growth between two grid x (brentq); never raises.

    The record's ``clipped`` is the summary of the C81 inputs its evaluations
    clipped (or None): the map warns once for all its crossings, not once per
    evaluation (:func:`_boundary`)."""
    warm = {} if takes_warm_start(point) else None
    with collected_range_warnings() as found:
        try:
            x0, info = brentq(lambda x: _flutter_growth(point, cfg, x_field, x, warm), a, b,
                              xtol=xtol, maxiter=40, full_output=True, disp=False)
            rec = {"y": y_si, "x": float(x0), "direction": direction, "x_lo": a, "x_hi": b,
                   "converged": bool(info.converged), "error": ""}
        except Exception as err:   # a point failed inside the bracket: keep the bracket
            rec = {"y": y_si, "x": 0.5 * (a + b), "direction": direction, "x_lo": a,
                   "x_hi": b, "converged": False, "error": f"{type(err).__name__}: {err}"}
    return {**rec, "clipped": found["clipped"]}


def map_files(out, n_rows: int) -> list[Path]:
    """The files a map keeps in its folder `out`: one sweep file per row, then the boundary's.

    Parameters
    ----------
    out : path-like
        The map's folder (``stability_map(out=...)``).
    n_rows : int
        Its y values.

    Returns
    -------
    list of pathlib.Path
        ``row_0.jsonl`` ... ``row_<n_rows - 1>.jsonl``, ``boundary.jsonl``.

    Examples
    --------
    >>> [p.name for p in map_files("m", 2)]
    ['row_0.jsonl', 'row_1.jsonl', 'boundary.jsonl']
    """
    out = Path(out)
    return [out / f"row_{k}.jsonl" for k in range(n_rows)] + [out / "boundary.jsonl"]


def stability_map(cfg: Config, x_field: str, x_values, y_field: str, y_values, *,
                  point: Callable | None = None, n_jobs: int = 1, backend: str = "joblib",
                  client=None, out=None, resume: bool = True, refine_boundary: bool = True,
                  xtol: float | None = None, progress: bool | None = None) -> MapResult:
    """Stability over a grid of two configuration fields.

    Parameters
    ----------
    cfg : Config
        Base configuration.
    x_field, y_field : str
        Dotted scalar fields (e.g. ``"flap.cg_offset"``, ``"flap.overhang"``).
    x_values, y_values : sequence
        Numbers (SI) or ``"value unit"`` strings.
    point : callable, optional
        As in :func:`tefcore.sweeps.sweep.sweep` (default
        :func:`tefcore.linear.stability.stability`).
    n_jobs, backend, client
        Parallel execution of each row's points, as in :func:`tefcore.sweeps.sweep.sweep`;
        a dask ``client`` (e.g. ``distributed.Client("tcp://scheduler:8786")``)
        runs them on a cluster, and the boundary refinement too.
    out : path, optional
        Folder for the map's files: ``row_<k>.jsonl`` (one sweep file per y
        value) and ``boundary.jsonl`` (:mod:`tefcore.sweeps.map_store`), each
        with a header of the configuration, input files and code that
        decide it; re-running resumes, and a file whose header does not
        match is refused before anything is computed.
    resume : bool
        With ``out``: load the points and boundary crossings already there;
        ``False`` starts every file anew.
    refine_boundary : bool
        Locate the zero of the flutter growth between grid points of a row
        where it changes sign (brentq, to ``xtol``).
    xtol : float, optional
        Tolerance of the boundary in x (default 1e-4 of the x range).
    progress : bool or None
        tqdm progress bar on stderr; ``None``: only if stderr is a terminal.

    Returns
    -------
    MapResult

    Raises
    ------
    tefcore.errors.SweepFileError
        A file in ``out`` holds work for other inputs (fields, configuration,
        input files, tefcore version, model code) or is damaged (naming the
        file and the line); a last line cut short by a crash is dropped
        with a warning instead, and computed again.
    tefcore.errors.OutputError
        A file in ``out`` is a link or is being written by another process.
    """
    y_values = list(y_values)
    x_values = list(x_values)
    if not x_values or not y_values:
        raise ValueError("a map needs at least one x value and one y value")
    if x_field == y_field:
        raise ValueError(f"the map's two fields are the same: {x_field!r}")
    outdir = None if out is None else Path(out)
    if outdir is not None:
        outdir.mkdir(parents=True, exist_ok=True)
    store = None
    if outdir is not None and refine_boundary:
        # checked (and locked) before any row is computed: a stale boundary is refused
        # first, never reused for another configuration or code (map_store)
        store = BoundaryFile(map_files(outdir, len(y_values))[-1],
                             boundary_header(cfg, x_field, y_field,
                                             point_name(point or default_point())), resume)
    try:
        return _run_map(cfg, x_field, x_values, y_field, y_values, point, n_jobs, backend,
                        client, outdir, resume, refine_boundary, xtol, progress, store)
    finally:
        if store is not None:
            store.close()


def _run_map(cfg, x_field, x_values, y_field, y_values, point, n_jobs, backend, client,
             outdir, resume, refine_boundary, xtol, progress, store) -> MapResult:
    """The rows, then the boundary (stored in `store`, or None) of :func:`stability_map`."""
    rows, frames = [], []
    row_cfgs = [(k, yv, _si(cfg, y_field, yv), cfg.with_overrides({y_field: yv}))
                for k, yv in enumerate(y_values)]
    outs = ([None] * len(y_values) if outdir is None
            else map_files(outdir, len(y_values))[:len(y_values)])
    if backend == "joblib" and n_jobs != 1 and len(y_values) > 1:
        # rows side by side, each a serial sweep in one worker: every worker busy
        # (a row's warm-start chains would leave one idle), the same points and
        # chains as row by row (tefcore.sweeps.evaluate.WARM_CHAIN): the same table
        results = _in_workers(_row_in_worker, [(cfg_y, x_field, x_values, point, outs[k], resume)
                                               for k, _, _, cfg_y in row_cfgs], n_jobs)
    else:
        results = [sweep(cfg_y, x_field, x_values, point=point, n_jobs=n_jobs, backend=backend,
                         client=client, out=outs[k], resume=resume, refine=False,
                         progress=progress, warn=False)
                   for k, _, _, cfg_y in row_cfgs]
    for (k, yv, y_si, _), res in zip(row_cfgs, results, strict=True):
        rows.append(res)
        frames.append(_row_frame(res, k, y_si, yv))
    table = pd.concat(frames, ignore_index=True)
    # one warning for the map (the rows keep theirs in the 'warning' column)
    warn_clipped(f"map of {x_field} x {y_field}", sum(r.n_clipped for r in rows), len(table),
                 merge_clipped(r.clipped for r in rows), stacklevel=4)
    boundary = pd.DataFrame(columns=["y", "x", "direction", "x_lo", "x_hi", "converged",
                                     "error"])
    if refine_boundary:
        boundary = _boundary(table, cfg, x_field, y_field, y_values, point, n_jobs, backend,
                             client, store, xtol)
    return MapResult(x_field=x_field, y_field=y_field, table=table, boundary=boundary,
                     rows=rows)


def _warn_clipped_crossings(clipped: list, x_field: str, y_field: str) -> None:
    """One warning for all the refinement's evaluations whose C81 inputs were clipped
    (each evaluation warned once before), with the most extreme inputs of all."""
    if (merged := merge_clipped(clipped)) is not None:
        n = sum(c is not None for c in clipped)
        warnings.warn(range_warning(
            f"boundary of the map of {x_field} x {y_field}: C81 table inputs clipped in "
            f"refining {n} of {len(clipped)} crossings; {describe_clipped(merged)}", merged),
            stacklevel=5)


def _boundary(table, cfg, x_field, y_field, y_values, point, n_jobs, backend, client, store,
              xtol):
    """Refined zeros of the flutter growth along each row (kept in `store`, a
    :class:`~tefcore.sweeps.map_store.BoundaryFile`, or None)."""
    point = default_point() if point is None else point
    xs_all = table["x"].to_numpy(float)
    xtol = float(1e-4 * (np.nanmax(xs_all) - np.nanmin(xs_all) or 1.0) if xtol is None
                 else xtol)
    jobs = []
    for k, g in table.groupby("y_index", sort=True):
        g = g.sort_values("x")
        x, y = g["x"].to_numpy(float), g["flutter_growth"].to_numpy(float)
        for i in range(len(x) - 1):
            if np.isfinite(y[i]) and np.isfinite(y[i + 1]) and (y[i] < 0) != (y[i + 1] < 0):
                direction = "destabilising" if y[i + 1] >= 0 else "stabilising"
                jobs.append((k, float(x[i]), float(x[i + 1]), direction, float(g["y"].iloc[0])))
    cache = {} if store is None else store.records
    todo = []
    results = []
    for k, a, b, direction, y_si in jobs:
        key = crossing_key(y_si, a, b, xtol)
        if key in cache:
            results.append(cache[key])
        else:
            todo.append((key, k, a, b, direction, y_si))
    if todo:
        cfgs = {k: cfg.with_overrides({y_field: y_values[k]}) for _, k, *_ in todo}
        args = [(point, cfgs[k], x_field, y_si, a, b, d, xtol) for _, k, a, b, d, y_si in todo]
        if backend == "dask" and client is not None:
            futures = [client.submit(_refine_in_worker, *a, pure=False) for a in args]
            found = client.gather(futures)
        elif n_jobs != 1 and len(args) > 1:
            found = _in_workers(_refine_in_worker, args, n_jobs)
        else:
            found = [_refine(*a) for a in args]
        clipped = [rec.pop("clipped", None) for rec in found]
        for (key, *_), rec in zip(todo, found, strict=True):
            rec = {"key": key, **rec}
            results.append(rec)
            if store is not None:
                store.append(rec)
        _warn_clipped_crossings(clipped, x_field, y_field)
    cols = ["y", "x", "direction", "x_lo", "x_hi", "converged", "error"]
    out = pd.DataFrame(results, columns=["key", *cols]).drop(columns="key")
    return out.sort_values(["y", "x"], ignore_index=True)
