// SPDX-License-Identifier: GPL-3.0-or-later
// Exact integer polynomials: arithmetic, exact signs at rationals, primitive Sturm sequences.
#include "windows/polynomial.hpp"
#include "core/cancel.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace btob::windows {

IntPoly::IntPoly(std::vector<mpz_class> coefficients) : c_(std::move(coefficients)) { trim(); }

IntPoly IntPoly::constant(const mpz_class& c) { return IntPoly({c}); }
IntPoly IntPoly::x_plus(long a) { return IntPoly({mpz_class(a), mpz_class(1)}); }

void IntPoly::trim() {
  while (!c_.empty() && c_.back() == 0) c_.pop_back();
}

IntPoly operator+(const IntPoly& a, const IntPoly& b) {
  std::vector<mpz_class> c(std::max(a.c_.size(), b.c_.size()));
  for (std::size_t i = 0; i < a.c_.size(); ++i) c[i] += a.c_[i];
  for (std::size_t i = 0; i < b.c_.size(); ++i) c[i] += b.c_[i];
  return IntPoly(std::move(c));
}

IntPoly operator-(const IntPoly& a, const IntPoly& b) {
  std::vector<mpz_class> c(std::max(a.c_.size(), b.c_.size()));
  for (std::size_t i = 0; i < a.c_.size(); ++i) c[i] += a.c_[i];
  for (std::size_t i = 0; i < b.c_.size(); ++i) c[i] -= b.c_[i];
  return IntPoly(std::move(c));
}

IntPoly operator*(const IntPoly& a, const IntPoly& b) {
  if (a.is_zero() || b.is_zero()) return {};
  std::vector<mpz_class> c(a.c_.size() + b.c_.size() - 1);
  for (std::size_t i = 0; i < a.c_.size(); ++i) {
    if (a.c_[i] == 0) continue;
    for (std::size_t j = 0; j < b.c_.size(); ++j)
      mpz_addmul(c[i + j].get_mpz_t(), a.c_[i].get_mpz_t(), b.c_[j].get_mpz_t());
  }
  return IntPoly(std::move(c));
}

IntPoly operator*(const mpz_class& k, const IntPoly& a) {
  std::vector<mpz_class> c(a.c_);
  for (auto& v : c) v *= k;
  return IntPoly(std::move(c));
}

IntPoly IntPoly::derivative() const {
  if (c_.size() <= 1) return {};
  std::vector<mpz_class> d(c_.size() - 1);
  for (std::size_t i = 1; i < c_.size(); ++i) d[i - 1] = c_[i] * static_cast<unsigned long>(i);
  return IntPoly(std::move(d));
}

IntPoly IntPoly::reversed(int as_degree) const {
  if (as_degree < degree())
    throw std::invalid_argument("reversed: got degree " + std::to_string(as_degree) + ", expected at least " +
                                std::to_string(degree()));
  std::vector<mpz_class> c(static_cast<std::size_t>(as_degree) + 1);
  for (std::size_t i = 0; i < c_.size(); ++i) c[static_cast<std::size_t>(as_degree) - i] = c_[i];
  return IntPoly(std::move(c));
}

IntPoly IntPoly::shifted(int k) const {
  if (is_zero()) return {};
  std::vector<mpz_class> c(static_cast<std::size_t>(k));
  c.insert(c.end(), c_.begin(), c_.end());
  return IntPoly(std::move(c));
}

mpz_class IntPoly::content() const {
  mpz_class g = 0;
  for (const auto& v : c_) {
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v.get_mpz_t());
    if (g == 1) break;
  }
  return g;
}

IntPoly IntPoly::primitive() const {
  const mpz_class g = content();
  if (g == 0 || g == 1) return *this;
  std::vector<mpz_class> c(c_);
  for (auto& v : c) mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), g.get_mpz_t());
  return IntPoly(std::move(c));
}

int IntPoly::divide_out(long root) {
  if (root != 1 && root != -1)
    throw std::invalid_argument("divide_out: got root " + std::to_string(root) + ", expected +1 or -1");
  int count = 0;
  while (degree() >= 1 && sign_at(mpz_class(root), mpz_class(1)) == 0) {
    // Synthetic division by (x - root): q_{k-1} = c_k + root * q_k, from the top.
    const std::size_t d = c_.size() - 1;
    std::vector<mpz_class> q(d);
    mpz_class carry = 0;
    for (std::size_t k = d; k >= 1; --k) {
      carry = c_[k] + root * carry;
      q[k - 1] = carry;
    }
    c_ = std::move(q);
    trim();
    ++count;
  }
  return count;
}

int IntPoly::sign_at(const mpz_class& num, const mpz_class& den) const {
  if (c_.empty()) return 0;
  // Horner on the homogenised form: v = c_d; v = v*num + c_k*den^(d-k).
  mpz_class v = c_.back(), dpow = 1;
  for (std::size_t k = c_.size() - 1; k-- > 0;) {
    dpow *= den;
    v *= num;
    mpz_addmul(v.get_mpz_t(), c_[k].get_mpz_t(), dpow.get_mpz_t());
  }
  return sgn(v);
}

std::string IntPoly::to_string(const char* var) const {
  if (c_.empty()) return "0";
  std::string s;
  for (std::size_t k = c_.size(); k-- > 0;) {
    const mpz_class& v = c_[k];
    if (v == 0) continue;
    const bool neg = v < 0;
    const mpz_class a = abs(v);
    if (s.empty()) s += neg ? "-" : "";
    else s += neg ? " - " : " + ";
    if (a != 1 || k == 0) s += a.get_str();
    if (k >= 1) s += var;
    if (k >= 2) s += "^" + std::to_string(k);
  }
  return s;
}

IntPoly pseudo_remainder(const IntPoly& a, const IntPoly& b) {
  if (b.is_zero()) throw std::invalid_argument("pseudo_remainder: divisor is the zero polynomial");
  if (a.degree() < b.degree()) return a;
  std::vector<mpz_class> r(a.coefficients());
  const auto& bc = b.coefficients();
  const mpz_class& lb = b.leading();
  const std::size_t db = static_cast<std::size_t>(b.degree());
  // Exactly delta + 1 steps r <- lb*r - lc(r) x^(k - deg b) b for k = deg a .. deg b, so the factor
  // in front of a is lb^(delta+1) (the classical definition, also when a leading entry is already 0).
  for (std::size_t k = static_cast<std::size_t>(a.degree()) + 1; k-- > db;) {
    const mpz_class lr = r[k];
    for (std::size_t i = 0; i < k; ++i) r[i] *= lb;
    if (lr != 0)
      for (std::size_t j = 0; j < db; ++j) mpz_submul(r[k - db + j].get_mpz_t(), lr.get_mpz_t(), bc[j].get_mpz_t());
    r[k] = 0;  // lb*lr - lr*lb
  }
  return IntPoly(std::move(r));
}

std::vector<IntPoly> sturm_sequence(const IntPoly& p, const core::CancelToken* cancel) {
  std::vector<IntPoly> seq;
  if (p.is_zero()) return seq;
  seq.push_back(p.primitive());
  IntPoly d = p.derivative();
  if (d.is_zero()) return seq;
  seq.push_back(d.primitive());
  while (true) {
    core::check_cancel(cancel);
    const IntPoly& a = seq[seq.size() - 2];
    const IntPoly& b = seq.back();
    IntPoly pr = pseudo_remainder(a, b);
    if (pr.is_zero()) break;
    // prem = lc(b)^(delta+1) * rem: the classical term -rem has the sign of -prem * sign(lc(b))^(delta+1).
    const int delta = a.degree() - b.degree();
    const bool flip = !(sgn(b.leading()) < 0 && (delta + 1) % 2 == 1);  // true -> negate prem
    IntPoly next = pr.primitive();
    if (flip) next = mpz_class(-1) * next;
    seq.push_back(std::move(next));
  }
  return seq;
}

namespace {
long variations(const std::vector<int>& signs) {
  long v = 0;
  int last = 0;
  for (int s : signs) {
    if (s == 0) continue;
    if (last != 0 && s != last) ++v;
    last = s;
  }
  return v;
}
std::vector<int> signs_at(const std::vector<IntPoly>& seq, const mpq_class& x) {
  std::vector<int> s;
  s.reserve(seq.size());
  for (const auto& q : seq) s.push_back(q.sign_at(x));
  return s;
}
}  // namespace

long sturm_count(const std::vector<IntPoly>& seq, const mpq_class& a, const mpq_class& b) {
  if (seq.empty()) throw std::invalid_argument("sturm_count: empty sequence");
  if (!(a < b))
    throw std::invalid_argument("sturm_count: expected a < b, got a = " + a.get_str() + ", b = " + b.get_str());
  if (seq.front().sign_at(a) == 0 || seq.front().sign_at(b) == 0)
    throw std::domain_error("sturm_count: an endpoint is a root of the polynomial");
  return variations(signs_at(seq, a)) - variations(signs_at(seq, b));
}

long sturm_count_to_infinity(const std::vector<IntPoly>& seq, const mpq_class& a) {
  if (seq.empty()) throw std::invalid_argument("sturm_count: empty sequence");
  if (seq.front().sign_at(a) == 0) throw std::domain_error("sturm_count: the endpoint is a root of the polynomial");
  std::vector<int> inf;
  for (const auto& q : seq) inf.push_back(sgn(q.leading()));
  return variations(signs_at(seq, a)) - variations(inf);
}

namespace {
using Coeffs = std::vector<mpz_class>;

// c(x) -> c(x + 1) in place (Horner-like O(d^2) additions).
void taylor_shift_one(Coeffs& c) {
  const std::size_t n = c.size();
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j-- > i;) c[j] += c[j + 1];
}

// c(x) -> c(x + u) in place, u an integer.
void taylor_shift(Coeffs& c, const mpz_class& u) {
  if (u == 0) return;
  if (u == 1) return taylor_shift_one(c);
  const std::size_t n = c.size();
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j-- > i;) mpz_addmul(c[j].get_mpz_t(), c[j + 1].get_mpz_t(), u.get_mpz_t());
}

// c(x) -> c(k x) for k > 0 (c_i k^i), then divided by the content.
void scale_and_reduce(Coeffs& c, const mpz_class& k) {
  mpz_class kp = 1;
  for (auto& v : c) v *= kp, kp *= k;
  IntPoly p(std::move(c));
  c = p.primitive().coefficients();
}

long sign_variations(const Coeffs& c) {
  std::vector<int> s;
  s.reserve(c.size());
  for (const auto& x : c) s.push_back(sgn(x));
  return variations(s);
}

// Descartes' bound for the roots of g in (0, 1): variations of (1 + t)^d g(1/(1 + t)).
long variations_on_unit(const Coeffs& g) {
  Coeffs r(g.rbegin(), g.rend());
  taylor_shift_one(r);
  return sign_variations(r);
}

// Distinct roots of g in (0, 1) by bisection: g_L(y) = 2^d g(y/2) on (0, 1/2), g_R = g_L(y + 1) on (1/2, 1).
long vca_unit(const Coeffs& g, int depth, const core::CancelToken* cancel) {
  core::check_cancel(cancel);
  const long v = variations_on_unit(g);
  if (v <= 1) return v;
  if (depth <= 0) return -1;
  const std::size_t d = g.size() - 1;
  Coeffs left(g);
  for (std::size_t i = 0; i < d; ++i) mpz_mul_2exp(left[i].get_mpz_t(), left[i].get_mpz_t(), d - i);
  Coeffs right(left);
  taylor_shift_one(right);
  const long at_midpoint = right[0] == 0 ? 1 : 0;  // the halves are open: a root at 1/2 is counted here
  const long l = vca_unit(left, depth - 1, cancel);
  if (l < 0) return -1;
  const long r = vca_unit(right, depth - 1, cancel);
  return r < 0 ? -1 : l + r + at_midpoint;
}

// D^d p((u + z)/D) as coefficients in z (D > 0): roots of p above u/D <-> positive roots in z.
Coeffs shifted_to(const IntPoly& p, const mpz_class& u, const mpz_class& den) {
  Coeffs c(p.coefficients());
  mpz_class dp = 1;  // h(z) = D^d p(z/D): c_i D^(d-i)
  for (std::size_t i = c.size(); i-- > 0;) c[i] *= dp, dp *= den;
  taylor_shift(c, u);
  return c;
}

void check_interval(const IntPoly& p, const mpq_class& a, const mpq_class& b) {
  if (!(a < b))
    throw std::invalid_argument("descartes_count: expected a < b, got a = " + a.get_str() + ", b = " + b.get_str());
  if (p.is_zero()) throw std::invalid_argument("descartes_count: the zero polynomial");
}

// A power of two B = 2^e > |every root of p| (Fujiwara: |z| <= 2 max_k |c_(d-k) / c_d|^(1/k), each ratio
// bounded by 2^(bits(c_(d-k)) - bits(c_d) + 1)); returns e.
long root_bound_exponent(const IntPoly& p) {
  const long d = p.degree();
  const long lead_bits = static_cast<long>(mpz_sizeinbase(p.leading().get_mpz_t(), 2));
  long e = 0;
  for (long k = 1; k <= d; ++k) {
    const mpz_class& c = p[static_cast<std::size_t>(d - k)];
    if (c == 0) continue;
    const long diff = static_cast<long>(mpz_sizeinbase(c.get_mpz_t(), 2)) - lead_bits + 1;
    if (diff > 0) e = std::max(e, (diff + k - 1) / k);
  }
  return e + 2;  // 2 * 2^e, and one more so that B is strictly above the bound
}
}  // namespace

long descartes_count(const IntPoly& p, const mpq_class& a_in, const mpq_class& b_in, int max_depth,
                     const core::CancelToken* cancel) {
  mpq_class a = a_in, b = b_in;
  a.canonicalize();
  b.canonicalize();
  check_interval(p, a, b);
  if (p.degree() == 0) return 0;
  // Common denominator D: a = u/D, b = v/D; g(y) = D^d p((u + (v - u) y)/D) for y in (0, 1).
  mpz_class den;
  mpz_lcm(den.get_mpz_t(), a.get_den().get_mpz_t(), b.get_den().get_mpz_t());
  const mpz_class u = a.get_num() * (den / a.get_den()), v = b.get_num() * (den / b.get_den());
  Coeffs g = shifted_to(p, u, den);
  scale_and_reduce(g, v - u);
  return vca_unit(g, max_depth, cancel);
}

long descartes_count_to_infinity(const IntPoly& p, const mpq_class& a_in, int max_depth,
                                 const core::CancelToken* cancel) {
  mpq_class a = a_in;
  a.canonicalize();
  if (p.is_zero()) throw std::invalid_argument("descartes_count: the zero polynomial");
  if (p.degree() == 0) return 0;
  const long v = sign_variations(shifted_to(p, a.get_num(), a.get_den()));  // x = a + z/D, z > 0
  if (v <= 1) return v;
  const long e = root_bound_exponent(p);
  mpz_class bound;
  mpz_ui_pow_ui(bound.get_mpz_t(), 2, static_cast<unsigned long>(e));
  return a < bound ? descartes_count(p, a, mpq_class(bound), max_depth + static_cast<int>(e), cancel) : 0;
}

long root_count(const IntPoly& p, const mpq_class& a, const mpq_class& b, std::vector<IntPoly>* seq_cache,
                const core::CancelToken* cancel) {
  if (p.sign_at(a) == 0 || p.sign_at(b) == 0)
    throw std::domain_error("root_count: an endpoint is a root of the polynomial");
  const long d = descartes_count(p, a, b, 64, cancel);
  if (d >= 0) return d;
  if (seq_cache->empty()) *seq_cache = sturm_sequence(p, cancel);
  return sturm_count(*seq_cache, a, b);
}

long root_count_to_infinity(const IntPoly& p, const mpq_class& a, std::vector<IntPoly>* seq_cache,
                            const core::CancelToken* cancel) {
  if (p.sign_at(a) == 0) throw std::domain_error("root_count: the endpoint is a root of the polynomial");
  const long d = descartes_count_to_infinity(p, a, 64, cancel);
  if (d >= 0) return d;
  if (seq_cache->empty()) *seq_cache = sturm_sequence(p, cancel);
  return sturm_count_to_infinity(*seq_cache, a);
}

IntPoly palindromic_reduce(const IntPoly& p) {
  const int d = p.degree();
  if (d < 0 || d % 2 != 0)
    throw std::invalid_argument("palindromic_reduce: got degree " + std::to_string(d) + ", expected an even degree");
  for (int i = 0; i <= d; ++i)
    if (p[static_cast<std::size_t>(i)] != p[static_cast<std::size_t>(d - i)])
      throw std::invalid_argument("palindromic_reduce: coefficients are not palindromic");
  const int m = d / 2;
  // x^-m p(x) = c_m + sum_{k>=1} c_{m+k} (x^k + x^-k), and x^k + x^-k = D_k(s), s = x + 1/x, with the
  // Dickson recurrence D_0 = 2, D_1 = s, D_k = s D_{k-1} - D_{k-2}.
  IntPoly r = IntPoly::constant(p[static_cast<std::size_t>(m)]);
  IntPoly dprev = IntPoly::constant(2), dcur({mpz_class(0), mpz_class(1)});
  const IntPoly s({mpz_class(0), mpz_class(1)});
  for (int k = 1; k <= m; ++k) {
    r = r + p[static_cast<std::size_t>(m + k)] * dcur;
    IntPoly dnext = s * dcur - dprev;
    dprev = std::move(dcur);
    dcur = std::move(dnext);
  }
  return r;
}

}  // namespace btob::windows
