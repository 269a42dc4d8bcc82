"""The report's layout in a real headless browser, at 1400 and 800 px width.

No element may spill out of its container horizontally (nor the page need a
horizontal scroll, nor a table hide columns behind a scroll bar), and no two
boxes of text may overlap.  Full-page screenshots go into the test's folder
(``tmp_path``) to be looked at.

An opt-in test (``TEFCORE_BROWSER=1``, with playwright and the Debian
package chromium, as tests/paper/test_explorer_app.py): it loads
``TEFCORE_REPORT`` (a report.html, e.g. a full reproduction's) or else a
report of notebook 04 at four CG offsets made here (about a minute).
"""

import importlib.util
import os
import shutil
from pathlib import Path

import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")

pytestmark = pytest.mark.skipif(
    os.environ.get("TEFCORE_BROWSER") != "1" or importlib.util.find_spec("playwright") is None
    or CHROMIUM is None,
    reason="a browser test: set TEFCORE_BROWSER=1, with playwright and chromium installed")

#: How the browser is started: no network, no first-run work of its own.
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run"]

#: Page widths checked [px]: a laptop and a narrow window (the page's one-column layout
#: starts at 1000 px).
WIDTHS = (1400, 800)

#: In the page: what spills horizontally and which text boxes overlap.  A box spills
#: when its right edge passes its container's by more than a pixel (rounding of
#: sub-pixel layout) and no scrolling ancestor clips it; a scrolling container fails
#: when its content is wider than itself.  Text boxes are the rectangles of every
#: visible text node; two overlap when they share more than 2 px in each direction
#: (anti-aliased glyph edges of adjacent lines touch by about 1 px).
MEASURE = """
() => {
  const spills = [], boxes = [];
  const name = (el) => el.tagName.toLowerCase() + (el.id ? '#' + el.id : '') +
      (el.className && typeof el.className === 'string' ? '.' + el.className.split(' ')[0] : '');
  const scrolls = (el) => ['auto', 'scroll', 'hidden'].includes(getComputedStyle(el).overflowX);
  // what a closed <details> holds is laid out but not shown: not measured
  const shown = (el) => {
    const d = el.closest('details');
    if (d && !d.open && !el.closest('summary')) return false;
    return el.checkVisibility({checkVisibilityCSS: true, contentVisibilityAuto: true});
  };
  for (const el of document.body.querySelectorAll('*')) {
    const r = el.getBoundingClientRect();
    if ((r.width === 0 && r.height === 0) || !shown(el)) continue;
    if (scrolls(el) && el.scrollWidth > el.clientWidth + 1)
      spills.push(name(el) + ' scrolls: content ' + el.scrollWidth + ' > ' + el.clientWidth);
    const parent = el.parentElement;
    if (!parent || parent === document.body) continue;
    let clipped = false;
    for (let a = parent; a && a !== document.body; a = a.parentElement)
      if (scrolls(a)) { clipped = true; break; }
    const p = parent.getBoundingClientRect();
    if (!clipped && r.right > p.right + 1)
      spills.push(name(el) + ' spills out of ' + name(parent) + ' by ' +
                  Math.round(r.right - p.right) + ' px');
  }
  if (document.documentElement.scrollWidth > window.innerWidth)
    spills.push('the page scrolls sideways: ' + document.documentElement.scrollWidth);
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    if (!n.textContent.trim() || !shown(n.parentElement)) continue;
    const range = document.createRange();
    range.selectNodeContents(n);
    for (const r of range.getClientRects())
      if (r.width > 0 && r.height > 0)
        boxes.push([r.left + scrollX, r.top + scrollY, r.right + scrollX, r.bottom + scrollY,
                    n.textContent.trim().slice(0, 40)]);
  }
  boxes.sort((a, b) => a[1] - b[1]);
  const overlaps = [];
  for (let i = 0; i < boxes.length; i++)
    for (let j = i + 1; j < boxes.length && boxes[j][1] < boxes[i][3] - 2; j++) {
      const a = boxes[i], b = boxes[j];
      const w = Math.min(a[2], b[2]) - Math.max(a[0], b[0]);
      const h = Math.min(a[3], b[3]) - Math.max(a[1], b[1]);
      if (w > 2 && h > 2) overlaps.push(a[4] + ' | ' + b[4]);
    }
  return {spills, overlaps, texts: boxes.length};
}
"""


@pytest.fixture(scope="module")
def report_page(tmp_path_factory):
    given = os.environ.get("TEFCORE_REPORT")
    if given:
        return Path(given).resolve()
    pytest.importorskip("papermill")
    from tefcore.paper.run import reproduce as rp

    out = tmp_path_factory.mktemp("browser") / "out"
    rp.reproduce(out, params={"04_cg_offset": {"n_points": 4}}, notebooks=["04"],
                 progress=False, variants=False, attribution=False)
    return out / "report.html"


@pytest.mark.parametrize("width", WIDTHS)
def test_the_report_spills_nothing_and_no_text_overlaps(report_page, width, tmp_path):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        try:
            page = browser.new_page(viewport={"width": width, "height": 1000})
            page.goto(report_page.as_uri())
            page.screenshot(path=str(tmp_path / f"report-top-{width}.png"))
            page.screenshot(path=str(tmp_path / f"report-{width}.png"), full_page=True)
            found = page.evaluate(MEASURE)
        finally:
            browser.close()
    print(f"screenshots: {tmp_path}")
    assert found["texts"] > 50                       # the page was measured, not blank
    assert found["spills"] == [], found["spills"][:10]
    assert found["overlaps"] == [], found["overlaps"][:10]
