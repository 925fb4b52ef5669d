#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""analyses/table_6_1_stats.py (the statistics of analyses/table_6_1_candidates.py) against independent routes:
the beta-binomial probability against Gauss-Legendre integration of binomial x beta density (exact for the
polynomial integrand of a small case), its binomial limit, the p-value and expected count against enumeration, the
log-likelihood of a synthetic table whose best candidate is known, the pixel count on tails whose answer is known,
and the candidates' samplers against the strip coordinates of eq. (6.4).  Usage: table_6_1_candidates_test.py ROOT
"""
import math
import os
import sys

import numpy as np

root = sys.argv[1]
sys.path.insert(0, os.path.join(root, "analyses"))
import table_6_1_stats as st  # noqa: E402
import table_6_1_candidates as tc  # noqa: E402  (numpy only at import: btob is imported by main())

failures = 0


def check(ok, msg):
    global failures
    if not ok:
        failures += 1
        print("FAIL:", msg)


def integrated_pmf(m, k, n, panels=1, nodes=40):
    """P(X = j) = int C(m,j) f^j (1-f)^(m-j) f^k (1-f)^(n-k) df / int f^k (1-f)^(n-k) df, composite Gauss-Legendre
    (no gamma function).  Log-space weights keep the large-n integrand finite."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    f = np.concatenate([(p + (x + 1) / 2) / panels for p in range(panels)])
    wt = np.tile(w / (2 * panels), panels)
    log_post = k * np.log(f) + (n - k) * np.log1p(-f)
    post = wt * np.exp(log_post - log_post.max())
    out = np.array([math.comb(m, j) * np.sum(post * f**j * (1 - f) ** (m - j)) for j in range(m + 1)])
    return out / post.sum()


# 1. Small case: the integrand has degree m + n = 50, so 40 Gauss-Legendre nodes (exact to degree 79) give the
#    integral up to rounding; relative 1e-12 allows ~100 ulp of accumulated sums.
for k in (0, 7, 20, 40):
    a, b = st.beta_binomial_pmf(10, k, 40), integrated_pmf(10, k, 40)
    check(np.allclose(a, b, rtol=1e-12, atol=1e-300), f"beta-binomial m=10 k={k} n=40: {a} vs {b}")
# 2. Large case (n = 4000, the script's default): 400 panels x 40 nodes resolve the posterior's width (sd 0.008, a
#    panel is 0.0025); agreement to 1e-9 relative on every count with P > 1e-12.
for k in (1, 1000, 2044, 3999):
    a, b = st.beta_binomial_pmf(10, k, 4000), integrated_pmf(10, k, 4000, panels=400)
    sel = b > 1e-12
    check(np.allclose(a[sel], b[sel], rtol=1e-9), f"beta-binomial m=10 k={k} n=4000: {a} vs {b}")
# 3. Binomial limit: n = 1e7 posterior sd 1.6e-4, so the pmf is binomial(10, k/n) within ~1e-6 absolute.
k, n = 3_000_000, 10_000_000
binom = np.array([math.comb(10, j) * 0.3**j * 0.7 ** (10 - j) for j in range(11)])
check(np.allclose(st.beta_binomial_pmf(10, k, n), binom, atol=5e-6), "binomial limit at n = 1e7")
# 4. Row statistics against enumeration: expected count sum j P(j), the tails, the 95% predictive interval.
p = st.beta_binomial_pmf(10, 500, 2000)
s = st.row_statistics(1, 10, 500, 2000)
check(abs(s["expected"] - float(np.dot(np.arange(11), p))) < 1e-12, f"expected count {s['expected']}")
check(abs(s["p_value"] - min(1, 2 * min(p[:2].sum(), p[1:].sum()))) < 1e-15, f"p-value {s['p_value']}")
check(abs(s["prob"] - p[1]) < 1e-15 and s["lo"] == 0 and s["hi"] == 5,
      f"P(K=1) {s['prob']} vs {p[1]}; interval [{s['lo']}, {s['hi']}] (f = 0.25: 2.5% / 97.5% quantiles 0 and 5)")
check(st.row_statistics(10, 10, 2000, 2000)["p_value"] == 1.0, "K = 10 with f near 1 is not inconsistent")
check(st.row_statistics(0, 10, 2000, 2000)["p_value"] < 1e-20, "K = 0 with f near 1 is inconsistent")
# 5. A synthetic table whose best candidate is known: 33 rows of K = 5 drawn against constant fractions 0.2, 0.5
#    and 0.8 (n = 10^6 orbits each): the middle one is best, and each value equals the sum of binomial log-pmfs.
rows = {f: [(5, 10, int(f * 10**6), 10**6)] * 33 for f in (0.2, 0.5, 0.8)}
ll = {f: st.table_log_likelihood(v) for f, v in rows.items()}
check(max(ll, key=ll.get) == 0.5, f"best candidate {ll}")
for f, v in ll.items():
    direct = 33 * math.log(math.comb(10, 5) * f**5 * (1 - f) ** 5)
    check(abs(v - direct) < 0.01, f"log-likelihood at f={f}: {v} vs binomial {direct}")  # n=1e6: O(1/n) per row
check(st.saturated_log_likelihood([5] * 33) >= max(ll.values()), "saturated bound")
# 5b. A pooled block of 9 rows with the same (near-exact) fraction 0.35 is Binomial(90, 0.35): the p-value of a
#     total of 19 against the binomial tails summed directly (n = 1e7: the fraction's spread adds ~1e-4 relative).
b90 = np.array([math.comb(90, j) * 0.35**j * 0.65 ** (90 - j) for j in range(91)])
want = min(1, 2 * min(b90[:20].sum(), b90[19:].sum()))
got = st.block_p_value([(1, 10, 3_500_000, 10**7)] * 4 + [(3, 10, 3_500_000, 10**7)] * 5)  # 4 x 1 + 5 x 3 = 19
check(abs(got - want) < 1e-3 * want, f"block p-value {got} vs binomial {want}")
# 6. Goodness of fit: the synthetic mean against the exact expectation sum_r sum_j P(j) log P(j), within 5 sd/sqrt(N).
mean, sd, share = st.table_goodness_of_fit(rows[0.5], 20000, np.random.default_rng(7))
exact = 33 * sum(q * math.log(q) for q in st.beta_binomial_pmf(10, 500000, 10**6))
check(abs(mean - exact) < 5 * sd / math.sqrt(20000), f"synthetic mean {mean} vs exact {exact}")
check(share > 0.5, f"a table at the mode is typical: share {share}")
# 7. Pixels: a 6-cycle repeated over 2000 steps is 6 pixels; 2000 points along w1 in [0, 1) at pixel 0.01 are 100;
#    points on either side of 0 are two pixels.
cyc = np.tile(np.array([0.1, 0.5, -0.7, 1.2, -1.9, 0.33]), 334)[:2000]
check(st.distinct_pixels(cyc[None, :], np.zeros((1, 2000)), 0.01, 0.01)[0] == 6, "6-cycle")
line = (np.arange(2000) + 0.5) / 2000
check(st.distinct_pixels(line[None, :], np.zeros((1, 2000)), 0.01, 0.01)[0] == 100, "segment")
check(st.distinct_pixels(np.array([[-0.001, 0.001]]), np.zeros((1, 2)), 0.01, 0.01)[0] == 2, "sign of w1")
# 7b. The paper's rule at pixel 0.01 and blobs of 2 pixels: a 6-cycle is finite; the same cycle approached as
#     0.5 * 0.999^t (0.07 = 7 pixels of streak over the last 2000 steps) is not; an irrational rotation on a ring of
#     radius 5 pixels is a ring (not finite), on a ring of 0.1 pixel a dot (finite); a rational rotation 1/7 is 7 dots.
t = np.arange(2000)
cyc2 = np.tile(np.array([0.2, -0.5, 0.7, 0.9, -0.1, 0.3]), 334)[:2000]
g = 2 * np.pi * (math.sqrt(5) - 1) / 2 * t
w1s = np.array([cyc, cyc + 0.5 * 0.999**t, 0.05 * np.cos(g), 0.001 * np.cos(g), 0.5 * np.cos(2 * np.pi * t / 7)])
w2s = np.array([cyc2, cyc2, 0.05 * np.sin(g), 0.001 * np.sin(g), 0.5 * np.sin(2 * np.pi * t / 7)])
got = st.finite_at_resolution(w1s, w2s, 0.01, 0.01, blob=2.0, max_period=256).tolist()
check(got == [True, False, False, True, True], f"finite_at_resolution {got}")
# 8. Samplers: strip2 lies in |w1| <= 2, |w2| <= 1 (w = (y, x + z) / (x - z), eq. (6.4)); the sphere's heights y are
#    uniform on [-1, 1] (mean 0, variance 1/3 within 5 standard errors).
names = [c[0] for c in tc.CANDIDATES]
u = tc.draw_points(names.index("strip2"), 5000, 1)
w1, w2 = u[:, 1] / (u[:, 0] - u[:, 2]), (u[:, 0] + u[:, 2]) / (u[:, 0] - u[:, 2])
check(np.all(np.abs(w1) <= 2) and np.all(np.abs(w2) <= 1) and w1.max() > 1.99, "strip2 sampler range")
y = tc.draw_points(names.index("sphere"), 20000, 1)[:, 1]
check(abs(y.mean()) < 5 * math.sqrt(1 / 3 / 20000) and abs(y.var() - 1 / 3) < 5 * math.sqrt(4 / 45 / 20000),
      f"sphere heights mean {y.mean()} var {y.var()}")
check(np.array_equal(tc.draw_points(0, 100, 3), tc.draw_points(0, 100, 3)), "same seed, same points")
print("table_6_1_candidates_test:", "FAILED" if failures else "ok")
sys.exit(1 if failures else 0)
