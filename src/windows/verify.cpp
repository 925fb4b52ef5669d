// SPDX-License-Identifier: GPL-3.0-or-later
// The iterator's check of the windows of stability.
#include "windows/verify.hpp"

#include "core/request.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "windows/windows.hpp"

#include <algorithm>
#include <stdexcept>

namespace btob::windows {

bool on_pattern(const std::uint8_t* s, long len, int n) {
  const int p = 2 * n;
  if (len < 2 * p) return false;
  for (long k = 0; k + p < len; ++k)
    if (s[k] != s[k + p]) return false;
  int ones = 0, threes = 0, changes = 0;
  for (int k = 0; k < p; ++k) {
    ones += s[k] == 1;
    threes += s[k] == 3;
    changes += s[k] != s[(k + 1) % p];
  }
  return ones == n && threes == n && changes == 2;
}

std::vector<VerifyRow> verify_windows(int first, int last, const VerifyOptions& opt) {
  validate_n(first, 2, "n");  // n = 1 (abcb) is never stable and has no r_crit,2
  validate_n(last, first, "n");
  if (opt.base_iterations < 100)
    throw core::InvalidField("iterations", std::to_string(opt.base_iterations), "at least 100");
  if (opt.per_n < 0) throw core::InvalidField("per-n", std::to_string(opt.per_n), "at least 0");
  if (opt.tail < 1 || opt.tail >= opt.base_iterations)
    throw core::InvalidField("tail", std::to_string(opt.tail),
                             "1..iterations-1 = " + std::to_string(opt.base_iterations - 1));
  const std::vector<core::Vec3<double>> grid = iterate::paper_grid();
  const char* names[4] = {"below", "inside_25", "inside_50", "inside_75"};
  std::vector<VerifyRow> rows;
  for (int n = first; n <= last; ++n) {
    const double lo = static_cast<double>(window_lower_bound(n, 20));
    const double up = static_cast<double>(r_crit2(n, 20));
    const double w = up - lo;
    iterate::Ensemble ens;
    ens.r = {lo - 0.05 * w, lo + 0.25 * w, lo + 0.5 * w, lo + 0.75 * w};
    ens.initial = grid;
    ens.grid_description = "paper";
    const long iterations = opt.base_iterations + opt.per_n * n;
    const long tail = std::max<long>(opt.tail, 4L * n);
    iterate::SymbolRecorder rec(ens.orbits(), iterations - tail + 1, iterations);
    iterate::RunOptions ro;
    ro.threads = opt.threads;
    ro.cancel = opt.cancel;
    if (opt.long_double) iterate::run<long double>(ens, iterations, rec, ro);
    else iterate::run<double>(ens, iterations, rec, ro);
    for (std::size_t j = 0; j < 4; ++j) {
      VerifyRow row;
      row.n = n;
      row.position = names[j];
      row.r = ens.r[j];
      row.lower = lo;
      row.upper = up;
      row.iterations = iterations;
      row.orbits = static_cast<long>(grid.size());
      row.expected_on = j > 0;
      for (std::size_t i = 0; i < grid.size(); ++i)
        row.on_pattern +=
            on_pattern(&rec.out[(j * grid.size() + i) * static_cast<std::size_t>(rec.count)], rec.count, n);
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace btob::windows
