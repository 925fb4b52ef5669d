// SPDX-License-Identifier: GPL-3.0-or-later
// The cost of an indivisible or expensive-per-item computation predicted from small instances of it: a word's
// analysis by word length, the thresholds by digits, a window's certified bound by n.  A dry run of such a request
// must not run the request (windows bounds --n 2000 --certify took 235 s to "estimate" by computing its largest n),
// so it times instances of sizes smallest, 2 smallest, 4 smallest, ... while the next one, predicted from the last
// two, fits in a budget of about a second, and fits seconds = c size^b through the largest two timed (the local
// exponent: costs such as n^2.4 for a window bound have lower-order terms that a fit over all sizes would weigh
// too much).  Between timed sizes the cost is interpolated the same way (a power law per segment); beyond the
// largest it is extrapolated with the last exponent, and the estimate says so ("extrapolated from sizes a..b").
#pragma once

#include "core/cancel.hpp"
#include "core/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace btob::core {

struct SizeFit {
  std::string parameter;               // what the size counts ("n", "word length", "digits")
  std::vector<double> sizes, seconds;  // the instances timed, in increasing size
  double exponent = 1;                 // b of the last segment (seconds ~ size^b)
  double spent = 0;                    // wall seconds of the timing
  // The predicted seconds of an instance of size s (the timed ones as measured).
  double at(double s) const {
    if (sizes.empty()) return 0;
    if (sizes.size() == 1 || s >= sizes.back()) return seconds.back() * std::pow(s / sizes.back(), exponent);
    std::size_t k = 1;
    while (k + 1 < sizes.size() && sizes[k] < s) ++k;
    const double b = segment(k);
    return seconds[k] * std::pow(s / sizes[k], b);
  }
  bool extrapolates(double s) const { return !sizes.empty() && s > sizes.back(); }
  // "extrapolated from sizes a..b (n^2.41)" when s lies beyond the timed sizes, else "measured at sizes a..b".
  std::string note(double s) const {
    if (sizes.empty()) return "no instance timed";
    return fmt::format("{} from sizes {:.0f}..{:.0f} of {} (seconds ~ ({})^{:.2f}, {} instances timed in {:.2f} s)",
                       extrapolates(s) ? "extrapolated" : "interpolated", sizes.front(), sizes.back(), parameter,
                       parameter, exponent, sizes.size(), spent);
  }

  // The exponent between timed sizes k-1 and k: times below 2 ms are too coarse for a slope, so a segment that
  // ends there takes the exponent of the whole fit.
  double segment(std::size_t k) const {
    if (k == 0 || seconds[k - 1] < 2e-3 || seconds[k] < 2e-3 || sizes[k] <= sizes[k - 1]) return exponent;
    return std::clamp(std::log(seconds[k] / seconds[k - 1]) / std::log(sizes[k] / sizes[k - 1]), 0.0, 4.0);
  }
};

// Times `run(size)` (an instance of that size; its wall time is measured here) at sizes smallest, 2 smallest, ...
// (integers, the last at most `largest`) while the next instance, predicted with the last exponent (3 until two
// sizes were timed above 2 ms: cautious), keeps the total within `budget` seconds and itself takes at most half of
// it.  The exponent is the last segment's, clamped to [0, 4].  Cancellation is checked between instances.
inline SizeFit fit_sizes(const std::string& parameter, double smallest, double largest,
                         const std::function<void(double)>& run, const CancelToken* cancel = nullptr,
                         double budget = 1.2) {
  SizeFit f;
  f.parameter = parameter;
  const auto t0 = std::chrono::steady_clock::now();
  double s = std::max(1.0, std::floor(std::min(smallest, largest)));
  double b = 3;
  for (;;) {
    check_cancel(cancel);
    const auto t = std::chrono::steady_clock::now();
    run(s);
    const double dt = seconds_since(t);
    f.sizes.push_back(s);
    f.seconds.push_back(dt);
    const std::size_t k = f.sizes.size() - 1;
    if (k > 0 && f.seconds[k - 1] >= 2e-3 && dt >= 2e-3) b = f.segment(k);  // exponent still holds 3 before
    f.exponent = b;
    f.spent = seconds_since(t0);
    if (s >= largest) break;
    const double next = std::min(2 * s, std::floor(largest));
    const double predicted = dt * std::pow(next / s, b);
    if (f.spent + predicted > budget || predicted > budget / 2) break;
    s = next;
  }
  if (f.sizes.size() >= 2 && f.seconds.back() >= 2e-3 && f.seconds[f.seconds.size() - 2] >= 2e-3)
    f.exponent = f.segment(f.sizes.size() - 1);
  return f;
}

}  // namespace btob::core
