// SPDX-License-Identifier: GPL-3.0-or-later
// Long checks of btob::patterns (label long): Table B.1 windows n = 2..7, the iterator against the analysis
// at every r of Table 6.1, and the 30-digit endpoint of 132312 stable under a change of MPFR precision.
#include "patterns/atlas.hpp"
#include "patterns/patterns.hpp"

#include "core/scalar.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include "reference_tables.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob::patterns;
using btob::core::mpfr_float;

TEST(LongPatterns, TableB1WindowsN2To7) {
  int checked = 0;
  for (const auto& row : btob::testing::table_b1().rows) {  // throws when the table is missing or short
    const std::string &n_s = row[0], &lo_s = row[1], &hi_s = row[2];
    const int n = std::stoi(n_s);
    if (n < 2 || n > 7) continue;
    Word w;
    w.s.assign(static_cast<std::size_t>(n), 1);
    w.s.insert(w.s.end(), static_cast<std::size_t>(n), 3);
    const auto set = stability_set<double>(w, default_grid(), 1e-15);
    ASSERT_EQ(set.size(), 1u) << "n = " << n;
    // Table B.1 prints 12 decimals: 6e-13 covers its rounding.
    const auto printed = bound(6e-13, "Table B.1 prints 12 decimals");
    EXPECT_CLOSE(set[0].lo, std::stod(lo_s), printed) << "n = " << n;
    EXPECT_CLOSE(set[0].hi, std::stod(hi_s), printed) << "n = " << n;
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

TEST(LongPatterns, IteratorAgreesWithTheAnalysisAtTable61) {
  // Every eventually symbol-periodic orbit either sits on a stable orbit of the analysis, or is a neutral
  // rotation (the dominant modulus is shared with a complex pair: |l2|/|l1| = 1 up to 1e-9).
  const DetectionRun d = detect_patterns(table_6_1_r(), 200, 5000, 2000, 5, 500, 0);
  ASSERT_FALSE(d.found.empty());
  for (const auto& f : d.found) {
    const auto v = analyse<double>(f.word, f.r);
    if (v.outcome == Outcome::stable) continue;
    EXPECT_GT(v.spectrum[1].modulus / v.spectrum[0].modulus, 1 - 1e-9)
        << to_paper(f.word) << " at r = " << f.r << ": " << v.reason;
  }
}

TEST(LongPatterns, Endpoint132312IndependentOfPrecision) {
  const auto at = [](unsigned digits) {
    mpfr_float::default_precision(digits);
    const auto s =
        stability_set<mpfr_float>(parse_word("132312"), default_grid(), mpfr_float(pow(mpfr_float(10), -35)));
    return s.at(0).lo;
  };
  const mpfr_float a = at(45), b = at(80);
  mpfr_float::default_precision(80);
  EXPECT_LT(abs(a - b), mpfr_float("1e-33"));  // both bisected to 1e-35; 45 digits carry the product's rounding
}
