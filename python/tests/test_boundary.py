# SPDX-License-Identifier: GPL-3.0-or-later
"""The boundary geometry of btob.basins and btob.basins_r (src/attractors/boundary.hpp) against a second route: the
basin entropies, the boundary-box count and the uncertain fractions counted again here with numpy from the labels
image the result carries, and basins_r's per-r values equal to a basins run on its boundary grid."""
import numpy as np
import pytest

import btob

OPTS = dict(transient=500, iterations=300, lyap_iterations=400, lyap_transient=50)


def entropies(labels, box):
    """S_b, S_bb and the boundary boxes on whole boxes of box x box cells from the corner, natural log."""
    n2, n1 = labels.shape
    m2, m1 = n2 // box, n1 // box
    blocks = labels[:m2 * box, :m1 * box].reshape(m2, box, m1, box).swapaxes(1, 2).reshape(m2 * m1, box * box)
    s = []
    for b in blocks:
        _, counts = np.unique(b, return_counts=True)
        p = counts / counts.sum()
        s.append(float(-(p * np.log(p)).sum()) if len(p) > 1 else 0.0)
    s = np.array(s)
    boundary = s > 0
    return s.mean(), (s[boundary].mean() if boundary.any() else 0.0), int(boundary.sum()), s.reshape(m2, m1)


def uncertain(labels, eps, margin):
    """The share of the cells at least `margin` from the edges with a label differing eps cells away along an axis."""
    n2, n1 = labels.shape
    c = labels[margin:n2 - margin, margin:n1 - margin]
    differs = np.zeros_like(c, dtype=bool)
    for dj, di in ((0, eps), (0, -eps), (eps, 0), (-eps, 0)):
        differs |= labels[margin + dj:n2 - margin + dj, margin + di:n1 - margin + di] != c
    return differs.mean()


@pytest.fixture(scope="module")
def res():
    # r = 0.25: several periodic sinks beside the P2 curves (Section 8).
    return btob.basins(r=0.25, grid="sphere:96x88", replicates=1, entropy_box=4, **OPTS)


def test_entropies_equal_a_numpy_count(res):
    labels = np.asarray(res.labels)
    sb, sbb, boundary, per_box = entropies(labels, 4)
    assert res.attrs["entropy_box"] == 4
    assert res.attrs["entropy_boxes"] == per_box.size == 24 * 22
    assert np.allclose(np.asarray(res.box_entropy), per_box, rtol=1e-13, atol=0)
    assert res.attrs["boundary_boxes"] == boundary
    # Sums of at most 528 terms in another order: a few hundred ulps at most.
    assert res.attrs["basin_entropy"] == pytest.approx(sb, rel=1e-12, abs=1e-15)
    assert res.attrs["boundary_basin_entropy"] == pytest.approx(sbb, rel=1e-12, abs=1e-15)
    assert res.attrs["basin_entropy_low"] <= res.attrs["basin_entropy_replicate_mean"] <= res.attrs["basin_entropy_high"]


def test_uncertain_fractions_equal_a_numpy_count(res):
    labels = np.asarray(res.labels)
    eps = np.asarray(res.uncertainty_eps).astype(int)
    assert eps[0] == 1 and eps[-1] == 88 // 8
    f = np.asarray(res.uncertainty_fraction)
    for e, got in zip(eps, f):
        assert got == pytest.approx(uncertain(labels, int(e), int(eps[-1])), rel=1e-12)
    # The fit: the least-squares slope of log f on log eps over the points with 0 < f <= 1/2, again with numpy; it is
    # made only over three such points spanning a decade, and otherwise the file says why (no exponent, no NaN).
    ok = (f > 0) & (f <= 0.5)
    if ok.sum() < 3 or eps[ok].max() < 10 * eps[ok].min():
        assert not res.attrs["uncertainty_fitted"]
        assert "uncertainty_exponent" not in res.attrs and res.attrs["uncertainty_note"]
        return
    assert res.attrs["uncertainty_fitted"]
    slope = np.polyfit(np.log(eps[ok]), np.log(f[ok]), 1)[0]
    assert res.attrs["uncertainty_exponent"] == pytest.approx(slope, rel=1e-9)
    assert res.attrs["uncertainty_exponent_low"] <= slope <= res.attrs["uncertainty_exponent_high"]
    assert res.attrs["boundary_dimension"] == pytest.approx(2 - slope, rel=1e-9)
    assert "Wada" in res.attrs["wada_verdict"] or "not applicable" in res.attrs["wada_verdict"]


def test_basins_r_boundary_equals_a_basins_run():
    rr = btob.basins_r(r_values=[0.25], grid="random:8", boundary_grid="sphere:96x88", boundary_replicates=1,
                       entropy_box=4, **OPTS)
    one = btob.basins(r=0.25, grid="sphere:96x88", replicates=1, entropy_box=4, **OPTS)
    assert np.asarray(rr.basin_entropy)[0] == one.attrs["basin_entropy"]
    assert np.asarray(rr.boundary_basin_entropy_high)[0] == one.attrs["boundary_basin_entropy_high"]
    if one.attrs["uncertainty_fitted"]:  # a grid this small may span less than the decade a fit needs
        assert np.asarray(rr.uncertainty_exponent)[0] == one.attrs["uncertainty_exponent"]


def test_bad_entropy_box_is_refused():
    with pytest.raises(ValueError, match="entropy-box"):
        btob.basins(r=0.25, grid="sphere:8x8", entropy_box=0, **OPTS)
