// SPDX-License-Identifier: GPL-3.0-or-later
// Template arithmetic of the periodic-orbit analysis (Section 7), shared by analysis_impl.hpp: the elementary
// functions in T, cancellation polls per symbol, normalised matrix products, 3x3 determinants and cofactors, the
// roots of the characteristic cubic and the eigenvector of a real eigenvalue.
#pragma once

#include "patterns/patterns.hpp"

#include "core/cancel.hpp"
#include "core/scalar.hpp"

#include <boost/multiprecision/eigen.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

namespace btob::patterns {
namespace detail {

template <class T> T abs_(const T& x) {
  using std::abs;
  return abs(x);
}
template <class T> T sqrt_(const T& x) {
  using std::sqrt;
  return sqrt(x);
}
template <class T> T log_(const T& x) {
  using std::log;
  return log(x);
}
template <class T> T exp_(const T& x) {
  using std::exp;
  return exp(x);
}
template <class T> T cos_(const T& x) {
  using std::cos;
  return cos(x);
}
template <class T> T acos_(const T& x) {
  using std::acos;
  return acos(x);
}
template <class T> T cbrt_(const T& x) {
  if (x == 0) return T(0);
  const T a = abs_(x);
  T y = exp_(log_(a) / 3);
  y -= (y * y * y - a) / (3 * y * y);  // one Newton step: exp/log lose a few ulps
  return x < 0 ? T(-y) : y;
}
template <class T> T eps_() { return std::numeric_limits<T>::epsilon(); }

// The cancellation poll inside a loop over a word's symbols, at symbol k (core/cancel.hpp; throws core::Cancelled);
// each such loop also polls once before it starts.  A step is one 3x3 product.  In the processor's types (float,
// double, long double) it takes nanoseconds, so a whole loop over the longest word parse_word accepts (10^5 symbols)
// takes milliseconds and the poll before it suffices: a test at every step cost 3-8% of the feasible atlas's inner
// loop (bm_particles' classify), where words are a few symbols long.  float128 (software, microseconds a step) polls
// every core::cancel_stride symbols; MPFR (up to milliseconds a step at thousands of digits: a 60000-symbol word at
// mpfr:2000 takes a minute) at every symbol.
template <class T> void poll_symbol([[maybe_unused]] const core::CancelToken* cancel, [[maybe_unused]] std::size_t k) {
  if constexpr (std::is_same_v<T, core::mpfr_float>) core::check_cancel(cancel);
  else if constexpr (!std::is_floating_point_v<T>) core::poll_cancel(cancel, static_cast<long>(k));
}

// A matrix product kept normalised: value = exp(log_scale) * m, max |m_ij| = 1.
template <class T> struct Scaled {
  Mat3<T> m = Mat3<T>::Identity();
  T log_scale = T(0);
  void normalise() {
    T mx = T(0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) mx = std::max<T>(mx, abs_<T>(m(i, j)));
    m /= mx;
    log_scale += log_(mx);
  }
};

template <class T> T det3(const Mat3<T>& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

template <class T> Mat3<T> cofactor(const Mat3<T>& a) {
  Mat3<T> c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      c(i, j) = a(i1, j1) * a(i2, j2) - a(i1, j2) * a(i2, j1);
    }
  return c;
}

// Eigenvalues of a real 3x3 matrix from its characteristic polynomial l^3 + a l^2 + b l + c.
template <class T> struct Root {
  T re, im;
  bool real;
};
// The root of largest modulus of l^3 + a l^2 + b l + c: Viete's trigonometric form when D <= 0 (three real roots),
// else stable Cardano (one real root, or a triple root when p = q = 0); then Newton steps on the cubic, kept only
// while |f| decreases (guards near double roots).  three_real: which form was used.
template <class T> T largest_root(const T& a, const T& b, const T& c, bool& three_real) {
  const T p = b - a * a / 3, q = 2 * a * a * a / 27 - a * b / 3 + c;
  const T D = (q / 2) * (q / 2) + (p / 3) * (p / 3) * (p / 3);  // < 0: three distinct real roots
  const auto f = [&](const T& l) -> T { return ((l + a) * l + b) * l + c; };
  const auto df = [&](const T& l) -> T { return (3 * l + 2 * a) * l + b; };
  T l;
  three_real = D <= 0 && p < 0;
  if (three_real) {
    const T m = 2 * sqrt_<T>(-p / 3);
    T arg = 3 * q / (p * m);
    arg = std::clamp<T>(arg, T(-1), T(1));
    const T th = acos_<T>(arg) / 3;
    const T two_pi_3 = 2 * acos_<T>(T(-1)) / 3;
    l = m * cos_<T>(th) - a / 3;
    for (int k = 1; k < 3; ++k) {
      const T x = m * cos_<T>(th - two_pi_3 * k) - a / 3;
      if (abs_<T>(x) > abs_<T>(l)) l = x;
    }
  } else {
    const T s = sqrt_<T>(std::max<T>(D, T(0)));
    const T u = cbrt_<T>(-q / 2 - (q < 0 ? T(-s) : s));
    const T t = u == 0 ? T(0) : T(u - p / (3 * u));
    l = t - a / 3;
  }
  for (int it = 0; it < 4; ++it) {
    const T d = df(l);
    if (d == 0) break;
    const T next = l - f(l) / d;
    if (!(abs_<T>(f(next)) < abs_<T>(f(l)))) break;
    l = next;
  }
  return l;
}

// The three roots: the largest (largest_root), then the other two from the quadratic factor, never from the
// trigonometric form: its roots carry an absolute error of a few ulps of the largest, so two roots far below it come
// out as noise (D's sign itself is cancellation there, and a clamped arccos argument makes them an exact double
// root).
template <class T> std::array<Root<T>, 3> cubic_roots(const T& a, const T& b, const T& c) {
  bool three_real = false;
  const T l = largest_root(a, b, c, three_real);
  std::array<Root<T>, 3> r;
  const T P =
      l != 0 ? T(-c / l) : T(b + l * (a + l));  // product of the other two (l dominant: -c/l has no cancellation)
  // Their sum S: -a - l carries an absolute error of eps |l|, all of S's when the two are far below l; then
  // b = l S + P with |P| << |b| gives S = (b - P) / l to b's relative accuracy instead.
  const T S = l != 0 && abs_<T>(P) <= abs_<T>(b) / 2 ? T((b - P) / l) : T(-a - l);
  // Three real roots: a negative discriminant of the factor is rounding (a near-double root), kept real.
  const T disc = three_real ? std::max<T>(S * S - 4 * P, T(0)) : T(S * S - 4 * P);
  r[0] = {l, T(0), true};
  if (disc < 0) {
    const T im = sqrt_<T>(-disc) / 2;
    r[1] = {S / 2, im, false};
    r[2] = {S / 2, T(-im), false};
  } else {
    const T sq = sqrt_<T>(disc);
    const T m1 = S >= 0 ? T((S + sq) / 2) : T((S - sq) / 2);
    const T m2 = m1 != 0 ? T(P / m1) : T(S - m1);
    r[1] = {m1, T(0), true};
    r[2] = {m2, T(0), true};
  }
  return r;
}

template <class T> T modulus(const Root<T>& x) { return x.real ? abs_<T>(x.re) : sqrt_<T>(x.re * x.re + x.im * x.im); }

// Unit eigenvector of A for the real eigenvalue l: the largest cross product of two rows of A - l I.
template <class T> Vec3<T> eigenvector(const Mat3<T>& A, const T& l) {
  Mat3<T> B = A;
  for (int i = 0; i < 3; ++i) B(i, i) -= l;
  Vec3<T> best = Vec3<T>::Zero();
  T bn = T(-1);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Vec3<T> v(B(i, 1) * B(j, 2) - B(i, 2) * B(j, 1), B(i, 2) * B(j, 0) - B(i, 0) * B(j, 2),
                    B(i, 0) * B(j, 1) - B(i, 1) * B(j, 0));
    const T n = v.squaredNorm();
    if (n > bn) {
      bn = n;
      best = v;
    }
  }
  if (!(bn > 0)) return Vec3<T>(T(1), T(0), T(0));  // A = l I: every vector (does not occur for P_r words)
  return best / sqrt_<T>(bn);
}

}  // namespace detail
}  // namespace btob::patterns
