// SPDX-License-Identifier: GPL-3.0-or-later
// The Lyapunov results' description: arrays, attributes, CSV text and tables.
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
// What an orbit's exponent is (docs/reference/numbers.md): an estimate whose bar is the batch-means standard error.
core::Status exponent_status(int blocks) {
  return core::estimated(
      fmt::format("batch-means standard error over {} blocks (err1, err2), at least 4 eps |lambda| "
                  "for the arithmetic; the finite-time bias of a slowly converging orbit is not in it",
                  blocks),
      "one standard error (68% if the block means are normal)");
}
}  // namespace

std::string ProjectiveResult::csv() const {
  core::CsvTable t(weighted_columns ? "lambda1_weighted,lambda2_weighted,lambda1,err1,lambda2,err2,iterations,status"
                                    : "lambda1,err1,lambda2,err2,iterations,status");
  const core::ValueWithError a = core::with_error(lambda[0].value, lambda[0].error),
                             b = core::with_error(lambda[1].value, lambda[1].error);
  const std::string row = fmt::format("{},{},{},{},{},estimated", a.value, a.error, b.value, b.error, iterations);
  t.line(weighted_columns ? fmt::format("{:.15g},{:.15g},{}", weighted[0], weighted[1], row) : row);
  return t.text();
}

void ProjectiveResult::describe(core::Contents& c) const {
  c.attr("lambda1", lambda[0].value);
  c.attr("err1", lambda[0].error);
  c.attr("lambda2", lambda[1].value);
  c.attr("err2", lambda[1].error);
  c.attr("iterations", iterations);
  c.attr("blocks", static_cast<long>(blocks));
  const core::Status st = exponent_status(blocks);
  c.status_of("lambda1", st);
  c.status_of("lambda2", st);
  if (has_weighted) {  // computed when asked (OrbitRequest::weighted; the library's default)
    c.attr("lambda1_weighted", weighted[0]);
    c.attr("lambda2_weighted", weighted[1]);
    const core::Status w = core::estimated(
        "weighted Birkhoff average (super-polynomial convergence on periodic and "
        "quasi-periodic orbits only)",
        "no error bar");
    c.status_of("lambda1_weighted", w);
    c.status_of("lambda2_weighted", w);
  }
  if (convergence.exponents.size() < 2) return;  // a result that was never run
  const std::vector<std::size_t> dims{convergence.n.size()};
  c.array("convergence_n", convergence.n, dims, "checkpoint", "iterations",
          "averaged steps at the checkpoint (powers of two and block ends)");
  c.coordinate("checkpoint", "convergence_n");
  c.array("convergence_lambda1", convergence.exponents[0], dims, "checkpoint", "1/iteration (natural log)",
          "running average of lambda1 at the checkpoint");
  c.array("convergence_lambda2", convergence.exponents[1], dims, "checkpoint", "1/iteration (natural log)",
          "running average of lambda2 at the checkpoint");
}

void MapResult::describe(core::Contents& c) const {
  const std::size_t R = ensemble.r.size(), I = ensemble.initial.size();
  const bool strip = n1 > 0;
  const std::vector<std::size_t> dims = strip ? std::vector<std::size_t>{n1, n2} : std::vector<std::size_t>{R, I};
  const std::string axes = strip ? "w1 cell, w2 cell" : "r, initial condition";
  const std::string per = "1/iteration (natural log)";
  c.array("r", ensemble.r, {R}, "r", "1", "restitution coefficients");
  const auto& e = exponents;
  c.array("lambda1", e.lambda1, dims, axes, per,
          "projective exponent of one tangent vector (v0 = e1; converges to the larger one), = chi2 - chi1");
  c.array("err1", e.err1, dims, axes, per, "batch-means standard error of lambda1");
  c.array("lambda2", e.lambda2, dims, axes, per,
          "log|det D^n|/n - lambda1, = chi3 - chi1 (may exceed lambda1 by O(1/n))");
  c.array("err2", e.err2, dims, axes, per, "batch-means standard error of lambda2");
  c.array("lambda_max", e.lambda_max, dims, axes, per, "the larger of lambda1, lambda2");
  c.array("err_max", e.err_max, dims, axes, per, "batch-means standard error of lambda_max");
  c.array("lambda_min", e.lambda_min, dims, axes, per, "the smaller of lambda1, lambda2");
  c.array("err_min", e.err_min, dims, axes, per, "batch-means standard error of lambda_min");
  c.array("chi1", e.chi1, dims, axes, per,
          "growth rate of the orbit vector u under the linear cocycle of the P_s (not P_s/r): log|P^n u0|/n");
  if (strip) {
    c.array("w1", w1, dims, axes, "1", "strip coordinate w1 of the cell centre");
    c.array("w2", w2, dims, axes, "1", "strip coordinate w2 of the cell centre");
    c.array("w1_cell", w1_cell, {n1}, "w1 cell", "1", "strip coordinate w1 (eq. (6.4)) of each column of cells");
    c.array("w2_cell", w2_cell, {n2}, "w2 cell", "1", "strip coordinate w2 (eq. (6.4)) of each row of cells");
    c.coordinate("w1 cell", "w1_cell");
    c.coordinate("w2 cell", "w2_cell");
  } else {
    const std::string s = "of lambda1 over the initial conditions at each r";
    c.array("min", summary.min, {R}, "r", per, "minimum " + s);
    c.array("median", summary.median, {R}, "r", per, "median " + s);
    c.array("max", summary.max, {R}, "r", per, "maximum " + s);
    c.array("min_err", summary.err_min, {R}, "r", per, "batch-means error of the orbit realising min");
    c.array("median_err", summary.err_median, {R}, "r", per,
            "batch-means error of the median (middle orbit, or half the RSS of the two middle orbits)");
    c.array("max_err", summary.err_max, {R}, "r", per, "batch-means error of the orbit realising max");
    c.array("frac_positive", summary.frac_positive, {R}, "r", "1", "fraction of orbits with lambda1 > 3 err1 + 10/n");
    c.array("frac_zero", summary.frac_zero, {R}, "r", "1", "fraction of orbits with |lambda1| <= 3 err1 + 10/n");
    c.array("frac_negative", summary.frac_negative, {R}, "r", "1",
            "fraction of orbits with lambda1 < -(3 err1 + 10/n)");
  }
  c.attr("iterations", e.iterations);
  c.attr("blocks", static_cast<long>(e.blocks));
  c.attr("convention",
         std::string("per map iteration, natural log; lambda1: one tangent vector's growth (-> the larger projective "
                     "exponent), lambda2 = log|det D^n|/n - lambda1; lambda_i = chi_{i+1} - chi1 with chi the linear "
                     "cocycle's exponents in frame order (chi1: the orbit vector); equal exponents (invariant curves, "
                     "complex pairs) fall either way by O(1/n), so lambda_max/lambda_min give them ordered"));
  c.attr("grid", ensemble.grid_description);
  c.attr("initial_conditions", static_cast<long>(I));
  c.attr("seed", static_cast<long>(ensemble.seed));
  c.attr("iteration_seconds", iteration_seconds);
  if (float_checked > 0) {
    c.attr("float_check_orbits", float_checked);
    c.attr("float_check_disagree", float_disagree);
    if (float_disagree > 0) c.attr("float_check_first_r", float_disagree_r);
  }
}

namespace {
constexpr const char* kSummaryHeader =
    "r,lambda1_min,lambda1_min_err,lambda1_median,lambda1_median_err,lambda1_max,lambda1_max_err,frac_positive,"
    "frac_zero,frac_negative";
}  // namespace

std::string summary_line(double r, const RSummary& s, std::size_t j) {
  // Each exponent with its bar by core::with_error (the printed interval contains the value of NAME.h5).
  const auto pair = [](double v, double e) {
    if (!std::isfinite(v) || !std::isfinite(e) || e < 0) return core::csv_number(v) + "," + core::csv_number(e);
    const core::ValueWithError p = core::with_error(v, e);
    return p.value + "," + p.error;
  };
  return fmt::format("{:.9f},{},{},{},{:.4f},{:.4f},{:.4f}", r, pair(s.min[j], s.err_min[j]),
                     pair(s.median[j], s.err_median[j]), pair(s.max[j], s.err_max[j]), s.frac_positive[j],
                     s.frac_zero[j], s.frac_negative[j]);
}

core::Tables MapResult::tables() const {
  if (n1 > 0) return {};  // a strip has no per-r summary
  core::CsvTable csv(kSummaryHeader);
  for (const std::string& line : summary_lines) csv.line(line);  // none when the MPI ranks write them
  return {{"summary", csv.text()}};
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
  c.array("orbit_lambda1", orbit_lambda1, {R, I}, oi, per, "lambda1 from the batched tangent recorder");
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
