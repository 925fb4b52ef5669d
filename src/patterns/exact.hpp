// SPDX-License-Identifier: GPL-3.0-or-later
// Exact characteristic polynomials of word matrices: polynomials in r with rational coefficients (GMP).
#pragma once

#include "patterns/patterns.hpp"

#include <boost/multiprecision/gmp.hpp>

#include <string>
#include <vector>

namespace btob::patterns {

using rational = boost::multiprecision::mpq_rational;

// p(r) = sum_k c[k] r^k, exact; c has no trailing zeros (the zero polynomial has c empty).
struct RationalPoly {
  std::vector<rational> c;
  RationalPoly() = default;
  RationalPoly(std::initializer_list<long> ints);  // {c0, c1, ...}
  static RationalPoly constant(const rational& v);
  int degree() const { return static_cast<int>(c.size()) - 1; }  // -1 for the zero polynomial
  void trim();
  rational eval(const rational& r) const;
  double eval(double r) const;
  std::string to_string(const char* var = "r") const;  // "7*r^6 - 24*r^5 + ... + 1", highest power first
  bool operator==(const RationalPoly& o) const { return c == o.c; }
};
RationalPoly operator+(const RationalPoly& a, const RationalPoly& b);
RationalPoly operator-(const RationalPoly& a, const RationalPoly& b);
RationalPoly operator*(const RationalPoly& a, const RationalPoly& b);
RationalPoly operator*(const rational& s, const RationalPoly& a);
RationalPoly pow(const RationalPoly& a, int n);

// chi(lambda) = det(lambda I - A) = lambda^3 + c2 lambda^2 + c1 lambda + c0 of A = J M_h when w = h J(h)
// (and reduce), else A = M_w (Theorem 7.1 proof: chi of J P2 P3 P1 for 132312).
struct CharPoly {
  RationalPoly c2, c1, c0;
};
CharPoly characteristic_polynomial(const Word& w, bool reduce = true);
// The discriminant in the paper's sign: (q/2)^2 + (p/3)^3 of the depressed cubic t^3 + p t + q, i.e.
// -1/108 times the classical discriminant; < 0 means three distinct real roots (proofs of Thms 6.1, 6.2).
RationalPoly discriminant(const CharPoly& chi);

}  // namespace btob::patterns
