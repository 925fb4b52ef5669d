// SPDX-License-Identifier: GPL-3.0-or-later
// The requests of `btob pattern` (Sections 6.2, 7 of the paper): what one word does at one r, its stability set,
// its exact characteristic polynomial (WordRequest), and the atlas of every word up to a length with its check
// against the iterator (AtlasRequest).  Values computed in a multiprecision type travel as decimal text with the
// precision's digits, never rounded to double; the numeric arrays (for plots and Python) are doubles.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"
#include "patterns/atlas.hpp"
#include "patterns/patterns.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace btob::patterns {

// `btob pattern WORD --r R` (verdict), `WORD --window` (stability set), `WORD --charpoly` (exact polynomial).
struct WordRequest {
  std::string word;                  // over 1, 2, 3: 132312, 132^3312^3, (ab)(cb)(acb)
  std::string r;                     // decimal text, read in the precision (exact to its digits): verdict mode
  std::string precision = "double";  // verdict: float, double, long-double, float128, mpfr:D; window: mpfr:D
  bool window = false, charpoly = false;
  long digits = 0;  // window: digits of the endpoints, 5..1000 (> 15 computes in MPFR); 0: 17

  enum class Mode { verdict, window, charpoly };
  Mode mode() const { return charpoly ? Mode::charpoly : window ? Mode::window : Mode::verdict; }
  void validate() const;
  template <class V> void fields(V&& v) {
    v("word", word, "a word over 1,2,3 (132312, 132^3312^3, (ab)(cb)(acb))", core::positional);
    v("r", r, "restitution coefficient in (0,1) (verdict mode), read in the precision");
    v("precision", precision, "verdict: float, double, long-double, float128 or mpfr:<digits>; window: mpfr:<digits>");
    v("window", window, "the stability set as CSV word,r_low,r_high,low_reason,high_reason");
    v("charpoly", charpoly, "the exact characteristic polynomial of the period matrix and its discriminant");
    v("digits", digits, "window mode: digits of the endpoints, 5..1000 (> 15 computes in MPFR)");
  }
};

// One eigenvalue of the period matrix, as text in the precision's digits.
struct EigenText {
  std::string re, im, ratio;  // ratio: |l| / |l1|
  bool real = false, in_domain = false, feasible = false;
  int first_failure = -1;             // -1 feasible, 0 domain, k: the k-th feasibility inequality
  int failing_symbol = 0;             // the symbol of that inequality
  std::array<std::string, 3> vector;  // real eigenvalues: unit eigenvector in Q
};

struct WordResult {
  WordRequest::Mode mode = WordRequest::Mode::verdict;  // what was computed: the verdict at r, the stability window, or
                                                        // the characteristic polynomial
  std::string scalar_type;                              // the type the numbers were computed in
  Word word, primitive;  // the word as given and its primitive root (the shortest period)
  // verdict
  std::string r;                     // r as the precision holds it
  bool reduced = false;              // analysed through J M_h (Section 7.1)
  std::vector<EigenText> spectrum;   // by decreasing modulus
  std::string outcome, reason;       // stable / unstable / neutral / undecided / none; why not stable
  std::string lyapunov2, lyapunov3;  // the orbit's exponents lambda1 >= lambda2 along its tangent directions,
                                     // log(|mu_j|/|mu_k|)/p (natural log, per iteration; patterns::Verdict)
  std::string letters;               // collision letters of the periodic orbit (when there is one)
  std::vector<std::array<std::string, 7>> orbit;  // k-th point: x y z theta w1 w2 (text) and its symbol first
  std::vector<double> eigen_re, eigen_im, eigen_modulus, orbit_xyz;  // numeric views [3], [3], [3], [p, 3]
  // The same numbers as decimals with the precision's digits (NAME.h5 and Python, beside the doubles): [3], [3],
  // [2] (lambda1, lambda2; empty without a periodic orbit), [3p] (x, y, z of each point).
  std::vector<std::string> eigen_re_decimal, eigen_im_decimal, exponents_decimal, orbit_decimal;
  // window
  std::vector<std::array<std::string, 4>> intervals;  // r_low, r_high, low_reason, high_reason
  std::vector<double> r_low,
      r_high;  // window: each interval's ends as doubles (the decimals are r_low_decimal, r_high_decimal)
  std::vector<std::string> r_low_decimal, r_high_decimal, low_reason, high_reason;  // the columns of intervals
  std::string window_tol;  // the bisection's tolerance in r (decimal text)
  int window_digits = 0;   // significant digits of the printed ends
  // charpoly: chi(lambda) = lambda^3 + c2 lambda^2 + c1 lambda + c0, exact in r
  std::string c2, c1, c0, discriminant;

  std::string text() const;        // what the command line prints
  std::string window_csv() const;  // word,r_low,r_high,low_reason,high_reason,status
  core::Tables tables() const;     // window mode: NAME.csv (window_csv); none otherwise
  void describe(core::Contents& c) const;
  void describe_window(core::Contents& c) const;
  void describe_verdict_decimals(core::Contents& c) const;
};

WordResult run(const WordRequest& req, const core::RunControl& control = {});
namespace detail {
std::string verdict_text(const WordResult& res);  // WordResult::text() in verdict mode (verdict_text.cpp)
}
// Its cost (core/work.hpp): one analysis of the word (verdict, window or characteristic polynomial), probed on the
// request itself: its cost depends on the word, the mode, the precision and the digits together.
core::Work work(const WordRequest& req);

// `btob pattern atlas`: every canonical primitive word of length <= max-length with its stability set and the
// check against the iterator at Table 6.1's r values; or, with --feasible, every feasible periodic orbit.
struct AtlasRequest {
  long max_length = 12;
  bool feasible = false, no_check = false;
  long ics = 1000, iterations = 5000, tail = 2000;  // the iterator check
  std::uint64_t seed = 1;
  long max_period = 500;

  void validate() const;
  // A sweep (core/sweep.hpp): items 0..W-1 are the words of enumerate_canonical(max-length), in its order; with
  // the iterator check, items W.. are Table 6.1's r values (the detection at each r is independent of the others).
  std::size_t work_items() const;
  // The same count, the words enumerated with `cancel` polled (3^16 words of length 16 take seconds): what the
  // sweep layer calls first (core::work_items), so that every later enumeration finds them listed.
  std::size_t work_items(const core::CancelToken* cancel) const;
  bool checks() const { return !feasible && !no_check; }
  std::string default_name() const { return feasible ? "feasible" : "atlas"; }
  template <class V> void fields(V&& v) {
    v("max-length", max_length, "longest word, in symbols, 1..16");
    v("feasible", feasible, "every feasible periodic orbit, stable or unstable (feasible.csv, feasible_counts.csv)");
    v("no-check", no_check, "skip the iterator check");
    v("ics", ics, "iterator check: random initial points per r");
    v("iterations", iterations, "iterator check: iterations per orbit");
    v("tail", tail, "iterator check: symbols kept at the end of each orbit, 1..iterations");
    v("seed", seed, "iterator check: seed of the initial points");
    v("max-period", max_period, "iterator check: longest period searched, 1..tail/2");
  }
};

struct AtlasResult {
  AtlasRequest request;   // what was computed (its lengths and check sizes go to the attributes)
  bool feasible = false;  // the request's mode: every feasible periodic orbit (true) or the stable atlas (false)
  double tol = 0;         // bisection width in r
  long grid_points = 0;   // r values of the scan's grid
  std::vector<AtlasEntry> entries;  // stable atlas
  std::vector<FeasibleEntry>
      feasible_entries;  // feasible atlas: every feasible periodic orbit's interval, stable or not
  long words_scanned = 0, stable_words = 0,
       unstable_only_words = 0;  // words scanned; of them, stable somewhere, and feasible but never stable
  long followed_checked = 0,
       followed_agree = 0;  // feasible atlas: unstable orbits followed by the map with a predicted escape time, and of
                            // them those that escaped within [predicted / 2 - 2, 2 predicted + 2] periods
  bool checked = false;     // the iterator check ran
  long detected = 0, disagreements = 0, quasi_periodic = 0,
       missed = 0;  // the iterator check's counts: periodic orbits detected, detections the atlas does not confirm,
                    // quasi-periodic orbits, atlas windows it missed
  double atlas_seconds = 0, check_seconds = 0;  // wall times of the atlas and of the iterator check, seconds
  core::Tables csv;                             // (role, content) in writing order: NAME.csv, NAME_detected.csv, ...
  std::vector<double> r_low, r_high, symbols;   // one row per interval (stable atlas; feasible: all)
  std::vector<std::uint8_t> stable;             // per row: 1 stable, 0 unstable (feasible atlas)
  std::vector<std::string> word;                // per row: the word, paper notation
  std::vector<std::string> low_reason, high_reason;  // per row: what begins / ends the interval (CSV columns)
  // The iterator check's tables as arrays (NAME_detected.csv, NAME_long_windows.csv, NAME_missed.csv: the same
  // rows and values), and the feasible atlas's counts (NAME_counts.csv), so that NAME.h5 holds every table.
  struct Detections {
    std::vector<double> r, symbols, symbol_periodic_fraction, periodic_fraction;
    std::vector<std::uint32_t> collisions, count;
    std::vector<std::string> word, status;
  } detections;
  struct LongWindows {
    std::vector<double> r_low, r_high, symbols;
    std::vector<std::string> word;
  } long_windows;
  struct Missed {
    std::vector<double> r, symbols, r_low, r_high;
    std::vector<std::string> word;
  } missed_entries;
  FeasibleCounts counts;  // feasible atlas: the counts of NAME_counts.csv

  core::Tables tables() const { return csv; }
  std::string summary() const;  // the lines the command line prints
  void describe(core::Contents& c) const;
  void describe_check(core::Contents& c) const;  // the iterator check's datasets (describe calls it)
};

// Some items of an atlas (ascending: words first, then r values of the check), item-major: what each computed.
// No rows(): per word a stability set of varying length and per r its patterns, which merge sorts into the tables;
// no dataset has one row per item.
struct AtlasPart {
  std::vector<std::size_t> items;
  std::vector<std::vector<Interval<double>>> stable;            // per word (stable atlas): its stability set
  std::vector<std::vector<FeasibleInterval<double>>> feasible;  // per word (feasible atlas): its feasibility set
  std::vector<std::vector<Followed>> followed;                  // per word (feasible atlas): its unstable intervals
  std::vector<long> periodic;                                   // per r: orbits with an eventual period
  std::vector<std::vector<std::pair<Word, long>>> found;        // per r: patterns and counts, as detect_patterns
  double atlas_seconds = 0, check_seconds = 0;
  template <class A> void members(A& a) {
    a(items, stable, feasible, followed, periodic, found, atlas_seconds, check_seconds);
  }
};
AtlasPart run_part(const AtlasRequest& req, const std::vector<std::size_t>& items,
                   const core::RunControl& control = {});
// The tables and counts of the whole atlas from its parts (the check's status column, the stability sets of the
// found patterns longer than max-length and the missed entries are derived here, on one process); the seconds
// are the parts' summed.
AtlasResult merge(const AtlasRequest& req, std::vector<AtlasPart> parts);
// merge(req, {run_part(req, every item)}).
AtlasResult run(const AtlasRequest& req, const core::RunControl& control = {});

}  // namespace btob::patterns
