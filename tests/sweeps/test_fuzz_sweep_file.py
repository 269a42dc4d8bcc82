"""Fuzzing sweep files: a truncated or garbled file is resumed or refused with a ValueError.

A ``{}`` line must not end in a KeyError, nor a stale file be resumed: a
valid sweep file is damaged -- truncated at any byte, lines
replaced by garbage or other JSON, duplicated or deleted, the header edited
-- and resumed.  The only allowed outcomes are a :class:`~tefcore.sweeps.sweep.SweepResult`
(the points that survived loaded, the others recomputed) or a ``ValueError``
(:class:`~tefcore.errors.SweepFileError`) naming the file.
"""

import json
import tempfile
import warnings
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tefcore.sweeps.sweep import SweepResult, sweep
from tests.sweeps.test_sweep import MDART, PARAM, ToyPoint, toy_result  # noqa: F401

VALUES = [0.0, 0.25, 0.5, 0.75]


def fresh_file(folder: Path) -> bytes:
    sweep(MDART, PARAM, VALUES, point=ToyPoint(fail_at=[0.5]), out=folder / "s.jsonl",
          progress=False)
    return (folder / "s.jsonl").read_bytes()


with tempfile.TemporaryDirectory() as _folder:
    GOOD = fresh_file(Path(_folder))
GOOD_LINES = GOOD.split(b"\n")[:-1]

json_value = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20), st.floats(),
              st.text(max_size=8)),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.sampled_from(
                                ["key", "status", "value_si", "error", "trim", "modes", "label",
                                 "real_part", "format", "version", "x"]), inner, max_size=4)),
    max_leaves=10)


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_damaged_sweep_files_resume_or_fail_with_a_value_error(data):
    lines = list(GOOD_LINES)
    kind = data.draw(st.sampled_from(["truncate", "garble", "json", "duplicate", "delete",
                                      "header", "field"]))
    k = data.draw(st.integers(0, len(lines) - 1))
    if kind == "garble":
        lines[k] = data.draw(st.binary(max_size=40)).replace(b"\n", b" ")
    elif kind == "json":
        lines[k] = json.dumps(data.draw(json_value)).encode()
    elif kind == "duplicate":
        lines.insert(k, lines[k])
    elif kind == "delete":
        del lines[k]
    elif kind in ("header", "field"):
        rec = json.loads(lines[0 if kind == "header" else k])
        key = data.draw(st.sampled_from(sorted(rec)))
        rec[key] = data.draw(json_value)
        lines[0 if kind == "header" else k] = json.dumps(rec).encode()
    text = b"\n".join(lines) + b"\n"
    if kind == "truncate":
        text = GOOD[:data.draw(st.integers(0, len(GOOD)))]
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "s.jsonl"
        out.write_bytes(text)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)   # incomplete last line, point
                res = sweep(MDART, PARAM, VALUES, point=ToyPoint(fail_at=[0.5]), out=out,
                            progress=False)
        except ValueError as err:
            assert str(out) in str(err)
            return
    assert isinstance(res, SweepResult)
    assert res.n_loaded + res.n_computed == len(VALUES)
    assert res.table["status"].tolist().count("failed") >= 1     # 0.5 still fails
