// SPDX-License-Identifier: GPL-3.0-or-later
// TangentRecorder: the projective derivative cocycle carried along every orbit of a batched run (Section 8.1 (3)).
#pragma once

#include "iterate/cocycle.hpp"
#include "iterate/lanes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "iterate/ensemble.hpp"

namespace btob::lyapunov {

using iterate::checked_bytes;
using iterate::Ensemble;
using iterate::Vec3;

// For every orbit, one tangent vector v of the sphere is pushed through the derivative of
// u -> M u / |M u| (M = P_s / r, the kernel's matrices: same projective map, same derivative), from the
// recorder's copy of the previous kernel state s and the step's symbol:
//     m = M s,   t = M v - m (m . M v) / |m|^2        (t is D v times |M u|, u = s / |s|)
// and v <- t with an exact power-of-two rescale.  Per orbit the recorder accumulates
//     L1   = log |v_k|                (+ exponents of the rescales)
//     logG = sum_k log |M u_k| = sum_k log g_k   (as a mantissa in [1,2) and an exponent: no log per step)
//     n13  = number of steps with symbol 1 or 3
// so that, over averaged steps, lambda1 = (dL1 - dlogG) / n (the paper's lambda_n(x) with v_0 = e1) and,
// from det D(u) = det M_s / |M u|^3 (det M_1 = det M_3 = r, det M_2 = 1), lambda1 + lambda2 =
// (dn13 log r - 3 dlogG) / n; the linear cocycle's chi1 = dlogG / n + log r.  Cumulative values are stored at
// the end of the transient and at every block end (batch means, see lyapunov::map_exponents).
// Records every step from 1 (the cocycle runs through the transient too); reads ensemble.initial for the
// state at step 0.  Storage: orbits x (13 + 3 (blocks + 1)) doubles.
struct TangentRecorder {
  static constexpr bool needs_symbols = true;
  const Ensemble* ens;
  long transient, n;
  int blocks;
  std::vector<long> block_end;  // averaged-step counts ending each block: n * j / blocks, j = 1..blocks
  std::size_t n_ic;
  std::vector<double> sx, sy, sz, vx, vy, vz, pg, eg, ev, n13, rr, aa, kk;
  std::vector<double> cum;  // cum[(o * (blocks + 1) + j) * 3 + q], q = 0: L1, 1: logG, 2: n13

  TangentRecorder(const Ensemble& e, long transient_, long iterations_, int blocks_)
      : ens(&e), transient(transient_), n(iterations_), blocks(blocks_), n_ic(e.initial.size()) {
    const std::size_t N = e.orbits();
    checked_bytes(N, sizeof(double) * (13 + 3 * (blocks + 1)), "tangent recorder");
    for (int j = 1; j <= blocks; ++j) block_end.push_back(n * j / blocks);
    // Whole batches of the widest kernel (96 float lanes with AVX-512, see iterate/lanes.hpp); a fixed
    // bound because this constructor also runs in units compiled without the kernel's flags.
    constexpr std::size_t widest = 128;
    const std::size_t padded = (N + widest - 1) / widest * widest;
    for (auto* a : {&sx, &sy, &sz, &vx, &vy, &vz, &pg, &eg, &ev, &n13, &rr, &aa, &kk})
      a->assign(padded, 1.0);  // padding lanes hold harmless finite values
    cum.assign(N * static_cast<std::size_t>(blocks + 1) * 3, 0.0);
    for (std::size_t o = 0; o < N; ++o) {
      rr[o] = e.r[o / n_ic];
      aa[o] = (1 + rr[o]) / 2;
      kk[o] = aa[o] / rr[o];
    }
  }
  long first_step() const { return 1; }
  // Lanes per kernel batch (iterate/lanes.hpp: detail::batch_lanes).
  template <class T> static constexpr int kLanes = iterate::detail::batch_lanes<T>();
  long total_steps() const { return transient + n; }  // the run's `iterations`

  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* x, const T* y, const T* z, const std::uint8_t* sym) {
    if (k == 1) init<T>(o0, lanes);
    // A full batch goes through the fixed-width loop (a compile-time trip count is what lets GCC vectorise it); a
    // partial one (the last batch of an ensemble, the scalar reference's lanes = 1) through the same loop on padded
    // copies, so that an orbit's bits do not depend on where in a batch it falls: the vectorised and the scalar
    // loop contract multiply-adds differently, and the exponents then depended on the ensemble's size (an MPI
    // rank's share of the r values gave other bits than the whole run).
    if (lanes == kLanes<T>)
      tangent_steps<T, kLanes<T>>(rr.data() + o0, aa.data() + o0, kk.data() + o0, x, y, z, sym, sx.data() + o0,
                                  sy.data() + o0, sz.data() + o0, vx.data() + o0, vy.data() + o0, vz.data() + o0,
                                  pg.data() + o0, eg.data() + o0, ev.data() + o0, n13.data() + o0);
    else partial_batch<T>(o0, lanes, x, y, z, sym);
    if (k == transient) store(o0, lanes, 0);
    else if (k > transient) {
      const auto it = std::lower_bound(block_end.begin(), block_end.end(), k - transient);
      if (it != block_end.end() && *it == k - transient) store(o0, lanes, static_cast<int>(it - block_end.begin()) + 1);
    }
  }

 private:
  // `lanes` < B orbits from o0: copied into B-wide buffers padded with the last orbit, stepped, copied back.
  template <class T>
  void partial_batch(std::size_t o0, int lanes, const T* x, const T* y, const T* z, const std::uint8_t* sym) {
    constexpr int B = kLanes<T>;
    alignas(64) T px[B], py[B], pz[B];
    alignas(64) std::uint8_t ps[B];
    alignas(64) double buf[13][B];
    std::vector<double>* const arrays[13] = {&rr, &aa, &kk, &sx, &sy, &sz, &vx, &vy, &vz, &pg, &eg, &ev, &n13};
    for (int l = 0; l < B; ++l) {
      const int s = std::min(l, lanes - 1);
      px[l] = x[s], py[l] = y[s], pz[l] = z[s], ps[l] = sym[s];
      for (int a = 0; a < 13; ++a) buf[a][l] = (*arrays[a])[o0 + static_cast<std::size_t>(s)];
    }
    tangent_steps<T, B>(buf[0], buf[1], buf[2], px, py, pz, ps, buf[3], buf[4], buf[5], buf[6], buf[7], buf[8], buf[9],
                        buf[10], buf[11], buf[12]);
    for (int a = 3; a < 13; ++a)  // the state, not r, alpha, alpha / r
      for (int l = 0; l < lanes; ++l) (*arrays[a])[o0 + static_cast<std::size_t>(l)] = buf[a][l];
  }

  // One step of the cocycle for B orbits; restrict-qualified parameters.
  template <class T, int B>
  static void tangent_steps(const double* __restrict R, const double* __restrict A, const double* __restrict K,
                            const T* __restrict x, const T* __restrict y, const T* __restrict z,
                            const std::uint8_t* __restrict sym, double* __restrict SX, double* __restrict SY,
                            double* __restrict SZ, double* __restrict VX, double* __restrict VY, double* __restrict VZ,
                            double* __restrict PG, double* __restrict EG, double* __restrict EV,
                            double* __restrict N13) {
    // Symbols widened to 64 bits first: a loop mixing 8-bit and 64-bit data gets a vectorisation factor of
    // 64 lanes (one 512-bit byte vector), more than a 32-lane batch, and GCC 12 then does not vectorise it.
    alignas(64) std::int64_t sw[B];
    for (int l = 0; l < B; ++l) sw[l] = sym[l];
    const std::int64_t* symw = sw;
#pragma omp simd
    for (int l = 0; l < B; ++l) {
      const double X = SX[l], Y = SY[l], Z = SZ[l], r = R[l], a = A[l], q = K[l];
      const double ux = VX[l], uy = VY[l], uz = VZ[l];
      const std::int64_t sl = symw[l];
      const bool s1 = sl == 1, s3 = sl == 3;
      // m = M_s s (the kernel's formulas, kernel_impl.hpp), t = M_s v.
      const double c1 = a * Y - X, c3 = a * Y - Z;
      const double mx = s1 ? c1 : (s3 ? r * X : -c1);
      const double my = s1 ? q * c1 - Y + a * Z : (s3 ? q * c3 - Y + a * X : Y - q * (c1 + c3));
      const double mz = s1 ? r * Z : (s3 ? c3 : -c3);
      const double d1 = a * uy - ux, d3 = a * uy - uz;
      double tx = s1 ? d1 : (s3 ? r * ux : -d1);
      double ty = s1 ? q * d1 - uy + a * uz : (s3 ? q * d3 - uy + a * ux : uy - q * (d1 + d3));
      double tz = s1 ? r * uz : (s3 ? d3 : -d3);
      const double mm = mx * mx + my * my + mz * mz, ss = X * X + Y * Y + Z * Z;
      const double f = (mx * tx + my * ty + mz * tz) / mm;
      tx -= f * mx;
      ty -= f * my;
      tz -= f * mz;
      // g^2 = |M u|^2 = |m|^2 / |s|^2, multiplied into the mantissa, its exponent moved to EG (exact).
      const std::uint64_t gb = std::bit_cast<std::uint64_t>(PG[l] * (mm / ss));
      EG[l] += static_cast<double>(static_cast<std::int64_t>(gb >> 52) - 1023);
      PG[l] = std::bit_cast<double>((gb & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
      // v rescaled so that max |component| is in [1, 2) (exact power of two), its exponent moved to EV.
      const double vm = std::max(std::fabs(tx), std::max(std::fabs(ty), std::fabs(tz)));
      const std::uint64_t e = std::bit_cast<std::uint64_t>(vm) >> 52;
      const double sc = std::bit_cast<double>(static_cast<std::uint64_t>(2046 - e) << 52);
      EV[l] += static_cast<double>(static_cast<std::int64_t>(e) - 1023);
      VX[l] = tx * sc;
      VY[l] = ty * sc;
      VZ[l] = tz * sc;
      N13[l] += (s1 || s3) ? 1.0 : 0.0;
      SX[l] = static_cast<double>(x[l]);
      SY[l] = static_cast<double>(y[l]);
      SZ[l] = static_cast<double>(z[l]);
    }
  }
  static constexpr double ln2 = 0.6931471805599453094;
  void store(std::size_t o0, int lanes, int j) {
    for (int l = 0; l < lanes; ++l) {
      const std::size_t o = o0 + static_cast<std::size_t>(l);
      double* c = cum.data() + (o * static_cast<std::size_t>(blocks + 1) + static_cast<std::size_t>(j)) * 3;
      c[0] = 0.5 * std::log(vx[o] * vx[o] + vy[o] * vy[o] + vz[o] * vz[o]) + ev[o] * ln2;
      c[1] = 0.5 * (std::log(pg[o]) + eg[o] * ln2);
      c[2] = n13[o];
    }
  }
  // State at step 0: the kernel's initial vector (normalised, in Q, rounded to T), and the tangent vector
  // e1 = u x axis / |u x axis| with the coordinate axis least aligned with u.
  template <class T> void init(std::size_t o0, int lanes) {
    for (int l = 0; l < lanes; ++l) {
      const std::size_t o = o0 + static_cast<std::size_t>(l);
      const Vec3<double>& u0 = ens->initial[o % n_ic];
      const Vec3<double> qd = core::to_quadrant<double>(u0 / u0.norm());
      const Vec3<double> u(static_cast<double>(static_cast<T>(qd(0))), static_cast<double>(static_cast<T>(qd(1))),
                           static_cast<double>(static_cast<T>(qd(2))));
      const Vec3<double> e1 = iterate::first_tangent(u);
      sx[o] = u(0), sy[o] = u(1), sz[o] = u(2);
      vx[o] = e1(0), vy[o] = e1(1), vz[o] = e1(2);
      pg[o] = 1, eg[o] = 0, ev[o] = 0, n13[o] = 0;
    }
    if (transient == 0) store(o0, lanes, 0);
  }
};

}  // namespace btob::lyapunov
