// SPDX-License-Identifier: GPL-3.0-or-later
// The text `btob pattern WORD --r R` prints: the word, its matrix, the spectrum with the digits the route vouches
// for (accuracy.hpp), the verdict with its reason, the exponents and the periodic orbit.
#include "patterns/requests.hpp"

#include <fmt/format.h>

#include <string>

namespace btob::patterns::detail {
namespace {

// What a reason code of the analysis means (Section 7's conditions, in the order analyse checks them).
std::string reason_text(const std::string& reason) {
  if (reason == "complex") return "the dominant eigenvalue mu1 is complex: no dominant real direction";
  if (reason == "domain") return "the dominant eigenvector lies outside the domain x z < 0";
  if (reason == "dominance") return "the eigenvalue with a feasible eigenvector is not the dominant one";
  if (reason.rfind("feas", 0) == 0)
    return fmt::format("feasibility inequality {} fails: the orbit does not see the word's symbol there",
                       reason.substr(4));
  if (reason == "end") return "the end of (0, 1)";
  return reason;
}

// The line of eigenvalue i (mu1, mu2, mu3): value, |mu|/|mu1|, and for a real one its eigenvector and feasibility.
std::string eigen_line(std::size_t i, const EigenText& e) {
  std::string s = fmt::format("mu{}         ", i + 1);
  if (e.real) {
    s += fmt::format("{} (real, |mu|/|mu1| = {}), eigenvector ({}, {}, {})", e.re, e.ratio, e.vector[0], e.vector[1],
                     e.vector[2]);
    if (e.feasible) s += ", in the domain, all feasibility inequalities hold";
    else if (!e.in_domain) s += ", outside the domain x z < 0";
    else
      s += fmt::format(", in the domain, feasibility inequality {} fails (symbol {})", e.first_failure,
                       e.failing_symbol);
  } else {
    const bool neg = !e.im.empty() && e.im[0] == '-';
    s += fmt::format("{} {} {} i (complex, |mu|/|mu1| = {})", e.re, neg ? "-" : "+", neg ? e.im.substr(1) : e.im,
                     e.ratio);
  }
  s += "\n";
  return s;
}

// What the verdict line adds in parentheses after the outcome: why it is neutral, unstable, undecided or not stable.
std::string outcome_explanation(const WordResult& res) {
  std::string why;
  if (res.outcome == outcome_name(Outcome::neutral))
    why = " (elliptic: both exponents zero within 64 eps; neither attracting nor repelling)";
  else if (res.outcome == outcome_name(Outcome::unstable)) why = " (a saddle or a source: lambda1 > 0)";
  else if (res.outcome == outcome_name(Outcome::undecided) && res.reason.rfind("precision", 0) == 0)
    why = fmt::format(
        " ({}: the verdict changes with the precision, so {} cannot give it; use --precision "
        "mpfr:<digits>)",
        res.reason, res.scalar_type);
  else if (res.outcome == outcome_name(Outcome::undecided) && res.reason == "range")
    why = fmt::format(
        " (range: a number the verdict needs, a component of the dominant eigenvector or the normalised "
        "product, is zero or subnormal in {}, below its range; use --precision mpfr:<digits>)",
        res.scalar_type);
  else if (res.outcome == outcome_name(Outcome::undecided))
    why = fmt::format(
        " (undecided in {}: the orbit's eigenvalue and another real one have equal moduli within 64 "
        "eps, so lambda1 is zero within its error and the eigenvalue test cannot order them; use a "
        "longer precision, --precision mpfr:<digits>)",
        res.scalar_type);
  else if (!res.reason.empty()) why = fmt::format(" (not stable: {}: {})", res.reason, reason_text(res.reason));
  return why;
}

}  // namespace

std::string verdict_text(const WordResult& res) {
  const Word& w = res.word;
  const Word& u = res.primitive;
  std::string s = fmt::format("word        {} = {} ({} symbols, {} collisions); canonical {}\n", to_paper(w),
                              to_digits(w), w.size(), collisions(w), to_paper(canonical(w)));
  if (!(u == w)) s += fmt::format("primitive   {} (the orbit of a power is the orbit of its root)\n", to_paper(u));
  s += fmt::format("r           {}\n", res.r);
  if (res.reduced) {
    const Word h{std::vector<std::uint8_t>(u.s.begin(), u.s.begin() + static_cast<long>(u.size() / 2))};
    s += fmt::format("matrix      J M_h with h = {}: M_w = (J M_h)^2 (Section 7.1)\n", to_digits(h));
  } else {
    s += fmt::format("matrix      M_w = P_{} ... P_{} (first symbol applied first)\n", int(u.s.back()),
                     int(u.s.front()));
  }
  for (std::size_t i = 0; i < res.spectrum.size(); ++i) s += eigen_line(i, res.spectrum[i]);
  const std::string why = outcome_explanation(res);
  s += fmt::format("verdict     {}{}\n", res.outcome, why);
  if (res.orbit.empty()) return s;  // no periodic point: the period matrix's exponents describe no orbit
  s += fmt::format(
      "exponents   lambda1 = {}, lambda2 = {} (the orbit's projective Lyapunov exponents along its two "
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

}  // namespace btob::patterns::detail
