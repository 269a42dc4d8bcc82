"""Where the compact tefcore model departs from the paper's UMARC analysis.

The text lives once, in ``departures.toml`` beside this module: a part common
to every figure and a part per group of figures.  Every notebook shows it
with :func:`show_departures`, and the reproduction report prints it beside
each figure (:func:`departures_text`).

Examples
--------
>>> text = departures_text("fig9")
>>> text.startswith("The paper's numbers come from UMARC") and "For Fig. 9" in text
True
>>> departures_text("fig9", common=False).startswith("For Fig. 9 in particular")
True
"""

from __future__ import annotations

import tomllib
from functools import cache
from importlib import resources

__all__ = ["departures_text", "load_departures", "show_departures"]


@cache
def load_departures() -> tuple[str, dict[str, str]]:
    """The common text and ``{figure: its own text}`` (markdown) from ``departures.toml``."""
    data = tomllib.loads(resources.files(__package__).joinpath("departures.toml")
                         .read_text(encoding="utf-8"))
    own = {}
    for group in data.get("figures", []):
        for fig in group["figures"]:
            if fig in own:
                raise ValueError(f"departures.toml: figure {fig!r} appears twice")
            own[fig] = group["text"].strip()
    return data["common"].strip(), own


def departures_text(*figures: str, common: bool = True) -> str:
    """Markdown: the common departures (``common``) and those of ``figures``.

    Parameters
    ----------
    *figures : str
        Paper figures (``"fig9"``); a group's text is given once even when
        several of its figures are named.
    common : bool
        Start with the part common to every figure.

    Raises
    ------
    KeyError
        For a figure without departures text.
    """
    shared, own = load_departures()
    parts = [shared] if common else []
    for fig in figures:
        if fig not in own:
            raise KeyError(f"no departures text for {fig!r}; known: {', '.join(own)}")
        if own[fig] not in parts:
            parts.append(own[fig])
    return "\n\n".join(parts)


def show_departures(*figures: str) -> None:
    """Display :func:`departures_text` in a notebook (markdown), or print it elsewhere.

    Parameters
    ----------
    *figures : str
        Paper figures whose specific departures follow the common ones.
    """
    text = departures_text(*figures)
    try:
        from IPython import get_ipython
        from IPython.display import Markdown, display
    except ImportError:
        print(text)
        return
    if get_ipython() is None:
        print(text)
    else:
        display(Markdown(text))
