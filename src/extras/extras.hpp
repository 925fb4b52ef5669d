// SPDX-License-Identifier: GPL-3.0-or-later
// What a command adds to a result beyond its describe(), where it needs the request: the named r overlays drawn
// on figures (thresholds, windows, stripes), per-command attributes, and the attractor of every orbit of
// lyapunov-map and bifurcation (their `attractors` field: classify's verdict, floor 4, which their own floor-3 runs
// cannot call).  The one route of the command line and the Python binding, so both write the same arrays and
// attributes.
#pragma once

#include "attractors/attractors.hpp"
#include "bifurcation/bifurcation.hpp"
#include "core/request.hpp"
#include "core/result.hpp"
#include "lyapunov/requests.hpp"
#include "precision/tradeoff.hpp"
#include "windows/requests.hpp"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace btob::extras {

// The names of the overlays ("stripes, thresholds, windows").
std::string overlay_names();
// The lines of the named overlays inside [r_min, r_max], flattened as (r, colour) pairs (colour 0 red, 1 blue,
// 2 grey), one per r value (a value of two overlays once); `labels` (when given) gets what each line is.  An
// unknown name throws core::InvalidField("overlay", ...).  `cancel` is polled while they are computed (the windows'
// bounds take ~1 s of one core the first time, spread over `threads`: 0 = all cores).
std::vector<double> overlay_values(const std::vector<std::string>& names, double r_min, double r_max,
                                   std::vector<std::string>* labels = nullptr,
                                   const core::CancelToken* cancel = nullptr, int threads = 1);

// The attractor of every orbit of an ensemble (orbit o = r index * initial conditions + initial condition index):
// attractors::classify at each r with `options`, the orbit's verdict named as `btob classify` names it (its pattern:
// "132^2", "1" for a collapse, "P2 invariant curves", "chaotic"; "undecided" when classify could not decide).
// Attractors are indexed over the whole ensemble: 0 is "undecided", then one per (type, key) of classify's verdicts
// in that order (attractors::collect's order at one r), the same index at every r.
struct OrbitAttractors {
  std::vector<std::uint32_t> label;     // [r, initial condition]: the index of the orbit's attractor
  std::vector<std::uint32_t> count;     // [r, attractor]: orbits of each attractor at each r
  std::vector<std::string> name, type;  // [attractor]: classify's pattern and type (attractors::type_name)
  std::vector<std::uint32_t> period;    // [attractor]: map iterations per period (1 for a collapse, 0 when none)
  std::size_t r_count = 0, n_ic = 0;    // the ensemble's r values and initial conditions
  attractors::Options options;          // what classify ran with
  void add_to(core::Contents& c) const;
};
OrbitAttractors orbit_attractors(const iterate::Ensemble& e, const attractors::Options& options,
                                 const core::RunControl& control);
// classify's options of the attractors field: lyapunov-map's transient and iterations, bifurcation's transient
// iterations - tail and iterations tail; max-period min(256, iterations) (a period longer than the window cannot
// return within it), the other thresholds at classify's defaults.
attractors::Options attractor_options(const lyapunov::MapRequest& req);
attractors::Options attractor_options(const bifurcation::Request& req);

struct Extras {
  bool has_overlay = false;
  bool has_attractors = false;
  OrbitAttractors attractors;         // when has_attractors (the attractors arrays view it)
  std::vector<double> overlay_lines;  // the storage the overlay_lines array views: keep Extras alive with the Contents
  std::vector<std::string> overlay_labels;  // what each line is (the overlay_labels texts view it)
  core::Attrs attrs;                        // set after the provenance and kind/name/... attributes (they override)
  // Adds the overlay_lines array (when the command has one) to `c`.
  void add_to(core::Contents& c) const;
  // Sets the attributes on `a`.
  void apply(core::Attrs& a) const {
    for (const auto& [k, v] : attrs) a[k] = v;
  }
};

// Unknown overlay names throw core::InvalidField("overlay", ...) without computing any line.  A command calls it
// before its run (an unknown name fails before any work) and of() after it, on MPI rank 0 only (the windows
// overlay's ~1 s of multiprecision root finding shared by the ranks before the run: share_overlays).
void check_overlays(const std::vector<std::string>& names);
template <class Req> void check(const Req& req) {
  if constexpr (requires { req.overlay; }) check_overlays(req.overlay);
}

// The overlays a request draws: bifurcation's --overlay, lyapunov-map's (thresholds and windows unless named).
std::vector<std::string> overlays_of(const bifurcation::Request& req);
std::vector<std::string> overlays_of(const lyapunov::MapRequest& req);

// Every rank's bytes on every rank, in rank order (a collective: io::Ranks::all_gather under mpirun).
using AllGather = std::function<std::vector<std::vector<char>>(std::vector<char>)>;
// Under mpirun, before a sweep's run, on every rank: the windows overlay's bounds that of() will read on rank 0
// (windows::window_overlay_last_n of r_min), computed in shares (n dealt round robin from the largest, rank k's
// every P-th) and exchanged, each rank's remembered by all (windows::remember_window_overlay_bounds; the same
// program's same computation, sent as bytes: bitwise what rank 0 would compute).  Rank 0 then does not compute them
// alone after the gather (~0.75 s of one core over the whole r range, most of it MPFR, which runs on one thread per
// process).  A collective when `names` holds "windows" (the same on every rank: it depends on the request alone);
// nothing otherwise.  Returns the seconds this rank spent on its own share (the exchange's wait for the others, who
// may have started later, apart); 0 when nothing was shared.
double share_window_bounds(const std::vector<std::string>& names, double r_min, std::size_t rank, std::size_t ranks,
                           const AllGather& all_gather, const core::RunControl& control);
template <class Req>
double share_overlays(const Req& req, std::size_t rank, std::size_t ranks, const AllGather& all_gather,
                      const core::RunControl& control) {
  if constexpr (requires { overlays_of(req); })
    return share_window_bounds(overlays_of(req), static_cast<double>(req.r_min), rank, ranks, all_gather, control);
  return 0;
}

// Per request type (overlay lines computed here, with `control`'s cancellation and threads).  Requests without
// extras get none.
template <class Req> Extras of(const Req&) { return {}; }
Extras of(const bifurcation::Request& req, const core::RunControl& control = {});
Extras of(const lyapunov::MapRequest& req, const core::RunControl& control = {});
Extras of(const lyapunov::StripRequest& req);
Extras of(const precision::TradeoffRequest& req);
Extras of(const windows::BoundPrecisionRequest& req);
// After the run, with its result: of(req) (the overloads above: a call in a template binds to those declared before
// it), and where the request asks for them (lyapunov-map and bifurcation with `attractors`) the attractor of every
// orbit of the result's ensemble, classified with `control`'s threads.
template <class Req, class Res> Extras of(const Req& req, const Res&, const core::RunControl&) { return of(req); }
Extras of(const lyapunov::MapRequest& req, const lyapunov::MapResult& res, const core::RunControl& control);
Extras of(const bifurcation::Request& req, const bifurcation::Result& res, const core::RunControl& control);

}  // namespace btob::extras
