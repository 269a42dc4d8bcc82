r"""An executed notebook as an HTML page that reads offline.

nbconvert's HTML pages load require.js, MathJax and mermaid from a CDN: read
without a network, their maths stayed blank.  :func:`notebook_html` exports
with the template ``templates/notebook/offline.html.j2`` (JupyterLab's
layout, no script fetched) and writes the maths of the markdown -- the
notebook's cells and the markdown the cells display -- as MathML
(:func:`tex_to_mathml`, with :mod:`latex2mathml`), which browsers draw
without a script.  Where latex2mathml is missing, or cannot read a formula,
the TeX is shown as code.

Examples
--------
>>> tex_to_mathml("growth $e^{2\\pi\\sigma}$ per rev").startswith("growth <math")
True
>>> tex_to_mathml("costs $5 and $6")        # a lone dollar is not maths
'costs $5 and $6'
"""

from __future__ import annotations

import html
import re
from pathlib import Path

__all__ = ["TEMPLATE", "notebook_html", "tex_to_mathml"]

#: The nbconvert template of the pages (beside the report's templates).
TEMPLATE = Path(__file__).resolve().parent / "templates" / "notebook" / "offline.html.j2"

#: ``$$...$$`` (display) or ``$...$`` (inline, not across a line, no space inside the dollars).
_MATH = re.compile(r"\$\$(?P<display>.+?)\$\$|(?<![\\$\w])\$(?P<inline>[^\s$](?:[^$\n]*?[^\s$\\])?)"
                   r"\$(?![\w$])", re.S)


def _formula(tex: str, display: bool) -> str:
    try:
        from latex2mathml.converter import convert
    except ImportError:
        convert = None
    if convert is not None:
        try:
            return convert(tex.strip(), display="block" if display else "inline")
        except Exception:  # latex2mathml raises its own errors for what it cannot read
            pass
    return f"<code>{html.escape(tex)}</code>"


def tex_to_mathml(text: str) -> str:
    """``$...$`` and ``$$...$$`` in markdown ``text`` as MathML.

    Parameters
    ----------
    text : str
        Markdown.

    Returns
    -------
    str
        The markdown with each formula replaced by a ``<math>`` element (or
        its TeX as code).
    """
    return _MATH.sub(lambda m: _formula(m.group("display") or m.group("inline"),
                                        m.group("display") is not None), text)


def _markdown_maths(nb) -> None:
    """The maths of the markdown cells and of the markdown outputs, as MathML, in place."""
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            cell.source = tex_to_mathml(cell.source)
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if "text/markdown" in data:
                text = data["text/markdown"]
                data["text/markdown"] = tex_to_mathml("".join(text) if isinstance(text, list)
                                                      else text)


def notebook_html(path) -> str:
    """The executed notebook at ``path`` as a page that reads offline.

    Parameters
    ----------
    path : path
        An ``.ipynb``.

    Returns
    -------
    str
        The HTML page (figures embedded, no script or style from the network).
    """
    import nbformat
    from nbconvert import HTMLExporter

    nb = nbformat.read(str(path), as_version=4)
    _markdown_maths(nb)
    exporter = HTMLExporter(template_file=str(TEMPLATE))
    body, _ = exporter.from_notebook_node(nb)
    return body
