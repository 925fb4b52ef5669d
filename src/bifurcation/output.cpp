// SPDX-License-Identifier: GPL-3.0-or-later
// The bifurcation result's description: its arrays and attributes, and the points outside the range.
#include "bifurcation/bifurcation.hpp"

#include <fmt/format.h>

namespace btob::bifurcation {

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
