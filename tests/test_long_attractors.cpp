// SPDX-License-Identifier: GPL-3.0-or-later
// Long checks of src/attractors (label long): the 1000 x 1000 grid at r = 0.2 and Table 6.1 with 2000 orbits per r.
#include "attractors/attractors.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/patterns.hpp"

#include <gtest/gtest.h>

#include <set>

namespace btob::attractors {
namespace {

// Its speed is measured by bm_attractors (basins_replicates/200/1000/2/2), never asserted here.
TEST(LongAttractors, Grid1000AtR02FewUndecided) {
  Options o;
  o.run.threads = 2;
  const Basins b = basins(0.2, parse_grid("strip:1000x1000", -2, 2), 0, 1, o);
  EXPECT_LT(b.undecided.value, 0.01);  // the target: under 1% undecided
  std::set<std::string> p;
  for (const auto& a : b.attractors) p.insert(a.pattern);
  EXPECT_TRUE(p.count("132^3312^3"));
  EXPECT_TRUE(p.count("P2 invariant curves"));
}

// Every pattern of Table 6.1 in [0.1, 0.6] is found among 2000 random initial conditions, and every periodic
// attractor found is stable for the pattern tool.
TEST(LongAttractors, Table61With2000Orbits) {
  const std::vector<std::pair<double, std::vector<std::string>>> table = {{0.1, {"111333"}},
                                                                          {0.101, {"111333"}},
                                                                          {0.15, {"1133"}},
                                                                          {0.16, {"1133"}},
                                                                          {0.17, {"1133"}},
                                                                          {0.172, {"132^36", "312^36"}},
                                                                          {0.174, {"132^14", "312^14"}},
                                                                          {0.176, {"132^10", "312^10"}},
                                                                          {0.178, {"132^8", "312^8"}},
                                                                          {0.18, {"132^7312^7"}},
                                                                          {0.19, {"132^4", "312^4"}},
                                                                          {0.2, {"132^3312^3"}},
                                                                          {0.21, {"132^2", "312^2", "132^3312^3"}},
                                                                          {0.22, {"132^2", "312^2"}},
                                                                          {0.23, {"132^2", "312^2"}},
                                                                          {0.24, {"132^2", "312^2", "132312"}},
                                                                          {0.25, {"312^2", "132312"}},
                                                                          {0.3, {"132312"}},
                                                                          {0.34, {"132312"}},
                                                                          {0.5, {"132312"}},
                                                                          {0.54, {"132312"}},
                                                                          {0.58, {"132312", "131312^3313132^3"}},
                                                                          {0.6, {"132312"}}};
  const auto pts = iterate::random_points(2000, 1);
  for (const auto& [r, pats] : table) {
    iterate::Ensemble e;
    e.r = {r};
    e.initial = pts;
    const auto a = collect(classify(e, {}), r, nullptr);
    std::set<std::string> found;
    for (const auto& x : a) {
      found.insert(x.pattern);
      if (x.type == Type::periodic)
        EXPECT_TRUE(patterns::is_stable<double>(patterns::parse_word(x.pattern), r)) << x.pattern << " r " << r;
    }
    for (const auto& p : pats) EXPECT_TRUE(found.count(p)) << p << " at r = " << r;
  }
}

}  // namespace
}  // namespace btob::attractors
