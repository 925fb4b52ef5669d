// SPDX-License-Identifier: GPL-3.0-or-later
// Independent routes to the b-to-b map, kept to test core::step and for the precision study:
// the cross-product algorithm of Definition 2.1, an event-driven particle simulation, and the
// trigonometric algorithm of Appendix A.1 (with a bifurcation-diagram driver for Figure 4.7).
#pragma once

#include <Eigen/Geometry>  // cross(); core/coords.hpp uses it without including it (see notes)

#include "core/coords.hpp"
#include "core/map.hpp"
#include "core/request.hpp"
#include "core/scalar.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/recorders.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::reference {

// Conventions:
//  * r in (0, 1) (callers validate with core::validate_r), alpha = (1 + r) / 2 (eq. 2.8).
//  * Collision letters: a = pair 1-2 (p1 = 0), b = pair 2-3 (p2 = 0), c = pair 3-4 (p3 = 0).  A cycle's
//    letters are those after the initial b, ending with the next b: "ab", "acb", "cab" or "cb".
//  * Directions u = (x, y, z) are normals to Span[p, q]; every function here accepts any scalar type
//    T with <cmath>-style functions (explicit instantiations in reference.cpp for float, double,
//    long double and core::float128 (include <boost/multiprecision/eigen.hpp> to use the latter);
//    bodies in reference_impl.hpp for other types).

using core::Mat3;
using core::Vec3;

// The collision matrices A, B, C of eq. (2.7), for letter 'a', 'b' or 'c' (throws on another).
template <class T> Mat3<T> collision_matrix(char letter, const T& r);

// ---- Definition 2.1: the cross-product algorithm ------------------------------------------------

template <class T> struct CrossProductImage {
  Vec3<T> u;            // u' = q' x p' of the last step, unit length, exactly as the algorithm returns it
  std::string letters;  // "ab", "acb", "cab" or "cb"
  bool degenerate;      // the input had x, y or z == 0, or a sign test q.v was 0 (excluded by the definition;
                        // the algorithm then took the q.v < 0 branch), or the second contact's q.v was zero
                        // within rounding (on the branch line: the map's tie rule, symbol 2, was taken)
  T condition;          // sum over the cross products a x b of |a| |b| / |a x b| (>= 1): rounding errors
                        // of u' are about eps * condition radians (large near x, y or z = 0)
};

// P-hat(u) by Definition 2.1, literally: u -> -u if x < 0; contact b; at each contact e:
// p = u x e, q = p x u, v = u - (u.e) e, the sign of q.v picks the next contact e' and K,
// p' = e' x u, q' = K q, u <- q' x p' (normalised, which does not change the direction), until
// contact b.  u must be non-zero, in the domain x*z <= 0.
template <class T> CrossProductImage<T> cross_product_map(const Vec3<T>& u, const T& r);

// ---- Event-driven particle simulation ----------------------------------------------------------

enum class ParticleStatus : std::uint8_t {
  ok,         // reached the next b-collision
  separated,  // no pair approaches any more before a b-collision (even after the retries below)
  too_many,   // more than 3 collisions without a b (impossible by Prop. 4.5 of DoHR025)
};

template <class T> struct ParticleCycle {
  core::Particles<T> state;  // (p, q) right after the next b-collision: p2 = 0, q2 > 0 (not normalised)
  std::string letters;       // collisions of the cycle, e.g. "acb"
  T lambda;                  // the run started from (p, q - lambda p), see simulate_b_to_b
  T time;                    // flight time from the start to the b-collision (units of the input)
  T condition;               // sum over flights of (|p| + t |q|) / |p + t q| plus |p| |q| / |p x q| at the
                             // end: rounding errors of the final plane are about eps * condition
  ParticleStatus status;
};

// From (p, q) right after a b-collision (p2 = 0, q2 > 0, p1, p3 >= 0), free flight p += t q (eq. 2.5b)
// and binary collisions q -> K q (eqs. 2.4-2.5) until the next b-collision.  The velocities are
// first shifted to q - lambda p: this keeps the plane Span[p, q] and so the order of collisions
// (Theorem 4.1 of DoHR025, used in the proof of Theorem 3.3), and makes the pairs approach.  The run
// is tried with lambda = 0, then lambda = 4^k |q| / |p| (k = 0, 1, ..., 40) from the same start
// until the particles reach a b-collision; each try is a genuine trajectory of the 4 particles.
template <class T> ParticleCycle<T> simulate_b_to_b(const core::Particles<T>& start, const T& r);

// ---- Appendix A.1: the trigonometric algorithm --------------------------------------------------

enum class TrigStatus : std::uint8_t {
  ok,
  acos_domain,   // acos got an argument outside [-1, 1] (by rounding, or cos(theta) ~ 0): the paper's
                 // "numerical singularities" (red dots of Figure 4.7); the state is left unchanged
  angle_lost,    // acos got exactly +-1 (theta or phi rounded to 0 or pi, e.g. cos(theta) == 1 once
                 // theta < 1.05e-8 in double): the state fell onto a triple-collision boundary and the
                 // orbit carries no more information (left unchanged)
  nan_state,     // the state became NaN or infinite
  tie,           // phi == pi/2 exactly: neither branch of the MATLAB code applies
  bad_sequence,  // a b-to-b cycle of more than 3 collisions ("aca...", impossible physically)
};
const char* trig_status_name(TrigStatus s);

// The state of the MATLAB code: unit positions X, unit velocities V orthogonal to X, and the pair in
// contact (1 = a, 2 = b, 3 = c).
template <class T> struct TrigState {
  Vec3<T> X, V;
  int contact;
};

// The initial b-state of Appendix A.1 for angles theta0 in (0, pi/2), phi0 in (0, pi), phi0 != pi/2:
// X = (sin th, 0, cos th), V = cos ph (cos th, 0, -sin th) + sin ph (0, 1, 0)  (eq. 2.18).
template <class T> TrigState<T> trig_start(const T& theta0, const T& phi0);

// One pass of the MATLAB while-loop: one collision.  Writes the local angles theta, phi of the state
// before the collision (as the MATLAB code does) when the pointers are non-null.  On a non-ok status
// the state is unchanged.
template <class T> TrigStatus trig_collision(TrigState<T>& s, const T& r, T* theta = nullptr, T* phi = nullptr);

template <class T> struct TrigCycle {
  T theta, phi;         // angles of the new b-state: theta = acos(X3) in [0, pi/2], phi = acos(V1 / cos theta)
  std::string letters;  // collisions of the cycle, e.g. "cab"
  TrigStatus status;
};

// From a b-state (contact == 2) to the next b-state: 2 or 3 calls of trig_collision.  theta and phi
// are those of eq. (2.18) at the new b-collision, so core::from_angles(theta, phi) is P-hat(u).
template <class T> TrigCycle<T> trig_b_to_b(TrigState<T>& s, const T& r);

// ---- Figure 4.7: a bifurcation diagram with the trigonometric algorithm -------------------------

// Runs every orbit of `ensemble` for `iterations` b-to-b steps with the trigonometric algorithm in
// precision T (double or long double), starting from theta, phi of the (normalised) initial vector,
// and counts the tail states into `rec` (first_step() <= k <= iterations, as iterate::run does), each
// state given to rec.record as the unit vector core::from_angles(theta, phi) with lanes = 1.  An orbit
// whose algorithm reports a non-ok status before `iterations` steps is not counted at all (its tail
// is buffered) and is counted as broken instead.  OpenMP over orbits, static schedule, `threads` <= 0
// means OpenMP's default; `rec` must have at least that many per-thread images.  The image and the
// counts do not depend on the thread count.
// Returns the number of broken orbits for each r value (index as ensemble.r).
template <class T>
// `cancel` (here and in trig_density_matlab): polled per orbit and every core::cancel_stride steps; a cancelled
// run throws core::Cancelled after its parallel region.
std::vector<std::uint64_t> trig_density(const iterate::Ensemble& ensemble, long iterations,
                                        iterate::DensityRecorder& rec, int threads = 0,
                                        const core::CancelToken* cancel = nullptr);

// The same orbits with MATLAB's semantics, i.e. what the paper's code draws: acos of an argument outside
// [-1, 1] returns a complex number (acos z = -i log(z + i sqrt(1 - z^2)), principal branches, as MATLAB) and
// the loop goes on in complex arithmetic (norm = sqrt(sum |x_i|^2), dot(V, X) = sum conj(V_i) X_i, the tests
// phi < pi/2 compare real parts); no orbit is stopped.  The real part of theta (or phi) of every tail b-state,
// as MATLAB's plot shows it, is counted into `bins` equal bins over [lo, hi] (Re acos lies in [0, pi]); NaN
// values (overflowing complex states) are counted apart.  OpenMP over r values (static), deterministic.
struct MatlabTrigImage {
  std::vector<std::uint32_t> counts;          // [r values x bins], row-major
  std::vector<std::uint64_t> complex_orbits;  // per r: orbits that took a complex acos at some step
  std::vector<std::uint64_t> nan_points;      // per r: tail values that were NaN (not counted in the image)
  std::vector<std::uint64_t> outside;         // per r: tail values outside [lo, hi]
  std::vector<std::uint64_t> stalled;         // per r: tail states never reached (no b-collision any more)
};
MatlabTrigImage trig_density_matlab(const iterate::Ensemble& ensemble, long iterations, long tail, bool phi, int bins,
                                    double lo, double hi, int threads = 0, const core::CancelToken* cancel = nullptr);

#define BTOB_REFERENCE_EXTERN(T)                                                            \
  extern template Mat3<T> collision_matrix<T>(char, const T&);                              \
  extern template CrossProductImage<T> cross_product_map<T>(const Vec3<T>&, const T&);      \
  extern template ParticleCycle<T> simulate_b_to_b<T>(const core::Particles<T>&, const T&); \
  extern template TrigState<T> trig_start<T>(const T&, const T&);                           \
  extern template TrigStatus trig_collision<T>(TrigState<T>&, const T&, T*, T*);            \
  extern template TrigCycle<T> trig_b_to_b<T>(TrigState<T>&, const T&);
BTOB_REFERENCE_EXTERN(float)
BTOB_REFERENCE_EXTERN(double)
BTOB_REFERENCE_EXTERN(long double)
BTOB_REFERENCE_EXTERN(core::float128)
#undef BTOB_REFERENCE_EXTERN
extern template std::vector<std::uint64_t> trig_density<double>(const iterate::Ensemble&, long,
                                                                iterate::DensityRecorder&, int,
                                                                const core::CancelToken*);
extern template std::vector<std::uint64_t> trig_density<long double>(const iterate::Ensemble&, long,
                                                                     iterate::DensityRecorder&, int,
                                                                     const core::CancelToken*);

}  // namespace btob::reference
