// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of btob::core's grid type: the one grammar KIND:NxM[:a:b] and its parser (each kind, ranges, errors), cell
// centres and edges against the formula in exact rational arithmetic, the charts' points, and the fields that
// read grids through it (basins, lyapunov-strip, hyperbolicity, transfer's boxes).
#include <gtest/gtest.h>

#include <boost/multiprecision/gmp.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "core/coords.hpp"
#include "core/grid.hpp"
#include "core/request.hpp"

namespace {

using namespace btob::core;
using Q = boost::multiprecision::mpq_rational;

const GridSyntax kAll{grid_kinds({GridKind::strip, GridKind::sphere, GridKind::angles, GridKind::boxes}), true, 0,
                      "every form"};

// The message of the InvalidField f throws (empty, and a failure, if it throws nothing or another type).
template <class F> std::string error_of(F f) {
  try {
    f();
  } catch (const InvalidField& e) {
    return e.what();
  } catch (...) {
    ADD_FAILURE() << "an exception of another type";
    return "";
  }
  ADD_FAILURE() << "no exception";
  return "";
}

TEST(Grid, ParsesEachKindWithItsChartAndAxes) {
  const Grid s = parse_grid("strip:40x30", kAll);
  EXPECT_EQ(s.kind, GridKind::strip);
  EXPECT_EQ(s.axis1.cells, 40);
  EXPECT_EQ(s.axis2.cells, 30);
  EXPECT_EQ(s.axis1.lo, -2.0);
  EXPECT_EQ(s.axis1.hi, 2.0);
  EXPECT_EQ(s.axis2.lo, -1.0);
  EXPECT_EQ(s.axis2.hi, 1.0);
  EXPECT_FALSE(s.has_range);
  EXPECT_EQ(s.axis1.name, "w1");
  EXPECT_EQ(s.axis2.name, "w2");
  const Grid h = parse_grid("sphere:7x5", kAll);
  EXPECT_EQ(h.kind, GridKind::sphere);
  EXPECT_EQ(h.axis1.hi, std::numbers::pi / 2);
  EXPECT_EQ(h.axis1.units, "rad");
  EXPECT_EQ(h.axis2.name, "y");
  EXPECT_EQ(h.axis2.units, "1");
  const Grid a = parse_grid("angles:3x4", kAll);
  EXPECT_EQ(a.kind, GridKind::angles);
  EXPECT_EQ(a.axis2.hi, std::numbers::pi);
  EXPECT_EQ(a.axis2.name, "phi");
  const Grid b = parse_grid("256x128", kAll);
  EXPECT_EQ(b.kind, GridKind::boxes);
  EXPECT_EQ(b.axis1.cells, 256);
  EXPECT_EQ(b.cells(), 256u * 128u);
  for (const char* spec : {"strip:40x30:-1.5:2.5", "sphere:7x5", "angles:3x4", "256x128"})
    EXPECT_EQ(grid_spec(parse_grid(spec, kAll)), spec);
}

TEST(Grid, ReadsAStripRangeOnlyWhereTheSyntaxAllowsIt) {
  const Grid s = parse_grid("strip:4x3:-1.5:2.5", kAll);
  EXPECT_TRUE(s.has_range);
  EXPECT_EQ(s.axis1.lo, -1.5);
  EXPECT_EQ(s.axis1.hi, 2.5);
  GridSyntax no_ranges = kAll;
  no_ranges.ranges = false;
  EXPECT_NE(error_of([&] { parse_grid("strip:4x3:-1:1", no_ranges); }).find("grid: got 'strip:4x3:-1:1'"),
            std::string::npos);
  EXPECT_FALSE(error_of([] { parse_grid("sphere:4x3:-1:1", kAll); }).empty());  // ranges are the strip's only
  Grid g = parse_grid("strip:4x3", kAll);
  g.set_range1(0.5, 3, "w1-range");
  EXPECT_EQ(g.axis1.lo, 0.5);
  EXPECT_EQ(error_of([&] { g.set_range1(3, 0.5, "w1-range"); }), "w1-range: got [3, 0.5], expected finite a < b");
  // A range whose width overflows: every centre would be infinite or NaN.
  EXPECT_EQ(error_of([&] { g.set_range1(-1e308, 1e308, "w1-range"); }),
            "w1-range: got [-1e+308, 1e+308], expected finite a < b");
}

TEST(Grid, RefusesMalformedSpecsNamingTheFieldAndTheAcceptedForms) {
  GridSyntax syntax = kAll;
  syntax.max_side = 100;
  syntax.expected = "KIND:NxM with 1 <= N, M <= 100";
  for (const char* bad : {"",
                          "disk:3x3",
                          "strip:",
                          "strip:3",
                          "strip:3x",
                          "strip:x3",
                          "strip:0x3",
                          "strip:3x-1",
                          "strip:3x4x5",
                          "strip:+3x4",
                          "strip: 3x4",
                          "strip:101x3",
                          "3x101",
                          "strip:3x4:1",
                          "strip:3x4:2:1",
                          "strip:3x4:0:inf",
                          "strip:3x4:-1e308:1e308",
                          "strip:3x4:a:b",
                          "strip:3x4:1:2:3",
                          "x",
                          "sphere:3.5x4"})
    EXPECT_EQ(error_of([&] { parse_grid(bad, syntax, "cells"); }),
              std::string("cells: got '") + bad + "', expected KIND:NxM with 1 <= N, M <= 100")
        << bad;
  GridSyntax only_boxes{grid_kinds({GridKind::boxes}), false, 0, "NxM"};
  EXPECT_FALSE(error_of([&] { parse_grid("strip:3x4", only_boxes, "boxes"); }).empty());
  EXPECT_EQ(parse_grid("3x4", only_boxes).kind, GridKind::boxes);
}

// Centres lo + (i + 1/2 + shift)(hi - lo)/N and edges lo + i (hi - lo)/N against the exact rational value: a centre
// takes five roundings (sum, difference, product, quotient, sum), an edge four, each of a value at most 2 max(|lo|,
// |hi|), so each is within eps/2 x 2 scale per rounding: 5 eps scale and 4 eps scale.  The edges ascend, each centre
// lies between its edges, edge N is hi exactly.
TEST(Grid, CentresAndEdgesFollowTheFormula) {
  for (const char* spec : {"strip:7x3:-1.3:2.9", "sphere:11x13", "angles:5x9", "strip:1x1"}) {
    const Grid g = parse_grid(spec, kAll);
    for (const GridAxis* ax : {&g.axis1, &g.axis2}) {
      const auto centres = ax->centres(), edges = ax->edges();
      ASSERT_EQ(centres.size(), static_cast<std::size_t>(ax->cells));
      ASSERT_EQ(edges.size(), static_cast<std::size_t>(ax->cells) + 1);
      EXPECT_EQ(edges.front(), ax->lo);
      EXPECT_EQ(edges.back(), ax->hi);
      const double scale = std::max(std::fabs(ax->lo), std::fabs(ax->hi)), eps = 0x1p-52;
      for (long i = 0; i < ax->cells; ++i) {
        for (double shift : {0.0, 0.25, -0.45}) {
          const Q exact = Q(ax->lo) + (Q(i) + Q(1, 2) + Q(shift)) * (Q(ax->hi) - Q(ax->lo)) / ax->cells;
          EXPECT_LE(std::fabs(static_cast<double>(Q(ax->centre(i, shift)) - exact)), 5 * eps * scale)
              << spec << " " << i;
        }
        const Q exact_edge = Q(ax->lo) + Q(i) * (Q(ax->hi) - Q(ax->lo)) / ax->cells;
        EXPECT_LE(std::fabs(static_cast<double>(Q(edges[static_cast<std::size_t>(i)]) - exact_edge)), 4 * eps * scale);
        EXPECT_LT(edges[static_cast<std::size_t>(i)], centres[static_cast<std::size_t>(i)]);
        EXPECT_LT(centres[static_cast<std::size_t>(i)], edges[static_cast<std::size_t>(i) + 1]);
      }
    }
  }
}

// A cell's point is its chart's point at the cell centre, bit for bit (the grids of every command are these points).
TEST(Grid, CellPointsAreTheChartsPointsAtTheCentres) {
  const Grid s = parse_grid("strip:6x4:-1:3", kAll), h = parse_grid("sphere:6x4", kAll),
             a = parse_grid("angles:6x4", kAll);
  for (long i = 0; i < 6; ++i)
    for (long j = 0; j < 4; ++j) {
      const double w1 = s.axis1.centre(i, 0.1), w2 = s.axis2.centre(j, -0.2);
      EXPECT_EQ(s.cell_point(i, j, 0.1, -0.2), from_strip<double>(w1, w2));
      EXPECT_EQ(s.cell_point(i, j),
                Vec3<double>((1 + s.axis2.centre(j)) / 2, s.axis1.centre(i), (s.axis2.centre(j) - 1) / 2));
      EXPECT_EQ(h.cell_point(i, j), from_height<double>(h.axis1.centre(i), h.axis2.centre(j)));
      EXPECT_EQ(a.cell_point(i, j), from_angles<double>(a.axis1.centre(i), a.axis2.centre(j)));
    }
}

}  // namespace
