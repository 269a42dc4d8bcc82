"""Reference data of the paper: claims, digitised curves and their checking.

The paper's figures are not available, so the reference is what its Results
text states (``reference_data/claims.toml``) plus curves a user digitises with
WebPlotDigitizer (``reference_data/curves/*.toml`` sidecars beside the CSV
exports).  The format is specified in ``reference_data/README.md``; this
module loads it into :class:`Claim` records, checking every field and raising
:class:`ReferenceDataError` naming the file and the record (or CSV row).
:mod:`tefcore.paper.claims.validation` compares the claims with model results.

Examples
--------
>>> claims = load_claims()
>>> c = next(c for c in claims if c.id == "fig9b-tef-unstable-after-0.26")
>>> c.kind, c.mode, c.expected, c.direction
('threshold', 'TEF', 0.26, 'destabilising')
>>> sorted({c.tag for c in claims})
['calibration', 'validation']
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from stat import S_ISREG

import pandas as pd

from ...config.configuration import resolve_field
from ..figures.catalogue import FIGURES, KNOWN_FIGURES, figure_config
from ..figures.quantities import QUANTITIES, x_to_si, y_to_canonical
from .files import ReferenceDataError, read_toml, read_wpd_csv, reference_dir

__all__ = ["KINDS", "ROOT_KINDS", "STATUSES", "Claim", "load_claims", "parse_claim"]

KINDS = ("value", "threshold", "range", "trend", "comparison", "mechanism", "curve",
         "not_reproducible")
TAGS = ("calibration", "validation")
#: best first; a status later in the tuple is "worse".  ``ambiguous``: an
#: exceptional point of the claim's mode (two roots coalescing in the plane of
#: the swept parameter and the blade-flap coupling) lies inside the claim's
#: range, where which root carries the name has no answer; ``not computable``: the
#: figure the claim reads could not be computed for this rotor (a trim that does not
#: converge, a configuration refused at the figure's parameters)
#: (:data:`tefcore.paper.run.report.STATUS_MEANINGS` words each status)
STATUSES = ("pass", "ambiguous", "not reproducible", "not computable", "fail")
#: kinds of root a mechanism claim can expect (:func:`tefcore.linear.mechanism.mechanism`)
ROOT_KINDS = ("flutter", "divergence")
_ID = re.compile(r"^[a-z0-9][a-z0-9._:-]*$")
_COMMON = {"id", "figure", "panel", "statement", "condition", "kind", "tag", "recorded_status",
           "notes"}
_CHECKED = {"mode", "quantity", "x_unit", "overrides", "tolerance", "tolerance_reason"}
_FIELDS = {  # kind -> allowed fields besides _COMMON
    "value": _CHECKED | {"x", "relative_to", "expected", "lower", "upper", "tolerance_type"},
    "threshold": _CHECKED | {"interval", "expected", "direction"},
    "range": _CHECKED | {"state", "expected_interval"},
    "trend": _CHECKED | {"interval", "direction", "method", "tolerance_type", "reference_mode"},
    "comparison": _CHECKED | {"interval", "statistic", "relation", "other_figure", "other_mode",
                              "other_quantity", "other_interval", "other_overrides"},
    "mechanism": _CHECKED | {"x", "root_kind", "driving_terms", "min_participation",
                             "knockout_terms", "rival_terms"},
    "curve": _CHECKED,
    "not_reproducible": {"mode", "quantity", "reason"},
}
_RELATIONS = {"slope": ("less", "greater"), "abs_slope": ("less", "greater"),
              "peak_to_peak": ("less", "greater"), "correlation": ("positive", "negative")}


@dataclass(frozen=True)
class Claim:
    """One checkable statement of the paper (fields: ``reference_data/README.md``).

    Made by :func:`parse_claim` (which checks every field for its kind) from a
    ``[[claim]]`` of ``claims.toml`` or a dataset of a digitised-curve
    sidecar; checked by :func:`tefcore.paper.claims.checks.validate_figure`.
    x values are in ``x_unit`` as written; expected values of a quantity are
    in its canonical unit (:data:`QUANTITIES`).  Fields that do not apply to
    a claim's kind keep their empty defaults.

    Parameters
    ----------
    id : str
        Unique identifier, ``[a-z0-9][a-z0-9._:-]*``
        (``"fig9b-tef-unstable-after-0.26"``).
    figure : str
        The analysis it is about: a stability figure (``"fig3"`` ...
        ``"fig17"``, ``"fig16a"``/``"fig16b"``) or ``"fig5"``-``"fig7"``.
    kind : str
        One of :data:`KINDS`: how the statement is checked.
    tag : str
        ``"validation"`` (never used to set a property; counted in the score)
        or ``"calibration"`` (used to set an assumed property: the four stated
        torsion frequencies).
    statement : str
        The paper's sentence(s), quoted exactly.
    source : str
        Where the claim was read (file, record or dataset, id), for messages.
    panel : str
        ``"a"``, ``"b"`` or ``""``: the figure's panel.
    condition : str
        The flight condition and fixed parameters of the caption.
    recorded_status : str
        The status tefcore had when last recorded (one of :data:`STATUSES` or
        ``""``); a later run worse than it is a regression.
    notes : str
        Interpretation choices (e.g. which root "the TEF mode" is).
    mode : str
        Tracked mode of a stability figure (``"TEF"``, ``"blade torsion 1"``,
        ``"flutter root"``); ``""`` for Figs. 5-7.
    quantity : str
        A key of :data:`QUANTITIES`: ``real_part`` [1/rev, eigenvalue over
        Omega, > 0 unstable], ``damping``, ``frequency_per_rev``,
        ``hinge_moment`` [N m], ``peak_power`` [W], ...
    x_unit : str
        Unit of the claim's x values (``"lb/in"``, ``"deg"``, ``"percent"``);
        ``""``: the SI unit or fraction of the swept field.
    overrides : dict
        Dotted configuration fields of a variant of the figure the claim is
        about (Fig. 12a's balanced flap: ``{"flap.cg_offset": 0.0}``).
    tolerance : float or None
        The allowance: on the value (``value``), on the x of a crossing or
        interval end in ``x_unit`` (``threshold``, ``range``), on the
        peak-to-peak (``constant`` trend), the least ``|r|`` (correlation),
        the least share of the growth rate a knockout removes (mechanism) or
        the y band of a digitised curve.
    tolerance_reason : str
        Why the tolerance is what it is (the precision of the statement,
        never a fit).
    tolerance_type : str
        ``"absolute"``, ``"relative"`` (times the expected value, or the
        mean magnitude for a trend) or ``"relative_to_mode"`` (times the
        peak-to-peak of ``reference_mode``).
    x : float or None
        Where a ``value`` or ``mechanism`` claim is evaluated, in ``x_unit``.
    relative_to : float or None
        The x of the reference value: the claim is then about the relative change
        ``q(x)/q(relative_to) - 1`` (Fig. 7a's "reduced by 60 %").
    expected : float or None
        Expected value (``value``, canonical unit) or crossing x
        (``threshold``, ``x_unit``).
    lower, upper : float or None
        Bounds of a ``value`` claim stated as an inequality.
    interval : tuple of (float, float) or None
        ``(low, high)`` x range, in ``x_unit``, the claim is restricted to.
    expected_interval : tuple of (float, float) or None
        The stated stable or unstable x interval of a ``range`` claim (Fig.
        15: unstable from 0.15 to 0.40 airfoil chord).
    state : str
        ``"unstable"`` (real part >= 0) or ``"stable"``, for a ``range``.
    direction : str
        ``"destabilising"``/``"stabilising"`` with increasing x (threshold),
        or ``"increasing"``/``"decreasing"``/``"constant"`` (trend).
    method : str
        Sign of a trend: ``"slope"`` (least-squares slope of the curve,
        :func:`tefcore.paper.claims.kinds.curve_slope`) or ``"net_change"``
        (last minus first).
    reference_mode : str
        Mode whose peak-to-peak scales a ``relative_to_mode`` tolerance.
    statistic : str
        Of a comparison: ``"slope"``, ``"abs_slope"``, ``"peak_to_peak"`` or
        ``"correlation"``.
    relation : str
        ``"less"``/``"greater"`` (or ``"positive"``/``"negative"`` for a
        correlation): how the claim's curve stands to the other one.
    other_figure, other_mode, other_quantity : str
        The second curve of a comparison (each defaults to the claim's own).
    other_interval : tuple of (float, float) or None
        The x range of the second curve (default: ``interval``).
    other_overrides : dict
        Configuration variant of the second curve (Fig. 12a's balanced
        against imbalanced flap).
    root_kind : str
        Of a mechanism claim: ``"flutter"`` (oscillatory, growing) or
        ``"divergence"`` (real, growing); see :data:`ROOT_KINDS`.
    driving_terms : tuple of str
        Terms of :data:`tefcore.linear.mechanism.TERMS`, one of which must do the
        largest destabilising work on the root.
    min_participation : dict
        Least participation share by kind of coordinate (``"flap"``,
        ``"lag"``, ``"torsion"``, ``"axial"``, ``"TEF"``) in [0, 1]: Fig. 9b's
        "flap-blade torsion flutter" needs both the flap and the torsion.
    knockout_terms : tuple of str
        Terms of which at least one, removed from the equations (a knockout),
        must take away ``tolerance`` or more of the root's growth rate.
    rival_terms : tuple of str
        The terms of a competing path (e.g. the flap's coupling to blade
        bending against its coupling to torsion): the claimed path's best
        knockout must take away more of the growth rate than any of these.
    reason : str
        Why a ``not_reproducible`` claim cannot be checked (e.g. it compares
        with test data tefcore does not have).
    example : bool
        A synthetic demonstration curve, never a claim of the paper; loaded
        only with ``include_examples``.
    points : pandas.DataFrame or None
        Digitised points of a ``curve``: ``x`` (unit of the result table),
        ``y`` (canonical unit of ``quantity``), ``band`` (y half-width) and
        ``x_band`` (x half-width).
    """

    id: str
    figure: str
    kind: str
    tag: str
    statement: str
    source: str
    panel: str = ""
    condition: str = ""
    recorded_status: str = ""
    notes: str = ""
    mode: str = ""
    quantity: str = ""
    x_unit: str = ""
    overrides: dict = field(default_factory=dict)
    tolerance: float | None = None
    tolerance_reason: str = ""
    tolerance_type: str = "absolute"
    x: float | None = None
    relative_to: float | None = None
    expected: float | None = None
    lower: float | None = None
    upper: float | None = None
    interval: tuple | None = None
    expected_interval: tuple | None = None
    state: str = ""
    direction: str = ""
    method: str = "slope"
    reference_mode: str = ""
    statistic: str = ""
    relation: str = ""
    other_figure: str = ""
    other_mode: str = ""
    other_quantity: str = ""
    other_interval: tuple | None = None
    other_overrides: dict = field(default_factory=dict)
    root_kind: str = ""
    driving_terms: tuple = ()
    min_participation: dict = field(default_factory=dict)
    knockout_terms: tuple = ()
    rival_terms: tuple = ()
    reason: str = ""
    example: bool = False
    points: pd.DataFrame | None = field(default=None, repr=False, compare=False)


# ------------------------------------------------------------------ record checks


class _Record:
    """Typed access to one raw TOML table; errors say where."""

    def __init__(self, raw, where: str):
        self.raw, self.where = raw, where
        if not isinstance(raw, dict):
            self.fail("a record must be a TOML table")

    def fail(self, msg: str):
        raise ReferenceDataError(f"{self.where}: {msg}")

    def text(self, key, required=False, choices=None, default=""):
        v = self.raw.get(key, default)
        if not isinstance(v, str):
            self.fail(f"field {key!r} must be a string, got {v!r}")
        if required and not v.strip():
            self.fail(f"missing required field {key!r}")
        if choices is not None and v not in choices:
            self.fail(f"field {key!r} = {v!r} is not one of {list(choices)}")
        return v.strip()

    def number(self, key, required=False):
        if key not in self.raw:
            return self.fail(f"missing required field {key!r}") if required else None
        v = self.raw[key]
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            self.fail(f"field {key!r} must be a finite number, got {v!r}")
        return float(v)

    def pair(self, key, required=False):
        if key not in self.raw:
            return self.fail(f"missing required field {key!r}") if required else None
        v = self.raw[key]
        ok = isinstance(v, list) and len(v) == 2 and all(
            isinstance(a, int | float) and not isinstance(a, bool) and math.isfinite(a) for a in v)
        if not ok or not v[0] < v[1]:
            self.fail(f"field {key!r} must be [low, high] numbers with low < high, got {v!r}")
        return float(v[0]), float(v[1])

    def overrides(self, key):
        v = self.raw.get(key, {})
        if not isinstance(v, dict):
            self.fail(f"field {key!r} must be a table of configuration overrides")
        for k in v:
            try:
                resolve_field(k)
            except ValueError as err:
                self.fail(f"field {key!r}: {err}")
        return dict(v)


def _quantity(r: _Record, key: str, figure: str, default: str = "") -> str:
    q = r.text(key, required=not default, choices=tuple(QUANTITIES), default=default)
    where = QUANTITIES[q][0]
    if not (figure in FIGURES if where == "stability" else figure in where):
        r.fail(f"quantity {q!r} does not exist for {figure}")
    return q


def parse_claim(raw: dict, where: str = "<claim>") -> Claim:
    """Check one raw claim table (as read from TOML) and return the :class:`Claim`.

    Parameters
    ----------
    raw : dict
        The claim's fields (``reference_data/README.md``).
    where : str
        Where it was read, for error messages.

    Raises
    ------
    ReferenceDataError
        Naming the claim and the field.
    """
    r = _Record(raw, where)
    cid = r.text("id", required=True)
    if not _ID.match(cid):
        r.fail(f"id {cid!r} must match {_ID.pattern}")
    r.where = f"{where} (id {cid!r})"
    kind = r.text("kind", required=True, choices=KINDS)
    figure = r.text("figure", required=True, choices=KNOWN_FIGURES)
    unknown = sorted(set(raw) - _COMMON - _FIELDS[kind])
    if unknown:
        r.fail(f"unknown field(s) {unknown} for kind {kind!r}")
    kw = dict(id=cid, figure=figure, kind=kind, tag=r.text("tag", required=True, choices=TAGS),
              statement=r.text("statement", required=True), source=r.where,
              panel=r.text("panel"), condition=r.text("condition", required=True),
              recorded_status=r.text("recorded_status", choices=("",) + STATUSES),
              notes=r.text("notes"))
    if kind == "not_reproducible":
        return Claim(**kw, mode=r.text("mode"), quantity=r.text("quantity"),
                     reason=r.text("reason", required=True))
    if kind == "mechanism":
        return _mechanism_claim(r, kw, figure)
    _curve_fields(r, kw)
    _KIND_FIELDS[kind](r, kw)
    return Claim(**kw)


def _curve_fields(r: _Record, kw: dict) -> None:
    """The fields naming the checked curve: mode, quantity, x unit, overrides, tolerance."""
    kind, figure = kw["kind"], kw["figure"]
    stability = figure in FIGURES
    q = _quantity(r, "quantity", figure, "real_part" if kind in ("threshold", "range") else "")
    if kind in ("threshold", "range") and q != "real_part":
        r.fail(f"a {kind} is a zero crossing of 'real_part', not of {q!r}")
    mode = r.text("mode", required=stability)
    if mode and not stability:
        r.fail(f"{figure} has no modes; leave 'mode' out")
    kw.update(mode=mode, quantity=q, x_unit=r.text("x_unit"), overrides=r.overrides("overrides"),
              interval=r.pair("interval"), tolerance=r.number("tolerance"),
              tolerance_reason=r.text("tolerance_reason"))
    if figure != "fig6":
        try:
            x_to_si(figure, 1.0, kw["x_unit"])
        except ValueError as err:
            r.fail(f"x_unit: {err}")
    if kw["overrides"] and not stability:
        r.fail("overrides are only supported for the stability figures")
    if kw["tolerance"] is not None and (kw["tolerance"] < 0 or not kw["tolerance_reason"]):
        r.fail("a tolerance must be >= 0 and have its 'tolerance_reason'")


def _need_tolerance(r: _Record, kw: dict, need: bool = True) -> None:
    if need and kw["tolerance"] is None:
        r.fail(f"this {kw['kind']} claim needs 'tolerance' and 'tolerance_reason'")


def _value_fields(r: _Record, kw: dict) -> None:
    kw.update({k: r.number(k, required=(k == "x" and kw["figure"] != "fig6"))
               for k in ("x", "relative_to", "expected", "lower", "upper")})
    kw["tolerance_type"] = r.text("tolerance_type", choices=("absolute", "relative"),
                                  default="absolute")
    if kw["expected"] is None and kw["lower"] is None and kw["upper"] is None:
        r.fail("a value claim needs 'expected' (with tolerance) or 'lower'/'upper'")
    _need_tolerance(r, kw, kw["expected"] is not None)


def _threshold_fields(r: _Record, kw: dict) -> None:
    kw.update(expected=r.number("expected"), direction=r.text(
        "direction", required=True, choices=("destabilising", "stabilising")))
    _need_tolerance(r, kw, kw["expected"] is not None)


def _range_fields(r: _Record, kw: dict) -> None:
    kw.update(state=r.text("state", required=True, choices=("unstable", "stable")),
              expected_interval=r.pair("expected_interval", required=True))
    _need_tolerance(r, kw)


def _trend_fields(r: _Record, kw: dict) -> None:
    kw.update(direction=r.text("direction", required=True,
                               choices=("increasing", "decreasing", "constant")),
              method=r.text("method", choices=("slope", "net_change"), default="slope"),
              tolerance_type=r.text("tolerance_type", default="absolute", choices=(
                  "absolute", "relative", "relative_to_mode")),
              reference_mode=r.text("reference_mode"))
    _need_tolerance(r, kw, kw["direction"] == "constant")
    if kw["tolerance_type"] == "relative_to_mode" and not kw["reference_mode"]:
        r.fail("tolerance_type 'relative_to_mode' needs 'reference_mode'")


def _comparison_fields(r: _Record, kw: dict) -> None:
    figure = kw["figure"]
    stat = r.text("statistic", required=True, choices=tuple(_RELATIONS))
    other = r.text("other_figure", choices=("",) + KNOWN_FIGURES) or figure
    kw.update(statistic=stat, relation=r.text("relation", required=True,
                                               choices=_RELATIONS[stat]),
              other_figure=other, other_mode=r.text("other_mode") or kw["mode"],
              other_quantity=_quantity(r, "other_quantity", other, kw["quantity"]),
              other_interval=r.pair("other_interval") or kw["interval"],
              other_overrides=r.overrides("other_overrides"))
    _need_tolerance(r, kw, stat == "correlation")
    if stat == "correlation" and other != figure:
        r.fail("a correlation compares two curves of the same figure")
    keys = ("figure", "mode", "quantity", "interval", "overrides")
    if all(kw[k] == kw[f"other_{k}"] for k in keys):
        r.fail("a comparison needs a second curve that differs (other_figure, other_mode, "
               "other_quantity, other_interval or other_overrides)")


#: kind -> the function reading its own fields (after :func:`_curve_fields`)
_KIND_FIELDS = {"value": _value_fields, "threshold": _threshold_fields,
                "range": _range_fields, "trend": _trend_fields,
                "comparison": _comparison_fields, "curve": lambda r, kw: None}


def _names(r: _Record, key: str, choices) -> tuple:
    v = r.raw.get(key, [])
    if not isinstance(v, list) or not all(isinstance(t, str) for t in v):
        r.fail(f"field {key!r} must be a list of term names")
    bad = [t for t in v if t not in choices]
    if bad:
        r.fail(f"field {key!r}: unknown term(s) {bad}; terms are {list(choices)}")
    return tuple(v)


def _mechanism_claim(r: _Record, kw: dict, figure: str) -> Claim:
    """A claim about why a root is unstable (:func:`tefcore.linear.mechanism.mechanism`)."""
    from ...linear.mechanism import TERMS

    if figure not in FIGURES:
        r.fail("a mechanism claim is about a root of a stability figure")
    kw.update(mode=r.text("mode", required=True), x_unit=r.text("x_unit"),
              overrides=r.overrides("overrides"), x=r.number("x", required=True),
              root_kind=r.text("root_kind", choices=("",) + ROOT_KINDS),
              driving_terms=_names(r, "driving_terms", TERMS),
              knockout_terms=_names(r, "knockout_terms", TERMS),
              rival_terms=_names(r, "rival_terms", TERMS),
              tolerance=r.number("tolerance"), tolerance_reason=r.text("tolerance_reason"))
    share = r.raw.get("min_participation", {})
    kinds = ("flap", "lag", "torsion", "axial", "TEF")
    if not isinstance(share, dict) or any(k not in kinds for k in share) or any(
            isinstance(v, bool) or not isinstance(v, int | float) or not 0 <= v <= 1
            for v in share.values()):
        r.fail(f"field 'min_participation' must map kinds {list(kinds)} to shares in [0, 1]")
    kw["min_participation"] = {k: float(v) for k, v in share.items()}
    try:
        x_to_si(figure, 1.0, kw["x_unit"])
    except ValueError as err:
        r.fail(f"x_unit: {err}")
    if not (kw["root_kind"] or kw["driving_terms"] or kw["min_participation"]
            or kw["knockout_terms"]):
        r.fail("a mechanism claim needs root_kind, driving_terms, min_participation or "
               "knockout_terms")
    if kw["rival_terms"] and not kw["knockout_terms"]:
        r.fail("rival_terms (a competing path) need knockout_terms (the claimed path)")
    if kw["knockout_terms"] and (kw["tolerance"] is None or not kw["tolerance_reason"]):
        r.fail("knockout_terms need 'tolerance' (the least share of the growth rate a "
               "knockout removes) and 'tolerance_reason'")
    return Claim(**kw)


# ------------------------------------------------------------------ WebPlotDigitizer


_SIDECAR = {"id", "figure", "panel", "statement", "condition", "tag", "x_unit", "file",
            "example", "source", "dataset", "notes"}
_DATASET = {"name", "id", "file", "mode", "quantity", "y_unit", "uncertainty",
            "x_uncertainty", "uncertainty_reason", "recorded_status"}


def _load_sidecar(path: Path) -> list[Claim]:
    side = _Record(read_toml(path), str(path))
    data = side.raw
    if sorted(set(data) - _SIDECAR):
        side.fail(f"unknown field(s) {sorted(set(data) - _SIDECAR)}")
    if not isinstance(data.get("example", False), bool):
        side.fail("'example' must be true or false")
    if not isinstance(data.get("dataset"), list) or not data["dataset"]:
        side.fail("needs at least one [[dataset]] table")
    shared = read_wpd_csv(path.parent / side.text("file")) if "file" in data else None
    base = {k: data[k] for k in ("figure", "panel", "statement", "condition", "tag", "x_unit",
                                 "notes") if k in data}
    claims = []
    for i, ds in enumerate(data["dataset"], start=1):
        r = _Record(ds, f"{path}: dataset {i}")
        if sorted(set(ds) - _DATASET):
            r.fail(f"unknown field(s) {sorted(set(ds) - _DATASET)}")
        name = r.text("name", required=True)
        if "file" in ds:
            pts = next(iter(read_wpd_csv(path.parent / r.text("file")).values()))
        elif shared is None:
            r.fail("no CSV: give 'file' in the sidecar (export all) or in the dataset")
        elif name not in shared:
            r.fail(f"dataset {name!r} not in {data['file']} (it has {sorted(shared)})")
        else:
            pts = shared[name]
        slug = re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")
        claim = parse_claim({**base, "kind": "curve", "id": ds.get("id") or
                             f"{side.text('id', required=True)}-{slug}",
                             **{k: ds[k] for k in ("mode", "quantity", "recorded_status")
                                if k in ds}}, r.where)
        dy, dx = r.number("uncertainty", required=True), r.number("x_uncertainty") or 0.0
        if dy < 0 or dx < 0 or not r.text("uncertainty_reason", required=True):
            r.fail("uncertainties must be >= 0, with their 'uncertainty_reason'")
        omega = (figure_config(claim.figure).rotor.rotor_speed if claim.figure in FIGURES
                 else None)
        try:
            unit = r.text("y_unit", default=QUANTITIES[claim.quantity][1])
            y = y_to_canonical(claim.quantity, pts["y"], unit, omega)
            band = float(y_to_canonical(claim.quantity, dy, unit, omega))
            fx = float(x_to_si(claim.figure, 1.0, claim.x_unit))
        except ValueError as err:
            r.fail(str(err))
        points = pd.DataFrame({"x": pts["x"] * fx, "y": y, "band": band, "x_band": dx * fx})
        claims.append(replace(claim, example=data.get("example", False), tolerance=band,
                              tolerance_reason=ds["uncertainty_reason"],
                              points=points.sort_values("x", ignore_index=True)))
    return claims


def load_claims(root=None, include_examples: bool = False) -> list[Claim]:
    """Load and check ``claims.toml`` and the curve sidecars ``curves/*.toml``.

    Parameters
    ----------
    root : path, optional
        Reference data folder (default :func:`reference_dir`).
    include_examples : bool
        Also return the curves of sidecars with ``example = true``
        (synthetic demonstration data, never a claim of the paper).

    Raises
    ------
    ReferenceDataError
        A malformed file, record or CSV row (named), or a duplicate id.
    """
    root = Path(root) if root is not None else reference_dir()
    files = sorted(root.glob("*.toml")) + sorted((root / "curves").glob("*.toml"))
    if not files:
        raise ReferenceDataError(f"{root}: no reference data (claims.toml) found")
    # read once while no file of the folder changes (size or modification
    # time): the figures, the claim checks and the attribution ask for the
    # claims many times (40 times in one lever of the attribution, 35 ms
    # each, measured).  A Claim is frozen, and nothing changes its dicts or
    # points (they are shared).  Not seen: a CSV a sidecar names outside
    # the folder, and the packaged MDART rotor speed a curve in Hz or rad/s
    # is converted with -- both read again in a new process
    key = (str(root.resolve()), include_examples)
    signature = _signature(root)
    held = _LOADED.get(key)
    if held is not None and held[0] == signature:
        return list(held[1])
    claims = _read_claims(files, include_examples)
    _LOADED[key] = (signature, tuple(claims))
    return claims


#: Claims read so far: (folder, include_examples) -> (its files' signature, claims).
_LOADED: dict = {}


def _signature(root: Path) -> tuple:
    """Every file under `root` with its size and modification time."""
    out = []
    for p in sorted(root.rglob("*")):
        try:
            st = p.stat()
        except OSError:         # a dangling link, a file removed meanwhile: not data
            continue
        if S_ISREG(st.st_mode):
            out.append((str(p), st.st_size, st.st_mtime_ns))
    return tuple(out)


def _read_claims(files, include_examples: bool) -> list[Claim]:
    claims, seen = [], {}
    for path in files:
        if path.parent.name == "curves":
            loaded = _load_sidecar(path)
        else:
            data = read_toml(path)
            if set(data) - {"claim", "format"} or not isinstance(data.get("claim", []), list):
                raise ReferenceDataError(f"{path}: expected only [[claim]] tables and 'format'")
            loaded = [parse_claim(raw, f"{path}: record {i}")
                      for i, raw in enumerate(data.get("claim", []), start=1)]
        for c in loaded:
            if c.id in seen:
                raise ReferenceDataError(f"{c.source}: duplicate id {c.id!r} (first in "
                                         f"{seen[c.id]})")
            seen[c.id] = c.source
            if include_examples or not c.example:
                claims.append(c)
    return claims
