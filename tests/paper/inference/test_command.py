"""``tefcore infer``: the estimate before the study, what the study holds after."""

from tefcore.cli import main
from tefcore.paper.inference.study import StudySpec, run_study

from . import fakes


def test_infer_shows_the_estimate_then_the_study(tmp_path, capsys, fixed_protocol):
    storage = str(tmp_path / "s.journal")
    # a study the stand-in filled, under the name the command gives it
    run_study(StudySpec(storage=storage, protocol=fixed_protocol,
                        name="protocol-continued-tpe-seed0"), 3, evaluator=fakes.quick)
    assert main(["infer", "--trials", "3", "--storage", storage]) == 0
    out = capsys.readouterr().out
    first, *rest = out.splitlines()
    assert first.startswith("protocol-continued-tpe-seed0 in ")
    assert "3 trials done, 0 to run" in first and "measured on its trials" in first
    assert "rotors checked" in rest[0] and "refused as physically impossible" in rest[0]
    assert any(line.startswith("  trial ") for line in rest)


def test_a_new_study_is_estimated_before_any_trial(tmp_path, capsys):
    assert main(["infer", "--trials", "0", "--storage", str(tmp_path / "new.journal"),
                 "--reading", "flutter", "--sampler", "qmc"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("protocol-flutter-qmc-seed0 in ")
    assert "assumed before any trial" in out and "0 rotors checked" in out


def test_bad_numbers_are_one_line(tmp_path, capsys):
    assert main(["infer", "--jobs", "0", "--storage", str(tmp_path / "x.journal")]) == 2
    err = capsys.readouterr().err
    assert err == "tefcore: error: --jobs 0: must be at least 1\n"
