// SPDX-License-Identifier: GPL-3.0-or-later
// The windows results' output: their text and CSV tables and the description of their arrays and attributes.
#include "windows/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "core/sweep.hpp"
#include "windows/direct.hpp"

#include <numbers>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iterator>
#include <optional>
#include <utility>

namespace btob::windows {

std::string PolyResult::text() const {
  std::string s;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!developed[i].empty()) s += fmt::format("Q_{} = {}\n", n[i], developed[i]);
    if (!factorised[i].empty()) s += fmt::format("Q_{} = {}\n", n[i], factorised[i]);
  }
  return s;
}

void PolyResult::describe(core::Contents& c) const {
  c.array("n", n, {n.size()}, "n", "1", "window index n of the pattern (ab)^n(cb)^n");
  c.array("degree", degree, {n.size()}, "n", "1", "degree of Q_n (4n)");
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!developed[i].empty()) c.attr(fmt::format("Q_{}_developed", n[i]), developed[i]);
    if (!factorised[i].empty()) c.attr(fmt::format("Q_{}_factorised", n[i]), factorised[i]);
  }
}

std::string BoundsResult::csv() const {
  // The last two columns say what each bound is (docs/reference/numbers.md): the lower bound certified by this
  // row's certificate (estimated without --certify or when it failed), r_crit,2(n) conjectured (Section 4).
  core::CsvTable t(certified_run ? "n,lower_bound,upper_bound,a,b,sign_Q_a,sign_Q_b,sturm_roots_0_a,sturm_roots_a_b,"
                                   "certified,lower_status,upper_status"
                                 : "n,lower_bound,upper_bound,lower_status,upper_status");
  for (std::size_t i = 0; i < n.size(); ++i) {
    std::string s = fmt::format("{},{},{}", n[i], lower_text[i], upper_text[i]);
    const bool proved = certified_run && certificates[i].valid();
    if (certified_run) {
      const Certificate& c = certificates[i];
      s += fmt::format(",{},{},{},{},{},{},{}", a_text[i], b_text[i], c.sign_a, c.sign_b, c.roots_0_a, c.roots_a_b,
                       proved ? "yes" : "no");
    }
    s += fmt::format(",{},{}", proved ? "certified" : "estimated", upper_text[i].empty() ? "" : "conjectured");
    t.line(s);
  }
  return t.text();
}

// The lower bounds are certified when every row's certificate holds: Q_n changes sign exactly on (a, b) and has
// no root in (0, a] and exactly one in (a, b), so the smallest positive root lies in (a, b) (Appendix B).
core::Status BoundsResult::lower_status() const {
  const bool all = certified_run && std::all_of(certificates.begin(), certificates.end(),
                                                [](const Certificate& c) { return c.valid(); });
  if (all)
    return core::certified(
        "certificate per n: a_decimal < root < b_decimal, sign_Q_a * sign_Q_b < 0, "
        "sturm_roots_0_a = 0, sturm_roots_a_b = 1 (exact rationals); dataset certified = 1");
  return core::estimated(certified_run ? "a certificate failed (dataset certified = 0): root of Q_n in MPFR, "
                                         "rounded to `digits` decimals"
                                       : "root of Q_n in MPFR with 20 guard digits, rounded to `digits` decimals; "
                                         "not certified (--certify proves it)",
                         "error bar half a unit of the last decimal, a numerical bound without proof");
}

// r_crit,2(n) (eq. (4.6)) is where the paper conjectures the window ends; nothing here proves the window reaches it.
core::Status BoundsResult::upper_status() const {
  return core::conjectured(
      "r_crit,2(n), eq. (4.6), computed to `digits` decimals: the paper's conjecture that the "
      "window of (ab)^n(cb)^n ends there (Section 4); the certificate covers the lower bound only");
}

void BoundsResult::describe(core::Contents& c) const {
  const std::size_t N = n.size();
  c.array("n", n, {N}, "n", "1", "window index n of the pattern (ab)^n(cb)^n");
  c.array("lower_bound", lower_bound, {N}, "n", "1", "smallest positive root of Q_n (rounded to double)");
  c.array("upper_bound", upper_bound, {N}, "n", "1", "r_crit,2(n), eq. (4.6), rounded to double (NaN for n = 1)");
  if (certified_run) {
    c.array("sign_Q_a", sign_a, {N}, "n", "1", "exact sign of Q_n at a = floor(lower 10^D) / 10^D");
    c.array("sign_Q_b", sign_b, {N}, "n", "1", "exact sign of Q_n at b = a + 10^-D");
    c.array("sturm_roots_0_a", roots_0_a, {N}, "n", "count",
            "distinct real roots of Q_n in (0, a] (Descartes rule after Moebius transforms, Sturm fallback)");
    c.array("sturm_roots_a_b", roots_a_b, {N}, "n", "count",
            "distinct real roots of Q_n in (a, b) (Descartes rule after Moebius transforms, Sturm fallback)");
    c.array("certified", valid, {N}, "n", "1", "1 when the certificate proves the lower bound lies in (a, b)");
  }
  const core::Status lower = lower_status(), upper = upper_status();
  c.decimal("lower_bound_decimal", lower_text, "n", "1",
            "smallest positive root of Q_n, `digits` decimals (correctly rounded)", lower);
  c.status_of("lower_bound", lower);
  c.decimal("upper_bound_decimal", upper_text, "n", "1", "r_crit,2(n), `digits` decimals (empty for n = 1)", upper);
  c.status_of("upper_bound", upper);
  if (certified_run) {
    const core::Status exact = core::certified(
        "exact: a = floor(lower 10^D) / 10^D and b = a + 10^-D are D-decimal "
        "fractions, printed with all D decimals");
    c.decimal("a_decimal", a_text, "n", "1", "the certificate's a, an exact D-decimal fraction", exact);
    c.decimal("b_decimal", b_text, "n", "1", "the certificate's b = a + 10^-D", exact);
  }
  c.attr("digits", static_cast<long>(digits));
  c.attr("certify", certified_run ? std::string("yes") : std::string("no"));
}

// ---- thresholds and stripes ------------------------------------------------------------------------------
namespace {
// What the thresholds' and the stripes' decimals are (docs/reference/numbers.md): closed forms evaluated in MPFR,
// not interval arithmetic, so their last decimal is vouched for numerically, not proved.
core::Status threshold_status() {
  return core::estimated(
      "closed form (names' formulas) evaluated in MPFR with 10 guard digits, rounded to `digits` "
      "decimals",
      "error bar one unit of the last decimal, a numerical bound without proof");
}
core::Status stripe_status() {
  return core::estimated(
      "eq. (6.3) with xi = cos(pi - 2 pi l/m) evaluated in MPFR with 10 guard digits, rounded to "
      "`digits` decimals",
      "error bar one unit of the last decimal, a numerical bound without proof");
}
}  // namespace

std::string ThresholdsResult::csv() const {
  core::CsvTable t("name,formula,value,status");
  const std::string st = threshold_status().kind;
  for (std::size_t i = 0; i < thresholds.size(); ++i) t.row({thresholds[i].name, thresholds[i].formula, text[i], st});
  return t.text();
}

void ThresholdsResult::describe(core::Contents& c) const {
  c.array("value", value, {value.size()}, "threshold", "1",
          "threshold values rounded to double, in the order of names");
  std::string names;
  for (const auto& t : thresholds) names += (names.empty() ? "" : ",") + t.name;
  c.attr("names", names);
  const core::Status st = threshold_status();
  c.decimal("value_decimal", text, "threshold", "1", "threshold values with `digits` decimals, in the order of names",
            st);
  c.status_of("value", st);
  for (std::size_t i = 0; i < thresholds.size(); ++i)
    c.attr(thresholds[i].name, thresholds[i].formula + " = " + text[i]);
}

std::string StripesResult::csv() const {
  core::CsvTable t("l,m,mirror_l,r,status");
  const std::string st = stripe_status().kind;
  for (std::size_t i = 0; i < l.size(); ++i)
    t.line(fmt::format("{},{},{},{},{}", l[i], m[i], mirror_l[i], text[i], st));
  return t.text();
}

void StripesResult::describe(core::Contents& c) const {
  const std::size_t S = l.size();
  c.array("l", l, {S}, "stripe", "1", "numerator of the rotation number l/m (1/4 < l/m <= 1/2, reduced)");
  c.array("m", m, {S}, "stripe", "1", "denominator of the rotation number");
  c.array("mirror_l", mirror_l, {S}, "stripe", "1", "numerator m - l of the mirror rotation number (same r)");
  c.array("r", r, {S}, "stripe", "1", "thin stripe r(l/m), eq. (6.3), rounded to double");
  const core::Status st = stripe_status();
  c.decimal("r_decimal", text, "stripe", "1", "thin stripe r(l/m) with `digits` decimals", st);
  c.status_of("r", st);
}

std::string VerifyResult::csv() const {
  core::CsvTable t("n,position,r,lower_bound,upper_bound,iterations,orbits,on_pattern,expected,verdict");
  for (const auto& row : rows)
    t.line(fmt::format("{},{},{:.17g},{:.17g},{:.17g},{},{},{},{},{}", row.n, core::csv_text(row.position), row.r,
                       row.lower, row.upper, row.iterations, row.orbits, row.on_pattern,
                       row.expected_on ? "all" : "none", row.pass() ? "pass" : "fail"));
  return t.text();
}

void VerifyResult::describe(core::Contents& c) const {
  const std::size_t R = rows.size();
  const std::string axes = "check (n, position)";
  c.array("n", n, {R}, axes, "1", "window index n");
  c.array("position", position, {R}, axes, "1", "0 below, 1 inside_25, 2 inside_50, 3 inside_75");
  c.array("r", r, {R}, axes, "1", "r of the check: lower - 0.05 w or lower + q w, w = r_crit2 - lower");
  c.array("lower_bound", lower, {R}, axes, "1", "window lower bound (20-decimal root of Q_n, in double)");
  c.array("upper_bound", upper, {R}, axes, "1", "r_crit,2(n) in double");
  c.array("steps", iterations_run, {R}, axes, "iteration", "map iterations of each orbit");
  c.array("orbits", orbits, {R}, axes, "count", "orbits of the Section 4 grid");
  c.array("on_pattern", on_pattern, {R}, axes, "count", "orbits ending on (ab)^n(cb)^n");
  c.array("expected_on", expected_on, {R}, axes, "1",
          "1: all orbits expected on the pattern (inside), 0: none (below)");
  c.array("pass", pass, {R}, axes, "1", "1 when the check passes");
  c.attr("n_first", static_cast<long>(range.first));
  c.attr("n_last", static_cast<long>(range.last));
  c.attr("grid", std::string("paper (Section 4, 32 initial conditions)"));
  c.attr("iterations", fmt::format("{} + {} n", options.base_iterations, options.per_n));
  c.attr("recorded", fmt::format("symbols of the last max({}, 4n) steps; on pattern = periodic with period 2n there "
                                 "and one period a rotation of 1^n 3^n",
                                 options.tail));
  c.attr("positions", std::string("below = lower - 0.05 (r_crit2 - lower); inside_q = lower + q (r_crit2 - lower)"));
  c.attr("checks", total);
  c.attr("passed", passed);
  c.attr("total_seconds", total_seconds);
}

std::string BoundPrecisionResult::csv() const {
  core::CsvTable t("precision,route,n,value,abs_error,correct_12,seconds");
  for (const auto& row : rows)
    t.line(fmt::format("{},{},{},{:.17g},{:.3e},{},{:.3e}", row.precision, row.route, row.n, row.value, row.abs_error,
                       row.correct_12 ? 1 : 0, row.seconds));
  return t.text();
}

std::string BoundPrecisionResult::summary_csv() const {
  core::CsvTable t("precision,route,largest_n_all_correct_12,largest_n_correct_12,seconds_per_bound");
  for (const auto& m : summary)
    t.line(fmt::format("{},{},{},{},{:.3e}", m.precision, m.route, m.largest_all, m.largest_any, m.seconds_per_bound));
  return t.text();
}

void BoundPrecisionResult::describe(core::Contents& c) const {
  const std::size_t P = summary.size(), N = n.size();
  const std::string axes = "precision and route, n";
  c.array("n", n, {N}, "n", "1", "window index n");
  c.text("precision", precision, "precision and route", "scalar type",
         "the row's scalar type: float, double, long-double, float128 or mpfr:DIGITS");
  c.text("route", route, "precision and route", "route",
         "the row's route: matrix (powers of the period matrix) or polynomial (Horner on Q_n's coefficients)");
  c.text("row", row, "precision and route", "text", "the row's scalar type and route, the coordinates of that axis");
  c.coordinate("precision and route", "row");
  c.array("value", value, {P, N}, axes, "1", "lower bound found by bisection in the row's precision and route");
  c.array("abs_error", abs_error, {P, N}, axes, "1", "|value - certified 40-decimal value| (NaN: no bound found)");
  c.array("correct_12", correct_12, {P, N}, axes, "1", "1 when abs_error <= 5e-13 (correct to 12 decimals)");
  c.array("seconds", seconds, {P, N}, axes, "s", "time of one bound");
  std::string names;
  for (const auto& m : summary) names += (names.empty() ? "" : ",") + m.precision + "/" + m.route;
  c.attr("rows", names);
  c.attr("n_first", static_cast<long>(range.first));
  c.attr("n_last", static_cast<long>(range.last));
  c.attr("reference",
         std::string("window_lower_bound(n, 40 decimals), certified route (Q_n in MPFR, root counts checked exactly)"));
  c.attr("criterion", std::string("|value - reference| <= 5e-13 (correct to 12 decimals)"));
  c.attr("root_finder", std::string("toms748 on (7-4sqrt3, r_crit2(n)), tolerance all but 2 bits of T"));
  c.attr("total_seconds", total_seconds);
}

}  // namespace btob::windows
