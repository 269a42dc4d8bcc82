"""The stability panels draw one root per line (tefcore.paper.figures.plotting.plot_modes)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from tefcore.paper.figures.plotting import plot_modes  # noqa: E402


def _table():
    """A sweep whose "TEF" name sits on root 4, moves to root 7 at one refined point
    (an exceptional point on each side of it: the spikes of Fig. 12b) and back,
    then is uncertain on root 4 over its last two points."""
    x = np.array([0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5])
    track = [4, 4, 4, 7, 4, 4, 4]
    rate = [-3.0, -3.1, -3.2, 0.5, -3.3, -3.4, -3.5]
    certain = [True, True, True, True, True, False, False]
    return pd.DataFrame({
        "point": range(7), "status": "ok", "value_si": x, "value": x, "label": "TEF",
        "track": track, "mode_id": 0, "refinement": [0, 0, 0, 3, 0, 0, 0],
        "real_part": rate, "frequency_per_rev": 10.0, "damping_ratio": 0.0,
        "identity_certain": certain, "dominant": "TEF", "flutter_root": False})


def test_a_line_never_joins_two_roots():
    """Known answer: the name's three pieces (root 4 up to 0.2, root 7 alone at 0.25,
    root 4 from 0.3 on) are drawn apart -- no line runs from a root at -3 /rev to
    one at +0.5 and back -- and a segment with
    an uncertain end is dotted (from the last certain point on)."""
    fig, ax = plt.subplots()
    plot_modes(ax, "fig9", _table(), labels=("TEF",), flutter=False)
    # the curves' lines: no markers, some data, not the zero line (axhline)
    drawn = [(line.get_linestyle(), np.asarray(line.get_xdata(), float))
             for line in ax.lines if line.get_marker() in ("None", "", None)
             and len(line.get_xdata()) > 0 and np.any(np.asarray(line.get_ydata()) != 0)]
    plt.close(fig)
    spans = sorted((style, tuple(float(v) for v in np.round(xs, 6))) for style, xs in drawn)
    assert spans == sorted([("-", (0.0, 0.1, 0.2)), ("-", (0.25,)), (":", (0.3, 0.4, 0.5))])


def test_the_flutter_roots_title_does_not_run_into_its_neighbours():
    """Fig. 15's locus: the flutter root continued from five modes, its title one line
    wider than its axes, ran into the TEF participation's title beside it."""
    from tefcore.paper.figures.plotting import locus_figure

    t = _table().assign(flutter_root=True, share_TEF=0.5, share_torsion=0.3, share_flap=0.2,
                        share_lag=0.0)
    names = ["TEF", "blade flap 5", "blade flap 4", "blade torsion 2", "blade flap 3"]
    t = pd.concat([t.assign(label=n, track=k, point=t["point"]) for k, n in enumerate(names)],
                  ignore_index=True)
    fig = locus_figure("fig15", t, labels=("TEF",))
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [ax.title.get_window_extent(renderer) for ax in fig.axes[:3] if ax.get_title()]
    plt.close(fig)
    assert len(boxes) == 3
    for left, right in zip(boxes, boxes[1:], strict=False):
        assert left.x1 <= right.x0, (left, right)            # side by side, never over
