// SPDX-License-Identifier: GPL-3.0-or-later
// The hyperbolicity requests: validation, the runs, and the description of their results.
#include "lyapunov/hyperbolicity_requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "lyapunov/lyapunov.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace btob::lyapunov {

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

HyperbolicityPart run_part(const HyperbolicityRequest& req, const std::vector<std::size_t>& items,
                           const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  const core::Grid s = req.strip();
  const auto t0 = std::chrono::steady_clock::now();
  // Cell (i, j) at i * n2 + j, as strip_singular_values (hyperbolicity.cpp) walks it: each cell the same call.
  const std::vector<iterate::Vec3<double>> grid = iterate::strip_grid(s);
  const std::size_t n2 = static_cast<std::size_t>(s.axis2.cells);
  HyperbolicityPart p;
  p.items = items;
  for (auto* v : {&p.s1, &p.s2}) v->reserve(items.size() * n2);
  p.symbol.reserve(items.size() * n2);
  for (std::size_t i : items)
    for (std::size_t j = 0; j < n2; ++j) {
      core::poll_cancel(control.cancel, static_cast<long>(j));
      const StepSingularValues sv = step_singular_values(grid.at(i * n2 + j), req.r);
      p.s1.push_back(sv.s1);
      p.s2.push_back(sv.s2);
      p.symbol.push_back(static_cast<std::uint8_t>(sv.symbol));
    }
  p.seconds = core::seconds_since(t0);
  return p;
}

HyperbolicityResult merge(const HyperbolicityRequest& req, std::vector<HyperbolicityPart> parts) {
  req.validate();
  const core::Grid s = req.strip();
  const std::size_t n2 = static_cast<std::size_t>(s.axis2.cells);
  const auto order = core::item_order(parts, req.work_items());
  HyperbolicityResult res;
  res.request = req;
  StripSingularValues& m = res.image;
  m.n1 = s.axis1.cells;
  m.n2 = s.axis2.cells;
  m.w1_min = s.axis1.lo;
  m.w1_max = s.axis1.hi;
  using V = std::vector<double>;
  m.s1 = core::merge_rows<HyperbolicityPart, double>(parts, order, n2,
                                                     [](const HyperbolicityPart& p) -> const V& { return p.s1; });
  m.s2 = core::merge_rows<HyperbolicityPart, double>(parts, order, n2,
                                                     [](const HyperbolicityPart& p) -> const V& { return p.s2; });
  m.symbol = core::merge_rows<HyperbolicityPart, std::uint8_t>(
      parts, order, n2, [](const HyperbolicityPart& p) -> const std::vector<std::uint8_t>& { return p.symbol; });
  const std::vector<iterate::Vec3<double>> grid = iterate::strip_grid(s);
  m.w1.resize(grid.size());
  m.w2.resize(grid.size());
  long expanding = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    std::tie(m.w1[i], m.w2[i]) = core::strip<double>(grid[i]);
    expanding += m.s1[i] >= 1;
  }
  m.expanding_fraction = static_cast<double>(expanding) / static_cast<double>(grid.size());
  for (long i = 0; i < s.axis1.cells; ++i)
    res.w1_cell.push_back(m.w1[static_cast<std::size_t>(i * s.axis2.cells)]);  // (i, j) at i n2 + j
  for (long j = 0; j < s.axis2.cells; ++j) res.w2_cell.push_back(m.w2[static_cast<std::size_t>(j)]);
  for (const auto& p : parts) res.seconds = std::max(res.seconds, p.seconds);  // the slowest part
  return res;
}

HyperbolicityResult run(const HyperbolicityRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

void HyperbolicityResult::describe(core::Contents& c) const {
  const auto& m = image;
  const std::vector<std::size_t> dims = {static_cast<std::size_t>(m.n1), static_cast<std::size_t>(m.n2)};
  const std::string axes = "w1 cell, w2 cell";
  c.array("s1", m.s1, dims, axes, "1", "largest singular value of the one-step derivative (round metric)");
  c.array("s2", m.s2, dims, axes, "1", "smallest singular value of the one-step derivative (round metric)");
  c.array("symbol", m.symbol, dims, axes, "branch", "branch 1, 2 or 3 of the map at the cell centre");
  c.array("w1", m.w1, dims, axes, "1", "strip coordinate w1 of the cell centre");
  c.array("w2", m.w2, dims, axes, "1", "strip coordinate w2 of the cell centre");
  c.array("w1_cell", w1_cell, {w1_cell.size()}, "w1 cell", "1",
          "strip coordinate w1 (eq. (6.4)) of each column of cells");
  c.array("w2_cell", w2_cell, {w2_cell.size()}, "w2 cell", "1", "strip coordinate w2 (eq. (6.4)) of each row of cells");
  c.coordinate("w1 cell", "w1_cell");
  c.coordinate("w2 cell", "w2_cell");
  c.attr("r", request.r);
  c.attr("alpha", core::alpha(request.r));
  c.attr("grid", fmt::format("strip:{}x{}:{}:{}", m.n1, m.n2, m.w1_min, m.w1_max));
  c.attr("w1_min", m.w1_min);
  c.attr("w1_max", m.w1_max);
  c.attr("metric", std::string("round metric of the unit sphere (tangent planes u^perp)"));
  c.attr("expanding_fraction", m.expanding_fraction);
  c.attr("seconds", seconds);
}

// ---- hyperbolicity-orbits ---------------------------------------------------------------------------------------

namespace {
ClvOptions clv_options(const HyperbolicityOrbitsRequest& req) {
  ClvOptions co;
  co.transient = req.transient;
  co.window = req.iterations;
  co.backward_transient = req.backward;
  co.bins = req.bins;
  return co;
}
}  // namespace

void HyperbolicityOrbitsRequest::validate() const {
  if (r_count < 1 || r_count > 1000000)
    throw core::InvalidField("r-count", std::to_string(r_count), "1 <= r-count <= 1000000");
  core::require_r_range(r_min, r_max, r_count);
  // lambda1 comes from lyapunov::map_exponents with 10 batch-means blocks, which needs iterations >= 10.
  if (iterations < 10) throw core::InvalidField("iterations", std::to_string(iterations), "at least 10");
  if (transient < 0) throw core::InvalidField("transient", std::to_string(transient), "at least 0");
  if (backward < 1) throw core::InvalidField("backward", std::to_string(backward), "at least 1");
  if (bins < 1) throw core::InvalidField("bins", std::to_string(bins), "at least 1");
  lyapunov::validate(clv_options(*this));
  (void)iterate::linspace_r(r_min, r_max, r_count);
  const auto ics = iterate::parse_grid(grid, seed, "grid");
  iterate::checked_bytes(ics.size() * static_cast<std::size_t>(iterations), sizeof(double) + 2, "iterations");
}

namespace {
// Row j of the part from the batched CLVs of every orbit at its r (covariant_vectors_batched: the same for any
// thread count and any other r in the part); angles only from non-degenerate orbits.
void clv_row(HyperbolicityOrbitsPart& res, std::size_t j, const ClvRow& row, std::size_t B) {
  const std::size_t I = row.orbit.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> l1s;
  double f = 0;
  long deg = 0;
  for (std::size_t i = 0; i < I; ++i) {
    const auto& c = row.orbit[i];
    const std::size_t o = j * I + i;
    res.orbit_frac_expanding[o] = c.expanding_fraction;
    res.orbit_angle_median[o] = c.degenerate ? nan : c.median_angle;
    res.orbit_angle_q05[o] = c.degenerate ? nan : c.q05_angle;
    res.orbit_lambda1_qr[o] = c.lambda[0];
    res.orbit_lambda2_qr[o] = c.lambda[1];
    res.orbit_degenerate[o] = c.degenerate;
    l1s.push_back(c.lambda[0]);
    f += c.expanding_fraction;
    deg += c.degenerate;
  }
  std::copy(row.histogram.begin(), row.histogram.end(), res.angle_histogram.begin() + static_cast<long>(j * B));
  res.frac_expanding[j] = f / static_cast<double>(I);
  res.frac_degenerate[j] = static_cast<double>(deg) / static_cast<double>(I);
  res.lambda1_qr_median[j] = median(l1s);  // as lyapunov-map's median column
  res.angle_median[j] = row.median_angle;
  res.angle_q05[j] = row.q05_angle;
  res.angle_min[j] = row.min_angle;
}
}  // namespace

HyperbolicityOrbitsPart run_part(const HyperbolicityOrbitsRequest& req, const std::vector<std::size_t>& items,
                                 const core::RunControl& control) {
  req.validate();
  const std::vector<double> all_r = iterate::linspace_r(req.r_min, req.r_max, req.r_count);
  iterate::Ensemble ens;  // the part's r values with the whole request's grid
  for (std::size_t i : items) ens.r.push_back(all_r.at(i));
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  const std::size_t R = ens.r.size(), N = ens.orbits(), B = static_cast<std::size_t>(req.bins);
  HyperbolicityOrbitsPart res;
  res.items = items;
  res.threads = core::thread_count(control.threads);
  for (auto* v : {&res.orbit_frac_expanding, &res.orbit_angle_median, &res.orbit_angle_q05, &res.orbit_lambda1_qr,
                  &res.orbit_lambda2_qr})
    v->resize(N);
  res.orbit_degenerate.resize(N);
  res.frac_expanding.resize(R);
  res.frac_degenerate.resize(R);
  res.lambda1_qr_median.resize(R);
  for (auto* v : {&res.angle_median, &res.angle_q05, &res.angle_min}) v->resize(R);
  res.angle_histogram.assign(R * B, 0.0);
  iterate::RunOptions run;
  run.threads = res.threads;
  run.progress = control.progress;
  run.cancel = control.cancel;
  const auto t0 = std::chrono::steady_clock::now();
  const ClvRows rows = covariant_vectors_batched(ens.r, ens.initial, clv_options(req), run);
  for (std::size_t j = 0; j < R; ++j) clv_row(res, j, rows[j], B);
  res.clv_seconds = core::seconds_since(t0);
  // lambda1 beside them, from the fused cocycle kernel (map_exponents) on the same orbits (same r, same grid).
  MapOptions mo;
  mo.transient = req.transient;
  mo.iterations = req.iterations;
  mo.blocks = 10;
  mo.run.threads = control.threads;
  mo.run.cancel = control.cancel;
  res.exponents = map_exponents(ens, mo);
  return res;
}

HyperbolicityOrbitsResult merge(const HyperbolicityOrbitsRequest& req, std::vector<HyperbolicityOrbitsPart> parts) {
  req.validate();
  HyperbolicityOrbitsResult res;
  res.request = req;
  auto& ens = res.ensemble;
  ens.r = iterate::linspace_r(req.r_min, req.r_max, req.r_count);
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  ens.grid_description = req.grid;
  ens.seed = req.seed;
  const std::size_t R = ens.r.size(), I = ens.initial.size();
  res.bins = static_cast<std::size_t>(req.bins);
  const auto order = core::item_order(parts, req.work_items());
  using P = HyperbolicityOrbitsPart;
  using V = std::vector<double>;
  const auto rows = [&](V P::*f, std::size_t width) {
    return core::merge_rows<P, double>(parts, order, width, [f](const P& p) -> const V& { return p.*f; });
  };
  res.frac_expanding = rows(&P::frac_expanding, 1);
  res.angle_median = rows(&P::angle_median, 1);
  res.angle_q05 = rows(&P::angle_q05, 1);
  res.angle_min = rows(&P::angle_min, 1);
  res.frac_degenerate = rows(&P::frac_degenerate, 1);
  res.lambda1_qr_median = rows(&P::lambda1_qr_median, 1);
  res.angle_histogram = rows(&P::angle_histogram, res.bins);
  res.orbit_frac_expanding = rows(&P::orbit_frac_expanding, I);
  res.orbit_angle_median = rows(&P::orbit_angle_median, I);
  res.orbit_angle_q05 = rows(&P::orbit_angle_q05, I);
  res.orbit_lambda1_qr = rows(&P::orbit_lambda1_qr, I);
  res.orbit_lambda2_qr = rows(&P::orbit_lambda2_qr, I);
  res.orbit_degenerate = core::merge_rows<P, std::uint8_t>(
      parts, order, I, [](const P& p) -> const std::vector<std::uint8_t>& { return p.orbit_degenerate; });
  OrbitExponents& e = res.exponents;
  const auto ex = [&](V OrbitExponents::*f) {
    return core::merge_rows<P, double>(parts, order, I, [f](const P& p) -> const V& { return p.exponents.*f; });
  };
  e.lambda1 = ex(&OrbitExponents::lambda1);
  e.err1 = ex(&OrbitExponents::err1);
  e.lambda2 = ex(&OrbitExponents::lambda2);
  e.err2 = ex(&OrbitExponents::err2);
  e.lambda_max = ex(&OrbitExponents::lambda_max);
  e.err_max = ex(&OrbitExponents::err_max);
  e.lambda_min = ex(&OrbitExponents::lambda_min);
  e.err_min = ex(&OrbitExponents::err_min);
  e.chi1 = ex(&OrbitExponents::chi1);
  e.iterations = req.iterations;
  e.blocks = 10;
  for (const P& p : parts) {
    res.threads = std::max(res.threads, p.threads);
    res.clv_seconds = std::max(res.clv_seconds, p.clv_seconds);  // the slowest part
  }
  res.summary = summarise(res.exponents, R, I);
  return res;
}

HyperbolicityOrbitsResult run(const HyperbolicityOrbitsRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

void HyperbolicityOrbitsResult::describe(core::Contents& c) const {
  const std::size_t R = ensemble.r.size(), I = ensemble.initial.size();
  const std::string rad = "rad", per = "1/iteration (natural log)", oi = "r, initial condition";
  c.array("r", ensemble.r, {R}, "r", "1", "restitution coefficients");
  c.array("frac_expanding", frac_expanding, {R}, "r", "1", "fraction of window steps with s1 >= 1, over the orbits");
  c.array("angle_median", angle_median, {R}, "r", rad, "median CLV angle pooled over the non-degenerate orbits");
  c.array("angle_q05", angle_q05, {R}, "r", rad, "5% quantile of the pooled CLV angles");
  c.array("angle_min", angle_min, {R}, "r", rad, "smallest pooled CLV angle");
  c.array("frac_degenerate", frac_degenerate, {R}, "r", "1", "fraction of orbits with lambda1 - lambda2 < 10/window");
  c.array("lambda1_median", summary.median, {R}, "r", per, "median of lambda1 (batched tangent recorder)");
  c.array("lambda1_frac_positive", summary.frac_positive, {R}, "r", "1",
          "fraction of orbits with lambda1 > 3 err1 + 10/n");
  c.array("lambda1_qr_median", lambda1_qr_median, {R}, "r", per, "median of the forward-QR lambda1 over the window");
  c.array("angle_histogram", angle_histogram, {R, bins}, "r, angle bin over [0, pi/2]", "count",
          "CLV angles of the non-degenerate orbits per bin");
  c.coordinate_array("angle_bin", core::bin_centres(0, std::numbers::pi / 2, bins), {"angle bin over [0, pi/2]"}, rad,
                     "centre of each CLV-angle bin of angle_histogram (bins of equal width over [0, pi/2])");
  c.array("orbit_frac_expanding", orbit_frac_expanding, {R, I}, oi, "1", "fraction of window steps with s1 >= 1");
  c.array("orbit_angle_median", orbit_angle_median, {R, I}, oi, rad, "median CLV angle (NaN if degenerate)");
  c.array("orbit_angle_q05", orbit_angle_q05, {R, I}, oi, rad, "5% quantile of the CLV angle (NaN if degenerate)");
  c.array("orbit_lambda1_qr", orbit_lambda1_qr, {R, I}, oi, per, "lambda1 from the forward QR over the window");
  c.array("orbit_lambda2_qr", orbit_lambda2_qr, {R, I}, oi, per, "lambda2 from the forward QR over the window");
  c.array("orbit_lambda1", exponents.lambda1, {R, I}, oi, per, "lambda1 from the batched tangent recorder");
  c.array("orbit_degenerate", orbit_degenerate, {R, I}, oi, "1", "1 when lambda1 - lambda2 < 10/window");
  c.attr("r_min", request.r_min);
  c.attr("r_max", request.r_max);
  c.attr("r_count", request.r_count);
  c.attr("grid", ensemble.grid_description);
  c.attr("initial_conditions", static_cast<long>(I));
  c.attr("seed", static_cast<long>(request.seed));
  c.attr("iterations", request.iterations);
  c.attr("transient", request.transient);
  c.attr("backward_transient", request.backward);
  c.attr("bins", static_cast<long>(request.bins));
  c.attr("angle_units", std::string("radians, in [0, pi/2], between the two CLVs in the round metric of the sphere"));
  c.attr("degenerate", std::string("lambda1 - lambda2 < 10 / iterations (forward QR): CLV angle undefined, left out"));
  c.attr("lambda1_source", std::string("lyapunov::map_exponents (batched tangent recorder), 10 blocks"));
  c.attr("clv_seconds", clv_seconds);
}

core::Tables HyperbolicityOrbitsResult::tables() const {
  core::CsvTable csv(
      "r,frac_expanding,angle_median,angle_q05,angle_min,frac_degenerate,lambda1_median,lambda1_frac_positive,"
      "lambda1_qr_median");
  const auto g = [](double v) { return core::csv_number(v, "{:.6g}"); };
  for (std::size_t i = 0; i < ensemble.r.size(); ++i)
    csv.line(fmt::format("{:.9f},{:.5f},{},{},{},{:.4f},{},{:.4f},{}", ensemble.r[i], frac_expanding[i],
                         g(angle_median[i]), g(angle_q05[i]), g(angle_min[i]), frac_degenerate[i], g(summary.median[i]),
                         summary.frac_positive[i], g(lambda1_qr_median[i])));
  return {{"summary", csv.text()}};
}

}  // namespace btob::lyapunov
