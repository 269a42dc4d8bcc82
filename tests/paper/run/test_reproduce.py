"""``tefcore reproduce``: parameters, report, exit status, determinism."""

import base64
import filecmp
import re
from pathlib import Path

import pandas as pd
import pytest

from tefcore.cli import main
from tefcore.paper.run import notebook_files as nbf
from tefcore.paper.run import params as run_params
from tefcore.paper.run import reproduce as rp
from tests.paper.run.test_report_html import check_page

pytest.importorskip("yaml")

# ------------------------------------------------------------------ parameters


def test_cli_params_are_yaml_typed_and_targeted():
    got = run_params.parse_cli_params([("n_jobs", "2"), ("values", "{fig8: [0.0, 0.5]}"),
                               ("03_overhang:n_points", "5"), ("4:aero_model", "table"),
                               ("07_flight_condition.ipynb:overrides",
                                "{flight.ct_sigma: 0.08}"), ("n_points", "null")])
    assert got == {"all": {"n_jobs": 2, "values": {"fig8": [0.0, 0.5]}, "n_points": None},
                   "03_overhang": {"n_points": 5}, "04_cg_offset": {"aero_model": "table"},
                   "07_flight_condition": {"overrides": {"flight.ct_sigma": 0.08}}}


def test_unknown_notebook_or_bad_name_is_an_error():
    with pytest.raises(ValueError, match="unknown notebook"):
        run_params.parse_cli_params([("99_nothing:n_points", "3")])
    with pytest.raises(ValueError, match="identifier"):
        run_params.parse_cli_params([("n-points", "3")])


def test_params_file_and_precedence(tmp_path, monkeypatch, capsys):
    f = tmp_path / "p.yaml"
    f.write_text("all:\n  n_jobs: 2\n  n_points: 4\n03:\n  n_points: 6\n"
                 "04_cg_offset:\n  damping_measure: damping_ratio\n")
    seen = {}

    def fake(out, params=None, notebooks=None, progress=True, nb_dir=None, jobs=None,
             variants=True, attribution=True):
        seen.update(out=out, params=params, notebooks=notebooks, progress=progress,
                    variants=variants, attribution=attribution)
        return 0

    monkeypatch.setattr(rp, "reproduce", fake)
    assert main(["reproduce", "--out", str(tmp_path / "o"), "--params", str(f),
                 "-p", "n_points", "8", "-p", "04:n_points", "3", "--only", "03", "04",
                 "--no-progress"]) == 0
    merged = run_params.merge_params(*seen["params"])
    # file all < file notebook < -p all < -p notebook
    assert merged["03_overhang"] == {"n_jobs": 2, "n_points": 8}
    assert merged["04_cg_offset"] == {"n_jobs": 2, "n_points": 3,
                                      "damping_measure": "damping_ratio"}
    assert merged["01_baseline_mdart_correlation"] == {"n_jobs": 2, "n_points": 8}
    assert seen["notebooks"] == ["03", "04"] and seen["progress"] is False
    assert seen["variants"] is True                  # the other variant is checked too
    assert seen["attribution"] is True        # on by default; --no-attribution skips it
    main(["reproduce", "--out", str(tmp_path / "o"), "--no-variants", "--no-attribution",
          "--no-progress"])
    assert seen["variants"] is False and seen["attribution"] is False
    # the search even where the package's attribution applies (the default rotor)
    main(["reproduce", "--out", str(tmp_path / "o"), "--attribute-again", "--no-progress"])
    assert seen["attribution"] == {"again": True}
    # skipping and searching again: one or the other, said in one line
    assert main(["reproduce", "--out", str(tmp_path / "o"), "--attribute-again",
                 "--no-attribution"]) == 2
    assert "not allowed with" in capsys.readouterr().err


def test_bad_params_file_is_a_clear_error(tmp_path, capsys):
    f = tmp_path / "p.yaml"
    f.write_text("03_overhang: 5\n")
    assert main(["reproduce", "--out", str(tmp_path / "o"), "--params", str(f)]) == 2
    assert "03_overhang" in capsys.readouterr().err


def test_every_notebook_has_parameters_kernelspec_and_outputs():
    pytest.importorskip("papermill")
    import nbformat

    for name in nbf.NOTEBOOKS:
        path = nbf.notebooks_dir() / f"{name}.ipynb"
        nb = nbformat.read(path, as_version=4)
        assert nb.metadata["kernelspec"]["name"] == "python3"
        tagged = [c for c in nb.cells if "parameters" in c.metadata.get("tags", [])]
        assert len(tagged) == 1
        params = nbf.notebook_parameters(path)
        assert {"output_dir", "n_jobs", "aero_model", "config", "overrides",
                "n_points"} <= set(params)
        code = [c for c in nb.cells if c.cell_type == "code"]
        assert all(c.get("execution_count") for c in code), f"{name} is not executed"
        assert [c.execution_count for c in code] == list(range(1, len(code) + 1))
        for c in code:
            for o in c.get("outputs", []):
                assert o.output_type != "error", f"{name}: stored error output"
                assert not (o.output_type == "stream" and o.name == "stderr"), \
                    f"{name}: stderr output: {o.text[:200]}"


def test_unknown_notebook_parameter_is_rejected_before_running(tmp_path, capsys):
    pytest.importorskip("papermill")
    assert main(["reproduce", "--out", str(tmp_path), "-p", "04:n_pointz", "3"]) == 2
    err = capsys.readouterr().err
    assert "n_pointz" in err and "n_points" in err
    assert not (tmp_path / "report.md").exists()


# ------------------------------------------------------------------ exit status


def _fake_runs(claims_rows, status="ok"):
    def run(out, params, names, progress=True, nb_dir=None, kernel_name="python3", jobs=None,
            stop=None):
        runs = []
        for name in names:
            (out / name).mkdir(parents=True, exist_ok=True)
            pd.DataFrame(claims_rows).to_csv(out / name / "claims.csv", index=False)
            runs.append(rp.NotebookRun(name, status=status,
                                       error="" if status == "ok" else "boom"))
        return runs
    return run


def _claim(status, recorded, tag="validation"):
    return {"id": "fig9b-x", "figure": "fig9", "panel": "b", "kind": "trend", "tag": tag,
            "statement": "s", "expected": "e", "computed": "c", "status": status,
            "reason": "", "recorded_status": recorded}


@pytest.mark.parametrize("status, recorded, run_status, code", [
    ("pass", "pass", "ok", 0),
    ("pass", "fail", "ok", 0),                 # better than recorded is fine
    ("not reproducible", "not reproducible", "ok", 0),
    ("fail", "pass", "ok", 1),                 # regression
    ("not reproducible", "pass", "ok", 1),     # regression
    ("pass", "pass", "failed", 1),             # a notebook failed
])
def test_exit_status(tmp_path, monkeypatch, status, recorded, run_status, code):
    pytest.importorskip("tefcore.paper.claims.validation")
    monkeypatch.setattr(rp, "run_notebooks", _fake_runs([_claim(status, recorded)], run_status))
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])  # test_variants.py
    assert rp.reproduce(tmp_path, notebooks=["04"], progress=False) == code
    md = (tmp_path / "report.md").read_text()
    assert "fig9b-x" in md
    assert ("Worse than recorded: 1" in md) == (code == 1 and run_status == "ok")


def test_the_kernelspec_is_looked_up_before_the_notebooks_thread_starts(tmp_path, monkeypatch):
    """The race seen in a reproduction: jupyter_client's kernelspec lookup imports
    IPython, and matplotlib's first canvas (the fan plot, drawn in the main
    thread while the notebooks start) reads ``IPython.version_info`` if IPython
    is in ``sys.modules`` -- half-imported in the other thread, an
    AttributeError.  The lookup must be done, in the main thread, before the
    notebooks' thread exists (a wrong order fails here, not once in a while)."""
    import threading
    events = []
    monkeypatch.setattr(rp, "ensure_kernel", lambda *a, **k: events.append(
        ("kernelspec", threading.current_thread() is threading.main_thread())))
    fake = _fake_runs([_claim("pass", "pass")])

    def runs(*a, **k):
        events.append(("notebooks", threading.current_thread() is threading.main_thread()))
        return fake(*a, **k)
    monkeypatch.setattr(rp, "run_notebooks", runs)
    monkeypatch.setattr(rp, "start_variant_runs", lambda *a, **k: [])
    assert rp.reproduce(tmp_path, notebooks=["04"], progress=False) == 0
    assert events[:2] == [("kernelspec", True), ("notebooks", False)]


# ------------------------------------------------------------------ a real tiny run


@pytest.fixture(scope="module")
def tiny_runs(tmp_path_factory):
    """Notebook 04 at 4 CG offsets, twice (papermill, a real kernel)."""
    pytest.importorskip("papermill")
    outs, codes = [], []
    for k in range(2):
        out = tmp_path_factory.mktemp(f"run{k}")
        codes.append(rp.reproduce(out, params={"04_cg_offset": {"n_points": 4}},
                                  notebooks=["04_cg_offset"], progress=False, variants=False,
                                  attribution=False))   # tests/paper/test_attribution.py
        outs.append(out)
    return outs, codes


def test_tiny_run_writes_report_with_all_claims_and_embedded_figures(tiny_runs):
    (out, _), (code, _) = tiny_runs
    nb_out = out / "04_cg_offset"
    assert (out / "notebooks" / "04_cg_offset.ipynb").exists()
    table = pd.read_csv(nb_out / "fig09_modes.csv")
    asked = table[table["refinement"] == 0]   # refinement adds points between them
    assert sorted(asked["value"].unique()) == pytest.approx([0.0, 0.4 / 3, 0.8 / 3, 0.4])
    claims = pd.read_csv(nb_out / "claims.csv", dtype=str, keep_default_na=False)
    assert len(claims) > 0 and set(claims["figure"]) == {"fig9"}
    md = (out / "report.md").read_text()
    page = (out / "report.html").read_text()
    for cid in claims["id"]:
        assert cid in md and cid in page
    assert re.search(r"!\[Fig\. 9: effect of flap CG offset[^]]*\]\(04_cg_offset/fig09\.png\)", md)
    assert (out / "notebooks" / "04_cg_offset.html").exists()
    imgs = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', page)
    assert len(imgs) >= 2      # fig09 and another of its figures (no fan plot: notebook 01 only)
    assert all(base64.b64decode(i)[:8] == b"\x89PNG\r\n\x1a\n" for i in imgs)
    assert 'src="http' not in page and "<link" not in page   # self-contained
    parsed = check_page(page)                     # anchors resolve, no literal markup
    assert "fig9" in parsed.ids
    worse = rp.regressions(rp.collect_claims(out, ["04_cg_offset"]))
    assert code == (1 if len(worse) else 0)


def test_two_runs_give_identical_csvs_and_figures(tiny_runs):
    (a, b), _ = tiny_runs
    files = sorted(p.relative_to(a) for p in a.rglob("*")
                   if p.suffix in (".csv", ".png", ".md") and p.is_file())
    assert any(p.suffix == ".png" for p in files) and len(files) >= 6
    for rel in files:
        assert filecmp.cmp(a / rel, b / rel, shallow=False), f"{rel} differs between runs"
    assert sorted(Path(p).relative_to(b) for p in b.rglob("*.csv")) == \
        [f for f in files if f.suffix == ".csv"]


@pytest.mark.parametrize("given, said", [
    (["-p", "n_points", "-2"], "n_points = -2; allowed"),
    (["-p", "04:aero_model", "foo"], "aero_model = 'foo'; allowed: thin_airfoil"),
    (["-p", "config", "nosuch.toml"], "no such configuration file: 'nosuch.toml'"),
    (["-p", "overrides", "{flap.cg_ofset: 0.2}"], "did you mean 'flap.cg_offset'"),
    (["-p", "overrides", "{flap.cg_offset: 3}"], "outside the allowed range [-1, 1]"),
    (["-p", "values", "{fig9: [a, b]}"], "values.fig9: cannot read 'a'"),
    (["-p", "values", "{fig9: [0.1, .nan]}"], "values.fig9: nan is not a number"),
])
def test_a_bad_parameter_value_is_refused_before_anything_runs(tmp_path, capsys, given, said):
    # the values are checked as `tefcore batch` checks them: one line, exit 2, no
    # notebook started and no output folder made
    out = tmp_path / "o"
    assert main(["reproduce", "--out", str(out), "--only", "04", "--no-variants",
                 "--no-progress", *given]) == 2
    err = capsys.readouterr().err
    assert said in err and "04_cg_offset" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()
