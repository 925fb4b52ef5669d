// SPDX-License-Identifier: GPL-3.0-or-later
// The windows analyses as requests and results (core/request.hpp): Q_n exactly (`btob windows poly`), certified
// lower bounds and r_crit,2 (`windows bounds`, Table B.1), the paper's thresholds, the thin stripes of eq. (6.3),
// the iterator's check inside and below each window (`windows verify`) and the precision study of the lower bound
// (`windows precision`).  Every field is named as the command line's flag; every result can print its CSV.
// Those whose work is a list of n (poly, bounds, verify, precision) are sweeps (core/sweep.hpp): item i is
// n = first + i of the request's range, and a part carries what its n computed, so `mpirun -n P` splits them.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"
#include "windows/verify.hpp"
#include "windows/windows.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace btob::windows {

// ---- ranges of n ------------------------------------------------------------------------------------------
struct NRange {
  int first = 1, last = 1;
  int count() const { return last - first + 1; }
  // The n of item i of a sweep over this range.
  int n_of(std::size_t item) const { return first + static_cast<int>(item); }
};
inline constexpr int max_range_n = 5000;  // Q_n costs minutes at n = 5000 (windows.hpp, validate_n)

// "A..B" or "A" (whole text, decimal integers) with min_n <= A <= B <= 5000; anything else throws
// core::InvalidField(field, "'text'", "A..B or A with min_n <= A <= B <= 5000").
NRange parse_n_range(std::string_view text, int min_n = 1, const std::string& field = "n");

// The decimals of `digits` fields: 10..10000 (windows.hpp, validate_digits), else InvalidField naming `field`.
void require_digits(long digits, const std::string& field = "digits");

// ---- btob windows poly -------------------------------------------------------------------------------------
struct PolyRequest {
  std::string n = "1..3";     // n or A..B, 1 <= n <= 5000
  std::string form = "both";  // developed, factorised or both

  void validate() const;
  std::size_t work_items() const;  // the n of the range (core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("n", n, "n or A..B, n >= 1");
    v("form", form, "developed, factorised or both");
  }
};

struct PolyResult {
  std::vector<std::uint32_t> n, degree;  // [N]: n and the degree 4n of Q_n
  std::vector<std::string> developed;    // [N] Table B.2 left ("" unless asked for)
  std::vector<std::string> factorised;   // [N] Table B.2 right ("" unless asked for)
  // "Q_n = ..." lines, developed before factorised for each n.
  std::string text() const;
  void describe(core::Contents& c) const;  // arrays n, degree; attributes Q_<n>_developed / Q_<n>_factorised
};
// Some n of the range (items: ascending indices, n = first + item): Q_n's degree and text, item-major.
// No rows(): the bulk is Q_n's text (attributes and the printed lines), not rows of a dataset.
struct PolyPart {
  std::vector<std::size_t> items;
  std::vector<std::uint32_t> degree;
  std::vector<std::string> developed, factorised;
  template <class A> void members(A& a) { a(items, degree, developed, factorised); }
};
PolyPart run_part(const PolyRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control = {});
PolyResult merge(const PolyRequest& req, std::vector<PolyPart> parts);
// merge(req, {run_part(req, every n)}).
PolyResult run(const PolyRequest& req, const core::RunControl& control = {});

// ---- btob windows bounds -----------------------------------------------------------------------------------
struct BoundsRequest {
  std::string n = "1..100";  // n or A..B, 1 <= n <= 5000
  int digits = 12;           // decimals after the point, 10..10000
  bool certify = false;      // exact rational sign change + exact root counts (Descartes, Sturm fallback) for each n

  void validate() const;
  std::size_t work_items() const;  // the n of the range (core/sweep.hpp)
  // The dry run's cost model (core::SizedSweep, core/size_model.hpp): an item's cost grows with its n (about n^2.4),
  // so the estimate times the request for small n alone and extrapolates instead of computing its largest n.
  static constexpr const char* size_parameter = "n";
  double item_size(std::size_t item) const { return parse_n_range(n, 1, "n").n_of(item); }
  BoundsRequest sized(double size) const {
    BoundsRequest one = *this;
    one.n = std::to_string(static_cast<long>(size));
    return one;
  }
  template <class V> void fields(V&& v) {
    v("n", n, "n or A..B, n >= 1");
    v("digits", digits, "decimals after the point, 10..10000");
    v("certify", certify, "exact rational sign change + exact root counts (Descartes, Sturm fallback) for each n");
  }
};

struct BoundsResult {
  int digits = 12;                               // the request's digits of the printed bounds
  bool certified_run = false;                    // the request's certify: the bounds were proved in exact arithmetic
  std::vector<std::uint32_t> n;                  // [N]
  std::vector<std::string> lower_text;           // [N] lower bound, `digits` decimals (correctly rounded)
  std::vector<std::string> upper_text;           // [N] r_crit,2(n), `digits` decimals; "" for n = 1
  std::vector<double> lower_bound, upper_bound;  // [N] the same in double (upper NaN for n = 1)
  std::vector<Certificate> certificates;         // [N] when certify
  std::vector<std::string> a_text, b_text;       // [N] the certificate's a, b: exact D-decimal fractions
  std::vector<double> sign_a, sign_b, roots_0_a, roots_a_b, valid;  // [N] when certify (valid: 1 or 0)

  // n,lower_bound,upper_bound[,a,b,sign_Q_a,sign_Q_b,sturm_roots_0_a,sturm_roots_a_b,certified],lower_status,upper_status
  std::string csv() const;
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv (--out, Python's save())
  core::Status lower_status() const;                     // certified when every certificate holds, else estimated
  core::Status upper_status() const;                     // conjectured: r_crit,2(n)
  void describe(core::Contents& c) const;
};
// Some n of the range (items ascending, n = first + item), item-major: the bounds, and with --certify the
// certificate's bracket (exact rationals as GMP text "p/q") and its signs and root counts.
// No rows(): a few numbers per n, which the CSV table reads.
struct BoundsPart {
  std::vector<std::size_t> items;
  std::vector<std::string> lower_text, upper_text;
  std::vector<double> lower_bound, upper_bound;
  std::vector<std::string> a, b;  // when certify
  std::vector<int> sign_a, sign_b;
  std::vector<long> roots_0_a, roots_a_b;
  template <class A> void members(A& x) {
    x(items, lower_text, upper_text, lower_bound, upper_bound, a, b, sign_a, sign_b, roots_0_a, roots_a_b);
  }
};
BoundsPart run_part(const BoundsRequest& req, const std::vector<std::size_t>& items,
                    const core::RunControl& control = {});
BoundsResult merge(const BoundsRequest& req, std::vector<BoundsPart> parts);
// merge(req, {run_part(req, every n)}).
BoundsResult run(const BoundsRequest& req, const core::RunControl& control = {});

// ---- btob windows thresholds / stripes ---------------------------------------------------------------------
struct ThresholdsRequest {
  int digits = 30;  // decimals, 10..10000

  void validate() const;
  template <class V> void fields(V&& v) { v("digits", digits, "decimals, 10..10000"); }
};

struct ThresholdsResult {
  std::vector<Threshold>
      thresholds;  // 7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1: name, formula and value (windows::thresholds)
  std::vector<std::string> text;                         // [4] the values with `digits` decimals
  std::vector<double> value;                             // [4] the values in double
  std::string csv() const;                               // name,formula,value,status
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv (--out, Python's save())
  void describe(core::Contents& c) const;
};
ThresholdsResult run(const ThresholdsRequest& req, const core::RunControl& control = {});
// Its cost (core/work.hpp): one run of the four thresholds at `digits` decimals, probed on the request itself.
core::Work work(const ThresholdsRequest& req);

struct StripesRequest {
  int max_m = 120;  // largest denominator m, 1..100000
  int digits = 20;  // decimals, 10..10000

  void validate() const;
  template <class V> void fields(V&& v) {
    v("max-m", max_m, "largest denominator m");
    v("digits", digits, "decimals, 10..10000");
  }
};

struct StripesResult {
  std::vector<std::uint32_t> l, m, mirror_l;             // [S] l/m and its mirror (m - l)/m, sorted by r
  std::vector<std::string> text;                         // [S] r(l/m) with `digits` decimals
  std::vector<double> r;                                 // [S] r(l/m) in double
  std::string csv() const;                               // l,m,mirror_l,r,status
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv (--out, Python's save())
  void describe(core::Contents& c) const;
};
StripesResult run(const StripesRequest& req, const core::RunControl& control = {});
// Its cost (core/work.hpp): the stripes l/m, m <= max-m (about 3 max-m^2 / (4 pi^2) of them), each r(l/m) at
// `digits` decimals, probed on a smaller max-m at the same digits.
core::Work work(const StripesRequest& req);

// ---- btob windows verify -----------------------------------------------------------------------------------
struct VerifyRequest {
  std::string n = "2..20";           // A..B, 2 <= A <= B <= 5000 (n = 1, abcb, is never stable)
  long iterations = 60000;           // iterations = this + per-n * n, >= 100
  long per_n = 400;                  // extra iterations per unit of n, >= 0
  long tail = 40000;                 // last steps whose symbols must follow the pattern, 1..iterations-1 (>= 4n used)
  std::string precision = "double";  // double or long-double

  void validate() const;
  std::size_t work_items() const;  // the n of the range (core/sweep.hpp)
  // The file stem when none is given: verify for the committed n = 2..125, else verify_A-B (verify_stem).
  std::string default_name() const;
  template <class V> void fields(V&& v) {
    v("n", n, "A..B, n >= 2");
    v("iterations", iterations, "iterations = this + per-n * n");
    v("per-n", per_n, "extra iterations per unit of n");
    v("tail", tail, "last steps whose symbols must follow the pattern (at least 4n)");
    v("precision", precision, "double or long-double");
  }
};

struct VerifyResult {
  NRange range;                 // the window indices n checked
  VerifyOptions options;        // the check's iterations, tail and arithmetic
  std::vector<VerifyRow> rows;  // 4 per n: below, inside_25, inside_50, inside_75
  long passed = 0, total = 0;   // checks that passed, of all
  double total_seconds = 0;     // wall time of the run, seconds
  // Flat views of the rows for describe(): [4N] each.
  std::vector<std::uint32_t> n, position, on_pattern, orbits, iterations_run, expected_on, pass;
  std::vector<double> r, lower, upper;

  std::string csv() const;  // n,position,r,lower_bound,upper_bound,iterations,orbits,on_pattern,expected,verdict
  core::Tables tables() const { return {{"", csv()}}; }  // NAME.csv
  void describe(core::Contents& c) const;
};
// Some n of the range (items ascending, n = first + item): their 4 rows each, item-major, and the seconds spent.
// No rows(): 4 rows per n, which the CSV table and the pass counts read.
struct VerifyPart {
  std::vector<std::size_t> items;
  std::vector<VerifyRow> rows;
  double seconds = 0;
  template <class A> void members(A& a) { a(items, rows, seconds); }
};
VerifyPart run_part(const VerifyRequest& req, const std::vector<std::size_t>& items,
                    const core::RunControl& control = {});
// total_seconds is the parts' seconds summed (one process: its run's time).
VerifyResult merge(const VerifyRequest& req, std::vector<VerifyPart> parts);
// merge(req, {run_part(req, every n)}).
VerifyResult run(const VerifyRequest& req, const core::RunControl& control = {});

// The file stem of a verify result: "verify" for the committed n = 2..125, else "verify_A-B".
std::string verify_stem(const NRange& r);

// ---- btob windows precision --------------------------------------------------------------------------------
struct BoundPrecisionRequest {
  std::string n = "1..150";  // A..B, 1 <= A <= B <= 5000
  int mpfr_digits = 32;      // digits of the MPFR row, 10..1000

  void validate() const;
  std::size_t work_items() const;  // the n of the range (core/sweep.hpp)
  template <class V> void fields(V&& v) {
    v("n", n, "A..B, n >= 1");
    v("mpfr-digits", mpfr_digits, "digits of the MPFR row");
  }
};

struct BoundPrecisionRow {
  std::string precision, route;
  int n = 0;
  double value = 0, abs_error = 0, seconds = 0;  // abs_error NaN when the bound is not finite
  bool correct_12 = false;
};
struct BoundPrecisionSummary {
  std::string precision, route;
  int largest_all = 0, largest_any = 0;  // largest n with every n up to it / with this n correct to 12 decimals
  double seconds_per_bound = 0;
};
struct BoundPrecisionResult {
  NRange range;                                // the window indices n compared
  std::vector<BoundPrecisionRow> rows;         // (route, precision, n) in that order of nesting
  std::vector<BoundPrecisionSummary> summary;  // per precision and route: correct digits and time per bound
  double total_seconds = 0;                    // wall time of the run, seconds
  // Flat views for describe(): [P, N] with P = the precision x route rows of the summary.
  std::vector<double> value, abs_error, seconds;
  std::vector<std::uint8_t> correct_12;
  std::vector<std::uint32_t> n;
  std::vector<std::string> precision, route;  // per row of the [P, N] views: its scalar type and route (names)
  std::vector<std::string> row;               // per row: "precision route", the rows' axis coordinates

  std::string csv() const;          // precision,route,n,value,abs_error,correct_12,seconds
  std::string summary_csv() const;  // precision,route,largest_n_all_correct_12,largest_n_correct_12,seconds_per_bound
  core::Tables tables() const { return {{"", csv()}, {"summary", summary_csv()}}; }  // NAME.csv, NAME_summary.csv
  void describe(core::Contents& c) const;
};
// Some n of the range (items ascending, n = first + item): per n its 10 bounds, route-major then precision (float,
// double, long-double, float128, mpfr:D), as in BoundPrecisionResult::rows; and the part's seconds.
// No rows(): 10 values per n, which the summary reads; the datasets are [precision x route, n] (not a row per n).
struct BoundPrecisionPart {
  std::vector<std::size_t> items;
  std::vector<double> value, abs_error, seconds;  // [items x 10]
  std::vector<std::uint8_t> correct_12;
  double total_seconds = 0;
  template <class A> void members(A& a) { a(items, value, abs_error, seconds, correct_12, total_seconds); }
};
BoundPrecisionPart run_part(const BoundPrecisionRequest& req, const std::vector<std::size_t>& items,
                            const core::RunControl& control = {});
// The rows and the summary (largest n correct from the first on, and at all) from the parts; total_seconds is
// the parts' seconds summed.
BoundPrecisionResult merge(const BoundPrecisionRequest& req, std::vector<BoundPrecisionPart> parts);
// merge(req, {run_part(req, every n)}).
BoundPrecisionResult run(const BoundPrecisionRequest& req, const core::RunControl& control = {});

}  // namespace btob::windows
