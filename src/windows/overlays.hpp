// SPDX-License-Identifier: GPL-3.0-or-later
// The windows' r values drawn on bifurcation diagrams: window lower bounds and r_crit,2(n), and thin stripes.
#pragma once

#include "core/request.hpp"

#include <utility>
#include <vector>

namespace btob::windows {

// Every lower bound (colour 1, blue) and r_crit,2(n) (colour 0, red) in [r_min, r_max], n = 1..400, as
// (r, colour) pairs.  Both decrease with n towards 7 - 4 sqrt 3 and lower(n) < r_crit,2(n), so the scan stops at
// the first n with r_crit,2(n) < r_min (windows beyond n = 400 are 1e-9 wide, below any plot's resolution).
// Lower bounds: n <= 150 from the 20-decimal root of Q_n (the certified route); n > 150 from the matrix route in
// long double, which the precision study (results/windows/precision.csv) shows correct to ~20 decimals for every
// n <= 150, while the polynomial route for n = 150..400 costs ~20 s in all.  Computed once per n (thread-safe).
// `cancel` is polled before every n (core::Cancelled): the first use over the whole r range takes ~0.75 s on one
// thread; the long-double route's third of it is spread over `threads` (0 = all cores; each n independent, so the
// result does not depend on them).  Not to be called from two threads at once with other MPFR work (core::MpfrDigits).
std::vector<std::pair<double, int>> window_overlay(double r_min, double r_max,
                                                   const core::CancelToken* cancel = nullptr, int threads = 1);

// The n whose bounds window_overlay(r_min, ...) reads: 1..the returned n (the largest n <= 400 with
// r_crit,2(n) >= r_min).
int window_overlay_last_n(double r_min);
// The (lower bound, r_crit,2 or NaN) in double of each n of `ns` (1..400) as window_overlay computes them, kept for
// the process's later calls; and such bounds computed by another process of the same program (an MPI rank's share,
// commands::compute) remembered as if computed here.
std::vector<std::pair<double, double>> window_overlay_bounds(const std::vector<int>& ns,
                                                             const core::CancelToken* cancel = nullptr,
                                                             int threads = 1);
void remember_window_overlay_bounds(int n, std::pair<double, double> bounds);

// The thin stripes r(l/m) of eq. (6.3) with m <= 120 (Figure 6.8) in [r_min, r_max], colour 1.
std::vector<std::pair<double, int>> stripes_overlay(double r_min, double r_max);

}  // namespace btob::windows
