// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/attractors: classification (Table 6.1 patterns, collapse, quasi-periodic, chaotic), identity,
// basins, fractions with intervals, determinism across thread counts, errors.
#include "attractors/attractors.hpp"
#include "attractors/recorders.hpp"
#include "attractors/requests.hpp"
#include "core/coords.hpp"
#include "core/fields.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "patterns/patterns.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace btob::attractors {
namespace {

iterate::Ensemble ensemble(double r, std::vector<Vec3<double>> pts) {
  iterate::Ensemble e;
  e.r = {r};
  e.initial = std::move(pts);
  return e;
}

// Patterns (paper notation) of the attractors found, by type.
std::map<std::string, Attractor> found(double r, const std::vector<Vec3<double>>& pts, const Options& o = {}) {
  const auto v = classify(ensemble(r, pts), o);
  std::map<std::string, Attractor> m;
  for (const auto& a : collect(v, r, nullptr)) m[a.pattern] = a;
  return m;
}

// Every periodic attractor must be a stable orbit of its word for the pattern tool at the same r.
void expect_stable(const std::map<std::string, Attractor>& m, double r) {
  for (const auto& [p, a] : m)
    if (a.type == Type::periodic) {
      EXPECT_EQ(a.stability, patterns::outcome_name(patterns::Outcome::stable)) << p << " at r = " << r;
      EXPECT_TRUE(patterns::is_stable<double>(patterns::parse_word(p), r)) << p << " at r = " << r;
      EXPECT_LT(a.lyapunov2, 0) << p;
    }
}

TEST(Attractors, PaperGridOneBasin1133AtR015) {
  const auto m = found(0.15, iterate::paper_grid());
  ASSERT_EQ(m.size(), 1u);
  ASSERT_TRUE(m.count("1133"));
  EXPECT_EQ(m.at("1133").count, 32u);
  EXPECT_EQ(m.at("1133").collisions, 8);  // Table 6.1: length 8
  expect_stable(m, 0.15);
}

TEST(Attractors, PaperGridOneBasin111333AtR01) {
  const auto m = found(0.1, iterate::paper_grid());
  ASSERT_EQ(m.size(), 1u);
  ASSERT_TRUE(m.count("111333"));
  EXPECT_EQ(m.at("111333").collisions, 12);
  expect_stable(m, 0.1);
}

TEST(Attractors, CollapseAndItsMirrorAtR005) {
  const auto pts = grid_points(parse_grid("strip:20x20", -2, 2));
  const auto v = classify(ensemble(0.05, pts), {});
  const auto a = collect(v, 0.05, nullptr);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].key, "C1");
  EXPECT_EQ(a[1].key, "C3");
  EXPECT_EQ(a[0].count + a[1].count, pts.size());
  for (const auto& x : v) {
    EXPECT_EQ(x.type, Type::collapse);
    const double th = core::theta<double>(x.point);
    // theta -> 0 with symbol 1, pi/2 with symbol 3 (Section 5.2); 1e-6 = Options::collapse_theta.
    EXPECT_LT(x.key == "C1" ? th : std::numbers::pi / 2 - th, 1e-6);
  }
  // r above 7 - 4 sqrt(3) never gives a collapse verdict.
  for (const auto& x : classify(ensemble(0.08, pts), {})) EXPECT_NE(x.type, Type::collapse);
}

TEST(Attractors, R02PeriodicCoexistsWithQuasiPeriodicCurves) {
  const double r = 0.2;
  const auto m = found(r, grid_points(parse_grid("strip:40x40", -2, 2)));
  ASSERT_TRUE(m.count("132^3312^3"));
  ASSERT_TRUE(m.count("P2 invariant curves"));
  EXPECT_EQ(m.at("132^3312^3").period, 10);
  EXPECT_EQ(m.at("132^3312^3").collisions, 26);
  expect_stable(m, r);
  // The rotation number of every P2 curve is beta / 2 pi with cos(beta) = -(1-r)^2/(4r) (Section 6.1), up to
  // the weighted average's accuracy (1e-9: Das-Yorke convergence at 4000 steps is far below).
  const auto& q = m.at("P2 invariant curves");
  const double beta = std::acos(-(1 - r) * (1 - r) / (4 * r)) / (2 * std::numbers::pi);
  const auto conv = bound(1e-9, "the weighted rotation average at 4000 steps (Das-Yorke convergence is far below)");
  EXPECT_CLOSE(std::fabs(q.rotation_min), beta, conv);
  EXPECT_CLOSE(std::fabs(q.rotation_max), beta, conv);
  EXPECT_LT(q.invariant_min, q.invariant_max);  // a family of different curves
}

TEST(Attractors, R021ThreePatternsCoexist) {
  const auto m = found(0.21, grid_points(parse_grid("strip:40x40", -2, 2)));
  for (const char* p : {"132^2", "312^2", "132^3312^3"}) EXPECT_TRUE(m.count(p)) << p;
  expect_stable(m, 0.21);
  // Mirror attractors are distinct (J symmetry: same canonical form, different keys) with equal basins
  // on the J-symmetric strip grid (w -> -w maps the grid onto itself).
  EXPECT_EQ(m.at("132^2").canonical, m.at("312^2").canonical);
  EXPECT_NE(m.at("132^2").key, m.at("312^2").key);
  EXPECT_EQ(m.at("132^2").count, m.at("312^2").count);
}

TEST(Attractors, Pattern132312From03To06) {
  const auto pts = grid_points(parse_grid("strip:16x16", -2, 2));
  for (double r : {0.3, 0.34, 0.45, 0.5, 0.6}) {
    const auto m = found(r, pts);
    EXPECT_TRUE(m.count("132312")) << "r = " << r;
    if (m.count("132312")) EXPECT_EQ(m.at("132312").collisions, 14);
    expect_stable(m, r);
  }
}

TEST(Attractors, ChaoticBetweenWindows) {
  // r = 0.102: Table 6.1 finds no periodic orbit; the exponent is positive beyond its error bar.
  const auto v = classify(ensemble(0.102, iterate::paper_grid()), {});
  for (const auto& x : v) {
    EXPECT_EQ(x.type, Type::chaotic) << x.detail;
    EXPECT_GT(x.lambda1, 3 * x.err1 + 0.01);
  }
}

TEST(Attractors, P2InvariantIsConservedAndDistinguishesCurves) {
  const double r = 0.3;
  // Two points near the P2 centre (strip origin) on different ellipses, and the image of the first.
  const Vec3<double> u1 = core::from_strip<double>(0.05, 0.02), u2 = core::from_strip<double>(0.1, 0.05);
  Vec3<double> u1b = core::to_quadrant<double>(core::P2<double>(r) * u1);
  const Options o;
  const OrbitVerdict a = classify_point(u1, r, o), b = classify_point(u2, r, o), c = classify_point(u1b, r, o);
  ASSERT_EQ(a.type, Type::quasi_periodic);
  ASSERT_EQ(b.type, Type::quasi_periodic);
  EXPECT_TRUE(a.p2_region);
  EXPECT_SMALL(a.invariant_spread,
               ulps(45000, "exact invariance: rounding only, accumulated over the orbit (measured 2660 eps)"));
  // I on the strip: 2 w2^2 - 4 alpha w1 w2 + 4 r w1^2 (attractor_recorder.hpp).
  const double al = (1 + r) / 2;
  EXPECT_CLOSE(a.invariant, 2 * 0.02 * 0.02 - 4 * al * 0.05 * 0.02 + 4 * r * 0.05 * 0.05,
               ulps(32, "I of the start from its strip coordinates: rounding only (measured 2.6 eps)"));
  EXPECT_TRUE(same_attractor(a, c, r));
  EXPECT_FALSE(same_attractor(a, b, r));
}

// Pass 2 (the fused cocycle kernel for lambda1, a plain run with the vectorised rotation recorder) gives an orbit the
// same bits alone, at any place in a batch (the last, partial batch included) and with any thread count: r = 0.12
// (chaotic, no rotation), r = 0.3 (P2 curves: rotation and invariant) and r = 0.9 (curves outside P2 as well).
TEST(Attractors, VerdictsDoNotDependOnTheBatch) {
  for (const double r : {0.12, 0.3, 0.9}) {
    const auto pts = grid_points(parse_grid("strip:10x7", -2, 2));  // 70 orbits: one full double batch and a partial
    Options o1, o2;
    o1.run.threads = 1, o2.run.threads = 2;
    const auto all = classify(ensemble(r, pts), o2);
    auto shifted = pts;
    std::rotate(shifted.begin(), shifted.begin() + 23, shifted.end());
    const auto moved = classify(ensemble(r, shifted), o1);
    int second_pass = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const OrbitVerdict& a = all[i];
      const OrbitVerdict& b = moved[(i + pts.size() - 23) % pts.size()];
      const OrbitVerdict c = classify_point(pts[i], r, o1);
      for (const OrbitVerdict* x : {&b, &c}) {
        EXPECT_EQ(a.key, x->key) << r << " " << i;
        EXPECT_EQ(a.residual, x->residual) << r << " " << i;  // pass 1's return test, a fixed-width vector loop
        EXPECT_EQ(a.closest_return, x->closest_return) << r << " " << i;
        EXPECT_EQ(a.point, x->point) << r << " " << i;
        EXPECT_EQ(a.lambda1, x->lambda1) << r << " " << i;
        EXPECT_EQ(a.err1, x->err1) << r << " " << i;
        EXPECT_EQ(a.rotation, x->rotation) << r << " " << i;
        EXPECT_EQ(a.rotation_delta, x->rotation_delta) << r << " " << i;
        EXPECT_EQ(a.invariant, x->invariant) << r << " " << i;
        EXPECT_EQ(a.invariant_spread, x->invariant_spread) << r << " " << i;
      }
      second_pass += a.type == Type::chaotic || a.type == Type::quasi_periodic;
    }
    EXPECT_GT(second_pass, 10) << r;  // the test reaches pass 2
  }
}

TEST(Attractors, PeriodicIdentityUpToPhase) {
  const double r = 0.15;
  const auto v = classify(ensemble(r, iterate::paper_grid()), {});
  for (std::size_t i = 1; i < v.size(); ++i) EXPECT_TRUE(same_attractor(v[0], v[i], r));
  // A perturbed copy of the cycle point is a different point: not on the cycle.
  OrbitVerdict w = v[0];
  w.point(1) += 1e-3;
  EXPECT_FALSE(same_attractor(v[0], w, r));
}

TEST(Attractors, ScalarReferenceGivesTheSameReturns) {
  const auto e = ensemble(0.21, grid_points(parse_grid("strip:6x6", -2, 2)));
  attractors::ReturnRecorder a(e.orbits(), 3000, 300, 64, 1e-9), b(e.orbits(), 3000, 300, 64, 1e-9);
  iterate::run<double>(e, a.total_steps(), a);
  iterate::run_scalar<double>(e, b.total_steps(), b);
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    EXPECT_EQ(a.period[o], b.period[o]) << o;
    for (int j = 1; j <= 64; ++j) EXPECT_EQ(a.symbol(o, j), b.symbol(o, j)) << o << " " << j;
  }
}

// The return distance d = max_c |u_c - s0_c| is a difference of two rounded unit vectors: near a return Sterbenz
// makes each difference exact, so d is a whole multiple of the spacing of doubles below |s0_c| for its coordinate c.
// A multiply-add contracting u_c = X_c / |X| into the difference (u_c never rounded) gave exact returns 1.31 ulps.
TEST(Attractors, ReturnDistanceIsADifferenceOfRoundedUnitVectors) {
  int periodic = 0;
  for (const double r : {0.15, 0.3}) {
    const auto e = ensemble(r, grid_points(parse_grid("strip:10x7", -2, 2)));
    attractors::ReturnRecorder rec(e.orbits(), 5000, 300, 64, 1e-9);
    iterate::run<double>(e, rec.total_steps(), rec);
    for (std::size_t o = 0; o < e.orbits(); ++o) {
      if (rec.period[o] == 0) continue;
      ++periodic;
      const double d = rec.resid[o];
      bool whole = false;
      for (const double s : {rec.s0x[o], rec.s0y[o], rec.s0z[o]}) {
        if (s == 0) continue;
        const double q = std::ldexp(1.0, std::ilogb(s) - 53);  // the spacing below |s|
        whole = whole || std::fmod(d, q) == 0;
      }
      EXPECT_TRUE(whole) << r << " " << o << " " << d;
    }
  }
  EXPECT_GT(periodic, 50);
}

TEST(Basins, FractionsSumToOneWithIntervals) {
  const Basins b = basins(0.21, parse_grid("strip:30x20", -2, 2), 2, 7, {});
  double sum = b.undecided.value;
  std::size_t count = 0;
  for (std::size_t i = 0; i < b.attractors.size(); ++i) {
    sum += b.fractions[i].value;
    count += b.attractors[i].count;
    EXPECT_LE(b.fractions[i].low, b.fractions[i].value);
    EXPECT_GE(b.fractions[i].high, b.fractions[i].value);
    EXPECT_EQ(b.attractors[i].id, static_cast<int>(i) + 1);
  }
  EXPECT_CLOSE(sum, 1.0,
               ulps(16,
                    "fractions of counts over one total: a rounding per term and per addition, "
                    "a few attractors (measured 0)"));
  EXPECT_EQ(b.labels.size(), 600u);
  EXPECT_EQ(b.replicate_fractions.size(), b.attractors.size() + 1);
  for (const auto& rf : b.replicate_fractions) EXPECT_EQ(rf.size(), 3u);
}

TEST(Basins, LabelsEqualClassifyAndCollectOfTheMainGrid) {
  // basins() keeps the verdicts of all grids in one array (grid k at [k n, (k + 1) n)); the main grid's labels,
  // counts and per-grid fractions must be those of classify + collect on that grid alone (independent route;
  // with replicates the ids come from the union, so compare keys, not ids).  r = 0.2: a period-10 sink and the
  // P2 invariant curves (pass 2), like the 1000 x 1000 benchmark grid.
  const Grid g = parse_grid("strip:24x16", -2, 2);
  const Basins b = basins(0.2, g, 2, 5, {});
  iterate::Ensemble e;
  e.r = {0.2};
  e.initial = grid_points(g);
  std::vector<std::uint32_t> labels;
  const std::vector<Attractor> alone = collect(classify(e, {}), 0.2, &labels);
  ASSERT_EQ(b.labels.size(), labels.size());
  ASSERT_GE(alone.size(), 2u);
  const auto key_of = [](const std::vector<Attractor>& as, std::uint32_t id) {
    return id == 0 ? std::string() : as[id - 1].key;
  };
  for (std::size_t o = 0; o < labels.size(); ++o)
    EXPECT_EQ(key_of(b.attractors, b.labels[o]), key_of(alone, labels[o])) << o;
  for (const Attractor& a : alone) {
    const auto it =
        std::find_if(b.attractors.begin(), b.attractors.end(), [&](const Attractor& x) { return x.key == a.key; });
    ASSERT_NE(it, b.attractors.end()) << a.key;
    EXPECT_EQ(it->count, a.count) << a.key;
    const std::size_t i = static_cast<std::size_t>(it - b.attractors.begin());
    EXPECT_EQ(b.replicate_fractions[i][0], static_cast<double>(a.count) / static_cast<double>(labels.size()));
  }
}

// The early exit (attractors.hpp) against the full-length route: the request's labels, counts per grid and the
// attractors' table (first point, ranges of the rotation and the invariant, as NAME_fractions.csv prints them)
// equal classify + collect over the main and replicate grids, with the replicate shifts drawn as basin_rows draws
// them.  r = 0.2: a period-10 sink and the P2 curves (most orbits certified); 0.21: three sinks and the curves;
// 0.15: 1133; 0.3: 132312; 0.11: chaos (nothing to certify); 0.05: the collapse (never certified).
TEST(Basins, EarlyExitGivesTheFullLengthVerdicts) {
  for (double r : {0.2, 0.21, 0.15, 0.3, 0.11, 0.05}) {
    BasinsRequest q;
    q.r = r, q.grid = "strip:33x21", q.replicates = 2, q.seed = 3;
    const BasinsResult res = run(q);
    const Grid g = q.parsed_grid();
    const std::size_t n = static_cast<std::size_t>(g.axis1.cells * g.axis2.cells);
    std::mt19937_64 rng(q.seed);
    std::uniform_real_distribution<double> shift(-0.45, 0.45);
    std::vector<OrbitVerdict> all;
    std::vector<std::vector<OrbitVerdict>> per_grid;
    for (int k = 0; k <= q.replicates; ++k) {
      const double du = k == 0 ? 0.0 : shift(rng), dv = k == 0 ? 0.0 : shift(rng);
      per_grid.push_back(classify(ensemble(r, grid_points(g, du, dv)), {}));
      all.insert(all.end(), per_grid.back().begin(), per_grid.back().end());
    }
    const std::vector<Attractor> want = collect(all, r, nullptr);
    const std::vector<Attractor>& got = res.basins.attractors;
    ASSERT_EQ(got.size(), want.size()) << "r = " << r;
    for (std::size_t i = 0; i < want.size(); ++i) {
      const std::string at = fmt::format("r = {}, {}", r, want[i].key);
      EXPECT_EQ(got[i].key, want[i].key) << at;
      EXPECT_EQ(got[i].type, want[i].type) << at;
      EXPECT_EQ(got[i].pattern, want[i].pattern) << at;
      EXPECT_EQ(got[i].period, want[i].period) << at;
      EXPECT_EQ(got[i].point, want[i].point) << at;
      // The table prints rotations with 10 and invariants with 8 significant digits.
      EXPECT_EQ(fmt::format("{:.10g} {:.10g}", got[i].rotation_min, got[i].rotation_max),
                fmt::format("{:.10g} {:.10g}", want[i].rotation_min, want[i].rotation_max))
          << at;
      EXPECT_EQ(fmt::format("{:.8g} {:.8g}", got[i].invariant_min, got[i].invariant_max),
                fmt::format("{:.8g} {:.8g}", want[i].invariant_min, want[i].invariant_max))
          << at;
      for (int k = 0; k <= q.replicates; ++k) {
        std::size_t c = 0;
        for (const auto& v : per_grid[static_cast<std::size_t>(k)])
          c += v.type != Type::undecided && v.key == want[i].key;
        EXPECT_EQ(res.basins.replicate_fractions[i][static_cast<std::size_t>(k)],
                  static_cast<double>(c) / static_cast<double>(n))
            << at << ", grid " << k;
      }
    }
    std::vector<std::uint32_t> labels;
    const auto main_only = collect(per_grid[0], r, &labels);
    ASSERT_EQ(res.basins.labels.size(), labels.size());
    for (std::size_t o = 0; o < labels.size(); ++o) {
      const std::string a = res.basins.labels[o] ? got[res.basins.labels[o] - 1].key : "";
      const std::string b = labels[o] ? main_only[labels[o] - 1].key : "";
      EXPECT_EQ(a, b) << "r = " << r << ", point " << o;
    }
    if (r == 0.2 || r == 0.21 || r == 0.15 || r == 0.3)
      EXPECT_GT(res.basins.certified, 3 * n / 2) << "r = " << r << ": most orbits should exit early";
    if (r == 0.05) EXPECT_EQ(res.basins.certified, 0u);
  }
}

TEST(Basins, ClopperPearsonReferenceValues) {
  // Exact two-sided 95% interval for 5 of 10 (tables of Clopper and Pearson 1934: 0.1871, 0.8129).
  const Fraction f = fraction(5, 10);
  EXPECT_CLOSE(f.low, 0.187086, bound(1e-6, "the reference printed to 6 decimals"));
  EXPECT_CLOSE(f.high, 0.812914, bound(1e-6, "the reference printed to 6 decimals"));
  const Fraction z = fraction(0, 100);
  EXPECT_EQ(z.low, 0.0);
  EXPECT_CLOSE(z.high, 1 - std::pow(0.025, 0.01),
               ulps(16, "(alpha/2)^(1/n) rule at k = 0 against Boost's inverse beta, a few eps (measured 0.25)"));
}

TEST(Basins, LabelsIdenticalWithOneAndTwoThreads) {
  Options o1, o2;
  o1.run.threads = 1;
  o2.run.threads = 2;
  const Grid g = parse_grid("strip:40x30", -2, 2);
  const Basins a = basins(0.24, g, 1, 3, o1), b = basins(0.24, g, 1, 3, o2);
  EXPECT_EQ(a.labels, b.labels);
  ASSERT_EQ(a.attractors.size(), b.attractors.size());
  for (std::size_t i = 0; i < a.attractors.size(); ++i) {
    EXPECT_EQ(a.attractors[i].key, b.attractors[i].key);
    EXPECT_EQ(a.fractions[i].value, b.fractions[i].value);
  }
  EXPECT_EQ(a.replicate_fractions, b.replicate_fractions);
}

// One bar for a basins run: the kernels inside a chunk (pass 1, the cocycle, the rotation run, refinement) report
// into the chunk's share, so the bar never moves back and ends at the part's orbit count.
TEST(Basins, ProgressNeverMovesBack) {
  struct Record final : core::ProgressSink {
    std::vector<std::pair<std::size_t, std::size_t>> seen;
    void update(std::size_t done, std::size_t total) override { seen.emplace_back(done, total); }
  } rec;
  Options o;
  o.run.progress = &rec;
  const Grid g = parse_grid("strip:30x20", -2, 2);
  (void)basins(0.12, g, 1, 3, o);  // chaotic: every orbit through both passes
  ASSERT_GT(rec.seen.size(), 2u);
  for (std::size_t i = 1; i < rec.seen.size(); ++i) EXPECT_GT(rec.seen[i].first, rec.seen[i - 1].first) << i;
  for (const auto& [done, total] : rec.seen) EXPECT_EQ(total, 2u * 30 * 20);
  EXPECT_EQ(rec.seen.back().first, 2u * 30 * 20);
}

TEST(Basins, IdsDoNotDependOnProcessingOrder) {
  const double r = 0.21;
  auto pts = grid_points(parse_grid("strip:20x20", -2, 2));
  const auto v1 = classify(ensemble(r, pts), {});
  std::reverse(pts.begin(), pts.end());
  const auto v2 = classify(ensemble(r, pts), {});
  const auto a1 = collect(v1, r, nullptr), a2 = collect(v2, r, nullptr);
  ASSERT_EQ(a1.size(), a2.size());
  for (std::size_t i = 0; i < a1.size(); ++i) {
    EXPECT_EQ(a1[i].key, a2[i].key);
    EXPECT_EQ(a1[i].id, a2[i].id);
    EXPECT_EQ(a1[i].count, a2[i].count);
  }
}

// ---- the requests (attractors/requests.hpp), run as a program would run them ----

// classify: the first point of the Section 4 grid at r = 0.15 falls on 1133 (Table 6.1, 100%); the request's
// verdict is the one classify_point gives directly, and the pattern tool confirms a stable orbit.
TEST(Requests, ClassifyMatchesTheDirectRoute) {
  ClassifyRequest q;
  q.r = 0.15;
  q.point = "1,-3,-1.1";
  const ClassifyResult res = run(q);
  const OrbitVerdict direct = classify_point(core::parse_point(q.point), q.r, Options{});
  EXPECT_EQ(res.verdict.type, Type::periodic);
  EXPECT_EQ(res.pattern, "1133");
  EXPECT_EQ(res.verdict.period, 4);
  EXPECT_EQ(res.verdict.lambda1, direct.lambda1);  // same orbit, same arithmetic: bitwise
  EXPECT_NE(res.detail.find("pattern tool: stable"), std::string::npos) << res.detail;
  core::Contents c;
  res.describe(c);
  EXPECT_EQ(std::get<std::string>(c.attrs.at("type")), "periodic");
  EXPECT_EQ(std::get<long>(c.attrs.at("period")), 4);
}

// basins: the request's labels and fractions are those of attractors::basins on the same grid, and the replicate
// spread is the mean and sample sd of replicate_fractions (recomputed here).
TEST(Requests, BasinsMatchTheDirectRoute) {
  BasinsRequest q;
  q.r = 0.21;
  q.grid = "strip:16x10";
  q.replicates = 2;
  q.seed = 7;
  core::RunControl one;
  one.threads = 1;
  const BasinsResult res = run(q, one);
  const Basins b = basins(q.r, parse_grid(q.grid, -2, 2), q.replicates, q.seed, {});
  EXPECT_EQ(res.basins.labels, b.labels);
  ASSERT_EQ(res.fraction.size(), b.attractors.size());
  ASSERT_EQ(res.replicate_mean.size(), b.attractors.size() + 1);
  double sum = b.undecided.value;
  for (std::size_t i = 0; i < res.fraction.size(); ++i) {
    EXPECT_EQ(res.fraction[i], b.fractions[i].value);
    sum += res.fraction[i];
  }
  EXPECT_CLOSE(sum, 1.0,
               ulps(16,
                    "fractions of counts over one total: a rounding per term and per addition, "
                    "a few attractors (measured 0)"));
  for (std::size_t i = 0; i < res.replicate_mean.size(); ++i) {
    const auto& v = b.replicate_fractions[i];
    ASSERT_EQ(v.size(), 3u);
    const double m = (v[0] + v[1] + v[2]) / 3;
    const double sd = std::sqrt(((v[0] - m) * (v[0] - m) + (v[1] - m) * (v[1] - m) + (v[2] - m) * (v[2] - m)) / 2);
    EXPECT_CLOSE(res.replicate_mean[i], m, ulps(4, "a mean of 3 terms <= 1: 2 additions and a division"));
    EXPECT_CLOSE(res.replicate_sd[i], sd, ulps(16, "the square root of a sum of 3 squares of those differences"));
  }
  core::Contents c;
  res.describe(c);
  ASSERT_NE(c.find("labels"), nullptr);
  EXPECT_EQ(c.find("labels")->dims, (std::vector<std::size_t>{10, 16}));
  // Refused requests name the field.
  const auto field_of = [](BasinsRequest bad) {
    try {
      bad.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).substr(0, std::string(e.what()).find(':'));
    }
    return std::string("accepted");
  };
  BasinsRequest bad = q;
  bad.replicates = 101;
  EXPECT_EQ(field_of(bad), "replicates");
  bad = q, bad.w1_range = {1};
  EXPECT_EQ(field_of(bad), "w1-range");
  bad = q, bad.grid = "strip:0x4";
  EXPECT_EQ(field_of(bad), "grid");
  bad = q, bad.r = 1;
  EXPECT_EQ(field_of(bad), "r");
}

// basins-r: Table 6.1's rows given as text; at r = 0.15 every orbit of the grid falls on 1133 (the paper: 100%,
// pattern 1133), so the comparison reads 1/1 found and consistent; each row of the fraction matrix sums to one.
TEST(Requests, BasinsRComparesWithTheTable) {
  BasinsRRequest q;
  q.r_values = {0.15};
  q.table = true;
  q.grid = "random:12";
  q.reference_csv = "r,percent,patterns\n0.15,100,1133\n0.21,70,132^3312^3;132^3312^4\n0.7,0,\n";
  EXPECT_EQ(q.all_r(), (std::vector<double>{0.15, 0.15, 0.21}));  // Table rows in [0.1, 0.6] are added
  q.table = false;
  q.r_values = {0.15, 0.21};
  q.boundary_grid = "sphere:24x20";  // the comparison is under test here, not the boundary geometry
  const BasinsRResult res = run(q);
  ASSERT_EQ(res.comparison.size(), 2u);
  const Comparison& c = res.comparison[0];
  EXPECT_TRUE(c.in_table && c.has_percent && c.consistent);
  EXPECT_EQ(c.paper_found, 1);
  EXPECT_EQ(c.paper_total, 1);
  EXPECT_EQ(c.periodic.value, 1.0);
  EXPECT_EQ(res.comparison[1].paper_total, 2);
  const std::size_t cols = res.columns.size();
  ASSERT_EQ(res.fraction.size(), 2 * cols);
  for (std::size_t i = 0; i < 2; ++i) {
    double s = 0;
    for (std::size_t j = 0; j < cols; ++j) s += res.fraction[i * cols + j];
    EXPECT_CLOSE(s, 1.0, ulps(16, "counts over one total: a rounding per term and per addition (measured 0)"));
  }
  // No r at all, and a table asked for without its text, are refused naming the field.
  BasinsRRequest none;
  none.grid = "random:4";
  EXPECT_THROW(none.validate(), core::InvalidField);
  none.table = true;
  none.reference = "missing.csv";
  EXPECT_NO_THROW(none.validate());  // the caller reads the file afterwards
  try {
    run(none);
    ADD_FAILURE() << "accepted";
  } catch (const core::InvalidField& e) {
    EXPECT_EQ(std::string(e.what()).rfind("reference:", 0), 0u) << e.what();
  }
}

TEST(Errors, NameTheField) {
  const auto msg = [](auto&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_THROW(parse_grid("strip:0x10", -2, 2), std::invalid_argument);
  EXPECT_NE(msg([] {
              parse_grid("strip:0x10", -2, 2);
            }).find("grid: got 'strip:0x10', expected sphere:NxM, strip:NxM or angles:NxM with N, M >= 1"),
            std::string::npos);
  EXPECT_THROW(parse_grid("strip:10", -2, 2), std::invalid_argument);
  EXPECT_THROW(parse_grid("disk:10x10", -2, 2), std::invalid_argument);
  // 2^32 x 2^32 cells: the point count wrapped to 0 in size_t, passed the memory check and wrote past the end.
  EXPECT_THROW(grid_points(parse_grid("strip:4294967296x4294967296", -2, 2)), std::length_error);
  EXPECT_NE(msg([] { parse_grid("strip:4x4", 2, -2); }).find("w1-range"), std::string::npos);
  Options o;
  o.return_tol = 0.5;
  EXPECT_THROW(validate(o), std::invalid_argument);
  EXPECT_NE(msg([&] { validate(o); }).find("return-tol: got 0.5"), std::string::npos);
  o = {};
  o.max_period = 2000;
  EXPECT_NE(msg([&] { validate(o); }).find("max-period"), std::string::npos);
  o = {};
  o.window = 10;
  EXPECT_NE(msg([&] { validate(o); }).find("window"), std::string::npos);
  o = {};
  o.rotation_tol = 0;
  EXPECT_NE(msg([&] { validate(o); }).find("rotation-tol"), std::string::npos);
  EXPECT_THROW(basins(1.0, parse_grid("strip:2x2", -2, 2), 0, 1, {}), core::InvalidField);
  EXPECT_NE(msg([] { basins(0.0, parse_grid("strip:2x2", -2, 2), 0, 1, {}); }).find("r: got 0"), std::string::npos);
  EXPECT_THROW(basins(0.2, parse_grid("strip:2x2", -2, 2), -1, 1, {}), std::invalid_argument);
  EXPECT_THROW(classify_point(Vec3<double>(1, 0, 1), 0.2, {}), core::InvalidField);  // x z > 0
  // A grid that cannot fit is refused before any work, with the size it needs.
  EXPECT_THROW(basins(0.2, parse_grid("strip:4000000x4000000", -2, 2), 0, 1, {}), std::length_error);
}

}  // namespace
}  // namespace btob::attractors

namespace btob::attractors {
namespace {

// The measure of the basin fractions.  The sphere grid is equal-area, so the share of its points in
// a region is the region's solid angle over pi (the domain Q); checked on regions whose solid angle is known in
// closed form, and the strip's closed-form share against random points uniform on the sphere (iterate::random_points,
// Archimedes' sampling: an independent route).
TEST(Measure, SphereGridCountsSolidAngle) {
  const Grid g = parse_grid("sphere:400x400", -2, 2);
  const auto pts = grid_points(g);
  const double n = static_cast<double>(pts.size());
  // A cap of angular radius 0.5 about (1, 0, -1)/sqrt(2) (inside Q: pi/4 from its edges): solid angle
  // 2 pi (1 - cos 0.5), i.e. 2 (1 - cos 0.5) = 0.2448 of Q.
  const Vec3<double> e = Vec3<double>(1, 0, -1).normalized();
  double cap = 0, band = 0;
  for (const auto& u : pts) {
    cap += u.normalized().dot(e) > std::cos(0.5);
    band += core::theta(u) < std::numbers::pi / 6 && u(1) > 0.3;  // theta < pi/6, y > 0.3: (1/3) (0.7 / 2) of Q
  }
  // A region's count on a grid of h x h cells is off by at most its boundary cells: perimeter / h cells of area
  // h^2 each, in the (theta, y) chart (cap perimeter ~2 pi 0.5 / cell widths pi/800, 2/400): ~ 3e-3 at most.
  EXPECT_CLOSE(cap / n, 2 * (1 - std::cos(0.5)), bound(3e-3, "boundary cells: perimeter / h cells of area h^2"));
  EXPECT_CLOSE(band / n, 0.7 / 6,
               bound(1e-12 + 2.0 / 400, "aligned with the cells: off by at most one row and column"));
  EXPECT_EQ(sphere_share(g), 1.0);
  // The strip rectangle's share of the sphere measure: (2/pi)(F(b) - F(a)), F(w) = asin(w / sqrt(1 + 2 w^2)).
  EXPECT_CLOSE(strip_sphere_share(-2, 2), 4 / std::numbers::pi * std::asin(2.0 / 3),
               ulps(4, "the same closed form, its argument 2/sqrt(9) rounded differently"));
  EXPECT_CLOSE(strip_sphere_share(-1e9, 1e9), 1.0,
               ulps(4, "the whole strip is the whole domain: asin(1/sqrt 2) x 4/pi"));
  const auto rnd = iterate::random_points(1000000, 5);
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{-2, 2}, {-0.5, 0.5}, {-32, 32}, {-1, 3}}) {
    double in = 0, in_grid = 0;
    for (const auto& u : rnd) in += core::strip<double>(u).first >= a && core::strip<double>(u).first <= b;
    for (const auto& u : pts) in_grid += core::strip<double>(u).first >= a && core::strip<double>(u).first <= b;
    const double p = strip_sphere_share(a, b), sd = std::sqrt(p * (1 - p) / 1e6);
    EXPECT_CLOSE(in / 1e6, p, statistical(5 * sd + 1e-12, "5 sigma of a binomial count of 1e6 points"))
        << "[" << a << ", " << b << "]";
    EXPECT_CLOSE(in_grid / n, p, bound(2e-3, "boundary cells, as above")) << "[" << a << ", " << b << "]";
  }
}

// The default measure does not depend on how it is sampled: at r = 0.21 the equal-area grid (btob basins) and random
// points (btob basins-r) give the same fractions within their sampling errors, while the rectangle w1 in [-2, 2]
// (Lebesgue on the plane x - z = 1) gives another measure's fractions: the P2 invariant curves hold 0.344 of the
// sphere measure (300 x 300 grid) but 0.217 of the rectangle.
TEST(Measure, SphereGridAndRandomPointsAgreeTheRectangleDoesNot) {
  BasinsRequest q;
  q.r = 0.21;
  q.grid = "sphere:60x60";
  q.replicates = 0;
  const BasinsResult s = run(q);
  q.grid = "strip:60x60";
  const BasinsResult t = run(q);
  const auto rnd = iterate::random_points(3600, 3);
  std::vector<Vec3<double>> tail(rnd.begin(), rnd.end());
  const auto v = classify(ensemble(q.r, tail), {});
  std::map<std::string, double> random_fraction, sphere_fraction, strip_fraction;
  for (const auto& a : collect(v, q.r, nullptr)) random_fraction[a.pattern] = static_cast<double>(a.count) / 3600;
  for (std::size_t i = 0; i < s.basins.attractors.size(); ++i)
    sphere_fraction[s.basins.attractors[i].pattern] = s.fraction[i];
  for (std::size_t i = 0; i < t.basins.attractors.size(); ++i)
    strip_fraction[t.basins.attractors[i].pattern] = t.fraction[i];
  ASSERT_EQ(sphere_fraction.size(), 4u);  // 312^2, 132^2, 132^3312^3 and the P2 curves
  for (const auto& [pattern, p] : sphere_fraction) {
    // Two estimates of one p from 3600 points each: their difference has sd sqrt(2 p (1 - p) / 3600); 4 sd.
    EXPECT_CLOSE(random_fraction[pattern], p,
                 statistical(4 * std::sqrt(2 * p * (1 - p) / 3600), "4 sd of the difference"))
        << pattern;
  }
  const double curves = sphere_fraction["P2 invariant curves"], rect = strip_fraction["P2 invariant curves"];
  std::printf("r = 0.21, P2 invariant curves: sphere grid %.4f, random %.4f, strip rectangle %.4f\n", curves,
              random_fraction["P2 invariant curves"], rect);
  EXPECT_GT(curves - rect, 8 * std::sqrt(2 * curves * (1 - curves) / 3600));  // another measure, not noise
  core::Contents c;
  s.describe(c);
  EXPECT_EQ(std::get<std::string>(c.attrs.at("measure")), measure_name(s.basins.grid));
  EXPECT_NE(measure_name(s.basins.grid).find("sphere"), std::string::npos);
  core::Contents ct;
  t.describe(ct);
  EXPECT_CLOSE(std::get<double>(ct.attrs.at("measure_sphere_share")), strip_sphere_share(-2, 2),
               ulps(4, "the attribute is strip_sphere_share of the same strip"));
  EXPECT_EQ(BasinsRequest{}.grid.rfind("sphere:", 0), 0u);  // the default measure is the sphere's
}

}  // namespace
}  // namespace btob::attractors
