// SPDX-License-Identifier: GPL-3.0-or-later
// The grid type: N x M cells over a chart of the quadrant Q, one grammar KIND:NxM[:ranges], one parser.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/map.hpp"

namespace btob::core {

// The charts a grid may cover (core/coords.hpp):
//   strip   w1 in [a, b] (default [-2, 2]) x w2 in [-1, 1]   (eq. (6.4); from_strip)
//   sphere  theta in [0, pi/2] x y in [-1, 1]                (equal-area chart; from_height)
//   angles  theta in [0, pi/2] x phi in [0, pi]              (eq. (2.18); from_angles)
//   boxes   N x M boxes of a chart its user names (transfer's `domain`): sizes only, each axis [0, 1] in box units
enum class GridKind : std::uint8_t { strip, sphere, angles, boxes };
const char* grid_kind_name(GridKind kind);

// One axis of a grid: `cells` equal cells over [lo, hi], with its name, units and meaning (the HDF5 coordinate
// scales of a result that describes the grid).
struct GridAxis {
  long cells = 0;
  double lo = 0, hi = 1;
  std::string name, units, meaning;
  // The centre of cell i shifted by `shift` cells (|shift| <= 1/2: replicate grids): lo + (i + 1/2 + shift)(hi - lo)/N,
  // evaluated in that order (every result that places points on a grid rounds the same way).
  double centre(long i, double shift = 0) const {
    return lo + (static_cast<double>(i) + 0.5 + shift) * (hi - lo) / static_cast<double>(cells);
  }
  // Edge i = 0..N: lo + i (hi - lo) / N (edge N is hi exactly).
  double edge(long i) const {
    return i == cells ? hi : lo + static_cast<double>(i) * (hi - lo) / static_cast<double>(cells);
  }
  std::vector<double> centres() const;
  std::vector<double> edges() const;
};

struct Grid {
  GridKind kind = GridKind::sphere;
  GridAxis axis1, axis2;   // columns (w1 or theta) x rows (w2, y or phi)
  bool has_range = false;  // strip: the spec gave w1min:w1max
  // The unit direction of the chart point (a, b) on axis1 x axis2 (strip: not unit; the kernel's start as the strip
  // grids have always given it).  Not for boxes.
  Vec3<double> point(double a, double b) const;
  // The point of cell (i, j) shifted by (du, dv) cells.
  Vec3<double> cell_point(long i, long j, double du = 0, double dv = 0) const {
    return point(axis1.centre(i, du), axis2.centre(j, dv));
  }
  // Sets axis1's range (strip grids whose w1 range is a field of its own); throws InvalidField naming `field`.
  void set_range1(double lo, double hi, const char* field);
  std::size_t cells() const { return static_cast<std::size_t>(axis1.cells) * static_cast<std::size_t>(axis2.cells); }
};

// What a field accepts: the kinds (a bit per GridKind), whether a strip spec may carry its range, the largest side,
// and the accepted forms as the error message spells them.
struct GridSyntax {
  unsigned kinds = 0;
  bool ranges = false;
  long max_side = 0;  // 0: no bound beyond N, M >= 1
  std::string expected;
  bool accepts(GridKind k) const { return (kinds >> static_cast<unsigned>(k)) & 1u; }
};
constexpr unsigned grid_kinds(std::initializer_list<GridKind> ks) {
  unsigned m = 0;
  for (GridKind k : ks) m |= 1u << static_cast<unsigned>(k);
  return m;
}

// The grid of a kind with n1 x n2 cells (>= 1) over the kind's default ranges (strip: w1 in [-2, 2]).
Grid make_grid(GridKind kind, long n1, long n2);
// Parses KIND:NxM[:a:b] (boxes: NxM, no kind) as `syntax` allows.  Throws InvalidField(field, 'spec', expected) for
// a malformed spec, a kind or range the syntax refuses, N or M < 1 or above max_side, or a range that is not a
// finite a < b.
Grid parse_grid(std::string_view spec, const GridSyntax& syntax, const char* field = "grid");
// The spec of a grid in the grammar (strip with its range; boxes as NxM).
std::string grid_spec(const Grid& g);

}  // namespace btob::core
