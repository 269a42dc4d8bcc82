"""Outputs are atomic, never written through a link, and locked.

The sweeps use the fast synthetic point function of ``test_sweep`` (``ToyPoint``).
"""

import json
import os
import shutil
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from tefcore.paper.run import reproduce as rp
from tefcore.sweeps.sweep import sweep
from tests.sweeps.test_sweep import MDART, PARAM, XS, ToyPoint, run

REPO = Path(__file__).resolve().parents[1]   # for `import tests...` in subprocesses


def lines(path):
    return [json.loads(x) for x in Path(path).read_text().splitlines()]


# ------------------------------------------------------------------ links


def test_sweep_does_not_write_through_a_planted_temp_link(tmp_path):
    """``ln -s victim.txt s.jsonl.tmp`` does not make the sweep overwrite victim.txt."""
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    (tmp_path / "s.jsonl.tmp").symlink_to(victim)
    out = tmp_path / "s.jsonl"
    run([0.0], out=out)
    assert victim.read_text() == "precious\n"
    assert not out.is_symlink() and lines(out)[0]["format"] == "tefcore.sweep"
    # no temporary file is left next to it either
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.jsonl", "s.jsonl.lock",
                                                          "s.jsonl.tmp", "victim.txt"]


def test_a_sweep_file_that_is_a_link_is_refused_untouched(tmp_path):
    real = tmp_path / "real.jsonl"
    run([0.0], out=real)
    before = real.read_bytes()
    link = tmp_path / "link.jsonl"
    link.symlink_to(real)
    with pytest.raises(OSError, match="symbolic link"):
        run([0.0, 0.5], out=link)          # would append the point 0.5 through the link
    assert real.read_bytes() == before


def test_tables_and_text_are_never_written_through_links(tmp_path):
    from tefcore.safe_io import atomic_write_text

    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    for name in ("t.csv", "r.md"):
        (tmp_path / name).symlink_to(victim)
    with pytest.raises(OSError, match="symbolic link"):
        run([0.0]).to_csv(tmp_path / "t.csv")
    with pytest.raises(OSError, match="symbolic link"):
        atomic_write_text(tmp_path / "r.md", "report")
    assert victim.read_text() == "precious\n"


def test_atomic_output_keeps_the_old_file_when_writing_fails(tmp_path):
    from tefcore.safe_io import atomic_output, atomic_write_text

    target = tmp_path / "t.csv"
    target.write_text("old\n")
    os.chmod(target, 0o640)
    with pytest.raises(RuntimeError), atomic_output(target) as f:
        f.write("half a table")
        raise RuntimeError("disk full")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["t.csv"]   # the temporary file is gone
    atomic_write_text(target, "new\n")
    assert target.read_text() == "new\n" and (target.stat().st_mode & 0o777) == 0o640


@pytest.mark.parametrize("make, match", [
    (lambda p: None, "folder .* does not exist"),
    (lambda p: p.mkdir(parents=True), "is a folder"),
])
def test_output_destinations_are_checked(tmp_path, make, match):
    from tefcore.safe_io import check_output_file

    target = tmp_path / "nodir" / "x.csv"
    make(target)
    with pytest.raises(OSError, match=match):
        check_output_file(target, "--csv")


# ------------------------------------------------------------------ reproduce


def _fake_reproduce(monkeypatch):
    """reproduce's computing replaced by fakes that write what it would write."""
    def fake_run(out, params, names, progress=True, nb_dir=None, kernel_name="python3",
                 jobs=None, stop=None):
        (out / "notebooks").mkdir(parents=True, exist_ok=True)
        for name in names:             # what papermill does: write the executed notebook
            (out / "notebooks" / f"{name}.ipynb").write_text("EXECUTED")
        return []

    monkeypatch.setattr(rp, "run_notebooks", fake_run)
    monkeypatch.setattr(rp, "baseline_blade", lambda out, cfg=None: None)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])


@pytest.fixture
def fake_repo(tmp_path, monkeypatch):
    """A tefcore source checkout as it is laid out (pyproject.toml naming the project,
    the package, the notebooks in tefcore/paper/notebooks/), as the working folder;
    reproduce's computing replaced by fakes."""
    repo = tmp_path / "repo"
    nb = repo / "tefcore" / "paper" / "notebooks"
    nb.mkdir(parents=True)
    (repo / "tefcore" / "__init__.py").write_text("")
    (repo / "pyproject.toml").write_text('[project]\nname = "tefcore"\nversion = "0.1.0"\n')
    src = nb / "04_cg_offset.ipynb"
    src.write_text("SOURCE NOTEBOOK")
    _fake_reproduce(monkeypatch)
    monkeypatch.setenv("TEFCORE_NOTEBOOKS", str(nb))
    monkeypatch.chdir(repo)
    return repo, src


def _tree(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@pytest.mark.parametrize("out", [".", "output", "tefcore/paper/notebooks", "tefcore",
                                 "tefcore/paper/notebooks/.."])
def test_reproduce_refuses_any_folder_in_a_source_checkout(fake_repo, out):
    """``--out .`` in the repository root is refused: looking for tracked files alone is
    not enough, as none of the output names are tracked (the notebooks live in
    tefcore/paper/notebooks/)."""
    repo, src = fake_repo
    before = _tree(repo)
    with pytest.raises(OSError, match=r"inside the tefcore source checkout .*repo"):
        rp.reproduce(Path(out), notebooks=["04"], progress=False)
    assert src.read_text() == "SOURCE NOTEBOOK"
    assert _tree(repo) == before                        # refused before writing anything


def test_a_checkout_is_found_by_its_package_without_a_pyproject(fake_repo):
    repo, _ = fake_repo
    (repo / "pyproject.toml").unlink()
    with pytest.raises(OSError, match="inside the tefcore source checkout"):
        rp.check_reproduce_folder(repo / "output", ["04_cg_offset"])


def test_another_project_is_not_a_tefcore_checkout(tmp_path, monkeypatch):
    _fake_reproduce(monkeypatch)
    other = tmp_path / "other"
    other.mkdir()
    (other / "pyproject.toml").write_text('[project]\nname = "not-tefcore"\n')
    assert rp.check_reproduce_folder(other / "out", ["04_cg_offset"]) == other / "out"
    (other / "pyproject.toml").write_text("[project\n")     # unreadable: not tefcore's either
    assert rp.check_reproduce_folder(other / "out", ["04_cg_offset"]) == other / "out"


def test_reproduce_never_writes_over_copied_source_notebooks(tmp_path, monkeypatch):
    # notebooks copied for editing (tefcore notebooks --copy), outside any checkout
    _fake_reproduce(monkeypatch)
    nb = tmp_path / "mine" / "notebooks"
    nb.mkdir(parents=True)
    (nb / "04_cg_offset.ipynb").write_text("MY NOTEBOOK")
    monkeypatch.setenv("TEFCORE_NOTEBOOKS", str(nb))
    with pytest.raises(OSError, match="overwrite the source notebooks"):
        rp.reproduce(tmp_path / "mine", notebooks=["04"], progress=False)
    assert (nb / "04_cg_offset.ipynb").read_text() == "MY NOTEBOOK"


def test_reproduce_refuses_the_filesystem_root(capsys):
    """``--out /`` is refused."""
    from tefcore.cli import main

    with pytest.raises(OSError, match="filesystem root"):
        rp.check_reproduce_folder(Path("/"), ["04_cg_offset"])
    assert main(["reproduce", "--out", "/", "--only", "04"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("tefcore: error: reproduce --out /: ") and err.count("\n") == 1


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_reproduce_refuses_a_folder_with_tracked_outputs(fake_repo, tmp_path):
    repo, _ = fake_repo
    out = tmp_path / "other"
    out.mkdir()
    (out / "report.md").write_text("tracked report")
    git = ["git", "-C", str(out), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "report.md"], check=True)
    with pytest.raises(OSError, match=r"tracked by git: report\.md"):
        rp.reproduce(out, notebooks=["04"], progress=False)
    assert (out / "report.md").read_text() == "tracked report"
    # an untracked folder inside the work tree is fine
    assert rp.check_reproduce_folder(out / "output", ["04_cg_offset"]) == out / "output"


# ------------------------------------------------------------------ one writer


SLOW_SWEEP = """
import sys, time
sys.path.insert(0, {repo!r})
from tests.sweeps.test_sweep import MDART, PARAM, XS, ToyPoint
from tefcore.sweeps.sweep import sweep

class SlowPoint(ToyPoint):
    def __call__(self, cfg):
        time.sleep(0.2)
        return super().__call__(cfg)

sweep(MDART, PARAM, XS[:6], point=SlowPoint(), out={out!r}, progress=False)
"""


def test_a_second_sweep_of_the_same_file_fails_clearly(tmp_path):
    """Two sweeps on one --out file: the second fails at once, no duplicate records."""
    out = tmp_path / "s.jsonl"
    script = tmp_path / "slow.py"
    script.write_text(textwrap.dedent(SLOW_SWEEP).format(repo=str(REPO), out=str(out)))
    first = subprocess.Popen([sys.executable, str(script)], stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while not (out.exists() and out.stat().st_size) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert out.exists(), "the first sweep did not start"
        with pytest.raises(OSError, match="being written by another process"):
            run(XS[:6], out=out)
    finally:
        assert first.wait(timeout=120) == 0, first.stderr.read()
    keys = [rec["key"] for rec in lines(out)[1:]]
    assert keys == [repr(float(x)) for x in XS[:6]]    # every point once, no duplicates


def test_the_lock_is_released_after_a_sweep_and_on_errors(tmp_path):
    from tefcore.safe_io import FileLock

    out = tmp_path / "s.jsonl"
    with FileLock(out), pytest.raises(OSError, match=r"another process \(lock .*process"):
        run([0.0], out=out)
    run([0.0], out=out)                                  # released: works
    with pytest.raises(KeyboardInterrupt):
        run(XS[:3], out=out, point=ToyPoint(interrupt_after=1))
    res = sweep(MDART, PARAM, XS[:3], point=ToyPoint(), out=out, progress=False)
    assert (res.n_loaded, res.n_computed) == (1, 2)     # the point before Ctrl-C was kept
