// SPDX-License-Identifier: GPL-3.0-or-later
// The scalar types of the lab: float, double, long double, float128 (quadmath) and MPFR (any digits).
#pragma once

#include <boost/multiprecision/float128.hpp>
#include <boost/multiprecision/mpfr.hpp>

#include <cstdlib>
#include <string>
#include <string_view>

namespace btob::core {

using float128 = boost::multiprecision::float128;
using mpfr_float = boost::multiprecision::mpfr_float;  // digits set at run time (mpfr_float::default_precision)

// A precision chosen by name: float, double, long-double, float128, mpfr:<digits> (10 <= digits <= 10000).
struct Precision {
  enum class Kind { f32, f64, f80, f128, mpfr } kind = Kind::f64;
  int mpfr_digits = 0;  // decimal digits, for Kind::mpfr
  std::string name() const;
};

// Parses a precision name; throws std::invalid_argument naming the field and the accepted names.
Precision parse_precision(std::string_view text, const char* field = "precision");

// MPFR's default precision set to `digits` decimal digits for the guard's lifetime, the previous one restored on
// every exit path (two runs at different precisions in one process see no state of each other).  In Boost 1.74
// (Debian 12) the default precision is one per process, not per thread (mpfr_float_backend<0>'s plain static):
// that is what lets an OpenMP loop's threads work at the digits set on the thread that opened it, and why two threads
// must never hold guards of different digits at once (each would change the other's working precision).
class MpfrDigits {
 public:
  explicit MpfrDigits(int digits) : previous_(mpfr_float::default_precision()) {
    mpfr_float::default_precision(static_cast<unsigned>(digits));
  }
  ~MpfrDigits() { mpfr_float::default_precision(previous_); }
  MpfrDigits(const MpfrDigits&) = delete;
  MpfrDigits& operator=(const MpfrDigits&) = delete;

 private:
  unsigned previous_;
};

// The T nearest a decimal text (correctly rounded: strtof/strtod/strtold, quadmath's strtoflt128, mpfr_set_str at
// MPFR's current default precision).  The text is one core::Decimal::parse accepted.
template <class T> T from_decimal(const std::string& text) {
  if constexpr (std::is_same_v<T, float>) return std::strtof(text.c_str(), nullptr);
  else if constexpr (std::is_same_v<T, double>) return std::strtod(text.c_str(), nullptr);
  else if constexpr (std::is_same_v<T, long double>) return std::strtold(text.c_str(), nullptr);
  else return T(text);
}

template <class T> constexpr const char* scalar_name() {
  if constexpr (std::is_same_v<T, float>) return "float";
  else if constexpr (std::is_same_v<T, double>) return "double";
  else if constexpr (std::is_same_v<T, long double>) return "long-double";
  else if constexpr (std::is_same_v<T, float128>) return "float128";
  else return "mpfr";
}

}  // namespace btob::core
