"""The sweep table's tracking: reused between the last refinement round and the table
only when the points are the very same results (a pure function of the records)."""

from __future__ import annotations

import pandas as pd

from tefcore.sweeps import table as T
from tests.sweeps.test_sweep import PARAM, XS, run


def test_a_cached_tracking_is_the_tracking_and_a_changed_point_is_tracked_again(monkeypatch):
    captured = {}
    real = T.build_table

    def spy(parameter, values, keys, records, cache=None):
        captured.update(args=(parameter, values, keys, records), cache=cache)
        return real(parameter, values, keys, records, cache)

    monkeypatch.setattr("tefcore.sweeps.sweep.build_table", spy)
    res = run()
    parameter, values, keys, records = captured["args"]
    cache = captured["cache"]
    # the sweep's last refinement round tracked these very records: the table
    # reused it, and it equals a tracking from scratch
    assert cache and len(cache["key"][0]) == len(XS)
    fresh, _, _ = real(parameter, values, keys, records)
    pd.testing.assert_frame_equal(res.table, fresh)

    calls = []
    track = T.track_modes
    monkeypatch.setattr(T, "track_modes", lambda *a, **k: calls.append(1) or track(*a, **k))
    real(parameter, values, keys, records, cache)
    assert calls == []                                   # same results: reused
    # one point's result replaced by an equal copy: not the same object, tracked again
    k0 = keys[3]
    changed = dict(records)
    changed[k0] = {**records[k0], "modes": {c: list(v) for c, v in records[k0]["modes"].items()}}
    again, _, _ = real(parameter, values, keys, changed, cache)
    assert calls == [1]
    pd.testing.assert_frame_equal(again, fresh)
    # a value moved: tracked again (the key compares the values)
    moved = dict(changed)
    moved[k0] = {**changed[k0], "value_si": changed[k0]["value_si"] + 1e-3}
    real(parameter, values, keys, moved, cache)
    assert calls == [1, 1]
    assert PARAM in set(fresh["parameter"])
