"""The numbered notebooks shipped with tefcore: names, location, parameters, copies.

The notebooks live in ``tefcore/paper/notebooks`` (package data): each as a
jupytext percent-format source ``NN_name.py`` and the executed ``NN_name.ipynb``
paired with it.  :func:`copy_notebooks` gives a user editable copies
(``tefcore notebooks --copy DIR``); :func:`notebook_parameters` reads a
notebook's ``parameters`` cell (what ``tefcore reproduce -p`` can set).

Examples
--------
>>> resolve_notebook("5"), resolve_notebook("07_flight_condition.ipynb")
('05_stiffness', '07_flight_condition')
>>> NOTEBOOK_FIGURES["04_cg_offset"]
('fig9',)
"""

from __future__ import annotations

import ast
import os
from pathlib import Path

from ...errors import OutputError
from ...safe_io import atomic_output, check_output_file, check_output_folder

__all__ = ["NOTEBOOKS", "NOTEBOOK_FIGURES", "NOTEBOOK_SECONDS", "check_parameters",
           "copy_notebooks",
           "notebook_parameters", "notebooks_dir", "resolve_notebook"]

#: The notebooks, in order.
NOTEBOOKS = (
    "01_baseline_mdart_correlation",
    "02_hinge_moments_and_flap_response",
    "03_overhang",
    "04_cg_offset",
    "05_stiffness",
    "06_size_and_location",
    "07_flight_condition",
    "08_assumptions",
    "09_design_maps",
    "10_unsteady",
    "11_watch_it_flutter",
    "12_inferred_rotor",
)
#: Wall seconds of each notebook in ``tefcore reproduce`` (kernel start, imports, HTML
#: export included; measured on 2 shared cores at load 3-4): the
#: reproduction starts the longest first, so the last to finish is a short one.
NOTEBOOK_SECONDS = {
    "01_baseline_mdart_correlation": 9.8,
    "02_hinge_moments_and_flap_response": 5.3,
    "03_overhang": 10.4,
    "04_cg_offset": 16.1,
    "05_stiffness": 25.5,
    "06_size_and_location": 40.8,
    "07_flight_condition": 16.6,
    "08_assumptions": 40.2,
    "09_design_maps": 13.8,
    "10_unsteady": 33.4,
    # an entry per notebook: a notebook without one would run last whatever
    # it costs
    "11_watch_it_flutter": 10.7,
    "12_inferred_rotor": 90.0,
}

#: Which paper figures each notebook reproduces.
NOTEBOOK_FIGURES = {
    "01_baseline_mdart_correlation": ("fig3", "fig4"),
    "02_hinge_moments_and_flap_response": ("fig5", "fig6"),
    "03_overhang": ("fig7", "fig8"),
    "04_cg_offset": ("fig9",),
    "05_stiffness": ("fig10", "fig11", "fig12"),
    "06_size_and_location": ("fig13", "fig14", "fig15"),
    "07_flight_condition": ("fig16a", "fig16b", "fig17"),
    "08_assumptions": (),               # no figure: the sensitivity of the headline results
    "09_design_maps": (),               # beyond the paper: two-parameter stability maps
    "10_unsteady": (),                  # beyond the paper: shed wake and dynamic inflow
    "11_watch_it_flutter": (),          # beyond the paper: the Floquet growth in the time domain
    "12_inferred_rotor": (),            # the unknown properties inferred from the claims
}


def notebooks_dir() -> Path:
    """Folder of the notebooks: ``$TEFCORE_NOTEBOOKS``, else the installed package's."""
    env = os.environ.get("TEFCORE_NOTEBOOKS")
    if env:
        return Path(env).resolve()
    return (Path(__file__).resolve().parent.parent / "notebooks").resolve()


def resolve_notebook(key: str) -> str:
    """Notebook name from ``"03"``, ``"03_overhang"``, ``"overhang"`` or ``"03_overhang.ipynb"``.

    Parameters
    ----------
    key : str
        What the user typed.

    Raises
    ------
    ValueError
        Unknown or ambiguous, naming the known notebooks.
    """
    k = str(key).strip().removesuffix(".ipynb").removesuffix(".py")
    if k in NOTEBOOKS:
        return k
    if k.isdigit():
        hits = [n for n in NOTEBOOKS if int(n[:2]) == int(k)]
    else:
        hits = [n for n in NOTEBOOKS if n.startswith(k) or n[3:] == k]
    if len(hits) != 1:
        raise ValueError(f"unknown notebook {key!r}; known: {', '.join(NOTEBOOKS)}")
    return hits[0]


def notebook_parameters(path) -> dict:
    """Names and default values of a notebook's ``parameters`` cell.

    Read from the cell's source (literal assignments), without a kernel.

    Parameters
    ----------
    path : path
        The ``.ipynb`` file.

    Raises
    ------
    ValueError
        The notebook has no cell tagged ``parameters``.
    """
    import nbformat

    nb = nbformat.read(str(path), as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code" and "parameters" in cell.metadata.get("tags", []):
            out = {}
            for node in ast.parse(cell.source).body:
                if isinstance(node, ast.Assign) and len(node.targets) == 1 \
                        and isinstance(node.targets[0], ast.Name):
                    try:
                        out[node.targets[0].id] = ast.literal_eval(node.value)
                    except ValueError:
                        out[node.targets[0].id] = ast.unparse(node.value)
            return out
    raise ValueError(f"{path}: no cell tagged 'parameters'")


def check_parameters(params: dict, names=NOTEBOOKS, nb_dir: Path | None = None) -> None:
    """Raise ``ValueError`` naming a parameter a notebook does not declare, or a missing notebook.

    Parameters
    ----------
    params : dict
        ``{notebook: {name: value}}``.
    names : sequence of str
        The notebooks to check.
    nb_dir : path, optional
        Their folder (default :func:`notebooks_dir`).
    """
    import difflib

    nb_dir = nb_dir or notebooks_dir()
    for name in names:
        src = nb_dir / f"{name}.ipynb"
        if not src.is_file():
            raise ValueError(f"notebook {src} not found (TEFCORE_NOTEBOOKS = "
                             f"{os.environ.get('TEFCORE_NOTEBOOKS', 'unset')})")
        known = notebook_parameters(src)
        for pname in sorted(set(params.get(name, {})) - set(known)):
            close = difflib.get_close_matches(pname, list(known), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"{name}: unknown parameter {pname!r}{hint}; the notebook has "
                             f"{', '.join(sorted(known))}")


def copy_notebooks(dest, names=NOTEBOOKS, nb_dir: Path | None = None) -> list[Path]:
    """Copy notebooks (``.ipynb`` with outputs and the ``.py`` source) into ``dest``.

    Parameters
    ----------
    dest : path
        Folder to create or fill; an existing file there is never overwritten.
    names : sequence of str
        Notebooks to copy (default: all).
    nb_dir : path, optional
        Source folder (default :func:`notebooks_dir`).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Raises
    ------
    tefcore.errors.OutputError
        ``dest`` is a file or a link, or a file to write exists (nothing is copied then).
    """
    nb_dir = nb_dir or notebooks_dir()
    dest = Path(dest)
    if dest.exists() or dest.is_symlink():
        check_output_folder(dest, "notebooks --copy")
    pairs = [(nb_dir / f"{n}{ext}", dest / f"{n}{ext}") for n in names
             for ext in (".ipynb", ".py")]
    for src, dst in pairs:
        if not src.is_file():
            raise ValueError(f"notebook source {src} not found")
        if dst.exists() or dst.is_symlink():
            raise OutputError(f"notebooks --copy: {dst} exists; copy into an empty folder "
                              "(your edits there are never overwritten)")
    check_output_folder(dest, "notebooks --copy", create=True)
    written = []
    for src, dst in pairs:
        check_output_file(dst, "notebooks --copy")
        with atomic_output(dst, "wb") as f:
            f.write(src.read_bytes())
        written.append(dst)
    return written
