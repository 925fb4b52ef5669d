// SPDX-License-Identifier: GPL-3.0-or-later
// The single-orbit step of lyapunov/orbit.hpp for MPFR: the mpfr_* C API on the frame's own numbers and its
// preallocated scratch, in place, so that a step allocates nothing (Boost's operators allocate a temporary per
// operation).  The point's arithmetic is the batched kernel's MPFR step operation for operation (map_step with
// mpfr_float: c1 = a y - x and c3 = a y - z fused, x' = r x or |c1|, z' = r z or -|c3|, y' = k (x' + z') -+ y with the
// sum, the product and the last addition each rounded once), so the orbit is the kernel's bit for bit.
#include "core/scalar.hpp"
#include "lyapunov/orbit.hpp"

#include <mpfr.h>

namespace btob::lyapunov::detail {
namespace {

constexpr mpfr_rnd_t kNearest = MPFR_RNDN;

struct Scratch {
  mpfr_ptr c1, c3, xn, zn, t;
};

// One vector's step under the branch (s1, s3), with d1 = a y - x, d3 = a y - z already in s.c1, s.c3: the point's |c1|
// and -|c3| are d1 or -d1 and d3 or -d3 with the signs its branch implies (the tangent vectors take the same signs).
// The point (point = true) takes |c1| and -|c3| themselves, as the kernel does (the same values, and the kernel's
// sign of zero at an exact tie).
inline void vector_step(mpfr_ptr x, mpfr_ptr y, mpfr_ptr z, bool s1, bool s3, mpfr_srcptr r, mpfr_srcptr k,
                        const Scratch& s, bool point) {
  if (s3) mpfr_mul(s.xn, r, x, kNearest);
  else if (point) mpfr_abs(s.xn, s.c1, kNearest);
  else if (s1) mpfr_swap(s.xn, s.c1);
  else mpfr_neg(s.xn, s.c1, kNearest);
  if (s1) mpfr_mul(s.zn, r, z, kNearest);
  else if (point) {
    mpfr_abs(s.zn, s.c3, kNearest);
    mpfr_neg(s.zn, s.zn, kNearest);
  } else if (s3) mpfr_swap(s.zn, s.c3);
  else mpfr_neg(s.zn, s.c3, kNearest);
  mpfr_add(s.t, s.xn, s.zn, kNearest);
  mpfr_mul(s.t, s.t, k, kNearest);
  if (s1 || s3) mpfr_sub(y, s.t, y, kNearest);
  else mpfr_add(y, s.t, y, kNearest);
  mpfr_swap(x, s.xn);
  mpfr_swap(z, s.zn);
}

}  // namespace

// Per step, for the point and the tangent vector: 4 fused a y - x, 2 products k (x' + z'), 2 additions x' + z', 2
// additions of -+y, and 2 r x or r z products on branches 1 and 3 (none on 2): 10 to 12 MPFR operations.
// Over the averaged steps the state after each step goes to the trace in long double (mpfr_get_ld: 6 conversions
// against the step's 10 to 12 operations).
template <>
void advance<core::mpfr_float>(OrbitFrame<core::mpfr_float>& f, long n, long first, std::uint8_t* ring,
                               Trace<long double> tr) {
  mpfr_ptr x = f.u[0].backend().data(), y = f.u[1].backend().data(), z = f.u[2].backend().data();
  mpfr_ptr v[3];
  for (int i = 0; i < 3; ++i) v[i] = f.v[i].backend().data();
  const mpfr_srcptr r = f.r.backend().data(), a = f.a.backend().data(), k = f.k.backend().data();
  const Scratch s{f.scratch[0].backend().data(), f.scratch[1].backend().data(), f.scratch[2].backend().data(),
                  f.scratch[3].backend().data(), f.scratch[4].backend().data()};  // allocated with the frame
  for (long i = 0; i < n; ++i) {
    mpfr_fms(s.c1, a, y, x, kNearest);
    mpfr_fms(s.c3, a, y, z, kNearest);
    const bool s1 = mpfr_sgn(s.c1) > 0, s3 = mpfr_sgn(s.c3) < 0;  // exact signs: MPFR's range has no underflow here
    // The point: |c1| = c1 on branch 1, -c1 on branch 2; -|c3| = c3 on branch 3, -c3 on branch 2.
    vector_step(x, y, z, s1, s3, r, k, s, true);
    mpfr_fms(s.c1, a, v[1], v[0], kNearest);
    mpfr_fms(s.c3, a, v[1], v[2], kNearest);
    vector_step(v[0], v[1], v[2], s1, s3, r, k, s, false);
    ring[(first + i) & (kSymbolRing - 1)] = static_cast<std::uint8_t>(s1 ? 1 : (s3 ? 3 : 2));
    if (tr.at) {
      const mpfr_srcptr state[6] = {x, y, z, v[0], v[1], v[2]};
      for (int c = 0; c < 6; ++c) tr.at[c * tr.stride + i + 1] = mpfr_get_ld(state[c], kNearest);
    }
  }
}

}  // namespace btob::lyapunov::detail
