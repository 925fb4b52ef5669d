// SPDX-License-Identifier: GPL-3.0-or-later
// Long runs at the extremes (label "long", skipped by CI): one batch of orbits iterated 1e9
// times each, in double and float, at the three-particle collapse, in chaos and on invariant curves.
// Run with: ctest --preset long -R extremes   (about a minute on 2 cores).
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob::iterate;

namespace {
template <class T> void billion(double r) {
  Ensemble e;
  e.r = {r};
  e.initial = random_points(48, 17);  // one SIMD batch in double (6 vectors x 8 lanes)
  const long n = 1000000000L;
  FinalRecorder f(e.orbits(), n);
  SymbolRecorder s(e.orbits(), n - 999, n);
  Both<FinalRecorder, SymbolRecorder> both(f, s);
  std::size_t degenerate = 99;
  RunOptions opt;
  opt.degenerate = &degenerate;
  run<T>(e, n, both, opt);
  EXPECT_EQ(degenerate, 0u) << "r = " << r;
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    const auto& u = f.out[o];
    ASSERT_TRUE(std::isfinite(u(0)) && std::isfinite(u(1)) && std::isfinite(u(2))) << "never NaN, r = " << r;
    EXPECT_CLOSE(u.norm(), 1.0,
                 ulps(8, "FinalRecorder normalises in double: a sqrt of 3 squares and a division (measured 1 eps)"))
        << "never a zero vector";
    EXPECT_GE(u(0), 0);
    EXPECT_LE(u(2), 0);
    for (long k = 0; k < s.count; ++k) ASSERT_TRUE(s.out[o * s.count + k] >= 1 && s.out[o * s.count + k] <= 3);
  }
  if (r < 7 - 4 * std::sqrt(3.0)) {  // three-particle collapse: symbol 1 or 3 forever
    for (std::size_t o = 0; o < e.orbits(); ++o) {
      const std::uint8_t first = s.out[o * s.count];
      EXPECT_TRUE(first == 1 || first == 3);
      for (long k = 0; k < s.count; ++k) ASSERT_EQ(s.out[o * s.count + k], first);
    }
  }
}
}  // namespace

TEST(LongExtremes, BillionIterationsDouble) {
  for (double r : {0.05, 0.11, 0.3}) billion<double>(r);
}
TEST(LongExtremes, BillionIterationsFloat) { billion<float>(0.11); }
