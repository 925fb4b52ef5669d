// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit instantiations of the periodic-orbit analysis and its scans (float, double, long double, float128, MPFR);
// the scan grid.
#include "patterns/scan_impl.hpp"

#include "core/scalar.hpp"

namespace btob::patterns {

std::vector<double> default_grid() {
  // Windows of (ab)^n(cb)^n shrink like n^-3 near 7 - 4 sqrt(3) (Table B.1: width 5.8e-4 at n = 6,
  // 3.6e-4 at n = 7): step 4.75e-5 on [0.07, 0.26) resolves them up to n ~ 10; coarser elsewhere.
  std::vector<double> g;
  const auto add = [&](double a, double b, int n) {
    for (int i = 0; i < n; ++i) g.push_back(a + (b - a) * (i + 0.5) / n);
  };
  add(0.0, 0.07, 1000);
  add(0.07, 0.26, 4000);
  add(0.26, 1.0, 2500);
  return g;
}

namespace {
thread_local std::uint64_t orbit_steps = 0;  // walk_steps.hpp
}  // namespace
std::uint64_t orbit_walk_steps() { return orbit_steps; }
void add_orbit_walk_steps(std::uint64_t steps) { orbit_steps += steps; }

std::string classification_name(const Classification& c) {
  if (c.outcome == Outcome::none || c.collapse) return outcome_name(c.outcome);
  return std::string(outcome_name(c.outcome)) + " (no collapse)";
}

#define BTOB_PATTERNS_INSTANTIATE(T)                                                                              \
  template Verdict<T> analyse<T>(const Word&, const T&, const core::CancelToken*);                                \
  template bool is_stable<T>(const Word&, const T&, const core::CancelToken*);                                    \
  template std::vector<Interval<T>> stability_set<T>(const Word&, const std::vector<double>&, const T&,           \
                                                     const core::CancelToken*);                                   \
  template T quantity<T>(const Word&, const T&, Track, Quantity, const core::CancelToken*);                       \
  template Classification classify<T>(const Word&, const T&, const core::CancelToken*);                           \
  template std::vector<FeasibleInterval<T>> feasibility_set<T>(const Word&, const std::vector<double>&, const T&, \
                                                               const core::CancelToken*);                         \
  template T quantity_root<T>(const Word&, T, T, Track, Quantity, const T&, const core::CancelToken*);

BTOB_PATTERNS_INSTANTIATE(float)
BTOB_PATTERNS_INSTANTIATE(double)
BTOB_PATTERNS_INSTANTIATE(long double)
BTOB_PATTERNS_INSTANTIATE(core::float128)
BTOB_PATTERNS_INSTANTIATE(core::mpfr_float)

}  // namespace btob::patterns
