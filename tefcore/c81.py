"""C81 airfoil decks: the deck, reading and writing.

The paper's second aerodynamic model takes the blade section coefficients
(C_l, C_d, C_m) and the flap coefficients (C_h, C_lf) "from the table lookup
for specific angles of attack (alpha), Mach number (M), and trailing-edge flap
deflection (delta_f)".  This module holds the tables of that lookup:

* :func:`read_c81` / :func:`parse_c81` read a standard blade C81 deck
  (C_l, C_d, C_m versus alpha and Mach) or a tefcore *flap deck* (the five
  coefficients versus alpha, Mach and delta) into a :class:`C81Deck`;
  :func:`write_c81` / :func:`format_c81` write one.  The accepted layout is
  specified in ``docs/c81_format.md``.  Every problem with a file's content
  -- layout, numbers, counts, encoding (not UTF-8) -- is a
  :class:`C81FormatError` naming the file, the 1-based line and column and
  what was expected.  The counts on the title line are checked against the
  number of lines in the file before anything is allocated.  Coefficients
  far outside the physical range of airfoil data (:data:`PLAUSIBLE_MAX`,
  e.g. ``.01000`` mistyped as ``01000``) give one
  :class:`C81PlausibilityWarning` naming the first such number.
* The table models :class:`C81Airfoil` and :class:`C81FlapTable` (inputs
  outside a table: :class:`C81RangeWarning` / :class:`C81RangeError`,
  defined here), :func:`generate_flap_deck`, the packaged example deck and
  the ``python -m tefcore.c81 example|check`` command are in
  :mod:`tefcore.c81_model`, and re-exported here.

Longer than ~400 lines because it is one fixed-column format: its parser, with
line/column error reporting, and the matching writer.

Examples
--------
>>> deck = parse_c81('''\\
... TOY                            2 3 2 3 2 3
...           0.0    0.5
...    -4.0  -0.40  -0.45
...     0.0    0.0    0.0
...     4.0   0.40   0.45
...           0.0    0.5
...    -4.0   .010   .012
...     0.0   .008   .009
...     4.0   .010   .012
...           0.0    0.5
...    -4.0    0.0    0.0
...     0.0    0.0    0.0
...     4.0    0.0    0.0
... ''')
>>> deck.tables["cl"].shape, deck.is_flap
((3, 2), False)
"""

from __future__ import annotations

import math
import os
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .errors import TefcoreError

if TYPE_CHECKING:  # at run time re-exported by __getattr__ (end of the module)
    from .c81_model import (
        EXAMPLE_DECK_NAME,
        C81Airfoil,
        C81FlapTable,
        example_deck_path,
        generate_flap_deck,
        make_example_deck,
    )

__all__ = [
    "BLADE_COEFFICIENTS",
    "COEFFICIENTS",
    "EXAMPLE_DECK_NAME",
    "PLAUSIBLE_MAX",
    "C81Airfoil",
    "C81Deck",
    "C81FlapTable",
    "C81FormatError",
    "C81PlausibilityWarning",
    "C81RangeError",
    "C81RangeWarning",
    "example_deck_path",
    "format_c81",
    "generate_flap_deck",
    "make_example_deck",
    "parse_c81",
    "read_c81",
    "write_c81",
]

#: Coefficients of a flap deck, in file order; a blade deck has the first three.
COEFFICIENTS = ("cl", "cd", "cm", "ch", "clf")
BLADE_COEFFICIENTS = COEFFICIENTS[:3]
_LABEL = {"cl": "C_l", "cd": "C_d", "cm": "C_m", "ch": "C_h", "clf": "C_lf"}

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

_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eEdD][+-]?[0-9]+)?\Z")
_NONFINITE = re.compile(r"[+-]?(?:nan|inf|infinity)\Z", re.IGNORECASE)
_TOKEN = re.compile(r"\S+")


# --------------------------------------------------------------------------
# errors and warnings


class C81FormatError(TefcoreError, ValueError):
    """A malformed C81 deck: ``"<file> line L, column C: <what was expected>"``.

    Attributes ``filename``, ``line`` and ``column`` (1-based) and ``reason``.
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
# reading


def _describe(text: str) -> str:
    return f"{text!r}" if text else "end of line"


class _Reader:
    """Line-by-line parser keeping 1-based line numbers for error messages."""

    def __init__(self, text: str, filename: str):
        self.filename = filename
        self.lines = text.split("\n")
        if self.lines and self.lines[-1] == "":
            self.lines.pop()
        self.lines = [ln.rstrip("\r") for ln in self.lines]
        self.i = 0  # index of the next line
        self.implausible: list[tuple[float, int, int, str]] = []  # (value, line, col, what)

    def error(self, line: int, column: int, reason: str):
        return C81FormatError(self.filename, line, column, reason)

    def next_line(self, expected: str) -> tuple[int, str]:
        if self.i >= len(self.lines):
            raise self.error(self.i + 1, 1, f"expected {expected}, got end of file "
                                            "(truncated file?)")
        self.i += 1
        return self.i, self.lines[self.i - 1]

    # -- one line of numbers ----------------------------------------------

    def numbers(self, n: int, what: list[str], *, lead: str, expected: str
                ) -> tuple[int, list[tuple[float, int]]]:
        """Read one line with ``n`` numbers; return (line number, [(value, column)]).

        ``lead`` says what columns 1-7 hold: ``"number"`` (the first of the n
        numbers, e.g. alpha), ``"blank"`` (Mach and continuation lines) or a
        keyword (flap decks).  ``what[k]`` describes the k-th number.
        """
        lineno, text = self.next_line(expected)
        head = text[:FIELD]
        tokens = [(m.group(), m.start()) for m in _TOKEN.finditer(text)]
        if lead == "number":
            if not head.strip():
                got = "a blank line" if not text.strip() else "blank columns 1-7"
                raise self.error(lineno, 1, f"expected {expected}, starting with "
                                 f"{what[0]} in columns 1-7, got {got} "
                                 "(missing row, or a count on the title line too large?)")
            start = 0
        elif lead == "blank":
            if head.strip():
                col = len(head) - len(head.lstrip()) + 1
                raise self.error(lineno, col, f"expected {expected}: 7 blank columns, then "
                                 f"{n} number(s); got {tokens[0][0]!r} in columns 1-7 "
                                 "(extra row, or a count on the title line too small?)")
            start = FIELD
        else:  # keyword
            if not tokens or tokens[0][0].upper() != lead:
                got = _describe(tokens[0][0] if tokens else "")
                col = tokens[0][1] + 1 if tokens else 1
                raise self.error(lineno, col, f"expected {expected}: the keyword "
                                 f"{lead!r} in columns 1-7, got {got}")
            start = FIELD
            tokens = tokens[1:]

        # fixed columns: field k occupies [start + 7k, start + 7k + 7)
        fixed, fixed_err = [], None
        if lead not in ("number", "blank") and head.strip().upper() != lead:
            fixed_err = (1, "")  # keyword field runs into the numbers: not fixed
        else:
            for k in range(n):
                a = start + FIELD * k
                raw = text[a:a + FIELD]
                s = raw.strip()
                col = a + 1 + len(raw) - len(raw.lstrip())
                if not s:
                    fixed_err = (a + 1, f"expected {what[k]}, got "
                                 + ("end of line" if not text[a:].strip() else "a blank field"))
                    break
                value = self._value(s, lineno, col, what[k])
                if value is None:
                    fixed_err = (col, f"expected a number, got {s!r} ({what[k]})")
                    break
                fixed.append((value, col))
            else:
                rest = text[start + FIELD * n:]
                if rest.strip():
                    col = start + FIELD * n + 1 + len(rest) - len(rest.lstrip())
                    fixed_err = (col, f"expected end of line after {n} number(s), "
                                      f"got {rest.strip()!r}")
        # whitespace-separated tokens
        free, free_err = [], None
        for k, (s, c) in enumerate(tokens):
            if k >= n:
                free_err = (c + 1, f"expected end of line after {n} number(s), got {s!r}")
                break
            value = self._value(s, lineno, c + 1, what[k])
            if value is None:
                free_err = (c + 1, f"expected a number, got {s!r} ({what[k]})")
                break
            free.append((value, c + 1))
        else:
            if len(free) < n:
                free_err = (len(text.rstrip()) + 1,
                            f"expected {what[len(free)]}, got end of line "
                            f"({n} number(s) expected, found {len(free)})")

        # When both succeed they agree: n non-blank fields and n tokens mean no
        # token crosses a field boundary.
        if fixed_err is None:
            return lineno, fixed
        if free_err is None:
            return lineno, free
        # Both readings fail: report the one that got further along the line.
        col, reason = fixed_err if fixed_err[0] >= free_err[0] else free_err
        raise self.error(lineno, col, reason)

    def _value(self, s: str, lineno: int, col: int, what: str):
        if _NONFINITE.match(s):
            raise self.error(lineno, col, f"expected a finite number, got {s!r} ({what})")
        if not _NUMBER.match(s):
            return None
        return float(s.replace("d", "e").replace("D", "e"))

    # -- structured pieces --------------------------------------------------

    def values_over_lines(self, n: int, what: list[str], *, expected: str
                          ) -> list[tuple[float, int, int]]:
        """``n`` numbers, 9 per line, each line leading with 7 blank columns."""
        out = []
        for k in range(0, n, PER_LINE):
            m = min(PER_LINE, n - k)
            lineno, vals = self.numbers(m, what[k:k + m], lead="blank", expected=expected)
            out.extend((v, lineno, c) for v, c in vals)
        return out

    def increasing(self, values: list[tuple[float, int, int]], label: str, where: str):
        for (v0, _, _), (v1, ln, col) in zip(values, values[1:], strict=False):
            if not v1 > v0:
                raise self.error(ln, col, f"{label} of {where} must increase strictly: "
                                 f"{v1:g} follows {v0:g}")

    def block(self, coef: str, n_mach: int, n_alpha: int, context: str):
        """One coefficient table: Mach line(s), then n_alpha rows."""
        where = f"the {_LABEL[coef]} table{context}"
        mach = self.values_over_lines(
            n_mach, [f"Mach number {j + 1} of {n_mach} of {where}" for j in range(n_mach)],
            expected=f"the Mach numbers of {where}")
        self.increasing(mach, "the Mach numbers", where)
        machs = [v for v, _, _ in mach]
        alphas, rows = [], []
        for r in range(n_alpha):
            what = ["alpha (deg)"]
            what += [f"{_LABEL[coef]} at M = {mm:g} in row {r + 1}{context}" for mm in machs]
            expected = f"row {r + 1} of {n_alpha} of {where}"
            vals = []
            k = 0
            n_total = 1 + n_mach
            while k < n_total:  # first line: alpha and up to 9 values; then 9 per line
                m = min(PER_LINE + 1, n_total) if k == 0 else min(PER_LINE, n_total - k)
                lineno, got = self.numbers(m, what[k:k + m], lead="number" if k == 0 else "blank",
                                           expected=expected)
                vals.extend((v, lineno, c) for v, c in got)
                k += m
            alphas.append(vals[0])
            rows.append([v for v, _, _ in vals[1:]])
            for k, (v, ln, col) in enumerate(vals[1:], start=1):
                if abs(v) > PLAUSIBLE_MAX:
                    self.implausible.append((v, ln, col, what[k]))
        self.increasing(alphas, "the angles of attack", where)
        return mach, alphas, np.array(rows, dtype=float).reshape(n_alpha, n_mach)

    def title(self):
        """Skip the ``#`` header and blank lines; parse the title line."""
        header = []
        while self.i < len(self.lines):
            s = self.lines[self.i].strip()
            if s.startswith("#"):
                body = s[1:]
                header.append(body[1:] if body.startswith(" ") else body)
            elif s:
                break
            self.i += 1
        lineno, text = self.next_line("the title line (name in columns 1-30, then counts)")
        name = text[:NAME_WIDTH].strip()
        rest = text[NAME_WIDTH:].rstrip()
        counts = None
        # fixed I2 fields: right-justified two-digit integers
        if len(rest) in (12, 20):
            fields = [rest[k:k + 2] for k in range(0, len(rest), 2)]
            if all(re.fullmatch(r" [0-9]|[0-9][0-9]", f) for f in fields):
                counts = [(int(f), NAME_WIDTH + 1 + 2 * k) for k, f in enumerate(fields)]
        if counts is None:
            toks = [(m.group(), m.start()) for m in _TOKEN.finditer(rest)]
            for s, c in toks:
                if not re.fullmatch(r"[0-9]{1,9}", s):
                    raise self.error(lineno, NAME_WIDTH + 1 + c, "expected an integer count "
                                     f"(I2 fields from column 31), got {s[:20]!r} "
                                     "(is the name longer than 30 columns?)")
            if len(toks) not in (6, 10):
                col = NAME_WIDTH + 1 + (toks[-1][1] + len(toks[-1][0]) if toks else 0)
                raise self.error(lineno, col, "expected 6 counts ML NL MD ND MM NM (blade "
                                 "deck) or 10 counts adding MH NH MF NF (flap deck) from "
                                 f"column 31, found {len(toks)}")
            counts = [(int(s), NAME_WIDTH + 1 + c) for s, c in toks]
        for v, c in counts:
            if v < 1:
                raise self.error(lineno, c, "expected a count of at least 1, got 0")
        return "\n".join(header), lineno, name, counts

    def check_room(self, counts, lineno: int):
        """Refuse a count that alone needs more lines than the file has (before allocating).

        A table of NM Mach numbers and NA angles takes at least
        ``ceil(NM / 9) + NA`` lines; smaller mismatches are reported where
        the tables run out, with what was expected there.
        """
        have = len(self.lines) - self.i
        for k in range(0, len(counts), 2):
            (nm, col), (na, _) = counts[k], counts[k + 1]
            need = -(-nm // PER_LINE) + na * (1 + -(-max(0, nm - PER_LINE) // PER_LINE))
            if need > have:
                raise self.error(lineno, col, f"the counts {nm} {na} on the title line need at "
                                 f"least {need} line(s) for one table, but the file has "
                                 f"{have} after the title line (a count too large?)")

    def deltas(self):
        """The DELTAS line(s): every line leads with the keyword, 9 values at most,
        only the last may be shorter."""
        out = []
        while True:
            if self.i >= len(self.lines):
                raise self.error(self.i + 1, 1, "expected the DELTAS line, got end of file")
            text = self.lines[self.i]
            tok = _TOKEN.match(text.lstrip())
            is_deltas = tok is not None and tok.group().upper() == DELTAS_KEY
            if not is_deltas:
                if not out:
                    self.i += 1
                    col = len(text) - len(text.lstrip()) + 1
                    raise self.error(self.i, col, "expected the keyword 'DELTAS' followed by the "
                                     "flap deflections (deg): a title line with 10 counts is a "
                                     f"flap deck; got {_describe(text.strip()[:20])}")
                return out
            if out and len(out) % PER_LINE:
                self.i += 1
                raise self.error(self.i, 1, "only the last DELTAS line may hold fewer than "
                                 f"{PER_LINE} values")
            # number of values on this line: count tokens, at most 9
            n_here = len(_TOKEN.findall(text)) - 1
            if text[:FIELD].strip().upper() == DELTAS_KEY:
                # fixed layout may have abutting fields: count 7-column fields instead
                n_here = max(n_here, math.ceil(len(text[FIELD:].rstrip()) / FIELD))
            if n_here < 1:
                self.i += 1
                raise self.error(self.i, len(text.rstrip()) + 1,
                                 "expected at least one flap deflection (deg) after 'DELTAS'")
            n_here = min(n_here, PER_LINE)
            what = [f"flap deflection (deg) number {len(out) + k + 1}" for k in range(n_here)]
            ln, vals = self.numbers(n_here, what, lead=DELTAS_KEY,
                                    expected="the flap deflections (deg)")
            out.extend((v, ln, c) for v, c in vals)

    def trailer(self):
        while self.i < len(self.lines):
            lineno, text = self.next_line("")
            s = text.strip()
            if s and not s.startswith("#"):
                col = len(text) - len(text.lstrip()) + 1
                raise self.error(lineno, col, "expected end of file after the last table, "
                                 f"got {s[:20]!r} (a count on the title line too small?)")


def parse_c81(text: str, filename: str = "<string>") -> C81Deck:
    """Parse the text of a C81 deck (blade or flap; see ``docs/c81_format.md``).

    Raises
    ------
    C81FormatError
        With the file name, 1-based line and column, and what was expected.
    """
    rd = _Reader(text, filename)
    header, title_line, name, counts = rd.title()
    rd.check_room(counts, title_line)
    flap = len(counts) == 10
    coefs = COEFFICIENTS if flap else BLADE_COEFFICIENTS
    n = {c: (counts[2 * k][0], counts[2 * k + 1][0]) for k, c in enumerate(coefs)}
    alpha, mach, tables = {}, {}, {}
    if not flap:
        for c in coefs:
            m, a, t = rd.block(c, *n[c], context="")
            mach[c] = np.array([v for v, _, _ in m])
            alpha[c] = np.array([v for v, _, _ in a])
            tables[c] = t
        rd.trailer()
        deck = C81Deck(name, alpha, mach, tables, header=header, source=filename)
        _warn_implausible(rd)
        return deck

    # flap deck: DELTAS line(s), then per delta a DELTA line and five blocks
    deltas = rd.deltas()
    rd.increasing(deltas, "the flap deflections", "the DELTAS line(s)")
    first = {}  # coefficient -> (mach values, alpha values) of the first delta
    per_delta = {c: [] for c in coefs}
    for j, (dval, _, _) in enumerate(deltas):
        ln, got = rd.numbers(1, [f"delta (deg) number {j + 1} of {len(deltas)}"],
                             lead=DELTA_KEY,
                             expected=f"the line 'DELTA {dval:g}' opening the tables for "
                                      f"delta number {j + 1} of {len(deltas)}")
        if not math.isclose(got[0][0], dval, rel_tol=1e-9, abs_tol=1e-9):
            raise rd.error(ln, got[0][1], f"expected delta = {dval:g} (number {j + 1} on "
                           f"the DELTAS line), got {got[0][0]:g}")
        context = f" for delta = {dval:g} deg"
        for c in coefs:
            m, a, t = rd.block(c, *n[c], context=context)
            if j == 0:
                first[c] = (m, a)
            else:
                for label, now, ref in (("Mach numbers", m, first[c][0]),
                                        ("angles of attack", a, first[c][1])):
                    for (v, ln2, col), (v0, ln0, _) in zip(now, ref, strict=True):
                        if v != v0:
                            raise rd.error(ln2, col, f"the {label} of the {_LABEL[c]} "
                                           f"table must be the same for every delta: got "
                                           f"{v:g}, expected {v0:g} as on line {ln0}")
            per_delta[c].append(t)
    rd.trailer()
    for c in coefs:
        mach[c] = np.array([v for v, _, _ in first[c][0]])
        alpha[c] = np.array([v for v, _, _ in first[c][1]])
        tables[c] = np.stack(per_delta[c], axis=-1)
    deck = C81Deck(name, alpha, mach, tables, delta=np.array([v for v, _, _ in deltas]),
                   header=header, source=filename)
    _warn_implausible(rd)
    return deck


def _warn_implausible(rd: _Reader) -> None:
    if not rd.implausible:
        return
    v, line, col, what = rd.implausible[0]
    more = len(rd.implausible) - 1
    warnings.warn(f"{rd.filename} line {line}, column {col}: {what} = {v:g} is far outside "
                  f"the physical range of airfoil coefficients (|c| <= {PLAUSIBLE_MAX:g}); "
                  "a lost decimal point?"
                  + (f" ({more} more such value(s))" if more else ""),
                  C81PlausibilityWarning, stacklevel=3)


def read_c81(path: str | os.PathLike) -> C81Deck:
    """Read a C81 deck (blade or tefcore flap deck) from a file.

    Raises
    ------
    C81FormatError
        Naming the file, the 1-based line and column, and what was expected.
    """
    path = Path(path)
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        start = data.rfind(b"\n", 0, err.start) + 1
        column = len(data[start:err.start].decode("utf-8", errors="replace")) + 1
        raise C81FormatError(str(path), line, column,
                             f"not UTF-8 text: byte 0x{data[err.start]:02x} (a C81 deck is "
                             "plain text; binary file, or another encoding?)") from None
    return parse_c81(text, filename=str(path))


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


def _coefficient_text(x: float) -> tuple[str, int]:
    """A coefficient in at most 6 characters (so a blank separates it from the
    previous field) rounded to as many decimals as fit, ``d``, the leading zero
    dropped for |x| < 1 (``-.1234``, ``.12345``, ``.40000``); a value that
    rounds to zero is ``0.0``.  Returns (text, d): the text is within
    ``0.5 * 10**-d`` of ``x`` (half the last printed digit)."""
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
        coeffs = [_coefficient_text(v)[0] for v in row]
        first, rest = coeffs[:PER_LINE], coeffs[PER_LINE:]
        lines.append(a_text.rjust(FIELD) + "".join(s.rjust(FIELD) for s in first))
        lines.extend(_continuation_lines(rest))
    return lines


def format_c81(deck: C81Deck, *, header: bool = True) -> str:
    """The text of a deck in the layout of ``docs/c81_format.md``.

    With ``header=False`` the ``#`` provenance lines are left out, so a blade
    deck is a strictly standard C81 deck.
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
    """Write ``deck`` to ``path`` (see :func:`format_c81`); returns the path."""
    from .safe_io import atomic_write_text  # deferred: only writing needs it

    return atomic_write_text(path, format_c81(deck, header=header))


# --------------------------------------------------------------------------
# re-exports of tefcore.c81_model

# tefcore.c81_model imports this module, so its names are looked up on first
# use (PEP 562) rather than imported here: no import cycle either way round.
_MODEL_NAMES = frozenset({
    "C81Airfoil", "C81FlapTable", "EXAMPLE_DECK_NAME", "EXAMPLE_GRID", "EXAMPLE_HEADER",
    "EXAMPLE_MODEL", "example_deck_path", "generate_flap_deck", "main", "make_example_deck",
})


def __getattr__(name: str):
    if name in _MODEL_NAMES:
        from . import c81_model

        return getattr(c81_model, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | _MODEL_NAMES)


if __name__ == "__main__":
    from .c81_model import main

    raise SystemExit(main())
