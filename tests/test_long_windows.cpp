// SPDX-License-Identifier: GPL-3.0-or-later
// Long checks of src/windows (label "long"): certificates n = 41..150, 256 vs 512 digits for n <= 150.
#include "windows/windows.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace {

using namespace btob::windows;

TEST(LongWindows, CertificatesFortyOneToHundredFifty) {
  for (int n = 41; n <= 150; ++n) {
    const auto t0 = std::chrono::steady_clock::now();
    const Certificate c = certify_lower_bound(n, 12);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(c.valid()) << "n = " << n << " a = " << c.a.get_str() << " signs " << c.sign_a << "," << c.sign_b
                           << " roots(0,a] = " << c.roots_0_a << " roots(a,b) = " << c.roots_a_b;
    if (n % 10 == 0) std::printf("certificate n = %d: %.3f s\n", n, s);
  }
}

TEST(LongWindows, TwoPrecisionsAgreeToHundredDigits) {
  for (int n = 1; n <= 150; ++n) {
    const mpfr_float a = window_lower_bound(n, 256), b = window_lower_bound(n, 512);
    mpfr_float::default_precision(600);
    EXPECT_LT(abs(a - b), mpfr_float("1e-100")) << "n = " << n;  // the target: >= 100 digits
    EXPECT_LT(abs(a - b), mpfr_float("1e-255")) << "n = " << n;  // and we claim all 256 requested decimals
  }
}

}  // namespace
