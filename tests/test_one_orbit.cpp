// SPDX-License-Identifier: GPL-3.0-or-later
// One orbit, one verdict: every route takes the same branch (exactly), every tool reports the same exponents
// and the same stability word for the same orbit.  Seeded; about 1 s in the release build.
#include "attractors/attractors.hpp"
#include "attractors/recorders.hpp"
#include "attractors/requests.hpp"
#include "core/fields.hpp"
#include "core/map.hpp"
#include "core/request.hpp"
#include "core/scalar.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"
#include "patterns/patterns.hpp"
#include "reference/reference.hpp"
#include "tolerance.hpp"

#include <boost/multiprecision/gmp.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

using namespace btob;
using Q = boost::multiprecision::mpq_rational;
using core::Vec3;

namespace {

// r = k / 256: alpha = (256 + k) / 512 is exact in every precision (9 bits), so every route sees one map.
struct Case {
  double r;
  Vec3<double> u;  // in Q = {x >= 0, z <= 0}
  const char* kind;
};

// The branch by the rule's definition, in exact rational arithmetic: 1 if a y - x > 0, 3 if a y - z < 0, else 2.
int exact_branch(const Vec3<double>& u, double r) {
  const Q a = (Q(1) + Q(r)) / 2;
  if (a * Q(u(1)) - Q(u(0)) > 0) return 1;
  if (a * Q(u(1)) - Q(u(2)) < 0) return 3;
  return 2;
}

// Random r in (7 - 4 sqrt(3), 1) as k / 256, and points: random, on the branch lines a y = x and a y = z
// (the rounded product a y and its two neighbours: an exact tie when a y is a double, else the nearest
// non-ties), on the invariant planes x = 0 and z = 0, and near 7 - 4 sqrt(3) and 3 - 2 sqrt(2).
std::vector<Case> cases(std::mt19937_64& g, int n) {
  std::uniform_int_distribution<int> K(19, 255);  // 19 / 256 > 7 - 4 sqrt(3) = 0.0718
  std::uniform_real_distribution<double> U(0.05, 1);
  std::vector<Case> out;
  const int ks[] = {19, 44};  // 0.0742 (near 7 - 4 sqrt 3), 0.1719 (near 3 - 2 sqrt 2)
  for (int i = 0; i < n; ++i) {
    const double r = i % 8 < 2 ? ks[i % 2] / 256.0 : K(g) / 256.0;
    const double a = (1 + r) / 2;
    const double y = U(g), x = U(g), z = -U(g);
    const double ay = a * y, ayn = a * -y;
    for (double d : {-1.0, 0.0, 1.0}) {
      out.push_back({r, {std::nextafter(ay, ay + d), y, z}, "a y = x"});
      out.push_back({r, {x, -y, std::nextafter(ayn, ayn + d)}, "a y = z"});
    }
    out.push_back({r, {x, y * (i % 2 ? 1 : -1), z}, "random"});
    out.push_back({r, {0.0, y, z}, "x = 0"});
    out.push_back({r, {x, y, 0.0}, "z = 0"});
  }
  return out;
}

template <class T> std::vector<int> kernel_symbols(const std::vector<Case>& cs, std::size_t i0, std::size_t n) {
  iterate::Ensemble e;
  e.r = {cs[i0].r};
  for (std::size_t i = i0; i < i0 + n; ++i) e.initial.push_back(cs[i].u);
  iterate::SymbolRecorder rec(n, 1, 1);
  iterate::RunOptions one;
  one.threads = 1;  // one step of 9 orbits: an OpenMP team would cost more than the run
  iterate::run<T>(e, 1, rec, one);
  return std::vector<int>(rec.out.begin(), rec.out.end());
}

int def21_symbol(const Vec3<double>& u, double r) {
  using F = core::float128;
  const auto img = reference::cross_product_map<F>(Vec3<F>(F(u(0)), F(u(1)), F(u(2))), F(r));
  if (img.letters == "ab") return 1;
  if (img.letters == "cb") return 3;
  return 2;
}

}  // namespace

// Map.step (core::step), core::branch in every precision, one step of the kernel in every precision and
// Definition 2.1 (float128) take the branch of the exact rule; a point scaled by 2^k takes the same branch.
TEST(OneOrbit, EveryRouteTakesTheExactBranch) {
  std::mt19937_64 g(5);
  const std::vector<Case> cs = cases(g, 200);
  core::MpfrDigits digits(40);
  const std::size_t group = 9;  // cases() emits 9 points per r (one r per group)
  std::size_t ties = 0;
  for (std::size_t i0 = 0; i0 < cs.size(); i0 += group) {
    const std::vector<int> kf = kernel_symbols<float>(cs, i0, group), kd = kernel_symbols<double>(cs, i0, group),
                           kl = kernel_symbols<long double>(cs, i0, group),
                           kq = kernel_symbols<core::float128>(cs, i0, group),
                           km = kernel_symbols<core::mpfr_float>(cs, i0, group);
    for (std::size_t j = 0; j < group; ++j) {
      const Case& c = cs[i0 + j];
      SCOPED_TRACE(::testing::Message() << c.kind << " r = " << c.r << " u = (" << std::hexfloat << c.u(0) << ", "
                                        << c.u(1) << ", " << c.u(2) << ")");
      const int want = exact_branch(c.u, c.r);
      ties += want == 2 && std::string(c.kind).find('=') != std::string::npos;
      EXPECT_EQ(core::step<double>(c.u, c.r).symbol, want) << "Map.step";
      EXPECT_EQ(core::branch<long double>(c.u.cast<long double>(), (long double)c.r), want) << "long double";
      using F = core::float128;
      EXPECT_EQ(core::branch<F>(Vec3<F>(F(c.u(0)), F(c.u(1)), F(c.u(2))), F(c.r)), want) << "float128";
      using M = core::mpfr_float;
      EXPECT_EQ(core::branch<M>(Vec3<M>(M(c.u(0)), M(c.u(1)), M(c.u(2))), M(c.r)), want) << "mpfr";
      EXPECT_EQ(kd[j], want) << "kernel double";
      EXPECT_EQ(kl[j], want) << "kernel long double";
      EXPECT_EQ(kq[j], want) << "kernel float128";
      EXPECT_EQ(km[j], want) << "kernel mpfr";
      // float: only where the point is a float (the kernel reads the double point rounded to float).
      const Vec3<float> uf = c.u.cast<float>();
      if (uf.cast<double>() == c.u) {
        EXPECT_EQ(kf[j], want) << "kernel float";
        EXPECT_EQ(core::branch<float>(uf, float(c.r)), want) << "core float";
      }
      // Definition 2.1 in float128: a double point's a y - x is 0 or at least 2^-107 |x|, far outside its band.
      if (c.u(0) != 0 && c.u(2) != 0) EXPECT_EQ(def21_symbol(c.u, c.r), want) << "Definition 2.1";
      for (int k : {-1000, -500, -7, 9, 500, 900}) {
        const Vec3<double> s(std::ldexp(c.u(0), k), std::ldexp(c.u(1), k), std::ldexp(c.u(2), k));
        EXPECT_EQ(core::step<double>(s, c.r).symbol, want) << "scaled by 2^" << k;
      }
    }
  }
  EXPECT_GT(ties, 50u);  // the exact ties a y = x are there (a y is a double for many y)
}

// classify's lambda1 equals lyapunov's (single orbit, projective cocycle) within their stated errors, and on a
// periodic point classify names its word, at random r and points; scaling a point by 2^k changes no bit.
TEST(OneOrbit, ClassifyAndLyapunovReportOneExponent) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> R(0.08, 0.95), U(0.05, 1);
  attractors::Options opt;
  opt.run.threads = 1;
  lyapunov::Options lo;
  lo.transient = 2000;
  lo.iterations = 20000;
  int checked = 0;
  for (int i = 0; i < 16; ++i) {
    const double r = i == 0 ? 0.1 : (i == 1 ? 0.25 : R(g));
    const Vec3<double> u =
        i == 0 ? Vec3<double>(1, 0, -1) : (i == 1 ? Vec3<double>(0.5, 0.8, -1) : Vec3<double>(U(g), U(g) - 0.5, -U(g)));
    SCOPED_TRACE(::testing::Message() << "r = " << r << " u = " << u.transpose());
    const attractors::OrbitVerdict v = attractors::classify_point(u, r, opt);
    const attractors::OrbitVerdict v2 = attractors::classify_point(std::ldexp(1.0, -600) * u, r, opt);
    EXPECT_EQ(v.lambda1, v2.lambda1);
    EXPECT_EQ(v.key, v2.key);
    EXPECT_EQ(v.point, v2.point);
    const lyapunov::ProjectiveResult p = lyapunov::projective_exponents<double>(u, r, lo);
    EXPECT_GE(p.lambda[0].value, p.lambda[1].value);
    if (v.type == attractors::Type::undecided || v.type == attractors::Type::quasi_periodic) continue;
    // lyapunov's error bar (batch means, at least 4 eps |lambda|) and classify's (0 on a cycle: exact), plus
    // the transient's bias on a cycle: the tangent vector aligns like exp((lambda2 - lambda1) n), gone after 2000
    // steps; 5 sigma + 1e-9.
    const double tol = 5 * (p.lambda[0].error + v.err1) + 1e-9;
    EXPECT_NEAR(v.lambda1, p.lambda[0].value, tol) << attractors::type_name(v.type) << " " << v.key;
    if (v.type == attractors::Type::periodic) {
      const patterns::Verdict<double> pv = patterns::analyse<double>(v.word, r);
      EXPECT_NEAR(v.lambda1, pv.lyapunov2, 1e-12);  // classify analyses the word's smallest rotation: 64 eps
      // The orbit's stability word agrees with the exponents' signs.
      if (pv.lyapunov2 > 1e-9) EXPECT_EQ(pv.outcome, patterns::Outcome::unstable);
      if (pv.lyapunov2 < -1e-9) EXPECT_EQ(pv.outcome, patterns::Outcome::stable);
    }
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

// pattern's verdict on the P2 fixed point u = (1, 0, -1): a saddle for r < 3 - 2 sqrt(2) (lambda1 = -lambda2 =
// log(|mu_other| / r) > 0, from M = P2's eigenvalues computed independently: r and the roots of
// mu^2 + (2 a^2 - 2 r) mu + r^2 - ... as the characteristic polynomial factors), neutral (elliptic) above.
TEST(OneOrbit, PatternVerdictOnTheP2FixedPointFollowsTheExponents) {
  for (double r : {0.05, 0.1, 0.15, 0.17, 0.175, 0.2, 0.3, 0.5, 0.9}) {
    SCOPED_TRACE(::testing::Message() << "r = " << r);
    const patterns::Verdict<double> v = patterns::analyse<double>(patterns::parse_word("2"), r);
    ASSERT_GE(v.orbit_eigen, 0);
    // The tangent plane at (1, 0, -1)/sqrt 2 is spanned by (0, 1, 0) and (1, 0, 1); P2 maps that plane to
    // itself (P2 (1,0,1) = (r, 2a, r), P2 (0,1,0) = (-r a, r - 2a^2, -r a)): the 2x2 block, divided by the orbit's
    // eigenvalue r, is the projective Jacobian.  Its eigenvalues, in long double, give the exponents.
    const long double a = (1 + (long double)r) / 2, rr = r;
    // Block in the basis e = (1,0,1), f = (0,1,0): P2 e = r e + 2a f, P2 f = -r a e + (r - 2a^2) f.
    const long double tr = (rr + (rr - 2 * a * a)) / rr, det = (rr * (rr - 2 * a * a) + 2 * a * rr * a) / (rr * rr);
    const long double disc = tr * tr - 4 * det;
    long double l1, l2;
    if (disc >= 0) {
      const long double m1 = std::fabs((tr + std::sqrt(disc)) / 2), m2 = std::fabs((tr - std::sqrt(disc)) / 2);
      l1 = std::log(std::max(m1, m2)), l2 = std::log(std::min(m1, m2));
    } else {
      l1 = l2 = std::log(det) / 2;
    }
    EXPECT_NEAR(v.lyapunov2, (double)l1, 1e-12);
    EXPECT_NEAR(v.lyapunov3, (double)l2, 1e-12);
    const double threshold = 3 - 2 * std::sqrt(2.0);
    if (r < threshold) EXPECT_EQ(v.outcome, patterns::Outcome::unstable);
    else EXPECT_EQ(v.outcome, patterns::Outcome::neutral);
  }
}

// Every exponent-reporting tool accepts the same r: classify refuses below lyapunov's smallest r in double.
TEST(OneOrbit, OneDomainOfR) {
  const double lo = core::smallest_r_exponents(core::parse_precision("double"));
  EXPECT_NEAR(lo, 4.7e-7, 0.05e-7);
  attractors::ClassifyRequest c;
  c.point = "1,0,-1";
  c.r = lo * 0.99;
  EXPECT_THROW(c.validate(), core::InvalidField);
  c.r = lo * 1.01;
  EXPECT_NO_THROW(c.validate());
}

// basins' label of a grid point is classify's verdict on that point (the early exit proves the full-length verdict).
TEST(OneOrbit, BasinsLabelIsClassifyOfThePoint) {
  attractors::Options opt;
  opt.run.threads = 1;
  for (double r : {0.15, 0.25, 0.4}) {
    const attractors::Grid g = attractors::parse_grid("sphere:6x6", -2, 2);
    const attractors::Basins b = attractors::basins(r, g, 0, 1, opt);
    const std::vector<Vec3<double>> pts = attractors::grid_points(g);
    ASSERT_EQ(pts.size(), b.labels.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const attractors::OrbitVerdict v = attractors::classify_point(pts[i], r, opt);
      const std::uint32_t label = b.labels[i];
      const std::string key = label == 0 ? "" : b.attractors[label - 1].key;
      EXPECT_EQ(attractors::attractor_key(v), key) << "r = " << r << " point " << pts[i].transpose();
    }
  }
}

// No collapse above 7 - 4 sqrt(3) (decided exactly), at random r within 1e-3 above it; just below the threshold
// the collapse stays a verdict.
TEST(OneOrbit, NoCollapseAboveTheThreshold) {
  attractors::Options opt;
  opt.run.threads = 1;
  const Vec3<double> u(1, -0.5, -1.1);
  const attractors::OrbitVerdict below = attractors::classify_point(u, 0.07179676972449, opt);  // 8e-16 below
  EXPECT_EQ(below.type, attractors::Type::collapse) << below.detail;
  const double threshold = 7 - 4 * std::sqrt(3.0);
  std::mt19937_64 g(23);
  std::uniform_real_distribution<double> R(0, 1e-3), U(0.05, 1);
  for (int i = 0; i < 12; ++i) {
    const double r = i == 0 ? 0.0717967697245 : std::nextafter(threshold + R(g), 1.0);
    const Vec3<double> p = i == 0 ? u : Vec3<double>(U(g), U(g) - 0.5, -U(g));
    const attractors::OrbitVerdict v = attractors::classify_point(p, r, opt);
    EXPECT_NE(v.type, attractors::Type::collapse) << "r = " << r << " u = " << p.transpose() << ": " << v.detail;
  }
}

// 9e-15 above 7 - 4 sqrt(3) the orbit of (1, -0.5, -1.1) turns slowly in the cone a y < z of P3 while x shrinks
// by r per step: x underflows to 0 in double (after ~300 steps) and stays far below double's range in MPFR.  x = 0
// is then x rounded to double: the double kernel takes the branches of the MPFR kernel (whose exponent range
// keeps x) step for step, and classify's lambda1 (double) is MPFR lyapunov's over the same steps within their
// errors; the verdict is the orbit's, not "undecided".
TEST(OneOrbit, AnOrbitBelowDoublesRangeInXIsFollowedInDouble) {
  const double r = 0.0717967697245;
  const Vec3<double> u(1, -0.5, -1.1);
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {u};
  const long n = 6000;
  iterate::SymbolRecorder sd(1, 1, n), sm(1, 1, n);
  attractors::StateRecorder fin(1, n);
  iterate::run<double>(e, n, sd, {});
  iterate::run<double>(e, n, fin, {});
  {
    core::MpfrDigits digits(30);
    iterate::run<core::mpfr_float>(e, n, sm, {});
  }
  EXPECT_EQ(fin.state[0](0), 0.0);  // the case this test is about: x below double's range
  EXPECT_TRUE(sd.out == sm.out);    // every branch of 6000 steps
  attractors::Options opt;
  opt.run.threads = 1;
  opt.refine_factor = 0;  // pass 2 right after the window: the steps MPFR's lyapunov averages below
  const attractors::OrbitVerdict v = attractors::classify_point(u, r, opt);
  EXPECT_NE(v.type, attractors::Type::collapse);
  EXPECT_EQ(v.detail.find("undecided"), std::string::npos) << v.detail;
  ASSERT_GT(v.err1, 0) << v.detail;  // a measured exponent, with its error bar
  // MPFR lyapunov over classify's pass-2 steps: transient = classify's steps before pass 2 plus its own alignment.
  lyapunov::Options lo;
  lo.transient = opt.transient + opt.window + opt.lyap_transient;
  lo.iterations = opt.lyap_iterations;
  lo.blocks = opt.lyap_blocks;
  core::MpfrDigits digits(30);
  using M = core::mpfr_float;
  const lyapunov::ProjectiveResult p = lyapunov::projective_exponents<M>(Vec3<M>(M(1), M(-0.5), M(-1.1)), M(r), lo);
  // Both are batch-means estimates of one finite-time average (error bars of 10 blocks): 5 sigma of the two.
  EXPECT_NEAR(v.lambda1, p.lambda[0].value, 5 * (v.err1 + p.lambda[0].error)) << v.detail;
  // With the refinement pass (66000 steps) the orbit returns within return-tol after one step near the rotation's
  // slow direction, but no periodic orbit of the word 3 exists at this r: measured like an orbit without a period.
  opt.refine_factor = attractors::Options{}.refine_factor;
  const attractors::OrbitVerdict refined = attractors::classify_point(u, r, opt);
  EXPECT_NE(refined.type, attractors::Type::periodic) << refined.detail;
  EXPECT_NE(refined.type, attractors::Type::collapse) << refined.detail;
  EXPECT_GT(refined.err1, 0) << refined.detail;
}

namespace {
// A corner point: x and y below 2^-969 next to z, where the vector step's fused a y - x underflows to 0 (its
// sign lost) although the exact value is not 0.
std::vector<Case> corner_cases(std::mt19937_64& g, int n) {
  std::uniform_int_distribution<int> K(19, 255);
  std::uniform_real_distribution<double> U(0.05, 1);
  std::vector<Case> out;
  for (int i = 0; i < n; ++i) {
    const double r = K(g) / 256.0, a = (1 + r) / 2;
    const double y = std::ldexp(U(g), -1030), ay = a * y;
    for (double d : {-1.0, 0.0, 1.0}) out.push_back({r, {std::nextafter(ay, ay + d), y, -U(g)}, "corner"});
  }
  return out;
}

// The point as the kernel starts it: in Q, scaled by 2^(1 - e) so that its largest component lies in [1, 2).
Vec3<double> kernel_start(const Vec3<double>& u) {
  int e = 0;
  std::frexp(u.cwiseAbs().maxCoeff(), &e);
  const Vec3<double> q = core::to_quadrant<double>(u);
  return {std::ldexp(q(0), 1 - e), std::ldexp(q(1), 1 - e), std::ldexp(q(2), 1 - e)};
}
}  // namespace

// Map.step (iterate::kernel_step, called here from a unit compiled without the kernel's instruction set as the
// Python module is) equals one step of the batched kernel bit for bit, on random points, points on and next to the
// branch lines, on the invariant planes and in the underflow corner; both take the exact branch; a point scaled
// by 2^k gives the image scaled by 2^k.
TEST(OneOrbit, MapStepIsOneKernelStepBitwise) {
  std::mt19937_64 g(29);
  std::vector<Case> cs = cases(g, 40);
  const std::vector<Case> cc = corner_cases(g, 20);
  cs.insert(cs.end(), cc.begin(), cc.end());
  int corner_zero = 0;
  for (const Case& c : cs) {
    SCOPED_TRACE(::testing::Message() << c.kind << " r = " << c.r << " u = (" << std::hexfloat << c.u(0) << ", "
                                      << c.u(1) << ", " << c.u(2) << ")");
    iterate::Ensemble e;
    e.r = {c.r};
    e.initial = {c.u};
    attractors::StateRecorder st(1, 1);
    iterate::SymbolRecorder sy(1, 1, 1);
    iterate::RunOptions one;
    one.threads = 1;  // 480 one-orbit runs: an OpenMP team each would cost seconds on a loaded machine
    iterate::run<double>(e, 1, st, one);
    iterate::run<double>(e, 1, sy, one);
    const core::Step<double> m = iterate::kernel_step(kernel_start(c.u), c.r);
    const int want = exact_branch(c.u, c.r);
    EXPECT_EQ(m.symbol, want);
    EXPECT_EQ(int(sy.out[0]), want) << "kernel";
    EXPECT_EQ(m.u, st.state[0]) << "kernel " << st.state[0].transpose() << " Map.step " << m.u.transpose();
    const double a = (1 + c.r) / 2;
    corner_zero += c.kind[0] == 'c' && std::fma(a, c.u(1), -c.u(0)) == 0 && want != 2;
    for (int k : {-7, 9, 300}) {
      if (c.kind[0] == 'c' && k < 0) continue;  // a subnormal point scaled down loses bits: another point
      const Vec3<double> s(std::ldexp(c.u(0), k), std::ldexp(c.u(1), k), std::ldexp(c.u(2), k));
      const core::Step<double> ms = iterate::kernel_step(s, c.r);
      EXPECT_EQ(ms.symbol, want) << "scaled by 2^" << k;
      if (c.kind[0] != 'c') EXPECT_EQ(ms.u, std::ldexp(1.0, k) * iterate::kernel_step(c.u, c.r).u) << k;
    }
  }
  EXPECT_GT(corner_zero, 5);  // the corner is exercised: fused values that underflowed to 0 on a non-tie
}

// The scalar routes of hyperbolicity (step_singular_values, covariant_vectors) and finite_difference_exponent
// branch on the point itself, kept scaled by powers of two, not on its rounded unit vector: on and next to the
// branch lines their first branch is the exact rule's, and a point times 2^k (k = -600: its squared norm would
// underflow) changes no output bit.
TEST(OneOrbit, ScalarRoutesBranchOnThePointNotItsUnitVector) {
  std::mt19937_64 g(31);
  const std::vector<Case> cs = cases(g, 24);
  lyapunov::ClvOptions co;
  co.transient = 0;
  co.window = 20;
  co.backward_transient = 20;
  lyapunov::Options fo;
  fo.transient = 0;
  fo.iterations = 40;
  fo.blocks = 2;
  for (const Case& c : cs) {
    if (c.u(0) == 0 && c.u(2) == 0) continue;
    SCOPED_TRACE(::testing::Message() << c.kind << " r = " << c.r << " u = (" << std::hexfloat << c.u(0) << ", "
                                      << c.u(1) << ", " << c.u(2) << ")");
    const int want = exact_branch(c.u, c.r);
    const lyapunov::StepSingularValues sv = lyapunov::step_singular_values(c.u, c.r);
    const lyapunov::ClvResult cv = lyapunov::covariant_vectors<double>(c.u, c.r, co);
    const lyapunov::FiniteDifference fd = lyapunov::finite_difference_exponent(c.u, c.r, 1e-7, fo);
    EXPECT_EQ(sv.symbol, want) << "step_singular_values";
    ASSERT_FALSE(cv.symbols.empty());
    EXPECT_EQ(int(cv.symbols[0]), want) << "covariant_vectors";
    for (int k : {-600, 9, 600}) {
      const Vec3<double> s(std::ldexp(c.u(0), k), std::ldexp(c.u(1), k), std::ldexp(c.u(2), k));
      const lyapunov::StepSingularValues sv2 = lyapunov::step_singular_values(s, c.r);
      EXPECT_TRUE(sv2.symbol == sv.symbol && sv2.s1 == sv.s1 && sv2.s2 == sv.s2) << "step_singular_values 2^" << k;
      const lyapunov::ClvResult cv2 = lyapunov::covariant_vectors<double>(s, c.r, co);
      EXPECT_TRUE(cv2.symbols == cv.symbols && cv2.angle == cv.angle && cv2.lambda == cv.lambda)
          << "covariant_vectors 2^" << k;
      const lyapunov::FiniteDifference fd2 = lyapunov::finite_difference_exponent(s, c.r, 1e-7, fo);
      EXPECT_TRUE(fd2.lambda1 == fd.lambda1 && fd2.straddles == fd.straddles) << "finite differences 2^" << k;
    }
  }
}

// One vocabulary: the atlas's interval word (patterns::classify) is pattern's verdict (patterns::analyse) on the
// same word and r, neutral on the P2 fixed point above 3 - 2 sqrt(2) included; at the double nearest 3 - 2 sqrt(2),
// where the complex pair merges into a real double eigenvalue of the orbit's modulus, the verdict is neutral when
// the tying eigenvalue came out complex and undecided when it came out real (double cannot order the moduli).
TEST(OneOrbit, AtlasIntervalsAndPatternSayTheSameWord) {
  const char* words[] = {"2", "12", "132", "1133", "132312", "1232", "13", "2232"};
  std::mt19937_64 g(37);
  std::uniform_real_distribution<double> R(0.01, 0.99);
  int neutral = 0;
  for (const char* w : words) {
    const patterns::Word word = patterns::parse_word(w);
    for (int i = 0; i < 40; ++i) {
      const double r = R(g);
      const patterns::Verdict<double> v = patterns::analyse<double>(word, r);
      const patterns::Classification c = patterns::classify<double>(word, r);
      EXPECT_EQ(patterns::outcome_name(c.outcome), patterns::outcome_name(v.outcome)) << w << " r = " << r;
      neutral += v.outcome == patterns::Outcome::neutral;
    }
  }
  EXPECT_GT(neutral, 10);
  const double t = 3 - 2 * std::sqrt(2.0);
  for (double r : {std::nextafter(t, 0.0), t, std::nextafter(t, 1.0)}) {
    const patterns::Verdict<double> v = patterns::analyse<double>(patterns::parse_word("2"), r);
    ASSERT_GE(v.orbit_eigen, 0);
    const bool real = v.spectrum[v.orbit_eigen == 0 ? 1 : 0].real;
    // 64 eps: the eigenvalue moduli's tie tolerance of analyse (period 1).
    if (std::abs(v.lyapunov2) <= 64 * std::numeric_limits<double>::epsilon())
      EXPECT_EQ(v.outcome, real ? patterns::Outcome::undecided : patterns::Outcome::neutral) << "r = " << r;
    else EXPECT_EQ(v.outcome, patterns::Outcome::unstable) << "r = " << r << " lambda1 = " << v.lyapunov2;
  }
}

// The one-orbit route of the batched kernel (iterate::run on an ensemble of at most one vector's lanes: one vector
// for float and double, one lane for the other precisions) against the route before it, the orbit as one lane of a
// full batch: the same symbols at every step and the same final state to the bit, in every precision, on a chaotic
// orbit (r = 0.12, lambda1 = 0.58) and on one that falls into a sink (r = 0.15, the cycle 1133).  On the chaotic
// orbit a difference of one ulp anywhere would grow by e^0.58 per step and reach the symbols within a few hundred
// steps (MPFR at 50 digits: 166 bits, about 200 steps), so equal symbols over n steps and an equal final state say
// the two runs computed the same numbers; on the sink the final state carries the last steps' roundings.
template <class T> struct OneOrbitRun {
  std::vector<std::uint8_t> symbols;  // [orbits x n]
  std::vector<Vec3<double>> final;    // [orbits]
};
template <class T> OneOrbitRun<T> run_orbits(const char* r, const std::vector<Vec3<double>>& starts, long n) {
  iterate::Ensemble e;
  e.set_r_list({core::Decimal::parse(r, "r")});
  e.initial = starts;
  iterate::SymbolRecorder sy(starts.size(), 1, n);
  iterate::FinalRecorder fin(starts.size(), n);
  iterate::Both<iterate::FinalRecorder, iterate::SymbolRecorder> both(fin, sy);
  iterate::RunOptions opt;
  opt.threads = 2;  // the full batch's ensemble is one batch: one thread steps it whatever the count
  iterate::run<T>(e, n, both, opt);
  return {sy.out, fin.out};
}

template <class T> void expect_one_orbit_is_a_lane_of_the_batch(const char* r, long n, bool sink) {
  SCOPED_TRACE(::testing::Message() << "r = " << r);
  const Vec3<double> u(1, -0.5, -1.1);
  std::vector<Vec3<double>> many = {u};
  for (const Vec3<double>& p : iterate::paper_grid()) many.push_back(p);  // 33 orbits: more than one vector's lanes
  const OneOrbitRun<T> full = run_orbits<T>(r, many, n);
  const std::size_t nn = static_cast<std::size_t>(n);
  for (std::size_t few : {std::size_t(1), std::size_t(2), std::size_t(8)}) {  // 2 and 8: float and double only
    if (few > 1 && !(std::is_same_v<T, float> || std::is_same_v<T, double>)) continue;
    SCOPED_TRACE(::testing::Message() << few << " orbits");
    const OneOrbitRun<T> one = run_orbits<T>(r, std::vector<Vec3<double>>(many.begin(), many.begin() + few), n);
    for (std::size_t o = 0; o < few; ++o) {
      EXPECT_TRUE(
          std::equal(one.symbols.begin() + o * nn, one.symbols.begin() + (o + 1) * nn, full.symbols.begin() + o * nn))
          << "orbit " << o;
      EXPECT_EQ(one.final[o], full.final[o]) << "orbit " << o;  // Eigen's == compares every component exactly
    }
  }
  // The orbit is what the case says: a sink repeats 1133 (in some rotation) at the end, a chaotic orbit does not.
  const auto period4 = [&](const std::vector<std::uint8_t>& s) {
    for (std::size_t k = nn - 40; k < nn; ++k)
      if (s[k] != s[k - 4]) return false;
    return true;
  };
  EXPECT_EQ(period4(full.symbols), sink);
}

TEST(OneOrbit, OneOrbitRouteIsALaneOfTheFullBatchBitwise) {
  expect_one_orbit_is_a_lane_of_the_batch<double>("0.12", 20000, false);
  expect_one_orbit_is_a_lane_of_the_batch<double>("0.15", 20000, true);
  expect_one_orbit_is_a_lane_of_the_batch<float>("0.12", 20000, false);
  expect_one_orbit_is_a_lane_of_the_batch<float>("0.15", 20000, true);
  expect_one_orbit_is_a_lane_of_the_batch<long double>("0.12", 5000, false);
  expect_one_orbit_is_a_lane_of_the_batch<long double>("0.15", 5000, true);
  expect_one_orbit_is_a_lane_of_the_batch<core::float128>("0.12", 2000, false);
  expect_one_orbit_is_a_lane_of_the_batch<core::float128>("0.15", 2000, true);
  const core::MpfrDigits digits(50);
  expect_one_orbit_is_a_lane_of_the_batch<core::mpfr_float>("0.12", 1000, false);
  expect_one_orbit_is_a_lane_of_the_batch<core::mpfr_float>("0.15", 1000, true);
}

// The same for the fused cocycle kernel (iterate::run_cocycle: lyapunov::map_exponents, classify's second pass): one
// orbit, and 2 and 8 orbits, run as one vector against the same orbits as lanes of a full batch (33 orbits): the
// exponents and their error bars to the bit, on the chaotic orbit and on the sink.
TEST(OneOrbit, OneOrbitCocycleIsALaneOfTheFullBatchBitwise) {
  const Vec3<double> u(1, -0.5, -1.1);
  std::vector<Vec3<double>> many = {u};
  for (const Vec3<double>& p : iterate::paper_grid()) many.push_back(p);
  lyapunov::MapOptions o;
  o.transient = 1000;
  o.iterations = 20000;
  o.run.threads = 2;
  for (const double r : {0.12, 0.15}) {
    iterate::Ensemble e;
    e.r = {r};
    e.initial = many;
    const lyapunov::OrbitExponents full = lyapunov::map_exponents(e, o);
    for (std::size_t few : {std::size_t(1), std::size_t(2), std::size_t(8)}) {
      SCOPED_TRACE(::testing::Message() << "r = " << r << ", " << few << " orbits");
      e.initial.assign(many.begin(), many.begin() + static_cast<std::ptrdiff_t>(few));
      const lyapunov::OrbitExponents one = lyapunov::map_exponents(e, o);
      for (std::size_t i = 0; i < few; ++i) {
        EXPECT_EQ(one.lambda1[i], full.lambda1[i]) << "orbit " << i;
        EXPECT_EQ(one.lambda2[i], full.lambda2[i]) << "orbit " << i;
        EXPECT_EQ(one.err1[i], full.err1[i]) << "orbit " << i;
      }
    }
    // r = 0.15 falls into the sink 1133: both exponents negative; r = 0.12 is chaotic.
    EXPECT_EQ(full.lambda1[0] < 0, r == 0.15) << full.lambda1[0];
  }
}

// classify of one point, 2 and 8 points (one vector of the kernel, the cocycle, and of the return and rotation
// recorders' loops) against the same points within a 33-point ensemble (full batches): every verdict to the bit, on
// a chaotic r, a sink and r = 0.2, where orbits of the P2 parallelogram take the rotation run.
TEST(OneOrbit, ClassifyOfFewPointsIsTheirVerdictInAFullBatchBitwise) {
  std::vector<Vec3<double>> many = {Vec3<double>(1, -0.5, -1.1), Vec3<double>(1, 0.05, -1)};
  for (const Vec3<double>& p : iterate::paper_grid()) many.push_back(p);
  attractors::Options opt;
  opt.run.threads = 2;
  int rotations = 0;
  for (const double r : {0.12, 0.15, 0.2}) {
    iterate::Ensemble e;
    e.r = {r};
    e.initial = many;
    const std::vector<attractors::OrbitVerdict> full = attractors::classify(e, opt);
    for (std::size_t few : {std::size_t(1), std::size_t(2), std::size_t(8)}) {
      SCOPED_TRACE(::testing::Message() << "r = " << r << ", " << few << " points");
      e.initial.assign(many.begin(), many.begin() + static_cast<std::ptrdiff_t>(few));
      const std::vector<attractors::OrbitVerdict> one = attractors::classify(e, opt);
      for (std::size_t i = 0; i < few; ++i) {
        const attractors::OrbitVerdict &a = one[i], &b = full[i];
        EXPECT_EQ(a.key, b.key) << "point " << i;
        EXPECT_EQ(a.residual, b.residual) << "point " << i;
        EXPECT_EQ(a.lambda1, b.lambda1) << "point " << i;
        EXPECT_EQ(a.err1, b.err1) << "point " << i;
        EXPECT_EQ(a.rotation, b.rotation) << "point " << i;
        EXPECT_EQ(a.invariant, b.invariant) << "point " << i;
        EXPECT_EQ(a.invariant_spread, b.invariant_spread) << "point " << i;
        EXPECT_EQ(a.point, b.point) << "point " << i;
        rotations += i == 1 && few == 2 && a.rotation != 0;
      }
    }
  }
  EXPECT_GE(rotations, 1);  // the rotation recorder's loop was exercised on a partial batch
}
