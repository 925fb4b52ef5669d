#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Latency of `btob explore`: request to PNG for a 1200 x 700 view at the page's first (default) level of work, against
the plain kernel's rate measured in the same run.

Usage: explore_latency.py BTOB BM_ITERATE OUT_DIR [--requests N] [--threads T]

Runs the plain batched kernel (bm_iterate's batched/double, T threads) before, halfway and after, starts
`btob explore --no-browser --port 0`, sends N requests for views of 1200 x 700 pixels (32 orbits x 2000 iterations,
last 100 binned) over r windows of several widths, one at a time, and times each from the request to the last byte of
the PNG.  The server's Server-Timing header splits its part into compute (of which iterate: the kernel with its density
recorder; the remainder is the request's setup and the merge of the per-thread images), colour and PNG; the rest
(HTTP, transfer, the client) is the difference.  Writes OUT_DIR/latency.csv (one row per request) and
OUT_DIR/latency.json (medians, 95th percentiles, the kernel's rate and what it predicts), and prints a summary.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from explore_common import start_server, stop_server  # noqa: E402

WIDTH, HEIGHT, ORBITS, ITERATIONS, TAIL = 1200, 700, 32, 2000, 100
# r windows of the page's typical zooms: the whole default window down to a 1e-6-wide one near 7 - 4 sqrt(3)
WINDOWS = [(0.0717, 0.1717), (0.0717, 0.0727), (0.12, 0.18), (0.0718, 0.07181), (0.2, 0.6), (0.0717, 0.0817),
           (0.09, 0.1), (0.07180, 0.071801)]


def kernel_rate(bm, threads):
    """Map iterations per second of the plain batched kernel (double, `threads` threads), median of 3."""
    out = subprocess.run([bm, f"--benchmark_filter=^batched/double/1000/5000/{threads}/", "--benchmark_repetitions=3",
                          "--benchmark_format=json", "--benchmark_min_time=0.3"],
                         check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type") == "iteration"]
    return statistics.median(b["items_per_second"] for b in runs)


def one_request(base, r_min, r_max):
    url = (f"{base}/api/bifurcation?r_min={r_min}&r_max={r_max}&coord=theta&lo=0&hi=1.5707963267948966"
           f"&width={WIDTH}&height={HEIGHT}&iterations={ITERATIONS}&tail={TAIL}")
    t0 = time.perf_counter()
    with urllib.request.urlopen(url, timeout=60) as r:
        body = r.read()
        timing = r.headers["Server-Timing"]
    total = (time.perf_counter() - t0) * 1e3
    parts = {k: float(v) for k, v in re.findall(r"(\w+);dur=([0-9.]+)", timing)}
    server = parts["compute"] + parts["colour"] + parts["png"]  # iterate is a part of compute
    return dict(total_ms=total, compute_ms=parts["compute"], iterate_ms=parts["iterate"], colour_ms=parts["colour"],
                png_ms=parts["png"], rest_ms=total - server, png_bytes=len(body))


def pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(round(q * (len(xs) - 1))))]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("btob")
    ap.add_argument("bm_iterate")
    ap.add_argument("out")
    ap.add_argument("--requests", type=int, default=40)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rates = [kernel_rate(a.bm_iterate, a.threads)]
    proc, base = start_server(a.btob, os.path.join(a.out, "exports-unused"), threads=a.threads)  # never written
    rows = []
    try:
        for i in range(3):  # warm-up: OpenMP's threads, the allocator
            one_request(base, *WINDOWS[i])
        for i in range(a.requests):
            if i == a.requests // 2:  # the kernel between the two halves too: the machine's load drifts
                rates.append(kernel_rate(a.bm_iterate, a.threads))
            rows.append(dict(window=i % len(WINDOWS), **one_request(base, *WINDOWS[i % len(WINDOWS)])))
    finally:
        stop_server(proc)
    rates.append(kernel_rate(a.bm_iterate, a.threads))
    rate = statistics.median(rates)
    keys = ["total_ms", "compute_ms", "iterate_ms", "colour_ms", "png_ms", "rest_ms", "png_bytes"]
    with open(os.path.join(a.out, "latency.csv"), "w") as f:
        f.write("request,r_min,r_max," + ",".join(keys) + "\n")
        for i, r in enumerate(rows):
            lo, hi = WINDOWS[r["window"]]
            f.write(f"{i},{lo},{hi}," + ",".join(f"{r[k]:.3f}" for k in keys) + "\n")
    work = WIDTH * ORBITS * ITERATIONS
    summary = dict(width=WIDTH, height=HEIGHT, orbits=ORBITS, iterations=ITERATIONS, tail=TAIL, threads=a.threads,
                   requests=len(rows), map_iterations=work,
                   kernel_rates=rates, kernel_rate=rate,
                   kernel_ms_predicted=work / rate * 1e3,
                   **{f"median_{k}": statistics.median(r[k] for r in rows) for k in keys},
                   **{f"p95_{k}": pct([r[k] for r in rows], 0.95) for k in keys})
    summary["compute_over_kernel"] = summary["median_compute_ms"] / summary["kernel_ms_predicted"]
    summary["iterate_over_kernel"] = summary["median_iterate_ms"] / summary["kernel_ms_predicted"]
    with open(os.path.join(a.out, "latency.json"), "w") as f:
        json.dump(summary, f, indent=1)
    # The run's provenance (btob_manifest sits next to btob, built from the same tree).
    subprocess.run([os.path.join(os.path.dirname(os.path.abspath(a.btob)), "btob_manifest"),
                    os.path.join(a.out, "manifest.json"), "analyses/explore_latency.py " + " ".join(sys.argv[1:]),
                    "latency.csv", "latency.json"], check=True)
    print(f"plain kernel ({a.threads} threads): {', '.join(f'{x:.3g}' for x in rates)} map iterations/s (before, "
          f"between the halves, after); "
          f"{work:.3g} map iterations -> {summary['kernel_ms_predicted']:.1f} ms")
    for k in keys[:-1]:
        print(f"{k:12s} median {summary['median_' + k]:7.1f}  p95 {summary['p95_' + k]:7.1f}")
    print(f"PNG {summary['median_png_bytes'] / 1e3:.0f} kB (median); compute / plain kernel = "
          f"{summary['compute_over_kernel']:.2f}, iterate / plain kernel = {summary['iterate_over_kernel']:.2f}")


if __name__ == "__main__":
    main()
