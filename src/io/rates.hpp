// SPDX-License-Identifier: GPL-3.0-or-later
// The calibrated speed of each route (core/work.hpp) and its cache: how a request that is not a sweep is priced before
// it runs (`--dry-run`, btob.estimate(), the note before a run predicted over 10 minutes).
//
// A route's rate (units per second) is measured the first time a request needs it, by timing the route's probe (a
// short fixed run, never the request's own inputs) grown until one probe takes 0.1 s, and kept in
// $XDG_CACHE_HOME/btob/rates.json ($HOME/.cache/btob/rates.json when XDG_CACHE_HOME is unset).  A rate's key is what
// invalidates it: the btob version and git commit, the CPU model (/proc/cpuinfo), the threads and the route.  The file
// is rewritten whole (a temporary file renamed into place); a file that does not parse, or was not written by this
// format, is recalibrated over, never an error; a directory that cannot be written just means no cache.
#pragma once

#include "core/request.hpp"
#include "core/work.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace btob::io {

// The cache file, or an empty path when neither XDG_CACHE_HOME nor HOME is set.
std::filesystem::path rates_path();

// The cache key of `route` run on `threads` threads by this build on this CPU.
std::string rate_key(const std::string& route, int threads);

// One route's rate and where it came from.
struct RouteRate {
  double units_per_second = 0;
  bool cached = false;                        // read from the cache; else calibrated now by its probe
  double probe_units = 0, probe_seconds = 0;  // the probe that measured it (now or when it was cached)
  std::string model;  // a sized term's (core::Term::sized_run): how its time was fitted, "extrapolated from ..."
};

// The rate of `term`'s route on `threads` threads (control.threads is set to it for the probe): the cached one, else
// the probe's, then cached.  Throws core::Cancelled when the control is cancelled during a probe.
RouteRate route_rate(const core::Term& term, const core::RunControl& control, int threads);

// Keeps a rate measured by a completed run of the request itself (a core::self_term's route: the request is its own
// probe), so that its dry run after a run reads the cache instead of running it again.
void remember_rate(const core::Term& term, int threads, double units, double seconds);

// A request's predicted cost: the work, each term's rate, and their sum.
struct WorkEstimate {
  core::Work work;
  std::vector<RouteRate> rates;  // one per term of work
  int threads = 1;
  double predicted_seconds = 0;
  // The dry run's report: work per term, rate and its source, predicted time, output and peak memory, "nothing
  // written".  The line "  predicted: <seconds> s ..." is the one scripts read.  dry_run false: the same report as
  // the note before a long run (no "nothing written").
  std::string text(const std::string& command, bool dry_run = true) const;
};
WorkEstimate estimate_work(core::Work work, const core::RunControl& control, int threads);

}  // namespace btob::io
