// SPDX-License-Identifier: GPL-3.0-or-later
// Bifurcation diagrams: validation, the kernel run with the density recorder, the trigonometric route.
#include "bifurcation/bifurcation.hpp"

#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "reference/reference.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

namespace btob::bifurcation {

namespace {
struct Axis {
  iterate::Coord coord;
  double lo, hi;
};

// The coordinate and its default range: theta in [0, pi/2], phi in [0, pi], log10 theta in [-16, 0.25],
// w1 in [-4, 4], w2 in [-1, 1]; a request's range replaces it.
Axis axis_of(const Request& req) {
  iterate::Coord c = iterate::parse_coord(req.coord, "coord");
  if (req.log) {
    if (c != iterate::Coord::theta) throw core::InvalidField("log", "--log with coord " + req.coord, "coord theta");
    c = iterate::Coord::log10_theta;
  }
  Axis a{c, 0, std::numbers::pi / 2};
  if (c == iterate::Coord::phi) a.hi = std::numbers::pi;
  if (c == iterate::Coord::log10_theta) a.lo = -16, a.hi = 0.25;
  if (c == iterate::Coord::w1) a.lo = -4, a.hi = 4;
  if (c == iterate::Coord::w2) a.lo = -1, a.hi = 1;
  if (!req.range.empty()) {
    a.lo = req.range[0];
    a.hi = req.range[1];
  }
  return a;
}

template <class T>
void run_kernel(const iterate::Ensemble& ens, long iterations, iterate::DensityRecorder& dens,
                iterate::TailRecorder* raw, const iterate::RunOptions& opt) {
  if (raw) {
    iterate::Both<iterate::DensityRecorder, iterate::TailRecorder> both(dens, *raw);
    iterate::run<T>(ens, iterations, both, opt);
  } else {
    iterate::run<T>(ens, iterations, dens, opt);
  }
}

// Calls f with a null T* for the precision's scalar type, MPFR's digits set for the call only.
template <class F> auto with_scalar(const core::Precision& p, F&& f) {
  switch (p.kind) {
    case core::Precision::Kind::f32: return f(static_cast<float*>(nullptr));
    case core::Precision::Kind::f80: return f(static_cast<long double*>(nullptr));
    case core::Precision::Kind::f128: return f(static_cast<core::float128*>(nullptr));
    case core::Precision::Kind::mpfr: {
      core::MpfrDigits digits(p.mpfr_digits);
      return f(static_cast<core::mpfr_float*>(nullptr));
    }
    default: return f(static_cast<double*>(nullptr));
  }
}
}  // namespace

double Request::map_steps() const {
  const double orbits = static_cast<double>(iterate::parse_grid(grid, seed, "grid").size());
  return static_cast<double>(r_count) * orbits * static_cast<double>(iterations);
}

void Request::validate() const {
  core::require_at_least(r_count, 1, "r-count");
  // Checked here, before an MPI job's checkpoint, not only where the r values are made: every rank refuses it alike.
  core::require_r_range(r_min, r_max, r_count);
  core::require_at_least(iterations, 1, "iterations");
  if (tail < 1 || tail > iterations)
    throw core::InvalidField("tail", std::to_string(tail), fmt::format("1 <= tail <= iterations = {}", iterations));
  if (bins < 1 || bins > 100000) throw core::InvalidField("bins", std::to_string(bins), "1..100000");
  const core::Precision prec = core::parse_precision(precision, "precision");
  if (!range.empty() && (range.size() != 2 || !(range[0] < range[1])))
    throw core::InvalidField("range", fmt::format("{} values", range.size()), "two numbers lo hi with lo < hi");
  if (!range.empty()) core::require_distinct(range[0], range[1], bins, "bins", "range");
  (void)axis_of(*this);
  if (algorithm != "linear" && algorithm != "trig")
    throw core::InvalidField("algorithm", "'" + algorithm + "'", "linear (Theorem 3.3) or trig (Appendix A.1)");
  if (algorithm == "trig" &&
      (raw || (prec.kind != core::Precision::Kind::f64 && prec.kind != core::Precision::Kind::f80)))
    throw core::InvalidField("algorithm", "trig with " + std::string(raw ? "--raw" : prec.name()),
                             "trig in double or long-double, without raw tails");
  iterate::Ensemble probe;
  probe.initial = iterate::parse_grid(grid, seed, "grid");
  iterate::checked_bytes(static_cast<std::size_t>(r_count) * probe.initial.size(), 64, "r-count x grid");
  if (raw)
    iterate::checked_bytes(static_cast<std::size_t>(r_count) * probe.initial.size() * static_cast<std::size_t>(tail), 8,
                           "r-count x grid x tail (raw)");
  if (attractors) {  // classify runs in double, on the linear map, from transient iterations - tail >= 1
    if (prec.kind != core::Precision::Kind::f64 || algorithm != "linear")
      throw core::InvalidField("attractors", "with " + std::string(prec.name()) + " and algorithm " + algorithm,
                               "precision double and algorithm linear (classify's)");
    if (tail >= iterations)
      throw core::InvalidField("attractors", fmt::format("with tail = iterations = {}", iterations),
                               "tail < iterations (classify's transient iterations - tail >= 1)");
    core::require_r_exponents(r_min, prec, "r-min", {});  // classify computes in double only
  }
}

Part run_part(const Request& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  req.validate();
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  const Axis ax = axis_of(req);
  iterate::Ensemble ens;  // the part's r values with the whole request's grid
  ens.set_r_range(req.r_min, req.r_max, req.r_count, &items);
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  ens.grid_description = req.grid;
  ens.seed = req.seed;
  Part part;
  part.items = items;

  iterate::RunOptions opt;
  std::size_t degenerate = 0;
  opt.degenerate = &degenerate;
  opt.threads = control.threads;
  opt.progress = control.progress;
  opt.cancel = control.cancel;
  const int threads = core::thread_count(control.threads);
  iterate::DensityRecorder dens(ax.coord, ens, req.iterations, req.tail, static_cast<std::size_t>(req.bins), ax.lo,
                                ax.hi, threads);
  std::unique_ptr<iterate::TailRecorder> raw;
  if (req.raw) raw = std::make_unique<iterate::TailRecorder>(ax.coord, ens.orbits(), req.iterations, req.tail);

  const auto t1 = std::chrono::steady_clock::now();
  part.broken.assign(ens.r.size(), 0);
  if (ens.r.empty()) {
    // a part with no r value (more processes than r values): nothing to run
  } else if (req.algorithm == "trig") {
    core::check_cancel(control.cancel);
    part.broken = prec.kind == core::Precision::Kind::f80
                      ? reference::trig_density<long double>(ens, req.iterations, dens, threads, control.cancel)
                      : reference::trig_density<double>(ens, req.iterations, dens, threads, control.cancel);
    // Re acos lies in [0, pi]: the whole range, so that nothing MATLAB would draw falls outside.
    core::check_cancel(control.cancel);
    part.matlab =
        reference::trig_density_matlab(ens, req.iterations, req.tail, ax.coord == iterate::Coord::phi,
                                       static_cast<int>(req.bins), 0.0, std::numbers::pi, threads, control.cancel);
  } else {
    with_scalar(prec, [&]<class T>(T*) { run_kernel<T>(ens, req.iterations, dens, raw.get(), opt); });
  }
  part.iteration_seconds = core::seconds_since(t1);
  part.density = dens.merge();
  part.underflow = std::move(dens.under);
  part.overflow = std::move(dens.over);
  if (raw) part.tail = std::move(raw->out);
  part.degenerate = degenerate;
  return part;
}

namespace {
// The trigonometric route's MATLAB image (Figure 4.7), rows by item.
reference::MatlabTrigImage merge_matlab(const std::vector<Part>& parts, const std::vector<core::ItemRef>& order,
                                        std::size_t bins) {
  reference::MatlabTrigImage m;
  using M = reference::MatlabTrigImage;
  const auto per_r = [&](std::vector<std::uint64_t> M::*field) {
    return core::merge_rows<Part, std::uint64_t>(
        parts, order, 1, [field](const Part& p) -> auto& { return p.matlab.*field; });
  };
  m.counts = core::merge_rows<Part, std::uint32_t>(
      parts, order, bins, [](const Part& p) -> auto& { return p.matlab.counts; });
  m.complex_orbits = per_r(&M::complex_orbits);
  m.nan_points = per_r(&M::nan_points);
  m.outside = per_r(&M::outside);
  m.stalled = per_r(&M::stalled);
  return m;
}
}  // namespace

Result merge(const Request& req, std::vector<Part> parts) {
  req.validate();
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  const Axis ax = axis_of(req);
  Result res;
  iterate::Ensemble& ens = res.ensemble;
  ens.set_r_range(req.r_min, req.r_max, req.r_count);
  ens.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  ens.grid_description = req.grid;
  ens.seed = req.seed;
  const auto order = core::item_order(parts, ens.r.size());
  const std::size_t bins = static_cast<std::size_t>(req.bins);
  res.density = core::merge_rows<Part, std::uint32_t>(
      parts, order, bins, [](const Part& p) -> auto& { return p.density; });
  res.underflow = core::merge_rows<Part, std::uint64_t>(
      parts, order, 1, [](const Part& p) -> auto& { return p.underflow; });
  res.overflow = core::merge_rows<Part, std::uint64_t>(
      parts, order, 1, [](const Part& p) -> auto& { return p.overflow; });
  res.broken = core::merge_rows<Part, std::uint64_t>(
      parts, order, 1, [](const Part& p) -> auto& { return p.broken; });
  if (req.raw)
    res.tail = core::merge_rows<Part, double>(
        parts, order, ens.initial.size() * static_cast<std::size_t>(req.tail),
        [](const Part& p) -> auto& { return p.tail; });
  if (req.algorithm == "trig") res.matlab = merge_matlab(parts, order, bins);
  for (const Part& p : parts) {
    res.degenerate += p.degenerate;
    res.iteration_seconds = std::max(res.iteration_seconds, p.iteration_seconds);  // the slowest part's wall time
  }
  res.r_min = req.r_min;
  res.r_max = req.r_max;
  res.coord = iterate::coord_name(ax.coord);
  res.lo = ax.lo;
  res.hi = ax.hi;
  res.bins = bins;
  for (std::size_t i = 0; i < bins; ++i)  // bin i covers [lo + i h, lo + (i+1) h): its centre
    res.bin_centre.push_back(ax.lo + (static_cast<double>(i) + 0.5) * (ax.hi - ax.lo) / static_cast<double>(bins));
  res.vlines = req.vline;
  res.raw = req.raw;
  res.scalar_type = prec.name();
  res.algorithm = req.algorithm;
  res.iterations = req.iterations;
  res.tail_length = req.tail;
  // The interval between exact power-of-two rescalings (0: the trigonometric route normalises every collision).
  res.renormalisation_interval = req.algorithm == "trig" ? 0 : with_scalar(prec, [&]<class T>(T*) {
    return iterate::renormalisation_interval<T>(ens.r);
  });
  return res;
}

Result run(const Request& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

std::uint64_t Result::points_below() const {
  std::uint64_t n = 0;
  for (auto v : underflow) n += v;
  return n;
}
std::uint64_t Result::points_above() const {
  std::uint64_t n = 0;
  for (auto v : overflow) n += v;
  return n;
}

void Result::describe(core::Contents& c) const {
  const std::size_t R = ensemble.r.size(), I = ensemble.initial.size();
  const std::string unit = coord == "log10_theta" ? "log10(rad)" : (coord == "w1" || coord == "w2") ? "1" : "rad";
  c.array("density", density, {R, bins}, "r, bin of " + coord, "count",
          fmt::format("tail points per bin; bin i covers [lo + i h, lo + (i+1) h), h = (hi - lo)/bins, the last bin "
                      "also holds hi ({} in {})",
                      coord, unit));
  c.array("r", ensemble.r, {R}, "r", "1", "restitution coefficients (the image's columns)");
  c.array("bin_centre", bin_centre, {bins}, "bin of " + coord, unit,
          "centre of each bin of " + coord + " (the image's rows)");
  c.coordinate("bin of " + coord, "bin_centre");
  c.array("underflow", underflow, {R}, "r", "count", "tail points below lo (or NaN) at each r");
  c.array("overflow", overflow, {R}, "r", "count", "tail points above hi at each r");
  c.array("vlines", vlines, {vlines.size()}, "line", "1", "r values drawn as vertical lines");
  c.array("broken", broken, {R}, "r", "count", "orbits the trigonometric algorithm lost (acos out of its domain)");
  if (!matlab.counts.empty()) {
    c.array("density_matlab", matlab.counts, {R, bins}, "r, bin of " + coord + " over [0, pi]", "count",
            "what the paper's MATLAB code draws: Re acos of the complex continuation past acos's domain");
    c.array("complex_orbits", matlab.complex_orbits, {R}, "r", "count", "orbits that took a complex acos at some step");
    c.array("nan_points_matlab", matlab.nan_points, {R}, "r", "count", "tail values that were NaN (not in the image)");
    c.array("outside_matlab", matlab.outside, {R}, "r", "count", "tail values outside [0, pi]");
    c.array("stalled_matlab", matlab.stalled, {R}, "r", "count", "tail states never reached (no b-collision any more)");
  }
  if (raw)
    c.array("tail", tail, {R, I, static_cast<std::size_t>(tail_length)}, "r, initial condition, step", unit,
            "the last values of the coordinate of every orbit");
  c.attr("r_min", r_min);
  c.attr("r_max", r_max);
  c.attr("r_count", static_cast<long>(R));
  c.attr("grid", ensemble.grid_description);
  c.attr("initial_conditions", static_cast<long>(I));
  c.attr("seed", static_cast<long>(ensemble.seed));
  c.attr("iterations", iterations);
  c.attr("tail", tail_length);
  c.attr("coord", coord);
  c.attr("range_lo", lo);
  c.attr("range_hi", hi);
  c.attr("bins", static_cast<long>(bins));
  c.attr("algorithm", algorithm);
  c.attr("renormalisation_interval", renormalisation_interval);
  c.attr("points_below_range", static_cast<long>(points_below()));
  c.attr("points_above_range", static_cast<long>(points_above()));
  c.attr("degenerate_orbits", static_cast<long>(degenerate));
  c.attr("iteration_seconds", iteration_seconds);
}

}  // namespace btob::bifurcation
