// SPDX-License-Identifier: GPL-3.0-or-later
// The statistics of Section 8.1 (2) as requests and results (core/request.hpp): C_N along one orbit with its
// power spectrum (`btob correlate`), and the empirical measures of many initial conditions at one r with their
// distances, groups and convergence against N (`btob measure`).
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/sweep.hpp"
#include "core/work.hpp"
#include "iterate/ensemble.hpp"
#include "stats/stats.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::stats {

// ---- C_N(phi, psi; n) along one orbit (`btob correlate`) ----------------------------------------------------
struct CorrelateRequest {
  double r = 0.11;                   // restitution coefficient, in (0, 1)
  std::string point = "1,-3,-1.1";   // initial direction x,y,z (x*z <= 0); the first point of the Section 4 grid
  std::string observable = "phi";    // phi[,psi], psi = phi when omitted (angles in rad)
  long n_max = 1000;                 // largest lag, 0 <= n-max < iterations
  long iterations = 100000;          // N, the number of terms averaged (the orbit has N + n-max states), >= 2
  long transient = 10000;            // map iterations discarded before x_0, >= 0
  std::string method = "fft";        // fft, direct or both
  std::string precision = "double";  // arithmetic of C_N: float, double or long-double
  long window = 10;                  // lags per window of the |C_N| envelope, >= 1
  long fit_lags = 200;               // lags 1..fit-lags enter the decay fit, >= window

  void validate() const;
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient, in (0,1)");
    v("point", point, "initial point x,y,z (domain x*z <= 0; any scale)");
    v("observable", observable,
      "phi[,psi], each one of " + observable_names() + " (angles in rad; psi = phi when omitted)");
    v("n-max", n_max, "largest lag n, 0 <= n-max < iterations");
    v("iterations", iterations, "N, the number of terms averaged (the orbit has N + n-max states)");
    v("transient", transient, "map iterations discarded before x_0");
    v("method", method, "fft (FFTW, O(N log N)), direct (the sum, O(N n-max)) or both (compared)");
    v("precision", precision, "arithmetic of C_N: float, double or long-double");
    v("window", window, "lags per window of the |C_N| envelope");
    v("fit-lags", fit_lags, "lags 1..fit-lags enter the decay-rate fit (needs n-max >= fit-lags)");
  }
};

struct CorrelateResult {
  CorrelateRequest request;                                 // the request, as run (validated)
  Observable phi = Observable::phi, psi = Observable::phi;  // the two observables of C_N (the request's)
  std::vector<double> c;                   // C_N(n), n = 0..n-max (computed in the request's precision)
  std::vector<double> c_direct;            // method both: the direct sum, else empty
  std::vector<double> envelope;            // max |C_N| over windows of `window` lags from lag 1
  std::vector<double> frequency;           // periodogram of phi over the first N values, averaged to <= 8192 points
  std::vector<double> power;               // the periodogram's power at each `frequency`
  double seconds = 0, seconds_direct = 0;  // wall times of the FFT route and of the direct sum (method both), seconds
  double max_rel_diff = 0;                 // method both: max |fft - direct| / max |direct|
  double peak_frequency = 0;               // of the unaveraged periodogram, cycles per iteration
  double noise_floor = 0;                  // 4 |C_N(0)| / sqrt(N)
  bool fitted = false;                     // n-max >= fit-lags >= 3 window: `decay` holds the fit
  Decay decay;                             // the fitted decay rate of the |C_N| envelope (when `fitted`)

  long N() const { return request.iterations; }
  // Arrays: C_N [n-max + 1], C_N_direct [n-max + 1] (method both), envelope [windows], spectrum_frequency and
  // power_spectrum [points]; attributes: the request, timings, noise floor, spectrum peak and the decay fit.
  void describe(core::Contents& c) const;
  // NAME.csv: lag,C_N[,C_N_direct] (what the run was is in NAME.json and NAME.h5).
  core::Tables tables() const;
};

CorrelateResult run(const CorrelateRequest& req, const core::RunControl& control = {});
// Its cost (core/work.hpp): the orbit's map steps (transient + iterations + n-max) with its FFT correlation and
// spectrum, and for method direct or both the direct sum's iterations x (n-max + 1) products.
core::Work work(const CorrelateRequest& req);

// ---- empirical measures at one r (`btob measure`) ------------------------------------------------------------
struct MeasureRequest {
  double r = 0.15;               // restitution coefficient, in (0, 1)
  std::string grid = "paper";    // initial conditions: paper, strip:NxM[:w1min:w1max], random:N, x,y,z;...
  std::uint64_t seed = 1;        // seed of random grids
  long iterations = 100000;      // N, points per measure (after the transient), >= 16
  long transient = 10000;        // map iterations discarded first, >= 0
  int bins = 200;                // bins per direction, 1..4000
  std::string coords = "strip";  // strip or angles
  std::vector<double> extent;    // empty, or u_lo,u_hi,v_lo,v_hi (zoom; mass outside kept as one cell)
  double tv_same = 0.05;         // measures closer than this in total variation are one group, in (0, 1]

  void validate() const;
  std::size_t work_items() const;  // the initial conditions of the grid (a sweep, core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient, in (0,1)");
    v("grid", grid, "initial conditions: paper (Section 4, 32 points), strip:NxM, random:N, x,y,z;...");
    v("seed", seed, "seed of random grids");
    v("iterations", iterations, "N, points per measure (after the transient), >= 16");
    v("transient", transient, "map iterations discarded first");
    v("bins", bins, "bins per direction, 1..4000");
    v("coords", coords, "strip (atan w1 in (-pi/2, pi/2), w2 in [-1,1]) or angles (theta, phi in rad)");
    v("extent", extent,
      "u_lo,u_hi,v_lo,v_hi: histogram only this part of the chart (zoom); mass outside is kept as one extra cell");
    v("tv-same", tv_same, "two measures closer than this in total variation count as one attractor");
  }
};

struct MeasureResult {
  MeasureRequest request;                         // the request, as run (validated)
  std::vector<iterate::Vec3<double>> initial;     // the initial conditions, in grid order
  std::vector<int> group;                         // per initial condition: its group 0..G-1 (by first appearance)
  std::vector<std::uint64_t> group_index;         // the same as uint64 (the HDF5 dataset `group`)
  std::vector<std::uint64_t> head, size;          // per group: its first member and its number of members
  std::vector<double> tv, w1_u, w1_v;             // per initial condition: distances to the head of its group
  std::vector<double> tv_max_group;               // per group: largest TV between two of its members
  std::vector<double> conv_n;                     // N = 16, 32, ..., iterations
  std::vector<double> conv_within, conv_to_full;  // [checkpoints, G]
  std::vector<std::uint32_t> counts;              // [G, bins, bins]: the head's counts per bin (mass * N)
  std::vector<double> marginal_u, marginal_v;     // [G, bins]
  std::vector<double> outside;                    // [G]: the head's mass outside the extent
  std::vector<double> extent;                     // the histogram's u_lo, u_hi, v_lo, v_hi
  std::size_t groups() const { return head.size(); }
  double tv_max_within_groups() const;

  // Arrays: group_counts [G, bins, bins], group_marginal_u/v [G, bins], group_head, group_size, group_outside,
  // group_tv_max [G], group, tv_to_group_head, w1_u/v_to_group_head [I], convergence_n [C],
  // convergence_tv_within_group and convergence_tv_to_full [C, G], extent [4].
  void describe(core::Contents& c) const;
  // NAME_report.csv: per initial condition its group and distances to the group's first member (the run's r, grid,
  // iterations, bins and chart are in NAME.json and NAME.h5).
  core::Tables tables() const;
};

// Some initial conditions (items: ascending grid indices): the bin of every point of their orbits (stats::
// measure_cells, -1 outside the extent), item-major [items, iterations].  Every measure of the result, at the full
// length and at the convergence checkpoints, is counted from these bins in merge, so the orbits never travel and
// the groups, distances and convergence are computed once, over all initial conditions in grid order.
// No rows(): the orbits' bins are no dataset; merge counts every measure, group and distance from them.
struct MeasurePart {
  std::vector<std::size_t> items;
  std::vector<std::int32_t> cells;
  double seconds = 0;
  template <class A> void members(A& a) { a(items, cells, seconds); }
};
MeasurePart run_part(const MeasureRequest& req, const std::vector<std::size_t>& items,
                     const core::RunControl& control = {});
MeasureResult merge(const MeasureRequest& req, std::vector<MeasurePart> parts);
// merge(req, {run_part(req, every initial condition)}).
MeasureResult run(const MeasureRequest& req, const core::RunControl& control = {});

}  // namespace btob::stats
