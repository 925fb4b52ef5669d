// SPDX-License-Identifier: GPL-3.0-or-later
// Individual orbits at fixed r in the strip (w1, w2) of eq. (6.4), Section 6.2 (Figures 6.9-6.11): the last
// `tail` states of orbits started from seeded random points of the strip, each with the verdict of the
// attractor classifier (src/attractors), which is what titles each panel "periodic" or "quasi-periodic".
#pragma once

#include "attractors/attractors.hpp"
#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::orbits {

// Conventions.
//  * Initial conditions: w1 uniform in [w1-min, w1-max], w2 uniform in (-1, 1), from a counter-based generator
//    seeded by (seed, orbit index): the same seed gives the same points on any thread count.  The paper
//    draws "randomly in the strip" without saying how; the range is recorded in the result.
//  * States: iterations k = 0 .. iterations; the tail holds k = iterations - tail + 1 .. iterations (the
//    paper: 5000 iterations, the last 2000 drawn).
struct StripOrbitsRequest {
  double r = 0.2;                       // restitution coefficient, in (0, 1)
  long orbits = 10;                     // number of orbits, 1 .. 1000
  long iterations = 5000;               // map iterations per orbit, tail .. 1e7
  long tail = 2000;                     // last states kept per orbit, 1 .. iterations (and orbits * tail <= 1e8)
  std::uint64_t seed = 1;               // seed of the initial conditions
  std::vector<double> w1_range{-2, 2};  // initial w1 range a,b (strip units), a < b, |a|, |b| <= 1e6

  void validate() const;
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient in (0, 1)");
    v("orbits", orbits, "number of orbits from random points of the strip, 1..1000");
    v("iterations", iterations, "map iterations per orbit, tail..1e7");
    v("tail", tail, "last states kept per orbit, 1..iterations");
    v("seed", seed, "seed of the random initial points");
    v("w1-range", w1_range, "initial points: w1 range a,b");
  }
};

struct StripOrbitsResult {
  StripOrbitsRequest request;              // the request, as run (validated)
  std::vector<double> start_w1, start_w2;  // [orbits]: the initial points
  std::vector<double> w1, w2;              // [orbits x tail], row-major: orbit o, state iterations - tail + 1 + j
  std::vector<attractors::OrbitVerdict> verdicts;  // [orbits]: the classifier's verdict (transient = iterations)
  std::vector<std::string> pattern;                // [orbits]: paper notation of the periodic word ("" otherwise)
  std::vector<std::string> verdict;                // [orbits]: panel_word of the verdict (the panel titles)
  std::vector<std::uint32_t> period;               // [orbits]: the verdict's period (map iterations; 0 when none)
  std::vector<double> rotation;  // [orbits]: the verdict's rotation number (turns per iteration; 0 when none)
  std::size_t periodic = 0, quasi_periodic = 0, other = 0;  // summary counts
  double seconds = 0;                                       // wall time of iteration and classification

  // One CSV line per orbit: where it started and what the classifier says (the panel titles).
  std::string csv() const;
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv
  void describe(core::Contents& c) const;
};

// Throws core::InvalidField (field named as the flag) on invalid input; core::Cancelled when cancelled.
StripOrbitsResult run(const StripOrbitsRequest& request, const core::RunControl& control = {});
// Its cost (core/work.hpp): orbits x iterations map steps of the tails, which the classifier then runs again from
// each start (transient = iterations, then its window and pass 2), priced together by a probe of 10 orbits at r = 0.2.
core::Work work(const StripOrbitsRequest& request);

// The paper's word for a verdict: "periodic", "quasi-periodic", "chaotic", "collapse" or "undecided".
const char* panel_word(attractors::Type t);

}  // namespace btob::orbits
