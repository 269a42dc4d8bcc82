"""Usage errors of every subcommand: one line, exit status 2, never a traceback.

Every subcommand of :func:`tefcore.cli.build_parser` (walked from the parser
itself, so a new subcommand is covered without editing this file) is driven
with a missing argument and with an extra one.
"""

import argparse
import subprocess
import sys

import pytest

from tefcore.cli import build_parser, main


def _leaves(parser, path=()):
    """``(path, parser)`` of every subcommand that runs something."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, parser
        return
    for name, sub in subs[0].choices.items():
        yield from _leaves(sub, (*path, name))


LEAVES = dict(_leaves(build_parser()))


def _positionals(parser):
    return [a for a in parser._actions if not a.option_strings and a.nargs != 0]


def _filled(parser) -> list[str]:
    """Placeholder values for the positionals (parsing stops before any command runs)."""
    out = []
    for action in _positionals(parser):
        n = action.nargs if isinstance(action.nargs, int) else 1
        out += ["1"] * n
    return out


def one_usage_line(capsys, *expected):
    err = capsys.readouterr().err
    assert err.startswith("tefcore: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and "usage:" not in err, err
    for text in expected:
        assert text in err, err
    return err


def test_every_subcommand_is_covered():
    # the walk finds the nested ones (c81 check, c81 example) and the paper's
    assert {"map", "sweep", "c81 check", "c81 example", "reproduce", "batch",
            "notebooks"} <= {" ".join(p) for p in LEAVES}


@pytest.mark.parametrize("path", sorted(LEAVES), ids=" ".join)
def test_an_extra_argument_is_one_usage_line(path, capsys):
    parser = LEAVES[path]
    assert main([*path, *_filled(parser), "--no-such-option"]) == 2
    one_usage_line(capsys, "unrecognized arguments: --no-such-option")


@pytest.mark.parametrize("path", sorted(LEAVES), ids=" ".join)
def test_a_missing_argument_is_one_usage_line(path, capsys):
    parser = LEAVES[path]
    positionals = _positionals(parser)
    if positionals:
        # the positionals all missing: each is named by its metavar
        assert main(list(path)) == 2
        names = [m for a in positionals
                 for m in (a.metavar if isinstance(a.metavar, tuple) else [a.metavar or a.dest])]
        one_usage_line(capsys, "the following arguments are required: " + ", ".join(names))
    # an option without its value
    options = [a for a in parser._actions if a.option_strings and a.nargs != 0]
    assert positionals or options, f"{path}: nothing can be missing"
    for option in options:
        assert main([*path, *_filled(parser), option.option_strings[-1]]) == 2
        one_usage_line(capsys, f"argument {'/'.join(option.option_strings)}: expected")


def test_map_with_a_range_cut_short_names_what_is_missing(capsys):
    """One usage line, exit 2, not a traceback from argparse's usage of tuple metavars."""
    assert main(["map", "flap.cg_offset", "0", "0.4", "5", "flap.overhang", "0", "0.4"]) == 2
    one_usage_line(capsys, "map: the following arguments are required: Y_NUM",
                   "tefcore map --help")
    assert main(["map"]) == 2
    one_usage_line(capsys, "required: x_field, X_START, X_STOP, X_NUM, y_field, Y_START, "
                           "Y_STOP, Y_NUM")


def test_a_bad_map_count_is_named_by_its_argument(capsys):
    """The map's messages said ``--range NUM``, an option the map does not have."""
    assert main(["map", "flap.cg_offset", "0", "0.4", "five", "flap.overhang", "0", "0.4",
                 "2"]) == 2
    err = one_usage_line(capsys, "X_NUM must be an integer", "'five'")
    assert "--range" not in err
    assert main(["map", "flap.cg_offset", "0", "0.4", "2", "flap.overhang", "0", "0.4",
                 "0"]) == 2
    one_usage_line(capsys, "Y_NUM must be an integer")


def test_usage_errors_in_a_fresh_process():
    # the console entry point, as a user meets it: one line on stderr, status 2
    r = subprocess.run([sys.executable, "-m", "tefcore", "map", "flap.cg_offset"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.startswith("tefcore: error: map: the following arguments are required: "
                               "X_START, X_STOP") and r.stderr.count("\n") == 1, r.stderr


def test_help_and_version_still_exit_zero():
    r = subprocess.run([sys.executable, "-m", "tefcore", "map", "--help"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "X_START X_STOP X_NUM" in r.stdout
