// The atlas of stable patterns (OpenMP over words) and pattern detection with the batched iterator.
#include "patterns/atlas.hpp"

#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <map>

namespace btob::patterns {

std::vector<AtlasEntry> compute_atlas(int max_length, const std::vector<double>& grid, double tol, int threads) {
  const std::vector<Word> words = enumerate_canonical(max_length);
  std::vector<AtlasEntry> out(words.size());
  const long n = static_cast<long>(words.size());
  const int nt = threads > 0 ? threads : omp_get_max_threads();
  // Interleaved static schedule: words are sorted by length, so chunks of 1 balance the load; each
  // iteration writes only its own entry.
#pragma omp parallel for schedule(static, 1) num_threads(nt)
  for (long i = 0; i < n; ++i) {
    out[i].word = words[i];
    out[i].intervals = stability_set<double>(words[i], grid, tol);
  }
  return out;
}

std::string atlas_csv(const std::vector<AtlasEntry>& atlas) {
  std::string s = "word,r_low,r_high,low_reason,high_reason\n";
  for (const auto& e : atlas)
    for (const auto& iv : e.intervals)
      s += fmt::format("{},{:.17g},{:.17g},{},{}\n", to_paper(e.word), iv.lo, iv.hi, iv.lo_reason, iv.hi_reason);
  return s;
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
                             int max_period, int threads) {
  if (ics < 1) throw std::invalid_argument(fmt::format("ics: got {}, expected at least 1", ics));
  if (tail < 2 || tail > iterations)
    throw std::invalid_argument(fmt::format("tail: got {}, expected 2 <= tail <= iterations = {}", tail, iterations));
  iterate::Ensemble ens;
  ens.r = r;
  for (double v : r) core::validate_r(v, "r");
  ens.initial = iterate::random_points(ics, seed);
  ens.seed = seed;
  ens.grid_description = fmt::format("random:{}", ics);
  iterate::SymbolRecorder rec(ens.orbits(), iterations - tail + 1, iterations);
  iterate::RunOptions opt;
  opt.threads = threads;
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
      const std::uint8_t* s = rec.out.data() + (ir * static_cast<std::size_t>(ics) + static_cast<std::size_t>(o)) * rec.count;
      const int p = eventual_period(s, rec.count, max_period);
      if (p == 0) continue;
      ++d.periodic[ir];
      Word w{std::vector<std::uint8_t>(s, s + p)};
      ++counts[canonical(w)];
    }
    std::vector<Detected> level;
    for (const auto& [w, c] : counts) level.push_back({r[ir], w, c});
    std::stable_sort(level.begin(), level.end(), [](const Detected& a, const Detected& b) { return a.count > b.count; });
    d.found.insert(d.found.end(), level.begin(), level.end());
  }
  return d;
}

std::vector<double> table_6_1_r() {
  return {0.1,  0.101, 0.102, 0.103, 0.15, 0.16, 0.17, 0.172, 0.174, 0.176, 0.178, 0.18, 0.19, 0.2,  0.21, 0.22, 0.23,
          0.24, 0.25,  0.3,   0.31,  0.32, 0.33, 0.34, 0.5,   0.51,  0.52,  0.53,  0.54, 0.57, 0.58, 0.59, 0.6};
}

}  // namespace btob::patterns
