// SPDX-License-Identifier: GPL-3.0-or-later
// The Lyapunov requests: validation, the runs, and the description of their results.
#include "lyapunov/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

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

template <class T> void all_finite(const T& values, const std::string& what) {
  for (double v : values)
    if (!std::isfinite(v))
      throw std::domain_error(
          fmt::format("{}: a non-finite exponent; this precision cannot represent the run "
                      "(use a wider --precision)",
                      what));
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

ProjectiveResult run(const OrbitRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  const core::Vec3<double> u = core::parse_point(req.point, "point");
  Options o;
  o.iterations = req.iterations;
  o.transient = req.transient;
  o.reorthonormalise = req.reorthonormalise;
  o.blocks = req.blocks;
  o.weighted = req.weighted;  // the weighted averages' pass only when asked for
  o.cancel = control.cancel;
  // The orbit and the tangent frame are iterated in T, r is T's own value of the request's r (a float128 run
  // at r = 0.1 uses float128's 0.1 when the request came as text), the sums of log R_ii accumulated in long
  // double and the exponents reported in double.
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  const auto in = [&]<class T>(T*) {
    const core::Vec3<T> ut(T(u(0)), T(u(1)), T(u(2)));
    return projective_exponents<T>(ut, core::from_decimal<T>(req.r.text), o);  // T's r, not double's widened
  };
  ProjectiveResult res;
  switch (prec.kind) {
    case core::Precision::Kind::f32: res = in(static_cast<float*>(nullptr)); break;
    case core::Precision::Kind::f64: res = in(static_cast<double*>(nullptr)); break;
    case core::Precision::Kind::f80: res = in(static_cast<long double*>(nullptr)); break;
    case core::Precision::Kind::f128: res = in(static_cast<core::float128*>(nullptr)); break;
    case core::Precision::Kind::mpfr: {
      core::MpfrDigits digits(prec.mpfr_digits);  // restored on every exit path
      res = in(static_cast<core::mpfr_float*>(nullptr));
      break;
    }
  }
  res.weighted_columns = req.weighted;
  all_finite(std::vector<double>{res.lambda[0].value, res.lambda[0].error, res.lambda[1].value, res.lambda[1].error,
                                 res.weighted[0], res.weighted[1]},
             fmt::format("r = {} in {}", req.r, prec.name()));
  return res;
}

namespace {
// One term of cocycle steps in `precision`, probed on a fixed chaotic orbit (r = 0.2 from (1, -0.5, -1.1): no
// collapse, no period, so every step costs what a long run's steps cost) with the request's interval.
core::Term cocycle_term(const std::string& precision, int reorthonormalise, double steps) {
  core::Term t;
  t.route =
      fmt::format("lyapunov orbit {} interval/{}", core::parse_precision(precision, "precision").name(),
                  reorthonormalise);  // the one-orbit route (orbit.hpp): a rate cached for the QR route is not its
  t.units = steps;
  t.what = fmt::format("map steps of the derivative cocycle in {} (transient + iterations)", precision);
  t.probe = [precision, reorthonormalise](double n, const core::RunControl& c) {
    OrbitRequest p;
    p.r = core::Decimal::parse("0.2", "r");
    p.point = "1,-0.5,-1.1";
    p.precision = precision;
    p.reorthonormalise = reorthonormalise;
    p.transient = 0;
    p.blocks = 2;
    p.iterations = std::max(static_cast<long>(n), 2L * reorthonormalise);
    (void)run(p, c);
    return static_cast<double>(p.iterations);
  };
  return t;
}
}  // namespace

core::Work work(const OrbitRequest& req) {
  core::Work w;
  const double steps = static_cast<double>(req.transient) + static_cast<double>(req.iterations);
  w.terms.push_back(cocycle_term(req.precision, req.reorthonormalise, steps));
  if (req.precision == "float") {  // the command line re-runs a float orbit in double to check lambda1's sign
    w.terms.push_back(cocycle_term("double", req.reorthonormalise, steps));
    w.terms.back().what += ", the float run's check";
  }
  // Printed: one CSV row; --convergence: a row per checkpoint (powers of two and block ends) of ~60 bytes.
  const double rows = std::log2(std::max(2.0, static_cast<double>(req.iterations))) + req.blocks;
  w.output_bytes = 120 + (req.convergence.empty() ? 0 : 60 * rows);
  w.peak_bytes = 64 * rows + 4096;  // the accumulator's checkpoints; the orbit itself is a few vectors
  return w;
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

double MapRequest::map_steps() const {
  const double orbits = static_cast<double>(iterate::parse_grid(grid, seed, "grid").size());
  return static_cast<double>(r_count) * orbits * (static_cast<double>(transient) + static_cast<double>(iterations));
}

double StripRequest::map_steps() const {
  const core::Grid g = spec();
  return static_cast<double>(g.axis1.cells) * static_cast<double>(g.axis2.cells) *
         (static_cast<double>(transient) + static_cast<double>(iterations));
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

namespace {
MapResult run_ensemble(iterate::Ensemble ens, long iterations, long transient, int blocks, const std::string& precision,
                       const core::RunControl& control) {
  MapOptions o;
  o.iterations = iterations;
  o.transient = transient;
  o.blocks = blocks;
  o.single_precision = precision == "float";
  o.run.threads = control.threads;
  o.run.progress = control.progress;
  o.run.cancel = control.cancel;
  MapResult res;
  const auto t0 = std::chrono::steady_clock::now();
  res.exponents = map_exponents(ens, o);
  res.iteration_seconds = core::seconds_since(t0);
  res.ensemble = std::move(ens);
  return res;
}

// The exponents of some orbits (rows of `width`) merged by item, with the slowest part's time.
MapResult merge_exponents(std::vector<MapPart>& parts, std::size_t items, std::size_t width, long iterations,
                          int blocks) {
  const auto order = core::item_order(parts, items);
  MapResult res;
  OrbitExponents& e = res.exponents;
  using V = std::vector<double>;
  const auto rows = [&](V OrbitExponents::*f) {
    return core::merge_rows<MapPart, double>(parts, order, width,
                                             [f](const MapPart& p) -> const V& { return p.exponents.*f; });
  };
  e.lambda1 = rows(&OrbitExponents::lambda1);
  e.err1 = rows(&OrbitExponents::err1);
  e.lambda2 = rows(&OrbitExponents::lambda2);
  e.err2 = rows(&OrbitExponents::err2);
  e.lambda_max = rows(&OrbitExponents::lambda_max);
  e.err_max = rows(&OrbitExponents::err_max);
  e.lambda_min = rows(&OrbitExponents::lambda_min);
  e.err_min = rows(&OrbitExponents::err_min);
  e.chi1 = rows(&OrbitExponents::chi1);
  e.iterations = iterations;
  e.blocks = blocks;
  for (const MapPart& p : parts) res.iteration_seconds = std::max(res.iteration_seconds, p.iteration_seconds);
  return res;
}
}  // namespace

namespace {
// The float check of a part: of its r values, those whose index is a multiple of k = ceil(R / 64) (at most 64 over
// the request) again in double, each orbit's sign class compared with float's.  Per r value, so the counts and the
// first disagreeing r are the same for any partition.
void check_float(MapPart& part, const iterate::Ensemble& ens, const MapRequest& req, const core::RunControl& control) {
  const std::size_t R = req.work_items(), I = ens.initial.size(), k = (R + 63) / 64;
  std::vector<std::size_t> checked;  // positions in the part
  for (std::size_t j = 0; j < part.items.size(); ++j)
    if (part.items[j] % k == 0) checked.push_back(j);
  if (checked.empty()) return;
  core::RunControl quiet = control;
  quiet.progress = nullptr;
  const MapResult d = run_ensemble(ens.with_r(checked), req.iterations, req.transient, req.blocks, "double", quiet);
  for (std::size_t c = 0; c < checked.size(); ++c)
    for (std::size_t ic = 0; ic < I; ++ic) {
      const std::size_t of = checked[c] * I + ic, od = c * I + ic;
      ++part.float_checked;
      if (classify(part.exponents.lambda1[of], part.exponents.err1[of], req.iterations) !=
          classify(d.exponents.lambda1[od], d.exponents.err1[od], req.iterations)) {
        if (part.float_disagree++ == 0) part.float_disagree_item = part.items[checked[c]];
      }
    }
}

// The per-r rows of the parts (summary), in item order, and the float check's counts.
void merge_per_r(MapResult& res, const std::vector<MapPart>& parts, std::size_t R) {
  const auto order = core::item_order(parts, R);
  RSummary& s = res.summary;
  for (auto f : {&RSummary::min, &RSummary::median, &RSummary::max, &RSummary::err_min, &RSummary::err_median,
                 &RSummary::err_max, &RSummary::frac_positive, &RSummary::frac_zero, &RSummary::frac_negative})
    s.*f = core::merge_rows<MapPart, double>(
        parts, order, 1, [f](const MapPart& p) -> const std::vector<double>& { return p.summary.*f; });
  std::size_t first = static_cast<std::size_t>(-1);
  for (const MapPart& p : parts) {
    res.float_checked += p.float_checked;
    res.float_disagree += p.float_disagree;
    first = std::min(first, p.float_disagree_item);
  }
  if (res.float_disagree > 0) res.float_disagree_r = res.ensemble.r[first];
}
}  // namespace

MapPart run_part(const MapRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  req.validate();
  iterate::Ensemble ens;  // the part's r values with the whole request's grid
  ens.set_r_range(req.r_min, req.r_max, req.r_count, &items);
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  MapResult res = run_ensemble(ens, req.iterations, req.transient, req.blocks, req.precision, control);
  MapPart part{items, std::move(res.exponents), {}, 0, 0, static_cast<std::size_t>(-1), res.iteration_seconds};
  part.summary = summarise(part.exponents, items.size(), ens.initial.size());
  if (req.precision == "float") check_float(part, ens, req, control);
  return part;
}

MapResult merge(const MapRequest& req, std::vector<MapPart> parts) {
  req.validate();
  const std::vector<core::Vec3<double>> grid = iterate::parse_grid(req.grid, req.seed, "grid");
  MapResult res = merge_exponents(parts, req.work_items(), grid.size(), req.iterations, req.blocks);
  iterate::Ensemble& ens = res.ensemble;
  ens.set_r_range(req.r_min, req.r_max, req.r_count);
  ens.initial = grid;
  ens.grid_description = req.grid;
  ens.seed = req.seed;
  merge_per_r(res, parts, ens.r.size());
  return res;
}

MapResult run(const MapRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

MapPart run_part(const StripRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  req.validate();
  const core::Grid g = req.spec();
  const auto grid = iterate::strip_grid(g);  // cell (i, j) at i * n2 + j
  const std::size_t n2 = static_cast<std::size_t>(g.axis2.cells);
  iterate::Ensemble ens;
  ens.set_r_list({req.r});
  for (std::size_t i : items)
    ens.initial.insert(ens.initial.end(), grid.begin() + static_cast<std::ptrdiff_t>(i * n2),
                       grid.begin() + static_cast<std::ptrdiff_t>((i + 1) * n2));
  MapResult res = run_ensemble(std::move(ens), req.iterations, req.transient, req.blocks, req.precision, control);
  MapPart part;
  part.items = items;
  part.exponents = std::move(res.exponents);
  part.iteration_seconds = res.iteration_seconds;
  return part;
}

MapResult merge(const StripRequest& req, std::vector<MapPart> parts) {
  req.validate();
  const core::Grid g = req.spec();
  MapResult res =
      merge_exponents(parts, req.work_items(), static_cast<std::size_t>(g.axis2.cells), req.iterations, req.blocks);
  iterate::Ensemble& ens = res.ensemble;
  ens.set_r_list({req.r});
  ens.initial = iterate::strip_grid(g);
  ens.grid_description = core::grid_spec(g);
  res.n1 = static_cast<std::size_t>(g.axis1.cells);
  res.n2 = static_cast<std::size_t>(g.axis2.cells);
  res.w1.resize(res.ensemble.initial.size());
  res.w2.resize(res.ensemble.initial.size());
  for (std::size_t i = 0; i < res.ensemble.initial.size(); ++i)
    std::tie(res.w1[i], res.w2[i]) = core::strip<double>(res.ensemble.initial[i]);
  for (std::size_t i = 0; i < res.n1; ++i) res.w1_cell.push_back(res.w1[i * res.n2]);  // cell (i, j) at i * n2 + j
  for (std::size_t j = 0; j < res.n2; ++j) res.w2_cell.push_back(res.w2[j]);
  return res;
}

MapResult run(const StripRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
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

core::Tables MapResult::tables() const {
  if (n1 > 0) return {};  // a strip has no per-r summary
  const auto& s = summary;
  core::CsvTable csv(
      "r,lambda1_min,lambda1_min_err,lambda1_median,lambda1_median_err,lambda1_max,lambda1_max_err,frac_positive,"
      "frac_zero,frac_negative");
  // Each exponent with its bar by core::with_error (the printed interval contains the value of NAME.h5).
  const auto pair = [](double v, double e) {
    if (!std::isfinite(v) || !std::isfinite(e) || e < 0) return core::csv_number(v) + "," + core::csv_number(e);
    const core::ValueWithError p = core::with_error(v, e);
    return p.value + "," + p.error;
  };
  for (std::size_t i = 0; i < ensemble.r.size(); ++i)
    csv.line(fmt::format("{:.9f},{},{},{},{:.4f},{:.4f},{:.4f}", ensemble.r[i], pair(s.min[i], s.err_min[i]),
                         pair(s.median[i], s.err_median[i]), pair(s.max[i], s.err_max[i]), s.frac_positive[i],
                         s.frac_zero[i], s.frac_negative[i]));
  return {{"summary", csv.text()}};
}

}  // namespace btob::lyapunov
