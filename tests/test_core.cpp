// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of btob::core: invariants of P_r (quadrant, symmetries, spectra), branch conventions on exact
// ties, coordinates (theta, phi, strip, particles) and the validation errors.
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/map.hpp"
#include "core/scalar.hpp"
#include "core/size_model.hpp"
#include "iterate/ensemble.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

using btob::core::Vec3;
using V = Vec3<double>;
using M = btob::core::Mat3<double>;
constexpr double eps = std::numeric_limits<double>::epsilon();

const std::vector<double> kR = {0.01, 0.07, 0.0718, 0.1, 0.17, 0.2, 0.5, 0.9, 0.99};

// S = -J: (x, y, z) -> (-z, -y, -x), the symmetry of the proof of Theorem 3.3; it maps Q onto Q.
V S(const V& u) { return V(-u(2), -u(1), -u(0)); }

// Expects `what()` of the exception thrown by f to contain every string of `parts`.
template <class E, class F> void expect_error(F f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    const std::string msg = e.what();
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "message '" << msg << "' lacks '" << p << "'";
  } catch (...) {
    ADD_FAILURE() << "exception of another type";
  }
}

TEST(Map, QuadrantIsInvariant) {
  const auto pts = btob::iterate::random_points(20000, 11);
  for (double r : kR)
    for (const V& u : pts) {
      const V w = btob::core::step(u, r).u;
      ASSERT_GE(w(0), 0.0) << "r=" << r;
      ASSERT_LE(w(2), 0.0) << "r=" << r;
      ASSERT_GT(w.norm(), 0.0);
    }
}

TEST(Map, OddExtension) {
  // P(u) = -P(-u) on the other quadrant (Theorem 3.3): step(-u) and step(u) give the same vector of Q.
  const auto pts = btob::iterate::random_points(20000, 12);
  for (double r : kR)
    for (const V& u : pts) {
      const auto a = btob::core::step(u, r), b = btob::core::step<double>(-u, r);
      ASSERT_EQ(a.symbol, b.symbol);
      ASSERT_EQ(a.u, b.u);                                 // bitwise: negation is exact
      ASSERT_EQ(btob::core::P(a.symbol, r) * (-u), -a.u);  // linearity of the branch, exact
    }
}

TEST(Map, JSymmetrySwapsSymbols1And3) {
  for (double r : kR) {
    const M J = btob::core::J<double>();
    // Permutations are exact, so these hold bitwise.
    EXPECT_EQ(J * btob::core::P1(r) * J, btob::core::P3(r));
    EXPECT_EQ(J * btob::core::P2(r) * J, btob::core::P2(r));
  }
  const auto pts = btob::iterate::random_points(20000, 13);
  for (double r : kR)
    for (const V& u : pts) {
      const auto a = btob::core::step(u, r), b = btob::core::step(S(u), r);
      ASSERT_EQ(b.symbol, 4 - a.symbol) << "r=" << r;  // branch tests negate exactly under S
      // P3 (S u) and S (P1 u) sum the same products in another order: a few ulps of |P| |u|.
      const auto tol =
          ulps(8, "the same products summed in another order").of(btob::core::P(a.symbol, r).norm() * u.norm());
      ASSERT_SMALL((b.u - S(a.u)).norm(), tol) << "r=" << r;
    }
}

TEST(Map, Determinants) {
  for (double r : kR) {
    // The cofactor sums cancel: terms of size r^(k-1) add up to r^k, so the relative error is a few
    // ulps divided by r.
    const auto tol = ulps(16 / r, "cofactor sums of terms r^(k-1) cancel to r^k: a few roundings over r");
    EXPECT_CLOSE(btob::core::P1(r).determinant() / std::pow(r, 4), 1.0, tol) << r;
    EXPECT_CLOSE(btob::core::P2(r).determinant() / std::pow(r, 3), 1.0, tol) << r;
    EXPECT_CLOSE(btob::core::P3(r).determinant() / std::pow(r, 4), 1.0, tol) << r;
  }
}

TEST(Map, EigenvectorsOfPropositions51And53) {
  for (double r : kR) {
    const double a = btob::core::alpha(r);
    // Prop. 5.2: P2 (1, 0, -1) = r (1, 0, -1); every product is exact (entries times 0 or 1).
    EXPECT_EQ(btob::core::P2(r) * V(1, 0, -1), r * V(1, 0, -1));
    // Prop. 5.1: P1 (alpha, r + 1, 3 alpha) = r^2 (alpha, r + 1, 3 alpha): rounding of 3 terms of size <= 4.
    const V e(a, r + 1, 3 * a);
    EXPECT_SMALL((btob::core::P1(r) * e - r * r * e).norm(),
                 ulps(16, "3 rounded terms of size <= 4 per entry").of(e.norm()))
        << r;
    // The planes z = 0 (P1) and x = z (P2) are invariant.
    EXPECT_EQ((btob::core::P1(r) * V(0.3, -0.7, 0))(2), 0.0);
    const V w = btob::core::P2(r) * V(0.3, -0.7, 0.3);
    EXPECT_EQ(w(0), w(2));
  }
  // Spectra: real below the thresholds 7 - 4 sqrt 3 (P1) and 3 - 2 sqrt 2 (P2), modulus r above.
  const auto sorted_eigs = [](const M& m) {
    Eigen::EigenSolver<M> es(m);
    std::vector<std::complex<double>> v(es.eigenvalues().data(), es.eigenvalues().data() + 3);
    std::sort(v.begin(), v.end(), [](auto x, auto y) { return x.real() < y.real(); });
    return v;
  };
  // Eigenvalues (all below 1) of a well-separated 3x3 spectrum: ~ eps * |P| * condition.
  const auto tol = ulps(64, "Eigen's 3x3 eigensolver: eps |P| times the spectrum's condition (measured 4 eps)");
  {
    const double r = 0.05, sq = std::sqrt(r * r - 14 * r + 1);
    const auto v = sorted_eigs(btob::core::P1(r));
    EXPECT_CLOSE(v[0].real(), r * r, tol);
    EXPECT_CLOSE(v[1].real(), (r * r - 6 * r + 1 - (r + 1) * sq) / 8, tol);
    EXPECT_CLOSE(v[2].real(), (r * r - 6 * r + 1 + (r + 1) * sq) / 8, tol);
    for (auto x : v) EXPECT_EQ(x.imag(), 0.0);
  }
  for (double r : {0.1, 0.5, 0.9}) {
    const auto v = sorted_eigs(btob::core::P1(r));
    int complex_pairs = 0;
    for (auto x : v)
      if (x.imag() != 0) {
        ++complex_pairs;
        EXPECT_CLOSE(std::abs(x), r, tol) << r;
      }
    EXPECT_EQ(complex_pairs, 2) << r;
  }
  {
    const double r = 0.1, a = btob::core::alpha(r), sq = std::sqrt(a * a - 2 * r);
    const auto v = sorted_eigs(btob::core::P2(r));
    EXPECT_CLOSE(v[0].real(), r - a * a - a * sq, tol);
    EXPECT_CLOSE(v[1].real(), r - a * a + a * sq, tol);
    EXPECT_CLOSE(v[2].real(), r, tol);
  }
  for (double r : {0.2, 0.5, 0.9}) {
    const auto v = sorted_eigs(btob::core::P2(r));
    for (auto x : v) EXPECT_CLOSE(std::abs(x), r, tol) << r;
  }
}

TEST(Map, BranchConventionsOnExactTies) {
  // r = 0.5: alpha = 0.75, so the ties below are exact in binary floating point.
  const double r = 0.5;
  ASSERT_EQ(btob::core::alpha(r), 0.75);
  EXPECT_EQ(btob::core::branch(V(0.75, 1, -1), r), 2);   // alpha y - x == 0 -> P2 (Remark 3.6)
  EXPECT_EQ(btob::core::branch(V(1, -1, -0.75), r), 2);  // alpha y - z == 0 -> P2
  EXPECT_EQ(btob::core::branch(V(1, 0, -1), r), 2);      // y == 0 -> P2
  EXPECT_EQ(btob::core::branch(V(0, 0, -1), r), 2);      // x == y == 0 (alpha y - x == 0) -> P2
  EXPECT_EQ(btob::core::branch(V(1, 0, 0), r), 2);       // y == z == 0 (alpha y - z == 0) -> P2
  // One ulp-sized step off the ties selects P1 / P3.
  EXPECT_EQ(btob::core::branch(V(0.75 - 0x1p-40, 1, -1), r), 1);
  EXPECT_EQ(btob::core::branch(V(1, -1, -0.75 + 0x1p-40), r), 3);
  EXPECT_EQ(btob::core::step(V(0.75, 1, -1), r).symbol, 2);
  EXPECT_EQ(btob::core::step(V(0.75, 1, -1), r).u, btob::core::P2(r) * V(0.75, 1, -1));
  // The other quadrant is folded first: (-0.75, -1, 1) is the same tie.
  EXPECT_EQ(btob::core::step(V(-0.75, -1, 1), r).symbol, 2);
  // Letters: y > 0 -> acb, y < 0 -> cab, y == 0 -> simultaneous a and c.
  EXPECT_EQ(btob::core::letters(2, V(1, 0.1, -1)), "acb");
  EXPECT_EQ(btob::core::letters(2, V(1, -0.1, -1)), "cab");
  EXPECT_EQ(btob::core::letters(2, V(1, 0, -1)), "(ac)b");
  EXPECT_EQ(btob::core::letters(1, V(0.1, 1, -1)), "ab");
  EXPECT_EQ(btob::core::letters(3, V(1, -1, -0.1)), "cb");
  expect_error<std::invalid_argument>([] { btob::core::P(4, 0.5); }, {"symbol", "got 4", "1, 2 or 3"});
}

TEST(Coords, AnglesRoundTrip) {
  // theta, phi come back through atan2 of products of sines and cosines: a few ulps of pi.
  const auto tol = ulps(14, "atan2 of products of sines and cosines, angles up to pi").of(std::numbers::pi);
  for (int i = 1; i < 50; ++i)
    for (int j = 1; j < 50; ++j) {
      const double th = 0.5 * std::numbers::pi * i / 50, ph = std::numbers::pi * j / 50;
      const V u = btob::core::from_angles(th, ph);
      EXPECT_CLOSE(u.norm(), 1.0, ulps(4, "sqrt of a sum of 3 squares of sines and cosines"));
      EXPECT_GE(u(0), 0.0);
      EXPECT_LE(u(2), 0.0);
      EXPECT_CLOSE(btob::core::theta(u), th, tol);
      EXPECT_CLOSE(btob::core::phi(u), ph, tol);
      // theta and phi depend on the direction only, and on neither quadrant representative.
      EXPECT_CLOSE(btob::core::theta<double>(-3.0 * u), th, tol);
      EXPECT_CLOSE(btob::core::phi<double>(-3.0 * u), ph, tol);
    }
}

TEST(Coords, StripRoundTrip) {
  for (double w1 = -8; w1 <= 8; w1 += 0.37)
    for (double w2 = -1; w2 <= 1; w2 += 0.0625) {
      const auto [a, b] = btob::core::strip(btob::core::from_strip(w1, w2));
      // x - z == 1 exactly for these inputs (w2 on a dyadic grid), so only the division rounds.
      const auto tol = ulps(45, "w -> u -> w: the construction's roundings and one division, relative to max(1, |w|)");
      EXPECT_CLOSE(a, w1, tol);
      EXPECT_CLOSE(b, w2, tol);
      const auto [c, d] = btob::core::strip<double>(-2.5 * btob::core::from_strip(w1, w2));
      EXPECT_CLOSE(c, w1, tol);
      EXPECT_CLOSE(d, w2, tol);
    }
}

TEST(Coords, StripBoundariesSeparateTheBranches) {
  // Section 6.2: w2 = 2 alpha w1 - 1 is alpha y - x = 0, w2 = 2 alpha w1 + 1 is alpha y - z = 0.
  const double d = 1e-9;  // far above rounding (1e-16) and far below the grid spacing
  for (double r : kR) {
    const double a = btob::core::alpha(r);
    for (double w1 = -3; w1 <= 3; w1 += 0.01) {
      const double lo = 2 * a * w1 - 1, hi = 2 * a * w1 + 1;
      const auto br = [&](double w2) { return btob::core::branch(btob::core::from_strip(w1, w2), r); };
      if (lo - d >= -1 && lo - d <= 1) EXPECT_EQ(br(lo - d), 1) << r << " " << w1;
      if (lo + d >= -1 && lo + d <= 1) EXPECT_EQ(br(lo + d), 2) << r << " " << w1;
      if (hi - d >= -1 && hi - d <= 1) EXPECT_EQ(br(hi - d), 2) << r << " " << w1;
      if (hi + d >= -1 && hi + d <= 1) EXPECT_EQ(br(hi + d), 3) << r << " " << w1;
      // Inside the parallelogram the letters are acb for w1 > 0 and cab for w1 < 0.
      const double mid = 2 * a * w1;
      if (mid >= -1 && mid <= 1 && std::abs(w1) > 1e-12) {
        const V u = btob::core::from_strip(w1, mid);
        EXPECT_EQ(btob::core::letters(btob::core::branch(u, r), u), w1 > 0 ? "acb" : "cab");
      }
    }
  }
}

TEST(Coords, ParticlesRoundTrip) {
  const auto pts = btob::iterate::random_points(20000, 14);
  double worst = 0;
  for (const V& u : pts) {
    const auto c = btob::core::to_particles(u);
    ASSERT_EQ(c.p(1), 0.0);  // right after a b-collision
    ASSERT_GE(c.p(0), 0.0);
    ASSERT_GE(c.p(2), 0.0);
    ASSERT_GT(c.q(1), 0.0);  // the pair 2-3 separates
    EXPECT_CLOSE(c.p.norm(), 1.0, ulps(4, "a normalised vector: its norm is a sqrt of 3 rounded squares"));
    EXPECT_CLOSE(c.q.norm(), 1.0, ulps(4, "a normalised vector: its norm is a sqrt of 3 rounded squares"));
    EXPECT_CLOSE(c.p.dot(c.q), 0.0, ulps(8, "q is built orthogonal to p: 3 rounded products of unit vectors"));
    // theta is the angle of p: tan theta = p1 / p3 (Section 4).
    EXPECT_CLOSE(std::atan2(c.p(0), c.p(2)), btob::core::theta(u),
                 ulps(45, "two atan2 of rounded components, angles <= pi/2").of(1));
    const V w = btob::core::from_particles(c);
    worst = std::max(worst, std::atan2(w.cross(u).norm(), w.dot(u)));
  }
  // p and q are orthogonal and unit, so p x q and the two cross products before it are well
  // conditioned: the direction comes back to a few ulps.
  EXPECT_SMALL(worst, ulps(45, "to particles and back: well-conditioned cross products, a few ulps"));
}

TEST(Validation, PointErrors) {
  using btob::core::validate_point;
  EXPECT_NO_THROW(validate_point(1, 2, -3));
  EXPECT_NO_THROW(validate_point(0, 1, -1));
  EXPECT_NO_THROW(validate_point(-1, 0, 2));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  expect_error<btob::core::InvalidField>([&] { validate_point(nan, 0, -1); }, {"point: got", "finite"});
  expect_error<btob::core::InvalidField>([&] { validate_point(1, inf, -1, "initial"); }, {"initial: got", "finite"});
  expect_error<btob::core::InvalidField>([&] { validate_point(0, 0, 0); }, {"point: got the zero vector", "non-zero"});
  // x = z = 0: p = (-z, 0, x) = 0, all four particles in contact; no strip point, no particles.
  expect_error<btob::core::InvalidField>([&] { validate_point(0, 1, 0); }, {"point: got (0, 1, 0)", "x = z = 0"});
  expect_error<btob::core::InvalidField>([&] { validate_point(1, 0, 1); }, {"point: got (1, 0, 1)", "x*z <= 0"});
  // x*z underflows to 0 but the signs agree: still outside the domain.
  expect_error<btob::core::InvalidField>([&] { validate_point(1e-200, 0, 1e-200, "grid"); }, {"grid:", "x*z <= 0"});
  expect_error<btob::core::InvalidField>([&] { validate_point(-1e-200, 0, -1e-200); }, {"point:", "x*z <= 0"});
}

TEST(Validation, RErrors) {
  using btob::core::validate_r;
  EXPECT_NO_THROW(validate_r(0.5));
  EXPECT_NO_THROW(validate_r(1e-300));
  for (double r :
       {0.0, 1.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    expect_error<btob::core::InvalidField>([&] { validate_r(r); }, {"r: got", "open interval (0, 1)"});
  expect_error<btob::core::InvalidField>([] { validate_r(2.0, "r-max"); }, {"r-max: got 2", "(0, 1)"});
  expect_error<btob::core::InvalidField>([] { validate_r(0.0L); }, {"r: got 0"});
}

TEST(Validation, PrecisionNames) {
  using btob::core::parse_precision;
  using btob::core::Precision;
  EXPECT_EQ(parse_precision("float").kind, Precision::Kind::f32);
  EXPECT_EQ(parse_precision("double").kind, Precision::Kind::f64);
  EXPECT_EQ(parse_precision("long-double").kind, Precision::Kind::f80);
  EXPECT_EQ(parse_precision("float128").kind, Precision::Kind::f128);
  const auto p = parse_precision("mpfr:50");
  EXPECT_EQ(p.kind, Precision::Kind::mpfr);
  EXPECT_EQ(p.mpfr_digits, 50);
  for (const char* name : {"float", "double", "long-double", "float128", "mpfr:10", "mpfr:10000"})
    EXPECT_EQ(parse_precision(name).name(), name);
  for (const char* bad : {"mpfr:9", "mpfr:10001", "mpfr:", "mpfr", "mpfr:1e3", "mpfr:-20", "mpfr:99999999999"})
    expect_error<std::invalid_argument>([&] { parse_precision(bad); },
                                        {"precision: got '", "mpfr:<digits> with 10 <= digits <= 10000"});
  expect_error<std::invalid_argument>(
      [] { parse_precision("quad", "scalar"); },
      {"scalar: got 'quad'", "expected one of float, double, long-double, float128, mpfr:<digits>"});
  EXPECT_STREQ(btob::core::scalar_name<double>(), "double");
  EXPECT_STREQ(btob::core::scalar_name<btob::core::float128>(), "float128");
}

}  // namespace

// The lab's CSV writer (core/csv.hpp): one header, a field per column on every row, nothing that needs quoting.
TEST(Csv, RowsMatchTheHeaderAndTextNeedsNoQuoting) {
  btob::core::CsvTable t("attractor,pattern,fraction");
  t.row({"1", "132^3312^3", "0.5"});
  t.row({"0", "a, \"b\" #2\nc", ""});  // text with every character genfromtxt would misread
  t.line("2,132312,0.25");
  EXPECT_EQ(t.text(), "attractor,pattern,fraction\n1,132^3312^3,0.5\n0,a; 'b' no.2 c,\n2,132312,0.25\n");
  EXPECT_EQ(t.rows(), 3u);
  EXPECT_THROW(t.row({"0", "undecided"}), std::logic_error);  // the old fractions.csv's short row
  EXPECT_THROW(t.line("1,2"), std::logic_error);
  EXPECT_THROW(t.line("1,\"a,b\",3"), std::logic_error);  // quoted fields are not read by genfromtxt
  EXPECT_THROW(t.line("1,a#b,3"), std::logic_error);
  EXPECT_THROW(btob::core::CsvTable("# comment,a"), std::logic_error);
  EXPECT_THROW(btob::core::CsvTable("a,b,a"), std::logic_error);
  EXPECT_THROW(btob::core::CsvTable("a,,b"), std::logic_error);
  EXPECT_EQ(btob::core::CsvTable("r,agree_min_r0.11").text(), "r,agree_min_r0.11\n");
}

// A number that is not finite is an empty cell, never "nan" or "inf"; a finite one reads back as written.
TEST(Csv, NonFiniteNumbersAreEmptyCells) {
  using btob::core::csv_number;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(csv_number(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(csv_number(inf), "");
  EXPECT_EQ(csv_number(-inf, "{:.6f}"), "");
  EXPECT_EQ(csv_number(0.1), "0.10000000000000001");  // {:.17g} by default: reads back bitwise
  EXPECT_EQ(std::stod(csv_number(0.1)), 0.1);
  EXPECT_EQ(std::strtod(csv_number(5e-324).c_str(), nullptr), 5e-324);  // subnormals too
  EXPECT_EQ(csv_number(0.25, "{:.6f}"), "0.250000");
  EXPECT_EQ(csv_number(-1234.5, "{:.3g}"), "-1.23e+03");
  btob::core::CsvTable t("r,gap");
  t.line("0.1," + csv_number(std::nan("")));
  EXPECT_EQ(t.text(), "r,gap\n0.1,\n");
}

// distinct_doubles counts representable values by their ordered bit patterns; checked against nextafter stepping
// (an independent route) on small ranges, and against the binade's known count.
TEST(Limits, DistinctDoublesAgreeWithNextafter) {
  for (const auto& [lo, steps] :
       std::vector<std::pair<double, int>>{{0.2, 1}, {0.2, 7}, {-1e-310, 40}, {-0.5, 3}, {1.0, 0}}) {
    double hi = lo;
    for (int k = 0; k < steps; ++k) hi = std::nextafter(hi, 2.0);
    // +0 and -0 are one value: a range across zero counts one double fewer than the nextafter steps give.
    const bool crosses_zero = lo < 0 && hi >= 0;
    EXPECT_EQ(btob::core::distinct_doubles(lo, hi), steps + 1 - (crosses_zero ? 1 : 0)) << lo << " + " << steps;
  }
  EXPECT_EQ(btob::core::distinct_doubles(1.0, 2.0), std::ldexp(1.0, 52) + 1);
  // [-2, 2]: 2^62 doubles on each side of zero and zero once, 2^63 + 1, which rounds to 2^63 in double (the key
  // difference overflowed int64 and gave -2^63 before).
  EXPECT_EQ(btob::core::distinct_doubles(-2.0, 2.0), std::ldexp(1.0, 63));
  // The user's 5000 values in [0.2, 0.2 + 1e-16]: 0.2 + 1e-16 rounds to 0.2 plus 4 units in the last place (the ulp
  // of 0.2 is 2^-55 = 2.8e-17), so the range holds 5 doubles, counted here by nextafter.
  const double hi = 0.2 + 1e-16;
  long n = 1;
  for (double x = 0.2; x < hi; x = std::nextafter(x, 1.0)) ++n;
  EXPECT_EQ(n, 5);
  EXPECT_EQ(btob::core::distinct_doubles(0.2, hi), n);
  EXPECT_THROW(btob::core::require_distinct(0.2, hi, n + 1, "r-count", "r-min..r-max"), btob::core::InvalidField);
  EXPECT_THROW(btob::core::require_distinct(0.2, hi, 5000, "r-count", "r-min..r-max"), btob::core::InvalidField);
  EXPECT_NO_THROW(btob::core::require_distinct(0.2, hi, n, "r-count", "r-min..r-max"));
}

// An error quotes a long input by its head and tail with its length; a short one whole; the description after a
// quoted input is kept.
TEST(Limits, ErrorsQuoteLongInputsShort) {
  const std::string word(100002, '1');
  const btob::core::InvalidField e("word", "'" + word + "', symbol 4 at position 100001", "a word over 1, 2, 3");
  const std::string what = e.what();
  EXPECT_LT(what.size(), 200u) << what;
  EXPECT_NE(what.find("(100002 characters), symbol 4 at position 100001"), std::string::npos) << what;
  EXPECT_NE(what.find("'111111"), std::string::npos) << what;
  EXPECT_EQ(btob::core::abbreviate("'0.5'"), "'0.5'");
  EXPECT_EQ(btob::core::abbreviate(std::string(80, 'x')), std::string(80, 'x'));
  EXPECT_EQ(btob::core::abbreviate(std::string(81, 'x')).size(), 30 + 3 + 30 + std::string(" (81 characters)").size());
}

// The cost model's interpolation and extrapolation (core/size_model.hpp) on given timings: a power law through the
// largest two beyond them, the segment's power law between timed sizes, the timed sizes themselves as measured.
TEST(Limits, SizeFitExtrapolatesThePowerLawOfItsLastSegment) {
  btob::core::SizeFit f;
  f.parameter = "n";
  f.sizes = {8, 16, 32, 64};
  f.seconds = {0.001, 0.01, 0.04, 0.32};  // exponents: -, 2, 3 over the last two
  f.exponent = f.segment(3);
  EXPECT_NEAR(f.exponent, 3, 1e-12);
  EXPECT_NEAR(f.at(128), 0.32 * 8, 1e-12);
  EXPECT_NEAR(f.at(32), 0.04, 1e-15);
  EXPECT_NEAR(f.at(24), 0.01 * std::pow(1.5, 2), 1e-12);  // the 16..32 segment's exponent 2
  EXPECT_TRUE(f.extrapolates(65));
  EXPECT_FALSE(f.extrapolates(64));
  EXPECT_NE(f.note(300).find("extrapolated from sizes 8..64 of n"), std::string::npos) << f.note(300);
}
