// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of btob::reference (include this to use another scalar type than the instantiated ones).
#pragma once

#include "core/cancel.hpp"
#include "core/request.hpp"
#include "core/run.hpp"
#include "iterate/parallel.hpp"
#include "reference/reference.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace btob::reference {
namespace detail {

template <class T> Vec3<T> unit_vector(int axis) {
  Vec3<T> e(T(0), T(0), T(0));
  e(axis) = T(1);
  return e;
}
inline int axis_of(char letter) { return letter - 'a'; }  // a -> x (p1), b -> y (p2), c -> z (p3)

// a x b, adding |a| |b| / |a x b| to `condition` (the amplification of relative rounding errors).
template <class T> Vec3<T> cross_counted(const Vec3<T>& a, const Vec3<T>& b, T& condition) {
  const Vec3<T> c = a.cross(b);
  condition += a.norm() * b.norm() / c.norm();
  return c;
}

template <class T> bool finite3(const Vec3<T>& v) {
  using std::isfinite;
  return isfinite(v(0)) && isfinite(v(1)) && isfinite(v(2));
}

}  // namespace detail

template <class T> Mat3<T> collision_matrix(char letter, const T& r) {
  const T a = core::alpha(r);
  Mat3<T> m = Mat3<T>::Identity();
  switch (letter) {  // eq. (2.7): column i carries the collision of pair i
    case 'a':
      m(0, 0) = -r;
      m(1, 0) = a;
      break;
    case 'b':
      m(0, 1) = a;
      m(1, 1) = -r;
      m(2, 1) = a;
      break;
    case 'c':
      m(1, 2) = a;
      m(2, 2) = -r;
      break;
    default: throw std::invalid_argument(std::string("collision letter: got '") + letter + "', expected a, b or c");
  }
  return m;
}

// ---- Definition 2.1 ----

template <class T> CrossProductImage<T> cross_product_map(const Vec3<T>& u_in, const T& r) {
  CrossProductImage<T> out{u_in, {}, false, T(0)};
  Vec3<T> u = u_in;
  if (u(0) < 0) u = -u;  // step 1
  out.degenerate = u(0) == 0 || u(1) == 0 || u(2) == 0;
  {
    // Scale by an exact power of two to max |coordinate| in [1, 2) before normalising: |u| of a subnormal or a
    // 1e300-scaled input under- or overflows (the direction came out NaN; tests/test_properties.cpp).
    using std::frexp;
    using std::ldexp;
    int e = 0;
    frexp(u.cwiseAbs().maxCoeff(), &e);
    for (int i = 0; i < 3; ++i) u(i) = ldexp(u(i), 1 - e);
  }
  u /= u.norm();
  const Mat3<T> K[3] = {collision_matrix<T>('a', r), collision_matrix<T>('b', r), collision_matrix<T>('c', r)};
  // At contact e, the sign of q.v chooses the next contact: "next_if_positive" when q.v > 0, else
  // "next_if_negative" (Definition 2.1, step 3).
  constexpr char next_if_positive[3] = {'b', 'c', 'a'};  // after a, b, c
  constexpr char next_if_negative[3] = {'c', 'a', 'b'};
  char contact = 'b';  // step 2
  bool tied = false;   // the second contact was a tie: the third goes to b
  for (int collisions = 0; collisions < 4; ++collisions) {
    const int i = detail::axis_of(contact);
    const Vec3<T> e = detail::unit_vector<T>(i);
    const Vec3<T> p = detail::cross_counted(u, e, out.condition);
    const Vec3<T> q = detail::cross_counted(p, u, out.condition);
    const Vec3<T> v = u - u.dot(e) * e;
    const T qv = q.dot(v);
    // At the second contact (a or c) the sign of q.v is the sign of alpha y - x (alpha y - z): the branch line.
    // Where it is zero within this route's rounding (4 eps times the cross products' condition, relative to
    // |q| |v|), the point is taken to lie on the line and goes where the map's tie rule sends it (core::branch:
    // symbol 2), through the third letter and then b: acb or cab.
    using std::abs;
    const T band = 4 * std::numeric_limits<T>::epsilon() * out.condition * q.norm() * v.norm();
    const bool tie = collisions == 1 && abs(qv) <= band;
    if (qv == 0 || tie) out.degenerate = true;
    if (tie) contact = contact == 'a' ? 'c' : 'a';
    else if (tied) contact = 'b';
    else contact = qv > 0 ? next_if_positive[i] : next_if_negative[i];
    tied = tied || tie;
    const int j = detail::axis_of(contact);
    const Vec3<T> p1 = detail::cross_counted(detail::unit_vector<T>(j), u, out.condition);
    const Vec3<T> q1 = K[j] * q;
    u = detail::cross_counted(q1, p1, out.condition);  // step 4
    u /= u.norm();                                     // u stays on S^2 (only its direction is used)
    out.letters += contact;
    if (contact == 'b') break;  // step 5
  }
  out.u = u;
  return out;
}

// ---- Particle simulation ----

namespace detail {

// One attempt from (p, q - lambda p).  Pair j collides first among those approaching (q_j < 0, p_j > 0):
// the smallest t_j = -p_j / q_j.
template <class T> ParticleCycle<T> particle_attempt(const core::Particles<T>& start, const T& r, const T& lambda) {
  ParticleCycle<T> out{start, {}, lambda, T(0), T(0), ParticleStatus::ok};
  Vec3<T> p = start.p, q = start.q - lambda * start.p;
  const Mat3<T> K[3] = {collision_matrix<T>('a', r), collision_matrix<T>('b', r), collision_matrix<T>('c', r)};
  for (int collisions = 0; collisions < 4; ++collisions) {
    int first = -1;
    T t_first = std::numeric_limits<T>::infinity();
    for (int j = 0; j < 3; ++j) {
      if (!(q(j) < 0) || !(p(j) > 0)) continue;
      const T t = -p(j) / q(j);
      if (t < t_first) {
        t_first = t;
        first = j;
      }
    }
    if (first < 0) {
      out.status = ParticleStatus::separated;
      break;
    }
    const T before = p.norm() + t_first * q.norm();
    p += t_first * q;  // free flight (eq. 2.5b)
    out.condition += before / p.norm();
    p(first) = T(0);                                          // exactly in contact
    for (int j = 0; j < 3; ++j) p(j) = std::max(p(j), T(0));  // rounding must not cross another wall
    q = K[first] * q;                                         // eq. (2.6)
    out.time += t_first;
    out.letters += static_cast<char>('a' + first);
    if (first == 1) {
      out.state = {p, q};
      out.condition += p.norm() * q.norm() / p.cross(q).norm();
      return out;
    }
  }
  if (out.status == ParticleStatus::ok) out.status = ParticleStatus::too_many;
  out.state = {p, q};
  return out;
}

}  // namespace detail

template <class T> ParticleCycle<T> simulate_b_to_b(const core::Particles<T>& start, const T& r) {
  ParticleCycle<T> out = detail::particle_attempt(start, r, T(0));
  const T scale = start.q.norm() / start.p.norm();
  T lambda = scale;
  for (int k = 0; k <= 40 && out.status == ParticleStatus::separated; ++k, lambda *= 4)
    out = detail::particle_attempt(start, r, lambda);
  return out;
}

// ---- Appendix A.1 ----

template <class T> TrigState<T> trig_start(const T& theta0, const T& phi0) {
  using std::cos;
  using std::sin;
  TrigState<T> s;
  s.X = Vec3<T>(sin(theta0), T(0), cos(theta0));
  s.V = cos(phi0) * Vec3<T>(cos(theta0), T(0), -sin(theta0)) + sin(phi0) * Vec3<T>(T(0), T(1), T(0));
  s.contact = 2;
  return s;
}

namespace detail {
// The MATLAB code's table of the next contact after contact c (1, 2, 3 for a, b, c): the unnormalised point X and
// its letter, on the branch phi < pi/2 (`low`) or above, from sin/cos of theta (st, ct) and of phi (sp, cp).
template <class T>
std::pair<Vec3<T>, char> trig_next_contact(int c, bool low, const T& st, const T& ct, const T& sp, const T& cp) {
  switch (c) {
    case 1:
      if (low) return {Vec3<T>(ct * sp, T(0), cp), 'b'};
      return {Vec3<T>(st * sp, -cp, T(0)), 'c'};
    case 2:
      if (low) return {Vec3<T>(cp, ct * sp, T(0)), 'c'};
      return {Vec3<T>(T(0), st * sp, -cp), 'a'};
    default:
      if (low) return {Vec3<T>(T(0), cp, ct * sp), 'a'};
      return {Vec3<T>(-cp, T(0), st * sp), 'b'};
  }
}
}  // namespace detail

template <class T> TrigStatus trig_collision(TrigState<T>& s, const T& r, T* theta_out, T* phi_out) {
  using std::acos;
  using std::cos;
  using std::sin;
  if (!detail::finite3(s.X) || !detail::finite3(s.V)) return TrigStatus::nan_state;
  // The MATLAB code reads theta from X(contact's neighbour) and cos(phi) from one entry of V:
  //   contact 1 (a): theta = acos(X2), cos phi = V3 / cos theta
  //   contact 2 (b): theta = acos(X3), cos phi = V1 / cos theta
  //   contact 3 (c): theta = acos(X1), cos phi = V2 / cos theta
  const int c = s.contact;
  const int ix = c == 1 ? 1 : (c == 2 ? 2 : 0);
  const int iv = c == 1 ? 2 : (c == 2 ? 0 : 1);
  const T ct_arg = s.X(ix);
  if (!(ct_arg >= -1 && ct_arg <= 1)) return TrigStatus::acos_domain;
  if (ct_arg == 1 || ct_arg == -1) return TrigStatus::angle_lost;
  const T theta = acos(ct_arg);
  const T cos_phi = s.V(iv) / cos(theta);
  if (!(cos_phi >= -1 && cos_phi <= 1)) return TrigStatus::acos_domain;
  if (cos_phi == 1 || cos_phi == -1) return TrigStatus::angle_lost;
  const T phi = acos(cos_phi);
  const T half_pi = acos(T(0));  // pi/2 in T
  if (phi == half_pi) return TrigStatus::tie;
  const bool low = phi < half_pi;
  const T st = sin(theta), ct = cos(theta), sp = sin(phi), cp = cos(phi);
  auto [X, letter] = detail::trig_next_contact(c, low, st, ct, sp, cp);
  X = X / X.norm();
  Vec3<T> V = collision_matrix<T>(letter, r) * s.V;
  V = V - V.dot(X) * X;
  V = V / V.norm();
  if (!detail::finite3(X) || !detail::finite3(V)) return TrigStatus::nan_state;
  s.X = X;
  s.V = V;
  s.contact = letter - 'a' + 1;
  if (theta_out) *theta_out = theta;
  if (phi_out) *phi_out = phi;
  return TrigStatus::ok;
}

template <class T> TrigCycle<T> trig_b_to_b(TrigState<T>& s, const T& r) {
  using std::acos;
  using std::cos;
  TrigCycle<T> out{T(0), T(0), {}, TrigStatus::ok};
  TrigState<T> work = s;
  for (int k = 0; k < 3; ++k) {
    out.status = trig_collision(work, r);
    if (out.status != TrigStatus::ok) return out;
    out.letters += static_cast<char>('a' + work.contact - 1);
    if (work.contact == 2) break;
  }
  if (work.contact != 2) {
    out.status = TrigStatus::bad_sequence;
    return out;
  }
  // The angles the next pass of the MATLAB loop reads (contact 2): theta = acos(X3), phi = acos(V1 / cos theta).
  const T x3 = work.X(2);
  if (!(x3 >= -1 && x3 <= 1)) {
    out.status = TrigStatus::acos_domain;
    return out;
  }
  if (x3 == 1 || x3 == -1) {
    out.status = TrigStatus::angle_lost;
    return out;
  }
  out.theta = acos(x3);
  const T cp = work.V(0) / cos(out.theta);
  if (!(cp >= -1 && cp <= 1)) {
    out.status = TrigStatus::acos_domain;
    return out;
  }
  if (cp == 1 || cp == -1) {
    out.status = TrigStatus::angle_lost;
    return out;
  }
  out.phi = acos(cp);
  s = work;
  return out;
}

// ---- Figure 4.7 driver ----

// Orbit o of the ensemble by the trigonometric algorithm: the points of steps first..iterations, x y z per step, in
// buf.  False when a step failed (the orbit is broken); a cancelled orbit stops early (Cancelled is thrown by the
// caller).
template <class T>
bool trig_orbit_tail(const iterate::Ensemble& ens, std::size_t o, long iterations, long first,
                     const core::CancelToken* cancel, std::vector<double>& buf) {
  const std::size_t n_ic = ens.initial.size();
  const T r = ens.r_at<T>(o / n_ic);  // T's r from the request's decimal
  const Vec3<double>& u0 = ens.initial[o % n_ic];
  Vec3<T> u(T(u0(0)), T(u0(1)), T(u0(2)));
  u = core::to_quadrant<T>(u / u.norm());
  TrigState<T> s = trig_start<T>(core::theta<T>(u), core::phi<T>(u));
  for (long k = 1; k <= iterations; ++k) {
    if (core::cancel_due(cancel, k)) break;  // the partial orbit is discarded: Cancelled is thrown by the caller
    const TrigCycle<T> c = trig_b_to_b(s, r);
    if (c.status != TrigStatus::ok) return false;
    if (k >= first) {
      const Vec3<T> w = core::from_angles<T>(c.theta, c.phi);
      const std::size_t j = static_cast<std::size_t>(3 * (k - first));
      buf[j] = static_cast<double>(w(0));
      buf[j + 1] = static_cast<double>(w(1));
      buf[j + 2] = static_cast<double>(w(2));
    }
  }
  return true;
}

template <class T>
std::vector<std::uint64_t> trig_density(const iterate::Ensemble& ens, long iterations, iterate::DensityRecorder& rec,
                                        int threads, const core::CancelToken* cancel) {
  const std::size_t n_orbits = ens.orbits(), n_ic = ens.initial.size();
  std::vector<std::uint8_t> broken(n_orbits, 0);
  const long first = std::max<long>(rec.first_step(), 1);
  const long tail = iterations >= first ? iterations - first + 1 : 0;
  const int nt = core::thread_count(threads);
  if (static_cast<std::size_t>(nt) > rec.per_thread.size())
    throw core::InvalidField(
        "threads", std::to_string(nt),
        "at most the " + std::to_string(rec.per_thread.size()) + " threads the density recorder was made for");
  iterate::parallel_for_scratch(
      n_orbits, nt, [&] { return std::vector<double>(static_cast<std::size_t>(3 * std::max<long>(tail, 1))); },
      [&](std::vector<double>& buf, std::size_t o) {
        if (cancel && cancel->cancelled()) return;  // no exception may leave an OpenMP region
        if (!trig_orbit_tail<T>(ens, o, iterations, first, cancel, buf)) {
          broken[o] = 1;
          return;
        }
        for (long k = first; k <= iterations; ++k) {
          const std::size_t j = static_cast<std::size_t>(3 * (k - first));
          rec.record(o, 1, k, &buf[j], &buf[j + 1], &buf[j + 2], nullptr);
        }
      });
  core::check_cancel(cancel);
  std::vector<std::uint64_t> per_r(ens.r.size(), 0);
  for (std::size_t o = 0; o < n_orbits; ++o) per_r[o / n_ic] += broken[o];
  return per_r;
}

}  // namespace btob::reference
