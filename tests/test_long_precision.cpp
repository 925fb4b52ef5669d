// SPDX-License-Identifier: GPL-3.0-or-later
// The precision study on a small workload (~30 s: the Lyapunov column runs 1e5 steps on three sinks in every
// arithmetic up to 100-digit MPFR).
#include "core/scalar.hpp"
#include "precision/tradeoff.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace btob::precision;

TEST(Tradeoff, SmallStudy) {
  TradeoffRequest req;
  req.orbits = 2;
  req.iterations = 200;
  req.r = {0.2, 0.58};
  req.window_n = {2, 3};
  const unsigned ambient = btob::core::mpfr_float::default_precision();
  const TradeoffResult res = run(req);
  EXPECT_EQ(btob::core::mpfr_float::default_precision(), ambient);  // every MPFR run held its digits in a guard
  ASSERT_EQ(res.rows.size(), 7u);
  for (const TradeoffRow& row : res.rows) {
    ASSERT_EQ(row.agree_min.size(), 2u);
    // At r = 0.2 and 0.58 (quasi-periodic and periodic regimes) no arithmetic loses a symbol in 200 steps.
    for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(row.agree_min[i], 200) << row.method;
    EXPECT_GT(row.rate, 0) << row.method;
    if (row.method == "trig/double") {
      EXPECT_EQ(row.n_max, -1);
      EXPECT_TRUE(std::isnan(row.lyapunov_error));
    } else {
      EXPECT_EQ(row.n_max, 3) << row.method;
      // float's exponent is good to ~1e-7, double and wider to the double resolution of the reported value.
      EXPECT_LT(row.lyapunov_error, row.digits <= 7 ? 1e-5 : 1e-14) << row.method;
      // The weak sink 312^150 at r = 0.171599 (lambda1 = -0.0116): float's rounding moves the orbit off it (its
      // exponent ~0: error ~|lambda1|); double and wider stay on it, to the weighted average's 1e-11 at 4e5 steps.
      if (row.digits <= 7) EXPECT_GT(row.lyapunov_near_neutral, 1e-3) << row.method;
      else EXPECT_LT(row.lyapunov_near_neutral, 1e-10) << row.method;
    }
    // The final state of the wider arithmetics is the reference's to their precision (angle in rad).
    if (row.digits >= 19 && row.method != "trig/double") EXPECT_LT(row.error_median[0], 1e-15) << row.method;
  }
  // One header line, then a row per method (what was run is in notes(), the manifest's description).
  const std::string csv = res.csv();
  EXPECT_EQ(csv.rfind("method,decimal_digits,iterations_per_second,", 0), 0u);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), res.rows.size() + 1);
  EXPECT_NE(btob::precision::TradeoffResult::notes(req).find("n in [2 3]"), std::string::npos);
  btob::core::Contents c;
  res.describe(c);
  EXPECT_EQ(c.find("agree_min")->dims, (std::vector<std::size_t>{7, 2}));
}

}  // namespace
