#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""btob beside pynamicalsys, measured side by side on the b-to-b map P_r: iterates, exponents, periodic orbits and
speed (docs/comparison.md quotes this script's output).

pynamicalsys is a general toolkit: you give it a map and its Jacobian (Numba-compiled).  P_r is written here for it
in the chart x - z = 1 of the quadrant Q = {x >= 0, z <= 0} (coordinates (x, y), z = x - 1): F(x, y) = (x', y') /
(x' - z') with (x', y', z') = P_s (x, y, x - 1) and s the branch of Theorem 3.3 (1 if a y - x > 0, 3 if a y - z < 0,
else 2; a = (1 + r) / 2).  The projective exponents do not depend on the chart, so pynamicalsys's two exponents of F
are btob's lambda1 and lambda2.

Runs only where both are importable (outside CI): pynamicalsys 1.2.2's source on Debian's python3-numba (its
__version__ module, written at install time, is supplied here), btob from the build:
  PYTHONPATH=/path/to/pynamicalsys/src:build/release/python python3 benchmarks/peers/pynamicalsys_peer.py
"""
import math
import sys
import time
import types

import numpy as np

try:
    sys.modules.setdefault("pynamicalsys.__version__", types.ModuleType("pynamicalsys.__version__"))
    sys.modules["pynamicalsys.__version__"].__version__ = "1.2.2"
    from numba import njit
    from pynamicalsys import DiscreteDynamicalSystem
    import btob
except ImportError as e:  # not an error: the peer is not installed here
    print(f"pynamicalsys_peer: skipped ({e})")
    sys.exit(0)


@njit
def matrix(s, r):
    """P_s of Theorem 3.3 (eqs. (3.5)-(3.6)), for the period matrix below."""
    a = (1 + r) / 2
    if s == 1:
        return np.array([[-r, r * a, 0.0], [-a, a * a - r, r * a], [0.0, 0.0, r * r]])
    if s == 3:
        return np.array([[r * r, 0.0, 0.0], [r * a, a * a - r, -a], [0.0, r * a, -r]])
    return np.array([[r, -r * a, 0.0], [a, -2 * a * a + r, a], [0.0, -r * a, r]])


@njit
def branch(x, y, z, r):
    a = (1 + r) / 2
    if a * y - x > 0:
        return 1
    if a * y - z < 0:
        return 3
    return 2


@njit
def rows(x, y, r):
    """(x', y', z') = P_s u at u = (x, y, x - 1) and the columns d/dx, d/dy of (x', y', z'), without an array: the
    map is called once a step and Numba's small arrays cost more than the arithmetic."""
    a = (1 + r) / 2
    z = x - 1
    s = branch(x, y, z, r)
    if s == 1:  # rows of P1: (-r, r a, 0), (-a, a^2 - r, r a), (0, 0, r^2)
        p = (-r, r * a, 0.0, -a, a * a - r, r * a, 0.0, 0.0, r * r)
    elif s == 3:  # P3: (r^2, 0, 0), (r a, a^2 - r, -a), (0, r a, -r)
        p = (r * r, 0.0, 0.0, r * a, a * a - r, -a, 0.0, r * a, -r)
    else:  # P2: (r, -r a, 0), (a, -2 a^2 + r, a), (0, -r a, r)
        p = (r, -r * a, 0.0, a, -2 * a * a + r, a, 0.0, -r * a, r)
    xn = p[0] * x + p[1] * y + p[2] * z
    yn = p[3] * x + p[4] * y + p[5] * z
    zn = p[6] * x + p[7] * y + p[8] * z
    return xn, yn, zn, p[0] + p[2], p[1], p[3] + p[5], p[4], p[6] + p[8], p[7]


@njit
def p_r(q, parameters):
    xn, yn, zn, _, _, _, _, _, _ = rows(q[0], q[1], parameters[0])
    d = xn - zn
    out = np.empty(2)
    out[0] = xn / d
    out[1] = yn / d
    return out


@njit
def p_r_jacobian(q, parameters, *args):
    xn, yn, zn, xx, xy, yx, yy, zx, zy = rows(q[0], q[1], parameters[0])
    d = xn - zn
    d2 = d * d
    J = np.empty((2, 2))
    J[0, 0] = (xx * d - xn * (xx - zx)) / d2
    J[0, 1] = (xy * d - xn * (xy - zy)) / d2
    J[1, 0] = (yx * d - yn * (xx - zx)) / d2
    J[1, 1] = (yy * d - yn * (xy - zy)) / d2
    return J


def chart(p):
    """A point of Q (x, y, z) in the chart x - z = 1."""
    x, y, z = p
    return np.array([x / (x - z), y / (x - z)])


def timed(f, *a, **k):
    t0 = time.perf_counter()
    out = f(*a, **k)
    return out, time.perf_counter() - t0


def main():
    ds = DiscreteDynamicalSystem(mapping=p_r, jacobian=p_r_jacobian, system_dimension=2, number_of_parameters=1)
    point = (1.0, -0.5, -1.1)
    q0 = chart(point)
    ds.lyapunov(q0, 1000, parameters=[0.12], transient_time=100)  # Numba's compilation, not timed
    print("task,case,pynamicalsys,btob,note")

    # Iterates: the branch sequences agree until rounding separates the chaotic orbits (pynamicalsys divides by
    # x' - z' every step, btob rescales by powers of two: other roundings, the same map).
    traj = ds.trajectory(q0, 200, parameters=[0.12])
    sym_peer = [branch(x, y, x - 1, 0.12) for x, y in np.vstack([q0, traj])[:200]]
    sym_btob = [int(s) for s in np.asarray(btob.iterate(r=0.12, points=[point], iterations=200, tail=200,
                                                        record="symbols")).ravel()]
    agree = next((i for i, (a, b) in enumerate(zip(sym_peer, sym_btob)) if a != b), len(sym_btob))
    print(f"iterates,r=0.12 branches equal from the start,{agree} steps,{agree} steps,the first difference "
          "after the Lyapunov time of the rounding (53 bits / lambda1 = 0.58: about 63 steps)")

    # Exponents: the chaotic orbit of the issue (r = 0.12) and the sink 1133 at r = 0.15 (exact from its eigenvalues).
    for r, n in ((0.12, 10**7), (0.15, 10**6)):
        peer, t_peer = timed(ds.lyapunov, q0, n + 1000, parameters=[r], transient_time=1000)
        ours, t_btob = timed(btob.lyapunov, r=r, point="1,-0.5,-1.1", iterations=n, transient=1000)
        a = ours.attrs
        print(f"lambda1,r={r} n={n},{peer[0]:.12g},{a['lambda1']:.12g} +- {a['err1']:.2g},")
        print(f"lambda2,r={r} n={n},{peer[1]:.12g},{a['lambda2']:.12g} +- {a['err2']:.2g},")
        print(f"speed,lyapunov r={r} (map steps/s),{(n + 1000) / t_peer:.3g},{(n + 1000) / t_btob:.3g},"
              f"btob/pynamicalsys = {t_peer / t_btob:.2f}")
    exact = btob_exact_1133()
    print(f"lambda1,sink 1133 exact (eigenvalues),{exact:.12g},{exact:.12g},")

    # Periodic orbits: pynamicalsys's grid refinement for period 4 at r = 0.15 (a 150 x 150 grid of the chart,
    # periodicity tolerance 1e-2) against btob's classification of the orbit from (1, -0.5, -1.1).
    gx, gy = np.meshgrid(np.linspace(0, 1, 150), np.linspace(-3, 3, 150), indexing="ij")
    try:
        found, t_find = timed(ds.find_periodic_orbit, np.stack([gx, gy], axis=-1), 4, parameters=[0.15],
                              tolerance=1e-2)
        peer = f"({found[0]:.15g} {found[1]:.15g}) in {t_find:.2f} s"
        word = "".join(str(branch(x, y, x - 1, 0.15)) for x, y in ds.trajectory(found, 4, parameters=[0.15]))
        peer += f" symbols {word}"
    except ValueError as e:
        peer = f"not found ({e})"
    cls, t_cls = timed(btob.classify, r=0.15, point="1,-0.5,-1.1")
    print(f"periodic,r=0.15 period 4,{peer},{cls.attrs['pattern']} in {t_cls:.2f} s "
          f"(lambda1 {cls.attrs['lambda1']:.15g}; {cls.attrs['detail']}),")


def btob_exact_1133():
    """log |l2 / l1| / 4 of the period matrix P3 P3 P1 P1 at r = 0.15 (numpy's eigenvalues, double)."""
    M = np.eye(3)
    for s in (1, 1, 3, 3):
        M = matrix(s, 0.15) @ M
    mod = sorted(abs(np.linalg.eigvals(M)), reverse=True)
    return math.log(mod[1] / mod[0]) / 4


if __name__ == "__main__":
    main()
