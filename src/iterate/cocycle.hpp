// SPDX-License-Identifier: GPL-3.0-or-later
// The linear cocycle on the batched kernel: every lane carries its point u and one tangent vector v, both
// multiplied by the step's matrix, in registers (docs/ARCHITECTURE.md, "The cocycle kernel").
#pragma once

#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <concepts>
#include <cstddef>
#include <vector>

namespace btob::iterate {

// What a cocycle run hands its recorder at each checkpoint, for `lanes` consecutive orbits from orbit0, after
// `step` steps (arrays of the kernel's batch width; lanes beyond `lanes` are padding):
//   x, y, z      the point u_k = M_{s_k} ... M_{s_1} u_0 (M_s = P_s / r, the plain kernel's matrices), rescaled:
//                its true length is |u| 2^log2u;
//   vx, vy, vz   the tangent vector w_k = Pi_k M_{s_k} ... M_{s_1} v_0 with Pi_k the orthogonal projection onto
//                u_k's complement, rescaled: its true length is |w| 2^log2v.  Because M maps the line of u_{k-1}
//                onto the line of u_k, Pi_k M Pi_{k-1} = Pi_k M: w_k is exactly the vector that projecting after
//                every step gives (the projective derivative of u -> M u / |M u| is Pi M / |M u|), so
//                log |w_k| - log |u_k| grows at the larger projective Lyapunov exponent;
//   n13          how many of the k steps had symbol 1 or 3 (det M_1 = det M_3 = r, det M_2 = 1);
//   log2u, log2v the sums of the exponents removed by the exact power-of-two rescalings (doubles: exact).
// v_0 is u_0 x e_i / |u_0 x e_i| with e_i the coordinate axis least aligned with u_0 (i the smallest |u_0(i)|, the
// first on ties), u_0 the orbit's start vector in Q; log2u = log2v = 0 at step 0.
// v_0 for a start vector u (any length): u x e_i / |u x e_i|, e_i the coordinate axis least aligned with u.  The one
// choice of the cocycle kernel and of lyapunov::TangentRecorder (their exponents are compared orbit by orbit).
inline Vec3<double> first_tangent(const Vec3<double>& u) {
  int i = 0;
  for (int j = 1; j < 3; ++j)
    if (std::fabs(u(j)) < std::fabs(u(i))) i = j;
  Vec3<double> axis = Vec3<double>::Zero();
  axis(i) = 1;
  return u.cross(axis).normalized();
}

template <class T> struct CocycleBatch {
  std::size_t orbit0 = 0;
  int lanes = 0;
  long step = 0;
  const T *x, *y, *z, *vx, *vy, *vz;
  const double *log2u, *log2v, *n13;
};

// A cocycle recorder says at which steps it wants the state (sorted, distinct, in [0, iterations]) and takes it.
// Calls for different batches may come from different threads at once (write only the batch's orbits).
template <class R>
concept CocycleRecorder = requires(R& rec, const R& crec, const CocycleBatch<double>& b) {
  { crec.checkpoints() } -> std::convertible_to<const std::vector<long>&>;
  rec.record(b);
};

// Steps between two projections of v for scalar type T (a constant of the precision, never of the ensemble, so that
// an orbit's bits do not depend on which r values share its run: MPI ranks, partial batches).  Over K steps the
// component of v along u grows against the rest by at most exp(-K lambda1) (lambda1 < 0 at a sink); projecting
// then loses that many bits to cancellation.  Where one block lost more than cocycle_loss_budget<T> bits (the
// difference of the binary exponents of max|v| before and after projecting) the block is redone for that lane with a
// projection after every step, so no lane ever keeps fewer than digits(T) - budget - 1 correct bits of w.
template <class T> constexpr int cocycle_interval() { return sizeof(T) == 4 ? 8 : 16; }
template <class T> constexpr int cocycle_loss_budget() { return sizeof(T) == 4 ? 12 : 30; }

// Whether run_cocycle<T> takes these r values: the plain kernel's bound on steps between rescalings (which keeps u and
// v normal and finite) must allow one projection interval; true for r >= 4.7e-7 in double, r >= 7.7e-3 in float.
template <class T> bool cocycle_accepts(const std::vector<double>& r) {
  return renormalisation_interval<T>(r) >= cocycle_interval<T>();
}

// Runs every orbit of the ensemble `iterations` steps with the fused cocycle kernel (T = float or double): the same
// symbols and points as iterate::run<T> (the point's steps are the plain kernel's, bit for bit), plus v.  Results
// never depend on threads or on the ensemble's other orbits.  Throws core::Cancelled when cancelled.  When
// opt.redone is set it receives the number of (orbit, block) pairs that were redone (tests check that it is rare).
template <class T, CocycleRecorder Rec>
void run_cocycle(const Ensemble& ensemble, long iterations, Rec& rec, const RunOptions& opt = {});

}  // namespace btob::iterate
