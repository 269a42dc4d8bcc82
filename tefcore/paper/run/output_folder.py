"""Where a reproduction may write: never over sources, tracked files, links or the root.

:func:`check_reproduce_folder` runs before any notebook does (``tefcore
reproduce`` and ``tefcore batch``), so a refused destination costs nothing.
"""

from __future__ import annotations

from pathlib import Path

from ...errors import OutputError
from ...safe_io import check_output_file, check_output_folder
from .notebook_files import NOTEBOOKS, notebooks_dir

__all__ = ["check_reproduce_folder", "source_checkout"]


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
                               "attribution.csv",
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
