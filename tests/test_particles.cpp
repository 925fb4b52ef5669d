// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of btob::particles: the event-driven simulator on cases with known answers (two particles, the
// three-particle collapse threshold 7 - 4 sqrt(3), the energy loss of eq. 2.1), and four particles realising
// periodic patterns against the map and the period matrix.
#include "particles/particles.hpp"

#include "core/coords.hpp"
#include "core/map.hpp"
#include "core/request.hpp"
#include "core/scalar.hpp"
#include "patterns/analysis_impl.hpp"
#include "patterns/atlas.hpp"
#include "patterns/exact.hpp"
#include "patterns/patterns.hpp"
#include "reference/reference.hpp"

#include "csv_cells.hpp"
#include <boost/multiprecision/eigen.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using namespace btob::particles;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

ParticlesResult run_word(const char* word, double r, long periods, const char* precision = "double",
                         const char* start = "self-similar") {
  ParticlesRequest q;
  q.word = word;
  q.r = r;
  q.periods = periods;
  q.precision = precision;
  q.start = start;
  return run(q);
}

std::string rotations_contain(const std::string& s, const std::string& t) {
  return s.size() == t.size() && (s + s).find(t) != std::string::npos ? "yes" : "no";
}

}  // namespace

TEST(ParticlesTwo, OneCollisionThenSeparation) {
  // Two particles at gap 1 approaching at relative speed 2: they meet at t = 1/2, leave at relative speed 2r;
  // the centre-of-mass energy drops from 1 to r^2.  r = 0.5 and these values are exact in binary: tolerance 0.
  const double r = 0.5;
  Gaps<double, 1> s{Vec<double, 1>(1.0), Vec<double, 1>(-2.0)};
  EXPECT_EQ((kinetic_energy<double, 1>(s.q)), 1.0);
  double t = 0;
  ASSERT_EQ((next_collision<double, 1>(s, t)), 0);
  EXPECT_EQ(t, 0.5);
  advance<double, 1>(s, t, 0, r);
  EXPECT_EQ(s.p(0), 0.0);
  EXPECT_EQ(s.q(0), 1.0);  // -r * (-2)
  EXPECT_EQ((kinetic_energy<double, 1>(s.q)), r * r);
  EXPECT_EQ((next_collision<double, 1>(s, t)), -1);  // separating for ever
}

TEST(ParticlesEnergy, LossPerCollisionIsTheRestitutionLaw) {
  // Eq. (2.1) with unit masses: a collision of pair j removes (1 - r^2) q_j^2 / 4 of the centre-of-mass kinetic
  // energy.  Tolerance 16 eps of the energy: E is a sum of four squares of sums of three terms (a few roundings).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.05 + 0.9 * (U(rng) + 1) / 2;
    Vec<double, 3> q(U(rng), U(rng), U(rng));
    const int j = trial % 3;
    if (q(j) > 0) q(j) = -q(j);
    const double e0 = kinetic_energy<double, 3>(q), w = q(j);
    collide<double, 3>(q, j, r);
    const double e1 = kinetic_energy<double, 3>(q);
    EXPECT_CLOSE(e0 - e1, (1 - r * r) * w * w / 4,
                 ulps(16, "a difference of two energies, each a few roundings").of(e0))
        << "trial " << trial;
    // Momentum: the centre-of-mass velocities still sum to zero (absolute() builds them so; the gaps' map is
    // the relative form of eq. 2.1) and the relative velocity of the pair is -r times its old value, exactly.
    EXPECT_EQ(q(j), -r * w);
  }
}

namespace {
// Three particles after a b-collision (p = (1, 0)) with velocities q; the number of collisions before they
// separate for ever (at most `limit`), checking that the letters alternate a, b.
long three_particle_collisions(const Vec<double, 2>& q0, double r, long limit, double* time_ratio = nullptr) {
  Gaps<double, 2> s{Vec<double, 2>(1.0, 0.0), q0};
  long n = 0, d = 0;            // d: binary exponent of the time unit (physical time = 2^d x scaled time)
  double period = 0, prev = 0;  // scaled duration of the current and of the previous "ab" period
  long prev_d = 0;
  for (; n < limit; ++n) {
    double t = 0;
    const int j = next_collision<double, 2>(s, t);
    if (j < 0) break;
    EXPECT_EQ(j, n % 2 == 0 ? 0 : 1) << "collision " << n;
    advance<double, 2>(s, t, j, r);
    period += t;
    if (j == 1) {  // a period ab ends: its duration against the previous one, then rescale by powers of two
      if (prev > 0 && time_ratio) *time_ratio = std::ldexp(period / prev, static_cast<int>(d - prev_d));
      prev = period;
      prev_d = d;
      period = 0;
      int ep = 0, eq = 0;
      std::frexp(std::max(s.p(0), s.p(1)), &ep);
      std::frexp(std::max(std::abs(s.q(0)), std::abs(s.q(1))), &eq);
      s.p = s.p * std::ldexp(1.0, -ep);  // exact
      s.q = s.q * std::ldexp(1.0, -eq);
      d += ep - eq;
    }
  }
  return n;
}
}  // namespace

TEST(ParticlesThree, CollapseOnlyBelowSevenMinusFourSqrtThree) {
  // Three particles collapse (ab repeated for ever) iff the product BA of the 2x2 collision matrices has real
  // eigenvalues: (alpha^2 - 2r)^2 >= 4 r^2, i.e. r <= 7 - 4 sqrt(3) ~ 0.0718.  Below: from the self-similar
  // velocity (eigenvector of BA for its larger eigenvalue) 10^5 collisions alternate ab and the period's time
  // ratio is mu2 / mu1; above: every start separates after a few collisions.
  const double rc = 7 - 4 * std::sqrt(3.0);
  for (double r : {0.02, 0.05, 0.07}) {
    ASSERT_LT(r, rc);
    const double a = (1 + r) / 2;
    const double tr = a * a - 2 * r, det = r * r, disc = std::sqrt(tr * tr / 4 - det);
    const double mu1 = tr / 2 + disc, mu2 = tr / 2 - disc;
    // BA = [[a^2 - r, a], [-r a, -r]]: eigenvector (a, mu1 - a^2 + r), sign so that q2 > 0.
    Vec<double, 2> q(a, mu1 - a * a + r);
    if (q(1) < 0) q = -q;
    double ratio = 0;
    EXPECT_EQ(three_particle_collisions(q, r, 100000, &ratio), 100000) << "r = " << r;
    // Time ratio of one ab period = mu2/mu1; tolerance 1e3 eps: the ratio of two flight times each computed
    // from gaps carrying O(10) roundings, divided by mu1 - mu2 which is small near the threshold (r = 0.07).
    EXPECT_CLOSE(ratio, mu2 / mu1, ulps(1e3 / (1 - mu2 / mu1), "two flight times of O(10) roundings, over mu1 - mu2"))
        << "r = " << r;
  }
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  for (double r : {0.075, 0.1, 0.3}) {
    for (int k = 0; k < 50; ++k) {
      const Vec<double, 2> q(-U(rng), U(rng) + 1e-3);  // a approaching, b separating
      EXPECT_LT(three_particle_collisions(q, r, 10000), 10000) << "r = " << r;
    }
  }
}

TEST(ParticlesPatterns, IndependentRoutesAgree) {
  // 1133 at r = 0.15, 111333 at r = 0.1, 132312 at r = 0.5: 10^4 periods of the four particles reproduce the
  // letters of the map's periodic point every period, and the contractions per period equal the prediction
  // from M_w's eigenvalues.  Tolerance 1e3 eps relative: the measured ratios come from norms of states that
  // carry O(letters) roundings per period, and the prediction from the roots of a cubic (a few ulps of the
  // largest modulus, divided by the smallest: a factor |l1/l3| <= 50 here).
  struct Case {
    const char* word;
    double r;
    const char* letters;
  };
  for (const Case& c : {Case{"1133", 0.15, "ababcbcb"}, Case{"111333", 0.1, "abababcbcbcb"}}) {
    const ParticlesResult s = run_word(c.word, c.r, 10000);
    EXPECT_TRUE(s.sequence_ok) << c.word << ": " << s.failure;
    EXPECT_EQ(s.periods_ok, 10000);
    EXPECT_EQ(rotations_contain(s.letters, c.letters), "yes") << c.word << " letters " << s.letters;
    EXPECT_EQ(s.outcome, "stable orbit") << c.word;
    EXPECT_TRUE(s.collapse) << c.word;
    const auto tol = ulps(1000, "event times and gaps carry roundings of every collision of a period");
    EXPECT_CLOSE(s.length_contraction / s.length_predicted, 1, tol) << c.word;
    EXPECT_CLOSE(s.velocity_contraction / s.velocity_predicted, 1, tol) << c.word;
    EXPECT_CLOSE(s.time_contraction / s.time_predicted, 1, tol) << c.word;
    // Converged: every ratio of the second half agrees.
    EXPECT_SMALL(s.length_spread, ulps(1000, "the ratios' own roundings, as above")) << c.word;
    EXPECT_TRUE(s.time_to_collapse > 0 && std::isfinite(s.time_to_collapse));
    // The map route: core::step from the periodic point, one letter group per symbol.
    patterns::Verdict<double> v = patterns::analyse<double>(patterns::parse_word(c.word), c.r);
    std::string map_letters;
    core::Vec3<double> u = v.orbit.front();
    for (std::size_t k = 0; k < v.word.size(); ++k) {
      const core::Vec3<double> w = core::to_quadrant(u);
      const auto st = core::step(w, c.r);
      map_letters += core::letters<double>(st.symbol, w);
      u = st.u / st.u.norm();
    }
    EXPECT_EQ(map_letters, s.letters) << c.word;
    // The reference particle route (src/reference), one b-to-b cycle at a time from the periodic point.
    std::string ref_letters;
    core::Particles<double> cfg = core::to_particles<double>(v.orbit.front());
    for (std::size_t k = 0; k < v.word.size(); ++k) {
      const auto cyc = reference::simulate_b_to_b<double>(cfg, c.r);
      ASSERT_EQ(cyc.status, reference::ParticleStatus::ok);
      ref_letters += cyc.letters;
      cfg = core::to_particles<double>(core::from_particles<double>(cyc.state));
    }
    EXPECT_EQ(ref_letters, s.letters) << c.word;
  }
}

TEST(ParticlesPatterns, TheStable132312IsNotACollapse) {
  // 132312 at r = 0.5 (stable for the map above 0.2201, Theorem 7.1): the map, the reference cycles and the
  // period matrix agree on the letters abcbcabcbabacb (the first 2 is cab: the J-symmetry forces y < 0 there).
  // But J M_h has a complex pair for r > 3 - 2 sqrt(2) (the discriminant of Section 7.1), so K_w turns the
  // velocities within the orbit's plane and no trajectory of four particles repeats the pattern: from the
  // periodic plane, every shift q - lambda p separates within the first period.
  const ParticlesResult s = run_word("132312", 0.5, 100);
  EXPECT_EQ(s.letters, "abcbcabcbabacb");
  EXPECT_EQ(s.outcome, "stable orbit");
  EXPECT_FALSE(s.collapse);
  EXPECT_FALSE(s.sequence_ok);
  EXPECT_EQ(s.periods_ok, 0);
  EXPECT_LT(s.collisions_unrescaled, 14);
  EXPECT_TRUE(std::isnan(s.length_predicted));
  const patterns::Verdict<double> v = patterns::analyse<double>(patterns::parse_word("132312"), 0.5);
  EXPECT_FALSE(v.spectrum[1].real);  // the pair of J M_h
  // Below 3 - 2 sqrt(2) the three roots are real: the pattern's unstable orbits there are collapses.
  for (double r : {0.05, 0.1, 0.15}) {
    const auto c = patterns::classify<double>(patterns::parse_word("132312"), r);
    if (c.outcome != patterns::Outcome::none) EXPECT_TRUE(c.collapse) << "r = " << r;
  }
}

TEST(ParticlesPatterns, Float128AgreesWithDouble) {
  // The exact period matrix in float128 (113-bit): contraction and prediction agree with double's to 1e3 eps
  // (double's own error, see above).
  const ParticlesResult d = run_word("111333", 0.1, 2000);
  const ParticlesResult q = run_word("111333", 0.1, 2000, "float128");
  EXPECT_TRUE(q.sequence_ok);
  EXPECT_CLOSE(q.length_predicted / d.length_predicted, 1, ulps(1000, "double's own error, as above"));
  // float128's own agreement (~1e3 of its eps 1.9e-34) is below half an ulp of the double ratio: exactly 1.
  EXPECT_CLOSE(q.length_contraction / q.length_predicted, 1, ulps(0, "float128 agreement, reported in double"));
  EXPECT_CLOSE(q.time_to_collapse / d.time_to_collapse, 1, ulps(1000, "double's own error, as above"));
}

TEST(ParticlesPatterns, NormalStartConvergesToTheSelfSimilarCollapse) {
  // From q normal to p (shifted by -lambda p), the velocities K_w^n q approach the dominant eigenvector at the
  // rate mu_l / mu_v per period: after 2000 periods the contraction is the self-similar one to 1e3 eps.
  for (const char* w : {"1133", "111333"}) {
    const double r = std::string(w) == "1133" ? 0.15 : 0.1;
    const ParticlesResult a = run_word(w, r, 2000, "double", "normal");
    EXPECT_TRUE(a.sequence_ok) << w << ": " << a.failure;
    EXPECT_CLOSE(a.length_contraction / a.length_predicted, 1, ulps(1000, "double's own error, as above")) << w;
    // The first period is off the self-similar value (this is a real convergence, not the start itself).
    EXPECT_GT(std::abs(a.length_ratio.front() / a.length_predicted - 1), 1e-6) << w;
  }
}

TEST(ParticlesPatterns, RescalingIsExactAndTheUnrescaledRunUnderflows) {
  // Rescaling by powers of two changes no rounding: the rescaled and unrescaled runs agree bit for bit while the
  // latter stays in the normal range; the unrescaled run then fails after about ln(DBL_MIN)/ln(rho) periods
  // (gaps in the subnormal range lose digits: allow up to 52 ln 2 / |ln rho| periods more, and none fewer than
  // 0.9 of the prediction).
  const ParticlesResult s = run_word("1133", 0.15, 5000);
  const patterns::Verdict<double> v = patterns::analyse<double>(patterns::parse_word("1133"), 0.15);
  Gaps<double, 3> g;  // the start of run(), rebuilt here
  ASSERT_TRUE(self_similar_start<double>(v.orbit.front(), s.letters, 0.15, g));
  g.p /= g.p.norm();
  const auto a = simulate_pattern<double>(g, s.letters, 0.15, 50, true);
  const auto b = simulate_pattern<double>(g, s.letters, 0.15, 50, false);
  const double rho = s.length_predicted;
  const long normal_periods = static_cast<long>(std::log(std::numeric_limits<double>::min()) / std::log(rho)) - 2;
  for (long n = 0; n < std::min<long>({50, normal_periods, a.periods_ok, b.periods_ok}); ++n)
    EXPECT_EQ(a.length_ratio[n], b.length_ratio[n]) << "period " << n;
  const double per = static_cast<double>(s.letters.size());
  EXPECT_GE(static_cast<double>(s.collisions_unrescaled), 0.9 * s.collisions_limit_predicted);
  EXPECT_LE(static_cast<double>(s.collisions_unrescaled),
            s.collisions_limit_predicted + per * (52 * std::log(2.0) / -std::log(rho) + 2));
  EXPECT_LT(s.collisions_unrescaled, 5000 * static_cast<long>(per));
}

TEST(ParticlesRequestContract, ErrorsNameTheField) {
  const auto field_of = [](ParticlesRequest q) -> std::string {
    try {
      q.validate();
    } catch (const core::InvalidField& e) {
      return e.field;
    }
    return "";
  };
  ParticlesRequest ok;
  EXPECT_EQ(field_of(ok), "");
  ParticlesRequest q = ok;
  q.word = "1113";  // feasible (unstable) only below r = 0.0864; ok.r = 0.5
  EXPECT_EQ(field_of(q), "word");
  q = ok;
  q.word = "1133";  // feasible only for small r; ok.r = 0.5
  EXPECT_EQ(field_of(q), "word");
  q = ok;
  q.r = 1.0;
  EXPECT_EQ(field_of(q), "r");
  q = ok;
  q.periods = 0;
  EXPECT_EQ(field_of(q), "periods");
  q = ok;
  q.precision = "quad";
  EXPECT_EQ(field_of(q), "precision");
  q = ok;
  q.start = "x";
  EXPECT_EQ(field_of(q), "start");
  q = ok;
  q.diagram_periods = 51;
  EXPECT_EQ(field_of(q), "diagram-periods");
  // fields() lists every input once, under the flag's name.
  std::vector<std::string> names;
  ok.fields([&](const char* n, auto&, const char*, auto...) { names.emplace_back(n); });
  EXPECT_EQ(names, (std::vector<std::string>{"word", "r", "periods", "precision", "start", "diagram-periods"}));
}

TEST(FeasibleAtlas, UnstableOrbitsAreFollowedAsLongAsPredicted) {
  // The map (core::step) from the periodic point of an unstable orbit repeats the word until rounding errors,
  // ~eps, grown by Lambda = |l_1 / l_o| per period, reach the smallest branch margin m: about ln(m/eps)/ln(Lambda)
  // periods.  Accepted: within [predicted/2 - 2, 2 predicted + 2] (the constant in front of eps and the margin's
  // direction relative to the unstable eigenvector are not modelled); long double follows at least as long.
  // Orbits whose instability comes from a complex dominant pair (13 at r = 0.5: Lambda = 1.058 per period) are
  // followed far longer than this (10^5 periods and more): not covered by the prediction, left out here and, by
  // its 2000-period cap, from the atlas's check (unstable_followed.csv).
  struct Case {
    const char* word;
    double r;
  };
  for (const Case& c : {Case{"13223122", 0.1}, Case{"13", 0.15}, Case{"12", 0.1}, Case{"132312", 0.1},
                        Case{"1133", 0.05}, Case{"111333", 0.05}, Case{"13", 0.3}}) {
    const auto d = patterns::follow_periodic_orbit<double>(patterns::parse_word(c.word), c.r, 100000);
    const auto l = patterns::follow_periodic_orbit<long double>(patterns::parse_word(c.word), c.r, 100000);
    if (!(d.expansion > 1.0001)) continue;  // neutral (the word 2 rotates on y = 0): nothing to predict
    EXPECT_GE(d.periods, d.predicted / 2 - 2) << c.word << " r = " << c.r << " predicted " << d.predicted;
    EXPECT_LE(d.periods, 2 * d.predicted + 2) << c.word << " r = " << c.r << " predicted " << d.predicted;
    EXPECT_GE(l.periods, d.periods) << c.word << " r = " << c.r;
  }
}

TEST(FeasibleAtlas, CollapsesEndAtTheLiteraturesCriticalValues) {
  // abcb (13) is a collapse of four particles up to r_crit ~ 0.1917 (the bound of the earlier literature quoted in
  // the Introduction); its periodic point stays feasible for the map above, without a collapse.
  const auto w13 = patterns::parse_word("13");
  EXPECT_TRUE(patterns::classify<double>(w13, 0.1916).collapse);
  EXPECT_EQ(patterns::classify<double>(w13, 0.1918).outcome, patterns::Outcome::unstable);
  EXPECT_FALSE(patterns::classify<double>(w13, 0.1918).collapse);
  // No word of length <= 8 is a collapse above 2^(2/3) - 1 (no collapse of four particles exists there at all).
  std::vector<double> grid;
  for (int i = 0; i < 80; ++i) grid.push_back(0.588 + 0.41 * i / 79.0);
  for (const auto& w : patterns::enumerate_canonical(8))
    for (double r : grid)
      EXPECT_FALSE(patterns::classify<double>(w, r).collapse) << patterns::to_digits(w) << " r = " << r;
}

TEST(FeasibleAtlas, OneThreadEqualsTwoThreads) {
  const auto grid = patterns::feasible_grid();
  const auto a = patterns::compute_feasible_atlas(6, grid, 1e-10, 1);
  const auto b = patterns::compute_feasible_atlas(6, grid, 1e-10, 2);
  EXPECT_EQ(patterns::feasible_csv(a), patterns::feasible_csv(b));
  EXPECT_GT(a.size(), 10u);
}

TEST(ParticlesPatterns, ContractionFromTheExactCharacteristicPolynomial) {
  // The exact route: chi(lambda) of A = J M_h (w = h J(h)) with rational coefficients in r (patterns/exact.hpp),
  // evaluated at r = 3/20 and 1/10 exactly, its roots in 50 digits; M_w's eigenvalues are their squares and the
  // length contraction is sqrt(r^n2 l_o l_b / l_a) (n2 = 0 here).  Against the double particle run: 1e3 eps (the
  // run's own error, see IndependentRoutesAgree).
  boost::multiprecision::mpfr_float::default_precision(50);
  using mp = boost::multiprecision::mpfr_float;
  struct Case {
    const char* word;
    double r;
    long num, den;
  };
  for (const Case& c : {Case{"1133", 0.15, 3, 20}, Case{"111333", 0.1, 1, 10}}) {
    const auto w = patterns::parse_word(c.word);
    const patterns::CharPoly chi = patterns::characteristic_polynomial(w);
    const patterns::rational r(c.num, c.den);
    const auto val = [&](const patterns::RationalPoly& p) { return mp(p.eval(r)); };
    auto roots = patterns::detail::cubic_roots<mp>(val(chi.c2), val(chi.c1), val(chi.c0));
    std::vector<mp> l;
    for (const auto& x : roots) {
      ASSERT_TRUE(x.real) << c.word;
      l.push_back(x.re * x.re);  // M_w = A^2
    }
    std::sort(l.begin(), l.end(), [](const mp& a, const mp& b) { return abs(a) > abs(b); });
    const double rho = static_cast<double>(sqrt(abs(l[0] * l[2] / l[1])));  // stable: the orbit's is l[0]
    const ParticlesResult s = run_word(c.word, c.r, 10000);
    const auto tol = ulps(1000, "the simulation's roundings over a period; MPFR eigenvalues rounded once to double");
    EXPECT_CLOSE(s.length_contraction / rho, 1, tol) << c.word;
    EXPECT_CLOSE(s.time_contraction / static_cast<double>(abs(l[2] / l[1])), 1, tol) << c.word;
  }
}

// ---- The files of `btob particles` (output.cpp), through the public API ----

using btob::testing::csv_cells;
using btob::testing::csv_column;
using btob::testing::expect_numbers_or_empty;

TEST(ParticlesFiles, ConvergenceRowsAreEveryPeriodTo99ThenTwentyPerDecade) {
  EXPECT_TRUE(convergence_rows(0).empty());
  for (std::size_t n : {1u, 50u, 99u, 100u}) {  // short runs: every period
    const auto rows = convergence_rows(n);
    ASSERT_EQ(rows.size(), n);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(rows[i], i);
  }
  for (std::size_t n : {101u, 1000u, 10000u, 123457u}) {
    const auto rows = convergence_rows(n);
    ASSERT_GE(rows.size(), 100u);
    for (std::size_t i = 0; i < 100; ++i) EXPECT_EQ(rows[i], i) << n;  // periods 1..100
    EXPECT_EQ(rows.back(), n - 1) << n;                                // and the last one
    // Beyond 100, consecutive periods k < k' (but the last) have k' = ceil(k 10^(1/20)): 20 per decade.
    for (std::size_t i = 100; i + 1 < rows.size(); ++i) {
      const double k = static_cast<double>(rows[i - 1] + 1), next = static_cast<double>(rows[i] + 1);
      EXPECT_GE(next, k * std::pow(10.0, 0.05)) << n << " row " << i;
      EXPECT_LT(next, k * std::pow(10.0, 0.05) + 1) << n << " row " << i;
    }
    const double decades = std::log10(static_cast<double>(n) / 100);
    EXPECT_CLOSE(static_cast<double>(rows.size() - 100), 20 * decades, bound(2, "20 rows per decade, +-1 at each end"))
        << n;
  }
}

TEST(ParticlesFiles, ACollapseHasNumbersEverywhereButTheFirstTimeRatio) {
  const ParticlesResult s = run_word("1133", 0.15, 20);
  ASSERT_TRUE(s.sequence_ok);
  const std::vector<std::pair<std::string, const char*>> files{{s.csv(), "particles.csv"},
                                                               {s.convergence_csv(), "convergence.csv"},
                                                               {s.events_csv(), "events.csv"},
                                                               {s.row_csv(true), "row"}};
  for (const auto& [csv, what] : files) expect_numbers_or_empty(csv, what);
  const auto conv = csv_cells(s.convergence_csv());
  ASSERT_EQ(conv.size(), 21u);  // header and 20 periods
  EXPECT_EQ(conv[1][3], "");    // period 1 has no previous duration
  EXPECT_CLOSE(std::stod(conv[20][1]), s.length_contraction,
               ulps(4, "the CSV's decimal read back").of(s.length_contraction));
  const auto row = csv_cells(s.csv());
  ASSERT_EQ(row.size(), 2u);
  EXPECT_EQ(row[0].size(), 20u);
  EXPECT_EQ(std::stod(row[1][7]), std::stod(fmt::format("{:.15g}", s.time_to_collapse)));
  // The printed row is the first eight columns of particles.csv.
  const auto printed = csv_cells(s.row_csv(false));
  ASSERT_EQ(printed.size(), 1u);
  EXPECT_EQ(printed[0], std::vector<std::string>(row[1].begin(), row[1].begin() + 8));
  EXPECT_EQ(csv_cells(s.row_csv(true))[0], std::vector<std::string>(row[0].begin(), row[0].begin() + 8));
  EXPECT_EQ(csv_cells(s.events_csv()).size(), s.events.size() / 8 + 1);
}

TEST(ParticlesFiles, NoCollapseLeavesEmptyCellsAndSaysWhy) {
  const ParticlesResult s = run_word("132312", 0.5, 5);  // stable, not a collapse: the particles separate
  ASSERT_FALSE(s.collapse);
  const std::vector<std::pair<std::string, const char*>> files{
      {s.csv(), "particles.csv"}, {s.convergence_csv(), "convergence.csv"}, {s.events_csv(), "events.csv"}};
  for (const auto& [csv, what] : files) expect_numbers_or_empty(csv, what);
  const auto row = csv_cells(s.csv());
  const auto col = [&](const std::string& name) { return row[1][csv_column(row[0], name)]; };
  for (const char* name : {"contraction", "predicted", "time_to_collapse", "velocity_predicted", "time_predicted"})
    EXPECT_EQ(col(name), "") << name;
  EXPECT_NE(col("failure").find("no collapse"), std::string::npos);
  for (const auto& e : csv_cells(s.events_csv())) EXPECT_EQ(e.size(), 8u);
  core::Contents c;
  s.describe(c);
  EXPECT_EQ(std::get<std::string>(c.attrs.at("time_to_collapse")), "nan");  // JSON has no NaN
  EXPECT_EQ(std::get<std::string>(c.attrs.at("start")), "self-similar");
  EXPECT_EQ(c.attrs.count("csv_empty_cells"), 1u);
}
