"""Drive the served explorer page in headless Chromium and report what a person would see.

Starts ``tefcore explore`` on a free port (the same Python; the repository
first on ``PYTHONPATH``), opens the page with Playwright in headless Chromium
at each width (1400 and 800 px by default), waits for the widgets and the
first figures, moves sliders (the flap CG offset down to a mass-balanced
flap, the advance ratio), clicks *animate the flutter root* once, and takes
a screenshot after each step.  It reports, per width: the console and page
errors, whether the page scrolls sideways (overflow), the figures' sizes,
the status line, and the slider values read back from the page.  Exit
status 1 when something is wrong (errors, overflow, a figure that never
came).

Needs voila (``pip install 'tefcore[app]'``), Playwright (``pip install
playwright``) and a Chromium (``apt-get install chromium``; or
``playwright install chromium`` where downloads are allowed)::

    python tools/check_explorer.py --out /tmp/explorer-check
    python tools/check_explorer.py --widths 1400 --no-animation
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

#: What the page must show once computed (selectors of ipywidgets 8 in voila).
SLIDER = ".widget-slider"
IMAGE = ".widget-image img, img.widget-image"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(REPO), *filter(None, [os.environ.get("PYTHONPATH")])])}
    proc = subprocess.Popen([sys.executable, "-m", "tefcore", "explore", "--port", str(port)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 90
    while time.time() < deadline:
        if proc.poll() is not None:
            raise SystemExit(f"tefcore explore exited: {proc.stdout.read()}")
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=5).read(100)
            return proc
        except OSError:
            time.sleep(1)
    proc.terminate()
    raise SystemExit("the server did not answer within 90 s")


def chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if path := shutil.which(name):
            return path
    return None


def wait_images(page, count: int, timeout: float = 240) -> list[dict]:
    """Wait until ``count`` figure images have content; their rendered sizes."""
    deadline = time.time() + timeout
    sizes: list[dict] = []
    while time.time() < deadline:
        sizes = page.evaluate("""(sel) => [...document.querySelectorAll(sel)]
            .filter(i => i.naturalWidth > 0)
            .map(i => ({w: i.getBoundingClientRect().width, h: i.getBoundingClientRect().height,
                        nw: i.naturalWidth}))""", IMAGE)
        if len(sizes) >= count:
            return sizes
        time.sleep(1)
    return sizes


def busy_wait(page, timeout: float = 240) -> str:
    """Wait while the status line says the page is computing; return it."""
    deadline = time.time() + timeout
    text = ""
    while time.time() < deadline:
        text = page.evaluate("""() => [...document.querySelectorAll('.widget-html-content')]
                                .map(e => e.innerText).join(' | ')""")
        if "…" not in text:
            return text
        time.sleep(1)
    return text


def move_slider(page, index: int, presses: int, key: str) -> None:
    """Focus the index-th slider's handle and press an arrow key (noUiSlider steps)."""
    handle = page.locator(f"{SLIDER} .noUi-handle").nth(index)
    handle.focus()
    for _ in range(presses):
        page.keyboard.press(key)
    page.keyboard.press("Tab")             # continuous_update=False: the value on release
    time.sleep(1.0)


def check_width(browser, url: str, width: int, out: Path, animation: bool) -> dict:
    # tall: voila's page scrolls inside its own container, which a full-page
    # screenshot does not unroll
    page = browser.new_page(viewport={"width": width, "height": 2000})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"console {m.type}: {m.text}")
            if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"page error: {e}"))
    page.on("requestfailed", lambda r: errors.append(f"request failed: {r.url}"))
    page.goto(url, timeout=240_000, wait_until="domcontentloaded")
    page.wait_for_selector(SLIDER, timeout=240_000)
    found = {"width": width, "first_images": wait_images(page, 2)}
    found["first_status"] = busy_wait(page)
    shots = [out / f"explorer-{width}-1-start.png"]
    page.screenshot(path=str(shots[-1]), full_page=True)
    move_slider(page, 0, 33, "ArrowLeft")        # CG offset 0.33 -> 0.00: mass-balanced
    found["status_after_cg"] = busy_wait(page)
    shots.append(out / f"explorer-{width}-2-balanced.png")
    page.screenshot(path=str(shots[-1]), full_page=True)
    move_slider(page, 0, 33, "ArrowRight")       # back to the paper's imbalanced flap
    move_slider(page, 3, 10, "ArrowLeft")        # advance ratio 0.30 -> 0.20
    found["status_after_mu"] = busy_wait(page)
    found["slider_values"] = page.evaluate("""() => [...document.querySelectorAll(
        '.widget-slider .widget-readout')].map(e => e.innerText || e.value)""")
    shots.append(out / f"explorer-{width}-3-mu020.png")
    page.screenshot(path=str(shots[-1]), full_page=True)
    if animation:
        page.get_by_text("animate the flutter root").click()
        time.sleep(2)
        found["status_after_animation"] = busy_wait(page, 400)
        found["images_after_animation"] = wait_images(page, 3, 60)
        shots.append(out / f"explorer-{width}-4-animation.png")
        page.screenshot(path=str(shots[-1]), full_page=True)
    found["overflow_px"] = page.evaluate(
        "() => document.documentElement.scrollWidth - window.innerWidth")
    # voila's page template links Font Awesome from a CDN, which an offline machine
    # cannot reach: reported apart (the page uses no icons), not a problem of the page
    offline = [e for e in errors if "ERR_NAME_NOT_RESOLVED" in e or "cdn.jsdelivr.net" in e]
    found["errors"] = [e for e in errors if e not in offline]
    found["offline_requests"] = sorted({e.split(": ", 1)[1] for e in offline
                                        if e.startswith("request failed")})
    found["screenshots"] = [str(s) for s in shots]
    page.close()
    return found


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="explorer-check", help="folder for the screenshots")
    p.add_argument("--widths", type=int, nargs="+", default=[1400, 800])
    p.add_argument("--no-animation", action="store_true", help="skip the animation button")
    p.add_argument("--brief", action="store_true", help="report without the image sizes")
    args = p.parse_args(argv)
    from playwright.sync_api import sync_playwright

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    port = free_port()
    server = start_server(port)
    report = []
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=chromium(), headless=True,
                                         args=["--no-sandbox"])
            for width in args.widths:
                report.append(check_width(browser, f"http://127.0.0.1:{port}/", width, out,
                                          not args.no_animation))
            browser.close()
    finally:
        server.terminate()
        server.wait(timeout=30)
    if args.brief:
        for r in report:
            for key in [k for k in r if "images" in k]:
                r[key] = [f"{i['w']:.0f}x{i['h']:.0f} (natural width {i['nw']})" for i in r[key]]
    print(json.dumps(report, indent=1))
    bad = [r for r in report if r["errors"] or r["overflow_px"] > 0
           or len(r["first_images"]) < 2]
    print(f"{len(report)} widths checked, {len(bad)} with problems", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
