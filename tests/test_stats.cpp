// Tests of src/stats: C_N by FFT equals the direct sum; periodicity, non-decay and decay of C_N on
// periodic, quasi-periodic and chaotic orbits; empirical measures in one basin and on distinct curves.
#include "stats/stats.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace btob;
using namespace btob::stats;

namespace {
double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}
double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::fabs(a[i] - b[i]));
  return d / max_abs(b);
}
const iterate::Vec3<double> kGrid0{1, -3, -1.1};  // first point of the Section 4 grid
}  // namespace

TEST(Correlation, FftEqualsDirectOnRandomSeries) {
  std::mt19937_64 gen(3);
  std::normal_distribution<double> g(0.7, 2.0);  // non-zero mean: the centring path is exercised
  std::vector<double> x(30000), y(30000);
  for (auto& v : x) v = g(gen);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = 0.3 * x[k] + g(gen);
  Correlator c;
  const long N = 20000, n_max = 5000;
  // Relative to the largest |C_N|: the direct sum's rounding grows like sqrt(N) eps |x||y|, the FFT's like
  // log(L) eps; both far below 1e-12 at N = 2e4.
  EXPECT_LT(max_rel_diff(c.correlation(x, y, N, n_max), correlation_direct(x, y, N, n_max)), 1e-12);
  EXPECT_LT(max_rel_diff(c.correlation(x, x, N, n_max), correlation_direct(x, x, N, n_max)), 1e-12);
  // The plan is reused for the next series of the same length.
  EXPECT_LT(max_rel_diff(c.correlation(y, x, N, n_max), correlation_direct(y, x, N, n_max)), 1e-12);
}

TEST(Correlation, FftEqualsDirectOnOrbitSeries) {
  const OrbitSeries s = orbit_series(0.11, kGrid0, 1000, 40000);
  Correlator c;
  for (Observable o : {Observable::phi, Observable::w2, Observable::cos_phi, Observable::symbol1}) {
    const auto x = observe(s, o);
    EXPECT_LT(max_rel_diff(c.correlation(x, x, 30000, 2000), correlation_direct(x, x, 30000, 2000)), 1e-12)
        << observable_name(o);
  }
}

TEST(Correlation, PeriodicOrbitGivesPeriodicCN) {
  // r = 0.15: the orbit sits on the sink 1133 (period 4) after the transient, to machine precision.
  const OrbitSeries s = orbit_series(0.15, kGrid0, 5000, 21000);
  const auto x = observe(s, Observable::phi);
  Correlator c;
  const auto cn = c.correlation(x, x, 20000, 1000);
  double worst = 0;
  for (long n = 0; n + 4 <= 1000; ++n) worst = std::max(worst, std::fabs(cn[n + 4] - cn[n]));
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(max_abs(cn), 0.1);  // and it is not trivially zero
}

TEST(Correlation, QuasiPeriodicDoesNotDecayChaoticDoes) {
  Correlator c;
  // r = 0.2 from (1, 0.02, -1): an invariant curve of the P2 rotation (Section 5.2).
  const auto q = observe(orbit_series(0.2, {1, 0.02, -1}, 1000, 101000), Observable::phi);
  const auto cq = c.correlation(q, q, 100000, 1000);
  const Decay dq = fit_decay(cq, 1000, 50);
  EXPECT_LT(std::fabs(dq.rate), 1e-3) << "quasi-periodic: envelope " << dq.envelope_first << " -> " << dq.envelope_last;
  EXPECT_GT(dq.envelope_last, 0.5 * dq.envelope_first);
  // r = 0.11 (apparent chaos, positive Lyapunov exponent ~0.66): |C_N| falls by two decades within ~30 lags.
  const auto x = observe(orbit_series(0.11, kGrid0, 1000, 201000), Observable::phi);
  const auto cx = c.correlation(x, x, 200000, 200);
  const Decay dx = fit_decay(cx, 30, 3);
  EXPECT_GT(dx.rate, 0.05) << "chaotic decay rate " << dx.rate << " +- " << dx.rate_error;
  EXPECT_LT(max_abs(std::vector<double>(cx.begin() + 50, cx.end())), 0.05 * cx[0]);
}

TEST(Measures, OneBasinGivesOneMeasure) {
  // r = 0.15: the 32 orbits of the Section 4 grid all end on 1133: their empirical measures coincide.
  const std::vector<iterate::Vec3<double>> ics = iterate::paper_grid();
  std::vector<Measure> ms;
  for (const auto& u : ics) ms.push_back(empirical_measure(orbit_series(0.15, u, 10000, 100000), Chart::strip, 200, 200));
  for (const auto& m : ms) {
    EXPECT_LT(total_variation(m, ms[0]), 1e-3);
    EXPECT_LT(wasserstein_1d(m.marginal_u(), ms[0].marginal_u(), m.u_lo, m.u_hi), 1e-3);
    double sum = 0;
    for (double v : m.mass) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-12);  // weights 1/N
  }
}

TEST(Measures, DistinctInvariantCurvesGiveDistinctMeasures) {
  // r = 0.2: two orbits on different invariant curves of the P2 rotation (Section 7.1).
  const Measure a = empirical_measure(orbit_series(0.2, {1, 0.01, -1}, 1000, 100000), Chart::strip, 400, 400);
  const Measure b = empirical_measure(orbit_series(0.2, {1, 0.06, -1}, 1000, 100000), Chart::strip, 400, 400);
  EXPECT_GT(total_variation(a, b), 0.5);
  const Measure a2 = empirical_measure(orbit_series(0.2, {1, 0.01, -1}, 1000, 100000), Chart::angles, 100, 100);
  EXPECT_NEAR(total_variation(a2, a2), 0.0, 0.0);
}

TEST(Stats, BadInputNamesTheField) {
  std::vector<double> x(100, 1.0);
  Correlator c;
  try {
    c.correlation(x, x, 50, 50);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("n-max"), std::string::npos) << e.what();
  }
  EXPECT_THROW(correlation_direct(x, x, 90, 20), std::invalid_argument);  // psi too short
  EXPECT_THROW(parse_observable("psi"), std::invalid_argument);
  const OrbitSeries s = orbit_series(0.3, kGrid0, 10, 100);
  EXPECT_THROW(empirical_measure(s, Chart::strip, 0, 10), std::invalid_argument);
  EXPECT_THROW(orbit_series(1.5, kGrid0, 10, 100), std::domain_error);
}
