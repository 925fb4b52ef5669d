// SPDX-License-Identifier: GPL-3.0-or-later
// Overlays of the windows on bifurcation diagrams (windows/overlays.hpp).
#include "windows/overlays.hpp"

#include "core/cancel.hpp"

#include "windows/direct.hpp"
#include "windows/windows.hpp"

#include <cmath>
#include <map>
#include <mutex>

namespace btob::windows {

namespace {
constexpr int kOverlayPolynomialMaxN = 150;
constexpr int kOverlayMaxN = 400;

// n -> (lower bound, r_crit,2 or NaN) in double, computed once.
std::pair<double, double> bounds_in_double(int n) {
  static std::mutex mu;
  static std::map<int, std::pair<double, double>> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const double lo = n <= kOverlayPolynomialMaxN
                        ? static_cast<double>(window_lower_bound(n, 20))
                        : static_cast<double>(window_lower_bound_in<long double>(n, Route::matrix));
  const double up = n >= 2 ? static_cast<double>(r_crit2(n, 20)) : std::nan("");
  return cache[n] = {lo, up};
}
}  // namespace

std::vector<std::pair<double, int>> window_overlay(double r_min, double r_max, const core::CancelToken* cancel) {
  std::vector<std::pair<double, int>> out;
  for (int n = 1; n <= kOverlayMaxN; ++n) {
    core::check_cancel(cancel);
    const double up_closed = n >= 2 ? static_cast<double>(r_crit2(n, 20)) : 1.0;
    if (up_closed < r_min) break;
    if (n >= 2 && up_closed >= r_min && up_closed <= r_max) out.push_back({up_closed, 0});  // red: r_crit,2(n)
    // lower(n) > 7 - 4 sqrt 3; skip the root finding when the whole window is above the range.
    if (n >= 2 && bounds_in_double(n).first > r_max) continue;
    const double lo = bounds_in_double(n).first;
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
