#!/usr/bin/env python3
"""Opens the built documentation site in headless Chromium (Debian's chromium and chromium-driver, driven by
Selenium) and checks what a reader sees: every page loads without a console error (severity SEVERE), every image has
loaded with a non-zero size, and the search page finds `lyapunov_map`.  Screenshots of a few pages go to
SHOTS_DIR.  Usage: browser_check.py HTML_DIR [SHOTS_DIR]"""
import os
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
         "performance.html", "paper.html", "gallery.html"]


def browser(profile):
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for f in FLAGS + [f"--user-data-dir={profile}"]:
        opts.add_argument(f)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
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
    return problems


def search_finds(d, root, word):
    """The search page lists at least one result for `word` (furo's search runs in the page's JavaScript)."""
    d.get("file://" + os.path.join(root, "search.html") + "?q=" + word)
    try:
        WebDriverWait(d, 30).until(lambda x: len(x.find_elements(By.CSS_SELECTOR, "ul.search li")) > 0)
    except Exception:
        return 0
    return len(d.find_elements(By.CSS_SELECTOR, "ul.search li"))


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
            for p in pages:
                failures += [f"{p}: {x}" for x in page_problems(d, "file://" + os.path.join(root, p))]
                if p in SHOTS:
                    d.save_screenshot(os.path.join(shots, p.replace("/", "_").replace(".html", ".png")))
            hits = search_finds(d, root, "lyapunov_map")
            d.save_screenshot(os.path.join(shots, "search.png"))
            if hits == 0:
                failures.append("search.html?q=lyapunov_map: no result")
        finally:
            d.quit()
    for f in failures:
        print("docs browser:", f)
    print(f"docs browser: {len(pages)} pages, search for lyapunov_map: {hits} results, {len(failures)} problems, "
          f"{time.monotonic() - t0:.1f} s; screenshots in {shots}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
