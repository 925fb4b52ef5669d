// SPDX-License-Identifier: GPL-3.0-or-later
// strip-orbits: what its result says (the panels' words, the CSV table, the arrays and attributes).
#include "orbits/orbits.hpp"

#include "core/csv.hpp"
#include "core/error_bar.hpp"

#include <fmt/format.h>

namespace btob::orbits {

const char* panel_word(attractors::Type t) {
  switch (t) {
    case attractors::Type::periodic: return "periodic";
    case attractors::Type::quasi_periodic: return "quasi-periodic";
    case attractors::Type::chaotic: return "chaotic";
    case attractors::Type::collapse: return "collapse";
    default: return "undecided";
  }
}

std::string StripOrbitsResult::csv() const {
  core::CsvTable csv("orbit,start_w1,start_w2,verdict,pattern,period,lambda1,err1,rotation,residual,detail");
  for (std::size_t o = 0; o < verdicts.size(); ++o) {
    const auto& v = verdicts[o];
    const core::ValueWithError l = core::with_error(v.lambda1, v.err1);  // the printed interval contains lambda1
    csv.row({fmt::format("{}", o + 1), fmt::format("{:.17g}", start_w1[o]), fmt::format("{:.17g}", start_w2[o]),
             panel_word(v.type), pattern[o], fmt::format("{}", v.period), l.value, l.error,
             fmt::format("{:.12g}", v.rotation), fmt::format("{:.3g}", v.residual), v.detail});
  }
  return csv.text();
}

void StripOrbitsResult::describe(core::Contents& c) const {
  const std::size_t n = start_w1.size(), t = static_cast<std::size_t>(request.tail);
  c.array("w1", w1, {n, t}, "orbit, step (the last tail iterations)", "1", "strip coordinate w1 of eq. (6.4)");
  c.array("w2", w2, {n, t}, "orbit, step (the last tail iterations)", "1",
          "strip coordinate w2 of eq. (6.4), in (-1, 1)");
  c.array("start_w1", start_w1, {n}, "orbit", "1", "initial w1");
  c.array("start_w2", start_w2, {n}, "orbit", "1", "initial w2");
  // The classifier's verdict on each orbit (the panel titles; also NAME.csv).
  c.text("verdict", verdict, "orbit", "name",
         "the classifier's verdict: periodic, quasi-periodic, chaotic, collapse or undecided");
  c.text("pattern", pattern, "orbit", "name",
         "paper notation of the periodic word (canonical; empty when not periodic)");
  c.array("period", period, {n}, "orbit", "iterations", "period of a periodic verdict in map iterations (0 otherwise)");
  c.array("rotation", rotation, {n}, "orbit", "turns/iteration",
          "weighted Birkhoff rotation number about the P2 centre (quasi-periodic verdicts; 0 when not computed)");
  c.attr("r", request.r);
  c.attr("orbits", request.orbits);
  c.attr("iterations", request.iterations);
  c.attr("tail", request.tail);
  c.attr("seed", static_cast<long>(request.seed));
  c.attr("w1_min", request.w1_range[0]);
  c.attr("w1_max", request.w1_range[1]);
  c.attr("initial_conditions",
         fmt::format("random strip points: w1 uniform in [{}, {}], w2 uniform in (-1, 1), seed {}", request.w1_range[0],
                     request.w1_range[1], request.seed));
  c.attr("periodic", static_cast<long>(periodic));
  c.attr("quasi_periodic", static_cast<long>(quasi_periodic));
  c.attr("other", static_cast<long>(other));
  c.attr("iteration_seconds", seconds);
}

}  // namespace btob::orbits
