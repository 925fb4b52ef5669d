// SPDX-License-Identifier: GPL-3.0-or-later
// Lyapunov exponents: periodic orbits against eigenvalues of period matrices, quasi-periodic orbits, the two QR
// routes against each other, the batched TangentRecorder against the QR route, finite differences, errors.
#include "core/map.hpp"
#include "core/scalar.hpp"
#include "iterate/cocycle.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"
#include "lyapunov/orbit.hpp"
#include "lyapunov/tangent.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include "reference_tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

using namespace btob;
using V3 = Eigen::Vector3d;

std::string word(const std::vector<int>& s) {
  std::string w;
  for (int x : s) w += static_cast<char>('0' + x);
  return w;
}
// True when a is a rotation of b (same cyclic word).
bool same_cycle(const std::string& a, const std::string& b) {
  return a.size() == b.size() && (b + b).find(a) != std::string::npos;
}

// The dominant real eigenvector of M, brought into Q.
V3 dominant_eigenvector(const Eigen::Matrix3d& M) {
  Eigen::EigenSolver<Eigen::Matrix3d> es(M);
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(es.eigenvalues()(i)) > std::abs(es.eigenvalues()(k))) k = i;
  const V3 v = es.eigenvectors().col(k).real();
  return core::to_quadrant<double>(v.normalized());
}

// (ab)^n(cb)^n: symbols 1^n 3^n, period matrix P3^n P1^n.
Eigen::Matrix3d ab_cb(int n, double r) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  for (int i = 0; i < n; ++i) M = core::P1(r) * M;
  for (int i = 0; i < n; ++i) M = core::P3(r) * M;
  return M;
}

// Table B.1 (reference CSV): lower and upper bounds of the window of (ab)^n(cb)^n.
// Throws when the table is missing or short, or has no row n (a test must not run on a made-up window).
std::pair<double, double> window(int n) {
  for (const auto& row : btob::testing::table_b1().rows)
    if (std::stoi(row[0]) == n) return {std::stod(row[1]), row[2].empty() ? 3 - 2 * std::sqrt(2.0) : std::stod(row[2])};
  throw std::runtime_error("Table B.1 has no row n = " + std::to_string(n));
}

// Runs the projective route from u0, checks the detected period is `expected` (up to rotation) and that the
// exponents match the eigenvalues of the period matrix.  `periods` full periods are averaged (a whole number of
// periods: a partial period adds an O(1/n) term).
void check_periodic(double r, const V3& u0, const std::string& expected, long periods, double tol) {
  SCOPED_TRACE("r = " + std::to_string(r) + ", pattern " + expected);
  const long p = static_cast<long>(expected.size());
  lyapunov::Options o;
  o.transient = 20000;  // the orbit and the frame converge geometrically; 2e4 steps is far beyond what they need
  o.iterations = p * periods;
  o.blocks = 10;
  const auto res = lyapunov::projective_exponents<double>(u0, r, o);
  const int found = lyapunov::detect_period(res.symbols_tail, 64, 512);
  ASSERT_EQ(found, p);
  const std::vector<int> period(res.symbols_tail.end() - p, res.symbols_tail.end());
  EXPECT_TRUE(same_cycle(word(period), expected)) << word(period);
  const auto ref = lyapunov::periodic_exponents(period, r);
  const auto plain = bound(tol, "the plain average's C / n frame term at this many periods");
  EXPECT_CLOSE(res.lambda[0].value, ref[0], plain);
  EXPECT_CLOSE(res.lambda[1].value, ref[1], plain);
  // The weighted Birkhoff averages: 1e-8 on every periodic orbit, real or complex subdominant eigenvalues.
  const auto weighted = bound(1e-8, "weighted Birkhoff averages on a periodic orbit, real or complex eigenvalues");
  EXPECT_CLOSE(res.weighted[0], ref[0], weighted);
  EXPECT_CLOSE(res.weighted[1], ref[1], weighted);
  // lambda1 + lambda2 = (log|det M| - 3 log|M u|) / p is exact on the orbit (no frame term): what is left is the
  // rounding of ~1e6 summed logarithms.
  EXPECT_CLOSE(res.lambda[0].value + res.lambda[1].value, ref[0] + ref[1],
               ulps(45000, "~1e6 summed logs of O(1) values: a random walk of ~1e3 eps (measured 78)"));
}

TEST(Lyapunov, DerivativeMatchesCentralDifferences) {
  // D(u) v against (F(u + h v) - F(u - h v)) / 2h, F(u) = P u / |P u|, at points inside each branch.
  const double r = 0.3;
  for (const V3& u : {V3(0.3, 0.9, -0.2), V3(0.7, 0.0, -0.7), V3(0.2, -0.9, -0.3)}) {
    const V3 q = u.normalized();
    const int s = core::branch(q, r);
    const Eigen::Matrix3d P = core::P<double>(s, r);
    const auto D = lyapunov::projective_derivative<double>(P, q);
    const auto T = lyapunov::tangent_basis<double>(q);
    for (int j = 0; j < 2; ++j) {
      const V3 v = T.col(j);
      const double h = 1e-6;
      const V3 a = P * (q + h * v), b = P * (q - h * v);
      const V3 fd = (a / a.norm() - b / b.norm()) / (2 * h);
      // central differences: O(h^2) truncation + O(eps/h) rounding ~ 1e-10; 1e-8 leaves room.
      EXPECT_SMALL((D * v - fd).norm(), bound(1e-8, "central differences: h^2 truncation + eps / h rounding ~1e-10"))
          << "branch " << s;
      EXPECT_CLOSE((D * v).dot(P * q), 0.0, ulps(45, "D v is tangent at the image: roundings of O(1) products"));
    }
  }
}

TEST(Lyapunov, PeriodicOrbit1133AtR015) { check_periodic(0.15, V3(1, -0.9, -0.2), "1133", 100000, 1e-8); }
TEST(Lyapunov, PeriodicOrbit111333AtR01) { check_periodic(0.1, V3(1, -0.9, -0.2), "111333", 100000, 1e-8); }

TEST(Lyapunov, PeriodicOrbit132312) {
  // Theorem (Stability of 132312): the periodic point is the dominant eigenvector of J P2 P3 P1.  Its
  // subdominant eigenvalues are a complex pair, so the tangent frame rotates and the plain finite-time exponents
  // converge like C / n with C up to ~0.5 (measured): 1e-7 at n = 6e6; the weighted averages reach 1e-8.
  for (double r : {0.3, 0.5}) {
    const Eigen::Matrix3d M = core::J<double>() * core::P2(r) * core::P3(r) * core::P1(r);
    check_periodic(r, dominant_eigenvector(M), "132312", 1000000, 1e-7);
  }
}

TEST(Lyapunov, PeriodicOrbitsAbCbInTheirWindows) {
  for (int n = 2; n <= 6; ++n) {
    const auto [lo, hi] = window(n);
    ASSERT_GT(hi, lo) << "Table B.1 row " << n;
    const double r = (lo + hi) / 2;
    std::string w = std::string(n, '1') + std::string(n, '3');
    check_periodic(r, dominant_eigenvector(ab_cb(n, r)), w, 1000000 / n, 1e-8);
  }
}

TEST(Lyapunov, QuasiPeriodicOrbitsAroundTheP2Centre) {
  // Section 5.2: for r > 3 - 2 sqrt2 the P2 fixed point (1,0,-1) is a centre; nearby orbits stay on invariant
  // curves inside the P2 region, where all eigenvalues of P2 have modulus r: both exponents are 0.
  for (double r : {0.2, 0.3}) {
    lyapunov::Options o;
    o.transient = 1000;
    o.iterations = 1000000;
    const auto res = lyapunov::projective_exponents<double>(V3(1, 0.02, -1), r, o);
    for (int s : res.symbols_tail) ASSERT_EQ(s, 2) << "the orbit left the P2 region";
    // 1e-4: the brief's bound; the bounded-frame term log(kappa)/n is ~1e-6 here.
    const auto briefs = bound(1e-4, "the brief's bound; the frame term log(kappa) / n is ~1e-6 here");
    EXPECT_SMALL(res.lambda[0].value, briefs);
    EXPECT_SMALL(res.lambda[0].value,
                 statistical(3 * res.lambda[0].error + 1e-6, "3 error bars of 0, plus the frame term"))
        << "not within 3 error bars of 0";
    EXPECT_SMALL(res.lambda[1].value, briefs);
  }
}

TEST(Lyapunov, ProjectiveEqualsLinearDifferences) {
  // lambda_i = chi_{i+1} - chi_1 step by step (same orbit, frames [u0, e1, e2]): equal up to rounding.
  struct Case {
    double r;
    V3 u;
    long n;
  };
  for (const Case& c : {Case{0.15, V3(1, -0.9, -0.2), 200000}, Case{0.3, V3(1, 0.02, -1), 200000},
                        Case{0.11, V3(1, -0.9, -0.2), 200000}, Case{0.5, V3(0.3, 0.5, -0.6), 200000}}) {
    for (int m : {1, 3}) {
      lyapunov::Options o;
      o.transient = 1000;
      o.iterations = c.n;
      o.reorthonormalise = m;
      const auto p = lyapunov::projective_exponents<double>(c.u, c.r, o);
      const auto l = lyapunov::linear_exponents<double>(c.u, c.r, o);
      const auto tol = ulps(45000, "sums of 2e5 logs in different orders: a random walk of ~450 eps (measured 18)");
      EXPECT_CLOSE(l.chi[1].value - l.chi[0].value, p.lambda[0].value, tol) << "r=" << c.r << " m=" << m;
      EXPECT_CLOSE(l.chi[2].value - l.chi[0].value, p.lambda[1].value, tol) << "r=" << c.r << " m=" << m;
    }
  }
}

TEST(Lyapunov, ChaoticBetweenWindowsIsPositiveAndPrecisionIndependent) {
  // r = 0.11 lies between the windows n = 2 (from 0.1275) and n = 3 (up to 0.1010): lambda1 > 0, the same in
  // double and long double within the error bars (different rounding, different orbits, same statistics).
  lyapunov::Options o;
  o.transient = 1000;
  o.iterations = 100000;
  const auto d = lyapunov::projective_exponents<double>(V3(1, -0.9, -0.2), 0.11, o);
  const auto q =
      lyapunov::projective_exponents<long double>(Eigen::Matrix<long double, 3, 1>(1, -0.9L, -0.2L), 0.11L, o);
  EXPECT_GT(d.lambda[0].value, 10 * d.lambda[0].error);
  EXPECT_CLOSE(d.lambda[0].value, q.lambda[0].value,
               statistical(5 * (d.lambda[0].error + q.lambda[0].error), "5 error bars of two chaotic estimates"));
}

TEST(Lyapunov, EveryPrecisionOnTheSink1133) {
  // Every precision: the cocycle runs in float, double, long double, float128 and MPFR.  On the sink 1133 at r = 0.15
  // the weighted averages of 2e4 steps (after a 2000-step transient) must give the period matrix's exponents:
  // float to 1e-5 (measured 2.9e-7: float's eps 1.2e-7 times the O(1) condition of the step), the others to
  // 1e-12 (the weighted average converges super-polynomially; what remains is the double of the reference and
  // of the reported value, ~1e-15).
  const double r = 0.15;
  lyapunov::Options o;
  o.transient = 2000;
  o.iterations = 20000;
  o.blocks = 10;
  const auto d = lyapunov::projective_exponents<double>(V3(1, -0.9, -0.2), r, o);
  const int p = lyapunov::detect_period(d.symbols_tail, 64, 512);
  ASSERT_EQ(p, 4);
  const std::vector<int> period(d.symbols_tail.end() - p, d.symbols_tail.end());
  const auto ref = lyapunov::periodic_exponents(period, r);
  const auto f = lyapunov::projective_exponents<float>(Eigen::Vector3f(1, -0.9f, -0.2f), float(r), o);
  const auto in_float = ulps<float>(83, "float's eps times the O(1) condition of the step (measured 2.4 eps)");
  EXPECT_CLOSE(f.weighted[0], ref[0], in_float);
  EXPECT_CLOSE(f.weighted[1], ref[1], in_float);
  // What remains of the others is the double rounding of the reference and of the reported value.
  const auto wide = ulps(45, "the reference's and the reported value's rounding to double, ~1e-15 (measured 3.5 eps)");
  EXPECT_CLOSE(d.weighted[0], ref[0], wide);
  using core::float128;
  using core::mpfr_float;
  const auto q = lyapunov::projective_exponents<float128>(
      Eigen::Matrix<float128, 3, 1>(1, float128(-0.9), float128(-0.2)), float128(r), o);
  EXPECT_CLOSE(q.weighted[0], ref[0], wide);
  EXPECT_CLOSE(q.weighted[1], ref[1], wide);
  mpfr_float::default_precision(50);
  const auto m = lyapunov::projective_exponents<mpfr_float>(
      Eigen::Matrix<mpfr_float, 3, 1>(mpfr_float(1), mpfr_float(-0.9), mpfr_float(-0.2)), mpfr_float(r), o);
  EXPECT_CLOSE(m.weighted[0], ref[0], wide);
  EXPECT_CLOSE(m.weighted[1], ref[1], wide);
  // The linear route in MPFR: chi2 - chi1 is the same exponent (the two routes, in high precision).
  const auto lin = lyapunov::linear_exponents<mpfr_float>(
      Eigen::Matrix<mpfr_float, 3, 1>(mpfr_float(1), mpfr_float(-0.9), mpfr_float(-0.2)), mpfr_float(r), o);
  EXPECT_CLOSE(lin.weighted[1] - lin.weighted[0], ref[0], wide);
}

TEST(Lyapunov, FiniteDifferencesStraddleBoundaries) {
  // Just below the upper end 3 - 2 sqrt2 of the 1133 window the periodic orbit passes close to a branch
  // boundary.  A finite-difference partner at distance delta lands on the other branch at every period: the
  // map is discontinuous there, the separation jumps to O(1), and the estimate is wrong (even positive),
  // while the tangent cocycle gives the eigenvalue answer.
  const double r = 0.1715;
  const V3 u0(1, -0.9, -0.2);
  lyapunov::Options o;
  o.transient = 20000;
  o.iterations = 4 * 25000;
  const auto res = lyapunov::projective_exponents<double>(u0, r, o);
  ASSERT_EQ(lyapunov::detect_period(res.symbols_tail, 16, 256), 4);
  const std::vector<int> period(res.symbols_tail.end() - 4, res.symbols_tail.end());
  const auto ref = lyapunov::periodic_exponents(period, r);
  EXPECT_CLOSE(res.lambda[0].value, ref[0], bound(1e-8, "the plain average's C / n frame term"));
  // The smallest relative distance of the orbit to a branch boundary, alpha y - x = 0 or alpha y - z = 0.
  double dmin = 1;
  {
    lyapunov::Options s = o;
    s.iterations = 4;
    s.blocks = 2;
    V3 u = res.final_point;
    for (int k = 0; k < 8; ++k) {
      const double a = core::alpha(r);
      dmin = std::min(
          {dmin, std::abs(a * u(1) - u(0)) / std::hypot(a, 1.0), std::abs(a * u(1) - u(2)) / std::hypot(a, 1.0)});
      u = core::step(u, r).u.normalized();
    }
  }
  const auto fd = lyapunov::finite_difference_exponent(u0, r, 10 * dmin, o);
  EXPECT_GT(fd.straddles, 1000);
  EXPECT_GT(std::abs(fd.lambda1 - ref[0]), 0.1) << "finite differences should be wrong here";
  // And far from boundaries (delta 1e-3 of the distance) finite differences are right to O(delta).
  const auto ok = lyapunov::finite_difference_exponent(u0, r, 1e-3 * dmin, o);
  EXPECT_EQ(ok.straddles, 0);
  EXPECT_CLOSE(ok.lambda1, ref[0], bound(1e-3, "finite differences with delta 1e-3 of the distance: O(delta)"));
}

TEST(Lyapunov, BatchedRecorderMatchesQrRoute) {
  iterate::Ensemble e;
  e.r = {0.0717, 0.15, 0.3, 0.11};
  e.initial = iterate::paper_grid();
  e.initial.resize(8);
  e.grid_description = "paper[0:8]";
  lyapunov::MapOptions mo;
  mo.transient = 1000;
  mo.iterations = 20000;
  mo.blocks = 10;
  mo.run.threads = 1;
  const auto m = lyapunov::map_exponents(e, mo);
  mo.run.threads = 2;
  const auto m2 = lyapunov::map_exponents(e, mo);
  EXPECT_EQ(m.lambda1, m2.lambda1);  // bitwise: threads never change results
  EXPECT_EQ(m.lambda2, m2.lambda2);
  lyapunov::Options o;
  o.transient = mo.transient;
  o.iterations = mo.iterations;
  o.blocks = mo.blocks;
  for (std::size_t k = 0; k < e.orbits(); ++k) {
    const double r = e.r[k / e.initial.size()];
    const auto p = lyapunov::projective_exponents<double>(e.initial[k % e.initial.size()], r, o);
    // Chaotic (r = 0.11): the orbits differ after ~50 steps, so 5 error bars; regular: the same orbit up to
    // rounding, the same exponent to ~1e-12.
    const auto tol = [&](double e1, double e2) {
      return r == 0.11 ? statistical(5 * (e1 + e2), "chaotic: two orbits, 5 error bars")
                       : ulps(4500, "regular: the same orbit up to rounding, exponents to ~1e-12 (measured 39 eps)");
    };
    EXPECT_CLOSE(m.lambda1[k], p.lambda[0].value, tol(p.lambda[0].error, m.err1[k])) << "orbit " << k << " r " << r;
    EXPECT_CLOSE(m.lambda2[k], p.lambda[1].value, tol(p.lambda[1].error, m.err2[k])) << "orbit " << k;
  }
  // The scalar reference kernel (one orbit at a time, normalised every step) with the same recorder.
  lyapunov::TangentRecorder rec(e, mo.transient, mo.iterations, mo.blocks);
  iterate::run_scalar<double>(e, rec.total_steps(), rec);
  const auto s = lyapunov::exponents_from(rec);
  for (std::size_t k = 0; k < 8; ++k)  // r = 0.0717: periodic
    EXPECT_CLOSE(s.lambda1[k], m.lambda1[k],
                 ulps(4500, "scalar loop and batched kernel round differently on a periodic orbit (measured 58 eps)"));
  const auto sum = lyapunov::summarise(m, e.r.size(), e.initial.size());
  EXPECT_EQ(sum.frac_positive[3], 1.0);  // r = 0.11: every orbit chaotic
  EXPECT_EQ(sum.frac_negative[1], 1.0);  // r = 0.15: every orbit on the stable 1133
}

// The fused cocycle kernel (map_exponents' double route) against the TangentRecorder on the plain kernel (v projected
// and normalised after every step): the points are the same bits (the same step code); the tangent vectors are the
// same vectors up to rounding (cocycle.hpp: projecting every K steps equals projecting every step), so the exponents
// agree far inside their error bars, on sinks, invariant curves and chaotic orbits alike.
TEST(Lyapunov, FusedCocycleMatchesTangentRecorder) {
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.0717, 0.6, 41);
  e.r.push_back(0.01);  // small r: the largest cancellation per projection interval (redone blocks)
  e.r.push_back(0.95);
  e.initial = iterate::paper_grid();
  e.grid_description = "paper";
  lyapunov::MapOptions mo;
  mo.transient = 500;
  mo.iterations = 5000;
  mo.blocks = 10;
  mo.run.threads = 2;
  std::size_t redone = 0;
  mo.run.redone = &redone;
  const auto m = lyapunov::map_exponents(e, mo);
  lyapunov::TangentRecorder rec(e, mo.transient, mo.iterations, mo.blocks);
  iterate::run<double>(e, rec.total_steps(), rec);
  const auto t = lyapunov::exponents_from(rec);
  double worst = 0;
  for (std::size_t k = 0; k < e.orbits(); ++k) {
    // Projecting every 16 steps keeps >= 22 correct bits of w per block (cocycle.hpp); its rounding, random from
    // block to block, moves an exponent by <= 2^-22 sqrt(n / 16) / n ~ 1e-8 here; measured 2.0e-13.
    const auto tol = bound(1e-11, "same orbit, same vectors up to rounding: measured 2.0e-13");
    EXPECT_CLOSE(m.lambda1[k], t.lambda1[k], tol) << "orbit " << k << " r " << e.r[k / 32];
    EXPECT_CLOSE(m.lambda2[k], t.lambda2[k], tol) << "orbit " << k << " r " << e.r[k / 32];
    EXPECT_CLOSE(m.chi1[k], t.chi1[k], tol) << "orbit " << k << " r " << e.r[k / 32];
    worst = std::max({worst, std::abs(m.lambda1[k] - t.lambda1[k]), std::abs(m.lambda2[k] - t.lambda2[k])});
  }
  const std::size_t blocks =
      e.orbits() * static_cast<std::size_t>((mo.transient + mo.iterations) / iterate::cocycle_interval<double>());
  std::printf("fused vs recorder: worst |dlambda| %.3g over %zu orbits, %zu (orbit, block) pairs redone of %zu\n",
              worst, e.orbits(), redone, blocks);
  EXPECT_LT(redone, blocks / 20)
      << "the redo is for the worst blocks only (measured 2.4%; the orbits at r = 0.01 are 2.3% of the ensemble)";
}

// The float cocycle (point, tangent vector and projections in float) against the double one: on sinks and invariant
// curves the same attractor, exponents within a few float rounding errors per block; between windows (chaotic) both
// positive and within their error bars.
TEST(Lyapunov, FloatCocycleAgreesWithDouble) {
  iterate::Ensemble e;
  e.r = {0.0717, 0.1, 0.11, 0.15, 0.2, 0.21, 0.3, 0.45, 0.6};
  e.initial = iterate::paper_grid();
  e.grid_description = "paper";
  lyapunov::MapOptions mo;
  mo.transient = 1000;
  mo.iterations = 10000;
  mo.blocks = 10;
  const auto d = lyapunov::map_exponents(e, mo);
  mo.single_precision = true;
  std::size_t redone = 0;
  mo.run.redone = &redone;
  const auto f = lyapunov::map_exponents(e, mo);
  int classes_differ = 0;
  double chaotic_diff = 0, chaotic_var = 0;
  for (std::size_t k = 0; k < e.orbits(); ++k) {
    const double r = e.r[k / e.initial.size()];
    const double bars = std::hypot(f.err1[k], d.err1[k]);
    classes_differ += lyapunov::classify(f.lambda1[k], f.err1[k], mo.iterations) !=
                      lyapunov::classify(d.lambda1[k], d.err1[k], mo.iterations);
    if (r == 0.11) {
      // Chaotic: float and double follow other orbits after a few dozen steps, so the two exponents are independent
      // estimates of one value, each with a batch-means error bar from 10 blocks (Student's t with 9 degrees of
      // freedom).  Per orbit, 6 bars: P(|t_9| > 6) ~ 2e-4, below 1% for the 32 orbits together (3 bars leave
      // P(|t_9| > 3) ~ 1.5% per orbit, a false failure in about a third of the runs); and the mean over the 32
      // within 3 standard errors, which still sees a systematic shift of float's exponents.
      EXPECT_CLOSE(f.lambda1[k], d.lambda1[k], statistical(6 * bars, "6 error bars of t_9 over 32 orbits"))
          << "orbit " << k << " r " << r;
      chaotic_diff += f.lambda1[k] - d.lambda1[k];
      chaotic_var += bars * bars;
      continue;
    }
    // Regular orbits: the same attractor; float's cocycle rounds ~1e-6 away (measured 1.05e-6 at r = 0.0717,
    // 5e-7 at 0.15: ~16 float epsilons of |lambda|, the projections' rounding).
    EXPECT_CLOSE(f.lambda1[k], d.lambda1[k],
                 statistical(3 * bars + 5e-6, "3 error bars + float's rounding of the cocycle (~16 eps_f |lambda|)"))
        << "orbit " << k << " r " << r;
  }
  EXPECT_EQ(classes_differ, 0);
  EXPECT_CLOSE(chaotic_diff, 0.0, statistical(3 * std::sqrt(chaotic_var), "3 standard errors of the 32 orbits' sum"))
      << "mean float - double exponent over the chaotic orbits";
  EXPECT_LT(redone, e.orbits() * 11000 / 8 / 100) << "more than 1% of float blocks redone";
}

TEST(Lyapunov, ErrorsNameTheField) {
  const auto msg = [](lyapunov::Options o) {
    try {
      lyapunov::validate(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  lyapunov::Options o;
  o.iterations = 0;
  EXPECT_EQ(msg(o).rfind("iterations: got 0", 0), 0u);
  o = {};
  o.transient = -1;
  EXPECT_EQ(msg(o).rfind("transient: got -1", 0), 0u);
  o = {};
  o.reorthonormalise = 0;
  EXPECT_EQ(msg(o).rfind("reorthonormalise: got 0", 0), 0u);
  o = {};
  o.iterations = 5;
  EXPECT_EQ(msg(o).rfind("blocks: got 20, expected at most iterations = 5", 0), 0u);
  EXPECT_THROW(lyapunov::projective_exponents<double>(V3(1, 0, -1), 1.5, {}), core::InvalidField);
  EXPECT_THROW(lyapunov::projective_exponents<double>(V3(1, 0, 1), 0.5, {}), core::InvalidField);
  EXPECT_EQ(lyapunov::classify(0.01, 0.001, 100000), 1);
  EXPECT_EQ(lyapunov::classify(-0.01, 0.001, 100000), -1);
  EXPECT_EQ(lyapunov::classify(0.002, 0.001, 100000), 0);
}

}  // namespace

// Ordered exponents: lambda1 (one tangent vector) is not always the larger exponent in finite time.  Over r in [0.18,
// 0.22] (invariant curves of the P2 rotation, both exponents 0, and sinks) lambda2 > lambda1 in about half the
// entries, but never by more than 3 sqrt(err1^2 + err2^2) + 10/n: the finite-time floor of a bounded cocycle that the
// batch-means errors do not see (maps.hpp).  lambda_max, lambda_min are the two ordered, each with its own error.
TEST(Lyapunov, OrderedExponentsAndTheirErrors) {
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.18, 0.22, 41);
  e.initial = iterate::paper_grid();
  lyapunov::MapOptions mo;
  mo.transient = 1000;
  mo.iterations = 10000;
  const auto m = lyapunov::map_exponents(e, mo);
  long reversed = 0;
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    const bool swap = m.lambda2[o] > m.lambda1[o];
    reversed += swap;
    EXPECT_GE(m.lambda_max[o], m.lambda_min[o]);
    EXPECT_EQ(m.lambda_max[o], swap ? m.lambda2[o] : m.lambda1[o]);
    EXPECT_EQ(m.err_max[o], swap ? m.err2[o] : m.err1[o]);  // each error travels with its exponent
    EXPECT_EQ(m.lambda_min[o], swap ? m.lambda1[o] : m.lambda2[o]);
    EXPECT_EQ(m.err_min[o], swap ? m.err1[o] : m.err2[o]);
    EXPECT_LE(m.lambda2[o] - m.lambda1[o], 3 * std::hypot(m.err1[o], m.err2[o]) + 10.0 / mo.iterations)
        << "orbit " << o;
  }
  std::printf("r in [0.18, 0.22], 41 x 32 orbits: lambda2 > lambda1 in %ld\n", reversed);
  EXPECT_GT(reversed, 0);  // as observed: the order is not a property of lambda1 alone
}

// The per-r summary carries the error of each statistic: the errors of the orbits realising min and max, and for the
// median that of the middle orbit (odd count) or half the root sum of squares of the two middle ones (even count).
TEST(Lyapunov, SummaryErrorBarsFollowTheirOrbits) {
  lyapunov::OrbitExponents e;
  e.iterations = 1000;
  e.lambda1 = {3, 1, 2, 4, /* r 2: */ -1, 5, 0.5};
  e.err1 = {0.3, 0.1, 0.2, 0.4, /* r 2: */ 0.01, 0.05, 0.005};
  const auto even = lyapunov::summarise(e, 1, 4);
  EXPECT_EQ(even.min[0], 1);
  EXPECT_EQ(even.err_min[0], 0.1);
  EXPECT_EQ(even.max[0], 4);
  EXPECT_EQ(even.err_max[0], 0.4);
  EXPECT_EQ(even.median[0], 2.5);
  EXPECT_DOUBLE_EQ(even.err_median[0], 0.5 * std::sqrt(0.2 * 0.2 + 0.3 * 0.3));
  e.lambda1.erase(e.lambda1.begin(), e.lambda1.begin() + 4);
  e.err1.erase(e.err1.begin(), e.err1.begin() + 4);
  const auto odd = lyapunov::summarise(e, 1, 3);
  EXPECT_EQ(odd.median[0], 0.5);
  EXPECT_EQ(odd.err_median[0], 0.005);
  EXPECT_EQ(odd.min[0], -1);
  EXPECT_EQ(odd.err_min[0], 0.01);
  EXPECT_EQ(odd.max[0], 5);
  EXPECT_EQ(odd.err_max[0], 0.05);
}

namespace {
// The one-orbit route (projective_orbit) against the kernel: r = 15/128 (exact in every precision, chaotic between the
// windows n = 3 and n = 2), the symbols of the last 4096 of 12000 steps.  The kernel's SymbolRecorder sees the same
// orbit only if the single-orbit step is the kernel's step with its roundings.
template <class T> void expect_the_kernels_orbit(const char* what) {
  SCOPED_TRACE(what);
  const double r = 0.1171875;
  lyapunov::Options o;
  o.transient = 2000;
  o.iterations = 10000;
  o.blocks = 10;
  const Eigen::Matrix<T, 3, 1> u0(T(1), T(-0.5), T(-1.1));
  const auto res = lyapunov::projective_orbit<T>(u0, T(r), o);
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {V3(1, -0.5, -1.1)};
  const long total = o.transient + o.iterations;
  iterate::SymbolRecorder rec(1, total - 4095, total);
  iterate::run<T>(e, total, rec);
  ASSERT_EQ(res.symbols_tail.size(), 4096u);
  long differ = 0;
  for (std::size_t i = 0; i < 4096; ++i) differ += res.symbols_tail[i] != rec.out[i];
  EXPECT_EQ(differ, 0);
}

// lambda1 of a periodic orbit from the eigenvalues of its period matrix, computed here in long double (the library's
// periodic_exponents works in double): log |l2 / l1| / p.
long double sink_lambda1(const std::vector<int>& period, long double r) {
  using M3 = Eigen::Matrix<long double, 3, 3>;
  M3 M = M3::Identity();
  for (int s : period) M = core::P<long double>(s, r) * M;
  const Eigen::EigenSolver<M3> es(M, false);
  std::array<long double, 3> mod;
  for (int i = 0; i < 3; ++i) mod[static_cast<std::size_t>(i)] = std::abs(es.eigenvalues()(i));
  std::sort(mod.begin(), mod.end(), std::greater<>());
  return std::log(mod[1] / mod[0]) / static_cast<long double>(period.size());
}
}  // namespace

TEST(LyapunovOrbit, TheOrbitIsTheKernelsBitForBit) {
  // Fails on the QR route (P_s u instead of the kernel's M_s u = P_s u / r: other roundings, another chaotic orbit).
  expect_the_kernels_orbit<double>("double");
  expect_the_kernels_orbit<float>("float");
  expect_the_kernels_orbit<long double>("long double");
  core::MpfrDigits digits(30);
  expect_the_kernels_orbit<core::mpfr_float>("mpfr 30 digits");
}

TEST(LyapunovOrbit, SinkExponentIsThePeriodMatrixEigenvaluesWithinTheErrorBar) {
  // The sink 1133 at r = 0.15 from (1, -0.5, -1.1): the plain average is the period matrix's exponent within the
  // reported error bar (whose floor includes what the deferred Gram-Schmidt can lose), and the weighted average to
  // the double rounding of both values.
  const double r = 0.15;
  lyapunov::Options o;
  o.transient = 2000;
  o.iterations = 4 * 25000;
  o.blocks = 10;
  const auto res = lyapunov::projective_orbit<double>(V3(1, -0.5, -1.1), r, o);
  ASSERT_EQ(lyapunov::detect_period(res.symbols_tail, 64, 512), 4);
  const std::vector<int> period(res.symbols_tail.end() - 4, res.symbols_tail.end());
  EXPECT_TRUE(same_cycle(word(period), "1133")) << word(period);
  const long double exact = sink_lambda1(period, 0.15L);
  EXPECT_NEAR(static_cast<double>(exact), -0.4683473803358724, 1e-15);  // the value quoted for this sink
  EXPECT_CLOSE(res.lambda[0].value, static_cast<double>(exact),
               statistical(res.lambda[0].error, "the route's own error bar (batch means and its rounding floor)"));
  EXPECT_CLOSE(res.weighted[0], static_cast<double>(exact),
               bound(1e-12,
                     "the weighted average over Gram-Schmidt intervals of uneven length: a midpoint rule of the "
                     "smooth weight, far below the plain average's C / n"));
  core::MpfrDigits digits(50);
  using core::mpfr_float;
  const auto m = lyapunov::projective_orbit<mpfr_float>(
      Eigen::Matrix<mpfr_float, 3, 1>(mpfr_float(1), mpfr_float(-0.5), mpfr_float(-1.1)), mpfr_float(r), o);
  EXPECT_CLOSE(m.lambda[0].value, static_cast<double>(exact),
               statistical(m.lambda[0].error, "the MPFR route's own error bar"));
  // MPFR at 100 digits: the weighted pass reads long double states, so the interval keeps the projection's
  // cancellation within long double's bits, not MPFR's (with B from 332 bits the weighted lambda1 was 4.9e-6 off).
  core::MpfrDigits digits100(100);
  const auto m100 = lyapunov::projective_orbit<mpfr_float>(
      Eigen::Matrix<mpfr_float, 3, 1>(mpfr_float(1), mpfr_float(-0.5), mpfr_float(-1.1)), mpfr_float(r), o);
  EXPECT_CLOSE(m100.weighted[0], static_cast<double>(exact),
               bound(1e-12, "as double's weighted average above: the per-step logs from long double states"));
}

TEST(LyapunovOrbit, AgreesWithTheQrRouteWithinTheErrorBars) {
  // The chaotic orbit (r = 0.12 from (1, -0.5, -1.1)): the one-orbit route, the QR route and the one-orbit
  // route in MPFR follow different orbits after the Lyapunov time (other roundings), so they agree in distribution:
  // within 5 error bars of the difference.
  lyapunov::Options o;
  o.transient = 1000;
  o.iterations = 200000;
  const V3 u0(1, -0.5, -1.1);
  const auto fast = lyapunov::projective_orbit<double>(u0, 0.12, o);
  const auto qr = lyapunov::projective_exponents_qr<double>(u0, 0.12, o);
  core::MpfrDigits digits(30);
  using core::mpfr_float;
  lyapunov::Options om = o;
  om.iterations = 40000;
  const auto mp = lyapunov::projective_orbit<mpfr_float>(
      Eigen::Matrix<mpfr_float, 3, 1>(mpfr_float(1), mpfr_float(-0.5), mpfr_float(-1.1)), mpfr_float("0.12"), om);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_GT(fast.lambda[i].error, 0.0);
    const double e_qr = std::hypot(fast.lambda[i].error, qr.lambda[i].error);
    EXPECT_CLOSE(fast.lambda[i].value, qr.lambda[i].value, statistical(5 * e_qr, "5 error bars of the difference"));
    const double e_mp = std::hypot(fast.lambda[i].error, mp.lambda[i].error);
    EXPECT_CLOSE(fast.lambda[i].value, mp.lambda[i].value, statistical(5 * e_mp, "5 error bars of the difference"));
  }
  EXPECT_GT(fast.lambda[0].value, 10 * fast.lambda[0].error);  // chaotic: lambda1 > 0
}

TEST(LyapunovOrbit, WeightedAverageOnTheWeaklyContractingSinkWeighsEveryStep) {
  // The precision study's hard case: the sink 312^150 (period 152, a complex pair, lambda1 = lambda2 = -0.0116) at
  // r = 0.171599 from the Section 4 grid's first point, 1e5 transient + 4e5 averaged steps.  With one weight per
  // Gram-Schmidt interval (~200 steps here) the weighted average was off by 1e-6 (a step-function weight converges
  // like C len / n); weighing every step (weighted.hpp) gives the period matrix's exponent as the QR route does.
  const double r = 0.171599;
  std::vector<int> word = {3, 1};
  word.insert(word.end(), 150, 2);
  lyapunov::Options o;
  o.transient = 100000;
  o.iterations = 400000;
  const auto res = lyapunov::projective_orbit<double>(iterate::paper_grid()[0], r, o);
  const auto qr = lyapunov::projective_exponents_qr<double>(iterate::paper_grid()[0], r, o);
  const long double exact = sink_lambda1(word, 0.171599L);
  // long double: the trace and the weighted pass in long double with libm (the path of float128 and MPFR too).
  const Eigen::Matrix<long double, 3, 1> u0 = iterate::paper_grid()[0].cast<long double>();
  const auto wide = lyapunov::projective_orbit<long double>(u0, core::from_decimal<long double>("0.171599"), o);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto why =
        "the weighted average of 4e5 steps of a period-152 orbit whose frame rotates: the precision "
        "study's bound (QR route, every step weighed: 1e-11 measured)";
    EXPECT_CLOSE(res.weighted[i], static_cast<double>(exact), bound(1e-10, why));
    EXPECT_CLOSE(wide.weighted[i], static_cast<double>(exact), bound(1e-10, why));
    EXPECT_CLOSE(res.weighted[i], qr.weighted[i],
                 bound(1e-12, "the same orbit and the same weights; the per-step logs from other roundings"));
  }
}
