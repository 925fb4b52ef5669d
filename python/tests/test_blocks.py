# SPDX-License-Identifier: GPL-3.0-or-later
"""The building blocks: btob.Map(r).step against the paper's matrices, btob.iterate against the bifurcation
kernel's raw tails (which test_requests.py ties to the command line bitwise) and against Map.step."""
import numpy as np
import pytest

import btob

EPS = np.finfo(float).eps
POINTS = np.array([[1.0, -0.5, -1.1], [1.0, 0.8, -1.0], [0.3, 0.2, -2.0], [2.0, -1.0, -0.25]])


def to_quadrant(u):
    return -u if (u[0] < 0 or (u[0] == 0 and u[2] > 0)) else u


def test_step_is_the_matrix_of_its_branch():
    for r in (0.11, 0.2, 0.45):
        m = btob.Map(r)
        P = {i: m.matrix(i) for i in (1, 2, 3)}
        # P3 = J P1 J (eq. 4.4): an independent check of the matrices themselves.
        J = np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0]], float)
        assert np.array_equal(P[3], J @ P[1] @ J)
        out, sym = m.step(POINTS)
        assert out.shape == (4, 3) and sym.dtype == np.uint8
        a = (1 + r) / 2
        for u, v, s in zip(POINTS, out, sym):
            q = to_quadrant(u)
            want = 1 if a * q[1] - q[0] > 0 else 3 if a * q[1] - q[2] < 0 else 2  # the branch rule of Theorem 3.3
            assert s == want
            # The kernel's step M_s u = P_s u / r: 3 products and 2 sums per entry, then / r: a few ulps of the
            # largest term.
            assert np.allclose(v, P[s] @ q / r, rtol=0, atol=8 * EPS * np.abs(P[s]).max() / r * np.abs(q).max())


def test_iterate_tail_equals_the_bifurcation_kernel_bitwise():
    grid = ";".join(",".join(repr(x) for x in p) for p in POINTS)
    res = btob.bifurcation(r_min=0.1, r_max=0.3, r_count=7, iterations=300, tail=25, grid=grid, raw=True)
    tails = btob.iterate(res.r, POINTS, iterations=300, record="tail", coord="theta", tail=25)
    assert tails.shape == (7, 4, 25) and tails.dtype == np.float64
    assert tails.tobytes() == res.tail.reshape(7, 4, 25).tobytes()


def test_iterate_symbols_follow_map_step():
    for r in (0.11, 0.2, 0.3):
        sym = btob.iterate(r, POINTS, iterations=25, record="symbols", tail=25)
        assert sym.shape == (4, 25)
        m = btob.Map(r)
        u = POINTS.copy()
        for k in range(25):
            u, s = m.step(u)
            u = u / np.abs(u).max(axis=1, keepdims=True)
            assert np.array_equal(s, sym[:, k]), (r, k)


def test_iterate_final_is_the_normalised_state():
    final = btob.iterate([0.2], POINTS, iterations=40, record="final")
    assert final.shape == (1, 4, 3)
    m = btob.Map(0.2)
    u = POINTS.copy()
    for _ in range(40):
        u, _s = m.step(u)
        u = u / np.linalg.norm(u, axis=1, keepdims=True)
    # 40 steps of a contracting or mildly expanding map: rounding stays below 1e-12.
    assert np.allclose(final[0], u, rtol=0, atol=1e-12)


def test_iterate_orbit_records_states_and_branches_per_step():
    orbit = btob.iterate(0.2, POINTS, iterations=30, record="orbit", tail=30)
    assert {k: v.shape for k, v in orbit.items()} == {k: (4, 30) for k in ("x", "y", "z", "branch", "theta", "phi")}
    m = btob.Map(0.2)
    u = POINTS.copy()
    for k in range(30):
        u, s = m.step(u)
        u = u / np.linalg.norm(u, axis=1, keepdims=True)
        assert np.array_equal(s, orbit["branch"][:, k]), k
        got = np.stack([orbit["x"][:, k], orbit["y"][:, k], orbit["z"][:, k]], axis=1)
        # 30 steps of rounding in the kernel and in this loop, then the angles' sin/cos: far below 1e-12.
        assert np.allclose(got, u, rtol=0, atol=1e-12), k


@pytest.mark.parametrize("precision", ["double", "float"])
def test_iterate_orbit_is_the_separate_records_from_one_kernel_run(precision):
    kw = dict(iterations=50, tail=20, precision=precision, threads=2)
    ends = []
    orbit = btob.iterate([0.2, 0.35], POINTS, record="orbit",
                         progress=lambda done, total: ends.append(done) if done == total else None, **kw)
    # One run of the kernel: its progress reaches its total once (three runs reached it three times).
    assert len(ends) == 1
    # Bit for bit the arrays of the separate records, which each run the kernel on their own.
    assert np.array_equal(orbit["theta"], btob.iterate([0.2, 0.35], POINTS, record="tail", coord="theta", **kw))
    assert np.array_equal(orbit["phi"], btob.iterate([0.2, 0.35], POINTS, record="tail", coord="phi", **kw))
    assert np.array_equal(orbit["branch"], btob.iterate([0.2, 0.35], POINTS, record="symbols", **kw))
    final = btob.iterate([0.2, 0.35], POINTS, record="final", **kw)
    assert np.array_equal(np.stack([orbit[k][..., -1] for k in "xyz"], axis=-1), final)
    assert orbit["branch"].dtype == np.uint8 and orbit["x"].dtype == np.float64


def test_iterate_float_and_long_double():
    d = btob.iterate(0.2, POINTS, iterations=30, record="symbols", tail=30)
    for p in ("float", "long-double"):
        s = btob.iterate(0.2, POINTS, iterations=30, record="symbols", tail=30, precision=p)
        assert (s[:, :10] == d[:, :10]).all()  # the first steps agree in any precision


def test_iterate_owns_its_arrays():
    a = btob.iterate(0.2, POINTS, iterations=10, record="tail", tail=5)
    assert a.base is not None and not a.flags.owndata  # a capsule owns the kernel's buffer: no copy


@pytest.mark.parametrize("call,message", [
    (lambda: btob.Map(1.5), "^r: got 1.5, expected a value in the open interval"),
    (lambda: btob.Map(0.2).step([1.0, 2.0]), "^points: got"),
    (lambda: btob.Map(0.2).step([1.0, 0.5, 1.0]), "x\\*z > 0"),
    (lambda: btob.iterate(0.2, POINTS, 10, record="nope"), "^record: got 'nope', expected tail, symbols, final or orbit"),
    (lambda: btob.iterate(0.2, POINTS, 10, tail=11), "^tail: got 11, expected 1..iterations = 10"),
    (lambda: btob.iterate(0, POINTS, 10), "^r: got 0"),
    (lambda: btob.iterate(0.2, POINTS, 10, precision="quad"), "^precision: got 'quad'"),
    (lambda: btob.iterate(0.2, POINTS, 10, coord="rho"), "coord"),
])
def test_block_errors(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_map_step_and_iterate_take_one_branch_on_the_branch_lines():
    # Points next to and on the lines alpha y = x and alpha y = z (alpha = (1 + r) / 2 exact for r = k / 256):
    # the rounded product alpha y and its two neighbours as x (or z).  The rule's signs are exact, so Map.step,
    # one step of iterate and the exact rational sign agree, and a point times 2^k takes the same branch.
    from fractions import Fraction
    rng = np.random.default_rng(5)
    for k in (19, 44, 64, 100, 200):
        r = k / 256
        a = (1 + r) / 2
        pts = []
        for y in rng.uniform(0.05, 1, 20):
            for d in (-np.inf, 0, np.inf):
                x = a * y if d == 0 else np.nextafter(a * y, d)
                pts.append([x, y, -0.7])
                z = -a * y if d == 0 else np.nextafter(-a * y, d)
                pts.append([0.3, -y, z])
        pts = np.array(pts)
        want = []
        for x, y, z in pts:
            fa, fy = Fraction(a), Fraction(y)
            want.append(1 if fa * fy - Fraction(x) > 0 else (3 if fa * fy - Fraction(z) < 0 else 2))
        u, s = btob.Map(r).step(pts)
        assert list(s) == want, r
        sym = btob.iterate(r, pts, iterations=1, record="symbols", tail=1)
        assert list(sym[:, 0]) == want, r
        for e in (-1000, -3, 7, 900):
            u2, s2 = btob.Map(r).step(np.ldexp(pts, e))
            assert list(s2) == want, (r, e)
            if e > -1000:  # no subnormal on the way: the image scales by 2^e exactly (the kernel's step, fused)
                assert np.array_equal(u2, np.ldexp(u, e)), (r, e)
