// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of reference::trig_density_matlab (Figure 4.7, panel a): where no acos argument leaves [-1, 1] it draws
// exactly what trig_density draws; where GNU Octave running the printed code takes no complex acos, neither does it;
// one thread and two threads give the same image.
#include "reference/reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace btob::reference {
namespace {

iterate::Ensemble ensemble(std::vector<double> r) {
  iterate::Ensemble e;
  e.r = std::move(r);
  e.initial = iterate::paper_grid();
  return e;
}

TEST(TrigMatlab, EqualsTheRealAlgorithmWhereItStaysInTheDomain) {
  // r = 0.15 and 0.3: the 32 orbits of the Section 4 grid never leave acos's domain in 300 steps.
  const auto e = ensemble({0.15, 0.3});
  const long iterations = 300, tail = 50;
  const int bins = 90;
  iterate::DensityRecorder rec(iterate::Coord::theta, e, iterations, tail, bins, 0.0, std::numbers::pi, 1);
  const auto broken = trig_density<double>(e, iterations, rec, 1);
  ASSERT_EQ(broken[0] + broken[1], 0u);
  const auto real = rec.merge();
  const MatlabTrigImage m = trig_density_matlab(e, iterations, tail, false, bins, 0.0, std::numbers::pi, 1);
  EXPECT_EQ(m.complex_orbits[0] + m.complex_orbits[1], 0u);
  EXPECT_EQ(m.nan_points[0] + m.nan_points[1], 0u);
  // The same theta, computed by the same real code path, binned the same way (the recorder gets theta back from
  // the unit vector core::from_angles(theta, phi), exact to a few ulps: a value on a bin edge could move, which
  // these r values do not have).
  ASSERT_EQ(m.counts.size(), real.size());
  for (std::size_t i = 0; i < real.size(); ++i) EXPECT_EQ(m.counts[i], real[i]) << "bin " << i;
}

TEST(TrigMatlab, NoOrbitOfTheGridTakesAComplexAcosWhereOctaveFindsNone) {
  // GNU Octave running the paper's Appendix A.1 code as printed (analyses/octave, grid_counts.m) on the Section 4
  // grid with 4 x 5000 collisions: at r = 0.072, 0.075, 0.078 no orbit takes a complex acos, and 17, 15, 20 of the
  // 32 stop producing b-collisions (they reach phi = pi/2 exactly, where the printed code changes nothing).  The
  // orbits are chaotic there, so the stalled counts are compared as counts, not orbit by orbit: every orbit is
  // accounted for, and a good share of them stall.  An acos evaluated as -i log(z + i sqrt(1 - z^2)) on real
  // arguments in [-1, 1] counted all 32 orbits as complex at r = 0.075.
  const auto e = ensemble({0.072, 0.075, 0.078});
  const long iterations = 5000, tail = 1;
  const MatlabTrigImage m = trig_density_matlab(e, iterations, tail, false, 100, 0.0, std::numbers::pi, 1);
  for (std::size_t ir = 0; ir < 3; ++ir) {
    EXPECT_EQ(m.complex_orbits[ir], 0u) << "r = " << e.r[ir];
    std::uint64_t drawn = 0;
    for (int b = 0; b < 100; ++b) drawn += m.counts[ir * 100 + b];
    // Every tail state is drawn, NaN, outside [0, pi] or never reached: nothing is dropped silently.
    EXPECT_EQ(drawn + m.nan_points[ir] + m.outside[ir] + m.stalled[ir], static_cast<std::uint64_t>(32 * tail));
    EXPECT_GE(m.stalled[ir], 8u) << "r = " << e.r[ir];  // Octave: 15-20 of 32
    EXPECT_LE(m.stalled[ir], 28u) << "r = " << e.r[ir];
  }
}

TEST(TrigMatlab, OneAndTwoThreadsAgree) {
  const auto e = ensemble({0.075, 0.09, 0.12});
  const auto a = trig_density_matlab(e, 500, 50, false, 60, 0.0, std::numbers::pi, 1);
  const auto b = trig_density_matlab(e, 500, 50, false, 60, 0.0, std::numbers::pi, 2);
  EXPECT_EQ(a.counts, b.counts);
  EXPECT_EQ(a.complex_orbits, b.complex_orbits);
  EXPECT_EQ(a.nan_points, b.nan_points);
}

}  // namespace
}  // namespace btob::reference
