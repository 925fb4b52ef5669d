// SPDX-License-Identifier: GPL-3.0-or-later
// Properties over random inputs: the batched kernel, the scalar loop (Appendix A.2) and Definition 2.1 (the
// cross-product construction, src/reference) agree on the next direction and symbol of one step of P_r, for
// random r in (1e-6, 1 - 1e-6) and random points, including points on and within rounding of the branch
// boundaries alpha*y = x and alpha*y = z, on x = 0 and z = 0, with subnormal coordinates and scaled by 1e300;
// every output is finite.  Where the symbols differ, the point must lie within the stated distance of a
// boundary (a branch test evaluated with rounding cannot decide closer than that).
#include "core/coords.hpp"
#include "core/map.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "reference/reference.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using core::Vec3;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

// The direction (unit vector) and symbol after the first step of every orbit, by the batched kernel or by the
// scalar loop: FinalRecorder normalises the kernel's power-of-two-scaled state (one more rounding, 1 eps).
struct FirstStep {
  std::vector<Vec3<double>> u;
  std::vector<int> sym;
};
FirstStep first_step(const iterate::Ensemble& e, bool batched) {
  iterate::FinalRecorder f(e.orbits(), 1);
  iterate::SymbolRecorder s(e.orbits(), 1, 1);
  if (batched) {
    iterate::Both<iterate::FinalRecorder, iterate::SymbolRecorder> both(f, s);
    iterate::run<double>(e, 1, both);
  } else {
    iterate::run_scalar<double>(e, 1, f);
    iterate::run_scalar<double>(e, 1, s);
  }
  return {f.out, std::vector<int>(s.out.begin(), s.out.end())};
}

int symbol_of(const std::string& letters) {
  if (letters == "ab") return 1;
  if (letters == "cb") return 3;
  return 2;  // acb, cab
}

// The point rescaled by an exact power of two into max |coordinate| in [1, 2) (long double: no rounding).
Vec3<long double> normal_range(const Vec3<double>& u) {
  int e = 0;
  std::frexp(u.cwiseAbs().maxCoeff(), &e);
  return Vec3<long double>(std::ldexp(static_cast<long double>(u(0)), 1 - e),
                           std::ldexp(static_cast<long double>(u(1)), 1 - e),
                           std::ldexp(static_cast<long double>(u(2)), 1 - e));
}

// Relative distance of u (in Q) to the branch boundaries alpha*y = x and alpha*y = z:
// |alpha y - x| / (alpha |y| + |x|), the quantity whose sign the branch tests evaluate, relative to the size of
// its terms (a rounding error of k eps in either term moves it by about k eps).  In long double (11 more bits).
double boundary_distance(const Vec3<double>& u_in, double r) {
  const Vec3<long double> u = normal_range(core::to_quadrant(u_in));
  const long double a = (1 + static_cast<long double>(r)) / 2;
  const auto rel = [&](long double p, long double q) {
    const long double den = std::fabs(a * p) + std::fabs(q);
    return den == 0 ? 0.0L : std::fabs(a * p - q) / den;
  };
  return static_cast<double>(std::min(rel(u(1), u(0)), rel(u(1), u(2))));
}

// Projective distance between two directions (u and -u are the same point of P^2).
double projective_distance(const Vec3<double>& a, const Vec3<double>& b) {
  const Vec3<double> na = a / a.norm(), nb = b / b.norm();
  return std::min((na - nb).norm(), (na + nb).norm());
}

// kappa = || |P| |q| || / || P q ||: the forward error of the matrix-vector product P q relative to its size
// is at most gamma_3 kappa (each component is a 3-term dot product, Higham Ch. 3).
double product_condition(int s, double r, const Vec3<double>& u_in) {
  const Vec3<long double> v = normal_range(core::to_quadrant(u_in));  // |u_in| itself may under- or overflow
  const Vec3<double> q = Vec3<double>(static_cast<double>(v(0)), static_cast<double>(v(1)), static_cast<double>(v(2)));
  const core::Mat3<double> P = core::P<double>(s, r);
  return (P.cwiseAbs() * q.cwiseAbs()).norm() / (P * q).norm();
}

struct Sample {
  double r;
  Vec3<double> u;
  const char* kind;
};

// The test points for one r: random on the sphere, on and within 1-4 ulps of both boundaries, on x = 0 and
// z = 0, on a boundary and a coordinate plane at once; each also scaled into the subnormal range, by 1e300
// and by 1e-300.
std::vector<Sample> samples(double r, std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0, 1);
  const double a = core::alpha(r);
  std::vector<Sample> base;
  auto sphere = [&] {
    const double y = 2 * U(g) - 1, az = 0.5 * std::numbers::pi * U(g), rho = std::sqrt(1 - y * y);
    return Vec3<double>(rho * std::cos(az), y, -rho * std::sin(az));
  };
  for (int i = 0; i < 8; ++i) base.push_back({r, sphere(), "random"});
  for (int i = 0; i < 4; ++i) {
    const double y = U(g) + 1e-3, z = -(U(g) + 1e-3), x = a * y;  // alpha*y = x, rounded
    base.push_back({r, {x, y, z}, "alpha*y = x"});
    double up = x, down = x;
    for (int k = 1; k <= 4; ++k) {
      up = std::nextafter(up, 2.0), down = std::nextafter(down, -1.0);
      base.push_back({r, {up, y, z}, "alpha*y = x + ulps"});
      base.push_back({r, {down, y, z}, "alpha*y = x - ulps"});
    }
    const double y3 = -(U(g) + 1e-3), x3 = U(g) + 1e-3, z3 = a * y3;  // alpha*y = z
    base.push_back({r, {x3, y3, z3}, "alpha*y = z"});
    base.push_back({r, {x3, y3, std::nextafter(z3, 1.0)}, "alpha*y = z + ulp"});
    base.push_back({r, {x3, y3, std::nextafter(z3, -2.0)}, "alpha*y = z - ulp"});
  }
  for (int i = 0; i < 3; ++i) {
    const double y = 2 * U(g) - 1;
    base.push_back({r, {0.0, y, -(U(g) + 1e-3)}, "x = 0"});
    base.push_back({r, {U(g) + 1e-3, y, 0.0}, "z = 0"});
    base.push_back({r, {0.0, -std::fabs(y) - 1e-3, -a * (std::fabs(y) + 1e-3)}, "x = 0, alpha*y = z"});
    base.push_back({r, {a * std::fabs(y), std::fabs(y), 0.0}, "z = 0, alpha*y = x"});
  }
  base.push_back({r, {0.0, 1.0, -1e-3}, "x = 0, y > 0"});
  base.push_back({r, {1e-3, -1.0, 0.0}, "z = 0, y < 0"});
  std::vector<Sample> out;
  for (const Sample& s : base) {
    out.push_back(s);
    out.push_back({s.r, s.u * 0x1p-1060, "subnormal"});  // exact: every coordinate becomes subnormal or 0
    out.push_back({s.r, s.u * 1e300, "scaled 1e300"});
    out.push_back({s.r, s.u * 1e-300, "scaled 1e-300"});
    out.push_back({s.r, -s.u, "negated"});  // the other half of the domain x*z <= 0
  }
  return out;
}

}  // namespace

TEST(Properties, KernelScalarLoopAndDefinition21AgreeOnOneStep) {
  std::mt19937_64 g(20261123);
  // r: half uniform in (1e-6, 1 - 1e-6), half log-uniform towards both ends.
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<double> rs;
  for (int i = 0; i < 60; ++i) rs.push_back(1e-6 + (1 - 2e-6) * U(g));
  for (int i = 0; i < 20; ++i) rs.push_back(std::pow(10.0, -6 * U(g)));
  for (int i = 0; i < 20; ++i) rs.push_back(1 - std::pow(10.0, -6 * U(g)));
  rs.push_back(1e-6);
  rs.push_back(1 - 1e-6);

  // Tolerances.  Symbols: the kernel (unit_start: exact power-of-two scaling) and the scalar loop (divided by
  // its rounded norm: 2 eps relative per coordinate) evaluate alpha*y - x on inputs a few eps apart, each with
  // one rounding of alpha*y (FMA contraction may skip it): they can only differ within 8 eps of a boundary.
  // Definition 2.1 decides by the signs of q.v built from cross products, each off by about eps * condition
  // (its own estimate, CrossProductImage::condition): it can only differ within 8 eps * condition.
  const auto kSymbolKernel = ulps(8, "kernel and scalar loop symbols differ only within 8 eps of a boundary");
  // Directions.  Kernel and scalar loop: two products P q with forward error <= gamma_3 kappa each
  // (product_condition), plus the normalisations (2 eps): 2 (3.1 eps kappa) + 4 eps <= 8 eps kappa.
  // Definition 2.1: eps * condition radians (its estimate) from the cross products; 8 eps * condition.
  std::size_t points = 0, boundary_cases = 0, def21_checked = 0, def21_degenerate = 0, def21_breakdowns = 0;
  double worst_kernel = 0, worst_def21 = 0;  // measured error / tolerance
  for (double r : rs) {
    const std::vector<Sample> ss = samples(r, g);
    iterate::Ensemble e;
    e.r = {r};
    for (const Sample& s : ss) e.initial.push_back(s.u);
    const FirstStep batched = first_step(e, true), scalar = first_step(e, false);
    for (std::size_t i = 0; i < ss.size(); ++i) {
      const Sample& s = ss[i];
      SCOPED_TRACE(::testing::Message() << s.kind << " r = " << r << " u = (" << s.u(0) << ", " << s.u(1) << ", "
                                        << s.u(2) << ")");
      ++points;
      const Vec3<double>& ub = batched.u[i];
      const Vec3<double>& us = scalar.u[i];
      ASSERT_TRUE(ub.allFinite() && ub.norm() > 0) << ub.transpose();
      ASSERT_TRUE(us.allFinite() && us.norm() > 0) << us.transpose();
      const double d = boundary_distance(s.u, r);
      if (batched.sym[i] != scalar.sym[i]) {
        EXPECT_SMALL(d, kSymbolKernel) << "kernel symbol " << batched.sym[i] << ", scalar loop " << scalar.sym[i];
        ++boundary_cases;
        continue;
      }
      const double kappa = product_condition(scalar.sym[i], r, s.u);
      const double tol = 8 * eps * kappa;
      const double dk = projective_distance(ub, us);
      EXPECT_SMALL(dk, ulps(8, "two products P q, gamma_3 kappa each, and the normalisations").of(kappa))
          << "kernel " << ub.transpose() << " vs scalar loop " << us.transpose();
      worst_kernel = std::max(worst_kernel, dk / tol);

      // Definition 2.1 on the point brought into Q (its step 1 flips only x < 0; x = 0, z > 0 is the other
      // half of the same projective point).
      const Vec3<double> q = core::to_quadrant(s.u);
      const auto ref = reference::cross_product_map<double>(q, r);
      if (!(ref.u.allFinite() && ref.u.norm() > 0 && std::isfinite(ref.condition))) {
        // Definition 2.1 excludes x, y or z = 0 (ref.degenerate), and on a branch boundary the image lies on a
        // coordinate plane: a cross product vanishes (0/0) and the literal construction has no answer.  Allowed
        // only there: on a coordinate plane, or within 4 eps of a boundary (points put there by construction,
        // alpha*y rounded: within 1 eps).
        EXPECT_TRUE(ref.degenerate || d < 4 * eps)
            << "Definition 2.1 broke down away from the excluded planes, at distance " << d << ": "
            << ref.u.transpose();
        ++def21_breakdowns;
        continue;
      }
      if (ref.degenerate) ++def21_degenerate;
      ++def21_checked;
      const double tol21 = 8 * eps * ref.condition;
      if (symbol_of(ref.letters) != scalar.sym[i]) {
        EXPECT_SMALL(d, ulps(8, "Definition 2.1's signs are off by eps times its condition").of(ref.condition))
            << "Definition 2.1 letters " << ref.letters << ", scalar loop " << scalar.sym[i] << " (condition "
            << ref.condition << ")";
        ++boundary_cases;
        continue;
      }
      const double d21 = projective_distance(ref.u, us);
      EXPECT_SMALL(d21, ulps(8, "Definition 2.1's and the scalar loop's errors added").of(ref.condition + kappa))
          << "Definition 2.1 " << ref.u.transpose() << " vs scalar loop " << us.transpose();
      worst_def21 = std::max(worst_def21, d21 / (tol21 + tol));
    }
  }
  std::printf(
      "%zu points, %zu symbol differences within rounding of a boundary, %zu through Definition 2.1 "
      "(%zu degenerate, %zu breakdowns on a boundary); worst error/tolerance: kernel %.3f, Definition 2.1 %.3f\n",
      points, boundary_cases, def21_checked, def21_degenerate, def21_breakdowns, worst_kernel, worst_def21);
  EXPECT_GT(def21_checked, points / 2);  // the comparison with Definition 2.1 is not vacuous
}

TEST(Properties, LongRandomOrbitsStayFiniteAtExtremeR) {
  // 2000 steps from random points scaled by 1e-300 at r near both ends of (0, 1): every state of the kernel stays
  // finite and non-zero (the renormalisation keeps it in the normal range).
  iterate::Ensemble e;
  e.r = {1e-6, 1e-3, 0.0717, 0.5, 0.999, 1 - 1e-6};
  e.initial = iterate::random_points(64, 11);
  for (auto& u : e.initial) u *= 1e-300;  // scaled starts
  iterate::FinalRecorder f(e.orbits(), 2000);
  iterate::SymbolRecorder sym(e.orbits(), 1, 2000);
  iterate::Both<iterate::FinalRecorder, iterate::SymbolRecorder> rec(f, sym);
  iterate::run<double>(e, 2000, rec);
  // A NaN or infinity anywhere in an orbit stays in its final state; the symbols are all 1, 2 or 3.
  for (const auto& u : f.out) ASSERT_TRUE(u.allFinite() && u.norm() > 0.5) << u.transpose();
  for (auto s : sym.out) ASSERT_TRUE(s >= 1 && s <= 3) << int(s);
}
