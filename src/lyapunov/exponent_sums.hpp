// SPDX-License-Identifier: GPL-3.0-or-later
// ExponentSums: the cocycle recorder of Lyapunov maps (iterate/cocycle.hpp): at the end of the transient and at every
// block end, per orbit, the cumulative sums from which lyapunov::exponents_from computes the projective exponents.
#pragma once

#include "iterate/cocycle.hpp"
#include "iterate/ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace btob::lyapunov {

// Per orbit and checkpoint j (0: end of the transient; j >= 1: end of block j), cum[(o (blocks + 1) + j) 3 + q]:
//   q = 0: L1   = log |w_k|   (w the projected tangent vector, true length: |w| 2^log2v)
//   q = 1: logG = log |u_k|   (u the point under the linear cocycle M_s = P_s / r; = sum_k log |M u_k| for unit u_k)
//   q = 2: n13  = steps with symbol 1 or 3
// so that, over the averaged steps, lambda1 = (dL1 - dlogG) / n and lambda1 + lambda2 = (dn13 log r - 3 dlogG) / n
// (det D = det M_s / |M u|^3; maps.cpp).  The same three sums as the TangentRecorder's, from the fused kernel.
struct ExponentSums {
  const iterate::Ensemble* ens;
  long transient, n;
  int blocks;
  std::vector<long> block_end;  // averaged-step counts ending each block: n j / blocks, j = 1..blocks
  std::vector<long> steps;      // the checkpoints: transient, transient + block_end[j]
  std::vector<double> cum;

  ExponentSums(const iterate::Ensemble& e, long transient_, long iterations_, int blocks_)
      : ens(&e), transient(transient_), n(iterations_), blocks(blocks_) {
    iterate::checked_bytes(e.orbits(), sizeof(double) * 3 * static_cast<std::size_t>(blocks + 1), "exponent sums");
    steps.push_back(transient);
    for (int j = 1; j <= blocks; ++j) {
      block_end.push_back(n * j / blocks);
      steps.push_back(transient + block_end.back());
    }
    cum.assign(e.orbits() * static_cast<std::size_t>(blocks + 1) * 3, 0.0);
  }
  const std::vector<long>& checkpoints() const { return steps; }
  long total_steps() const { return transient + n; }

  template <class T> void record(const iterate::CocycleBatch<T>& b) {
    constexpr double ln2 = 0.6931471805599453094;
    const std::size_t j =
        static_cast<std::size_t>(std::lower_bound(steps.begin(), steps.end(), b.step) - steps.begin());
    for (int l = 0; l < b.lanes; ++l) {
      const std::size_t o = b.orbit0 + static_cast<std::size_t>(l);
      double* c = cum.data() + (o * static_cast<std::size_t>(blocks + 1) + j) * 3;
      const double wx = b.vx[l], wy = b.vy[l], wz = b.vz[l], x = b.x[l], y = b.y[l], z = b.z[l];
      c[0] = 0.5 * std::log(wx * wx + wy * wy + wz * wz) + b.log2v[l] * ln2;
      c[1] = 0.5 * std::log(x * x + y * y + z * z) + b.log2u[l] * ln2;
      c[2] = b.n13[l];
    }
  }
};

}  // namespace btob::lyapunov
