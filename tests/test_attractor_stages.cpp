// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the attractors module's stages alone (attractors/stages.hpp, attractors/certify.hpp): the certificates of
// early exits against independent routes (the scalar map core::step, the pattern tool's exact cycles), the decision
// type, the one merge of the curve ranges, the smallest rotation of a word.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "attractors/certify.hpp"
#include "attractors/stages.hpp"
#include "core/map.hpp"
#include "patterns/patterns.hpp"
#include "tolerance.hpp"

using btob::test::ulps;

namespace btob::attractors::stages {
namespace {

// Every stable cycle the probe finds at r lies in its own cone: the pattern tool's exact points (an independent route:
// exact rationals, then rounded) have ratio |(c2, c3)| / c1 of a few eps times the frame's condition, far below
// 1e-6, at some phase; and the limit at the first checkpoint proves something (it is positive).
TEST(AttractorStages, EachProbedCycleLiesInItsOwnCone) {
  const Options opt;
  for (double r : {0.21, 0.58}) {
    const std::vector<Cone> cones = probe_cones(r, opt);
    ASSERT_FALSE(cones.empty()) << "r = " << r;  // stable cycles attract most of the sphere at these r (Table 6.1)
    for (const Cone& c : cones) {
      const patterns::Verdict<double> pv = patterns::analyse<double>(c.word, r);
      ASSERT_EQ(pv.outcome, patterns::Outcome::stable) << c.key;
      for (const auto& q : pv.orbit) EXPECT_TRUE(in_cone(c, q, 1e-6)) << c.key << " r = " << r;
      EXPECT_GT(c.delta, 0.0);
      EXPECT_LT(c.b, 1.0);
      EXPECT_GT(cone_limit(c, opt.transient - 64, opt), 0.0) << c.key;
      EXPECT_FALSE(make_cone(c.key, c.word, r, opt, {}).has_value()) << "no exact points, no cone";
    }
  }
}

// The trap's claim against the scalar map: a point whose invariant I is below (1 - margin)^2 I_max stays in the P2
// branch (symbol 2 at every step of core::step, its own exact branch rule) and keeps I over 2000 steps within the
// trap's drift model, 16 eps per step relative (cond(S)^2 aside: the map is a rotation on I's ellipses); a point with
// I above I_max is refused.
TEST(AttractorStages, P2TrapHoldsUnderTheScalarMap) {
  const Options opt;
  const double r = 0.3;
  const P2Trap t = make_trap(r, opt);
  ASSERT_TRUE(t.on);
  EXPECT_EQ(make_trap(0.1, opt).on, false) << "r <= 3 - 2 sqrt(2): P2 does not rotate";
  for (double share : {0.1, 0.3, 0.8}) {
    // On the chart a = 1, v = ((1 + s)/2, y, (s - 1)/2) with s = 0: I = 4 r y^2, so y = sqrt(share I_max / (4 r)).
    Vec3<double> u(0.5, std::sqrt(share * t.I_max / (4 * r)), -0.5);
    double I0 = 0;
    ASSERT_TRUE(on_p2_curve(t, u, opt, I0)) << share;
    EXPECT_CLOSE(I0, share * t.I_max, ulps<double>(8, "a few roundings of I's quadratic form"));
    for (int k = 0; k < 2000; ++k) {
      const core::Step<double> s = core::step(u, r);
      ASSERT_EQ(s.symbol, 2) << "step " << k << " share " << share;
      u = s.u / s.u.norm();
    }
    EXPECT_CLOSE(invariant_of(u, r, core::alpha(r)), I0, ulps<double>(16 * 2000, "16 eps per step, 2000 steps").of(I0));
  }
  double I = 0;
  EXPECT_FALSE(on_p2_curve(t, Vec3<double>(0.5, std::sqrt(1.1 * t.I_max / (4 * r)), -0.5), opt, I));
}

TEST(AttractorStages, DecisionsKeepTheirKindApart) {
  const Decision full = Decision::full_length(), p2 = Decision::p2_curve(), c0 = Decision::cone(0),
                 c3 = Decision::cone(3);
  EXPECT_TRUE(full.is_full_length());
  EXPECT_TRUE(Decision{}.is_full_length());
  EXPECT_TRUE(p2.is_p2_curve());
  EXPECT_FALSE(p2.is_full_length());
  EXPECT_FALSE(c0.is_full_length() || c0.is_p2_curve());
  EXPECT_EQ(c3.cone_index(), 3u);
  EXPECT_NE(c0, c3);
  EXPECT_NE(p2, full);
  EXPECT_EQ(c3, Decision::cone(3));
}

TEST(AttractorStages, CurveRangesWidenFromEmpty) {
  Attractor a;
  a.rotation_min = a.invariant_min = std::numeric_limits<double>::infinity();
  a.rotation_max = a.invariant_max = -std::numeric_limits<double>::infinity();
  OrbitVerdict v;
  v.rotation = 0.25, v.invariant = 3;
  widen_curve_ranges(a, v);
  EXPECT_EQ(a.rotation_min, 0.25);
  EXPECT_EQ(a.rotation_max, 0.25);
  widen_curve_ranges(a, 0.1, 0.2, 4, 5);
  EXPECT_EQ(a.rotation_min, 0.1);
  EXPECT_EQ(a.rotation_max, 0.25);
  EXPECT_EQ(a.invariant_min, 3);
  EXPECT_EQ(a.invariant_max, 5);
}

// The key of a periodic attractor: the smallest rotation in the order 1 < 3 < 2, its shift, mirrors apart.
TEST(AttractorStages, SmallestRotationOrdersOneThreeTwo) {
  std::size_t shift = 99;
  EXPECT_EQ(patterns::to_digits(smallest_rotation(patterns::parse_word("2132", "w"), &shift)), "1322");
  EXPECT_EQ(shift, 1u);
  EXPECT_EQ(patterns::to_digits(smallest_rotation(patterns::parse_word("2312", "w"))), "1223");
  EXPECT_EQ(patterns::to_digits(smallest_rotation(patterns::parse_word("3122", "w"))), "1223");
}

}  // namespace
}  // namespace btob::attractors::stages
