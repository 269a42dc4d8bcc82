"""The batch file of ``tefcore batch``: runs, grids, layers, and clear errors.

Every problem is found before anything runs, as one :class:`BatchFileError`
naming the file, the run and the field, with a close match where there is
one; the fuzz tests check that nothing else ever escapes the parser.
"""

import re
import textwrap
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tefcore.cli import main
from tefcore.paper.run.batch_spec import BatchFileError, load_batch, parse_batch

pytest.importorskip("yaml")
pytest.importorskip("nbformat")
EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def parse(text, **kw):
    return parse_batch(textwrap.dedent(text), origin="runs.yaml", **kw)


def error(text, **kw) -> str:
    with pytest.raises(BatchFileError) as info:
        parse(text, **kw)
    msg = str(info.value)
    assert msg.startswith("runs.yaml: ") and "\n" not in msg and len(msg) < 600
    return msg


# ------------------------------------------------------------------ what a file means


def test_grid_is_the_product_with_readable_names_in_key_order():
    runs = parse("""
        notebooks: [03, 04]
        params: {all: {n_points: 5}}
        grid: {overrides.flap.cg_offset: [0.0, 0.15], overrides.flap.overhang: [0.2, 0.29, 0.4]}
    """)
    assert [r.name for r in runs] == [f"cg_offset={c}-overhang={o}" for c in (0.0, 0.15)
                                      for o in (0.2, 0.29, 0.4)]
    r = runs[4]
    assert r.notebooks == ("03_overhang", "04_cg_offset")
    for nb in r.notebooks:
        assert r.params[nb] == {"n_points": 5, "overrides": {"flap.cg_offset": 0.15,
                                                             "flap.overhang": 0.29}}
    assert r.settings == {"n_points": 5, "overrides.flap.cg_offset": 0.15,
                          "overrides.flap.overhang": 0.29}


def test_named_runs_layers_and_targeted_grid_keys():
    runs = parse("""
        notebooks: [04, 05]
        params:
          all: {overrides: {flight.advance_ratio: 0.2}, n_points: 3}
          05: {n_points: 4}
        runs:
          - name: base
          - name: stiff
            notebooks: [05]
            params: {all: {overrides: {actuator.stiffness: "163.04 ft-lb/rad"}}}
            grid: {05:values.fig11: [[0.75, 2.0], [1.0, 1.5]]}
    """, extra_params=[{"all": {"n_points": 6}}])
    assert [r.name for r in runs] == ["base", "stiff-fig11=0.75_2.0",
                                      "stiff-fig11=1.0_1.5"]
    base, stiff = runs[0], runs[1]
    assert base.notebooks == ("04_cg_offset", "05_stiffness")
    # command-line layers win over the file's; dictionaries merge key by key
    assert base.params["05_stiffness"] == {"n_points": 6,
                                           "overrides": {"flight.advance_ratio": 0.2}}
    assert stiff.params["05_stiffness"]["overrides"] == {
        "flight.advance_ratio": 0.2, "actuator.stiffness": "163.04 ft-lb/rad"}
    assert stiff.params["05_stiffness"]["values"] == {"fig11": [0.75, 2.0]}
    assert stiff.notebooks == ("05_stiffness",)


def test_only_keeps_the_runs_notebooks_and_drops_runs_without_any():
    text = """
        runs:
          - {name: a, notebooks: [04, 05]}
          - {name: b, notebooks: [07]}
    """
    runs = parse(text, only=["4"])
    assert [(r.name, r.notebooks) for r in runs] == [("a", ("04_cg_offset",))]
    assert "no run has any of these notebooks" in error(text, only=["03"])


def test_config_is_relative_to_the_batch_file_or_a_shipped_name(tmp_path):
    from tefcore.config.io import load_config, save_config

    save_config(load_config("mdart").with_overrides({"flap.cg_offset": 0.1}),
                tmp_path / "rotor.toml")
    f = tmp_path / "runs.yaml"
    f.write_text("runs: [{name: mine, config: rotor.toml}, {name: shipped, config: mdart}]\n"
                 "notebooks: [04]\n")
    mine, shipped = load_batch(f)
    assert mine.config == str((tmp_path / "rotor.toml").resolve())
    assert mine.settings["config"] == "rotor.toml" and shipped.config == "mdart"
    f.write_text("config: nothere.toml\n")
    with pytest.raises(BatchFileError, match="nothere.toml not found"):
        load_batch(f)
    (tmp_path / "bad.toml").write_text("[flap]\ncg_offset = 'x'\n")
    f.write_text("config: bad.toml\nnotebooks: [4]\nname: x\n")
    with pytest.raises(BatchFileError, match="config: .*bad.toml: missing required field"):
        load_batch(f)


def test_examples_parse_and_say_what_they_run():
    cls = load_batch(EXAMPLES / "class_assignment.yaml")
    assert len(cls) == 9 and {r.notebooks for r in cls} == {("03_overhang", "04_cg_offset")}
    assert cls[0].name == "cg_offset=0.0-overhang=0.2"
    rev = load_batch(EXAMPLES / "flap_inertia_doubled.yaml", only=["04"],
                     extra_params=[{"all": {"n_points": 4}}])
    assert [r.name for r in rev] == ["baseline", "flap-inertia-x2"]
    assert rev[1].params["04_cg_offset"] == {
        "overrides": {"flap.inertia_cg": "0.48 lb*in^2/ft"}, "n_points": 4}
    readme = (EXAMPLES / "README.md").read_text()
    assert "class_assignment.yaml" in readme and "flap_inertia_doubled.yaml" in readme


# ------------------------------------------------------------------ errors, named


@pytest.mark.parametrize("text, expected", [
    ("notebooks: [13]", "unknown notebook 13"),   # 01-11 exist
    ("notebooks: [4, 04_cg_offset]", "listed twice"),
    ("runs: [{name: a, notebooks: [cg_ofset]}]", "did you mean"),
    ("params: {07_flite: {n_points: 3}}", "unknown notebook '07_flite'"),
    ("grid: {99:n_points: [2, 3]}", "unknown notebook '99'"),
])
def test_unknown_notebook(text, expected):
    msg = error(text)
    assert expected in msg and "04_cg_offset" in msg


@pytest.mark.parametrize("text, expected", [
    ("notebooks: [4]\nname: a\nparams: {all: {n_pointz: 3}}",
     "04_cg_offset has no parameter 'n_pointz' (did you mean 'n_points'?)"),
    ("notebooks: [4]\ngrid: {n_pointz: [3, 4]}",
     "04_cg_offset has no parameter 'n_pointz' (did you mean 'n_points'?)"),
    ("notebooks: [4]\nname: a\nparams: {all: {overrides: {flap.inertia: 1.0}}}",
     "overrides: unknown field 'flap.inertia'"),
    ("notebooks: [4]\nname: a\nparams: {all: {output_dir: x}}", "sets each notebook's output"),
    ("notebooks: [4]\nname: a\nparams: {all: {config: x.toml}}", "'config' key"),
    ("notebooks: [4]\nname: a\nparams: {all: {n_points: 1}}", "n_points = 1; allowed"),
    ("notebooks: [4]\nname: a\nparams: {all: {aero_model: xfoyl}}", "aero_model = 'xfoyl'"),
    ("notebooks: [4]\nname: a\nparams: {all: {values: {fig8: [0.1]}}}",
     "04_cg_offset computes no figure 'fig8' (did you mean 'fig9'?)"),
    ("notebooks: [4]\nname: a\nparams: {all: {overrides: {flap.cg_offset: 5.0}}}",
     "flap.cg_offset"),
    ("notebooks: [4]\nname: a\nparams: {all: {n_points: .nan}}", "not a finite number"),
    ("runs: [{name: a, notebok: [4]}]", "unknown key 'notebok' (did you mean 'notebooks'?)"),
    ("gird: {n_points: [3]}", "unknown key 'gird' (did you mean 'grid'?)"),
])
def test_unknown_or_bad_parameter(text, expected):
    assert expected in error(text)


@pytest.mark.parametrize("text, expected", [
    ("grid: [overrides.flap.overhang, 0.2]", "a grid maps"),
    ("grid: {}", "a grid maps"),
    ("grid: {overrides.flap.overhang: 0.2}", "must be a non-empty list"),
    ("grid: {overrides.flap.overhang: []}", "must be a non-empty list"),
    ("grid: {overrides.flap.overhang: [0.2, 0.2]}", "value 0.2 is listed twice"),
    ("notebooks: [4]\ngrid: {n_points.x: [3, 4]}", "n_points is not a mapping parameter"),
    ("notebooks: [4]\ngrid: {05:n_points: [3, 4]}", "05_stiffness is not one of the run's"),
    ("grid: {2x: [1, 2]}", "'2x' is not a parameter name"),
    ("notebooks: [4]\ngrid: {n_points: [2, 3, 4, 5, 6, 7, 8, 9],\n"
     "       n_jobs: [1, 2, 3, 4, 5, 6, 7, 8],\n       damping_measure: [a, b, c, d, e, f, g, h]}",
     "more than 500 runs"),
    ("notebooks: [4]\ngrid: {overrides.flap.overhang: [0.2, 0.9]}",
     "run 'overhang=0.9', 04_cg_offset: overrides: flap.mass"),    # the flap does not fit
])
def test_bad_grid(text, expected):
    assert expected in error(text)


@pytest.mark.parametrize("text, expected", [
    ("runs: [{name: a}, {name: a}]", "duplicate run name 'a'"),
    ("runs: [{name: Base}, {name: base}]", "duplicate run name 'base'"),       # case-blind FS
    ("notebooks: [4]\ngrid: {overrides.flap.overhang: [0.2, '0.2']}", "duplicate run name"),
    ("runs: [{name: a/b}]", "is not a folder name"),
    ("runs: [{name: ../up}]", "is not a folder name"),
    ("runs: [{name: index.html}]", "taken by the batch's own files"),
    ("runs: [{notebooks: [4]}]", "a run needs a name"),
    ("name: x\nruns: [{name: a}]", "top-level name"),
    ("runs: []", "non-empty list of runs"),
    ("runs: [a, b]", "a run is a mapping"),
])
def test_bad_run_names(text, expected):
    assert expected in error(text)


@pytest.mark.parametrize("text, expected", [
    ("runs: [{name: a}\n", "not valid YAML (line 2"),
    ("grid: {a: [1, 2]\n  b: 3", "not valid YAML"),
    ("", "the file is empty"),
    ("- a\n- b", "top level must be a mapping"),
    ("params: {all: {when: 2024-01-01}}", "is not a number, string, list or mapping"),
    ("a: &x [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\nb: &y [*x, *x, *x, *x, *x, *x, *x, *x, *x, *x]\n"
     "c: &z [*y, *y, *y, *y, *y, *y, *y, *y, *y, *y]\nd: &w [*z, *z, *z, *z, *z, *z, *z, *z, *z]\n"
     "e: [*w, *w, *w, *w, *w, *w, *w, *w, *w, *w, *w, *w, *w, *w]", "more than 100000 values"),
])
def test_bad_yaml(text, expected):
    assert expected in error(text)


def test_cli_gives_one_line_for_a_bad_batch_file(tmp_path, capsys):
    f = tmp_path / "runs.yaml"
    f.write_text("notebooks: [04]\nname: a\nparams: {all: {n_pointz: 3}}\n")
    assert main(["batch", str(f), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "n_pointz" in err and "n_points" in err
    assert "Traceback" not in err and not (tmp_path / "out").exists()   # nothing ran
    assert main(["batch", str(tmp_path / "none.yaml"), "--out", str(tmp_path / "o")]) == 2
    assert "cannot read the batch file" in capsys.readouterr().err


# ------------------------------------------------------------------ fuzzing (bounded time)

FUZZ = settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])

scalar = st.one_of(st.none(), st.booleans(), st.integers(-3, 700), st.floats(allow_nan=True),
                   st.text(max_size=8),
                   st.sampled_from(["04", "4", "all", "0.2", "800 lb/in", "fig9", "x.toml",
                                    "mdart", "thin_airfoil", "table", "flap.overhang"]))
key = st.one_of(st.sampled_from(["config", "grid", "name", "notebooks", "params", "runs",
    "all", "04", "05_stiffness", "03:n_points", "overrides.flap.overhang", "n_points",
    "overrides", "values", "fig9", "interactive", "flap.cg_offset", "04:values.fig9",
    "damping_measure", "n_jobs", "aero_model", "output_dir"]), st.text(max_size=6))
document = st.recursive(scalar, lambda inner: st.one_of(
    st.lists(inner, max_size=3), st.dictionaries(key, inner, max_size=4)), max_leaves=12)


@FUZZ
@given(doc=st.dictionaries(key, document, max_size=5))
def test_fuzz_structured_documents_give_runs_or_a_batch_file_error(doc):
    import yaml

    try:
        runs = parse_batch(yaml.safe_dump(doc), origin="fuzz.yaml")
    except BatchFileError as exc:
        assert str(exc).startswith("fuzz.yaml: ")
        return
    assert runs and all(re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._=+-]{0,99}", r.name)
                        for r in runs)
    assert len({r.name.lower() for r in runs}) == len(runs)


@FUZZ
@given(text=st.text(alphabet=st.sampled_from(list("{}[]:,-&*!|>'\"#% \n\tab04.=")),
                    max_size=60))
def test_fuzz_arbitrary_text_gives_runs_or_a_batch_file_error(text):
    try:
        parse_batch(text, origin="fuzz.yaml")
    except BatchFileError:
        pass
