# SPDX-License-Identifier: GPL-3.0-or-later
"""pattern-curves against an independent route: mpmath's QR eigensolver at 50 digits.

btob computes the spectrum of the period matrix from its characteristic polynomial in long double (the trace, the
trace of the adjugate as a product of the factors' adjugates, the determinant as the product of the factors'
r^3 and r^4) and the tracked eigenvector from A - l I.  mpmath forms the same matrix product at 50 digits and
diagonalises it by QR iterations: no shared code and no shared formula.  Checked, for 13223122 (the negative
real eigenvalue, Figures 7.6-7.8) and 132312 (the dominant one, Figures 7.1-7.5) on 400 values of r in
[0.0005, 0.9995]:
  * every eigenvalue to 1e4 x long double's epsilon x the largest modulus (the cubic's roots carry a few ulps of
    it; 1e4 covers the matrix product's rounding, 8 factors), times largest / distance to the nearest other root
    where that exceeds 1 (first-order perturbation of a near-double root);
  * the feasibility column u_z (= u_z / u_x) wherever btob calls the row resolved, within the bound u_error
    propagated through the ratio plus the two roundings to double (the bound is a bound: no slack factor);
  * the critical r where u_x or u_z changes sign: the same grid intervals in both routes, none more, none less.
Usage: pattern_curves_mpmath.py BTOB"""
import os
import subprocess
import sys
import tempfile

import h5py
import mpmath as mp
import numpy as np

mp.mp.dps = 50
EPS_L = 2.0 ** -63  # long double's epsilon on x86-64


def P(i, r):
    a = (1 + r) / 2
    if i == 1:
        return mp.matrix([[-r, r * a, 0], [-a, a * a - r, r * a], [0, 0, r * r]])
    if i == 2:
        return mp.matrix([[r, -r * a, 0], [a, -2 * a * a + r, a], [0, -r * a, r]])
    return mp.matrix([[r * r, 0, 0], [r * a, a * a - r, -a], [0, r * a, -r]])


def analysed(word, reduced, r):
    m = mp.eye(3)
    for s in word:
        m = P(int(s), r) * m
    if reduced:
        m = mp.matrix([[0, 0, 1], [0, 1, 0], [1, 0, 0]]) * m
    return m


def tracked(word, reduced, r, negative):
    """(eigenvalues, the tracked eigenvalue, its unit eigenvector) at 50 digits, or None when none is tracked."""
    E, V = mp.eig(analysed(word, reduced, r))
    lam = [complex(e) for e in E]
    best = None
    for k in range(3):
        if abs(mp.im(E[k])) <= mp.mpf(10) ** -40 * abs(E[k]) and (not negative or mp.re(E[k]) < 0):
            if best is None or abs(E[k]) > abs(E[best]):
                best = k
    if best is None:
        return lam, None, None
    u = [mp.re(V[i, best]) for i in range(3)]
    n = mp.sqrt(sum(x * x for x in u))
    return lam, float(mp.re(E[best])), [x / n for x in u]


def run_btob(btob, word, track, out):
    subprocess.run([btob, "pattern-curves", "--word", word, "--track", track, "--r-count", "400", "--out", out,
                    "--name", "c", "--no-plot", "--quiet"], check=True)
    return h5py.File(os.path.join(out, "c.h5"), "r")


def check(btob, word, track):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        f = run_btob(btob, word, track, tmp)
        r, eig_re, eig_im, tr, feas = (f[k][:] for k in ("r", "eig_re", "eig_im", "tracked", "feas"))
        u_error, resolved = f["u_error"][:], f["resolved"][:]
        analysed_word, reduced = f.attrs["analysed"], bool(f.attrs["reduced"])
        crit = [(float(x), w.decode() if isinstance(w, bytes) else w)
                for x, w in zip(f["critical_r"][:], f["critical_what"][:])]
    negative = track == "negative"
    signs, worst = [], 0.0
    for i, ri in enumerate(r):
        lam, t, u = tracked(analysed_word, reduced, mp.mpf(float(ri)), negative)
        big = max(abs(x) for x in lam)
        ours = [complex(a, b) for a, b in zip(eig_re[i], eig_im[i])]
        for a, b in zip(sorted(lam, key=lambda z: (z.real, z.imag)), sorted(ours, key=lambda z: (z.real, z.imag))):
            # First-order perturbation: a change of eps x big in the polynomial moves a root by that over its
            # distance to the nearest other root (a near-double root is square-root conditioned).
            gap = min(abs(a - z) for z in lam if z is not a) if len(lam) > 1 else big
            if abs(a - b) > 1e4 * EPS_L * big * max(1.0, big / max(gap, 1e-300)):
                failures.append(f"{word} r={ri:.6f}: eigenvalue {b} against mpmath {a} (largest {big:.3g})")
        if t is None:
            signs.append(None)
            continue
        signs.append(-u[0] * u[2] > 0)
        if resolved[i] and u[0] != 0:
            # u_z / u_x moves by at most e (1 / |u_x| + |u_z| / u_x^2) when each unit component moves by e.
            want, spread = float(u[2] / u[0]), float(1 / abs(u[0]) + abs(u[2]) / (u[0] * u[0]))
            # plus the rounding of the stored double and of the 50-digit value to double (half an ulp each)
            err, bound = abs(feas[i, 0] - want), u_error[i] * spread + 2.0 ** -52 * abs(want)
            worst = max(worst, err / bound)
            if not err <= bound:
                failures.append(f"{word} r={ri:.6f}: u_z {feas[i, 0]!r} against mpmath {want!r} (bound "
                                f"{u_error[i] * spread:.3g} from u_error {u_error[i]:.3g})")
    # Sign changes of -u_x u_z between grid neighbours, both routes.
    want = {i for i in range(len(r) - 1) if signs[i] is not None and signs[i + 1] is not None and signs[i] != signs[i + 1]}
    got = {int(np.searchsorted(r, x)) - 1 for x, w in crit if w in ("u_x = 0", "u_z = 0")}
    undecided = {int(np.searchsorted(r, x)) - 1 for x, w in crit if w.startswith("undecided")}
    if got != want:
        failures.append(f"{word}: sign changes of u_x u_z in grid intervals {sorted(got)} (undecided {sorted(undecided)}); "
                        f"mpmath has {sorted(want)}")
    print(f"{word} ({track}): {len(r)} r, {len(want)} critical r where u leaves the domain, "
          f"{int(sum(resolved))} rows resolved, max u_error {np.nanmax(u_error):.3g}, largest error of u_z over its "
          f"bound {worst:.3g}")
    return failures


def main():
    btob = sys.argv[1]
    failures = check(btob, "13223122", "negative") + check(btob, "132312", "dominant")
    for f in failures[:20]:
        print("FAIL:", f)
    if failures:
        sys.exit(f"{len(failures)} failures")
    print("pattern-curves agrees with mpmath")


if __name__ == "__main__":
    main()
