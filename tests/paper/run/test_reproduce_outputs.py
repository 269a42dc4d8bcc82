"""``reproduce --only`` writes only what the chosen notebooks make.

The baseline blade's files at the top of the output folder
(``mdart_modes.csv``, ``mdart_frequency_checks.csv``, ``mdart_fanplot.png``)
belong to notebook 01 (the blade's correlation); ``--only 03 04`` wrote them
too.  The notebooks' execution is replaced by a fake that writes what
papermill would.
"""

from pathlib import Path

import pytest

from tefcore.paper.run import reproduce as rp

pytest.importorskip("papermill")


@pytest.fixture
def fake_notebooks(monkeypatch):
    blade_calls = []

    def fake_run(out, params, names, progress=True, nb_dir=None, kernel_name="python3",
                 jobs=None, stop=None):
        (out / "notebooks").mkdir(parents=True, exist_ok=True)
        for name in names:
            (out / "notebooks" / f"{name}.ipynb").write_text("EXECUTED")
            (out / name).mkdir(exist_ok=True)
            (out / name / "table.csv").write_text("a\n1\n")
        return [rp.NotebookRun(name, status="ok") for name in names]

    def fake_blade(out, cfg=None):
        blade_calls.append(out)
        for f in ("mdart_modes.csv", "mdart_frequency_checks.csv", "mdart_fanplot.png"):
            (Path(out) / f).write_text("blade")
        return None

    monkeypatch.setattr(rp, "run_notebooks", fake_run)
    monkeypatch.setattr(rp, "baseline_blade", fake_blade)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])
    return blade_calls


def test_only_some_notebooks_write_no_baseline_blade_files(tmp_path, fake_notebooks):
    out = tmp_path / "out"
    rp.reproduce(out, notebooks=["03", "04"], progress=False)
    # (these fake notebooks check no claim: there is nothing to attribute)
    assert sorted(p.name for p in out.iterdir()) == [
        "03_overhang", "04_cg_offset", "claims.csv", "notebooks",
        "report.html", "report.md", "reproduction.json"]
    assert fake_notebooks == []


def test_the_baseline_notebook_brings_the_blade_files(tmp_path, fake_notebooks):
    out = tmp_path / "out"
    rp.reproduce(out, notebooks=["01", "04"], progress=False)
    assert {"mdart_modes.csv", "mdart_frequency_checks.csv", "mdart_fanplot.png"} <= \
        {p.name for p in out.iterdir()}
    # drawn into the run's folder, which then became OUT
    assert fake_notebooks == [out.with_name("out.incomplete")]
