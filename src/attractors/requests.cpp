// SPDX-License-Identifier: GPL-3.0-or-later
#include "attractors/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
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
int threads_of(const core::RunControl& control) {
  return control.threads > 0 ? control.threads : omp_get_max_threads();
}

// The attractor's own spelling (mirror-aware) from a one-verdict collection.
std::string pattern_of(const OrbitVerdict& v, double r) {
  if (v.type == Type::undecided) return "";
  const auto a = collect({v}, r, nullptr);
  return a.empty() ? "" : a[0].pattern;
}

void threshold_attrs(core::Contents& c, const Options& o) {
  c.attr("transient", o.transient);
  c.attr("window", o.window);
  c.attr("max_period", static_cast<long>(o.max_period));
  c.attr("return_tol", o.return_tol);
  c.attr("point_tol", o.point_tol);
  c.attr("collapse_theta", o.collapse_theta);
  c.attr("lyap_transient", o.lyap_transient);
  c.attr("lyap_iterations", o.lyap_iterations);
  c.attr("lyap_blocks", static_cast<long>(o.lyap_blocks));
  c.attr("rotation_tol", o.rotation_tol);
  c.attr("refine_factor", static_cast<long>(o.refine_factor));
}
}  // namespace

// ---- classify ----
// The exponent-reporting tools share lyapunov's domain: r from the smallest that double's exponents resolve.
static void require_r_double(double r, const char* field) {
  core::require_r(r, field);
  core::require_r_exponents(r, core::parse_precision("double"), field, {});  // no --precision to advise
}

void ClassifyRequest::validate() const {
  require_r_double(r, "r");
  core::parse_point(point, "point");
  attractors::validate(thresholds);
}

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

namespace {
// What classify's lambda1 is (docs/reference/numbers.md).  A periodic orbit's or a collapse's is the cycle's exact
// exponent log|mu2/mu1|/p evaluated in double (err 0: no average, only rounding); any other orbit's is pass 2's
// average with the batch-means standard error of lyapunov's method (err).
core::Status lambda1_status(const OrbitVerdict& v, const Options& o) {
  if (v.type == Type::periodic || v.type == Type::collapse)
    return core::estimated(
        "the detected cycle's exponent log|mu2/mu1|/p from its period matrix in double; batch_err = "
        "4 eps max(1, |lambda1|), its rounding (no average, no batch means)",
        "a numerical bound without proof (no statistical error: the exponent is not an average)");
  return core::estimated(
      fmt::format("average over {} steps after {} (pass 2); batch_err its batch-means standard error "
                  "over {} blocks, at least 4 eps max(1, |lambda1|) (lyapunov's err1); the "
                  "finite-time bias (up to about log(n)/n on invariant curves) is not in it: the "
                  "verdict's zero band is 3 batch_err + 10/n",
                  o.lyap_iterations, o.lyap_transient, o.lyap_blocks),
      "one standard error of the block means (68% if they are normal), bias excluded");
}
}  // namespace

std::string ClassifyResult::csv() const {
  core::CsvTable t("type,pattern,period,lambda1,batch_err,detail");
  const core::ValueWithError l = core::with_error(verdict.lambda1, verdict.err1);
  t.row({type_name(verdict.type), pattern, fmt::format("{}", verdict.period), l.value, l.error, detail});
  return t.text();
}

void ClassifyResult::describe(core::Contents& c) const {
  c.attr("r", request.r);
  c.attr("point", request.point);
  c.attr("type", std::string(type_name(verdict.type)));
  c.attr("pattern", pattern);
  c.attr("period", static_cast<long>(verdict.period));
  c.attr("lambda1", verdict.lambda1);
  c.attr("batch_err", verdict.err1);
  c.status_of("lambda1", lambda1_status(verdict, request.thresholds));
  c.attr("detail", detail);
  c.attr("iterations", verdict.iterations);
  threshold_attrs(c, request.thresholds);
}

// ---- basins ----
Grid BasinsRequest::parsed_grid() const {
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  return parse_grid(grid, w1_range[0], w1_range[1], "grid");
}

void BasinsRequest::validate() const {
  require_r_double(r, "r");
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  if (!(std::isfinite(w1_range[0]) && std::isfinite(w1_range[1]) && w1_range[0] < w1_range[1]))  // any grid kind
    throw core::InvalidField("w1-range", fmt::format("[{}, {}]", w1_range[0], w1_range[1]), "finite a < b");
  attractors::validate(thresholds);
  if (replicates < 0 || replicates > 100) throw core::InvalidField("replicates", std::to_string(replicates), "0..100");
  if (entropy_box < 1 || entropy_box > 1000)
    throw core::InvalidField("entropy-box", std::to_string(entropy_box), "1..1000 cells");
  const Grid g = parsed_grid();
  // Per point of the main grid: its label in a part and in the merged result (the work runs in bounded chunks).
  iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells), 8, "grid");
}

std::size_t BasinsRequest::work_items() const { return basin_items(parsed_grid(), replicates); }

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

void BasinsResult::describe(core::Contents& c) const {
  const Basins& b = basins;
  const Grid& g = b.grid;
  const core::GridAxis &ax1 = g.axis1, &ax2 = g.axis2;  // names, units and meanings of the coordinate scales
  c.array(ax1.name, axis1, {axis1.size()}, ax1.name, ax1.units, ax1.meaning);
  c.array(ax2.name, axis2, {axis2.size()}, ax2.name, ax2.units, ax2.meaning);
  c.array("labels", b.labels, {static_cast<std::size_t>(ax2.cells), static_cast<std::size_t>(ax1.cells)},
          fmt::format("{}, {}", ax2.name, ax1.name), "attractor id",
          "attractor of each grid point (0 = undecided; legend_<id>)");
  c.array("fraction", fraction, {fraction.size()}, "attractor", "1", "fraction of the main grid in each basin");
  c.array("ci_low", ci_low, {ci_low.size()}, "attractor", "1",
          "lower end of the Clopper-Pearson 95% interval of the fraction (sampling only)");
  c.array("ci_high", ci_high, {ci_high.size()}, "attractor", "1",
          "upper end of the Clopper-Pearson 95% interval of the fraction (sampling only)");
  c.array("replicate_mean", replicate_mean, {replicate_mean.size()}, "attractor then undecided", "1",
          "mean fraction over the main and the randomly shifted replicate grids (undecided last)");
  c.array("replicate_sd", replicate_sd, {replicate_sd.size()}, "attractor then undecided", "1",
          "sample standard deviation of the fraction over the main and replicate grids (0 with one grid)");
  c.attr("interval", "Clopper-Pearson 95% (sampling only)");
  c.status_of("fraction",
              core::estimated("the share of the main grid's points in each basin; its bar ci_low .. ci_high "
                              "(sampling only; the grid's own error shows in replicate_sd)",
                              "95% Clopper-Pearson"));
  const std::size_t n = points();
  c.attr("r", request.r);
  c.attr("grid", request.grid);
  c.attr("n1", ax1.cells);
  c.attr("n2", ax2.cells);
  c.attr("axis1_lo", ax1.lo);
  c.attr("axis1_hi", ax1.hi);
  c.attr("axis2_lo", ax2.lo);
  c.attr("axis2_hi", ax2.hi);
  c.attr("grid_kind", std::string(core::grid_kind_name(g.kind)));
  c.attr("measure", measure_name(g));
  c.attr("measure_sphere_share", sphere_share(g));  // share of the sphere measure of the domain the grid covers
  c.attr("replicates", static_cast<long>(request.replicates));
  c.attr("seed", static_cast<long>(request.seed));
  threshold_attrs(c, request.thresholds);
  c.attr("attractors", static_cast<long>(b.attractors.size()));
  c.attr("undecided_fraction", b.undecided.value);
  c.attr("undecided_ci_low", b.undecided.low);
  c.attr("undecided_ci_high", b.undecided.high);
  c.attr("undecided_first_pass", static_cast<long>(b.undecided_first_pass));
  c.attr("map_iterations", b.iterations_total);
  c.attr("certified_early", static_cast<long>(b.certified));  // orbits decided before the full length (all grids)
  c.attr("seconds", b.seconds);
  c.attr("points_per_second", static_cast<double>(n * static_cast<std::size_t>(request.replicates + 1)) / b.seconds);
  for (const auto& x : b.attractors)
    c.attr(fmt::format("legend_{}", x.id), fmt::format("{} ({})", x.pattern, type_name(x.type)));
  describe_boundary(c);
}

// ---- basins-r ----
std::vector<TableRow> parse_table(const std::string& csv) {
  std::vector<TableRow> rows;
  std::stringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ',')) f.push_back(item);
    if (f.size() < 2) continue;
    rows.push_back({std::stod(f[0]), f[1], f.size() > 2 ? f[2] : ""});
  }
  return rows;
}

std::vector<double> BasinsRRequest::all_r() const {
  std::vector<double> rs = r_values;
  if (r_count > 0)
    for (double r : iterate::linspace_r(r_min, r_max, r_count)) rs.push_back(r);
  if (table)
    for (const auto& t : parse_table(reference_csv))
      if (t.r >= 0.1 - 1e-12 && t.r <= 0.6 + 1e-12) rs.push_back(t.r);
  return rs;
}

namespace {
void require_table(const BasinsRRequest& q) {
  if (q.table && parse_table(q.reference_csv).empty())
    throw core::InvalidField("reference", q.reference.empty() ? "the lab's Table 6.1" : "'" + q.reference + "'",
                             "a readable CSV of Table 6.1 (r,percent,patterns)");
}
}  // namespace

void BasinsRRequest::validate() const {
  attractors::validate(thresholds);
  // With `table` the r values come from reference_csv, which the caller may fill after this first check (the
  // command line reads the file named by `reference`); run() checks the table itself.
  const bool table_pending = table && reference_csv.empty();
  if (!table_pending) require_table(*this);
  if (r_count < 0 || r_count > 100000)
    throw core::InvalidField("r-count", std::to_string(r_count), "0 (no range) .. 100000");
  if (r_count > 0) {
    require_r_double(r_min, "r-min");
    require_r_double(r_max, "r-max");
    if (r_min <= r_max) core::require_distinct(r_min, r_max, r_count, "r-count", "r-min..r-max");
  }
  const std::vector<double> rs = all_r();
  if (rs.empty() && !table_pending)
    throw core::InvalidField("r-values", "none", "a list of r in (0, 1), a range (r-min, r-max, r-count) or --table");
  for (double r : rs) require_r_double(r, "r-values");
  const auto pts = iterate::parse_grid(grid, seed, "grid");
  if (pts.empty()) throw core::InvalidField("grid", "'" + grid + "' with no points", "at least one");
  iterate::checked_bytes(pts.size(), 800, "grid");
  if (boundary_replicates < 0 || boundary_replicates > 100)
    throw core::InvalidField("boundary-replicates", std::to_string(boundary_replicates), "0..100");
  if (entropy_box < 1 || entropy_box > 1000)
    throw core::InvalidField("entropy-box", std::to_string(entropy_box), "1..1000 cells");
  if (has_boundary_grid(*this)) {
    const Grid g = boundary_grid_of(*this);
    iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells),
                           8 * static_cast<std::size_t>(boundary_replicates + 1), "boundary-grid");
  }
}

bool has_boundary_grid(const BasinsRRequest& req) { return req.boundary_grid != "none"; }
// A strip boundary grid spans the basins default w1 range [-2, 2].
Grid boundary_grid_of(const BasinsRRequest& req) { return parse_grid(req.boundary_grid, -2, 2, "boundary-grid"); }

BasinsRPart run_part(const BasinsRRequest& req, const std::vector<std::size_t>& items,
                     const core::RunControl& control) {
  req.validate();
  require_table(req);
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
  part.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
  require_table(req);
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
  res.seconds = part_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

std::string grid_measure(const std::string& spec) {
  if (spec.starts_with("random:")) return "uniform on the sphere of directions of the domain (random points)";
  if (spec.starts_with("strip:")) {
    const core::Grid s = iterate::parse_strip(spec, "grid");
    return strip_measure_name(s.axis1.lo, s.axis1.hi);
  }
  if (spec == "paper") return "the 32 points of the Section 4 grid (fractions of orbits, no measure)";
  return "the listed points (fractions of orbits, no measure)";
}

void BasinsRResult::describe(core::Contents& c) const {
  c.array("r", r, {r.size()}, "r value", "1", "restitution coefficients");
  c.array("fraction", fraction, {r.size(), columns.size()}, "r value, attractor (column_<j>; undecided last)", "1",
          "fraction of the initial conditions in each basin");
  c.text("column", columns, "attractor (column_<j>; undecided last)", "name",
         "the attractor of each column of fraction: its pattern and type, undecided last (as column_<j>)");
  c.coordinate("r value", "r");
  c.coordinate("attractor (column_<j>; undecided last)", "column");
  for (std::size_t j = 0; j < columns.size(); ++j) c.attr(fmt::format("column_{}", j), columns[j]);
  for (std::size_t q = 0; q < boundary_names.size(); ++q)
    c.array(boundary_names[q], boundary_values[q], {r.size()}, "r value", boundary_units(boundary_names[q]),
            boundary_meaning(boundary_names[q]));
  if (!boundary_names.empty()) {
    c.attr("boundary_grid", request.boundary_grid);
    c.attr("boundary_replicates", static_cast<long>(request.boundary_replicates));
    c.attr("entropy_box", static_cast<long>(request.entropy_box));
  }
  c.attr("grid", request.grid);
  c.attr("measure", grid_measure(request.grid));
  c.attr("seed", static_cast<long>(request.seed));
  c.attr("points", static_cast<long>(points));
  c.attr("columns", static_cast<long>(columns.size()));
  threshold_attrs(c, request.thresholds);
  c.attr("seconds", seconds);
}

// NAME_fractions.csv: the requested columns first, then counts, replicate spread and evidence; the undecided
// points are the last row (attractor 0), with the columns that describe an attractor left empty.
core::Tables BasinsResult::tables() const {
  const Basins& b = basins;
  core::CsvTable t(
      "attractor,type,pattern,fraction,ci_low,ci_high,count,replicate_mean,replicate_sd,canonical,period,collisions,"
      "stability,lambda2,rotation_min,rotation_max,invariant_min,invariant_max,w1,w2,letters,measure");
  const std::string measure = measure_name(b.grid);
  const auto f = [](double v) { return fmt::format("{:.6f}", v); };
  for (std::size_t i = 0; i < b.attractors.size(); ++i) {
    const auto& at = b.attractors[i];
    const auto w = core::strip<double>(at.point);
    t.row({fmt::format("{}", at.id),
           type_name(at.type),
           at.pattern,
           f(b.fractions[i].value),
           f(b.fractions[i].low),
           f(b.fractions[i].high),
           fmt::format("{}", at.count),
           f(replicate_mean[i]),
           f(replicate_sd[i]),
           at.canonical,
           fmt::format("{}", at.period),
           fmt::format("{}", at.collisions),
           at.stability,
           fmt::format("{:.6g}", at.lyapunov2),
           fmt::format("{:.10g}", at.rotation_min),
           fmt::format("{:.10g}", at.rotation_max),
           fmt::format("{:.8g}", at.invariant_min),
           fmt::format("{:.8g}", at.invariant_max),
           fmt::format("{:.12g}", w.first),
           fmt::format("{:.12g}", w.second),
           at.letters,
           measure});
  }
  const std::size_t u = b.attractors.size();
  std::vector<std::string> row = {"0",
                                  "undecided",
                                  "",
                                  f(b.undecided.value),
                                  f(b.undecided.low),
                                  f(b.undecided.high),
                                  fmt::format("{}", undecided_count),
                                  f(replicate_mean[u]),
                                  f(replicate_sd[u])};
  row.resize(t.columns().size());
  row.back() = measure;
  t.row(row);
  return {{"fractions", t.text()}, {"boundary", boundary_csv()}};
}

std::string BasinsRResult::fractions_csv() const {
  core::CsvTable t("r,attractor_key,type,pattern,fraction,ci_low,ci_high,count,stability,measure");
  const std::string measure = core::csv_text(grid_measure(request.grid));
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.attractors.size(); ++i)
      t.line(fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{},{},{}", row.r, core::csv_text(row.attractors[i].key),
                         type_name(row.attractors[i].type), core::csv_text(row.attractors[i].pattern),
                         row.fractions[i].value, row.fractions[i].low, row.fractions[i].high, row.attractors[i].count,
                         core::csv_text(row.attractors[i].stability), measure));
    t.line(fmt::format(
        "{},,undecided,,{:.6f},{:.6f},{:.6f},{},,{}", row.r, row.undecided.value, row.undecided.low, row.undecided.high,
        static_cast<std::size_t>(std::llround(row.undecided.value * static_cast<double>(points))), measure));
  }
  return t.text();
}

// table_6_1_comparison.csv: periodic fraction (paper: % of 10 orbits) and the patterns found, per r.
std::string BasinsRResult::comparison_csv() const {
  core::CsvTable cmp(
      "r,paper_percent_periodic,paper_ci_low,paper_ci_high,consistent,paper_patterns,periodic_fraction,ci_low,ci_high,"
      "patterns_found,paper_patterns_found,extra_patterns,other_types,measure");
  const std::string measure = core::csv_text(grid_measure(request.grid));
  for (const auto& c : comparison) {
    std::string pci_lo, pci_hi, consistent;
    if (c.has_percent) {
      pci_lo = fmt::format("{:.4f}", c.paper.low), pci_hi = fmt::format("{:.4f}", c.paper.high);
      consistent = c.consistent ? "yes" : "no";
    }
    const std::string paper_found = c.in_table ? fmt::format("{}/{}", c.paper_found, c.paper_total) : "";
    cmp.line(fmt::format("{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{},{}", c.r, c.paper_percent, pci_lo, pci_hi,
                         consistent, core::csv_text(c.paper_patterns), c.periodic.value, c.periodic.low,
                         c.periodic.high, core::csv_text(c.found), paper_found, core::csv_text(c.extra),
                         core::csv_text(c.other), measure));
  }
  return cmp.text();
}

core::Tables BasinsRResult::tables() const {
  core::Tables t{{"", fractions_csv()}, {"table_6_1_comparison.csv", comparison_csv()}};
  if (!boundary_names.empty()) t.push_back({"boundary", boundary_r_csv()});
  return t;
}

}  // namespace btob::attractors
