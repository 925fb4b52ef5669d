// SPDX-License-Identifier: GPL-3.0-or-later
// Long checks of src/stats (label long): C_N at the benchmark's series length N = 1e6 by FFT and by the direct
// sum (n_max = 1e4: 1e10 multiply-adds), and the non-decay of C_N on a quasi-periodic orbit at r = 0.3 over 1e5 lags.
#include "stats/stats.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

using namespace btob;
using namespace btob::stats;

TEST(LongCorrelation, FftEqualsDirectAtFullSize) {
  // N = 1e6 as in the benchmark; n_max = 1e4 instead of its 1e5 (the direct sum took 2 minutes of CI): the FFT's
  // rounding grows with its length L = fast_fft_length(N + n_max), which barely changes, not with how many lags
  // are compared.
  const long N = 1000000, n_max = 10000;
  const auto x = observe(orbit_series(0.11, {1, -3, -1.1}, 10000, N + n_max), Observable::phi);
  Correlator<double> c(N, n_max);
  const auto f = c(x, x), d = correlation_direct(x, x, N, n_max);
  double diff = 0, scale = 0;
  for (long n = 0; n <= n_max; ++n) {
    diff = std::max(diff, std::fabs(f[n] - d[n]));
    scale = std::max(scale, std::fabs(d[n]));
  }
  std::printf("N = 1e6, n_max = 1e4, r = 0.11, phi: max |fft - direct| / max |C_N| = %.3g\n", diff / scale);
  // Measured 1.95e-16 here (L = fast_fft_length(1.01e6)) and 4.9e-17 with n_max = 1e5 (another L): both routes
  // round at about eps of max |C_N| (compensated sums in the direct route, FFTW's O(eps log L) in the other); 4e-16
  // (1.8 eps), about twice the larger, catches any lost or misplaced term.
  EXPECT_SMALL(diff / scale, ulps(1.8, "both routes round at about eps of max |C_N|; twice the measured 0.88 eps"));
}

TEST(LongCorrelation, QuasiPeriodicR03DoesNotDecay) {
  // r = 0.3, started near (1, 0, -1) inside the P2 rotation region: an invariant curve (Section 5.2).
  const long N = 1000000, n_max = 100000;
  const auto x = observe(orbit_series(0.3, {1, 0.05, -1}, 10000, N + n_max), Observable::phi);
  Correlator<double> c(N, n_max);
  const auto cn = c(x, x);
  const auto env = envelope(cn, 1000);
  const double lo = *std::min_element(env.begin(), env.end()), hi = *std::max_element(env.begin(), env.end());
  const Decay d = fit_decay(cn, n_max - 1, 1000, 4 * cn[0] / std::sqrt(static_cast<double>(N)));
  std::printf(
      "r = 0.3 quasi-periodic: C_N(0) = %.4g, envelope over windows of 1000 lags in [%.4g, %.4g], rate %.3g +- %.2g\n",
      cn[0], lo, hi, d.rate, d.rate_error);
  EXPECT_FALSE(d.decays);
  EXPECT_GT(lo, 0.9 * hi);  // flat envelope to 10% over 1e5 lags
}
