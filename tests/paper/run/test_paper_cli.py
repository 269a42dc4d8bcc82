"""``tefcore notebooks`` and ``tefcore reproduce`` as a user meets them."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest

from tefcore.cli import main
from tefcore.paper.run import notebook_files as nbf

matplotlib.use("Agg")


def test_notebooks_lists_them(capsys):
    assert main(["notebooks"]) == 0
    out = capsys.readouterr().out
    assert all(n in out for n in nbf.NOTEBOOKS) and "Fig. 9" in out


def test_copy_gives_editable_pairs_and_never_overwrites(tmp_path, capsys):
    dest = tmp_path / "mine"
    assert main(["notebooks", "--copy", str(dest), "--only", "04", "05"]) == 0
    got = sorted(p.name for p in dest.iterdir())
    assert got == ["04_cg_offset.ipynb", "04_cg_offset.py", "05_stiffness.ipynb",
                   "05_stiffness.py"]
    assert (dest / "04_cg_offset.py").read_bytes() == \
        (nbf.notebooks_dir() / "04_cg_offset.py").read_bytes()
    (dest / "04_cg_offset.py").write_text("# my edits")
    capsys.readouterr()
    assert main(["notebooks", "--copy", str(dest), "--only", "04"]) == 2
    err = capsys.readouterr().err
    assert "exists" in err and err.count("\n") == 1 and "Traceback" not in err
    assert (dest / "04_cg_offset.py").read_text() == "# my edits"


def test_copy_refuses_a_file_or_a_link_as_folder(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    assert main(["notebooks", "--copy", str(f)]) == 2
    link = tmp_path / "link"
    link.symlink_to(tmp_path / "elsewhere", target_is_directory=True)
    assert main(["notebooks", "--copy", str(link)]) == 2
    assert not (tmp_path / "elsewhere").exists()


def test_missing_reference_data_is_an_error_not_zero_of_zero(tmp_path, monkeypatch, capsys):
    pytest.importorskip("papermill")
    monkeypatch.setenv("TEFCORE_REFERENCE_DATA", str(tmp_path / "nothing"))
    assert main(["reproduce", "--only", "04", "--out", str(tmp_path / "out"),
                 "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert "reference data" in err and "Traceback" not in err
    assert not (tmp_path / "out" / "report.html").exists()     # refused before running


def test_copied_notebooks_are_what_reproduce_runs(tmp_path, monkeypatch):
    """TEFCORE_NOTEBOOKS points reproduce at a user's copies (parameters read from them)."""
    dest = tmp_path / "mine"
    nbf.copy_notebooks(dest, ["04_cg_offset"])
    monkeypatch.setenv("TEFCORE_NOTEBOOKS", str(dest))
    assert nbf.notebooks_dir() == dest.resolve()
    params = nbf.notebook_parameters(dest / "04_cg_offset.ipynb")
    assert params["n_jobs"] == 1 and params["interactive"] is True
    with pytest.raises(ValueError, match="did you mean 'n_points'"):
        nbf.check_parameters({"04_cg_offset": {"n_pointz": 3}}, ["04_cg_offset"], dest)


# ------------------------------------------------------------------ explorer


def test_static_explorer_marks_the_tef_and_flutter_roots():
    from tefcore.linear.stability import stability
    from tefcore.modes.continuation import tef_root
    from tefcore.paper.explorer import explore, explorer_config, root_map

    fig = explore(interactive=False, cg_offset=0.33, advance_ratio=0.3)
    roots, bars = fig.axes[0], fig.axes[1]          # (the third is the colour bar)
    cfg = explorer_config(cg_offset=0.33, overhang=0.29, actuator_scale=1.0,
                          advance_ratio=0.3)
    res = stability(cfg)
    eta, _ = tef_root(res.system, basis=res.trim_result.model.tracking_basis())
    ring = [ln for ln in roots.get_lines() if ln.get_label() == "TEF root"][0]
    assert ring.get_xdata()[0] == pytest.approx(eta.imag) and \
        ring.get_ydata()[0] == pytest.approx(eta.real)
    state = root_map(cfg)
    fr = state.modes.loc[state.flutter]
    assert fr["share_TEF"] >= 0.1
    assert fr["real_part"] == state.modes.loc[state.modes["share_TEF"] >= 0.1,
                                              "real_part"].max()
    labels = [t.get_text() for t in bars.get_yticklabels()]
    assert "TEF root" in labels and "flutter root" in labels
    assert np.isfinite([p.get_width() for p in bars.patches]).all()


def test_explorer_shows_why_there_are_no_roots():
    import matplotlib.pyplot as plt

    from tefcore.paper.explorer import draw_root_map, explorer_state

    # the flap's inertia about the elastic axis no longer fits in its section
    state = explorer_state(cg_offset=0.0, overhang=0.95, actuator_scale=1.0, advance_ratio=0.3)
    assert state.modes.empty and "does not fit" in state.error
    fig = draw_root_map(plt.figure(), state)
    assert any("does not fit" in t.get_text() for t in fig.axes[0].texts)


def test_widget_explorer_redraws_and_keeps_a_trail():
    widgets = pytest.importorskip("ipywidgets")
    from tefcore.paper import explorer

    box = explorer.explore(interactive=True, cg_offset=0.0, advance_ratio=0.0)
    assert isinstance(box, widgets.VBox)
    sliders = [w for w in box.children[0].children[0].children + box.children[0].children[1]
               .children if isinstance(w, widgets.FloatSlider)]
    assert [s.description for s in sliders] == [v[0] for v in explorer.SLIDERS.values()]
    with pytest.raises(TypeError, match="unknown parameter"):
        explorer.explore(interactive=False, cg=0.3)
    Path  # noqa: B018
