// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of the batched kernel; included only by src/iterate/kernel_*.cpp (kernel flags).
#pragma once

#include "core/cancel.hpp"
#include "core/map.hpp"
#include "core/run.hpp"
#include "iterate/kernel.hpp"
#include "iterate/lanes.hpp"
#include "iterate/mpfr_lane.hpp"

#include <Eigen/Dense>
#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

namespace btob::iterate {
namespace detail {

// One step of the map for all lanes, with the matrices divided by r (M_i = P_i / r: same direction,
// same symbol, better conditioned).  In Q, with c1 = a y - x, c3 = a y - z and k = a / r:
//   M1 u = (c1, k c1 - y + a z, r z)           if c1 > 0          (symbol 1, ab)
//   M3 u = (r x, k c3 - y + a x, c3)           else if c3 < 0     (symbol 3, cb)
//   M2 u = (-c1, y - k (c1 + c3), -c3)         otherwise          (symbol 2, acb/cab; ties go here)
// Rewritten with fewer operations (11 per lane instead of 18, the kernel is throughput-bound):
//   x' = (symbol 3) ? r x : |c1|        (c1 > 0 in case 1, c1 <= 0 in case 2)
//   z' = (symbol 1) ? r z : -|c3|       (c3 < 0 in case 3, c3 >= 0 in case 2)
//   y' = k (x' + z') - y  in cases 1 and 3,  k (x' + z') + y  in case 2
// (case 1: k (c1 + r z) = k c1 + a z; case 3: k (r x + c3) = a x + k c3; case 2: -k (c1 + c3)).
// The selection is branch-free; the quadrant Q is invariant (x' >= 0, z' <= 0 by construction).
// Written once for a scalar T or a GCC vector type V (the scalar form is the reference of the SIMD one).
// GCC vector types of the SIMD path.
using vf64 = double __attribute__((vector_size(kVectorBytes)));
using vi64 = std::int64_t __attribute__((vector_size(kVectorBytes)));
using vf32 = float __attribute__((vector_size(kVectorBytes)));
using vi32 = std::int32_t __attribute__((vector_size(kVectorBytes)));
// |v| and -|v| of a vector by sign-bit arithmetic (GCC vector casts reinterpret the bits).
inline vf64 abs_of(vf64 v) { return (vf64)((vi64)v & ~(vi64{} + INT64_MIN)); }
inline vf64 negabs_of(vf64 v) { return (vf64)((vi64)v | (vi64{} + INT64_MIN)); }
inline vf32 abs_of(vf32 v) { return (vf32)((vi32)v & ~(vi32{} + INT32_MIN)); }
inline vf32 negabs_of(vf32 v) { return (vf32)((vi32)v | (vi32{} + INT32_MIN)); }

template <class V> struct StepResult { V x, y, z; };
template <class T> inline T abs_of(const T& v) {
  using std::fabs;  // and boost::multiprecision's fabs by argument-dependent lookup
  return fabs(v);
}
template <class T> inline T negabs_of(const T& v) { return -abs_of(v); }

// a y - x rounded once, for a vector: the FMA instruction where the unit is compiled with it, so that the
// value and its sign do not depend on what the compiler contracts (core::fms is the scalar form).  Without
// FMA, a y - x is rounded twice; its sign is still exact unless the rounded product equals x, where the result
// is 0 and settle_ties recomputes the lane (so both builds give every lane the same bits).
template <class V> inline V fms(V a, V y, V x) {
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm512_fmsub_pd((__m512d)a, (__m512d)y, (__m512d)x);
    else return (V)_mm512_fmsub_ps((__m512)a, (__m512)y, (__m512)x);
  }
#endif
#if defined(__FMA__)
  if constexpr (sizeof(V) == 32) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm256_fmsub_pd((__m256d)a, (__m256d)y, (__m256d)x);
    else return (V)_mm256_fmsub_ps((__m256)a, (__m256)y, (__m256)x);
  }
  if constexpr (sizeof(V) == 16) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm_fmsub_pd((__m128d)a, (__m128d)y, (__m128d)x);
    else return (V)_mm_fmsub_ps((__m128)a, (__m128)y, (__m128)x);
  }
#endif
  const V ay = a * y;  // reached only without FMA, where nothing contracts
  return ay - x;
}
// k s + t rounded once where the unit has FMA (the instruction GCC's default contraction chose here before: written
// out so that the scalar lane step, lane_step, rounds it the same way), else rounded twice.
template <class V> inline V fma_add(V k, V s, V t) {
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm512_fmadd_pd((__m512d)k, (__m512d)s, (__m512d)t);
    else return (V)_mm512_fmadd_ps((__m512)k, (__m512)s, (__m512)t);
  }
#endif
#if defined(__FMA__)
  if constexpr (sizeof(V) == 32) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm256_fmadd_pd((__m256d)k, (__m256d)s, (__m256d)t);
    else return (V)_mm256_fmadd_ps((__m256)k, (__m256)s, (__m256)t);
  }
  if constexpr (sizeof(V) == 16) {
    if constexpr (std::is_same_v<V, vf64>) return (V)_mm_fmadd_pd((__m128d)k, (__m128d)s, (__m128d)t);
    else return (V)_mm_fmadd_ps((__m128)k, (__m128)s, (__m128)t);
  }
  if constexpr (std::is_same_v<V, double> || std::is_same_v<V, float>) return std::fma(k, s, t);
#endif
  const V ks = k * s;  // without FMA nothing contracts
  return ks + t;
}
// Whether any lane of v is zero: one compare and a mask test (c1 c3 == 0 covers both differences; a product that
// underflows only sends a lane to settle_ties, which recomputes it exactly).
template <class V> inline bool any_zero(V v) {
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64) {
    if constexpr (std::is_same_v<V, vf64>) return _mm512_cmp_pd_mask((__m512d)v, _mm512_setzero_pd(), _CMP_EQ_OQ) != 0;
    else return _mm512_cmp_ps_mask((__m512)v, _mm512_setzero_ps(), _CMP_EQ_OQ) != 0;
  }
#endif
#if defined(__AVX__)
  if constexpr (sizeof(V) == 32) {
    if constexpr (std::is_same_v<V, vf64>)
      return _mm256_movemask_pd(_mm256_cmp_pd((__m256d)v, _mm256_setzero_pd(), _CMP_EQ_OQ));
    else return _mm256_movemask_ps(_mm256_cmp_ps((__m256)v, _mm256_setzero_ps(), _CMP_EQ_OQ));
  }
#endif
  if constexpr (sizeof(V) == 16) {
    if constexpr (std::is_same_v<V, vf64>) return _mm_movemask_pd(_mm_cmpeq_pd((__m128d)v, _mm_setzero_pd()));
    else return _mm_movemask_ps(_mm_cmpeq_ps((__m128)v, _mm_setzero_ps()));
  }
  bool any = false;
  for (int l = 0; l < static_cast<int>(sizeof(V) / sizeof(v[0])); ++l) any |= v[l] == 0;
  return any;
}
// A zero a y - x is an exact tie (branch 2), a product rounded onto x (no FMA), or an exact value below the
// smallest subnormal: lanes whose c1 or c3 is zero get the exact fused value and the exact sign (core::
// sign_of_fms).  Such lanes are rare (ties are a set of measure zero), so the common path costs one test.
template <class V, class M> inline void settle_ties(V x, V y, V z, V a, V& c1, V& c3, M& s1, M& s3) {
  using T = std::remove_cvref_t<decltype(x[0])>;
  constexpr int W = sizeof(V) / sizeof(T);
  for (int l = 0; l < W; ++l) {
    if (c1[l] == 0) {
      c1[l] = core::fms<T>(a[l], y[l], x[l]);
      s1[l] = core::sign_of_fms<T>(a[l], y[l], x[l], c1[l]) > 0 ? -1 : 0;
    }
    if (c3[l] == 0) {
      c3[l] = core::fms<T>(a[l], y[l], z[l]);
      s3[l] = core::sign_of_fms<T>(a[l], y[l], z[l], c3[l]) < 0 ? -1 : 0;
    }
  }
}

template <class V, class M> inline StepResult<V> map_step(V x, V y, V z, V r, V a, V k, M& s1, M& s3) {
  // 4 multiply-class operations per lane (two fused a y - x, a y - z, r x, r z, one FMA) and 3 additions:
  // on a core whose 512-bit multiplies and additions issue on separate pipes the step costs ~4 cycles per
  // vector.  V(...) around each arm: expression-template types (Boost.Multiprecision) need one common type.
  // The branch is core::branch's rule: the exact signs of a y - x and a y - z (ties to symbol 2).
  V c1, c3;
  if constexpr (std::is_same_v<M, bool> && (std::is_same_v<V, double> || std::is_same_v<V, float>)) {
    // A lane of the vector step below, in scalar code (lane_step): the same roundings, exact signs everywhere.
#if defined(__FMA__) || defined(__AVX512F__)
    c1 = core::fms<V>(a, y, x);
    c3 = core::fms<V>(a, y, z);
#else
    c1 = fms(a, y, x);
    c3 = fms(a, y, z);
    if (c1 == 0) c1 = core::fms<V>(a, y, x);  // as settle_ties
    if (c3 == 0) c3 = core::fms<V>(a, y, z);
#endif
    s1 = core::sign_of_fms<V>(a, y, x, c1) > 0;
    s3 = core::sign_of_fms<V>(a, y, z, c3) < 0;
  } else if constexpr (std::is_same_v<M, bool>) {
    c1 = core::fms<V>(a, y, x);
    c3 = core::fms<V>(a, y, z);
    s1 = core::sign_of_fms<V>(a, y, x, c1) > 0;
    s3 = core::sign_of_fms<V>(a, y, z, c3) < 0;
  } else {
    c1 = fms(a, y, x);
    c3 = fms(a, y, z);
    s1 = c1 > V{};
    s3 = c3 < V{};
#if !defined(__FMA__) && !defined(__AVX512F__)
    // Without FMA a zero c1 may be a product rounded onto x: settle those lanes (a test per vector-step).
    if (__builtin_expect(any_zero(V(c1 * c3)), 0)) settle_ties(x, y, z, a, c1, c3, s1, s3);
#endif
    // With FMA, c1 = fl(a y - x) is zero only at an exact tie (symbol 2, as the rule says) or when a y - x is
    // below the smallest subnormal: the exact value is a multiple of 2^(e_y - 105) (e_y the exponent of y), so that
    // needs |y| < 2^-968.  The corner kept out below has the margin |y| < 2^-916 (at or above it the exact value
    // is a multiple of 2^-1021 or coarser, a normal number): a lane whose y lies 2^-409 below its largest component
    // (>= 2^-507 between renormalisations).
    // That corner is not settled here (a test per vector-step made the plain kernel 1.7x slower): run() steps a
    // batch whose start has such a lane lane by lane (first_step_exact), and one step leaves the corner.  The
    // dynamics re-enter it only within 2^-409 of the direction (0, 0, 1), which no orbit from another start
    // reaches except through the exact preimages of that direction.
  }
  const V xn = s3 ? V(r * x) : V(abs_of(c1));
  const V zn = s1 ? V(r * z) : V(negabs_of(c3));
  const V sy = (s1 | s3) ? V(-y) : y;
  if constexpr (std::is_same_v<V, double> || std::is_same_v<V, float> || !std::is_same_v<M, bool>)
    return {xn, fma_add(k, V(xn + zn), sy), zn};
  else return {xn, V(k * (xn + zn) + sy), zn};
}

// Generic lanes (long double, or any T without a vector type): the per-lane loop; one MPFR lane on the C API
// (mpfr_lane.hpp: the same operations without a temporary per operation).
template <class T, int B, bool Sym>
inline void steps(T* __restrict x, T* __restrict y, T* __restrict z, const T* __restrict r, const T* __restrict a,
                  const T* __restrict k, std::uint8_t* __restrict sym, int n) {
  if constexpr (B == 1 && MpfrNumber<T>) return mpfr_lane_steps<T, Sym>(*x, *y, *z, *r, *a, *k, sym, n);
  for (int s = 0; s < n; ++s) {
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      bool s1 = false, s3 = false;
      const StepResult<T> o = map_step<T, bool>(x[l], y[l], z[l], r[l], a[l], k[l], s1, s3);
      x[l] = o.x;
      y[l] = o.y;
      z[l] = o.z;
      if constexpr (Sym) sym[l] = static_cast<std::uint8_t>(s1 ? 1 : (s3 ? 3 : 2));
    }
  }
}

// SIMD lanes for float/double: GCC vectors of kVectorBytes (one AVX-512, AVX or SSE2 register).
// NV = kVectorsInFlight (lanes.hpp: 6) independent vectors are kept in registers for the n steps between
// renormalisations: lanes.hpp gives the step's latency and issue cost that this count hides.
template <class T> struct SimdTypes;
template <> struct SimdTypes<double> {
  using V = vf64;
  using I = vi64;
  using Bytes = std::uint8_t __attribute__((vector_size(kVectorBytes / 8)));  // a symbol per lane
};
template <> struct SimdTypes<float> {
  using V = vf32;
  using I = vi32;
  using Bytes = std::uint8_t __attribute__((vector_size(kVectorBytes / 4)));
};
template <class T> struct Simd {
  static constexpr int W = kVectorBytes / sizeof(T);  // lanes per vector
  static constexpr int NV = kVectorsInFlight;         // vectors in flight
  static constexpr int B = W * NV;                    // lanes per batch
  using V = typename SimdTypes<T>::V;
  using I = typename SimdTypes<T>::I;
  static V load(const T* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  static void store(T* p, V v) { std::memcpy(p, &v, sizeof v); }
};

// NV vectors of W lanes: kVectorsInFlight for a full batch, 1 for an ensemble of at most W orbits (one orbit's step is
// latency-bound: the other five vectors would only add their issue cost to it, lanes.hpp).  Each lane's arithmetic
// is the same whatever NV (the same map_step on the same vector type).
template <class T, int NV, bool Sym>
inline void steps_simd(T* __restrict xs, T* __restrict ys, T* __restrict zs, const T* __restrict rs,
                       const T* __restrict as, const T* __restrict ks, std::uint8_t* __restrict sym, int n) {
  using S = Simd<T>;
  using V = typename S::V;
  using I = typename S::I;
  V x[NV], y[NV], z[NV], r[NV], a[NV], k[NV];
  I s1[NV], s3[NV];
  for (int j = 0; j < NV; ++j) {
    x[j] = S::load(xs + j * S::W);
    y[j] = S::load(ys + j * S::W);
    z[j] = S::load(zs + j * S::W);
    r[j] = S::load(rs + j * S::W);
    a[j] = S::load(as + j * S::W);
    k[j] = S::load(ks + j * S::W);
  }
  for (int s = 0; s < n; ++s) {
#pragma GCC unroll 8
    for (int j = 0; j < NV; ++j) {
      const StepResult<V> o = map_step<V, I>(x[j], y[j], z[j], r[j], a[j], k[j], s1[j], s3[j]);
      x[j] = o.x;
      y[j] = o.y;
      z[j] = o.z;
    }
  }
  for (int j = 0; j < NV; ++j) {
    S::store(xs + j * S::W, x[j]);
    S::store(ys + j * S::W, y[j]);
    S::store(zs + j * S::W, z[j]);
    if constexpr (Sym) {
      // Narrowed as one vector (a byte per lane; lane by lane, GCC inserts and extracts each: half of the
      // classification's first pass went there).
      using Bytes = typename SimdTypes<T>::Bytes;
      const I code = s1[j] ? I{} + 1 : (s3[j] ? I{} + 3 : I{} + 2);
      const Bytes narrow = __builtin_convertvector(code, Bytes);
      std::memcpy(sym + j * S::W, &narrow, sizeof narrow);
    }
  }
}

template <class T> constexpr bool has_simd = std::is_same_v<T, float> || std::is_same_v<T, double>;

// Whether a lane of a batch starts where the vector step's fused a y - x (a y - z) may underflow to 0 although the
// exact value is not 0: with the largest component in [1, 2), the exact value is a multiple of 2^(e - 2 p + 2)
// (e the exponent of y, p the precision's digits; a = (1 + r) / 2 is a multiple of 2^-p), below the smallest
// subnormal 2^(m - p) (m = min_exponent) only when |y| < 2^(m + p - 2).  One test per batch, not per step.
template <class T, int B> inline bool start_in_corner(const T* y) {
  const T lim = std::ldexp(T(1), std::numeric_limits<T>::min_exponent + std::numeric_limits<T>::digits);
  bool any = false;
  for (int l = 0; l < B; ++l) any |= std::fabs(y[l]) < lim;
  return any;
}
// n steps of a batch: the vector step, or lane by lane with exact signs (steps, map_step<T, bool>: the same
// roundings) for the batch's first step when a lane starts in the corner above; one step leaves it (the image's y
// is its largest component within a factor 1 / alpha when x and y were tiny).
template <class T, int B, bool Sym>
inline void advance(T* __restrict x, T* __restrict y, T* __restrict z, const T* __restrict r, const T* __restrict a,
                    const T* __restrict k, std::uint8_t* __restrict sym, int n, bool exact_first) {
  if constexpr (has_simd<T>) {
    if (exact_first) {
      steps<T, B, Sym>(x, y, z, r, a, k, sym, 1);
      if (--n == 0) return;
    }
    static_assert(B % Simd<T>::W == 0, "a batch is whole vectors");
    steps_simd<T, B / Simd<T>::W, Sym>(x, y, z, r, a, k, sym, n);
  } else {
    steps<T, B, Sym>(x, y, z, r, a, k, sym, n);
  }
}

// Exact rescaling by a power of two so that max(|x|,|y|,|z|) lies in [1, 2): the symbols are exactly
// those of the unnormalised iteration.  float/double: exponent-bit arithmetic (vectorises);
// other types: frexp/ldexp.
template <class T, int B> inline void renormalise(T* __restrict x, T* __restrict y, T* __restrict z) {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>) {
    using U = std::conditional_t<std::is_same_v<T, double>, std::uint64_t, std::uint32_t>;
    constexpr int mant = std::numeric_limits<T>::digits - 1;                // 52 / 23
    constexpr U two_bias = 2 * (std::numeric_limits<T>::max_exponent - 1);  // 2046 / 254
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const T ax = std::fabs(x[l]), ay = std::fabs(y[l]), az = std::fabs(z[l]);
      const T mxy = ax > ay ? ax : ay;
      const T m = mxy > az ? mxy : az;          // by value: std::max's references make GCC emit gathers
      const U e = std::bit_cast<U>(m) >> mant;  // biased exponent of m (m >= 0, normal)
      const T s = std::bit_cast<T>(static_cast<U>((two_bias - e) << mant));  // 2^-(unbiased exponent)
      x[l] *= s;
      y[l] *= s;
      z[l] *= s;
    }
  } else {
    using std::fabs;
    using std::frexp;
    using std::ldexp;
    for (int l = 0; l < B; ++l) {
      const T m = std::max(fabs(x[l]), std::max(fabs(y[l]), fabs(z[l])));
      int e = 0;
      frexp(m, &e);
      x[l] = ldexp(x[l], 1 - e);
      y[l] = ldexp(y[l], 1 - e);
      z[l] = ldexp(z[l], 1 - e);
    }
  }
}

// The starting vector of an orbit: the initial vector brought into Q and scaled by an exact power of
// two so that its largest component lies in [1, 2) (subnormal inputs included).  The direction is the
// user's to the last bit (exact ties alpha*y = x stay ties), and every precision starts from it.
inline core::Vec3<double> unit_start(const core::Vec3<double>& u) {
  int e = 0;
  std::frexp(u.cwiseAbs().maxCoeff(), &e);
  const core::Vec3<double> q = core::to_quadrant<double>(u);
  return {std::ldexp(q(0), 1 - e), std::ldexp(q(1), 1 - e), std::ldexp(q(2), 1 - e)};
}

// log2 bounds of one step's growth and shrinkage in the max-norm, over the three scaled branch
// matrices: |M u| <= |M| |u| and |M u| >= |u| / |M^-1| (operator infinity norms).
inline void step_log2_bounds(double r, double& grow, double& shrink) {
  grow = 0;
  shrink = 0;
  for (int i = 1; i <= 3; ++i) {
    const Eigen::Matrix3d m = core::P<double>(i, r) / r;
    const double g = m.cwiseAbs().rowwise().sum().maxCoeff();
    const double h = m.inverse().cwiseAbs().rowwise().sum().maxCoeff();
    grow = std::max(grow, std::log2(g));
    shrink = std::max(shrink, std::log2(h));
  }
}

// What every batched run does at the end of a batch and at the end of the run: count the lanes whose state is no
// longer a finite non-zero vector (the precision could not cope: callers say so instead of plotting garbage), report
// progress from thread 0, and publish both; a cancelled run throws core::Cancelled once the parallel region is over.
struct RunTally {
  std::atomic<std::size_t> done{0}, degenerate{0};
  // bad(l): whether lane l's state is degenerate (evaluated only when the caller asked for the count).
  template <class Bad> void batch_end(const RunOptions& opt, std::size_t n_batches, int lanes, Bad bad) {
    if (opt.degenerate) {
      std::size_t n = 0;
      for (int l = 0; l < lanes; ++l) n += bad(l) ? 1 : 0;
      if (n) degenerate.fetch_add(n, std::memory_order_relaxed);
    }
    if (opt.progress) {
      const std::size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (omp_get_thread_num() == 0) opt.progress->update(d, n_batches);
    }
  }
  void finish(const RunOptions& opt, std::size_t n_batches) {
    core::check_cancel(opt.cancel);
    if (opt.progress) opt.progress->update(n_batches, n_batches);
    if (opt.degenerate) *opt.degenerate = degenerate.load();
  }
};
// Every r value of the ensemble in T from its decimal source (Ensemble::r_at), evaluated once per run (MPFR: at the
// caller's digits) into `own`; double's are ens.r itself, so double runs read exactly the doubles they always read.
template <class T> inline const T* r_values(const Ensemble& ens, std::vector<T>& own) {
  if constexpr (std::is_same_v<T, double>) {
    return ens.r.data();
  } else {
    own = ens.r_in<T>();
    return own.data();
  }
}
template <class T> inline bool degenerate_vector(const T& x, const T& y, const T& z) {
  using std::isfinite;
  return !(isfinite(x) && isfinite(y) && isfinite(z)) || (x == 0 && y == 0 && z == 0);
}

}  // namespace detail

template <class T> int renormalisation_interval(const std::vector<double>& r) {
  // After a rescale the max-norm is in [1, 2).  Over K steps it stays in [2^(-K*shrink), 2^(1+K*grow)];
  // keep it 4 binary orders away from the square root of the overflow threshold and of the smallest normal
  // number (bounds are in double; the margin absorbs rounding of the matrices in T).  Square roots: recorders
  // square the state (phi's sqrt(x^2 + z^2), FinalRecorder's norm) and add its coordinates (the strip's x - z)
  // between rescales; with the full range, a state near 2^1000 at r = 1e-6 gave |u| = inf and a final direction
  // (0, 0, 0) (tests/test_properties.cpp).  Rescaling is exact, so this changes no symbol and no recorded value.
  constexpr double emax = std::numeric_limits<T>::max_exponent / 2 - 4;
  constexpr double emin = -(std::numeric_limits<T>::min_exponent) / 2 - 4;
  double grow = 0, shrink = 0;
  for (double rv : r) {
    double g = 0, s = 0;
    detail::step_log2_bounds(rv, g, s);
    grow = std::max(grow, g);
    shrink = std::max(shrink, s);
  }
  const double k = std::min(grow > 0 ? emax / grow : 1e9, shrink > 0 ? emin / shrink : 1e9);
  return static_cast<int>(std::clamp(std::floor(k), 1.0, 1024.0));
}

namespace detail {

// What every batch of a run shares.
template <class T> struct RunShape {
  std::size_t n_orbits, n_ic, n_batches;
  int K;       // renormalisation_interval
  long first;  // the recorder's first step (at least 1)
  const T* r;  // r of each column in T (r_values)
};

// Batch b of B lanes through the run's two phases: the orbits b B .. b B + lanes - 1 (padded with the last one),
// their unrecorded steps K at a time, each block followed by an exact power-of-two rescale, then the recorded steps.
template <class T, int B, Recorder Rec>
void run_batch(const RunShape<T>& sh, std::size_t b, const Ensemble& ens, long iterations, Rec& rec,
               const RunOptions& opt, RunTally& tally) {
  alignas(64) T x[B], y[B], z[B], r[B], a[B], k[B];
  alignas(64) std::uint8_t sym[B];
  const std::size_t o0 = b * B;
  const int lanes = static_cast<int>(std::min<std::size_t>(B, sh.n_orbits - o0));
  for (int l = 0; l < B; ++l) {
    const std::size_t o = o0 + static_cast<std::size_t>(std::min(l, lanes - 1));  // pad with the last orbit
    const core::Vec3<double> q = unit_start(ens.initial[o % sh.n_ic]);
    x[l] = static_cast<T>(q(0));
    y[l] = static_cast<T>(q(1));
    z[l] = static_cast<T>(q(2));
    r[l] = sh.r[o / sh.n_ic];
    a[l] = (T(1) + r[l]) / T(2);
    k[l] = a[l] / r[l];
  }
  renormalise<T, B>(x, y, z);
  bool corner = false;  // the other precisions' per-lane step settles every lane
  if constexpr (has_simd<T>) corner = start_in_corner<T, B>(y);
  const int K = sh.K;
  // Phase 1: unrecorded steps, K at a time, then an exact power-of-two rescale.
  long step = 0;
  const long quiet = std::min(iterations, sh.first - 1);
  // A cancelled run leaves the batch early (a transient of 1e12 steps is one batch): polled once per K steps
  // here and every core::cancel_stride steps below; the partial batch is discarded by RunTally::finish.
  while (step < quiet && !(opt.cancel && opt.cancel->cancelled())) {
    const int n = static_cast<int>(std::min<long>(K, quiet - step));
    advance<T, B, false>(x, y, z, r, a, k, sym, n, corner && step == 0);
    renormalise<T, B>(x, y, z);
    step += n;
  }
  // Phase 2: recorded steps (none once cancelled: a recorder may only see steps from its first_step() on).
  int since = 0;
  if (step < quiet) step = iterations;
  while (step < iterations && !core::cancel_due(opt.cancel, step)) {
    advance<T, B, Rec::needs_symbols>(x, y, z, r, a, k, sym, 1, corner && step == 0);
    ++step;
    if (++since == K) {
      renormalise<T, B>(x, y, z);
      since = 0;
    }
    rec.record(o0, lanes, step, x, y, z, Rec::needs_symbols ? sym : nullptr);
  }
  tally.batch_end(opt, sh.n_batches, lanes, [&](int l) { return degenerate_vector(x[l], y[l], z[l]); });
}

template <class T, int B, Recorder Rec>
void run_batches(const Ensemble& ens, long iterations, Rec& rec, const RunOptions& opt) {
  const std::size_t n_orbits = ens.orbits();
  RunShape<T> sh{n_orbits,
                 ens.initial.size(),
                 (n_orbits + B - 1) / B,
                 renormalisation_interval<T>(ens.r),
                 std::max<long>(rec.first_step(), 1),
                 nullptr};
  // No more threads than batches: one orbit is one batch, stepped by one thread either way.
  const int threads = static_cast<int>(std::min<std::size_t>(core::thread_count(opt.threads), sh.n_batches));
  RunTally tally;
  std::vector<T> r_own;
  sh.r = r_values<T>(ens, r_own);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t b = 0; b < sh.n_batches; ++b) {
    if (opt.cancel && opt.cancel->cancelled()) continue;  // no exception may leave an OpenMP region
    run_batch<T, B>(sh, b, ens, iterations, rec, opt, tally);
  }
  tally.finish(opt, sh.n_batches);
}

}  // namespace detail

// An ensemble of at most few_lanes<T>() orbits runs as one batch of that width: one vector for float and double (8
// and 16 lanes with AVX-512), one lane for the other precisions (a single orbit).  Its step is then the scalar
// limit, a chain of dependent operations (fused a y - x, compare, select, x' + z', fused y': docs/performance.md),
// instead of that chain for one lane and the issue cost of 47 others.  Every lane's arithmetic is the full batch's
// (the same map_step on the same types, the same rescaling every K steps), so the results are the same bits.
template <class T> constexpr int few_lanes() {
  if constexpr (detail::has_simd<T>) return detail::Simd<T>::W;
  else return 1;
}

template <class T, Recorder Rec> void run(const Ensemble& ens, long iterations, Rec& rec, const RunOptions& opt) {
  if (ens.orbits() == 0 || iterations < 0) return;
  if (ens.orbits() <= static_cast<std::size_t>(few_lanes<T>()))
    return detail::run_batches<T, few_lanes<T>()>(ens, iterations, rec, opt);
  detail::run_batches<T, detail::batch_lanes<T>()>(ens, iterations, rec, opt);
}

template <class T, Recorder Rec> void run_scalar(const Ensemble& ens, long iterations, Rec& rec) {
  const std::size_t n_ic = ens.initial.size();
  const long first = std::max<long>(rec.first_step(), 1);
  for (std::size_t o = 0; o < ens.orbits(); ++o) {
    const T rv = ens.r_at<T>(o / n_ic);
    const core::Vec3<double> u0 = detail::unit_start(ens.initial[o % n_ic]);
    core::Vec3<T> u(T(u0(0)), T(u0(1)), T(u0(2)));
    {
      using std::sqrt;
      u /= sqrt(u(0) * u(0) + u(1) * u(1) + u(2) * u(2));  // Appendix A.2 starts from X/norm(X)
    }
    const core::Mat3<T> Pm[3] = {core::P1(rv), core::P2(rv), core::P3(rv)};
    const T av = core::alpha(rv);
    for (long step = 1; step <= iterations; ++step) {
      // Appendix A.2, as printed: branch on y and the two conditions, normalise every step.
      const T c2 = av * u(1) - u(0), c3 = av * u(1) - u(2);
      int s = 2;
      if (u(1) > 0 && c2 > 0) s = 1;
      else if (u(1) < 0 && c3 < 0) s = 3;
      u = Pm[s - 1] * u;
      using std::sqrt;
      u /= sqrt(u(0) * u(0) + u(1) * u(1) + u(2) * u(2));
      if (step >= first) {
        T x = u(0), y = u(1), z = u(2);
        std::uint8_t sym = static_cast<std::uint8_t>(s);
        rec.record(o, 1, step, &x, &y, &z, Rec::needs_symbols ? &sym : nullptr);
      }
    }
  }
}

}  // namespace btob::iterate
