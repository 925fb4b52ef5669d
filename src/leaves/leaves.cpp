// SPDX-License-Identifier: GPL-3.0-or-later
// One leaf followed by the map, where a grid's orbits land, and the law of their labels (leaves/leaves.hpp).
#include "leaves/leaves.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace btob::leaves {

namespace {
constexpr double pi = std::numbers::pi;

double das_yorke(double x) { return x <= 0 || x >= 1 ? 0.0 : std::exp(-1 / (x * (1 - x))); }
double wrap(double d) { return d > pi ? d - 2 * pi : (d <= -pi ? d + 2 * pi : d); }

// The weighted Birkhoff average (turns) of the increments psi_j - psi_{j-1}, j = 1 .. m.
double weighted_rotation(const std::vector<double>& psi, long m) {
  double s = 0, w = 0;
  for (long j = 1; j <= m; ++j) {
    const double wj = das_yorke((static_cast<double>(j) - 0.5) / static_cast<double>(m));
    s += wj * wrap(psi[static_cast<std::size_t>(j)] - psi[static_cast<std::size_t>(j - 1)]);
    w += wj;
  }
  return s / w / (2 * pi);
}

// sup |F_n - F| for sorted samples x and a CDF F (the two one-sided gaps at every sample).
template <class F> double ks_distance(const std::vector<double>& x, F cdf) {
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, (static_cast<double>(i) + 1) / n - f, f - static_cast<double>(i) / n});
  }
  return d;
}

// sup_k |k / N - G_k| over the nodes of an arc-length table: its distance to the uniform law in psi.
double law_distance(const std::vector<double>& g) {
  const double nodes = static_cast<double>(g.size() - 1);
  double d = 0;
  for (std::size_t k = 0; k < g.size(); ++k) d = std::max(d, std::fabs(static_cast<double>(k) / nodes - g[k]));
  return d;
}
}  // namespace

double ks_critical(long n) { return 1.358 / std::sqrt(static_cast<double>(n)); }

LeafStudy study_leaf(double t, const Geometry& g, long n, const core::CancelToken* cancel) {
  LeafStudy s;
  s.t = t, s.I = t * t * g.I_max, s.exact_rotation = g.rotation;
  std::vector<double> psi(static_cast<std::size_t>(n) + 1);
  Vec3<double> u = leaf_point(t, 0, g);
  for (long k = 0; k <= n; ++k) {
    core::poll_cancel(cancel, k);
    psi[static_cast<std::size_t>(k)] = eigen_angle(u, g);
    if (s.stays) s.label_drift = std::max(s.label_drift, std::fabs(label(u, g) - t));
    if (k == n) break;
    const core::Step<double> st = core::step<double>(u, g.r);
    if (st.symbol != 2 && s.stays) s.stays = false, s.exit_step = k;
    u = st.u / st.u.norm();
  }
  s.birkhoff = weighted_rotation(psi, n);
  s.birkhoff_half = weighted_rotation(psi, n / 2);
  std::vector<double> x(psi.begin(), psi.end() - 1);
  std::sort(x.begin(), x.end());
  const std::vector<double> strip = arc_cdf(t, g, Arc::strip), sphere = arc_cdf(t, g, Arc::sphere);
  s.ks_uniform = ks_distance(x, [](double p) { return (p + pi) / (2 * pi); });
  s.ks_strip = ks_distance(x, [&](double p) { return cdf_at(strip, p); });
  s.ks_sphere = ks_distance(x, [&](double p) { return cdf_at(sphere, p); });
  s.law_strip = law_distance(strip), s.law_sphere = law_distance(sphere);
  return s;
}

Landing land(const Geometry& g, const attractors::Grid& grid, const attractors::Options& opt) {
  iterate::Ensemble ens;
  ens.r = {g.r};
  ens.initial = attractors::grid_points(grid);
  ens.grid_description = attractors::measure_name(grid);
  const std::vector<attractors::OrbitVerdict> v = attractors::classify(ens, opt);
  Landing l;
  l.t.assign(v.size(), -1.0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i].type == attractors::Type::undecided) ++l.undecided;
    if (attractors::attractor_key(v[i]) != "Q2") continue;
    l.t[i] = std::sqrt(std::max(0.0, v[i].invariant) / g.I_max);
    ++l.q2;
    if (l.t[i] > 1) ++l.above_one;
  }
  return l;
}

Density density(const std::vector<double>& t, int bins) {
  Density d;
  const std::size_t n = t.size(), nb = static_cast<std::size_t>(bins);
  const double h = 1.0 / bins;
  std::vector<std::size_t> count(nb, 0);
  std::vector<double> in;
  for (double x : t)
    if (x >= 0 && x <= 1) in.push_back(x), ++count[std::min(nb - 1, static_cast<std::size_t>(x / h))];
  for (std::size_t k = 0; k < nb; ++k) {
    const attractors::Fraction f = attractors::fraction(count[k], n);
    d.value.push_back(f.value / h), d.low.push_back(f.low / h), d.high.push_back(f.high / h);
    // Gaussian kernel of bandwidth h, reflected at 0 and 1 (the labels' range), per unit t, total mass in.size() / n.
    const double c = (static_cast<double>(k) + 0.5) * h;
    double s = 0;
    for (double x : in)
      for (double y : {x, -x, 2 - x}) s += std::exp(-0.5 * (c - y) * (c - y) / (h * h));
    d.kde.push_back(n ? s / (static_cast<double>(n) * h * std::sqrt(2 * pi)) : 0.0);
  }
  if (!in.empty()) {
    double m = 0, q = 0;
    for (double x : in) m += x;
    m /= static_cast<double>(in.size());
    for (double x : in) q += (x - m) * (x - m);
    d.mean = m, d.sd = std::sqrt(q / static_cast<double>(in.size()));
  }
  return d;
}

}  // namespace btob::leaves
