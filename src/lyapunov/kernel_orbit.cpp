// SPDX-License-Identifier: GPL-3.0-or-later
// The single-orbit step of lyapunov/orbit.hpp in the kernel's unit flags (-march=native: the fused multiply-subtract of
// the branch rule is one instruction, not a libm call), for float, double, long double and float128.
#include "core/scalar.hpp"
#include "iterate/kernel_impl.hpp"
#include "lyapunov/orbit.hpp"

#include <immintrin.h>

#include <bit>
#include <cstdint>
#include <type_traits>

namespace btob::lyapunov::detail {
namespace {

template <class T> constexpr bool hardware_fma = std::is_same_v<T, double> || std::is_same_v<T, float>;

// a y - x and k t + s for the tangent vectors: fused where the hardware fuses (double, float), else two roundings
// (long double has no FMA instruction, float128's is software: the tangent vectors need no exact sign).
template <class T> [[gnu::always_inline]] inline T mul_sub(const T& a, const T& y, const T& x) {
  if constexpr (hardware_fma<T>) return core::fms<T>(a, y, x);
  else return T(a * y - x);
}
template <class T> [[gnu::always_inline]] inline T mul_add(const T& k, const T& t, const T& s) {
  using std::fma;
  if constexpr (hardware_fma<T>) return fma(k, t, s);
  else return T(k * t + s);
}

// A tangent vector's step under the branch (s1, s3) the point took: M_s v with the kernel's formulas, the signs that
// the point's |c1| and -|c3| stand for written out (c1 > 0 on branch 1, c1 <= 0 on 2; c3 < 0 on 3, c3 >= 0 on 2).
template <class T>
[[gnu::always_inline]] inline void tangent_step(T& x, T& y, T& z, bool s1, bool s3, const T& r, const T& a,
                                                const T& k) {
  const T d1 = mul_sub(a, y, x), d3 = mul_sub(a, y, z);
  const T xn = s3 ? T(r * x) : (s1 ? d1 : T(-d1));
  const T zn = s1 ? T(r * z) : (s3 ? d3 : T(-d3));
  const T sy = (s1 || s3) ? T(-y) : y;
  y = mul_add(k, T(xn + zn), sy);
  x = xn;
  z = zn;
}

// float and double: the same step without a conditional jump on the symbol (a chaotic orbit's symbols are not
// predictable, and a mispredicted jump costs more than the step): the signs as masks, the selections as bit blends.
// The values are map_step's bit for bit: c1, c3 fused, x' = r x or |c1|, z' = r z or -|c3|, y' = fma(k, x' + z', -+y);
// the tangent vectors take d or -d where the point takes |c| or -|c| (the signs its branch implies).  An exact zero
// c1 or c3 (a tie, or an underflow that core::sign_of_fms settles) takes the rare path of the exact rule.
template <class T> struct Bits;
template <> struct Bits<double> { using U = std::uint64_t; };
template <> struct Bits<float> { using U = std::uint32_t; };

template <class T> [[gnu::always_inline]] inline T blend(typename Bits<T>::U mask, T yes, T no) {
  using U = typename Bits<T>::U;
  return std::bit_cast<T>(static_cast<U>((mask & std::bit_cast<U>(yes)) | (~mask & std::bit_cast<U>(no))));
}
template <class T> [[gnu::always_inline]] inline T flip(typename Bits<T>::U sign, T v) {
  return std::bit_cast<T>(static_cast<typename Bits<T>::U>(std::bit_cast<typename Bits<T>::U>(v) ^ sign));
}

template <class T> struct Masks {
  typename Bits<T>::U m1, m3, not1, not3, either;  // all-ones masks of s1, s3; sign bits of !s1, !s3, s1 || s3
};
template <class T> [[gnu::always_inline]] inline Masks<T> masks(bool s1, bool s3) {
  using U = typename Bits<T>::U;
  constexpr int top = 8 * sizeof(U) - 1;
  return {static_cast<U>(-static_cast<U>(s1)), static_cast<U>(-static_cast<U>(s3)), static_cast<U>(U(!s1) << top),
          static_cast<U>(U(!s3) << top), static_cast<U>(U(s1 || s3) << top)};
}

template <class T>
[[gnu::always_inline]] inline void blended_tangent(T& x, T& y, T& z, const Masks<T>& m, T r, T a, T k) {
  using std::fma;
  const T d1 = core::fms<T>(a, y, x), d3 = core::fms<T>(a, y, z);
  const T xn = blend(m.m3, T(r * x), flip(m.not1, d1));
  const T zn = blend(m.m1, T(r * z), flip(m.not3, d3));
  y = fma(k, T(xn + zn), flip(m.either, y));
  x = xn;
  z = zn;
}

// The state after step i into the trace (weighted.hpp reads it): six stores, off the step's dependency chain.
template <class T, class W>
[[gnu::always_inline]] inline void record(const Trace<W>& tr, long i, const T& x, const T& y, const T& z, const T& p,
                                          const T& q, const T& w) {
  W* at = tr.at + i;
  const long s = tr.stride;
  at[0] = static_cast<W>(x), at[s] = static_cast<W>(y), at[2 * s] = static_cast<W>(z);
  at[3 * s] = static_cast<W>(p), at[4 * s] = static_cast<W>(q), at[5 * s] = static_cast<W>(w);
}

template <class T, bool Record>
void advance_blended(OrbitFrame<T>& f, long n, long first, std::uint8_t* ring, Trace<double> tr) {
  using std::fabs;
  using std::fma;
  T x = f.u[0], y = f.u[1], z = f.u[2];
  T p = f.v[0], q = f.v[1], w = f.v[2];
  const T r = f.r, a = f.a, k = f.k;
  for (long i = 0; i < n; ++i) {
    const T c1 = core::fms<T>(a, y, x), c3 = core::fms<T>(a, y, z);
    bool s1 = c1 > 0, s3 = c3 < 0;
    if (__builtin_expect(c1 == 0 || c3 == 0, 0)) {
      s1 = core::sign_of_fms<T>(a, y, x, c1) > 0;
      s3 = core::sign_of_fms<T>(a, y, z, c3) < 0;
    }
    const Masks<T> m = masks<T>(s1, s3);
    const T xn = blend(m.m3, T(r * x), T(fabs(c1)));
    const T zn = blend(m.m1, T(r * z), T(-fabs(c3)));
    y = fma(k, T(xn + zn), flip(m.either, y));
    x = xn;
    z = zn;
    blended_tangent(p, q, w, m, r, a, k);
    ring[(first + i) & (kSymbolRing - 1)] = static_cast<std::uint8_t>(2 - s1 + s3);
    if constexpr (Record) record(tr, i + 1, x, y, z, p, q, w);
  }
  f.u[0] = x, f.u[1] = y, f.u[2] = z;
  f.v[0] = p, f.v[1] = q, f.v[2] = w;
}

#if defined(__AVX__) && defined(__FMA__)
// double: the point and the tangent vector as the two lanes of one 128-bit vector (lane 0 the point, lane 1 the
// tangent vector), so that the branch's masks never leave the vector registers: the chain per step is fused a y - x
// (4 cycles) -> compare (3) -> the mask to both lanes (1) -> blend (1) -> x' + z' (3) -> fused y' (4), where the
// scalar blends above move each value to the integer registers and back (about 3 cycles each way).  The values are
// advance_blended's bit for bit: lane 0 takes |c1| and -|c3| (the kernel's), lane 1 d or -d with the point's signs.
struct PairMasks {
  __m128d m1, m3;  // all-ones in both lanes where the point took branch 1 (resp. 3)
};
[[gnu::always_inline]] inline PairMasks pair_masks(__m128d c1, __m128d c3, __m128d a, __m128d y, __m128d x, __m128d z) {
  const __m128d zero = _mm_setzero_pd();
  if (__builtin_expect(_mm_cvtsd_f64(c1) == 0 || _mm_cvtsd_f64(c3) == 0, 0)) {  // a tie or an underflow: exact signs
    const double a0 = _mm_cvtsd_f64(a), y0 = _mm_cvtsd_f64(y);
    const bool s1 = core::sign_of_fms<double>(a0, y0, _mm_cvtsd_f64(x), _mm_cvtsd_f64(c1)) > 0;
    const bool s3 = core::sign_of_fms<double>(a0, y0, _mm_cvtsd_f64(z), _mm_cvtsd_f64(c3)) < 0;
    const __m128d ones = _mm_castsi128_pd(_mm_set1_epi64x(-1));
    return {s1 ? ones : zero, s3 ? ones : zero};
  }
  return {_mm_movedup_pd(_mm_cmp_pd(c1, zero, _CMP_GT_OQ)), _mm_movedup_pd(_mm_cmp_pd(c3, zero, _CMP_LT_OQ))};
}

template <bool Record>
void advance_paired(OrbitFrame<double>& f, long n, long first, std::uint8_t* ring, Trace<double> tr) {
  __m128d x = _mm_set_pd(f.v[0], f.u[0]), y = _mm_set_pd(f.v[1], f.u[1]), z = _mm_set_pd(f.v[2], f.u[2]);
  const __m128d r = _mm_set1_pd(f.r), a = _mm_set1_pd(f.a), k = _mm_set1_pd(f.k);
  const __m128d sign = _mm_set1_pd(-0.0);
  const __m128d abs_point = _mm_castsi128_pd(_mm_set_epi64x(-1, 0x7fffffffffffffffLL));  // lane 0: |c|
  const __m128d neg_point = _mm_set_pd(0.0, -0.0);                                       // lane 0: -|c|
  const __m128d flip_tangent = _mm_set_pd(-0.0, 0.0);                                    // lane 1: -d
  for (long i = 0; i < n; ++i) {
    const __m128d c1 = _mm_fmsub_pd(a, y, x), c3 = _mm_fmsub_pd(a, y, z);
    const PairMasks m = pair_masks(c1, c3, a, y, x, z);
    const __m128d xc = _mm_xor_pd(_mm_and_pd(c1, abs_point), _mm_andnot_pd(m.m1, flip_tangent));
    const __m128d zc = _mm_xor_pd(_mm_or_pd(c3, neg_point), _mm_andnot_pd(m.m3, flip_tangent));
    const __m128d xn = _mm_blendv_pd(xc, _mm_mul_pd(r, x), m.m3);
    const __m128d zn = _mm_blendv_pd(zc, _mm_mul_pd(r, z), m.m1);
    const __m128d sy = _mm_xor_pd(y, _mm_and_pd(_mm_or_pd(m.m1, m.m3), sign));
    y = _mm_fmadd_pd(k, _mm_add_pd(xn, zn), sy);
    x = xn;
    z = zn;
    const int s1 = _mm_movemask_pd(m.m1) & 1, s3 = _mm_movemask_pd(m.m3) & 1;
    ring[(first + i) & (kSymbolRing - 1)] = static_cast<std::uint8_t>(2 - s1 + s3);
    if constexpr (Record)
      record(tr, i + 1, _mm_cvtsd_f64(x), _mm_cvtsd_f64(y), _mm_cvtsd_f64(z), _mm_cvtsd_f64(_mm_unpackhi_pd(x, x)),
             _mm_cvtsd_f64(_mm_unpackhi_pd(y, y)), _mm_cvtsd_f64(_mm_unpackhi_pd(z, z)));
  }
  f.u[0] = _mm_cvtsd_f64(x), f.u[1] = _mm_cvtsd_f64(y), f.u[2] = _mm_cvtsd_f64(z);
  f.v[0] = _mm_cvtsd_f64(_mm_unpackhi_pd(x, x)), f.v[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(y, y));
  f.v[2] = _mm_cvtsd_f64(_mm_unpackhi_pd(z, z));
}
#endif

// The same step for every precision, the branch by map_step's exact rule (long double, float128; and float, double
// without FMA).
template <class T, bool Record>
void advance_generic(OrbitFrame<T>& f, long n, long first, std::uint8_t* ring, Trace<TraceReal<T>> tr) {
  T x = f.u[0], y = f.u[1], z = f.u[2];
  T p = f.v[0], q = f.v[1], w = f.v[2];
  const T r = f.r, a = f.a, k = f.k;
  for (long i = 0; i < n; ++i) {
    bool s1 = false, s3 = false;
    const iterate::detail::StepResult<T> o = iterate::detail::map_step<T, bool>(x, y, z, r, a, k, s1, s3);
    x = o.x;
    y = o.y;
    z = o.z;
    tangent_step(p, q, w, s1, s3, r, a, k);
    ring[(first + i) & (kSymbolRing - 1)] = static_cast<std::uint8_t>(s1 ? 1 : (s3 ? 3 : 2));
    if constexpr (Record) record(tr, i + 1, x, y, z, p, q, w);
  }
  f.u[0] = x, f.u[1] = y, f.u[2] = z;
  f.v[0] = p, f.v[1] = q, f.v[2] = w;
}

}  // namespace

// Per step: the point (iterate::detail::map_step, the kernel's roundings and exact signs: 2 fused a y - x, a y - z, at
// most one r x or r z, one addition, one FMA) and the same for the tangent vector, then one byte stored (and six
// numbers over the averaged steps, for the weighted average).  The dependency chain through the point is
// fms -> |c1| -> x' + z' -> fma (docs/performance.md: the ceiling).
template <class T> void advance(OrbitFrame<T>& f, long n, long first, std::uint8_t* ring, Trace<TraceReal<T>> tr) {
#if defined(__AVX__) && defined(__FMA__)
  if constexpr (std::is_same_v<T, double>)
    return tr.at ? advance_paired<true>(f, n, first, ring, tr) : advance_paired<false>(f, n, first, ring, tr);
#endif
#if defined(__FMA__)
  if constexpr (hardware_fma<T>)
    return tr.at ? advance_blended<T, true>(f, n, first, ring, tr) : advance_blended<T, false>(f, n, first, ring, tr);
#endif
  return tr.at ? advance_generic<T, true>(f, n, first, ring, tr) : advance_generic<T, false>(f, n, first, ring, tr);
}

template void advance<float>(OrbitFrame<float>&, long, long, std::uint8_t*, Trace<TraceReal<float>>);
template void advance<double>(OrbitFrame<double>&, long, long, std::uint8_t*, Trace<TraceReal<double>>);
template void advance<long double>(OrbitFrame<long double>&, long, long, std::uint8_t*, Trace<TraceReal<long double>>);
template void advance<core::float128>(OrbitFrame<core::float128>&, long, long, std::uint8_t*,
                                      Trace<TraceReal<core::float128>>);

}  // namespace btob::lyapunov::detail
