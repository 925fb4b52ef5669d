// SPDX-License-Identifier: GPL-3.0-or-later
// Recorders of the attractor classification (src/attractors): period returns and the P2 rotation (Section 5.2).
#pragma once

#include "core/map.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/lanes.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/exponent_sums.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace btob::attractors {

using iterate::checked_bytes;
using iterate::Ensemble;
using iterate::Vec3;

// |u|^2 with its multiply-adds spelled out in the order GCC contracts X X + Y Y + Z Z in scalar code (Y Y, then X X
// and Z Z added): the same bits in scalar and in vector loops, which would otherwise each contract it their own way.
inline double norm2(double X, double Y, double Z) { return std::fma(Z, Z, std::fma(X, X, Y * Y)); }
// The unit vector of a kernel state (the kernel's powers of two drop out: the same bits from any run of the orbit).
inline Vec3<double> unit_of(double X, double Y, double Z) {
  const double inv = 1 / std::sqrt(norm2(X, Y, Z));
  return Vec3<double>(X * inv, Y * inv, Z * inv);
}

// Calls f.template operator()<W>(x, y, z) with a whole batch of W lanes: the kernel's full batch itself (W =
// batch_lanes), or a partial one (the scalar route's single lane too) as copies padded with its last lane, to one
// vector's lanes when it fits in one (the one-vector batch of a few orbits, iterate::run's few_lanes: a single
// orbit's record then costs one vector's work, not six), else to the full batch.  A recorder's fixed-width loop over
// f's arrays then treats every orbit alike: a vectorised loop and its scalar remainder contract multiply-adds
// differently, and an orbit's bits would depend on where in a batch it falls; a loop of one whole vector and a loop
// of six whole vectors do the same operations on each lane.
template <class T, int W, class F> inline void padded_batch(int lanes, const T* x, const T* y, const T* z, F& f) {
  alignas(64) T px[W], py[W], pz[W];
  for (int l = 0; l < W; ++l) {
    const int q = std::min(l, lanes - 1);
    px[l] = x[q], py[l] = y[q], pz[l] = z[q];
  }
  f.template operator()<W>(px, py, pz);
}
template <class T, class F> inline void as_whole_batch(int lanes, const T* x, const T* y, const T* z, F&& f) {
  constexpr int B = iterate::detail::batch_lanes<T>();
  constexpr int V = iterate::detail::kVectorBytes / static_cast<int>(sizeof(T));
  if (lanes == B) return f.template operator()<B>(x, y, z);
  if (lanes <= V) return padded_batch<T, V>(lanes, x, y, z, f);
  padded_batch<T, B>(lanes, x, y, z, f);
}

// First pass of the classification.  For every orbit, over the window of steps transient+1 .. transient+window:
//   * s0: the unit state after `transient` steps (the reference point of the return test);
//   * the symbols of the first max_period window steps, 2 bits each (word w_1 .. w_p, w_1 applied to s0);
//   * d_j = max-norm distance between the unit state after j window steps and s0 (j <= max_period):
//     the first j with d_j < return_tol is the period, d_j its residual; the smallest d_j is kept as evidence;
//   * counts of symbols 1 and 3 over the whole window (collapse and P2-region tests);
//   * the unit state at the end of the window.
// Requires transient >= 1, window >= max_period >= 1.  Storage: orbits x (11 doubles + 4 ints + words).
struct ReturnRecorder {
  static constexpr bool needs_symbols = true;
  long transient, window;
  int max_period;
  double return_tol;
  int words;  // uint64 words of packed symbols per orbit
  std::size_t n_orbits;
  std::vector<double> s0x, s0y, s0z, fx, fy, fz, best_d, resid;
  std::vector<std::int32_t> best_j, period, n1, n3;
  std::vector<std::uint64_t>
      syms;  // word w of orbit o at w * n_orbits + o: a step's symbols are contiguous over a batch

  ReturnRecorder(std::size_t orbits, long transient_, long window_, int max_period_, double return_tol_)
      : transient(transient_),
        window(window_),
        max_period(max_period_),
        return_tol(return_tol_),
        words((2 * max_period_ + 63) / 64),
        n_orbits(orbits) {
    checked_bytes(orbits, 8 * 8 + 4 * 4 + 8 * static_cast<std::size_t>(words), "orbits (return recorder)");
    // The return test's arrays have room for a whole batch of the widest kernel after the last orbit (as
    // RotationRecorder's): its vector loop runs over a full batch even for the last, partial one.
    constexpr std::size_t widest = 128;
    const std::size_t padded = orbits + widest;
    for (auto* v : {&fx, &fy, &fz}) v->assign(orbits, 0.0);
    for (auto* v : {&s0x, &s0y, &s0z, &resid}) v->assign(padded, 0.0);
    best_d.assign(padded, std::numeric_limits<double>::infinity());
    for (auto* v : {&best_j, &period}) v->assign(padded, 0);
    for (auto* v : {&n1, &n3}) v->assign(orbits, 0);
    syms.assign(orbits * static_cast<std::size_t>(words), 0);
  }
  long first_step() const { return transient; }
  long total_steps() const { return transient + window; }  // the run's `iterations`
  // Symbol j = 1 .. max_period of the window of orbit o.
  int symbol(std::size_t o, int j) const {
    const std::size_t b = static_cast<std::size_t>(2 * (j - 1));
    return static_cast<int>((syms[b / 64 * n_orbits + o] >> (b % 64)) & 3u);
  }

  // Steps 1 .. max_period: the return test, in one fixed-width vector loop over the whole batch (as_whole_batch); the
  // steps after it count symbols only (no unit state), but the last, which keeps the final state.
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t* sym) {
    const long j = k - transient;
    if (j == 0 || j == window) {  // the unit state: s0, or the final state
      std::vector<double>&ux = j == 0 ? s0x : fx, &uy = j == 0 ? s0y : fy, &uz = j == 0 ? s0z : fz;
      for (int l = 0; l < lanes; ++l) {
        const std::size_t o = o0 + static_cast<std::size_t>(l);
        const Vec3<double> u = unit_of(static_cast<double>(x[l]), static_cast<double>(y[l]), static_cast<double>(z[l]));
        ux[o] = u(0), uy[o] = u(1), uz[o] = u(2);
      }
      if (j == 0) return;
    }
    std::int32_t* __restrict c1 = n1.data() + o0;
    std::int32_t* __restrict c3 = n3.data() + o0;
#pragma omp simd
    for (int l = 0; l < lanes; ++l) {
      c1[l] += sym[l] == 1;
      c3[l] += sym[l] == 3;
    }
    if (j > max_period) return;
    const std::size_t b = static_cast<std::size_t>(2 * (j - 1));
    std::uint64_t* __restrict w = syms.data() + b / 64 * n_orbits + o0;
    const unsigned shift = static_cast<unsigned>(b % 64);
#pragma omp simd
    for (int l = 0; l < lanes; ++l) w[l] |= static_cast<std::uint64_t>(sym[l]) << shift;
    as_whole_batch(lanes, x, y, z,
                   [&]<int W>(const T* bx, const T* by, const T* bz) { returns<T, W>(o0, j, bx, by, bz); });
  }

 private:
  // The return test of window step j (1 <= j <= max_period) for the B orbits from o0 (arrays padded past the last
  // orbit: the padding lanes of a partial batch write there).  Bit for bit the scalar loop's: no contraction here
  // but norm2's explicit multiply-adds (written out: a call would not inline across the attribute), so the unit
  // vector is rounded before its difference to s0 (a contracted X inv - s0x made an exact return's distance 1.31
  // ulps instead of 1).
  template <class T, int B>
  __attribute__((optimize("fp-contract=off"))) void returns(std::size_t o0, long j, const T* __restrict x,
                                                            const T* __restrict y, const T* __restrict z) {
    const double* __restrict ax = s0x.data() + o0;
    const double* __restrict ay = s0y.data() + o0;
    const double* __restrict az = s0z.data() + o0;
    double* __restrict bd = best_d.data() + o0;
    double* __restrict rs = resid.data() + o0;
    std::int32_t* __restrict bj = best_j.data() + o0;
    std::int32_t* __restrict per = period.data() + o0;
    const double tol = return_tol;
    const std::int32_t jj = static_cast<std::int32_t>(j);
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const double X = static_cast<double>(x[l]), Y = static_cast<double>(y[l]), Z = static_cast<double>(z[l]);
      const double inv = 1 / std::sqrt(std::fma(Z, Z, std::fma(X, X, Y * Y)));
      const double ux = X * inv, uy = Y * inv, uz = Z * inv;
      const double dx = std::fabs(ux - ax[l]), dy = std::fabs(uy - ay[l]), dz = std::fabs(uz - az[l]);
      const double dyz = dy < dz ? dz : dy;  // std::max's selections, NaN included
      const double d = dx < dyz ? dyz : dx;
      const bool better = d < bd[l];
      bd[l] = better ? d : bd[l];
      bj[l] = better ? jj : bj[l];
      const bool first = per[l] == 0 && d < tol;
      per[l] = first ? jj : per[l];
      rs[l] = first ? d : rs[l];
    }
  }
};

// The kernel's state after `steps` steps, as it is (the unnormalised iterate times a power of two).  A run started
// from it continues the same iteration bit for bit: the kernel only rescales by exact powers of two, which commute
// with every rounding of the step, and the recorders above read scale-invariant quantities.  Storage: 3 doubles.
struct StateRecorder {
  static constexpr bool needs_symbols = false;
  long steps;
  std::vector<Vec3<double>> state;
  StateRecorder(std::size_t orbits, long steps_) : steps(steps_) {
    checked_bytes(orbits, sizeof(Vec3<double>), "orbits (state recorder)");
    state.assign(orbits, Vec3<double>::Zero());
  }
  long first_step() const { return steps; }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t*) {
    if (k != steps) return;
    for (int l = 0; l < lanes; ++l)
      state[o0 + static_cast<std::size_t>(l)] =
          Vec3<double>(static_cast<double>(x[l]), static_cast<double>(y[l]), static_cast<double>(z[l]));
  }
};

// atan2(a, b) on the whole circle, in (-pi, pi], from the vectorisable atan_pos.
template <class T> inline T atan2_full(T a, T b) {
  const T t = iterate::atan_pos<T>(std::fabs(a), std::fabs(b));  // in [0, pi/2]
  const T q = b >= T(0) ? t : T(std::numbers::pi) - t;
  return a >= T(0) ? q : -q;
}

// Second pass (orbits not found periodic): the rotation about the P2 centre (1, 0, -1) and the conserved
// quantity of P2 (Section 5.2), averaged with the weights w(t) = exp(-1/(t(1-t))) of Das and Yorke.
// With s = x + z, a = x - z (a >= 0 in Q):
//   I(u) = (2 s^2 - 4 alpha s y + 4 r y^2) / a^2    (= 2 w2^2 - 4 alpha w1 w2 + 4 r w1^2 on the strip)
// is invariant under P2 for every r (P2 keeps the plane x = z and a -> r a, and det(P2|_{x=z}) = r^2); for
// r > 3 - 2 sqrt(2) it is positive definite and, in the coordinates xi = (s - alpha y)/sqrt(2),
// eta = sqrt(r - alpha^2/2) y, P2 acts as a rotation by the angle beta of cos(beta) = -(1-r)^2/(4r).
// Per orbit: weighted Birkhoff averages of the angle increment (in (-pi, pi]) over the whole record and
// over its first half, and min / max / weighted mean of I.  Records steps start .. start + n (n >= 4);
// the increments of steps start+1 .. start+n are averaged.  One r per run (the classification runs
// one r at a time); `rotation_defined` is false when r <= 3 - 2 sqrt(2) (no rotation, angles not kept).
struct RotationRecorder {
  static constexpr bool needs_symbols = false;
  long start, n;
  double r, alpha, c_eta;
  bool rotation_defined;
  std::vector<double> w_full, w_half;  // weights of increments j = 1 .. n (w_half zero beyond n/2)
  double sum_full = 0, sum_half = 0;
  std::vector<double> last, s_full, s_half, i_min, i_max, i_mean;
  std::vector<double> fx, fy, fz;  // the unit state at step start + n (where a longer run would continue)

  RotationRecorder(std::size_t orbits, double r_, long start_, long n_)
      : start(start_), n(n_), r(r_), alpha(core::alpha(r_)) {
    checked_bytes(orbits, 9 * sizeof(double), "orbits (rotation recorder)");
    rotation_defined = defined(r);
    c_eta = rotation_defined ? std::sqrt(eta2(r)) : 0.0;
    w_full.assign(static_cast<std::size_t>(n) + 1, 0.0);
    w_half.assign(static_cast<std::size_t>(n) + 1, 0.0);
    const auto w = [](double t) { return t <= 0 || t >= 1 ? 0.0 : std::exp(-1 / (t * (1 - t))); };
    const long h = n / 2;
    for (long j = 1; j <= n; ++j) {
      w_full[static_cast<std::size_t>(j)] = w((static_cast<double>(j) - 0.5) / static_cast<double>(n));
      if (j <= h) w_half[static_cast<std::size_t>(j)] = w((static_cast<double>(j) - 0.5) / static_cast<double>(h));
      sum_full += w_full[static_cast<std::size_t>(j)];
      sum_half += w_half[static_cast<std::size_t>(j)];
    }
    // Room for a whole batch of the widest kernel (96 float lanes with AVX-512, iterate/lanes.hpp; a fixed bound
    // because this constructor also runs in units compiled without the kernel's flags) after the last orbit: the
    // per-step loop runs over a full batch even for the last, partial one, whose padding lanes are never read.
    constexpr std::size_t widest = 128;
    const std::size_t padded = orbits + widest;
    for (auto* v : {&last, &s_full, &s_half, &i_mean}) v->assign(padded, 0.0);
    for (auto* v : {&fx, &fy, &fz}) v->assign(orbits, 0.0);
    i_min.assign(padded, std::numeric_limits<double>::infinity());
    i_max.assign(padded, -std::numeric_limits<double>::infinity());
  }
  // I's coefficient r - alpha^2 / 2 (c_eta^2); P2 acts as a rotation at r (I positive definite) where it is > 0:
  // r > 3 - 2 sqrt(2).
  static double eta2(double r) {
    const double al = core::alpha(r);
    return r - al * al / 2;
  }
  static bool defined(double r) { return eta2(r) > 0; }
  long first_step() const { return start; }
  // Weighted Birkhoff averages of the angle increment, in turns (rotation numbers in (-1/2, 1/2]).
  double rotation(std::size_t o) const { return s_full[o] / sum_full / (2 * std::numbers::pi); }
  double rotation_half(std::size_t o) const { return s_half[o] / sum_half / (2 * std::numbers::pi); }
  double invariant(std::size_t o) const { return i_mean[o] / sum_full; }

  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t*) {
    const long j = k - start;
    if (j > n) return;
    if (j == n)
      for (int l = 0; l < lanes; ++l) {
        const std::size_t o = o0 + static_cast<std::size_t>(l);
        const Vec3<double> u = unit_of(static_cast<double>(x[l]), static_cast<double>(y[l]), static_cast<double>(z[l]));
        fx[o] = u(0), fy[o] = u(1), fz[o] = u(2);
      }
    // One fixed-width loop over the whole batch (as_whole_batch).
    as_whole_batch(lanes, x, y, z, [&]<int W>(const T* bx, const T* by, const T* bz) {
      if (rotation_defined) steps<T, W, true>(o0, j, bx, by, bz);
      else steps<T, W, false>(o0, j, bx, by, bz);
    });
  }

 private:
  // Step j of the record for the B orbits from o0: one vector loop, no branch but selections, the invariant and (Rot)
  // the angle of each lane.  Compiled without GCC's partial redundancy elimination, which evaluated atan_pos's
  // rational function once for each side of its reduction's selection and selected afterwards (a fourth division per
  // vector); the same operations otherwise, so the same bits.  The angle's abscissa (s - alpha Y) sqrt(2)/2 is one
  // product by the double nearest sqrt(2), halved: round(v round(sqrt 2)) / 2 = round(v (round(sqrt 2) / 2)) exactly
  // (a power of two commutes with rounding; v is never subnormal, the kernel keeps the state's exponent within
  // about +-500 and v = 0 gives 0 either way).
  template <class T, int B, bool Rot>
  __attribute__((optimize("no-tree-pre"))) void steps(std::size_t o0, long j, const T* __restrict x,
                                                      const T* __restrict y, const T* __restrict z) {
    const double wf = w_full[static_cast<std::size_t>(j)], wh = w_half[static_cast<std::size_t>(j)];
    const double al = alpha, rr = r, ce = c_eta, inf = std::numeric_limits<double>::infinity();
    constexpr double pi = std::numbers::pi, half_sqrt2 = std::numbers::sqrt2 / 2;
    double* __restrict lo = i_min.data() + o0;
    double* __restrict hi = i_max.data() + o0;
    double* __restrict mean = i_mean.data() + o0;
    double* __restrict prev = last.data() + o0;
    double* __restrict full = s_full.data() + o0;
    double* __restrict half = s_half.data() + o0;
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const double X = static_cast<double>(x[l]), Y = static_cast<double>(y[l]), Z = static_cast<double>(z[l]);
      const double s = X + Z, a = X - Z;
      const double inv = a > 0 ? 1 / (a * a) : inf;
      const double I = (2 * s * s - 4 * al * s * Y + 4 * rr * Y * Y) * inv;
      lo[l] = I < lo[l] ? I : lo[l];
      hi[l] = I > hi[l] ? I : hi[l];
      mean[l] += wf * I;
      if constexpr (Rot) {
        const double ang = atan2_full<double>(ce * Y, (s - al * Y) * half_sqrt2);
        double d = ang - prev[l];
        d = d > pi ? d - 2 * pi : (d <= -pi ? d + 2 * pi : d);
        full[l] += wf * d;  // step 0 only sets the first angle: its weights are 0
        half[l] += wh * d;
        prev[l] = ang;
      }
    }
  }
};

// Pass 2's cocycle recorder: lambda1's sums (lyapunov::ExponentSums) and, at the last checkpoint, the unit state
// where a refinement pass continues (the fused kernel steps the plain kernel's points; they differ from a plain run's
// only by exact powers of two, which normalising removes: the same bits).  Storage: orbits x 3 doubles more.
struct PassTwoSums : lyapunov::ExponentSums {
  std::vector<double> fx, fy, fz;
  PassTwoSums(const Ensemble& e, long transient_, long iterations_, int blocks_)
      : ExponentSums(e, transient_, iterations_, blocks_) {
    checked_bytes(e.orbits(), 3 * sizeof(double), "orbits (pass 2)");
    for (auto* v : {&fx, &fy, &fz}) v->assign(e.orbits(), 0.0);
  }
  template <class T> void record(const iterate::CocycleBatch<T>& b) {
    ExponentSums::record(b);
    if (b.step != total_steps()) return;
    for (int l = 0; l < b.lanes; ++l) {
      const std::size_t o = b.orbit0 + static_cast<std::size_t>(l);
      const Vec3<double> u = unit_of(b.x[l], b.y[l], b.z[l]);
      fx[o] = u(0), fy[o] = u(1), fz[o] = u(2);
    }
  }
};

}  // namespace btob::attractors
