// SPDX-License-Identifier: GPL-3.0-or-later
// Exact integer polynomials in one variable (GMP), their exact signs at rationals, and Sturm counts.
#pragma once

#include "core/request.hpp"

#include <gmpxx.h>

#include <cstddef>
#include <string>
#include <vector>

namespace btob::windows {

// p(x) = sum_i c[i] x^i with integer coefficients; the zero polynomial has no coefficients.  Every
// operation returns a normalised polynomial (no trailing zero coefficients).
class IntPoly {
 public:
  IntPoly() = default;
  explicit IntPoly(std::vector<mpz_class> coefficients);
  static IntPoly constant(const mpz_class& c);
  static IntPoly x_plus(long a);  // x + a

  int degree() const { return static_cast<int>(c_.size()) - 1; }  // -1 for the zero polynomial
  bool is_zero() const { return c_.empty(); }
  const std::vector<mpz_class>& coefficients() const { return c_; }
  const mpz_class& operator[](std::size_t i) const { return c_[i]; }
  const mpz_class& leading() const { return c_.back(); }

  friend IntPoly operator+(const IntPoly& a, const IntPoly& b);
  friend IntPoly operator-(const IntPoly& a, const IntPoly& b);
  friend IntPoly operator*(const IntPoly& a, const IntPoly& b);
  friend IntPoly operator*(const mpz_class& k, const IntPoly& a);
  friend bool operator==(const IntPoly& a, const IntPoly& b) { return a.c_ == b.c_; }

  IntPoly derivative() const;
  IntPoly reversed(int as_degree) const;  // x^as_degree p(1/x); needs as_degree >= degree()
  IntPoly shifted(int k) const;           // x^k p(x)
  mpz_class content() const;              // gcd of the coefficients (>= 0)
  IntPoly primitive() const;              // p / content (sign kept)

  // Exact division by (x - root) for root = +1 or -1, when p(root) == 0; returns how many times it
  // divided and replaces *this by the quotient.
  int divide_out(long root);

  // Sign (-1, 0, +1) of p(num/den) for den > 0, computed exactly as sum c_i num^i den^(deg-i).
  int sign_at(const mpz_class& num, const mpz_class& den) const;
  int sign_at(const mpq_class& x) const { return sign_at(x.get_num(), x.get_den()); }

  // "c0 + c1*r + ..." style text, highest power first: "5r^6 - 50r^5 + ... + 5".
  std::string to_string(const char* var = "r") const;

 private:
  std::vector<mpz_class> c_;
  void trim();
};

// Pseudo-remainder of a by b (b non-zero): lc(b)^(deg a - deg b + 1) a = q b + prem.
IntPoly pseudo_remainder(const IntPoly& a, const IntPoly& b);

// The Sturm sequence of p (p, p', -rem, ...) computed as a primitive pseudo-remainder sequence: every
// term is a positive multiple of the classical term, so sign variations are those of the classical
// sequence.  Exact; coefficient sizes grow roughly linearly along the sequence.
// `cancel` (here and below): polled before every remainder or bisection step; throws core::Cancelled when set.
std::vector<IntPoly> sturm_sequence(const IntPoly& p, const core::CancelToken* cancel = nullptr);

// Number of distinct real roots of p in (a, b] from its Sturm sequence, a < b.  a and b must not be
// roots of p (throws std::domain_error otherwise).  b_infinite counts on (a, +infinity).
long sturm_count(const std::vector<IntPoly>& seq, const mpq_class& a, const mpq_class& b);
long sturm_count_to_infinity(const std::vector<IntPoly>& seq, const mpq_class& a);

// Distinct real roots of p in the open interval (a, b), a < b, by Descartes' rule of signs after the
// Moebius transform x = (a + b t)/(1 + t), which maps t in (0, inf) onto (a, b) (the Vincent-Collins-Akritas
// bisection): a transformed polynomial with 0 sign variations has no root there, with 1 exactly one (simple)
// root; otherwise the interval is halved (Taylor shifts on exact integers).  Endpoints may be roots (they
// are not counted; a root at a bisection point is).  Returns -1 when it cannot decide within max_depth
// halvings (a multiple root, or roots closer than (b - a) 2^-max_depth): callers then fall back to Sturm.
long descartes_count(const IntPoly& p, const mpq_class& a, const mpq_class& b, int max_depth = 64,
                     const core::CancelToken* cancel = nullptr);
// The same on (a, +infinity): x = a + t, then (a, B) with B a power of two above every root (Fujiwara's
// bound) when that leaves two or more variations.
long descartes_count_to_infinity(const IntPoly& p, const mpq_class& a, int max_depth = 64,
                                 const core::CancelToken* cancel = nullptr);

// Distinct real roots in (a, b) and in (a, +inf) (endpoints not roots, as sturm_count): Descartes first, the
// Sturm sequence (computed once, on demand, in *seq_cache) when Descartes cannot decide.
long root_count(const IntPoly& p, const mpq_class& a, const mpq_class& b, std::vector<IntPoly>* seq_cache,
                const core::CancelToken* cancel = nullptr);
long root_count_to_infinity(const IntPoly& p, const mpq_class& a, std::vector<IntPoly>* seq_cache,
                            const core::CancelToken* cancel = nullptr);

// For a palindromic p of even degree 2m (c_i = c_{2m-i}): the R of degree m with p(x) = x^m R(x + 1/x).
// Throws std::invalid_argument when p is not palindromic of even degree.
IntPoly palindromic_reduce(const IntPoly& p);

}  // namespace btob::windows
