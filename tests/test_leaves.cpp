// SPDX-License-Identifier: GPL-3.0-or-later
// The leaves of P2 (src/leaves): the request's claims checked exactly (rational linear algebra) and in MPFR, the
// closed forms against independent routes (direct counts on grids, finite differences, the map's own orbits), and
// the landing law against the basins command's classification.
#include "leaves/geometry.hpp"
#include "leaves/leaves.hpp"
#include "leaves/requests.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include "attractors/attractors.hpp"
#include "core/scalar.hpp"
#include "windows/windows.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <boost/multiprecision/eigen.hpp>

#include <array>
#include <cmath>
#include <numbers>

namespace {

using btob::core::Vec3;
using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;
using Q = boost::multiprecision::cpp_rational;
using M3 = std::array<std::array<Q, 3>, 3>;
using V3 = std::array<Q, 3>;
namespace lv = btob::leaves;

// P2 of Theorem 3.3 in exact rationals (written out again here, not taken from core/map.hpp).
M3 p2_exact(const Q& r) {
  const Q a = (1 + r) / 2;
  return {{{r, -r * a, 0}, {a, -2 * a * a + r, a}, {0, -r * a, r}}};
}
V3 mul(const M3& m, const V3& v) {
  V3 w{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w[i] += m[i][j] * v[j];
  return w;
}
Q invariant_exact(const V3& u, const Q& r) {  // I = (2 s^2 - 4 alpha s y + 4 r y^2) / a^2
  const Q a = (1 + r) / 2, s = u[0] + u[2], d = u[0] - u[2];
  return (2 * s * s - 4 * a * s * u[1] + 4 * r * u[1] * u[1]) / (d * d);
}

// Claims: (1, 0, -1) has eigenvalue r; the plane x = z is invariant; on it P2 has trace 2 (r - alpha^2) and
// determinant r^2, so P2 / r's pair is e^{+-i theta} with cos(theta) = (r - alpha^2) / r = 1 - (1 + r)^2 / (4 r),
// complex exactly when r^2 - 6 r + 1 < 0; I is invariant.  Exact, at rational r on both sides of 3 - 2 sqrt(2).
TEST(LeavesClaims, EigenstructureAndInvariantExactly) {
  for (const Q& r : {Q(1, 10), Q(1, 6), Q(1, 5), Q(1, 4), Q(3, 10), Q(1, 2), Q(9, 10)}) {
    const M3 P = p2_exact(r);
    const Q a = (1 + r) / 2;
    EXPECT_EQ(mul(P, V3{1, 0, -1}), (V3{r, 0, -r}));
    const V3 e = mul(P, V3{1, 0, 1}), f = mul(P, V3{0, 1, 0});
    EXPECT_EQ(e[0], e[2]);
    EXPECT_EQ(f[0], f[2]);
    // The restriction in the basis (1, 0, 1), (0, 1, 0): columns (e_x, e_y), (f_x, f_y).
    const Q tr = e[0] + f[1], det = e[0] * f[1] - f[0] * e[1];
    EXPECT_EQ(tr, 2 * (r - a * a));
    EXPECT_EQ(det, r * r);
    const Q cos_theta = tr / (2 * r);
    EXPECT_EQ(cos_theta, 1 - (1 + r) * (1 + r) / (4 * r));
    EXPECT_EQ(cos_theta * cos_theta < 1, r * r - 6 * r + 1 < 0) << r;
    for (const V3& u : {V3{3, 1, -1}, V3{5, -2, -4}, V3{1, Q(1, 3), Q(-1, 7)}})
      EXPECT_EQ(invariant_exact(mul(P, u), r), invariant_exact(u, r));
    if (cos_theta * cos_theta < 1) {
      const lv::Geometry g = lv::geometry(static_cast<double>(r));
      EXPECT_CLOSE(g.cos_theta, static_cast<double>(cos_theta), ulps(8, "a few roundings of 1 - (1 + r)^2 / (4 r)"));
    }
  }
}

// Periodicity at a resonance theta / (2 pi) = l / m: P2^m = r^m Id, in MPFR at 60 digits, at the r(l/m) of
// eq. (6.3) (windows::thin_stripes, an independent formula); and the double rotation number there is l / m.
TEST(LeavesClaims, ResonancesArePeriodicInMpfr) {
  using btob::core::mpfr_float;
  btob::core::MpfrDigits d(60);
  int checked = 0;
  for (const auto& s : btob::windows::thin_stripes(9, 40)) {
    // l/m = 1/2 is r = 3 - 2 sqrt(2) itself: there the pair meets at -1 in a Jordan block, P2^2 != r^2 Id (no leaves).
    if (s.value >= 1 || 2 * s.l == s.m) continue;
    const mpfr_float r = s.value;
    const btob::core::Mat3<mpfr_float> P = btob::core::P2<mpfr_float>(r);
    btob::core::Mat3<mpfr_float> M = btob::core::Mat3<mpfr_float>::Identity();
    for (int k = 0; k < s.m; ++k) M = M * P;
    M -= pow(r, s.m) * btob::core::Mat3<mpfr_float>::Identity();
    mpfr_float worst = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) worst = std::max(worst, mpfr_float(abs(M(i, j))));
    EXPECT_LT(worst, mpfr_float("1e-50")) << s.l << "/" << s.m;  // r(l/m) to 40 digits, 60-digit arithmetic
    const lv::Geometry g = lv::geometry(r.convert_to<double>());
    EXPECT_CLOSE(g.rotation, static_cast<double>(s.l) / s.m, ulps(64, "acos near a rational angle: cond <= 1/sin"));
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

// The eigen-angle turns by +theta per step on every leaf inside the region (the sign convention of the classifier's
// rotation numbers), and the label is kept: the map's own step against the closed form.
TEST(LeavesGeometry, MapTurnsTheEigenAngleByTheta) {
  for (double r : {0.2, 0.25, 0.3, 0.45, 0.8}) {
    const lv::Geometry g = lv::geometry(r);
    ASSERT_TRUE(g.defined);
    for (double t : {0.1, 0.5, 0.9})
      for (double psi : {-2.5, -1.0, 0.0, 0.7, 3.0}) {
        const Vec3<double> u = lv::leaf_point(t, psi, g);
        EXPECT_CLOSE(lv::label(u, g), t, ulps(64, "a unit vector's invariant: a few roundings, cond of the chart"));
        const auto st = btob::core::step<double>(u, r);
        EXPECT_EQ(st.symbol, 2);
        double dpsi = lv::eigen_angle(st.u, g) - lv::eigen_angle(u, g);
        dpsi -= 2 * std::numbers::pi * std::round((dpsi - g.theta) / (2 * std::numbers::pi));
        EXPECT_CLOSE(dpsi, g.theta, ulps(64, "two atan2 of chart points with a few roundings each").of(4));
      }
    EXPECT_FALSE(lv::geometry(0.17).defined);  // below 3 - 2 sqrt(2) = 0.1716: real eigenvalues
  }
}

// Leaves with t <= 1 stay in P2's region and t slightly above 1 do not: the map's branch on the leaf points
// against the closed form I_max = (2 r - alpha^2) / r.
TEST(LeavesGeometry, LabelOneIsTheRegionBoundary) {
  for (double r : {0.2, 0.25, 0.3, 0.6}) {
    const lv::Geometry g = lv::geometry(r);
    for (double t : {0.999, 1.001}) {
      bool all_two = true;
      for (int k = 0; k < 20000; ++k) {
        const double psi = -std::numbers::pi + 2 * std::numbers::pi * (k + 0.5) / 20000;
        all_two = all_two && btob::core::branch<double>(lv::leaf_point(t, psi, g), r) == 2;
      }
      EXPECT_EQ(all_two, t < 1) << "r = " << r << ", t = " << t;
    }
  }
}

// The region's sphere measure: the cone's quadrature against a direct count on an equal-area sphere grid (the
// count's error is the boundary's cells, about perimeter x cell side: < 2 / N at N = 400); its density against a
// central difference; the strip's ellipse area against a count on a strip grid.
TEST(LeavesGeometry, RegionMeasureAgainstDirectCounts) {
  for (double r : {0.2, 0.3}) {
    const lv::Geometry g = lv::geometry(r);
    const auto grid = btob::core::make_grid(btob::core::GridKind::sphere, 400, 400);
    std::size_t in = 0;
    for (const auto& u : btob::attractors::grid_points(grid)) in += lv::label(u, g) <= 1;
    const double count = static_cast<double>(in) / static_cast<double>(grid.cells());
    EXPECT_CLOSE(lv::region_share(1, g), count, bound(2.0 / 400, "boundary cells of a 400 x 400 grid"));
    // Geometric convergence: 64 nodes are off by ~4e-6 at r = 0.2 (an eccentric cone), so 256 (the default) by ~1e-22.
    EXPECT_CLOSE(lv::region_share(1, g, 256), lv::region_share(1, g, 1024),
                 ulps(64, "trapezoid rule converged at 256 nodes"));
    const double h = 1e-4, fd = (lv::region_share(0.6 + h, g) - lv::region_share(0.6 - h, g)) / (2 * h);
    EXPECT_CLOSE(lv::region_density(0.6, g), fd, bound(1e-7, "central difference: h^2 f''' / 6 and 1e-16 / h"));
  }
}

// One leaf followed by the map: inside the region the weighted Birkhoff average is theta / (2 pi) to ~1e-10 (Das-Yorke:
// faster than any power of 1/n), the empirical eigen-angle law is uniform within the KS scale, and arc length (whose
// law differs from the uniform one by more than the KS scale) is rejected.  Outside, the orbit leaves the region.
TEST(LeavesDynamics, RotationAndMeasureOnALeaf) {
  const lv::Geometry g = lv::geometry(0.25);
  const long n = 20000;
  const lv::LeafStudy s = lv::study_leaf(0.8, g, n);
  EXPECT_TRUE(s.stays);
  EXPECT_CLOSE(s.birkhoff, g.rotation, bound(1e-9, "weighted Birkhoff average at n = 2e4 on an exact rotation"));
  EXPECT_SMALL(s.label_drift, ulps(16 * n, "rounding drift of the label over n steps (a random walk is far less)"));
  EXPECT_LT(s.ks_uniform, lv::ks_critical(n));
  EXPECT_GT(s.law_strip, 3 * lv::ks_critical(n));
  EXPECT_GT(s.ks_strip, lv::ks_critical(n));
  EXPECT_GT(s.ks_sphere, lv::ks_critical(n));
  const lv::LeafStudy out = lv::study_leaf(1.2, g, n);
  EXPECT_FALSE(out.stays);
  EXPECT_GE(out.exit_step, 0);
}

// (i) Where orbits land: the mass on the P2 curves equals the basins command's "Q2" fraction on the same grid with
// the same thresholds (the same classifier: equal counts); every grid point that starts on a leaf inside the region
// lands on that leaf (the classifier's I against the closed-form label); the histogram and the kernel estimator
// carry the same mass.
TEST(LeavesLanding, MassEqualsBasinsAndStartsOnALeafStay) {
  const double r = 0.25;
  const lv::Geometry g = lv::geometry(r);
  const auto grid = btob::attractors::parse_grid("sphere:24x24", -2, 2);
  btob::attractors::Options opt;
  opt.transient = 600, opt.window = 300, opt.lyap_transient = 100, opt.lyap_iterations = 1500, opt.refine_factor = 0;
  const lv::Landing l = lv::land(g, grid, opt);
  const btob::attractors::Basins b = btob::attractors::basins(r, grid, 0, 1, opt);
  std::size_t q2 = 0;
  for (const auto& a : b.attractors)
    if (a.key == "Q2") q2 = a.count;
  EXPECT_EQ(l.q2, q2);
  EXPECT_GT(l.q2, 0u);
  const auto pts = btob::attractors::grid_points(grid);
  int starts = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double t0 = lv::label(pts[i], g);
    if (t0 > 0.98) continue;  // leave the classifier's margin near the boundary alone
    ++starts;
    EXPECT_CLOSE(l.t[i], t0, bound(1e-9, "the label is kept by P2 up to rounding over ~2000 steps"));
  }
  EXPECT_GT(starts, 20);
  const lv::Density d = lv::density(l.t, 10);
  double hist = 0, kde = 0;
  for (int k = 0; k < 10; ++k) hist += d.value[k] / 10, kde += d.kde[k] / 10;
  EXPECT_CLOSE(hist, static_cast<double>(l.q2 - l.above_one) / pts.size(), ulps(16, "a sum of 10 bins"));
  EXPECT_CLOSE(kde, hist,
               bound(0.1 * hist, "midpoint rule of a kernel density of bandwidth h on bins of width h").of(1));
}

// Bad input: one field named with its range.
TEST(LeavesRequest, ValidationNamesTheField) {
  const auto field_of = [](const lv::Request& q) {
    try {
      q.validate();
    } catch (const btob::core::InvalidField& e) {
      return e.field;
    }
    return std::string();
  };
  lv::Request q;
  EXPECT_EQ(field_of(q), "");
  q.r = 0.15;
  EXPECT_EQ(field_of(q), "r");
  q = {}, q.bins = 7;
  EXPECT_EQ(field_of(q), "bins");
  q = {}, q.grid = "angles:4x4";
  EXPECT_EQ(field_of(q), "grid");
  q = {}, q.grid = "strip:4x4", q.w1_range = {-1, 1};
  EXPECT_EQ(field_of(q), "w1-range");
  q = {}, q.r_count = 3, q.r_min = 0.5, q.r_max = 0.3;
  EXPECT_EQ(field_of(q), "r-max");
  q = {}, q.labels = {0.5, -1};
  EXPECT_EQ(field_of(q), "labels");
}

}  // namespace
