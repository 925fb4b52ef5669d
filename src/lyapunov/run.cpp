// SPDX-License-Identifier: GPL-3.0-or-later
// The Lyapunov requests' runs: one orbit, the maps' parts and merges, the hyperbolicity images and CLV sweeps.
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
template <class T> void all_finite(const T& values, const std::string& what) {
  for (double v : values)
    if (!std::isfinite(v))
      throw std::domain_error(
          fmt::format("{}: a non-finite exponent; this precision cannot represent the run "
                      "(use a wider --precision)",
                      what));
}
}  // namespace

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

double MapRequest::map_steps() const {
  const double orbits = static_cast<double>(iterate::parse_grid(grid, seed, "grid").size());
  return static_cast<double>(r_count) * orbits * (static_cast<double>(transient) + static_cast<double>(iterations));
}

double StripRequest::map_steps() const {
  const core::Grid g = spec();
  return static_cast<double>(g.axis1.cells) * static_cast<double>(g.axis2.cells) *
         (static_cast<double>(transient) + static_cast<double>(iterations));
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

// The parts' per-r summaries of lambda1 (Part::summary, one row per item) in item order: lyapunov-map's and
// hyperbolicity-orbits', each computed in its part from the r value's own orbits.
template <class Part>
RSummary merge_summaries(const std::vector<Part>& parts, const std::vector<core::ItemRef>& order) {
  RSummary s;
  for (auto f : {&RSummary::min, &RSummary::median, &RSummary::max, &RSummary::err_min, &RSummary::err_median,
                 &RSummary::err_max, &RSummary::frac_positive, &RSummary::frac_zero, &RSummary::frac_negative})
    s.*f = core::merge_rows<Part, double>(parts, order, 1,
                                          [f](const Part& p) -> const std::vector<double>& { return p.summary.*f; });
  return s;
}

// The per-r rows of the parts (summary), in item order, and the float check's counts.
void merge_per_r(MapResult& res, const std::vector<MapPart>& parts, std::size_t R) {
  const auto order = core::item_order(parts, R);
  res.summary = merge_summaries(parts, order);
  res.summary_lines = core::merge_rows<MapPart, std::string>(
      parts, order, 1, [](const MapPart& p) -> const std::vector<std::string>& { return p.summary_lines; });
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
  MapPart part{items, std::move(res.exponents), {}, {}, 0, 0, static_cast<std::size_t>(-1), res.iteration_seconds};
  part.summary = summarise(part.exponents, items.size(), ens.initial.size());
  part.summary_lines.reserve(items.size());
  for (std::size_t j = 0; j < items.size(); ++j) part.summary_lines.push_back(summary_line(ens.r[j], part.summary, j));
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

// ---- hyperbolicity -----------------------------------------------------------------------------------------------

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
      p.expanding += sv.s1 >= 1;
      p.s1_min = std::min(p.s1_min, sv.s1);
      p.s1_max = std::max(p.s1_max, sv.s1);
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
  for (std::size_t i = 0; i < grid.size(); ++i) std::tie(m.w1[i], m.w2[i]) = core::strip<double>(grid[i]);
  for (long i = 0; i < s.axis1.cells; ++i)
    res.w1_cell.push_back(m.w1[static_cast<std::size_t>(i * s.axis2.cells)]);  // (i, j) at i n2 + j
  for (long j = 0; j < s.axis2.cells; ++j) res.w2_cell.push_back(m.w2[static_cast<std::size_t>(j)]);
  long expanding = 0;
  res.s1_min = std::numeric_limits<double>::infinity(), res.s1_max = -res.s1_min;
  for (const auto& p : parts) {
    expanding += p.expanding;
    res.s1_min = std::min(res.s1_min, p.s1_min), res.s1_max = std::max(res.s1_max, p.s1_max);
    res.seconds = std::max(res.seconds, p.seconds);  // the slowest part
  }
  m.expanding_fraction = static_cast<double>(expanding) / static_cast<double>(grid.size());
  return res;
}

HyperbolicityResult run(const HyperbolicityRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

// ---- hyperbolicity-orbits ---------------------------------------------------------------------------------------

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
  const ClvRows rows = covariant_vectors_batched(ens.r, ens.initial, detail::clv_options(req), run);
  for (std::size_t j = 0; j < R; ++j) clv_row(res, j, rows[j], B);
  res.clv_seconds = core::seconds_since(t0);
  // lambda1 beside them, from the fused cocycle kernel (map_exponents) on the same orbits (same r, same grid).
  MapOptions mo;
  mo.transient = req.transient;
  mo.iterations = req.iterations;
  mo.blocks = 10;
  mo.run.threads = control.threads;
  mo.run.cancel = control.cancel;
  OrbitExponents e = map_exponents(ens, mo);
  e.iterations = req.iterations;  // the classification's floor 10/n (summarise)
  res.summary = summarise(e, R, ens.initial.size());
  res.orbit_lambda1 = std::move(e.lambda1);  // the one exponent the result keeps per orbit (a dataset)
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
  const std::size_t I = ens.initial.size();
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
  res.summary = merge_summaries(parts, order);
  res.angle_histogram = rows(&P::angle_histogram, res.bins);
  res.orbit_frac_expanding = rows(&P::orbit_frac_expanding, I);
  res.orbit_angle_median = rows(&P::orbit_angle_median, I);
  res.orbit_angle_q05 = rows(&P::orbit_angle_q05, I);
  res.orbit_lambda1_qr = rows(&P::orbit_lambda1_qr, I);
  res.orbit_lambda2_qr = rows(&P::orbit_lambda2_qr, I);
  res.orbit_lambda1 = rows(&P::orbit_lambda1, I);
  res.orbit_degenerate = core::merge_rows<P, std::uint8_t>(
      parts, order, I, [](const P& p) -> const std::vector<std::uint8_t>& { return p.orbit_degenerate; });
  for (const P& p : parts) {
    res.threads = std::max(res.threads, p.threads);
    res.clv_seconds = std::max(res.clv_seconds, p.clv_seconds);  // the slowest part
  }
  return res;
}

HyperbolicityOrbitsResult run(const HyperbolicityOrbitsRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

}  // namespace btob::lyapunov
