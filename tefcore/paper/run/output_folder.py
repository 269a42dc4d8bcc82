"""The reproduction's output folder: checked, locked, written beside and swapped in whole.

:func:`check_reproduce_folder` runs before any notebook does (``tefcore
reproduce`` and ``tefcore batch``), so a refused destination costs nothing:
never over sources, tracked files, links or the root.

:class:`ReproductionFolder` is how ``tefcore reproduce`` writes ``OUT``:

* one run at a time: a lock on ``.OUT.lock`` beside the folder
  (:class:`tefcore.safe_io.FileLock`); a second run is refused at once with
  the folder and the process that holds it;
* ``OUT`` is empty, missing, or a previous reproduction (its
  :data:`MARKER`, or, from a version without one, nothing but the names a
  reproduction writes); any other folder is refused, and so is a previous
  reproduction holding a file no reproduction writes (it would be deleted);
* the run writes into ``OUT.incomplete`` beside it (with :data:`INCOMPLETE`
  saying so) and, once everything is written, swaps it with ``OUT`` in one
  step (Linux ``renameat2(RENAME_EXCHANGE)``; elsewhere two renames) and
  deletes the previous result.  A run killed at any moment leaves ``OUT``
  as it was -- the previous result whole, or no folder -- and its partial
  work in ``OUT.incomplete``, which the next run removes.

Examples
--------
>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "out"
>>> with ReproductionFolder(out) as folder:
...     _ = (folder.staging / "report.md").write_text("new")
...     _ = folder.commit({"notebooks": ["04_cg_offset"]})
>>> sorted(p.name for p in out.iterdir())
['report.md', 'reproduction.json']
>>> with ReproductionFolder(out):
...     ReproductionFolder(out).__enter__()  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
tefcore.errors.OutputError: reproduce --out ...out: another tefcore reproduce (process ...) ...
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import json
import os
import re
import shutil
import sys
from pathlib import Path

from ...errors import OutputError
from ...safe_io import FileLock, atomic_write_text, check_output_file, check_output_folder
from .notebook_files import NOTEBOOKS, notebooks_dir

__all__ = ["INCOMPLETE", "MARKER", "ReproductionFolder", "check_reproduce_folder",
           "previous_reproduction", "source_checkout"]

#: The file that makes a folder a reproduction's: what ran (written last, before the swap).
MARKER = "reproduction.json"
#: The file in a reproduction still being written (``OUT.incomplete``).
INCOMPLETE = "INCOMPLETE.txt"
#: The names a reproduction writes at the top of its folder.
_WRITTEN = re.compile(r"(report\.(md|html)|claims(-variants)?\.csv|attribution\.(csv|json)"
                      r"|mdart_(modes|frequency_checks)\.csv|mdart_fanplot\.(png|json)"
                      r"|notebooks|variants|\d\d_\w+|" + re.escape(MARKER) + ")")


def _tracked_files(paths: list[Path]) -> list[str]:
    """Those of `paths` (files or folders) tracked by git; [] outside a work tree, or no git."""
    import subprocess

    probe = next((p for p in (paths[0], *paths[0].parents) if p.is_dir()), None)
    if probe is None:
        return []
    try:
        top = subprocess.run(["git", "-C", str(probe), "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True, timeout=30)
        if top.returncode != 0:
            return []
        root = Path(top.stdout.strip()).resolve()
        rel = [str(p.relative_to(root)) for p in paths if p.is_relative_to(root)]
        if not rel:
            return []
        listed = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--", *rel],
                                capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return []
    return [f for f in listed.stdout.split("\0") if f] if listed.returncode == 0 else []


def _names_tefcore(pyproject: Path) -> bool:
    """Whether `pyproject` is a readable ``pyproject.toml`` whose project is tefcore."""
    import tomllib

    try:
        name = tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]["name"]
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError, KeyError, TypeError):
        return False
    return isinstance(name, str) and name.strip().lower().replace("_", "-") == "tefcore"


def source_checkout(folder) -> Path | None:
    """The tefcore source checkout (or installed package's folder) `folder` is in, or None.

    Walks up from `folder` (resolved) to the filesystem root: a folder is a
    checkout when its ``pyproject.toml`` names the project ``tefcore``, or
    when it holds the package (``tefcore/__init__.py`` beside
    ``tefcore/paper/``, as in a checkout or an installation).

    Parameters
    ----------
    folder : path
        A folder (it need not exist).

    Returns
    -------
    pathlib.Path or None
    """
    folder = Path(folder).resolve()
    for above in (folder, *folder.parents):
        package = above / "tefcore"
        if _names_tefcore(above / "pyproject.toml") or (
                (package / "__init__.py").is_file() and (package / "paper").is_dir()):
            return above
    return None


def check_reproduce_folder(out, names=NOTEBOOKS, nb_dir: Path | None = None) -> Path:
    """Refuse an output folder whose files would overwrite sources; return it resolved.

    ``reproduce`` writes ``OUT/notebooks/<name>.ipynb`` (and ``.html``),
    ``OUT/<name>/`` and the report files.  Refused
    (:class:`~tefcore.errors.OutputError`, before anything runs): the
    filesystem root; any folder inside a tefcore source checkout or the
    installed package (:func:`source_checkout`); ``OUT/notebooks`` is the
    folder of the source notebooks; any file that would be written is
    tracked by git; a destination is a link or a folder.

    Parameters
    ----------
    out : path
        The output folder.
    names : sequence of str
        The notebooks to run.
    nb_dir : path, optional
        The source notebooks' folder.
    """
    given = out
    out = Path(out).resolve()
    if out == Path(out.anchor):
        raise OutputError(f"reproduce --out {given}: refusing to write into the filesystem "
                          "root; choose an output folder (default: output)")
    checkout = source_checkout(out)
    if checkout is not None:
        raise OutputError(f"reproduce --out {given}: {out} is inside the tefcore source "
                          f"checkout {checkout}; write the reproduction outside it (e.g. "
                          f"--out {checkout.parent / 'tefcore-output'})")
    if out.exists() or out.is_symlink():
        check_output_folder(out, "reproduce --out")
    nb_dir = (nb_dir or notebooks_dir()).resolve()
    if (out / "notebooks").resolve() == nb_dir or out.resolve() == nb_dir:
        raise OutputError(f"reproduce --out {out}: the executed notebooks would overwrite the "
                          f"source notebooks in {nb_dir}; choose another output folder "
                          "(default: output)")
    files = [out / f for f in ("report.md", "report.html", "claims.csv", "claims-variants.csv",
                               "attribution.csv", "attribution.json",
                               "mdart_modes.csv",
                               "mdart_frequency_checks.csv", "mdart_fanplot.png")]
    files += [out / "notebooks" / f"{n}{ext}" for n in names for ext in (".ipynb", ".html")]
    tracked = _tracked_files(files + [out / n for n in names])
    if tracked:
        shown = ", ".join(tracked[:3]) + (f" and {len(tracked) - 3} more" if len(tracked) > 3
                                          else "")
        raise OutputError(f"reproduce --out {out} would overwrite file(s) tracked by git: "
                          f"{shown}; choose another output folder (default: output)")
    for f in files:
        if f.exists() or f.is_symlink():
            check_output_file(f, "reproduce output")
    return out


def _foreign(folder: Path) -> list[str]:
    """The entries at the top of ``folder`` no reproduction writes (hidden ones aside)."""
    return sorted(p.name for p in folder.iterdir()
                  if not p.name.startswith(".") and not _WRITTEN.fullmatch(p.name))


def previous_reproduction(folder) -> dict | None:
    """What the reproduction in ``folder`` ran (its :data:`MARKER`), or None when it is none.

    A folder from a version that wrote no marker counts when it holds a
    ``report.md``, ``claims.csv`` or ``notebooks/`` and nothing a
    reproduction does not write; its record is then ``{}``.

    Parameters
    ----------
    folder : path
        An existing folder.

    Returns
    -------
    dict or None
    """
    folder = Path(folder)
    marker = folder / MARKER
    if marker.is_file() and not marker.is_symlink():
        try:
            record = json.loads(marker.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            record = None
        if isinstance(record, dict):
            return record
    legacy = any((folder / n).exists() for n in ("report.md", "claims.csv", "notebooks"))
    return {} if legacy and not _foreign(folder) else None


def _exchange(a: Path, b: Path) -> bool:
    """Swap two folders in one step (Linux ``renameat2``); False where it is not available."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EPERM):   # the file system cannot
        return False
    raise OSError(err, os.strerror(err), str(b))


def _fsync_folder(folder: Path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


class ReproductionFolder:
    """``OUT`` of one reproduction: locked, written beside as ``OUT.incomplete``, swapped in.

    Use it as a context manager; write into :attr:`staging`; call
    :meth:`commit` when everything is written.  Leaving the ``with`` block
    without a commit (an error, Ctrl-C) leaves ``OUT`` as it was and the
    partial work in ``OUT.incomplete``.

    Parameters
    ----------
    out : path
        The output folder (resolved; :func:`check_reproduce_folder` first).
    what : str
        The option, for messages.

    Attributes
    ----------
    out, staging : pathlib.Path
        The folder and where the run writes until :meth:`commit`.
    previous : dict or None
        What the reproduction being replaced ran (:func:`previous_reproduction`),
        read on entry; None when there is none.
    """

    def __init__(self, out, what: str = "reproduce --out"):
        self.out = Path(out).resolve()
        self.what = what
        self.staging = self.out.with_name(self.out.name + ".incomplete")
        self.replaced = self.out.with_name(self.out.name + ".replaced")
        self.lock = FileLock(self.out.with_name("." + self.out.name), what)
        self.previous: dict | None = None
        self.committed = False

    def _refuse(self, why: str) -> OutputError:
        return OutputError(f"{self.what} {self.out}: {why}")

    def _take_lock(self) -> None:
        try:
            self.lock.acquire()
        except OutputError as err:
            holder = ""
            with contextlib.suppress(OSError, ValueError, IndexError):
                holder = f" (process {int(self.lock.lock_path.read_text().split()[0])})"
            if "another process" not in str(err):
                raise
            raise self._refuse(f"another tefcore reproduce{holder} is writing this folder "
                               "(lock " + str(self.lock.lock_path) + "); wait until it has "
                               "finished, or choose another --out") from None

    def _check_existing(self) -> None:
        out = self.out
        cwd = Path.cwd().resolve()
        if cwd == out or out in cwd.parents:
            raise self._refuse("the current folder is inside it, and the folder is replaced "
                               "whole; run from another folder")
        if not out.exists() or not any(out.iterdir()):
            return
        record = previous_reproduction(out)
        if record is None:
            raise self._refuse("the folder is not empty and holds no reproduction; choose a "
                               "new or empty folder (a reproduction replaces its folder whole)")
        foreign = _foreign(out)
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more"
                                              if len(foreign) > 3 else "")
            raise self._refuse(f"the previous reproduction there also holds {shown}, which no "
                               "reproduction writes; the folder is replaced whole: move them "
                               "out first")
        self.previous = record

    def _remove_leftover(self, folder: Path) -> None:
        """A killed run's ``OUT.incomplete`` or ``OUT.replaced`` (ours: refused otherwise)."""
        if not (folder.exists() or folder.is_symlink()):
            return
        ours = (folder.is_dir() and not folder.is_symlink()
                and ((folder / INCOMPLETE).is_file()
                     or previous_reproduction(folder) is not None))
        if not ours:
            raise self._refuse(f"{folder} is in the way (a reproduction writes there before "
                               "it replaces the folder) and is not a reproduction's; move it")
        shutil.rmtree(folder)

    def __enter__(self) -> ReproductionFolder:
        check_output_folder(self.out.parent, f"{self.what} {self.out}: its folder",
                            create=True)
        self._take_lock()
        try:
            self._check_existing()
            self._remove_leftover(self.staging)
            self._remove_leftover(self.replaced)
            self.staging.mkdir()
            atomic_write_text(self.staging / INCOMPLETE, (
                f"This folder holds a reproduction that has not finished (tefcore reproduce, "
                f"process {os.getpid()}).  The finished result goes to {self.out} when it "
                "has; if the run was stopped, this folder is what it wrote, and the next run "
                "into the same folder removes it.\n"))
        except BaseException:
            self.lock.release()
            raise
        return self

    def commit(self, record: dict) -> Path:
        """Write the :data:`MARKER` and put the staging folder in place of ``OUT``.

        Paths to the staging folder in the executed notebooks are renamed to
        ``OUT``'s (their ``output_dir`` parameter, the files they name).

        Parameters
        ----------
        record : dict
            What ran (JSON): the notebooks, their parameters, the version.

        Returns
        -------
        pathlib.Path
            ``OUT``.
        """
        _rename_paths(self.staging, self.out)
        atomic_write_text(self.staging / MARKER,
                          json.dumps(record, indent=1, sort_keys=True, default=str) + "\n")
        (self.staging / INCOMPLETE).unlink(missing_ok=True)
        if self.out.exists():
            if not _exchange(self.staging, self.out):
                os.rename(self.out, self.replaced)
                os.rename(self.staging, self.out)
            else:
                os.rename(self.staging, self.replaced)
            shutil.rmtree(self.replaced, ignore_errors=True)
        else:
            os.rename(self.staging, self.out)
        _fsync_folder(self.out.parent)
        self.committed = True
        return self.out

    def __exit__(self, *exc) -> None:
        self.lock.release()


def _rename_paths(staging: Path, out: Path) -> None:
    """``staging`` named as ``out`` in the executed notebooks and their HTML pages."""
    old, new = str(staging), str(out)
    for page in sorted((staging / "notebooks").glob("*")):
        if page.suffix not in (".ipynb", ".html") or page.is_symlink():
            continue
        text = page.read_text(encoding="utf-8")
        if old in text:
            atomic_write_text(page, text.replace(old, new))
