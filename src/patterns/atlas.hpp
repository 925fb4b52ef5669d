// The atlas of stable periodic patterns over r, and its check against the batched iterator (Table 6.1).
#pragma once

#include "patterns/patterns.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace btob::patterns {

struct AtlasEntry {
  Word word;                               // canonical, primitive
  std::vector<Interval<double>> intervals; // stability set in (0, 1), endpoints to `tol`
};

// Every canonical primitive word of length 1..max_length with its stability set (OpenMP over words,
// threads <= 0: OpenMP's default; the result does not depend on the thread count).  Entries keep the
// order of enumerate_canonical; words never stable are included with no interval.
std::vector<AtlasEntry> compute_atlas(int max_length, const std::vector<double>& grid, double tol, int threads);
// CSV word,r_low,r_high,low_reason,high_reason: one row per interval, words in paper notation, 17 digits.
std::string atlas_csv(const std::vector<AtlasEntry>& atlas);

// Periodic symbol sequences seen by the iterator.  For each r: `ics` random initial points (seeded),
// `iterations` steps of the batched kernel (double), symbols of the last `tail` steps; the eventual period
// is the smallest p <= max_period with s_k = s_{k+p} over the whole tail (0: none).
struct Detected {
  double r;
  Word word;   // canonical
  long count;  // orbits with this pattern
};
struct DetectionRun {
  std::vector<double> r;
  long ics = 0, iterations = 0, tail = 0;
  std::uint64_t seed = 0;
  std::vector<long> periodic;     // per r: orbits with an eventual period
  std::vector<Detected> found;    // sorted by r, then count (descending)
};
DetectionRun detect_patterns(const std::vector<double>& r, long ics, long iterations, long tail, std::uint64_t seed,
                             int max_period, int threads);
// The eventual period of one symbol stream (0 when not periodic with period <= max_period).
int eventual_period(const std::uint8_t* s, long n, int max_period);

// Table 6.1's r values.
std::vector<double> table_6_1_r();

}  // namespace btob::patterns
