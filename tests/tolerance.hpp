// SPDX-License-Identifier: GPL-3.0-or-later
// Tolerances of the tests as statements (docs/ARCHITECTURE.md, "Tolerances"): every comparison of two numbers
// says how far apart they may be and why, in one of three forms, and a failure prints both numbers, their
// difference in the units of the statement, and the reason.
//
//   EXPECT_CLOSE(a, b, ulps<double>(8, "one rounding per matrix entry, ..."));   k eps x max(1, |a|, |b|)
//   EXPECT_CLOSE(a, b, ulps<float>(64, "...").of(s0));                           k eps x s0 (a stated magnitude)
//   EXPECT_CLOSE(a, b, statistical(5 * sd, "5 sigma of a binomial count"));     an error bar, sample size
//   EXPECT_CLOSE(a, b, bound(1e-8, "C / n truncation at n = 1e6, C <= 0.5"));  a truncation, bisection width,
//                                                                                 printed decimals: not eps
//   EXPECT_SMALL(err, ulps(16, "..."));      an error already measured (a norm of a difference, an angle, a worst
//                                           case over a loop): |err| within the allowance, compared with 0
//
// With BTOB_TOLERANCE_REPORT set in the environment, every check (passing ones too) prints one line to stderr:
// where its tolerance was stated, the difference measured and the allowance, both in eps where the statement is
// in eps.  That is how the multiples below were checked against what the code does.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <source_location>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

namespace btob::test {

template <class T = double>
inline constexpr long double eps = static_cast<long double>(std::numeric_limits<T>::epsilon());

struct Tolerance {
  enum class Kind { rounding, statistical, bound };
  Kind kind = Kind::rounding;
  long double k = 0;      // rounding: the multiple of eps
  long double unit = 0;   // rounding: the epsilon of the precision the statement is about
  long double scale = 0;  // rounding: a stated magnitude; 0 = max(1, |a|, |b|) of the values compared
  long double tol = 0;    // statistical, bound: the absolute allowance
  long double floor = 0;  // rounding: an absolute allowance below which the multiple is not taken (at_least)
  std::string why;
  std::source_location where;

  // The same multiple of eps, of a stated magnitude instead of the values' own (a singular value, a norm).
  Tolerance of(long double magnitude) const {
    Tolerance t = *this;
    t.scale = magnitude;
    return t;
  }
  // No less than `absolute` (an error model whose conditioning factor can be small while other roundings are not).
  Tolerance at_least(long double absolute) const {
    Tolerance t = *this;
    t.floor = absolute;
    return t;
  }
  long double magnitude(long double a, long double b) const {
    return scale != 0 ? scale : std::max({1.0L, std::fabs(a), std::fabs(b)});
  }
  long double allowed(long double a, long double b) const {
    return kind == Kind::rounding ? std::max(floor, k * unit * magnitude(a, b)) : tol;
  }
};

// k roundings of the precision T, relative to the magnitude of the values compared (at least 1: a quantity of
// order 1 or smaller is compared absolutely to k eps).
template <class T = double>
Tolerance ulps(long double k, std::string why, std::source_location where = std::source_location::current()) {
  return {Tolerance::Kind::rounding, k, eps<T>, 0, 0, 0, std::move(why), where};
}
// An error bar: k sigma / sqrt(N), a binomial count, a Monte Carlo estimate.
inline Tolerance statistical(long double tol, std::string why,
                             std::source_location where = std::source_location::current()) {
  return {Tolerance::Kind::statistical, 0, 0, 0, tol, 0, std::move(why), where};
}
// Neither rounding nor sampling: a truncation or convergence rate, a bisection width, the decimals a table prints.
inline Tolerance bound(long double tol, std::string why, std::source_location where = std::source_location::current()) {
  return {Tolerance::Kind::bound, 0, 0, 0, tol, 0, std::move(why), where};
}

inline const char* kind_name(Tolerance::Kind k) {
  return k == Tolerance::Kind::rounding ? "rounding" : k == Tolerance::Kind::statistical ? "statistical" : "bound";
}

// The gtest predicate behind EXPECT_CLOSE: |a - b| <= allowance (NaN fails).
template <class A, class B>
::testing::AssertionResult close_format(const char* ea, const char* eb, const char*, const A& a_in, const B& b_in,
                                        const Tolerance& t) {
  static_assert(std::is_arithmetic_v<A> && std::is_arithmetic_v<B>, "EXPECT_CLOSE compares built-in numbers");
  const long double a = a_in, b = b_in, diff = std::fabs(a - b), allowed = t.allowed(a, b);
  const bool ok = diff <= allowed;
  const auto in_eps = [&](long double x) { return x / (t.unit * t.magnitude(a, b)); };
  if (std::getenv("BTOB_TOLERANCE_REPORT") != nullptr) {
    if (t.kind == Tolerance::Kind::rounding)
      std::fprintf(stderr, "tolerance %s:%u %s diff %.3Lg eps of allowed %.4Lg eps (magnitude %.3Lg)\n",
                   t.where.file_name(), static_cast<unsigned>(t.where.line()), ok ? "ok" : "FAIL", in_eps(diff),
                   in_eps(allowed), t.magnitude(a, b));
    else
      std::fprintf(stderr, "tolerance %s:%u %s diff %.3Lg of allowed %.3Lg (%s)\n", t.where.file_name(),
                   static_cast<unsigned>(t.where.line()), ok ? "ok" : "FAIL", diff, allowed, kind_name(t.kind));
  }
  if (ok) return ::testing::AssertionSuccess();
  std::ostringstream m;
  m << std::setprecision(std::numeric_limits<long double>::max_digits10) << ea << " = " << a << "\n"
    << eb << " = " << b << "\n|difference| = " << diff;
  if (t.kind == Tolerance::Kind::rounding) {
    m << std::setprecision(4) << " = " << in_eps(diff) << " eps x " << t.magnitude(a, b) << ", allowed " << t.k
      << " eps x " << t.magnitude(a, b);
    if (t.floor > 0) m << " or at least " << t.floor;
    m << " (eps = " << t.unit << ")";
  } else {
    m << std::setprecision(4) << ", allowed " << allowed << " (" << kind_name(t.kind) << ")";
  }
  m << "\nwhy: " << t.why << " [stated at " << t.where.file_name() << ":" << t.where.line() << "]";
  return ::testing::AssertionFailure() << m.str();
}

// EXPECT_SMALL: an error measure against 0 (its magnitude is then max(1, |err|) unless stated with .of()).
template <class A>
::testing::AssertionResult small_format(const char* ea, const char* et, const A& a, const Tolerance& t) {
  return close_format(ea, "0", et, a, 0.0, t);
}

}  // namespace btob::test

#define EXPECT_CLOSE(a, b, tolerance) EXPECT_PRED_FORMAT3(::btob::test::close_format, a, b, tolerance)
#define ASSERT_CLOSE(a, b, tolerance) ASSERT_PRED_FORMAT3(::btob::test::close_format, a, b, tolerance)
#define EXPECT_SMALL(err, tolerance) EXPECT_PRED_FORMAT2(::btob::test::small_format, err, tolerance)
#define ASSERT_SMALL(err, tolerance) ASSERT_PRED_FORMAT2(::btob::test::small_format, err, tolerance)
