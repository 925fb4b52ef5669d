// SPDX-License-Identifier: GPL-3.0-or-later
// How a long loop polls the cancellation token of core::RunControl (request.hpp) without slowing down.
//
// A loop that may run for more than ~0.1 s (one orbit's 1e12 steps, a transient, one window's certificate, an
// Arnoldi iteration) polls the token every `cancel_stride` steps: one mask test per step and one relaxed atomic
// load per stride.  The stride is a power of two small enough that the slowest step btob takes (an MPFR step at
// a few hundred digits, well under 0.2 ms) still sees a request within ~0.05 s, and large enough that the load costs
// nothing measurable in the double kernel (the benchmarks' before/after ratio is within their noise).
// Outside an OpenMP region a poll throws core::Cancelled; inside one (no exception may leave it) the loop tests
// `due(...)` and leaves early, and the region's owner throws once it is over (iterate's RunTally::finish).
#pragma once

#include "core/request.hpp"

namespace btob::core {

inline constexpr long cancel_stride = 256;  // steps between two polls; a power of two

// Whether the token asks to stop and `step` is a polling step (every cancel_stride steps).
inline bool cancel_due(const CancelToken* token, long step) {
  return (step & (cancel_stride - 1)) == 0 && token && token->cancelled();
}

// Throws core::Cancelled when the token asks to stop and `step` is a polling step.
inline void poll_cancel(const CancelToken* token, long step) {
  if (cancel_due(token, step)) throw Cancelled();
}

// Throws core::Cancelled when the token asks to stop (a loop whose every iteration is long: a window, an item).
inline void check_cancel(const CancelToken* token) {
  if (token && token->cancelled()) throw Cancelled();
}

}  // namespace btob::core
