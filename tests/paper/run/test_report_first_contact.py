"""The report as a first-time reader meets it (README command 1, read in a browser).

Its top says in three sentences, made from the claims table, what
reproduces, what does not and the key finding; "why we differ" speaks of
the claims' sentences and of properties with their units and plausible
ranges; a sentence every figure's caption repeats is said once; notebook 11
is in the report; the frequency table has named columns; the executed
notebooks' pages read offline.
"""

import base64
import html
import json
import re

import pandas as pd
import pytest

from tefcore.paper.run.report import build_report, render
from tefcore.paper.run.reproduce import NotebookRun
from tests.paper.run.test_report_html import PNG, check_page

GIF = base64.b64decode("R0lGODlhAQABAIAAAAAAAP///yH5BAEAAAAALAAAAAABAAEAAAIBRAA7")
SHARED = ("Lines join the computed points of one root. Filled markers are the figure's own "
          "sweep points.")


def _claim(cid, figure, status, **kw):
    return {"notebook": "04_cg_offset", "id": cid, "figure": figure, "panel": "b",
            "kind": "trend", "tag": "validation", "mode": "", "quantity": "",
            "statement": f"statement of {cid}", "expected": "x", "computed": "y",
            "computed_value": "", "status": status, "reason": "", "recorded_status": status,
            **kw}


CLAIMS = pd.DataFrame([
    _claim("fig9b-tef-unstable", "fig9", "fail", kind="threshold", mode="TEF",
           statement="The TEF mode becomes unstable after a CG offset of 0.26.",
           computed="crossings: none (real part -4.9 to -2.99 1/rev)"),
    _claim("fig9b-flutter-mechanism", "fig9", "fail", kind="mechanism", mode="flutter root",
           computed="flutter at +2.71 +10.3i /rev; TEF participation 0.21; torsion "
                    "participation 0.49", computed_value="2.71"),
    _claim("fig9b-flap-damping", "fig9", "pass"),
    _claim("fig10b-tef-more-unstable", "fig10", "pass"),
    _claim("fig10b-lag", "fig10", "pass"),
    _claim("fig12b-tef-stable", "fig12", "ambiguous", kind="threshold", mode="TEF",
           statement="The TEF mode is stable above 1.5 times the actuator stiffness.",
           reason="an exceptional point lies inside the claim's range " + "and more " * 60),
])

ATTRIBUTION = pd.DataFrame([
    {"claim": "fig9b-tef-unstable", "status": "fail", "assumption": "Fig. 6 flap-system inertia",
     "flips_at": "0.0006814", "plausible_low": "0.0", "plausible_high": "0.000778714",
     "within_plausible": "True", "figure": "fig9", "setting": "actuator.reflected_inertia",
     "baseline": "0.0", "confirmed": "True", "conflicts": "", "tried": "", "evaluations": "4",
     "note": ""},
    {"claim": "fig9b-flutter-mechanism", "status": "fail", "assumption": "none",
     "flips_at": "", "plausible_low": "", "plausible_high": "", "within_plausible": "False",
     "figure": "fig9", "setting": "", "baseline": "", "confirmed": "", "conflicts": "",
     "tried": "", "evaluations": "", "note": "none within plausible range"},
])


@pytest.fixture
def report_folder(tmp_path):
    """Notebook 04's figures (two sharing the legend sentences) and notebook 11's animation."""
    nb = tmp_path / "04_cg_offset"
    nb.mkdir()
    for stem, fig in (("fig09", "fig9"), ("fig09_locus", "fig9"), ("fig10", "fig10"),
                      ("fig12", "fig12")):
        (nb / f"{stem}.png").write_bytes(PNG)
        (nb / f"{stem}.json").write_text(json.dumps(
            {"figure": fig, "caption": f"Fig. {fig[3:]}: {stem} (μ = 0.30). {SHARED}"}))
    eleven = tmp_path / "11_watch_it_flutter"
    eleven.mkdir()
    (eleven / "imbalanced.gif").write_bytes(GIF)
    (tmp_path / "notebooks").mkdir()
    (tmp_path / "notebooks" / "11_watch_it_flutter.ipynb").write_text(json.dumps(
        {"cells": [{"cell_type": "markdown", "source": ["# 11 -- Watch it flutter\n", "text"]}]}))
    runs = [NotebookRun("04_cg_offset", status="ok"), NotebookRun("11_watch_it_flutter")]
    checks = pd.DataFrame({"case": ["pitch link 158 lb/in"], "stated_per_rev": [2.3],
                           "computed_per_rev": [2.306], "error_percent": [0.26],
                           "flap1_per_rev": [1.05], "lag1_per_rev": [0.6], "source": ["s"]})
    r = build_report(tmp_path, runs, CLAIMS, CLAIMS.iloc[0:0], checks=checks,
                     figures_of={"04_cg_offset": ("fig9", "fig10", "fig12"),
                                 "11_watch_it_flutter": ()},
                     attribution=ATTRIBUTION)
    return r, {fmt: render(r, fmt) for fmt in ("md", "html")}


def _text(html):
    return " ".join(re.sub(r"<[^>]+>", " ", html).split())


def test_the_top_says_what_reproduces_what_does_not_and_the_key_finding(report_folder):
    r, pages = report_folder
    sentences = re.split(r"(?<!Fig\.)(?<!Figs\.)(?<=\.) (?=[A-Z0-9])", r.intro)
    assert len(sentences) == 3, sentences
    assert sentences[0] == ("3 of the paper's 6 validation claims reproduce, among them every "
                            "statement on Fig. 10.")
    assert sentences[1].startswith("2 do not (on Fig. 9), and 1 cannot be decided")
    assert "of the 1 statement that the TEF mode becomes unstable" in sentences[2]
    assert "+2.7 /rev in Fig. 9" in sentences[2]             # from the table, not written in
    assert pages["md"].index(r.intro) < pages["md"].index("What a claim's status means")


def test_why_we_differ_speaks_of_sentences_properties_units_and_ranges(report_folder):
    r, pages = report_folder
    page = html.unescape(pages["html"])
    why = _text(page[page.index('id="why-we-differ"'):page.index('id="reading-figures"')])
    assert "The TEF mode becomes unstable after a CG offset of 0.26." in why
    assert "actuator.reflected_inertia, plausible 0 kg m² to 0.000779 kg m²" in why
    assert "with a conflict" not in page
    section = r.sections[0]
    row = section.attribution[0]
    assert row["plausible"] == ["Fig. 6 flap-system inertia = 0.000681 kg m² (actuator."
                                "reflected_inertia: plausible 0 kg m² to 0.000779 kg m²; "
                                "baseline 0 kg m²)"]


def test_a_sentence_every_caption_repeats_is_said_once(report_folder):
    r, pages = report_folder
    assert r.figure_notes == ["Lines join the computed points of one root.",
                              "Filled markers are the figure's own sweep points."]
    for fmt in ("md", "html"):
        page = html.unescape(pages[fmt])
        assert page.count("Filled markers are the figure's own sweep points.") == 1
    caps = [im.caption for s in r.sections for im in s.images if s.key.startswith("fig")]
    assert caps[0] == "Fig. 9: fig09 (μ = 0.30)."


def test_notebook_11_is_in_the_report_with_its_animation(report_folder):
    r, pages = report_folder
    eleven = [s for s in r.sections if s.notebook == "11_watch_it_flutter"]
    assert [s.title for s in eleven] == ["11 — Watch it flutter"]
    assert eleven[0].images[0].mime == "image/gif"
    assert "data:image/gif;base64," in pages["html"]
    check_page(pages["html"])


def test_the_frequency_table_has_named_columns_with_units(report_folder):
    _, pages = report_folder
    assert "stated torsion 1 [/rev]" in pages["html"] and "computed_per_rev" not in pages["html"]


def test_a_long_reason_is_folded(report_folder):
    _, pages = report_folder
    page = pages["html"]
    row = page[page.index("fig12b-tef-stable"):]
    assert row.index("<details") < row.index("and more and more")


def test_the_executed_notebook_page_reads_offline(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    pytest.importorskip("nbconvert")
    pytest.importorskip("latex2mathml")
    from tefcore.paper.run.notebook_page import notebook_html

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("growth $e^{2\\pi\\sigma}$ per revolution"),
                nbformat.v4.new_code_cell("1 + 1")]
    path = tmp_path / "n.ipynb"
    nbformat.write(nb, path)
    page = notebook_html(path)
    assert not re.findall(r"""(?:src|href)=["']https?://""", page)   # no CDN: MathJax, require
    assert "<math" in page and "e^{2" not in page


def test_truncation_dependent_verdicts_are_listed_with_both(tmp_path):
    # a claim the nine-mode basis passes and the converged basis fails is listed
    # with both verdicts; without converged verdicts there is no such section
    from tefcore.paper.claims.truncation import mark_truncation

    conv = pd.DataFrame({"id": ["fig10b-tef-more-unstable", "fig10b-lag"],
                         "status": ["fail", "pass"], "n_modes": [24, 24],
                         "computed_value": [0.0, 0.0]})
    claims = mark_truncation(CLAIMS, conv)
    runs = [NotebookRun("04_cg_offset", status="ok")]
    r = build_report(tmp_path, runs, claims, claims.iloc[0:0],
                     figures_of={"04_cg_offset": ("fig10",)})
    assert r.truncation == [{"id": "fig10b-tef-more-unstable", "status": "pass",
                             "converged_status": "fail", "converged_modes": "24"}]
    for fmt in ("md", "html"):
        page = html.unescape(render(r, fmt))
        assert "Truncation-dependent verdicts" in page and "fig10b-tef-more-unstable" in page
    plain = build_report(tmp_path, runs, CLAIMS, CLAIMS.iloc[0:0],
                         figures_of={"04_cg_offset": ("fig10",)})
    assert plain.truncation == [] and "Truncation-dependent" not in render(plain, "html")
