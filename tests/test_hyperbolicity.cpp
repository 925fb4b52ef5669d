// SPDX-License-Identifier: GPL-3.0-or-later
// Non-hyperbolicity: singular values of D P-hat (closed form vs SVD and central differences, the
// P2 centre), covariant Lyapunov vectors (periodic sinks vs eigenvectors of the period matrix, covariance on a
// chaotic orbit, the degenerate rotation region of P2), strip images and errors.
#include "core/coords.hpp"
#include "core/map.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

using namespace btob;
using V3 = Eigen::Vector3d;
using M32 = Eigen::Matrix<double, 3, 2>;

std::string sci(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3e", x);
  return b;
}

double det_of(int s, double r) { return s == 2 ? r * r * r : r * r * r * r; }

// |sin| of the angle between two lines spanned by a and b.
double sin_between(const V3& a, const V3& b) { return a.normalized().cross(b.normalized()).norm(); }

TEST(Hyperbolicity, ClosedFormEqualsSvdOfTheDerivative) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double r : {0.08, 0.3, 0.6}) {
    for (int s = 1; s <= 3; ++s) {
      const Eigen::Matrix3d P = core::P<double>(s, r);
      for (int i = 0; i < 200; ++i) {
        const V3 u = core::to_quadrant<double>(V3(std::abs(U(rng)), U(rng), -std::abs(U(rng)))).normalized();
        const V3 w = (P * u).normalized();
        const Eigen::Matrix2d A = lyapunov::tangent_basis<double>(w).transpose() *
                                  lyapunov::projective_derivative<double>(P, u) * lyapunov::tangent_basis<double>(u);
        const Eigen::JacobiSVD<Eigen::Matrix2d> svd(A);
        const auto sv = lyapunov::singular_values<double>(P, det_of(s, r), u);
        // Both are backward stable: errors ~ eps * s1 * (|P| / |P u|) <= 1e-13 s1 here; 1e-11 leaves room.
        const auto tol =
            ulps(4500, "backward stable: eps s1 |P| / |P u| <= 450 eps s1 here (measured 14 eps), 10x room").of(sv[0]);
        EXPECT_CLOSE(sv[0], svd.singularValues()(0), tol) << "r=" << r << " s=" << s;
        EXPECT_CLOSE(sv[1], svd.singularValues()(1), tol) << "r=" << r << " s=" << s;
      }
    }
  }
}

TEST(Hyperbolicity, SingularValuesMatchCentralDifferences) {
  // u -> P u / |P u| differentiated along the great circles through u in the directions of the tangent basis,
  // projected on the tangent basis at the image.  Central differences with h = 1e-5: truncation h^2 |F'''| / 6
  // with |F'''| ~ 6 k^3 (k = |P| / |P u|, each derivative of the quotient brings one factor k), rounding
  // eps k / h.  The bound below uses 10x that sum.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 1e-5, eps = 2.2e-16;
  double worst = 0;
  for (double r : {0.1, 0.3, 0.6}) {
    for (int i = 0; i < 300; ++i) {
      const V3 u = V3(std::abs(U(rng)), U(rng), -std::abs(U(rng))).normalized();
      const int s = core::branch(u, r);
      const Eigen::Matrix3d P = core::P<double>(s, r);
      const auto F = [&](const V3& v) { return V3((P * v).normalized()); };
      const M32 Bu = lyapunov::tangent_basis<double>(u), Bw = lyapunov::tangent_basis<double>(F(u));
      Eigen::Matrix2d J;
      for (int j = 0; j < 2; ++j) {
        // F is projectively invariant, so F(u +- h e) = F of the great-circle point (u +- h e) / sqrt(1 + h^2),
        // whose velocity at h = 0 is e.
        J.col(j) = Bw.transpose() * (F(u + h * Bu.col(j)) - F(u - h * Bu.col(j))) / (2 * h);
      }
      const Eigen::JacobiSVD<Eigen::Matrix2d> svd(J);
      const auto sv = lyapunov::singular_values<double>(P, det_of(s, r), u);
      const double k = Eigen::JacobiSVD<Eigen::Matrix3d>(P).singularValues()(0) / (P * u).norm();
      const double tol = 10 * (h * h * k * k * k + eps * k / h) * sv[0];
      const auto fd = bound(tol, "central differences: 10 x (truncation h^2 k^3 + rounding eps k / h)");
      EXPECT_CLOSE(sv[0], svd.singularValues()(0), fd) << "r=" << r << " k=" << k;
      EXPECT_CLOSE(sv[1], svd.singularValues()(1), fd) << "r=" << r << " k=" << k;
      worst = std::max(worst, std::abs(sv[0] - svd.singularValues()(0)) / sv[0]);
    }
  }
  RecordProperty("worst_relative_difference_s1", sci(worst));
}

TEST(Hyperbolicity, P2CentreHasUnitDeterminantAndExpands) {
  // Section 5.2: (1, 0, -1) is the real eigenvector of P2 (eigenvalue r), so |P2 u| = r and s1 s2 = r^3 / r^3 = 1
  // exactly: the derivative is conjugate to a rotation, s1 >= 1 >= s2, and the centre is never contracting.
  for (double r : {0.2, 0.3, 0.6}) {
    const V3 c = V3(1, 0, -1).normalized();
    ASSERT_SMALL((core::P2(r) * c - r * c).norm(), ulps(4, "an eigenvector of P2: a few roundings of unit entries"));
    const auto sv = lyapunov::step_singular_values(c, r);
    EXPECT_EQ(sv.symbol, 2);
    EXPECT_CLOSE(sv.s1 * sv.s2, 1.0, ulps(45, "a few roundings of O(1) quantities"));
    EXPECT_GE(sv.s1, 1.0);
  }
}

// Runs Ginelli's method on a periodic sink and compares, at every window step, the CLVs with the projections on
// the tangent plane of the subdominant eigenvectors of the period matrix started at that step.
void check_periodic_clvs(double r, const V3& u0, std::size_t period) {
  SCOPED_TRACE("r = " + std::to_string(r));
  lyapunov::ClvOptions o;
  o.transient = 20000;  // the orbit converges geometrically; 2e4 steps bring it to rounding level
  o.window = 400;
  o.backward_transient = 2000;  // the backward vectors converge like exp(-(lambda1 - lambda2) k), gap >= 0.05 here
  o.keep_vectors = true;
  const auto res = lyapunov::covariant_vectors<double>(u0, r, o);
  EXPECT_FALSE(res.degenerate);
  double worst = 0;
  for (std::size_t j = 0; j + period < res.angle.size(); ++j) {
    Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
    for (std::size_t i = 0; i < period; ++i) M = core::P<double>(res.symbols[j + i], r) * M;
    const Eigen::EigenSolver<Eigen::Matrix3d> es(M);
    std::array<int, 3> idx = {0, 1, 2};
    std::sort(idx.begin(), idx.end(),
              [&](int a, int b) { return std::abs(es.eigenvalues()(a)) > std::abs(es.eigenvalues()(b)); });
    for (int i : idx) ASSERT_EQ(es.eigenvalues()(i).imag(), 0.0) << "complex eigenvalues: CLVs undefined";
    const V3 u = res.points[j];
    ASSERT_SMALL(sin_between(es.eigenvectors().col(idx[0]).real(), u),
                 bound(1e-9, "the orbit converged onto the cycle"))
        << "not on the periodic orbit";
    const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - u * u.transpose();
    const V3 t2 = proj * es.eigenvectors().col(idx[1]).real(), t3 = proj * es.eigenvectors().col(idx[2]).real();
    // Eigenvectors from the solver carry ~eps * cond errors (cond <= 1e3 here); the CLVs converge to rounding level.
    const auto converged = bound(1e-9, "the CLVs converged (geometrically) onto the eigenvectors");
    EXPECT_SMALL(sin_between(res.clv1[j], t2), converged) << j;
    EXPECT_SMALL(sin_between(res.clv2[j], t3), converged) << j;
    const double expected = std::acos(std::min(1.0, std::abs(t2.normalized().dot(t3.normalized()))));
    EXPECT_CLOSE(res.angle[j], expected, bound(1e-9, "the CLVs are within sin 1e-9 of the eigenvectors (above)")) << j;
    worst = std::max(worst, std::abs(res.angle[j] - expected));
  }
  testing::Test::RecordProperty("worst_angle_error_r" + std::to_string(r), sci(worst));
}

TEST(Hyperbolicity, ClvsOnPeriodicSinksAreProjectedEigenvectors) {
  check_periodic_clvs(0.15, V3(1, -0.9, -0.2), 4);  // 1133 (colleague's test_lyapunov)
  check_periodic_clvs(0.1, V3(1, -0.9, -0.2), 6);   // 111333
}

TEST(Hyperbolicity, ClvsAreCovariantOnAChaoticOrbit) {
  // r = 0.11 (between the windows n = 3 and n = 2, lambda1 > 0): D_k CLV_j(k) must be parallel to CLV_j(k+1),
  // and the mean log growth of CLV_j equal the forward QR exponents.
  const double r = 0.11;
  lyapunov::ClvOptions o;
  o.transient = 10000;
  o.window = 20000;
  o.backward_transient = 10000;
  o.keep_vectors = true;
  const auto res = lyapunov::covariant_vectors<double>(V3(1, -0.9, -0.2), r, o);
  ASSERT_FALSE(res.degenerate);
  ASSERT_GT(res.lambda[0], 0.1);
  double worst = 0, growth[2] = {0, 0};
  for (std::size_t k = 0; k + 1 < res.points.size(); ++k) {
    const V3 u = res.points[k];
    const Eigen::Matrix3d D = lyapunov::projective_derivative<double>(core::P<double>(res.symbols[k], r), u);
    const V3 a = D * res.clv1[k], b = D * res.clv2[k];
    worst = std::max({worst, sin_between(a, res.clv1[k + 1]), sin_between(b, res.clv2[k + 1])});
    growth[0] += std::log(a.norm());
    growth[1] += std::log(b.norm());
  }
  // Each step commits rounding ~eps * |D| / s2(D) to the covariant direction; backward iteration keeps it from
  // growing.  1e-9 is a generous bound on this orbit (|D| / s2 < 1e5 measured).
  EXPECT_SMALL(worst, ulps(450000, "eps |D| / s2(D) per step, |D| / s2 < 1e5 measured (the sine measured 54 eps)"));
  RecordProperty("worst_covariance_sin", sci(worst));
  const double n = static_cast<double>(res.points.size() - 1);
  // CLV growth differs from the QR diagonal by log of bounded angle ratios at the two ends: O(10 / n) = 5e-4.
  const auto ends = bound(5e-4, "log of bounded angle ratios at the two ends, O(10 / n)");
  EXPECT_CLOSE(growth[0] / n, res.lambda[0], ends);
  EXPECT_CLOSE(growth[1] / n, res.lambda[1], ends);
  // The expanding fraction agrees with step_singular_values at the recorded points.
  long e = 0;
  for (std::size_t k = 0; k < res.points.size(); ++k) e += lyapunov::step_singular_values(res.points[k], r).s1 >= 1;
  EXPECT_EQ(e, static_cast<long>(res.expanding_fraction * static_cast<double>(res.points.size()) + 0.5));
}

TEST(Hyperbolicity, RotationRegionOfP2IsDegenerate) {
  // In the P2 region around the centre (r > 3 - 2 sqrt2), P2 = r * E diag(1, R_theta) E^{-1} with R_theta a
  // rotation (all eigenvalues of modulus r): in the chart (a1/a0, a2/a0) of the eigenbasis E the projective map
  // is a rigid rotation.  The invariant curves are the circles a1^2 + a2^2 = t a0^2, their tangent field is
  // covariant, but so is every direction (no twist): lambda1 = lambda2 = 0 and the Oseledets splitting is
  // trivial, so Ginelli's CLVs are not defined there -- the orbit must be flagged degenerate.
  for (double r : {0.2, 0.3}) {
    const Eigen::EigenSolver<Eigen::Matrix3d> es(core::P2(r));
    int k0 = 0;
    for (int i = 0; i < 3; ++i)
      if (es.eigenvalues()(i).imag() == 0) k0 = i;
    const int kc = (k0 + 1) % 3;
    for (int i = 0; i < 3; ++i) ASSERT_CLOSE(std::abs(es.eigenvalues()(i)), r, ulps(45, "rounding of a 3x3 solver"));
    Eigen::Matrix3d E;
    E << es.eigenvectors().col(k0).real(), es.eigenvectors().col(kc).real(), es.eigenvectors().col(kc).imag();
    const Eigen::Matrix3d Einv = E.inverse();
    lyapunov::ClvOptions o;
    o.transient = 1000;
    o.window = 20000;
    o.backward_transient = 1000;
    o.keep_vectors = true;
    const auto res = lyapunov::covariant_vectors<double>(V3(1, 0.02, -1), r, o);
    for (auto s : res.symbols) ASSERT_EQ(s, 2) << "the orbit left the P2 region";
    EXPECT_TRUE(res.degenerate) << res.lambda[0] << " " << res.lambda[1];
    const auto t_of = [&](const V3& u) {
      const V3 a = Einv * u;
      return (a(1) * a(1) + a(2) * a(2)) / (a(0) * a(0));
    };
    const auto tangent = [&](const V3& u) {  // tangent of the invariant circle through u: u x grad Q_t(u)
      const V3 a = Einv * u;
      const V3 grad = Einv.transpose() * V3(-t_of(u) * a(0), a(1), a(2));
      return V3(u.cross(grad));
    };
    const double t0 = t_of(res.points.front());
    double worst = 0;
    for (std::size_t k = 0; k + 1 < res.points.size(); ++k) {
      // The circle is invariant: what moves is rounding, a few eps per step over 2e4 steps.
      EXPECT_CLOSE(t_of(res.points[k]), t0, ulps(450000, "rounding drift over 2e4 steps, ~20 eps each").of(t0));
      const Eigen::Matrix3d D = lyapunov::projective_derivative<double>(core::P2(r), res.points[k]);
      worst = std::max(worst, sin_between(D * tangent(res.points[k]), tangent(res.points[k + 1])));
    }
    EXPECT_SMALL(worst,
                 ulps(450000, "the tangent field is covariant: rounding on O(1) quantities (measured 4400 eps)"));
    // Both exponents vanish: |lambda| <= 2 log(cond E) / n, cond E < 1e2 here.
    const auto frame = bound(10.0 / 20000, "2 log(cond E) / n with cond E < 1e2, n = 2e4");
    EXPECT_SMALL(res.lambda[0], frame);
    EXPECT_SMALL(res.lambda[1], frame);
  }
}

TEST(Hyperbolicity, StripImage) {
  const auto img = lyapunov::strip_singular_values(0.3, 40, 20, -2, 2);
  ASSERT_EQ(img.s1.size(), 800u);
  for (std::size_t i = 0; i < img.s1.size(); ++i) {
    const auto sv = lyapunov::step_singular_values(core::from_strip(img.w1[i], img.w2[i]), 0.3);
    // The strip coordinates round-trip to a few ulps; s1 is Lipschitz with constant ~ s1 there.
    EXPECT_CLOSE(sv.s1, img.s1[i],
                 ulps(450, "the strip round trip's few ulps, times s1's Lipschitz constant ~ s1").of(img.s1[i]));
    EXPECT_EQ(sv.symbol, img.symbol[i]);
    EXPECT_GE(img.s1[i], img.s2[i]);
  }
  // Branch 1 lies below w2 = 2 alpha w1 - 1, branch 3 above w2 = 2 alpha w1 + 1 (Section 6.2).
  const double a = core::alpha(0.3);
  for (std::size_t i = 0; i < img.s1.size(); ++i) {
    if (img.w2[i] < 2 * a * img.w1[i] - 1 - 1e-12) EXPECT_EQ(img.symbol[i], 1);
    else if (img.w2[i] > 2 * a * img.w1[i] + 1 + 1e-12) EXPECT_EQ(img.symbol[i], 3);
    else EXPECT_EQ(img.symbol[i], 2);
  }
  EXPECT_GT(img.expanding_fraction, 0.0);
  EXPECT_LT(img.expanding_fraction, 1.0);
}

TEST(Hyperbolicity, Errors) {
  const auto msg = [](auto f) {
    try {
      f();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  lyapunov::ClvOptions o;
  o.window = 0;
  EXPECT_EQ(msg([&] { lyapunov::validate(o); }), "window: got 0, expected at least 1");
  o = {};
  o.transient = -1;
  EXPECT_EQ(msg([&] { lyapunov::validate(o); }), "transient: got -1, expected at least 0");
  o = {};
  o.backward_transient = 0;
  EXPECT_EQ(msg([&] { lyapunov::validate(o); }), "backward-transient: got 0, expected at least 1");
  o = {};
  o.bins = 0;
  EXPECT_EQ(msg([&] { lyapunov::validate(o); }), "bins: got 0, expected at least 1");
  EXPECT_THROW(lyapunov::covariant_vectors<double>(V3(1, 0, 1), 0.3, {}), std::logic_error);  // x z > 0
  o = {};
  o.window = 0;
  EXPECT_EQ(msg([&] { lyapunov::covariant_vectors_batched({0.3}, {V3(1, -0.5, -1)}, o); }),
            "window: got 0, expected at least 1");
  EXPECT_THROW(lyapunov::covariant_vectors_batched({0.3}, {V3(1, 0, 1)}, {}), std::logic_error);
  EXPECT_THROW(lyapunov::covariant_vectors_batched({1.5}, {V3(1, -0.5, -1)}, {}), core::InvalidField);
  EXPECT_THROW(lyapunov::strip_singular_values(1.5, 4, 4, -1, 1), core::InvalidField);
  EXPECT_NE(msg([] { lyapunov::strip_singular_values(0.3, 0, 4, -1, 1); }).find("grid"), std::string::npos);
  EXPECT_NE(msg([] { lyapunov::strip_singular_values(0.3, 4, 4, 1, -1); }).find("w1"), std::string::npos);
}

// ---- the batched route (covariant_vectors_batched) against the scalar reference ---------------------------

// One orbit through both routes, the batched one with its per-step arrays.
struct BothRoutes {
  lyapunov::ClvResult scalar, batched;
};
BothRoutes both_routes(double r, const V3& u0, const lyapunov::ClvOptions& o) {
  const auto rows = lyapunov::covariant_vectors_batched({r}, {u0}, o, {}, true);
  return {lyapunov::covariant_vectors<double>(u0, r, o), rows.at(0).orbit.at(0)};
}

TEST(HyperbolicityBatched, PeriodicSinksMatchTheScalarRoute) {
  // On a sink both routes converge onto the same cycle and the same eigenvector CLVs, possibly at another phase
  // (from this start at r = 0.1 the batched orbit lands one step ahead: the transient's roundings differ); with a
  // window of whole periods every statistic is the same up to rounding, and per step they agree once aligned.
  for (const auto& [r, period] : {std::pair{0.15, 4}, std::pair{0.1, 6}}) {
    SCOPED_TRACE("r = " + std::to_string(r));
    lyapunov::ClvOptions o;
    o.transient = 20000;  // as ClvsOnPeriodicSinksAreProjectedEigenvectors: the orbit at rounding level
    o.window = 396;       // whole periods of both cycles
    o.backward_transient = 2000;
    const auto [sc, ba] = both_routes(r, V3(1, -0.9, -0.2), o);
    ASSERT_FALSE(ba.degenerate);
    int shift = 0;
    const auto aligned = [&](int d) {
      for (std::size_t j = 0; j + period < sc.symbols.size(); ++j)
        if (ba.symbols[j] != sc.symbols[j + static_cast<std::size_t>(d)]) return false;
      return true;
    };
    while (shift < period && !aligned(shift)) ++shift;
    ASSERT_LT(shift, period) << "not the same cycle";
    double worst = 0;
    for (std::size_t j = 0; j + period < sc.angle.size(); ++j)
      worst = std::max(worst, std::abs(ba.angle[j] - sc.angle[j + static_cast<std::size_t>(shift)]));
    // Both within 1e-9 of the projected eigenvectors (ClvsOnPeriodicSinksAreProjectedEigenvectors); the two
    // routes' roundings of the same cycle are closer still.
    const auto cycle = ulps(64, "the same cycle's CLV angles rounded along two routes (measured 15 eps)");
    EXPECT_SMALL(worst, cycle);
    EXPECT_CLOSE(ba.median_angle, sc.median_angle, cycle);
    EXPECT_CLOSE(ba.q05_angle, sc.q05_angle, cycle);
    EXPECT_CLOSE(ba.min_angle, sc.min_angle, cycle);
    EXPECT_EQ(ba.histogram, sc.histogram);
    EXPECT_EQ(ba.expanding_fraction, sc.expanding_fraction);
    // The window's mean of log r11 (r22): the scalar's sum of logs against the batched telescoped sums (logs at
    // the window's ends, exact exponents, one mantissa product).
    const auto mean = ulps(16, "396 logs of O(1) values summed two ways (measured 1.75 eps)");
    EXPECT_CLOSE(ba.lambda[0], sc.lambda[0], mean);
    EXPECT_CLOSE(ba.lambda[1], sc.lambda[1], mean);
  }
}

TEST(HyperbolicityBatched, SymbolsAreThePlainKernels) {
  // The batched route steps its points with the plain kernel's map_step: the window's symbols are those of
  // iterate::run<double> bit for bit, on chaotic orbits too (r = 0.11), where any other rounding would diverge.
  const double r = 0.11;
  lyapunov::ClvOptions o;
  o.transient = 3000;
  o.window = 5000;
  o.backward_transient = 100;
  iterate::Ensemble e;
  e.r = {r};
  e.initial = iterate::parse_grid("random:21", 3);
  iterate::SymbolRecorder rec(e.orbits(), o.transient + 1, o.transient + o.window);
  iterate::run<double>(e, o.transient + o.window, rec);
  const auto rows = lyapunov::covariant_vectors_batched({r}, e.initial, o, {}, true);
  for (std::size_t i = 0; i < e.initial.size(); ++i) {
    const auto& sym = rows[0].orbit[i].symbols;
    ASSERT_EQ(sym.size(), static_cast<std::size_t>(o.window));
    EXPECT_TRUE(std::equal(sym.begin(), sym.end(), rec.out.begin() + static_cast<long>(i) * o.window)) << i;
  }
}

TEST(HyperbolicityBatched, ChaoticOrbitsAgreeInDistribution) {
  // r = 0.11: the two routes round differently and lambda1 > 0 takes their orbits apart, so they are compared as
  // samples: each per-orbit statistic's mean over 16 orbits, against 5 sigma of the difference of two such means
  // (sigma the spread over the scalar route's orbits).
  const double r = 0.11;
  lyapunov::ClvOptions o;
  o.transient = 2000;
  o.window = 20000;
  o.backward_transient = 2000;
  o.bins = 18;
  const auto ics = iterate::parse_grid("random:16", 5);
  const auto rows = lyapunov::covariant_vectors_batched({r}, ics, o);
  std::vector<lyapunov::ClvResult> sc;
  for (const auto& u : ics) sc.push_back(lyapunov::covariant_vectors<double>(u, r, o));
  const auto compare = [&](const char* what, auto stat) {
    double mb = 0, ms = 0, ss = 0;
    const double n = static_cast<double>(ics.size());
    for (std::size_t i = 0; i < ics.size(); ++i) mb += stat(rows[0].orbit[i]) / n, ms += stat(sc[i]) / n;
    for (std::size_t i = 0; i < ics.size(); ++i) ss += (stat(sc[i]) - ms) * (stat(sc[i]) - ms) / (n - 1);
    EXPECT_CLOSE(mb, ms, statistical(5 * std::sqrt(2 * ss / n), "5 sigma of a difference of two means of 16 orbits"))
        << what;
  };
  for (std::size_t i = 0; i < ics.size(); ++i) ASSERT_FALSE(rows[0].orbit[i].degenerate || sc[i].degenerate) << i;
  compare("lambda1", [](const auto& c) { return c.lambda[0]; });
  compare("lambda2", [](const auto& c) { return c.lambda[1]; });
  compare("median", [](const auto& c) { return c.median_angle; });
  compare("q05", [](const auto& c) { return c.q05_angle; });
  compare("min", [](const auto& c) { return c.min_angle; });
  compare("expanding", [](const auto& c) { return c.expanding_fraction; });
  for (int b = 0; b < o.bins; ++b)
    compare(("histogram bin " + std::to_string(b)).c_str(),
            [b](const auto& c) { return c.histogram[static_cast<std::size_t>(b)]; });
}

TEST(HyperbolicityBatched, P2RegionIsDegenerateOnBothRoutes) {
  // The rotation region of P2 (RotationRegionOfP2IsDegenerate): lambda1 = lambda2 = 0, the splitting is not
  // resolved and the angle is undefined, so only the flag and the exponents are compared.
  for (const double r : {0.2, 0.3}) {
    SCOPED_TRACE("r = " + std::to_string(r));
    lyapunov::ClvOptions o;
    o.transient = 1000;
    o.window = 20000;
    o.backward_transient = 1000;
    const auto [sc, ba] = both_routes(r, V3(1, 0.02, -1), o);
    for (auto s : ba.symbols) ASSERT_EQ(s, 2) << "the orbit left the P2 region";
    EXPECT_TRUE(sc.degenerate);
    EXPECT_TRUE(ba.degenerate);
    // Both are 2 log(cond E) / n from 0 (RotationRegionOfP2IsDegenerate); the frames start alike, so closer.
    const auto frame = bound(10.0 / 20000, "2 log(cond E) / n with cond E < 1e2, n = 2e4");
    EXPECT_CLOSE(ba.lambda[0], sc.lambda[0], frame);
    EXPECT_CLOSE(ba.lambda[1], sc.lambda[1], frame);
    EXPECT_EQ(ba.expanding_fraction, sc.expanding_fraction);
  }
}

TEST(HyperbolicityBatched, AnOrbitsBitsDependOnItselfOnly) {
  // 37 orbits: full batches and a partial one.  Each orbit alone, and the whole row on 1 and 2 threads: bitwise.
  lyapunov::ClvOptions o;
  o.transient = 500;
  o.window = 1000;
  o.backward_transient = 500;
  o.bins = 9;
  const auto ics = iterate::parse_grid("random:37", 9);
  const std::vector<double> rs = {0.11, 0.3};
  iterate::RunOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const auto a = lyapunov::covariant_vectors_batched(rs, ics, o, one, true);
  const auto b = lyapunov::covariant_vectors_batched(rs, ics, o, two, true);
  const auto same = [](const lyapunov::ClvResult& x, const lyapunov::ClvResult& y) {
    const auto bits = [](double p, double q) { return std::memcmp(&p, &q, sizeof p) == 0; };
    return x.angle == y.angle && x.symbols == y.symbols && x.expanding == y.expanding && x.histogram == y.histogram &&
           bits(x.lambda[0], y.lambda[0]) && bits(x.lambda[1], y.lambda[1]) && x.degenerate == y.degenerate &&
           bits(x.median_angle, y.median_angle) && bits(x.q05_angle, y.q05_angle) && bits(x.min_angle, y.min_angle) &&
           bits(x.expanding_fraction, y.expanding_fraction);
  };
  for (std::size_t ir = 0; ir < rs.size(); ++ir) {
    for (std::size_t i = 0; i < ics.size(); ++i) {
      EXPECT_TRUE(same(a[ir].orbit[i], b[ir].orbit[i])) << ir << " " << i;
      if (i % 6 == 0 || i + 1 == ics.size()) {
        const auto alone = lyapunov::covariant_vectors_batched({rs[ir]}, {ics[i]}, o, one, true);
        EXPECT_TRUE(same(alone[0].orbit[0], a[ir].orbit[i])) << ir << " " << i;
      }
    }
    EXPECT_EQ(std::memcmp(&a[ir].median_angle, &b[ir].median_angle, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a[ir].q05_angle, &b[ir].q05_angle, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a[ir].min_angle, &b[ir].min_angle, sizeof(double)), 0);
    EXPECT_EQ(a[ir].histogram, b[ir].histogram);
  }
}

TEST(HyperbolicityBatched, ComposedBackwardTransientEqualsTheRecursion) {
  // The backward transient is composed forward into one map of tau per lane (kernel_clv.cpp); the window's steps are
  // stored and recursed back.  Run A (window 1500, backward transient 1003) composes steps 1500..2502; run B (window
  // 2503) stores and recurses over the same steps.  Both step the same points (rescaling by powers of two changes no
  // bit), so on the first 1500 window steps their angles differ only by the roundings of the two evaluations of tau
  // at step 1500, the last steps most.  Chaotic orbits (r = 0.11), lengths not multiples of the rescaling interval,
  // a partial batch.
  lyapunov::ClvOptions o;
  o.transient = 1000;
  o.window = 1500;
  o.backward_transient = 1003;
  const auto ics = iterate::parse_grid("random:21", 5);
  const auto a = lyapunov::covariant_vectors_batched({0.11}, ics, o, {}, true).at(0);
  o.window = 2503;
  o.backward_transient = 500;
  const auto b = lyapunov::covariant_vectors_batched({0.11}, ics, o, {}, true).at(0);
  double worst = 0;
  int compared = 0;
  for (std::size_t i = 0; i < ics.size(); ++i) {
    const auto& x = a.orbit[i];
    const auto& y = b.orbit[i];
    ASSERT_TRUE(std::equal(x.symbols.begin(), x.symbols.end(), y.symbols.begin())) << i;  // the same points
    if (x.degenerate) continue;
    ++compared;
    for (std::size_t j = 0; j < x.angle.size(); ++j) worst = std::max(worst, std::fabs(x.angle[j] - y.angle[j]));
  }
  ASSERT_GT(compared, 10);
  EXPECT_SMALL(worst, ulps(64, "the same angles from tau composed or recursed (measured 1 eps)").of(1.0));
}

// ---- the requests (`btob hyperbolicity`, `btob hyperbolicity-orbits`) -----------------------------------------

// The field a request's validation names, or "" when it passes (core::InvalidField's field; the grid and point
// parsers still throw std::invalid_argument / std::domain_error whose message starts with the field).
template <class Req> std::string invalid_field(const Req& req) {
  try {
    req.validate();
  } catch (const core::InvalidField& e) {
    return e.field;
  } catch (const std::exception& e) {  // the grid and point checks of core/iterate: "<field>: got ..."
    const std::string w = e.what();
    return w.substr(0, w.find(':'));
  }
  return "";
}

TEST(HyperbolicityRequest, ValidationNamesTheField) {
  lyapunov::HyperbolicityRequest q;
  q.r = 0.3;
  EXPECT_EQ(invalid_field(q), "");
  const auto with = [&](auto set) {
    lyapunov::HyperbolicityRequest b = q;
    set(b);
    return invalid_field(b);
  };
  EXPECT_EQ(with([](auto& b) { b.r = 0; }), "r");
  EXPECT_EQ(with([](auto& b) { b.r = 1; }), "r");
  EXPECT_EQ(with([](auto& b) { b.grid = "paper"; }), "grid");
  EXPECT_EQ(with([](auto& b) { b.grid = "strip:0x4"; }), "grid");
  EXPECT_EQ(with([](auto& b) { b.grid = "strip:4x4:-1:1"; }), "grid");  // the range is w1-range's
  EXPECT_EQ(with([](auto& b) { b.w1_range = "1,-1"; }), "w1-range");
  EXPECT_EQ(with([](auto& b) { b.w1_range = "1"; }), "w1-range");
  EXPECT_EQ(with([](auto& b) { b.w1_range = "a,b"; }), "w1-range");
  EXPECT_EQ(with([](auto& b) { b.w1_range = "0,inf"; }), "w1-range");
  EXPECT_EQ(q.default_name(), "hyperbolicity_strip_r0.3");
}

TEST(HyperbolicityRequest, RunIsTheStripImage) {
  lyapunov::HyperbolicityRequest q;
  q.r = 0.11;
  q.grid = "strip:30x12";
  q.w1_range = "-1.5,2.5";
  const auto res = lyapunov::run(q);
  const auto img = lyapunov::strip_singular_values(0.11, 30, 12, -1.5, 2.5);
  EXPECT_EQ(res.image.s1, img.s1);  // the same computation: bitwise
  EXPECT_EQ(res.image.s2, img.s2);
  EXPECT_EQ(res.image.symbol, img.symbol);
  EXPECT_EQ(res.image.w1, img.w1);
  EXPECT_EQ(res.image.expanding_fraction, img.expanding_fraction);
  core::Contents c;
  res.describe(c);
  ASSERT_NE(c.find("s1"), nullptr);
  EXPECT_EQ(c.find("s1")->dims, (std::vector<std::size_t>{30, 12}));
  EXPECT_EQ(std::get<std::string>(c.attrs.at("grid")), "strip:30x12:-1.5:2.5");
}

TEST(HyperbolicityOrbitsRequest, ValidationNamesTheField) {
  lyapunov::HyperbolicityOrbitsRequest q;
  q.r_count = 2;
  EXPECT_EQ(invalid_field(q), "");
  const auto with = [&](auto set) {
    lyapunov::HyperbolicityOrbitsRequest b = q;
    set(b);
    return invalid_field(b);
  };
  EXPECT_EQ(with([](auto& b) { b.r_min = 0; }), "r-min");
  EXPECT_EQ(with([](auto& b) { b.r_max = 1.5; }), "r-max");
  EXPECT_EQ(with([](auto& b) { b.r_count = 0; }), "r-count");
  EXPECT_EQ(with([](auto& b) { b.iterations = 9; }), "iterations");
  EXPECT_EQ(with([](auto& b) { b.transient = -1; }), "transient");
  EXPECT_EQ(with([](auto& b) { b.backward = 0; }), "backward");
  EXPECT_EQ(with([](auto& b) { b.bins = 0; }), "bins");
  EXPECT_EQ(with([](auto& b) { b.grid = "1,1,1"; }), "grid");
  EXPECT_EQ(with([](auto& b) { b.grid = "strip:0x3"; }), "grid");
}

TEST(HyperbolicityOrbitsRequest, RunPoolsTheClvsOfEachOrbit) {
  lyapunov::HyperbolicityOrbitsRequest q;
  q.r_min = 0.11;
  q.r_max = 0.3;
  q.r_count = 2;
  q.grid = "1,-3,-1.1;1,0.1,-1;1,0.4,-1";
  q.iterations = 400;
  q.transient = 200;
  q.backward = 200;
  q.bins = 9;
  core::RunControl one;
  one.threads = 1;
  core::RunControl two;
  two.threads = 2;
  const auto res = lyapunov::run(q, one);
  const auto res2 = lyapunov::run(q, two);
  // 1 thread and 2 threads: bitwise the same (NaN where an orbit is degenerate, so compare the bytes).
  const auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  EXPECT_TRUE(same_bits(res.orbit_angle_median, res2.orbit_angle_median));
  EXPECT_TRUE(same_bits(res.angle_median, res2.angle_median));
  const std::size_t R = 2, I = 3;
  ASSERT_EQ(res.orbit_lambda1_qr.size(), R * I);
  EXPECT_EQ(res.orbit_lambda1_qr, res2.orbit_lambda1_qr);
  EXPECT_EQ(res.angle_histogram, res2.angle_histogram);
  EXPECT_EQ(res.orbit_lambda1, res2.orbit_lambda1);
  // Against the functions it wraps, orbit by orbit.
  lyapunov::ClvOptions co;
  co.transient = q.transient;
  co.window = q.iterations;
  co.backward_transient = q.backward;
  co.bins = q.bins;
  const auto grid = iterate::parse_grid(q.grid, 1);
  for (std::size_t ir = 0; ir < R; ++ir) {
    std::vector<double> l1, pooled;
    std::vector<double> hist(static_cast<std::size_t>(q.bins), 0.0);
    // The batched route with its angles: the pooled statistics are those of quantile() on them, bit for bit.
    const auto row = lyapunov::covariant_vectors_batched({res.ensemble.r[ir]}, grid, co, {}, true).at(0);
    for (std::size_t i = 0; i < I; ++i) {
      const auto& c = row.orbit[i];
      if (!c.degenerate) {
        EXPECT_EQ(c.median_angle, lyapunov::quantile(c.angle, 0.5));
        EXPECT_EQ(c.q05_angle, lyapunov::quantile(c.angle, 0.05));
        EXPECT_EQ(c.min_angle, *std::min_element(c.angle.begin(), c.angle.end()));
        std::vector<double> own(hist.size(), 0.0);  // the fast binning's counts are those of the angles
        for (double a : c.angle) own[static_cast<std::size_t>(lyapunov::angle_bin(a, q.bins))] += 1;
        EXPECT_EQ(c.histogram, own);
      }
      const std::size_t o = ir * I + i;
      EXPECT_EQ(res.orbit_lambda1_qr[o], c.lambda[0]);
      EXPECT_EQ(res.orbit_lambda2_qr[o], c.lambda[1]);
      EXPECT_EQ(res.orbit_frac_expanding[o], c.expanding_fraction);
      EXPECT_EQ(res.orbit_degenerate[o], c.degenerate ? 1 : 0);
      if (!c.degenerate) {
        EXPECT_EQ(res.orbit_angle_median[o], c.median_angle);
        pooled.insert(pooled.end(), c.angle.begin(), c.angle.end());
        for (std::size_t b = 0; b < hist.size(); ++b) hist[b] += c.histogram[b];
      } else {
        EXPECT_TRUE(std::isnan(res.orbit_angle_median[o]));
      }
      l1.push_back(c.lambda[0]);
    }
    EXPECT_EQ(res.lambda1_qr_median[ir], lyapunov::median(l1));
    if (!pooled.empty()) {
      EXPECT_EQ(res.angle_median[ir], lyapunov::quantile(pooled, 0.5));
      EXPECT_EQ(res.angle_q05[ir], lyapunov::quantile(pooled, 0.05));
      EXPECT_EQ(res.angle_min[ir], *std::min_element(pooled.begin(), pooled.end()));
    }
    EXPECT_EQ(std::vector<double>(res.angle_histogram.begin() + static_cast<long>(ir * hist.size()),
                                  res.angle_histogram.begin() + static_cast<long>((ir + 1) * hist.size())),
              hist);
  }
  // lambda1 beside them: the batched recorder on the same ensemble.
  lyapunov::MapOptions mo;
  mo.transient = q.transient;
  mo.iterations = q.iterations;
  mo.blocks = 10;
  EXPECT_EQ(res.orbit_lambda1, lyapunov::map_exponents(res.ensemble, mo).lambda1);
  // A cancelled run throws and returns nothing.
  core::CancelToken token;
  token.cancel();
  core::RunControl cancelled;
  cancelled.cancel = &token;
  EXPECT_THROW(lyapunov::run(q, cancelled), core::Cancelled);
}

}  // namespace
