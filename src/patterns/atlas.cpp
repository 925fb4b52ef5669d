// SPDX-License-Identifier: GPL-3.0-or-later
// The atlas of stable patterns (OpenMP over words) and pattern detection with the batched iterator.
#include "patterns/atlas.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"

#include "patterns/analysis_impl.hpp"

#include "iterate/kernel.hpp"
#include "iterate/parallel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace btob::patterns {

std::vector<AtlasEntry> compute_atlas(int max_length, const std::vector<double>& grid, double tol, int threads) {
  return compute_atlas(enumerate_canonical(max_length), grid, tol, threads);
}

std::vector<AtlasEntry> compute_atlas(const std::vector<Word>& words, const std::vector<double>& grid, double tol,
                                      int threads, const core::CancelToken* cancel) {
  std::vector<AtlasEntry> out(words.size());
  // Interleaved static schedule: words are sorted by length, so chunks of 1 balance the load; each
  // iteration writes only its own entry.
  iterate::parallel_for(words.size(), threads, 1, [&](std::size_t i) {
    if (cancel && cancel->cancelled()) return;  // no exception may leave an OpenMP region
    out[i].word = words[i];
    // The word's scan polls the token (its refinement near spectral events can evaluate thousands of r values);
    // Cancelled is caught inside the iteration, since no exception may leave the region, and thrown after it.
    try {
      out[i].intervals = stability_set<double>(words[i], grid, tol, cancel);
    } catch (const core::Cancelled&) {
      return;
    }
  });
  core::check_cancel(cancel);
  return out;
}

std::string atlas_csv(const std::vector<AtlasEntry>& atlas) {
  core::CsvTable s("word,r_low,r_high,low_reason,high_reason");
  for (const auto& e : atlas)
    for (const auto& iv : e.intervals)
      s.row(
          {to_paper(e.word), fmt::format("{:.17g}", iv.lo), fmt::format("{:.17g}", iv.hi), iv.lo_reason, iv.hi_reason});
  return s.text();
}

std::vector<FeasibleEntry> compute_feasible_atlas(int max_length, const std::vector<double>& grid, double tol,
                                                  int threads, long* words_scanned) {
  const std::vector<Word> words = enumerate_canonical(max_length);
  if (words_scanned) *words_scanned = static_cast<long>(words.size());
  std::vector<FeasibleEntry> out;
  for (auto& e : compute_feasible_atlas(words, grid, tol, threads))
    if (!e.intervals.empty()) out.push_back(std::move(e));
  return out;
}

std::vector<FeasibleEntry> compute_feasible_atlas(const std::vector<Word>& words, const std::vector<double>& grid,
                                                  double tol, int threads, const core::CancelToken* cancel) {
  std::vector<FeasibleEntry> all(words.size());
  iterate::parallel_for(words.size(), threads, 1, [&](std::size_t i) {
    if (cancel && cancel->cancelled()) return;  // no exception may leave an OpenMP region
    all[i].word = words[i];
    all[i].intervals = feasibility_set<double>(words[i], grid, tol);
  });
  core::check_cancel(cancel);
  return all;
}

std::vector<double> feasible_grid() {
  std::vector<double> g;
  const auto add = [&](double a, double b, int n) {
    for (int i = 0; i < n; ++i) g.push_back(a + (b - a) * (i + 0.5) / n);
  };
  add(0.02, 0.07, 250);
  add(0.07, 0.26, 950);
  add(0.26, 1.0, 370);
  return g;
}

std::string feasible_csv(const std::vector<FeasibleEntry>& atlas) {
  core::CsvTable s("word,digits,length,collisions,r_low,r_high,outcome,collapse,low_reason,high_reason");
  for (const auto& e : atlas)
    for (const auto& iv : e.intervals)
      s.row({to_paper(e.word), to_digits(e.word), fmt::format("{}", e.word.size()),
             fmt::format("{}", collisions(e.word)), fmt::format("{:.17g}", iv.lo), fmt::format("{:.17g}", iv.hi),
             outcome_name(iv.outcome), iv.collapse ? "true" : "false", iv.lo_reason, iv.hi_reason});
  return s.text();
}

FeasibleCounts feasible_counts(const std::vector<FeasibleEntry>& atlas, const std::vector<double>& r) {
  FeasibleCounts c;
  c.r = r;
  for (double x : r) {
    std::uint32_t st = 0, un = 0, fe = 0, stc = 0, unc = 0;  // fe: every feasible entry (neutral and undecided too)
    for (const auto& e : atlas) {
      const FeasibleInterval<double>* in = nullptr;
      for (const auto& iv : e.intervals)
        if (iv.lo <= x && x < iv.hi) in = &iv;
      if (!in) continue;
      st += in->outcome == Outcome::stable;
      un += in->outcome == Outcome::unstable;
      fe += in->outcome != Outcome::none;
      stc += in->outcome == Outcome::stable && in->collapse;
      unc += in->outcome == Outcome::unstable && in->collapse;
    }
    c.stable.push_back(st);
    c.unstable.push_back(un);
    c.feasible.push_back(fe);
    c.stable_collapse.push_back(stc);
    c.unstable_collapse.push_back(unc);
  }
  return c;
}

std::string feasible_counts_csv(const FeasibleCounts& c) {
  core::CsvTable s("r,stable,unstable,feasible,stable_collapse,unstable_collapse");
  for (std::size_t i = 0; i < c.r.size(); ++i)
    s.line(fmt::format("{:.6g},{},{},{},{},{}", c.r[i], c.stable[i], c.unstable[i], c.feasible[i], c.stable_collapse[i],
                       c.unstable_collapse[i]));
  return s.text();
}

template <class T> Followed follow_periodic_orbit(const Word& w0, const T& r, long max_periods) {
  const Verdict<T> v = analyse<T>(w0, r);
  Followed f;
  if (v.orbit_eigen < 0)
    throw core::InvalidField("word", "a word with no feasible periodic point at this r", "a feasible word");
  const Word& w = v.word;
  // Expansion per period of M_w (moduli squared when analysed through J M_h).
  const T lo = v.spectrum[v.orbit_eigen].modulus, l1 = v.spectrum[0].modulus;
  f.expansion = static_cast<double>(v.reduced ? T((l1 / lo) * (l1 / lo)) : T(l1 / lo));
  std::vector<T> margins;
  // The orbit's own points: a saddle's carried forward from its first would leave it (detail::orbit_points).
  if (v.orbit_eigen == 0) (void)detail::feasibility(w, r, v.orbit.front(), &margins);
  else (void)detail::feasibility_of(w, r, v.orbit, &margins);
  T m =
      margins.front() > 0 ? detail::sqrt_<T>(margins.front()) : T(0);  // domain margin -x z: a product, its square root
  for (std::size_t k = 1; k < margins.size(); ++k) m = std::min<T>(m, margins[k]);
  f.margin = static_cast<double>(m);
  const double eps = static_cast<double>(std::numeric_limits<T>::epsilon());
  f.predicted = f.expansion > 1 ? std::log(f.margin / eps) / std::log(f.expansion) : INFINITY;
  Vec3<T> u = v.orbit.front();
  for (long n = 0; n < max_periods; ++n) {
    for (auto c : w.s) {
      const core::Step<T> st = core::step<T>(u, r);
      if (st.symbol != c) return f;
      u = st.u / st.u.norm();
    }
    f.periods = n + 1;
  }
  return f;
}
template Followed follow_periodic_orbit<double>(const Word&, const double&, long);
template Followed follow_periodic_orbit<long double>(const Word&, const long double&, long);

std::string followed_csv(const std::vector<FeasibleEntry>& atlas, long max_periods, int threads, long* agree,
                         long* checked) {
  return followed_table(atlas, follow_unstable(atlas, max_periods, threads), max_periods, agree, checked);
}

std::vector<std::vector<Followed>> follow_unstable(const std::vector<FeasibleEntry>& atlas, long max_periods,
                                                   int threads, const core::CancelToken* cancel) {
  struct Row {
    const Word* w;
    double r;
    Followed* f;
  };
  std::vector<std::vector<Followed>> out(atlas.size());
  std::vector<Row> rows;
  for (std::size_t k = 0; k < atlas.size(); ++k) {
    std::size_t unstable = 0;
    for (const auto& iv : atlas[k].intervals) unstable += iv.outcome == Outcome::unstable;
    out[k].resize(unstable);
    std::size_t j = 0;
    for (const auto& iv : atlas[k].intervals)
      if (iv.outcome == Outcome::unstable) rows.push_back({&atlas[k].word, (iv.lo + iv.hi) / 2, &out[k][j++]});
  }
  iterate::parallel_for(rows.size(), threads, 1, [&](std::size_t i) {
    if (cancel && cancel->cancelled()) return;  // no exception may leave an OpenMP region
    try {
      *rows[i].f = follow_periodic_orbit<double>(*rows[i].w, rows[i].r, max_periods);
    } catch (const std::invalid_argument&) {
      rows[i].f->periods = -1;  // not feasible at the midpoint (an interval narrower than the bisection noise)
    }
  });
  core::check_cancel(cancel);
  return out;
}

std::string followed_table(const std::vector<FeasibleEntry>& atlas, const std::vector<std::vector<Followed>>& followed,
                           long max_periods, long* agree, long* checked) {
  struct Row {
    const Word* w;
    double r;
    const Followed* f;
  };
  std::vector<Row> rows;
  for (std::size_t k = 0; k < atlas.size(); ++k) {
    std::size_t j = 0;
    for (const auto& iv : atlas[k].intervals)
      if (iv.outcome == Outcome::unstable)
        rows.push_back({&atlas[k].word, (iv.lo + iv.hi) / 2, &followed.at(k).at(j++)});
  }
  long a = 0, c = 0;
  core::CsvTable s("word,r,expansion,margin,predicted,followed");
  for (const auto& row : rows) {
    const Followed& f = *row.f;
    if (f.expansion > 1 && f.periods >= 0 && 2 * f.predicted + 2 < static_cast<double>(max_periods)) {
      ++c;
      a += f.periods >= f.predicted / 2 - 2 && f.periods <= 2 * f.predicted + 2;
    }
    s.line(fmt::format("{},{:.17g},{:.10g},{:.6g},{:.6g},{}", to_paper(*row.w), row.r, f.expansion, f.margin,
                       f.predicted, f.periods));
  }
  if (agree) *agree = a;
  if (checked) *checked = c;
  return s.text();
}

int eventual_period(const std::uint8_t* s, long n, int max_period) {
  for (int p = 1; p <= max_period && 2 * p <= n; ++p) {
    bool ok = true;
    for (long k = n - 1 - p; k >= 0 && ok; --k) ok = s[k] == s[k + p];
    if (ok) return p;
  }
  return 0;
}

DetectionRun detect_patterns(const std::vector<double>& r, long ics, long iterations, long tail, std::uint64_t seed,
                             int max_period, int threads, const core::CancelToken* cancel) {
  if (ics < 1) throw core::InvalidField("ics", fmt::format("{}", ics), "at least 1");
  if (tail < 2 || tail > iterations)
    throw core::InvalidField("tail", fmt::format("{}", tail), fmt::format("2 <= tail <= iterations = {}", iterations));
  iterate::Ensemble ens;
  ens.r = r;
  for (double v : r) core::validate_r(v, "r");
  ens.initial = iterate::random_points(ics, seed);
  ens.seed = seed;
  ens.grid_description = fmt::format("random:{}", ics);
  iterate::SymbolRecorder rec(ens.orbits(), iterations - tail + 1, iterations);
  iterate::RunOptions opt;
  opt.threads = threads;
  opt.cancel = cancel;
  iterate::run<double>(ens, iterations, rec, opt);
  DetectionRun d;
  d.r = r;
  d.ics = ics;
  d.iterations = iterations;
  d.tail = tail;
  d.seed = seed;
  d.periodic.assign(r.size(), 0);
  for (std::size_t ir = 0; ir < r.size(); ++ir) {
    std::map<Word, long> counts;
    for (long o = 0; o < ics; ++o) {
      const std::uint8_t* s =
          rec.out.data() + (ir * static_cast<std::size_t>(ics) + static_cast<std::size_t>(o)) * rec.count;
      const int p = eventual_period(s, rec.count, max_period);
      if (p == 0) continue;
      ++d.periodic[ir];
      Word w{std::vector<std::uint8_t>(s, s + p)};
      ++counts[canonical(w)];
    }
    std::vector<Detected> level;
    for (const auto& [w, c] : counts) level.push_back({r[ir], w, c});
    std::stable_sort(level.begin(), level.end(),
                     [](const Detected& a, const Detected& b) { return a.count > b.count; });
    d.found.insert(d.found.end(), level.begin(), level.end());
  }
  return d;
}

std::vector<double> table_6_1_r() {
  return {0.1,  0.101, 0.102, 0.103, 0.15, 0.16, 0.17, 0.172, 0.174, 0.176, 0.178, 0.18, 0.19, 0.2,  0.21, 0.22, 0.23,
          0.24, 0.25,  0.3,   0.31,  0.32, 0.33, 0.34, 0.5,   0.51,  0.52,  0.53,  0.54, 0.57, 0.58, 0.59, 0.6};
}

}  // namespace btob::patterns
