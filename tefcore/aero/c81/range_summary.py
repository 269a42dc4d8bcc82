"""C81 range warnings counted and summarised: one line per point, not one per call.

A C81 table model clips inputs outside its table and warns once per call
(:class:`~tefcore.aero.c81.format.C81RangeWarning`).  A trim and its Floquet
analysis evaluate the airloads hundreds of times, so one point of the
packaged XFOIL deck at mu = 0.3 printed about 80 warnings (alpha up to 107
deg on the retreating side, Mach 0.81 at the advancing tip) while the point
reported "ok".  :func:`summarised_range_warnings` collects the warnings of a
block and emits **one** ``C81RangeWarning`` saying how many evaluations were
clipped and the most extreme alpha, Mach and delta reached, against the
table's range; its ``clipped`` attribute carries the same as a JSON-able
dict (:func:`merge_clipped`, :func:`describe_clipped`), which a sweep keeps
with the point (:mod:`tefcore.sweeps.evaluate`).

Examples
--------
>>> import warnings
>>> def clip():
...     w = C81RangeWarning("clipped")
...     w.clipped = {"calls": 1, "decks": ["TOY"], "extremes": {"mach": [0.81, 0.0, 0.7]}}
...     warnings.warn(w)
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     with summarised_range_warnings():
...         clip(); clip()
>>> len(caught), caught[0].message.clipped["calls"]
(1, 2)
>>> print(str(caught[0].message).replace(": ", ":\\n"))
C81 deck 'TOY':
inputs outside the table clipped to its edges in 2 evaluations:
mach reached 0.81 (table 0 to 0.7)
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterable, Iterator

from .format import C81RangeWarning

__all__ = ["clipped_of", "collected_range_warnings", "describe_clipped", "merge_clipped",
           "range_warning", "summarised_range_warnings"]

_UNITS = {"alpha": " deg", "mach": "", "delta": " deg"}
#: Where the passed-on warnings are registered as shown (``warnings.warn_explicit``).
_REGISTRY: dict = {}


def _outside(worst: float, lo: float, hi: float) -> float:
    return lo - worst if worst < lo else worst - hi


def merge_clipped(parts: Iterable[dict | None]) -> dict | None:
    """Several summaries of clipped inputs as one: calls added, the most extreme values kept.

    Parameters
    ----------
    parts : iterable of dict or None
        ``{"calls": int, "decks": [name, ...], "extremes": {variable: [worst, lo,
        hi]}}`` each (None entries are skipped).

    Returns
    -------
    dict or None
        The merged summary; None when there is none.
    """
    calls, decks, extremes = 0, [], {}
    for part in parts:
        if not part:
            continue
        calls += int(part.get("calls", 0))
        decks += [d for d in part.get("decks", []) if d not in decks]
        for var, (worst, lo, hi) in part.get("extremes", {}).items():
            if var not in extremes or _outside(worst, lo, hi) > _outside(*extremes[var]):
                extremes[var] = [float(worst), float(lo), float(hi)]
    if not calls:
        return None
    return {"calls": calls, "decks": decks, "extremes": extremes}


def describe_clipped(clipped: dict) -> str:
    """One line: the deck(s), how many evaluations were clipped, the extreme inputs.

    Parameters
    ----------
    clipped : dict
        A summary (:func:`merge_clipped`).

    Returns
    -------
    str
    """
    decks = ", ".join(repr(d) for d in clipped["decks"]) or "(unnamed)"
    reached = "; ".join(
        f"{var} reached {worst:.4g}{_UNITS.get(var, '')} (table {lo:g} to {hi:g})"
        for var, (worst, lo, hi) in clipped["extremes"].items())
    calls = clipped["calls"]
    return (f"C81 deck {decks}: inputs outside the table clipped to its edges in {calls} "
            f"evaluation{'s' if calls != 1 else ''}: {reached}")


def range_warning(message: str, clipped: dict) -> C81RangeWarning:
    """A :class:`C81RangeWarning` carrying its summary as ``clipped``.

    Parameters
    ----------
    message : str
        The warning's text.
    clipped : dict
        The summary (:func:`merge_clipped`).

    Returns
    -------
    C81RangeWarning
    """
    w = C81RangeWarning(message)
    w.clipped = clipped
    return w


def clipped_of(caught: Iterable[warnings.WarningMessage]) -> tuple[dict | None, list]:
    """Split recorded warnings: the summary of the C81 range warnings, and the others.

    Parameters
    ----------
    caught : iterable of warnings.WarningMessage
        From ``warnings.catch_warnings(record=True)``.

    Returns
    -------
    clipped : dict or None
        The merged summary of the ``C81RangeWarning`` among them.
    others : list of warnings.WarningMessage
    """
    parts, others = [], []
    for w in caught:
        if issubclass(w.category, C81RangeWarning):
            parts.append(getattr(w.message, "clipped", None)
                         or {"calls": 1, "decks": [], "extremes": {}})
        else:
            others.append(w)
    return merge_clipped(parts), others


@contextlib.contextmanager
def collected_range_warnings() -> Iterator[dict]:
    """Collect the block's ``C81RangeWarning`` into a summary instead of showing them.

    Other warnings are passed on as they were (the filters in force decide
    whether they show).

    Yields
    ------
    dict
        Its ``"clipped"`` item is set when the block ends: the summary
        (:func:`merge_clipped`), or None when nothing was clipped.
    """
    found: dict = {"clipped": None}
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield found
    finally:
        found["clipped"], others = clipped_of(caught)
        for w in others:   # one registry: the "default" action shows each once, as before
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno,
                                   registry=_REGISTRY, source=w.source)


@contextlib.contextmanager
def summarised_range_warnings(stacklevel: int = 3) -> Iterator[None]:
    """Collect the block's ``C81RangeWarning`` and emit one summary of them after it.

    Other warnings are passed on as they were (the filters in force decide
    whether they show).  The summary is emitted only when the block ends
    normally.

    Parameters
    ----------
    stacklevel : int, optional
        Stack level of the summary warning (3: the caller of the function
        whose body is the block).
    """
    with collected_range_warnings() as found:
        yield
    if found["clipped"] is not None:
        warnings.warn(range_warning(describe_clipped(found["clipped"]), found["clipped"]),
                      stacklevel=stacklevel)
