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
  outside a table: :class:`C81RangeWarning` / :class:`C81RangeError`),
  :func:`generate_flap_deck` and the packaged example deck.
* ``tefcore c81 example|check`` (:mod:`tefcore.cli`) regenerates the example
  deck and checks decks.

This module gathers the public names of :mod:`tefcore.aero.c81.format` (the deck,
its errors, the writer), :mod:`tefcore.aero.c81.reader` (the parser) and
:mod:`tefcore.aero.c81.tables` (the table models).

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

from .format import (
    BLADE_COEFFICIENTS,
    COEFFICIENT_LABELS,
    COEFFICIENTS,
    PLAUSIBLE_MAX,
    C81Deck,
    C81FormatError,
    C81PlausibilityWarning,
    C81RangeError,
    C81RangeWarning,
    format_c81,
    write_c81,
)
from .reader import parse_c81, read_c81
from .tables import (
    EXAMPLE_DECK_NAME,
    C81Airfoil,
    C81FlapTable,
    example_deck_path,
    generate_flap_deck,
    make_example_deck,
    xfoil_deck_path,
)

__all__ = [
    "BLADE_COEFFICIENTS",
    "COEFFICIENTS",
    "COEFFICIENT_LABELS",
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
    "xfoil_deck_path",
    "format_c81",
    "generate_flap_deck",
    "make_example_deck",
    "parse_c81",
    "read_c81",
    "write_c81",
]
