// SPDX-License-Identifier: GPL-3.0-or-later
// The windows requests' runs: run_part over the n of a range, merge of the parts, run, and the work estimates.
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

namespace {
void progress(const core::RunControl& control, std::size_t done, std::size_t total) {
  if (control.progress) control.progress->update(done, total);
}

// The items of a sweep over `range`, checked (a part names only n of its request).
void check_items(const std::vector<std::size_t>& items, const NRange& range) {
  for (std::size_t i : items)
    if (i >= static_cast<std::size_t>(range.count())) throw std::logic_error("windows sweep: item beyond the n range");
}
}  // namespace

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
  part.seconds = core::seconds_since(t0);
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
  const double s = core::seconds_since(t0);
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
  part.total_seconds = core::seconds_since(t0);
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

}  // namespace btob::windows
