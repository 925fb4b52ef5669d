// Template bodies of the batched kernel; included only by src/iterate/kernel_*.cpp (kernel flags).
#pragma once

#include "core/map.hpp"
#include "iterate/kernel.hpp"

#include <Eigen/Dense>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace btob::iterate {
namespace detail {

// Lanes per batch: 4 vectors of 512 bits in flight (perf-notes: one step's dependency chain is ~21
// cycles and its issue cost ~5, so 4 independent vectors hide the latency; 8 spill registers).
template <class T> constexpr int batch_lanes() {
  if constexpr (std::is_same_v<T, float>) return 64;
  else if constexpr (std::is_same_v<T, double>) return 32;
  else return 8;
}

// One step of the map for all lanes, with the matrices divided by r (M_i = P_i / r: same direction,
// same symbol, better conditioned).  In Q, with c1 = a y - x and c3 = a y - z, k = a / r:
//   M1 u = (c1, k c1 - y + a z, r z)           if c1 > 0          (symbol 1, ab)
//   M3 u = (r x, k c3 - y + a x, c3)           else if c3 < 0     (symbol 3, cb)
//   M2 u = (-c1, y - k (c1 + c3), -c3)         otherwise          (symbol 2, acb/cab; ties go here)
// The selection is branch-free (blends); the quadrant Q is invariant.
template <class T, int B, bool Sym>
inline void steps(T* __restrict x, T* __restrict y, T* __restrict z, const T* __restrict r, const T* __restrict a,
                  const T* __restrict k, std::uint8_t* __restrict sym, int n) {
  for (int s = 0; s < n; ++s) {
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const T xl = x[l], yl = y[l], zl = z[l], rl = r[l], al = a[l], kl = k[l];
      const T ay = al * yl;
      const T c1 = ay - xl, c3 = ay - zl;
      const bool s1 = c1 > T(0);
      const bool s3 = c3 < T(0);
      const T x1 = c1, y1 = kl * c1 - yl + al * zl, z1 = rl * zl;
      const T x3 = rl * xl, y3 = kl * c3 - yl + al * xl, z3 = c3;
      const T x2 = -c1, y2 = yl - kl * (c1 + c3), z2 = -c3;
      x[l] = s1 ? x1 : (s3 ? x3 : x2);
      y[l] = s1 ? y1 : (s3 ? y3 : y2);
      z[l] = s1 ? z1 : (s3 ? z3 : z2);
      if constexpr (Sym) sym[l] = static_cast<std::uint8_t>(s1 ? 1 : (s3 ? 3 : 2));
    }
  }
}

// Exact rescaling by a power of two so that max(|x|,|y|,|z|) lies in [1, 2): the symbols are exactly
// those of the unnormalised iteration.  float/double: exponent-bit arithmetic (vectorises);
// other types: frexp/ldexp.
template <class T, int B> inline void renormalise(T* __restrict x, T* __restrict y, T* __restrict z) {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>) {
    using U = std::conditional_t<std::is_same_v<T, double>, std::uint64_t, std::uint32_t>;
    constexpr int mant = std::numeric_limits<T>::digits - 1;        // 52 / 23
    constexpr U two_bias = 2 * (std::numeric_limits<T>::max_exponent - 1);  // 2046 / 254
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const T m = std::max(std::fabs(x[l]), std::max(std::fabs(y[l]), std::fabs(z[l])));
      const U e = std::bit_cast<U>(m) >> mant;           // biased exponent of m (m >= 0, normal)
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

}  // namespace detail

template <class T> int renormalisation_interval(const std::vector<double>& r) {
  // After a rescale the max-norm is in [1, 2).  Over K steps it stays in [2^(-K*shrink), 2^(1+K*grow)];
  // keep it 4 binary orders away from overflow and from the smallest normal number (bounds are in
  // double; the margin absorbs rounding of the matrices in T).
  constexpr double emax = std::numeric_limits<T>::max_exponent - 4;
  constexpr double emin = -(std::numeric_limits<T>::min_exponent) - 4;
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

template <class T, class Rec> void run(const Ensemble& ens, long iterations, Rec& rec, const RunOptions& opt) {
  constexpr int B = detail::batch_lanes<T>();
  const std::size_t n_orbits = ens.orbits();
  const std::size_t n_ic = ens.initial.size();
  if (n_orbits == 0 || iterations < 0) return;
  const std::size_t n_batches = (n_orbits + B - 1) / B;
  const int K = renormalisation_interval<T>(ens.r);
  const long first = std::max<long>(rec.first_step(), 1);
  const int threads = opt.threads > 0 ? opt.threads : omp_get_max_threads();
  std::atomic<std::size_t> done{0};

#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t b = 0; b < n_batches; ++b) {
    alignas(64) T x[B], y[B], z[B], r[B], a[B], k[B];
    alignas(64) std::uint8_t sym[B];
    const std::size_t o0 = b * B;
    const int lanes = static_cast<int>(std::min<std::size_t>(B, n_orbits - o0));
    for (int l = 0; l < B; ++l) {
      const std::size_t o = o0 + static_cast<std::size_t>(std::min(l, lanes - 1));  // pad with the last orbit
      const auto& u = ens.initial[o % n_ic];
      const core::Vec3<double> q = core::to_quadrant<double>(u / u.norm());
      const double rv = ens.r[o / n_ic];
      x[l] = static_cast<T>(q(0));
      y[l] = static_cast<T>(q(1));
      z[l] = static_cast<T>(q(2));
      r[l] = static_cast<T>(rv);
      a[l] = (T(1) + r[l]) / T(2);
      k[l] = a[l] / r[l];
    }
    detail::renormalise<T, B>(x, y, z);
    // Phase 1: unrecorded steps, K at a time, then an exact power-of-two rescale.
    long step = 0;
    const long quiet = std::min(iterations, first - 1);
    while (step < quiet) {
      const int n = static_cast<int>(std::min<long>(K, quiet - step));
      detail::steps<T, B, false>(x, y, z, r, a, k, sym, n);
      detail::renormalise<T, B>(x, y, z);
      step += n;
    }
    // Phase 2: recorded steps.
    int since = 0;
    while (step < iterations) {
      detail::steps<T, B, Rec::needs_symbols>(x, y, z, r, a, k, sym, 1);
      ++step;
      if (++since == K) {
        detail::renormalise<T, B>(x, y, z);
        since = 0;
      }
      rec.record(o0, lanes, step, x, y, z, Rec::needs_symbols ? sym : nullptr);
    }
    if (opt.progress) {
      const std::size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (omp_get_thread_num() == 0) opt.progress->update(d, n_batches);
    }
  }
  if (opt.progress) opt.progress->update(n_batches, n_batches);
}

template <class T, class Rec> void run_scalar(const Ensemble& ens, long iterations, Rec& rec) {
  const std::size_t n_ic = ens.initial.size();
  const long first = std::max<long>(rec.first_step(), 1);
  for (std::size_t o = 0; o < ens.orbits(); ++o) {
    const T rv = static_cast<T>(ens.r[o / n_ic]);
    const core::Vec3<double>& u0 = ens.initial[o % n_ic];
    core::Vec3<T> u = core::to_quadrant<T>(core::Vec3<T>(T(u0(0)), T(u0(1)), T(u0(2))));
    u /= u.norm();
    const core::Mat3<T> Pm[3] = {core::P1(rv), core::P2(rv), core::P3(rv)};
    const T av = core::alpha(rv);
    for (long step = 1; step <= iterations; ++step) {
      // Appendix A.2, as printed: branch on y and the two conditions, normalise every step.
      const T c2 = av * u(1) - u(0), c3 = av * u(1) - u(2);
      int s = 2;
      if (u(1) > 0 && c2 > 0) s = 1;
      else if (u(1) < 0 && c3 < 0) s = 3;
      u = Pm[s - 1] * u;
      u /= u.norm();
      if (step >= first) {
        T x = u(0), y = u(1), z = u(2);
        std::uint8_t sym = static_cast<std::uint8_t>(s);
        rec.record(o, 1, step, &x, &y, &z, Rec::needs_symbols ? &sym : nullptr);
      }
    }
  }
}

}  // namespace btob::iterate
