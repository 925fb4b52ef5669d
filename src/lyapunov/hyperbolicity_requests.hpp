// SPDX-License-Identifier: GPL-3.0-or-later
// The (non-)hyperbolicity analyses of Section 8.1 (3) as requests and results (core/request.hpp): singular values
// of the one-step derivative over a strip grid (`btob hyperbolicity`), and per r the fraction of expanding steps
// and the angles between covariant Lyapunov vectors along orbits, beside lambda1 (`btob hyperbolicity-orbits`).
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/sweep.hpp"
#include "iterate/ensemble.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/maps.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace btob::lyapunov {

// ---- singular values over a strip grid (`btob hyperbolicity`) -----------------------------------------------
struct HyperbolicityRequest {
  double r = 0;                        // restitution coefficient, in (0, 1)
  std::string grid = "strip:400x200";  // strip:NxM, cells along w1 x w2 (core::parse_grid; no range here)
  std::string w1_range = "-2,2";       // w1 range a,b of the image, finite, a < b (w2 runs over [-1, 1])

  void validate() const;
  std::size_t work_items() const;  // columns of w1 cells, N of strip:NxM (a sweep, core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient, in (0,1)", core::required);
    v("grid", grid, "strip:NxM cells along w1 x w2");
    v("w1-range", w1_range, "w1 range a,b of the image");
  }
  // The file stem when none is given: hyperbolicity_strip_r<r>.
  std::string default_name() const;
  core::Grid strip() const;  // the grid with the range of w1-range (validated)
};

struct HyperbolicityResult {
  HyperbolicityRequest request;          // the request, as run (validated)
  StripSingularValues image;             // s1, s2, symbol, w1, w2 over n1 x n2 cells, and the expanding fraction
                                         // (s1, s2, symbol empty where the MPI ranks write their rows themselves)
  std::vector<double> w1_cell, w2_cell;  // [n1], [n2]: the cell centres along each axis
  double s1_min = 0, s1_max = 0;         // the extremes of s1 over the cells (the printed line)
  double seconds = 0;                    // wall time of the run, seconds

  // Arrays: s1, s2, symbol, w1, w2 [n1, n2]; attributes: r, alpha, grid, w1 range, metric, expanding_fraction.
  void describe(core::Contents& c) const;
};

// Some w1 columns of the strip (items: ascending indices 0..N-1): the n2 cells of each, item-major, and what the
// result derives from them, counted here (a count and extremes over the part's cells: any partition sums and folds
// them to the same numbers).  The cells' values are then the bulk that MPI ranks write themselves (rows()).
struct HyperbolicityPart {
  std::vector<std::size_t> items;
  std::vector<double> s1, s2;        // [items, n2]
  std::vector<std::uint8_t> symbol;  // [items, n2]
  long expanding = 0;                // cells with s1 >= 1
  double s1_min = std::numeric_limits<double>::infinity(), s1_max = -std::numeric_limits<double>::infinity();
  double seconds = 0;
  template <class A> void members(A& a) { a(items, s1, s2, symbol, expanding, s1_min, s1_max, seconds); }
  // The cells' singular values and branches, by their datasets' names (core::HasRows).
  template <class A> void rows(A& a) {
    a("s1", s1);
    a("s2", s2);
    a("symbol", symbol);
  }
};
HyperbolicityPart run_part(const HyperbolicityRequest& req, const std::vector<std::size_t>& items,
                           const core::RunControl& control = {});
// The columns in item order; the cell centres from the grid, the expanding fraction and s1's extremes from the
// parts' counts (never from the merged cells, which the MPI ranks may keep).
HyperbolicityResult merge(const HyperbolicityRequest& req, std::vector<HyperbolicityPart> parts);
// merge(req, {run_part(req, every column)}).
HyperbolicityResult run(const HyperbolicityRequest& req, const core::RunControl& control = {});

// ---- CLV angles and expanding steps along orbits over r (`btob hyperbolicity-orbits`) ------------------------
struct HyperbolicityOrbitsRequest {
  double r_min = 0.0717, r_max = 0.6;  // r range, each in (0, 1)
  long r_count = 100;                  // evenly spaced r values, 1..1000000
  std::string grid = "paper";          // paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...
  std::uint64_t seed = 1;              // seed of random grids
  long iterations = 10000;             // window: steps with CLV angles and expanding flags, >= 10 (10 blocks)
  long transient = 10000;              // forward steps before the window, >= 0
  long backward = 10000;               // forward steps after the window, iterated back first, >= 1
  int bins = 90;                       // angle histogram bins over [0, pi/2], >= 1

  void validate() const;
  std::size_t work_items() const { return static_cast<std::size_t>(r_count); }  // a sweep over r (core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("r-min", r_min, "smallest r, in (0,1)");
    v("r-max", r_max, "largest r, in (0,1)");
    v("r-count", r_count, "number of evenly spaced r values");
    v("grid", grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...");
    v("seed", seed, "seed of random grids");
    v("iterations", iterations, "window: steps with CLV angles and expanding flags");
    v("transient", transient, "forward steps before the window");
    v("backward", backward, "forward steps after the window, iterated back first");
    v("bins", bins, "angle histogram bins over [0, pi/2]");
  }
};

struct HyperbolicityOrbitsResult {
  HyperbolicityOrbitsRequest request;  // the request, as run (validated)
  iterate::Ensemble ensemble;  // the r values and initial conditions iterated (orbit = r index * I + initial condition)
  std::size_t bins = 0;        // bins of the CLV angle histogram (angle_histogram)
  // Per r [R]: pooled over the orbits (angles only from non-degenerate ones), NaN when no orbit contributes.
  std::vector<double> frac_expanding, angle_median, angle_q05, angle_min, frac_degenerate, lambda1_qr_median;
  std::vector<double> angle_histogram;  // [R, bins]
  // Per orbit [R, I] (with angle_histogram: empty where the MPI ranks write their rows themselves).
  std::vector<double> orbit_frac_expanding, orbit_angle_median, orbit_angle_q05, orbit_lambda1_qr, orbit_lambda2_qr;
  std::vector<std::uint8_t> orbit_degenerate;
  std::vector<double> orbit_lambda1;  // lambda1 from the batched tangent recorder on the same orbits, 10 blocks
  RSummary summary;                   // its summary per r [R]
  int threads = 0;                    // threads of the CLV loop
  double clv_seconds = 0;

  void describe(core::Contents& c) const;
  // NAME_summary.csv: per r the expanding and degenerate fractions, the CLV angle's median, 5% quantile and minimum
  // (empty cells where every orbit is degenerate: no angle is defined), lambda1's median and sign fraction.
  core::Tables tables() const;
};

// Some r values (items: ascending indices into linspace(r-min, r-max, r-count)): everything per r and per orbit
// of them, item-major, and lambda1 of their orbits (the whole request's grid) with its summary per r.  Each r's
// pooled statistics and summary depend on its own orbits only, so they are rows like the rest, computed here; the
// per-orbit arrays and the histograms are then the bulk that MPI ranks write themselves (rows()): nothing merged
// reads them.
struct HyperbolicityOrbitsPart {
  std::vector<std::size_t> items;
  std::vector<double> frac_expanding, angle_median, angle_q05, angle_min, frac_degenerate,
      lambda1_qr_median;                // [items]
  RSummary summary;                     // [items]: lambda1's (summarise)
  std::vector<double> angle_histogram;  // [items, bins]
  std::vector<double> orbit_frac_expanding, orbit_angle_median, orbit_angle_q05, orbit_lambda1_qr, orbit_lambda2_qr,
      orbit_lambda1;                           // [items, I]
  std::vector<std::uint8_t> orbit_degenerate;  // [items, I]
  int threads = 0;
  double clv_seconds = 0;
  template <class A> void members(A& a) {
    a(items, frac_expanding, angle_median, angle_q05, angle_min, frac_degenerate, lambda1_qr_median, summary.min,
      summary.median, summary.max, summary.err_min, summary.err_median, summary.err_max, summary.frac_positive,
      summary.frac_zero, summary.frac_negative, angle_histogram, orbit_frac_expanding, orbit_angle_median,
      orbit_angle_q05, orbit_lambda1_qr, orbit_lambda2_qr, orbit_lambda1, orbit_degenerate, threads, clv_seconds);
  }
  // The per-orbit arrays and the angle histograms, by their datasets' names (core::HasRows).
  template <class A> void rows(A& a) {
    a("angle_histogram", angle_histogram);
    a("orbit_frac_expanding", orbit_frac_expanding);
    a("orbit_angle_median", orbit_angle_median);
    a("orbit_angle_q05", orbit_angle_q05);
    a("orbit_lambda1_qr", orbit_lambda1_qr);
    a("orbit_lambda2_qr", orbit_lambda2_qr);
    a("orbit_lambda1", orbit_lambda1);
    a("orbit_degenerate", orbit_degenerate);
  }
};
HyperbolicityOrbitsPart run_part(const HyperbolicityOrbitsRequest& req, const std::vector<std::size_t>& items,
                                 const core::RunControl& control = {});
// The rows in item order (the parts' per-r rows, lambda1's summary among them).
HyperbolicityOrbitsResult merge(const HyperbolicityOrbitsRequest& req, std::vector<HyperbolicityOrbitsPart> parts);
// merge(req, {run_part(req, every r)}).
HyperbolicityOrbitsResult run(const HyperbolicityOrbitsRequest& req, const core::RunControl& control = {});

}  // namespace btob::lyapunov
