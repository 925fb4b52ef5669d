// SPDX-License-Identifier: GPL-3.0-or-later
// Windows of stability of (ab)^n(cb)^n: the exact polynomials Q_n, their roots in high precision with
// exact certificates, the conjectured upper bounds r_crit,2(n), the paper's thresholds and thin stripes.
#pragma once

#include "core/scalar.hpp"
#include "windows/polynomial.hpp"

#include <gmpxx.h>

#include <string>
#include <vector>

namespace btob::windows {

using core::mpfr_float;

// Conventions.
//  * A, B are the collision matrices of eq. (2.7) with alpha = (1 + r)/2:
//      A = [[-r,0,0],[alpha,1,0],[0,0,1]],  B = [[1,alpha,0],[0,-r,0],[0,alpha,1]];  J swaps x and z (4.2).
//  * n >= 1 (the pattern (ab)^n(cb)^n); functions throw core::InvalidField "n: got X, expected ..."
//    on n < 1 (n < 2 for r_crit,2) and on digits outside 10..10000.
//  * "decimals" D means D digits after the decimal point (the paper prints 12).

// A polynomial with rational coefficients, numerator(r) / denominator (denominator > 0, a power of 2
// here, coprime with the content of the numerator).
struct RationalPoly {
  IntPoly numerator;
  mpz_class denominator = 1;
  int degree() const { return numerator.degree(); }
  mpq_class coefficient(int i) const;                  // reduced
  std::string developed(const char* var = "r") const;  // "5/256r^8 - 5/32r^7 + ..." (Table B.2, left)
};

// Q_n = (1/denominator) (r+1)^plus_one (r-1)^minus_one cofactor(r), cofactor(+-1) != 0 (Table B.2, right).
struct Factorised {
  mpz_class denominator;
  int plus_one = 0, minus_one = 0;
  IntPoly cofactor;
  std::string to_string(const char* var = "r") const;  // "1/256 (r+1)^2 (5r^6 - ...)"; (r^2-1)^k when equal
};

RationalPoly trace_polynomial(int n);  // P_n = tr(J (BA)^n), degree 2n (Section 4)
// Q_n = r^(2n) P_n(r) P_n(1/r) - r^(2n), eq. (4.3), degree 4n; `cancel` polled at every matrix power and product row.
RationalPoly window_polynomial(int n, const core::CancelToken* cancel = nullptr);
Factorised factorise(const RationalPoly& q);

// The lower bound of the n-th window: the smallest positive root of Q_n.  It lies in
// (7 - 4 sqrt(3), r_crit,2(n)) (n >= 2) or (7 - 4 sqrt(3), 1/2) (n = 1), where Q_n has exactly one sign
// change; the certificate below proves that no smaller positive root exists.  Returned with at least
// `decimals` + 3 correct decimals (precision raised until the sign change around the result is reliable).
// `cancel` (here and below): polled at every evaluation of Q_n, Newton step, bisection and remainder step; throws
// core::Cancelled when set.
mpfr_float window_lower_bound(int n, int decimals, const core::CancelToken* cancel = nullptr);

// Exact certificate of window_lower_bound(n) to D decimals, all in rational arithmetic:
//   a = k/10^D < b, Q_n(a) and Q_n(b) of opposite signs (so a root lies in (a, b)),
//   Sturm: Q_n has no real root in (0, a] and exactly one distinct real root in (a, b).
// Hence the smallest positive root of Q_n lies in (a, b).
struct Certificate {
  int n = 0, decimals = 0;
  mpq_class a, b;
  int sign_a = 0, sign_b = 0;
  long roots_0_a = -1, roots_a_b = -1;
  bool valid() const { return sign_a * sign_b < 0 && roots_0_a == 0 && roots_a_b == 1 && a < b && a > 0; }
};
Certificate certify_lower_bound(int n, int decimals, const core::CancelToken* cancel = nullptr);
// The same checks on a given bracket (a, b) (decimals = 0): valid() only if it proves that the smallest positive
// root of Q_n lies in (a, b).  certify_lower_bound runs it on the D-decimal truncation of window_lower_bound(n).
Certificate certify_interval(int n, const mpq_class& a, const mpq_class& b, const core::CancelToken* cancel = nullptr);

// r_crit,2(n) = (2 cos(pi/(2n)) - sqrt(4 cos^2(pi/(2n)) - 1))^2, eq. (4.6); n >= 2.  `digits` significant
// (10..10000, the range every `digits` field documents), computed and returned with `guard` digits more: a caller
// that wants more guard digits passes them here rather than adding them to `digits`, which would refuse the
// documented 10000.
mpfr_float r_crit2(int n, int digits, int guard = 10);

// The paper's threshold constants in `digits` significant digits.
struct Threshold {
  std::string name, formula;
  mpfr_float value;
};
std::vector<Threshold> thresholds(int digits);  // 7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1

// Thin stripes, eq. (6.3): r(l/m) = 1 + 2 xi - 2 sqrt(xi + xi^2), xi = cos(pi - 2 pi l/m), for reduced
// l/m with 1/4 < l/m <= 1/2 and m <= max_m (l/m and 1 - l/m give the same r; l/m = 1/4 gives r = 1,
// outside (0, 1)).  Sorted by r; all values lie in [3 - 2 sqrt 2, 1).
struct Stripe {
  int l = 0, m = 0;
  mpfr_float value;
};
std::vector<Stripe> thin_stripes(int max_m, int digits);

// A decimal string of x with `decimals` digits after the point, rounded to nearest.
std::string fixed(const mpfr_float& x, int decimals);

// Validation shared by the API and the CLI.
void validate_n(long n, long min_n = 1, const char* field = "n");
void validate_digits(long digits, const char* field = "digits");  // 10..10000

}  // namespace btob::windows
