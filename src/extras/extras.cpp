// SPDX-License-Identifier: GPL-3.0-or-later
// The overlays and per-command attributes of extras.hpp.
#include "extras/extras.hpp"

#include "attractors/requests.hpp"
#include "core/map.hpp"
#include "core/request.hpp"
#include "windows/overlays.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <tuple>

namespace btob::extras {
namespace {

using OverlayFn = std::function<std::vector<std::pair<double, int>>(double r_min, double r_max,
                                                                    const core::CancelToken* cancel, int threads)>;

// Constants quoted in the paper (Sections 1, 4, 5): three-particle collapse 7-4*sqrt(3), end of the
// (ab)^2(cb)^2 window 3-2*sqrt(2), end of the (ab)^3(cb)^3 window 5-2*sqrt(6), no four-particle
// collapse above 2^(2/3)-1.
std::vector<std::pair<double, int>> thresholds(double, double, const core::CancelToken*, int) {
  return {
      {7 - 4 * std::sqrt(3.0), 0}, {3 - 2 * std::sqrt(2.0), 0}, {5 - 2 * std::sqrt(6.0), 0}, {std::cbrt(4.0) - 1, 0}};
}

const std::map<std::string, OverlayFn>& overlays() {
  static const std::map<std::string, OverlayFn> m{
      {"thresholds", thresholds},
      {"windows", windows::window_overlay},
      {"stripes", [](double a, double b, const core::CancelToken*, int) { return windows::stripes_overlay(a, b); }}};
  return m;
}

}  // namespace

std::string overlay_names() {
  std::string s;
  for (const auto& [k, v] : overlays()) s += (s.empty() ? "" : ", ") + k;
  return s;
}

void check_overlays(const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (!overlays().count(n)) throw core::InvalidField("overlay", "'" + n + "'", "one of " + overlay_names());
}

namespace {
// What a line of an overlay is: the thresholds by name, the other overlays by colour (windows: r_crit,2(n) red,
// lower bounds blue; stripes: r(l/m)).
std::string line_label(const std::string& overlay, double r, int colour) {
  if (overlay == "thresholds") {
    const std::pair<double, const char*> known[] = {
        {7 - 4 * std::sqrt(3.0), "7-4sqrt3 (three-particle collapse)"},
        {3 - 2 * std::sqrt(2.0), "3-2sqrt2 (end of the (ab)^2(cb)^2 window)"},
        {5 - 2 * std::sqrt(6.0), "5-2sqrt6 (end of the (ab)^3(cb)^3 window)"},
        {std::cbrt(4.0) - 1, "2^(2/3)-1 (no four-particle collapse above)"}};
    for (const auto& [v, name] : known)
      if (v == r) return std::string("thresholds: ") + name;
  }
  if (overlay == "windows") return colour == 0 ? "windows: r_crit,2(n)" : "windows: lower bound of a window";
  if (overlay == "stripes") return "stripes: thin stripe r(l/m), eq. (6.3)";
  return overlay;
}
}  // namespace

std::vector<double> overlay_values(const std::vector<std::string>& names, double r_min, double r_max,
                                   std::vector<std::string>* labels, const core::CancelToken* cancel, int threads) {
  check_overlays(names);
  std::vector<double> out;
  std::vector<std::string> lab;
  for (const auto& n : names) {
    auto it = overlays().find(n);
    for (const auto& [r, colour] : it->second(r_min, r_max, cancel, threads)) {
      if (!(r >= r_min && r <= r_max)) continue;
      // One line per r: a value two overlays share (3-2sqrt2 is a threshold and r_crit,2(2)) is drawn once, its
      // labels joined; 1e-12 relative: the routes round the same number differently by a few ulps at most.
      std::size_t k = 0;
      while (k < lab.size() && !(std::fabs(out[2 * k] - r) <= 1e-12 * std::fabs(r))) ++k;
      const std::string l = line_label(n, r, colour);
      if (k < lab.size()) {
        lab[k] += "; " + l;
        continue;
      }
      out.push_back(r);
      out.push_back(colour);
      lab.push_back(l);
    }
  }
  if (labels) *labels = std::move(lab);
  return out;
}

void Extras::add_to(core::Contents& c) const {
  if (has_attractors) attractors.add_to(c);
  if (!has_overlay) return;
  c.array("overlay_lines", overlay_lines, {overlay_lines.size() / 2, 2}, "line, (r, colour)", "1",
          "r values of the named overlays (column 0) and their colour code (column 1: 0 red, 1 blue, 2 grey); "
          "overlay_labels names each line");
  c.text("overlay_labels", overlay_labels, "line", "name", "what each line of overlay_lines is (overlay: value)");
}

std::vector<std::string> overlays_of(const bifurcation::Request& req) { return req.overlay; }
std::vector<std::string> overlays_of(const lyapunov::MapRequest& req) {
  return req.overlay.empty() ? std::vector<std::string>{"thresholds", "windows"} : req.overlay;
}

double share_window_bounds(const std::vector<std::string>& names, double r_min, std::size_t rank, std::size_t ranks,
                           const AllGather& all_gather, const core::RunControl& control) {
  if (ranks <= 1 || !all_gather || std::find(names.begin(), names.end(), "windows") == names.end()) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<int> mine;  // largest n first: the long-double route's cost grows with n, as the polynomial route's
  for (int n = windows::window_overlay_last_n(r_min), k = 0; n >= 1; --n, ++k)
    if (static_cast<std::size_t>(k) % ranks == rank) mine.push_back(n);
  const std::vector<std::pair<double, double>> b =
      windows::window_overlay_bounds(mine, control.cancel, control.threads);
  struct Entry {  // one n's bounds as bytes: the same binary on every rank
    int n;
    double lower, upper;
  };
  std::vector<char> bytes(mine.size() * sizeof(Entry));
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const Entry e{mine[i], b[i].first, b[i].second};
    std::memcpy(bytes.data() + i * sizeof(Entry), &e, sizeof(Entry));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const std::vector<char>& from : all_gather(std::move(bytes)))
    for (std::size_t at = 0; at + sizeof(Entry) <= from.size(); at += sizeof(Entry)) {
      Entry e;
      std::memcpy(&e, from.data() + at, sizeof(Entry));
      windows::remember_window_overlay_bounds(e.n, {e.lower, e.upper});
    }
  return seconds;
}

Extras of(const bifurcation::Request& req, const core::RunControl& control) {
  Extras e;
  e.has_overlay = true;
  e.overlay_lines =
      overlay_values(overlays_of(req), req.r_min, req.r_max, &e.overlay_labels, control.cancel, control.threads);
  return e;
}

namespace {
// The attributes both Lyapunov images record.
template <class Req> Extras lyapunov_common(const Req& req) {
  Extras e;
  e.attrs["transient"] = req.transient;
  e.attrs["error_estimate"] = fmt::format("batch means over {} blocks of the averaged steps", req.blocks);
  e.attrs["classification"] =
      std::string("positive if lambda1 > 3 err1 + 10/n, negative if < -(3 err1 + 10/n), else zero");
  return e;
}
}  // namespace

Extras of(const lyapunov::MapRequest& req, const core::RunControl& control) {
  Extras e = lyapunov_common(req);
  e.attrs["r_min"] = req.r_min;
  e.attrs["r_max"] = req.r_max;
  e.attrs["r_count"] = req.r_count;
  const std::vector<std::string> names = overlays_of(req);
  e.has_overlay = true;
  e.overlay_lines = overlay_values(names, req.r_min, req.r_max, &e.overlay_labels, control.cancel, control.threads);
  e.attrs["overlays"] = fmt::format("{}", fmt::join(names, ","));
  return e;
}

// ---- per-orbit attractors ----
OrbitAttractors orbit_attractors(const iterate::Ensemble& e, const attractors::Options& options,
                                 const core::RunControl& control) {
  attractors::Options opt = attractors::run_options(options, control);
  opt.run.progress = nullptr;  // the run's own progress has finished; this pass is the classification's
  attractors::validate(opt);
  OrbitAttractors out;
  out.options = options;
  const std::size_t R = e.r.size(), I = e.initial.size();
  out.r_count = R, out.n_ic = I;
  // Per r: classify's verdicts and collect's attractors; then one index per (type, key) over every r.
  std::vector<std::vector<attractors::Attractor>> found(R);
  std::vector<std::vector<std::uint32_t>> ids(R);
  std::map<std::pair<int, std::string>, std::uint32_t> index;
  for (std::size_t i = 0; i < R; ++i) {
    iterate::Ensemble one;
    one.r = {e.r[i]};
    one.initial = e.initial;
    found[i] = attractors::collect(attractors::classify(one, opt), e.r[i], &ids[i]);
    for (const auto& a : found[i]) index.emplace(std::make_pair(static_cast<int>(a.type), a.key), 0);
  }
  out.name = {"undecided"};
  out.type = {attractors::type_name(attractors::Type::undecided)};
  out.period = {0};
  for (auto& [k, v] : index) {
    v = static_cast<std::uint32_t>(out.name.size());
    out.name.emplace_back();
    out.type.emplace_back(attractors::type_name(static_cast<attractors::Type>(k.first)));
    out.period.push_back(0);
  }
  const std::size_t A = out.name.size();
  out.label.assign(R * I, 0);
  out.count.assign(R * A, 0);
  for (std::size_t i = 0; i < R; ++i) {
    std::vector<std::uint32_t> global(found[i].size() + 1, 0);  // collect's id (1-based, 0 undecided) -> index
    for (const auto& a : found[i]) {
      const std::uint32_t g = index.at({static_cast<int>(a.type), a.key});
      global[static_cast<std::size_t>(a.id)] = g;
      out.name[g] = a.pattern;  // the same key has the same pattern at every r (attractors::attractor_key)
      out.period[g] = static_cast<std::uint32_t>(a.period);
    }
    for (std::size_t j = 0; j < I; ++j) {
      const std::uint32_t g = global[ids[i][j]];
      out.label[i * I + j] = g;
      ++out.count[i * A + g];
    }
  }
  return out;
}

void OrbitAttractors::add_to(core::Contents& c) const {
  const std::size_t A = name.size();
  c.array("attractor", label, {r_count, n_ic}, "r, initial condition", "index",
          "the orbit's attractor: an index into attractor_name (0 undecided), classify's verdict on the orbit");
  c.array("attractor_count", count, {r_count, A}, "r, attractor", "count", "orbits of each attractor at each r");
  c.array("attractor_period", period, {A}, "attractor", "iterations",
          "map iterations per period of each attractor (1 for a collapse, 0 for none)");
  c.text("attractor_name", name, "attractor", "name",
         "each attractor as btob classify names it: its pattern (paper notation), P2 invariant curves, chaotic, "
         "or undecided");
  c.text("attractor_type", type, "attractor", "name", "classify's type of each attractor");
  c.attr("attractor_transient", options.transient);
  c.attr("attractor_iterations", options.window);
  c.attr("attractor_max_period", static_cast<long>(options.max_period));
  c.attr("attractor_classification",
         std::string("btob classify --r R --point P --transient T --iterations W --max-period M, the other thresholds "
                     "at classify's defaults (T, W, M: attractor_transient, attractor_iterations, "
                     "attractor_max_period)"));
}

attractors::Options attractor_options(const lyapunov::MapRequest& req) {
  attractors::Options o;
  o.transient = req.transient;
  o.window = req.iterations;
  o.max_period = static_cast<int>(std::min<long>(o.max_period, o.window));
  return o;
}

attractors::Options attractor_options(const bifurcation::Request& req) {
  attractors::Options o;
  o.transient = req.iterations - req.tail;
  o.window = req.tail;
  o.max_period = static_cast<int>(std::min<long>(o.max_period, o.window));
  return o;
}

Extras of(const lyapunov::MapRequest& req, const lyapunov::MapResult& res, const core::RunControl& control) {
  Extras e = of(req, control);
  if (!req.attractors) return e;
  e.has_attractors = true;
  e.attractors = orbit_attractors(res.ensemble, attractor_options(req), control);
  return e;
}

Extras of(const bifurcation::Request& req, const bifurcation::Result& res, const core::RunControl& control) {
  Extras e = of(req, control);
  if (!req.attractors) return e;
  e.has_attractors = true;
  e.attractors = orbit_attractors(res.ensemble, attractor_options(req), control);
  return e;
}

Extras of(const lyapunov::StripRequest& req) {
  Extras e = lyapunov_common(req);
  e.attrs["r"] = req.r;
  const core::Grid g = req.spec();
  e.attrs["w1_min"] = g.axis1.lo;
  e.attrs["w1_max"] = g.axis1.hi;
  e.attrs["alpha"] = core::alpha(req.r);
  return e;
}

Extras of(const precision::TradeoffRequest& req) {
  Extras e;
  e.attrs["orbits"] = req.orbits;
  e.attrs["iterations"] = req.iterations;
  e.attrs["seed"] = static_cast<long>(req.seed);
  e.attrs["description"] = precision::TradeoffResult::notes(req);  // what the columns of tradeoff.csv mean
  return e;
}

Extras of(const windows::BoundPrecisionRequest&) {
  Extras e;
  e.attrs["threads"] = 1L;  // the study runs on one thread (its seconds column times one bound each)
  return e;
}

}  // namespace btob::extras
