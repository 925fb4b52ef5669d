// SPDX-License-Identifier: GPL-3.0-or-later
// Ulam's transfer operator (src/transfer): the generic construction against maps whose invariant densities are
// known in closed form (logistic map at 4: arcsine; baker map: uniform), the ergodic decomposition against a
// hand-made chain, the block spectrum against Spectra on the whole matrix, the two routes of P^_r against each
// other, thread independence, and the request's errors.
#include "attractors/attractors.hpp"
#include "iterate/ensemble.hpp"
#include "transfer/stages.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_impl.hpp"

#include "csv_cells.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using namespace btob::transfer;

namespace {

// The logistic map x -> 4 x (1 - x) on [0, 1] (second coordinate a dummy of one box).
void logistic(double* a, double*, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) a[k] = 4 * a[k] * (1 - a[k]);
}
// The baker map (x, y) -> (2x mod 1, (y + floor(2x)) / 2) on [0, 1)^2; preserves Lebesgue measure.
void baker(double* a, double* b, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) {
    const double f = std::floor(2 * a[k]);
    a[k] = 2 * a[k] - f;
    b[k] = (b[k] + f) / 2;
  }
}

double tv(const std::vector<double>& p, const std::vector<double>& q) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) s += std::fabs(p[i] - q[i]);
  return s / 2;
}

// The only closed class's invariant density.
std::vector<double> invariant(const UlamMatrix& P) {
  const Decomposition d = decompose(P);
  EXPECT_EQ(d.classes.size(), 1u);
  return class_density(P, d, 1);
}

TEST(Transfer, FindsAndNamesItsPeriodicAttractorsWithoutCycles) {
  // r = 0.15: one closed class holding the stable cycle 1133 (Table 6.1), found from the class's boxes alone.
  TransferRequest q;
  q.r = 0.15;
  q.boxes = "64x64";
  q.samples = 16;
  q.eigenvalues = 2;
  q.measure_orbits = 0;
  const auto res = run(q);
  EXPECT_EQ(res.attractors_found, std::vector<std::string>{"1133"});
  ASSERT_EQ(res.cycles.size(), 1u);
  EXPECT_EQ(res.cycles[0].word, "1133");
  EXPECT_EQ(res.cycles[0].outcome, "stable orbit");
  // The class is named by classify's verdict on its boxes' centres: every one reaches the sink.
  EXPECT_EQ(res.class_names.name, std::vector<std::string>{"1133"});
  EXPECT_EQ(res.class_names.verdict, std::vector<std::string>{"stable"});
  ASSERT_EQ(res.class_names.reached.size(), 1u);
  EXPECT_EQ(res.class_names.majority, res.class_names.classified);
  q.cycles = {"1133"};
  const auto named = run(q);
  EXPECT_TRUE(named.attractors_found.empty());  // named cycles: nothing searched
  EXPECT_TRUE(named.class_names.name.empty());
  EXPECT_EQ(named.classes_csv(), "");
}

TEST(Transfer, NamesTheSinksThatClassifyFindsWithoutCycles) {
  // r = 0.21: three sinks (132^2, its mirror 312^2, 132^3312^3) and the P2 invariant curves share one closed class
  // at 32 x 32 boxes.  Transfer without --cycle must name the stable periodic words that attractors::classify finds
  // from a 16 x 16 strip grid of its own (the counting route of `btob basins`), and target each in its basins.
  TransferRequest q;
  q.r = 0.21;
  q.boxes = "32x32";
  q.samples = 16;
  q.eigenvalues = 0;
  q.measure_orbits = 0;
  q.tv_bins = 16;
  const auto res = run(q);
  iterate::Ensemble grid;
  grid.r = {q.r};
  grid.initial = iterate::strip_grid(16, 16, -2, 2);
  std::vector<std::string> sinks;
  for (const auto& a : attractors::collect(attractors::classify(grid, attractors::Options{}), q.r, nullptr))
    if (a.type == attractors::Type::periodic) sinks.push_back(a.pattern);
  ASSERT_EQ(sinks.size(), 3u);
  auto found = res.attractors_found;
  std::sort(found.begin(), found.end());
  std::sort(sinks.begin(), sinks.end());
  EXPECT_EQ(found, sinks);
  for (const auto& w : res.attractors_found)
    EXPECT_TRUE(std::any_of(res.basins.begin(), res.basins.end(), [&](const BasinInfo& b) { return b.attractor == w; }))
        << w;
  // No attractor holds a majority of the class's starts: its name is undecided, and classes.csv lists them all.
  EXPECT_EQ(res.class_names.name, std::vector<std::string>{"undecided"});
  EXPECT_EQ(res.class_names.verdict, std::vector<std::string>{"undecided"});
  long starts = 0;
  for (const auto& a : res.class_names.reached) {
    starts += a.starts;
    EXPECT_TRUE(a.verdict == "stable" || a.verdict == "neutral" || a.verdict == "undecided") << a.attractor;
  }
  EXPECT_EQ(starts, static_cast<long>(res.class_names.classified[0]));
  EXPECT_EQ(btob::testing::csv_cells(res.classes_csv()).size(), res.class_names.reached.size() + 1);
}

}  // namespace

TEST(Transfer, LogisticArcsineDensityConvergesWithTheBoxes) {
  // Exact box masses of the arcsine density 1 / (pi sqrt(x (1 - x))): (2/pi) (asin sqrt(b) - asin sqrt(a)).
  double previous = 1;
  for (long n : {64L, 256L, 1024L}) {
    Partition p;
    p.n1 = n, p.n2 = 1;
    const auto P = ulam(p, 256, logistic);
    const auto u = invariant(P);
    std::vector<double> exact(static_cast<std::size_t>(n));
    for (long i = 0; i < n; ++i)
      exact[static_cast<std::size_t>(i)] =
          2 / std::numbers::pi * (std::asin(std::sqrt(double(i + 1) / n)) - std::asin(std::sqrt(double(i) / n)));
    const double d = tv(u, exact);
    // Ulam's method converges in L1 for this map (Li 1976); the arcsine density's 1/sqrt singularities at 0
    // and 1 make the boxes next to them converge like h^(1/2) (measured: TV 0.064, 0.036, 0.020 at n = 64, 256,
    // 1024, a rate n^-0.43).  Bound 0.7 / sqrt(n), and each refinement by 4 must shrink the distance.
    std::printf("logistic n = %ld: TV %.3g\n", n, d);
    EXPECT_LT(d, 0.7 / std::sqrt(double(n))) << "n = " << n;
    EXPECT_LT(d, previous) << "n = " << n;
    previous = d;
  }
}

TEST(Transfer, BakerUniformDensityConvergesWithTheBoxes) {
  double previous = 1;
  for (long n : {12L, 24L, 48L}) {  // not powers of two: the partition is not the baker map's Markov partition
    Partition p;
    p.n1 = p.n2 = n;
    const auto P = ulam(p, static_cast<int>(4 * n), baker);
    const auto u = invariant(P);
    const std::vector<double> uniform(static_cast<std::size_t>(n * n), 1.0 / double(n * n));
    const double d = tv(u, uniform);
    // Lebesgue is invariant, so P is doubly stochastic up to the sampling error of the rows (S = 4n
    // low-discrepancy samples per box: ~1/S per transition probability); bound 1/(2n), and each refinement by 2
    // (with twice the samples) must shrink the distance (measured: 0.027, 0.012, 0.0097 at n = 12, 24, 48).
    std::printf("baker n = %ld: TV %.3g\n", n, d);
    EXPECT_LT(d, 0.6 / double(n)) << "n = " << n;
    EXPECT_LT(d, previous) << "n = " << n;
    previous = d;
  }
}

TEST(Transfer, DecompositionOfAHandMadeChain) {
  // Boxes 0 -> 1 -> 2 -> 0 (a cycle of period 3), 3 -> {0, 4}, 4 -> 4 (a fixed point), 5 -> 3.
  UlamMatrix P;
  P.n = 6;
  P.row_ptr = {0, 1, 2, 3, 5, 6, 7};
  P.col = {1, 2, 0, 0, 4, 4, 3};
  P.val = {1, 1, 1, 0.5, 0.5, 1, 1};
  const Decomposition d = decompose(P);
  ASSERT_EQ(d.classes.size(), 2u);
  EXPECT_EQ(d.class_of_box[0], 1u);
  EXPECT_EQ(d.class_of_box[4], 2u);
  EXPECT_EQ(d.class_of_box[3], 0u);
  EXPECT_EQ(d.classes[0].period, 3);
  EXPECT_EQ(d.classes[1].period, 1);
  const auto e = leading_eigenpairs(P, d, 4, false);
  ASSERT_EQ(e.size(), 4u);
  int ones = 0, roots = 0;
  for (const auto& x : e) {
    EXPECT_CLOSE(std::abs(x.value), 1.0,
                 ulps(64, "dense eigensolver of 3x3 and 1x1 blocks: rounding only (measured 1 eps)"));
    ones += std::abs(x.value - 1.0) < 1e-12;
    roots += std::abs(std::pow(x.value, 3) - 1.0) < 1e-12;
  }
  EXPECT_EQ(ones, 2);
  EXPECT_EQ(roots, 4);
}

namespace {
// Boxes 0 -> 1 -> 2 -> 0 (a cycle of period 3), 3 -> {0, 4} (half each), 4 -> 4 (a fixed point), 5 -> 3.
UlamMatrix hand_made_chain() {
  UlamMatrix P;
  P.n = 6;
  P.row_ptr = {0, 1, 2, 3, 5, 6, 7};
  P.col = {1, 2, 0, 0, 4, 4, 3};
  P.val = {1, 1, 1, 0.5, 0.5, 1, 1};
  return P;
}
}  // namespace

TEST(TransferStages, AbsorbersProjectionAndBasinsOfAHandMadeChainAlone) {
  // The stages of `btob transfer` run alone on the chain: the closed classes {0, 1, 2} and {4} absorb; Lebesgue
  // measure (1/6 per box) started on box 3 splits in halves, box 5's reaches box 3 after one step and splits too.
  const UlamMatrix P = hand_made_chain();
  const Decomposition d = decompose(P);
  const Absorbers absorbers = find_absorbers(P, d, {}, 1e-2, nullptr);
  ASSERT_EQ(absorbers.list.size(), 2u);
  EXPECT_EQ(absorbers.list[0].boxes, (std::vector<long>{0, 1, 2}));
  EXPECT_EQ(absorbers.of_box, (std::vector<std::uint32_t>{1, 1, 1, 0, 2, 0}));
  for (double m : absorbers.list[0].density)  // the 3-cycle's invariant density is uniform (dense eigensolver)
    EXPECT_CLOSE(m, 1.0 / 3, ulps(64, "a 3x3 dense eigenvector, normalised: rounding only"));
  const std::vector<double> mu(6, 1.0 / 6);
  const Projection projection = project_lebesgue(P, absorbers, mu, nullptr);
  const std::vector<double> entry{1.0 / 3, 1.0 / 6, 1.0 / 6, 0, 1.0 / 3, 0};
  for (std::size_t i = 0; i < entry.size(); ++i)
    EXPECT_CLOSE(projection.entry[i], entry[i], ulps(4, "sums of three halvings of 1/6")) << "box " << i;
  EXPECT_EQ(projection.unabsorbed, 0.0);  // everything is absorbed after two steps
  // Basins with the fixed point as the only target: boxes 3 and 5 reach it with probability 1/2.
  BasinTargets targets;
  targets.basins.resize(1);
  targets.basins[0].attractor = "fixed point";
  targets.of_box = {0, 0, 0, 0, 1, 0};
  const Basins basins = absorb(P, targets, mu);
  EXPECT_EQ(basins.basin_of_box, (std::vector<std::uint32_t>{0, 0, 0, 1, 1, 1}));
  const std::vector<double> probability{0, 0, 0, 0.5, 1, 0.5};
  for (std::size_t i = 0; i < probability.size(); ++i)
    EXPECT_CLOSE(basins.basin_probability[i], probability[i], bound(1e-12, "BiCGSTAB's relative residual")) << i;
  EXPECT_CLOSE(basins.basins[0].fraction, 1.0 / 3, bound(1e-12, "BiCGSTAB's relative residual"));
  EXPECT_CLOSE(basins.unabsorbed, 2.0 / 3, bound(1e-12, "BiCGSTAB's relative residual"));
}

TEST(Transfer, BlockSpectrumAgreesWithSpectraOnTheWholeMatrix) {
  // r = 0.11: one chaotic closed class, simple leading eigenvalues; 48 x 48 boxes.
  const Partition p = domain_partition(Domain::strip, 48, 48);
  const auto P = ulam_btob(0.11, Domain::strip, p, 16, "direct");
  const Decomposition d = decompose(P);
  const auto blocks = leading_eigenpairs(P, d, 6, false);
  const auto whole = leading_eigenvalues_whole(P, 6);
  ASSERT_GE(whole.size(), 3u);
  // Both are Arnoldi / QR to ~1e-10 relative (Spectra's tolerance); the leading three moduli must agree to 1e-8.
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_CLOSE(std::abs(blocks[k].value), std::abs(whole[k]), bound(1e-8, "two Arnoldi runs to Spectra's 1e-10"))
        << k;
  EXPECT_CLOSE(blocks[0].value.real(), 1.0, bound(1e-10, "Spectra's convergence tolerance"));
}

TEST(Transfer, RoutesAgreeAndThreadsDoNotMatter) {
  const Partition p = domain_partition(Domain::strip, 32, 32);
  core::RunControl one, two;
  one.threads = 1, two.threads = 2;
  for (const char* route : {"direct", "kernel"}) {
    const auto a = ulam_btob(0.2, Domain::strip, p, 16, route, one),
               b = ulam_btob(0.2, Domain::strip, p, 16, route, two);
    EXPECT_EQ(a.row_ptr, b.row_ptr) << route;
    EXPECT_EQ(a.col, b.col) << route;
    EXPECT_EQ(a.val, b.val) << route;
  }
  // The kernel divides the matrices by r and rescales by powers of two; a sample whose image lies within
  // rounding of a box edge may land in the neighbour: rows may differ, but only in a few boxes.
  const auto a = ulam_btob(0.2, Domain::strip, p, 16, "direct"), b = ulam_btob(0.2, Domain::strip, p, 16, "kernel");
  long differ = 0;
  for (long i = 0; i < a.n; ++i) {
    const auto s = static_cast<std::size_t>(i);
    std::vector<int> ca(a.col.begin() + a.row_ptr[s], a.col.begin() + a.row_ptr[s + 1]);
    std::vector<int> cb(b.col.begin() + b.row_ptr[s], b.col.begin() + b.row_ptr[s + 1]);
    differ += ca != cb;
  }
  EXPECT_LE(differ, a.n / 100);
  for (const char* route : {"direct", "kernel"}) {
    const auto x = ulam_btob(0.3, Domain::angles, domain_partition(Domain::angles, 16, 16), 4, route);
    EXPECT_EQ(x.lost, 0u) << route;
    for (long i = 0; i < x.n; ++i) {
      double s = 0;
      for (int e = x.row_ptr[static_cast<std::size_t>(i)]; e < x.row_ptr[static_cast<std::size_t>(i + 1)]; ++e)
        s += x.val[static_cast<std::size_t>(e)];
      EXPECT_CLOSE(s, 1.0, ulps(4500, "a row sums k / S for k = 1..S: rounding of at most S additions"));
    }
  }
}

TEST(Transfer, SinkAtR015HoldsTheDensity) {
  TransferRequest q;
  q.r = 0.15;
  q.boxes = "128x128";
  q.samples = 64;
  q.eigenvalues = 8;
  q.measure_orbits = 0;
  q.tv_bins = 16;
  q.cycles = {"1133"};
  const auto res = run(q);
  EXPECT_EQ(res.closed_classes(), 1);
  ASSERT_EQ(res.cycles.size(), 1u);
  EXPECT_EQ(res.cycles[0].outcome, "stable orbit");
  // 99% of the invariant density lies within a few boxes of the cycle's four boxes (Ulam's smearing of a sink
  // spans a number of boxes independent of h: 4 to 6 at 128^2 to 512^2, see the README).
  EXPECT_LE(res.cycles[0].radius99, 8);
  EXPECT_GE(res.cycles[0].radius99, 0);
  double total = 0;
  for (const auto& c : res.components) total += c.lebesgue;
  EXPECT_CLOSE(total + res.unabsorbed, 1.0,
               ulps(4500, "mass conservation of the projection: 16384 sums, a random walk of ~128 eps (measured 38)"));
  // Basins from the Ulam graph: the sink is the only attractor named, and every box of the rectangle reaches it.
  ASSERT_EQ(res.basins.size(), 1u);
  EXPECT_EQ(res.basins[0].attractor, "1133");
  EXPECT_EQ(res.basins[0].target_boxes, 4);
  EXPECT_CLOSE(res.basins[0].fraction, 1.0, bound(1e-9, "BiCGSTAB to a relative residual of 1e-12 on 16384 boxes"));
}

// r = 0.21: three sinks and the P2 invariant curves coexist.  The spectral route sees one closed class (the P2
// lamination's diffusion ties them together); absorption into each attractor's boxes gives one basin each.
TEST(Transfer, BasinsFromTheUlamGraphAtR021) {
  TransferRequest q;
  q.r = 0.21;
  q.boxes = "64x64";
  q.samples = 64;
  q.eigenvalues = 4;
  q.measure_orbits = 0;
  q.tv_bins = 16;
  q.cycles = {"1322,3122,132^3312^3"};
  const auto res = run(q);
  ASSERT_EQ(res.basins.size(), 4u);
  EXPECT_EQ(res.basins[3].attractor, "P2 region");
  double sum = 0;
  for (const auto& b : res.basins) {
    EXPECT_GT(b.fraction, 0.05) << b.attractor;
    sum += b.fraction;
  }
  EXPECT_CLOSE(sum + res.basin_unabsorbed, 1.0, ulps(64, "the unabsorbed mass is defined as 1 - the sum"));
  EXPECT_SMALL(std::fabs(res.basin_unabsorbed), bound(1e-8, "every box reaches an attractor; solves to 1e-12"));
  EXPECT_LT(res.basin_residual, 1e-11);
  // The P2 region R = {I < 2 - alpha^2/r} lies inside |w1| < 2 at r = 0.21: its share of the 4 x 2 rectangle is
  // the ellipse's area pi c / sqrt(det M) / 8, M = [[4r, -2 alpha], [-2 alpha, 2]] (`btob basins` counts 0.2172).
  const double al = (1 + q.r) / 2, c = 2 - al * al / q.r;
  const double area = std::numbers::pi * c / std::sqrt(8 * q.r - 4 * al * al) / 8;
  EXPECT_CLOSE(res.basins[3].exact, area, bound(1e-7, "midpoint rule on 2^17 points with square-root ends"));
  // Ulam's blur puts the boundary boxes of R into R's basin: the fraction exceeds R's measure (0.40 at 64^2,
  // 0.27 at 256^2, see the README); the boxes of R alone weigh less than R.
  EXPECT_GT(res.basins[3].fraction, area);
  // The map of basins: every target box is its own attractor's with probability 1.
  ASSERT_EQ(res.basin_of_box.size(), 4096u);
  long p2 = 0;
  for (std::size_t i = 0; i < res.basin_of_box.size(); ++i)
    if (res.basin_of_box[i] == 4 && res.basin_probability[i] == 1) ++p2;
  EXPECT_GE(p2, res.basins[3].target_boxes);
}

TEST(Transfer, RequestErrorsNameTheirField) {
  const auto field = [](auto q) -> std::string {
    try {
      q.validate();
    } catch (const core::InvalidField& e) {
      return e.field;
    }
    return "";
  };
  TransferRequest q;
  q.measure_orbits = 0;
  EXPECT_EQ(field(q), "");
  auto b = q;
  b.boxes = "0x10";
  EXPECT_EQ(field(b), "boxes");
  b.boxes = "30000x30000";
  EXPECT_EQ(field(b), "boxes");
  b.boxes = "12";
  EXPECT_EQ(field(b), "boxes");
  auto r = q;
  r.r = 1;
  EXPECT_EQ(field(r), "r");
  auto k = q;
  k.boxes = "4x4";
  k.tv_bins = 4;
  k.eigenvalues = 17;
  EXPECT_EQ(field(k), "eigenvalues");
  auto s = q;
  s.samples = 0;
  EXPECT_EQ(field(s), "samples");
  auto d = q;
  d.domain = "disc";
  EXPECT_EQ(field(d), "domain");
  auto t = q;
  t.tv_bins = 7;
  EXPECT_EQ(field(t), "tv-bins");
  auto c = q;
  c.cycles = {"14"};
  EXPECT_THROW(c.validate(), std::invalid_argument);
  // eigenvalues 0 (no spectrum, only the basins): allowed when there is an attractor and no cross-check.
  auto z = q;  // r = 0.15 < 3 - 2 sqrt 2: no P2 region, no cycle
  z.eigenvalues = 0;
  EXPECT_EQ(field(z), "eigenvalues");
  z.cycles = {"132312"};  // not stable at 0.15
  EXPECT_EQ(field(z), "eigenvalues");
  z.cycles = {"1133"};
  EXPECT_EQ(field(z), "");
  z.check_whole = true;
  EXPECT_EQ(field(z), "eigenvalues");
  auto p2 = q;
  p2.r = 0.21;  // the P2 region is a target
  p2.eigenvalues = 0;
  EXPECT_EQ(field(p2), "");
  p2.eigenvalues = -1;
  EXPECT_EQ(field(p2), "eigenvalues");
  TransferRRequest rr;
  rr.r_max = 0.05;
  EXPECT_EQ(field(rr), "r-max");
  TransferRRequest r0;  // transfer-r's output is the spectrum: no 0
  r0.eigenvalues = 0;
  EXPECT_EQ(field(r0), "eigenvalues");
}

// ---- The files of `btob transfer` and `btob transfer-r` (output.cpp), through the public API ----

using btob::testing::csv_cells;
using btob::testing::csv_column;
using btob::testing::expect_numbers_or_empty;

TEST(TransferFiles, TablesAndArraysOfOneRunAgreeWithTheResult) {
  TransferRequest q;
  q.r = 0.15;
  q.boxes = "16x16";
  q.samples = 4;
  q.eigenvalues = 4;
  q.measure_orbits = 0;
  q.tv_bins = 16;
  q.cycles = {"1133"};
  const TransferResult res = run(q);
  // spectrum.csv: one row per eigenvalue, modulus = |lambda|, the cross-check's columns empty (check-whole off).
  const auto spec = csv_cells(res.spectrum_csv());
  expect_numbers_or_empty(res.spectrum_csv(), "spectrum.csv");
  ASSERT_EQ(spec.size(), res.eig_re.size() + 1);
  for (std::size_t k = 0; k < res.eig_re.size(); ++k) {
    const auto& row = spec[k + 1];
    EXPECT_CLOSE(std::stod(row[csv_column(spec[0], "modulus")]),
                 std::abs(std::complex<double>(res.eig_re[k], res.eig_im[k])),
                 ulps(4, "the CSV's decimal of the same modulus, read back"));
    EXPECT_EQ(row[csv_column(spec[0], "whole_re")], "");
  }
  // components.csv: the Lebesgue fractions and what the projection left unabsorbed make the whole measure.
  const auto comp = csv_cells(res.components_csv());
  expect_numbers_or_empty(res.components_csv(), "components.csv");
  ASSERT_EQ(comp.size(), res.components.size() + 1);
  double total = res.unabsorbed;
  for (std::size_t k = 1; k < comp.size(); ++k) total += std::stod(comp[k][csv_column(comp[0], "lebesgue_fraction")]);
  EXPECT_CLOSE(total, 1.0, bound(1e-5 * static_cast<double>(comp.size()), "the CSV prints 6 decimals per fraction"));
  // cycles.csv: the cycle with its points; the same points as the HDF5 array cycle_points.
  const auto cyc = csv_cells(res.cycles_csv());
  expect_numbers_or_empty(res.cycles_csv(), "cycles.csv");
  ASSERT_EQ(cyc.size(), 2u);
  EXPECT_EQ(cyc[1][csv_column(cyc[0], "word")], "1133");
  EXPECT_EQ(std::stoul(cyc[1][csv_column(cyc[0], "points")]), res.cycles[0].a.size());
  core::Contents c;
  res.describe(c);
  const core::ArrayView* pts = c.find("cycle_points");
  ASSERT_NE(pts, nullptr);
  EXPECT_EQ(pts->dims, (std::vector<std::size_t>{res.cycles[0].a.size(), 2}));
  // basins.csv: the sink's row, its fraction as the result holds it; the P2 column "exact" empty (no P2 region).
  const auto bas = csv_cells(res.basins_csv());
  expect_numbers_or_empty(res.basins_csv(), "basins.csv");
  ASSERT_EQ(bas.size(), res.basins.size() + 1);
  EXPECT_EQ(bas[1][csv_column(bas[0], "attractor")], "1133");
  EXPECT_CLOSE(std::stod(bas[1][csv_column(bas[0], "fraction")]), res.basins[0].fraction,
               bound(5e-7, "the CSV prints 6 decimals"));
  EXPECT_EQ(bas[1][csv_column(bas[0], "exact")], "");
  for (const char* name : {"density", "second", "component", "basin", "basin_probability"}) {
    const core::ArrayView* a = c.find(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->size(), static_cast<std::size_t>(res.part.size())) << name;  // "second" too, when there is none
  }
  EXPECT_EQ(std::get<std::string>(c.attrs.at("boxes")), "16x16");
  EXPECT_EQ(std::get<std::string>(c.attrs.at("cycle")), "1133");
  EXPECT_EQ(std::get<std::string>(c.attrs.at("w1-range")), "-2,2");
  EXPECT_EQ(c.attrs.count("p2_beta"), 0u);  // r = 0.15 < 3 - 2 sqrt 2: no P2 curves, no NaN in the manifest
}

// --eigenvalues 0 (no spectrum): the basins are computed from the matrix alone, so they must be those of a run with
// the spectrum, to the last bit (same matrix, same solves); the outputs that need eigenvectors are left out.
TEST(Transfer, BasinsWithoutTheSpectrumAreThoseWithIt) {
  TransferRequest q;
  q.r = 0.3;  // 132312 and the P2 region
  q.boxes = "32x32";
  q.samples = 16;
  q.eigenvalues = 8;
  q.measure_orbits = 2;
  q.measure_iterations = 200;
  q.tv_bins = 16;
  q.cycles = {"132312"};
  const TransferResult with = run(q);
  q.eigenvalues = 0;
  const TransferResult without = run(q);
  ASSERT_EQ(with.basins.size(), 2u);
  ASSERT_EQ(without.basins.size(), with.basins.size());
  for (std::size_t k = 0; k < with.basins.size(); ++k) {
    EXPECT_EQ(without.basins[k].attractor, with.basins[k].attractor);
    EXPECT_EQ(without.basins[k].target_boxes, with.basins[k].target_boxes);
    EXPECT_EQ(without.basins[k].fraction, with.basins[k].fraction) << with.basins[k].attractor;
  }
  EXPECT_EQ(without.basin_of_box, with.basin_of_box);
  EXPECT_EQ(without.basin_probability, with.basin_probability);
  EXPECT_EQ(without.basin_iterations, with.basin_iterations);
  EXPECT_EQ(without.closed_classes(), with.closed_classes());
  EXPECT_EQ(without.basins_csv(), with.basins_csv());
  // Nothing that needs an eigenvector: no eigenvalue, component, density, TV; the cycle's boxes are there.
  EXPECT_TRUE(without.eig_re.empty());
  EXPECT_TRUE(without.components.empty());
  EXPECT_TRUE(without.density.empty());
  EXPECT_EQ(without.tv_boxes, -1);
  ASSERT_EQ(without.cycles.size(), 1u);
  EXPECT_EQ(without.cycles[0].boxes, with.cycles[0].boxes);
  // The closed class holding the cycle's boxes is the component whose invariant density the spectrum puts on them.
  ASSERT_EQ(without.classes.size(), with.classes.size());
  EXPECT_GE(without.cycles[0].component, 1);
  EXPECT_EQ(without.cycles[0].component, with.cycles[0].component);
  std::vector<std::string> names;
  for (const auto& [name, text] : without.tables()) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"cycles.csv", "basins.csv"}));
  const auto cyc = csv_cells(without.cycles_csv());
  expect_numbers_or_empty(without.cycles_csv(), "cycles.csv");
  ASSERT_EQ(cyc.size(), 2u);
  EXPECT_EQ(cyc[1][csv_column(cyc[0], "boxes_found")], "6");
  EXPECT_EQ(cyc[1][csv_column(cyc[0], "mass_boxes")], "");
  EXPECT_EQ(cyc[1][csv_column(cyc[0], "component")], std::to_string(without.cycles[0].component));
  EXPECT_EQ(cyc[1][csv_column(cyc[0], "radius99")], "");
  core::Contents c;
  without.describe(c);
  for (const char* name : {"density", "second", "component", "eig_re", "lebesgue"})
    EXPECT_EQ(c.find(name), nullptr) << name;
  for (const char* name : {"basin", "basin_probability", "basin_fraction", "cycle_points"})
    EXPECT_NE(c.find(name), nullptr) << name;
  for (const char* name : {"tv_boxes", "near_one_count", "second_value", "cycle_1_mass_boxes"})
    EXPECT_EQ(c.attrs.count(name), 0u) << name;
  EXPECT_EQ(std::get<long>(c.attrs.at("eigenvalues")), 0);
}

TEST(TransferFiles, UndefinedValuesAcrossRAreEmptyCells) {
  TransferRRequest q;
  q.r_min = 0.15;  // below 3 - 2 sqrt 2: no P2 angle
  q.r_max = 0.3;   // above it: beta = acos(-(1 - r)^2 / (4 r))
  q.r_count = 2;
  q.boxes = "8x8";
  q.samples = 4;
  q.eigenvalues = 4;
  const TransferRResult res = run(q);
  expect_numbers_or_empty(res.peripheral_csv(), "peripheral_r.csv");
  expect_numbers_or_empty(res.spectrum_csv(), "spectrum_r.csv");
  expect_numbers_or_empty(res.windows_csv(), "windows.csv");
  const auto per = csv_cells(res.peripheral_csv());
  ASSERT_EQ(per.size(), 3u);
  const std::size_t beta = csv_column(per[0], "p2_beta");
  EXPECT_EQ(per[1][beta], "");
  EXPECT_CLOSE(std::stod(per[2][beta]), std::acos(-(1 - 0.3) * (1 - 0.3) / (4 * 0.3)),
               ulps(4, "the CSV's decimal of the same closed form").of(1));
  for (std::size_t i = 0; i < res.r.size(); ++i) {  // an empty gap exactly where the result has none
    EXPECT_EQ(per[i + 1][csv_column(per[0], "gap")].empty(), !std::isfinite(res.gap[i])) << i;
    EXPECT_EQ(per[i + 1][csv_column(per[0], "rest_modulus")].empty(), !std::isfinite(res.rest_modulus[i])) << i;
  }
  // spectrum_r.csv: every converged eigenvalue, none of the NaN placeholders.
  std::size_t finite = 0;
  for (double x : res.re) finite += std::isfinite(x);
  EXPECT_EQ(csv_cells(res.spectrum_csv()).size(), finite + 1);
  // windows.csv: n = 1 has no upper end; the window of n = 1 starts, and that of n = 2 ends, at 3 - 2 sqrt 2.
  const auto win = csv_cells(res.windows_csv());
  ASSERT_EQ(win.size(), 13u);
  EXPECT_EQ(win[1][2], "");
  EXPECT_CLOSE(std::stod(win[1][1]), 3 - 2 * std::numbers::sqrt2, ulps(4, "the CSV's decimal of the same closed form"));
  EXPECT_CLOSE(std::stod(win[2][2]), 3 - 2 * std::numbers::sqrt2, ulps(4, "the CSV's decimal of the same closed form"));
  for (std::size_t n = 2; n < win.size(); ++n) EXPECT_LT(std::stod(win[n][1]), std::stod(win[n][2])) << n;
  core::Contents c;
  res.describe(c);
  EXPECT_EQ(std::get<long>(c.attrs.at("r-count")), 2);
  EXPECT_EQ(c.find("re")->dims, (std::vector<std::size_t>{2, 4}));
}

TEST(TransferFiles, CycleItemsHoldingCommasGiveSeveralWords) {
  TransferRequest q;  // --cycle 1322,3122 --cycle 132312, as analyses/transfer.sh passes them
  q.cycles = {"1322,3122", "132312", ",1133,"};
  EXPECT_EQ(q.cycle_words(), (std::vector<std::string>{"1322", "3122", "132312", "1133"}));
  q.cycles = {"1322,14"};
  try {
    q.validate();
    ADD_FAILURE() << "14 is not a word";
  } catch (const core::InvalidField& e) {
    EXPECT_EQ(e.field, "cycle");
  }
}
