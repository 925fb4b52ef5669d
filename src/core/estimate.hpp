// SPDX-License-Identifier: GPL-3.0-or-later
// The cost of a sweep (core/sweep.hpp) predicted from a sample of its own items: the command line's `--dry-run` and
// Python's btob.estimate().
//
// The program calibrates on the request itself rather than on a table of rates: it runs run_part on items spread
// evenly over 0..n-1 (items i*n/m, so costs that grow along the sweep, as a window's with n, are sampled across
// their range), doubling m until the sample took 0.2 s and holds at least 32 items, or took 1 s, and scales: time =
// sample seconds / m x n / ranks.  The item count matters as much as the time: items differ in cost (a basin
// image's rows cross different basins), and a sample of two or four items, which 0.2 s alone buys where an item
// takes ~0.1 s (the sanitizer build), predicted a basin image 2-4 times too long on a loaded machine; sixteen
// 0.09 s rows of the same image predicted it within 12%.  The 1 s cap bounds the sample (and the note before a long
// StepCounted sweep) where items are slow: the doubling then costs at most about 2 s.
// The packed size of the sample's parts, scaled the same way, is what rank 0 gathers and keeps; the result files
// are about that size, and rank 0 holds about twice it while merging.  Nothing is written.
//
// A sweep whose items' cost grows steeply with a size (windows bounds: n, about n^2.4) is a core::SizedSweep: its
// sample would compute its largest items (windows bounds --n 1..2000 --certify ran 235 s to "estimate" itself), so
// its estimate times one-item requests of small sizes instead and extrapolates (core/size_model.hpp), and says so.
#pragma once

#include "core/pack.hpp"
#include "core/request.hpp"
#include "core/run.hpp"
#include "core/size_model.hpp"
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
  std::string model;  // a SizedSweep's: how the prediction was fitted ("extrapolated from sizes 8..128 of n ...")
  // dry: --dry-run's report; else the note before a long run (the same numbers, on stderr).
  std::string text(const std::string& command, int threads, bool dry = true) const {
    if (!model.empty())
      return fmt::format(
          "btob {}: {}\n"
          "  work: {} items (the sweep's n values or words)\n"
          "  sample: {} one-item requests of small sizes in {:.3f} s (never the request's own items)\n"
          "  model: {}\n"
          "  predicted: {:.3g} s on {} process{} x {} threads\n"
          "  data: about {:.3g} MB gathered and written; peak memory about {:.3g} MB on rank 0 (parts and merge)\n",
          command,
          dry ? "dry run (a cost model fitted on small instances, nothing written)" : "estimate before the run", items,
          sampled, sample_seconds, model, predicted_seconds, ranks, ranks == 1 ? "" : "es", threads, bytes / 1e6,
          2 * bytes / 1e6);
    return fmt::format(
        "btob {}: {}\n"
        "  work: {} items (the sweep's r values, grid rows, n values or words)\n"
        "  sample: {} items in {:.3f} s on {} threads ({:.3g} s per item)\n"
        "  predicted: {:.3g} s on {} process{} x {} threads\n"
        "  data: about {:.3g} MB gathered and written; peak memory about {:.3g} MB on rank 0 (parts and merge)\n",
        command,
        dry ? "dry run (a sample computed, nothing written)" : "estimate before the run (a sample of its items)", items,
        sampled, sample_seconds, threads, sampled ? sample_seconds / static_cast<double>(sampled) : 0.0,
        predicted_seconds, ranks, ranks == 1 ? "" : "es", threads, bytes / 1e6, 2 * bytes / 1e6);
  }
};

// A sweep with a cost model in a size: item i has size item_size(i), and sized(s) is the same request for one item
// of size s (a one-item range).
template <class Req>
concept SizedSweep = Sweep<Req> && requires(const Req& r, std::size_t i, double s) {
  { r.item_size(i) } -> std::convertible_to<double>;
  { r.sized(s) } -> std::convertible_to<Req>;
  { Req::size_parameter } -> std::convertible_to<std::string>;
};

// A SizedSweep's estimate: fit_sizes on one-item requests from size 8 (or the smallest item's, when smaller) up to
// the largest item's, the predicted seconds summed over every item's size, on `ranks` processes (the items of a
// rank run one after another).  The data: the last instance's packed part times the items.
template <SizedSweep Req> SweepEstimate estimate_sized(const Req& req, const core::RunControl& control, int ranks) {
  SweepEstimate e;
  e.items = core::work_items(req, control.cancel);
  e.ranks = ranks;
  if (e.items == 0) return e;
  double smallest = req.item_size(0), largest = smallest;
  for (std::size_t i = 0; i < e.items; ++i) {
    smallest = std::min(smallest, req.item_size(i));
    largest = std::max(largest, req.item_size(i));
  }
  double part_bytes = 0;
  const SizeFit f = fit_sizes(
      Req::size_parameter, std::min(smallest, 8.0), largest,
      [&](double s) { part_bytes = static_cast<double>(core::pack(run_part(req.sized(s), {0}, control)).size()); },
      control.cancel);
  double total = 0;
  for (std::size_t i = 0; i < e.items; ++i) total += f.at(req.item_size(i));
  e.sampled = f.sizes.size();
  e.sample_seconds = f.spent;
  e.predicted_seconds = total / ranks;
  e.bytes = part_bytes * static_cast<double>(e.items);
  e.model = f.note(largest);
  return e;
}

// The sample: m items spread over 0..n-1, m doubled (from `start`, the threads: every thread gets an item) until it
// took `target` seconds with at least `min_items` items, or took `cap` seconds, or covers n.  `ranks`: the
// processes the prediction divides the work over.
template <core::Sweep Req>
SweepEstimate estimate_sweep(const Req& req, const core::RunControl& control, int ranks, std::size_t start,
                             double target = 0.2, std::size_t min_items = 32, double cap = 1.0) {
  if constexpr (SizedSweep<Req>) return estimate_sized(req, control, ranks);
  SweepEstimate e;
  e.items = core::work_items(req, control.cancel);  // polled: the atlas enumerates its words
  e.ranks = ranks;
  for (std::size_t m = std::min(std::max<std::size_t>(start, 1), e.items); m > 0; m = std::min(2 * m, e.items)) {
    std::vector<std::size_t> items;
    for (std::size_t k = 0; k < m; ++k) items.push_back(k * e.items / m);
    const auto t0 = std::chrono::steady_clock::now();
    const auto part = run_part(req, items, control);
    e.sample_seconds = seconds_since(t0);
    e.sampled = m;
    e.bytes = static_cast<double>(core::pack(part).size()) * static_cast<double>(e.items) / static_cast<double>(m);
    if (m == e.items || e.sample_seconds >= cap || (e.sample_seconds >= target && m >= min_items)) break;
  }
  if (e.sampled == 0) return e;  // no items (a validated request has some): nothing to time, and no 0 / 0
  e.predicted_seconds = e.sample_seconds / static_cast<double>(e.sampled) * static_cast<double>(e.items) / ranks;
  return e;
}

// A sweep that counts its map steps from its fields (`double map_steps() const`, and its precision in
// `precision`) gets its estimate before the run when it may exceed 10 minutes: the sample above runs only when the
// count alone takes over a minute at the fastest kernel rate of its precision (faster than any measured route:
// double's batched kernel makes ~6e8 steps/s per core, long double ~1e8, float128 and MPFR < 1e7), so a short
// run pays nothing and a long one the sample's 0.2-2 s.
template <class Req>
concept StepCounted = Sweep<Req> && requires(const Req& r) {
  { r.map_steps() } -> std::convertible_to<double>;
  { r.precision } -> std::convertible_to<std::string>;
};
inline double fastest_steps_per_second(const std::string& precision) {
  if (precision == "float" || precision == "double") return 1e9;
  if (precision == "long-double") return 2e8;
  return 2e7;
}

}  // namespace btob::core
