// SPDX-License-Identifier: GPL-3.0-or-later
// The bifurcation sweep's run: its parts (the kernel's density and raw tails per r value), their merge, and run().
#include "core/run.hpp"
#include "bifurcation/bifurcation.hpp"
#include "bifurcation/request_detail.hpp"
#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "reference/reference.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

namespace btob::bifurcation {

namespace {
using detail::Axis;
using detail::axis_of;

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

}  // namespace btob::bifurcation
