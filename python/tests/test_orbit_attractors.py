# SPDX-License-Identifier: GPL-3.0-or-later
"""Per-orbit attractors: `lyapunov_map(attractors=True)` and `bifurcation(attractors=True)` record each orbit's
attractor, which is `btob.classify`'s verdict on that orbit (same point, r, transient and iterations), and leave the
run they are added to unchanged."""
import numpy as np

import btob

# Points whose orbits over r in [0.048, 0.448] reach every kind of attractor: collapses (r = 0.048), chaos (0.088),
# sinks, the P2 fixed point (the last point), P2 invariant curves.
POINTS = [(1.0, -0.5, -1.1), (0.3, 0.2, -1.0), (1.0, 0.9, -0.2), (0.05, -0.3, -1.0), (0.7, 0.0, -0.7)]
GRID = ";".join(",".join(repr(c) for c in p) for p in POINTS)


def classify_each(res, transient, iterations, max_period):
    """classify's (pattern or 'undecided', type, period) of every orbit of the result, in its [r, point] order."""
    out = []
    for r in res.r:
        row = []
        for p in POINTS:
            v = btob.classify(r=float(r), point=p, transient=transient, iterations=iterations, max_period=max_period)
            row.append((v.attrs["pattern"] or "undecided", v.attrs["type"], int(v.attrs["period"])))
        out.append(row)
    return out


def recorded(res):
    names, types, periods = list(res.attractor_name), list(res.attractor_type), res.attractor_period
    return [[(names[a], types[a], int(periods[a])) for a in row] for row in res.attractor]


def test_lyapunov_map_attractor_is_classify_of_the_orbit():
    kw = dict(r_min=0.048, r_max=0.448, r_count=11, grid=GRID, transient=600, iterations=1500, threads=2)
    res = btob.lyapunov_map(attractors=True, **kw)
    want = classify_each(res, 600, 1500, 256)
    assert recorded(res) == want
    kinds = {t for row in want for _n, t, _p in row}
    assert kinds >= {"collapse", "chaotic", "periodic", "quasi-periodic"}, kinds  # the comparison is not vacuous
    # Counts per r per attractor are those of the labels; the exponents are the run without attractors, bit for bit.
    for i, row in enumerate(res.attractor):
        assert np.array_equal(res.attractor_count[i], np.bincount(row, minlength=len(res.attractor_name)))
    plain = btob.lyapunov_map(**kw)
    assert np.array_equal(plain.lambda1, res.lambda1) and np.array_equal(plain.err1, res.err1)
    assert not hasattr(plain, "attractor")  # the default run records no attractors


def test_bifurcation_attractor_is_classify_over_the_tail():
    kw = dict(r_min=0.1, r_max=0.45, r_count=4, grid=GRID, iterations=800, tail=120, bins=50, threads=2)
    res = btob.bifurcation(attractors=True, **kw)
    # classify with transient iterations - tail and iterations tail (max-period at most the window).
    assert recorded(res) == classify_each(res, 680, 120, 120)
    assert res.attrs["attractor_transient"] == 680 and res.attrs["attractor_iterations"] == 120
    assert np.array_equal(btob.bifurcation(**kw).density, res.density)
