// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/precision: the exact exponent of a periodic word (MPFR Newton solve) against the double route of
// lyapunov::periodic_exponents, its independence from MPFR's ambient precision, and the request's validation.
// The study itself runs in tests/test_long_precision.cpp (~30 s).
#include "core/scalar.hpp"
#include "lyapunov/lyapunov.hpp"
#include "precision/tradeoff.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <string>
#include <vector>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

using btob::core::mpfr_float;
using namespace btob::precision;

struct Sink {
  std::vector<int> word;
  double r;
};
// The sinks of the study's Lyapunov column: 1133 at r = 0.15, 111333 at r = 0.1, 132312 at r = 0.5.
const Sink kSinks[] = {{{1, 1, 3, 3}, 0.15}, {{1, 1, 1, 3, 3, 3}, 0.1}, {{1, 3, 2, 3, 1, 2}, 0.5}};

TEST(ExactLambda1, AgreesWithTheDoubleEigenvalueRoute) {
  for (const Sink& s : kSinks) {
    const double exact = exact_lambda1(s.word, s.r);
    const double dbl = btob::lyapunov::periodic_exponents(s.word, s.r)[0];
    // The double route's eigen-solver gives |l2/l1| to a few eps relative; log of it to ~1e-15, divided by p.
    EXPECT_CLOSE(exact, dbl, ulps(450, "|l2/l1| to a few eps relative, its log to ~5 eps, over p")) << "r = " << s.r;
    EXPECT_LT(exact, 0);  // a sink
  }
}

// MPFR's default precision is process state: exact_lambda1 holds its 60 digits with a guard, so it gives the same
// bits whatever precision the caller had set, and leaves that precision as it was.
TEST(ExactLambda1, IndependentOfTheAmbientPrecision) {
  const unsigned ambient = mpfr_float::default_precision();
  std::vector<double> first;
  for (const Sink& s : kSinks) first.push_back(exact_lambda1(s.word, s.r));
  EXPECT_EQ(mpfr_float::default_precision(), ambient);
  for (int digits : {12, 500}) {
    btob::core::MpfrDigits guard(digits);
    for (std::size_t i = 0; i < std::size(kSinks); ++i)
      EXPECT_EQ(exact_lambda1(kSinks[i].word, kSinks[i].r), first[i]) << digits << " digits";
    EXPECT_EQ(mpfr_float::default_precision(), static_cast<unsigned>(digits));
  }
  EXPECT_EQ(mpfr_float::default_precision(), ambient);
}

TEST(TradeoffRequest, ValidationNamesTheField) {
  const auto field = [](TradeoffRequest req) {
    try {
      req.validate();
    } catch (const btob::core::InvalidField& e) {
      return e.field;
    }
    return std::string("no throw");
  };
  TradeoffRequest ok;
  EXPECT_EQ(field(ok), "no throw");
  TradeoffRequest r = ok;
  r.orbits = 0;
  EXPECT_EQ(field(r), "orbits");
  r = ok;
  r.iterations = 5;
  EXPECT_EQ(field(r), "iterations");
  r = ok;
  r.r = {0.2, 1.0};
  EXPECT_EQ(field(r), "r-values");
  r = ok;
  r.r = {};
  EXPECT_EQ(field(r), "r-values");
  r = ok;
  r.window_n = {2, 2.5};
  EXPECT_EQ(field(r), "window-n");
  r = ok;
  r.window_n = {1};
  EXPECT_EQ(field(r), "window-n");
  r = ok;
  r.window_n = {401};
  EXPECT_EQ(field(r), "window-n");
}

}  // namespace
