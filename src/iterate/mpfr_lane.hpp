// SPDX-License-Identifier: GPL-3.0-or-later
// One MPFR orbit's steps for the batched kernel's one-lane batch (kernel_impl.hpp, steps): map_step's operations on
// the mpfr_* C API, in place on the lane's own numbers and on three scratch numbers kept per thread, so that a step
// allocates nothing (Boost's operators allocate a temporary per operation).  Included only by kernel_impl.hpp.
#pragma once

#include <mpfr.h>

#include <concepts>
#include <cstdint>

namespace btob::iterate::detail {

// Boost's mpfr_float (its backend's data() is the mpfr_t), named without including Boost.Multiprecision here.
template <class T>
concept MpfrNumber = requires(T& t) {
  { t.backend().data() } -> std::convertible_to<mpfr_ptr>;
};

// c1, c3 and the sum x' + z' of a step, at the lane's precision: allocated when a thread first steps an MPFR lane
// and when the precision changes, not per step.
struct MpfrScratch {
  mpfr_t c1, c3, t;
  mpfr_prec_t prec = 0;
  MpfrScratch() = default;
  MpfrScratch(const MpfrScratch&) = delete;
  MpfrScratch& operator=(const MpfrScratch&) = delete;
  ~MpfrScratch() {
    if (prec) mpfr_clears(c1, c3, t, static_cast<mpfr_ptr>(nullptr));
  }
  void at(mpfr_prec_t p) {
    if (p == prec) return;
    if (prec) mpfr_clears(c1, c3, t, static_cast<mpfr_ptr>(nullptr));
    mpfr_inits2(p, c1, c3, t, static_cast<mpfr_ptr>(nullptr));
    prec = p;
  }
};
inline thread_local MpfrScratch mpfr_scratch;

// n steps of one lane, operation for operation map_step<T, bool> with T = mpfr_float (each operation rounded once to
// the lane's precision, as Boost rounds each of its operators):
//   c1 = a y - x and c3 = a y - z fused (core::fms); the branch by their exact signs (MPFR's exponent range has no
//   underflow, so a zero is an exact tie: core::sign_of_fms's rule);
//   x' = r x on branch 3, else |c1|;  z' = r z on branch 1, else -|c3|;  y' = k (x' + z') - y on branches 1 and 3,
//   k (x' + z') + y on branch 2 (the sum, the product and the last addition each rounded).
// 6 or 7 mpfr_* operations per step (2 fused, 1 or 2 products by r or none, 1 addition, 1 product by k, 1 addition),
// x, y, z overwritten in place once c1 and c3 are known.
template <class T, bool Sym>
void mpfr_lane_steps(T& X, T& Y, T& Z, const T& R, const T& A, const T& K, std::uint8_t* sym, int n) {
  constexpr mpfr_rnd_t rn = MPFR_RNDN;
  const mpfr_ptr x = X.backend().data(), y = Y.backend().data(), z = Z.backend().data();
  const mpfr_srcptr r = R.backend().data(), a = A.backend().data(), k = K.backend().data();
  MpfrScratch& s = mpfr_scratch;
  s.at(mpfr_get_prec(x));
  for (int i = 0; i < n; ++i) {
    mpfr_fms(s.c1, a, y, x, rn);
    mpfr_fms(s.c3, a, y, z, rn);
    const bool s1 = mpfr_sgn(s.c1) > 0, s3 = mpfr_sgn(s.c3) < 0;
    if (s3) mpfr_mul(x, r, x, rn);
    else mpfr_abs(x, s.c1, rn);
    if (s1) mpfr_mul(z, r, z, rn);
    else mpfr_setsign(z, s.c3, 1, rn);  // -|c3|, -0 at a tie (map_step's negabs_of)
    mpfr_add(s.t, x, z, rn);
    mpfr_mul(s.t, s.t, k, rn);
    if (s1 || s3) mpfr_sub(y, s.t, y, rn);
    else mpfr_add(y, s.t, y, rn);
    if constexpr (Sym) *sym = static_cast<std::uint8_t>(s1 ? 1 : (s3 ? 3 : 2));
  }
}

}  // namespace btob::iterate::detail
