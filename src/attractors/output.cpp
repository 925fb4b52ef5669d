// SPDX-License-Identifier: GPL-3.0-or-later
// The attractors results' output: their CSV tables and the description of their arrays and attributes.
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

namespace {
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
