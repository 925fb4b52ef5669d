// SPDX-License-Identifier: GPL-3.0-or-later
// The SIMD geometry of the batched kernel: vector width and lanes per batch (kernel units only).
#pragma once

#include <type_traits>

namespace btob::iterate::detail {

// The vector width follows the instruction set the kernel unit is compiled for (BTOB_KERNEL_ARCH):
// 64 bytes with AVX-512, 32 with AVX, 16 (SSE2, every x86-64) otherwise.  Wider GCC vectors would also
// be correct on narrow targets, but their lowering there is slow (28x on SSE2, measured).
#if defined(__AVX512F__)
inline constexpr int kVectorBytes = 64;
#elif defined(__AVX__)
inline constexpr int kVectorBytes = 32;
#else
inline constexpr int kVectorBytes = 16;
#endif
// Lanes per batch: 6 vectors in flight.  One step's dependency chain is ~18 cycles and its issue cost ~3-5 per
// vector, so 6 independent vectors hide the latency; 8 would need more live state and parameters (36 vectors) than
// the 32 zmm registers hold.  (CHANGELOG.md keeps the measurements behind the choice.)
inline constexpr int kVectorsInFlight = 6;
template <class T> constexpr int batch_lanes() {
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>)
    return kVectorsInFlight * kVectorBytes / static_cast<int>(sizeof(T));
  else return 8;
}

}  // namespace btob::iterate::detail
