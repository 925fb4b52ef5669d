// SPDX-License-Identifier: GPL-3.0-or-later
// Ensembles of orbits: r values x initial conditions (the Section 4 grid, strip grids, seeded random, lists).
#pragma once

#include "core/grid.hpp"
#include "core/map.hpp"
#include "core/request.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace btob::iterate {

using core::Vec3;

// Orbit o of an ensemble has r = r[o / initial.size()] and starts at initial[o % initial.size()]:
// every r value sees the same initial conditions (same grid, same seed).
//
// r in the run's precision: r holds the double values (what double runs use, bit for bit as linspace_r gives them);
// the decimal source below lets every other precision T evaluate r from the request's text (r_at<T>), so a float128
// run at r = 0.1 uses float128's 0.1, not double's 0.1 widened (5.5e-18 relative).  Set r through set_r_range /
// set_r_list to keep the source; r assigned directly (values computed in double: window bounds, probes) has none,
// and r_at<T> widens the double exactly.
struct Ensemble {
  std::vector<double> r;              // restitution coefficients, each in (0, 1)
  std::vector<Vec3<double>> initial;  // initial directions, each in the domain x*z <= 0
  std::string grid_description;       // how `initial` was made (recorded in every result)
  std::uint64_t seed = 0;             // seed of random grids (0 when none)

  // The decimal source of r: a list (r_text[j] is the text of r[j]) or a range (r[j] is the value of index
  // r_index[j] of r_count evenly spaced values from r_lo to r_hi); both empty when r has no decimal source.
  std::vector<std::string> r_text;
  std::string r_lo, r_hi;
  long r_count = 0;
  std::vector<std::size_t> r_index;

  std::size_t orbits() const { return r.size() * initial.size(); }

  // r[j] in precision T.  double: r[j] itself.  Otherwise from the source: a listed value is T's nearest to its
  // text; a range value is lo + (hi - lo) i / (n - 1) evaluated in T from T's lo and hi (the expression and order
  // of linspace_r, so each precision rounds it like double does; i = 0 and i = n - 1 are exactly lo and hi), for
  // float rounded once from float128 (the float nearest the exact value but for ties within 1e-34).  No source:
  // T(r[j]), exact.  T = float, double, long double, core::float128, core::mpfr_float (at MPFR's current default
  // precision: hold a core::MpfrDigits).  Throws std::logic_error when r and its source disagree in size.
  template <class T> T r_at(std::size_t j) const;
  // r_at<T> for every j.
  template <class T> std::vector<T> r_in() const;

  // r = the values of the given indices (all when null) of linspace_r(lo, hi, n), with their source: a sweep's part
  // keeps the whole request's range and its items' indices.
  void set_r_range(const core::Decimal& lo, const core::Decimal& hi, long n,
                   const std::vector<std::size_t>* items = nullptr);
  // r = the listed values, with their texts.
  void set_r_list(const std::vector<core::Decimal>& values);
  // The ensemble restricted to the r values of the given indices (source kept), same initial conditions.
  Ensemble with_r(const std::vector<std::size_t>& indices) const;
};

// n evenly spaced values from a to b inclusive (n = 1 gives a).  Throws on an empty or invalid range.
std::vector<double> linspace_r(double a, double b, long n);

// The 8x4 grid of Section 4: X = (1, -(1+8)/(2+g), -0.1-h), g = 1..8, h = 1..4, as printed in the paper
// (y = -9/(2+g); README explains the choice).  Ordered g-major.
std::vector<Vec3<double>> paper_grid();

// An n1 x n2 grid of cell centres on the strip (eq. (6.4)): w1 in [w1_min, w1_max], w2 in [-1, 1].
std::vector<Vec3<double>> strip_grid(long n1, long n2, double w1_min = -2, double w1_max = 2);

// n points uniform on the quarter sphere {x >= 0, z <= 0} (the projective uniform measure), from a
// counter-based generator seeded by (seed, index): the same seed gives the same points on any thread count.
std::vector<Vec3<double>> random_points(long n, std::uint64_t seed);

// A strip grid's spec "strip:NxM[:w1min:w1max]" read as a core::Grid (core/grid.hpp's parser with the strip syntax;
// has_range is false when the range is omitted, then w1 in [-2, 2]).  Throws core::InvalidField naming `field` for
// a spec of another form, N or M < 1, or a range that is not finite a < b.
core::Grid parse_strip(std::string_view spec, const char* field = "grid");
// The cells' points of a strip grid, w1-major (cell (i, j) at i n2 + j), as strip_grid(n1, n2, w1_min, w1_max).
std::vector<Vec3<double>> strip_grid(const core::Grid& g);

// Parses a grid spec: "paper", "strip:NxM[:w1min:w1max]", "random:N", or a list "x,y,z;x,y,z;...".
// Throws std::invalid_argument naming `field` and the accepted forms.
std::vector<Vec3<double>> parse_grid(std::string_view spec, std::uint64_t seed, const char* field = "grid");

// Bytes needed to hold `count` items of `item_bytes`; throws std::length_error naming `field` and the
// size when it exceeds the memory budget (default: 3/4 of physical memory).
std::size_t checked_bytes(std::size_t count, std::size_t item_bytes, const char* field);
// The same for a grid of count1 x count2 items, the product taken without overflow (strip:4294967296x4294967296
// is 2^64 points, not 0).
std::size_t checked_bytes(std::size_t count1, std::size_t count2, std::size_t item_bytes, const char* field);

}  // namespace btob::iterate
