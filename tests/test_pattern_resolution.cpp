// SPDX-License-Identifier: GPL-3.0-or-later
// Scans and fixed-size routes at the edge of their resolution and range: the stability set of 1^n 3^n against the
// windows module (Table B.1), every stable sample of random words inside the stability set, long words in every
// fixed precision against MPFR, and the digits printed for an eigenvalue against 60-digit MPFR.
#include "patterns/patterns.hpp"
#include "patterns/requests.hpp"
#include "windows/direct.hpp"
#include "windows/windows.hpp"

#include "core/scalar.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cctype>
#include <cmath>
#include <random>
#include <string>

using namespace btob::patterns;
using btob::core::mpfr_float;
using btob::test::bound;

namespace {

Word power_word(int n) { return parse_word(fmt::format("1^{} 3^{}", n, n)); }

// Table B.1's window of 1^n 3^n from the windows module: its lower bound (the matrix route in long double, correct
// to ~20 decimals for n <= 150 by results/windows/precision.csv, and to the bisection width beyond) and r_crit,2(n).
std::pair<double, double> table_b1(int n) {
  return {static_cast<double>(btob::windows::window_lower_bound_in<long double>(n, btob::windows::Route::matrix)),
          static_cast<double>(btob::windows::r_crit2(n, 30))};
}

// The stability set of 1^n 3^n is exactly one interval, Table B.1's.  Tolerance: the bisection width 1e-15 and,
// at the lower end, the tie zone of the dominance test: there |mu1| and |mu2| cross, and double calls them tied
// (not stable) while they differ by less than 64 eps relative; measured (n = 2..200), the stable side begins within
// 2e-14 of the crossing.
void expect_table_b1(int n) {
  const auto set = stability_set<double>(power_word(n), default_grid(), 1e-15);
  ASSERT_EQ(set.size(), 1u) << "n = " << n;
  const auto [lo, hi] = table_b1(n);
  EXPECT_CLOSE(set[0].lo, lo, bound(5e-14, "bisection width 1e-15 and the tie zone of |mu1| = |mu2| at the crossing"))
      << "n = " << n;
  EXPECT_CLOSE(set[0].hi, hi, bound(5e-14, "bisection width 1e-15 and double's error on the eigenvector's sign"))
      << "n = " << n;
}

}  // namespace

TEST(ScanResolution, WindowOfOneNThreeNIsTableB1) {
  // Before the scan followed spectral events, n >= 22 gave an empty set (the window, 1.1e-5 wide at n = 22, fits
  // inside one step of the grid).
  for (int n = 2; n <= 30; ++n) expect_table_b1(n);
  for (int n : {50, 99, 150, 200}) expect_table_b1(n);
}

TEST(ScanResolution, StabilitySetContainsEveryStableSample) {
  // Random words (lengths 2..12) and random 1^k 3^k (k = 10..60), each sampled at random r, densely where the thin
  // windows are; every r where analyse says stable must lie in the stability set (up to its bisection width).
  std::mt19937_64 rng(20260);
  std::uniform_int_distribution<int> len(2, 12), sym(1, 3), k(10, 60);
  std::uniform_real_distribution<double> any(0.001, 0.999), thin(0.0718, 0.0735);
  long stable_samples = 0;
  for (int t = 0; t < 40; ++t) {
    Word w;
    if (t % 2 == 0) {
      w = power_word(k(rng));
    } else {
      const int p = len(rng);
      for (int i = 0; i < p; ++i) w.s.push_back(static_cast<std::uint8_t>(sym(rng)));
    }
    const auto set = stability_set<double>(w, default_grid(), 1e-15);
    for (int i = 0; i < 600; ++i) {
      const double r = i % 2 == 0 ? any(rng) : thin(rng);
      if (analyse<double>(w, r).outcome != Outcome::stable) continue;
      ++stable_samples;
      bool inside = false;
      for (const auto& iv : set) inside = inside || (iv.lo - 1e-15 <= r && r <= iv.hi + 1e-15);
      EXPECT_TRUE(inside) << to_paper(w) << " stable at r = " << r << " outside its stability set";
    }
  }
  EXPECT_GT(stable_samples, 40);  // the property was exercised (50 with this seed)
}

namespace {

WordResult verdict(const std::string& word, const std::string& r, const std::string& precision) {
  WordRequest req;
  req.word = word;
  req.r = r;
  req.precision = precision;
  return run(req);
}

// No text of the verdict is nan, inf or a bare zero eigenvalue.
void expect_no_lost_numbers(const WordResult& res, const std::string& what) {
  const std::string text = res.text();
  const auto context = [&](std::size_t at) { return text.substr(at < 80 ? 0 : at - 80, 160); };
  // As a word of its own ("dominant" holds "nan", "infeasible" "inf").
  const auto token = [&](const std::string& t) {
    for (std::size_t p = text.find(t); p != std::string::npos; p = text.find(t, p + 1)) {
      const bool before = p > 0 && std::isalpha(static_cast<unsigned char>(text[p - 1]));
      const bool after = p + t.size() < text.size() && std::isalpha(static_cast<unsigned char>(text[p + t.size()]));
      if (!before && !after) return p;
    }
    return std::string::npos;
  };
  const std::size_t nan = token("nan"), inf = token("inf");
  EXPECT_EQ(nan, std::string::npos) << what << ": ..." << (nan == std::string::npos ? "" : context(nan));
  EXPECT_EQ(inf, std::string::npos) << what << ": ..." << (inf == std::string::npos ? "" : context(inf));
  for (const auto& e : res.spectrum) {
    EXPECT_NE(e.re, "0") << what;
    EXPECT_NE(e.re, "-0") << what;
  }
}

}  // namespace

TEST(FixedPrecision, LongWordsAgreeWithMpfrOrSayUndecided) {
  // Words of 10^4 symbols: |mu1| ~ 1e-2300 (1^5000 3^5000 at r = 0.0718) or 1e-3000 (random letters at r = 0.5),
  // below every fixed type's range.  Each fixed precision gives MPFR's verdict or undecided with a reason; no number
  // printed is nan or a lost zero.  Before: mu1 0, |mu|/|mu1| = -nan.
  std::mt19937_64 rng(45);
  std::uniform_int_distribution<int> sym(1, 3);
  std::string random_word;
  for (int i = 0; i < 10000; ++i) random_word += static_cast<char>('0' + sym(rng));
  const btob::core::MpfrDigits mp(40);  // the windows module's matrix route in MPFR (long double has no bracket here)
  const double lo =
      static_cast<double>(btob::windows::window_lower_bound_in<mpfr_float>(5000, btob::windows::Route::matrix));
  const double hi = static_cast<double>(btob::windows::r_crit2(5000, 30));
  const std::string inside = fmt::format("{:.17g}", (lo + hi) / 2);  // in the window of 1^5000 3^5000: stable
  const std::vector<std::pair<std::string, std::string>> cases = {
      {random_word, "0.5"}, {"1^5000 3^5000", "0.0718"}, {"1^5000 3^5000", inside}};
  for (const auto& [word, r] : cases) {
    const WordResult ref = verdict(word, r, "mpfr:40");
    for (const char* p : {"float", "double", "long-double", "float128"}) {
      const WordResult got = verdict(word, r, p);
      const std::string what = fmt::format("{} symbols at r = {} in {}", word.size() > 20 ? "random 10^4" : word, r, p);
      expect_no_lost_numbers(got, what);
      if (got.outcome != outcome_name(Outcome::undecided)) EXPECT_EQ(got.outcome, ref.outcome) << what;
      else EXPECT_FALSE(got.reason.empty()) << what;
    }
  }
}

namespace {
// The number of significant digits of a decimal text (mantissa digits without leading zeros).
int significant_digits(const std::string& s) {
  int n = 0;
  bool started = false;
  for (char c : s) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;
    started = started || c != '0';
    n += started;
  }
  return n;
}
}  // namespace

TEST(FixedPrecision, PrintsOnlyTheDigitsItVouchesFor) {
  // 1^200 3^200 just below r_crit,2 (two roots about to merge): double's mu1 was printed to 17 digits,
  // -1.0061711415606279e-229, against -1.006171141768647887e-229 from 60-digit MPFR: wrong from the 10th digit.
  // Now every printed eigenvalue lies within one unit of its last printed digit of MPFR's value.
  const btob::core::MpfrDigits digits(60);
  const Verdict<mpfr_float> m = analyse<mpfr_float>(power_word(200), mpfr_float("0.07180187"));
  for (const char* p : {"float", "double", "long-double", "float128"}) {
    const WordResult got = verdict("1^200 3^200", "0.07180187", p);
    ASSERT_EQ(got.spectrum.size(), 3u) << p;
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string& text = got.spectrum[i].re;
      if (text.rfind("~", 0) == 0) continue;  // no digit vouched: the order of magnitude only
      const mpfr_float printed(text);
      // The nearest of MPFR's eigenvalues: near the crossing a route may order two moduli differently.
      mpfr_float want = m.spectrum[0].re;
      for (const auto& e : m.spectrum)
        if (abs(e.re - printed) < abs(want - printed)) want = e.re;
      const int d = significant_digits(text);
      ASSERT_GT(d, 0) << text;
      const mpfr_float unit = pow(mpfr_float(10), floor(log10(abs(printed))) - (d - 1));
      EXPECT_LE(abs(printed - want), unit)
          << p << " mu" << i + 1 << " printed " << text << " (" << d << " digits), MPFR " << want.str(20);
    }
  }
}
