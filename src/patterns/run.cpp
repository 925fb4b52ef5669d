// SPDX-License-Identifier: GPL-3.0-or-later
// The patterns requests' runs: a word's verdict, window or characteristic polynomial in the chosen precision, and
// the atlas of stable or feasible windows with its check against Table 6.1 (run_part, merge).
#include "patterns/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "core/sweep.hpp"
#include "patterns/accuracy.hpp"
#include "patterns/exact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

namespace btob::patterns {

namespace {

// Decimal text of a value with at most the digits its type holds.
template <class T> std::string str(const T& v, int digits) {
  if constexpr (std::is_same_v<T, float>) return fmt::format("{:.{}g}", v, std::min(digits, 9));
  else if constexpr (std::is_same_v<T, double>) return fmt::format("{:.{}g}", v, std::min(digits, 17));
  else if constexpr (std::is_same_v<T, long double>) return fmt::format("{:.{}g}", v, std::min(digits, 21));
  else return v.str(digits);
}

template <class T> T from_text(const std::string& s) {
  if constexpr (std::is_same_v<T, float>) return std::stof(s);
  else if constexpr (std::is_same_v<T, double>) return std::stod(s);
  else if constexpr (std::is_same_v<T, long double>) return std::stold(s);
  else return T(s);
}

// The text of eigenvalue i of the verdict v: each part to the digits the reference vouches for (chk).
template <class T> EigenText eigen_text(const Verdict<T>& v, const accuracy::Check& chk, std::size_t i, int digits) {
  const Word& u = v.word;
  const EigenInfo<T>& e = v.spectrum[i];
  EigenText t;
  const int dr = chk.re_digits[i], di = chk.im_digits[i];
  t.re = accuracy::scaled_text(e.scaled_re, e.log_scale, dr, str(e.re, dr), e.re);
  const T abs_im = e.im < 0 ? T(-e.im) : e.im;
  t.im = accuracy::scaled_text(T(e.scaled_im < 0 ? T(-e.scaled_im) : e.scaled_im), e.log_scale, di, str(abs_im, di),
                               abs_im);
  if (e.im < 0) t.im = "-" + t.im;
  // |mu|/|mu1| from the normalised moduli (the same scale): never 0/0
  const T ratio = e.scaled_modulus / v.spectrum[0].scaled_modulus;
  const int dq = accuracy::vouched_digits(chk.error[i] + chk.error[0], std::min(digits, 6));
  t.ratio = accuracy::scaled_text(ratio, T(0), dq, str(ratio, std::max(dq, 1)), ratio);
  t.real = e.real;
  t.in_domain = e.in_domain;
  t.feasible = e.feasible;
  t.first_failure = e.first_failure;
  if (e.first_failure > 0) t.failing_symbol = int(u.s[static_cast<std::size_t>(e.first_failure - 1)]);
  if (e.real)
    for (int i = 0; i < 3; ++i) t.vector[static_cast<std::size_t>(i)] = str(e.vector(i), 10);
  return t;
}

// The periodic orbit's points of the verdict v: symbol, x, y, z to `digits`, theta, w1, w2 to 12.
template <class T> void fill_orbit(WordResult& res, const Verdict<T>& v, int digits, const core::CancelToken* cancel) {
  const Word& u = v.word;
  for (std::size_t k = 0; k < v.orbit.size(); ++k) {
    core::check_cancel(cancel);  // a point's seven decimals: milliseconds in MPFR at thousands of digits
    const auto& p = v.orbit[k];
    const auto [w1, w2] = core::strip<T>(p);
    res.orbit.push_back({std::to_string(int(u.s[k])), str(p(0), digits), str(p(1), digits), str(p(2), digits),
                         str(core::theta<T>(p), 12), str(w1, 12), str(w2, 12)});
    for (int i = 0; i < 3; ++i) res.orbit_xyz.push_back(static_cast<double>(p(i)));
    for (int i = 1; i <= 3; ++i) res.orbit_decimal.push_back(res.orbit.back()[static_cast<std::size_t>(i)]);
  }
}

template <class T>
void fill_verdict(WordResult& res, const Word& w, const std::string& r_text, int digits,
                  const core::CancelToken* cancel) {
  const Verdict<T> v = analyse<T>(w, from_text<T>(r_text), cancel);
  accuracy::Check chk;  // the digits printed: those the reference in the next wider type confirms (accuracy.hpp)
  chk.fill(digits);
  std::string ref_outcome, ref_type;
  if constexpr (!std::is_same_v<T, core::mpfr_float>) {
    using H = typename accuracy::Reference<T>::type;
    const core::MpfrDigits guard(accuracy::mpfr_digits);
    const Verdict<H> ref = analyse<H>(w, from_text<H>(r_text), cancel);
    chk = accuracy::check(v, ref);
    ref_outcome = outcome_name(ref.outcome);
    ref_type =
        std::is_same_v<H, core::mpfr_float> ? fmt::format("mpfr:{}", accuracy::mpfr_digits) : core::scalar_name<H>();
  }
  const Word& u = v.word;
  res.scalar_type = core::scalar_name<T>();
  res.primitive = u;
  res.r = str(v.r, digits);
  res.reduced = v.reduced;
  for (std::size_t i = 0; i < v.spectrum.size(); ++i) {
    const EigenInfo<T>& e = v.spectrum[i];
    const EigenText t = eigen_text(v, chk, i, digits);
    res.spectrum.push_back(t);
    res.eigen_re.push_back(static_cast<double>(e.re));
    res.eigen_im.push_back(static_cast<double>(e.im));
    res.eigen_modulus.push_back(static_cast<double>(e.modulus));
    res.eigen_re_decimal.push_back(t.re);
    res.eigen_im_decimal.push_back(t.im);
  }
  res.outcome = outcome_name(v.outcome);
  res.reason = v.reason;
  res.lyapunov2 = str(v.lyapunov2, std::max(chk.lyapunov_digits, 1));
  res.lyapunov3 = str(v.lyapunov3, std::max(chk.lyapunov_digits, 1));
  if (!chk.same_outcome) {  // the verdict is not the precision's to give: no orbit is vouched for either
    res.outcome = outcome_name(Outcome::undecided);
    res.reason =
        fmt::format("precision: {} in {}, {} in {}", outcome_name(v.outcome), res.scalar_type, ref_outcome, ref_type);
    return;
  }
  if (v.orbit_eigen < 0) return;
  res.exponents_decimal = {res.lyapunov2, res.lyapunov3};
  res.letters = v.letters;
  fill_orbit(res, v, digits, cancel);
}

template <class T>
void fill_window(WordResult& res, const Word& w, const T& tol, int digits, const core::CancelToken* cancel) {
  res.scalar_type = core::scalar_name<T>();
  res.window_tol = str(tol, 3);
  res.window_digits = digits;
  for (const auto& iv : stability_set<T>(w, default_grid(), tol, cancel)) {
    res.intervals.push_back({str(iv.lo, digits), str(iv.hi, digits), iv.lo_reason, iv.hi_reason});
    res.r_low.push_back(static_cast<double>(iv.lo));
    res.r_high.push_back(static_cast<double>(iv.hi));
    res.r_low_decimal.push_back(res.intervals.back()[0]);
    res.r_high_decimal.push_back(res.intervals.back()[1]);
    res.low_reason.push_back(iv.lo_reason);
    res.high_reason.push_back(iv.hi_reason);
  }
}

void verdict(WordResult& res, const WordRequest& req, const Word& w, const core::CancelToken* cancel) {
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  switch (prec.kind) {
    case core::Precision::Kind::f32: fill_verdict<float>(res, w, req.r, 9, cancel); break;
    case core::Precision::Kind::f80: fill_verdict<long double>(res, w, req.r, 21, cancel); break;
    case core::Precision::Kind::f128: fill_verdict<core::float128>(res, w, req.r, 34, cancel); break;
    case core::Precision::Kind::mpfr: {
      const core::MpfrDigits guard(prec.mpfr_digits);
      fill_verdict<core::mpfr_float>(res, w, req.r, prec.mpfr_digits, cancel);
      break;
    }
    default: fill_verdict<double>(res, w, req.r, 17, cancel); break;
  }
}

void window(WordResult& res, const WordRequest& req, const Word& w, const core::CancelToken* cancel) {
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  const int digits = static_cast<int>(req.digits);
  if (digits > 15 || prec.kind == core::Precision::Kind::mpfr) {
    const int d = std::max(digits, prec.mpfr_digits);
    const core::MpfrDigits guard(d + 15);  // guard digits for the products
    // Bisection down to 10^-(d+3): the d printed digits are then correct up to rounding.
    fill_window<core::mpfr_float>(res, w, core::mpfr_float(pow(core::mpfr_float(10), -(d + 3))), d, cancel);
  } else {
    fill_window<double>(res, w, 1e-15, digits > 0 ? digits : 17, cancel);  // 1e-15: a few ulps of r near 0.2
  }
}

void charpoly(WordResult& res, const Word& w) {
  const CharPoly chi = characteristic_polynomial(w);
  res.scalar_type = "exact rational";
  res.reduced = is_J_square(primitive_root(w));  // the same test characteristic_polynomial applies
  res.c2 = chi.c2.to_string();
  res.c1 = chi.c1.to_string();
  res.c0 = chi.c0.to_string();
  res.discriminant = discriminant(chi).to_string();
}

}  // namespace

WordResult run(const WordRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  WordResult res;
  res.mode = req.mode();
  res.word = parse_word(req.word, "word");
  res.primitive = primitive_root(res.word);
  switch (res.mode) {
    case WordRequest::Mode::verdict: verdict(res, req, res.word, control.cancel); break;
    case WordRequest::Mode::window: window(res, req, res.word, control.cancel); break;
    case WordRequest::Mode::charpoly: charpoly(res, res.word); break;
  }
  return res;
}

}  // namespace btob::patterns

namespace btob::patterns {
namespace {

// Whether `f.r` lies inside one of the atlas's stability intervals of f.word.
bool in_atlas(const std::vector<AtlasEntry>& entries, const Detected& f) {
  for (const auto& e : entries)
    if (e.word == f.word)
      for (const auto& iv : e.intervals)
        if (iv.lo < f.r && f.r < iv.hi) return true;
  return false;
}

// The status column of detected.csv for one (r, pattern) pair; counts disagreements and neutral orbits.
std::string detection_status(const AtlasRequest& req, const std::vector<AtlasEntry>& entries, const Detected& f,
                             AtlasResult& res) {
  if (static_cast<long>(f.word.size()) > req.max_length) {
    const Verdict<double> v = analyse<double>(f.word, f.r);
    res.disagreements += v.outcome != Outcome::stable;
    return v.outcome == Outcome::stable
               ? std::string("longer than L: stable (verdict)")
               : fmt::format("longer than L: NOT stable (verdict: {}; {}; |l2|/|l1| = {:.6f})", outcome_name(v.outcome),
                             v.reason, v.spectrum[1].modulus / v.spectrum[0].modulus);
  }
  if (in_atlas(entries, f)) return "stable in atlas";
  // A symbol-periodic orbit that is not a stable periodic orbit: say what the analysis sees there.
  const Verdict<double> v = analyse<double>(f.word, f.r);
  const double ratio = v.spectrum[1].modulus / v.spectrum[0].modulus;
  // A neutral period matrix (|l2| = |l1|, e.g. the rotation P2 of the word 2): the orbit turns on an invariant
  // curve with a periodic symbol sequence; it is quasi-periodic, not a periodic sink, and the atlas (sinks only)
  // rightly does not list it.  1e-9: the moduli are computed in double.
  if (std::fabs(ratio - 1) < 1e-9) {
    ++res.quasi_periodic;
    return fmt::format("quasi-periodic (neutral period matrix, |l2|/|l1| = {:.6f}: invariant curves)", ratio);
  }
  ++res.disagreements;
  return fmt::format("NOT stable in atlas ({}; {}; |l2|/|l1| = {:.6f})", outcome_name(v.outcome), v.reason, ratio);
}

// The iterator's detections at Table 6.1's r values, each with its status against the atlas: the "detected" table
// and its datasets; returns the (r, word) pairs seen.
std::set<std::pair<double, Word>> detected_table(const AtlasRequest& req, const DetectionRun& d, AtlasResult& res) {
  const std::vector<double>& rs = d.r;
  // Per r: symbol_periodic_fraction counts the orbits whose symbol sequence is eventually periodic, which includes
  // the invariant curves of P2 (symbols 222..., quasi-periodic in the state); periodic_fraction counts only the
  // orbits whose word the row's status does not call quasi-periodic (periodic orbits of the map itself).
  core::CsvTable det("r,word,symbols,collisions,count,ics,symbol_periodic_fraction,periodic_fraction,status");
  std::set<std::pair<double, Word>> seen;
  std::vector<std::string> status;
  std::vector<long> periodic(rs.size(), 0);
  for (const auto& f : d.found) {
    status.push_back(detection_status(req, res.entries, f, res));
    const std::size_t ir = static_cast<std::size_t>(std::find(rs.begin(), rs.end(), f.r) - rs.begin());
    if (status.back().rfind("quasi-periodic", 0) != 0) periodic[ir] += f.count;
  }
  for (std::size_t k = 0; k < d.found.size(); ++k) {
    const Detected& f = d.found[k];
    seen.insert({f.r, f.word});
    const std::size_t ir = static_cast<std::size_t>(std::find(rs.begin(), rs.end(), f.r) - rs.begin());
    const double ics = static_cast<double>(d.ics);
    det.row({fmt::format("{}", f.r), to_paper(f.word), fmt::format("{}", f.word.size()),
             fmt::format("{}", collisions(f.word)), fmt::format("{}", f.count), fmt::format("{}", d.ics),
             fmt::format("{:.4f}", static_cast<double>(d.periodic[ir]) / ics),
             fmt::format("{:.4f}", static_cast<double>(periodic[ir]) / ics), status[k]});
    AtlasResult::Detections& a = res.detections;
    a.r.push_back(f.r);
    a.word.push_back(to_paper(f.word));
    a.symbols.push_back(static_cast<double>(f.word.size()));
    a.collisions.push_back(static_cast<std::uint32_t>(collisions(f.word)));
    a.count.push_back(static_cast<std::uint32_t>(f.count));
    a.symbol_periodic_fraction.push_back(static_cast<double>(d.periodic[ir]) / ics);
    a.periodic_fraction.push_back(static_cast<double>(periodic[ir]) / ics);
    a.status.push_back(status[k]);
  }
  res.csv.emplace_back("detected", det.text());
  return seen;
}

// Stability sets of the found patterns longer than L (not in the atlas), same columns as the atlas: the
// "long_windows" table and its datasets.
void long_windows(const AtlasRequest& req, const std::vector<double>& grid, const DetectionRun& d, AtlasResult& res) {
  std::vector<AtlasEntry> long_entries;
  for (const auto& f : d.found)
    if (static_cast<long>(f.word.size()) > req.max_length &&
        std::none_of(long_entries.begin(), long_entries.end(), [&](const AtlasEntry& e) { return e.word == f.word; }))
      long_entries.push_back({f.word, stability_set<double>(f.word, grid, res.tol)});
  for (const auto& e : long_entries)
    for (const auto& iv : e.intervals) {
      res.long_windows.word.push_back(to_paper(e.word));
      res.long_windows.symbols.push_back(static_cast<double>(e.word.size()));
      res.long_windows.r_low.push_back(iv.lo);
      res.long_windows.r_high.push_back(iv.hi);
    }
  res.csv.emplace_back("long_windows", atlas_csv(long_entries));
}

// The atlas's stable intervals containing one of Table 6.1's r at which the iterator did not see the word: the
// "missed" table and its datasets.
void missed_table(const std::vector<double>& rs, const std::set<std::pair<double, Word>>& seen, AtlasResult& res) {
  core::CsvTable missed("r,word,symbols,r_low,r_high");
  for (double r : rs)
    for (const auto& e : res.entries)
      for (const auto& iv : e.intervals)
        if (iv.lo < r && r < iv.hi && !seen.count({r, e.word})) {
          missed.row({fmt::format("{}", r), to_paper(e.word), fmt::format("{}", e.word.size()),
                      fmt::format("{:.17g}", iv.lo), fmt::format("{:.17g}", iv.hi)});
          res.missed_entries.r.push_back(r);
          res.missed_entries.word.push_back(to_paper(e.word));
          res.missed_entries.symbols.push_back(static_cast<double>(e.word.size()));
          res.missed_entries.r_low.push_back(iv.lo);
          res.missed_entries.r_high.push_back(iv.hi);
          ++res.missed;
        }
  res.csv.emplace_back("missed", missed.text());
}

// The iterator at Table 6.1's r values against the atlas (`d` is its detection there, in their order): detected ->
// long windows -> missed.
void check(const AtlasRequest& req, const std::vector<double>& grid, const DetectionRun& d, AtlasResult& res) {
  const std::set<std::pair<double, Word>> seen = detected_table(req, d, res);
  long_windows(req, grid, d, res);
  missed_table(d.r, seen, res);
  res.checked = true;
  res.detected = static_cast<long>(d.found.size());
}

// Bisection widths in r: stable endpoints to ~1e-15 (double resolves r to 2.8e-17 near 0.2); feasible transitions
// are reported to ~13 digits.
constexpr double stable_tol = 1e-15, feasible_tol = 1e-13;
constexpr long followed_max_periods = 2000;

// The stable atlas's tables and counts from its entries (and the check from `d` unless null).
void stable_atlas(const AtlasRequest& req, AtlasResult& res, const DetectionRun* d) {
  res.tol = stable_tol;
  const std::vector<double> grid = default_grid();
  res.grid_points = static_cast<long>(grid.size());
  res.words_scanned = static_cast<long>(res.entries.size());
  for (const auto& e : res.entries) {
    res.stable_words += !e.intervals.empty();
    for (const auto& iv : e.intervals) {
      res.r_low.push_back(iv.lo);
      res.r_high.push_back(iv.hi);
      res.symbols.push_back(static_cast<double>(e.word.size()));
      res.word.push_back(to_paper(e.word));
      res.stable.push_back(1);
      res.low_reason.push_back(iv.lo_reason);
      res.high_reason.push_back(iv.hi_reason);
    }
  }
  res.csv.emplace_back("", atlas_csv(res.entries));
  if (d) check(req, grid, *d, res);
}

// The feasible atlas's tables and counts from its entries (feasible words only) and their followed orbits.
void feasible_atlas(AtlasResult& res, const std::vector<std::vector<Followed>>& followed) {
  res.tol = feasible_tol;
  res.grid_points = static_cast<long>(feasible_grid().size());
  std::vector<double> rs;
  for (int i = 1; i < 1000; ++i) rs.push_back(i / 1000.0);
  for (const auto& e : res.feasible_entries) {
    bool st = false;
    for (const auto& iv : e.intervals) {
      st = st || iv.outcome == Outcome::stable;
      res.r_low.push_back(iv.lo);
      res.r_high.push_back(iv.hi);
      res.symbols.push_back(static_cast<double>(e.word.size()));
      res.word.push_back(to_paper(e.word));
      res.stable.push_back(iv.outcome == Outcome::stable ? 1 : 0);
      res.low_reason.push_back(iv.lo_reason);
      res.high_reason.push_back(iv.hi_reason);
    }
    res.stable_words += st;
    res.unstable_only_words += !st;
  }
  res.csv.emplace_back("", feasible_csv(res.feasible_entries));
  res.counts = feasible_counts(res.feasible_entries, rs);
  res.csv.emplace_back("counts", feasible_counts_csv(res.counts));
  res.csv.emplace_back("unstable_followed", followed_table(res.feasible_entries, followed, followed_max_periods,
                                                           &res.followed_agree, &res.followed_checked));
}

}  // namespace

AtlasPart run_part(const AtlasRequest& req, const std::vector<std::size_t>& items, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  const std::vector<Word> all = enumerate_canonical(static_cast<int>(req.max_length), control.cancel);
  const std::vector<double> table = req.checks() ? table_6_1_r() : std::vector<double>{};
  std::vector<Word> words;
  std::vector<double> rs;
  for (std::size_t i : items) {
    if (i < all.size()) words.push_back(all[i]);
    else if (i - all.size() < table.size()) rs.push_back(table[i - all.size()]);
    else throw std::logic_error("pattern atlas sweep: item beyond the words and r values");
  }
  AtlasPart part;
  part.items = items;
  auto t0 = std::chrono::steady_clock::now();
  if (!req.feasible) {
    for (auto& e : compute_atlas(words, default_grid(), stable_tol, control.threads, control.cancel))
      part.stable.push_back(std::move(e.intervals));
  } else {
    const std::vector<FeasibleEntry> f =
        compute_feasible_atlas(words, feasible_grid(), feasible_tol, control.threads, control.cancel);
    part.followed = follow_unstable(f, followed_max_periods, control.threads, control.cancel);
    for (const auto& e : f) part.feasible.push_back(e.intervals);
  }
  part.atlas_seconds = core::seconds_since(t0);
  core::check_cancel(control.cancel);
  if (!rs.empty()) {
    t0 = std::chrono::steady_clock::now();
    const DetectionRun d = detect_patterns(rs, req.ics, req.iterations, req.tail, req.seed,
                                           static_cast<int>(req.max_period), control.threads, control.cancel);
    part.periodic = d.periodic;
    part.found.resize(rs.size());
    for (const auto& f : d.found)  // sorted by r in the order of rs
      part.found[static_cast<std::size_t>(std::find(rs.begin(), rs.end(), f.r) - rs.begin())].emplace_back(f.word,
                                                                                                           f.count);
    part.check_seconds = core::seconds_since(t0);
  }
  core::check_cancel(control.cancel);
  return part;
}

AtlasResult merge(const AtlasRequest& req, std::vector<AtlasPart> parts) {
  const std::vector<Word> all = enumerate_canonical(static_cast<int>(req.max_length));
  const std::size_t W = all.size();
  const auto order = core::item_order(parts, req.work_items());
  // A part's items are ascending, words first: its r items follow its `words` word items.
  std::vector<std::size_t> words_in(parts.size(), 0);
  for (std::size_t p = 0; p < parts.size(); ++p)
    words_in[p] = static_cast<std::size_t>(
        std::count_if(parts[p].items.begin(), parts[p].items.end(), [&](std::size_t i) { return i < W; }));
  AtlasResult res;
  res.request = req;
  res.feasible = req.feasible;
  for (const auto& p : parts) {
    res.atlas_seconds += p.atlas_seconds;
    res.check_seconds += p.check_seconds;
  }
  if (req.feasible) {
    res.words_scanned = static_cast<long>(W);
    std::vector<std::vector<Followed>> followed;
    for (std::size_t i = 0; i < W; ++i) {
      AtlasPart& p = parts[order[i].part];
      std::vector<FeasibleInterval<double>>& iv = p.feasible.at(order[i].index);
      if (iv.empty()) continue;  // never feasible on the grid: left out, as compute_feasible_atlas does
      res.feasible_entries.push_back({all[i], std::move(iv)});
      followed.push_back(std::move(p.followed.at(order[i].index)));
    }
    feasible_atlas(res, followed);
    return res;
  }
  for (std::size_t i = 0; i < W; ++i)
    res.entries.push_back({all[i], std::move(parts[order[i].part].stable.at(order[i].index))});
  if (!req.checks()) {
    stable_atlas(req, res, nullptr);
    return res;
  }
  const auto t0 = std::chrono::steady_clock::now();
  DetectionRun d;
  d.r = table_6_1_r();
  d.ics = req.ics;
  d.iterations = req.iterations;
  d.tail = req.tail;
  d.seed = req.seed;
  for (std::size_t k = 0; k < d.r.size(); ++k) {
    const AtlasPart& p = parts[order[W + k].part];
    const std::size_t j = order[W + k].index - words_in[order[W + k].part];
    d.periodic.push_back(p.periodic.at(j));
    for (const auto& [w, count] : p.found.at(j)) d.found.push_back({d.r[k], w, count});
  }
  stable_atlas(req, res, &d);
  res.check_seconds += core::seconds_since(t0);  // the status column and the long words' stability sets, here
  return res;
}

AtlasResult run(const AtlasRequest& req, const core::RunControl& control) {
  core::work_items(req, control.cancel);  // the words first, polling the token: later enumerations find them listed
  return merge(req, {run_part(req, core::all_items(req), control)});
}

}  // namespace btob::patterns
