// SPDX-License-Identifier: GPL-3.0-or-later
// What a printed number vouches for (docs/reference/numbers.md): core::with_error, the one rule by which lyapunov and
// classify print a value with its error bar, is checked in exact rational arithmetic (GMP) against the double it
// prints; and the status of every decimal a result describes.
#include "core/error_bar.hpp"
#include "core/result.hpp"
#include "patterns/requests.hpp"
#include "windows/requests.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

namespace {

using btob::core::with_error;

// A decimal text ("-4.68e-01", "0.1", "12") as the exact rational it denotes.
mpq_class exact(const std::string& s) {
  std::size_t i = 0;
  const bool neg = !s.empty() && s[0] == '-';
  if (neg || (!s.empty() && s[0] == '+')) ++i;
  std::string digits;
  long exp10 = 0;
  bool point = false;
  for (; i < s.size() && s[i] != 'e' && s[i] != 'E'; ++i) {
    if (s[i] == '.') point = true;
    else digits += s[i], exp10 -= point ? 1 : 0;
  }
  if (i < s.size()) exp10 += std::stol(s.substr(i + 1));
  mpq_class q{mpz_class(digits, 10)};  // base 10: a leading 0 is not octal
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::labs(exp10)));
  q = exp10 >= 0 ? mpq_class(q * p) : mpq_class(q / p);
  q.canonicalize();
  return neg ? mpq_class(-q) : q;
}

void expect_contains(double value, double error) {
  const auto p = with_error(value, error);
  const mpq_class v = exact(p.value), e = exact(p.error), x(value);  // mpq_class(double) is exact
  EXPECT_LE(v - e, x) << value << " +- " << error << " printed " << p.value << " +- " << p.error;
  EXPECT_GE(v + e, x) << value << " +- " << error << " printed " << p.value << " +- " << p.error;
  EXPECT_GE(e, mpq_class(error)) << "the printed bar is never below the stored one";
  // Not wider than needed: the value's rounding is at most 5% of the bar, or half a unit of its 17th digit (below
  // 0.5e-16 |value|) when the bar is finer than a double, and two digits round up by < 10%.
  if (error >= 1e-300) EXPECT_LE(e, mpq_class(1.2 * (error + 1e-16 * std::fabs(value)))) << p.error;
}

// The issue's case: the 1133 sink's exponent at r = 0.15 printed as -0.468347380336 +- 8.88e-16 excluded the
// stored value by 1.3e-13.
TEST(ErrorBar, TheSinkOfTheIssue) {
  expect_contains(-0.4683473803358724, 8.881784197001252e-16);
  const auto p = with_error(-0.4683473803358724, 8.881784197001252e-16);
  EXPECT_EQ(p.error, "9.0e-16");                       // 8.88e-16 and the half unit of the 17th digit, rounded up
  EXPECT_EQ(std::stod(p.value), -0.4683473803358724);  // all 17 digits: the double itself
  EXPECT_EQ(with_error(0.0123456, 0.0002).value, "0.012346");
  EXPECT_EQ(with_error(0.0123456, 0.0002).error, "2.1e-04");  // 2e-4 and the half unit 5e-7, rounded up
}

// A property over 20000 pseudo-random pairs: values of either sign from 1e-30 to 1e5, bars from 1e-18 to 10 times
// the value, zero and subnormal bars and values.
TEST(ErrorBar, PrintedIntervalContainsTheValue) {
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> mant(1, 10), ev(-30, 5), ee(-18, 1);
  for (int k = 0; k < 20000; ++k) {
    const double v = (k % 2 ? -1 : 1) * mant(g) * std::pow(10.0, std::floor(ev(g)));
    const double e = mant(g) * std::pow(10.0, std::floor(ee(g))) * (k % 3 ? std::fabs(v) : 1.0);
    expect_contains(v, e);
  }
  for (double v : {0.0, -0.0, 1.0, -3.5e-310, 1e308})
    for (double e : {0.0, 5e-324, 1e-300, 1e-16, 2.0}) expect_contains(v, e);
  EXPECT_THROW(with_error(NAN, 1), std::invalid_argument);
  EXPECT_THROW(with_error(1, -1), std::invalid_argument);
}

// Every decimal a result describes says what it is; window upper bounds are conjectured even when the lower bounds
// are certified, and a pattern window's ends carry decimals beside their doubles.
TEST(NumberStatus, EveryDecimalHasAStatus) {
  btob::windows::BoundsRequest b;
  b.n = "2..3";
  b.certify = true;
  b.digits = 20;
  btob::core::Contents c;
  btob::windows::run(b).describe(c);
  for (const auto& d : c.decimals) ASSERT_TRUE(c.status.count(d.name)) << d.name;
  EXPECT_EQ(c.status.at("lower_bound_decimal").kind, "certified");
  EXPECT_EQ(c.status.at("upper_bound").kind, "conjectured");
  btob::patterns::WordRequest w;
  w.word = "132312";
  w.window = true;
  w.digits = 30;
  const auto res = btob::patterns::run(w);
  btob::core::Contents pc;
  res.describe(pc);
  ASSERT_FALSE(res.r_low_decimal.empty());
  EXPECT_EQ(pc.status.at("r_low_decimal").kind, "estimated");
  EXPECT_GE(res.r_low_decimal[0].size(), 30u);
  // The double is the MPFR value rounded once; the 30 digits rounded to double may differ by one rounding more.
  EXPECT_LE(std::fabs(std::stod(res.r_low_decimal[0]) - res.r_low[0]), std::ldexp(res.r_low[0], -52));
}

}  // namespace
