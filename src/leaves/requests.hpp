// SPDX-License-Identifier: GPL-3.0-or-later
// `btob leaves` / btob.leaves: Section 8's programme on P2's invariant curves at one r or across r.
//   the leaves:        label t in closed form (leaves/geometry.hpp), the labels whose leaf stays in P2's region
//                      (0 <= t <= 1), the region's sphere measure and the law of labels it carries, the rotation
//                      number theta / (2 pi) of every such leaf against weighted Birkhoff averages along the map;
//   (i) landing:       the law of the label of the leaf each orbit of a grid lands on (the classifier's "Q2"), a
//                      density with Clopper-Pearson bands, a second estimator (kernel), two bin widths, its mass;
//   (ii) leaf measure: Kolmogorov-Smirnov distances of long orbits' eigen-angles to the uniform eigen-angle (the
//                      invariant probability) and to normalised arc length (strip chart and sphere);
//   (iv) across r:     all of the above per r of a range, with the resonances theta / (2 pi) = l / m (the thin
//                      stripes r(l/m) of eq. (6.3)).
#pragma once

#include "attractors/requests.hpp"
#include "core/request.hpp"
#include "core/result.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::leaves {

struct Request {
  double r = 0.25;                      // one r in (3 - 2 sqrt(2), 1) (used when r-count is 0)
  double r_min = 0.18, r_max = 0.6;     // a range of r-count values, both ends included
  long r_count = 0;                     // 0: the single r
  std::string grid = "sphere:60x60";    // initial points: sphere:NxM (the sphere measure) or strip:NxM
  std::vector<double> w1_range{-2, 2};  // w1 range of a strip grid
  int bins = 20;                        // label bins over [0, 1] (even: the coarse histogram has bins / 2)
  std::vector<double> labels{0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.05, 1.2};  // leaves followed by the map
  long leaf_iterations = 20000;                                          // map steps along each of those leaves
  int max_m = 12;                                                        // resonances l / m with m <= max-m
  attractors::Options thresholds;  // the classifier's thresholds (attractors::threshold_fields)

  void validate() const;
  std::vector<double> all_r() const;                         // r, or the range
  std::size_t work_items() const { return all_r().size(); }  // a sweep over all_r() (core/sweep.hpp)
  attractors::Grid parsed_grid() const;
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient in (3 - 2 sqrt(2), 1) = (0.1716, 1) (when r-count is 0)");
    v("r-min", r_min, "smallest r of the range, in (3 - 2 sqrt(2), 1)");
    v("r-max", r_max, "largest r of the range, in (3 - 2 sqrt(2), 1)");
    v("r-count", r_count, "r values of the range r-min..r-max, 0..1000 (0: the single r)");
    v("grid", grid, "initial points: sphere:NxM (uniform measure on the sphere of directions) or strip:NxM");
    v("w1-range", w1_range, "w1 range a,b of a strip grid");
    v("bins", bins, "label bins over [0, 1], even, 2..1000");
    v("labels", labels, "labels t of the leaves followed by the map, each in (0, 3]");
    v("leaf-iterations", leaf_iterations, "map steps along each followed leaf, 100..1e7");
    v("max-m", max_m, "resonances theta / (2 pi) = l / m marked up to this m, 2..120");
    attractors::threshold_fields(v, thresholds);
  }
};

struct Result {
  Request request;                   // the request, as run (validated)
  attractors::Grid grid;             // the strip grid of initial conditions (n1 cells along w1, n2 along w2)
  std::vector<double> axis1, axis2;  // the grid's cell centres
  // [R] per r:
  std::vector<double> r, cos_theta, rotation, I_max, region_share, region_mean;
  std::vector<double> mass, mass_low, mass_high, landing_mean, landing_sd, outside_mass;
  std::vector<std::uint64_t> q2, above_one, undecided;
  // [R, bins] (coarse: [R, bins / 2]):
  std::vector<double> density, density_low, density_high, kde, density_coarse, region_density;
  std::vector<double> label_map;  // [R, n2, n1]: the landing label, -1 off the P2 curves (empty where the MPI
                                  // ranks write its rows themselves)
  // [R, labels]: the leaves followed by the map
  std::vector<double> leaf_exact, leaf_birkhoff, leaf_birkhoff_half, leaf_exit, leaf_drift;
  std::vector<double> ks_uniform, ks_strip, ks_sphere, law_strip, law_sphere;
  std::vector<std::uint8_t> leaf_stays;
  // Resonances l / m (m <= max-m) with their r (eq. (6.3)), all of them in (3 - 2 sqrt(2), 1):
  std::vector<double> stripe_r;
  std::vector<std::uint64_t> stripe_l, stripe_m;
  double ks_critical = 0;
  double seconds = 0;
  int threads = 0;

  void describe(core::Contents& c) const;
  // NAME.csv (per r), NAME_landing.csv (per r and bin), NAME_leaves.csv (per r and followed leaf).
  core::Tables tables() const;
};

// Every array of a Result with one row per r, with its row width (B label bins, C grid cells, L followed leaves), in
// one order: what a sweep's part carries (Part::members) and merge() places by item.  R: Result or const Result.
template <class R, class F> void per_r_arrays(R& res, std::size_t B, std::size_t C, std::size_t L, F&& f) {
  for (auto* v : {&res.r, &res.cos_theta, &res.rotation, &res.I_max, &res.region_share, &res.region_mean, &res.mass,
                  &res.mass_low, &res.mass_high, &res.landing_mean, &res.landing_sd, &res.outside_mass})
    f(*v, std::size_t{1});
  for (auto* v : {&res.q2, &res.above_one, &res.undecided}) f(*v, std::size_t{1});
  for (auto* v : {&res.density, &res.density_low, &res.density_high, &res.kde, &res.region_density}) f(*v, B);
  f(res.density_coarse, B / 2);
  f(res.label_map, C);
  for (auto* v : {&res.leaf_exact, &res.leaf_birkhoff, &res.leaf_birkhoff_half, &res.leaf_exit, &res.leaf_drift,
                  &res.ks_uniform, &res.ks_strip, &res.ks_sphere, &res.law_strip, &res.law_sphere})
    f(*v, L);
  f(res.leaf_stays, L);
}

// Some r values (items: ascending indices into all_r()): their rows of every per-r array (per_r_arrays), in item
// order.  Each r's numbers depend only on the request and the r, so any partition merges to run()'s result bitwise.
// The landing labels of the grid's points (label_map, C values per r) are the bulk, written by the MPI ranks
// themselves (rows()): the landing law, mass and moments are computed from them per r here, and nothing merged
// reads them.
struct Part {
  std::vector<std::size_t> items;
  Result per_r;  // only the per-r arrays are set
  double seconds = 0;
  int threads = 0;
  template <class A> void members(A& a) {
    a(items, seconds, threads);
    per_r_arrays(per_r, 0, 0, 0, [&](auto& v, std::size_t) { a(v); });
  }
  // The label map, by its dataset's name (core::HasRows).
  template <class A> void rows(A& a) { a("label_map", per_r.label_map); }
};
Part run_part(const Request& req, const std::vector<std::size_t>& items, const core::RunControl& control = {});
Result merge(const Request& req, std::vector<Part> parts);
// merge(req, {run_part(req, every r)}).
Result run(const Request& req, const core::RunControl& control = {});

}  // namespace btob::leaves
