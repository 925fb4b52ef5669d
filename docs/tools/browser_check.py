#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Opens the built documentation site in headless Chromium (Debian's chromium and chromium-driver, driven by
Selenium) and checks what a reader sees: every page loads without a console error (severity SEVERE), every image has
loaded with a non-zero size, every formula is rendered by MathJax (each Sphinx math element holds MathJax's output,
none is a TeX error, no raw `$$` or `$...\command...$` is left in the text outside code), no page requests anything
but local files (Chromium's network log: every request of every page, scripts, styles, fonts, images), the
search page finds `lyapunov_map` without a console error, and the home page is a landing page (no table of
contents in it, at most HOME_MAX_LINKS links, a figure).  Screenshots of a few pages go to SHOTS_DIR.
Usage: browser_check.py HTML_DIR [SHOTS_DIR]"""
import json
import os
import re
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage", "--window-size=1280,1000"]
SHOTS = ["index.html", "guides/attractors.html", "tutorials/fig4_1.html", "reference/cli.html", "reference/python.html",
         "reference/cpp.html", "reference/cpp/lyapunov_requests.html",
         "performance.html", "paper.html", "gallery.html"]


def browser(profile):
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for f in FLAGS + [f"--user-data-dir={profile}"]:
        opts.add_argument(f)
    # performance: Chromium's DevTools events, among them Network.requestWillBeSent for every request a page makes.
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)


def page_problems(d, url):
    """Console errors and broken images of one page (after it has loaded)."""
    d.get(url)
    WebDriverWait(d, 30).until(lambda x: x.execute_script("return document.readyState") == "complete")
    problems = [f"console: {e['message']}" for e in d.get_log("browser") if e.get("level") == "SEVERE"]
    broken = d.execute_script(
        "return Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0)"
        ".map(i => i.getAttribute('src'));")
    problems += [f"broken image: {src}" for src in broken]
    return problems + formula_problems(d) + remote_requests(d)


# Sphinx wraps each formula in span.math / div.math; MathJax 2 (CommonHTML output) adds a .mjx-chtml element inside
# it, and a TeX error becomes an merror (MathJax's noErrors extension shows the source instead).  The script waits for MathJax to finish (its queue empty).
UNRENDERED_JS = """
const maths = Array.from(document.querySelectorAll('span.math, div.math'));
const pending = maths.filter(m => !m.querySelector('.mjx-chtml')).map(m => m.textContent.slice(0, 60));
const errors = Array.from(document.querySelectorAll('.mjx-merror, .mjx-noError, [data-mathml*="<merror"]'))
  .map(e => e.textContent.slice(0, 60));
const hub = window.MathJax && window.MathJax.Hub;
const busy = hub ? (hub.queue.pending > 0 || hub.queue.running > 0) : false;
return {count: maths.length, pending: pending, errors: errors, busy: busy};
"""
# Text outside code that is TeX nobody rendered: $$, or $...$ holding a backslash command.
RAW_TEX = re.compile(r"\$\$|\$[^$\n]{0,80}\\[A-Za-z]+[^$\n]{0,80}\$")
TEXT_OUTSIDE_CODE_JS = """
const body = document.querySelector('article') || document.body;
const copy = body.cloneNode(true);
copy.querySelectorAll('pre, code, script, .math, .highlight').forEach(e => e.remove());
return copy.textContent;
"""


def formula_problems(d):
    """Formulas MathJax did not render (or rendered as errors), and raw TeX left in the page's text."""
    state = d.execute_script(UNRENDERED_JS)
    if state["count"]:
        try:
            WebDriverWait(d, 30).until(lambda x: not (s := x.execute_script(UNRENDERED_JS))["pending"] and not s["busy"])
        except Exception:
            pass
        state = d.execute_script(UNRENDERED_JS)
    problems = [f"formula not rendered: {t!r}" for t in state["pending"][:5]]
    problems += [f"formula with a TeX error: {t!r}" for t in list(dict.fromkeys(state["errors"]))[:5]]
    raw = RAW_TEX.findall(d.execute_script(TEXT_OUTSIDE_CODE_JS))
    problems += [f"raw TeX in the text: {t!r}" for t in raw[:5]]
    return problems


def remote_requests(d):
    """Every URL the page requested that is not a local file (or inline data): the site must work offline."""
    urls = []
    for entry in d.get_log("performance"):
        msg = json.loads(entry["message"])["message"]
        if msg.get("method") == "Network.requestWillBeSent":
            url = msg["params"]["request"]["url"]
            if not url.startswith(("file:", "data:", "blob:", "about:", "chrome:", "devtools:")):
                urls.append(url)
    return [f"network request: {u}" for u in sorted(set(urls))]


def search_problems(d, root, word):
    """Searches for `word` as a reader does (furo's search runs in the page's JavaScript): (the number of results
    listed, the console errors of the search, the request, the index's loading and the listing included)."""
    d.get_log("browser")  # what earlier pages logged
    d.get("file://" + os.path.join(root, "search.html") + "?q=" + word)
    try:
        WebDriverWait(d, 30).until(lambda x: len(x.find_elements(By.CSS_SELECTOR, "ul.search li")) > 0)
        hits = len(d.find_elements(By.CSS_SELECTOR, "ul.search li"))
    except Exception:
        hits = 0
    time.sleep(0.5)  # the summaries of the results load after the list: their errors too
    errors = [f"console: {e['message']}" for e in d.get_log("browser") if e.get("level") == "SEVERE"]
    return hits, errors


# The home page is a landing page: a few paragraphs, a figure and a short list of where to go, not the site's table
# of contents (its toctrees are hidden: the sidebar has them).
HOME_JS = """
const body = document.querySelector('article') || document.body;
return {links: body.querySelectorAll('a[href]:not(.headerlink)').length,
        toc: body.querySelectorAll('.toctree-wrapper a').length,
        images: body.querySelectorAll('img').length};
"""
HOME_MAX_LINKS = 40


def home_problems(d, root):
    d.get("file://" + os.path.join(root, "index.html"))
    home = d.execute_script(HOME_JS)
    problems = []
    if home["toc"]:
        problems.append(f"index.html: a table of contents of {home['toc']} links in the page (hide its toctrees)")
    if home["links"] > HOME_MAX_LINKS:
        problems.append(f"index.html: {home['links']} links, more than a landing page's {HOME_MAX_LINKS}")
    if home["images"] < 1:
        problems.append("index.html: no figure")
    return problems


def main():
    root = os.path.abspath(sys.argv[1])
    shots = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(os.path.dirname(root), "screenshots")
    os.makedirs(shots, exist_ok=True)
    pages = sorted(os.path.relpath(os.path.join(dp, f), root) for dp, _, fs in os.walk(root) for f in fs
                   if f.endswith(".html") and not dp.startswith(os.path.join(root, "_")))
    t0, failures = time.monotonic(), []
    with tempfile.TemporaryDirectory(prefix="btob-docs-chromium-") as profile:
        d = browser(profile)
        try:
            d.get_log("performance")  # the start page's events
            for p in pages:
                failures += [f"{p}: {x}" for x in page_problems(d, "file://" + os.path.join(root, p))]
                if p in SHOTS:
                    d.save_screenshot(os.path.join(shots, p.replace("/", "_").replace(".html", ".png")))
            hits, errors = search_problems(d, root, "lyapunov_map")
            d.save_screenshot(os.path.join(shots, "search.png"))
            if hits == 0:
                failures.append("search.html?q=lyapunov_map: no result")
            failures += [f"search.html?q=lyapunov_map: {e}" for e in errors]
            failures += home_problems(d, root)
        finally:
            d.quit()
    for f in failures:
        print("docs browser:", f)
    print(f"docs browser: {len(pages)} pages, search for lyapunov_map: {hits} results, {len(failures)} problems, "
          f"{time.monotonic() - t0:.1f} s; screenshots in {shots}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
