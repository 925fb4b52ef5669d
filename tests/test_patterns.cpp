// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of btob::patterns: word algebra, Theorems 7.1 and 7.3, windows of Table B.1, Table 6.1, errors.
#include "patterns/atlas.hpp"
#include "patterns/exact.hpp"
#include "patterns/patterns.hpp"

#include "core/map.hpp"
#include "core/scalar.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include "reference_tables.hpp"

#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

using namespace btob::patterns;
using btob::core::float128;
using btob::core::mpfr_float;
using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

Word W(const char* s) { return parse_word(s); }

// Absolute tolerance helper with the reason stated at each call.
void expect_near_mp(const mpfr_float& got, const char* expected, const char* tol, const char* what) {
  EXPECT_LT(abs(got - mpfr_float(expected)), mpfr_float(tol))
      << what << ": got " << got.str(30) << ", expected " << expected;
}

// A polynomial in r from integer coefficients, highest power first, divided by `den`.
RationalPoly poly_hi(std::initializer_list<long> hi_first, long den = 1) {
  RationalPoly p;
  std::vector<long> v(hi_first);
  for (auto it = v.rbegin(); it != v.rend(); ++it) p.c.emplace_back(*it, den);
  p.trim();
  return p;
}

// RAII: MPFR working precision for one test.
struct MpfrDigits {
  unsigned old;
  explicit MpfrDigits(unsigned d) : old(mpfr_float::default_precision()) { mpfr_float::default_precision(d); }
  ~MpfrDigits() { mpfr_float::default_precision(old); }
};

}  // namespace

// ---------------------------------------------------------------- words
TEST(Words, ParsesThePapersNotations) {
  EXPECT_EQ(to_digits(W("132^3312^3")), "1322231222");
  EXPECT_EQ(to_digits(W("132^{3}312^{3}")), "1322231222");
  EXPECT_EQ(to_digits(W("131312^3313132^3")), "1313122231313222");
  EXPECT_EQ(W("132^67312^67").size(), 138u);      // Section 6.2: 138 b-collisions
  EXPECT_EQ(collisions(W("132^67312^67")), 410);  // ... and 410 collisions in total
  EXPECT_EQ(to_digits(W("(ab)(cb)(acb)")), "132");
  EXPECT_EQ(to_digits(W("(ab)(cb)(cab)")), "132");
  EXPECT_EQ(to_digits(W("abcbacbcbabacb")), "132312");  // Section 7.3's spelling of 132312
  EXPECT_EQ(to_digits(W("(ab)^2(cb)^2")), "1133");
  EXPECT_EQ(to_digits(W("(13)^3")), "131313");
  EXPECT_EQ(to_letters(W("132312")), "abcbacbcbabacb");
}

TEST(Words, PaperNotationRoundTrips) {
  std::mt19937 g(7);
  for (int t = 0; t < 2000; ++t) {
    Word w;
    const int n = 1 + static_cast<int>(g() % 40);
    for (int i = 0; i < n; ++i) {
      const std::uint8_t s = static_cast<std::uint8_t>(1 + g() % 3);
      const int run = 1 + static_cast<int>(g() % 12);
      for (int k = 0; k < run; ++k) w.s.push_back(s);
    }
    ASSERT_EQ(parse_word(to_paper(w)), w) << to_paper(w);
  }
  EXPECT_EQ(to_paper(W("1322231222")), "132^3312^3");
  EXPECT_EQ(to_paper(W("12222222222223")), "12^{12}3");
}

TEST(Words, CollisionCountsMatchTable61) {
  // Every pattern of Table 6.1 has the length printed in its last column (a, b, c collisions).
  // Table 6.1: 33 r values; r, percent periodic, patterns (;-separated), their lengths.  Throws if missing/short.
  const auto table = btob::testing::read_reference_table("patterns_paper_table_6_1.csv", 33, 4);
  std::string c;
  int checked = 0;
  for (const auto& col : table.rows) {
    if (col[2].empty()) continue;  // no periodic orbit found at this r
    std::vector<std::string> pats, lens;
    for (std::stringstream p(col[2]); std::getline(p, c, ';');) pats.push_back(c);
    for (std::stringstream p(col[3]); std::getline(p, c, ';');) lens.push_back(c);
    std::set<int> allowed;
    for (auto& l : lens) allowed.insert(std::stoi(l));
    for (auto& p : pats) {
      EXPECT_TRUE(allowed.count(collisions(W(p.c_str())))) << p << " at r = " << col[0];
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
}

TEST(Words, CanonicalFormIsInvariantUnderRotationAndJ) {
  EXPECT_EQ(to_digits(canonical(W("312132"))), "132312");
  EXPECT_EQ(to_digits(canonical(W("3311"))), "1133");
  EXPECT_EQ(to_digits(canonical(W("3122213222"))), "1322231222");
  EXPECT_EQ(to_paper(canonical(W("2^{36}31"))), "132^36");  // 312^36 and 132^36 are one pattern up to J
  std::mt19937 g(3);
  for (int t = 0; t < 500; ++t) {
    Word w;
    for (int i = 0, n = 1 + static_cast<int>(g() % 14); i < n; ++i)
      w.s.push_back(static_cast<std::uint8_t>(1 + g() % 3));
    const Word c = canonical(w);
    EXPECT_EQ(canonical(apply_J(w)), c);
    EXPECT_EQ(canonical(rotate(w, g() % w.size())), c);
    EXPECT_EQ(canonical(c), c);
  }
  EXPECT_EQ(to_digits(primitive_root(W("131313"))), "13");
  EXPECT_TRUE(is_primitive(W("1133")));
  EXPECT_TRUE(is_J_square(W("132312")));
  EXPECT_TRUE(is_J_square(W("13223122")));
  EXPECT_FALSE(is_J_square(W("1322")));
}

// The canonical form against its definition: the smallest of the 2n rotations of w and J(w) in the order 1 < 3 < 2,
// found by listing them all (every word of length <= 8, and powers, whose equal rotations end the linear scan).
TEST(Words, CanonicalFormIsTheSmallestOfAllRotations) {
  const auto key = [](const Word& w) {
    std::string k;
    for (auto c : w.s) k.push_back(c == 1 ? 'a' : (c == 3 ? 'b' : 'c'));
    return k;
  };
  const auto brute = [&](const Word& w) {
    Word best = w;
    for (const Word& v : {w, apply_J(w)})
      for (std::size_t i = 0; i < w.size(); ++i)
        if (key(rotate(v, i)) < key(best)) best = rotate(v, i);
    return best;
  };
  long checked = 0;
  for (int n = 1; n <= 8; ++n) {
    Word w{std::vector<std::uint8_t>(static_cast<std::size_t>(n), 1)};
    for (long code = 0, total = static_cast<long>(std::pow(3, n)); code < total; ++code, ++checked) {
      long c = code;
      for (int i = 0; i < n; ++i, c /= 3) w.s[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(1 + c % 3);
      ASSERT_EQ(canonical(w), brute(w)) << to_digits(w);
    }
  }
  EXPECT_EQ(checked, 9840);  // 3 + 9 + ... + 3^8
  for (const char* p : {"(3122)^7", "(2131)^5", "(132312)^40", "(2)^9", "(31)^6 3"})
    EXPECT_EQ(canonical(W(p)), brute(W(p))) << p;
}

TEST(Words, EnumerationHoldsEachClassOnce) {
  // Brute force over all words of length <= 7: the set of their canonical primitive forms equals the list.
  const auto list = enumerate_canonical(7);
  std::set<Word> want;
  for (int n = 1; n <= 7; ++n) {
    Word w{std::vector<std::uint8_t>(static_cast<std::size_t>(n), 1)};
    for (long code = 0, total = static_cast<long>(std::pow(3, n)); code < total; ++code) {
      long c = code;
      for (int i = 0; i < n; ++i, c /= 3) w.s[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(1 + c % 3);
      if (is_primitive(w)) want.insert(canonical(w));
    }
  }
  EXPECT_EQ(std::set<Word>(list.begin(), list.end()), want);
  EXPECT_EQ(list.size(), want.size());
}

TEST(Words, BadInputNamesTheField) {
  // " " and ". ." parsed to an empty word (found by tests/fuzz/fuzz_words).
  for (const char* bad : {"", "1x3", "(ab", "2^0", "()", "ac", "1^", " ", ". ."}) {
    try {
      parse_word(bad);
      ADD_FAILURE() << "no error for '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("word: got '", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW(analyse<double>(Word{}, 0.3), std::invalid_argument);
  for (double r : {0.0, 1.0, -0.2, 1.5, std::nan("")}) {
    try {
      analyse<double>(W("132312"), r);
      ADD_FAILURE() << "no error for r = " << r;
    } catch (const btob::core::InvalidField& e) {
      EXPECT_EQ(std::string(e.what()).rfind("r: got", 0), 0u) << e.what();
    }
  }
}

// ---------------------------------------------------------------- Theorem 7.1
TEST(Theorem71, CharacteristicPolynomialAndDiscriminantEqualThePapers) {
  const CharPoly chi = characteristic_polynomial(W("132312"));  // of J P2 P3 P1
  EXPECT_EQ(chi.c2, poly_hi({7, -24, -29, 0, 21, -8, 1}, 32));
  EXPECT_EQ(chi.c1, poly_hi({1, -8, 21, 0, -29, -24, 7, 0, 0, 0, 0, 0}, 32));
  EXPECT_EQ(chi.c0, poly_hi({1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  const RationalPoly Q = poly_hi({49, -1150, 11561, -64272, 210772, -445384, 907556, -1807728, 1753646, -3227252,
                                  1753646, -1807728, 907556, -445384, 210772, -64272, 11561, -1150, 49});
  const RationalPoly r10 = pow(RationalPoly{0, 1}, 10);
  const RationalPoly expected =
      rational(-1, 113246208) * r10 * pow(RationalPoly{-1, 1}, 4) * pow(RationalPoly{1, 1}, 2) * Q;
  EXPECT_EQ(discriminant(chi), expected);
}

TEST(Theorem71, CriticalValuesTo20Digits) {
  MpfrDigits d(50);
  const mpfr_float tol("1e-40");  // bisection width, far below the 20 digits compared
  const auto set = stability_set<mpfr_float>(W("132312"), default_grid(), tol);
  ASSERT_EQ(set.size(), 1u);
  // 1e-20: the paper prints 20 digits.
  expect_near_mp(set[0].lo, "0.22006978614631047521", "1e-20", "r_crit,132J");
  EXPECT_EQ(set[0].lo_reason, "feas1");  // alpha y - x = 0 (eq. r_crit,132J,2)
  EXPECT_EQ(set[0].hi, 1);
  const mpfr_float r1 = quantity_root<mpfr_float>(W("132312"), mpfr_float("0.15"), mpfr_float("0.2"),
                                                  Track::dominant_real, Quantity::x_component, tol);
  expect_near_mp(r1, "0.18261545379260806055", "1e-20", "r_crit,132J,1");
  // The same endpoint in double to 1e-14 (the brief's accuracy in double).
  const auto sd = stability_set<double>(W("132312"), default_grid(), 1e-15);
  ASSERT_EQ(sd.size(), 1u);
  EXPECT_CLOSE(sd[0].lo, 0.22006978614631047521, ulps(45, "the brief's accuracy in double (1e-14)"));
}

TEST(Theorem71, StableOrbitMatchesTheIteratedMap) {
  // The periodic point of 132312 at r = 0.3, iterated with core::step, follows the word and returns.
  for (double r : {0.25, 0.3, 0.6, 0.9}) {
    const Verdict<double> v = analyse<double>(W("132312"), r);
    ASSERT_EQ(v.outcome, Outcome::stable) << r;
    EXPECT_TRUE(v.reduced);
    EXPECT_LT(v.spectrum[0].re, 0);  // Section 7.1: feasible reduced eigenvalues are negative
    btob::core::Vec3<double> u = v.orbit[0];
    for (std::size_t k = 0; k < 6; ++k) {
      const auto st = btob::core::step(u, r);
      EXPECT_EQ(st.symbol, int(v.word.s[k]));
      u = st.u / st.u.norm();
    }
    u = btob::core::to_quadrant(u);
    EXPECT_SMALL((u - v.orbit[0]).norm(), ulps(4500, "a few ulps times the conditioning of 6 steps")) << r;
    // Exponents from the cofactor product equal those of the reduced spectrum: M = A^2, p = 6.
    EXPECT_CLOSE(v.lyapunov2, 2 * std::log(v.spectrum[1].modulus / v.spectrum[0].modulus) / 6,
                 ulps(4500, "cofactor product against the reduced spectrum: two routes' roundings, log of a ratio"));
  }
  EXPECT_NE(analyse<double>(W("132312"), 0.2).outcome, Outcome::stable);
}

// ---------------------------------------------------------------- Theorem 7.3
TEST(Theorem73, CharacteristicPolynomialAndDiscriminantEqualThePapers) {
  const CharPoly chi = characteristic_polynomial(W("13223122"));  // of J P2 P2 P3 P1
  EXPECT_EQ(chi.c2, poly_hi({-7, 42, -18, -58, 24, 38, -30, 10, -1}, 64));
  EXPECT_EQ(chi.c1, poly_hi({-1, 10, -30, 38, 24, -58, -18, 42, -7, 0, 0, 0, 0, 0, 0}, 64));
  EXPECT_EQ(chi.c0, pow(RationalPoly{0, 1}, 14));
  const RationalPoly Q =
      poly_hi({49,        -1666,     25057,      -221216,   1281770,    -5145140,  14717738,   -31143328, 54462799,
               -92352670, 144006079, -174418496, 197859020, -246451544, 197859020, -174418496, 144006079, -92352670,
               54462799,  -31143328, 14717738,   -5145140,  1281770,    -221216,   25057,      -1666,     49});
  const RationalPoly expected =
      rational(-1, 1811939328) * pow(RationalPoly{0, 1}, 12) * pow(RationalPoly{1, 1, 1, 1}, 2) * Q;
  EXPECT_EQ(discriminant(chi), expected);
}

TEST(Theorem73, CriticalValuesTo20Digits) {
  MpfrDigits d(50);
  const mpfr_float tol("1e-40");
  const Word w = W("13223122");
  const auto root = [&](const char* lo, const char* hi, Quantity q) {
    return quantity_root<mpfr_float>(w, mpfr_float(lo), mpfr_float(hi), Track::negative_real, q, tol);
  };
  expect_near_mp(root("0.1", "0.17", Quantity::dominance_gap), "0.16028989151805950668", "1e-20", "r_crit,1322J,1");
  expect_near_mp(root("0.18", "0.5", Quantity::dominance_gap), "0.25112749544281462755", "1e-20", "r_crit,1322J,2");
  expect_near_mp(root("0.2", "0.25", Quantity::x_component), "0.23636180678365848104", "1e-20", "r_crit,1322J,3");
  const mpfr_float s = 3 - 2 * sqrt(mpfr_float(2));
  EXPECT_LT(abs(root("0.165", "0.2", Quantity::z_component) - s), mpfr_float("1e-30"))
      << "r_crit,1322J,4 = 3 - 2 sqrt 2";
  EXPECT_LT(abs(root("0.165", "0.2", Quantity::alpha_y_minus_x) - s), mpfr_float("1e-30"))
      << "r_crit,1322J,5 = 3 - 2 sqrt 2";
}

TEST(Theorem73, NeverStableOnAFineGrid) {
  const Word w = W("13223122");
  for (int i = 1; i < 100000; ++i) ASSERT_FALSE(is_stable<double>(w, i / 100000.0)) << "r = " << i / 100000.0;
  EXPECT_TRUE(stability_set<double>(w, default_grid(), 1e-15).empty());
}

// ---------------------------------------------------------------- windows (Table B.1)
TEST(Windows, TableB1ForN2AndN3) {
  // Table B.1 prints 12 decimals: 6e-13 covers its rounding.
  const auto w2 = stability_set<double>(W("1133"), default_grid(), 1e-15);
  ASSERT_EQ(w2.size(), 1u);
  const auto printed = bound(6e-13, "Table B.1 prints 12 decimals");
  const auto closed = ulps(45, "bisection to 1e-15 (4.5 eps) and the closed form's cancellation");
  EXPECT_CLOSE(w2[0].lo, 0.127544097592, printed);
  EXPECT_CLOSE(w2[0].hi, 0.171572875254, printed);
  EXPECT_CLOSE(w2[0].hi, 3 - 2 * std::sqrt(2.0), closed);
  const auto w3 = stability_set<double>(W("111333"), default_grid(), 1e-15);
  ASSERT_EQ(w3.size(), 1u);
  EXPECT_CLOSE(w3[0].lo, 0.094519407247, printed);
  EXPECT_CLOSE(w3[0].hi, 0.101020514434, printed);
  EXPECT_CLOSE(w3[0].hi, 5 - 2 * std::sqrt(6.0), closed);
  EXPECT_TRUE(stability_set<double>(W("abcb"), default_grid(), 1e-15).empty());  // n = 1: never stable
  EXPECT_TRUE(stability_set<double>(W("13"), default_grid(), 1e-15).empty());
}

TEST(Windows, PrecisionsAgree) {
  // long double and float128 agree with double on the verdict and eigenvalues (1e-13: double's error on
  // a product of 6 matrices and a cubic, well above its 1e-16 unit roundoff).
  for (double r : {0.15, 0.25, 0.5}) {
    for (const char* s : {"1133", "132312", "132^2"}) {
      const auto d = analyse<double>(W(s), r);
      const auto l = analyse<long double>(W(s), static_cast<long double>(r));
      const auto q = analyse<float128>(W(s), float128(r));
      EXPECT_EQ(d.outcome, l.outcome);
      EXPECT_EQ(d.outcome, q.outcome);
      const auto in_double = ulps(450, "double's error on a product of 6 matrices and a cubic").of(1);
      EXPECT_CLOSE(d.spectrum[0].re, static_cast<double>(l.spectrum[0].re), in_double);
      EXPECT_CLOSE(d.spectrum[0].re, static_cast<double>(q.spectrum[0].re), in_double);
      // float (every precision of the lab): same verdict away from the window ends; the dominant eigenvalue to
      // 1e-5 relative (float's 6e-8 unit roundoff times the conditioning of 6 products and a cubic).
      const auto f = analyse<float>(W(s), static_cast<float>(r));
      EXPECT_EQ(d.outcome, f.outcome);
      EXPECT_CLOSE(d.spectrum[0].re, static_cast<double>(f.spectrum[0].re),
                   ulps<float>(83, "float's roundoff times the conditioning of 6 products and a cubic")
                       .of(std::fabs(d.spectrum[0].re)));
    }
  }
}

TEST(Spectrum, SmallEigenvaluesKeepTheirRelativeAccuracy) {
  // 13223122 at small r: mu2 ~ 1e-10 mu1 and mu3 ~ 1e-15 mu1.  From the product's entries (det3 and the 2x2 minors)
  // they were noise (mu3 = 2.3e-14 at r = 0.0075 where it is 9.58e-17); from the exact determinant, the product of
  // the factors' cofactors (detail::char_poly) and the quadratic factor with S = (c2 - P) / mu1 (cubic_roots) each
  // keeps its relative accuracy in double: c2's relative error is eps / (4 r) <= 2e-14 here (its factors' one
  // cancellation), plus a few ulps per product (measured: 2e-15 against 50-digit MPFR).
  const btob::core::MpfrDigits digits(50);
  for (double r : {0.003, 0.0075, 0.02, 0.05}) {
    const auto d = analyse<double>(W("13223122"), r);
    const auto m = analyse<mpfr_float>(W("13223122"), mpfr_float(r));
    for (int i = 0; i < 3; ++i) {
      const double want = static_cast<double>(m.spectrum[i].modulus);
      EXPECT_CLOSE(d.spectrum[i].modulus, want,
                   bound(1e-13 * want, "c2's relative error eps / (4 r) <= 2e-14 and a few ulps per product"))
          << "mu" << i + 1 << " at r = " << r;
    }
  }
}

// Double's verdict on every word's orbits against 60-digit MPFR's, saddles included.  A saddle's orbit (the middle
// eigenvalue) used to be its eigenvector carried forward along the word, which multiplies the eigenvector's error by
// up to |mu1 / mu2| per period: at 13223122, r = 0.0075 (ratio 1e20) double found inequality 5 failing and "no
// periodic orbit" where every margin is >= 0.012 and the orbit is unstable.  Each eigenvalue's points now come from
// an iteration stable for it (detail::orbit_points), so double agrees with MPFR at every r of the grid that is not
// within 1e-6 of a change of MPFR's verdict (where rounding may decide either way), and a saddle's points agree to
// 1e-12 (measured 2e-16 at 13223122, r = 0.0075; the plane intersection's conditioning allowed for).
TEST(Spectrum, SaddleOrbitsAgreeWithMpfr) {
  const btob::core::MpfrDigits digits(60);
  std::vector<Word> words = enumerate_canonical(6);
  words.push_back(W("13223122"));
  words.push_back(W("132^3312^3"));
  int compared = 0, saddles = 0;
  for (const Word& w : words)
    for (int k = 0; k < 24; ++k) {
      const double r = 0.0075 * std::pow(80.0, k / 23.0);  // 0.0075 .. 0.6, log-spaced
      const auto m = analyse<mpfr_float>(w, mpfr_float(r));
      if (analyse<mpfr_float>(w, mpfr_float(r * (1 - 1e-6))).outcome != m.outcome ||
          analyse<mpfr_float>(w, mpfr_float(r * (1 + 1e-6))).outcome != m.outcome)
        continue;
      const auto d = analyse<double>(w, r);
      ++compared;
      EXPECT_EQ(outcome_name(d.outcome), std::string(outcome_name(m.outcome))) << to_paper(w) << " at r = " << r;
      // Which eigenvalue is the orbit's: only where its modulus is separated (a neutral orbit's ties with a
      // complex pair, as the single letter 2's three moduli r, may be ordered either way).
      if (m.outcome != Outcome::stable && m.outcome != Outcome::unstable) continue;
      EXPECT_EQ(d.orbit_eigen, m.orbit_eigen) << to_paper(w) << " at r = " << r;
      if (d.orbit_eigen <= 0 || d.orbit_eigen != m.orbit_eigen) continue;
      ++saddles;
      for (std::size_t j = 0; j < d.orbit.size(); ++j)
        for (int c = 0; c < 3; ++c)
          EXPECT_CLOSE(d.orbit[j](c), static_cast<double>(m.orbit[j](c)),
                       bound(1e-12, "a saddle's points: eigenvectors of stable iterations"))
              << to_paper(w) << " at r = " << r << ", point " << j;
    }
  EXPECT_GT(compared, 2000);  // 2496 (word, r) pairs compared, 1484 of them saddles
  EXPECT_GT(saddles, 1000);
}

// The case that showed it, in double against the 60-digit points (cheap: under the sanitizers too).
TEST(Spectrum, SaddleOrbitOf13223122AtSmallR) {
  const btob::core::MpfrDigits digits(60);
  const auto d = analyse<double>(W("13223122"), 0.0075);
  const auto m = analyse<mpfr_float>(W("13223122"), mpfr_float(0.0075));
  ASSERT_EQ(d.outcome, Outcome::unstable);
  ASSERT_EQ(d.orbit_eigen, 1);  // mu2's orbit: a saddle
  ASSERT_EQ(m.orbit_eigen, 1);
  for (std::size_t j = 0; j < d.orbit.size(); ++j)
    for (int c = 0; c < 3; ++c)
      EXPECT_CLOSE(d.orbit[j](c), static_cast<double>(m.orbit[j](c)), ulps<double>(64, "a saddle's points").of(1.0))
          << "point " << j;
}

// ---------------------------------------------------------------- Table 6.1
TEST(Table61, EveryPatternIsStableWhereThePaperSawIt) {
  const std::vector<std::pair<const char*, double>> seen = {{"111333", 0.1},         {"111333", 0.101},
                                                            {"1133", 0.15},          {"1133", 0.16},
                                                            {"1133", 0.17},          {"132^36", 0.172},
                                                            {"312^36", 0.172},       {"132^14", 0.174},
                                                            {"132^10", 0.176},       {"132^8", 0.178},
                                                            {"132^7312^7", 0.18},    {"132^4", 0.19},
                                                            {"132^3312^3", 0.2},     {"132^2", 0.21},
                                                            {"132^3312^3", 0.21},    {"132^2", 0.22},
                                                            {"132^2", 0.23},         {"132^2", 0.24},
                                                            {"132312", 0.24},        {"312^2", 0.25},
                                                            {"132312", 0.25},        {"132312", 0.3},
                                                            {"132312", 0.34},        {"132312", 0.5},
                                                            {"132312", 0.6},         {"131312^3313132^3", 0.58},
                                                            {"132^67312^67", 0.1717}};
  for (const auto& [p, r] : seen) {
    const auto v = analyse<double>(W(p), r);
    EXPECT_EQ(v.outcome, Outcome::stable) << p << " at r = " << r << ": " << v.reason;
  }
  // The row r = 0.18 prints one pattern of length 50: 132^7312^7 (18 symbols, 50 collisions) is stable
  // there, the half 132^7 (25 collisions) is not an orbit at all.
  EXPECT_EQ(collisions(W("132^7312^7")), 50);
  EXPECT_EQ(analyse<double>(W("132^7"), 0.18).outcome, Outcome::none);
}

// ---------------------------------------------------------------- iterator
TEST(Iterator, EventualPeriod) {
  const std::vector<std::uint8_t> a = {2, 3, 1, 1, 3, 3, 1, 1, 3, 3, 1, 1, 3, 3, 1, 1, 3, 3};
  EXPECT_EQ(eventual_period(a.data() + 2, static_cast<long>(a.size()) - 2, 10), 4);
  EXPECT_EQ(eventual_period(a.data(), static_cast<long>(a.size()), 10), 0);  // 2, 3 at the start break it
  const std::vector<std::uint8_t> c(20, 2);
  EXPECT_EQ(eventual_period(c.data(), 20, 10), 1);
}

TEST(Iterator, FindsOnly1133At016) {
  // Table 6.1: 100% of orbits end on 1133 at r = 0.16; every detected pattern must be stable there.
  const DetectionRun d = detect_patterns({0.16}, 40, 3000, 600, 11, 100, 1);
  ASSERT_FALSE(d.found.empty());
  EXPECT_EQ(to_digits(d.found[0].word), "1133");
  EXPECT_GE(d.found[0].count, 30);
  for (const auto& f : d.found) EXPECT_TRUE(is_stable<double>(f.word, f.r)) << to_paper(f.word) << " at " << f.r;
}

TEST(Iterator, SymbolPeriodicButNeutralAt03) {
  // At r = 0.3 some orbits stay in the P2 region for ever (symbol sequence 2 2 2 ...), but P2 has three
  // eigenvalues of modulus r there (det P2 = r^3, complex pair on the same circle): a neutral rotation,
  // not a periodic orbit.  The analysis says so; the detection has to be read with the verdict.
  const auto v = analyse<double>(W("2"), 0.3);
  EXPECT_EQ(v.reason, "complex");
  EXPECT_CLOSE(v.spectrum[0].modulus, 0.3, ulps(45, "a complex pair of modulus r from the eigensolver"));
  EXPECT_CLOSE(v.spectrum[1].modulus, 0.3, ulps(45, "a complex pair of modulus r from the eigensolver"));
}

// ------------------------------------------------------------------------------------------------ requests
#include "core/request.hpp"
#include "patterns/requests.hpp"

namespace {
template <class F> std::string invalid_field(F&& f) {
  try {
    f();
  } catch (const btob::core::InvalidField& e) {
    return e.field;
  }
  return "";
}
}  // namespace

TEST(PatternRequests, ValidationNamesTheField) {
  using btob::patterns::AtlasRequest;
  using btob::patterns::WordRequest;
  EXPECT_EQ(invalid_field([] { WordRequest{"14", "0.3"}.validate(); }), "word");
  EXPECT_EQ(invalid_field([] { WordRequest{"", "0.3"}.validate(); }), "word");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "1.2"}.validate(); }), "r");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "0.2x"}.validate(); }), "r");
  EXPECT_EQ(invalid_field([] { WordRequest{"132"}.validate(); }), "r");  // no mode
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "0.2", "double", false, true}.validate(); }), "charpoly");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "", "float", true}.validate(); }), "precision");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "", "double", true, false, 3}.validate(); }), "digits");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "0.2", "quad"}.validate(); }), "precision");
  EXPECT_EQ(invalid_field([] { WordRequest{"132", "0.2"}.validate(); }), "");
  AtlasRequest a;
  a.max_length = 17;
  EXPECT_EQ(invalid_field([&] { a.validate(); }), "max-length");
  a = AtlasRequest{};
  a.max_period = a.tail;  // a period must fit twice into the tail
  EXPECT_EQ(invalid_field([&] { a.validate(); }), "max-period");
  a = AtlasRequest{};
  a.feasible = a.no_check = true;
  EXPECT_EQ(invalid_field([&] { a.validate(); }), "no-check");
}

TEST(PatternRequests, VerdictIsTheAnalysisInText) {
  // Theorem 7.1: 132312 is stable for r > r_crit,132J = 0.2200697...; the request's numbers are analyse<double>'s.
  btob::patterns::WordRequest req{"132312", "0.3"};
  const auto res = btob::patterns::run(req);
  const auto v = btob::patterns::analyse<double>(btob::patterns::parse_word("132312"), 0.3);
  EXPECT_EQ(res.outcome, "stable orbit");
  ASSERT_EQ(res.eigen_re.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(res.eigen_re[i], v.spectrum[i].re);  // the same route: bitwise
  ASSERT_EQ(res.orbit_xyz.size(), 3 * v.orbit.size());
  EXPECT_EQ(res.orbit_xyz[0], v.orbit[0](0));
  EXPECT_NE(res.text().find("exponents"), std::string::npos);
  // Below the threshold the first feasibility inequality fails: no orbit, no exponents, the reason explained.
  req.r = "0.2";
  const auto no = btob::patterns::run(req);
  EXPECT_EQ(no.reason, "feas1");
  EXPECT_EQ(no.text().find("exponents"), std::string::npos);
  EXPECT_NE(no.text().find("feasibility inequality 1 fails"), std::string::npos);
  // In MPFR with 40 digits r is read from its text (not from a double) and printed with 40 digits.
  req.precision = "mpfr:40";
  req.r = "0.3";
  const auto mp = btob::patterns::run(req);
  EXPECT_EQ(mp.r.substr(0, 3), "0.3");  // read from the text: a double would print 0.29999999999999998889...
  EXPECT_EQ(mp.r.find("0.2999"), std::string::npos);
  EXPECT_EQ(mp.outcome, "stable orbit");
}

TEST(PatternRequests, WindowEndsAtTwoMinusSqrtThree) {
  // The window of 1322 = (ab)(cb)^2 ... ends where its eigenvector leaves the domain, at r = 2 - sqrt(3)
  // (closed form, independent of the bisection); tolerance: the bisection width 1e-15 plus a few ulps.
  btob::patterns::WordRequest req{"1322", "", "double", true};
  const auto res = btob::patterns::run(req);
  ASSERT_EQ(res.r_high.size(), 1u);
  EXPECT_CLOSE(res.r_high[0], 2 - std::sqrt(3.0), ulps(9, "the bisection width 1e-15 (4.5 eps) plus a few ulps"));
  EXPECT_EQ(res.intervals[0][3], "domain");
  req.digits = 30;  // MPFR: the same end to 30 digits
  const auto mp = btob::patterns::run(req);
  EXPECT_EQ(mp.intervals[0][1].substr(0, 30), "0.2679491924311227064725536584");  // 28 digits of 2 - sqrt(3)
}

TEST(PatternRequests, AtlasFilesAndCancellation) {
  btob::patterns::AtlasRequest req;
  req.max_length = 4;
  req.no_check = true;
  const auto res = btob::patterns::run(req);
  ASSERT_EQ(res.csv.size(), 1u);  // no check: the atlas only
  EXPECT_EQ(res.r_low.size(), res.r_high.size());
  std::size_t rows = 0;
  for (const auto& e : res.entries) rows += e.intervals.size();
  EXPECT_EQ(rows, res.r_low.size());
  btob::core::CancelToken token;
  token.cancel();
  btob::core::RunControl control;
  control.cancel = &token;
  EXPECT_THROW(btob::patterns::run(req, control), btob::core::Cancelled);
}
