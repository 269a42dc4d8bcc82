"""Rebuild and execute the notebooks from their jupytext sources (developers).

The notebooks' sources are the percent-format ``tefcore/paper/notebooks/NN_*.py``
files; the ``.ipynb`` beside them are the same cells with their outputs, which
nbval compares.  After editing a source, or after any change to the numerics,
run::

    python tools/refresh_notebooks.py            # all notebooks, two at a time
    python tools/refresh_notebooks.py 04 07      # some
    python tools/refresh_notebooks.py --sources-only   # layout/comment edits only

``--sources-only`` copies the sources' cells into the stored notebooks and
keeps their outputs, without executing: for edits that cannot change an
output (line breaks, comments, markdown).  nbval then tells whether that was
true.

Each notebook is built from its source (jupytext), executed with papermill in
one temporary working folder (outputs go there, not into the package) with
``interactive = False`` where a notebook has that parameter (the static
figure, not widget state), and written back without papermill's injected
cell and timings, with cell ids numbered in order, so that an unchanged
notebook is rewritten byte-identically.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import jupytext
import nbformat
import papermill  # noqa: E402

NB_DIR = Path(__file__).resolve().parent.parent / "tefcore" / "paper" / "notebooks"


def build(source: Path) -> nbformat.NotebookNode:
    """The notebook of a jupytext source, without outputs, with deterministic ids."""
    nb = jupytext.read(source)
    nb.metadata.setdefault("kernelspec", {"display_name": "Python 3", "language": "python",
                                          "name": "python3"})
    nb.metadata.setdefault("language_info", {"name": "python"})
    for i, cell in enumerate(nb.cells):
        cell["id"] = f"cell-{i:03d}"
    return nb


def clean(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """Drop papermill's injected parameters cell and its run metadata."""
    nb.cells = [c for c in nb.cells if "injected-parameters" not in c.metadata.get("tags", [])]
    nb.metadata.pop("papermill", None)
    count = 0
    for i, cell in enumerate(nb.cells):
        cell.metadata.pop("papermill", None)
        cell.metadata.pop("execution", None)
        if cell.metadata.get("tags") == []:       # papermill adds empty tag lists
            cell.metadata.pop("tags")
        cell["id"] = f"cell-{i:03d}"
        if cell.cell_type == "code":
            # numbered in order (nbval takes a cell without a count for one never run)
            count += 1
            cell.execution_count = count
            for out in cell.get("outputs", []):
                if "execution_count" in out:
                    out["execution_count"] = count
    return nb


def refresh(source: Path, work: Path) -> tuple[str, float]:
    """Build, execute (kernel in the process's working folder ``work``) and store one notebook."""
    start = time.perf_counter()
    target = source.with_suffix(".ipynb")
    unexecuted = work / target.name
    nbformat.write(build(source), unexecuted)
    params = papermill.inspect_notebook(str(unexecuted))
    executed = papermill.execute_notebook(
        str(unexecuted), str(work / f"executed-{target.name}"),
        parameters={"interactive": False} if "interactive" in params else {},
        kernel_name="python3", cwd=None, progress_bar=False, log_output=False,
        extra_arguments=["--IPKernelApp.log_level=ERROR"])
    nbformat.write(clean(executed), target)
    return source.stem, time.perf_counter() - start


def resync_sources(source: Path) -> str:
    """Copy the cells' sources of ``source`` into its stored notebook, keeping outputs."""
    target = source.with_suffix(".ipynb")
    fresh, stored = build(source), nbformat.read(target, as_version=4)
    kinds = [c.cell_type for c in fresh.cells]
    if kinds != [c.cell_type for c in stored.cells]:
        raise SystemExit(f"{source.name}: cells added, removed or changed kind; execute it "
                         "instead (without --sources-only)")
    for new, old in zip(fresh.cells, stored.cells, strict=True):
        old.source = new.source
        old.metadata = new.metadata
    nbformat.write(clean(stored), target)
    return source.stem


def write_readme_picture() -> None:
    """docs/fig09.png: notebook 04's first stored PNG (the README's picture of Fig. 9)."""
    import base64
    import json

    nb = json.loads((NB_DIR / "04_cg_offset.ipynb").read_text("utf-8"))
    png = next(base64.b64decode(out["data"]["image/png"])
               for cell in nb["cells"] for out in cell.get("outputs", [])
               if "image/png" in out.get("data", {}))
    (NB_DIR.parents[2] / "docs" / "fig09.png").write_bytes(png)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("notebooks", nargs="*", help="numbers or names (default: all)")
    p.add_argument("--jobs", type=int, default=2, help="notebooks executed at once")
    p.add_argument("--sources-only", action="store_true",
                   help="copy the sources' cells into the notebooks, keep the outputs")
    args = p.parse_args(argv)
    sources = sorted(NB_DIR.glob("[0-9][0-9]_*.py"))
    if args.notebooks:
        sources = [s for s in sources if any(s.stem.startswith(k.zfill(2)) or s.stem == k
                                             for k in args.notebooks)]
    if args.sources_only:
        for source in sources:
            print(f"{resync_sources(source)}: sources copied", file=sys.stderr)
        return 0
    # one working folder for all (papermill's own cwd would chdir the whole process,
    # which races between threads); each notebook writes into output/<its name> there
    with tempfile.TemporaryDirectory(prefix="tefcore-refresh-") as tmp:
        os.chdir(tmp)
        with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for name, seconds in pool.map(lambda s: refresh(s, Path(tmp)), sources):
                print(f"{name}: {seconds:.1f} s", file=sys.stderr)
        os.chdir(NB_DIR)
    if any(s.stem.startswith("04") for s in sources):
        write_readme_picture()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
