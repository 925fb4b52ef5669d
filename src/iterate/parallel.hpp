// SPDX-License-Identifier: GPL-3.0-or-later
// The OpenMP driver of the analyses' own loops over independent items (r values, words, lags): one parallel loop,
// a static schedule, each item writing only its own output slice, so that the result does not depend on the
// thread count.  Besides the batched and cocycle kernels (kernel_impl.hpp, cocycle_impl.hpp) this is where the
// analyses' parallel loops live; a module calls it instead of opening a parallel region of its own.
#pragma once

#include "core/run.hpp"

#include <omp.h>

#include <cstddef>

namespace btob::iterate {

// Calls body(i) for i = 0..n-1 on `threads` threads (0 = all cores), items dealt statically in blocks of `chunk`
// consecutive items (0: one contiguous block per thread, OpenMP's schedule(static); 1: round robin, for items whose
// cost grows with their index).  No exception may leave body: a cancelled body returns early and the caller throws
// after the loop.
template <class Body> void parallel_for(std::size_t n, int threads, std::size_t chunk, Body&& body) {
  const int nt = core::thread_count(threads);
  if (chunk == 0) {
#pragma omp parallel for schedule(static) num_threads(nt)
    for (std::size_t i = 0; i < n; ++i) body(i);
  } else {
#pragma omp parallel for schedule(static, chunk) num_threads(nt)
    for (std::size_t i = 0; i < n; ++i) body(i);
  }
}
template <class Body> void parallel_for(std::size_t n, int threads, Body&& body) {
  parallel_for(n, threads, 0, static_cast<Body&&>(body));
}

// The same with per-thread scratch: each thread makes its own (make()) once and passes it to body(scratch, i), items
// dealt as by schedule(static).
template <class Make, class Body> void parallel_for_scratch(std::size_t n, int threads, Make&& make, Body&& body) {
  const int nt = core::thread_count(threads);
#pragma omp parallel num_threads(nt)
  {
    auto scratch = make();
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) body(scratch, i);
  }
}

}  // namespace btob::iterate
