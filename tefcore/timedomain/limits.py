"""The bounds of a march and its animation, checked before anything is computed.

They keep a typed number (``--revs 1e9``, ``--anim-revs inf``) from
marching or drawing without end, the memory growing all the while.  This
module imports nothing, so that the command's help can state them.

Examples
--------
>>> check_bounded("revs", 6, MAX_REVS, "revolutions marched")
>>> check_bounded("revs", float("inf"), MAX_REVS, "revolutions marched")
Traceback (most recent call last):
...
ValueError: revs = inf: must be a number in (0, 100] (revolutions marched)
"""

from __future__ import annotations

import math
import numbers

__all__ = ["MAX_AMPLITUDE", "MAX_ANIMATED_REVS", "MAX_REVS", "check_bounded"]

#: Most revolutions marched.  Each costs about 1.4 MB (the dense solution and the
#: fit's samples) and 0.2-0.3 s at the MDART mu = 0.3 point; the growth is fitted
#: from two, and a root growing at +3 /rev leaves a float's range in 40.
MAX_REVS = 100
#: Most revolutions animated.  Each takes about 0.35 GB of frames and 6 s to
#: draw at the MDART mu = 0.3 point (its TEF mode, 18 /rev at 8 frames a cycle:
#: 146 frames a revolution, measured 0.52 GB for one and 1.2 GB for three);
#: six are a clip of over a minute at 12 frames per second.
MAX_ANIMATED_REVS = 6
#: Largest perturbation, in chords: the linearised march is about small motions.
MAX_AMPLITUDE = 1.0


def check_bounded(name: str, value, high: float, what: str) -> None:
    """Refuse a value outside ``(0, high]``, NaN and infinities included: one line.

    Parameters
    ----------
    name : str
        The argument, for the message.
    value : float
        Its value.
    high : float
        The bound.
    what : str
        What the value counts, for the message.

    Raises
    ------
    ValueError
        Naming the argument, its value and the range.
    """
    if not (isinstance(value, numbers.Real) and math.isfinite(value) and 0 < value <= high):
        raise ValueError(f"{name} = {value}: must be a number in (0, {high:g}] ({what})")
