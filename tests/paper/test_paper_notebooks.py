"""The notebooks as reviewable sources, their shared text, titles from the parameters used.

Issue 14, item 2: jupytext percent sources paired with the executed
notebooks (a pair out of sync fails here), the departures text written once,
figure titles and captions built from the configuration actually analysed.
"""

import re
from pathlib import Path

import nbformat
import pytest

from tefcore.paper.attribution.departures import departures_text, load_departures
from tefcore.paper.figures.captions import figure_caption, figure_title
from tefcore.paper.figures.catalogue import FIGURES
from tefcore.paper.figures.responses import response_config
from tefcore.paper.figures.runs import run_config
from tefcore.paper.run import notebook_files as nbf

jupytext = pytest.importorskip("jupytext")

NB_DIR = nbf.notebooks_dir()


def _cells(nb):
    return [(c.cell_type, c.source.strip(), tuple(c.metadata.get("tags", ())))
            for c in nb.cells]


@pytest.mark.parametrize("name", nbf.NOTEBOOKS)
def test_source_and_notebook_are_in_sync(name):
    """The .ipynb holds exactly the cells of its .py source (outputs aside)."""
    source = jupytext.read(NB_DIR / f"{name}.py")
    stored = nbformat.read(NB_DIR / f"{name}.ipynb", as_version=4)
    a, b = _cells(source), _cells(stored)
    for i, (x, y) in enumerate(zip(a, b, strict=False)):
        assert x == y, (f"{name}: cell {i} differs between the .py source and the .ipynb; "
                        "run python tools/refresh_notebooks.py " + name[:2])
    assert len(a) == len(b), f"{name}: {len(a)} cells in the source, {len(b)} in the notebook"
    assert stored.metadata["kernelspec"]["name"] == "python3"
    assert "py:percent" in source.metadata["jupytext"]["formats"]


def test_sync_check_fails_on_an_edited_cell(tmp_path):
    """The comparison above is not vacuous: one changed character is found."""
    source = jupytext.read(NB_DIR / "04_cg_offset.py")
    stored = nbformat.read(NB_DIR / "04_cg_offset.ipynb", as_version=4)
    k = next(i for i, c in enumerate(stored.cells) if c.cell_type == "code")
    stored.cells[k].source = stored.cells[k].source.replace("n_jobs = 1", "n_jobs = 2", 1)
    assert _cells(source) != _cells(stored)


def test_every_source_is_shipped_with_its_notebook():
    for name in nbf.NOTEBOOKS:
        assert (NB_DIR / f"{name}.py").is_file() and (NB_DIR / f"{name}.ipynb").is_file()
    assert not (Path(__file__).resolve().parents[2] / "notebooks" / "build_notebooks.py").exists()


def test_departures_are_written_once_and_cover_every_figure():
    common, own = load_departures()
    figures = {f for figs in nbf.NOTEBOOK_FIGURES.values() for f in figs}
    assert figures <= set(own), f"no departures text for {sorted(figures - set(own))}"
    first_line = common.splitlines()[0]
    for name, figs in nbf.NOTEBOOK_FIGURES.items():
        src = (NB_DIR / f"{name}.py").read_text(encoding="utf-8")
        assert first_line not in src, f"{name} pastes the departures text"
        if figs:
            calls = re.findall(r"nt\.show_departures\(([^)]*)\)", src)
            assert len(calls) == 1, f"{name}: show the departures once"
            shown = set(re.findall(r'"(fig\w+)"', calls[0]))
            assert shown == set(figs), f"{name}: departures of {shown}, figures {set(figs)}"
    text = departures_text("fig10", "fig11")
    assert text.count("For Figs. 10-12 in particular") == 1     # a group is given once


def test_titles_are_not_hard_coded_in_the_notebooks():
    """Figure titles come from the configuration used (an override must show)."""
    for name in nbf.NOTEBOOKS:
        src = (NB_DIR / f"{name}.py").read_text(encoding="utf-8")
        literal = re.findall(r'(?:suptitle|set_title)\(\s*"Fig\.', src)
        assert not literal, f"{name}: hard-coded figure title"


@pytest.mark.parametrize("name", [*FIGURES, "fig5", "fig6", "fig7"])
def test_title_and_caption_follow_overrides(name):
    over = {"flight.advance_ratio": 0.17, "flap.cg_offset": 0.21}
    cfg = (run_config(name, overrides=over) if name in FIGURES
           else response_config(None, **over))
    title, caption = figure_title(name, cfg), figure_caption(name, cfg, "panels")
    swept = FIGURES[name].parameter if name in FIGURES else "flap.overhang"
    assert title.startswith(f"Fig. {name[3:]}:")
    if swept != "flight.advance_ratio":
        assert "μ = 0.17" in title
    if swept != "flap.cg_offset" and cfg.model.tef != "none":
        assert "c_cg/c_f = 0.21" in title
    assert caption.startswith(title) and "panels." in caption and "hollow marker" in caption
    default = figure_title(name, run_config(name) if name in FIGURES else response_config())
    assert default != title


def test_every_notebook_has_a_measured_time_for_the_schedule():
    # tefcore reproduce starts the longest notebook first; a notebook without
    # a time would run last whatever it costs (11 did, at 21 s, until stop 36)
    assert set(nbf.NOTEBOOK_SECONDS) == set(nbf.NOTEBOOKS)
    assert all(t > 0 for t in nbf.NOTEBOOK_SECONDS.values())
