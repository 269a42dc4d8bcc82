"""The mode-name type: a root's name read by field, written once, parsed in one place.

The names are the paper's modes (``blade flap 1`` ... ``TEF``) and the marks
tefcore adds (a locked pair's second root, two roots that meet).  The text is
for tables and plots; the round trip text -> :class:`ModeName` -> text is
exact, so a table written and read back names the same roots.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

import tefcore
from tefcore.modes.names import (
    BLADE_FAMILIES,
    ModeName,
    base_name,
    how_named,
    is_locked,
    is_tef,
    locked_name,
    mode_kind,
    mode_pair,
    pair_text,
)

PACKAGE = Path(tefcore.__file__).resolve().parent

names = st.one_of(
    st.builds(ModeName, st.sampled_from(BLADE_FAMILIES), st.integers(1, 40), st.booleans()),
    st.builds(lambda locked: ModeName("TEF", 0, locked), st.booleans()))


@given(names)
def test_a_name_written_and_read_back_is_the_same_name(name):
    assert ModeName.parse(str(name)) == name
    assert base_name(str(name)) == str(name.base)
    assert is_locked(str(name)) == name.locked
    assert is_tef(str(name)) == name.is_tef
    assert mode_kind(str(name)) == name.family
    assert ModeName.parse(locked_name(str(name))) == name.base.locked_twin()


@given(names, names)
def test_a_meeting_is_written_in_one_order_and_read_back(a, b):
    text = pair_text(a, b)
    assert text == pair_text(b, a)
    assert set(mode_pair(text)) == {a, b}


@given(st.text(max_size=30))
def test_any_other_text_is_refused_with_the_form_it_should_have(text):
    try:
        name = ModeName.parse(text)
    except ValueError as err:
        assert "is not a root's name" in str(err) and repr(text) in str(err)
    else:        # only a real name parses, and it writes back as the same text
        assert str(name) == text


@pytest.mark.parametrize("text", ["blade flap 0", "blade bending 1", "TEF 1", "blade flap",
                                  "blade  flap 1", "tef", "blade flap 1 (locked) (locked)",
                                  "blade flap -1", "blade flap 1(locked)"])
def test_near_misses_are_not_names(text):
    with pytest.raises(ValueError, match="is not a root's name"):
        ModeName.parse(text)


def test_a_name_is_compared_by_its_fields():
    assert ModeName.parse("blade torsion 2 (locked)").base == ModeName("torsion", 2)
    assert ModeName.parse("blade flap 10") != ModeName.parse("blade flap 1")
    with pytest.raises(ValueError, match="numbered from 1"):
        ModeName("flap", 0)
    with pytest.raises(ValueError, match="not one of"):
        ModeName("bending", 1)


def test_how_a_name_was_decided_is_one_word():
    # an exceptional point on the path makes it ambiguous whatever else holds
    assert how_named(True, True, meets="TEF") == "ambiguous"
    assert how_named(False, False) == "ambiguous"
    assert how_named(False, True) == "nearest"
    assert how_named(True, True) == "continued"


# ------------------------------------------------------------------ one place

#: The marks tefcore writes into a name's text: what a reader of names would take apart.
MARKS = ("(locked)", " / ", "blade ", "TEF")
#: String methods that take a text apart by a mark.
TAKING_APART = {"split", "rsplit", "removesuffix", "removeprefix", "endswith", "startswith",
                "partition", "rpartition", "replace", "index", "find"}
#: Where names are parsed: the type itself.
HOME = PACKAGE / "modes" / "names.py"


def _sources():
    for path in sorted(PACKAGE.rglob("*.py")):
        if path != HOME:
            yield path


def _parsing_sites(tree: ast.AST) -> list[int]:
    """Lines that take a name's text apart: a string method called with a mark,
    or ``x.split()[i]`` on a label (the family by position)."""
    out = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in TAKING_APART):
            consts = [a.value for a in node.args if isinstance(a, ast.Constant)
                      and isinstance(a.value, str | tuple)]
            flat = [c for v in consts for c in (v if isinstance(v, tuple) else (v,))
                    if isinstance(c, str)]
            if any(m in c for c in flat for m in MARKS) or any(
                    c.strip() in ("(locked)", "blade", "TEF") for c in flat):
                out.append(node.lineno)
        if (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Call)
                and isinstance(node.value.func, ast.Attribute)
                and node.value.func.attr == "split" and not node.value.args
                and re.search(r"lab|name|origin|mode", ast.unparse(node.value.func.value))):
            out.append(node.lineno)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            for side in (node.left, node.right):
                if isinstance(side, ast.Constant) and isinstance(side.value, str) \
                        and "(locked)" in side.value:
                    out.append(node.lineno)
    return sorted(set(out))


def test_the_site_finder_finds_planted_parsing():
    planted = ast.parse(
        'a = name.removesuffix(" (locked)")\n'
        'b = lab.split()[1]\n'
        'c = pair.split(" / ")\n'
        'd = label.startswith("blade")\n'
        'e = base + " (locked)"\n'
        'f = path.removesuffix(".py")\n')
    assert _parsing_sites(planted) == [1, 2, 3, 4, 5]


def test_no_code_outside_the_type_takes_a_name_apart():
    found = []
    for path in _sources():
        for line in _parsing_sites(ast.parse(path.read_text(encoding="utf-8"))):
            found.append(f"{path.relative_to(PACKAGE)}:{line}")
    assert not found, "read names with tefcore.modes.names:\n" + "\n".join(found)
