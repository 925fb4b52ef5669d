// SPDX-License-Identifier: GPL-3.0-or-later
// Stage 10 of `btob transfer` (stages.hpp): the transfer density against the empirical measure of `btob measure`
// (stats module) from an NxN grid of the request's Lebesgue rectangle, in total variation.
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"

#include "core/coords.hpp"
#include "iterate/ensemble.hpp"
#include "stats/stats.hpp"

#include <algorithm>
#include <numbers>

namespace btob::transfer {

namespace {

// The measure m on a coarser b1 x b2 grid (b1, b2 divide its bins).
stats::Measure coarsen(const stats::Measure& m, int b1, int b2) {
  stats::Measure c = m;
  c.bins_u = b1, c.bins_v = b2;
  c.mass.assign(static_cast<std::size_t>(b1) * static_cast<std::size_t>(b2), 0);
  const int f1 = m.bins_u / b1, f2 = m.bins_v / b2;
  for (int i = 0; i < m.bins_u; ++i)
    for (int j = 0; j < m.bins_v; ++j)
      c.mass[static_cast<std::size_t>(i / f1) * b2 + j / f2] += m.mass[static_cast<std::size_t>(i) * m.bins_v + j];
  return c;
}

// The initial conditions: a g x g grid of cell centres of the strip rectangle, or of the angles' chart.
std::vector<core::Vec3<double>> measure_grid(const TransferRequest& q, Domain dom) {
  const int g = q.measure_orbits;
  if (dom == Domain::strip) return iterate::strip_grid(g, g, q.w1_range[0], q.w1_range[1]);
  std::vector<core::Vec3<double>> u0;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      u0.push_back(core::from_angles<double>(std::numbers::pi / 2 * (i + 0.5) / g, std::numbers::pi * (j + 0.5) / g));
  return u0;
}

// The orbits' empirical measures on the boxes, averaged: each orbit weighs its initial condition's share of
// Lebesgue measure (equal cells: equal weights).
stats::Measure empirical(const TransferRequest& q, Domain dom, const Partition& part, const core::RunControl& control) {
  iterate::RunOptions opt;  // the orbits poll the run's token
  opt.threads = control.threads;
  opt.cancel = control.cancel;
  const auto series = stats::orbit_series(q.r, measure_grid(q, dom), q.measure_transient, q.measure_iterations, opt);
  const stats::Chart chart = dom == Domain::strip ? stats::Chart::strip : stats::Chart::angles;
  stats::Measure mean;
  for (std::size_t o = 0; o < series.size(); ++o) {
    const auto m = stats::empirical_measure(series[o], chart, static_cast<int>(part.n1), static_cast<int>(part.n2));
    if (o == 0) mean = m, std::fill(mean.mass.begin(), mean.mass.end(), 0.0), mean.outside = 0, mean.points = 0;
    for (std::size_t i = 0; i < m.mass.size(); ++i) mean.mass[i] += m.mass[i] / static_cast<double>(series.size());
    mean.outside += m.outside / static_cast<double>(series.size());
    mean.points += m.points;
  }
  return mean;
}

}  // namespace

MeasureComparison compare_with_empirical(const TransferRequest& q, Domain dom, const Partition& part,
                                         const std::vector<double>& density, const core::RunControl& control) {
  const stats::Measure orbits = empirical(q, dom, part, control);
  stats::Measure ulam = orbits;  // the same bins, the transfer density's masses
  double total = 0;
  for (double v : density) total += v;
  for (std::size_t i = 0; i < ulam.mass.size(); ++i) ulam.mass[i] = density[i] / total;
  ulam.outside = 0;
  MeasureComparison out;
  out.tv_boxes = stats::total_variation(ulam, orbits);
  out.tv_coarse = stats::total_variation(coarsen(ulam, q.tv_bins, q.tv_bins), coarsen(orbits, q.tv_bins, q.tv_bins));
  out.points = orbits.points;
  return out;
}

}  // namespace btob::transfer
