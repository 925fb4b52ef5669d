// SPDX-License-Identifier: GPL-3.0-or-later
// What the verdict's fixed-size routes (float, double, long double, float128) vouch for: each is checked against
// the same analysis in the next wider type (the reference), and prints only the digits the two share.
//
// Why a second precision rather than an a-priori bound: the eigenvalues of a product of p matrices carry a
// relative error of up to p eps times the growth of the product, divided by the distance to the nearest other root
// (and like sqrt(eps) at a double root), and the growth and the distance are what long words and window ends
// make extreme: 1^200 3^200 at r = 0.07180187 (just below r_crit,2, where two roots merge) gave mu1 in double
// wrong from the 10th digit.  The reference's error is smaller by the ratio of the two epsilons (2^11 for double
// against long double, 2^49 for long double against float128; its square root at a double root), so the
// difference of the two values is the lower route's error to within that factor.
#pragma once

#include "core/scalar.hpp"
#include "patterns/patterns.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace btob::patterns::accuracy {

template <class T> struct Reference;  // the next wider type of each fixed-size route
template <> struct Reference<float> { using type = double; };
template <> struct Reference<double> { using type = long double; };
template <> struct Reference<long double> { using type = core::float128; };
template <> struct Reference<core::float128> { using type = core::mpfr_float; };
// Digits of the MPFR reference of float128 (34 digits) and of the MPFR arithmetic below: 16 more than float128's.
inline constexpr int mpfr_digits = 50;

// Significant decimal digits each route prints at most (what `btob pattern` printed before the check).
template <class T> constexpr int max_digits() {
  if constexpr (std::is_same_v<T, float>) return 9;
  else if constexpr (std::is_same_v<T, double>) return 17;
  else if constexpr (std::is_same_v<T, long double>) return 21;
  else return 34;
}

// x in MPFR (exactly: every type here has at most 113 bits; callers hold an MpfrDigits of mpfr_digits).
template <class T> core::mpfr_float to_mp(const T& x) {
  if constexpr (std::is_same_v<T, core::mpfr_float>) return x;
  else if constexpr (std::is_same_v<T, core::float128>) return core::mpfr_float(x.str(40, std::ios_base::scientific));
  else return core::mpfr_float(x);
}

// x e^s in MPFR, whose exponent range (2^+-2^30 at least) holds what T's does not.
template <class T> core::mpfr_float scaled(const T& x, const T& s) { return to_mp(x) * exp(to_mp(s)); }

// |a - b| / |scale| (0 when a == b; infinite when scale is 0 and a != b).
inline double relative_difference(const core::mpfr_float& a, const core::mpfr_float& b, const core::mpfr_float& scale) {
  if (a == b) return 0;
  if (scale == 0) return std::numeric_limits<double>::infinity();
  return static_cast<double>(abs(core::mpfr_float(a - b)) / abs(scale));
}

// The significant digits d a value of relative error e may be printed with so that the printed number lies within
// one unit of its last digit of the true one: rounding to d digits adds at most half a unit, and a unit is
// 10^(1-d) of the leading digit's place, at least 10^(-d) of the value (a mantissa up to 10), so e <= 0.5 10^(-d)
// suffices; with a factor 2 for the reference's own error (measured: 1^200 3^200 near r_crit,2, where the roots'
// errors go like sqrt(eps)), d = floor(log10(0.25 / e)); at most max_d, at least 0.
inline int vouched_digits(double e, int max_d) {
  if (!(e > 0)) return max_d;
  const double d = std::floor(std::log10(0.25 / e));
  return d < 0 ? 0 : d > max_d ? max_d : static_cast<int>(d);
}

// Decimal text of x e^s with `digits` significant digits: `plain` (the route's own formatting of the unscaled
// value with those digits) when that is a normal number, or zero with x zero, else MPFR's, so that an eigenvalue
// below the type's range prints as 1.0061711e-2300 instead of 0, a subnormal or nan.  0 digits vouched: "~" and
// one digit, the order of magnitude only.
template <class T>
std::string scaled_text(const T& x, const T& s, int digits, const std::string& plain, const T& unscaled) {
  using std::fpclassify;
  const int c = fpclassify(unscaled);
  const bool normal = c == FP_NORMAL || (c == FP_ZERO && x == 0);
  if (normal) return digits < 1 ? "~" + plain : plain;
  const core::mpfr_float v = scaled(x, s);
  std::string text;
  if (digits >= 2) {
    text = v.str(digits - 1, std::ios_base::scientific);
  } else {  // one digit (boost's str takes 0 for "all digits"): the mantissa rounded by hand
    const long e = static_cast<long>(floor(log10(abs(v))));
    text = fmt::format("{:.0f}e{}", static_cast<double>(v / pow(core::mpfr_float(10), e)), e);
  }
  return digits < 1 ? "~" + text : text;
}

// The check of a verdict in T against its reference in the next wider type H.
struct Check {
  std::array<int, 3> re_digits{}, im_digits{};  // per eigenvalue (decreasing modulus): digits vouched
  std::array<double, 3> error{};                // per eigenvalue: |mu - mu_ref| / |mu_ref|
  int lyapunov_digits = 10;                     // the exponents' (printed with 10 at most)
  bool same_outcome = true;
  void fill(int digits) {
    re_digits.fill(digits);
    im_digits.fill(digits);
  }
};

template <class T> std::array<core::mpfr_float, 2> eigen_mp(const EigenInfo<T>& e) {
  return {scaled(e.scaled_re, e.log_scale), scaled(e.scaled_im, e.log_scale)};
}

// Each eigenvalue of v against the nearest of ref's (the order by modulus may differ at a tie), the exponents
// against ref's, and the outcomes.  A reference without a spectrum (its own range guard) vouches for nothing.
template <class T, class H> Check check(const Verdict<T>& v, const Verdict<H>& ref) {
  Check c;
  c.same_outcome = v.outcome == ref.outcome;
  for (std::size_t i = 0; i < v.spectrum.size() && i < 3; ++i) {
    const auto [re, im] = eigen_mp(v.spectrum[i]);
    c.error[i] = std::numeric_limits<double>::infinity();
    if (re == 0 && im == 0) continue;  // lost below the range (det M_w = +-r^k is never 0): no digit vouched
    core::mpfr_float dist = 0, ref_re = 0, ref_im = 0;  // the nearest reference eigenvalue and the distance to it
    for (const auto& f : ref.spectrum) {
      const auto [fr, fi] = eigen_mp(f);
      const core::mpfr_float d = hypot(core::mpfr_float(re - fr), core::mpfr_float(im - fi));
      const double rel = relative_difference(d, 0, hypot(fr, fi));
      if (rel < c.error[i]) {
        c.error[i] = rel;
        dist = d;
        ref_re = fr;
        ref_im = fi;
      }
    }
    const auto part_digits = [&](const core::mpfr_float& part) {
      return vouched_digits(relative_difference(dist, 0, part), max_digits<T>());
    };
    c.re_digits[i] = std::isfinite(c.error[i]) ? part_digits(ref_re) : 0;
    c.im_digits[i] = !std::isfinite(c.error[i]) ? 0 : im == 0 && ref_im == 0 ? max_digits<T>() : part_digits(ref_im);
  }
  const double e2 = relative_difference(to_mp(v.lyapunov2), to_mp(ref.lyapunov2), to_mp(ref.lyapunov2));
  const double e3 = relative_difference(to_mp(v.lyapunov3), to_mp(ref.lyapunov3), to_mp(ref.lyapunov3));
  c.lyapunov_digits = vouched_digits(std::max(e2, e3), 10);
  return c;
}

}  // namespace btob::patterns::accuracy
