// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of patterns::run(CurvesRequest) (Figures 7.1-7.8): the critical values of Theorems 7.1 and 7.3 against
// the paper's 20-digit values, the spectrum against analyse(), the feasibility columns, and the errors.
#include "patterns/curves.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace btob::patterns {
namespace {

double find(const CurvesResult& c, const std::string& what, double near) {
  double best = -1;
  for (const auto& k : c.critical)
    if (k.what == what && (best < 0 || std::abs(k.r - near) < std::abs(best - near))) best = k.r;
  return best;
}

TEST(PatternCurves, CriticalValuesOf132312And13223122) {
  CurvesRequest q;
  q.r_count = 400;
  const CurvesResult a = run(q);
  EXPECT_TRUE(a.reduced);
  EXPECT_EQ(a.analysed, "132");
  // Bisection to 1e-15 on a long double spectrum: 1e-13 leaves room for the eigenvector's conditioning.
  const auto tol = ulps(450, "bisection to 1e-15 (4.5 eps), times the eigenvector's conditioning");
  EXPECT_CLOSE(find(a, "u_x = 0", 0.18), 0.18261545379260806055, tol);  // r_crit,132J,1 (Section 7.1)
  q.word = "13223122";
  q.track = "negative";
  const CurvesResult b = run(q);
  EXPECT_EQ(b.analysed, "1322");
  EXPECT_CLOSE(find(b, "dominance", 0.16), 0.16028989151805950668, tol);  // r_crit,1322J,1
  EXPECT_CLOSE(find(b, "dominance", 0.25), 0.25112749544281462755, tol);  // r_crit,1322J,2
  EXPECT_CLOSE(find(b, "u_x = 0", 0.236), 0.23636180678365848104, tol);   // r_crit,1322J,3
  EXPECT_CLOSE(find(b, "u_z = 0", 0.17), 3 - 2 * std::sqrt(2.0), tol);    // r_crit,1322J,4 = 3 - 2 sqrt 2
}

TEST(PatternCurves, SpectrumAgreesWithTheAnalysis) {
  CurvesRequest q;
  q.r_min = 0.3;
  q.r_max = 0.9;
  q.r_count = 7;
  const CurvesResult c = run(q);
  for (std::size_t i = 0; i < c.r.size(); ++i) {
    // The dominant eigenvalue of J P2 P3 P1 is real for every r (Theorem 7.1) and the verdict is stable above
    // r_crit,132J: its lyapunov2 = log(|l2|/|l1|)/p with p = 6 symbols, l = the reduced eigenvalues squared.
    const Verdict<double> v = analyse<double>(parse_word("132312"), c.r[i]);
    EXPECT_EQ(v.outcome, Outcome::stable);
    double l1 = 0, l2 = 0;
    for (int j = 0; j < 3; ++j) {
      const double m = c.modulus[3 * i + j];
      if (m > l1) l2 = l1, l1 = m;
      else if (m > l2) l2 = m;
    }
    EXPECT_CLOSE(2 * std::log(l2 / l1) / 6, v.lyapunov2,
                 ulps(45000,
                      "two routes; the cubic's conditioning amplifies rounding near close roots "
                      "(measured 22 eps)"));
    EXPECT_CLOSE(std::abs(c.tracked[i]), l1, ulps(4, "the tracked eigenvalue is the dominant one: a modulus").of(1));
    // Feasibility for r > r_crit,132J (Section 7.1): u_z < 0, alpha u_y - u_x > 0, (P1 u)_y < 0, ...
    const std::size_t nf = c.feas_names.size();
    ASSERT_EQ(nf, 10u);
    const double* f = &c.feas[i * nf];
    EXPECT_LT(f[0], 0);  // u_z
    EXPECT_GT(f[2], 0);  // ay-x(v0)
    EXPECT_LT(f[4], 0);  // y(v1)
    EXPECT_LT(f[6], 0);  // ay-z(v1)
    EXPECT_LT(f[8], 0);  // ay-x(v2)
    EXPECT_GT(f[9], 0);  // ay-z(v2)
  }
}

TEST(PatternCurves, ErrorsNameTheField) {
  auto field_of = [](CurvesRequest q) {
    try {
      q.validate();
    } catch (const core::InvalidField& e) {
      return e.field;
    }
    return std::string("none");
  };
  CurvesRequest q;
  q.word = "14";
  EXPECT_EQ(field_of(q), "word");
  q = {};
  q.r_min = 0;
  EXPECT_EQ(field_of(q), "r-min");
  q = {};
  q.r_max = q.r_min;
  EXPECT_EQ(field_of(q), "r-max");
  q = {};
  q.r_count = 1;
  EXPECT_EQ(field_of(q), "r-count");
  q = {};
  q.track = "largest";
  EXPECT_EQ(field_of(q), "track");
}

}  // namespace
}  // namespace btob::patterns
