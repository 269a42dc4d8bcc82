"""C81 airfoil decks: the parser.

:func:`read_c81` / :func:`parse_c81` read a standard blade C81 deck (C_l,
C_d, C_m versus alpha and Mach) or a tefcore *flap deck* (the five
coefficients versus alpha, Mach and delta) into a
:class:`~tefcore.aero.c81.format.C81Deck`; the layout is specified in
``docs/c81_format.md``.  Every problem with a file's content -- layout,
numbers, counts, encoding (not UTF-8) -- is a
:class:`~tefcore.aero.c81.format.C81FormatError` naming the file, the 1-based
line and column and what was expected.  The counts on the title line are
checked against the number of lines in the file before anything is
allocated.  Coefficients far outside the physical range of airfoil data
(:data:`~tefcore.aero.c81.format.PLAUSIBLE_MAX`, e.g. ``.01000`` mistyped as
``01000``) give one :class:`~tefcore.aero.c81.format.C81PlausibilityWarning`
naming the first such number.

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
from pathlib import Path

import numpy as np

from .format import (
    BLADE_COEFFICIENTS,
    COEFFICIENT_LABELS,
    COEFFICIENTS,
    DELTA_KEY,
    DELTAS_KEY,
    FIELD,
    NAME_WIDTH,
    PER_LINE,
    PLAUSIBLE_MAX,
    C81Deck,
    C81FormatError,
    C81PlausibilityWarning,
)

__all__ = ["parse_c81", "read_c81"]

_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eEdD][+-]?[0-9]+)?\Z")
_NONFINITE = re.compile(r"[+-]?(?:nan|inf|infinity)\Z", re.IGNORECASE)
_TOKEN = re.compile(r"\S+")


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
        where = f"the {COEFFICIENT_LABELS[coef]} table{context}"
        mach = self.values_over_lines(
            n_mach, [f"Mach number {j + 1} of {n_mach} of {where}" for j in range(n_mach)],
            expected=f"the Mach numbers of {where}")
        self.increasing(mach, "the Mach numbers", where)
        machs = [v for v, _, _ in mach]
        alphas, rows = [], []
        for r in range(n_alpha):
            what = ["alpha (deg)"]
            label = COEFFICIENT_LABELS[coef]
            what += [f"{label} at M = {mm:g} in row {r + 1}{context}" for mm in machs]
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

    Parameters
    ----------
    text : str
        The deck.
    filename : str, optional
        For messages.

    Returns
    -------
    C81Deck

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
                            raise rd.error(ln2, col, f"the {label} of the {COEFFICIENT_LABELS[c]} "
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

    Parameters
    ----------
    path : str or os.PathLike
        The deck (UTF-8 text).

    Returns
    -------
    C81Deck

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
