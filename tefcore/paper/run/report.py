"""The reproduction report: one model, rendered to markdown and HTML.

:func:`build_report` gathers what a reproduction wrote -- the notebooks' runs,
their figures with the captions they recorded (JSON beside each PNG,
:func:`tefcore.paper.figures.plotting.savefig`), the claims table and the stated
blade frequencies -- into a
:class:`Report` organised like the paper: a summary on top (score, figure
thumbnails linking down), then one section per figure with its caption, its
claims beside it and where the compact model departs from the paper's.
:func:`render` turns the one model into markdown or a self-contained,
responsive HTML page (figures embedded) with the jinja2 templates in
``tefcore/paper/run/templates``.

Examples
--------
>>> r = Report(title="t", intro="i", passed=1, total=2, counts={"pass": 1, "fail": 1},
...            worse=[], notebooks=[], sections=[], checks=[], version="0")
>>> "1 passed of 2" in render(r, "md")
True
"""

from __future__ import annotations

import base64
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import jinja2
import pandas as pd

from ...safe_io import atomic_write_text
from ..attribution.departures import departures_text, load_departures
from ..claims.reference import STATUSES, TAGS
from ..inference.packaged import load_results
from .report_views import (
    check_rows,
    headline,
    inference_view,
    notebook_title,
    shared_notes,
    why_view,
)

__all__ = ["FIGURE_TITLES", "Image", "Report", "STATUS_MEANINGS", "Section", "TAG_MEANINGS",
           "WORSE_MEANING", "build_report", "render", "template_environment", "variants_view",
           "write_report"]

#: The paper's figure captions (its own words), by tefcore figure name.
FIGURE_TITLES = {
    "fig3": "Figure 3: Blade inplane stability in hover for the baseline rotor "
            "(without trailing-edge flaps)",
    "fig4": "Figure 4: Blade inplane stability in forward flight for the baseline rotor "
            "(without trailing-edge flaps)",
    "fig5": "Figure 5: Flap hinge moment in one complete revolution, with prescribed flap "
            "motion",
    "fig6": "Figure 6: Trailing-edge flap response with actuator input",
    "fig7": "Figure 7: Trailing-edge flap actuation power and response (half peak-to-peak) "
            "versus trailing-edge flap overhang length",
    "fig8": "Figure 8: Effect of overhang length on blade and trailing-edge flap (TEF) "
            "stability in hover",
    "fig9": "Figure 9: Effect of flap CG offset on blade and trailing-edge flap (TEF) "
            "stability in forward flight",
    "fig10": "Figure 10: Effect of pitch link stiffness on blade and trailing-edge flap (TEF) "
             "stability in forward flight",
    "fig11": "Figure 11: Effect of blade torsional stiffness on blade and trailing-edge flap "
             "(TEF) stability in forward flight",
    "fig12": "Figure 12: Effect of actuator stiffness on blade and trailing-edge flap (TEF) "
             "stability in forward flight",
    "fig13": "Figure 13: Effect of flap spanwise location on blade and trailing-edge flap "
             "(TEF) stability in forward flight",
    "fig14": "Figure 14: Effect of flap length on blade and trailing-edge flap (TEF) "
             "stability in forward flight",
    "fig15": "Figure 15: Effect of flap chord size on blade and trailing-edge flap (TEF) "
             "stability in forward flight",
    "fig16a": "Figure 16(a): Effect of collective pitch on blade and trailing-edge flap (TEF) "
              "stability, hover",
    "fig16b": "Figure 16(b): Effect of collective pitch on blade and trailing-edge flap (TEF) "
              "stability, forward flight",
    "fig17": "Figure 17: Effect of forward speed on blade and trailing-edge flap (TEF) "
             "stability",
}
_STATUS_CLASS = {"pass": "pass", "fail": "fail", "ambiguous": "ambig",
                 "not reproducible": "notrep", "not computable": "notrep"}

#: What each claim status means, one sentence each (the report's header;
#: :data:`tefcore.paper.claims.reference.STATUSES` lists them best first).
STATUS_MEANINGS = {
    "pass": "the computation agrees with the paper's statement within the claim's stated "
            "tolerance (each tolerance gives its reason in the reference data).",
    "fail": "the computation contradicts the statement beyond its tolerance, or lacks what "
            "the statement is about (no such root, no crossing); the reason says which.",
    "ambiguous": "two roots meet inside the claim's range (an exceptional point), so which "
                 "of them carries the claim's mode has no single answer there, and the "
                 "verdict depends on the choice. The reason says where they meet and what "
                 "the same check gives on the flutter root ([docs/theory.md, section 9.3]("
                 + "{theory}#93-exceptional-points-along-a-sweep)).",
    "not reproducible": "tefcore cannot check the statement: it compares with data tefcore "
                        "does not have (wind-tunnel tests, other analyses, the paper's "
                        "tables), its digitised points all lie outside the computed range, "
                        "or a result it needs was not computed; the reason says which.",
    "not computable": "the figure the claim reads could not be computed for this rotor (the "
                      "trim did not converge, or the configuration is refused at the figure's "
                      "own parameters); the reason names the figure and the error.",
}

#: What each claim tag means, one sentence each.
TAG_MEANINGS = {
    "validation": "a statement of the paper never used to tune the model; the score counts "
                  "these.",
    "calibration": "a stated value used to set an assumed property (the stated torsion "
                   "frequencies on both variants, the flap response of Figure 6 on mdart-fig6); "
                   "listed, "
                   "not scored.",
}

#: What "worse than recorded" means.
WORSE_MEANING = ("a claim whose status is worse than the one recorded in the reference data "
                 "(best first: " + ", ".join(STATUSES) + "): a regression.")


@dataclass
class Image:
    """One figure file of a section.

    Parameters
    ----------
    src : str
        Path of the PNG relative to the report folder (the markdown link).
    data : str
        The PNG, base64-encoded (embedded in the HTML page, which is
        self-contained).
    caption : str
        Caption as plain text (the JSON written beside the PNG by
        :func:`tefcore.paper.figures.plotting.savefig`, markdown marks removed).
    anchor : str
        HTML id of the image, a slug of its file name.
    mime : str
        ``image/png``, or ``image/gif`` for an animation.
    shared : bool
        The caption had the sentences the figures share
        (:attr:`Report.figure_notes`), said once above them.
    """

    src: str
    data: str
    caption: str
    anchor: str
    mime: str = "image/png"
    shared: bool = False


@dataclass
class Section:
    """One paper figure (or group) in the report.

    Parameters
    ----------
    key : str
        The paper figure (``"fig9"``), or the notebook's name for a section
        of its further results.
    title : str
        Heading: the paper's own caption (:data:`FIGURE_TITLES`).
    anchor : str
        HTML id, linked from the summary's thumbnails.
    notebook : str
        Name of the notebook that computed it (``"04_cg_offset"``).
    notebook_html : str
        Link to the executed notebook's HTML export, relative to the report.
    images : list of Image
        The figure files the notebook saved for this figure.
    claims : list of dict
        The figure's claims as plain-text rows of the claims table, each with
        its status and a ``css`` class for the status colour.
    departures : str
        Where the model departs from the paper for this figure (markdown,
        :func:`tefcore.paper.attribution.departures.load_departures`).
    shown_with : str
        Key of the section whose figure also shows this one (Fig. 16a and
        16b share one figure), when this one has no image of its own.
    thumb : str
        Base64 PNG of the summary's thumbnail (its first image or the one
        it is shown with).
    tally : str
        The claims' statuses, e.g. ``"3 pass, 1 fail"``.
    attribution : list of dict
        Why the figure's failing claims fail: one row per claim of
        :func:`tefcore.paper.run.report_views.why_view` (``id``, ``statement``,
        ``plausible``, ``beyond``, ``breaks``); empty without an attribution.
    thumb_mime : str
        The thumbnail's image type.
    """

    key: str
    title: str
    anchor: str
    notebook: str
    notebook_html: str
    images: list = field(default_factory=list)
    claims: list = field(default_factory=list)
    departures: str = ""
    shown_with: str = ""
    thumb: str = ""
    tally: str = ""
    attribution: list = field(default_factory=list)
    thumb_mime: str = "image/png"


@dataclass
class Report:
    """Everything the report shows, rendered by :func:`render`.

    Parameters
    ----------
    title : str
        Page title.
    intro : str
        Opening paragraph (markdown): what reproduces, what does not, the key
        finding (:func:`tefcore.paper.run.report_views.headline`).
    passed : int
        Validation claims that pass (the score; calibration targets are
        listed, not scored).
    total : int
        Validation claims checked.
    counts : dict
        Claims by status over all claims: ``{"pass": n, "fail": n,
        "ambiguous": n, "not reproducible": n}``.
    worse : list of dict
        Claims whose status is worse than their recorded status (the
        regressions), as plain-text rows.
    notebooks : list of dict
        Each notebook run: ``name``, ``status``, ``error`` and ``html`` (link
        to its HTML export).
    sections : list of Section
        One per paper figure, in the paper's order within each notebook.
    checks : list of dict
        The first-torsion frequencies stated in the text against the model's
        (:func:`tefcore.paper.calibration.frequency_checks`), rounded.
    version : str
        The version of tefcore, shown in the summary.
    statuses : list of dict
        The header's legend of the claim statuses: ``name`` and ``meaning``
        (one sentence), every status of
        :data:`tefcore.paper.claims.reference.STATUSES` (:data:`STATUS_MEANINGS`).
    tags : list of dict
        The same for the claim tags (:data:`TAG_MEANINGS`).
    worse_meaning : str
        What "worse than recorded" means (:data:`WORSE_MEANING`).
    fanplot : Image or None
        Fan plot of the (assumed) MDART blade's coupled modes, if written.
    departures : str
        Departures from the paper common to all figures (markdown); each
        section has its own part.
    up : str
        Link to the page this report belongs to (a batch's comparison,
        ``../index.html``); ``""`` for a report of its own.
    variants : dict or None
        The claims on both packaged variants (:func:`variants_view`), or None
        when the other variant was not checked.
    why : dict or None
        "Why we differ": :func:`tefcore.paper.run.report_views.why_view` of the
        run's attribution (which few assumptions explain most failing claims,
        which no plausible assumption explains); None without one.
    what_if : str
        The changed parameters of a what-if run (its claims are not compared
        with the recorded statuses); ``""`` for the recorded computation.
    guide : str
        How the sections read (markdown), below the opening paragraph.
    figure_notes : list of str
        The sentences the figures' captions share (how to read their lines
        and markers), said once; a caption that had them links to them.
    truncation : list of dict
        The truncation-dependent claims (``id``, ``status``, ``converged_status``,
        ``converged_modes``): verdicts the nine-mode basis decides otherwise
        than a converged one (:mod:`tefcore.paper.claims.truncation`).
    inference : dict or None
        "What the paper's rotor must have been": the packaged inference studies
        (:func:`tefcore.paper.run.report_views.inference_view`); None without them.
    """

    title: str
    intro: str
    passed: int
    total: int
    counts: dict
    worse: list
    notebooks: list
    sections: list
    checks: list
    version: str
    statuses: list = field(default_factory=lambda: _legend(STATUS_MEANINGS, STATUSES))
    tags: list = field(default_factory=lambda: _legend(TAG_MEANINGS, TAGS))
    worse_meaning: str = WORSE_MEANING
    fanplot: Image | None = None
    departures: str = ""
    up: str = ""
    variants: dict | None = None
    why: dict | None = None
    what_if: str = ""
    guide: str = ""
    figure_notes: list = field(default_factory=list)
    truncation: list = field(default_factory=list)
    inference: dict | None = None


def _theory_url() -> str:
    """Where docs/theory.md is read: the project's source (its package metadata)."""
    from importlib import metadata

    try:
        urls = metadata.metadata("tefcore").get_all("Project-URL") or []
    except metadata.PackageNotFoundError:
        urls = []
    source = next((u.split(",", 1)[1].strip() for u in urls
                   if u.lower().startswith("source")), "https://github.com/tefcore/tefcore")
    return source.rstrip("/") + "/blob/main/docs/theory.md"


def _legend(meanings: dict, names) -> list[dict]:
    """``[{"name", "meaning"}]`` in the order of `names`; a name without a meaning is an error."""
    missing = [n for n in names if n not in meanings]
    if missing:
        raise KeyError(f"no meaning written for {missing} (tefcore.paper.run.report)")
    return [{"name": n, "meaning": meanings[n].replace("{theory}", _theory_url())}
            for n in names]


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")


def _plain(text: str) -> str:
    """Markdown emphasis and code marks out of a string shown as plain text."""
    text = re.sub(r"\*\*(.+?)\*\*", r"\1", str(text))
    text = re.sub(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])", r"\1", text)
    return text.replace("`", "")


def _image(path: Path, root: Path, caption: str) -> Image:
    return Image(src=path.relative_to(root).as_posix(),
                 data=base64.b64encode(path.read_bytes()).decode("ascii"),
                 caption=_plain(caption), anchor=_slug(path.stem),
                 mime="image/gif" if path.suffix == ".gif" else "image/png")


def _sidecars(folder: Path) -> dict:
    """``{stem: {"figures": [...], "caption": str, "file": name}}``: the figures beside their
    JSON captions, and the animations a notebook saved (GIF, without a caption file)."""
    out = {}
    for gif in sorted(folder.glob("*.gif")) if folder.exists() else []:
        if not gif.with_suffix(".json").exists():
            out[gif.stem] = {"figures": [], "file": gif.name,
                             "caption": f"Animation: {gif.stem.replace('-', ' ')} "
                                        "(as the notebook shows it)"}
    for side in sorted(folder.glob("*.json")) if folder.exists() else []:
        try:
            meta = json.loads(side.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        if isinstance(meta, dict) and (side.with_suffix(".png")).exists():
            out[side.stem] = {"figures": str(meta.get("figure") or "").split(),
                              "caption": str(meta.get("caption") or side.stem),
                              "file": f"{side.stem}.png"}
    return out


#: A reason longer than this is folded (its start shown, the rest on a click).
LONG_REASON = 240


def _claim_rows(claims: pd.DataFrame, figure: str) -> list[dict]:
    """A figure's claims as plain-text rows with their status class; a long reason folded
    (``reason_start``: its first words, ``""`` when it is short)."""
    cl = claims[claims["figure"] == figure] if "figure" in claims else claims.iloc[0:0]
    rows = []
    for row in cl.fillna("").astype(str).to_dict("records"):
        r = dict.fromkeys(("id", "statement", "expected", "computed", "reason", "status"), "")
        r |= {k: _plain(v) for k, v in row.items()}
        reason = r["reason"]
        r["reason_start"] = (reason[:160].rsplit(" ", 1)[0] + " …"
                             if len(reason) > LONG_REASON else "")
        rows.append(r | {"css": _STATUS_CLASS.get(row.get("status", ""), "notrep")})
    return rows


def _notebook_sections(out: Path, name: str, figures, claims: pd.DataFrame) -> list[Section]:
    """The sections of one notebook: one per paper figure, then its other figures."""
    folder = out / name
    sides = _sidecars(folder)
    html_nb = f"notebooks/{name}.html"
    _, own_departures = load_departures()
    sections = []
    for fig in figures:
        mine = [stem for stem, m in sides.items() if m["figures"][:1] == [fig]]
        shared = [m["figures"][0] for m in sides.values() if fig in m["figures"][1:]]
        rows = _claim_rows(claims, fig)
        if not (mine or shared or rows):
            continue
        sections.append(Section(
            key=fig, title=FIGURE_TITLES.get(fig, fig), anchor=fig, notebook=name,
            notebook_html=html_nb, departures=own_departures.get(fig, ""),
            shown_with=shared[0] if shared and not mine else "", claims=rows,
            images=[_image(folder / sides[stem]["file"], out, sides[stem]["caption"])
                    for stem in mine]))
    extra = [stem for stem, m in sides.items() if not m["figures"]]
    if extra:     # figures a notebook saved without a paper figure (e.g. its own studies)
        sections.append(Section(
            key=name, title=notebook_title(out, name), anchor=_slug(name), notebook=name,
            notebook_html=html_nb,
            images=[_image(folder / sides[stem]["file"], out, sides[stem]["caption"])
                    for stem in extra]))
    return sections


def variants_view(v: dict | None) -> dict | None:
    """The variants' part of the report as plain text rows (None: not checked).

    Parameters
    ----------
    v : dict or None
        :func:`tefcore.paper.run.variant_runs.finish_variant_runs`'s result.

    Returns
    -------
    dict or None
        ``names``, ``base``, ``reason``, ``summaries`` and ``scores`` (one row
        per variant), ``rows`` (every claim: its statuses, a calibration tag
        marked, and why they differ), ``differences`` (the rows that differ),
        ``conflict`` (``columns``, ``rows``) and ``conflict_text`` (the measured
        conflict in sentences), ``worse`` and ``errors``.
    """
    if not v:
        return None
    from ..fig6_calibration import conflict_text

    names = v["names"]
    rows = []
    for r in v["comparison"].to_dict("records"):
        marks = [r[f"status {n}"] + (" (calibration)" if r[f"tag {n}"] == "calibration"
                                     else "") for n in names]
        rows.append({"id": r["id"], "figure": r["figure"], "statuses": marks,
                     "css": [_STATUS_CLASS.get(r[f"status {n}"], "notrep") for n in names],
                     "why": _plain(r["why"]), "differs": bool(r["differs"])})
    conflict = v.get("conflict")
    table = None if conflict is None else conflict.fillna("").astype(str)
    worse = v["worse"]
    return {"names": names, "base": v["base"], "reason": _plain(v["reason"]),
            "summaries": [{"name": n, "summary": _plain(v["summaries"][n]),
                           "passed": v["scores"][n][0], "total": v["scores"][n][1]}
                          for n in names],
            "rows": rows, "differences": [r for r in rows if r["differs"]],
            "conflict": None if table is None else {"columns": list(table.columns),
                                                    "rows": table.values.tolist()},
            "conflict_text": "" if conflict is None else conflict_text(conflict),
            "worse": [] if worse.empty else worse.fillna("").astype(str).to_dict("records"),
            "errors": list(v["errors"])}


def _parameters_text(params: dict) -> str:
    """A notebook's parameters as ``name = value`` pairs (its output folder left out)."""
    return ", ".join(f"{k} = {v!r}" for k, v in sorted((params or {}).items())
                     if k != "output_dir")


def build_report(out, runs, claims: pd.DataFrame, worse: pd.DataFrame, *, figures_of,
                 checks: pd.DataFrame | None = None, version: str = "",
                 title: str = "tefcore reproduction report", up: str = "",
                 variants: dict | None = None,
                 attribution: pd.DataFrame | None = None, what_if: str = "",
                 attribution_source: str = "") -> Report:
    """Collect a reproduction's outputs in ``out`` into a :class:`Report`.

    Parameters
    ----------
    out : path
        The reproduction folder (``<notebook>/`` with PNGs, their JSON
        captions (:func:`tefcore.paper.figures.plotting.savefig`) and claims;
        ``notebooks/<notebook>.html``).
    runs : list
        Notebook runs (``name, status, error, seconds``).
    claims, worse : DataFrame
        All claims (with a ``notebook`` column) and those worse than recorded.
    figures_of : dict
        Notebook -> the paper figures it reproduces, in order.
    checks : DataFrame, optional
        The stated blade frequencies against the model's.
    version : str
        The version of tefcore, shown in the summary.  Run times are printed
        by :func:`tefcore.paper.run.reproduce.reproduce`, not kept in the report,
        so that two runs write identical reports.
    title : str
        The page title.
    up : str
        Link to the page the report belongs to (``""``: none).
    variants : dict, optional
        The other variant's claims beside these
        (:func:`tefcore.paper.run.variant_runs.finish_variant_runs`).
    attribution : DataFrame, optional
        The run's attribution (:mod:`tefcore.paper.attribution.differences`): "why we
        differ" per figure and for the whole run.
    what_if : str
        The parameters that make the run a what-if (:mod:`tefcore.paper.run.outcome`);
        ``""`` for the recorded computation.
    attribution_source : str
        How the attribution was obtained, a sentence for "why we differ"
        (:attr:`tefcore.paper.attribution.differences.Attribution.source`;
        ``""``: searched by this run).

    Returns
    -------
    Report
        The model :func:`render` turns into markdown or HTML.
    """
    out = Path(out)
    status = claims.get("status", pd.Series(dtype=str))
    validation = claims[claims["tag"] == "validation"] if "tag" in claims else claims
    passed = int((validation.get("status", pd.Series(dtype=str)) == "pass").sum())
    counts = {s: int((status == s).sum()) for s in _STATUS_CLASS}
    sections = [sec for run in runs
                for sec in _notebook_sections(out, run.name, figures_of.get(run.name, ()),
                                              claims)]
    by_key = {sec.key: sec for sec in sections}
    for sec in sections:
        shown = sec.images or (by_key[sec.shown_with].images if sec.shown_with in by_key
                               else [])
        sec.thumb = shown[0].data if shown else ""
        sec.thumb_mime = shown[0].mime if shown else "image/png"
        n = pd.Series([c["status"] for c in sec.claims], dtype=str).value_counts()
        sec.tally = ", ".join(f"{n[st]} {st}" for st in _STATUS_CLASS if st in n) \
            or "no claims checked"
    # the sentences every stability figure's caption repeats, said once above them
    notes, short = shared_notes(im.caption for sec in sections for im in sec.images)
    for sec in sections:
        for im in sec.images:
            im.shared = bool(notes) and short[im.caption] != im.caption
            im.caption = short[im.caption]
    why = None
    if attribution is not None:
        why = {**why_view(attribution, claims), "source": attribution_source}
        for sec in sections:
            sec.attribution = why["figures"].get(sec.key, [])
    fan = out / "mdart_fanplot.png"
    return Report(
        title=title, up=up,
        intro=headline(claims, what_if),
        guide=("Each section below shows one figure of the paper as tefcore computes it, the "
               "paper's statements about it checked against the computation, and where the "
               "compact model departs from the paper's. A root is named by the uncoupled mode "
               "it continues from as the blade-flap coupling is switched on (docs/theory.md "
               "9.1)."),
        passed=passed, total=len(validation), counts=counts,
        worse=worse.fillna("").astype(str).to_dict("records") if not worse.empty else [],
        notebooks=[{"name": r.name, "status": r.status, "error": r.error,
                    "html": f"notebooks/{r.name}.html",
                    "parameters": _parameters_text(getattr(r, "parameters", {}))}
                   for r in runs],
        sections=sections, figure_notes=notes,
        checks=check_rows(checks),
        version=version,
        fanplot=_image(fan, out, "MDART blade (assumed properties): fan plot of the coupled "
                                 "modes") if fan.exists() else None,
        departures=departures_text(), variants=variants_view(variants), why=why,
        what_if=what_if, truncation=_truncation_rows(claims),
        inference=inference_view(load_results()))


def _truncation_rows(claims: pd.DataFrame) -> list[dict]:
    """The claims whose verdict depends on the modal basis, as the report lists them."""
    if "truncation" not in claims:
        return []
    rows = claims[claims["truncation"].fillna("").astype(str) == "truncation-dependent"]
    return rows[["id", "status", "converged_status", "converged_modes"]].fillna("") \
        .astype(str).to_dict("records")


def template_environment(**filters) -> jinja2.Environment:
    """The jinja2 environment of tefcore's report templates (``tefcore/paper/run/templates``).

    HTML templates are autoescaped, undefined names are errors, and the filter
    ``mdcell`` makes a value fit one markdown table cell.

    Parameters
    ----------
    **filters : callable
        Further template filters by name (e.g. ``md_to_html``).

    Returns
    -------
    jinja2.Environment
    """
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("tefcore.paper.run", "templates"),
        autoescape=jinja2.select_autoescape(enabled_extensions=("html", "html.j2"),
                                            default_for_string=False),
        trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined)
    env.filters["mdcell"] = lambda v: str(v).replace("|", "\\|").replace("\n", " ")
    env.filters.update(filters)
    return env


def _md_inline_to_html(text: str):
    """Minimal inline markdown (emphasis, code, paragraphs, bullets) to safe HTML."""
    from markupsafe import Markup, escape

    out, items = [], []
    for block in re.split(r"\n\s*\n", str(text).strip()):
        lines = block.strip().splitlines()
        if all(ln.lstrip().startswith(("* ", "- ")) or not ln.strip() or ln.startswith("  ")
               for ln in lines) and lines and lines[0].lstrip().startswith(("* ", "- ")):
            items = []
            for ln in lines:
                if ln.lstrip().startswith(("* ", "- ")):
                    items.append(ln.lstrip()[2:])
                elif items:
                    items[-1] += " " + ln.strip()
            out.append("<ul>" + "".join(f"<li>{_inline(escape(i))}</li>" for i in items)
                       + "</ul>")
        else:
            heading = re.match(r"^(#+)\s+(.*)$", lines[0]) if lines else None
            if heading:
                out.append(f"<h4>{_inline(escape(heading.group(2)))}</h4>")
                lines = lines[1:]
            if lines:
                out.append(f"<p>{_inline(escape(' '.join(ln.strip() for ln in lines)))}</p>")
    return Markup("\n".join(out))


def _inline(text) -> str:
    s = str(text)
    s = re.sub(r"\[([^\]]+)\]\(((?:https?://|#)[^)\s]+)\)", r'<a href="\2">\1</a>', s)
    s = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", s)
    s = re.sub(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])", r"<em>\1</em>", s)
    s = re.sub(r"`([^`]+)`", r"<code>\1</code>", s)
    return s


def render(report: Report, fmt: str = "html") -> str:
    """The report as ``"html"`` (self-contained, figures embedded) or ``"md"``.

    Parameters
    ----------
    report : Report
        What to show (:func:`build_report`).
    fmt : {"html", "md"}
        Output format: one responsive HTML page with the figures embedded as
        base64, or markdown linking the PNGs beside it.

    Returns
    -------
    str
        The rendered text (jinja2 templates ``tefcore/paper/run/templates``).

    Raises
    ------
    ValueError
        Another format.
    """
    if fmt not in ("html", "md"):
        raise ValueError(f"format must be 'html' or 'md', got {fmt!r}")
    from markupsafe import Markup, escape

    return template_environment(
        md_to_html=_md_inline_to_html, md_inline=lambda t: Markup(_inline(escape(t)))
    ).get_template(
        f"report.{fmt}.j2").render(r=report)


def write_report(report: Report, out) -> tuple[Path, Path]:
    """Write ``report.md`` and ``report.html`` into ``out``; return their paths.

    Each file is written atomically (:func:`tefcore.safe_io.atomic_write_text`).

    Parameters
    ----------
    report : Report
        What to show.
    out : path
        Existing reproduction folder (the markdown links the PNGs in it).

    Returns
    -------
    tuple of pathlib.Path
        ``(out/report.md, out/report.html)``.
    """
    out = Path(out)
    paths = out / "report.md", out / "report.html"
    for path, fmt in zip(paths, ("md", "html"), strict=True):
        atomic_write_text(path, render(report, fmt))
    return paths
