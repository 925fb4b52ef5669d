// SPDX-License-Identifier: GPL-3.0-or-later
// The attractors requests' validation (classify, basins, basins-r), their grids, r values and Table 6.1.
#include "attractors/request_detail.hpp"
#include "attractors/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/patterns.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace btob::attractors {

// ---- classify ----
// The exponent-reporting tools share lyapunov's domain: r from the smallest that double's exponents resolve.
static void require_r_double(double r, const char* field) {
  core::require_r(r, field);
  core::require_r_exponents(r, core::parse_precision("double"), field, {});  // no --precision to advise
}

void ClassifyRequest::validate() const {
  require_r_double(r, "r");
  core::parse_point(point, "point");
  attractors::validate(thresholds);
}

// ---- basins ----
Grid BasinsRequest::parsed_grid() const {
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  return parse_grid(grid, w1_range[0], w1_range[1], "grid");
}

void BasinsRequest::validate() const {
  require_r_double(r, "r");
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  if (!(std::isfinite(w1_range[0]) && std::isfinite(w1_range[1]) && w1_range[0] < w1_range[1]))  // any grid kind
    throw core::InvalidField("w1-range", fmt::format("[{}, {}]", w1_range[0], w1_range[1]), "finite a < b");
  attractors::validate(thresholds);
  if (replicates < 0 || replicates > 100) throw core::InvalidField("replicates", std::to_string(replicates), "0..100");
  if (entropy_box < 1 || entropy_box > 1000)
    throw core::InvalidField("entropy-box", std::to_string(entropy_box), "1..1000 cells");
  const Grid g = parsed_grid();
  // Per point of the main grid: its label in a part and in the merged result (the work runs in bounded chunks).
  iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells), 8, "grid");
}

std::size_t BasinsRequest::work_items() const { return basin_items(parsed_grid(), replicates); }

// ---- basins-r ----
std::vector<TableRow> parse_table(const std::string& csv) {
  std::vector<TableRow> rows;
  std::stringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ',')) f.push_back(item);
    if (f.size() < 2) continue;
    rows.push_back({std::stod(f[0]), f[1], f.size() > 2 ? f[2] : ""});
  }
  return rows;
}

std::vector<double> BasinsRRequest::all_r() const {
  std::vector<double> rs = r_values;
  if (r_count > 0)
    for (double r : iterate::linspace_r(r_min, r_max, r_count)) rs.push_back(r);
  if (table)
    for (const auto& t : parse_table(reference_csv))
      if (t.r >= 0.1 - 1e-12 && t.r <= 0.6 + 1e-12) rs.push_back(t.r);
  return rs;
}

void detail::require_table(const BasinsRRequest& q) {
  if (q.table && parse_table(q.reference_csv).empty())
    throw core::InvalidField("reference", q.reference.empty() ? "the lab's Table 6.1" : "'" + q.reference + "'",
                             "a readable CSV of Table 6.1 (r,percent,patterns)");
}

void BasinsRRequest::validate() const {
  attractors::validate(thresholds);
  // With `table` the r values come from reference_csv, which the caller may fill after this first check (the
  // command line reads the file named by `reference`); run() checks the table itself.
  const bool table_pending = table && reference_csv.empty();
  if (!table_pending) detail::require_table(*this);
  if (r_count < 0 || r_count > 100000)
    throw core::InvalidField("r-count", std::to_string(r_count), "0 (no range) .. 100000");
  if (r_count > 0) {
    core::require_r_range(r_min, r_max, r_count);
    require_r_double(r_min, "r-min");
    require_r_double(r_max, "r-max");
  }
  const std::vector<double> rs = all_r();
  if (rs.empty() && !table_pending)
    throw core::InvalidField("r-values", "none", "a list of r in (0, 1), a range (r-min, r-max, r-count) or --table");
  for (double r : rs) require_r_double(r, "r-values");
  const auto pts = iterate::parse_grid(grid, seed, "grid");
  if (pts.empty()) throw core::InvalidField("grid", "'" + grid + "' with no points", "at least one");
  iterate::checked_bytes(pts.size(), 800, "grid");
  if (boundary_replicates < 0 || boundary_replicates > 100)
    throw core::InvalidField("boundary-replicates", std::to_string(boundary_replicates), "0..100");
  if (entropy_box < 1 || entropy_box > 1000)
    throw core::InvalidField("entropy-box", std::to_string(entropy_box), "1..1000 cells");
  if (has_boundary_grid(*this)) {
    const Grid g = boundary_grid_of(*this);
    iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells),
                           8 * static_cast<std::size_t>(boundary_replicates + 1), "boundary-grid");
  }
}

bool has_boundary_grid(const BasinsRRequest& req) { return req.boundary_grid != "none"; }
// A strip boundary grid spans the basins default w1 range [-2, 2].
Grid boundary_grid_of(const BasinsRRequest& req) { return parse_grid(req.boundary_grid, -2, 2, "boundary-grid"); }

}  // namespace btob::attractors
