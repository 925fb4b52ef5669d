// SPDX-License-Identifier: GPL-3.0-or-later
// The boundary geometry of basins and basins-r (attractors/boundary.hpp) in their files and on the terminal: HDF5
// datasets and attributes, NAME_boundary.csv, the summary lines.
#include "attractors/requests.hpp"
#include "core/csv.hpp"

#include <fmt/format.h>

#include <cmath>

namespace btob::attractors {

namespace {

// Attributes NAME, NAME_low, NAME_high (the t interval over main and replicate grids), NAME_replicate_mean, _sd.
void spread_attrs(core::Contents& c, const std::string& name, const Spread& s) {
  c.attr(name, s.value);
  c.attr(name + "_low", s.low);
  c.attr(name + "_high", s.high);
  c.attr(name + "_replicate_mean", s.mean);
  c.attr(name + "_replicate_sd", s.sd);
}

void uncertainty_attrs(core::Contents& c, const UncertaintyFit& u) {
  c.attr("uncertainty_fitted", u.fitted);
  c.attr("uncertainty_method",
         "f(eps): share of main-grid cells whose label differs from one of the 4 cells eps cells away along the grid "
         "axes (the same interior cells for every eps); least squares of log f on log eps; D = 2 - alpha");
  if (!u.fitted) {
    c.attr("uncertainty_note", u.why);
    return;
  }
  c.attr("uncertainty_exponent", u.alpha);
  c.attr("uncertainty_exponent_low", u.low);
  c.attr("uncertainty_exponent_high", u.high);
  c.attr("uncertainty_exponent_se", u.se);
  c.attr("boundary_dimension", u.dimension());
  c.attr("boundary_dimension_low", 2 - u.high);
  c.attr("boundary_dimension_high", 2 - u.low);
  c.attr("uncertainty_eps_min_cells", static_cast<long>(u.eps_min));
  c.attr("uncertainty_eps_max_cells", static_cast<long>(u.eps_max));
  c.attr("uncertainty_eps_fitted", static_cast<long>(u.used));
}

void wada_attrs(core::Contents& c, const WadaTest& w) {
  c.attr("wada_verdict", w.verdict());
  c.attr("wada", w.wada);
  c.attr("wada_basins", static_cast<long>(w.basins));
  c.attr("wada_method", "merging (Daza et al. 2018): Hausdorff distance (chessboard, cells) of the basins' boundaries");
  if (!w.applies) return;
  c.attr("wada_hausdorff_cells", static_cast<long>(w.hausdorff));
  c.attr("wada_resolution_cells", static_cast<long>(w.cells));
  c.attr("wada_all_basins_share", w.all_basins_share);
}

std::string interval(const Spread& s) { return fmt::format("{:.4f} [{:.4f}, {:.4f}]", s.value, s.low, s.high); }

}  // namespace

void BasinsResult::fill_boundary() {
  const BoundaryGeometry& g = basins.boundary;
  box_entropies = g.entropy.per_box;
  eps_cells.clear(), eps_fraction.clear(), eps_ci_low.clear(), eps_ci_high.clear();
  for (const auto& p : g.uncertainty.points) {
    eps_cells.push_back(p.eps);
    eps_fraction.push_back(p.f);
    eps_ci_low.push_back(p.low);
    eps_ci_high.push_back(p.high);
  }
}

void BasinsResult::describe_boundary(core::Contents& c) const {
  const BoundaryGeometry& g = basins.boundary;
  const std::size_t rows = g.entropy.columns ? g.entropy.per_box.size() / g.entropy.columns : 0;
  c.array("box_entropy", box_entropies, {rows, g.entropy.columns}, "box row, box column", "nats",
          "entropy -sum p log p of the labels in each entropy box of the main grid (0: one basin)");
  // The boxes' centres in grid cells (box i covers cells i box .. (i + 1) box - 1 of its axis), as the coordinates of
  // the two box axes.
  std::vector<double> row_centres(rows), column_centres(g.entropy.columns);
  for (std::size_t i = 0; i < rows; ++i)
    row_centres[i] = (static_cast<double>(i) + 0.5) * static_cast<double>(g.entropy.box);
  for (std::size_t j = 0; j < column_centres.size(); ++j)
    column_centres[j] = (static_cast<double>(j) + 0.5) * static_cast<double>(g.entropy.box);
  c.coordinate_array("box_row", std::move(row_centres), {"box row"}, "cells",
                     "centre of each entropy box's rows, in grid cells");
  c.coordinate_array("box_column", std::move(column_centres), {"box column"}, "cells",
                     "centre of each entropy box's columns, in grid cells");
  c.array("uncertainty_eps", eps_cells, {eps_cells.size()}, "eps", "cells", "perturbation eps in grid cells");
  c.array("uncertainty_fraction", eps_fraction, {eps_fraction.size()}, "eps", "1",
          "fraction f(eps) of eps-uncertain cells of the main grid");
  c.array("uncertainty_ci_low", eps_ci_low, {eps_ci_low.size()}, "eps", "1", "Clopper-Pearson 95% lower end of f(eps)");
  c.array("uncertainty_ci_high", eps_ci_high, {eps_ci_high.size()}, "eps", "1",
          "Clopper-Pearson 95% upper end of f(eps)");
  c.coordinate("eps", "uncertainty_eps");
  c.attr("entropy_box", static_cast<long>(g.entropy.box));
  c.attr("entropy_boxes", static_cast<long>(g.entropy.boxes));
  c.attr("boundary_boxes", static_cast<long>(g.entropy.boundary_boxes));
  c.attr("entropy_interval", "t 95% interval of the mean over the main and replicate grids (value: main grid)");
  spread_attrs(c, "basin_entropy", g.sb);
  spread_attrs(c, "boundary_basin_entropy", g.sbb);
  spread_attrs(c, "boundary_box_share", g.boundary_share);
  c.attr("log2_criterion", g.entropy.sbb > std::log(2.0));  // S_bb > log 2: fractal boundary (sufficient)
  uncertainty_attrs(c, g.uncertainty);
  wada_attrs(c, g.wada);
}

std::string BasinsResult::boundary_csv() const {
  const BoundaryGeometry& g = basins.boundary;
  core::CsvTable t("quantity,value,low,high,replicate_mean,replicate_sd,detail");
  const auto row = [&](const std::string& q, const Spread& s, const std::string& detail) {
    t.row({q, fmt::format("{:.6f}", s.value), fmt::format("{:.6f}", s.low), fmt::format("{:.6f}", s.high),
           fmt::format("{:.6f}", s.mean), fmt::format("{:.6f}", s.sd), detail});
  };
  const std::string boxes = fmt::format("boxes of {} cells: {} boxes, {} boundary boxes (main grid)", g.entropy.box,
                                        g.entropy.boxes, g.entropy.boundary_boxes);
  row("basin_entropy", g.sb, boxes);
  row("boundary_basin_entropy", g.sbb,
      boxes + (g.entropy.sbb > std::log(2.0) ? "; above log 2: fractal boundary" : ""));
  row("boundary_box_share", g.boundary_share, boxes);
  const UncertaintyFit& u = g.uncertainty;
  if (u.fitted) {
    const std::string range = fmt::format("fit over eps = {}..{} cells ({} values)", u.eps_min, u.eps_max, u.used);
    t.row({"uncertainty_exponent", fmt::format("{:.6f}", u.alpha), fmt::format("{:.6f}", u.low),
           fmt::format("{:.6f}", u.high), "", "", range});
    t.row({"boundary_dimension", fmt::format("{:.6f}", u.dimension()), fmt::format("{:.6f}", 2 - u.high),
           fmt::format("{:.6f}", 2 - u.low), "", "", range});
  } else {
    t.row({"uncertainty_exponent", "", "", "", "", "", u.why});
  }
  t.row({"wada_hausdorff_cells", g.wada.applies ? fmt::format("{}", g.wada.hausdorff) : "", "", "", "", "",
         g.wada.verdict()});
  for (const auto& p : u.points)
    t.row({fmt::format("uncertain_fraction_eps_{}", p.eps), fmt::format("{:.6g}", p.f), fmt::format("{:.6g}", p.low),
           fmt::format("{:.6g}", p.high), "", "", fmt::format("{} of {} cells", p.uncertain, p.points)});
  return t.text();
}

std::string boundary_summary(const BoundaryGeometry& g) {
  std::string s = fmt::format(
      "  boundary (boxes of {} cells, {} boxes, {} on the boundary; 95% t interval over the grids):"
      " S_b {}, S_bb {}{}, boundary boxes {}\n",
      g.entropy.box, g.entropy.boxes, g.entropy.boundary_boxes, interval(g.sb), interval(g.sbb),
      g.entropy.sbb > std::log(2.0) ? " (> log 2: fractal)" : "", interval(g.boundary_share));
  const UncertaintyFit& u = g.uncertainty;
  if (u.fitted)
    s += fmt::format(
        "  uncertainty exponent alpha {:.3f} [{:.3f}, {:.3f}] over eps = {}..{} cells, boundary dimension "
        "D = {:.3f}\n",
        u.alpha, u.low, u.high, u.eps_min, u.eps_max, u.dimension());
  else s += "  uncertainty exponent not fitted: " + u.why + "\n";
  return s + "  Wada test (merging): " + g.wada.verdict() + "\n";
}

namespace {
// The per-r columns of basins-r: name, units, meaning, value.
struct Column {
  const char* name;
  const char* units;
  const char* meaning;
  double (*value)(const BoundaryGeometry&);
};
const Column kColumns[] = {
    {"basin_entropy", "nats", "basin entropy S_b on the boundary grid (main grid)",
     [](const BoundaryGeometry& g) { return g.sb.value; }},
    {"basin_entropy_low", "nats", "t 95% lower end of S_b over the main and replicate grids",
     [](const BoundaryGeometry& g) { return g.sb.low; }},
    {"basin_entropy_high", "nats", "t 95% upper end of S_b over the main and replicate grids",
     [](const BoundaryGeometry& g) { return g.sb.high; }},
    {"boundary_basin_entropy", "nats", "boundary basin entropy S_bb on the boundary grid (main grid)",
     [](const BoundaryGeometry& g) { return g.sbb.value; }},
    {"boundary_basin_entropy_low", "nats", "t 95% lower end of S_bb over the grids",
     [](const BoundaryGeometry& g) { return g.sbb.low; }},
    {"boundary_basin_entropy_high", "nats", "t 95% upper end of S_bb over the grids",
     [](const BoundaryGeometry& g) { return g.sbb.high; }},
    {"boundary_box_share", "1", "share of entropy boxes holding two or more labels (main grid)",
     [](const BoundaryGeometry& g) { return g.boundary_share.value; }},
    {"uncertainty_fitted", "1", "1: the uncertainty exponent was fitted; 0: not (its values are then 0)",
     [](const BoundaryGeometry& g) { return g.uncertainty.fitted ? 1.0 : 0.0; }},
    {"uncertainty_exponent", "1", "uncertainty exponent alpha (f(eps) ~ eps^alpha, main grid)",
     [](const BoundaryGeometry& g) { return g.uncertainty.alpha; }},
    {"uncertainty_exponent_low", "1", "lower end of alpha's 95% fit interval",
     [](const BoundaryGeometry& g) { return g.uncertainty.low; }},
    {"uncertainty_exponent_high", "1", "upper end of alpha's 95% fit interval",
     [](const BoundaryGeometry& g) { return g.uncertainty.high; }},
    {"wada_hausdorff_cells", "cells", "Hausdorff distance of the basins' boundaries (merging test; 0 with < 3 basins)",
     [](const BoundaryGeometry& g) { return static_cast<double>(g.wada.hausdorff); }},
};
}  // namespace

void fill_boundary_columns(BasinsRResult& res) {
  res.boundary_names.clear(), res.boundary_values.clear();
  if (res.rows.empty() || !res.rows[0].has_boundary) return;
  for (const Column& col : kColumns) {
    res.boundary_names.push_back(col.name);
    std::vector<double> v;
    for (const auto& row : res.rows) v.push_back(col.value(row.boundary));
    res.boundary_values.push_back(std::move(v));
  }
}

std::string boundary_units(const std::string& name) {
  for (const Column& col : kColumns)
    if (name == col.name) return col.units;
  return "";
}
std::string boundary_meaning(const std::string& name) {
  for (const Column& col : kColumns)
    if (name == col.name) return col.meaning;
  return "";
}

std::string BasinsRResult::boundary_r_csv() const {
  core::CsvTable t(
      "r,basin_entropy,basin_entropy_low,basin_entropy_high,boundary_basin_entropy,boundary_basin_entropy_low,"
      "boundary_basin_entropy_high,boundary_box_share,uncertainty_exponent,uncertainty_exponent_low,"
      "uncertainty_exponent_high,boundary_dimension,eps_range_cells,wada,boxes");
  for (const auto& row : rows) {
    const BoundaryGeometry& g = row.boundary;
    const UncertaintyFit& u = g.uncertainty;
    const auto f = [](double v) { return fmt::format("{:.6f}", v); };
    t.row({fmt::format("{}", row.r), f(g.sb.value), f(g.sb.low), f(g.sb.high), f(g.sbb.value), f(g.sbb.low),
           f(g.sbb.high), f(g.boundary_share.value), u.fitted ? f(u.alpha) : "", u.fitted ? f(u.low) : "",
           u.fitted ? f(u.high) : "", u.fitted ? f(u.dimension()) : "",
           u.fitted ? fmt::format("{}..{}", u.eps_min, u.eps_max) : u.why, g.wada.verdict(),
           fmt::format("{} of {} cells", g.entropy.boxes, g.entropy.box)});
  }
  return t.text();
}

}  // namespace btob::attractors
