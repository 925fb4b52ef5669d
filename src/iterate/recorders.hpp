// Recorders: what a run keeps (tails of theta/phi/strip, symbol streams, final states, density images).
#pragma once

#include "iterate/ensemble.hpp"

#include <omp.h>

#include <cmath>
#include <cstdint>
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
template <class T> inline T atan_pos(T a, T b) {
  const bool swap = a > b;
  const T num = swap ? b : a, den = swap ? a : b;
  const T t = den > T(0) ? num / den : T(0);  // in [0, 1]
  const bool big = t > T(0.66);
  const T tt = big ? (t - T(1)) / (t + T(1)) : t;
  const T zz = tt * tt;
  const T p = (((T(-8.750608600031904122785E-1) * zz + T(-1.615753718733365076637E1)) * zz +
                T(-7.500855792314704667340E1)) * zz + T(-1.228866684490136173410E2)) * zz +
              T(-6.485021904942025371773E1);
  const T q = ((((zz + T(2.485846490142306297962E1)) * zz + T(1.650270098316988542046E2)) * zz +
                T(4.328810604912902668951E2)) * zz + T(4.853903996359136964868E2)) * zz +
              T(1.945506571482613964425E2);
  constexpr T pio4 = T(0.78539816339744830962), pio2 = T(1.57079632679489661923);
  constexpr T morebits = T(6.123233995736765886130E-17);  // pi/2 - double(pi/2)
  T res = tt + tt * (zz * p / q);
  res = big ? (pio4 + res) + T(0.5) * morebits : res;
  return swap ? (pio2 - res) + morebits : res;
}

// The coordinates a recorder can keep (paper's definitions, see core/coords.hpp).
enum class Coord { theta, log10_theta, phi, w1, w2 };
Coord parse_coord(const std::string& name, const char* field = "coord");
const char* coord_name(Coord c);

// atan2 for a, b >= 0: the vectorisable atan_pos in float/double, the type's own atan2 otherwise
// (long double, float128, MPFR keep their precision).
template <class T> inline T atan2_pos(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) return atan_pos<T>(a, b);
  else {
    using std::atan2;
    return atan2(a, b);
  }
}

template <class T> inline T coord_value(Coord c, const T& x, const T& y, const T& z) {
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

// Keeps one coordinate of the last `tail` states of every orbit: out[o * tail + j] is the value at
// state iterations - tail + 1 + j.  Values are stored in double (log-scale theta reaches 1e-140).
struct TailRecorder {
  static constexpr bool needs_symbols = false;
  Coord coord;
  long iterations, tail;
  std::vector<double> out;
  TailRecorder(Coord c, std::size_t orbits, long iterations_, long tail_)
      : coord(c), iterations(iterations_), tail(tail_), out(checked_bytes(orbits, sizeof(double) * tail_, "tail") / sizeof(double)) {}
  long first_step() const { return iterations - tail + 1; }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t*) {
    const long j = k - first_step();
    const Coord c = coord;
#pragma omp simd
    for (int l = 0; l < lanes; ++l)
      out[(o0 + l) * tail + j] = static_cast<double>(coord_value<T>(c, x[l], y[l], z[l]));
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

// The density image of a bifurcation diagram: counts[col * bins + bin] of the tail values of one
// coordinate, one column per r value, `bins` equal bins over [lo, hi] (hi in the last bin).  Values outside (and -inf of
// log10(0)) go to the under/overflow counters.  Each thread counts into its own image; merge() adds
// them in thread order (integer sums, so the result is independent of the thread count).
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
  template <class T>
  void record(std::size_t o0, int lanes, long, const T* x, const T* y, const T* z, const std::uint8_t*) {
    const int t = omp_get_thread_num();
    std::uint32_t* img = per_thread[static_cast<std::size_t>(t)].data();
    const double scale = static_cast<double>(bins) / (hi - lo);
    alignas(64) double v[64];
    // Column (r index) of the first lane, then advanced without a division per point.
    std::size_t col = o0 / n_ic, in_col = o0 % n_ic;
    for (int l0 = 0; l0 < lanes; l0 += 64) {
      const int n = std::min(64, lanes - l0);
      values(coord, n, x + l0, y + l0, z + l0, v);
      for (int l = 0; l < n; ++l) {
        // Bins are [lo + i h, lo + (i+1) h); the last one also holds hi itself (theta = pi/2 exactly is the
        // three-particle collapse x = 0, a value of the diagram, not an overflow).
        const double f = (v[l] - lo) * scale;
        if (!(f >= 0)) ++under_t[t][col];
        else if (f > static_cast<double>(bins)) ++over_t[t][col];
        else ++img[col * bins + std::min(static_cast<std::size_t>(f), bins - 1)];
        if (++in_col == n_ic) {
          in_col = 0;
          ++col;
        }
      }
    }
  }
  // v[l] = coordinate c of lanes 0..n-1, one vectorisable loop per coordinate (the switch is hoisted).
  template <class T> static void values(Coord c, int n, const T* x, const T* y, const T* z, double* v) {
    switch (c) {
      case Coord::theta:
#pragma omp simd
        for (int l = 0; l < n; ++l) v[l] = static_cast<double>(coord_value<T>(Coord::theta, x[l], y[l], z[l]));
        break;
      case Coord::phi:
#pragma omp simd
        for (int l = 0; l < n; ++l) v[l] = static_cast<double>(coord_value<T>(Coord::phi, x[l], y[l], z[l]));
        break;
      default:
        for (int l = 0; l < n; ++l) v[l] = static_cast<double>(coord_value<T>(c, x[l], y[l], z[l]));
    }
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

}  // namespace btob::iterate
