"""Every OS error from the command line names the path and what was being done.

A full disk is met for real: the command runs in a child process whose
largest file is limited (``RLIMIT_FSIZE``, with ``SIGXFSZ`` ignored), so a
write past the limit fails with ``EFBIG`` ("File too large") exactly where a
full disk fails with ``ENOSPC``: inside ``os.write`` or a buffered flush,
where Python's error carries no file name.
"""

import json
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tefcore.aero.c81 import example_deck_path
from tefcore.cli import main

#: Largest file of the child [bytes]: a sweep header (~400 B) fits, a point record
#: (the modes, trim and shapes: ~20 kB, measured) does not; a mode table's CSV does not.
FILE_LIMIT = 1500


def _limited():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_LIMIT, FILE_LIMIT))


def run_limited(args, cwd):
    return subprocess.run([sys.executable, "-m", "tefcore", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300, preexec_fn=_limited)


def one_error_line(err: str) -> str:
    assert err.startswith("tefcore: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and "[Errno" not in err, err
    return err


def test_a_full_disk_while_appending_a_sweep_point_names_the_file(tmp_path):
    """A full disk names the file, not a bare ``[Errno 28] No space left on device``."""
    r = run_limited(["sweep", "flap.cg_offset", "--values", "0", "0.1", "--quiet",
                     "--out", "s.jsonl", "--csv", "s.csv"], tmp_path)
    assert r.returncode == 2
    err = one_error_line(r.stderr)
    assert "sweep file s.jsonl" in err and "cannot append" in err and "File too large" in err
    # nothing is lost: the header is whole, and the file resumes (the cut-short line dropped)
    head = json.loads((tmp_path / "s.jsonl").read_text().splitlines()[0])
    assert head["format"] == "tefcore.sweep"


def test_a_full_disk_while_writing_a_table_names_the_file(tmp_path):
    (tmp_path / "modes.csv").write_text("old table\n")
    r = run_limited(["stability", "--csv", "modes.csv"], tmp_path)
    assert r.returncode == 2
    err = one_error_line(r.stderr)
    assert "--csv modes.csv" in err and "cannot write" in err and "File too large" in err
    assert (tmp_path / "modes.csv").read_text() == "old table\n"      # unchanged
    assert sorted(p.name for p in tmp_path.iterdir()) == ["modes.csv"]  # no temporary file


def test_atomic_output_names_the_file_when_the_disk_is_full(tmp_path, monkeypatch):
    import errno
    import os

    from tefcore.errors import OutputError
    from tefcore.safe_io import atomic_write_text

    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    with pytest.raises(OutputError, match=r"report \S*/r\.md: cannot write it \(No space left"):
        atomic_write_text(tmp_path / "r.md", "text", what="report")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("make, reason", [
    (lambda p: p.mkdir(), "a folder"),
    (lambda p: p.symlink_to(p.parent / "nowhere.c81"), "a link to a missing file"),
    (lambda p: None, "no such file"),
])
def test_c81_check_of_a_folder_or_a_dangling_link_names_it(tmp_path, capsys, make, reason):
    """A folder or a dangling link is an error before any deck is read, with the
    ``tefcore: error:`` prefix, naming it (not a raw ``[Errno 21] Is a directory``)."""
    target = tmp_path / "deck.c81"
    make(target)
    assert main(["c81", "check", str(example_deck_path()), str(target)]) == 2
    out, err = capsys.readouterr()
    assert err == f"tefcore: error: c81 check: FILE {target}: cannot read it ({reason})\n"
    assert out == ""                                # checked before any deck is parsed


def test_an_unreadable_parameters_file_says_what_it_is(tmp_path, capsys):
    folder = tmp_path / "params.yaml"
    folder.mkdir()
    assert main(["reproduce", "--params", str(folder), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err == (f"tefcore: error: {folder}: cannot read the parameters file "
                   "(Is a directory)\n")
    assert not Path(tmp_path / "o").exists()
