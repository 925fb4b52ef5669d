// SPDX-License-Identifier: GPL-3.0-or-later
// The leaves request's validation, its grid and its r values.
#include "leaves/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"
#include "leaves/leaves.hpp"
#include "windows/windows.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace btob::leaves {

namespace {
// r in (0, 1) (core's check and wording), then where P2 / r has the complex pair: r^2 - 6 r + 1 < 0 and r < 1
// (3 - 2 sqrt(2) < r < 1).
void require_leaf_r(double r, const char* field) {
  core::require_r(r, field);
  if (!(std::isfinite(r) && r * r - 6 * r + 1 < 0 && r < 1))
    throw core::InvalidField(field, fmt::format("{}", r),
                             "a number in (3 - 2 sqrt(2), 1) = (0.17157287525, 1), where P2 has complex eigenvalues");
}
}  // namespace

attractors::Grid Request::parsed_grid() const {
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  const attractors::Grid g = attractors::parse_grid(grid, w1_range[0], w1_range[1], "grid");
  if (g.kind != core::GridKind::sphere && g.kind != core::GridKind::strip)
    throw core::InvalidField("grid", "'" + grid + "'", "sphere:NxM or strip:NxM");
  return g;
}

void Request::validate() const {
  if (r_count < 0 || r_count > 1000) throw core::InvalidField("r-count", fmt::format("{}", r_count), "0..1000");
  if (r_count == 0) require_leaf_r(r, "r");
  if (r_count > 0) {
    require_leaf_r(r_min, "r-min"), require_leaf_r(r_max, "r-max");
    core::require_r_range(r_min, r_max, r_count);
  }
  const attractors::Grid g = parsed_grid();
  if (g.cells() > 4000000) throw core::InvalidField("grid", "'" + grid + "'", "at most 4e6 points");
  // A strip grid must hold the region (|w1| <= 1 / sqrt(2 r) on it) for the closed-form share of its measure.
  const double r_lo = r_count == 0 ? r : r_min, reach = 1 / std::sqrt(2 * r_lo);
  if (g.kind == core::GridKind::strip && !(g.axis1.lo <= -reach && g.axis1.hi >= reach))
    throw core::InvalidField(
        "w1-range", fmt::format("[{}, {}]", g.axis1.lo, g.axis1.hi),
        fmt::format("a range holding [-{0:.6g}, {0:.6g}] (the region's w1 at r = {1})", reach, r_lo));
  if (bins < 2 || bins > 1000 || bins % 2 != 0)
    throw core::InvalidField("bins", fmt::format("{}", bins), "even, 2..1000");
  if (labels.empty() || labels.size() > 100)
    throw core::InvalidField("labels", fmt::format("{} values", labels.size()), "1..100 labels");
  for (double t : labels)
    if (!(t > 0 && t <= 3)) throw core::InvalidField("labels", fmt::format("{}", t), "labels in (0, 3]");
  if (leaf_iterations < 100 || leaf_iterations > 10000000)
    throw core::InvalidField("leaf-iterations", fmt::format("{}", leaf_iterations), "100..1e7");
  if (max_m < 2 || max_m > 120) throw core::InvalidField("max-m", fmt::format("{}", max_m), "2..120");
  attractors::validate(thresholds);
}

std::vector<double> Request::all_r() const {
  if (r_count == 0) return {r};
  std::vector<double> v;
  for (long k = 0; k < r_count; ++k)
    v.push_back(r_count == 1 ? r_min
                             : r_min + (r_max - r_min) * static_cast<double>(k) / static_cast<double>(r_count - 1));
  return v;
}

}  // namespace btob::leaves
