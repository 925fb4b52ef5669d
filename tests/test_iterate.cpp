// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the batched iterator: equals the scalar reference, deterministic across threads, the paper's
// periodic orbits of Section 4, renormalisation at the extremes, recorders and ensembles.
#include "core/coords.hpp"
#include "iterate/kernel.hpp"
#include "iterate/parallel.hpp"
#include "iterate/recorders.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using namespace btob::iterate;

namespace {

Ensemble make(std::vector<double> r, std::vector<Vec3<double>> ic) {
  Ensemble e;
  e.r = std::move(r);
  e.initial = std::move(ic);
  return e;
}

// True when seq (symbols 1/2/3) is periodic with a rotation of `word` (e.g. "1133").
bool on_cycle(const std::uint8_t* seq, std::size_t n, const std::string& word) {
  const std::size_t p = word.size();
  for (std::size_t shift = 0; shift < p; ++shift) {
    bool ok = true;
    for (std::size_t i = 0; i < n && ok; ++i) ok = seq[i] == word[(i + shift) % p] - '0';
    if (ok) return true;
  }
  return false;
}

}  // namespace

TEST(Ensemble, PaperGridAsPrinted) {
  const auto g = paper_grid();
  ASSERT_EQ(g.size(), 32u);
  // X = (1, -(1+8)/(2+g), -0.1-h), g = 1..8, h = 1..4 (Section 4), g-major.
  EXPECT_DOUBLE_EQ(g[0](1), -3.0);
  EXPECT_DOUBLE_EQ(g[0](2), -1.1);
  EXPECT_DOUBLE_EQ(g[31](1), -0.9);
  EXPECT_DOUBLE_EQ(g[31](2), -4.1);
  for (const auto& u : g) EXPECT_LT(u(1), 0);  // first collisions cb or cab, as the paper wants
}

TEST(Ensemble, RandomPointsAreSeededAndInTheQuadrant) {
  const auto a = random_points(1000, 42), b = random_points(1000, 42), c = random_points(1000, 43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (const auto& u : a) {
    EXPECT_GE(u(0), 0);
    EXPECT_LE(u(2), 0);
    EXPECT_CLOSE(u.norm(), 1.0, ulps(4, "unit vectors up to rounding of sqrt/cos/sin"));
  }
}

TEST(Ensemble, StripGridMapsToStripCoordinates) {
  const auto g = strip_grid(4, 3, -2, 2);
  ASSERT_EQ(g.size(), 12u);
  const auto [w1, w2] = core::strip<double>(g[0]);
  EXPECT_CLOSE(w1, -1.5, ulps(3, "first cell centre: from_strip then strip, a few roundings"));
  EXPECT_CLOSE(w2, -2.0 / 3.0, ulps(3, "first cell centre: from_strip then strip, a few roundings"));
}

TEST(Ensemble, ErrorsNameTheField) {
  EXPECT_THROW(parse_grid("strip:0x4", 1), std::invalid_argument);
  EXPECT_THROW(parse_grid("random:-3", 1), std::invalid_argument);
  EXPECT_THROW(parse_grid("hexagon", 1), std::invalid_argument);
  EXPECT_THROW(parse_grid("1,2,3", 1), core::InvalidField);  // x*z > 0: outside the domain
  EXPECT_THROW(parse_grid("0,0,0", 1), core::InvalidField);
  EXPECT_THROW(parse_grid("nan,1,-1", 1), core::InvalidField);
  EXPECT_THROW(parse_grid("strip:100000000x100000000", 1), std::length_error);
  // 2^32 x 2^32 = 2^64 points: the product wrapped to 0 in size_t and passed the memory check (found writing the grid
  // fuzz harness).
  EXPECT_THROW(parse_grid("strip:4294967296x4294967296", 1), std::length_error);
  EXPECT_THROW(parse_grid("strip:4294967297x4294967295", 1), std::length_error);
  try {
    linspace_r(0.5, 1.5, 10);
    FAIL();
  } catch (const core::InvalidField& e) {
    EXPECT_NE(std::string(e.what()).find("r-max"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(0, 1)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(linspace_r(0.2, 0.1, 10), std::invalid_argument);
  EXPECT_THROW(linspace_r(0.1, 0.2, 0), std::invalid_argument);
}

TEST(Recorders, AtanPosMatchesStdAtan2) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, worst_f = 0;
  for (int i = 0; i < 200000; ++i) {
    // Spread over many orders of magnitude, both sides of the diagonal.
    const double a = std::pow(10.0, -30 * u(gen)) * u(gen), b = std::pow(10.0, -30 * u(gen)) * u(gen);
    const double ref = std::atan2(a, b);
    if (ref == 0) continue;
    worst = std::max(worst, std::fabs(atan_pos<double>(a, b) - ref) / ref);
    const float af = static_cast<float>(a), bf = static_cast<float>(b);
    if (af > 0 && bf > 0)
      worst_f = std::max(
          worst_f, static_cast<double>(std::fabs(atan_pos<float>(af, bf) - std::atan2(af, bf)) / std::atan2(af, bf)));
  }
  // Cephes' atan is accurate to ~1 ulp; allow 2 ulp (4.4e-16) in double and 2 ulp (2.4e-7) in float.
  EXPECT_SMALL(worst, ulps<double>(2, "Cephes' atan ~1 ulp, relative error"));
  EXPECT_SMALL(worst_f, ulps<float>(2, "Cephes' atan ~1 ulp, relative error"));
  EXPECT_EQ(atan_pos<double>(0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(atan_pos<double>(1.0, 0.0), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(atan_pos<double>(1.0, 1.0), std::numbers::pi / 4);
}

TEST(Recorders, AtanFastWithinItsBound) {
  // The density image's fast route (atan_fast) against atan2 in long double, over 40 orders of magnitude on both
  // sides of the diagonal and near its reduction points (t = tan(pi/8), t = 1); NaN where its bound does not hold.
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0;
  const auto check = [&](double a, double b) {
    const double got = atan_fast(a, b);
    const long double ref = std::atan2(static_cast<long double>(a), static_cast<long double>(b));
    worst = std::max(worst, static_cast<double>(std::fabs(static_cast<long double>(got) - ref)));
  };
  for (int i = 0; i < 1000000; ++i) {
    check(std::pow(10.0, -20 * u(gen)) * u(gen) + 1e-280, std::pow(10.0, -20 * u(gen)) * u(gen) + 1e-280);
    const double t = 0.41421356237309503 * (1 + 1e-3 * (u(gen) - 0.5)),
                 s = std::ldexp(1 + u(gen), 40 - static_cast<int>(80 * u(gen)));
    check(t * s, s);
    check(s, t * s);
    check(s * (1 + 1e-3 * (u(gen) - 0.5)), s);
  }
  EXPECT_SMALL(worst, bound(kAtanFastError, "atan_fast's stated bound (fit 1.17e-7, three Newton steps 4.3e-11)"));
  EXPECT_GT(worst, kAtanFastError / 10);  // the bound is the polynomial's, not a loose one
  EXPECT_TRUE(std::isnan(atan_fast(0.0, 0.0)));
  EXPECT_TRUE(std::isnan(atan_fast(1e-310, 1e-310)));
  EXPECT_TRUE(std::isnan(atan_fast(1.0, 1e301)));
  EXPECT_EQ(atan_fast(0.0, 1.0), 0.0);
}

namespace {

// The image by the rule of DensityRecorder::exact_bin from recorded values (under, over: per column).
struct RuleImage {
  std::vector<std::uint32_t> img;
  std::vector<std::uint64_t> under, over;
};
RuleImage rule_image(const std::vector<double>& values, std::size_t n_ic, std::size_t columns, long tail,
                     std::size_t bins, double lo, double hi) {
  RuleImage out{std::vector<std::uint32_t>(columns * bins, 0), std::vector<std::uint64_t>(columns, 0),
                std::vector<std::uint64_t>(columns, 0)};
  const double scale = static_cast<double>(bins) / (hi - lo);
  for (std::size_t o = 0; o < columns * n_ic; ++o)
    for (long j = 0; j < tail; ++j) {
      const std::size_t col = o / n_ic;
      const double f = (values[o * static_cast<std::size_t>(tail) + static_cast<std::size_t>(j)] - lo) * scale;
      if (!(f >= 0)) ++out.under[col];
      else if (f > static_cast<double>(bins)) ++out.over[col];
      else ++out.img[col * bins + std::min(static_cast<std::size_t>(f), bins - 1)];
    }
  return out;
}

template <class T> void expect_image_of_exact_values(Coord c, std::size_t bins, double lo, double hi) {
  // Batches straddle columns (11 orbits per r), r spans windows and chaos; 2 threads.
  const Ensemble e = make(linspace_r(0.0717, 0.3, 23), random_points(11, 3));
  const long iters = 600, tail = 60;
  DensityRecorder dens(c, e, iters, tail, bins, lo, hi, 2);
  TailRecorder raw(c, e.orbits(), iters, tail);
  Both<DensityRecorder, TailRecorder> both(dens, raw);
  RunOptions opt;
  opt.threads = 2;
  run<T>(e, iters, both, opt);
  const RuleImage want = rule_image(raw.out, e.initial.size(), e.r.size(), tail, bins, lo, hi);
  EXPECT_EQ(dens.merge(), want.img) << coord_name(c) << " bins " << bins;
  EXPECT_EQ(dens.under, want.under);
  EXPECT_EQ(dens.over, want.over);
}

}  // namespace

TEST(Recorders, DensityImageIsTheExactCoordinatesImage) {
  // The fast route (atan_fast, bins proven by its error bound) gives the image of coord_value<T> bit for bit.  At
  // 800 bins over pi/2 the guard band (DensityRecorder::fast_error in bin units, both sides of each edge) sends
  // ~2e-4 of double's values and ~3e-3 of float's to coord_value<T>; at 2e5 bins over pi ~2.5e-2 and ~0.4.  Also a
  // range cutting the values (under and over), and the coordinates without a fast route.
  for (const std::size_t bins : {std::size_t{800}, std::size_t{200000}}) {
    expect_image_of_exact_values<double>(Coord::theta, bins, 0, std::numbers::pi / 2);
    expect_image_of_exact_values<float>(Coord::theta, bins, 0, std::numbers::pi / 2);
    expect_image_of_exact_values<double>(Coord::phi, bins, 0, std::numbers::pi);
    expect_image_of_exact_values<float>(Coord::phi, bins, 0, std::numbers::pi);
  }
  expect_image_of_exact_values<double>(Coord::theta, 300, 0.2, 1.1);
  expect_image_of_exact_values<double>(Coord::phi, 300, 1.0, 2.0);
  expect_image_of_exact_values<double>(Coord::w2, 500, -1, 1);
  expect_image_of_exact_values<float>(Coord::w1, 500, -3, 3);
  expect_image_of_exact_values<double>(Coord::log10_theta, 200, -8, 0.5);
  expect_image_of_exact_values<long double>(Coord::theta, 800, 0, std::numbers::pi / 2);
}

TEST(Recorders, DensityValuesOnBinEdgesTakeTheExactRoute) {
  // Lanes whose exact coordinate lies on a bin edge, or within the fast route's error of one, are binned by
  // coord_value<T>: theta = pi/2 (x = 0) in the last bin, theta = 0 (z = 0) in the first, and values a hair on
  // either side of an edge placed at an exact coordinate value.
  const std::vector<Vec3<double>> ic{{1, 0.3, -0.4}, {0, 0.5, -1}, {1, 0.2, 0}, {0.7, 0.1, -0.9}};
  const Ensemble e = make({0.2}, ic);
  const std::size_t bins = 1000;
  const double v0 = atan_pos<double>(0.4, 1.0), h = 1e-3;
  const double lo = v0 - 400 * h, hi = lo + static_cast<double>(bins) * h;  // v0 within rounding of the edge 400
  DensityRecorder rec(Coord::theta, e, 1, 1, bins, lo, hi, 1);
  alignas(64) double x[4] = {1, 0, 1, 0.7}, y[4] = {0.3, 0.5, 0.2, 0.1}, z[4] = {-0.4, -1, 0, -0.9};
  rec.record<double>(0, 4, 1, x, y, z, nullptr);
  std::vector<double> vals;
  for (int l = 0; l < 4; ++l) vals.push_back(coord_value<double>(Coord::theta, x[l], y[l], z[l]));
  const RuleImage want = rule_image(vals, 4, 1, 1, bins, lo, hi);
  EXPECT_EQ(rec.merge(), want.img);
  EXPECT_EQ(rec.under, want.under);
  EXPECT_EQ(rec.over, want.over);
  DensityRecorder full(Coord::theta, e, 1, 1, 10, 0, std::numbers::pi / 2, 1);
  full.record<double>(0, 4, 1, x, y, z, nullptr);
  const std::vector<std::uint32_t> img = full.merge();
  EXPECT_EQ(img[9], 1u);  // theta = pi/2: the last bin, not overflow
  EXPECT_EQ(img[0], 1u);  // theta = 0
  EXPECT_EQ(full.over[0] + full.under[0], 0u);
}

TEST(Kernel, BatchedEqualsScalarLoopOnTheSection4WorkloadAtR015) {
  // Section 4 workload at r = 0.15: 32 orbits of the paper grid.  The orbits converge to the sink
  // 1133, so symbol sequences are reproducible across implementations (perf-notes: chaotic orbits
  // are not, and are compared by distribution below).
  const Ensemble e = make({0.15}, paper_grid());
  SymbolRecorder batched(e.orbits(), 1, 1000), scalar(e.orbits(), 1, 1000), batched_f(e.orbits(), 1, 1000);
  run<double>(e, 1000, batched);
  run_scalar<double>(e, 1000, scalar);
  run<float>(e, 1000, batched_f);
  EXPECT_EQ(batched.out, scalar.out);
  EXPECT_EQ(batched_f.out, scalar.out);  // float too: the window is wide and the sink strongly attracting
}

TEST(Kernel, GenericLanesEqualSimdLanesOnSinks) {
  // long double runs the per-lane generic path.  At r = 0.15 the orbits reach the sink 1133 without a
  // chaotic transient, so whole symbol sequences agree; at r = 0.1 the transient is chaotic and only
  // the final cycle 111333 is compared.
  const Ensemble e = make({0.15}, paper_grid());
  SymbolRecorder d(e.orbits(), 1, 2000), ld(e.orbits(), 1, 2000);
  run<double>(e, 2000, d);
  run<long double>(e, 2000, ld);
  EXPECT_EQ(d.out, ld.out);
  const Ensemble e2 = make({0.1}, paper_grid());
  SymbolRecorder t(e2.orbits(), 29881, 30000);
  run<long double>(e2, 30000, t);
  for (std::size_t o = 0; o < e2.orbits(); ++o) EXPECT_TRUE(on_cycle(&t.out[o * t.count], t.count, "111333")) << o;
}

TEST(Kernel, OneThreadEqualsTwoThreadsBitwise) {
  Ensemble e = make(linspace_r(0.0717, 0.1717, 37), random_points(11, 5));  // batches straddle r values
  RunOptions one, two;
  one.threads = 1;
  two.threads = 2;
  TailRecorder a(Coord::theta, e.orbits(), 3000, 50), b(Coord::theta, e.orbits(), 3000, 50);
  run<double>(e, 3000, a, one);
  run<double>(e, 3000, b, two);
  EXPECT_EQ(a.out, b.out);  // bitwise: each orbit is computed by the same instructions on any thread
  DensityRecorder da(Coord::phi, e, 3000, 50, 300, 0, std::numbers::pi, 1),
      db(Coord::phi, e, 3000, 50, 300, 0, std::numbers::pi, 2);
  run<float>(e, 3000, da, one);
  run<float>(e, 3000, db, two);
  EXPECT_EQ(da.merge(), db.merge());
}

TEST(Kernel, PaperSection4Sinks) {
  // At r = 0.15 all 32 orbits end on the cycle 1133 (four b-collisions per period); at r = 0.1 on
  // 111333 (Section 4, Table 6.1).
  for (const auto& [r, word] : std::vector<std::pair<double, std::string>>{{0.15, "1133"}, {0.1, "111333"}}) {
    const Ensemble e = make({r}, paper_grid());
    SymbolRecorder s(e.orbits(), 20001, 20120);
    run<double>(e, 20120, s);
    for (std::size_t o = 0; o < e.orbits(); ++o)
      EXPECT_TRUE(on_cycle(&s.out[o * s.count], s.count, word)) << "r = " << r << " orbit " << o;
  }
}

TEST(Kernel, ThreeParticleCollapseBelowThreshold) {
  // r = 0.05 < 7 - 4 sqrt(3): orbits converge to the three-particle collapse, symbol 1 forever with
  // theta -> 0, or symbol 3 forever with theta -> pi/2 (Section 5.2, Proposition 5.1).
  const Ensemble e = make({0.05}, paper_grid());
  SymbolRecorder s(e.orbits(), 4801, 5000);
  TailRecorder t(Coord::theta, e.orbits(), 5000, 1);
  Both<SymbolRecorder, TailRecorder> both(s, t);
  run<double>(e, 5000, both);
  int ones = 0, threes = 0;
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    const bool all1 = on_cycle(&s.out[o * s.count], s.count, "1");
    const bool all3 = on_cycle(&s.out[o * s.count], s.count, "3");
    EXPECT_TRUE(all1 || all3) << "orbit " << o;
    if (all1) {
      ++ones;
      EXPECT_LT(t.out[o], 1e-100);  // theta decays like (r^2/lambda_P1,3)^k per step: far below 1e-100 at k = 5000
    }
    if (all3) {
      ++threes;
      EXPECT_GT(t.out[o], std::numbers::pi / 2 - 1e-15);
    }
    EXPECT_TRUE(std::isfinite(t.out[o]));
  }
  EXPECT_EQ(ones + threes, 32);
}

TEST(Kernel, TailHistogramsAgreeWithScalarLoopAtEveryR) {
  // Across Figure 4.1's range the batched kernel and the scalar loop give the same distribution of
  // tail values at every r.  On chaotic r the orbits part after ~60 steps (perf-notes), so compare
  // distributions: per r, the Kolmogorov-Smirnov distance of the 32 x 100 tail thetas.
  const long iters = 3000, tail = 100;
  const Ensemble e = make(linspace_r(0.0717, 0.1717, 60), paper_grid());
  TailRecorder a(Coord::theta, e.orbits(), iters, tail), b(Coord::theta, e.orbits(), iters, tail);
  run<double>(e, iters, a);
  run_scalar<double>(e, iters, b);
  const std::size_t per_r = e.initial.size() * tail;
  // Histograms at the plots' resolution (200 bins on [0, pi/2]); the distance is the largest gap
  // between the two cumulative histograms (Kolmogorov-Smirnov on binned data).  Exact values are
  // not comparable where orbits collapse (theta ~ 1e-150 in one run, 1e-160 in the other).
  const int bins = 200;
  double worst = 0, mean = 0;
  for (std::size_t ir = 0; ir < e.r.size(); ++ir) {
    std::vector<double> ha(bins, 0), hb(bins, 0);
    for (std::size_t i = ir * per_r; i < (ir + 1) * per_r; ++i) {
      ha[std::min(bins - 1, static_cast<int>(a.out[i] / (std::numbers::pi / 2) * bins))] += 1.0 / per_r;
      hb[std::min(bins - 1, static_cast<int>(b.out[i] / (std::numbers::pi / 2) * bins))] += 1.0 / per_r;
    }
    double ca = 0, cb = 0, d = 0;
    for (int k = 0; k < bins; ++k) {
      ca += ha[k];
      cb += hb[k];
      d = std::max(d, std::fabs(ca - cb));
    }
    worst = std::max(worst, d);
    mean += d / static_cast<double>(e.r.size());
  }
  // Tail points of one orbit are correlated, so the effective sample is between the 32 orbits and the
  // 3200 points: the two-sample KS distance exceeds 0.34 (n = 32) or 0.034 (n = 3200) with probability
  // 5%.  The bounds below, about twice the largest distance seen on two processor generations, leave room for noise but
  // fail on any systematic difference (a wrong branch, a lost rescale, a skipped step).
  std::printf("binned KS distance batched vs scalar: worst %.3f, mean %.3f over %zu r values\n", worst, mean,
              e.r.size());
  EXPECT_SMALL(worst, statistical(0.14, "KS distance of correlated samples: twice the largest measured"))
      << "mean KS distance " << mean;
  EXPECT_SMALL(mean, statistical(0.02, "mean KS distance: twice the largest measured"));
}

TEST(Kernel, RenormalisationAtTheExtremes) {
  // r = 1e-6: the branch matrices shrink vectors by ~r per step; the interval adapts and the state
  // stays finite and non-zero in float and double (perf-notes: a fixed K underflows as r -> 0).
  for (double r : {1e-6, 1e-3, 0.5, 0.999999}) {
    const Ensemble e = make({r}, random_points(64, 3));
    FinalRecorder fd(e.orbits(), 20000), ff(e.orbits(), 20000);
    run<double>(e, 20000, fd);
    run<float>(e, 20000, ff);
    for (std::size_t o = 0; o < e.orbits(); ++o) {
      for (const auto* rec : {&fd, &ff}) {
        const auto& u = rec->out[o];
        ASSERT_TRUE(std::isfinite(u(0)) && std::isfinite(u(1)) && std::isfinite(u(2))) << "r = " << r;
        EXPECT_CLOSE(u.norm(), 1.0,
                     ulps(8, "FinalRecorder normalises in double: sqrt of 3 squares, a division (measured 1 eps)"));
        EXPECT_GE(u(0), 0);
        EXPECT_LE(u(2), 0);
      }
    }
    EXPECT_GE(renormalisation_interval<float>({r}), 1);
    EXPECT_GE(renormalisation_interval<double>({r}), renormalisation_interval<float>({r}));
  }
  EXPECT_EQ(renormalisation_interval<double>({0.1}), renormalisation_interval<double>({0.1, 0.1}));
}

TEST(Kernel, KernelStepMatchesThePaperMatrices) {
  // One step of the kernel (matrices divided by r, power-of-two rescaling) gives the direction of
  // P_s u and the branch s of core::step, on random points of every branch, to a few ulps.
  std::vector<Vec3<double>> ic = random_points(2000, 11);
  for (double r : {0.01, 0.0718, 0.2, 0.9}) {
    const Ensemble e = make({r}, ic);
    FinalRecorder f(e.orbits(), 1);
    SymbolRecorder s(e.orbits(), 1, 1);
    Both<FinalRecorder, SymbolRecorder> rec(f, s);
    run<double>(e, 1, rec);
    for (std::size_t o = 0; o < ic.size(); ++o) {
      const core::Step<double> st = core::step<double>(ic[o], r);
      const Vec3<double> ref = st.u / st.u.norm();
      EXPECT_EQ(s.out[o], st.symbol) << "r = " << r << " point " << o;
      EXPECT_SMALL((f.out[o] - ref).norm(), ulps(45, "unit vectors: a few ulps of 1")) << "r = " << r;
    }
  }
}

TEST(Build, RecorderVectorCodeIsInlinedIntoEachCaller) {
  // Only the kernel's units are compiled for the host's instruction set.  A header function left out of line is
  // emitted by every unit that calls it, and the linker keeps one copy: btob's DensityRecorder::certain_bins<double>
  // was reference.cpp's baseline SSE2 copy (docs/ARCHITECTURE.md, "Determinism").  The recorders' per-lane functions
  // are always_inline, so btob must hold no out-of-line copy of them.
  const std::string bin = BTOB_BINARY;  // tests/CMakeLists.txt: this build's btob
  ASSERT_TRUE(std::ifstream(bin).good()) << "btob not built at " << bin;
  FILE* p = popen(("nm -C --defined-only " + bin + " 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string found;
  long symbols = 0;
  char* buf = nullptr;
  std::size_t cap = 0;
  while (getline(&buf, &cap, p) > 0) {  // whole lines: a demangled name can exceed any fixed buffer
    const std::string line = buf;
    ++symbols;
    // The functions themselves; the lambdas inside them are functions of their own, emitted where used when the build
    // does not optimise (the debug preset; check_kernel_symbols covers them in optimised builds).
    if (line.find("{lambda") != std::string::npos) continue;
    // (iterate::TailRecorder by its qualified name: StateTailRecorder's per-lane normalisation of the tail is not
    // vector code and may stay out of line where the build does not optimise.)
    for (const char* f :
         {"DensityRecorder::certain_bins", "DensityRecorder::record", "iterate::TailRecorder::record",
          "iterate::coord_values<", "iterate::coord_value<", "iterate::atan_fast", "iterate::atan_pos<"})
      if (line.find(f) != std::string::npos) found += line;
  }
  std::free(buf);
  EXPECT_EQ(pclose(p), 0);
  EXPECT_GT(symbols, 1000);  // nm read btob's symbol table
  EXPECT_EQ(found, "") << "out-of-line copies of vectorising recorder code in btob";
}

// ---- iterate::parallel_for: the analyses' one parallel loop -----------------------------------------------------

// Every item is visited exactly once whatever the thread count and the chunk (0: contiguous blocks, 1: round robin),
// and per-thread scratch is made once per thread, never more than the threads asked for.
TEST(ParallelFor, EveryItemOnceForEveryScheduleAndThreadCount) {
  for (std::size_t n : {0, 1, 7, 1000})
    for (int threads : {1, 2, 3})
      for (std::size_t chunk : {0, 1, 5}) {
        std::vector<int> seen(n, 0);
        iterate::parallel_for(n, threads, chunk, [&](std::size_t i) { ++seen[i]; });
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(n)) << n << " " << threads << " " << chunk;
      }
  for (int threads : {1, 2, 3}) {
    std::vector<int> seen(100, 0);
    std::atomic<int> made{0};
    iterate::parallel_for_scratch(
        seen.size(), threads, [&] { return ++made; }, [&](int& scratch, std::size_t i) { seen[i] += scratch > 0; });
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 100);
    EXPECT_GE(made.load(), 1);
    EXPECT_LE(made.load(), threads);
  }
}
