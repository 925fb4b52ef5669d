// SPDX-License-Identifier: GPL-3.0-or-later
// The leaves of P2 (Proposition 5.2, Section 8): for r > 3 - 2 sqrt(2) the projective action of P2 keeps a quadratic
// invariant, and its level sets are closed curves (leaves) on which P2 turns an eigen-angle by theta.  Closed forms
// only; the derivations are in docs/guides/leaves.md.
#pragma once

#include "core/map.hpp"

#include <vector>

namespace btob::leaves {

using core::Vec3;

// Conventions (the attractor classifier's, attractors/recorders.hpp, so that labels and rotation numbers compare):
//  * s = x + z, a = x - z (a > 0 in Q), y: on the chart a = 1 (the strip of eq. (6.4)), (w1, w2) = (y, s).
//  * Eigen-coordinates of the plane x = z (P2's invariant plane, where P2 / r has the eigenvalues e^{+-i theta}):
//      xi = (s - alpha y) / sqrt(2),  eta = sqrt(r - alpha^2 / 2) y,
//    per unit of a (the coordinate along P2's real eigenvector (1, 0, -1), eigenvalue r).  P2 / r maps
//    (xi, eta) / a to itself turned by +theta, cos(theta) = 1 - (1 + r)^2 / (4 r) = -(1 - r)^2 / (4 r).
//  * The invariant I = 4 (xi^2 + eta^2) / a^2 = (2 s^2 - 4 alpha s y + 4 r y^2) / a^2 (the classifier's
//    OrbitVerdict::invariant); the leaf label t = sqrt(I / I_max), I_max = (2 r - alpha^2) / r: the leaf of label t
//    lies wholly in P2's region (the parallelogram |s - 2 alpha y| <= a, |s| <= a) exactly when t <= 1 (both
//    sides of the parallelogram are touched at t = 1).
//  * The eigen-angle psi = atan2(eta, xi) in (-pi, pi]; rotation numbers in turns per iteration.
struct Geometry {
  double r = 0, alpha = 0;
  bool defined = false;  // r > 3 - 2 sqrt(2): P2 / r has a complex pair (else the fields below are 0)
  double cos_theta = 0;  // 1 - (1 + r)^2 / (4 r)
  double theta = 0;      // acos(cos_theta), in (pi/2, pi)
  double rotation = 0;   // theta / (2 pi): the rotation number of every leaf with t <= 1, in (1/4, 1/2)
  double c_eta = 0;      // sqrt(r - alpha^2 / 2)
  double I_max = 0;      // (2 r - alpha^2) / r
};
Geometry geometry(double r);

double invariant(const Vec3<double>& u, const Geometry& g);    // I (any scale of u, a > 0)
double label(const Vec3<double>& u, const Geometry& g);        // t = sqrt(I / I_max)
double eigen_angle(const Vec3<double>& u, const Geometry& g);  // psi in (-pi, pi]
// The unit point of label t and eigen-angle psi (in Q for t <= 1; a > 0 always).
Vec3<double> leaf_point(double t, double psi, const Geometry& g);

// The sphere measure (uniform on the directions of Q, total solid angle pi) of {label <= t}: the solid angle of the
// elliptic cone 4 p^2 - 4 sqrt(2) alpha p q + 4 r q^2 <= 2 t^2 I_max w^2 (p = s / sqrt 2, q = y, w = a / sqrt 2, an
// orthonormal frame), Omega = int_0^{2 pi} (1 - cos gamma(psi)) dpsi with tan^2 gamma = 2 t^2 I_max /
// (l1 cos^2 psi + l2 sin^2 psi) (l1, l2 the eigenvalues of the (p, q) block), by the trapezoid rule on `nodes`
// points (a periodic analytic integrand: the error falls geometrically with the nodes), divided by pi.
double region_share(double t, const Geometry& g, int nodes = 256);
// Its derivative in t: the density of labels of the sphere measure (the disintegration of the measure over the
// lamination's labels), per unit of t, as a fraction of Q's measure.
double region_density(double t, const Geometry& g, int nodes = 256);

// Normalised arc length along the leaf t as a function of the eigen-angle, on `nodes` + 1 equally spaced angles
// psi_k = -pi + 2 pi k / nodes (value 0 at -pi, 1 at pi): in the strip chart (w1, w2) (an ellipse) or on the sphere
// (unit vectors).  Cumulative trapezoid rule on the exact speed |d gamma / d psi|.
enum class Arc { strip, sphere };
std::vector<double> arc_cdf(double t, const Geometry& g, Arc arc, int nodes = 4096);
// Linear interpolation of such a table at psi in [-pi, pi].
double cdf_at(const std::vector<double>& cdf, double psi);

}  // namespace btob::leaves
