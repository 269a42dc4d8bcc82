"""A root's name as a value: the uncoupled mode it continues from, compared by field.

A name is written ``blade flap 1``, ``blade torsion 2``, ``TEF``; the second
real root of a locked pair (two roots whose Floquet frequencies locked at a
multiple of 1/2 /rev) is ``blade flap 1 (locked)``; two roots that meet at an
exceptional point are written ``TEF / blade torsion 1``.  That text is for
tables and plots.  Code reads a name through :class:`ModeName` (its family,
index and whether it is a lock's second root) and a meeting through
:func:`mode_pair`; nothing else in tefcore takes a name's text apart.

How a name was decided is separate from the name: the modes table carries it
in ``named_by_path`` (the root's own path of continuation brought it),
``identity_certain`` (every step of that path decided) and ``meets`` (the
names of the roots its path met); :func:`how_named` reads them as one word.

Examples
--------
>>> name = ModeName.parse("blade torsion 2 (locked)")
>>> name.family, name.index, name.locked
('torsion', 2, True)
>>> str(name.base), name.base.is_tef, str(ModeName.tef())
('blade torsion 2', False, 'TEF')
>>> str(ModeName("flap", 1).locked_twin())
'blade flap 1 (locked)'
>>> [str(n) for n in mode_pair("TEF / blade torsion 1")]
['TEF', 'blade torsion 1']
>>> pair_text("blade torsion 1", "TEF")
'TEF / blade torsion 1'
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace

__all__ = ["BLADE_FAMILIES", "FAMILIES", "HOW_NAMED", "LOCKED_SUFFIX", "PAIR_SEPARATOR", "TEF_NAME",
           "ModeName", "base_name", "how_named", "is_locked", "is_tef", "locked_name", "mode_kind",
           "mode_pair", "pair_labels", "pair_text"]

#: The blade's mode families (the structure's coordinate labels, ``flap 1`` ...).
BLADE_FAMILIES = ("flap", "lag", "torsion", "axial")

#: Every family a root can continue from: the blade's and the flap's own mode.
FAMILIES = (*BLADE_FAMILIES, "TEF")

#: The flap's own mode, as tables write it.
TEF_NAME = "TEF"

#: Written after a locked pair's second root.
LOCKED_SUFFIX = " (locked)"

#: Between the two names of roots that meet.
PAIR_SEPARATOR = " / "

#: The words of :func:`how_named`.
HOW_NAMED = ("continued", "nearest", "ambiguous")


@dataclass(frozen=True)
class ModeName:
    """The uncoupled mode a root continues from.

    Parameters
    ----------
    family : str
        One of :data:`FAMILIES`: ``"flap"``, ``"lag"``, ``"torsion"``,
        ``"axial"`` (a blade mode) or ``"TEF"`` (the flap on its actuator).
    index : int
        The blade mode's number within its family, from 1; 0 for the TEF.
    locked : bool
        The second real root of a locked pair of this mode.
    """

    family: str
    index: int = 0
    locked: bool = False

    def __post_init__(self):
        if self.family not in FAMILIES:
            raise ValueError(f"mode family {self.family!r} is not one of {', '.join(FAMILIES)}")
        if (self.family == "TEF") != (self.index == 0) or self.index < 0:
            raise ValueError(f"mode index {self.index!r} of family {self.family!r}: a blade "
                             "mode is numbered from 1, the TEF has no number (0)")

    @classmethod
    def tef(cls) -> ModeName:
        """The flap's own mode."""
        return cls("TEF")

    @classmethod
    def parse(cls, text) -> ModeName:
        """The name written ``text`` (``"blade flap 1"``, ``"TEF (locked)"``).

        Raises
        ------
        ValueError
            ``text`` is not a root's name (the message shows it and the form).
        """
        return _parse(str(text))

    @classmethod
    def coordinate(cls, label) -> ModeName:
        """The name of a structural coordinate's label (``"flap 1"``: the structure's own)."""
        return _parse(f"blade {label}")

    @property
    def base(self) -> ModeName:
        """The same mode without the lock's second-root mark."""
        return replace(self, locked=False) if self.locked else self

    @property
    def is_tef(self) -> bool:
        """The flap's own mode (either root of its lock)."""
        return self.family == "TEF"

    @property
    def kind(self) -> str:
        """The family, as the ``kind`` column writes it."""
        return self.family

    def locked_twin(self) -> ModeName:
        """The second root of this mode's locked pair."""
        return replace(self, locked=True)

    def __str__(self) -> str:
        text = "TEF" if self.is_tef else f"blade {self.family} {self.index}"
        return text + (LOCKED_SUFFIX if self.locked else "")


@functools.lru_cache(maxsize=512)
def _parse(text: str) -> ModeName:
    body, locked = _split(text)
    if body == "TEF":
        return ModeName("TEF", 0, locked)
    words = body.split(" ")
    if (len(words) == 3 and words[0] == "blade" and words[1] in BLADE_FAMILIES
            and words[2].isdigit() and int(words[2]) >= 1):
        return ModeName(words[1], int(words[2]), locked)
    raise ValueError(f"{text!r} is not a root's name: 'TEF' or 'blade <family> <n>' with a "
                     f"family of {', '.join(BLADE_FAMILIES)}, optionally followed by "
                     f"'{LOCKED_SUFFIX.strip()}'")


def _split(name) -> tuple[str, bool]:
    """``(text without the lock mark, whether it had it)``: the one reading of the mark."""
    text = str(name)
    body = text.removesuffix(LOCKED_SUFFIX)
    return body, body != text


def base_name(name) -> str:
    """A root's name without the mark of a locked pair's second root, as text.

    Any track label (a sweep of a point function of the user's may label its
    roots as it likes) follows the same convention; ``""`` (a root no path
    explains) stays ``""``.

    Parameters
    ----------
    name : str or ModeName
        ``"blade flap 1 (locked)"``, ``"TEF"``, ...

    Returns
    -------
    str

    Examples
    --------
    >>> base_name("blade flap 1 (locked)"), base_name("")
    ('blade flap 1', '')
    """
    return _split(name)[0]


def is_locked(name) -> bool:
    """Whether a label is a locked pair's second root.

    Parameters
    ----------
    name : str or ModeName
        A root's name or any track label.

    Returns
    -------
    bool
    """
    return _split(name)[1]


def is_tef(name) -> bool:
    """Whether a label is the flap's own mode, either root of its lock.

    Parameters
    ----------
    name : str or ModeName
        A root's name or any track label.

    Returns
    -------
    bool
    """
    return _split(name)[0] == "TEF"


def locked_name(name) -> str:
    """The label of the second root of ``name``'s locked pair.

    Parameters
    ----------
    name : str or ModeName
        A root's name or any track label.

    Returns
    -------
    str

    Examples
    --------
    >>> locked_name("TEF"), locked_name("blade flap 2 (locked)")
    ('TEF (locked)', 'blade flap 2 (locked)')
    """
    return _split(name)[0] + LOCKED_SUFFIX


def mode_kind(name) -> str:
    """The family of a root's name (the ``kind`` column): ``"flap"`` ... ``"TEF"``.

    Parameters
    ----------
    name : str or ModeName
        A root's name.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        ``name`` is not a root's name.

    Examples
    --------
    >>> mode_kind("blade torsion 1 (locked)"), mode_kind("TEF")
    ('torsion', 'TEF')
    """
    return ModeName.parse(name).family


def pair_text(a, b) -> str:
    """Two roots that meet, written in a fixed order (sorted by their text).

    Parameters
    ----------
    a, b : str or ModeName
        Their names.

    Returns
    -------
    str
    """
    return PAIR_SEPARATOR.join(sorted((str(a), str(b))))


def pair_labels(text) -> tuple[str, str]:
    """The two labels of a meeting written by :func:`pair_text`, as text.

    Parameters
    ----------
    text : str
        ``"A / B"``.

    Returns
    -------
    tuple of str

    Raises
    ------
    ValueError
        ``text`` is not two labels joined by :data:`PAIR_SEPARATOR`.
    """
    parts = str(text).split(PAIR_SEPARATOR)
    if len(parts) != 2:
        raise ValueError(f"{text!r} is not two roots' names joined by {PAIR_SEPARATOR!r}")
    return parts[0], parts[1]


def mode_pair(text) -> tuple[ModeName, ModeName]:
    """The two names of a meeting written by :func:`pair_text`.

    Parameters
    ----------
    text : str
        ``"A / B"``.

    Returns
    -------
    tuple of ModeName

    Raises
    ------
    ValueError
        ``text`` is not two roots' names joined by :data:`PAIR_SEPARATOR`.
    """
    a, b = pair_labels(text)
    return ModeName.parse(a), ModeName.parse(b)


def how_named(by_path: bool, certain: bool, meets: str = "") -> str:
    """How a root's name was decided, as one of :data:`HOW_NAMED`.

    ``continued``: its own path from zero coupling brought the name and every
    step was decided; ``ambiguous``: its path met another root's (an
    exceptional point) or a step was not decided; ``nearest``: the final
    naming gave it the name left (a flap-free root's coordinate, a lock's
    second root).

    Parameters
    ----------
    by_path : bool
        The root's own path brought its name (``named_by_path``).
    certain : bool
        Every step of that path was decided (``identity_certain``).
    meets : str, optional
        The names of the roots its path met (``meets``; empty: none).

    Returns
    -------
    str

    Examples
    --------
    >>> how_named(True, True), how_named(True, False), how_named(False, True)
    ('continued', 'ambiguous', 'nearest')
    """
    if meets or not certain:
        return "ambiguous"
    return "continued" if by_path else "nearest"
