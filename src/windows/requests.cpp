// SPDX-License-Identifier: GPL-3.0-or-later
// The windows requests: validation, the runs, their CSV text and the description of their results.
#include "windows/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
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

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void progress(const core::RunControl& control, std::size_t done, std::size_t total) {
  if (control.progress) control.progress->update(done, total);
}

// The items of a sweep over `range`, checked (a part names only n of its request).
void check_items(const std::vector<std::size_t>& items, const NRange& range) {
  for (std::size_t i : items)
    if (i >= static_cast<std::size_t>(range.count())) throw std::logic_error("windows sweep: item beyond the n range");
}
}  // namespace

NRange parse_n_range(std::string_view text, int min_n, const std::string& field) {
  const auto [a, b] = core::parse_int_range(text, min_n, max_range_n, field);
  return {static_cast<int>(a), static_cast<int>(b)};
}

namespace {
// The run_part of a per-n sweep (core/sweep.hpp): validates the request, reads its n range (n >= min_n), checks the
// items, and calls f(part, n) for each item's n in the items' order, checking cancellation before and reporting
// progress after each.  Returns the part, its items set.
template <class Part, class Req, class F>
Part for_each_n(const Req& req, int min_n, const std::vector<std::size_t>& items, const core::RunControl& control,
                F&& f) {
  req.validate();
  const NRange r = parse_n_range(req.n, min_n, "n");
  check_items(items, r);
  Part part;
  part.items = items;
  for (std::size_t j = 0; j < items.size(); ++j) {
    core::check_cancel(control.cancel);
    f(part, r.n_of(items[j]));
    progress(control, j + 1, items.size());
  }
  return part;
}

// The merge preamble of a per-n sweep: the request's n range and where each of its items is among the parts.
template <class Part>
std::pair<NRange, std::vector<core::ItemRef>> n_order(const std::string& n, int min_n, const std::vector<Part>& parts) {
  const NRange r = parse_n_range(n, min_n, "n");
  return {r, core::item_order(parts, static_cast<std::size_t>(r.count()))};
}
}  // namespace

void require_digits(long digits, const std::string& field) {
  if (digits < 10 || digits > 10000) throw core::InvalidField(field, std::to_string(digits), "10..10000");
}

// ---- poly ------------------------------------------------------------------------------------------------
void PolyRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  if (form != "developed" && form != "factorised" && form != "both")
    throw core::InvalidField("form", "'" + form + "'", "developed, factorised or both");
}

std::size_t PolyRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 1, "n").count()); }

PolyPart run_part(const PolyRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  return for_each_n<PolyPart>(req, 1, items, control, [&](PolyPart& part, int n) {
    const RationalPoly q = window_polynomial(n);
    part.degree.push_back(static_cast<std::uint32_t>(q.degree()));
    part.developed.push_back(req.form != "factorised" ? q.developed() : "");
    part.factorised.push_back(req.form != "developed" ? factorise(q).to_string() : "");
  });
}

PolyResult merge(const PolyRequest& req, std::vector<PolyPart> parts) {
  const auto [r, order] = n_order(req.n, 1, parts);
  PolyResult res;
  for (std::size_t i = 0; i < order.size(); ++i) {
    PolyPart& p = parts[order[i].part];
    const std::size_t j = order[i].index;
    res.n.push_back(static_cast<std::uint32_t>(r.n_of(i)));
    res.degree.push_back(p.degree.at(j));
    res.developed.push_back(std::move(p.developed.at(j)));
    res.factorised.push_back(std::move(p.factorised.at(j)));
  }
  return res;
}

PolyResult run(const PolyRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

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

// ---- bounds ----------------------------------------------------------------------------------------------
void BoundsRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  require_digits(digits);
}

std::size_t BoundsRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 1, "n").count()); }

BoundsPart run_part(const BoundsRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  return for_each_n<BoundsPart>(req, 1, items, control, [&](BoundsPart& part, int n) {
    const mpfr_float lo = window_lower_bound(n, req.digits, control.cancel);
    part.lower_text.push_back(fixed(lo, req.digits));
    part.lower_bound.push_back(static_cast<double>(lo));
    if (n >= 2) {
      const mpfr_float up = r_crit2(n, req.digits, 15);  // 15 guard digits for the D-decimal rounding
      part.upper_text.push_back(fixed(up, req.digits));
      part.upper_bound.push_back(static_cast<double>(up));
    } else {
      part.upper_text.emplace_back();
      part.upper_bound.push_back(std::nan(""));
    }
    if (req.certify) {
      const Certificate cert = certify_lower_bound(n, req.digits, control.cancel);
      part.a.push_back(cert.a.get_str());  // canonical p/q: mpq_class reads it back exactly
      part.b.push_back(cert.b.get_str());
      part.sign_a.push_back(cert.sign_a);
      part.sign_b.push_back(cert.sign_b);
      part.roots_0_a.push_back(cert.roots_0_a);
      part.roots_a_b.push_back(cert.roots_a_b);
    }
  });
}

BoundsResult merge(const BoundsRequest& req, std::vector<BoundsPart> parts) {
  const auto [r, order] = n_order(req.n, 1, parts);
  BoundsResult res;
  res.digits = req.digits;
  res.certified_run = req.certify;
  // a, b = k / 10^D exactly: their D decimals, printed from MPFR with 20 guard digits.
  const auto dec = [&](const mpq_class& q) {
    core::MpfrDigits guard(req.digits + 20);
    return fixed(mpfr_float(q.get_mpq_t()), req.digits);
  };
  for (std::size_t i = 0; i < order.size(); ++i) {
    BoundsPart& p = parts[order[i].part];
    const std::size_t j = order[i].index;
    res.n.push_back(static_cast<std::uint32_t>(r.n_of(i)));
    res.lower_text.push_back(std::move(p.lower_text.at(j)));
    res.upper_text.push_back(std::move(p.upper_text.at(j)));
    res.lower_bound.push_back(p.lower_bound.at(j));
    res.upper_bound.push_back(p.upper_bound.at(j));
    if (req.certify) {
      Certificate cert;
      cert.n = r.n_of(i);
      cert.decimals = req.digits;
      cert.a = mpq_class(p.a.at(j));
      cert.b = mpq_class(p.b.at(j));
      cert.sign_a = p.sign_a.at(j);
      cert.sign_b = p.sign_b.at(j);
      cert.roots_0_a = p.roots_0_a.at(j);
      cert.roots_a_b = p.roots_a_b.at(j);
      res.a_text.push_back(dec(cert.a));
      res.b_text.push_back(dec(cert.b));
      res.sign_a.push_back(cert.sign_a);
      res.sign_b.push_back(cert.sign_b);
      res.roots_0_a.push_back(static_cast<double>(cert.roots_0_a));
      res.roots_a_b.push_back(static_cast<double>(cert.roots_a_b));
      res.valid.push_back(cert.valid() ? 1 : 0);
      res.certificates.push_back(std::move(cert));
    }
  }
  return res;
}

BoundsResult run(const BoundsRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
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

void ThresholdsRequest::validate() const { require_digits(digits); }

ThresholdsResult run(const ThresholdsRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  ThresholdsResult res;
  res.thresholds = thresholds(req.digits);
  for (const auto& t : res.thresholds) {
    res.text.push_back(t.value.str(req.digits, std::ios_base::fixed));
    res.value.push_back(static_cast<double>(t.value));
  }
  return res;
}

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

void StripesRequest::validate() const {
  if (max_m < 1 || max_m > 100000) throw core::InvalidField("max-m", std::to_string(max_m), "1..100000");
  require_digits(digits);
}

StripesResult run(const StripesRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  StripesResult res;
  for (const auto& s : thin_stripes(req.max_m, req.digits)) {
    res.l.push_back(static_cast<std::uint32_t>(s.l));
    res.m.push_back(static_cast<std::uint32_t>(s.m));
    res.mirror_l.push_back(static_cast<std::uint32_t>(s.m - s.l));
    res.text.push_back(fixed(s.value, req.digits));
    res.r.push_back(static_cast<double>(s.value));
  }
  return res;
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

core::Work work(const ThresholdsRequest& req) {
  core::Work w;
  // One indivisible computation whose cost grows with the digits: priced by the thresholds at 10, 20, 40, ...
  // digits (core::Term::sized_run), never by running the request.
  core::Term t;
  t.route = fmt::format("windows thresholds {} digits", req.digits);
  t.units = 1;
  t.what = fmt::format(
      "run of the four thresholds at {} decimals (one indivisible computation, priced by a cost "
      "model in the digits)",
      req.digits);
  t.size_parameter = "digits";
  t.size = req.digits;
  t.smallest = 10;
  t.sized_run = [](double digits, const core::RunControl& c) {
    ThresholdsRequest one;
    one.digits = static_cast<int>(digits);
    (void)run(one, c);
  };
  w.terms.push_back(std::move(t));
  w.output_bytes = 4 * (req.digits + 60.0);
  w.peak_bytes = 65536 + 64.0 * req.digits;
  return w;
}

namespace {
// The reduced l/m in (1/4, 1/2] with m <= M: a quarter of the Farey fractions, sum phi(m) ~ 3 M^2 / pi^2.
double stripes_about(double M) { return 3 * M * M / (4 * std::numbers::pi * std::numbers::pi); }
}  // namespace

core::Work work(const StripesRequest& req) {
  core::Work w;
  core::Term t;
  t.route = fmt::format("windows stripes {} digits", req.digits);
  t.units = std::max(1.0, stripes_about(req.max_m));
  t.what = fmt::format("thin stripes r(l/m) at {} decimals (about 3 max-m^2 / (4 pi^2))", req.digits);
  t.probe = [digits = req.digits](double n, const core::RunControl& c) {
    StripesRequest p;
    p.digits = digits;
    p.max_m = static_cast<int>(std::clamp(std::sqrt(n * 4 * std::numbers::pi * std::numbers::pi / 3), 4.0, 100000.0));
    return static_cast<double>(run(p, c).l.size());
  };
  w.output_bytes = t.units * (req.digits + 40.0) * 2;  // l, m, mirror_l and the r text, in NAME.h5 and the CSV
  w.peak_bytes = t.units * (req.digits + 64.0) + 65536;
  w.terms.push_back(std::move(t));
  return w;
}

// ---- verify ----------------------------------------------------------------------------------------------
void VerifyRequest::validate() const {
  (void)parse_n_range(n, 2, "n");  // n = 1 (abcb) is never stable and has no r_crit,2
  if (iterations < 100) throw core::InvalidField("iterations", std::to_string(iterations), "at least 100");
  if (per_n < 0) throw core::InvalidField("per-n", std::to_string(per_n), "at least 0");
  if (tail < 1 || tail >= iterations)
    throw core::InvalidField("tail", std::to_string(tail), fmt::format("1..iterations-1 = {}", iterations - 1));
  if (precision != "double" && precision != "long-double")
    throw core::InvalidField("precision", "'" + precision + "'", "double or long-double");
}

std::size_t VerifyRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 2, "n").count()); }

namespace {
VerifyOptions verify_options(const VerifyRequest& req, int threads) {
  VerifyOptions o;
  o.base_iterations = req.iterations;
  o.per_n = req.per_n;
  o.tail = req.tail;
  o.long_double = req.precision == "long-double";
  o.threads = threads;
  return o;
}
}  // namespace

VerifyPart run_part(const VerifyRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  VerifyOptions options = verify_options(req, control.threads);
  options.cancel = control.cancel;
  // One n at a time, for progress and cancellation; the rows do not depend on the grouping.
  VerifyPart part = for_each_n<VerifyPart>(req, 2, items, control, [&](VerifyPart& p, int n) {
    const std::vector<VerifyRow> rows = verify_windows(n, n, options);
    if (rows.size() != 4) throw std::logic_error("windows verify: not 4 rows per n");  // merge places 4 per item
    p.rows.insert(p.rows.end(), rows.begin(), rows.end());
  });
  part.seconds = seconds_since(t0);
  return part;
}

VerifyResult merge(const VerifyRequest& req, std::vector<VerifyPart> parts) {
  VerifyResult res;
  const auto [range, order] = n_order(req.n, 2, parts);
  res.range = range;
  res.options = verify_options(req, 0);
  for (const auto& p : parts) res.total_seconds += p.seconds;
  res.rows = core::merge_rows<VerifyPart, VerifyRow>(
      parts, order, 4, [](const VerifyPart& p) -> const std::vector<VerifyRow>& { return p.rows; });
  for (std::size_t k = 0; k < res.rows.size(); ++k) {
    const VerifyRow& row = res.rows[k];
    res.passed += row.pass();
    ++res.total;
    res.n.push_back(static_cast<std::uint32_t>(row.n));
    res.position.push_back(static_cast<std::uint32_t>(k % 4));
    res.r.push_back(row.r);
    res.lower.push_back(row.lower);
    res.upper.push_back(row.upper);
    res.iterations_run.push_back(static_cast<std::uint32_t>(row.iterations));
    res.orbits.push_back(static_cast<std::uint32_t>(row.orbits));
    res.on_pattern.push_back(static_cast<std::uint32_t>(row.on_pattern));
    res.expected_on.push_back(row.expected_on ? 1 : 0);
    res.pass.push_back(row.pass() ? 1 : 0);
  }
  return res;
}

VerifyResult run(const VerifyRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
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

std::string verify_stem(const NRange& r) {
  return r.first == 2 && r.last == 125 ? std::string("verify") : fmt::format("verify_{}-{}", r.first, r.last);
}

std::string VerifyRequest::default_name() const { return verify_stem(parse_n_range(n, 2, "n")); }

// ---- precision study of the lower bound ------------------------------------------------------------------
void BoundPrecisionRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  if (mpfr_digits < 10 || mpfr_digits > 1000)
    throw core::InvalidField("mpfr-digits", std::to_string(mpfr_digits), "10..1000");
}

std::size_t BoundPrecisionRequest::work_items() const {
  return static_cast<std::size_t>(parse_n_range(n, 1, "n").count());
}

namespace {
// The rows of the study, in the order of nesting of BoundPrecisionResult::rows: route, then precision.
constexpr Route study_routes[] = {Route::matrix, Route::polynomial};
constexpr int study_precisions = 5;  // float, double, long-double, float128, mpfr:D
std::string precision_name(int k, int mpfr_digits) {
  static const char* names[] = {"float", "double", "long-double", "float128"};
  return k < 4 ? std::string(names[k]) : fmt::format("mpfr:{}", mpfr_digits);
}

// One bound of precision T by `route` against the certified value `exact`; `mpfr_digits` > 0 for the MPFR row (its
// working precision, held by a guard for the bound).
template <class T> void study(Route route, int n, const mpfr_float& exact, int mpfr_digits, BoundPrecisionPart& part) {
  std::optional<core::MpfrDigits> working;
  if (mpfr_digits > 0) working.emplace(mpfr_digits);
  const auto t0 = std::chrono::steady_clock::now();
  const T v = window_lower_bound_in<T>(n, route);
  const double s = seconds_since(t0);
  working.reset();
  core::MpfrDigits sixty(60);  // the error against the 40-decimal reference
  const mpfr_float err = abs(mpfr_float(v) - exact);
  const bool finite = std::isfinite(static_cast<double>(v));
  // Correct to 12 decimals: within half a unit of the 12th decimal of the certified value.
  const bool ok = finite && err <= mpfr_float("5e-13");
  part.value.push_back(static_cast<double>(v));
  part.abs_error.push_back(finite ? static_cast<double>(err) : std::nan(""));
  part.correct_12.push_back(ok ? 1 : 0);
  part.seconds.push_back(s);
}
}  // namespace

BoundPrecisionPart run_part(const BoundPrecisionRequest& req, const std::vector<std::size_t>& items,
                            const core::RunControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  BoundPrecisionPart part = for_each_n<BoundPrecisionPart>(req, 1, items, control, [&](BoundPrecisionPart& p, int n) {
    const mpfr_float exact = window_lower_bound(n, 40);
    for (const Route route : study_routes) {
      study<float>(route, n, exact, 0, p);
      study<double>(route, n, exact, 0, p);
      study<long double>(route, n, exact, 0, p);
      study<core::float128>(route, n, exact, 0, p);
      study<mpfr_float>(route, n, exact, req.mpfr_digits, p);
    }
  });
  part.total_seconds = seconds_since(t0);
  return part;
}

BoundPrecisionResult merge(const BoundPrecisionRequest& req, std::vector<BoundPrecisionPart> parts) {
  BoundPrecisionResult res;
  const auto [r, order] = n_order(req.n, 1, parts);
  res.range = r;
  constexpr std::size_t per_n = std::size(study_routes) * study_precisions;
  for (const auto& p : parts) res.total_seconds += p.total_seconds;
  std::size_t k = 0;  // route x precision row
  for (const Route route : study_routes)
    for (int prec = 0; prec < study_precisions; ++prec, ++k) {
      const std::string name = precision_name(prec, req.mpfr_digits);
      int largest_all = 0, largest_any = 0;
      bool prefix = true;
      double total_s = 0;
      for (std::size_t i = 0; i < order.size(); ++i) {
        const BoundPrecisionPart& p = parts[order[i].part];
        const std::size_t at = order[i].index * per_n + k;
        BoundPrecisionRow row;
        row.precision = name;
        row.route = route_name(route);
        row.n = r.n_of(i);
        row.value = p.value.at(at);
        row.abs_error = p.abs_error.at(at);
        row.correct_12 = p.correct_12.at(at) != 0;
        row.seconds = p.seconds.at(at);
        total_s += row.seconds;
        if (row.correct_12) largest_any = row.n;
        prefix = prefix && row.correct_12;
        if (prefix) largest_all = row.n;
        res.rows.push_back(row);
      }
      res.summary.push_back({name, route_name(route), largest_all, largest_any, total_s / r.count()});
      res.precision.push_back(name);
      res.route.push_back(route_name(route));
      res.row.push_back(name + " " + route_name(route));
    }
  for (const auto& row : res.rows) {
    res.value.push_back(row.value);
    res.abs_error.push_back(row.abs_error);
    res.seconds.push_back(row.seconds);
    res.correct_12.push_back(row.correct_12 ? 1 : 0);
  }
  for (int n = r.first; n <= r.last; ++n) res.n.push_back(static_cast<std::uint32_t>(n));
  return res;
}

BoundPrecisionResult run(const BoundPrecisionRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
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
