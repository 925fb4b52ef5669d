// The hyperbolicity requests: validation, the runs, and the description of their results.
#include "lyapunov/hyperbolicity_requests.hpp"

#include "core/coords.hpp"
#include "core/fields.hpp"
#include "lyapunov/lyapunov.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace btob::lyapunov {

// ---- hyperbolicity (strip image) ----------------------------------------------------------------------------

iterate::StripSpec HyperbolicityRequest::strip() const {
  iterate::StripSpec s;
  const std::string cells = "strip:NxM with N, M >= 1 (the w1 range is the field w1-range)";
  try {
    s = iterate::parse_strip(grid, "grid");
  } catch (const std::invalid_argument&) {
    throw core::InvalidField("grid", "'" + grid + "'", cells);
  }
  if (s.has_range || s.n1 < 1 || s.n2 < 1) throw core::InvalidField("grid", "'" + grid + "'", cells);
  std::vector<double> range;
  core::set_field(range, {w1_range}, "w1-range");  // finite numbers, split at the comma
  if (range.size() != 2 || !(range[0] < range[1]))
    throw core::InvalidField("w1-range", "'" + w1_range + "'", "two finite numbers a,b with a < b");
  s.w1_min = range[0];
  s.w1_max = range[1];
  return s;
}

void HyperbolicityRequest::validate() const {
  core::require_r(r, "r");
  const iterate::StripSpec s = strip();
  // The grid, the four images and the symbols.
  iterate::checked_bytes(static_cast<std::size_t>(s.n1) * static_cast<std::size_t>(s.n2),
                         sizeof(iterate::Vec3<double>) + 4 * sizeof(double) + 1, "grid");
}

std::string HyperbolicityRequest::default_name() const { return fmt::format("hyperbolicity_strip_r{}", r); }

HyperbolicityResult run(const HyperbolicityRequest& req, const core::RunControl& control) {
  req.validate();
  control.check_cancelled();
  const iterate::StripSpec s = req.strip();
  HyperbolicityResult res;
  res.request = req;
  const auto t0 = std::chrono::steady_clock::now();
  res.image = strip_singular_values(req.r, s.n1, s.n2, s.w1_min, s.w1_max);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
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
  core::require_r(r_min, "r-min");
  core::require_r(r_max, "r-max");
  if (r_count < 1 || r_count > 1000000)
    throw core::InvalidField("r-count", std::to_string(r_count), "1 <= r-count <= 1000000");
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
// The CLVs of every orbit at r index ir (OpenMP, static schedule), pooled in orbit order: the same for any
// thread count; angles only from non-degenerate orbits.
void clv_row(HyperbolicityOrbitsResult& res, std::size_t ir, const ClvOptions& co) {
  const auto& ens = res.ensemble;
  const std::size_t I = ens.initial.size(), B = res.bins;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<ClvResult> clv(I);
  const double r = ens.r[ir];
#pragma omp parallel for schedule(static) num_threads(res.threads)
  for (long i = 0; i < static_cast<long>(I); ++i) {
    clv[static_cast<std::size_t>(i)] = covariant_vectors<double>(ens.initial[static_cast<std::size_t>(i)], r, co);
    clv[static_cast<std::size_t>(i)].symbols = {};  // only the angles are pooled below
  }
  std::vector<double> pooled, l1s;
  double f = 0;
  long deg = 0;
  for (std::size_t i = 0; i < I; ++i) {
    const auto& c = clv[i];
    const std::size_t o = ir * I + i;
    res.orbit_frac_expanding[o] = c.expanding_fraction;
    res.orbit_angle_median[o] = c.degenerate ? nan : c.median_angle;
    res.orbit_angle_q05[o] = c.degenerate ? nan : c.q05_angle;
    res.orbit_lambda1_qr[o] = c.lambda[0];
    res.orbit_lambda2_qr[o] = c.lambda[1];
    res.orbit_degenerate[o] = c.degenerate;
    l1s.push_back(c.lambda[0]);
    f += c.expanding_fraction;
    deg += c.degenerate;
    if (c.degenerate) continue;
    pooled.insert(pooled.end(), c.angle.begin(), c.angle.end());
    for (std::size_t b = 0; b < B; ++b) res.angle_histogram[ir * B + b] += c.histogram[b];
  }
  res.frac_expanding[ir] = f / static_cast<double>(I);
  res.frac_degenerate[ir] = static_cast<double>(deg) / static_cast<double>(I);
  res.lambda1_qr_median[ir] = median(l1s);  // as lyapunov-map's median column
  if (!pooled.empty()) {
    res.angle_median[ir] = quantile(pooled, 0.5);
    res.angle_q05[ir] = quantile(pooled, 0.05);
    res.angle_min[ir] = *std::min_element(pooled.begin(), pooled.end());
  }
}
}  // namespace

HyperbolicityOrbitsResult run(const HyperbolicityOrbitsRequest& req, const core::RunControl& control) {
  req.validate();
  HyperbolicityOrbitsResult res;
  res.request = req;
  auto& ens = res.ensemble;
  ens.r = iterate::linspace_r(req.r_min, req.r_max, req.r_count);
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  ens.grid_description = req.grid;
  ens.seed = req.seed;
  const std::size_t R = ens.r.size(), N = ens.orbits();
  res.bins = static_cast<std::size_t>(req.bins);
  res.threads = control.threads > 0 ? control.threads : omp_get_max_threads();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto* v : {&res.orbit_frac_expanding, &res.orbit_angle_median, &res.orbit_angle_q05, &res.orbit_lambda1_qr,
                  &res.orbit_lambda2_qr})
    v->resize(N);
  res.orbit_degenerate.resize(N);
  res.frac_expanding.resize(R);
  res.frac_degenerate.resize(R);
  res.lambda1_qr_median.resize(R);
  for (auto* v : {&res.angle_median, &res.angle_q05, &res.angle_min}) v->assign(R, nan);
  res.angle_histogram.assign(R * res.bins, 0.0);
  const ClvOptions co = clv_options(req);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t ir = 0; ir < R; ++ir) {
    control.check_cancelled();
    clv_row(res, ir, co);
    if (control.progress) control.progress->update(ir + 1, R);
  }
  res.clv_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // lambda1 beside them, from the batched tangent recorder on the same orbits (same r, same grid).
  MapOptions mo;
  mo.transient = req.transient;
  mo.iterations = req.iterations;
  mo.blocks = 10;
  mo.run.threads = control.threads;
  mo.run.cancel = control.cancel;
  res.exponents = map_exponents(ens, mo);
  res.summary = summarise(res.exponents, R, ens.initial.size());
  return res;
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
  c.array("lambda1_frac_positive", summary.frac_positive, {R}, "r", "1", "fraction of orbits with lambda1 > 3 err1 + 10/n");
  c.array("lambda1_qr_median", lambda1_qr_median, {R}, "r", per, "median of the forward-QR lambda1 over the window");
  c.array("angle_histogram", angle_histogram, {R, bins}, "r, angle bin over [0, pi/2]", "count",
          "CLV angles of the non-degenerate orbits per bin");
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

}  // namespace btob::lyapunov
