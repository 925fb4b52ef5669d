// SPDX-License-Identifier: GPL-3.0-or-later
// The attractors requests' runs: classify, the basins' rows (run_part, merge), the sweep over r and its comparison
// with Table 6.1, and the work estimates.
#include "attractors/request_detail.hpp"
#include "attractors/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/patterns.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace btob::attractors {

Options run_options(const Options& thresholds, const core::RunControl& control) {
  Options o = thresholds;
  o.run.threads = control.threads;
  o.run.progress = control.progress;
  o.run.cancel = control.cancel;
  return o;
}

namespace {
int threads_of(const core::RunControl& control) { return core::thread_count(control.threads); }

// The attractor's own spelling (mirror-aware) from a one-verdict collection.
std::string pattern_of(const OrbitVerdict& v, double r) {
  if (v.type == Type::undecided) return "";
  const auto a = collect({v}, r, nullptr);
  return a.empty() ? "" : a[0].pattern;
}
}  // namespace

ClassifyResult run(const ClassifyRequest& req, const core::RunControl& control) {
  req.validate();
  ClassifyResult res;
  res.request = req;
  const core::Vec3<double> u = core::parse_point(req.point, "point");
  res.verdict = classify_point(u, req.r, run_options(req.thresholds, control));
  const OrbitVerdict& v = res.verdict;
  res.detail = v.detail + fmt::format("; {} iterations", v.iterations);
  if (v.type == Type::periodic && !v.word.s.empty()) {
    // The pattern tool's verdict at this r: stability and the collision letters (acb / cab resolved).
    const patterns::Verdict<double> pv = patterns::analyse<double>(v.word, req.r, control.cancel);
    res.detail += fmt::format("; pattern tool: {}; letters {}", patterns::outcome_name(pv.outcome), pv.letters);
  }
  res.pattern = pattern_of(v, req.r);
  return res;
}

namespace {
// A probe of the classifier on one orbit that no pass decides early: r = 0.2 from (1, -0.5, -1.1), whose orbit has
// no period (pass 1 goes to the end of its window: quasi-periodic, on a P2 invariant curve, so pass 2 runs and
// records its rotation), with the refinement off.
ClassifyRequest classify_probe(long transient, long window, long lyap_iterations) {
  ClassifyRequest p;
  p.r = 0.2;
  p.point = "1,-0.5,-1.1";
  p.thresholds.max_period = 1;
  p.thresholds.transient = transient;
  p.thresholds.window = window;
  p.thresholds.lyap_transient = 1;
  p.thresholds.lyap_blocks = 2;
  p.thresholds.lyap_iterations = lyap_iterations;
  p.thresholds.refine_factor = 0;
  return p;
}
}  // namespace

core::Work work(const ClassifyRequest& req) {
  const Options& o = req.thresholds;
  const double passes = o.refine_factor > 0 ? 2 : 1;
  core::Work w;
  core::Term one;
  one.route = "classify pass 1 double";
  one.units =
      static_cast<double>(o.transient + o.window) +
      (o.refine_factor > 0 ? static_cast<double>(o.transient) * o.refine_factor + static_cast<double>(o.window) : 0.0);
  one.what = "map steps of pass 1 in double (transient + iterations, and transient x refine-factor + iterations)";
  one.probe = [](double n, const core::RunControl& c) {
    const ClassifyRequest p = classify_probe(std::max(1L, static_cast<long>(n)), 20, 20);
    (void)run(p, c);
    return static_cast<double>(p.thresholds.transient + p.thresholds.window);
  };
  core::Term two;
  two.route = "classify pass 2 cocycle double";
  two.units = passes * static_cast<double>(o.lyap_transient + o.lyap_iterations);
  two.what = "steps of pass 2's derivative cocycle in double (lyap-transient + lyap-iterations, per pass)";
  two.probe = [](double n, const core::RunControl& c) {
    const ClassifyRequest p = classify_probe(1, 1, std::max(20L, static_cast<long>(n)));
    (void)run(p, c);
    return static_cast<double>(p.thresholds.lyap_transient + p.thresholds.lyap_iterations);
  };
  w.terms = {one, two};
  w.bound = "pass 1 decides periodic orbits and collapses without pass 2, and only an undecided orbit is refined";
  w.output_bytes = 400;  // one printed row (or NAME.json with its attributes under --out)
  // Pass 1 keeps the window's states (3 doubles and a symbol each); pass 2 the rotation record (2 doubles a step).
  w.peak_bytes =
      32 * static_cast<double>(o.window + o.max_period) + 16 * static_cast<double>(o.lyap_iterations) + 65536;
  return w;
}

BasinRows run_part(const BasinsRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  req.validate();
  BasinRows part =
      basin_rows(req.r, req.parsed_grid(), req.replicates, req.seed, run_options(req.thresholds, control), items);
  part.threads = threads_of(control);
  return part;
}

BasinsResult merge(const BasinsRequest& req, std::vector<BasinRows> parts) {
  req.validate();
  BasinsResult res;
  res.request = req;
  for (const auto& p : parts) res.threads = std::max(res.threads, p.threads);
  res.basins =
      merge_basins(req.r, req.parsed_grid(), req.replicates, req.thresholds, std::move(parts), req.entropy_box);
  res.fill_boundary();
  const Basins& b = res.basins;
  for (const auto& f : b.fractions) {
    res.fraction.push_back(f.value);
    res.ci_low.push_back(f.low);
    res.ci_high.push_back(f.high);
  }
  // The spread of each fraction over the main and replicate grids (undecided last).
  for (const auto& v : b.replicate_fractions) {
    double m = 0, s = 0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) s += (x - m) * (x - m);
    res.replicate_mean.push_back(m);
    res.replicate_sd.push_back(v.size() > 1 ? std::sqrt(s / static_cast<double>(v.size() - 1)) : 0.0);
  }
  for (auto l : b.labels) res.undecided_count += l == 0;
  res.axis1 = b.grid.axis1.centres();  // cell centres of the main (unshifted) grid, where its points lie
  res.axis2 = b.grid.axis2.centres();
  return res;
}

BasinsResult run(const BasinsRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

BasinsRPart run_part(const BasinsRRequest& req, const std::vector<std::size_t>& items,
                     const core::RunControl& control) {
  req.validate();
  detail::require_table(req);
  const auto t0 = std::chrono::steady_clock::now();
  BasinsRPart part;
  part.items = items;
  part.threads = threads_of(control);
  const std::vector<core::Vec3<double>> pts = iterate::parse_grid(req.grid, req.seed, "grid");
  const Options opt = run_options(req.thresholds, control);
  const std::vector<double> all_r = req.all_r();
  // Per r: the attractors (matched across r by key), fractions and intervals.
  for (std::size_t i : items) {
    core::check_cancel(control.cancel);
    const double r = all_r.at(i);
    iterate::Ensemble e;
    e.r = {r};
    e.initial = pts;
    const auto v = classify(e, opt);
    BasinsRRow row{r, collect(v, r, nullptr), {}, {}};
    std::size_t undec = 0;
    for (const auto& x : v) undec += x.type == Type::undecided;
    for (const auto& x : row.attractors) row.fractions.push_back(fraction(x.count, v.size()));
    row.undecided = fraction(undec, v.size());
    if (has_boundary_grid(req)) {
      // The same classifier over an image of the domain: the boundary geometry at r.
      row.has_boundary = true;
      row.boundary = basins(r, boundary_grid_of(req), req.boundary_replicates, req.seed, opt, req.entropy_box).boundary;
    }
    part.rows.push_back(std::move(row));
  }
  part.seconds = core::seconds_since(t0);
  return part;
}

BasinsRResult run(const BasinsRRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

namespace {
// Per r, the paper's periodic fraction and patterns of Table 6.1 against ours.
void compare(BasinsRResult& res, const std::vector<TableRow>& table) {
  const std::size_t n_points = res.points;
  // Comparison with Table 6.1.
  for (const auto& row : res.rows) {
    Comparison cmp;
    cmp.r = row.r;
    const TableRow* t = nullptr;
    for (const auto& x : table)
      if (std::fabs(x.r - row.r) < 1e-9) t = &x;
    std::size_t periodic = 0;
    std::set<std::string> found;
    for (std::size_t i = 0; i < row.attractors.size(); ++i) {
      const auto& x = row.attractors[i];
      if (x.type == Type::periodic) {
        periodic += x.count;
        found.insert(x.pattern);
        cmp.found += fmt::format("{}{} ({:.3f})", cmp.found.empty() ? "" : "; ", x.pattern, row.fractions[i].value);
      } else {
        const std::string type = type_name(x.type);
        const std::string label = x.pattern.empty() || x.pattern == type ? type : type + " " + x.pattern;
        cmp.other += fmt::format("{}{} ({:.3f})", cmp.other.empty() ? "" : "; ", label, row.fractions[i].value);
      }
    }
    cmp.other += fmt::format("{}undecided ({:.3f})", cmp.other.empty() ? "" : "; ", row.undecided.value);
    std::set<std::string> paper;
    if (t) {
      cmp.in_table = true;
      cmp.paper_percent = t->percent;
      cmp.paper_patterns = t->patterns;
      std::stringstream ss(t->patterns);
      std::string p;
      while (std::getline(ss, p, ';'))
        if (!p.empty()) paper.insert(p);
    }
    for (const auto& p : paper) cmp.paper_found += found.count(p) ? 1 : 0;
    cmp.paper_total = static_cast<int>(paper.size());
    for (const auto& p : found)
      if (!paper.count(p)) cmp.extra += (cmp.extra.empty() ? "" : "; ") + p;
    cmp.periodic = fraction(periodic, n_points);
    // The paper's percentage is k of 10 orbits: its own 95% interval, and whether our fraction lies inside.
    if (t && !t->percent.empty()) {
      cmp.has_percent = true;
      const auto k = static_cast<std::size_t>(std::llround(std::stod(t->percent) / 10));
      cmp.paper = fraction(k, 10);
      cmp.consistent = cmp.periodic.value >= cmp.paper.low && cmp.periodic.value <= cmp.paper.high;
    }
    res.comparison.push_back(std::move(cmp));
  }
}
}  // namespace

BasinsRResult merge(const BasinsRRequest& req, std::vector<BasinsRPart> parts) {
  req.validate();
  detail::require_table(req);
  const auto t0 = std::chrono::steady_clock::now();
  BasinsRResult res;
  res.request = req;
  res.points = iterate::parse_grid(req.grid, req.seed, "grid").size();
  const auto order = core::item_order(parts, req.work_items());
  for (const auto& at : order) res.rows.push_back(std::move(parts[at.part].rows.at(at.index)));
  double part_seconds = 0;
  for (const auto& p : parts) {
    part_seconds = std::max(part_seconds, p.seconds);
    res.threads = std::max(res.threads, p.threads);
  }
  compare(res, parse_table(req.reference_csv));

  // The fraction matrix [r x key] for the stacked areas: keys across r sorted (type, key), undecided last.
  std::map<std::pair<int, std::string>, std::string> keys;
  for (const auto& row : res.rows)
    for (const auto& x : row.attractors) keys[{static_cast<int>(x.type), x.key}] = x.pattern;
  const std::size_t cols = keys.size() + 1, nr = res.rows.size();
  res.fraction.assign(nr * cols, 0.0);
  std::size_t col = 0;
  for (const auto& [k, pat] : keys) {
    for (std::size_t i = 0; i < nr; ++i)
      for (std::size_t j = 0; j < res.rows[i].attractors.size(); ++j)
        if (res.rows[i].attractors[j].key == k.second) res.fraction[i * cols + col] = res.rows[i].fractions[j].value;
    const std::string type = type_name(static_cast<Type>(k.first));
    res.columns.push_back(pat.empty() || pat == type ? type : fmt::format("{} ({})", pat, type));
    ++col;
  }
  for (std::size_t i = 0; i < nr; ++i) {
    res.fraction[i * cols + col] = res.rows[i].undecided.value;
    res.r.push_back(res.rows[i].r);
  }
  res.columns.push_back("undecided");
  fill_boundary_columns(res);
  res.seconds = part_seconds + core::seconds_since(t0);
  return res;
}

}  // namespace btob::attractors
