// SPDX-License-Identifier: GPL-3.0-or-later
// The Lyapunov requests' validation: lyapunov, lyapunov-map, lyapunov-strip, hyperbolicity, hyperbolicity-orbits.
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/request_detail.hpp"
#include "lyapunov/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "lyapunov/lyapunov.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace btob::lyapunov {

namespace {
void check_lengths(long iterations, long transient, int blocks) {
  if (iterations < 1) throw core::InvalidField("iterations", std::to_string(iterations), "at least 1");
  if (transient < 0) throw core::InvalidField("transient", std::to_string(transient), "at least 0");
  if (transient > iterations)
    throw core::InvalidField("transient", std::to_string(transient),
                             fmt::format("at most iterations = {}", iterations));
  if (blocks < 2 || blocks > iterations)
    throw core::InvalidField("blocks", std::to_string(blocks),
                             fmt::format("2 <= blocks <= iterations = {}", iterations));
}

void check_kernel_precision(const std::string& p) {
  if (p != "float" && p != "double")
    throw core::InvalidField("precision", "'" + p + "'", "float or double (the batched tangent kernel)");
}
}  // namespace

void OrbitRequest::validate() const {
  core::require_r(r, "r");
  check_lengths(iterations, transient, blocks);
  if (reorthonormalise < 1)
    throw core::InvalidField("reorthonormalise", std::to_string(reorthonormalise), "at least 1");
  (void)core::parse_point(point, "point");
  core::require_r_exponents(r, core::parse_precision(precision, "precision"), "r");
}

void MapRequest::validate() const {
  core::require_at_least(r_count, 1, "r-count");
  // Checked here, before an MPI job's checkpoint, not only where the r values are made: every rank refuses it alike.
  core::require_r_range(r_min, r_max, r_count);
  check_lengths(iterations, transient, blocks);
  check_kernel_precision(precision);
  core::require_r_exponents(r_min, core::parse_precision(precision), "r-min",
                            {"float", "double"});  // r-min <= r-max from here on
  (void)iterate::parse_grid(grid, seed, "grid");
  // classify runs in double from transient >= 1 (attractors::validate refuses the rest of its options).
  if (attractors && precision != "double")
    throw core::InvalidField("attractors", "with precision " + precision, "precision double (classify's precision)");
  if (attractors && transient < 1)
    throw core::InvalidField("attractors", "with transient 0", "transient >= 1 (classify's transient)");
}

void StripRequest::validate() const {
  core::require_r(r, "r");
  const core::Grid g = spec();  // N, M >= 1 and the range checked by the parser
  check_lengths(iterations, transient, blocks);
  check_kernel_precision(precision);
  core::require_r_exponents(r, core::parse_precision(precision), "r",
                            {"float", "double"});  // the cocycle runs in this precision
  iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells), 200, "grid");
}

// ---- hyperbolicity (strip image) ----------------------------------------------------------------------------

core::Grid HyperbolicityRequest::strip() const {
  static const core::GridSyntax cells{core::grid_kinds({core::GridKind::strip}), false, 0,
                                      "strip:NxM with N, M >= 1 (the w1 range is the field w1-range)"};
  core::Grid s = core::parse_grid(grid, cells, "grid");
  std::vector<double> range;
  core::set_field(range, {w1_range}, "w1-range");  // finite numbers, split at the comma
  if (range.size() != 2 || !(range[0] < range[1]) || !std::isfinite(range[1] - range[0]))  // the width too
    throw core::InvalidField("w1-range", "'" + w1_range + "'", "two finite numbers a,b with a < b");
  s.axis1.lo = range[0];
  s.axis1.hi = range[1];
  return s;
}

void HyperbolicityRequest::validate() const {
  core::require_r(r, "r");
  const core::Grid s = strip();
  // The grid, the four images and the symbols.
  iterate::checked_bytes(s.cells(), sizeof(iterate::Vec3<double>) + 4 * sizeof(double) + 1, "grid");
}

std::string HyperbolicityRequest::default_name() const { return fmt::format("hyperbolicity_strip_r{}", r); }

std::size_t HyperbolicityRequest::work_items() const { return static_cast<std::size_t>(strip().axis1.cells); }

// ---- hyperbolicity-orbits ---------------------------------------------------------------------------------------

void HyperbolicityOrbitsRequest::validate() const {
  if (r_count < 1 || r_count > 1000000)
    throw core::InvalidField("r-count", std::to_string(r_count), "1 <= r-count <= 1000000");
  core::require_r_range(r_min, r_max, r_count);
  // lambda1 comes from lyapunov::map_exponents with 10 batch-means blocks, which needs iterations >= 10.
  if (iterations < 10) throw core::InvalidField("iterations", std::to_string(iterations), "at least 10");
  if (transient < 0) throw core::InvalidField("transient", std::to_string(transient), "at least 0");
  if (backward < 1) throw core::InvalidField("backward", std::to_string(backward), "at least 1");
  if (bins < 1) throw core::InvalidField("bins", std::to_string(bins), "at least 1");
  lyapunov::validate(detail::clv_options(*this));
  (void)iterate::linspace_r(r_min, r_max, r_count);
  const auto ics = iterate::parse_grid(grid, seed, "grid");
  iterate::checked_bytes(ics.size() * static_cast<std::size_t>(iterations), sizeof(double) + 2, "iterations");
}

}  // namespace btob::lyapunov
