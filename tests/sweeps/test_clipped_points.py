"""A point whose C81 table inputs were clipped says so; a sweep or map warns once.

The packaged XFOIL deck at mu = 0.3 clips (alpha beyond 16 deg on the
retreating side, Mach beyond 0.7 at the advancing tip); in hover it does not.
"""

import json
import warnings

from tefcore.aero.c81 import C81RangeWarning
from tefcore.sweeps.maps import stability_map
from tefcore.sweeps.sweep import sweep
from tests.linear.test_stability_signal import XFOIL


def run(func, *args, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = func(*args, **kw)
    return result, [w for w in caught if issubclass(w.category, C81RangeWarning)]


def test_a_sweep_marks_clipped_points_and_warns_once(tmp_path):
    out = tmp_path / "s.jsonl"
    res, caught = run(sweep, XFOIL, "flight.advance_ratio", [0.0, 0.3], out=out,
                      progress=False, refine=False)
    points = res.table.drop_duplicates("point").set_index("value")
    assert points.loc[0.0, "warning"] is None                 # hover: inside the table
    assert "C81 deck 'NACA0012 35%TEF XFOIL'" in points.loc[0.3, "warning"]
    assert "alpha reached" in points.loc[0.3, "warning"]
    assert (points["status"] == "ok").all()                  # the values are kept
    assert len(caught) == 1 and res.n_clipped == 1
    assert "clipped at 1 of 2 points" in str(caught[0].message)
    # stored with the point, so a resumed sweep says the same
    rec = [json.loads(x) for x in out.read_text().splitlines()[1:]]
    assert [r["key"] for r in rec if "clipped" in r] == ["0.3"]
    again, caught = run(sweep, XFOIL, "flight.advance_ratio", [0.0, 0.3], out=out,
                        progress=False, refine=False)
    assert again.n_computed == 0 and len(caught) == 1
    assert list(again.table["warning"]) == list(res.table["warning"])


def test_a_map_marks_clipped_points_and_warns_once():
    m, caught = run(stability_map, XFOIL, "flight.advance_ratio", [0.0, 0.3],
                    "flap.cg_offset", [0.0, 0.1], progress=False, refine_boundary=False)
    assert m.table.loc[m.table["x"] == 0.3, "warning"].str.contains("alpha reached").all()
    assert m.table.loc[m.table["x"] == 0.0, "warning"].isna().all()
    assert len(caught) == 1 and "clipped at 2 of 4 points" in str(caught[0].message)


class ClippingToy:
    """The toy map's point (flutter where cg_offset + overhang^2 > 0.3), each call warning
    that a C81 deck clipped its inputs, as a point of the XFOIL deck at mu = 0.3 does."""

    def __call__(self, cfg):
        from tefcore.aero.c81.range_summary import range_warning
        from tests.sweeps.test_stability_map import Toy

        x = cfg.flap.cg_offset
        clipped = {"calls": 3, "decks": ["TOY"], "extremes": {"alpha": [20 + x, -15, 15]}}
        warnings.warn(range_warning(f"clipped at {x}", clipped), stacklevel=2)
        return Toy()(cfg)


def test_the_boundary_refinement_warns_once():
    # the refinement's brentq evaluations printed one C81RangeWarning each (27 lines)
    m, caught = run(stability_map, XFOIL, "flap.cg_offset", [0.0, 0.2, 0.4], "flap.overhang",
                    [0.0, 0.2], point=ClippingToy(), progress=False)
    assert len(m.boundary) == 2 and m.boundary["converged"].all()
    refine = [w for w in caught if "boundary" in str(w.message)]
    assert len(caught) == 2 and len(refine) == 1, [str(w.message) for w in caught]
    text = str(refine[0].message)
    assert "refining 2 of 2 crossings" in text and "C81 deck 'TOY'" in text
    # the most extreme input of all the evaluations, not the last one's
    assert refine[0].message.clipped["extremes"]["alpha"][0] > 20.2
