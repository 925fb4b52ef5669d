// SPDX-License-Identifier: GPL-3.0-or-later
// The leaves' dynamics: one leaf followed by the map (rotation number, the empirical measure against the invariant
// probability and against arc length) and where the orbits of a grid land (the attractor classifier's "P2 invariant
// curves", key "Q2", with the label of their leaf).
#pragma once

#include "attractors/attractors.hpp"
#include "core/cancel.hpp"
#include "leaves/geometry.hpp"

#include <cstddef>
#include <vector>

namespace btob::leaves {

// One orbit of the map P_r (core::step, double) from the point of label t and eigen-angle 0, for n steps.
//  * Rotation: the exact theta / (2 pi) (leaves with t <= 1 never leave P2's region, where the map is P2) against the
//    weighted Birkhoff average of the eigen-angle increments (Das-Yorke weights exp(-1 / (x (1 - x))), x = (j - 1/2)
//    / n, as the classifier's RotationRecorder; over n and over n / 2 steps).
//  * Measure: the Kolmogorov-Smirnov distance D_n = sup |F_n - F| of the n eigen-angles psi_0 .. psi_{n-1} to three
//    laws: uniform in psi (the push-forward of the rotation's invariant probability, the leaf's invariant measure when
//    theta / (2 pi) is irrational), normalised arc length in the strip chart, and normalised arc length on the sphere;
//    and the distance sup |U - G| between the uniform law and each arc-length law (the leaf's own geometry).  At the
//    95% level D_n is significant above ks_critical(n) = 1.358 / sqrt(n) (independent samples; the rotation's samples
//    are far more even, D_n = O(log n / n) against its own law, so this scale is conservative for acceptance).
struct LeafStudy {
  double t = 0, I = 0;
  double exact_rotation = 0;                           // theta / (2 pi)
  double birkhoff = 0, birkhoff_half = 0;              // weighted averages over n and over the first n / 2 increments
  bool stays = true;                                   // every step used P2 (symbol 2)
  long exit_step = -1;                                 // first step with symbol 1 or 3 (-1: none)
  double label_drift = 0;                              // max |t_k - t| over the steps before the exit (rounding only)
  double ks_uniform = 0, ks_strip = 0, ks_sphere = 0;  // D_n against the three laws
  double law_strip = 0, law_sphere = 0;                // sup |U - G| for each arc-length law
};
LeafStudy study_leaf(double t, const Geometry& g, long n, const core::CancelToken* cancel = nullptr);
double ks_critical(long n);  // 1.358 / sqrt(n): the asymptotic 95% point of sqrt(n) D_n (Kolmogorov)

// Where the orbits of a grid land: per grid point (grid_points order) the label t of the leaf its orbit reached when
// the classifier's verdict is "Q2" (quasi-periodic in P2's region, the basins command's "P2 invariant curves"), the
// weighted mean of I over its record turned into t; -1 for every other verdict.
struct Landing {
  std::vector<double> t;
  std::size_t q2 = 0;         // orbits on a P2 invariant curve
  std::size_t above_one = 0;  // of those, labels above 1 (a leaf that leaves the region: none expected)
  std::size_t undecided = 0;  // orbits the classifier left undecided
};
Landing land(const Geometry& g, const attractors::Grid& grid, const attractors::Options& opt);

// The law of the labels in [0, 1] as a density per unit t with respect to the grid's measure (total mass = the
// fraction of points on a P2 curve): per bin the count / (N h), and the Clopper-Pearson 95% interval of the count
// (binomial: each point lands in the bin or not) divided by h.  `kde`: a second estimator, a Gaussian kernel density
// with bandwidth h reflected at 0 and 1, at the bin centres.
struct Density {
  std::vector<double> value, low, high, kde;
  double mean = 0, sd = 0;  // of the labels <= 1
};
Density density(const std::vector<double>& t, int bins);

}  // namespace btob::leaves
