// SPDX-License-Identifier: GPL-3.0-or-later
// Numerical stability at the extremes: extreme r, points on and within 1e-300 of the branch
// boundaries, subnormal coordinates, exact ties; float, double and long double.
#include "core/coords.hpp"
#include "core/map.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>
#include <limits>
#include <numbers>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using namespace btob::iterate;

namespace {

const double kThree = 7 - 4 * std::sqrt(3.0);  // three-particle collapse threshold
const double kTwo = 3 - 2 * std::sqrt(2.0);    // end of real spectrum of P2

std::vector<double> extreme_r() {
  return {1e-6, 1e-3, kThree - 1e-12, kThree + 1e-12, kTwo - 1e-12, kTwo + 1e-12, 0.5, 0.999999};
}

// Points on and within 1e-300 of the boundaries x = 0, z = 0, y = 0, alpha*y - x = 0, alpha*y - z = 0
// (for the alpha of r), and with subnormal coordinates.
std::vector<Vec3<double>> boundary_points(double r) {
  const double a = (1 + r) / 2, tiny = 1e-300, sub = 4.9e-324;
  std::vector<Vec3<double>> p = {
      {0, 1, -1},
      {0, -1, -1},
      {0, 0.3, -1},
      {1, 1, 0},
      {1, -1, 0},
      {1, 0.2, 0},
      {tiny, 1, -1},
      {tiny, -1, -1},
      {1, 1, -tiny},
      {1, -1, -tiny},
      {1, 0, -1},
      {1, tiny, -1},
      {1, -tiny, -1},
      {a, 1, -1},
      {1, -1, -a},
      {a * (1 + 1e-15), 1, -1},
      {1, -1, -a * (1 + 1e-15)},
      {a * tiny, tiny, -1},
      {1, -tiny, -a * tiny},
      {sub, 1, -1},
      {1, sub, -sub},
      {sub, sub, -sub},
      {2 * sub, -sub, -3 * sub},
      {1e-310, 2e-310, -3e-310},
      {-1, 0.5, 1},  // other half
  };
  return p;
}

template <class T> void check_orbits(double r, long iterations) {
  Ensemble e;
  e.r = {r};
  e.initial = boundary_points(r);
  for (const auto& u : random_points(40, 9)) e.initial.push_back(u);
  TailRecorder th(Coord::theta, e.orbits(), iterations, 50), ph(Coord::phi, e.orbits(), iterations, 50);
  FinalRecorder fin(e.orbits(), iterations);
  Both<TailRecorder, TailRecorder> both(th, ph);
  std::size_t degenerate = 99;
  RunOptions opt;
  opt.degenerate = &degenerate;
  run<T>(e, iterations, both, opt);
  run<T>(e, iterations, fin);
  EXPECT_EQ(degenerate, 0u) << "r = " << r;
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    const auto& u = fin.out[o];
    ASSERT_TRUE(std::isfinite(u(0)) && std::isfinite(u(1)) && std::isfinite(u(2))) << "r = " << r << " orbit " << o;
    EXPECT_CLOSE(u.norm(), 1.0,
                 ulps(8, "FinalRecorder normalises in double: a sqrt of 3 squares and a division (measured 1 eps)"))
        << "never a zero vector";
    EXPECT_GE(u(0), 0) << "quadrant x >= 0 invariant";
    EXPECT_LE(u(2), 0) << "quadrant z <= 0 invariant";
    // Angles are rounded in T: pi/2 in float is 4.4e-8 above the real pi/2, so allow 2 ulp of T at pi.
    const double slack = 2 * std::max(1e-16, static_cast<double>(std::numeric_limits<T>::epsilon())) * std::numbers::pi;
    for (long j = 0; j < 50; ++j) {
      const double t = th.out[o * 50 + j], p = ph.out[o * 50 + j];
      ASSERT_TRUE(t >= 0 && t <= std::numbers::pi / 2 + slack) << "theta " << t << " r = " << r;
      ASSERT_TRUE(p >= 0 && p <= std::numbers::pi + slack) << "phi " << p << " r = " << r;
    }
  }
}

}  // namespace

TEST(Extremes, DoubleNeverNanNeverZeroQuadrantInvariant) {
  for (double r : extreme_r()) check_orbits<double>(r, 20000);
}
TEST(Extremes, FloatNeverNanNeverZeroQuadrantInvariant) {
  for (double r : extreme_r()) check_orbits<float>(r, 20000);
}
TEST(Extremes, LongDoubleNeverNanNeverZeroQuadrantInvariant) {
  for (double r : extreme_r()) check_orbits<long double>(r, 5000);
}

TEST(Extremes, ExactTiesFollowTheDocumentedConvention) {
  // r = 0.5: alpha = 0.75 exactly, so the ties below are exact in binary floating point.
  const double r = 0.5;
  EXPECT_EQ(core::step<double>({0.75, 1, -1}, r).symbol, 2);   // alpha*y - x = 0 -> P2 (Remark 3.6)
  EXPECT_EQ(core::step<double>({1, -1, -0.75}, r).symbol, 2);  // alpha*y - z = 0 -> P2
  EXPECT_EQ(core::step<double>({1, 0, -1}, r).symbol, 2);      // y = 0 -> P2
  EXPECT_EQ(core::step<double>({std::nextafter(0.75, 0.0), 1, -1}, r).symbol, 1);
  EXPECT_EQ(core::step<double>({1, -1, std::nextafter(-0.75, 0.0)}, r).symbol, 3);
  // The batched kernel starts from the user's bits (power-of-two scaling only) and takes the same branch.
  Ensemble e;
  e.r = {r};
  e.initial = {{0.75, 1, -1},
               {1, -1, -0.75},
               {1, 0, -1},
               {std::nextafter(0.75, 0.0), 1, -1},
               {1, -1, std::nextafter(-0.75, 0.0)},
               {0.75 * 0x1p-1000, 0x1p-1000, -1}};
  SymbolRecorder s(e.orbits(), 1, 1);
  run<double>(e, 1, s);
  EXPECT_EQ(s.out, (std::vector<std::uint8_t>{2, 2, 2, 1, 3, 2}));
  run<float>(e, 1, s);  // 0.75, 1, -1 are exact in float too
  EXPECT_EQ(s.out[0], 2);
  EXPECT_EQ(s.out[1], 2);
  EXPECT_EQ(s.out[2], 2);
  // (1, 0, -1) is the P2 eigenvector of eigenvalue r (Proposition 5.3): a fixed point, symbol 2 forever.
  Ensemble f;
  f.r = {0.3};
  f.initial = {{1, 0, -1}};
  SymbolRecorder t(1, 1, 1000);
  run<double>(f, 1000, t);
  for (auto v : t.out) ASSERT_EQ(v, 2);
}

TEST(Extremes, ThreeParticleCollapseStillFoundBelowThreshold) {
  // Below 7 - 4 sqrt(3) orbits of the Section 4 grid end in the three-particle collapse: symbol 1 (or 3)
  // forever.  At r = 1e-3 the convergence is fast; at 0.07 it takes a chaotic transient.
  for (double r : {1e-3, 0.05, 0.07}) {
    Ensemble e;
    e.r = {r};
    e.initial = paper_grid();
    SymbolRecorder s(e.orbits(), 19801, 20000);
    run<double>(e, 20000, s);
    for (std::size_t o = 0; o < e.orbits(); ++o) {
      const std::uint8_t first = s.out[o * s.count];
      EXPECT_TRUE(first == 1 || first == 3) << "r = " << r;
      for (long j = 0; j < s.count; ++j) ASSERT_EQ(s.out[o * s.count + j], first) << "r = " << r << " orbit " << o;
    }
  }
}

TEST(Extremes, MultiprecisionLanesAgreeWithDoubleOnSinks) {
  // float128 runs the generic lanes with its own atan2: same sink 1133 at r = 0.15 as double.
  Ensemble e;
  e.r = {0.15};
  e.initial = paper_grid();
  SymbolRecorder d(e.orbits(), 1, 400), q(e.orbits(), 1, 400);
  run<double>(e, 400, d);
  run<btob::core::float128>(e, 400, q);
  EXPECT_EQ(d.out, q.out);
}
