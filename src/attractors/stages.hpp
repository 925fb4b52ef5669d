// SPDX-License-Identifier: GPL-3.0-or-later
// The stages the attractors module's files share (classify.cpp, certify.cpp, basins.cpp), declared here so that each
// can be called and tested alone.  Not part of the module's public API (attractors.hpp).
#pragma once

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "attractors/attractors.hpp"

namespace btob::attractors::stages {

// r <= 7 - 4 sqrt(3): the eigenvalues of P1 and P3 are real and the collapse z = 0 (x = 0) attracts (Section 5.2).
// Decided exactly.
bool collapse_possible(double r);
// The smallest rotation of w in the order 1 < 3 < 2 of patterns::canonical (no J: mirrors stay apart), and its
// shift k (w rotated by k).
patterns::Word smallest_rotation(const patterns::Word& w, std::size_t* shift = nullptr);
// |a - b|_inf.
inline double dist_max(const Vec3<double>& a, const Vec3<double>& b) { return (a - b).cwiseAbs().maxCoeff(); }

// One periodic key's exact orbit (patterns::analyse), cached per classification by key.
struct ExactCycle {
  patterns::Verdict<double> verdict;
  std::vector<Vec3<double>> points;
};
using ExactCycles = std::map<std::string, ExactCycle>;

// The classification of orbits that have already made `done` < transient steps (ens.initial holds their kernel
// states): the first pass runs the remaining transient - done steps, so every verdict is classify()'s from the
// original starts (the kernel restarted from its own state continues bit for bit).
std::vector<OrbitVerdict> classify_from(const iterate::Ensemble& ens, const Options& opt, long done);

// The attractor reached by the verdict v (the first of its basin): type, key, spellings, the exact cycle's point and
// stability for periodic keys; count 0, ranges start at v's values.
Attractor attractor_of(const OrbitVerdict& v, double r);

// The ranges of rotation number and invariant I of an attractor (Attractor, BasinClass) widened by [rot_lo, rot_hi]
// and [inv_lo, inv_hi]: the one merge of those extrema.
template <class Ranges>
void widen_curve_ranges(Ranges& into, double rot_lo, double rot_hi, double inv_lo, double inv_hi) {
  into.rotation_min = std::min(into.rotation_min, rot_lo);
  into.rotation_max = std::max(into.rotation_max, rot_hi);
  into.invariant_min = std::min(into.invariant_min, inv_lo);
  into.invariant_max = std::max(into.invariant_max, inv_hi);
}
// By one verdict's values.
template <class Ranges> void widen_curve_ranges(Ranges& into, const OrbitVerdict& v) {
  widen_curve_ranges(into, v.rotation, v.rotation, v.invariant, v.invariant);
}

}  // namespace btob::attractors::stages
