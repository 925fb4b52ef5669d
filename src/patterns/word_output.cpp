// What `btob pattern WORD` gives back: the text the command line prints (verdict, window CSV, characteristic
// polynomial), the result's description (NAME.h5, Python) with the decimals of every number computed in the run's
// precision and what kind of number each is (docs/reference/numbers.md), and the CSV tables of --out.
#include "patterns/requests.hpp"

#include <fmt/format.h>

#include <string>

namespace btob::patterns {
namespace {

// What a reason code of the analysis means (Section 7's conditions, in the order analyse checks them).
std::string reason_text(const std::string& reason) {
  if (reason == "complex") return "the dominant eigenvalue mu1 is complex: no dominant real direction";
  if (reason == "domain") return "the dominant eigenvector lies outside the domain x z < 0";
  if (reason == "dominance") return "the eigenvalue with a feasible eigenvector is not the dominant one";
  if (reason.rfind("feas", 0) == 0)
    return fmt::format("feasibility inequality {} fails: the orbit does not see the word's symbol there", reason.substr(4));
  if (reason == "end") return "the end of (0, 1)";
  return reason;
}

std::string verdict_text(const WordResult& res) {
  const Word& w = res.word;
  const Word& u = res.primitive;
  std::string s = fmt::format("word        {} = {} ({} symbols, {} collisions); canonical {}\n", to_paper(w), to_digits(w),
                              w.size(), collisions(w), to_paper(canonical(w)));
  if (!(u == w)) s += fmt::format("primitive   {} (the orbit of a power is the orbit of its root)\n", to_paper(u));
  s += fmt::format("r           {}\n", res.r);
  if (res.reduced) {
    const Word h{std::vector<std::uint8_t>(u.s.begin(), u.s.begin() + static_cast<long>(u.size() / 2))};
    s += fmt::format("matrix      J M_h with h = {}: M_w = (J M_h)^2 (Section 7.1)\n", to_digits(h));
  } else {
    s += fmt::format("matrix      M_w = P_{} ... P_{} (first symbol applied first)\n", int(u.s.back()), int(u.s.front()));
  }
  for (std::size_t i = 0; i < res.spectrum.size(); ++i) {
    const EigenText& e = res.spectrum[i];
    s += fmt::format("mu{}         ", i + 1);
    if (e.real) {
      s += fmt::format("{} (real, |mu|/|mu1| = {}), eigenvector ({}, {}, {})", e.re, e.ratio, e.vector[0], e.vector[1],
                       e.vector[2]);
      if (e.feasible) s += ", in the domain, all feasibility inequalities hold";
      else if (!e.in_domain) s += ", outside the domain x z < 0";
      else s += fmt::format(", in the domain, feasibility inequality {} fails (symbol {})", e.first_failure, e.failing_symbol);
    } else {
      const bool neg = !e.im.empty() && e.im[0] == '-';
      s += fmt::format("{} {} {} i (complex, |mu|/|mu1| = {})", e.re, neg ? "-" : "+", neg ? e.im.substr(1) : e.im, e.ratio);
    }
    s += "\n";
  }
  std::string why;
  if (res.outcome == outcome_name(Outcome::neutral))
    why = " (elliptic: both exponents zero within 64 eps; neither attracting nor repelling)";
  else if (res.outcome == outcome_name(Outcome::unstable))
    why = " (a saddle or a source: lambda1 > 0)";
  else if (res.outcome == outcome_name(Outcome::undecided))
    why = fmt::format(" (undecided in {}: the orbit's eigenvalue and another real one have equal moduli within 64 "
                      "eps, so lambda1 is zero within its error and the eigenvalue test cannot order them; use a "
                      "longer precision, --precision mpfr:<digits>)", res.scalar_type);
  else if (!res.reason.empty())
    why = fmt::format(" (not stable: {}: {})", res.reason, reason_text(res.reason));
  s += fmt::format("verdict     {}{}\n", res.outcome, why);
  if (res.orbit.empty()) return s;  // no periodic point: the period matrix's exponents describe no orbit
  s += fmt::format("exponents   lambda1 = {}, lambda2 = {} (the orbit's projective Lyapunov exponents along its two "
                   "tangent directions, log(|mu_j|/|mu_k|)/p for the eigenvalues mu_j other than the orbit's own mu_k, "
                   "lambda1 >= lambda2, per iteration, natural log)\n",
                   res.lyapunov2, res.lyapunov3);
  s += fmt::format("letters     {} ({} collisions)\n", res.letters, collisions(u));
  s += "orbit       k symbol x y z theta w1 w2\n";
  for (std::size_t k = 0; k < res.orbit.size(); ++k) {
    const auto& p = res.orbit[k];
    s += fmt::format("            {} {} {} {} {} {} {} {}\n", k, p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
  }
  return s;
}

// What the window's ends are: the r where the verdict changes, found on the scan grid and bisected in the run's
// precision to `window_tol`; nothing proves them (no interval arithmetic), and an interval narrower than the grid
// step may be missed (patterns::stability_set).  The bar is the bisection's and the printed digits' rounding.
core::Status window_status(const WordResult& res) {
  return core::estimated(fmt::format("verdict change on the scan grid, bisected in {} to {} (absolute, in r) and "
                                     "printed to {} significant digits",
                                     res.scalar_type, res.window_tol, res.window_digits),
                         "error bar the bisection's tolerance plus half a unit of the last printed digit, a "
                         "numerical bound without proof");
}

// The verdict's eigenvalues, exponents and orbit points: computed in the run's precision, printed to its digits.
core::Status verdict_status(const WordResult& res) {
  return core::estimated(fmt::format("eigenvalues of the period matrix (and the orbit's points and exponents from "
                                     "them) computed in {}, printed to its digits",
                                     res.scalar_type),
                         "error bar a few units of the type's last digit times the eigenvalue's condition, not "
                         "verified");
}

}  // namespace

std::string WordResult::window_csv() const {
  std::string s = "word,r_low,r_high,low_reason,high_reason,status\n";
  const std::string st = window_status(*this).kind;
  for (const auto& iv : intervals)
    s += fmt::format("{},{},{},{},{},{}\n", to_paper(word), iv[0], iv[1], iv[2], iv[3], st);
  return s;
}

core::Tables WordResult::tables() const {
  if (mode == WordRequest::Mode::window) return {{"", window_csv()}};  // NAME.csv: what the command prints
  return {};
}

// The window's ends as exact decimals (the printed digits) beside their doubles, and their reasons.
void WordResult::describe_window(core::Contents& c) const {
  const std::size_t N = r_low.size();
  const core::Status st = window_status(*this);
  c.attr("mode", std::string("window"));
  c.array("r_low", r_low, {N}, "interval", "1", "lower ends of the stability intervals in r (double view of r_low_decimal)");
  c.array("r_high", r_high, {N}, "interval", "1", "upper ends of the stability intervals in r (double view of r_high_decimal)");
  c.decimal("r_low_decimal", r_low_decimal, "interval", "1", "lower ends of the stability intervals, the digits computed", st);
  c.decimal("r_high_decimal", r_high_decimal, "interval", "1", "upper ends of the stability intervals, the digits computed", st);
  c.status_of("r_low", st);
  c.status_of("r_high", st);
  c.text("low_reason", low_reason, "interval", "reason", "what begins the interval at r_low (docs/reference/numbers.md)");
  c.text("high_reason", high_reason, "interval", "reason", "what ends the interval at r_high (docs/reference/numbers.md)");
  c.attr("window_tol", window_tol);
  c.attr("window_digits", static_cast<long>(window_digits));
}

// The verdict's numbers as decimals in the run's precision: eigenvalues, the orbit's exponents and points.
void WordResult::describe_verdict_decimals(core::Contents& c) const {
  const core::Status st = verdict_status(*this);
  c.decimal("eigen_re_decimal", eigen_re_decimal, "eigenvalue (decreasing modulus)", "1",
            "real parts of the period matrix's eigenvalues, the digits computed", st);
  c.decimal("eigen_im_decimal", eigen_im_decimal, "eigenvalue (decreasing modulus)", "1", "imaginary parts, the digits computed", st);
  c.decimal("exponents_decimal", exponents_decimal, "exponent (lambda1, lambda2)", "1/iteration (natural log)",
            "the orbit's projective exponents lambda1 >= lambda2 (empty without a periodic orbit)", st);
  c.decimal("orbit_decimal", orbit_decimal, "coordinate (x, y, z of u_0, then u_1, ...)", "1",
            "the periodic orbit's points, flattened point-major, the digits computed (empty without a periodic point)", st);
  for (const char* name : {"eigen_re", "eigen_im", "eigen_modulus", "orbit"}) c.status_of(name, st);
}

std::string WordResult::text() const {
  switch (mode) {
    case WordRequest::Mode::verdict: return verdict_text(*this);
    case WordRequest::Mode::window: return window_csv();
    case WordRequest::Mode::charpoly:
      return fmt::format(
          "word          {} ({} symbols); matrix {}\n"
          "chi(lambda) = det(lambda I - A) = lambda^3 + c2 lambda^2 + c1 lambda + c0, exact in r:\n"
          "c2            {}\nc1            {}\nc0            {}\ndiscriminant  {}\n"
          "              (the paper's sign: (q/2)^2 + (p/3)^3 of the depressed cubic; < 0: three real roots)\n",
          to_paper(word), word.size(), reduced ? "A = J M_h, M_w = A^2 (w = h J(h))" : "A = M_w", c2, c1, c0, discriminant);
  }
  return {};
}

void WordResult::describe(core::Contents& c) const {
  c.attr("word", to_paper(word));
  c.attr("primitive", to_paper(primitive));
  c.attr("scalar_type", scalar_type);
  switch (mode) {
    case WordRequest::Mode::verdict:
      c.attr("mode", std::string("verdict"));
      c.attr("r", r);
      c.attr("verdict", outcome);
      c.attr("reason", reason);
      c.attr("lyapunov2", lyapunov2);
      c.attr("lyapunov3", lyapunov3);
      c.attr("letters", letters);
      c.array("eigen_re", eigen_re, {eigen_re.size()}, "eigenvalue (decreasing modulus)", "1",
              "real parts of the eigenvalues of the period matrix (double view of the text attributes)");
      c.array("eigen_im", eigen_im, {eigen_im.size()}, "eigenvalue (decreasing modulus)", "1", "imaginary parts");
      c.array("eigen_modulus", eigen_modulus, {eigen_modulus.size()}, "eigenvalue (decreasing modulus)", "1", "moduli");
      c.array("orbit", orbit_xyz, {orbit_xyz.size() / 3, 3}, "point of the periodic orbit, (x, y, z)", "1",
              "the periodic orbit's points u_0 .. u_{p-1}, unit vectors in Q (empty without a periodic point)");
      describe_verdict_decimals(c);
      break;
    case WordRequest::Mode::window: describe_window(c); break;
    case WordRequest::Mode::charpoly:
      c.attr("mode", std::string("charpoly"));
      c.attr("c2", c2);
      c.attr("c1", c1);
      c.attr("c0", c0);
      c.attr("discriminant", discriminant);
      break;
  }
}

}  // namespace btob::patterns
