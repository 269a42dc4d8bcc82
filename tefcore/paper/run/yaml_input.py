"""YAML given by users (batch files, notebook parameters) as plain, bounded data.

``yaml.safe_load`` builds only plain types, but YAML aliases can expand a
small file into a huge tree, and YAML has values (dates, sets, non-finite
floats) that a notebook parameter or a run record cannot carry.
:func:`plain_problem` finds the first such value.

Examples
--------
>>> plain_problem({"params": {"n_points": 4, "values": [0.0, 0.2]}})
>>> plain_problem({"x": [1.0, float("nan")]})
('.x[1]', 'nan is not a finite number')
"""

from __future__ import annotations

import math

__all__ = ["MAX_NODES", "plain_problem"]

#: Most values (nodes) a YAML document may expand to.
MAX_NODES = 100_000


def plain_problem(value, max_nodes: int = MAX_NODES) -> tuple[str, str] | None:
    """The first value papermill and a run record cannot carry, or None.

    Parameters
    ----------
    value : object
        What ``yaml.safe_load`` returned.
    max_nodes : int, optional
        Most values the document may hold (aliases expand).

    Returns
    -------
    (str, str) or None
        ``(where, message)``: the path of the value (``.params.n_points``,
        ``.x[1]``; empty for the whole document) and what is wrong with it.
    """
    budget = [max_nodes]
    stack = [("", value)]
    while stack:
        where, v = stack.pop()
        budget[0] -= 1
        if budget[0] < 0:
            return "", f"the file expands to more than {max_nodes} values (YAML aliases?)"
        if v is None or isinstance(v, bool | int | str):
            continue
        if isinstance(v, float):
            if not math.isfinite(v):
                return where, f"{v!r} is not a finite number"
            continue
        if isinstance(v, list):
            stack += [(f"{where}[{i}]", x) for i, x in reversed(list(enumerate(v)))]
            continue
        if isinstance(v, dict):
            for k in v:
                if not isinstance(k, str) and not (isinstance(k, int) and not isinstance(k, bool)):
                    return where, f"key {k!r} must be a name (a string)"
            stack += [(f"{where}.{k}", x) for k, x in reversed(list(v.items()))]
            continue
        return where, f"{v!r} ({type(v).__name__}) is not a number, string, list or mapping"
    return None
