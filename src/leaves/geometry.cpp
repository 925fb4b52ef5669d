// SPDX-License-Identifier: GPL-3.0-or-later
// Closed forms of P2's leaves (leaves/geometry.hpp); derivations in docs/guides/leaves.md.
#include "leaves/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace btob::leaves {

namespace {
constexpr double pi = std::numbers::pi;

// The (xi, eta) chart point of label t and angle psi on a = 1, as (y, s): y = eta / c_eta, s = sqrt(2) xi + alpha y.
struct ChartPoint {
  double y, s, dy, ds;  // and their derivatives in psi
};
ChartPoint chart(double t, double psi, const Geometry& g) {
  const double rho = t * std::sqrt(g.I_max) / 2;  // I = 4 rho^2
  const double c = std::cos(psi), sn = std::sin(psi);
  ChartPoint p;
  p.y = rho * sn / g.c_eta;
  p.s = std::numbers::sqrt2 * rho * c + g.alpha * p.y;
  p.dy = rho * c / g.c_eta;
  p.ds = -std::numbers::sqrt2 * rho * sn + g.alpha * p.dy;
  return p;
}

// The eigenvalues l1, l2 of the (p, q) block [[4, -2 sqrt(2) alpha], [-2 sqrt(2) alpha, 4 r]] of the cone's form.
void block_eigenvalues(const Geometry& g, double& l1, double& l2) {
  const double m = 2 + 2 * g.r, d = std::sqrt((2 - 2 * g.r) * (2 - 2 * g.r) + 8 * g.alpha * g.alpha);
  l1 = m + d, l2 = m - d;  // l2 > 0 exactly when 2 r > alpha^2 (16 r - 8 alpha^2 = l1 l2)
}
}  // namespace

Geometry geometry(double r) {
  Geometry g;
  g.r = r, g.alpha = core::alpha(r);
  // r > 3 - 2 sqrt(2) <=> r^2 - 6 r + 1 < 0 <=> cos(theta) > -1; tested on the polynomial (no rounded threshold).
  if (!(r * r - 6 * r + 1 < 0) || !(r < 1)) return g;
  g.defined = true;
  g.cos_theta = 1 - (1 + r) * (1 + r) / (4 * r);
  g.theta = std::acos(g.cos_theta);
  g.rotation = g.theta / (2 * pi);
  g.c_eta = std::sqrt(r - g.alpha * g.alpha / 2);
  g.I_max = (2 * r - g.alpha * g.alpha) / r;
  return g;
}

double invariant(const Vec3<double>& u, const Geometry& g) {
  const double s = u(0) + u(2), a = u(0) - u(2);
  return (2 * s * s - 4 * g.alpha * s * u(1) + 4 * g.r * u(1) * u(1)) / (a * a);
}

double label(const Vec3<double>& u, const Geometry& g) { return std::sqrt(std::max(0.0, invariant(u, g)) / g.I_max); }

double eigen_angle(const Vec3<double>& u, const Geometry& g) {
  const double s = u(0) + u(2);
  return std::atan2(g.c_eta * u(1), (s - g.alpha * u(1)) / std::numbers::sqrt2);
}

Vec3<double> leaf_point(double t, double psi, const Geometry& g) {
  const ChartPoint p = chart(t, psi, g);
  const Vec3<double> v((1 + p.s) / 2, p.y, (p.s - 1) / 2);
  return v / v.norm();
}

double region_share(double t, const Geometry& g, int nodes) {
  double l1, l2;
  block_eigenvalues(g, l1, l2);
  double sum = 0;
  for (int k = 0; k < nodes; ++k) {
    const double psi = 2 * pi * k / nodes, c = std::cos(psi), s = std::sin(psi);
    const double kk = 2 * g.I_max / (l1 * c * c + l2 * s * s);  // tan^2 gamma = t^2 kk
    sum += 1 - 1 / std::sqrt(1 + t * t * kk);
  }
  return sum * (2 * pi / nodes) / pi;
}

double region_density(double t, const Geometry& g, int nodes) {
  double l1, l2;
  block_eigenvalues(g, l1, l2);
  double sum = 0;
  for (int k = 0; k < nodes; ++k) {
    const double psi = 2 * pi * k / nodes, c = std::cos(psi), s = std::sin(psi);
    const double kk = 2 * g.I_max / (l1 * c * c + l2 * s * s);
    sum += t * kk / std::pow(1 + t * t * kk, 1.5);  // d/dt (1 - (1 + t^2 kk)^(-1/2))
  }
  return sum * (2 * pi / nodes) / pi;
}

std::vector<double> arc_cdf(double t, const Geometry& g, Arc arc, int nodes) {
  std::vector<double> speed(static_cast<std::size_t>(nodes) + 1), cdf(speed.size(), 0.0);
  for (int k = 0; k <= nodes; ++k) {
    const ChartPoint p = chart(t, -pi + 2 * pi * k / nodes, g);
    if (arc == Arc::strip) {
      speed[static_cast<std::size_t>(k)] = std::hypot(p.dy, p.ds);
      continue;
    }
    const Vec3<double> v((1 + p.s) / 2, p.y, (p.s - 1) / 2), dv(p.ds / 2, p.dy, p.ds / 2);
    const double n = v.norm();
    const Vec3<double> e = v / n;
    speed[static_cast<std::size_t>(k)] = (dv - e * e.dot(dv)).norm() / n;  // |d(v / |v|) / dpsi|
  }
  for (std::size_t k = 1; k < cdf.size(); ++k) cdf[k] = cdf[k - 1] + (speed[k - 1] + speed[k]) / 2;
  const double total = cdf.back();
  for (double& c : cdf) c /= total;
  return cdf;
}

double cdf_at(const std::vector<double>& cdf, double psi) {
  const double nodes = static_cast<double>(cdf.size() - 1);
  const double x = std::clamp((psi + pi) / (2 * pi) * nodes, 0.0, nodes);
  const std::size_t k = std::min(static_cast<std::size_t>(x), cdf.size() - 2);
  const double f = x - static_cast<double>(k);
  return cdf[k] + f * (cdf[k + 1] - cdf[k]);
}

}  // namespace btob::leaves
