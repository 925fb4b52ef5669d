// SPDX-License-Identifier: GPL-3.0-or-later
// Exact polynomial arithmetic in r and characteristic polynomials of word matrices (Theorems 7.1, 7.3).
#include "patterns/exact.hpp"

#include <fmt/format.h>

#include <array>

namespace btob::patterns {

RationalPoly::RationalPoly(std::initializer_list<long> ints) {
  for (long v : ints) c.emplace_back(v);
  trim();
}
RationalPoly RationalPoly::constant(const rational& v) {
  RationalPoly p;
  p.c = {v};
  p.trim();
  return p;
}
void RationalPoly::trim() {
  while (!c.empty() && c.back() == 0) c.pop_back();
}
rational RationalPoly::eval(const rational& r) const {
  rational s = 0;
  for (std::size_t k = c.size(); k-- > 0;) s = s * r + c[k];
  return s;
}
double RationalPoly::eval(double r) const {
  double s = 0;
  for (std::size_t k = c.size(); k-- > 0;) s = s * r + c[k].convert_to<double>();
  return s;
}
std::string RationalPoly::to_string(const char* var) const {
  if (c.empty()) return "0";
  std::string out;
  for (std::size_t k = c.size(); k-- > 0;) {
    if (c[k] == 0) continue;
    const rational a = abs(c[k]);
    const bool neg = c[k] < 0;
    if (out.empty()) out += neg ? "-" : "";
    else out += neg ? " - " : " + ";
    const bool one = a == 1;
    if (!one || k == 0) out += a.str();
    if (k > 0) out += fmt::format("{}{}{}", one ? "" : "*", var, k > 1 ? fmt::format("^{}", k) : "");
  }
  return out;
}
RationalPoly operator+(const RationalPoly& a, const RationalPoly& b) {
  RationalPoly s;
  s.c.resize(std::max(a.c.size(), b.c.size()));
  for (std::size_t k = 0; k < a.c.size(); ++k) s.c[k] += a.c[k];
  for (std::size_t k = 0; k < b.c.size(); ++k) s.c[k] += b.c[k];
  s.trim();
  return s;
}
RationalPoly operator-(const RationalPoly& a, const RationalPoly& b) { return a + rational(-1) * b; }
RationalPoly operator*(const RationalPoly& a, const RationalPoly& b) {
  RationalPoly s;
  if (a.c.empty() || b.c.empty()) return s;
  s.c.assign(a.c.size() + b.c.size() - 1, rational(0));
  for (std::size_t i = 0; i < a.c.size(); ++i)
    for (std::size_t j = 0; j < b.c.size(); ++j) s.c[i + j] += a.c[i] * b.c[j];
  s.trim();
  return s;
}
RationalPoly operator*(const rational& v, const RationalPoly& a) {
  RationalPoly s = a;
  for (auto& x : s.c) x *= v;
  s.trim();
  return s;
}
RationalPoly pow(const RationalPoly& a, int n) {
  RationalPoly s = RationalPoly::constant(1);
  for (int i = 0; i < n; ++i) s = s * a;
  return s;
}

namespace {
using PMat = std::array<std::array<RationalPoly, 3>, 3>;

PMat mul(const PMat& a, const PMat& b) {
  PMat m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) m[i][j] = m[i][j] + a[i][k] * b[k][j];
  return m;
}

// P1, P2, P3 of eq. (3.6) with alpha = (1 + r)/2 (eq. 2.8), entries exact polynomials in r.
PMat P(int s) {
  const RationalPoly r{0, 1}, a = rational(1, 2) * RationalPoly{1, 1}, zero;
  const RationalPoly one = RationalPoly::constant(1);
  switch (s) {
    case 1: return {{{rational(-1) * r, r * a, zero}, {rational(-1) * a, a * a - r, r * a}, {zero, zero, r * r}}};
    case 2:
      return {{{r, rational(-1) * r * a, zero}, {a, rational(-2) * a * a + r, a}, {zero, rational(-1) * r * a, r}}};
    default: return {{{r * r, zero, zero}, {r * a, a * a - r, rational(-1) * a}, {zero, r * a, rational(-1) * r}}};
  }
}
}  // namespace

CharPoly characteristic_polynomial(const Word& w0, bool reduce) {
  const Word w = primitive_root(w0);
  const bool red = reduce && is_J_square(w);
  const std::size_t n = red ? w.size() / 2 : w.size();
  const RationalPoly one = RationalPoly::constant(1), zero;
  PMat m{{{one, zero, zero}, {zero, one, zero}, {zero, zero, one}}};
  for (std::size_t k = 0; k < n; ++k) m = mul(P(w.s[k]), m);
  if (red) std::swap(m[0], m[2]);  // J M: swap rows x and z
  const RationalPoly tr = m[0][0] + m[1][1] + m[2][2];
  const RationalPoly minors = m[0][0] * m[1][1] - m[0][1] * m[1][0] + m[0][0] * m[2][2] - m[0][2] * m[2][0] +
                              m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const RationalPoly det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return {rational(-1) * tr, minors, rational(-1) * det};
}

RationalPoly discriminant(const CharPoly& chi) {
  const RationalPoly& a = chi.c2;
  const RationalPoly& b = chi.c1;
  const RationalPoly& c = chi.c0;
  // Depressed cubic: p = b - a^2/3, q = 2a^3/27 - ab/3 + c.
  const RationalPoly p = b - rational(1, 3) * a * a;
  const RationalPoly q = rational(2, 27) * a * a * a - rational(1, 3) * a * b + c;
  return rational(1, 4) * q * q + rational(1, 27) * p * p * p;
}

}  // namespace btob::patterns
