// SPDX-License-Identifier: GPL-3.0-or-later
// The b-to-b map P_r of Theorem 3.3: matrices P1, P2, P3, the branch choice, symbols and collision letters.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace btob::core {

// Conventions (paper, Sections 3 and 6.2):
//  * u = (x, y, z) is a normal vector to the plane Span[p, q] right after a b-collision; only its
//    direction matters (P(-u) = -P(u)).
//  * The domain is the double quadrant x*z <= 0.  Every map evaluation first brings u into the
//    quadrant Q = {x >= 0, z <= 0} (u -> -u when x < 0, or x == 0 and z > 0), which P keeps invariant.
//  * In Q the branch (symbol) is 1 (collisions ab, matrix P1) when alpha*y - x > 0, 3 (cb, P3) when
//    alpha*y - z < 0, and 2 (acb or cab, P2) otherwise.  In Q these tests imply the sign of y used in
//    Theorem 3.3 (alpha*y > x >= 0 forces y > 0, alpha*y < z <= 0 forces y < 0), and the two cannot hold
//    together.  Ties alpha*y - x = 0 or alpha*y - z = 0 go to P2 (Remark 3.6), and so does y = 0.
//  * On x = 0 (p3 = 0: particles 3 and 4 touch at the b-collision) or z = 0 (p1 = 0) the physical
//    system has a triple collision; the map is extended by the same formulas.  z = 0 is invariant under
//    P1 (three-particle collapse of particles 1-2-3, theta -> 0), x = 0 under P3 (theta -> pi/2).
//  * alpha = (1 + r) / 2 (eq. 2.8), r in (0, 1).

template <class T> using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T> using Mat3 = Eigen::Matrix<T, 3, 3>;

// The symbols of Section 6.2: 1 = ab, 2 = acb or cab, 3 = cb.
enum class Symbol : std::uint8_t { ab = 1, acb_or_cab = 2, cb = 3 };

template <class T> T alpha(const T& r) { return (1 + r) / 2; }  // eq. (2.8)

// Theorem 3.3, eqs. (3.5)-(3.6).
template <class T> Mat3<T> P1(const T& r) {
  const T a = alpha(r);
  Mat3<T> m;
  m << -r, r * a, T(0),      //
      -a, a * a - r, r * a,  //
      T(0), T(0), r * r;
  return m;
}
template <class T> Mat3<T> P2(const T& r) {
  const T a = alpha(r);
  Mat3<T> m;
  m << r, -r * a, T(0),      //
      a, -2 * a * a + r, a,  //
      T(0), -r * a, r;
  return m;
}
template <class T> Mat3<T> P3(const T& r) {
  const T a = alpha(r);
  Mat3<T> m;
  m << r * r, T(0), T(0),    //
      r * a, a * a - r, -a,  //
      T(0), r * a, -r;
  return m;
}
// P_i for i in {1, 2, 3}.
template <class T> Mat3<T> P(int i, const T& r) {
  switch (i) {
    case 1: return P1(r);
    case 2: return P2(r);
    case 3: return P3(r);
    default: throw std::invalid_argument("symbol: got " + std::to_string(i) + ", expected 1, 2 or 3");
  }
}
// J of eq. (4.4): swaps x and z.  P3 = J P1 J.
template <class T> Mat3<T> J() {
  Mat3<T> m;
  m << T(0), T(0), T(1), T(0), T(1), T(0), T(1), T(0), T(0);
  return m;
}

// u or -u, whichever lies in Q = {x >= 0, z <= 0} (for u in the domain x*z <= 0).
template <class T> Vec3<T> to_quadrant(const Vec3<T>& u) {
  if (u(0) < 0 || (u(0) == 0 && u(2) > 0)) return -u;
  return u;
}

// a y - x rounded once (a fused multiply-subtract): zero only when a y = x exactly or when the exact value
// lies below the precision's smallest subnormal (sign_of_fms settles that case).  The same bits in every
// route: the batched kernel computes the same fused value (iterate/kernel_impl.hpp, fms), whatever the
// compiler contracts elsewhere.
// always_inline (here and below): the kernel units call these too, compiled for the host's instruction set
// (docs/ARCHITECTURE.md, "Determinism"); each caller gets its own unit's code.
template <class T> [[gnu::always_inline]] inline T fms(const T& a, const T& y, const T& x) {
  using std::fma;  // and fmaq / mpfr_fma for Boost.Multiprecision's float128 and mpfr_float (by ADL)
  return T(fma(a, y, T(-x)));
}
// The exact sign (-1, 0, +1) of a y - x, given d = fms(a, y, x).  A correctly rounded value has the sign of the
// exact one unless it underflows to zero; then a y - x is recomputed with x and y scaled up by the same power of
// two (exact: no bit is lost scaling up, and the sign of a y - x does not change).
template <class T> [[gnu::always_inline]] inline int sign_of_fms(const T& a, const T& y, const T& x, const T& d) {
  if (d > 0) return 1;
  if (d < 0) return -1;
  using std::fabs;
  using std::frexp;
  using std::ldexp;
  const T m = fabs(x) > fabs(y) ? T(fabs(x)) : T(fabs(y));
  int e = 0;
  frexp(m, &e);
  if (m == 0 || e > -16) return 0;  // no underflow possible: a y = x exactly
  const T d2 = fms(a, T(ldexp(y, -e)), T(ldexp(x, -e)));
  return (d2 > 0) - (d2 < 0);
}
// The exact sign of a y - x.
template <class T> [[gnu::always_inline]] inline int exact_sign(const T& a, const T& y, const T& x) {
  return sign_of_fms(a, y, x, fms(a, y, x));
}

// The branch 1, 2 or 3 of a vector already in Q: 1 when a y - x > 0, 3 when a y - z < 0, 2 otherwise (ties
// included), with a = alpha(r) in T and the signs exact (not the signs of rounded differences: a rounded
// product a y can equal x when a y - x is not zero, and which of the two roundings the compiler keeps would
// decide the branch).  This is the branch rule of every route and every precision.
template <class T> int branch(const Vec3<T>& u, const T& r) {
  const T a = alpha(r);
  if (exact_sign(a, T(u(1)), T(u(0))) > 0) return 1;
  if (exact_sign(a, T(u(1)), T(u(2))) < 0) return 3;
  return 2;
}

template <class T> struct Step {
  Vec3<T> u;   // P u (not normalised), in Q
  int symbol;  // 1, 2 or 3
};

// One application of the piecewise-linear map (unnormalised), with the branch it used.
template <class T> Step<T> step(const Vec3<T>& u, const T& r) {
  const Vec3<T> q = to_quadrant(u);
  const int s = branch(q, r);
  return {P(s, r) * q, s};
}

// Collision letters of one step from u in Q: "ab", "cb", "acb" (y > 0) or "cab" (y < 0).  For symbol 2
// with y == 0 the a and c collisions are simultaneous (K = CA = AC, Section 2.1): "(ac)b".
template <class T> std::string letters(int symbol, const Vec3<T>& u_in_quadrant) {
  if (symbol == 1) return "ab";
  if (symbol == 3) return "cb";
  if (u_in_quadrant(1) > 0) return "acb";
  if (u_in_quadrant(1) < 0) return "cab";
  return "(ac)b";
}

namespace detail {
std::string shortest(double v);  // the shortest decimal that reads back as v
// Throws core::InvalidField "FIELD: got R, expected a value in the open interval (0, 1)": the one wording of a bad
// r (core::require_r and validate_r below).
[[noreturn]] void refuse_r(double r, const char* field);
}  // namespace detail
// Validation at the edge (CLI, scenes, public API); the kernel assumes valid input.  r in (0, 1), compared in T
// (an r of T outside (0, 1) converts to a double outside it too, so the message's double says why).
template <class T> void validate_r(const T& r, const char* field = "r") {
  using std::isfinite;
  if (!(r > 0 && r < 1) || !isfinite(static_cast<double>(r))) detail::refuse_r(static_cast<double>(r), field);
}
// A point u = (x, y, z): finite, non-zero, in the domain x*z <= 0; else core::InvalidField naming `field`.
void validate_point(double x, double y, double z, const char* field = "point");

}  // namespace btob::core
