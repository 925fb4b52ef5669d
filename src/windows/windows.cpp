// SPDX-License-Identifier: GPL-3.0-or-later
// Windows of stability: Q_n exact, its smallest positive root in MPFR, exact certificates, r_crit,2.
#include "windows/windows.hpp"
#include "core/cancel.hpp"
#include "core/request.hpp"

#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <numeric>
#include <stdexcept>

namespace btob::windows {

void validate_n(long n, long min_n, const char* field) {
  // n: the exact Q_n has degree 4n and coefficients of ~n digits; one bound costs ~0.4 s at n = 400,
  // ~2.3 s at n = 800 (growing like n^2.4), so a few minutes at n = 5000 and hours beyond.  m (thin
  // stripes) is cheap: up to 100000.
  const bool is_n = std::string(field) == "n";
  const long max_n = is_n ? 5000 : 100000;
  if (n < min_n || n > max_n)
    throw core::InvalidField(field, std::to_string(n),
                             "an integer in " + std::to_string(min_n) + ".." + std::to_string(max_n) +
                                 (is_n ? " (Q_n costs minutes at n = 5000)" : ""));
}

void validate_digits(long digits, const char* field) {
  // Below 10 digits the double overlays would be coarser than the paper's table; above 10000 the
  // polynomial evaluations take minutes per root for no reader.
  if (digits < 10 || digits > 10000) throw core::InvalidField(field, std::to_string(digits), "10..10000");
}

namespace {

// MPFR working precision for the scope of an object (process-wide in Boost 1.74: core::MpfrDigits).
using ScopedDigits = core::MpfrDigits;

using Mat = std::array<IntPoly, 9>;  // row-major 3x3 matrix of integer polynomials

Mat mul(const Mat& x, const Mat& y) {
  Mat z;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      IntPoly s;
      for (int k = 0; k < 3; ++k) s = s + x[3 * i + k] * y[3 * k + j];
      z[3 * i + j] = std::move(s);
    }
  return z;
}

// 4 B A with integer polynomial entries: 2A = [[-2r,0,0],[1+r,2,0],[0,0,2]],
// 2B = [[2,1+r,0],[0,-2r,0],[0,1+r,2]] (eq. 2.7 with alpha = (1+r)/2).
Mat four_BA() {
  const IntPoly zero, two = IntPoly::constant(2), one_r = IntPoly::x_plus(1);
  const IntPoly m2r({mpz_class(0), mpz_class(-2)});
  const Mat A2{m2r, zero, zero, one_r, two, zero, zero, zero, two};
  const Mat B2{two, one_r, zero, zero, m2r, zero, zero, one_r, two};
  return mul(B2, A2);
}

// Numerators T_n = tr(J (4BA)^n), so P_n = T_n / 4^n.  Cached for all n computed so far (a cancelled call leaves
// the powers computed until then, each complete).
IntPoly trace_numerator(int n, const core::CancelToken* cancel = nullptr) {
  static std::mutex mu;
  static std::vector<IntPoly> traces;  // traces[k] = T_{k+1}
  static Mat power;                    // (4BA)^(traces.size())
  static const Mat base = four_BA();
  std::lock_guard<std::mutex> lock(mu);
  if (traces.empty()) power = base, traces.push_back(power[6] + power[4] + power[2]);
  while (static_cast<int>(traces.size()) < n) {
    core::check_cancel(cancel);
    power = mul(base, power);
    traces.push_back(power[6] + power[4] + power[2]);  // tr(J M) = M_31 + M_22 + M_13
  }
  return traces[static_cast<std::size_t>(n - 1)];
}

mpz_class pow2(unsigned long k) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 2, k);
  return p;
}

RationalPoly reduce(IntPoly num, mpz_class den) {
  const mpz_class g = gcd(num.content(), den);
  if (g > 1) {
    std::vector<mpz_class> c(num.coefficients());
    for (auto& v : c) mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), g.get_mpz_t());
    num = IntPoly(std::move(c));
    mpz_divexact(den.get_mpz_t(), den.get_mpz_t(), g.get_mpz_t());
  }
  return {std::move(num), std::move(den)};
}

std::string rational_text(const mpq_class& q) { return q.get_den() == 1 ? q.get_num().get_str() : q.get_str(); }

}  // namespace

mpq_class RationalPoly::coefficient(int i) const {
  if (i < 0 || i > degree()) return 0;
  mpq_class q(numerator[static_cast<std::size_t>(i)], denominator);
  q.canonicalize();
  return q;
}

std::string RationalPoly::developed(const char* var) const {
  if (numerator.is_zero()) return "0";
  std::string s;
  for (int k = degree(); k >= 0; --k) {
    const mpq_class q = coefficient(k);
    if (q == 0) continue;
    const mpq_class a = abs(q);
    if (s.empty()) s += q < 0 ? "-" : "";
    else s += q < 0 ? " - " : " + ";
    if (a != 1 || k == 0) s += rational_text(a) + (k >= 1 && a.get_den() != 1 ? " " : "");
    if (k >= 1) s += var;
    if (k >= 2) s += "^" + std::to_string(k);
  }
  return s;
}

std::string Factorised::to_string(const char* var) const {
  std::string s = "1/" + denominator.get_str();
  const std::string v(var);
  const int both = std::min(plus_one, minus_one);
  auto power = [](const std::string& base, int k) { return k == 1 ? base : base + "^" + std::to_string(k); };
  if (both > 0) s += " " + power("(" + v + "^2-1)", both);
  if (plus_one > both) s += " " + power("(" + v + "+1)", plus_one - both);
  if (minus_one > both) s += " " + power("(" + v + "-1)", minus_one - both);
  s += " (" + cofactor.to_string(var) + ")";
  return s;
}

RationalPoly trace_polynomial(int n) {
  validate_n(n);
  return reduce(trace_numerator(n), pow2(2 * static_cast<unsigned long>(n)));
}

namespace {
// a * b as IntPoly's operator*, one row of a at a time with a poll between rows (the product of two degree-2n
// polynomials with 4n-bit coefficients is the longest single step of a window at large n: seconds at n = 1000).
IntPoly product(const IntPoly& a, const IntPoly& b, const core::CancelToken* cancel) {
  if (a.is_zero() || b.is_zero()) return {};
  const auto& ac = a.coefficients();
  const auto& bc = b.coefficients();
  std::vector<mpz_class> c(ac.size() + bc.size() - 1);
  for (std::size_t i = 0; i < ac.size(); ++i) {
    core::check_cancel(cancel);
    if (ac[i] == 0) continue;
    for (std::size_t j = 0; j < bc.size(); ++j) mpz_addmul(c[i + j].get_mpz_t(), ac[i].get_mpz_t(), bc[j].get_mpz_t());
  }
  return IntPoly(std::move(c));
}
}  // namespace

RationalPoly window_polynomial(int n, const core::CancelToken* cancel) {
  validate_n(n);
  // P_n = T/4^n with deg T <= 2n, r^(2n) P_n(1/r) = rev_2n(T)/4^n, so
  // Q_n = (T(r) rev_2n(T)(r) - 16^n r^(2n)) / 16^n   (eq. 4.3).
  const IntPoly t = trace_numerator(n, cancel);
  const unsigned long un = static_cast<unsigned long>(n);
  const IntPoly prod = product(t, t.reversed(2 * n), cancel);
  const IntPoly shift = IntPoly::constant(pow2(4 * un)).shifted(2 * n);
  return reduce(prod - shift, pow2(4 * un));
}

Factorised factorise(const RationalPoly& q) {
  Factorised f;
  IntPoly c = q.numerator;
  f.plus_one = c.divide_out(-1);
  f.minus_one = c.divide_out(1);
  // Pull the sign and the content into the cofactor so that it reads like Table B.2 (positive leading
  // coefficient, integer coefficients, 1/2^k in front).
  f.cofactor = c;
  f.denominator = q.denominator;
  return f;
}

namespace {

// Horner in MPFR with Higham's running error bound: |computed - exact| <= err (up to a few ulps of err).
struct Eval {
  mpfr_float value, error;
};
Eval horner(const std::vector<mpfr_float>& c, const mpfr_float& x) {
  mpfr_float v = c.back();
  mpfr_float mu = abs(v) / 2;
  const mpfr_float ax = abs(x);
  for (std::size_t k = c.size() - 1; k-- > 0;) {
    v = v * x + c[k];
    mu = mu * ax + abs(v);
  }
  const mpfr_float u = std::numeric_limits<mpfr_float>::epsilon();
  return {v, u * (2 * mu - abs(v))};
}

std::vector<mpfr_float> to_mpfr(const RationalPoly& q) {
  std::vector<mpfr_float> c;
  c.reserve(q.numerator.coefficients().size());
  for (const auto& v : q.numerator.coefficients()) c.emplace_back(mpfr_float(v.get_mpz_t()));
  return c;
}

mpfr_float three_particle_threshold() { return 7 - 4 * sqrt(mpfr_float(3)); }  // Section 4, 7 - 4 sqrt(3)

mpfr_float r_crit2_here(int n) {
  const mpfr_float c = cos(boost::math::constants::pi<mpfr_float>() / (2 * n));
  const mpfr_float t = 2 * c - sqrt(4 * c * c - 1);
  return t * t;  // eq. (4.6)
}

}  // namespace

mpfr_float r_crit2(int n, int digits, int guard) {
  validate_n(n, 2);
  validate_digits(digits);
  ScopedDigits sd(digits + guard);  // guard digits (10 by default): cos/sqrt of well-conditioned arguments
  mpfr_float v = r_crit2_here(n);
  v.precision(static_cast<unsigned>(digits + guard));
  return v;
}

namespace {

// The smallest positive root of Q_n by bracketing (TOMS 748) at a working precision raised until the sign
// change around the result is reliable.
mpfr_float lower_bound_by_bracketing(const RationalPoly& q, int n, int decimals, const core::CancelToken* cancel) {
  // Q_n's integer numerator has coefficients up to ~2^(4n) times a polynomial factor; Horner at r ~ 0.07
  // cancels up to that many digits in the worst case.  Start with 20 guard digits and double them until
  // the running error bound shows a reliable sign change across the result.
  unsigned guard = 20;
  for (int attempt = 0; attempt < 12; ++attempt, guard *= 2) {
    const unsigned work = static_cast<unsigned>(decimals) + guard;
    ScopedDigits sd(static_cast<int>(work));
    const std::vector<mpfr_float> c = to_mpfr(q);
    auto f = [&](const mpfr_float& x) {
      core::check_cancel(cancel);
      return horner(c, x).value;
    };
    // Bracket: Q_n > 0 at the three-particle threshold 7 - 4 sqrt(3) (there BA has a double eigenvalue)
    // and changes sign once before r_crit,2(n) (checked for n = 1..300 on a 400-point grid and by the
    // Sturm certificates).  n = 1: Q_1 = (r+1)^2 (r^2 - 6r + 1)/16, root 3 - 2 sqrt 2 < 1/2.
    mpfr_float lo = three_particle_threshold();
    mpfr_float hi = n >= 2 ? r_crit2_here(n) : mpfr_float(1) / 2;
    mpfr_float flo = f(lo), fhi = f(hi);
    const Eval elo = horner(c, lo), ehi = horner(c, hi);
    if (!(abs(elo.value) > elo.error && abs(ehi.value) > ehi.error)) continue;  // signs not reliable yet
    if (!(flo > 0 && fhi < 0)) {
      // Should not happen (see above); scan from the left for the first sign change to stay correct.
      const int steps = 64;
      const mpfr_float a0 = lo, width = hi - lo;
      bool found = false;
      mpfr_float x0 = a0, f0 = f(a0);
      for (int i = 1; i <= steps && !found; ++i) {
        mpfr_float x1 = a0 + width * i / steps, f1 = f(x1);
        if (sign(f0) * sign(f1) < 0) lo = x0, hi = x1, flo = f0, fhi = f1, found = true;
        x0 = x1, f0 = f1;
      }
      if (!found) continue;  // the signs are noise at this precision (Q_n is tiny near 7 - 4 sqrt 3): more digits
    }
    const int target_bits = static_cast<int>((decimals + 6) * 3.33) + 8;  // 6 decimals beyond the request
    std::uintmax_t max_iter = 500;
    auto [a, b] = boost::math::tools::toms748_solve(
        f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<mpfr_float>(target_bits), max_iter);
    mpfr_float x = (a + b) / 2;
    // Reliability: at x -+ 10^-(D+3) the signs must be opposite and larger than the error bound.
    const mpfr_float delta = pow(mpfr_float(10), -(decimals + 3));
    const Eval el = horner(c, x - delta), er = horner(c, x + delta);
    if (abs(el.value) > el.error && abs(er.value) > er.error && sign(el.value) * sign(er.value) < 0) return x;
  }
  throw std::domain_error("digits: no reliable root of Q_" + std::to_string(n) + " at " + std::to_string(decimals) +
                          " digits after raising the working precision; ask for fewer digits or a smaller n");
}

// Horner for p and p' together (no error bound).
std::pair<mpfr_float, mpfr_float> horner_with_derivative(const std::vector<mpfr_float>& c, const mpfr_float& x) {
  mpfr_float v = c.back(), dv = 0;
  for (std::size_t k = c.size() - 1; k-- > 0;) {
    dv = dv * x + v;
    v = v * x + c[k];
  }
  return {v, dv};
}

// True when Q_n changes sign reliably (beyond Horner's running error bound) across x -+ 10^-(D+3).
bool reliable_root(const std::vector<mpfr_float>& c, const mpfr_float& x, int decimals) {
  const mpfr_float delta = pow(mpfr_float(10), -(decimals + 3));
  const Eval el = horner(c, x - delta), er = horner(c, x + delta);
  return abs(el.value) > el.error && abs(er.value) > er.error && sign(el.value) * sign(er.value) < 0;
}

// Many decimals: Newton's iteration from the root to 30 decimals, at a working precision chosen once from
// Horner's running error bound there (digits lost ~ log10(2 mu / |x Q'(x)|)), then the same reliability
// check as the bracketing.  Returns false (and the caller brackets) when it does not converge near the seed.
bool lower_bound_by_newton(const RationalPoly& q, int n, int decimals, mpfr_float& out,
                           const core::CancelToken* cancel) {
  const int seed_decimals = 30;
  const mpfr_float seed = lower_bound_by_bracketing(q, n, seed_decimals, cancel);
  int lost = 0;
  {
    ScopedDigits sd(static_cast<int>(seed.precision()));
    const std::vector<mpfr_float> c = to_mpfr(q);
    const Eval e = horner(c, seed);
    const mpfr_float slope = abs(horner_with_derivative(c, seed).second * seed);
    if (slope == 0) return false;
    lost = std::max(0, static_cast<int>(ceil(log10(2 * e.error / std::numeric_limits<mpfr_float>::epsilon() / slope))));
  }
  const int work = decimals + 6 + lost + 10;  // 6 decimals beyond the request (as the bracketing), 10 guard
  ScopedDigits sd(work);
  const std::vector<mpfr_float> c = to_mpfr(q);
  mpfr_float x = seed;
  x.precision(static_cast<unsigned>(work));
  const mpfr_float stop = pow(mpfr_float(10), -(decimals + 8)), near = pow(mpfr_float(10), -(seed_decimals - 5));
  for (int it = 0; it < 40; ++it) {
    core::check_cancel(cancel);
    const auto [v, dv] = horner_with_derivative(c, x);
    if (dv == 0) return false;
    const mpfr_float dx = v / dv;
    x -= dx;
    if (abs(x - seed) > near) return false;  // left the seed's neighbourhood
    if (abs(dx) < stop) break;               // quadratic convergence: x is now good to ~2x as many decimals
  }
  if (!reliable_root(c, x, decimals)) return false;
  out = x;
  return true;
}

}  // namespace

mpfr_float window_lower_bound(int n, int decimals, const core::CancelToken* cancel) {
  validate_n(n);
  validate_digits(decimals, "digits");
  const RationalPoly q = window_polynomial(n, cancel);
  mpfr_float x;
  if (decimals > 40 && lower_bound_by_newton(q, n, decimals, x, cancel)) return x;
  return lower_bound_by_bracketing(q, n, decimals, cancel);
}

Certificate certify_interval(int n, const mpq_class& a_in, const mpq_class& b_in, const core::CancelToken* cancel) {
  Certificate cert;
  cert.n = n;
  cert.a = a_in;
  cert.b = b_in;
  cert.a.canonicalize();
  cert.b.canonicalize();
  if (!(cert.a > 0 && cert.a < cert.b)) return cert;  // invalid, counts stay -1
  const RationalPoly q = window_polynomial(n, cancel);
  cert.sign_a = q.numerator.sign_at(cert.a);
  cert.sign_b = q.numerator.sign_at(cert.b);
  // The Sturm counts run on the palindromic cofactor reduced to s = r + 1/r (degree about 2n instead of
  // 4n): r in (0, a] <-> s in [a + 1/a, inf), r in (a, b) <-> s in (b + 1/b, a + 1/a).  The factors
  // (r +- 1) have no root in (0, 1), so the cofactor has the same roots there as Q_n.
  if (cert.sign_a == 0 || cert.sign_b == 0 || cert.sign_a * cert.sign_b > 0) return cert;  // invalid, counts stay -1
  core::check_cancel(cancel);
  Factorised f = factorise(q);
  core::check_cancel(cancel);
  IntPoly p = f.cofactor;
  IntPoly reduced_poly;
  try {
    reduced_poly = palindromic_reduce(p);
  } catch (const std::invalid_argument&) {
    reduced_poly = IntPoly();
  }
  // Counts of distinct real roots: Descartes' rule after Moebius transforms (one or a few Taylor shifts), the
  // Sturm sequence only when that cannot decide (root_count).
  std::vector<IntPoly> seq;
  if (!reduced_poly.is_zero()) {
    const mpq_class sa = cert.a + 1 / cert.a, sb = cert.b + 1 / cert.b;
    cert.roots_0_a = root_count_to_infinity(reduced_poly, sa, &seq, cancel);
    cert.roots_a_b = root_count(reduced_poly, sb, sa, &seq, cancel);
  } else {
    // Not palindromic of even degree (never seen): count on Q_n itself.
    cert.roots_0_a = root_count(q.numerator, mpq_class(0), cert.a, &seq, cancel);
    cert.roots_a_b = root_count(q.numerator, cert.a, cert.b, &seq, cancel);
  }
  return cert;
}

Certificate certify_lower_bound(int n, int decimals, const core::CancelToken* cancel) {
  const mpfr_float x = window_lower_bound(n, decimals, cancel);
  mpz_class scale;
  mpz_ui_pow_ui(scale.get_mpz_t(), 10, static_cast<unsigned long>(decimals));
  // k = floor(x 10^D): the D-decimal truncation of x.
  mpz_class k;
  {
    ScopedDigits sd(static_cast<int>(x.precision()));
    const mpfr_float t = floor(x * mpfr_float(scale.get_mpz_t()));
    mpfr_get_z(k.get_mpz_t(), t.backend().data(), MPFR_RNDN);
  }
  Certificate cert = certify_interval(n, mpq_class(k, scale), mpq_class(k + 1, scale), cancel);
  cert.decimals = decimals;
  return cert;
}

std::vector<Threshold> thresholds(int digits) {
  validate_digits(digits);
  ScopedDigits sd(digits + 10);  // 10 guard digits for the subtractions below
  const mpfr_float three(3), two(2), six(6), four(4);
  return {
      {"three_particle_collapse", "7-4*sqrt(3)", 7 - 4 * sqrt(three)},
      {"end_of_window_2", "3-2*sqrt(2)", 3 - 2 * sqrt(two)},
      {"end_of_window_3", "5-2*sqrt(6)", 5 - 2 * sqrt(six)},
      {"no_four_particle_collapse", "2^(2/3)-1", cbrt(four) - 1},
  };
}

std::vector<Stripe> thin_stripes(int max_m, int digits) {
  validate_n(max_m, 1, "m");
  validate_digits(digits);
  ScopedDigits sd(digits + 10);  // 10 guard digits: sqrt(xi + xi^2) near xi = 0 loses few
  const mpfr_float pi = boost::math::constants::pi<mpfr_float>();
  std::vector<Stripe> out;
  for (int m = 1; m <= max_m; ++m)
    for (int l = 1; 2 * l <= m; ++l) {
      if (std::gcd(l, m) != 1 || 4 * l <= m) continue;  // reduced, 1/4 < l/m <= 1/2
      const mpfr_float xi = cos(pi - 2 * pi * l / m);
      out.push_back({l, m, 1 + 2 * xi - 2 * sqrt(xi + xi * xi)});  // eq. (6.3)
    }
  std::sort(out.begin(), out.end(), [](const Stripe& a, const Stripe& b) { return a.value < b.value; });
  return out;
}

std::string fixed(const mpfr_float& x, int decimals) {
  return x.str(static_cast<std::streamsize>(decimals), std::ios_base::fixed);
}

}  // namespace btob::windows
