// SPDX-License-Identifier: GPL-3.0-or-later
// Overlays of the windows on bifurcation diagrams (windows/overlays.hpp).
#include "windows/overlays.hpp"

#include "core/cancel.hpp"
#include "iterate/parallel.hpp"

#include "windows/direct.hpp"
#include "windows/windows.hpp"

#include <atomic>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>

namespace btob::windows {

namespace {
constexpr int kOverlayPolynomialMaxN = 150;
constexpr int kOverlayMaxN = 400;

std::mutex cache_mu;
std::map<int, std::pair<double, double>> cache;  // n -> (lower bound, r_crit,2 or NaN) in double
// Held while bounds are computed: two callers at once (the explorer's server threads) would each set MPFR's
// process-wide precision for their own n (core::MpfrDigits), so computations take turns; the cache is read freely.
std::mutex compute_mu;

// Lower bounds: n <= 150 by the polynomial route (window_lower_bound, MPFR), n > 150 by the matrix route in long
// double; r_crit,2(n) in MPFR.
double lower_in_double(int n) {
  return n <= kOverlayPolynomialMaxN ? static_cast<double>(window_lower_bound(n, 20))
                                     : static_cast<double>(window_lower_bound_in<long double>(n, Route::matrix));
}
double upper_in_double(int n) { return n >= 2 ? static_cast<double>(r_crit2(n, 20)) : std::nan(""); }

// The bounds of the n of `ns` that no earlier call computed (or remembered).  Only the long-double route (n > 150,
// about a third of the cost at r_min = 0.0717) runs over `threads` threads: everything in MPFR stays on the calling
// thread, because Boost 1.74's MPFR default precision, which core::MpfrDigits sets, is one per process, not per thread
// (two threads raising it for different n make each other's root finding unreliable: seen as "no reliable root of
// Q_150").
void compute_missing(const std::vector<int>& ns, const core::CancelToken* cancel, int threads) {
  std::lock_guard<std::mutex> computing(compute_mu);
  std::vector<int> missing;
  {
    std::lock_guard<std::mutex> lock(cache_mu);
    for (int n : ns)
      if (!cache.count(n)) missing.push_back(n);
  }
  std::vector<std::pair<double, double>> got(missing.size());
  std::vector<std::size_t> matrix;  // positions in `missing` of the n for the threads
  for (std::size_t i = 0; i < missing.size(); ++i) {
    core::check_cancel(cancel);
    got[i].second = upper_in_double(missing[i]);
    if (missing[i] <= kOverlayPolynomialMaxN) got[i].first = lower_in_double(missing[i]);
    else matrix.push_back(i);
  }
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex error_mu;
  iterate::parallel_for(matrix.size(), threads, 1, [&](std::size_t k) {  // round robin: the cost grows with n
    if (stop.load(std::memory_order_relaxed)) return;
    if (cancel && cancel->cancelled()) {
      stop = true;
      return;
    }
    try {
      got[matrix[k]].first = lower_in_double(missing[matrix[k]]);
    } catch (...) {  // no exception may leave the loop (iterate::parallel_for): kept, rethrown after it
      std::lock_guard<std::mutex> lock(error_mu);
      if (!error) error = std::current_exception();
      stop = true;
    }
  });
  if (error) std::rethrow_exception(error);
  core::check_cancel(cancel);
  std::lock_guard<std::mutex> lock(cache_mu);
  for (std::size_t i = 0; i < missing.size(); ++i) cache[missing[i]] = got[i];
}

// n -> (lower bound, r_crit,2 or NaN) in double, of an n that compute_missing has put in the cache.
std::pair<double, double> cached(int n) {
  std::lock_guard<std::mutex> lock(cache_mu);
  return cache.at(n);
}
}  // namespace

int window_overlay_last_n(double r_min) {
  // r_crit,2(n) decreases with n: one cos and one sqrt at 30 digits per n
  int last = 1;
  while (last < kOverlayMaxN && static_cast<double>(r_crit2(last + 1, 20)) >= r_min) ++last;
  return last;
}

std::vector<std::pair<double, double>> window_overlay_bounds(const std::vector<int>& ns,
                                                             const core::CancelToken* cancel, int threads) {
  for (int n : ns)
    if (n < 1 || n > kOverlayMaxN) throw std::logic_error("window_overlay_bounds: n outside 1..400");
  compute_missing(ns, cancel, threads);
  std::vector<std::pair<double, double>> out;
  for (int n : ns) out.push_back(cached(n));
  return out;
}

void remember_window_overlay_bounds(int n, std::pair<double, double> bounds) {
  std::lock_guard<std::mutex> lock(cache_mu);
  cache.emplace(n, bounds);
}

std::vector<std::pair<double, int>> window_overlay(double r_min, double r_max, const core::CancelToken* cancel,
                                                   int threads) {
  // The n the range needs, 1..last; their lower bounds are the cost, computed first (in part over the threads).
  const int last = window_overlay_last_n(r_min);
  std::vector<int> ns(static_cast<std::size_t>(last));
  for (int n = 1; n <= last; ++n) ns[static_cast<std::size_t>(n - 1)] = n;
  compute_missing(ns, cancel, threads);
  std::vector<std::pair<double, int>> out;
  for (int n = 1; n <= last; ++n) {
    const auto [lo, up] = cached(n);
    if (n >= 2 && up <= r_max) out.push_back({up, 0});       // red: r_crit,2(n) (>= r_min for every n <= last)
    if (lo >= r_min && lo <= r_max) out.push_back({lo, 1});  // blue: lower bound
  }
  return out;
}

std::vector<std::pair<double, int>> stripes_overlay(double r_min, double r_max) {
  static const std::vector<std::pair<double, int>> all = [] {
    std::vector<std::pair<double, int>> v;
    for (const auto& s : thin_stripes(120, 20)) v.push_back({static_cast<double>(s.value), 1});  // Figure 6.8: m <= 120
    return v;
  }();
  std::vector<std::pair<double, int>> out;
  for (const auto& p : all)
    if (p.first >= r_min && p.first <= r_max) out.push_back(p);
  return out;
}

}  // namespace btob::windows
