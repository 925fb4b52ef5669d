// The cost of a sweep (core/sweep.hpp) predicted from a sample of its own items: the command line's `--dry-run` and
// Python's btob.estimate().
//
// The program calibrates on the request itself rather than on a table of rates: it runs run_part on a few items
// spread evenly over 0..n-1 (items i*n/m, so costs that grow along the sweep, as a window's with n, are sampled
// across their range), doubling m until the sample took ~0.2 s, and scales: time = sample seconds / m x n / ranks.
// The packed size of the sample's parts, scaled the same way, is what rank 0 gathers and keeps; the result files
// are about that size, and rank 0 holds about twice it while merging.  Nothing is written.
#pragma once

#include "core/pack.hpp"
#include "core/request.hpp"
#include "core/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace btob::core {

struct SweepEstimate {
  std::size_t items = 0, sampled = 0;
  double sample_seconds = 0;     // the sample's wall time
  double predicted_seconds = 0;  // the whole request on `ranks` processes of the sample's threads
  double bytes = 0;              // the parts' packed bytes, scaled to every item
  int ranks = 1;
  std::string text(const std::string& command, int threads) const {
    return fmt::format(
        "btob {}: dry run (a sample computed, nothing written)\n"
        "  work: {} items (the sweep's r values, grid rows, n values or words)\n"
        "  sample: {} items in {:.3f} s on {} threads ({:.3g} s per item)\n"
        "  predicted: {:.3g} s on {} process{} x {} threads\n"
        "  data: about {:.3g} MB gathered and written; peak memory about {:.3g} MB on rank 0 (parts and merge)\n",
        command, items, sampled, sample_seconds, threads, sample_seconds / static_cast<double>(sampled),
        predicted_seconds, ranks, ranks == 1 ? "" : "es", threads, bytes / 1e6, 2 * bytes / 1e6);
  }
};

// The sample: m items spread over 0..n-1, m doubled (from `start`, the threads: every thread gets an item) until it
// took `target` seconds or covers n.  `ranks`: the processes the prediction divides the work over.
template <core::Sweep Req>
SweepEstimate estimate_sweep(const Req& req, const core::RunControl& control, int ranks, std::size_t start,
                             double target = 0.2) {
  SweepEstimate e;
  e.items = req.work_items();
  e.ranks = ranks;
  for (std::size_t m = std::min(std::max<std::size_t>(start, 1), e.items); m > 0; m = std::min(2 * m, e.items)) {
    std::vector<std::size_t> items;
    for (std::size_t k = 0; k < m; ++k) items.push_back(k * e.items / m);
    const auto t0 = std::chrono::steady_clock::now();
    const auto part = run_part(req, items, control);
    e.sample_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.sampled = m;
    e.bytes = static_cast<double>(core::pack(part).size()) * static_cast<double>(e.items) / static_cast<double>(m);
    if (e.sample_seconds >= target || m == e.items) break;
  }
  e.predicted_seconds = e.sample_seconds / static_cast<double>(e.sampled) * static_cast<double>(e.items) / ranks;
  return e;
}

}  // namespace btob::core
