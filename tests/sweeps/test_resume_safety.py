"""Resuming a sweep refuses stale inputs and damaged files.

The header of a sweep file records everything that decides a point: the
configuration, the content of the files it refers to (the C81 deck), the
tefcore version and the model code.  Resuming when any of them changed must
refuse, naming what changed; a damaged record must be a clear error.
"""

import json
import shutil
from pathlib import Path

import pytest

from tefcore.aero.c81 import example_deck_path
from tefcore.sweeps.sweep import sweep
from tests.sweeps.test_sweep import MDART, PARAM, XS, ToyPoint, run


def rewrite_header(path, **changes):
    head, *rest = Path(path).read_text().splitlines(keepends=True)
    head = json.loads(head)
    head.update(changes)
    Path(path).write_text(json.dumps(head) + "\n" + "".join(rest))


@pytest.fixture
def c81_config(tmp_path):
    deck = tmp_path / "deck.c81"
    shutil.copyfile(example_deck_path(), deck)
    cfg = MDART.with_overrides({"model.aero_model": "c81", "model.c81_deck": str(deck)})
    return cfg, deck


def test_resume_refuses_a_c81_deck_edited_in_place(tmp_path, c81_config):
    """After the deck is edited at the same path, resuming refuses the old points."""
    cfg, deck = c81_config
    out = tmp_path / "s.jsonl"
    sweep(cfg, PARAM, XS[:3], point=ToyPoint(), out=out, progress=False)
    text = deck.read_text()
    deck.write_text(text.replace(" .01000", " .02000", 1))   # same path, new drag
    p = ToyPoint()
    with pytest.raises(ValueError, match=r"cannot resume .*model\.c81_deck has changed"):
        sweep(cfg, PARAM, XS[:3], point=p, out=out, progress=False)
    assert p.calls == 0
    head = json.loads(out.read_text().splitlines()[0])
    assert head["inputs"]["model.c81_deck"].startswith("sha256:")
    deck.write_text(text)                              # the same content again: resumes
    res = sweep(cfg, PARAM, XS[:3], point=p, out=out, progress=False)
    assert res.n_loaded == 3 and p.calls == 0


def test_resume_refuses_another_tefcore_version(tmp_path):
    """A header claiming another tefcore version is refused."""
    out = tmp_path / "s.jsonl"
    run(XS[:2], out=out)
    rewrite_header(out, tefcore_version="0.0.1")
    with pytest.raises(ValueError, match=r"cannot resume .*tefcore version \('0\.0\.1' then"):
        run(XS[:2], out=out)


def test_resume_refuses_another_model_code(tmp_path):
    from tefcore.errors import SweepFileError
    from tefcore.provenance import model_stamp

    out = tmp_path / "s.jsonl"
    run(XS[:2], out=out)
    assert json.loads(out.read_text().splitlines()[0])["model_stamp"] == model_stamp()
    rewrite_header(out, model_stamp="0123456789abcdef")
    with pytest.raises(SweepFileError, match="model code"):
        run(XS[:2], out=out)
    # resume=False starts afresh with the current stamp
    res = run(XS[:2], out=out, resume=False)
    assert res.n_computed == 2


def test_resume_says_when_the_numerical_stack_differs_and_goes_on(tmp_path):
    # another numpy or BLAS kernel changes the last digits, never a name or a
    # verdict: the header records it and a resumed run says so, reusing the points
    from tefcore.provenance import numerical_environment

    out = tmp_path / "s.jsonl"
    run(XS[:2], out=out)
    head = json.loads(out.read_text().splitlines()[0])
    assert head["environment"] == numerical_environment()
    then = dict(head["environment"], blas="openblas 0.3.20 Sandybridge")
    rewrite_header(out, environment=then)
    with pytest.warns(UserWarning, match=r"computed with blas openblas 0\.3\.20 Sandybridge "
                                         r"\(now "):
        res = run(XS[:2], out=out)
    assert res.n_loaded == 2 and res.n_computed == 0


def test_resume_refuses_a_version_1_file_that_recorded_no_inputs(tmp_path):
    out = tmp_path / "s.jsonl"
    run(XS[:2], out=out)
    head = json.loads(out.read_text().splitlines()[0])
    old = {k: v for k, v in head.items() if k not in ("inputs", "model_stamp")}
    Path(out).write_text(json.dumps({**old, "version": 1}) + "\n"
                         + "".join(out.read_text().splitlines(keepends=True)[1:]))
    with pytest.raises(ValueError, match="version 1.*cannot be checked"):
        run(XS[:2], out=out)


def test_model_stamp_covers_the_numerics_not_the_presentation():
    from tefcore.provenance import PRESENTATION_MODULES

    assert {"cli", "safe_io", "sweeps.boundary"} <= PRESENTATION_MODULES
    assert not {"floquet._analysis", "linear.stability", "model.coupled", "trimming.trim",
                "config.sections"} & PRESENTATION_MODULES


@pytest.mark.parametrize("line, reason", [
    ("{}", "a record without 'key'"),                                  # not a KeyError
    ("[1, 2]", "a JSON list, not a record"),
    ('{"key": "0.5", "status": "ok", "value_si": 0.5, "error": null, "trim": {}, '
     '"modes": {"label": ["TEF"]}}', "lacks the column"),
    ('{"key": "0.5", "status": "maybe", "value_si": 0.5, "error": null, "trim": {}, '
     '"modes": null}', "'status' must be"),
    ('{"key": "0.5", "status": "ok", "value_si": 0.5, "error": null, "trim": {}, "modes": '
     '{"mode_id": [0], "label": ["TEF"], "frequency_per_rev": ["x"], "real_part": [0.1], '
     '"damping_ratio": [0.0]}}', "must hold numbers"),
    ("\xff\xfe not text", "not a JSON record"),
])
def test_a_damaged_record_is_a_clear_error_naming_the_line(tmp_path, line, reason):
    """A ``{}`` line in a sweep file is an error naming the line, not a KeyError."""
    out = tmp_path / "s.jsonl"
    run(XS[:2], out=out)
    with open(out, "ab") as f:
        f.write(line.encode("latin-1") + b"\n")
    with pytest.raises(ValueError, match=rf"s\.jsonl, line 4: .*{reason}"):
        run(XS[:3], out=out)
