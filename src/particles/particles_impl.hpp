// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of the particle simulator (include this for another scalar type than the instantiated ones).
#pragma once

#include "core/cancel.hpp"
#include "particles/particles.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace btob::particles {

template <class T, int G> void collide(Vec<T, G>& q, int j, const T& r) {
  const T a = core::alpha(r);
  const T w = q(j);
  q(j) = -r * w;
  if (j > 0) q(j - 1) += a * w;
  if (j + 1 < G) q(j + 1) += a * w;
}

template <class T, int G> int next_collision(const Gaps<T, G>& s, T& t) {
  int first = -1;
  for (int j = 0; j < G; ++j) {
    if (!(s.q(j) < 0) || s.p(j) < 0) continue;
    const T tj = -s.p(j) / s.q(j);
    if (first < 0 || tj < t) {
      t = tj;
      first = j;
    }
  }
  return first;
}

template <class T, int G> void advance(Gaps<T, G>& s, const T& t, int j, const T& r) {
  s.p += t * s.q;  // eq. (2.2)
  s.p(j) = T(0);   // exactly in contact
  for (int i = 0; i < G; ++i)
    if (s.p(i) < 0) s.p(i) = T(0);  // rounding must not cross another pair
  collide<T, G>(s.q, j, r);
}

template <class T, int G> Eigen::Matrix<T, G + 1, 1> absolute(const Vec<T, G>& g) {
  constexpr int n = G + 1;
  Eigen::Matrix<T, n, 1> x;
  T first = T(0);
  for (int j = 0; j < G; ++j) first -= T(n - 1 - j) * g(j);  // x_1 = -(1/n) sum_j (n - j) p_j (1-based j)
  x(0) = first / T(n);
  for (int j = 0; j < G; ++j) x(j + 1) = x(j) + g(j);
  return x;
}

template <class T, int G> T kinetic_energy(const Vec<T, G>& q) {
  const auto v = absolute<T, G>(q);
  return v.squaredNorm() / 2;
}

namespace detail {
template <class T> T norm3(const Vec<T, 3>& v) {
  using std::sqrt;
  return sqrt(v.squaredNorm());
}
// Multiplies v by 2^-e with e the binary exponent of its largest entry (exact); returns e.
template <class T> long normalise_pow2(Vec<T, 3>& v) {
  using std::abs;
  using std::frexp;
  using std::ldexp;
  T m = T(0);
  for (int i = 0; i < 3; ++i)
    if (abs(v(i)) > m) m = abs(v(i));
  if (!(m > 0)) return 0;
  int e = 0;
  (void)frexp(m, &e);
  for (int i = 0; i < 3; ++i) v(i) = ldexp(v(i), -e);
  return e;
}
template <class T> bool finite(const Vec<T, 3>& v) {
  using std::isfinite;
  return isfinite(v(0)) && isfinite(v(1)) && isfinite(v(2));
}
}  // namespace detail

template <class T>
PatternRun<T> simulate_pattern(const Gaps<T, 3>& start, const std::string& letters, const T& r, long periods,
                               bool rescale, long record_periods, const core::CancelToken* cancel) {
  using std::ldexp;
  PatternRun<T> out;
  Gaps<T, 3> s = start;
  long ep = 0, eq = 0;  // physical p = 2^ep p_scaled, q = 2^eq q_scaled
  const auto record = [&](long period, const T& t, int letter) {
    const auto x = absolute<T, 3>(s.p);
    out.events.push_back(static_cast<double>(period));
    out.events.push_back(static_cast<double>(ldexp(t, static_cast<int>(ep - eq))));
    for (int i = 0; i < 4; ++i) out.events.push_back(static_cast<double>(ldexp(x(i), static_cast<int>(ep))));
    out.events.push_back(letter);
  };
  T prev_t = T(0);
  long prev_d = 0;
  for (long n = 0; n < periods; ++n) {
    core::poll_cancel(cancel, n);
    const T p0 = detail::norm3(s.p), q0 = detail::norm3(s.q);
    T t_period = T(0);
    if (n < record_periods) record(n, t_period, 0);
    for (char expected : letters) {
      T t{};
      const int j = next_collision<T, 3>(s, t);
      if (j < 0) {
        out.failure = "separated (no approaching pair) in period " + std::to_string(n);
        return out;
      }
      const char got = static_cast<char>('a' + j);
      if (got != expected) {
        out.failure = std::string("letter ") + got + " instead of " + expected + " in period " + std::to_string(n);
        return out;
      }
      advance<T, 3>(s, t, j, r);
      t_period += t;
      if (!detail::finite(s.p) || !detail::finite(s.q)) {
        out.failure = "non-finite state in period " + std::to_string(n);
        return out;
      }
      ++out.collisions;
      if (n < record_periods) record(n, t_period, j + 1);
    }
    out.length_ratio.push_back(static_cast<double>(T(detail::norm3(s.p) / p0)));
    out.velocity_ratio.push_back(static_cast<double>(T(detail::norm3(s.q) / q0)));
    const T d = ldexp(t_period, static_cast<int>(ep - eq));
    out.duration.push_back(static_cast<double>(d));
    out.time_ratio.push_back(
        n == 0 ? std::numeric_limits<double>::quiet_NaN()
               : static_cast<double>(T(ldexp(T(t_period / prev_t), static_cast<int>(ep - eq - prev_d)))));
    prev_t = t_period;
    prev_d = ep - eq;
    out.total_time += d;
    ++out.periods_ok;
    if (rescale) {
      ep += detail::normalise_pow2<T>(s.p);
      eq += detail::normalise_pow2<T>(s.q);
    }
  }
  return out;
}

}  // namespace btob::particles
