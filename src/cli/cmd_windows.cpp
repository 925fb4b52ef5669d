// `btob windows`: Q_n, certified window bounds, thresholds, thin stripes, the iterator check and the
// precision study of issue 4; and the bifurcation overlays "windows" and "stripes".
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/scalar.hpp"
#include "io/io.hpp"
#include "windows/direct.hpp"
#include "windows/verify.hpp"
#include "windows/windows.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>

namespace btob::cli {
namespace {

using windows::mpfr_float;

struct Range {
  int first = 1, last = 1;
};

// "A..B" or "A" with 1 <= A <= B <= 5000 (min_n raises the lower limit).
Range parse_range(const std::string& text, int min_n, const char* field = "n") {
  const std::string expected = fmt::format("expected A..B or A with {} <= A <= B <= 5000", min_n);
  auto number = [&](const std::string& s) {
    std::size_t used = 0;
    long v = 0;
    try {
      v = std::stol(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || s.empty()) throw UsageError(fmt::format("{}: got '{}', {}", field, text, expected));
    return v;
  };
  const auto dots = text.find("..");
  const long a = number(dots == std::string::npos ? text : text.substr(0, dots));
  const long b = dots == std::string::npos ? a : number(text.substr(dots + 2));
  if (a < min_n || b < a || b > 5000) throw UsageError(fmt::format("{}: got '{}', {}", field, text, expected));
  return {static_cast<int>(a), static_cast<int>(b)};
}

void check_digits(int digits) {
  if (digits < 10 || digits > 10000) throw UsageError(fmt::format("digits: got {}, expected 10..10000", digits));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---- btob windows poly ------------------------------------------------------------------------------
void cmd_poly(const std::string& range, const std::string& form) {
  const Range r = parse_range(range, 1);
  if (form != "developed" && form != "factorised" && form != "both")
    throw UsageError(fmt::format("form: got '{}', expected developed, factorised or both", form));
  for (int n = r.first; n <= r.last; ++n) {
    const windows::RationalPoly q = windows::window_polynomial(n);
    if (form != "factorised") std::cout << fmt::format("Q_{} = {}\n", n, q.developed());
    if (form != "developed") std::cout << fmt::format("Q_{} = {}\n", n, windows::factorise(q).to_string());
  }
}

// ---- btob windows bounds ----------------------------------------------------------------------------
void cmd_bounds(const std::string& range, int digits, bool certify) {
  const Range r = parse_range(range, 1);
  check_digits(digits);
  std::cout << (certify ? "n,lower_bound,upper_bound,a,b,sign_Q_a,sign_Q_b,sturm_roots_0_a,sturm_roots_a_b,certified\n"
                        : "n,lower_bound,upper_bound\n");
  for (int n = r.first; n <= r.last; ++n) {
    const mpfr_float lo = windows::window_lower_bound(n, digits);
    const std::string up = n >= 2 ? windows::fixed(windows::r_crit2(n, digits + 5), digits) : "";
    std::cout << n << ',' << windows::fixed(lo, digits) << ',' << up;
    if (certify) {
      const windows::Certificate c = windows::certify_lower_bound(n, digits);
      auto dec = [&](const mpq_class& q) {  // q = k / 10^D exactly: print its D decimals
        mpfr_float::default_precision(static_cast<unsigned>(digits) + 20);
        return windows::fixed(mpfr_float(q.get_mpq_t()), digits);
      };
      std::cout << ',' << dec(c.a) << ',' << dec(c.b) << ',' << c.sign_a << ',' << c.sign_b << ',' << c.roots_0_a << ','
                << c.roots_a_b << ',' << (c.valid() ? "yes" : "no");
      if (!c.valid()) std::cerr << fmt::format("btob: warning: certificate of n = {} failed\n", n);
    }
    std::cout << '\n' << std::flush;
  }
}

// ---- btob windows thresholds / stripes ---------------------------------------------------------------
void cmd_thresholds(int digits) {
  check_digits(digits);
  std::cout << "name,formula,value\n";
  for (const auto& t : windows::thresholds(digits))
    std::cout << t.name << ',' << t.formula << ',' << t.value.str(digits, std::ios_base::fixed) << '\n';
}

void cmd_stripes(int max_m, int digits) {
  check_digits(digits);
  if (max_m < 1 || max_m > 100000) throw UsageError(fmt::format("max-m: got {}, expected 1..100000", max_m));
  std::cout << "l,m,mirror_l,r\n";
  for (const auto& s : windows::thin_stripes(max_m, digits))
    std::cout << s.l << ',' << s.m << ',' << s.m - s.l << ',' << windows::fixed(s.value, digits) << '\n';
}

// ---- overlays ---------------------------------------------------------------------------------------
// Lower bounds and r_crit,2 in double, computed once per n (cached).  n <= 150: from the 20-decimal
// root of Q_n (the certified route); n > 150: from the matrix route in long double, which the precision
// study (results/windows/precision.csv) shows correct to ~20 decimals for every n <= 150, while the
// polynomial route for n = 150..400 costs ~20 s in all (Q_n of degree up to 1600).
constexpr int kOverlayPolynomialMaxN = 150;
struct BoundCache {
  std::mutex mu;
  std::map<int, std::pair<double, double>> v;  // n -> (lower, r_crit,2 or NaN)
  std::pair<double, double> get(int n) {
    std::lock_guard<std::mutex> lock(mu);
    auto it = v.find(n);
    if (it != v.end()) return it->second;
    const double lo = n <= kOverlayPolynomialMaxN
                          ? static_cast<double>(windows::window_lower_bound(n, 20))
                          : static_cast<double>(windows::window_lower_bound_in<long double>(n, windows::Route::matrix));
    const double up = n >= 2 ? static_cast<double>(windows::r_crit2(n, 20)) : std::nan("");
    return v[n] = {lo, up};
  }
};
BoundCache& bound_cache() {
  static BoundCache c;
  return c;
}

// All n whose lower bound or r_crit,2 lies in [r_min, r_max].  Both decrease with n towards 7 - 4 sqrt 3
// and lower(n) < r_crit,2(n), so the scan stops at the first n with r_crit,2(n) < r_min; at most n = 400
// (windows that close to 7 - 4 sqrt 3 are 1e-9 wide, below any plot's resolution).
constexpr int kOverlayMaxN = 400;
RegisterOverlay windows_overlay("windows", [](double r_min, double r_max) {
  std::vector<std::pair<double, int>> out;
  for (int n = 1; n <= kOverlayMaxN; ++n) {
    const double up_closed = n >= 2 ? static_cast<double>(windows::r_crit2(n, 20)) : 1.0;
    if (up_closed < r_min) break;
    if (n >= 2 && up_closed >= r_min && up_closed <= r_max) out.push_back({up_closed, 0});  // red: r_crit,2(n)
    // lower(n) > 7 - 4 sqrt 3; skip the root finding when the whole window is above the range.
    if (n >= 2 && bound_cache().get(n).first > r_max) continue;
    const double lo = bound_cache().get(n).first;
    if (lo >= r_min && lo <= r_max) out.push_back({lo, 1});  // blue: lower bound
  }
  return out;
});

RegisterOverlay stripes_overlay("stripes", [](double r_min, double r_max) {
  static const std::vector<std::pair<double, int>> all = [] {
    std::vector<std::pair<double, int>> v;
    for (const auto& s : windows::thin_stripes(120, 20)) v.push_back({static_cast<double>(s.value), 1});  // Figure 6.8: m <= 120
    return v;
  }();
  std::vector<std::pair<double, int>> out;
  for (const auto& p : all)
    if (p.first >= r_min && p.first <= r_max) out.push_back(p);
  return out;
});

// ---- btob windows verify ----------------------------------------------------------------------------
struct VerifyArgs {
  std::string range = "2..20", out = "results/windows", precision = "double";
  windows::VerifyOptions opt;
  bool quiet = false;
};

void cmd_verify(VerifyArgs a, const std::string& command_line) {
  const auto t0 = std::chrono::steady_clock::now();
  const Range r = parse_range(a.range, 2);  // n = 1 (abcb) is never stable and has no r_crit,2
  if (a.opt.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.opt.threads));
  if (a.precision != "double" && a.precision != "long-double")
    throw UsageError(fmt::format("precision: got '{}', expected double or long-double", a.precision));
  a.opt.long_double = a.precision == "long-double";
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  std::ostringstream csv;
  csv << "n,position,r,lower_bound,upper_bound,iterations,orbits,on_pattern,expected,verdict\n";
  long passed = 0, total = 0;
  // One n at a time so that progress shows; the rows do not depend on the grouping.
  for (int n = r.first; n <= r.last; ++n) {
    for (const auto& row : windows::verify_windows(n, n, a.opt)) {
      passed += row.pass();
      ++total;
      csv << fmt::format("{},{},{:.17g},{:.17g},{:.17g},{},{},{},{},{}\n", row.n, row.position, row.r, row.lower, row.upper,
                         row.iterations, row.orbits, row.on_pattern, row.expected_on ? "all" : "none",
                         row.pass() ? "pass" : "fail");
    }
    if (!a.quiet) std::cerr << fmt::format("\rbtob: windows verify n = {} ({} of {} checks pass)", n, passed, total);
  }
  if (!a.quiet) std::cerr << "\n";
  const std::string stem = r.first == 2 && r.last == 125 ? std::string("verify")
                                                         : fmt::format("verify_{}-{}", r.first, r.last);
  const io::fs::path file = out / (stem + ".csv");
  io::write_text_atomic(file, csv.str());
  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("windows_verify");
  attrs["n_first"] = static_cast<long>(r.first);
  attrs["n_last"] = static_cast<long>(r.last);
  attrs["grid"] = std::string("paper (Section 4, 32 initial conditions)");
  attrs["iterations"] = fmt::format("{} + {} n", a.opt.base_iterations, a.opt.per_n);
  attrs["recorded"] = fmt::format("symbols of the last max({}, 4n) steps; on pattern = periodic with period 2n there "
                                  "and one period a rotation of 1^n 3^n", a.opt.tail);
  attrs["positions"] = std::string("below = lower - 0.05 (r_crit2 - lower); inside_q = lower + q (r_crit2 - lower)");
  attrs["scalar_type"] = a.precision;
  attrs["threads"] = static_cast<long>(a.opt.threads > 0 ? a.opt.threads : omp_get_max_threads());
  attrs["checks"] = total;
  attrs["passed"] = passed;
  attrs["total_seconds"] = seconds_since(t0);
  io::write_manifest(out / (stem + ".json"), attrs);
  std::cout << fmt::format("windows verify n = {}..{}: {} of {} checks pass ({:.1f} s); wrote {}\n", r.first, r.last,
                           passed, total, seconds_since(t0), file.string());
}

// ---- btob windows precision -------------------------------------------------------------------------
struct PrecisionArgs {
  std::string range = "1..150", out = "results/windows";
  int mpfr_digits = 32;
  bool no_plot = false;
};

template <class T>
void study(const char* name, windows::Route route, const Range& r, const std::vector<mpfr_float>& exact,
           std::ostringstream& csv, std::ostringstream& summary) {
  int largest_all = 0, largest_any = 0;
  bool prefix = true;
  double total_s = 0;
  const unsigned digits = mpfr_float::default_precision();  // the MPFR row's working precision
  for (int n = r.first; n <= r.last; ++n) {
    mpfr_float::default_precision(digits);
    const auto t0 = std::chrono::steady_clock::now();
    const T v = windows::window_lower_bound_in<T>(n, route);
    const double s = seconds_since(t0);
    total_s += s;
    mpfr_float::default_precision(60);
    const mpfr_float err = abs(mpfr_float(v) - exact[static_cast<std::size_t>(n - r.first)]);
    const bool finite = std::isfinite(static_cast<double>(v));
    // Correct to 12 decimals: within half a unit of the 12th decimal of the certified value.
    const bool ok = finite && err <= mpfr_float("5e-13");
    if (ok) largest_any = n;
    prefix = prefix && ok;
    if (prefix) largest_all = n;
    const double e = finite ? static_cast<double>(err) : std::nan("");
    csv << fmt::format("{},{},{},{:.17g},{:.3e},{},{:.3e}\n", name, windows::route_name(route), n,
                       static_cast<double>(v), e, ok ? 1 : 0, s);
  }
  summary << fmt::format("{},{},{},{},{:.3e}\n", name, windows::route_name(route), largest_all, largest_any,
                         total_s / (r.last - r.first + 1));
}

void cmd_precision(const PrecisionArgs& a, const std::string& command_line) {
  const auto t0 = std::chrono::steady_clock::now();
  const Range r = parse_range(a.range, 1);
  if (a.mpfr_digits < 10 || a.mpfr_digits > 1000)
    throw UsageError(fmt::format("mpfr-digits: got {}, expected 10..1000", a.mpfr_digits));
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  std::vector<mpfr_float> exact;
  for (int n = r.first; n <= r.last; ++n) exact.push_back(windows::window_lower_bound(n, 40));
  std::ostringstream csv, summary;
  csv << "precision,route,n,value,abs_error,correct_12,seconds\n";
  summary << "precision,route,largest_n_all_correct_12,largest_n_correct_12,seconds_per_bound\n";
  const std::string mp = fmt::format("mpfr:{}", a.mpfr_digits);
  for (auto route : {windows::Route::matrix, windows::Route::polynomial}) {
    study<float>("float", route, r, exact, csv, summary);
    study<double>("double", route, r, exact, csv, summary);
    study<long double>("long-double", route, r, exact, csv, summary);
    study<core::float128>("float128", route, r, exact, csv, summary);
    mpfr_float::default_precision(static_cast<unsigned>(a.mpfr_digits));
    study<mpfr_float>(mp.c_str(), route, r, exact, csv, summary);
  }
  io::write_text_atomic(out / "precision.csv", csv.str());
  io::write_text_atomic(out / "precision_summary.csv", summary.str());
  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("windows_precision");
  attrs["n_first"] = static_cast<long>(r.first);
  attrs["n_last"] = static_cast<long>(r.last);
  attrs["reference"] = std::string("window_lower_bound(n, 40 decimals), certified route (Q_n in MPFR, Sturm-checked)");
  attrs["criterion"] = std::string("|value - reference| <= 5e-13 (correct to 12 decimals)");
  attrs["root_finder"] = std::string("toms748 on (7-4sqrt3, r_crit2(n)), tolerance all but 2 bits of T");
  attrs["threads"] = 1L;
  attrs["total_seconds"] = seconds_since(t0);
  io::write_manifest(out / "precision.json", attrs);
  std::cout << summary.str();
  if (!a.no_plot) io::run_plot("windows_precision.py", {(out / "precision.csv").string(), (out / "precision.png").string()});
}

Register reg([](CLI::App& app) {
  CLI::App* w = app.add_subcommand("windows", "Windows of stability of (ab)^n(cb)^n: Q_n, bounds, checks (Section 4, App. B)");
  w->require_subcommand(1);

  auto poly_range = std::make_shared<std::string>("1..3");
  auto poly_form = std::make_shared<std::string>("both");
  CLI::App* p = w->add_subcommand("poly", "Q_n = r^2n P_n(r) P_n(1/r) - r^2n exactly, developed and factorised (Table B.2)");
  p->add_option("--n", *poly_range, "n or A..B, n >= 1")->capture_default_str();
  p->add_option("--form", *poly_form, "developed, factorised or both")->capture_default_str();
  p->callback([=] { cmd_poly(*poly_range, *poly_form); });

  auto b_range = std::make_shared<std::string>("1..100");
  auto b_digits = std::make_shared<int>(12);
  auto b_cert = std::make_shared<bool>(false);
  CLI::App* b = w->add_subcommand("bounds", "CSV n,lower_bound,upper_bound (Table B.1); --certify adds exact certificates");
  b->add_option("--n", *b_range, "n or A..B, n >= 1")->capture_default_str();
  b->add_option("--digits", *b_digits, "decimals after the point, 10..10000")->capture_default_str();
  b->add_flag("--certify", *b_cert, "exact rational sign change + Sturm counts for each n");
  b->callback([=] { cmd_bounds(*b_range, *b_digits, *b_cert); });

  auto t_digits = std::make_shared<int>(30);
  CLI::App* t = w->add_subcommand("thresholds", "7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1 in high precision");
  t->add_option("--digits", *t_digits, "decimals, 10..10000")->capture_default_str();
  t->callback([=] { cmd_thresholds(*t_digits); });

  auto s_m = std::make_shared<int>(120);
  auto s_digits = std::make_shared<int>(20);
  CLI::App* s = w->add_subcommand("stripes", "thin stripes r(l/m), eq. (6.3), 1/4 < l/m <= 1/2, m <= max-m");
  s->add_option("--max-m", *s_m, "largest denominator m")->capture_default_str();
  s->add_option("--digits", *s_digits, "decimals, 10..10000")->capture_default_str();
  s->callback([=] { cmd_stripes(*s_m, *s_digits); });

  auto va = std::make_shared<VerifyArgs>();
  CLI::App* v = w->add_subcommand("verify", "iterate the Section 4 grid inside/below each window; CSV + manifest");
  v->add_option("--n", va->range, "A..B, n >= 2")->capture_default_str();
  v->add_option("--out", va->out, "output directory")->capture_default_str();
  v->add_option("--iterations", va->opt.base_iterations, "iterations = this + per-n * n")->capture_default_str();
  v->add_option("--per-n", va->opt.per_n, "extra iterations per unit of n")->capture_default_str();
  v->add_option("--tail", va->opt.tail, "last steps whose symbols must follow the pattern (at least 4n)")
      ->capture_default_str();
  v->add_option("--precision", va->precision, "double or long-double")->capture_default_str();
  v->add_option("--threads", va->opt.threads, "OpenMP threads (default: all)");
  v->add_flag("--quiet", va->quiet, "no progress on stderr");
  v->callback([va, v] { cmd_verify(*va, command_line_of(v)); });

  auto pa = std::make_shared<PrecisionArgs>();
  CLI::App* q = w->add_subcommand("precision", "largest n with a 12-decimal bound per precision and route; CSV + PNG");
  q->add_option("--n", pa->range, "A..B, n >= 1")->capture_default_str();
  q->add_option("--out", pa->out, "output directory")->capture_default_str();
  q->add_option("--mpfr-digits", pa->mpfr_digits, "digits of the MPFR row")->capture_default_str();
  q->add_flag("--no-plot", pa->no_plot, "write data only");
  q->callback([pa, q] { cmd_precision(*pa, command_line_of(q)); });
});

}  // namespace
}  // namespace btob::cli
