// SPDX-License-Identifier: GPL-3.0-or-later
// The thread count and the clock of core/run.hpp.
#include "core/run.hpp"

#include <omp.h>

namespace btob::core {

int thread_count(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace btob::core
