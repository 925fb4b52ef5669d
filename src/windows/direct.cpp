// SPDX-License-Identifier: GPL-3.0-or-later
// The matrix and polynomial routes to the window lower bound in float .. MPFR (the precision study).
#include "windows/direct.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace btob::windows {

const char* route_name(Route r) { return r == Route::matrix ? "matrix" : "polynomial"; }

namespace {

template <class T> using M3 = std::array<T, 9>;

template <class T> M3<T> mul(const M3<T>& x, const M3<T>& y) {
  M3<T> z;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) z[3 * i + j] = x[3 * i] * y[j] + x[3 * i + 1] * y[3 + j] + x[3 * i + 2] * y[6 + j];
  return z;
}

// tr(J base^n) as mantissa * 2^exponent: after each product the matrix is scaled by an exact power of two.
template <class T> T scaled_trace_power(const M3<T>& base, int n, long& exponent) {
  using std::abs;
  using std::frexp;
  using std::ldexp;
  M3<T> m = base;
  exponent = 0;
  for (int k = 0; k <= n; ++k) {
    T big = 0;
    for (const T& v : m) big = abs(v) > big ? abs(v) : big;
    int e = 0;
    (void)frexp(big, &e);
    for (T& v : m) v = ldexp(v, -e);
    exponent += e;
    if (k + 1 < n) m = mul(base, m);
    else break;
  }
  return m[6] + m[4] + m[2];  // tr(J M) = M_31 + M_22 + M_13
}

template <class T> T from_rational(const mpz_class& num, const mpz_class& den) {
  // Through MPFR with 60 digits (more than float128's 34), then to T by its decimal string.
  std::string s;
  {
    core::MpfrDigits sixty(60);
    const mpfr_float q = mpfr_float(num.get_mpz_t()) / mpfr_float(den.get_mpz_t());
    s = q.str(40, std::ios_base::scientific);
  }
  if constexpr (std::is_same_v<T, float>) return std::strtof(s.c_str(), nullptr);
  else if constexpr (std::is_same_v<T, double>) return std::strtod(s.c_str(), nullptr);
  else if constexpr (std::is_same_v<T, long double>) return std::strtold(s.c_str(), nullptr);
  else return T(s);
}

template <class T> T r_crit2_in(int n) {
  using std::cos;
  using std::sqrt;
  const T c = cos(boost::math::constants::pi<T>() / T(2 * n));
  const T t = 2 * c - sqrt(4 * c * c - 1);
  return t * t;  // eq. (4.6)
}

}  // namespace

template <class T> T window_condition(int n, const T& r) {
  using std::ldexp;
  const T a = (1 + r) / 2;  // alpha, eq. (2.8)
  // BA and B~A~ = r^2 B(1/r) A(1/r) with A~ = [[-1,0,0],[alpha,r,0],[0,0,r]], B~ = [[r,alpha,0],[0,-1,0],[0,alpha,r]].
  const M3<T> A{-r, T(0), T(0), a, T(1), T(0), T(0), T(0), T(1)};
  const M3<T> B{T(1), a, T(0), T(0), -r, T(0), T(0), a, T(1)};
  const M3<T> At{T(-1), T(0), T(0), a, r, T(0), T(0), T(0), r};
  const M3<T> Bt{r, a, T(0), T(0), T(-1), T(0), T(0), a, r};
  long e1 = 0, e2 = 0;
  const T t1 = scaled_trace_power(mul(B, A), n, e1);    // P_n(r) = t1 2^e1
  const T t2 = scaled_trace_power(mul(Bt, At), n, e2);  // r^(2n) P_n(1/r) = t2 2^e2
  // r^(2n) as mantissa * 2^er.
  using std::frexp;
  int er = 0;
  const T rm = frexp(r, &er);
  T p = 1;
  long ep = 0;
  for (int k = 0; k < 2 * n; ++k) {
    int e = 0;
    p = frexp(p * rm, &e);
    ep += e + er;
  }
  // Q_n / r^(2n) = P_n(r) P_n(1/r) - 1, eq. (4.3).
  return ldexp(t1 * t2 / p, static_cast<int>(e1 + e2 - ep)) - 1;
}

template <class T> T window_lower_bound_in(int n, Route route) {
  validate_n(n);
  using std::sqrt;
  std::vector<T> coef;
  if (route == Route::polynomial) {
    const RationalPoly q = window_polynomial(n);
    for (const auto& c : q.numerator.coefficients()) coef.push_back(from_rational<T>(c, q.denominator));
  }
  auto f = [&](const T& x) -> T {
    if (route == Route::matrix) return window_condition<T>(n, x);
    T v = coef.back();
    for (std::size_t k = coef.size() - 1; k-- > 0;) v = v * x + coef[k];
    return v;
  };
  T lo = T(7) - 4 * sqrt(T(3));  // 7 - 4 sqrt 3, Section 4
  T hi = n >= 2 ? r_crit2_in<T>(n) : T(1) / 2;
  const T flo = f(lo), fhi = f(hi);
  if (!(flo > 0 && fhi < 0)) return std::numeric_limits<T>::quiet_NaN();
  // Tolerance: all but 2 bits of T (the last bits are noise of the evaluation anyway).
  std::uintmax_t max_iter = 300;
  try {
    auto [a, b] = boost::math::tools::toms748_solve(
        f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<T>(std::numeric_limits<T>::digits - 2), max_iter);
    return (a + b) / 2;
  } catch (const std::exception&) {
    return std::numeric_limits<T>::quiet_NaN();  // noisy signs inside the bracket: no answer in T
  }
}

template float window_condition<float>(int, const float&);
template double window_condition<double>(int, const double&);
template long double window_condition<long double>(int, const long double&);
template core::float128 window_condition<core::float128>(int, const core::float128&);
template mpfr_float window_condition<mpfr_float>(int, const mpfr_float&);
template float window_lower_bound_in<float>(int, Route);
template double window_lower_bound_in<double>(int, Route);
template long double window_lower_bound_in<long double>(int, Route);
template core::float128 window_lower_bound_in<core::float128>(int, Route);
template mpfr_float window_lower_bound_in<mpfr_float>(int, Route);

}  // namespace btob::windows
