// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/orbits: the strip tails against core::step one orbit at a time, determinism (seed, threads),
// the verdicts of Figures 6.9 and 6.11 (132^3312^3 at r = 0.2, 132^67312^67 at r = 0.1717), and the errors.
#include "orbits/orbits.hpp"

#include "core/coords.hpp"
#include "core/map.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace btob::orbits {
namespace {

StripOrbitsRequest small(double r) {
  StripOrbitsRequest q;
  q.r = r;
  q.orbits = 4;
  q.iterations = 600;
  q.tail = 50;
  return q;
}

TEST(StripOrbits, TailsEqualTheScalarMapStepByStep) {
  const StripOrbitsRequest q = small(0.2);
  const StripOrbitsResult res = run(q);
  ASSERT_EQ(res.w1.size(), static_cast<std::size_t>(q.orbits * q.tail));
  for (long o = 0; o < q.orbits; ++o) {
    core::Vec3<double> u = core::from_strip(res.start_w1[o], res.start_w2[o]);
    u /= u.norm();
    for (long k = 1; k <= q.iterations; ++k) {
      u = core::step<double>(u, q.r).u;
      u /= u.norm();
      if (k > q.iterations - q.tail) {
        const auto [w1, w2] = core::strip(u);
        const std::size_t j = static_cast<std::size_t>(o * q.tail + (k - (q.iterations - q.tail + 1)));
        // Two routes (batched kernel with power-of-two rescaling vs normalising every step) round differently;
        // on these attracting orbits the difference stays at a few hundred ulps of |w| <= 30.
        const auto tol = ulps(1500, "two routes' roundings on attracting orbits, of |w| <= 30").of(30);
        EXPECT_CLOSE(res.w1[j], w1, tol) << "orbit " << o << " step " << k;
        EXPECT_CLOSE(res.w2[j], w2, tol) << "orbit " << o << " step " << k;
      }
    }
  }
}

TEST(StripOrbits, SameSeedSameResultOnOneAndTwoThreads) {
  StripOrbitsRequest q = small(0.2);
  core::RunControl one, two;
  one.threads = 1;
  two.threads = 2;
  const auto a = run(q, one), b = run(q, two);
  EXPECT_EQ(a.w1, b.w1);  // bitwise: static partition, no reduction across orbits
  EXPECT_EQ(a.w2, b.w2);
  EXPECT_EQ(a.start_w1, b.start_w1);
  EXPECT_EQ(a.pattern, b.pattern);
  q.seed = 2;
  EXPECT_NE(run(q, one).start_w1, a.start_w1);
}

TEST(StripOrbits, StartPointsLieInTheRequestedPartOfTheStrip) {
  StripOrbitsRequest q = small(0.3);
  q.orbits = 200;
  q.w1_range = {-0.5, 0.25};
  q.iterations = q.tail = 1;
  const auto res = run(q);
  for (std::size_t o = 0; o < res.start_w1.size(); ++o) {
    EXPECT_GE(res.start_w1[o], q.w1_range[0]);
    EXPECT_LE(res.start_w1[o], q.w1_range[1]);
    EXPECT_GT(res.start_w2[o], -1);
    EXPECT_LT(res.start_w2[o], 1);
  }
}

TEST(StripOrbits, VerdictsOfFigures69And611) {
  StripOrbitsRequest q;  // the scene of Figure 6.9: r = 0.2, 10 orbits, 5000 iterations, seed 1
  const auto a = run(q);
  EXPECT_EQ(a.periodic + a.quasi_periodic + a.other, 10u);
  for (std::size_t o = 0; o < a.pattern.size(); ++o)
    if (a.verdicts[o].type == attractors::Type::periodic) EXPECT_EQ(a.pattern[o], "132^3312^3");
  EXPECT_GE(a.periodic, 1u);
  q.r = 0.1717;  // Figure 6.11: the paper reads 132^67312^67 off the trajectory
  const auto b = run(q);
  ASSERT_GE(b.periodic, 1u);
  for (std::size_t o = 0; o < b.pattern.size(); ++o)
    if (b.verdicts[o].type == attractors::Type::periodic) EXPECT_EQ(b.pattern[o], "132^67312^67");
}

TEST(StripOrbits, ErrorsNameTheField) {
  auto expect_field = [](StripOrbitsRequest q, const char* field) {
    try {
      q.validate();
      ADD_FAILURE() << "no error for " << field;
    } catch (const core::InvalidField& e) {
      EXPECT_EQ(e.field, field);
      EXPECT_EQ(std::string(e.what()).rfind(std::string(field) + ": got ", 0), 0u) << e.what();
    }
  };
  StripOrbitsRequest q;
  q.r = 1;
  expect_field(q, "r");
  q = {};
  q.orbits = 0;
  expect_field(q, "orbits");
  q = {};
  q.tail = 0;
  expect_field(q, "tail");
  q = {};
  q.iterations = 10;
  expect_field(q, "iterations");
  q = {};
  q.w1_range = {1, 1};
  expect_field(q, "w1-range");
  q = {};
  q.w1_range = {-1e7, 0};
  expect_field(q, "w1-range");
  q = {};
  q.w1_range = {0};
  expect_field(q, "w1-range");
}

}  // namespace
}  // namespace btob::orbits
