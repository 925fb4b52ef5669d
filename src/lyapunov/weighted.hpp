// SPDX-License-Identifier: GPL-3.0-or-later
// The weighted Birkhoff averages of one orbit's projective exponents, exact under deferred projection.
//
// The weight exp(-1/(t (1 - t))) (Das, Sander, Yorke 2017; lyapunov.hpp) makes the average of a quasi-periodic
// sequence converge faster than any power of 1/n only if every step carries its own weight: weighting the log-growth
// of a whole Gram-Schmidt interval by the weight at its middle is a step-function weight, and its average converges
// like C len / n again (measured: off by 3e-7 on the weakly contracting sink 312^150 at r = 0.171599 with 4e5 steps,
// intervals of ~200 steps; the QR route, one step per interval, is within 1e-11).  The per-step log-growth is
// recovered from the states between two projections, which advance writes to a trace over the averaged steps:
// with u the point and v the unprojected tangent vector (both stepped by M_s, v orthogonal to u at the interval's
// start), the projective tangent vector after step k is the component of v_k orthogonal to u_k over |u_k|, of length
//   |p_k| / |u_k| = |u_k x v_k| / |u_k|^2,
// so lambda1's per-step log-growth is f_k = (log Z_k - log Z_{k-1}) / 2 with Z = |u x v|^2 / |u|^4, and
// lambda1 + lambda2's is [s_k != 2] log r - 3/2 (log Y_k - log Y_{k-1}) with Y = |u|^2 (the area growth of
// orbit.cpp's gram_schmidt, step by step).  The sums over an interval telescope to gram_schmidt's logs (the same
// states), so the weighted sums see the same exponents, each step with its own weight, as the QR route does.
//
// The cost: per averaged step, 6 stores in advance, then here 2 logs, one exp, a cross product and two norms, in a
// loop over the interval that the compiler vectorises (double: logs and exp written out below, not libm's scalar
// calls; the precisions beyond double use long double and libm, next to steps that cost far more).
#pragma once

#include "lyapunov/orbit.hpp"

#include <cstdint>

namespace btob::lyapunov::detail {

struct WeightedSums {
  long double lambda1 = 0;  // sum over averaged steps of w_k f_k
  long double area = 0;     // sum of w_k times lambda1 + lambda2's per-step log
  long double norm = 0;     // sum of w_k
};

// One interval: the states 0..len in `trace` (0: right after the previous projection), the symbols of its steps at
// ring[(step0 + k) % kSymbolRing], k = 1..len; j0 averaged steps before it, n averaged steps in all (step j's weight
// at t = (j - 1/2) / n, the QR route's).  len <= trace.stride - 1.
template <class W>
void weigh(const Trace<W>& trace, long len, const std::uint8_t* ring, long step0, long j0, long n, long double log_r,
           WeightedSums& sums);

}  // namespace btob::lyapunov::detail
