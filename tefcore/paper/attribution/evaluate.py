"""A claim's own check on a changed configuration, computing only the points that decide it.

The attribution (:mod:`tefcore.paper.attribution.differences`) asks one question many
times: does this claim pass with that assumption moved?  :func:`check_claims`
answers it with :func:`tefcore.paper.claims.checks.validate_figure` -- the
check the notebooks ran -- on results computed at the fewest points that
decide the claims (:func:`claim_values`): a value or mechanism claim at its
x (and its reference x), a claim over an interval at the sweep values in
it, a comparison on both of its curves, everything else on the whole sweep.
Sweeps are cached by figure and configuration hash (:class:`FigureCache`):
the points of one figure at one configuration are computed once, whichever
claim asks, and a claim that needs more points adds only those.

:class:`RunSettings` is how the notebooks ran: their base configuration and
section aerodynamics, their overrides and sweep values.

Examples
--------
>>> from tefcore.paper.claims.reference import load_claims
>>> c = next(c for c in load_claims() if c.id == "fig17-tef-weakly-unstable-hover")
>>> claim_values(c, [0.0, 0.05, 0.1, 0.3])
[0.0]
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ...config.configuration import Config
from ...units import parse_quantity
from ..claims.checks import validate_figure
from ..claims.curves import X_SLACK
from ..claims.validation import figure_values, not_computable_rows
from ..figures.catalogue import FIGURES, variant_key
from ..figures.frames import FIG7_OVERHANGS
from ..figures.quantities import swept_dimension, x_to_si
from ..figures.responses import flap_response_figure, hinge_moment_figure
from ..figures.runs import base_config, quiet_stability, run_config

__all__ = ["FigureCache", "RunSettings", "check_claims", "checked_claims", "claim_needs",
           "claim_values"]


@dataclass(frozen=True)
class RunSettings:
    """How the notebooks computed the figures: configuration, overrides, sweep values.

    Parameters
    ----------
    base : tefcore.config.configuration.Config
        Base configuration with the notebooks' section aerodynamics
        (:func:`tefcore.paper.figures.runs.base_config`); a lever moves it.
    overrides : dict
        Dotted fields that win over each figure's caption (notebook parameter
        ``overrides``).
    n_points : int or None
        Points per stability figure (None: the paper's values and the
        claims' x, :func:`tefcore.paper.claims.validation.figure_values`).
    values : dict
        Explicit sweep values per figure.
    fig7_overhangs : tuple
        Overhangs of Fig. 7.
    point : callable
        Point function of the sweeps (default the notebooks':
        :func:`tefcore.paper.figures.runs.quiet_stability`).
    refine : bool
        Refine the sweeps where a mode's identity between two points is in
        doubt, as the notebooks do (:func:`tefcore.sweeps.sweep.sweep`); the
        attribution searches without (about five times cheaper) and confirms
        each flip with it.
    """

    base: Config
    overrides: dict = field(default_factory=dict)
    n_points: int | None = None
    values: dict = field(default_factory=dict)
    fig7_overhangs: tuple = tuple(FIG7_OVERHANGS)
    point: object = quiet_stability
    refine: bool = False

    @classmethod
    def from_params(cls, params: dict | None = None) -> RunSettings:
        """The settings of a notebook run from its papermill parameters.

        Parameters
        ----------
        params : dict, optional
            ``aero_model``, ``config``, ``overrides``, ``n_points``, ``values``,
            ``fig7_overhangs`` (others are ignored); missing ones take the
            notebooks' defaults.

        Returns
        -------
        RunSettings
        """
        p = params or {}
        return cls(base_config(p.get("aero_model") or "thin_airfoil", config=p.get("config")),
                   dict(p.get("overrides") or {}), p.get("n_points"), dict(p.get("values") or {}),
                   tuple(p.get("fig7_overhangs") or FIG7_OVERHANGS))

    def sweep_values(self, figure: str) -> list:
        """The values a notebook sweeps `figure` over (the overhangs of Fig. 7).

        Parameters
        ----------
        figure : str
            A stability figure or ``"fig7"``.
        """
        if figure == "fig7":
            return list(self.fig7_overhangs)
        return figure_values(figure, self.n_points, self.values.get(figure))


def _si(figure: str, v) -> float:
    if isinstance(v, str):
        return parse_quantity(v, swept_dimension(figure))
    return float(v)


def _near(a: float, b: float) -> bool:
    return abs(a - b) <= X_SLACK * max(abs(a), abs(b), 1e-300)


def _at(figure, values, si, xs) -> list:
    """The values at each x of `xs`, or the two that bracket it."""
    keep = set()
    for x in xs:
        hit = [i for i, v in enumerate(si) if _near(v, x)]
        if hit:
            keep.add(hit[0])
            continue
        below = [i for i, v in enumerate(si) if v < x]
        above = [i for i, v in enumerate(si) if v > x]
        keep |= {max(below, key=si.__getitem__)} if below else set()
        keep |= {min(above, key=si.__getitem__)} if above else set()
    return [values[i] for i in sorted(keep, key=si.__getitem__)]


def claim_values(claim, values, interval="own") -> list:
    """The sweep values of `values` that decide `claim` on its own figure.

    Parameters
    ----------
    claim : tefcore.paper.claims.reference.Claim
        A claim about a stability figure or Fig. 7.
    values : sequence
        The figure's sweep values (numbers or ``"value unit"`` strings).
    interval : "own", tuple or None
        The x interval of the curve (in the claim's ``x_unit``): ``"own"``
        the claim's ``interval``; a comparison's other curve passes its own.

    Returns
    -------
    list
        A value or mechanism claim: the values at its x (and ``relative_to``),
        or the two bracketing one that is not swept; a claim over an interval:
        the values in it; otherwise all of them.
    """
    fig, values = claim.figure, list(values)
    si = [_si(fig, v) for v in values] if fig in FIGURES else [float(v) for v in values]
    if claim.kind in ("value", "mechanism") and claim.x is not None:
        xs = [float(x_to_si(fig, v, claim.x_unit)) for v in (claim.x, claim.relative_to)
              if v is not None]
        return _at(fig, values, si, xs)
    span = claim.interval if interval == "own" else interval
    if claim.kind in ("threshold", "trend", "comparison") and span is not None:
        lo, hi = (float(x_to_si(fig, v, claim.x_unit)) for v in span)
        slack = X_SLACK * max(abs(lo), abs(hi), 1e-300)
        return [v for v, s in zip(values, si, strict=True) if lo - slack <= s <= hi + slack]
    return values


def claim_needs(claim, settings: RunSettings) -> list[tuple[str, dict, list]]:
    """The results a claim's check reads: ``(figure, overrides, values)`` each.

    Parameters
    ----------
    claim : tefcore.paper.claims.reference.Claim
        The claim.
    settings : RunSettings
        The run's sweep values.

    Returns
    -------
    list of tuple
        Its own curve, and a comparison's other curve (another figure, or a
        variant with overrides); Figs. 5 and 6 with no values.
    """
    def curve(fig, overrides, span):
        if fig in ("fig5", "fig6"):
            return fig, dict(overrides), []
        c = claim if fig == claim.figure else _other_view(claim, fig)
        return fig, dict(overrides), claim_values(c, settings.sweep_values(fig), span)

    out = [curve(claim.figure, claim.overrides, "own")]
    if claim.kind == "comparison":
        out.append(curve(claim.other_figure or claim.figure, claim.other_overrides,
                         claim.other_interval))
    return out


def _other_view(claim, fig):
    """The claim as seen from another figure (only its kind and x unit matter)."""
    from dataclasses import replace

    return replace(claim, figure=fig)


class FigureCache:
    """Figure results by (figure, configuration hash): each point computed once.

    Stability figures are sweeps written to ``folder/<figure>-<hash>.jsonl``
    (:func:`tefcore.sweeps.sweep.sweep` with ``out``): a later sweep of the
    same configuration at other values loads the points already there and
    computes the rest.  Figs. 5-7 are kept in memory, Fig. 7 by overhang.

    A sweep file another tefcore wrote (another version or model code: its
    header's ``tefcore_version`` and ``model_stamp``) is not resumed -- the
    sweep would refuse it as stale, and every figure read from the cache
    would be "not computable" -- but removed and computed again: the files
    are this cache's own, derived data (a study or notebook 12's small study
    resumed over an older solver's Fig. 8 would count Fig. 8 not computable
    in every trial).

    Parameters
    ----------
    folder : path
        An existing folder of this cache's sweep files (one process only).
    """

    def __init__(self, folder):
        self.folder = Path(folder)
        self.memory: dict = {}
        self.checked: set = set()       # sweep files whose header was read

    def _drop_stale(self, path: Path) -> None:
        """Remove `path` if another tefcore version or model code wrote it (once per file)."""
        if path in self.checked:
            return
        self.checked.add(path)
        import json

        from ..._version import __version__
        from ...provenance import model_stamp

        try:
            with open(path, "rb") as f:
                head = json.loads(f.readline())
        except (OSError, ValueError):
            return                      # absent, or damaged: the sweep says which
        if not isinstance(head, dict):
            return
        if (head.get("model_stamp"), head.get("tefcore_version")) != (model_stamp(),
                                                                      __version__):
            path.unlink(missing_ok=True)

    def result(self, figure: str, cfg, settings: RunSettings, overrides: dict, values):
        """The result of `figure` for the base `cfg`, with a variant's `overrides`.

        Parameters
        ----------
        figure : str
            ``"fig5"``, ``"fig6"``, ``"fig7"`` or a stability figure.
        cfg : tefcore.config.configuration.Config
            The base configuration (a lever moved); the caption and
            ``settings.overrides`` are applied over it, then `overrides`.
        settings : RunSettings
            The run.
        overrides : dict
            A variant's dotted fields (empty: the figure as captioned).
        values : sequence
            Sweep values (overhangs for Fig. 7); ignored for Figs. 5-6.

        Returns
        -------
        SweepResult, DataFrame or dict
            As :func:`tefcore.paper.figures.frames.compute_figure` returns it.
        """
        from ...sweeps.store import config_hash

        over = {**settings.overrides, **overrides}
        if figure in ("fig5", "fig6", "fig7"):
            return self._response(figure, cfg, over, values, config_hash(cfg))
        fig_cfg = run_config(figure, cfg, settings.overrides).with_overrides(overrides)
        parameter = FIGURES[figure].parameter
        chash = config_hash(fig_cfg, exclude=[parameter])
        key = (figure, chash, tuple(map(str, values)), settings.refine)
        if key not in self.memory:
            from ...sweeps.sweep import sweep

            out = self.folder / f"{figure}-{chash}.jsonl"
            self._drop_stale(out)
            self.memory[key] = sweep(fig_cfg, parameter, list(values), point=settings.point,
                                     out=out, progress=False, warn=False,
                                     refine=settings.refine)
        return self.memory[key]

    def _response(self, figure, cfg, over, values, chash):
        key = (figure, chash, variant_key(over))
        if figure == "fig5":
            if key not in self.memory:
                self.memory[key] = hinge_moment_figure(cfg, **over)
            return self.memory[key]
        if figure == "fig6":
            if key not in self.memory:
                self.memory[key] = flap_response_figure(cfg, **over)
            return self.memory[key]
        rows = []
        for ov in values:
            k = key + (float(ov),)
            if k not in self.memory:
                r = flap_response_figure(cfg, **{**over, "flap.overhang": float(ov)})
                self.memory[k] = {"overhang": ov, "half_peak_to_peak_deg":
                                  r["half_peak_to_peak_deg"], "peak_power": r["peak_power"],
                                  "mean_power": r["mean_power"]}
            rows.append(self.memory[k])
        return pd.DataFrame(rows)


def _union(needs) -> dict:
    """``(figure, variant key) -> (overrides, values)``: the values of all claims together."""
    out: dict = {}
    for fig, over, values in needs:
        key = (fig, variant_key(over))
        have = out.setdefault(key, (over, []))[1]
        have += [v for v in values if str(v) not in map(str, have)]
    return out


def check_claims(claims, cfg, settings: RunSettings, cache: FigureCache) -> pd.DataFrame:
    """The claims' own checks with the base configuration `cfg`, on the points that decide them.

    Parameters
    ----------
    claims : sequence of tefcore.paper.claims.reference.Claim
        Claims (any figures); each is checked by
        :func:`tefcore.paper.claims.checks.validate_figure` with its figure's
        results.
    cfg : tefcore.config.configuration.Config
        The base configuration (a lever moved).
    settings : RunSettings
        The run: overrides and sweep values.
    cache : FigureCache
        Where results are kept between calls.

    Returns
    -------
    pandas.DataFrame
        One row per claim (:data:`tefcore.paper.claims.checks.COLUMNS`), in order.

    Raises
    ------
    ValueError
        `cfg` with the figure's parameters is not admitted.
    """
    needed = _union(n for c in claims for n in claim_needs(c, settings))
    results = {key: cache.result(key[0], cfg, settings, over, values)
               for key, (over, values) in needed.items()}
    claims_cfg = cfg.with_overrides(settings.overrides) if settings.overrides else cfg
    return checked_claims(claims, claims_cfg, results)


def checked_claims(claims, cfg, results: dict, broken: dict | None = None) -> pd.DataFrame:
    """Each claim checked on its figures' computed results, in the claims' order.

    Parameters
    ----------
    claims : sequence of tefcore.paper.claims.reference.Claim
        Claims (any figures).
    cfg : tefcore.config.configuration.Config
        The configuration the claims are checked with.
    results : dict
        ``(figure, variant key) -> result`` (``""``: the figure itself), as
        :meth:`FigureCache.result` gives them.
    broken : dict, optional
        Figure -> why it could not be computed: its claims, and those that
        read it, get the status ``not computable`` with that reason.

    Returns
    -------
    pandas.DataFrame
        One row per claim (:data:`tefcore.paper.claims.checks.COLUMNS`).
    """
    broken = broken or {}
    tables = []
    for fig in dict.fromkeys(c.figure for c in claims):
        mine = [c for c in claims if c.figure == fig]
        # a claim reads its own figure and, for a comparison, another one
        dead = {f for c in mine for f in (c.figure, c.other_figure) if f in broken}
        if dead:
            tables.append(not_computable_rows(mine, "; ".join(broken[f] for f in sorted(dead))))
            continue
        tables.append(validate_figure(
            fig, results.get((fig, "")), mine, cfg=cfg, compute_missing=False,
            variants={k: r for (f, k), r in results.items() if f == fig and k},
            others={f: r for (f, k), r in results.items() if not k}))
    order = {c.id: i for i, c in enumerate(claims)}
    table = pd.concat(tables, ignore_index=True)
    return table.sort_values("id", key=lambda s: s.map(order), ignore_index=True)
