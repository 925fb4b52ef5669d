// SPDX-License-Identifier: GPL-3.0-or-later
// The weighted sums of lyapunov/weighted.hpp, compiled with the kernel's flags so that the loops over an interval
// vectorise (double: the log and exp below are branch-free polynomials on the bits; long double: libm).
#include "lyapunov/weighted.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace btob::lyapunov::detail {
namespace {

constexpr double kLn2Hi = 0x1.62e42fefa3800p-1, kLn2Lo = 0x1.ef35793c76730p-45;  // ln 2 = hi + lo, hi * k exact
constexpr long kMaxLen = 1025;  // iterate::renormalisation_interval's cap + 1 states

// log x for a positive normal double: x = 2^e m with m in [sqrt(1/2), sqrt(2)) (the bits minus sqrt(1/2)'s give e),
// log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716: the series to s^23 leaves < 2e-19 (|s|^25 / 25); the
// error is that of the division and the Horner sum, a few ulp of log m, and e ln 2 is exact to 2^-60 e.
inline double log_bits(double x) {
  const std::uint64_t b = std::bit_cast<std::uint64_t>(x);
  const std::int64_t e = static_cast<std::int64_t>(b - 0x3fe6a09e667f3bcdULL) >> 52;
  const double m = std::bit_cast<double>(b - (static_cast<std::uint64_t>(e) << 52));
  const double s = (m - 1) / (m + 1), s2 = s * s;
  double p = 1.0 / 23;
#pragma GCC unroll 16
  for (int j = 21; j >= 1; j -= 2) p = std::fma(p, s2, 1.0 / j);
  const double ed = static_cast<double>(e);
  return std::fma(ed, kLn2Hi, std::fma(ed, kLn2Lo, 2 * s * p));
}

// exp g for g in [-700, 0]: g = k ln 2 + h, |h| <= ln 2 / 2, e^h by its Taylor series to h^13 (|h|^14 / 14! < 4e-18),
// times 2^k on the exponent bits (k >= -1010: a normal number).
inline double exp_bits(double g) {
  constexpr double shift = 0x1.8p52;  // adding it rounds g / ln 2 to the integer in the low bits
  const double kd0 = std::fma(g, 1 / 0x1.62e42fefa39efp-1, shift);
  const std::int64_t k =
      static_cast<std::int64_t>(std::bit_cast<std::uint64_t>(kd0) - std::bit_cast<std::uint64_t>(shift));
  const double kd = kd0 - shift;
  const double h = std::fma(-kd, kLn2Lo, std::fma(-kd, kLn2Hi, g));
  constexpr double inv_factorial[14] = {
      1.0,        1.0,         1.0 / 2,      1.0 / 6,       1.0 / 24,       1.0 / 120,       1.0 / 720,
      1.0 / 5040, 1.0 / 40320, 1.0 / 362880, 1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800.0};
  double p = inv_factorial[13];
#pragma GCC unroll 16
  for (int j = 12; j >= 0; --j) p = std::fma(p, h, inv_factorial[j]);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(p) + (static_cast<std::uint64_t>(k) << 52));
}

// log |u_k x v_k|^2 and log Y_k (weighted.hpp: log Z = log |u x v|^2 - 2 log Y) for k = 0..len, in W (double: the
// bit-level log, which needs a positive normal argument; long double: libm).  Returns whether every argument was a
// positive normal number of W (else the caller redoes the interval in long double, whose range holds the squares).
template <class W> bool state_logs(const Trace<W>& tr, long len, W* lc, W* ly) {
  const long s = tr.stride;
  const W *ux = tr.at, *uy = ux + s, *uz = uy + s, *vx = uz + s, *vy = vx + s, *vz = vy + s;
  W lo = std::numeric_limits<W>::max(), hi = 0;
#pragma omp simd reduction(min : lo) reduction(max : hi)
  for (long k = 0; k <= len; ++k) {
    const W y = ux[k] * ux[k] + uy[k] * uy[k] + uz[k] * uz[k];
    const W cx = uy[k] * vz[k] - uz[k] * vy[k], cy = uz[k] * vx[k] - ux[k] * vz[k], cz = ux[k] * vy[k] - uy[k] * vx[k];
    const W c = cx * cx + cy * cy + cz * cz;
    lo = std::min(lo, std::min(c, y));
    hi = std::max(hi, std::max(c, y));
    if constexpr (std::is_same_v<W, double>) {
      lc[k] = log_bits(c);
      ly[k] = log_bits(y);
    } else {
      lc[k] = std::log(c);
      ly[k] = std::log(y);
    }
  }
  return lo >= std::numeric_limits<W>::min() && hi <= std::numeric_limits<W>::max();
}

// The sums over k = 1..len (an OpenMP simd reduction: a fixed order for a given interval, whatever the threads).
template <class W>
void interval_sums(const W* lc, const W* ly, const W* n13, long len, long j0, long n, W log_r, WeightedSums& sums) {
  W l1 = 0, ar = 0, no = 0;
  const W inv_n = W(1) / static_cast<W>(n);
#pragma omp simd reduction(+ : l1, ar, no)
  for (long k = 1; k <= len; ++k) {
    const W t = (static_cast<W>(j0 + k) - W(0.5)) * inv_n;
    const W g = std::max(W(-1) / (t * (1 - t)), W(-700));
    W w;
    if constexpr (std::is_same_v<W, double>) w = exp_bits(g);
    else w = std::exp(g);
    l1 += w * (W(0.5) * (lc[k] - lc[k - 1]) - (ly[k] - ly[k - 1]));  // (log Z_k - log Z_{k-1}) / 2
    ar += w * (n13[k] * log_r - W(1.5) * (ly[k] - ly[k - 1]));
    no += w;
  }
  sums.lambda1 += static_cast<long double>(l1);
  sums.area += static_cast<long double>(ar);
  sums.norm += static_cast<long double>(no);
}

}  // namespace

template <class W>
void weigh(const Trace<W>& tr, long len, const std::uint8_t* ring, long step0, long j0, long n, long double log_r,
           WeightedSums& sums) {
  alignas(64) W lc[kMaxLen], ly[kMaxLen], n13[kMaxLen];
  for (long k = 1; k <= len; ++k) n13[k] = ring[(step0 + k) & (kSymbolRing - 1)] != 2 ? W(1) : W(0);
  const bool in_range = state_logs(tr, len, lc, ly);
  if constexpr (std::is_same_v<W, double>) {
    if (!in_range) {  // a square outside double's normal range (far-fetched r): the interval again in long double
      alignas(64) static thread_local long double wide[6 * kMaxLen];
      for (int c = 0; c < 6; ++c)
        for (long k = 0; k <= len; ++k) wide[c * kMaxLen + k] = tr.at[c * tr.stride + k];
      return weigh<long double>({wide, kMaxLen}, len, ring, step0, j0, n, log_r, sums);
    }
  }
  interval_sums<W>(lc, ly, n13, len, j0, n, static_cast<W>(log_r), sums);
}

template void weigh<double>(const Trace<double>&, long, const std::uint8_t*, long, long, long, long double,
                            WeightedSums&);
template void weigh<long double>(const Trace<long double>&, long, const std::uint8_t*, long, long, long, long double,
                                 WeightedSums&);

}  // namespace btob::lyapunov::detail
