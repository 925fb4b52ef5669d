# SPDX-License-Identifier: GPL-3.0-or-later
"""Statistics of Table 6.1 against btob: how probable the paper's count of periodic orbits out of ten is when the
periodic fraction is btob's, itself estimated from n orbits, and how probable the whole table is.

Model.  At one r, btob classifies n orbits drawn from a candidate initial distribution and finds k periodic.  With
a uniform prior the fraction f has the posterior Beta(k + 1, n - k + 1).  The paper drew m = 10 orbits from its own
(unknown) distribution and saw K periodic: under the candidate, K | f ~ Binomial(m, f), so integrating over f,
K ~ BetaBinomial(m, k + 1, n - k + 1):

    P(K) = C(m, K) B(K + k + 1, m - K + n - k + 1) / B(k + 1, n - k + 1)        (B: Euler's beta function)

A row's two-sided p-value is min(1, 2 min(P(X <= K), P(X >= K))) (equal tails, X the beta-binomial count); the
table's log-likelihood is the sum over its rows of log P(K_r) (the rows are independent draws).  Nothing here
imports btob: tests/table_6_1_candidates_test.py checks these functions against direct numerical integration.
"""
import math

import numpy as np


def log_beta(a, b):
    """log B(a, b) = lgamma(a) + lgamma(b) - lgamma(a + b), for a, b > 0."""
    return math.lgamma(a) + math.lgamma(b) - math.lgamma(a + b)


def log_choose(m, j):
    return math.lgamma(m + 1) - math.lgamma(j + 1) - math.lgamma(m - j + 1)


def beta_binomial_pmf(m, k, n):
    """P(X = j), j = 0..m, of X ~ BetaBinomial(m, k + 1, n - k + 1): m draws with the fraction's posterior after k
    successes in n trials (uniform prior).  Returns a numpy array of length m + 1 summing to 1."""
    if not (isinstance(m, int) and m >= 1 and 0 <= k <= n):
        raise ValueError(f"beta_binomial_pmf: got m={m}, k={k}, n={n}, expected m >= 1 and 0 <= k <= n")
    a, b = k + 1, n - k + 1
    logp = [log_choose(m, j) + log_beta(j + a, m - j + b) - log_beta(a, b) for j in range(m + 1)]
    p = np.exp(np.array(logp))
    return p / p.sum()  # the closed form sums to 1 up to rounding (a few ulp); renormalised for the tails


def row_statistics(K, m, k, n):
    """One row of Table 6.1 under one candidate: the paper's count K of m against btob's k periodic of n.
    Returns expected count m (k+1)/(n+2), the central 95% predictive interval [lo, hi] of the count (smallest j with
    P(X <= j) >= 0.025, smallest with P(X <= j) >= 0.975), P(K), log P(K) and the two-sided p-value."""
    if not 0 <= K <= m:
        raise ValueError(f"row_statistics: got K={K}, expected 0 <= K <= m={m}")
    p = beta_binomial_pmf(m, k, n)
    cdf = np.cumsum(p)
    lower_tail = float(cdf[K])                    # P(X <= K)
    upper_tail = float(p[K:].sum())               # P(X >= K)
    return {
        "expected": m * (k + 1) / (n + 2),
        "lo": int(np.searchsorted(cdf, 0.025 - 1e-12)),  # 1e-12: cdf rounding must not push a bound one step up
        "hi": int(np.searchsorted(cdf, 0.975 - 1e-12)),
        "prob": float(p[K]),
        "log_prob": float(math.log(p[K])) if p[K] > 0 else -math.inf,
        "p_value": min(1.0, 2 * min(lower_tail, upper_tail)),
    }


def table_log_likelihood(rows):
    """Sum of log P(K_r) over rows given as (K, m, k, n)."""
    return sum(row_statistics(K, m, k, n)["log_prob"] for K, m, k, n in rows)


def table_goodness_of_fit(rows, draws, rng):
    """How typical the table's log-likelihood is under the candidate itself: `draws` synthetic tables drawn from
    each row's beta-binomial; returns (mean, sd of the synthetic log-likelihoods, share at or below the table's)."""
    pmfs = [beta_binomial_pmf(m, k, n) for _, m, k, n in rows]
    observed = sum(math.log(p[K]) for p, (K, _, _, _) in zip(pmfs, rows))
    total = np.zeros(draws)
    for p in pmfs:
        logp = np.log(np.maximum(p, 1e-300))
        total += logp[rng.choice(len(p), size=draws, p=p)]
    return float(total.mean()), float(total.std()), float(np.mean(total <= observed))


def block_p_value(rows):
    """Two-sided p-value of a block of rows (K, m, k, n) pooled: the total count sum K against the distribution of a
    sum of independent beta-binomials (the convolution of the rows' pmfs), min(1, 2 min(P(S <= s), P(S >= s)))."""
    pmf = np.ones(1)
    for _, m, k, n in rows:
        pmf = np.convolve(pmf, beta_binomial_pmf(m, k, n))
    s = sum(K for K, _, _, _ in rows)
    return min(1.0, 2 * min(float(pmf[:s + 1].sum()), float(pmf[s:].sum())))


def saturated_log_likelihood(counts, m=10):
    """The table's log-likelihood when each row's fraction is its own K/m (binomial): the best any candidate can
    reach, a scale for the candidates' values."""
    out = 0.0
    for K in counts:
        f = K / m
        out += log_choose(m, K) + (K * math.log(f) if K else 0.0) + ((m - K) * math.log(1 - f) if K < m else 0.0)
    return out


def distinct_pixels(w1, w2, h1, h2):
    """Number of distinct pixels of width h1 (w1) and height h2 (w2) that the points of each row of w1, w2
    (shape (orbits, tail)) fall in: what a plot of the tail at that resolution shows.  Returns an int array."""
    # w1 is unbounded (near u = +-e_y); beyond 1e6 every point is off any plot, so clipping merges nothing visible.
    i = np.floor(np.clip(np.asarray(w1), -1e6, 1e6) / h1).astype(np.int64)
    j = np.floor(np.asarray(w2) / h2).astype(np.int64)
    key = np.sort((i << 32) + (j & 0xFFFFFFFF), axis=1)  # unique while |i|, |j| < 2^31 (h1 >= 1e-3)
    return 1 + np.count_nonzero(np.diff(key, axis=1), axis=1)


def finite_at_resolution(w1, w2, h1, h2, blob=2.0, max_period=256, tries=4):
    """The paper's criterion, "the orbits seemed to accumulate on only a finite number of points", at the
    resolution of its plot: a row of w1, w2 (shape (orbits, tail)) passes when, for some p <= max_period, each of
    the p classes t mod p of its tail spans at most `blob` pixels (width h1 in w1, h2 in w2) in both coordinates,
    i.e. the plot shows p dots no larger than `blob` pixels.  Converging cycles pass once their remaining distance
    to the cycle is below a pixel; invariant curves and chaotic tails fail, however small the curve (a ring wider
    than `blob` pixels is a ring on the plot), and so do cycles whose approach is still visible as streaks.
    Candidate periods are the first `tries` p at which the last point returns within `blob` pixels."""
    a = np.clip(np.asarray(w1), -1e6, 1e6) / h1
    b = np.asarray(w2) / h2
    n, T = a.shape
    P = min(max_period, T - 1)
    # dist[:, p - 1]: the last point against the point p steps earlier, in pixels (max norm)
    dist = np.maximum(np.abs(a[:, -1:] - a[:, -2:-P - 2:-1]), np.abs(b[:, -1:] - b[:, -2:-P - 2:-1]))
    out = np.zeros(n, dtype=bool)
    for o in np.nonzero((dist <= blob).any(axis=1))[0]:
        for p in (np.nonzero(dist[o] <= blob)[0] + 1)[:tries]:
            m = (T // p) * p
            if max(np.ptp(a[o, T - m:].reshape(-1, p), axis=0).max(),
                   np.ptp(b[o, T - m:].reshape(-1, p), axis=0).max()) <= blob:
                out[o] = True
                break
    return out
