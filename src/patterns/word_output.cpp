// SPDX-License-Identifier: GPL-3.0-or-later
// What `btob pattern WORD` gives back: the text the command line prints (verdict, window CSV, characteristic
// polynomial), the result's description (NAME.h5, Python) with the decimals of every number computed in the run's
// precision and what kind of number each is (docs/reference/numbers.md), and the CSV tables of --out.
#include "patterns/requests.hpp"

#include <fmt/format.h>

#include <string>

namespace btob::patterns {
namespace {

// What the window's ends are: the r where the verdict changes, found on the scan grid and bisected in the run's
// precision to `window_tol`; nothing proves them (no interval arithmetic).  The scan refines the grid at spectral
// events (scan_impl.hpp), and an empty window says on stderr what it could not resolve.  The bar is the bisection's
// and the printed digits' rounding.
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
  c.array("r_low", r_low, {N}, "interval", "1",
          "lower ends of the stability intervals in r (double view of r_low_decimal)");
  c.array("r_high", r_high, {N}, "interval", "1",
          "upper ends of the stability intervals in r (double view of r_high_decimal)");
  c.decimal("r_low_decimal", r_low_decimal, "interval", "1",
            "lower ends of the stability intervals, the digits computed", st);
  c.decimal("r_high_decimal", r_high_decimal, "interval", "1",
            "upper ends of the stability intervals, the digits computed", st);
  c.status_of("r_low", st);
  c.status_of("r_high", st);
  c.text("low_reason", low_reason, "interval", "reason",
         "what begins the interval at r_low (docs/reference/numbers.md)");
  c.text("high_reason", high_reason, "interval", "reason",
         "what ends the interval at r_high (docs/reference/numbers.md)");
  c.attr("window_tol", window_tol);
  c.attr("window_digits", static_cast<long>(window_digits));
}

// The verdict's numbers as decimals in the run's precision: eigenvalues, the orbit's exponents and points.
void WordResult::describe_verdict_decimals(core::Contents& c) const {
  const core::Status st = verdict_status(*this);
  c.decimal("eigen_re_decimal", eigen_re_decimal, "eigenvalue (decreasing modulus)", "1",
            "real parts of the period matrix's eigenvalues, the digits computed", st);
  c.decimal("eigen_im_decimal", eigen_im_decimal, "eigenvalue (decreasing modulus)", "1",
            "imaginary parts, the digits computed", st);
  c.decimal("exponents_decimal", exponents_decimal, "exponent (lambda1, lambda2)", "1/iteration (natural log)",
            "the orbit's projective exponents lambda1 >= lambda2 (empty without a periodic orbit)", st);
  c.decimal("orbit_decimal", orbit_decimal, "coordinate (x, y, z of u_0, then u_1, ...)", "1",
            "the periodic orbit's points, flattened point-major, the digits computed (empty without a periodic point)",
            st);
  for (const char* name : {"eigen_re", "eigen_im", "eigen_modulus", "orbit"}) c.status_of(name, st);
}

std::string WordResult::text() const {
  switch (mode) {
    case WordRequest::Mode::verdict: return detail::verdict_text(*this);  // verdict_text.cpp
    case WordRequest::Mode::window: return window_csv();
    case WordRequest::Mode::charpoly:
      return fmt::format(
          "word          {} ({} symbols); matrix {}\n"
          "chi(lambda) = det(lambda I - A) = lambda^3 + c2 lambda^2 + c1 lambda + c0, exact in r:\n"
          "c2            {}\nc1            {}\nc0            {}\ndiscriminant  {}\n"
          "              (the paper's sign: (q/2)^2 + (p/3)^3 of the depressed cubic; < 0: three real roots)\n",
          to_paper(word), word.size(), reduced ? "A = J M_h, M_w = A^2 (w = h J(h))" : "A = M_w", c2, c1, c0,
          discriminant);
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
