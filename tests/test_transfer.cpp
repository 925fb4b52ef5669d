// Ulam's transfer operator (src/transfer): the generic construction against maps whose invariant densities are
// known in closed form (logistic map at 4: arcsine; baker map: uniform), the ergodic decomposition against a
// hand-made chain, the block spectrum against Spectra on the whole matrix, the two routes of P^_r against each
// other, thread independence, and the request's errors.
#include "transfer/transfer.hpp"
#include "transfer/transfer_impl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

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
      exact[static_cast<std::size_t>(i)] = 2 / std::numbers::pi *
                                           (std::asin(std::sqrt(double(i + 1) / n)) - std::asin(std::sqrt(double(i) / n)));
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
    EXPECT_NEAR(std::abs(x.value), 1.0, 1e-12);  // dense eigensolver of 3x3 and 1x1 blocks: rounding only
    ones += std::abs(x.value - 1.0) < 1e-12;
    roots += std::abs(std::pow(x.value, 3) - 1.0) < 1e-12;
  }
  EXPECT_EQ(ones, 2);
  EXPECT_EQ(roots, 4);
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
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(std::abs(blocks[k].value), std::abs(whole[k]), 1e-8) << k;
  EXPECT_NEAR(blocks[0].value.real(), 1.0, 1e-10);
}

TEST(Transfer, RoutesAgreeAndThreadsDoNotMatter) {
  const Partition p = domain_partition(Domain::strip, 32, 32);
  core::RunControl one, two;
  one.threads = 1, two.threads = 2;
  for (const char* route : {"direct", "kernel"}) {
    const auto a = ulam_btob(0.2, Domain::strip, p, 16, route, one), b = ulam_btob(0.2, Domain::strip, p, 16, route, two);
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
      EXPECT_NEAR(s, 1.0, 1e-12);  // a row sums k / S for k = 1..S: rounding of at most S additions
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
  EXPECT_EQ(res.closed_classes, 1);
  ASSERT_EQ(res.cycles.size(), 1u);
  EXPECT_EQ(res.cycles[0].outcome, "stable orbit");
  // 99% of the invariant density lies within a few boxes of the cycle's four boxes (Ulam's smearing of a sink
  // spans a number of boxes independent of h: 4 to 6 at 128^2 to 512^2, see the README).
  EXPECT_LE(res.cycles[0].radius99, 8);
  EXPECT_GE(res.cycles[0].radius99, 0);
  double total = 0;
  for (const auto& c : res.components) total += c.lebesgue;
  EXPECT_NEAR(total + res.unabsorbed, 1.0, 1e-9);  // mass conservation of the projection, rounding of 16384 sums
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
  TransferRRequest rr;
  rr.r_max = 0.05;
  EXPECT_EQ(field(rr), "r-max");
}
