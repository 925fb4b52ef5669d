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
  long leaf_iterations = 20000;         // map steps along each of those leaves
  int max_m = 12;                       // resonances l / m with m <= max-m
  attractors::Options thresholds;       // the classifier's thresholds (attractors::threshold_fields)

  void validate() const;
  std::vector<double> all_r() const;    // r, or the range
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
  Request request;  // the request, as run (validated)
  attractors::Grid grid;  // the strip grid of initial conditions (n1 cells along w1, n2 along w2)
  std::vector<double> axis1, axis2;  // the grid's cell centres
  // [R] per r:
  std::vector<double> r, cos_theta, rotation, I_max, region_share, region_mean;
  std::vector<double> mass, mass_low, mass_high, landing_mean, landing_sd, outside_mass;
  std::vector<std::uint64_t> q2, above_one, undecided;
  // [R, bins] (coarse: [R, bins / 2]):
  std::vector<double> density, density_low, density_high, kde, density_coarse, region_density;
  std::vector<double> label_map;     // [R, n2, n1]: the landing label, -1 off the P2 curves
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

Result run(const Request& req, const core::RunControl& control = {});

}  // namespace btob::leaves
