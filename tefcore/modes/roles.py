"""The roles a root plays: the TEF mode, the flutter root, and a claim's mode.

A root's *name* is where it comes from: the uncoupled mode it continues into
as the blade-flap coupling is switched on
(:func:`tefcore.modes.continuation.continue_roots`; :func:`name_roots` writes
it into a point's modes table).  A *role* is a name given to one root of each
point by a rule that says why:

* **the TEF mode** -- the root the uncoupled flap mode continues into (the
  rows named ``TEF``; along a sweep the *TEF branch*, ``tef_branch``);
* **the flutter root** -- the least stable *flap-induced* root of a point:
  a root that freeing the flap makes unstable, or much less stable, than it
  is with the flap held at its trimmed motion (:func:`flap_induced`,
  :func:`flutter_root`);
* **a claim's mode** -- the rows of a figure's table that a claim about
  ``"TEF"``, ``"blade torsion 1"`` or ``"flutter root"`` is about
  (:func:`mode_rows`).

Which root is which has no answer at one kind of place only: an
**exceptional point**, where two roots of the family in (parameter,
coupling) coalesce; passing it, the names of two roots exchange.  Along a
sweep it shows as a root whose name changes between neighbouring points, or
a point where two paths met (:func:`exceptional_points`); a claim whose range
holds one for its mode is undecided.

Examples
--------
The blade torsion root is unstable with the flap free (+0.3 /rev) and stable
with it held (-0.5): flap-induced, and the least stable such root.  The
lag root is unstable either way, the flap changing little: not the flap's.

>>> import pandas as pd
>>> modes = pd.DataFrame({"label": ["blade lag 1", "TEF", "blade torsion 1"],
...                       "real_part": [0.4, -0.05, 0.3],
...                       "real_part_uncoupled": [0.39, -1.2, -0.5],
...                       "flap_motion": [1e-6, 0.9, 0.2]})
>>> flap_induced(modes).tolist(), flutter_root(modes)
([False, True, True], 2)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .continuation import FLAP_ACTIVE
from .names import (
    TEF_NAME,
    base_name,
    is_tef,
    locked_name,
    mode_kind,
    pair_labels,
    pair_text,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["FLUTTER_PARTICIPATION", "FLUTTER_ROOT", "RATE_RESOLUTION", "ModeNotFound",
           "assign_roles", "exceptional_points", "flap_induced", "flutter_root",
           "mode_rows", "name_roots", "named_columns", "switch_steps", "uncoupled_relation",
           "undecided_steps"]

#: Least share of the flap's participation for a root to count as a flutter root
#: where roots are not named by continuation (a point function that labels its
#: modes otherwise): a tenth.
FLUTTER_PARTICIPATION = 0.1

#: The ``mode`` of a claim about the flutter root of each point.
FLUTTER_ROOT = "flutter root"

#: Smallest rise of a damping rate [/rev] that counts as the flap's doing: the
#: resolution of the paper's damping plots (about 0.01 /rev), ten times the
#: Floquet exponents' accuracy (:data:`tefcore.floquet.DEFAULT_ATOL`).
RATE_RESOLUTION = 1e-2


class ModeNotFound(ValueError):
    """The rows a mode's role asks for are not in the table."""


# ------------------------------------------------------------------ one point


def flap_induced(modes: pd.DataFrame) -> np.ndarray:
    """Which roots of a point the flap makes unstable, or much less stable.

    A root of the coupled system continues from a root of the uncoupled one
    (``real_part_uncoupled``, :func:`name_roots`): for a blade root, the root
    of the blade with the flap held at its trimmed motion; for the TEF, the
    flap alone.  The rule (docs/theory.md 9.2): the TEF root is the flap's
    own; a blade root is flap-induced when the flap moves in it (``flap_motion
    >=`` :data:`tefcore.modes.continuation.FLAP_ACTIVE`: a root without flap
    motion is not driven through the flap), freeing the flap raises its real
    part by more than :data:`RATE_RESOLUTION`, and either it was stable with
    the flap held or at least half its growth comes from the flap
    (``sigma - sigma_held >= sigma / 2``).  A root unstable with the flap held
    and barely changed by freeing it is not the flap's instability.

    Parameters
    ----------
    modes : pandas.DataFrame
        A stability modes table with ``label`` (the continued identity),
        ``real_part``, ``real_part_uncoupled`` and ``flap_motion``.

    Returns
    -------
    numpy.ndarray of bool
    """
    return _induced(modes["real_part"].to_numpy(float),
                    modes["real_part_uncoupled"].to_numpy(float), modes["label"],
                    modes["flap_motion"].to_numpy(float))


def _induced(sigma, held, labels, motion) -> np.ndarray:
    """:func:`flap_induced` on the columns' arrays."""
    own = np.array([is_tef(x) for x in labels], bool)
    moves = motion >= FLAP_ACTIVE
    raised = sigma - held
    with np.errstate(invalid="ignore"):      # NaN: no uncoupled root, not induced
        return own | (moves & (raised > RATE_RESOLUTION)
                      & ((held < 0.0) | (raised >= 0.5 * np.maximum(sigma, 0.0))))


def _least_stable(rates, mask):
    """Position of the largest of ``rates[mask]`` (the first of ties), or None."""
    idx = np.flatnonzero(mask)
    return None if idx.size == 0 else int(idx[np.argmax(rates[idx])])


def flutter_root(modes: pd.DataFrame, threshold: float = FLUTTER_PARTICIPATION):
    """Row of the least stable flap-induced root, or None.

    Parameters
    ----------
    modes : pandas.DataFrame
        A stability modes table (:attr:`tefcore.linear.stability.StabilityResult.modes`).
        Named by continuation (with ``real_part_uncoupled``): the least
        stable root of :func:`flap_induced`.  Otherwise (a point function that
        names roots its own way): the least stable root with a flap
        participation ``share_TEF >= threshold``; without that either, the
        least stable root.
    threshold : float, optional
        Smallest flap participation, for tables not named by continuation.

    Returns
    -------
    int or None
        The row's index label.
    """
    if "real_part_uncoupled" in modes and "flap_motion" in modes:
        mask = flap_induced(modes)
    elif "share_TEF" in modes:
        mask = modes["share_TEF"].to_numpy(float) >= threshold
    else:
        mask = np.ones(len(modes), bool)
    # the first of equal rates, as DataFrame.idxmax
    pos = _least_stable(modes["real_part"].to_numpy(float), mask)
    return None if pos is None else int(modes.index[pos])


def name_roots(table: pd.DataFrame, continued, shares=None, coordinates=None) -> pd.DataFrame:
    """A point's modes table named by continuation, with its flutter root.

    Parameters
    ----------
    table : pandas.DataFrame
        The modes table by participation (``label`` the coordinate a root
        carries most; kept as ``dominant``).
    continued : tefcore.modes.continuation.ContinuedRoots
        The roots' paths from zero coupling, per row of `table`.
    shares : numpy.ndarray, optional
        The coordinates' shares of each root (coordinates x rows,
        :func:`tefcore.modes.labels.coordinate_shares`), for ``coordinate_share``.
    coordinates : list of str, optional
        The coordinates' labels (the rows of `shares`).

    Returns
    -------
    pandas.DataFrame
        `table` with ``label`` the continued identity (the uncoupled mode the
        root continues from; of a locked pair the less stable root has the
        plain name; ``kind`` and ``coordinate_share`` of it),
        ``identity_certain`` (every step of its path decided), ``meets`` (the
        name of the root its path met: an exceptional point within the
        smallest step of the coupling; empty otherwise),
        ``real_part_uncoupled`` (where the path starts: the root with the flap
        held, or the flap alone), ``frequency_continued`` (the root's frequency
        as its path carried it from there, or NaN), ``flap_motion``,
        ``named_by_path`` (the name is the one the root's own path brought,
        not one the final naming gave it: a flap-free root's coordinate, a
        name left, a lock's second root), ``flap_induced`` and
        ``flutter_root`` (one row at most).
    """
    import pandas as pd

    named = named_columns({c: table[c].to_numpy() for c in table.columns}, continued,
                          shares, coordinates)
    return pd.DataFrame(named, index=table.index)


def named_columns(columns: dict, continued, shares=None, coordinates=None) -> dict:
    """:func:`name_roots` on a modes table given as its columns (name -> array).

    The point's table is built once from these columns
    (:func:`tefcore.linear.stability.stability`): building it, then copying
    and inserting into it, cost 3-4 ms of a 11 ms hover point (measured, stop
    35).  The columns and their order are those :func:`name_roots` returns.

    Parameters
    ----------
    columns : dict
        Column name -> values (one per root), in the table's order; with
        ``label`` and ``real_part``.
    continued : tefcore.modes.continuation.ContinuedRoots
        See :func:`name_roots`.
    shares : numpy.ndarray, optional
        See :func:`name_roots`.
    coordinates : list of str, optional
        See :func:`name_roots`.

    Returns
    -------
    dict
        The named table's columns, in order.
    """
    cols = dict(columns)
    added = ("real_part_uncoupled", "frequency_uncoupled", "frequency_continued",
             "identity_certain", "meets", "flap_motion", "named_by_path", "flap_induced",
             "flutter_root")
    present = [c for c in added if c in cols]
    if present:
        raise ValueError(f"the modes table is named already (has {present})")
    # a root no path explains (and no final naming placed: constant
    # coefficients, or no labels at full coupling) keeps the coordinate it
    # carries, not an empty name (which would read as kind 'TEF')
    origin = [o if o else str(d)
              for o, d in zip(continued.origin, cols["label"], strict=True)]
    rates = np.asarray(cols["real_part"], float)
    origin = _plain_name_to_less_stable(origin, rates)
    cols["label"] = np.array(origin, dtype=object)
    cols["kind"] = np.array([mode_kind(o) for o in origin],
                            dtype=object)
    if shares is not None:
        names = list(coordinates)
        cols["coordinate_share"] = np.array([shares[names.index(base_name(o)), j]
                                             if base_name(o) in names else np.nan
                                             for j, o in enumerate(origin)], float)
    met: dict = {}
    # ContinuedRoots names them without building its meetings table; any other
    # object with a ``meetings`` table will do
    pairs = (continued.meeting_origins() if hasattr(continued, "meeting_origins")
             else [str(x) for x in continued.meetings["origins"]])
    for pair in pairs:
        a, b = pair_labels(pair)
        met.setdefault(a, []).append(b)
        met.setdefault(b, []).append(a)
    by_path = getattr(continued, "by_path", None)
    motion = np.asarray(continued.flap_motion, float)
    new = {"real_part_uncoupled": continued.uncoupled.real,
           "frequency_uncoupled": continued.uncoupled.imag,
           "frequency_continued": continued.frequency,
           "identity_certain": continued.certain,
           "meets": np.array([", ".join(met.get(base_name(o), [])) for o in origin],
                             dtype=object),
           "flap_motion": motion,
           "named_by_path": (np.array([bool(o) for o in continued.origin], bool)
                             if by_path is None else by_path)}
    induced = _induced(rates, new["real_part_uncoupled"], origin, motion)
    flutter = np.zeros(len(origin), bool)
    row = _least_stable(rates, induced)
    if row is not None:
        flutter[row] = True
    new.update(flap_induced=induced, flutter_root=flutter)
    # the order of DataFrame.insert calls: after real_part, then at 3 and 4
    order = list(cols)
    pos = order.index("real_part") + 1
    order[pos:pos] = ["real_part_uncoupled", "frequency_uncoupled", "frequency_continued"]
    order.insert(3, "identity_certain")
    order.insert(4, "meets")
    order += ["flap_motion", "named_by_path", "flap_induced", "flutter_root"]
    cols.update(new)
    return {c: cols[c] for c in order}


def _plain_name_to_less_stable(names, rates):
    """Of two roots named ``X`` and ``X (locked)``, the plain name to the less stable
    (and to a root that is the only one of its name)."""
    names = list(names)
    for x in {base_name(n) for n in names}:
        idx = [i for i, n in enumerate(names) if base_name(n) == x]
        if len(idx) == 1:              # the pair left its lock: one root, the plain name
            names[idx[0]] = x
        if len(idx) == 2:
            lo, hi = sorted(idx, key=lambda i: -rates[i])
            names[lo], names[hi] = x, locked_name(x)
    return names


# ------------------------------------------------------------------ along a sweep


def assign_roles(table: pd.DataFrame, threshold: float = FLUTTER_PARTICIPATION) -> None:
    """Columns ``tef_branch``, ``tef_branch_certain`` and ``flutter_root`` of a sweep table.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table: one row per (point, mode), with ``point``, ``status``,
        ``label`` (each row's name) and the mode columns; changed in place.
        ``tef_branch``: the rows named ``TEF`` (the root the uncoupled flap
        continues into, at every point); ``tef_branch_certain``: and its path
        was decided (``identity_certain``, where the table has it);
        ``flutter_root``: the points' own flutter roots (the column the
        point function gave, else :func:`flutter_root` by the share cut).
    threshold : float, optional
        Smallest flap participation of a flutter root, for points not named
        by continuation.
    """
    ok = (table["status"] == "ok").to_numpy()
    tef = ok & (table["label"].astype(str).to_numpy() == TEF_NAME)
    table["tef_branch"] = tef
    certain = (table["identity_certain"].fillna(False).astype(bool).to_numpy()
               if "identity_certain" in table else np.ones(len(table), bool))
    table["tef_branch_certain"] = tef & certain
    if "flutter_root" in table and "real_part_uncoupled" in table:
        table["flutter_root"] = ok & table["flutter_root"].fillna(False).astype(bool).to_numpy()
        return
    table["flutter_root"] = False
    good = table[ok]
    for _, rows in good.groupby("point", sort=False):
        row = flutter_root(rows, threshold)
        if row is not None:
            table.loc[row, "flutter_root"] = True


def _switches(table: pd.DataFrame, x: str):
    """Consecutive rows of one track whose names differ across an exceptional point
    (:func:`_moves` with :func:`_is_exceptional`).

    The exchange of two names ``a -> b`` along a track between two points is
    one when: the root of the other name is there at both points (the pair
    exchanged, not a lock forming), both names were decided at both points
    (``identity_certain``), both roots move the flap on one side at least
    (at an exceptional point the two share one shape, flap and all:
    :data:`tefcore.modes.continuation.FLAP_ACTIVE`), and the two uncoupled
    roots did not cross between the points (their frequencies at zero
    coupling changing order: the uncoupled modes themselves change places,
    exactly known on either side, and the name moves across the coupled
    pair's gap with them).
    """
    return _moves(table, x, _is_exceptional)


def _moves(table: pd.DataFrame, x: str, kind) -> list:
    """``(x_before, x_after, a, b, what)`` where a track's name changes ``a -> b``,
    the other name is there at both points (the pair exchanged, not a lock
    forming) and ``what = kind(rows)`` is true (rows: a, b at the first point;
    a, b at the second, as a dict of the columns' values; :data:`_ROW_COLUMNS`
    -- chosen by :func:`_partner`).

    The columns are read once: picking each candidate's four rows from the
    table takes 1.1 ms, 0.6 s of a 10.8 s Fig. 13 sweep's refinement rounds
    (measured).
    """
    import pandas as pd

    out = []
    t = table.sort_values([x, "track"], kind="stable")
    labels = [str(v) for v in t["label"]]
    base = [base_name(v) for v in labels]
    xs_all = t[x].to_numpy(float)
    tracks = t["track"].to_numpy()
    # a name's rows at a point (a locked pair has two), the plain one first
    # (the less stable root, as mode_rows reads a name); a track's row at a point
    rows_of: dict = {}
    on_track: dict = {}
    for i, (v, n) in enumerate(zip(xs_all, base, strict=True)):
        here = rows_of.setdefault((float(v), n), [])
        if labels[i] == n:
            here.insert(0, i)
        else:
            here.append(i)
        if not pd.isna(tracks[i]):
            on_track[(tracks[i], float(v))] = i
    cols = {c: t[c].to_numpy() for c in _ROW_COLUMNS if c in t}
    # each track's rows, the tracks in the order they first appear and rows
    # without a track left out (as groupby("track", sort=False) gave them)
    groups: dict = {}
    for i, tr in enumerate(tracks):
        if not pd.isna(tr):
            groups.setdefault(tr, []).append(i)
    for g in groups.values():
        names = np.array([base[i] for i in g], dtype=object)
        xs = xs_all[g]
        for i in np.flatnonzero(names[1:] != names[:-1]):
            a, b = names[i], names[i + 1]
            rows = [g[i], *_partner(rows_of, on_track, tracks, base, xs[i], xs[i + 1], a, b),
                    g[i + 1]]
            what = None if None in rows else kind({c: v[rows] for c, v in cols.items()})
            if what:
                out.append((xs[i], xs[i + 1], a, b, what))
    return out


def _partner(rows_of, on_track, tracks, base, x1, x2, a, b):
    """The rows of name `b` at `x1` and `a` at `x2` a track's move ``a -> b`` is judged with.

    The track that made the opposite move (``b -> a``) where there is one, so
    that both tracks of an exchange judge it on the same four rows (beside a
    lock, the plain row of a name on a track that never moved would make the
    partner's judgment an exceptional point and the moving track's an
    undecided step); else each name's row there, the
    plain one of a locked pair.
    """
    import pandas as pd

    for j in rows_of.get((x2, a), ()):
        k = on_track.get((tracks[j], x1)) if not pd.isna(tracks[j]) else None
        if k is not None and base[k] == b:
            return k, j
    first = [rows_of.get((x, n), [None])[0] for x, n in ((x1, b), (x2, a))]
    return first[0], first[1]


#: The columns :func:`_moves` gives its ``kind`` (those present in the table).
_ROW_COLUMNS = ("label", "identity_certain", "named_by_path", "flap_motion",
                "frequency_uncoupled", "meets")


def _flags(values) -> np.ndarray:
    """Booleans of a column that may hold None or NaN (missing: False)."""
    import pandas as pd

    return np.array([False if pd.isna(v) else bool(v) for v in values], bool)


def _uncoupled_crossed(rows: dict) -> bool:
    """The two uncoupled roots changed order between the points (their Floquet
    conventions, the dominant harmonic of one blade mode or of the flap alone,
    are continuous in the parameter: measured on every figure's sweep)."""
    if "frequency_uncoupled" not in rows:
        return False
    f = np.asarray(rows["frequency_uncoupled"], float)
    return bool((f[0] - f[1]) * (f[2] - f[3]) < 0)


def _decided(rows: dict) -> np.ndarray:
    """Per row: its name decided by its own path (``identity_certain`` and, where
    known, ``named_by_path``: not a name the final naming gave a root whose path
    brought another)."""
    certain = _flags(rows["identity_certain"])
    if "named_by_path" in rows:
        certain &= _flags(rows["named_by_path"])
    return certain


def _is_undecided(rows: dict) -> bool:
    """Rows (a, b at the first point; a, b at the second) of a move with a name undecided.

    Undecided: a name not ``identity_certain`` or not the one its root's path
    brought (:func:`_decided`).  Not where the two paths met at either point
    (their rows' ``meets``): that is an exceptional point, located (``"paths
    meet"``, :func:`exceptional_points`).
    """
    certain = _decided(rows)
    if certain.all() or _uncoupled_crossed(rows):
        return False
    if "meets" in rows:
        names = [base_name(n) for n in rows["label"]]
        met = [set(str(m).split(", ")) if isinstance(m, str) and m else set()
               for m in rows["meets"]]
        if any(names[j] in met[i] for i, j in enumerate((1, 0, 3, 2))):   # a's partner: b
            return False
    return True


def _is_exceptional(rows: dict) -> bool:
    """Rows (a, b at the first point; a, b at the second) of an exchange through an EP.

    The four names decided by their paths (:func:`_decided`): only an exchange
    of continued identities is evidence of an exceptional point, not one in
    which a name came from the final naming (measured on Fig. 13 at 0.71875 R:
    blade torsion 1's name, given by participation to the flap-free root whose
    path was the TEF's, read as an exchange of blade flap 3 and torsion 1 with
    the root that carried torsion 1's path at 0.725 R; the paths themselves
    had not exchanged).
    """
    if "identity_certain" in rows and not _decided(rows).all():
        return False
    if "flap_motion" in rows and not _both_move_the_flap(rows):
        return False
    return not _uncoupled_crossed(rows)


def _both_move_the_flap(rows: dict) -> bool:
    """Each of the two names' roots moves the flap (:data:`FLAP_ACTIVE`) on one side at
    least (rows: a, b at the first point; a, b at the second)."""
    m = np.asarray(rows["flap_motion"], float)
    return max(m[0], m[2]) >= FLAP_ACTIVE and max(m[1], m[3]) >= FLAP_ACTIVE


def _is_flap_free_exchange(rows: dict) -> bool:
    """Rows (a, b at the first point; a, b at the second) of an exchange of two
    decided names, one of them on roots the flap does not move.

    The four names decided (:func:`_decided`), the uncoupled pair in the same
    order, and one of the names on roots below
    :data:`tefcore.modes.continuation.FLAP_ACTIVE` on both sides: no
    exceptional point of the blade-flap coupling (there the two roots share
    one shape, flap and all: :func:`_is_exceptional` asks both names to move
    the flap on a side), and that name is the coordinate its flap-free root
    carries (participation, the final naming).  With neither name moving the
    flap, the blade's own modes veered between the points (measured on Fig.
    12's balanced flap at mu 0.3: blade flap 5 and torsion 2 at 11.72 /rev,
    0.01 /rev apart, flap motion 2e-3 to 5e-3, their flap shares 0.65 / 0.34
    at 138 and 0.41 / 0.59 at 166 ft-lb/rad).
    """
    if "flap_motion" not in rows or ("identity_certain" in rows
                                     and not _decided(rows).all()):
        return False
    return not _both_move_the_flap(rows) and not _uncoupled_crossed(rows)


def switch_steps(table: pd.DataFrame, x: str = "value_si") -> list[tuple[float, float]]:
    """The parameter steps across which a root's name changes (an exceptional point between).

    A root followed along a sweep (its ``track``) whose continued name differs
    between two neighbouring points has passed an exceptional point of the
    family in (parameter, coupling) between them; the flap moves in the root
    there (``flap_motion >=`` :data:`tefcore.modes.continuation.FLAP_ACTIVE`:
    at an exceptional point the two roots share one shape, flap and all).  A
    locked pair's two roots exchanging their names is not one.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table (ok rows) with `x`, ``track``, ``label``.
    x : str, optional
        The column of the parameter.

    Returns
    -------
    list of (float, float)
        The steps ``(x_before, x_after)``, sorted, without repeats.
    """
    return sorted({(a, b) for a, b, *_ in _switches(table, x)})


def exceptional_points(table: pd.DataFrame, x: str = "x") -> pd.DataFrame:
    """Where along a sweep which root is which has no answer.

    Two kinds, both an exceptional point of the family in (parameter,
    coupling): a root whose name changes between neighbouring points
    (:func:`switch_steps`; the point lies between them), and a point where
    two paths met on the way from zero coupling (its rows' ``meets``).

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table or figure frame (ok rows) with `x`, ``track``,
        ``label`` (and ``meets``, ``flap_motion`` where known).
    x : str, optional
        The column of the parameter.

    Returns
    -------
    pandas.DataFrame
        ``modes`` (the two names, ``"A / B"``), ``x_low``, ``x_high``,
        ``kind`` (``"names exchange"`` or ``"paths meet"``); overlapping
        intervals of one pair merged; ``uncoupled``: the two modes'
        frequencies at zero coupling there and how near they lie
        (:func:`uncoupled_relation`; empty where the table does not say).
    """
    import pandas as pd

    rows = [{"modes": pair_text(a, b), "x_low": lo, "x_high": hi,
             "kind": "names exchange"} for lo, hi, a, b, _ in _switches(table, x)]
    if "meets" in table:
        met = table[table["meets"].fillna("").astype(str) != ""]
        for _, r in met.iterrows():
            for other in str(r["meets"]).split(", "):
                rows.append({"modes": pair_text(base_name(r["label"]), other),
                             "x_low": float(r[x]), "x_high": float(r[x]),
                             "kind": "paths meet"})
    out = _merged(pd.DataFrame(rows, columns=["modes", "x_low", "x_high", "kind"]))
    out["uncoupled"] = [uncoupled_relation(table, e["modes"], e["x_low"], e["x_high"], x)
                        for _, e in out.iterrows()]
    return out


def uncoupled_relation(table: pd.DataFrame, modes: str, lo: float, hi: float,
                       x: str = "x") -> str:
    """The two modes' uncoupled frequencies over ``[lo, hi]`` and how near they lie.

    Two roots coalesce at an exceptional point of the family in (parameter,
    coupling); their frequencies at zero coupling say which two modes the
    coupling brought together and how far apart they started: in hover the
    difference, in forward flight the nearest combination ``f_a -+ f_b = k
    /rev`` (Floquet frequencies are equal modulo 1/rev and up to the sign).
    On the reproduction's 56 points the residual is smaller than chance
    (median 0.085 /rev against 0.146 for random pairs; docs/theory.md 9.3),
    not zero: the coalescence lies at a coupling well above zero.  From the
    table's ``frequency_uncoupled`` (the mean over the points of the
    bracket); forward flight is told by a finite ``frequency_continued``.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table or figure frame with `x`, ``label``,
        ``frequency_uncoupled`` (and ``frequency_continued``).
    modes : str
        ``"A / B"``, as :func:`exceptional_points` writes them.
    lo, hi : float
        The bracket.
    x : str, optional
        The column of the parameter.

    Returns
    -------
    str
        E.g. ``"uncoupled TEF 17.66, blade flap 5 10.71 /rev: TEF - blade
        flap 5 = 7 /rev to 0.05"``; empty when a frequency is not known.

    Examples
    --------
    >>> import pandas as pd
    >>> t = pd.DataFrame({"x": [0.0, 0.0], "label": ["TEF", "blade flap 5"],
    ...                   "frequency_uncoupled": [17.66, 10.71],
    ...                   "frequency_continued": [17.2, 10.9]})
    >>> uncoupled_relation(t, "TEF / blade flap 5", 0.0, 0.0)
    'uncoupled TEF 17.66, blade flap 5 10.71 /rev: TEF - blade flap 5 = 7 /rev to 0.05'
    """
    if "frequency_uncoupled" not in table:
        return ""
    a, b = pair_labels(modes)
    at = table[(table[x] >= lo) & (table[x] <= hi)]
    label = at["label"].astype(str)
    f = [at.loc[label == m, "frequency_uncoupled"].to_numpy(float) for m in (a, b)]
    if not all(v.size and np.isfinite(v).all() for v in f):
        return ""
    fa, fb = (float(v.mean()) for v in f)
    text = f"uncoupled {a} {fa:.2f}, {b} {fb:.2f} /rev: "
    periodic = ("frequency_continued" in table
                and bool(np.isfinite(table["frequency_continued"].to_numpy(float)).any()))
    if not periodic:
        return text + f"{a} - {b} = {fa - fb:.2f} /rev"
    # modulo 1/rev and up to the sign: the nearer of f_a - f_b and f_a + f_b to an integer
    sign, k = min(((s, round(fa - s * fb)) for s in (1, -1)),
                  key=lambda sk: abs(fa - sk[0] * fb - sk[1]))
    return text + f"{a} {'-' if sign > 0 else '+'} {b} = {k} /rev to {abs(fa - sign * fb - k):.2f}"


def undecided_steps(table: pd.DataFrame, x: str = "x") -> pd.DataFrame:
    """Where a name moves to another root along a sweep with its identity undecided.

    A root followed along the sweep (its ``track``) whose name changes between
    two neighbouring points, the other name being there at both points, is
    either an exchange through an exceptional point
    (:func:`exceptional_points`), the uncoupled modes themselves changing
    places (their frequencies at zero coupling changing order), or -- listed
    here -- a step where one of the two names was not decided
    (``identity_certain`` False on either side: a path that met an undecided
    match no step resolved and that was no coalescence, or a name given at
    the end; or ``named_by_path`` False: a root whose path brought another
    name, named by the coordinate it carries) -- or, also listed, two decided
    names exchanged where one of them is on roots the flap does not move
    (kind ``"named by participation"``, :func:`_is_flap_free_exchange`: that
    name is the coordinate its root carries; with both flap-free, the blade's
    own modes veered between the points).  The name did move between roots
    there, with no located exceptional point to say why: a reader sees it
    instead of a silent jump.
    A claim is not withheld for it (only an exceptional point makes a claim
    ambiguous).

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table or figure frame (ok rows) with `x`, ``track``,
        ``label``, ``identity_certain`` (and ``frequency_uncoupled`` where
        known).
    x : str, optional
        The column of the parameter.

    Returns
    -------
    pandas.DataFrame
        ``modes`` (``"A / B"``), ``x_low``, ``x_high``, ``kind``
        (``"identity undecided"`` or ``"named by participation"``);
        overlapping intervals of one pair and kind merged.

    Examples
    --------
    Two names exchange tracks between x = 0 and 1, one of them undecided at 1:

    >>> import pandas as pd
    >>> rows = [{"x": x, "track": k, "label": n, "identity_certain": x == 0 or k == 0}
    ...         for x, names in ((0.0, ["TEF", "blade flap 3"]), (1.0, ["blade flap 3", "TEF"]))
    ...         for k, n in enumerate(names)]
    >>> undecided_steps(pd.DataFrame(rows))[["modes", "x_low", "x_high"]].values.tolist()
    [['TEF / blade flap 3', 0.0, 1.0]]
    """
    import pandas as pd

    rows = []
    if "identity_certain" in table:
        rows = [{"modes": pair_text(a, b), "x_low": lo, "x_high": hi, "kind": what}
                for lo, hi, a, b, what in _moves(table, x, _undecided_kind)]
    return _merged(pd.DataFrame(rows, columns=["modes", "x_low", "x_high", "kind"]))


def _undecided_kind(rows: dict) -> str | None:
    """The kind of :func:`undecided_steps` a move is, or None (rows as :func:`_moves`)."""
    if _is_undecided(rows):
        return "identity undecided"
    if _is_flap_free_exchange(rows):
        return "named by participation"
    return None


def _merged(out: pd.DataFrame) -> pd.DataFrame:
    """Overlapping intervals of one pair and kind merged, sorted by ``x_low``."""
    import pandas as pd

    if out.empty:
        return out
    merged = []
    for (modes, kind), g in out.sort_values("x_low").groupby(["modes", "kind"], sort=True):
        lo, hi = None, None
        for a, b in zip(g["x_low"], g["x_high"], strict=True):
            if lo is not None and a <= hi:
                hi = max(hi, b)
                continue
            if lo is not None:
                merged.append({"modes": modes, "x_low": lo, "x_high": hi, "kind": kind})
            lo, hi = a, b
        merged.append({"modes": modes, "x_low": lo, "x_high": hi, "kind": kind})
    return pd.DataFrame(merged).sort_values(["x_low", "modes"], ignore_index=True)


# ------------------------------------------------------------------ a claim's mode


def mode_rows(frame: pd.DataFrame, mode: str) -> pd.DataFrame:
    """Rows of a figure's table that are `mode`, one per point.

    Parameters
    ----------
    frame : pandas.DataFrame
        A figure's long table (an ``x`` column, a sweep's names and roles).
    mode : str
        :data:`FLUTTER_ROOT` (the flutter root of each point) or a name
        (``"TEF"``, ``"blade torsion 1"``: the root of that name at each point;
        of a locked pair the less stable, which has the plain name).

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    ModeNotFound
        The table has no such rows.
    """
    if mode == FLUTTER_ROOT:
        if "flutter_root" not in frame:
            raise ModeNotFound("the result has no flutter roots (no flap)")
        rows = frame[frame["flutter_root"].fillna(False).astype(bool)]
        if rows.empty:
            raise ModeNotFound("no flap-induced root in the sweep")
        return rows
    names = frame["label"].astype(str)
    rows = frame[names.map(base_name) == mode]
    if rows.empty:
        raise ModeNotFound(f"no mode {mode!r} in the result; names: "
                           f"{sorted(set(frame['label'].dropna().astype(str)))}")
    # of a locked pair the plain name (the less stable root); a root alone
    # with the suffix is the only one of its name there
    plain = (rows["label"].astype(str) == mode).to_numpy()
    return rows.assign(_p=~plain).sort_values(["x", "_p"], kind="stable").drop_duplicates(
        "x").drop(columns="_p")
