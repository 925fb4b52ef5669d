// SPDX-License-Identifier: GPL-3.0-or-later
// What the precision study's result says: its notes, the CSV table (tradeoff.csv), the arrays and attributes.
#include "precision/tradeoff.hpp"

#include "core/csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <string>

namespace btob::precision {

std::string TradeoffResult::notes(const TradeoffRequest& req) {
  std::string s =
      "btob precision study: symbol agreement with a 256-digit MPFR run of the same orbits, and the angle (rad) "
      "between the final states (median over orbits); lyapunov_error: largest |lambda1 - exact| on the sinks 1133 "
      "(r=0.15), 111333 (r=0.1), 132312 (r=0.5), weighted average of 1e5 steps, against log|l2/l1|/p of the period "
      "matrix in 60-digit MPFR (exponents are reported in double: 0 means below the double resolution, ~1e-16); "
      "lyapunov_error_near_neutral: the same on the weakly contracting sink 312^150 (period 152, lambda1 = -0.0116) at "
      "r = 0.171599 from the Section 4 grid's first point, 4e5 steps after 1e5, whatever the orbit does. ";
  s += fmt::format(
      "orbits={} random:{} seed={} iterations={} window test: 8 orbits of the Section 4 grid at "
      "the middle of window n, 20000+400n iterations, n in [{}]",
      req.orbits, req.orbits, req.seed, req.iterations, fmt::join(req.window_n, " "));
  return s;
}

std::string TradeoffResult::csv() const {
  std::string h = "method,decimal_digits,iterations_per_second";
  for (double x : r) h += fmt::format(",agree_min_r{0},agree_median_r{0},final_error_median_r{0}", x);
  core::CsvTable t(h + ",window_n_max,lyapunov_error,lyapunov_error_near_neutral");
  for (const TradeoffRow& row : rows) {
    std::string s = fmt::format("{},{},{:.4g}", row.method, row.digits, row.rate);
    for (std::size_t i = 0; i < row.agree_min.size(); ++i)
      s += fmt::format(",{},{},{:.3g}", row.agree_min[i], row.agree_median[i], row.error_median[i]);
    t.line(
        s +
        fmt::format(",{},{}", row.n_max < 0 ? std::string("") : std::to_string(row.n_max),
                    std::isnan(row.lyapunov_error) ? std::string("") : fmt::format("{:.3g}", row.lyapunov_error)) +
        (std::isnan(row.lyapunov_near_neutral) ? std::string(",") : fmt::format(",{:.3g}", row.lyapunov_near_neutral)));
  }
  return t.text();
}

void TradeoffResult::describe(core::Contents& c) const {
  const std::size_t M = rows.size(), R = r.size();
  c.array("r", r, {R}, "r", "1", "r values of the symbol comparison");
  c.array("decimal_digits", digits, {M}, "method", "digits", "decimal digits of the method's arithmetic");
  c.array("iterations_per_second", rate, {M}, "method", "1/s", "map iterations per second (all threads of the run)");
  c.array("agree_min", agree_min, {M, R}, "method, r", "iteration",
          "fewest leading symbols equal to the 256-digit reference's, over the orbits");
  c.array("agree_median", agree_median, {M, R}, "method, r", "iteration",
          "median number of leading symbols equal to the reference's");
  c.array("final_error_median", error_median, {M, R}, "method, r", "rad",
          "median angle between the final state and the reference's");
  c.array("window_n_max", window_n_max, {M}, "method", "1", "largest listed window n resolved (-1: not tested)");
  c.array("lyapunov_error", lyapunov_error, {M}, "method", "1/iteration (natural log)",
          "largest |lambda1 - exact| on the sinks 1133, 111333, 132312 (NaN: not tested)");
  c.array("lyapunov_error_near_neutral", lyapunov_near_neutral, {M}, "method", "1/iteration (natural log)",
          "|lambda1 - exact| on the weakly contracting sink 312^150 at r = 0.171599 (NaN: not tested)");
  c.text("method", method, "method", "name",
         "the method: algorithm (linear: Theorem 3.3's matrices; trig: Appendix A.1) / arithmetic, the coordinates "
         "of that axis");
  c.coordinate("method", "method");
  std::string names;
  for (const auto& row : rows) names += (names.empty() ? "" : ",") + row.method;
  c.attr("methods", names);
  c.attr("reference", std::string("mpfr:256"));
  c.attr("iterations", iterations);
}

}  // namespace btob::precision
