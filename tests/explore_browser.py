#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The explorer's page in a real browser (headless Chromium through chromium-driver and Selenium): it loads and draws
a first image; a box zoom changes the view and the address, and Back restores it; the wheel zooms in and a double
click resets; the r window [0.0717, 0.0727]
typed in gives a new image with the window lower bounds drawn; a link reproduces a view; a click inside the window of
(ab)^2(cb)^2 (its bounds read from results/windows/bounds_certified.csv) shows the word 1133; the basins at that r come
with their fractions; Export writes a scene that `btob run` reproduces.  Screenshots go to SHOTS.

Usage: explore_browser.py BTOB SOURCE_DIR SHOTS
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
import urllib.parse

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.actions.wheel_input import ScrollOrigin
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import WebDriverWait

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from explore_common import start_server, stop_server  # noqa: E402

TIMEOUT = 120  # s: generous, the machine may be loaded (and the sanitizer build is ~30x slower); each step takes
# well under a second on an idle machine


def browser(profile):
    o = webdriver.ChromeOptions()
    o.binary_location = "/usr/bin/chromium"
    for a in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--disable-sync",
              "--disable-dev-shm-usage", f"--user-data-dir={profile}", "--window-size=1500,1000"]:
        o.add_argument(a)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def view_of(d):
    return d.execute_script("return window.btob.imageView && Object.assign({}, window.btob.imageView)")


def wait_image(d, pred=lambda v: True):
    """Waits for an image whose view satisfies pred; returns that view."""
    WebDriverWait(d, TIMEOUT).until(lambda d: (v := view_of(d)) is not None and pred(v))
    return view_of(d)


def canvas_data(d):
    return d.execute_script("return document.getElementById('image-canvas').toDataURL()")


def blue_pixels(d):
    """Pixels of the overlay canvas in the window lower bounds' blue (#1f5fd6)."""
    return d.execute_script("""
      const c = document.getElementById('overlay-canvas'), p = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < p.length; i += 4) if (p[i + 3] > 200 && p[i + 2] > 180 && p[i] < 80) ++n;
      return n;""")


def click_at_r(d, r):
    """Clicks the plot at r (the page's own mapping), mid-height."""
    ov = d.find_element(By.ID, "overlay-canvas")
    x, y = d.execute_script("""
      const v = window.btob.view, c = document.getElementById('overlay-canvas'), ml = 78, mr = 16;
      const iw = c.width - ml - mr;
      return [ml + 0.5 + (arguments[0] - v.r_min) / (v.r_max - v.r_min) * (iw - 1), c.height / 2];""", r)
    ActionChains(d).move_to_element_with_offset(ov, x - ov.size["width"] / 2, y - ov.size["height"] / 2).click().perform()


def window_1133(source):
    """The bounds of the window n = 2, (ab)^2(cb)^2, whose stable orbit has the word 1133."""
    with open(os.path.join(source, "results", "windows", "bounds_certified.csv")) as f:
        row = next(r for r in csv.DictReader(f) if r["n"] == "2")
    return float(row["lower_bound"]), float(row["upper_bound"])


def zoom_and_back(d):
    first = canvas_data(d)
    url0 = d.current_url
    ov = d.find_element(By.ID, "overlay-canvas")
    ActionChains(d).move_to_element_with_offset(ov, -300, -100).click_and_hold().move_by_offset(200, 150) \
        .release().perform()
    v = wait_image(d, lambda v: v["r_min"] > 0.072 and v["r_max"] < 0.17)
    assert d.current_url != url0 and "r_min=" in d.current_url, d.current_url
    d.back()
    wait_image(d, lambda v: abs(v["r_min"] - 0.0717) < 1e-12 and abs(v["r_max"] - 0.1717) < 1e-12)
    print(f"explore_browser: box zoom to r in [{v['r_min']:.5f}, {v['r_max']:.5f}], Back restores the first view")
    ActionChains(d).scroll_from_origin(ScrollOrigin.from_element(ov), 0, -400).perform()  # wheel up: zoom in
    v = wait_image(d, lambda v: v["r_max"] - v["r_min"] < 0.09)
    ActionChains(d).double_click(ov).perform()
    wait_image(d, lambda v: abs(v["r_min"] - 0.0717) < 1e-12 and abs(v["r_max"] - 0.1717) < 1e-12)
    print(f"explore_browser: the wheel zooms to a window {v['r_max'] - v['r_min']:.4f} wide; a double click resets")
    return first


def zoom_in(d, first, shots):
    for field, value in [("r-min-input", "0.0717"), ("r-max-input", "0.0727")]:
        e = d.find_element(By.ID, field)
        e.clear()
        e.send_keys(value)
    e.send_keys(Keys.ENTER)
    wait_image(d, lambda v: v["r_min"] == 0.0717 and v["r_max"] == 0.0727)
    WebDriverWait(d, TIMEOUT).until(lambda d: json.loads(
        d.find_element(By.ID, "overlay-canvas").get_attribute("data-drawn") or "{}").get("window_bounds", 0) > 0)
    assert canvas_data(d) != first, "the image did not change"
    drawn = json.loads(d.find_element(By.ID, "overlay-canvas").get_attribute("data-drawn"))
    blue = blue_pixels(d)
    assert blue > 100, f"window lower bounds: {drawn['window_bounds']} lines but {blue} blue pixels"
    wait_image(d, lambda v: v["iterations"] >= 6000)  # refined while the view stays
    d.save_screenshot(os.path.join(shots, "explore_zoom.png"))
    print(f"explore_browser: r in [0.0717, 0.0727]: new image, {drawn['window_bounds']} window lower bounds drawn "
          f"({blue} blue pixels), refined to {view_of(d)['iterations']} iterations")


def pick_1133(d, base, source, shots):
    lo, hi = window_1133(source)
    d.get(base + "/?" + urllib.parse.urlencode({"r_min": 0.12, "r_max": 0.18, "coord": "phi", "lo": 0, "hi": 3.1416,
                                                   "levels": 2}))
    v = wait_image(d, lambda v: v["r_min"] == 0.12 and v["coord"] == "phi")  # a link reproduces its view
    r = (lo + hi) / 2
    click_at_r(d, r)
    WebDriverWait(d, TIMEOUT).until(lambda d: "1133" in d.find_element(By.ID, "info").text)
    info = d.find_element(By.ID, "info").text
    assert "periodic" in info and "period 4" in info, info
    d.find_element(By.ID, "basins-button").click()
    WebDriverWait(d, TIMEOUT).until(lambda d: "%" in d.find_element(By.ID, "basins-table").text)
    table = d.find_element(By.ID, "basins-table").text
    assert "1133" in table, table
    assert "undecided" in table and "NaN" not in table, table  # the verdict's one word, its share read from the JSON
    d.save_screenshot(os.path.join(shots, "explore_1133.png"))
    print(f"explore_browser: click at r = {r:.6f} in the window [{lo}, {hi}] reads: " + info.replace("\n", "; "))
    print("explore_browser: basins: " + table.replace("\n", "; "))


def export_and_run(d, btob, export_dir, tmp):
    d.find_element(By.ID, "export-button").click()
    WebDriverWait(d, TIMEOUT).until(lambda d: d.find_element(By.ID, "export-status").get_attribute("data-scene"))
    scene = d.find_element(By.ID, "export-status").get_attribute("data-scene")
    out = os.path.join(tmp, "run")
    subprocess.run([btob, "run", os.path.join(export_dir, scene), "--out", out, "--no-plot", "--quiet"], check=True)
    v = view_of(d)
    h5 = [f for f in os.listdir(out) if f.endswith(".h5")]
    assert h5, os.listdir(out)
    with open(os.path.join(export_dir, scene)) as f:
        text = f.read()
    assert f'r-min = "{v["r_min"]}"' in text and 'coord = "phi"' in text, text
    print(f"explore_browser: exported {scene}; btob run wrote {h5[0]}")


def main(btob, source, shots):
    os.makedirs(shots, exist_ok=True)
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        export_dir = os.path.join(tmp, "exports")
        proc, base = start_server(btob, export_dir, cwd=tmp)
        d = None
        try:
            d = browser(os.path.join(tmp, "profile"))
            d.get(base + "/?levels=2")  # two levels: 32 x 6000 at most (the sanitizer build runs this too)
            wait_image(d)
            d.save_screenshot(os.path.join(shots, "explore_start.png"))
            first = zoom_and_back(d)
            zoom_in(d, first, shots)
            pick_1133(d, base, source, shots)
            export_and_run(d, btob, export_dir, tmp)
        finally:
            if d:
                d.quit()
            stop_server(proc)
    print(f"explore_browser: ok ({time.time() - t0:.1f} s)")


if __name__ == "__main__":
    main(*sys.argv[1:4])
