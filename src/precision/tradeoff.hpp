// SPDX-License-Identifier: GPL-3.0-or-later
// The precision study (`btob precision`): speed against accuracy of each precision and algorithm.
// The same random orbits run in float, double, long double, float128, MPFR with 50 and 100 digits (the batched
// linear kernel) and with the trigonometric algorithm of Appendix A.1 (double); each is compared with a 256-digit
// MPFR run of the same orbits (how many symbols agree, the angle between the final states), timed, tested on the
// windows (ab)^n(cb)^n near 7 - 4 sqrt 3, and its Lyapunov exponent checked on three sinks against the exact
// eigenvalues of their period matrices.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::precision {

struct TradeoffRequest {
  long orbits = 16;                                    // random initial conditions per r, 1..4096
  long iterations = 3000;                              // symbols compared per orbit, 10..1000000
  std::vector<core::Decimal> r{0.11, 0.2, 0.3, 0.58};  // r values of the symbol comparison, each in (0, 1), as given
  std::vector<double> window_n{2, 3, 5, 8, 12, 20, 30, 45, 60, 80, 100, 125};  // integers 2..400
  std::uint64_t seed = 7;                                                      // seed of the random initial conditions

  void validate() const;
  template <class V> void fields(V&& v) {
    v("orbits", orbits, "random initial conditions per r");
    v("iterations", iterations, "symbols compared per orbit");
    v("r-values", r, "r values of the symbol comparison");
    v("window-n", window_n, "window indices n tested near 7-4*sqrt(3)");
    v("seed", seed, "seed of the random initial conditions");
  }
};

// One method (an arithmetic and an algorithm) against the reference.
struct TradeoffRow {
  std::string method;                         // linear/float .. linear/mpfr:100, trig/double
  int digits = 0;                             // decimal digits of the arithmetic
  double rate = 0;                            // iterations per second (all threads of the run)
  std::vector<long> agree_min, agree_median;  // [R] leading symbols equal to the reference's (min, median over orbits)
  std::vector<double> error_median;           // [R] median angle (rad) between the final state and the reference's
  double lyapunov_error = 0;         // largest |lambda1 - exact| on the three sinks; NaN for trig or off a sink
  double lyapunov_near_neutral = 0;  // |lambda1 - exact| on the weak sink 312^150 at r = 0.171599; NaN for trig
  int n_max = 0;                     // largest listed window n resolved (with every smaller listed n); -1 for trig
};

struct TradeoffResult {
  std::vector<TradeoffRow> rows;  // one per method (arithmetic and algorithm), in the order they ran
  // Flat views for describe(): [M] and [M, R], M methods in the order of `rows`, R r values.
  std::vector<double> r, digits, rate, agree_min, agree_median, error_median, lyapunov_error, lyapunov_near_neutral,
      window_n_max;
  std::vector<std::string> method;  // [M] the methods' names (TradeoffRow::method), the axis "method"
  long iterations = 0;              // symbols compared per orbit (the request's)

  // The CSV of results/precision/tradeoff.csv: one header line, a row per method (columns per r of `r`).
  std::string csv() const;
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv
  // What the columns measure and how (the manifest's "description"; the CSV itself has only its header line).
  static std::string notes(const TradeoffRequest& req);
  void describe(core::Contents& c) const;
};

TradeoffResult run(const TradeoffRequest& req, const core::RunControl& control = {});

// Its cost (core/work.hpp): one indivisible study whose time is mostly fixed parts (each method's window tests up
// to the largest window-n, its Lyapunov errors on the sinks, its throughput: about a minute whatever the orbits),
// which no short probe prices; so the request is its own probe (core::self_term): the first dry run of a request
// runs it once, and a completed run keeps its time in the rate cache for the dry runs after it.
core::Work work(const TradeoffRequest& req);

// lambda1 = log|l2/l1| / p of the periodic word `period` (symbols 1, 2, 3) at r (read from its decimal
// text to 60 digits: the r that T's runs read, not double's value widened), in MPFR with 60 digits: the period matrix,
// its dominant eigenvalue l1 by Newton on det(t - M) from the double estimate, and l2, l3 from t^2 - (tr M - l1) t +
// det M / l1 (a complex pair when the discriminant is negative, then |l2| = sqrt(det M / l1)).  MPFR's default
// precision is restored on return.
double exact_lambda1(const std::vector<int>& period, const core::Decimal& r);

}  // namespace btob::precision
