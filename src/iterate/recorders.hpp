// SPDX-License-Identifier: GPL-3.0-or-later
// Recorders: what a run keeps (tails of theta/phi/strip, symbol streams, final states, density images).
#pragma once

#include "iterate/ensemble.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace btob::iterate {

// atan2(a, b) for a, b >= 0 (not both zero), in [0, pi/2]; branch-free so that it vectorises.
// Cephes' atan (S. Moshier): reduction to |t| <= 0.66 and a rational approximation; relative error
// about 1e-16 in double (tested against std::atan2), exact-to-rounding ~1e-7 in float.
template <class T> [[gnu::always_inline]] inline T atan_pos(T a, T b) {
  const bool swap = a > b;
  const T num = swap ? b : a, den = swap ? a : b;
  const T t = den > T(0) ? num / den : T(0);  // in [0, 1]
  const bool big = t > T(0.66);
  const T tt = big ? (t - T(1)) / (t + T(1)) : t;
  const T zz = tt * tt;
  const T p =
      (((T(-8.750608600031904122785E-1) * zz + T(-1.615753718733365076637E1)) * zz + T(-7.500855792314704667340E1)) *
           zz +
       T(-1.228866684490136173410E2)) *
          zz +
      T(-6.485021904942025371773E1);
  const T q =
      ((((zz + T(2.485846490142306297962E1)) * zz + T(1.650270098316988542046E2)) * zz + T(4.328810604912902668951E2)) *
           zz +
       T(4.853903996359136964868E2)) *
          zz +
      T(1.945506571482613964425E2);
  constexpr T pio4 = T(0.78539816339744830962), pio2 = T(1.57079632679489661923);
  constexpr T morebits = T(6.123233995736765886130E-17);  // pi/2 - double(pi/2)
  T res = tt + tt * (zz * p / q);
  res = big ? (pio4 + res) + T(0.5) * morebits : res;
  return swap ? (pio2 - res) + morebits : res;
}

// atan2(a, b) for a, b >= 0, for binning only (DensityRecorder::certain_bins): cheap, with a proven error bound, and
// NaN where the bound does not hold.  No division (a vector division costs as much as the rest together): the
// reduction to |u| <= tan(pi/8) picks u = a/b or (a - b)/(a + b) after ordering a <= b, and 1/d starts from the
// exponent-flipping integer subtraction (relative error <= 0.051) refined by three Newton steps (<= 4.3e-11, so u
// within 2e-11); atan(u) is a degree-7 odd polynomial fitted to atan on that interval (least squares on Chebyshev
// nodes weighted by u; 1.17e-7).  Absolute error below kAtanFastError (tests/test_iterate.cpp checks it); NaN for
// denominators outside [1e-300, 1e300] (the bit trick needs normal numbers) and for a = b = 0.
inline constexpr double kAtanFastError = 2e-7;
[[gnu::always_inline]] inline double atan_fast(double a, double b) {
  const bool swap = a > b;
  const double num = swap ? b : a, den = swap ? a : b;
  const bool big = num > 0.41421356237309503 * den;  // t = num/den > tan(pi/8)
  const double nn = big ? num - den : num, dd = big ? num + den : den;
  const bool normal = dd >= 1e-300 && dd <= 1e300;
  const double d = normal ? dd : 1.0;
  double rd = std::bit_cast<double>(std::uint64_t{0x7FDE623822FC16E6} - std::bit_cast<std::uint64_t>(d));
  rd = rd * (2.0 - d * rd);
  rd = rd * (2.0 - d * rd);
  rd = rd * (2.0 - d * rd);
  const double u = nn * rd;
  const double s = u * u;
  const double p =
      0.9999974560342069 + s * (-0.33313351949743975 + s * (0.1957022354347687 + s * -0.10739878673227493));
  constexpr double pio4 = 0.78539816339744830962, pio2 = 1.57079632679489661923;
  const double res = u * p + (big ? pio4 : 0.0);
  return normal ? (swap ? pio2 - res : res) : std::numeric_limits<double>::quiet_NaN();
}

// The coordinates a recorder can keep (paper's definitions, see core/coords.hpp).
enum class Coord { theta, log10_theta, phi, w1, w2 };
Coord parse_coord(const std::string& name, const char* field = "coord");
const char* coord_name(Coord c);

// atan2 for a, b >= 0: the vectorisable atan_pos in float/double, the type's own atan2 otherwise
// (long double, float128, MPFR keep their precision).
template <class T> [[gnu::always_inline]] inline T atan2_pos(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) return atan_pos<T>(a, b);
  else {
    using std::atan2;
    return atan2(a, b);
  }
}

template <class T> [[gnu::always_inline]] inline T coord_value(Coord c, const T& x, const T& y, const T& z) {
  using std::log10;
  using std::sqrt;
  switch (c) {
    case Coord::theta: return atan2_pos<T>(-z, x);
    case Coord::log10_theta: return log10(atan2_pos<T>(-z, x));
    case Coord::phi: {
      const T n = sqrt(x * x + z * z);
      return -y >= T(0) ? atan2_pos<T>(n, -y) : T(std::numbers::pi) - atan2_pos<T>(n, y);
    }
    case Coord::w1: return y / (x - z);
    case Coord::w2: return (x + z) / (x - z);
  }
  return T(0);
}

// out[i * stride] = coord_value<T>(c, x[i], y[i], z[i]) for i < n, in double: one vector loop over whole blocks of 64
// lanes (a partial block padded with its last state), so that every caller in a translation unit gets the same vector
// code's value.  coord_value<T> in a vectorised loop and in scalar code may contract its multiply-adds differently and
// differ by an ulp (seen: phi in float, 2.65536857 against 2.65536833); the density image's exact route and the
// recorded tails must agree to the bit.
//
// This function and every recorder function that vectorises are inlined (always_inline): an out-of-line copy of a
// function defined in a header is emitted by every translation unit that calls it, each compiled for its own
// instruction set, and the linker keeps one of them.  btob's DensityRecorder::certain_bins<double> was reference.cpp's
// baseline SSE2 copy (Figure 4.7's trig_density calls record), not the AVX-512 kernel's.
template <class T>
[[gnu::always_inline]] inline void coord_values(Coord c, int n, const T* x, const T* y, const T* z, double* out,
                                                std::size_t stride = 1) {
  constexpr int kBlock = 64;
  alignas(64) T xs[kBlock], ys[kBlock], zs[kBlock];
  alignas(64) double vs[kBlock];
  for (int i0 = 0; i0 < n; i0 += kBlock) {
    const int m = std::min(kBlock, n - i0);
    for (int l = 0; l < kBlock; ++l) {
      const int i = i0 + std::min(l, m - 1);
      xs[l] = x[i];
      ys[l] = y[i];
      zs[l] = z[i];
    }
#pragma omp simd
    for (int l = 0; l < kBlock; ++l) vs[l] = static_cast<double>(coord_value<T>(c, xs[l], ys[l], zs[l]));
    for (int l = 0; l < m; ++l) out[static_cast<std::size_t>(i0 + l) * stride] = vs[l];
  }
}

// Keeps one coordinate of the last `tail` states of every orbit: out[o * tail + j] is the value at
// state iterations - tail + 1 + j.  Values are stored in double (log-scale theta reaches 1e-140).
struct TailRecorder {
  static constexpr bool needs_symbols = false;
  Coord coord;
  long iterations, tail;
  std::vector<double> out;
  TailRecorder(Coord c, std::size_t orbits, long iterations_, long tail_)
      : coord(c),
        iterations(iterations_),
        tail(tail_),
        out(checked_bytes(orbits, sizeof(double) * tail_, "tail") / sizeof(double)) {}
  long first_step() const { return iterations - tail + 1; }
  template <class T>
  [[gnu::always_inline]] void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z,
                                     const std::uint8_t*) {
    const std::size_t j = static_cast<std::size_t>(k - first_step());
    const std::size_t stride = static_cast<std::size_t>(tail);
    coord_values<T>(coord, lanes, x, y, z, out.data() + o0 * stride + j, stride);
  }
};

// Keeps the symbols 1/2/3 of steps from..to (inclusive) of every orbit: out[o * count + (k - from)].
struct SymbolRecorder {
  static constexpr bool needs_symbols = true;
  long from, to, count;
  std::vector<std::uint8_t> out;
  SymbolRecorder(std::size_t orbits, long from_, long to_)
      : from(from_), to(to_), count(to_ - from_ + 1), out(checked_bytes(orbits, to_ - from_ + 1, "symbols")) {}
  long first_step() const { return from; }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T*, const T*, const T*, const std::uint8_t* sym) {
    if (k > to) return;
    for (int l = 0; l < lanes; ++l) out[(o0 + l) * count + (k - from)] = sym[l];
  }
};

// Keeps the final state of every orbit (normalised to unit length, in double).
struct FinalRecorder {
  static constexpr bool needs_symbols = false;
  long iterations;
  std::vector<Vec3<double>> out;
  FinalRecorder(std::size_t orbits, long iterations_) : iterations(iterations_), out(orbits) {}
  long first_step() const { return iterations; }
  template <class T>
  void record(std::size_t o0, int lanes, long, const T* x, const T* y, const T* z, const std::uint8_t*) {
    for (int l = 0; l < lanes; ++l) {
      Vec3<double> u(static_cast<double>(x[l]), static_cast<double>(y[l]), static_cast<double>(z[l]));
      out[o0 + l] = u / u.norm();
    }
  }
};

// Keeps the unit state of the last `tail` states of every orbit, in double: x[o * tail + j] (and y, z) is the state
// after step iterations - tail + 1 + j normalised as FinalRecorder normalises (u / |u|), so its last column is
// FinalRecorder's state bit for bit.
struct StateTailRecorder {
  static constexpr bool needs_symbols = false;
  long iterations, tail;
  std::vector<double> x, y, z;
  StateTailRecorder(std::size_t orbits, long iterations_, long tail_)
      : iterations(iterations_),
        tail(tail_),
        x(checked_bytes(orbits, 3 * sizeof(double) * tail_, "states") / (3 * sizeof(double))),
        y(x.size()),
        z(x.size()) {}
  long first_step() const { return iterations - tail + 1; }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* px, const T* py, const T* pz, const std::uint8_t*) {
    const std::size_t j = static_cast<std::size_t>(k - first_step()), stride = static_cast<std::size_t>(tail);
    for (int l = 0; l < lanes; ++l) {
      Vec3<double> u(static_cast<double>(px[l]), static_cast<double>(py[l]), static_cast<double>(pz[l]));
      u = u / u.norm();
      const std::size_t at = (o0 + static_cast<std::size_t>(l)) * stride + j;
      x[at] = u(0), y[at] = u(1), z[at] = u(2);
    }
  }
};

// The density image of a bifurcation diagram: counts[col * bins + bin] of the tail values of one
// coordinate, one column per r value, `bins` equal bins over [lo, hi] (hi in the last bin).  Values outside (and -inf
// of log10(0)) go to the under/overflow counters.  Each thread counts into its own image; merge() adds them in thread
// order (integer sums, so the result is independent of the thread count).
struct DensityRecorder {
  static constexpr bool needs_symbols = false;
  Coord coord;
  long iterations, tail;
  std::size_t n_ic, columns, bins;
  double lo, hi;
  std::vector<std::vector<std::uint32_t>> per_thread;
  std::vector<std::uint64_t> under, over;  // per column
  std::vector<std::vector<std::uint64_t>> under_t, over_t;
  DensityRecorder(Coord c, const Ensemble& e, long iterations_, long tail_, std::size_t bins_, double lo_, double hi_,
                  int threads);
  long first_step() const { return iterations - tail + 1; }
  // Each lane's bin is that of coord_value<T> under the rule of `exact_bin`.  float/double take a fast route: the
  // coordinate from atan_fast (no division, no branch) and the bin index in one vector loop, where the bin is
  // certain (the value lies farther than the two routes' error bound from every bin edge); the other lanes (about
  // 2e-4 of them in Figure 4.1, and every value outside [lo, hi)) take coord_value<T> itself, so the image is
  // the one coord_value<T> gives, bit for bit.
  template <class T>
  [[gnu::always_inline]] void record(std::size_t o0, int lanes, long, const T* x, const T* y, const T* z,
                                     const std::uint8_t*) {
    const int t = omp_get_thread_num();
    std::uint32_t* img = per_thread[static_cast<std::size_t>(t)].data();
    alignas(64) std::int32_t bin[64];
    for (int l0 = 0; l0 < lanes; l0 += 64) {
      const int n = std::min(64, lanes - l0);
      certain_bins(n, x + l0, y + l0, z + l0, bin);
      // The certain lanes, one column (r value) at a time; the others after, each with coord_value<T>.
      const std::size_t o = o0 + static_cast<std::size_t>(l0);
      std::size_t col = o / n_ic, in_col = o % n_ic;
      bool rest = false;
      for (int l = 0; l < n;) {
        const int seg = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(n - l), n_ic - in_col));
        std::uint32_t* row = img + col * bins;
        for (const int end = l + seg; l < end; ++l) {
          if (bin[l] >= 0) ++row[bin[l]];
          else rest = true;
        }
        ++col;
        in_col = 0;
      }
      if (rest) {  // the uncertain lanes, compacted, through coord_values<T> as the recorded tails are
        alignas(64) T xs[64], ys[64], zs[64];
        alignas(64) double v[64];
        int m = 0;
        for (int l = 0; l < n; ++l)
          if (bin[l] < 0) {
            xs[m] = x[l0 + l];
            ys[m] = y[l0 + l];
            zs[m] = z[l0 + l];
            bin[m++] = l;
          }
        coord_values<T>(coord, m, xs, ys, zs, v);
        for (int i = 0; i < m; ++i) exact_bin(t, (o + static_cast<std::size_t>(bin[i])) / n_ic, v[i]);
      }
    }
  }
  // The rule: bins are [lo + i h, lo + (i+1) h); the last one also holds hi itself (theta = pi/2 exactly is the
  // three-particle collapse x = 0, a value of the diagram, not an overflow); NaN and values below lo are under,
  // values above hi over.
  double scale() const { return static_cast<double>(bins) / (hi - lo); }  // bins per unit of the coordinate
  void exact_bin(int t, std::size_t col, double v) {
    const double f = (v - lo) * scale();
    if (!(f >= 0)) ++under_t[static_cast<std::size_t>(t)][col];
    else if (f > static_cast<double>(bins)) ++over_t[static_cast<std::size_t>(t)][col];
    else ++per_thread[static_cast<std::size_t>(t)][col * bins + std::min(static_cast<std::size_t>(f), bins - 1)];
  }
  // bin[l] = the bin of lane l where the fast route proves it, -1 elsewhere (always -1 for the wide types).
  template <class T>
  [[gnu::always_inline]] void certain_bins(int n, const T* x, const T* y, const T* z, std::int32_t* bin) const {
    if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) {
      const double scale = this->scale(), nb = static_cast<double>(bins), lo_ = lo;
      // Guard in bin units: the two routes' distance (fast_error), and the rounding of (v - lo) * scale (a few ulps
      // of f <= bins).
      const double g = fast_error<T>(coord) * scale * (1 + 1e-9) + 8 * std::numeric_limits<double>::epsilon() * nb;
      // One vectorisable loop per coordinate (the switch hoisted); v(l) is the fast route's value of lane l.
      const auto bins_of = [&](auto v) {
#pragma omp simd
        for (int l = 0; l < n; ++l) {
          const double f = (v(l) - lo_) * scale;
          const double fl = std::floor(f);
          const bool ok = fl >= 0 && fl < nb && f - fl > g && fl + 1 - f > g;  // false for NaN
          bin[l] = ok ? static_cast<std::int32_t>(fl) : -1;
        }
      };
      switch (coord) {
        case Coord::theta:  // NaN outside the domain a, b >= 0 of atan_fast: coord_value<T> decides those lanes
          return bins_of([&](int l) {
            const double a = -static_cast<double>(z[l]), b = static_cast<double>(x[l]);
            return a >= 0 && b >= 0 ? atan_fast(a, b) : std::numeric_limits<double>::quiet_NaN();
          });
        case Coord::phi:
          return bins_of([&](int l) {
            const double xd = static_cast<double>(x[l]), yd = static_cast<double>(y[l]), zd = static_cast<double>(z[l]);
            const double nn = std::sqrt(xd * xd + zd * zd);
            return -yd >= 0 ? atan_fast(nn, -yd) : std::numbers::pi - atan_fast(nn, yd);
          });
        case Coord::w1:
          return bins_of([&](int l) { return static_cast<double>(coord_value<T>(Coord::w1, x[l], y[l], z[l])); });
        case Coord::w2:
          return bins_of([&](int l) { return static_cast<double>(coord_value<T>(Coord::w2, x[l], y[l], z[l])); });
        default: break;
      }
    }
    for (int l = 0; l < n; ++l) bin[l] = -1;
  }
  // Bound on |fast route - coord_value<T>| of coordinate c (0: the fast route is coord_value<T> itself).  theta and
  // phi: atan_fast's error plus coord_value<T>'s own (atan_pos ~2 ulps of T relative; phi adds the rounding of T's
  // sqrt and of pi - a), bounded by 8 ulps of T times pi.
  template <class T> static constexpr double fast_error(Coord c) {
    return c == Coord::theta || c == Coord::phi
               ? kAtanFastError + 8 * static_cast<double>(std::numeric_limits<T>::epsilon()) * std::numbers::pi
               : 0.0;
  }
  // The merged image (columns x bins) and under/overflow counts; call once (it consumes the images).
  std::vector<std::uint32_t> merge();
};

// Several recorders in one run.
template <class... R> struct Both {
  static constexpr bool needs_symbols = (R::needs_symbols || ...);
  std::tuple<R&...> parts;
  explicit Both(R&... r) : parts(r...) {}
  long first_step() const {
    return std::apply([](auto&... p) { return std::min({p.first_step()...}); }, parts);
  }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t* s) {
    std::apply([&](auto&... p) { ((k >= p.first_step() ? p.record(o0, lanes, k, x, y, z, s) : void()), ...); }, parts);
  }
};

// The whole tail of an orbit from one run: unit states, theta, phi and branches (Python's iterate(record="orbit")).
using OrbitRecorders = Both<StateTailRecorder, TailRecorder, TailRecorder, SymbolRecorder>;

}  // namespace btob::iterate
