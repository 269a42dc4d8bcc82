"""What the README shows is what tefcore does: every command and printed line is run here.

The README's fenced blocks are of three kinds, and each is checked:

* ``console``: ``$ tefcore ...`` lines, each followed by what it prints.  Each
  command runs in a fresh process (``python -m tefcore``) in an empty folder,
  and its standard output must be the lines shown -- doctest's ``ELLIPSIS``
  lets ``...`` stand for text left out or for a timing -- with nothing on
  standard error.
* ``python``: doctests, run in order in one namespace per file.
* ``bash``: the two commands of the quick start, which install packages and
  take minutes, so they are checked rather than run: the test command is
  exactly the one ``.ci/run`` runs, the extras they install exist, the paths
  they name exist, and the ``tefcore`` command parses.

``docs/guide.md``'s ``console`` and ``python`` blocks are run the same way (its
``bash`` blocks are illustrations: a dask cluster, long reproductions).  Every
inline ```tefcore ...``` command of the README is parsed by the command's own
parser, so a renamed subcommand or option fails here too.  The README's
picture is notebook 04's stored Fig. 9, byte for byte.

Outside a source checkout (an installed wheel has no README) these tests skip.
"""

from __future__ import annotations

import base64
import doctest
import json
import os
import re
import shlex
import subprocess
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

import pytest

import tefcore

REPO = Path(__file__).resolve().parents[1]
README = REPO / "README.md"
GUIDE = REPO / "docs" / "guide.md"

pytestmark = pytest.mark.skipif(not README.is_file(), reason="no README: not a source checkout")

#: The README is a front door: what tefcore is, two commands, what the result
#: means, a few examples, where to go next; the rest lives in docs/.
MAX_README_LINES = 200

#: Seconds a shown command may take before the test gives up on it (each takes
#: 1-3 s of CPU; a shared machine's load stretches the wall time several-fold).
COMMAND_TIMEOUT = 300

FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.M | re.S)


@dataclass(frozen=True)
class Block:
    """A fenced block: its file, language, first line number and text."""

    path: Path
    lang: str
    line: int
    text: str


def blocks(path: Path) -> list[Block]:
    """The fenced blocks of a markdown file, in order."""
    if not path.is_file():
        return []
    text = path.read_text(encoding="utf-8")
    return [Block(path, m.group(1), text.count("\n", 0, m.start()) + 2, m.group(2))
            for m in FENCE.finditer(text)]


def console_commands(block: Block) -> list[tuple[int, str, str]]:
    """``(line, command, shown output)`` for each ``$ `` line of a console block."""
    out = []
    for k, line in enumerate(block.text.splitlines()):
        if line.startswith("$ "):
            out.append([block.line + k, line[2:], []])
        else:
            assert out, f"{block.path.name}:{block.line + k}: output before any '$ ' command"
            out[-1][2].append(line)
    return [(n, cmd, "\n".join(lines) + "\n") for n, cmd, lines in out]


def shown_commands() -> list[tuple[str, int, str, str]]:
    """``(file name, line, command, shown output)`` of the README's and the guide's commands."""
    found = []
    for path in (README, GUIDE):
        for block in blocks(path):
            if block.lang == "console":
                found += [(path.name, n, cmd, want) for n, cmd, want in console_commands(block)]
    return found


def stripped(text: str) -> str:
    """Each line without trailing blanks (an editor strips them from the README)."""
    return "\n".join(line.rstrip() for line in text.splitlines()) + "\n"


def test_the_readme_is_a_front_door():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= MAX_README_LINES, (
        f"README.md has {len(lines)} lines, at most {MAX_README_LINES}: move detail to docs/")


def test_every_readme_block_is_checked():
    # a block of another kind would show something no test runs
    kinds = [b.lang for b in blocks(README)]
    assert set(kinds) <= {"console", "python", "bash"}, kinds
    assert kinds.count("bash") == 1 and "console" in kinds and "python" in kinds
    for block in blocks(README) + blocks(GUIDE):
        if block.lang == "python":
            assert ">>> " in block.text, f"{block.path.name}:{block.line}: code no test runs"


def test_the_shown_commands_are_found():
    # the collection below is only as good as this parse
    names = {(name, cmd.split()[1]) for name, _, cmd, _ in shown_commands()}
    assert {("README.md", "stability"), ("README.md", "simulate"),
            ("guide.md", "sweep")} <= names


@pytest.mark.parametrize("name, line, command, want",
                         [pytest.param(*c, id=f"{c[0]}:{c[1]}") for c in shown_commands()])
def test_a_shown_command_prints_what_is_shown(tmp_path, name, line, command, want):
    argv = shlex.split(command)
    assert argv[0] == "tefcore", f"{name}:{line}: only tefcore's commands are run here"
    env = dict(os.environ)
    # the tefcore under test, also when the process starts in another folder
    env["PYTHONPATH"] = os.pathsep.join(
        [str(Path(tefcore.__file__).resolve().parents[1])]
        + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    run = subprocess.run([sys.executable, "-m", "tefcore", *argv[1:]], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=COMMAND_TIMEOUT)
    assert run.returncode == 0, f"{name}:{line}: {command}\n{run.stderr}"
    assert run.stderr == "", f"{name}:{line}: {command} printed to stderr:\n{run.stderr}"
    checker = doctest.OutputChecker()
    got, shown = stripped(run.stdout), stripped(want)
    if not checker.check_output(shown, got, doctest.ELLIPSIS):
        example = doctest.Example(command, shown)
        pytest.fail(f"{name}:{line}: {command}\n"
                    + checker.output_difference(example, got, doctest.ELLIPSIS))


@pytest.mark.parametrize("path", [README, GUIDE], ids=lambda p: p.name)
def test_the_python_examples_run_as_shown(path):
    parser = doctest.DocTestParser()
    examples = []
    for block in blocks(path):
        if block.lang == "python":
            for ex in parser.get_examples(block.text):
                ex.lineno += block.line - 1
                examples.append(ex)
    assert examples, f"{path.name} shows no Python example"
    test = doctest.DocTest(examples, {}, path.name, str(path), 0, None)
    report = []
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    result = runner.run(test, out=report.append)
    assert result.failed == 0, "".join(report)


def quick_start() -> tuple[str, str]:
    """The README's two quick-start commands: (reproduce, test)."""
    (bash,) = [b for b in blocks(README) if b.lang == "bash"]
    lines = [ln for ln in bash.text.splitlines() if ln.strip() and not ln.startswith("#")]
    assert len(lines) == 2, lines
    return lines[0], lines[1]


def test_ci_runs_exactly_the_readme_test_command():
    _, test_command = quick_start()
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert test_command in ci, f".ci/run must run the README's test command:\n{test_command}"


def test_the_quick_start_commands_are_sound():
    from tefcore.cli import build_parser

    extras = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))[
        "project"]["optional-dependencies"]
    for command in quick_start():
        for group in re.findall(r'-e "\.\[([\w,]+)\]"', command):
            assert set(group.split(",")) <= set(extras), group
        for part in command.split(" && "):
            argv = shlex.split(part)
            if argv[0] == "tefcore":
                assert build_parser().parse_args(argv[1:]).command == "reproduce"
            elif argv[:3] == ["python", "-m", "pytest"]:
                for arg in argv[3:]:
                    if "/" in arg:
                        assert (REPO / arg).exists(), arg


def inline_commands() -> list[str]:
    """The README's inline ```tefcore ...``` spans."""
    text = README.read_text(encoding="utf-8") if README.is_file() else ""
    return sorted(set(re.findall(r"`(tefcore [^`]+)`", text)))


def test_inline_commands_are_found():
    assert "tefcore reproduce --out out" in inline_commands()


@pytest.mark.parametrize("command", inline_commands())
def test_an_inline_readme_command_parses(command, capsys):
    from tefcore.cli import build_parser

    try:
        build_parser().parse_args(shlex.split(command)[1:])
    except SystemExit as stop:                    # argparse's way to refuse (or --help)
        assert stop.code == 0, capsys.readouterr().err


def test_the_picture_is_notebook_04s_stored_figure_9():
    picture = REPO / "docs" / "fig09.png"
    assert "](docs/fig09.png)" in README.read_text(encoding="utf-8")
    nb = json.loads((REPO / "tefcore/paper/notebooks/04_cg_offset.ipynb").read_text("utf-8"))
    stored = next(base64.b64decode(out["data"]["image/png"])
                  for cell in nb["cells"] for out in cell.get("outputs", [])
                  if "image/png" in out.get("data", {}))
    assert picture.read_bytes() == stored, (
        "docs/fig09.png is not notebook 04's Fig. 9: after refreshing the notebooks, write "
        "the notebook's first PNG output to docs/fig09.png")


def test_the_readme_counts_are_the_recorded_statuses():
    # "N of the paper's M validation claims pass; F fail, A are ambiguous ...,
    # and R need data": the recorded statuses of the default rotor, which the
    # reproduction compares with (tefcore/paper/reference_data/claims.toml)
    from tefcore.paper.claims.reference import load_claims

    text = " ".join(README.read_text(encoding="utf-8").split())
    m = re.search(r"(\d+) of the paper's (\d+) validation claims pass; (\d+) fail, (\d+) are "
                  r"ambiguous .*?, and (\d+) need data", text)
    assert m, "the README no longer states the score in its usual sentence"
    passed, total, failed, ambiguous, missing = (int(g) for g in m.groups())
    recorded = [c.recorded_status for c in load_claims() if c.tag == "validation"]
    assert (passed, total, failed, ambiguous, missing) == (
        recorded.count("pass"), len(recorded), recorded.count("fail"),
        recorded.count("ambiguous"), recorded.count("not reproducible"))


def test_the_readme_score_of_the_inferred_rotor_is_its_recorded_one():
    # "(the variant `mdart-inferred`) passes N of M": its recorded statuses, the
    # claims it was fitted to (tagged calibration for it) counted with the rest
    from tefcore.paper.claims.reference import load_claims
    from tefcore.paper.claims.variants import load_variants

    text = " ".join(README.read_text(encoding="utf-8").split())
    m = re.search(r"\(the variant `mdart-inferred`\) passes (\d+) of (\d+)", text)
    assert m, "the README no longer states the inferred rotor's score"
    v = load_variants()["mdart-inferred"]
    validation = [c.id for c in load_claims() if c.tag == "validation"]
    passed = sum(v.recorded_status[i] == "pass" for i in validation)
    assert (int(m.group(1)), int(m.group(2))) == (passed, len(validation))
