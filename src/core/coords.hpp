// SPDX-License-Identifier: GPL-3.0-or-later
// Coordinates of a direction u: angles (theta, phi), the strip (w1, w2) of eq. (6.4), particles (p, q).
#pragma once

#include "core/map.hpp"

#include <Eigen/Geometry>  // cross products

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace btob::core {

// theta in [0, pi/2]: tan(theta) = p1/p3 = -z/x (Section 4).  theta = 0 on z = 0, pi/2 on x = 0.
template <class T> T theta(const Vec3<T>& u) {
  using std::atan2;
  const Vec3<T> q = to_quadrant(u);
  return atan2(-q(2), q(0));
}

// phi in [0, pi]: cos(phi) = -y/|u| (eq. (6.1)), computed in the quadrant Q.
template <class T> T phi(const Vec3<T>& u) {
  using std::atan2;
  using std::sqrt;
  const Vec3<T> q = to_quadrant(u);
  // atan2 form: accurate near phi = 0 and pi, where acos loses half the digits.
  return atan2(sqrt(q(0) * q(0) + q(2) * q(2)), -q(1));
}

// The strip of eq. (6.4): w = (y, x + z) / (x - z), w1 in R, w2 in [-1, 1].  Needs x - z > 0.
template <class T> std::pair<T, T> strip(const Vec3<T>& u) {
  const Vec3<T> q = to_quadrant(u);
  const T d = q(0) - q(2);
  return {q(1) / d, (q(0) + q(2)) / d};
}

// The point of the plane x - z = 1 with strip coordinates (w1, w2): u = ((1 + w2)/2, w1, (w2 - 1)/2).
template <class T> Vec3<T> from_strip(const T& w1, const T& w2) { return Vec3<T>((1 + w2) / 2, w1, (w2 - 1) / 2); }

// u from the angles of eq. (2.18): p0 = (sin th, 0, cos th), q0 = (cos ph cos th, sin ph, -cos ph sin th);
// u = -(p0 x q0) = (cos th sin ph, -cos ph, -sin th sin ph), a unit vector in Q.
template <class T> Vec3<T> from_angles(const T& th, const T& ph) {
  using std::cos;
  using std::sin;
  return Vec3<T>(cos(th) * sin(ph), -cos(ph), -sin(th) * sin(ph));
}

// The equal-area chart of Q (Archimedes): theta as above and the height y in [-1, 1]; the uniform measure on the
// sphere of directions restricted to Q (solid angle pi) is (1/pi) dtheta dy.  The same point as
// from_angles(th, acos(-y)), without the acos: u = (s cos th, y, -s sin th), s = sqrt(1 - y^2).
template <class T> Vec3<T> from_height(const T& th, const T& y) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T s = sqrt(std::max(T(0), 1 - y * y));
  return Vec3<T>(s * cos(th), y, -s * sin(th));
}

// Particle configuration right after a b-collision: relative positions p = (p1, 0, p3), p1, p3 >= 0,
// and relative velocities q with q2 > 0 (Section 3).  u is the normal p x q, taken in Q.
template <class T> struct Particles {
  Vec3<T> p;  // relative positions x_{i+1} - x_i
  Vec3<T> q;  // relative velocities v_{i+1} - v_i
};

template <class T> Vec3<T> from_particles(const Particles<T>& c) { return to_quadrant<T>(c.p.cross(c.q)); }

// The configuration with unit |p| and q normal to p (Theorem 4.1 of DoHR025 allows this choice):
// p = u x e_y = (-z, 0, x), q = p x u = (-x y, x^2 + z^2, -y z), both normalised.
template <class T> Particles<T> to_particles(const Vec3<T>& u) {
  const Vec3<T> w = to_quadrant(u);
  Vec3<T> p(-w(2), T(0), w(0));
  Vec3<T> q = p.cross(w);
  p /= p.norm();
  q /= q.norm();
  return {p, q};
}

}  // namespace btob::core
