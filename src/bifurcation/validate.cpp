// SPDX-License-Identifier: GPL-3.0-or-later
// The bifurcation request's validation and its binned coordinate.
#include "bifurcation/bifurcation.hpp"
#include "bifurcation/request_detail.hpp"
#include "core/fields.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"

#include <fmt/format.h>

#include <numbers>

namespace btob::bifurcation {

namespace detail {
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
}  // namespace detail

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
  (void)detail::axis_of(*this);
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

}  // namespace btob::bifurcation
