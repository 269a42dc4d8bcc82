"""C81 airfoil decks: the deck, its errors and the writer.

The fixed-column layout is specified in ``docs/c81_format.md``; the parser
is :mod:`tefcore.aero.c81.reader`, the table models are :mod:`tefcore.aero.c81.tables`,
and :mod:`tefcore.aero.c81` gathers all three.

Examples
--------
>>> import numpy as np
>>> deck = C81Deck("TOY", alpha={c: [-4.0, 0.0, 4.0] for c in BLADE_COEFFICIENTS},
...                mach={c: [0.0, 0.5] for c in BLADE_COEFFICIENTS},
...                tables={c: np.zeros((3, 2)) for c in BLADE_COEFFICIENTS})
>>> print(format_c81(deck, header=False).splitlines()[0])
TOY                            2 3 2 3 2 3
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...errors import TefcoreError

__all__ = [
    "BLADE_COEFFICIENTS",
    "COEFFICIENTS",
    "COEFFICIENT_LABELS",
    "DELTAS_KEY",
    "DELTA_KEY",
    "FIELD",
    "NAME_WIDTH",
    "PER_LINE",
    "PLAUSIBLE_MAX",
    "C81Deck",
    "C81FormatError",
    "C81PlausibilityWarning",
    "C81RangeError",
    "C81RangeWarning",
    "coefficient_text",
    "format_c81",
    "write_c81",
]

COEFFICIENTS = ("cl", "cd", "cm", "ch", "clf")
BLADE_COEFFICIENTS = COEFFICIENTS[:3]
#: How messages and summaries name each coefficient.
COEFFICIENT_LABELS = {"cl": "C_l", "cd": "C_d", "cm": "C_m", "ch": "C_h", "clf": "C_lf"}

FIELD = 7  # width of every number field (F7.x)
PER_LINE = 9  # numbers per line after the first 7-column field
NAME_WIDTH = 30  # columns 1-30 of the title line
DELTAS_KEY = "DELTAS"  # flap deck: the list of delta values
DELTA_KEY = "DELTA"  # flap deck: start of the tables for one delta

#: Largest plausible magnitude of a section coefficient.  Airfoil data over the
#: full circle of angles of attack stay within about 2.5 (lift, and the drag of
#: a flat plate broadside); 10 leaves room for any real deck and catches a
#: number whose decimal point was lost (".4650" -> "4650").
PLAUSIBLE_MAX = 10.0


# --------------------------------------------------------------------------
# errors and warnings


class C81FormatError(TefcoreError, ValueError):
    """A malformed C81 deck: ``"<file> line L, column C: <what was expected>"``.

    The arguments are kept as attributes of the same names.

    Parameters
    ----------
    filename : str
        The deck's file name.
    line, column : int
        Where the problem is, 1-based.
    reason : str
        What was expected.
    """

    def __init__(self, filename: str, line: int, column: int, reason: str):
        self.filename = filename
        self.line = line
        self.column = column
        self.reason = reason
        super().__init__(f"{filename} line {line}, column {column}: {reason}")


class C81PlausibilityWarning(UserWarning):
    """A coefficient in a deck far outside the physical range (:data:`PLAUSIBLE_MAX`)."""


class C81RangeWarning(UserWarning):
    """Inputs outside a C81 table were clipped to the table edges."""


class C81RangeError(ValueError):
    """Inputs outside a C81 table with ``out_of_range="raise"``."""


# --------------------------------------------------------------------------
# the deck


def _strictly_increasing(x: np.ndarray) -> bool:
    return bool(np.all(np.diff(x) > 0))


@dataclass(eq=False)
class C81Deck:
    """An airfoil deck: coefficient tables on (alpha, Mach[, delta]) grids.

    Attributes
    ----------
    name : str
        Airfoil name (at most 30 characters in a file).
    alpha, mach : dict of str -> ndarray
        Per coefficient, the angles of attack (deg) and Mach numbers of its
        table, strictly increasing.
    tables : dict of str -> ndarray
        ``'cl', 'cd', 'cm'`` (blade deck) or also ``'ch', 'clf'`` (flap deck),
        each of shape ``(n_alpha, n_mach)`` or ``(n_alpha, n_mach, n_delta)``.
    delta : ndarray or None
        Flap deflections (deg), strictly increasing, or None for a blade deck.
    header : str
        Provenance / comment text (the ``#`` lines before the title line).
    source : str
        Where the deck was read from (for messages; not compared).
    """

    name: str
    alpha: dict[str, np.ndarray]
    mach: dict[str, np.ndarray]
    tables: dict[str, np.ndarray]
    delta: np.ndarray | None = None
    header: str = ""
    source: str = field(default="<memory>", compare=False)

    def __post_init__(self):
        if self.delta is not None:
            self.delta = np.asarray(self.delta, dtype=float)
            if self.delta.ndim != 1 or self.delta.size < 1:
                raise ValueError("delta must be a non-empty 1-D array (deg)")
            if not (np.all(np.isfinite(self.delta)) and _strictly_increasing(self.delta)):
                raise ValueError("delta must be finite and strictly increasing")
        expected = COEFFICIENTS if self.delta is not None else BLADE_COEFFICIENTS
        kind = "flap" if self.delta is not None else "blade"
        for what, mapping in (("tables", self.tables), ("alpha", self.alpha),
                              ("mach", self.mach)):
            if set(mapping) != set(expected):
                raise ValueError(f"a {kind} deck needs {what} for exactly {list(expected)}, "
                                 f"got {sorted(mapping)}")
        self.alpha = {c: np.asarray(self.alpha[c], dtype=float) for c in expected}
        self.mach = {c: np.asarray(self.mach[c], dtype=float) for c in expected}
        self.tables = {c: np.asarray(self.tables[c], dtype=float) for c in expected}
        for c in expected:
            a, m, t = self.alpha[c], self.mach[c], self.tables[c]
            for label, x in (("alpha", a), ("mach", m)):
                if x.ndim != 1 or x.size < 1:
                    raise ValueError(f"{label}[{c!r}] must be a non-empty 1-D array")
                if not (np.all(np.isfinite(x)) and _strictly_increasing(x)):
                    raise ValueError(f"{label}[{c!r}] must be finite and strictly increasing")
            shape = (a.size, m.size) + (() if self.delta is None else (self.delta.size,))
            if t.shape != shape:
                raise ValueError(f"tables[{c!r}] has shape {t.shape}, expected {shape} "
                                 "(n_alpha, n_mach[, n_delta])")
            if not np.all(np.isfinite(t)):
                raise ValueError(f"tables[{c!r}] contains NaN or infinite values")

    @property
    def is_flap(self) -> bool:
        """True for a flap deck (tables also versus delta)."""
        return self.delta is not None

    @property
    def coefficients(self) -> tuple[str, ...]:
        """Coefficient names in file order."""
        return COEFFICIENTS if self.is_flap else BLADE_COEFFICIENTS

    def __eq__(self, other):
        if not isinstance(other, C81Deck):
            return NotImplemented
        if (self.name, self.header, self.coefficients) != (other.name, other.header,
                                                           other.coefficients):
            return False
        if self.is_flap and not np.array_equal(self.delta, other.delta):
            return False
        return all(np.array_equal(getattr(self, k)[c], getattr(other, k)[c])
                   for c in self.coefficients for k in ("alpha", "mach", "tables"))


# --------------------------------------------------------------------------
# writing


def _format_axis(values: np.ndarray) -> list[str]:
    """Axis values (alpha, Mach, delta) with one number of decimals for all:
    the fewest (at least 1) that represent every value, as many as fit."""
    values = np.asarray(values, dtype=float)
    for d in range(1, 6):
        if np.all(np.abs(np.round(values, d) - values) <= 1e-9 * np.maximum(1, np.abs(values))):
            break
    while d > 0 and any(len(f"{v:.{d}f}") > FIELD - 1 for v in values):
        d -= 1
    out = []
    for v in values:
        s = f"{v:.{d}f}" if d else f"{v:.0f}."
        if float(s) == 0:
            s = s.lstrip("-")
        if len(s) > FIELD - 1:
            raise ValueError(f"{v!r} does not fit a 7-column field")
        out.append(s)
    return out


def coefficient_text(x: float) -> tuple[str, int]:
    """A coefficient as the writer prints it (``docs/c81_format.md``, section 6).

    At most 6 characters (so a blank separates it from the previous field),
    rounded to as many decimals as fit, ``d``, the leading zero dropped for
    |x| < 1 (``-.1234``, ``.12345``, ``.40000``); a value that rounds to zero
    is ``0.0``.

    Parameters
    ----------
    x : float
        The coefficient.

    Returns
    -------
    text : str
        Within ``0.5 * 10**-d`` of ``x`` (half the last printed digit).
    d : int
        Its number of decimals.

    Raises
    ------
    ValueError
        When ``x`` does not fit a 7-column field (``|x| >= 1e5``).

    Examples
    --------
    >>> coefficient_text(0.123456), coefficient_text(-1.23456)
    (('.12346', 5), ('-1.235', 3))
    """
    x = float(x)
    for d in range(5, -1, -1):
        s = f"{x:.{d}f}"
        if s.startswith("0."):
            s = s[1:]
        elif s.startswith("-0."):
            s = "-" + s[2:]
        if len(s) <= FIELD - 1:
            break
    else:
        raise ValueError(f"coefficient {x!r} does not fit a 7-column field")
    if float(s) == 0:
        return "0.0", d
    return (s + "." if d == 0 and len(s) < FIELD - 1 else s), d


def _continuation_lines(texts: list[str]) -> list[str]:
    """Numbers 9 per line, each line leading with 7 blanks (Mach lines and
    continuation lines)."""
    return [" " * FIELD + "".join(t.rjust(FIELD) for t in texts[k:k + PER_LINE])
            for k in range(0, len(texts), PER_LINE)]


def _block_lines(alpha, mach, table) -> list[str]:
    lines = _continuation_lines(_format_axis(mach))
    for a_text, row in zip(_format_axis(alpha), table, strict=True):
        coeffs = [coefficient_text(v)[0] for v in row]
        first, rest = coeffs[:PER_LINE], coeffs[PER_LINE:]
        lines.append(a_text.rjust(FIELD) + "".join(s.rjust(FIELD) for s in first))
        lines.extend(_continuation_lines(rest))
    return lines


def format_c81(deck: C81Deck, *, header: bool = True) -> str:
    """The text of a deck in the layout of ``docs/c81_format.md``.

    With ``header=False`` the ``#`` provenance lines are left out, so a blade
    deck is a strictly standard C81 deck.

    Parameters
    ----------
    deck : C81Deck
        The deck.
    header : bool, optional
        Include the ``#`` provenance lines.

    Returns
    -------
    str
    """
    if len(deck.name) > NAME_WIDTH or "\n" in deck.name or deck.name.lstrip().startswith("#"):
        raise ValueError(f"deck name {deck.name!r} must fit columns 1-30 and not start with '#'")
    lines = []
    if header and deck.header:
        lines += [("# " + ln).rstrip() for ln in deck.header.splitlines()]
    counts = []
    for c in deck.coefficients:
        nm, na = deck.mach[c].size, deck.alpha[c].size
        if nm > 99 or na > 99:
            raise ValueError(f"{c}: {na} angles x {nm} Mach numbers exceed the I2 counts (99)")
        counts += [nm, na]
    lines.append(deck.name.ljust(NAME_WIDTH) + "".join(f"{k:2d}" for k in counts))
    if not deck.is_flap:
        for c in deck.coefficients:
            lines += _block_lines(deck.alpha[c], deck.mach[c], deck.tables[c])
    else:
        dtext = _format_axis(deck.delta)
        for k in range(0, len(dtext), PER_LINE):
            lines.append(DELTAS_KEY.ljust(FIELD)
                         + "".join(s.rjust(FIELD) for s in dtext[k:k + PER_LINE]))
        for j, d in enumerate(dtext):
            lines.append(DELTA_KEY.ljust(FIELD) + d.rjust(FIELD))
            for c in deck.coefficients:
                lines += _block_lines(deck.alpha[c], deck.mach[c], deck.tables[c][:, :, j])
    return "\n".join(lines) + "\n"


def write_c81(deck: C81Deck, path: str | os.PathLike, *, header: bool = True) -> Path:
    """Write ``deck`` to ``path`` (see :func:`format_c81`); returns the path.

    Parameters
    ----------
    deck : C81Deck
        The deck.
    path : str or os.PathLike
        The file (written atomically).
    header : bool, optional
        Include the ``#`` provenance lines.

    Returns
    -------
    pathlib.Path
    """
    from ...safe_io import atomic_write_text  # deferred: only writing needs it

    return atomic_write_text(path, format_c81(deck, header=header))
