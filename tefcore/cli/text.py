"""What the ``tefcore`` command prints: tables and summaries that fit :data:`WIDTH` columns.

:mod:`tefcore.cli` computes; this module words the results for a terminal:

* the modes table of ``tefcore stability`` (:func:`modes_text`): one row
  per root -- its name, frequency, real part and damping ratio, the
  coordinate it carries most, and a note that marks the unstable roots and
  the flutter root -- with a one-line legend (:data:`LEGEND`) and a
  sentence naming the flutter root (:func:`flutter_text`);
* the trim and other long ``name=value`` lists, wrapped (:func:`wrap`);
* the root ``tefcore mechanism`` decomposes when no ``--mode`` is given
  (:func:`mechanism_choice`);
* after ``tefcore sweep``, one summary per role -- the TEF mode and the
  flutter root: where it becomes unstable, its largest growth, the
  exceptional points of its names (:func:`sweep_summary`).

The flutter root of a point is its least stable flap-induced root
(docs/theory.md 9.2); the command calls it so only when it is unstable:
a real part above zero and not ``neutral`` (within the solver's error
estimate, where its sign means nothing).

Examples
--------
>>> import pandas as pd
>>> t = pd.DataFrame({"label": ["blade lag 1", "TEF", "blade flap 5"],
...                   "dominant": ["blade lag 1", "TEF", "blade flap 4"],
...                   "frequency_per_rev": [0.59, 6.42, 9.79],
...                   "real_part": [-0.0116, -4.74, 2.98],
...                   "damping_ratio": [0.0196, 0.594, -0.291],
...                   "neutral": [False, False, False],
...                   "flutter_root": [False, False, True]})
>>> print(modes_text(t))
root          freq /rev  real /rev  damping ratio  carries most  note
blade lag 1      0.5900    -0.0116         0.0196
TEF              6.4200    -4.7400         0.5940
blade flap 5     9.7900    +2.9800        -0.2910  blade flap 4  FLUTTER ROOT
>>> flutter_text(t)
'flutter root: blade flap 5 at +2.980 /rev (continues from blade flap 5), frequency 9.790 /rev'
"""

from __future__ import annotations

import re
import textwrap
from typing import TYPE_CHECKING

import numpy as np

from ..config.text_input import field_param
from ..modes.names import base_name, is_locked, pair_labels
from ..units import from_si

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["LEGEND", "LOCKED_LEGEND", "UNCERTAIN", "UNCERTAIN_LEGEND", "WIDTH", "flutter_row",
           "flutter_text", "legend", "mechanism_choice", "modes_text", "onset", "real_part_text",
           "sweep_summary", "timing_lines", "trim_lines", "unstable", "wrap"]

#: Widest line the command prints, in characters.
WIDTH = 100

#: What the notes of ``tefcore stability``'s table mean (one line).
LEGEND = ("UNSTABLE: real part > 0 (not 'neutral'); FLUTTER ROOT: the least stable "
          "flap-induced root, unstable")

#: The legend line of a locked pair, printed when a root is named ``X (locked)``.
LOCKED_LEGEND = ("X (locked): the more damped root of X's pair at a Floquet lock "
                 "(frequency a multiple of 1/2 /rev)")

#: The note of a root whose name is not certain (``identity_certain`` False): a step
#: of its path from zero coupling no halving decided, or the name its path brought
#: was another root's.
UNCERTAIN = "name uncertain"

#: The legend line of :data:`UNCERTAIN`, printed when a root has it.
UNCERTAIN_LEGEND = ("name uncertain: a step of its path from zero coupling was not "
                    "decided (theory 9.1)")


def wrap(text: str, indent: str = "  ") -> str:
    """`text` filled to :data:`WIDTH` columns, continuation lines indented.

    Parameters
    ----------
    text : str
        One paragraph; words are never broken, its leading spaces kept.
    indent : str, optional
        Prefix of the continuation lines (after the leading spaces).

    Returns
    -------
    str

    Examples
    --------
    >>> print(wrap("trim: " + ", ".join(f"x{i}=1.234" for i in range(12))))
    trim: x0=1.234, x1=1.234, x2=1.234, x3=1.234, x4=1.234, x5=1.234, x6=1.234, x7=1.234, x8=1.234,
      x9=1.234, x10=1.234, x11=1.234
    """
    lead = text[:len(text) - len(text.lstrip())]
    return textwrap.fill(" ".join(text.split()), WIDTH, initial_indent=lead,
                         subsequent_indent=lead + indent, break_long_words=False,
                         break_on_hyphens=False)


def real_part_text(value: float, neutral: bool) -> str:
    """A real part as printed: ``neutral`` below the solver's resolution, else signed.

    Parameters
    ----------
    value : float
        The real part [1/rev].
    neutral : bool
        Whether ``|value|`` is within its error estimate (its sign means nothing).

    Returns
    -------
    str
        ``"neutral"``, 4 decimals with their sign, or a signed exponent for a
        resolved value too small for 4 decimals (never ``-0.0000``).

    Examples
    --------
    >>> real_part_text(2.98051, False), real_part_text(-3.09e-5, False), real_part_text(1e-9, True)
    ('+2.9805', '-3.09e-05', 'neutral')
    """
    if neutral:
        return "neutral"
    return f"{value:+.4f}" if abs(value) >= 5e-5 else f"{value:+.2e}"


def _n_rows(table) -> int:
    """Rows of a DataFrame or of a mapping of columns (name -> one value per row)."""
    return len(table) if hasattr(table, "columns") else len(next(iter(table.values()), ()))


def _flags(table, name: str, missing: bool) -> np.ndarray:
    """A column of truth values, missing ones (NaN, None, NA) and a missing column as `missing`."""
    if name not in table:
        return np.full(_n_rows(table), missing)
    out = []
    for v in np.asarray(table[name], dtype=object):
        try:
            out.append(missing if v is None or (isinstance(v, float) and v != v) else bool(v))
        except TypeError:                     # pandas' NA
            out.append(missing)
    return np.array(out, bool)


def unstable(table) -> np.ndarray:
    """Which rows of a modes (or sweep) table are unstable: real part > 0 and not neutral.

    Parameters
    ----------
    table : pandas.DataFrame or mapping
        With ``real_part`` and, when known, ``neutral``: a table or its
        columns (name -> values, as
        :attr:`tefcore.linear.stability.StabilityResult.columns`).

    Returns
    -------
    numpy.ndarray of bool
    """
    real = np.asarray(table["real_part"], float)
    with np.errstate(invalid="ignore"):
        return (real > 0) & ~_flags(table, "neutral", False)


def _flutter_position(table):
    """Position of the point's flutter root when it is unstable, else None."""
    if "flutter_root" not in table:
        return None
    mask = _flags(table, "flutter_root", False) & unstable(table)
    return int(np.flatnonzero(mask)[0]) if mask.any() else None


def flutter_row(table):
    """Index label of the point's flutter root when it is unstable, else None.

    Parameters
    ----------
    table : pandas.DataFrame or mapping
        A modes table with ``flutter_root`` (:func:`tefcore.modes.roles.name_roots`),
        or its columns (then the row's position is returned).

    Returns
    -------
    object or None
    """
    pos = _flutter_position(table)
    if pos is None or not hasattr(table, "index"):
        return pos
    return table.index[pos]


def _notes(table) -> list[str]:
    row = _flutter_position(table)
    bad = unstable(table)
    certain = _flags(table, "identity_certain", True)
    out = []
    for i in range(_n_rows(table)):
        marks = ["FLUTTER ROOT" if i == row else "UNSTABLE" if bad[i] else ""]
        marks += [] if certain[i] else [UNCERTAIN]
        out.append(", ".join(m for m in marks if m))
    return out


def _layout(columns: list[tuple[str, list[str], str]]) -> list[str]:
    """Lines of a table: ``(header, cells, align)`` columns, two spaces apart."""
    widths = [max([len(h), *map(len, cells)]) for h, cells, _ in columns]
    rows = zip(*([h, *cells] for h, cells, _ in columns), strict=True)
    return ["  ".join(c.ljust(w) if a == "<" else c.rjust(w)
                      for c, w, (_, _, a) in zip(row, widths, columns, strict=True)).rstrip()
            for row in rows]


def modes_text(table) -> str:
    """The modes table as ``tefcore stability`` prints it, at most :data:`WIDTH` wide.

    One row per root: ``root`` (its name, the uncoupled mode it continues
    from), ``freq /rev``, ``real /rev`` (:func:`real_part_text`), ``damping
    ratio``, ``carries most`` (the coordinate it carries most, shown where it
    is not the name; no column when it is the name everywhere) and ``note``:
    ``FLUTTER ROOT`` (:func:`flutter_row`), ``UNSTABLE`` (:func:`unstable`),
    ``name uncertain`` (its path met another's).  A table too wide leaves
    out ``carries most`` (the CSV has it as ``dominant``).

    Parameters
    ----------
    table : pandas.DataFrame or mapping
        :attr:`tefcore.linear.stability.StabilityResult.modes`, or its
        ``columns`` (the command prints these: no pandas needed).

    Returns
    -------
    str
    """
    neutral = _flags(table, "neutral", False)
    names = [str(x) for x in table["label"]]
    carries = (["" if str(d) == n else str(d) for d, n in zip(table["dominant"], names,
                                                               strict=True)]
               if "dominant" in table else [])
    columns = [("root", names, "<"),
               ("freq /rev", [f"{v:.4f}" for v in table["frequency_per_rev"]], ">"),
               ("real /rev", [real_part_text(v, n) for v, n in
                              zip(table["real_part"], neutral, strict=True)], ">"),
               ("damping ratio", [f"{v:.4f}" for v in table["damping_ratio"]], ">"),
               ("carries most", carries, "<"), ("note", _notes(table), "<")]
    if not any(carries):
        columns.pop(4)
        carries = []
    lines = _layout(columns)
    if max(map(len, lines)) > WIDTH and carries:
        lines = _layout(columns[:4] + columns[5:])
    return "\n".join(lines)


def legend(table) -> list[str]:
    """The legend lines under :func:`modes_text`: :data:`LEGEND`, :data:`LOCKED_LEGEND`
    when a root is the locked partner of another, and :data:`UNCERTAIN_LEGEND` when a
    root's name is uncertain.

    Parameters
    ----------
    table : pandas.DataFrame or mapping
        The modes table, or its columns.

    Returns
    -------
    list of str
    """
    uncertain = "identity_certain" in table and not _flags(table, "identity_certain", True).all()
    locked = "label" in table and any(is_locked(n) for n in table["label"])
    return ([LEGEND] + ([LOCKED_LEGEND] if locked else [])
            + ([UNCERTAIN_LEGEND] if uncertain else []))


def trim_lines(trim: dict) -> list[str]:
    """The trim scalars, wrapped: the controls and inflow, then the flap's harmonics.

    Parameters
    ----------
    trim : dict
        :attr:`tefcore.linear.stability.StabilityResult.trim` (name -> scalar);
        ``delta_<harmonic>_deg`` are the flap deflection's harmonics.

    Returns
    -------
    list of str

    Examples
    --------
    >>> trim_lines({"collective_deg": 6.1081, "ct_sigma": 0.075, "delta_mean_deg": 2.078,
    ...             "delta_1c_deg": 0.85234})
    ['trim: collective_deg=6.108, ct_sigma=0.075', 'flap deflection [deg]: mean=2.078, 1c=0.8523']
    """
    flap = {k: v for k, v in trim.items() if re.fullmatch(r"delta_\w+_deg", k)}
    rest = ", ".join(f"{k}={v:.4g}" for k, v in trim.items() if k not in flap)
    lines = [wrap(f"trim: {rest}")]
    if flap:
        lines.append(wrap("flap deflection [deg]: " + ", ".join(
            f"{k.removeprefix('delta_').removesuffix('_deg')}={v:.4g}"
            for k, v in flap.items())))
    return lines


def flutter_text(table) -> str | None:
    """One sentence on the point's flutter root, or None without a flap.

    Parameters
    ----------
    table : pandas.DataFrame or mapping
        A modes table with ``flutter_root``, or its columns.

    Returns
    -------
    str or None
        ``"flutter root: <name> at +x.xxx /rev (continues from <name>), frequency f /rev"``
        when it is unstable; else which flap-induced root is least stable and
        that it is stable (or neutral).
    """
    def value(name, pos):
        return np.asarray(table[name], dtype=object)[pos]

    pos = _flutter_position(table)
    if pos is not None:
        label = value("label", pos)
        return wrap(f"flutter root: {label} at {value('real_part', pos):+.3f} /rev (continues "
                    f"from {base_name(label)}), frequency {value('frequency_per_rev', pos):.3f}"
                    " /rev")
    marked = np.flatnonzero(_flags(table, "flutter_root", False))
    if not marked.size:
        return None
    pos = int(marked[0])
    state = ("neutral (its real part within its error)" if _flags(table, "neutral", False)[pos]
             else f"stable ({value('real_part', pos):+.4f} /rev)")
    return wrap(f"no flutter root: the least stable flap-induced root, {value('label', pos)}, "
                f"is {state}")


def mechanism_choice(result, table: pd.DataFrame) -> str:
    """The line ``tefcore mechanism`` prints when no ``--mode`` is given: which root it took.

    :func:`tefcore.linear.mechanism.mechanism` with ``mode=None`` takes the
    flutter root when it is unstable, else the TEF mode.

    Parameters
    ----------
    result : tefcore.linear.mechanism.MechanismResult
        The decomposition.
    table : pandas.DataFrame
        The modes table it was taken from.

    Returns
    -------
    str
    """
    eta = result.eigenvalue
    marked = table["flutter_root"].fillna(False).to_numpy(bool) if "flutter_root" in table \
        else np.zeros(len(table), bool)
    flutter = table[marked & (table["real_part"].to_numpy(float) > 0)]
    if not flutter.empty and result.label == str(flutter["label"].iloc[0]):
        return wrap(f"decomposing the flutter root ({result.label}, {eta.real:+.2f} /rev); "
                    "--mode TEF for the flap mode")
    return wrap(f"decomposing the TEF mode ({eta.real:+.2f} /rev): no flutter root is unstable; "
                "--mode flutter to take it anyway")


# ------------------------------------------------------------------ sweeps


def _x_unit(table: pd.DataFrame, parameter: str) -> tuple[str, float]:
    """The unit the sweep's values were given in, and its factor from SI (1 and "" when bare)."""
    given = table["value"].dropna()
    m = re.match(r"^\s*[-+0-9.eE]+\s+(\S.*)$", str(given.iloc[0])) if len(given) else None
    if m is None:
        return "", 1.0
    p = field_param(parameter)
    try:
        # linear units: a value in SI times from_si(1) is the value in the unit
        return m.group(1).strip(), from_si(1.0, m.group(1).strip(), p.dimension if p else None)
    except ValueError:
        return "", 1.0


def onset(x, real, neutral=None) -> tuple[str, float]:
    """Where a role's root first becomes unstable along a sweep, in words and as a number.

    Parameters
    ----------
    x : array_like
        The parameter at the points, ascending.
    real : array_like
        The root's real part there [1/rev].
    neutral : array_like of bool, optional
        Real parts within their error (stable for this purpose).

    Returns
    -------
    text : str
        ``"stable throughout"``, ``"unstable throughout"``, ``"unstable from
        the first point"`` or ``"onset at {x}"`` (the sign change of the real
        part linearly interpolated between the two neighbouring points),
        with the number of later sign changes.
    value : float
        The onset (the first x when unstable from the start; NaN when stable
        throughout).

    Examples
    --------
    >>> onset([0.0, 0.1, 0.2], [-0.2, -0.1, 0.3])
    ('onset at 0.125', 0.125)
    >>> onset([0.0, 0.1], [-0.2, -0.1])
    ('stable throughout', nan)
    """
    x, y = np.asarray(x, float), np.asarray(real, float)
    bad = y > 0 if neutral is None else (y > 0) & ~np.asarray(neutral, bool)
    if not bad.any():
        return "stable throughout", np.nan
    if bad.all():
        return "unstable throughout", float(x[0])
    changes = np.flatnonzero(bad[1:] != bad[:-1]) + 1
    if bad[0]:
        text, value, later = "unstable from the first point", float(x[0]), len(changes)
    else:
        i = int(changes[0])
        y0, y1 = min(y[i - 1], 0.0), y[i]
        value = float(x[i - 1] + (x[i] - x[i - 1]) * (-y0) / (y1 - y0))
        text, later = f"onset at {value:.4g}", len(changes) - 1
    if later:
        text += f" ({later} later sign change{'s' if later > 1 else ''})"
    return text, value


def _role_line(what: str, rows: pd.DataFrame, unit: tuple[str, float], names_ep,
               undecided=()) -> str:
    """One role's summary: onset, largest growth, exceptional points of its names and
    the steps where one of its names moved with no exceptional point located
    (``undecided``: ``(modes, x_low, x_high, kind)``, said under their kind,
    :func:`tefcore.modes.roles.undecided_steps`)."""
    rows = rows[np.isfinite(rows["real_part"].to_numpy(float))]
    if rows.empty:
        return wrap(f"{what}: not at any point of the sweep")
    u, f = unit
    x = rows["value_si"].to_numpy(float) * f
    neutral = rows["neutral"].fillna(False).to_numpy(bool) if "neutral" in rows else None
    text, _ = onset(x, rows["real_part"], neutral)
    i = int(np.argmax(rows["real_part"].to_numpy(float)))
    top = rows.iloc[i]
    name = "" if what == "TEF mode" else f" ({top['label']})"
    line = (f"{what}: {text}; largest real part {top['real_part']:+.3f} /rev at "
            f"{x[i]:.4g}{(' ' + u) if u else ''}{name}")
    own = set(map(base_name, rows["label"]))
    kinds = [(names_ep, "exceptional points")] + [
        ([e[:3] for e in undecided if e[3] == k], k)
        for k in dict.fromkeys(e[3] for e in undecided)]
    for found, what_kind in kinds:
        hits = [e for e in found if set(pair_labels(e[0])) & own]
        if hits:
            where = "; ".join(f"{m} " + (f"at {lo * f:.4g}" if lo == hi else
                                           f"between {lo * f:.4g} and {hi * f:.4g}")
                              for m, lo, hi in hits)
            line += f"; {what_kind}{' of its names' if name else ''}: {where}"
    return wrap(line)


def timing_lines(timing: dict) -> list[str]:
    """How a sweep's points were computed (:attr:`tefcore.sweeps.sweep.SweepResult.timing`).

    Parameters
    ----------
    timing : dict
        ``wall_s``, ``point_s``, ``processes``, ``speedup``.

    Returns
    -------
    list of str
        One line; none when no point was computed (all loaded from the sweep file).
    """
    if not timing.get("wall_s"):
        return []
    return [f"computed in {timing['wall_s']:.2f} s on {timing['processes']} process(es): "
            f"{timing['point_s']:.2f} s of point time, speed-up {timing['speedup']:.2f}x"]


def sweep_summary(result) -> list[str]:
    """The lines ``tefcore sweep`` prints after a sweep: the TEF mode and the flutter root.

    For each role, over the points asked for (``refinement == 0``) that
    were computed: the onset of instability (:func:`onset`), the largest
    real part and where (with the flutter root's name there), the
    exceptional points (:attr:`tefcore.sweeps.sweep.SweepResult.exceptional_points`)
    involving its names, and the steps where one of its names moved to
    another root with no exceptional point located, under their kind
    (:attr:`tefcore.sweeps.sweep.SweepResult.undecided_steps`).  Values of
    the parameter are in the unit the sweep was given in.

    Parameters
    ----------
    result : tefcore.sweeps.sweep.SweepResult
        The sweep.

    Returns
    -------
    list of str
        Lines of at most :data:`WIDTH` characters (a long summary wraps,
        indented).
    """
    t = result.table
    ok = t[t["status"] == "ok"]
    if ok.empty:
        return ["no point computed"]
    if "refinement" in ok:
        ok = ok[ok["refinement"] == 0]
    unit = _x_unit(t, result.parameter)
    named = list(result.exceptional_points[["modes", "x_low", "x_high"]].itertuples(
        index=False, name=None))
    undecided = list(result.undecided_steps[["modes", "x_low", "x_high", "kind"]].itertuples(
        index=False, name=None))
    head = f"{result.parameter}" + (f" in {unit[0]}" if unit[0] else "")
    lines = [f"along {head}:"]
    for what, col in (("TEF mode", "tef_branch"), ("flutter root", "flutter_root")):
        if col in ok:
            rows = ok[ok[col].fillna(False).astype(bool)]
            rows = rows.sort_values("value_si", key=lambda s: s.astype(float), kind="stable")
            lines.append(_role_line(what, rows, unit, named, undecided))
    return "\n".join(lines).splitlines()
