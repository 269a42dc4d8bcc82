"""Every long phase of ``tefcore reproduce`` shows how far it is and the time left.

The notebooks' bar stopped at 10/11 (it closed before the last notebook's
HTML export counted it) and the attribution then ran for minutes without a
word.  Each phase -- notebooks, other variants, attribution, report -- now
has a bar with its estimate of the time left, each ending at 100 %.
"""

import re

import nbformat
import pandas as pd
import pytest

from tefcore.paper.run import reproduce as rp


def _last_states(err: str) -> dict:
    """Each bar's last state, by its name (tqdm redraws a bar with carriage returns)."""
    out = {}
    for state in re.split(r"[\r\n]+", err):
        m = re.match(r"(notebooks|attribution|report|other variants)\b", state.strip())
        if m:
            out[m.group(1)] = state.strip()
    return out


@pytest.fixture
def tiny_notebooks(tmp_path):
    folder = tmp_path / "nbs"
    folder.mkdir()
    for name in ("03_overhang", "04_cg_offset"):
        nb = nbformat.v4.new_notebook()
        params = nbformat.v4.new_code_cell("output_dir = 'out'")
        params.metadata["tags"] = ["parameters"]
        nb.cells = [params, nbformat.v4.new_code_cell("x = 1")]
        nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                     "language": "python"}
        nbformat.write(nb, folder / f"{name}.ipynb")
    return folder


def test_the_notebooks_bar_ends_at_the_last_notebook(tmp_path, tiny_notebooks, capsys):
    pytest.importorskip("papermill")
    runs = rp.run_notebooks(tmp_path / "out", {}, ["03_overhang", "04_cg_offset"],
                            nb_dir=tiny_notebooks, jobs=1)
    assert [r.status for r in runs] == ["ok", "ok"]
    bar = _last_states(capsys.readouterr().err)["notebooks"]
    assert bar.startswith("notebooks 2/2 100%"), bar
    assert re.search(r"\[\d\d:\d\d<\d\d:\d\d\]", bar), bar        # time spent < time left


def test_the_attribution_and_the_report_show_progress(tmp_path, monkeypatch, capsys):
    def run(out, params, names, **kw):
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame([{"id": "fig9b-x", "figure": "fig9", "status": "fail",
                           "tag": "validation", "reason": "", "recorded_status": "fail"}]
                         ).to_csv(out / name / "claims.csv", index=False)
        return [rp.NotebookRun(n, status="ok") for n in names]

    def attribute(out, claims, attribution):   # the tasks' weights, as the attribution adds them
        bar = attribution["progress"]
        bar.total = 6.0
        bar.refresh()
        for w in (3.0, 2.0, 1.0):
            bar.update(w)
        return None

    monkeypatch.setattr(rp, "run_notebooks", run)
    monkeypatch.setattr(rp, "attribute_claims", attribute)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])
    rp.reproduce(tmp_path / "out", notebooks=["04"], progress=True)
    bars = _last_states(capsys.readouterr().err)
    for phase in ("attribution", "report"):
        assert re.match(rf"{phase}\s+100%\|", bars[phase]), bars
        assert re.search(r"\[\d\d:\d\d<\d\d:\d\d\]", bars[phase]), bars[phase]


def test_the_help_states_the_measured_cost():
    from tefcore.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    text = sub.choices["reproduce"].format_help()
    assert "about an hour" not in text
    assert re.search(r"about \d+ minutes", " ".join(text.split())), text
