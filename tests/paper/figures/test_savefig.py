"""Saved figures: the PNG and its caption, and in a notebook the cell shows that PNG once."""

from __future__ import annotations

import base64
import json

import matplotlib
import pytest

matplotlib.use("agg")
import matplotlib.pyplot as plt  # noqa: E402

from tefcore.paper.figures.plotting import savefig, show_saved  # noqa: E402


def test_savefig_writes_the_png_and_its_caption_and_leaves_the_figure_alone(tmp_path):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    try:
        assert savefig(fig, tmp_path, "f", figure="fig9", caption="c") is None
        png = (tmp_path / "f.png").read_bytes()
        assert png.startswith(b"\x89PNG") and b"Software" not in png   # reproducible bytes
        assert json.loads((tmp_path / "f.json").read_text()) == {"caption": "c",
                                                                   "figure": "fig9"}
        # outside a notebook nothing is shown and the figure stays pyplot's
        assert show_saved(fig, png) is False
        assert plt.fignum_exists(fig.number)
    finally:
        plt.close(fig)


def _png_size(png: bytes) -> tuple[int, int]:
    return int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")


def test_outside_a_kernel_nothing_is_shown_even_with_the_inline_backend(monkeypatch, capsys):
    # a script started from a notebook inherits MPLBACKEND=...backend_inline but
    # has no kernel: IPython's display would print the whole PNG as text there
    pytest.importorskip("matplotlib_inline.backend_inline")
    monkeypatch.setattr(matplotlib, "get_backend",
                        lambda: "module://matplotlib_inline.backend_inline")
    fig, ax = plt.subplots()
    try:
        assert show_saved(fig, b"\x89PNG") is False
        assert plt.fignum_exists(fig.number)
        assert capsys.readouterr().out == ""
    finally:
        plt.close(fig)


def test_in_a_notebook_the_cell_shows_the_saved_png_once(tmp_path):
    # the inline backend would draw the figure again at the end of the cell
    # (its own PNG, with a Software tag): the cell's one image output must be
    # the saved file, byte for byte, with the backend's text, shown at the
    # size the backend's own picture of the same figure has (the notebooks
    # save at 110 dpi and show figures at 80: deterministic_matplotlib)
    nbformat = pytest.importorskip("nbformat")
    pytest.importorskip("papermill")
    from tefcore.paper.run import reproduce as rp

    make = ("fig, ax = plt.subplots(figsize=(4, 3))\n"
            "ax.plot([0, 1, 2], [1, 3, 2])\n"
            "ax.set_title('a title')\n")
    cells = ["import matplotlib.pyplot as plt\n"
             "from tefcore.paper.figures.plotting import deterministic_matplotlib, savefig\n"
             "deterministic_matplotlib()",
             make + f"open({str(tmp_path / 'repr.txt')!r}, 'w').write(repr(fig))\n"
             f"savefig(fig, {str(tmp_path)!r}, 'shown')",
             make]                                   # the backend's own picture
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nb.metadata["kernelspec"] = {"name": rp.KERNEL_NAME, "display_name": "Python 3",
                                 "language": "python"}
    src = tmp_path / "nb.ipynb"
    nbformat.write(nb, str(src))
    run = rp.execute_notebook("nb", src, tmp_path, {}, export=False)
    assert run.status == "ok", run.error
    done = nbformat.read(str(tmp_path / "notebooks" / "nb.ipynb"), 4).cells
    images = [o for o in done[1].outputs if "image/png" in o.get("data", {})]
    assert len(images) == 1
    png = base64.b64decode(images[0].data["image/png"])
    assert png == (tmp_path / "shown.png").read_bytes()
    assert images[0].data["text/plain"] == (tmp_path / "repr.txt").read_text()
    assert images[0].data["text/plain"].startswith("<Figure size ")
    # shown at the backend's size (within the pixel each side rounds to),
    # from a file drawn at 110/80 of it
    backend = [o for o in done[2].outputs if "image/png" in o.get("data", {})]
    own = _png_size(base64.b64decode(backend[0].data["image/png"]))
    shown = (images[0].metadata["image/png"]["width"], images[0].metadata["image/png"]["height"])
    assert all(abs(a - b) <= 1 for a, b in zip(shown, own, strict=True)), (shown, own)
    assert _png_size(png)[0] > 1.3 * own[0]
