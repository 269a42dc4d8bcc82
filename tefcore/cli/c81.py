"""``tefcore c81 check|example``: C81 airfoil decks checked, the example deck regenerated."""

from __future__ import annotations

import sys

from ..safe_io import check_outputs

__all__ = ["add_arguments", "run_check", "run_example"]


def run_example(args) -> int:
    """``tefcore c81 example``: write the example flap deck, into the current folder or ``--out``.

    The packaged copy (``tefcore/data/example_flap_generated.c81``) is written
    only when ``--out`` names it: a user's command never writes into the package.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``c81 example`` options.

    Returns
    -------
    int
        The exit status.
    """
    from ..aero.c81.format import write_c81
    from ..aero.c81.tables import example_deck_path, make_example_deck

    out = args.out or example_deck_path().name
    check_outputs([(out, "--out")])
    print(f"wrote {write_c81(make_example_deck(), out)}")
    return 0


def _unreadable(path) -> str | None:
    """Why `path` cannot be read as a deck, or None when it can."""
    import os

    if os.path.isfile(path):
        return None if os.access(path, os.R_OK) else "no permission to read it"
    if os.path.islink(path):
        return "a link to a missing file"
    if os.path.isdir(path):
        return "a folder"
    return "not a file" if os.path.exists(path) else "no such file"


def run_check(args) -> int:
    """``tefcore c81 check``: parse each deck, print its summary or its first problem.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``c81 check`` options.

    Returns
    -------
    int
        0, or 1 when a deck is bad (each problem one ``tefcore: error:`` line).

    Raises
    ------
    OSError
        A FILE that is missing or not a readable file, before any is parsed.
    """
    from ..aero.c81.format import COEFFICIENT_LABELS, C81FormatError
    from ..aero.c81.reader import read_c81

    for f in args.files:                    # every file there before any is parsed
        if (why := _unreadable(f)) is not None:
            raise OSError(f"c81 check: FILE {f}: cannot read it ({why})")
    status = 0
    for f in args.files:
        try:
            deck = read_c81(f)
        except C81FormatError as exc:       # names the file, line and column
            print(f"tefcore: error: c81 check: {exc}", file=sys.stderr)
            status = 1
            continue
        except OSError as exc:              # gone or unreadable since it was checked
            print(f"tefcore: error: c81 check: {f}: cannot read the C81 deck "
                  f"({exc.strerror or exc})", file=sys.stderr)
            status = 1
            continue
        kind = f"flap deck, {deck.delta.size} deltas" if deck.is_flap else "blade deck"
        sizes = ", ".join(f"{COEFFICIENT_LABELS[c]} {deck.alpha[c].size}x{deck.mach[c].size}"
                          for c in deck.coefficients)
        print(f"{f}: {deck.name!r} ({kind}; alpha x Mach: {sizes})")
    return status


def add_arguments(sub, add) -> None:
    """Add ``c81`` and its ``check`` and ``example`` to the ``tefcore`` parser.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommands of the ``tefcore`` parser.
    add : callable
        Makes one subcommand in the house style (``tefcore.cli``).
    """
    p = add(sub, "c81", "C81 airfoil decks: check decks, regenerate the example deck",
            "C81 airfoil decks (layout: docs/c81_format.md).", None, common=False)
    c81 = p.add_subparsers(dest="c81_command", required=True, metavar="C81COMMAND",
                           title="subcommands")
    q = add(c81, "check", "parse decks and print a one-line summary of each",
            "Parse each deck and print its summary, or its first problem with file, line "
            "and column. Exit status 1 when a deck is bad.", run_check, common=False)
    q.add_argument("files", nargs="+", metavar="FILE", help="C81 deck (blade or flap)")
    q = add(c81, "example", "write the example flap deck (the packaged one's source)",
            "Write the example flap deck, tabulated from the thin-airfoil model of the "
            "MDART flap (GENERATED data, not test data). The package ships it as "
            "tefcore/data/example_flap_generated.c81; give that path as --out to "
            "regenerate it.", run_example, common=False)
    q.add_argument("--out", default=None, help="output file (default: "
                                                "example_flap_generated.c81 in the current "
                                                "folder)")
