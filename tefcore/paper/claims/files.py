"""The files of the paper's reference data: where they are, TOML and digitised CSV.

The reference data (``reference_data/``: claims in TOML, digitised curves
as WebPlotDigitizer CSV exports, see its README) is read here; a malformed
file is a :class:`ReferenceDataError` naming the file and the record or CSV
row.  What the records mean is :mod:`tefcore.paper.claims.reference`.
"""

from __future__ import annotations

import csv
import io
import math
import os
import tomllib
from pathlib import Path

import pandas as pd

__all__ = ["ReferenceDataError", "read_toml", "read_wpd_csv", "reference_dir"]


class ReferenceDataError(ValueError):
    """A malformed reference file; the message names the file and record or row."""


def reference_dir() -> Path:
    """The reference data folder: ``$TEFCORE_REFERENCE_DATA`` or the repository's."""
    env = os.environ.get("TEFCORE_REFERENCE_DATA")
    return Path(env) if env else Path(__file__).resolve().parent.parent / "reference_data"


def read_toml(path: Path) -> dict:
    """The TOML file at `path` as a dict.

    Parameters
    ----------
    path : pathlib.Path
        A TOML file.

    Returns
    -------
    dict

    Raises
    ------
    ReferenceDataError
        Not valid TOML (the message names the file).
    """
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as err:
        raise ReferenceDataError(f"{path}: not valid TOML: {err}") from None


def _num(cell: str, where: str) -> float:
    try:
        v = float(cell)
    except ValueError:
        raise ReferenceDataError(f"{where}: {cell!r} is not a number") from None
    if not math.isfinite(v):
        raise ReferenceDataError(f"{where}: {cell!r} is not a finite number")
    return v


def read_wpd_csv(path) -> dict[str, pd.DataFrame]:
    """Read a WebPlotDigitizer CSV export into ``{dataset name: DataFrame(x, y)}``.

    Layouts (``,``, ``;`` or tab separated): *per dataset* -- two columns
    ``x, y``, no header or one header line, returned under the name ``""``;
    *export all* -- dataset names on row 1 (above each X column), ``X, Y``
    pairs on row 2, then the points (shorter datasets leave cells empty).

    Parameters
    ----------
    path : path
        The CSV file.

    Raises
    ------
    ReferenceDataError
        Naming the file and 1-based row.
    """
    path = Path(path)
    text = path.read_text(encoding="utf-8-sig")
    first = text.lstrip().split("\n", 1)[0]
    delim = next((d for d in (",", ";", "\t") if d in first), ",")
    rows = [(n, [c.strip() for c in row]) for n, row in
            enumerate(csv.reader(io.StringIO(text), delimiter=delim), start=1) if any(
                c.strip() for c in row)]
    if not rows:
        raise ReferenceDataError(f"{path}: no data")
    xy = [c.upper() for c in (rows[1][1] if len(rows) > 1 else [])]
    while xy and not xy[-1]:
        xy.pop()
    if xy and len(xy) % 2 == 0 and xy == ["X", "Y"] * (len(xy) // 2):
        return _wpd_export_all(path, rows, len(xy) // 2)
    return {"": _wpd_two_columns(path, rows)}


def _wpd_export_all(path: Path, rows, n_sets: int) -> dict[str, pd.DataFrame]:
    """WebPlotDigitizer's "export all": names on row 1, X/Y on row 2, points below."""
    names, out = rows[0][1] + [""] * (2 * n_sets), {}
    for j in range(0, 2 * n_sets, 2):
        name = names[j]
        if not name or name in out:
            raise ReferenceDataError(f"{path}, row {rows[0][0]}: dataset name above column "
                                     f"{j + 1} is {'repeated' if name else 'empty'}")
        pts = []
        for n, row in rows[2:]:
            cx, cy = (row + ["", ""])[j:j + 2]
            if not (cx or cy):
                continue                    # a shorter dataset ends here
            if not (cx and cy):
                raise ReferenceDataError(f"{path}, row {n}: dataset {name!r} has only "
                                         "one of its X/Y cells")
            pts.append((_num(cx, f"{path}, row {n}"), _num(cy, f"{path}, row {n}")))
        out[name] = pd.DataFrame(pts, columns=["x", "y"])
    return out


def _wpd_two_columns(path: Path, rows) -> pd.DataFrame:
    """One dataset as two columns x, y, with at most one header line."""
    try:
        [float(c) for c in rows[0][1] if c]
    except ValueError:
        rows = rows[1:]  # one header line such as "x,y"
    pts = []
    for n, row in rows:
        cells = [c for c in row if c]
        if len(cells) != 2:
            raise ReferenceDataError(f"{path}, row {n}: expected two columns x, y, got {row}")
        pts.append((_num(cells[0], f"{path}, row {n}"), _num(cells[1], f"{path}, row {n}")))
    if not pts:
        raise ReferenceDataError(f"{path}: no data rows")
    return pd.DataFrame(pts, columns=["x", "y"])
