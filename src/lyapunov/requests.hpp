// SPDX-License-Identifier: GPL-3.0-or-later
// The Lyapunov analyses as requests and results (core/request.hpp): one orbit in any precision, a map over
// r values x initial conditions, and a strip image at one r.  Exponents are per map iteration, natural log;
// the projective exponents lambda1, lambda2 of the 2-D map (lyapunov.hpp states the conventions).
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/sweep.hpp"
#include "core/work.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::lyapunov {

// ---- one orbit (`btob lyapunov`) --------------------------------------------------------------------------
struct OrbitRequest {
  core::Decimal r = 0;               // restitution coefficient, in (0, 1), kept as given (read in the precision)
  std::string point;                 // initial direction x,y,z (x*z <= 0)
  long iterations = 100000;          // averaged map iterations, >= blocks
  long transient = 1000;             // iterations discarded first, 0..iterations
  int reorthonormalise = 1;          // QR every this many steps, >= 1
  int blocks = 20;                   // batch-means blocks, 2..iterations
  std::string precision = "double";  // float, double, long-double, float128 or mpfr:D
  std::string convergence;           // also write exponent against n to this CSV file (command line only)
  bool weighted = false;             // also compute and report the weighted Birkhoff averages

  void validate() const;
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient, in (0,1)", core::required);
    v("point", point, "initial point x,y,z (x*z <= 0)", core::required);
    v("iterations", iterations, "averaged map iterations");
    v("transient", transient, "iterations discarded first (orbit and tangent frame)");
    v("reorthonormalise", reorthonormalise, "QR every this many steps");
    v("blocks", blocks, "batch-means blocks for the error bars");
    v("precision", precision, "float, double, long-double, float128 or mpfr:D (D digits, 10..10000)");
    v("convergence", convergence, "also write exponent against n to this CSV file");
    v("weighted", weighted,
      "also compute the weighted Birkhoff averages (printed first; attributes lambda1_weighted, lambda2_weighted): "
      "1e-8 or better on periodic and quasi-periodic orbits where the plain average converges like 1/n; their pass "
      "over the orbit's states costs about 40% of a step in double");
  }
};

// The exponents of one orbit, every value finite (a precision that cannot represent the run is refused).
ProjectiveResult run(const OrbitRequest& req, const core::RunControl& control = {});
// Its cost (core/work.hpp): transient + iterations steps of the derivative cocycle in the request's precision (and
// as many in double after a float run, which the command line re-runs in double); a fixed orbit probes the route.
core::Work work(const OrbitRequest& req);

// ---- maps over r x initial conditions (`btob lyapunov-map`) and a strip at one r (`btob lyapunov-strip`) ----
struct MapRequest {
  core::Decimal r_min = 0.0717, r_max = 0.6;  // r range, each in (0, 1), kept as given (float reads it)
  long r_count = 5000;                        // evenly spaced r values, >= 1
  std::string grid = "paper";                 // paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...
  std::uint64_t seed = 1;                     // seed of random grids
  long iterations = 10000, transient = 1000;
  int blocks = 10;
  std::string precision = "double";  // float or double: the whole cocycle (point, tangent vector, projections)
  std::vector<std::string> overlay;  // named r overlays drawn on the figure (not part of the computation)
  // Also classify every orbit (`btob classify` with this transient and iterations, in double): what extras::of adds
  // after the run (src/extras), so the exponents' run and its speed are the same with or without it.
  bool attractors = false;

  void validate() const;
  std::size_t work_items() const { return static_cast<std::size_t>(r_count); }  // a sweep over r (core/sweep.hpp)
  double map_steps() const;  // r values x initial conditions x (transient + iterations) (core::StepCounted)
  template <class V> void fields(V&& v) {
    v("r-min", r_min, "smallest r, in (0,1)");
    v("r-max", r_max, "largest r, in (0,1)");
    v("r-count", r_count, "number of evenly spaced r values");
    v("grid", grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...");
    v("seed", seed, "seed of random grids");
    v("iterations", iterations, "averaged map iterations per orbit");
    v("transient", transient, "iterations discarded first (orbit and tangent vector)");
    v("blocks", blocks, "batch-means blocks for the error bars");
    v("precision", precision, "cocycle precision: float or double (point and tangent vector)");
    v("overlay", overlay, "named r overlays (default: thresholds, windows)");
    v("attractors", attractors, "also record each orbit's attractor (classify with this transient and iterations)");
  }
};

struct StripRequest {
  core::Decimal r = 0.3;               // restitution coefficient, in (0, 1), kept as given (float reads it)
  std::string grid = "strip:200x100";  // cells n1 along w1 x n2 along w2, w1 range (default [-2, 2])
  long iterations = 5000, transient = 500;
  int blocks = 10;
  std::string precision = "double";

  void validate() const;
  // The grid: "strip:NxM[:w1min:w1max]" (iterate::parse_strip: core::parse_grid with the strip syntax).
  core::Grid spec() const { return iterate::parse_strip(grid, "grid"); }
  std::size_t work_items() const {
    return static_cast<std::size_t>(spec().axis1.cells);
  }                          // columns of w1 cells (core/sweep.hpp)
  double map_steps() const;  // cells x (transient + iterations) (core::StepCounted)
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient, in (0,1)");
    v("grid", grid, "strip:NxM[:w1min:w1max]: N cells along w1 x M along w2 (w2 in [-1, 1], w1 by default in [-2, 2])");
    v("iterations", iterations, "averaged map iterations per orbit");
    v("transient", transient, "iterations discarded first (orbit and tangent vector)");
    v("blocks", blocks, "batch-means blocks for the error bars");
    v("precision", precision, "cocycle precision: float or double (point and tangent vector)");
  }
};

// Exponents of every orbit (orbit o = r index * initial conditions + initial condition index) and, for a map,
// their summary per r.
struct MapResult {
  iterate::Ensemble ensemble;  // the r values and initial conditions iterated (orbit = r index * I + initial condition)
  OrbitExponents exponents;    // per orbit: lambda1, lambda2 and their batch-means errors, chi1, iterations
  RSummary summary;            // lyapunov-map only
  // lyapunov-map only: the line of NAME_summary.csv of each r value (summary_line), formatted by the part that
  // computed it; empty, like summary, on MPI rank 0 when the ranks write their rows (core::HasRows).
  std::vector<std::string> summary_lines;
  std::vector<double> w1, w2;            // lyapunov-strip only: the cell centres, n1 x n2
  std::vector<double> w1_cell, w2_cell;  // lyapunov-strip only: the cell centres along each axis, [n1] and [n2]
  std::size_t n1 = 0, n2 = 0;            // lyapunov-strip only
  double iteration_seconds = 0;          // wall time of the iteration, seconds
  // lyapunov-map --precision float only: the orbits of every k-th r value (at most 64 r values) re-run in double,
  // and how many of them get another sign class (positive / zero / negative, maps.hpp classify).  Float rounds the
  // orbit at 6e-8 per step: near-neutral sinks (r just above 3 - 2 sqrt(2)) lose their orbits to it.
  long float_checked = 0, float_disagree = 0;
  double float_disagree_r = 0;  // the first r value with a disagreement

  // Arrays: r [R]; lambda1, err1, lambda2, err2, chi1 [R, I] (map) or [n1, n2] (strip); summary [R].
  void describe(core::Contents& c) const;
  // lyapunov-map: NAME_summary.csv, per r each statistic of lambda1 with its error bar and the sign fractions (the
  // classification adds the floor 10/n): its header and summary_lines; lyapunov-strip: none.
  core::Tables tables() const;
};

// Line j of NAME_summary.csv (without its newline): r and row j of `s`, each exponent with its error bar
// (core::with_error).  Formatted where the summary is computed (run_part), so that MPI ranks write their lines.
std::string summary_line(double r, const RSummary& s, std::size_t j);

// Some r values of a map (items: ascending indices into linspace(r-min, r-max, r-count)): the exponents of their
// orbits, item-major ([items, initial conditions]), and what the result derives from them per r, computed here
// (each r's from its own orbits alone, so any partition gives the same rows): the summary of lambda1 and, in float,
// the check of every k-th r value in double.  The per-orbit exponents are then the bulk that MPI ranks write
// themselves (rows()): nothing merged reads them.
struct MapPart {
  std::vector<std::size_t> items;
  OrbitExponents exponents;
  RSummary summary;                        // lyapunov-map: [items]
  std::vector<std::string> summary_lines;  // lyapunov-map: [items], summary_line
  long float_checked = 0, float_disagree = 0;
  std::size_t float_disagree_item = static_cast<std::size_t>(-1);  // the first item with a disagreement
  double iteration_seconds = 0;
  template <class A> void members(A& a) {
    a(items, exponents.lambda1, exponents.err1, exponents.lambda2, exponents.err2, exponents.lambda_max,
      exponents.err_max, exponents.lambda_min, exponents.err_min, exponents.chi1, exponents.iterations,
      exponents.blocks, summary.min, summary.median, summary.max, summary.err_min, summary.err_median, summary.err_max,
      summary.frac_positive, summary.frac_zero, summary.frac_negative, summary_lines, float_checked, float_disagree,
      float_disagree_item, iteration_seconds);
  }
  // The per-orbit exponents, the per-r summary and its table's lines, by their datasets' and table's names
  // (core::HasRows; lyapunov-strip has no summary: its datasets and table do not exist and are skipped).  Rank 0 then
  // keeps of each r value only its r and the float check's counts.
  template <class A> void rows(A& a) {
    a("lambda1", exponents.lambda1);
    a("err1", exponents.err1);
    a("lambda2", exponents.lambda2);
    a("err2", exponents.err2);
    a("lambda_max", exponents.lambda_max);
    a("err_max", exponents.err_max);
    a("lambda_min", exponents.lambda_min);
    a("err_min", exponents.err_min);
    a("chi1", exponents.chi1);
    a("min", summary.min);
    a("median", summary.median);
    a("max", summary.max);
    a("min_err", summary.err_min);
    a("median_err", summary.err_median);
    a("max_err", summary.err_max);
    a("frac_positive", summary.frac_positive);
    a("frac_zero", summary.frac_zero);
    a("frac_negative", summary.frac_negative);
    a("summary", summary_lines);
  }
};
MapPart run_part(const MapRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control = {});
MapResult merge(const MapRequest& req, std::vector<MapPart> parts);
// merge(req, {run_part(req, every r)}).
MapResult run(const MapRequest& req, const core::RunControl& control = {});
// Some w1 columns of a strip (items: ascending indices 0..n1-1): their n2 cells each, item-major.
MapPart run_part(const StripRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control = {});
MapResult merge(const StripRequest& req, std::vector<MapPart> parts);
// merge(req, {run_part(req, every column)}).
MapResult run(const StripRequest& req, const core::RunControl& control = {});

}  // namespace btob::lyapunov
