// SPDX-License-Identifier: GPL-3.0-or-later
// The cost of a request that is not a sweep, before it runs: its work counted from its fields, in units of the routes
// it runs (map steps of the double derivative cocycle, particle collisions in MPFR at D digits, Ulam sample images),
// and for each route a probe: a short fixed run of that route, which io/rates.hpp times once per machine, build and
// thread count and keeps in a cache.  predicted time = sum over terms of units / (the route's units per second).
//
//   core::Work work(const Request&);   // in the request's namespace (found by argument-dependent lookup)
//
// A sweep (core/sweep.hpp) is predicted instead from a sample of its own items (core/estimate.hpp): its items differ
// in cost along the sweep (orbits that collapse early, windows whose cost grows with n), which a fixed route's rate
// cannot know.  Nothing here runs the request or writes anything.
#pragma once

#include "core/request.hpp"

#include <concepts>
#include <functional>
#include <string>
#include <vector>

namespace btob::core {

// One route's share of a request's work.
struct Term {
  // The route as the rate cache names it: what the speed of a unit depends on and nothing else ("lyapunov cocycle
  // mpfr:50", "particles events double").  Two terms of one route share one rate.
  std::string route;
  double units = 0;  // how many units this request runs on the route
  std::string what;  // the units in words, with how they are counted from the fields
  // The route's probe: runs a fixed run of the route (fixed r and point, never the request's own) of about n units
  // and returns the units it ran.  The calibration doubles n from 16 until one probe takes 0.1 s.
  std::function<double(double n, const RunControl&)> probe;
  bool probe_is_request = false;  // self_term: calibrating runs the request itself (no note before such a run)
  // A term priced by a cost model in a size instead of a route's rate (core/size_model.hpp), for a request that is
  // one indivisible computation whose cost grows with one size (a word's verdict with the word's length, the
  // thresholds with their digits): sized_run(s, control) runs an instance of size s (a prefix of the word, the
  // thresholds at s digits); the estimate times sizes from `smallest` up (about a second in all, never the
  // request itself when it is larger) and extrapolates to `size`.  No probe and no cache: units = 1 run.
  std::string size_parameter;
  double size = 0, smallest = 1;
  std::function<void(double size, const RunControl&)> sized_run;
  // When set, the time of an instance is proportional to work_of(size) (counted, not a power of the size: a word's
  // verdict walks the orbits for as many periods as its eigenvalue ratios need): the request is priced at the time
  // of the largest instance timed times work_of(size) / work_of(that instance's size), not by a power law in size.
  std::function<double(double size)> work_of;
};

struct Work {
  std::vector<Term> terms;
  // The run may stop early (a collapse, an orbit resolved in its first pass): the count is then an upper bound,
  // and `bound` says why.
  std::string bound;
  double output_bytes = 0;  // the arrays and tables the result writes (or prints), from the fields; figures excluded
  double peak_bytes = 0;    // the largest memory the run holds at once, from the fields
};

// A term whose probe is the request itself, for a request that is one indivisible computation whose cost depends on
// all its fields together (a word's verdict or stability window at D digits, four thresholds at D digits): no fixed
// run stands for it, so its route names the whole request and its rate is measured on it, one run per unit
// (the probe runs it max(1, n / 16) times).  The dry run of such a request costs at least one run of it.
template <class Req> Term self_term(const Req& req, std::string route, std::string what) {
  Term t;
  t.route = std::move(route);
  t.units = 1;
  t.what = std::move(what);
  t.probe_is_request = true;
  t.probe = [req](double n, const RunControl& c) {
    const long k = n < 32 ? 1L : static_cast<long>(n / 16);
    for (long i = 0; i < k; ++i) (void)run(req, c);  // the module's run, by argument-dependent lookup
    return static_cast<double>(k);
  };
  return t;
}

// A request whose cost work(request) predicts.
template <class Req>
concept Costed = requires(const Req& r) {
  { work(r) } -> std::convertible_to<Work>;
};

}  // namespace btob::core
