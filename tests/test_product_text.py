"""The product speaks of the product: no file tells how it was made.

A comment, docstring, doc page or notebook says what is measured and why, in
the present tense of the product; the history of the work (numbered work
items, milestones, review notes) belongs in commit messages. These tests fail
on such a reference in any file git tracks (``git ls-files`` from the
repository root: the check ``git ls-files | xargs grep -E PATTERN`` makes), and
in the package's own files, which is what an installed wheel has to check when
there is no git checkout.

The pattern is assembled from pieces, so that this file, which must spell it,
does not match it itself.
"""

import re
import shutil
import subprocess
from pathlib import Path

import pytest

import tefcore

REPO = Path(__file__).resolve().parents[1]
PACKAGE = Path(tefcore.__file__).resolve().parent

#: What the history of the work looks like in text: a numbered milestone, a
#: numbered work item, a note of what a review turned up, a week of the calendar.
PIECES = (
    "[Ss]" + "tops? [0-9]+",
    "[Ii]" + "ssues? #?[0-9]+",
    "found .*" + "rev" + "iew",
    "[Tt]his" + " week",
)
PATTERN = re.compile("|".join(PIECES).encode())


def offending_lines(paths, root: Path) -> list[str]:
    """``path:line: text`` for every line of `paths` (relative to `root`) the pattern finds."""
    found = []
    for rel in paths:
        path = root / rel
        if not path.is_file() or path.is_symlink():
            continue
        for number, line in enumerate(path.read_bytes().splitlines(), 1):
            if PATTERN.search(line):
                text = line.decode("utf-8", "replace").strip()[:120]
                found.append(f"{rel}:{number}: {text}")
    return found


def tracked_files() -> list[str] | None:
    """The files git tracks in the repository, or None outside a git checkout."""
    git = shutil.which("git")
    if git is None or not (REPO / ".git").exists():
        return None
    out = subprocess.run([git, "ls-files", "-z"], cwd=REPO, capture_output=True)
    if out.returncode != 0:
        return None
    return [p for p in out.stdout.decode("utf-8", "surrogateescape").split("\0") if p]


def test_the_pattern_finds_history_and_leaves_physics_alone():
    # planted: each kind of reference the pattern exists for, and plain text
    # that merely shares a word with it
    history = ["measured at s" + "top 35: 3-4 ms", "goals of i" + "ssue 25",
               "(I" + "ssue #13)", "found in a differential r" + "eview",
               "measured t" + "his week"]
    product = ["the march stops after 6 revolutions", "an issue of units",
               "a reviewer's first question", "found at 0.33 c_f",
               "Stop the sweep with Ctrl-C"]
    assert all(PATTERN.search(s.encode()) for s in history)
    assert not any(PATTERN.search(s.encode()) for s in product)


def test_no_tracked_file_tells_its_history():
    files = tracked_files()
    if files is None:
        pytest.skip("not a git checkout (an installed package): the package's files "
                    "are checked by the test below")
    assert len(files) > 100                   # the listing really is the repository's
    found = offending_lines(files, REPO)
    assert not found, ("say what is measured and why, in the present; history goes in "
                       "commit messages:\n" + "\n".join(found))


def test_no_package_file_tells_its_history():
    files = [p.relative_to(PACKAGE) for p in PACKAGE.rglob("*")
             if "__pycache__" not in p.parts]
    assert any(p.suffix == ".ipynb" for p in files)      # the notebooks are seen too
    found = offending_lines(files, PACKAGE)
    assert not found, "\n".join(found)
