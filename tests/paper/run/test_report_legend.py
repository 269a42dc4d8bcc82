"""The report's header explains every claim status and tag in short sentences."""

import re

import pytest

from tefcore.paper.claims.reference import STATUSES, TAGS
from tefcore.paper.run.report import (
    STATUS_MEANINGS,
    TAG_MEANINGS,
    WORSE_MEANING,
    Report,
    build_report,
    render,
)
from tests.paper.run.test_report_html import check_page, folder  # noqa: F401 (a fixture)


def plain(text: str) -> str:
    """Text as read: tags and markdown marks out, entities decoded, whitespace collapsed."""
    import html

    text = html.unescape(re.sub(r"<[^>]+>", " ", text))
    return " ".join(text.replace("**", "").replace("*", "").split())


@pytest.fixture
def pages(folder):  # noqa: F811 (the fixture of test_report_html)
    out, runs, claims = folder
    r = build_report(out, runs, claims, claims.iloc[0:0],
                     figures_of={"07_flight_condition": ("fig16a", "fig16b", "fig17")})
    return {fmt: render(r, fmt) for fmt in ("md", "html")}


def test_every_status_and_tag_has_one_sentence():
    # every status a claim can get (reference.STATUSES), nothing else
    assert set(STATUS_MEANINGS) == set(STATUSES) and set(TAG_MEANINGS) == set(TAGS)
    for name, meaning in [*STATUS_MEANINGS.items(), *TAG_MEANINGS.items(),
                          ("worse", WORSE_MEANING)]:
        # "ambiguous" takes two short sentences and a link to the theory
        most = 1 if name == "ambiguous" else 0
        assert meaning.count(". ") <= most and meaning.rstrip(")").endswith("."), meaning
        assert len(meaning.split(". ")[0].split()) <= 45, name


@pytest.mark.parametrize("fmt", ["md", "html"])
def test_the_header_explains_each_status_and_tag(pages, fmt):
    page = plain(pages[fmt])
    header = page[:page.index("Validation claims:")]        # above the score
    for name, meaning in [*STATUS_MEANINGS.items(), *(("tag " + k, v)
                                                      for k, v in TAG_MEANINGS.items()),
                          ("worse than recorded", WORSE_MEANING)]:
        meaning = plain(re.sub(r"\[([^]]+)\]\([^)]+\)", r"\1", meaning.split(" ([docs")[0]))
        assert f"{name}: {meaning}" in header or f"{name} {meaning}" in header, name


def test_ambiguous_is_two_short_sentences_with_a_link_to_the_theory(pages):
    text = plain(pages["md"])
    said = text[text.index("ambiguous:"):text.index("not reproducible:")]
    for words in ("two roots meet inside the claim's range", "exceptional point",
                  "no single answer", "the verdict depends on the choice",
                  "The reason says where they meet"):
        assert words in said, words
    assert len(said.split()) <= 70         # it was one sentence of 90 words
    assert '<a href="https://' in pages["html"] and "theory.md#93-exceptional-points" in \
        pages["html"]
    # the old wording (a veering as a reason for ambiguity) is gone
    assert "veering" not in text


def test_no_would_pass_beside_a_status(pages):
    for page in pages.values():
        assert "would pass" not in page and "would fail" not in page


def test_the_html_header_is_a_legend_and_stays_valid(pages):
    page = check_page(pages["html"])
    assert "statuses" in page.ids
    html = pages["html"]
    legend = html[html.index('<dl class="legend"'):html.index("</dl>")]
    assert legend.count("<dt") == len(STATUSES) + len(TAGS) + 1


def test_a_status_without_its_sentence_is_refused(monkeypatch):
    """A new status must be explained: the report cannot be built without its sentence."""
    monkeypatch.delitem(STATUS_MEANINGS, "ambiguous")
    with pytest.raises(KeyError, match="ambiguous"):
        Report(title="t", intro="i", passed=0, total=0, counts={}, worse=[], notebooks=[],
               sections=[], checks=[], version="0")
