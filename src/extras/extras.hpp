// What a command adds to a result beyond its describe(), where it needs the request: the named r overlays drawn
// on figures (thresholds, windows, stripes) and per-command attributes.  The one route of the command line and
// the Python binding, so both write the same arrays and attributes.
#pragma once

#include "bifurcation/bifurcation.hpp"
#include "core/result.hpp"
#include "lyapunov/requests.hpp"
#include "precision/tradeoff.hpp"
#include "windows/requests.hpp"

#include <string>
#include <utility>
#include <vector>

namespace btob::extras {

// The names of the overlays ("stripes, thresholds, windows").
std::string overlay_names();
// The lines of the named overlays inside [r_min, r_max], flattened as (r, colour) pairs (colour 0 red, 1 blue,
// 2 grey), one per r value (a value of two overlays once); `labels` (when given) gets what each line is.  An
// unknown name throws core::InvalidField("overlay", ...).
std::vector<double> overlay_values(const std::vector<std::string>& names, double r_min, double r_max,
                                   std::vector<std::string>* labels = nullptr);

struct Extras {
  bool has_overlay = false;
  std::vector<double> overlay_lines;  // the storage the overlay_lines array views: keep Extras alive with the Contents
  std::vector<std::string> overlay_labels;  // what each line is (the overlay_labels texts view it)
  core::Attrs attrs;                  // set after the provenance and kind/name/... attributes (they override)
  // Adds the overlay_lines array (when the command has one) to `c`.
  void add_to(core::Contents& c) const;
  // Sets the attributes on `a`.
  void apply(core::Attrs& a) const {
    for (const auto& [k, v] : attrs) a[k] = v;
  }
};

// Unknown overlay names throw core::InvalidField("overlay", ...) without computing any line.  A command calls it
// before its run (an unknown name fails before any work) and of() after it, on MPI rank 0 only: the windows
// overlay is ~1 s of multiprecision root finding that no other rank uses.
void check_overlays(const std::vector<std::string>& names);
template <class Req> void check(const Req& req) {
  if constexpr (requires { req.overlay; }) check_overlays(req.overlay);
}

// Per request type (overlay lines computed here).  Requests without extras get none.
template <class Req> Extras of(const Req&) { return {}; }
Extras of(const bifurcation::Request& req);
Extras of(const lyapunov::MapRequest& req);
Extras of(const lyapunov::StripRequest& req);
Extras of(const precision::TradeoffRequest& req);
Extras of(const windows::BoundPrecisionRequest& req);

}  // namespace btob::extras
