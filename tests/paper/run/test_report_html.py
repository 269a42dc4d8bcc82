"""The reproduction report: one model, markdown and HTML, checked structurally.

Images embedded, every in-page link resolves, no literal
markdown in the HTML, a viewport for small screens, a real caption under each
figure, claims beside their figure, departures per figure and once in full.
"""

import base64
import json
import re
from html.parser import HTMLParser

import pandas as pd
import pytest

from tefcore.paper.run.report import build_report, render, write_report
from tefcore.paper.run.reproduce import NotebookRun

PNG = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg==")


class _Page(HTMLParser):
    """Ids, in-page links, images and visible text of a page."""

    def __init__(self):
        super().__init__()
        self.ids, self.links, self.imgs, self.text, self._skip = set(), [], [], [], 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and a.get("href", "").startswith("#"):
            self.links.append(a["href"][1:])
        if tag == "img":
            self.imgs.append(a)
        if tag in ("style", "script"):
            self._skip += 1

    def handle_endtag(self, tag):
        if tag in ("style", "script"):
            self._skip -= 1

    def handle_data(self, data):
        if not self._skip:
            self.text.append(data)


def check_page(page: str) -> _Page:
    """Assert the structural rules; return the parsed page."""
    p = _Page()
    p.feed(page)
    assert '<meta name="viewport"' in page
    missing = sorted(set(p.links) - p.ids)
    assert not missing, f"links to missing anchors: {missing}"
    assert p.imgs, "no figures"
    for img in p.imgs:
        kind = img["src"][:22]
        assert kind in ("data:image/png;base64,", "data:image/gif;base64,"), img["src"][:40]
        magic = base64.b64decode(img["src"].split(",", 1)[1])[:6]
        assert magic[:6] in (b"\x89PNG\r\n", b"GIF89a", b"GIF87a"), magic
        assert img.get("alt")
    text = " ".join(p.text)
    literal = re.findall(r"\*\*[^*]+\*\*|(?<![\w*])\*[A-Za-z][^*]*\*(?![\w*])|`[^`]+`", text)
    assert not literal, f"literal markdown in the page: {literal[:3]}"
    assert 'src="http' not in page and "<link" not in page      # self-contained
    return p


@pytest.fixture
def folder(tmp_path):
    """A reproduction folder: notebook 07 with a figure for 16a and 16b, one for 17."""
    nb = tmp_path / "07_flight_condition"
    nb.mkdir()
    for stem, figs, cap in (("fig16", "fig16a fig16b", "Fig. 16: **collective** (μ = 0.30)"),
                            ("fig17", "fig17", "Fig. 17: forward speed, *imbalanced* flap"),
                            ("extra", "", "a study of `my` own")):
        (nb / f"{stem}.png").write_bytes(PNG)
        (nb / f"{stem}.json").write_text(json.dumps({"figure": figs, "caption": cap}))
    claims = pd.DataFrame([
        {"notebook": "07_flight_condition", "id": "fig17-a", "figure": "fig17",
         "statement": "the TEF is *more* unstable", "expected": "x", "computed": "y",
         "status": "pass", "reason": "", "tag": "validation", "recorded_status": "pass"},
        {"notebook": "07_flight_condition", "id": "fig16a-b", "figure": "fig16a",
         "statement": "s", "expected": "x", "computed": "y", "status": "fail",
         "reason": "r", "tag": "validation", "recorded_status": "fail"}])
    runs = [NotebookRun("07_flight_condition", status="ok")]
    return tmp_path, runs, claims


def test_report_sections_follow_the_paper(folder):
    out, runs, claims = folder
    r = build_report(out, runs, claims, claims.iloc[0:0],
                     figures_of={"07_flight_condition": ("fig16a", "fig16b", "fig17")})
    assert [s.key for s in r.sections] == ["fig16a", "fig16b", "fig17", "07_flight_condition"]
    a, b, c, extra = r.sections
    assert len(a.images) == 1 and not b.images and b.shown_with == "fig16a"
    assert [x["id"] for x in c.claims] == ["fig17-a"] and c.images[0].caption.startswith(
        "Fig. 17: forward speed, imbalanced flap")                 # markup out of captions
    assert "For Figs. 16-17 in particular" in a.departures and r.departures
    assert (r.passed, r.total) == (1, 2)
    assert extra.images[0].caption == "a study of my own"


def test_html_is_self_contained_linked_and_free_of_markup(folder):
    out, runs, claims = folder
    r = build_report(out, runs, claims, claims.iloc[0:0],
                     figures_of={"07_flight_condition": ("fig16a", "fig16b", "fig17")})
    md_path, html_path = write_report(r, out)
    page = check_page(html_path.read_text(encoding="utf-8"))
    assert {"fig16a", "fig16b", "fig17", "departures"} <= page.ids
    assert len(page.imgs) >= 3 + 2                  # thumbnails link down to the figures
    md = md_path.read_text(encoding="utf-8")
    assert "](07_flight_condition/fig16.png)" in md and "(#fig16a)" in md


def test_structural_check_fails_on_a_broken_page(folder):
    """The checks above can fail: a dangling link, a linked image, literal markup."""
    out, runs, claims = folder
    r = build_report(out, runs, claims, claims.iloc[0:0],
                     figures_of={"07_flight_condition": ("fig16a", "fig16b", "fig17")})
    good = render(r, "html")
    for bad in (good.replace('id="fig17"', 'id="fig-17"'),
                good.replace("data:image/png;base64,", "http://x/", 1),
                good.replace("</main>", "<p>**bold**</p></main>")):
        with pytest.raises(AssertionError):
            check_page(bad)
