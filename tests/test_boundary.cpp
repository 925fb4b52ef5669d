// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/attractors/boundary: basin entropy, boundary basin entropy, the uncertainty exponent and the Wada
// merging test on synthetic label images whose values are known in closed form or counted here by a second route.
#include "attractors/boundary.hpp"
#include "attractors/requests.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace btob::attractors {
namespace {

using Labels = std::vector<std::uint32_t>;

template <class F> Labels image(std::size_t n1, std::size_t n2, F label) {
  Labels l(n1 * n2);
  for (std::size_t j = 0; j < n2; ++j)
    for (std::size_t i = 0; i < n1; ++i) l[j * n1 + i] = label(i, j);
  return l;
}

// Shannon entropy of a two-colour split k : (n - k) (natural log), written out.
double h2(double k, double n) {
  const double p = k / n, q = 1 - p;
  return -(p * std::log(p) + q * std::log(q));
}

TEST(BasinEntropy, CheckerboardEveryBoxIsABoundaryBox) {
  const Labels l = image(50, 40, [](auto i, auto j) { return 1 + static_cast<std::uint32_t>((i + j) % 2); });
  // Boxes of 5 x 5 cells from a corner: 13 of one colour and 12 of the other in every box.
  const BoxEntropy e = box_entropy({&l, 50, 40}, 5);
  EXPECT_EQ(e.boxes, 10u * 8u);
  EXPECT_EQ(e.boundary_boxes, e.boxes);
  EXPECT_CLOSE(e.sb, h2(13, 25), ulps(16, "80 box entropies summed and divided, each a few roundings"));
  EXPECT_CLOSE(e.sbb, e.sb, ulps(4, "the same sum divided by the same count"));
  // Even boxes split 1/2 : 1/2: log 2 exactly in every box.
  const BoxEntropy e4 = box_entropy({&l, 50, 40}, 4);
  EXPECT_EQ(e4.boxes, 12u * 10u);  // 50 / 4 = 12 whole boxes a row (2 columns left out)
  EXPECT_CLOSE(e4.sb, std::log(2.0), ulps(16, "120 equal terms summed"));
}

TEST(BasinEntropy, StraightBoundaryKnownExactly) {
  // A vertical boundary at column 23: boxes of 5 columns [20, 25) hold 3 columns of one colour, 2 of the other.
  const std::size_t n1 = 60, n2 = 45;
  const Labels l = image(n1, n2, [](auto i, auto) { return i < 23 ? 1u : 2u; });
  const BoxEntropy e = box_entropy({&l, n1, n2}, 5);
  EXPECT_EQ(e.boxes, 12u * 9u);
  EXPECT_EQ(e.boundary_boxes, 9u);  // one column of boxes
  EXPECT_CLOSE(e.sbb, h2(3, 5), ulps(16, "9 equal terms summed and divided"));
  EXPECT_CLOSE(e.sb, h2(3, 5) / 12, ulps(16, "9 equal terms over 108 boxes"));
  EXPECT_NEAR(e.boundary_share(), 1.0 / 12, 1e-15);
  // No boundary: every entropy 0 exactly.
  const Labels one(n1 * n2, 3);
  const BoxEntropy z = box_entropy({&one, n1, n2}, 5);
  EXPECT_EQ(z.sb, 0.0);
  EXPECT_EQ(z.sbb, 0.0);
  EXPECT_EQ(z.boundary_boxes, 0u);
}

TEST(BasinEntropy, RandomLabelsApproachLogK) {
  // k colours drawn uniformly: a box of n cells has expected plug-in entropy log k - (k - 1) / (2 n) + O(1/n^2)
  // (Miller-Madow bias).  Over B boxes the mean's sd is sqrt(var / B), var ~ (k - 1) / (2 n^2) per box.
  std::mt19937_64 rng(7);
  for (std::uint32_t k : {2u, 3u, 5u}) {
    std::uniform_int_distribution<std::uint32_t> pick(1, k);
    const std::size_t n1 = 400, n2 = 400;
    const Labels l = image(n1, n2, [&](auto, auto) { return pick(rng); });
    const int box = 20;
    const BoxEntropy e = box_entropy({&l, n1, n2}, box);
    const double n = box * box, expected = std::log(k) - (k - 1) / (2 * n);
    const double sd = std::sqrt((k - 1) / (2 * n * n) / static_cast<double>(e.boxes));
    EXPECT_EQ(e.boundary_boxes, e.boxes);
    EXPECT_CLOSE(e.sb, expected, statistical(5 * sd + 1 / (n * n), "5 sd of the mean, plus the O(1/n^2) bias"));
  }
}

TEST(BasinEntropy, AgainstADirectCountOnARandomBlockImage) {
  // Blocks of random colours, 3 x 3 cells, sampled on boxes of 5 cells: the entropy counted here from scratch.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::uint32_t> pick(0, 3);
  Labels blocks(20 * 20);
  for (auto& b : blocks) b = pick(rng);
  const std::size_t n1 = 57, n2 = 52;
  const Labels l = image(n1, n2, [&](auto i, auto j) { return blocks[(j / 3) * 20 + i / 3]; });
  double sum = 0;
  std::size_t boundary = 0;
  for (std::size_t bj = 0; bj + 5 <= n2; bj += 5)
    for (std::size_t bi = 0; bi + 5 <= n1; bi += 5) {
      double count[4] = {0, 0, 0, 0};
      for (std::size_t j = bj; j < bj + 5; ++j)
        for (std::size_t i = bi; i < bi + 5; ++i) count[l[j * n1 + i]] += 1;
      double s = 0;
      for (double c : count)
        if (c > 0 && c < 25) s -= c / 25 * std::log(c / 25);
      sum += s;
      boundary += s > 0;
    }
  const BoxEntropy e = box_entropy({&l, n1, n2}, 5);
  EXPECT_EQ(e.boxes, 11u * 10u);
  EXPECT_EQ(e.boundary_boxes, boundary);
  EXPECT_CLOSE(e.sb, sum / 110, ulps(64, "110 sums of <= 4 terms in another order"));
  EXPECT_CLOSE(e.sbb, sum / static_cast<double>(boundary), ulps(64, "the same sums"));
}

TEST(BasinEntropy, BoxLargerThanTheImageHasNoBoxes) {
  const Labels l(10 * 8, 1);
  EXPECT_EQ(box_entropy({&l, 10, 8}, 9).boxes, 0u);  // no whole box: no boxes, entropies 0
  EXPECT_THROW(box_entropy({&l, 10, 8}, 0), std::invalid_argument);
}

TEST(UncertaintyExponent, StraightBoundaryIsExactlyLinear) {
  // A vertical line: the uncertain cells are the 2 e columns next to it, among the same interior cells for every
  // e: f = 2 e / (n1 - 2 margin) exactly, alpha = 1 with a zero residual.
  const std::size_t n1 = 256, n2 = 200;
  const Labels l = image(n1, n2, [](auto i, auto) { return i < 128 ? 1u : 2u; });
  const UncertaintyFit fit = uncertainty_exponent({&l, n1, n2});
  ASSERT_TRUE(fit.fitted) << fit.why;
  EXPECT_EQ(fit.eps_min, 1);
  EXPECT_EQ(fit.eps_max, 25);  // 200 / 8
  for (const auto& p : fit.points) EXPECT_EQ(p.uncertain, 2u * static_cast<std::size_t>(p.eps) * (n2 - 50)) << p.eps;
  EXPECT_CLOSE(fit.alpha, 1.0, ulps(64, "a least-squares slope through exact points, 8 logs"));
  EXPECT_CLOSE(fit.dimension(), 1.0, ulps(64, "2 - alpha"));
}

TEST(UncertaintyExponent, SmoothCurvedBoundaryHasAlphaOne) {
  // A disc: a smooth boundary, D = 1, alpha = 1 (the fit's interval contains it and is narrow).
  const std::size_t n = 400;
  const Labels l = image(n, n, [](auto i, auto j) {
    const double x = (i + 0.5) / 400 - 0.5, y = (j + 0.5) / 400 - 0.5;
    return x * x + y * y < 0.3 * 0.3 ? 1u : 2u;
  });
  const UncertaintyFit fit = uncertainty_exponent({&l, n, n});
  ASSERT_TRUE(fit.fitted) << fit.why;
  EXPECT_LE(fit.low, 1.0);
  EXPECT_GE(fit.high, 1.0);
  EXPECT_CLOSE(fit.alpha, 1.0, bound(0.03, "pixelation of the circle at eps of one cell"));
}

TEST(UncertaintyExponent, WeierstrassGraphHasAlphaH) {
  // Below the graph of W(x) = sum_k 2^(-k H) cos(2^k 2 pi x) (box dimension 2 - H, Kaplan-Mallet-Paret-Yorke): a
  // cell is eps-uncertain when W crosses its height within eps along x, which happens on a set of measure
  // ~ eps^H (the oscillation of W over an interval eps), so alpha = H.
  const double H = 0.5;
  const std::size_t n = 1024;
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n;
    for (int k = 0; k < 30; ++k) w[i] += std::pow(2.0, -k * H) * std::cos(std::ldexp(2 * std::numbers::pi * x, k));
  }
  const double lo = *std::min_element(w.begin(), w.end()), hi = *std::max_element(w.begin(), w.end());
  const Labels l = image(n, n, [&](auto i, auto j) { return lo + (hi - lo) * (j + 0.5) / n < w[i] ? 1u : 2u; });
  const UncertaintyFit fit = uncertainty_exponent({&l, n, n});
  ASSERT_TRUE(fit.fitted) << fit.why;
  EXPECT_CLOSE(fit.alpha, H, bound(0.1, "finite range of eps (1..128 cells) on a graph sampled at 1024 points"));
  // The smooth graph (k = 0 only) at the same resolution gives 1: the test tells the two apart.
  const Labels s = image(n, n, [&](auto i, auto j) {
    return (j + 0.5) / n < 0.5 + 0.3 * std::cos(2 * std::numbers::pi * (i + 0.5) / n) ? 1u : 2u;
  });
  EXPECT_CLOSE(uncertainty_exponent({&s, n, n}).alpha, 1.0, bound(0.05, "pixelation at one cell"));
}

TEST(UncertaintyExponent, NotFittedWithoutABoundaryOrADecade) {
  const Labels one(200 * 200, 1);
  const UncertaintyFit none = uncertainty_exponent({&one, 200, 200});
  EXPECT_FALSE(none.fitted);
  EXPECT_FALSE(none.why.empty());
  const Labels small = image(40, 40, [](auto i, auto) { return i < 20 ? 1u : 2u; });  // eps up to 5 cells only
  EXPECT_FALSE(uncertainty_exponent({&small, 40, 40}).fitted);
}

// The Wada test by brute force: for every pair of basins, the largest chessboard distance of a cell of B_j to B_i.
int hausdorff_brute(const Labels& l, std::size_t n1, std::size_t n2, std::uint32_t basins) {
  const auto on = [&](std::size_t i, std::size_t j, std::uint32_t b) {
    const bool in = l[j * n1 + i] == b;
    const auto differs = [&](long a, long c) {
      return a >= 0 && c >= 0 && a < long(n1) && c < long(n2) && (l[std::size_t(c) * n1 + std::size_t(a)] == b) != in;
    };
    return differs(long(i) - 1, long(j)) || differs(long(i) + 1, long(j)) || differs(long(i), long(j) - 1) ||
           differs(long(i), long(j) + 1);
  };
  int worst = 0;
  for (std::uint32_t a = 1; a <= basins; ++a)
    for (std::uint32_t b = 1; b <= basins; ++b) {
      if (a == b) continue;
      for (std::size_t j = 0; j < n2; ++j)
        for (std::size_t i = 0; i < n1; ++i) {
          if (!on(i, j, b)) continue;
          int best = 1 << 30;
          for (std::size_t q = 0; q < n2; ++q)
            for (std::size_t p = 0; p < n1; ++p)
              if (on(p, q, a))
                best = std::min<int>(best, static_cast<int>(std::max(p > i ? p - i : i - p, q > j ? q - j : j - q)));
          worst = std::max(worst, best);
        }
    }
  return worst;
}

TEST(Wada, MergingAgreesWithBruteForceOnRandomBlocks) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::uint32_t> pick(1, 3);
  for (int trial = 0; trial < 3; ++trial) {
    Labels blocks(6 * 6);
    for (auto& b : blocks) b = pick(rng);
    const std::size_t n = 30;
    const Labels l = image(n, n, [&](auto i, auto j) { return blocks[(j / 5) * 6 + i / 5]; });
    const WadaTest w = wada_merging({&l, n, n}, 2);
    ASSERT_TRUE(w.applies);
    EXPECT_EQ(w.hausdorff, hausdorff_brute(l, n, n, 3)) << trial;
  }
}

TEST(Wada, ThreeBandsAreNotWada) {
  // Bands 1 | 2 | 3 of 40 columns: B_1 is the 1|2 interface, B_3 the 2|3 interface, 40 cells apart (the cells of
  // B_2 next to the 2|3 interface are 39 or 40 cells from B_1).
  const Labels l = image(120, 60, [](auto i, auto) { return 1 + static_cast<std::uint32_t>(i / 40); });
  const WadaTest w = wada_merging({&l, 120, 60});
  EXPECT_TRUE(w.applies);
  EXPECT_FALSE(w.wada);
  EXPECT_EQ(w.hausdorff, 40);
  EXPECT_EQ(w.all_basins_share, 0.0);
  // Two basins: the property does not apply.
  const Labels two = image(120, 60, [](auto i, auto) { return i < 60 ? 1u : 2u; });
  EXPECT_FALSE(wada_merging({&two, 120, 60}).applies);
}

TEST(Wada, NewtonBasinsOfZCubedMinusOneAreWada) {
  // Newton's method for z^3 = 1: three basins whose common boundary is the Julia set (a classic Wada system).
  const std::size_t n = 300;
  const Labels l = image(n, n, [](auto i, auto j) {
    std::complex<double> z(-1.5 + 3.0 * (i + 0.5) / 300, -1.5 + 3.0 * (j + 0.5) / 300);
    for (int k = 0; k < 100 && std::abs(z) > 1e-12; ++k) z -= (z * z * z - 1.0) / (3.0 * z * z);
    const double a = std::arg(z);
    return a > 1.0 ? 2u : a < -1.0 ? 3u : 1u;
  });
  const WadaTest w = wada_merging({&l, n, n});
  EXPECT_EQ(w.basins, 3);
  EXPECT_TRUE(w.wada) << w.verdict();
  EXPECT_LE(w.hausdorff, 4);  // measured: 4 cells at 300 x 300, within max(3, 300 / 50) = 6
  // Every boundary cell sees the three basins within 6 cells (the grid method's first level: 1.0 measured).
  EXPECT_GT(w.all_basins_share, 0.99);
}

TEST(Spread, TIntervalOfTheMean) {
  const Spread s = spread({1.0, 2.0, 3.0});
  EXPECT_EQ(s.value, 1.0);
  EXPECT_CLOSE(s.mean, 2.0, ulps(4, "three sums"));
  EXPECT_CLOSE(s.sd, 1.0, ulps(8, "a square root of a sum of squares"));
  // Student's t with 2 degrees of freedom in closed form: t_p = (2p - 1) sqrt(2 / (4 p (1 - p))); half width
  // t_0.975 / sqrt(3).
  const double t = 0.95 * std::sqrt(2 / (4 * 0.975 * 0.025));
  EXPECT_CLOSE(s.high - s.mean, t / std::sqrt(3.0), ulps(64, "boost's t quantile against the closed form"));
  const Spread one = spread({0.5});
  EXPECT_EQ(one.low, 0.5);
  EXPECT_EQ(one.high, 0.5);
}

}  // namespace
}  // namespace btob::attractors
