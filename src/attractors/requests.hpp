// SPDX-License-Identifier: GPL-3.0-or-later
// The attractors of Section 8.1 (1) as requests and results (core/request.hpp): one orbit classified
// (`btob classify`), the basins at one r over a grid (`btob basins`) and the basin fractions across r compared
// with Table 6.1 (`btob basins-r`).
#pragma once

#include "attractors/attractors.hpp"
#include "core/request.hpp"
#include "core/result.hpp"
#include "core/sweep.hpp"
#include "core/work.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::attractors {

// The classification thresholds shared by the three requests (Options without its run settings): each
// request's fields() calls this once.
template <class V> void threshold_fields(V& v, Options& o) {
  v("transient", o.transient, "steps before the window (>= 1)");
  v("iterations", o.window, "window of the period / collapse test (>= max-period)");
  v("max-period", o.max_period, "longest period searched, 1..1024");
  v("return-tol", o.return_tol, "return distance counted as a period, (0, 1e-3]");
  v("point-tol", o.point_tol, "distance to the exact cycle, (0, 1e-2]");
  v("collapse-theta", o.collapse_theta, "theta (pi/2 - theta) of a collapse, (0, 0.1]");
  v("lyap-transient", o.lyap_transient, "tangent alignment steps of pass 2");
  v("lyap-iterations", o.lyap_iterations, "averaged steps of pass 2");
  v("lyap-blocks", o.lyap_blocks, "batch-means blocks, 2..1000");
  v("rotation-tol", o.rotation_tol, "convergence of the weighted rotation number (turns), (0, 0.1]");
  v("refine-factor", o.refine_factor, "transient factor of the refinement pass (0 = off)");
}

// The options of a run: the thresholds with the run control's threads, progress and cancellation.
Options run_options(const Options& thresholds, const core::RunControl& control);

// ---- one orbit (`btob classify`) ------------------------------------------------------------------------------
struct ClassifyRequest {
  double r = 0;        // restitution coefficient, in (0, 1)
  std::string point;   // initial direction x,y,z with x z <= 0
  Options thresholds;  // classification thresholds (threshold_fields)

  void validate() const;
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient in (0, 1)", core::Required{});
    v("point", point, "initial direction x,y,z with x z <= 0", core::Required{});
    threshold_fields(v, thresholds);
  }
};

struct ClassifyResult {
  ClassifyRequest request;  // the request, as run (validated)
  OrbitVerdict verdict;     // the classifier's verdict: type, period, word, lambda1 and its evidence
  std::string pattern;      // the attractor's own spelling (mirror-aware); empty when undecided
  std::string detail;       // the verdict's evidence, iterations, and for periodic orbits the pattern tool's verdict
  // Attributes only: type, pattern, period, lambda1, batch_err, detail, iterations; lambda1's status (an estimate).
  // batch_err is what lyapunov's err1 is (batch means floored at the rounding), named so because on a slowly
  // converging orbit (invariant curves: a bias of about log(n)/n) it is not the whole error of lambda1.
  void describe(core::Contents& c) const;
  // What `btob classify` prints and --out writes to NAME.csv: type,pattern,period,lambda1,batch_err,detail, lambda1
  // and batch_err by core::with_error (the printed interval contains lambda1).
  std::string csv() const;
  core::Tables tables() const { return {{"", csv()}}; }
};

ClassifyResult run(const ClassifyRequest& req, const core::RunControl& control = {});
// Its cost (core/work.hpp): the map steps of pass 1 (transient + window) and the cocycle steps of pass 2, each again
// in the refinement pass (transient x refine-factor): an upper bound, since pass 1 decides periodic orbits and
// collapses without pass 2, and only undecided orbits are refined.
core::Work work(const ClassifyRequest& req);

// ---- basins at one r (`btob basins`) --------------------------------------------------------------------------
struct BasinsRequest {
  double r = 0;                         // restitution coefficient, in (0, 1)
  std::string grid = "sphere:200x200";  // sphere:NxM (equal-area theta x y), strip:NxM (w1 x w2), angles:NxM
  std::vector<double> w1_range{-2, 2};  // w1 range a < b of a strip grid
  int replicates = 2;                   // randomly shifted replicate grids, 0..100
  std::uint64_t seed = 1;               // seed of the replicate shifts
  int entropy_box = 5;                  // side of the boxes of the basin entropies (cells), 1..1000
  Options thresholds;                   // classification thresholds (threshold_fields)

  void validate() const;
  Grid parsed_grid() const;        // the grid (validated)
  std::size_t work_items() const;  // rows of the main and replicate grids (core/sweep.hpp, attractors::basin_rows)
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient in (0, 1)", core::Required{});
    v("grid", grid,
      "sphere:NxM (equal-area grid of theta x y: fractions of the uniform measure on the sphere of directions), "
      "strip:NxM (w1 x w2: fractions of Lebesgue measure on that rectangle) or angles:NxM (theta x phi)");
    v("w1-range", w1_range, "w1 range a,b of a strip grid");
    v("replicates", replicates, "randomly shifted replicate grids, 0..100");
    v("seed", seed, "seed of the replicate shifts");
    v("entropy-box", entropy_box, "side of the boxes of the basin entropies S_b, S_bb (cells), 1..1000");
    threshold_fields(v, thresholds);
  }
};

struct BasinsResult {
  BasinsRequest request;  // the request, as run (validated)
  Basins basins;          // the attractors (union over all grids), each grid point's label and the boundary geometry
  std::vector<double> fraction, ci_low, ci_high;     // [attractors]: main-grid fractions and their 95% intervals
  std::vector<double> replicate_mean, replicate_sd;  // [attractors + 1] over main and replicate grids; undecided last
  std::vector<double> axis1, axis2;                  // [n1], [n2]: the main grid's cell centres along each axis
  std::size_t undecided_count = 0;                   // undecided points of the main grid
  int threads = 0;                                   // threads used
  std::size_t points() const { return basins.labels.size(); }
  // Arrays: labels [n2, n1] (attractor id per grid point, 0 = undecided) with its axes' coordinates (w1, w2 on a
  // strip; theta, y = -cos phi on the sphere; theta, phi for angles), fraction, ci_low, ci_high [attractors],
  // replicate_mean, replicate_sd [attractors + 1]; attributes: the request, the grid, counts, timings, legend_<id>;
  // the boundary geometry (describe_boundary).
  void describe(core::Contents& c) const;
  // NAME_fractions.csv: per attractor its fraction and 95% interval, counts, replicate spread and evidence; the
  // undecided points last (attractor 0), their attractor columns empty; the measure on every row.  NAME_boundary.csv:
  // the boundary geometry, one quantity a row with its interval, then f(eps) a row per eps.
  core::Tables tables() const;
  std::string boundary_csv() const;
  void describe_boundary(core::Contents& c) const;  // boundary_output.cpp
  std::vector<double> box_entropies;  // [n2 / box, n1 / box]: each box's entropy on the main grid (boundary panel)
  std::vector<double> eps_cells, eps_fraction, eps_ci_low, eps_ci_high;  // [eps]: f(eps) on the main grid
  void fill_boundary();  // box_entropies and the eps arrays from basins (merge calls it)
};

// In parts (core/sweep.hpp): item k * n2 + j is row j of grid k (0: main, then the replicates).
BasinRows run_part(const BasinsRequest& req, const std::vector<std::size_t>& items,
                   const core::RunControl& control = {});
BasinsResult merge(const BasinsRequest& req, std::vector<BasinRows> parts);
// merge(req, {run_part(req, every row)}).
BasinsResult run(const BasinsRequest& req, const core::RunControl& control = {});

// ---- basin fractions across r (`btob basins-r`) ---------------------------------------------------------------
// Table 6.1 as the lab ships it (a data file, io::data_file): the default reference of basins-r.
inline constexpr const char* table_6_1_file = "reference/patterns_paper_table_6_1.csv";

// One row of Table 6.1: r, the paper's percentage of periodic orbits (of 10) and its patterns (';'-separated).
struct TableRow {
  double r = 0;
  std::string percent, patterns;
};
// Table 6.1 from its CSV text (header r,percent,patterns); empty rows are skipped.
std::vector<TableRow> parse_table(const std::string& csv);
// The measure whose fractions the counts over an iterate grid spec estimate (random:N: the uniform measure on the
// sphere of directions of the domain; strip: Lebesgue on its rectangle, with its share of the sphere measure; paper
// and point lists: counts of orbits, no measure).
std::string grid_measure(const std::string& spec);

struct BasinsRRequest {
  std::vector<double> r_values;     // r values in (0, 1)
  double r_min = 0.1, r_max = 0.6;  // a range of r_count values, both ends included (r_count = 0: none)
  long r_count = 0;
  bool table = false;                // add the r values of Table 6.1 in [0.1, 0.6]
  std::string grid = "random:2000";  // initial conditions: random:N, paper, strip:NxM or x,y,z;...
  std::uint64_t seed = 1;            // seed of random grids
  std::string reference;             // Table 6.1 as CSV (a path; empty: the lab's own copy, read by the caller)
  // The boundary geometry per r (attractors/boundary.hpp) from a basins run on this grid ("none": off), with its
  // replicates and entropy boxes; the points of `grid` give the fractions.  200 x 200 is the coarsest sphere grid
  // on which the uncertainty exponent is fitted where the boundary is smooth (r = 0.2, 0.3: f(eps) stays below 1/2
  // over eps = 1..16 cells); on 100 x 100 f passed 1/2 before eps spanned a decade at every r of Table 6.1.
  std::string boundary_grid = "sphere:200x200";
  int boundary_replicates = 2;
  int entropy_box = 5;
  Options thresholds;  // classification thresholds (threshold_fields)
  // Not a field: the text of the reference CSV, set by the caller (the command line reads `reference`).
  std::string reference_csv;

  void validate() const;
  std::vector<double> all_r() const;                         // r_values, the range's, then Table 6.1's when `table`
  std::size_t work_items() const { return all_r().size(); }  // a sweep over all_r() (core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("r-values", r_values, "r values r1,r2,... in (0, 1)");
    v("r-min", r_min, "smallest r of the range, in (0, 1)");
    v("r-max", r_max, "largest r of the range, in (0, 1)");
    v("r-count", r_count, "r values of the range r-min..r-max (0: no range)");
    v("table", table, "add the r values of Table 6.1 in [0.1, 0.6]");
    v("grid", grid, "initial conditions: random:N, paper, strip:NxM or x,y,z;...");
    v("seed", seed, "seed of random grids");
    v("reference", reference, "Table 6.1 as CSV (default: the lab's copy)");
    v("boundary-grid", boundary_grid,
      "grid of the basin entropies and uncertainty exponent per r (sphere:NxM, strip:NxM, angles:NxM; none: off)");
    v("boundary-replicates", boundary_replicates, "replicate grids of the entropies' intervals, 0..100");
    v("entropy-box", entropy_box, "side of the boxes of the basin entropies S_b, S_bb (cells), 1..1000");
    threshold_fields(v, thresholds);
  }
};

struct BasinsRRow {
  double r = 0;
  std::vector<Attractor> attractors;
  std::vector<Fraction> fractions;  // per attractor
  Fraction undecided;
  bool has_boundary = false;  // boundary-grid not "none"
  BoundaryGeometry boundary;  // from a basins run on boundary-grid at r
  template <class A> void members(A& a) {
    a(r, attractors, fractions, undecided, has_boundary, boundary);
  }  // core/pack.hpp
};

// The comparison with Table 6.1 at one r: the periodic fraction (paper: % of 10 orbits) and the patterns found.
struct Comparison {
  double r = 0;
  bool in_table = false;
  std::string paper_percent, paper_patterns;
  bool has_percent = false;
  Fraction paper;           // k of 10 with its 95% interval (has_percent)
  bool consistent = false;  // our periodic fraction within the paper's interval (has_percent)
  Fraction periodic;        // ours
  std::string found;        // "pattern (fraction); ..."
  int paper_found = 0, paper_total = 0;
  std::string extra;  // periodic patterns found that the paper does not list
  std::string other;  // other types and undecided with their fractions
};

struct BasinsRResult {
  BasinsRRequest request;              // the request, as run (validated)
  std::size_t points = 0;              // initial conditions per r (the grid's points)
  std::vector<BasinsRRow> rows;        // one per r value, ascending: attractors, fractions, boundary
  std::vector<Comparison> comparison;  // per row
  std::vector<double> r;               // [rows]
  std::vector<double> fraction;        // [rows, columns]: per attractor key (sorted by type, key), undecided last
  std::vector<std::string> columns;    // column labels
  int threads = 0;                     // OpenMP threads used
  double seconds = 0;                  // wall time of the run, seconds
  // Arrays: r [rows], fraction [rows, columns]; with a boundary grid, the boundary geometry per r (boundary_arrays);
  // attributes: column_<j>, the request and timings.
  void describe(core::Contents& c) const;
  // Per r (boundary grid): S_b, S_bb and the boundary-box share with their replicate intervals, the uncertainty
  // exponent with its fit interval (uncertainty_fitted 0: not fitted, values 0), the Wada distance; in this order.
  std::vector<std::string> boundary_names;
  std::vector<std::vector<double>> boundary_values;
  std::string boundary_r_csv() const;  // NAME_boundary.csv: per r the boundary geometry (boundary_output.cpp)
  std::string fractions_csv() const;   // NAME.csv: per r and attractor, fraction, interval, count, measure
  std::string comparison_csv() const;  // table_6_1_comparison.csv: the periodic fraction and patterns against Table 6.1
  core::Tables tables() const;         // both
};

// Some r values (items: ascending indices into all_r()), one row each.
// No rows(): per r a few attractors, fractions and the boundary geometry (from that r's own labels, in the part),
// all read by the tables; no per-point array leaves the part.
struct BasinsRPart {
  std::vector<std::size_t> items;
  std::vector<BasinsRRow> rows;  // in item order
  double seconds = 0;
  int threads = 0;
  template <class A> void members(A& a) { a(items, rows, seconds, threads); }
};
BasinsRPart run_part(const BasinsRRequest& req, const std::vector<std::size_t>& items,
                     const core::RunControl& control = {});
// The boundary geometry in a few lines for the terminal: entropies with their intervals, alpha and D with the fit's
// range, the Wada verdict.
std::string boundary_summary(const BoundaryGeometry& g);
// boundary_names / boundary_values of a merged basins-r result (boundary_output.cpp), and each name's units and
// meaning.
void fill_boundary_columns(BasinsRResult& res);
std::string boundary_units(const std::string& name);
std::string boundary_meaning(const std::string& name);
// basins-r's boundary grid, validated ("none": off).
bool has_boundary_grid(const BasinsRRequest& req);
Grid boundary_grid_of(const BasinsRRequest& req);
BasinsRResult merge(const BasinsRRequest& req, std::vector<BasinsRPart> parts);
// merge(req, {run_part(req, every r)}).
BasinsRResult run(const BasinsRRequest& req, const core::RunControl& control = {});

}  // namespace btob::attractors
