"""Mode tracking along a parameter sweep: one curve is one physical mode.

An eigen-solver returns the modes of each sweep point in its own order
(usually by frequency), so where two modes cross in frequency, "mode 3" at
one point is "mode 4" at the next.  :func:`track_modes` re-orders them so that
each ``track`` follows one mode, matching the modes of consecutive points by
an optimal assignment (:func:`scipy.optimize.linear_sum_assignment`) on the
cost

.. math::

    C_{ij} = w_\\text{mac}\\,(1 - \\text{MAC}_{ij})
           + w_\\lambda\\,\\frac{|\\hat\\lambda_i - \\lambda_j|}{|\\hat\\lambda_i| + |\\lambda_j|}

between track *i* (its last eigenvector and its eigenvalue extrapolated
linearly to the new parameter value, :math:`\\hat\\lambda_i`) and mode *j* of
the new point, with eigenvalues :math:`\\lambda = \\text{real\\_part} +
i\\,\\text{frequency\\_per\\_rev}` in /rev.  Both terms lie in [0, 1], so
the default weights ``mac_weight = eig_weight = 1`` make them equally
important: far from a crossing they agree; at a frequency crossing the
eigenvalue term is ~0 for both candidates and the mode shape (MAC) decides;
where shapes mix (veering), MAC is similar for both candidates and the
extrapolated eigenvalue decides.  Without eigenvectors (e.g. points loaded
from a resumed sweep file) the MAC term is left out and the extrapolated
eigenvalue alone decides, which still follows straight crossings.

Each track keeps the ``label`` its mode had where the track starts; the
point function's own label at each point is kept as ``label_here``, so a
label that changes along a curve (a mode that changes character, or labels
assigned by frequency order) is visible, and :func:`label_changes` lists it.

Examples
--------
Two modes whose frequencies cross; the solver lists them by frequency:

>>> import numpy as np, pandas as pd
>>> def pt(x):
...     f = {"a": 1.0 + x, "b": 2.0 - x}
...     order = sorted(f, key=f.get)
...     modes = pd.DataFrame({"mode_id": [0, 1], "label": order,
...                           "frequency_per_rev": [f[k] for k in order],
...                           "real_part": [-0.01, -0.02] if order[0] == "a" else [-0.02, -0.01]})
...     vecs = np.array([[1, 0] if k == "a" else [0, 1] for k in order], complex).T
...     return modes, vecs
>>> t = track_modes([pt(x) for x in (0.0, 0.4, 0.8)], values=[0.0, 0.4, 0.8])
>>> for label, curve in t.groupby("label"):
...     print(label, curve["frequency_per_rev"].tolist(), curve["label_here"].tolist())
a [1.0, 1.4, 1.8] ['a', 'a', 'a']
b [2.0, 1.6, 1.2] ['b', 'b', 'b']
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.optimize import linear_sum_assignment

__all__ = ["label_changes", "mac", "match_modes", "track_modes"]

#: Columns every modes table must have.
MODE_COLUMNS = ("mode_id", "label", "frequency_per_rev", "real_part")


def mac(phi_a, phi_b) -> np.ndarray:
    """Modal assurance criterion between the columns of two (complex) mode sets.

    ``MAC[i, j] = |phi_a[:, i]^H phi_b[:, j]|^2 / ((phi_a_i^H phi_a_i)(phi_b_j^H phi_b_j))``,
    which is 1 for parallel vectors (whatever their complex scaling) and 0
    for orthogonal ones.

    Parameters
    ----------
    phi_a : array_like, shape (n,) or (n, p)
    phi_b : array_like, shape (n,) or (n, q)

    Returns
    -------
    ndarray, shape (p, q)
        (A 1-D input counts as one column.)

    Raises
    ------
    ValueError
        Different vector lengths, or a zero (or non-finite) vector.

    Examples
    --------
    >>> import numpy as np
    >>> a = np.array([[1, 0], [1j, 1], [0, 0]])
    >>> mac(a, a * (2 - 3j)).round(3)
    array([[1. , 0.5],
           [0.5, 1. ]])
    """
    a = np.asarray(phi_a)
    b = np.asarray(phi_b)
    a = a[:, None] if a.ndim == 1 else a
    b = b[:, None] if b.ndim == 1 else b
    if a.ndim != 2 or b.ndim != 2:
        raise ValueError(f"mode sets must be 1-D or 2-D, got shapes {a.shape} and {b.shape}")
    if a.shape[0] != b.shape[0]:
        raise ValueError(f"mode vectors differ in length: {a.shape[0]} and {b.shape[0]}")
    na = np.einsum("ij,ij->j", a.conj(), a).real
    nb = np.einsum("ij,ij->j", b.conj(), b).real
    for name, norms in (("phi_a", na), ("phi_b", nb)):
        bad = ~(np.isfinite(norms) & (norms > 0))
        if bad.any():
            raise ValueError(f"{name} column(s) {np.flatnonzero(bad).tolist()} are zero or "
                             "non-finite: MAC undefined")
    cross = a.conj().T @ b
    return np.abs(cross) ** 2 / np.outer(na, nb)


def _eig(modes: pd.DataFrame) -> np.ndarray:
    return modes["real_part"].to_numpy(float) + 1j * modes["frequency_per_rev"].to_numpy(float)


def _eig_distance(pred: np.ndarray, eig: np.ndarray) -> np.ndarray:
    diff = np.abs(pred[:, None] - eig[None, :])
    scale = np.abs(pred)[:, None] + np.abs(eig)[None, :]
    return np.divide(diff, scale, out=np.zeros_like(diff), where=scale > 0)


def _cost(pred, vecs_prev, eig, vecs, mac_weight, eig_weight) -> np.ndarray:
    """Assignment cost (rows: previous modes/tracks, columns: new modes)."""
    cost = eig_weight * _eig_distance(pred, eig)
    if vecs is None or mac_weight == 0:
        return cost
    for i, v in enumerate(vecs_prev):
        if v is not None and v.shape[0] == vecs.shape[0]:
            cost[i] += mac_weight * (1.0 - mac(v, vecs)[0])
    return cost


def match_modes(prev, curr, *, predicted=None, mac_weight=1.0, eig_weight=1.0) -> np.ndarray:
    """Which mode of `curr` continues each mode of `prev`.

    Parameters
    ----------
    prev, curr
        Points: a result object with ``modes`` (DataFrame) and
        ``eigenvectors`` attributes, a ``(modes, eigenvectors)`` tuple, a
        mapping with those keys, or a bare modes DataFrame (no vectors).
    predicted : array_like of complex, optional
        Eigenvalues of `prev` extrapolated to `curr` (default: as in `prev`).
    mac_weight, eig_weight : float
        Weights of the cost (see the module docstring).

    Returns
    -------
    ndarray of int, one per row of ``prev.modes``
        Row index in ``curr.modes``, or -1 when `curr` has fewer modes and
        this one is left unmatched.
    """
    pm, pv = _as_point(prev)
    cm, cv = _as_point(curr)
    pred = _eig(pm) if predicted is None else np.asarray(predicted, complex)
    vecs_prev = [None if pv is None else pv[:, i] for i in range(len(pm))]
    cost = _cost(pred, vecs_prev, _eig(cm), cv, mac_weight, eig_weight)
    rows, cols = linear_sum_assignment(cost)
    out = np.full(len(pm), -1)
    out[rows] = cols
    return out


def _as_point(p):
    """Normalise a point to (modes DataFrame, eigenvectors ndarray or None)."""
    if isinstance(p, pd.DataFrame):
        modes, vecs = p, None
    elif isinstance(p, Mapping):
        modes, vecs = p["modes"], p.get("eigenvectors")
    elif isinstance(p, tuple) and len(p) == 2:
        modes, vecs = p
    elif hasattr(p, "modes"):
        modes, vecs = p.modes, getattr(p, "eigenvectors", None)
    else:
        raise TypeError(f"cannot read modes from {type(p).__name__}")
    missing = [c for c in MODE_COLUMNS if c not in modes.columns]
    if missing:
        raise ValueError(f"modes table lacks column(s) {missing}")
    modes = modes.reset_index(drop=True)
    if vecs is not None:
        vecs = np.asarray(vecs)
        if vecs.ndim != 2 or vecs.shape[1] != len(modes):
            raise ValueError(f"eigenvectors of shape {vecs.shape} do not match "
                             f"{len(modes)} modes (one column per mode)")
    return modes, vecs


@dataclass
class _Track:
    label: str
    eig: list = field(default_factory=list)  # last two (x, eigenvalue)
    vec: np.ndarray | None = None
    last_label: str = ""

    def predict(self, x, use: bool) -> complex:
        (x1, e1) = self.eig[-1]
        if use and len(self.eig) == 2:
            (x0, e0) = self.eig[0]
            if x1 != x0 and np.isfinite(e0) and np.isfinite(e1):
                return e1 + (e1 - e0) * (x - x1) / (x1 - x0)
        return e1

    def update(self, x, eig, vec, label=""):
        self.eig = [*self.eig[-1:], (x, eig)]
        self.last_label = label
        if vec is not None:
            self.vec = vec


def track_modes(points: Sequence, values=None, *, mac_weight: float = 1.0,
                eig_weight: float = 1.0, predict: bool = True,
                label_weight: float = 0.0) -> pd.DataFrame:
    """Order the modes of successive sweep points into continuous tracks.

    Parameters
    ----------
    points : sequence
        One entry per sweep point, in sweep order: a result with ``modes``
        and ``eigenvectors`` attributes (e.g. a ``StabilityResult``), a
        ``(modes, eigenvectors)`` tuple, a mapping with those keys, or a
        bare modes DataFrame; ``None`` for a failed point (skipped; tracks
        continue across the gap).  Modes tables need the columns
        ``mode_id``, ``label``, ``frequency_per_rev`` and ``real_part``.
        Eigenvectors (columns aligned with the rows of ``modes``) may be
        missing for some or all points; MAC is used where both sides have
        vectors of the same length.
    values : sequence of float, optional
        Parameter value of each point, for the linear extrapolation of the
        eigenvalues; default: equally spaced.
    mac_weight, eig_weight : float
        Weights of (1 - MAC) and of the normalised eigenvalue distance in
        the assignment cost (module docstring).
    predict : bool
        Extrapolate each track's eigenvalue linearly from its last two
        points (default) instead of comparing with its last value.
    label_weight : float
        Cost added when a mode's own label (participation-based, without a
        ``(locked)`` suffix) differs from the label the track carried at the
        previous point. Where two modes coalesce in flutter their shapes mix
        and the extrapolated eigenvalues mislead, while the participation
        still tells which one the flap drives; with weight 1 a track follows
        its label unless MAC and eigenvalue together disagree by more than
        one unit of cost. Default 0: labels assigned by frequency order, as
        some solvers do, would mislead, and even participation labels flip
        between points where two modes coalesce.

    Returns
    -------
    DataFrame
        One row per (point, mode): ``step`` (index into `points`),
        ``track`` (0, 1, ... in the order of the first point's modes; modes
        that cannot be matched start new tracks), ``label`` (the track's
        label where it starts), ``label_here`` (the point's own label), and
        the remaining columns of the modes tables.  Sorted by step, track.
    """
    if mac_weight < 0 or eig_weight < 0 or mac_weight + eig_weight == 0:
        raise ValueError("mac_weight and eig_weight must be >= 0 and not both 0")
    if values is None:
        values = np.arange(len(points), dtype=float)
    values = list(values)
    if len(values) != len(points):
        raise ValueError(f"{len(values)} values for {len(points)} points")
    tracks: list[_Track] = []
    frames = []
    for step, (p, x) in enumerate(zip(points, values, strict=True)):
        if p is None:
            continue
        modes, vecs = _as_point(p)
        try:
            x = float(x)
        except (TypeError, ValueError):
            x = float(step)
        eig = _eig(modes)
        col_vec = [None if vecs is None else vecs[:, j] for j in range(len(modes))]
        assigned = np.full(len(modes), -1)
        base = [str(lab).split(" (")[0] for lab in modes["label"]]
        if tracks and len(modes):
            pred = np.array([t.predict(x, predict) for t in tracks])
            cost = _cost(pred, [t.vec for t in tracks], eig, vecs, mac_weight, eig_weight)
            if label_weight:
                last = np.array([t.last_label for t in tracks], dtype=object)
                cost = cost + label_weight * (last[:, None] != np.array(base, dtype=object))
            rows, cols = linear_sum_assignment(cost)
            assigned[cols] = rows
        for j in np.flatnonzero(assigned < 0):
            tracks.append(_Track(label=str(modes["label"].iloc[j])))
            assigned[j] = len(tracks) - 1
        for j, t in enumerate(assigned):
            tracks[t].update(x, eig[j], col_vec[j], base[j])
        frame = modes.drop(columns="label")
        frame.insert(0, "label_here", modes["label"])
        frame.insert(0, "label", [tracks[t].label for t in assigned])
        frame.insert(0, "track", assigned)
        frame.insert(0, "step", step)
        frames.append(frame)
    if not frames:
        return pd.DataFrame(columns=["step", "track", "label", "label_here", "mode_id",
                                     "frequency_per_rev", "real_part"])
    out = pd.concat(frames, ignore_index=True)
    return out.sort_values(["step", "track"], kind="stable", ignore_index=True)


def label_changes(tracked: pd.DataFrame) -> pd.DataFrame:
    """Where the point function's label of a tracked mode changes along its track.

    Parameters
    ----------
    tracked : DataFrame
        Output of :func:`track_modes` (or a sweep table), with columns
        ``track``, ``label`` and ``label_here``, in sweep order.

    Returns
    -------
    DataFrame
        One row per change: ``track``, ``label`` (the track's label),
        ``row`` (index in `tracked` where the new label first appears),
        ``from_label`` and ``to_label``.
    """
    rows = []
    valid = tracked[tracked["track"].notna()]
    for track, g in valid.groupby("track", sort=True):
        here = g["label_here"].astype(str).to_numpy()
        for k in np.flatnonzero(here[1:] != here[:-1]) + 1:
            rows.append({"track": track, "label": g["label"].iloc[k], "row": g.index[k],
                         "from_label": here[k - 1], "to_label": here[k]})
    return pd.DataFrame(rows, columns=["track", "label", "row", "from_label", "to_label"])
