// SPDX-License-Identifier: GPL-3.0-or-later
// The atlas of stable periodic patterns over r, and its check against the batched iterator (Table 6.1).
#pragma once

#include "core/request.hpp"
#include "patterns/patterns.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace btob::patterns {

struct AtlasEntry {
  Word word;                                // canonical, primitive
  std::vector<Interval<double>> intervals;  // stability set in (0, 1), endpoints to `tol`
};

// Every canonical primitive word of length 1..max_length with its stability set (OpenMP over words,
// threads <= 0: OpenMP's default; the result does not depend on the thread count).  Entries keep the
// order of enumerate_canonical; words never stable are included with no interval.
std::vector<AtlasEntry> compute_atlas(int max_length, const std::vector<double>& grid, double tol, int threads);
// The same for the given words, in their order (an entry depends on its word only: any subset gives its entries).
// `cancel` (here and below): polled before every word (or row, or batch of orbits); throws core::Cancelled when set.
std::vector<AtlasEntry> compute_atlas(const std::vector<Word>& words, const std::vector<double>& grid, double tol,
                                      int threads, const core::CancelToken* cancel = nullptr);
// CSV word,r_low,r_high,low_reason,high_reason: one row per interval, words in paper notation, 17 digits.
std::string atlas_csv(const std::vector<AtlasEntry>& atlas);

// The feasible atlas: every canonical primitive word of length 1..max_length with the intervals of r on
// which it has a feasible periodic point, each marked stable or unstable (feasibility_set on `grid`, changes
// bisected to `tol`; OpenMP over words, static interleaved schedule, independent of the thread count).
// Words never feasible on the grid are left out.
struct FeasibleEntry {
  Word word;  // canonical, primitive
  std::vector<FeasibleInterval<double>> intervals;
};
std::vector<FeasibleEntry> compute_feasible_atlas(int max_length, const std::vector<double>& grid, double tol,
                                                  int threads, long* words_scanned = nullptr);
// The same for the given words, in their order, words never feasible included (with no interval).
std::vector<FeasibleEntry> compute_feasible_atlas(const std::vector<Word>& words, const std::vector<double>& grid,
                                                  double tol, int threads, const core::CancelToken* cancel = nullptr);
// The scan grid of the feasible atlas: 1570 points on [0.02, 1), step 2e-4 on [0.02, 0.26) where the windows
// are thin (1^7 3^7 is 3.6e-4 wide), 2e-3 on [0.26, 1).  Below 0.02 the subdominant eigenvalues of long words
// fall below double's resolution relative to the dominant one (their eigenvectors are then unreliable).
std::vector<double> feasible_grid();
// CSV word,digits,length,collisions,r_low,r_high,outcome,collapse,low_reason,high_reason: one row per interval.
std::string feasible_csv(const std::vector<FeasibleEntry>& atlas);
// At each r of `r`, the number of words of the atlas with a stable / an unstable feasible periodic point
// (classify's choice), their sum (every feasible entry, neutral and undecided too), and those of them that four
// particles can follow in a collapse (Classification::collapse).
struct FeasibleCounts {
  std::vector<double> r;
  std::vector<std::uint32_t> stable, unstable, feasible, stable_collapse, unstable_collapse;
};
FeasibleCounts feasible_counts(const std::vector<FeasibleEntry>& atlas, const std::vector<double>& r);
// The same as CSV r,stable,unstable,feasible,stable_collapse,unstable_collapse (r to 6 significant digits).
std::string feasible_counts_csv(const FeasibleCounts& counts);

// An unstable periodic orbit followed by the map: core::step in T (double or long double) from the periodic
// point of analyse<T>(w, r) (which must be feasible), the number of whole periods whose symbols are w's before
// the first wrong symbol (at most max_periods).  Rounding errors (~eps) grow by Lambda = |l_1| / |l_o| per
// period (l_o the orbit's eigenvalue of M_w, l_1 the dominant), and the orbit leaves the pattern when they
// reach the smallest branch margin m along the orbit (unit vectors): after about ln(m / eps) / ln(Lambda)
// periods, which followed_prediction returns (infinity when Lambda <= 1).
struct Followed {
  long periods = 0;                                                                    // measured
  double predicted = 0;                                                                // ln(m / eps) / ln(Lambda)
  double expansion = 0;                                                                // Lambda per period
  double margin = 0;                                                                   // m
  template <class A> void members(A& a) { a(periods, predicted, expansion, margin); }  // core/pack.hpp
};
template <class T> Followed follow_periodic_orbit(const Word& w, const T& r, long max_periods);
// follow_periodic_orbit<double> at the middle of every unstable interval of the atlas (OpenMP over rows):
// CSV word,r,expansion,margin,predicted,followed.  `checked` receives the number of rows with an expansion > 1
// and 2 predicted + 2 < max_periods, `agree` those of them followed within [predicted / 2 - 2, 2 predicted + 2].
std::string followed_csv(const std::vector<FeasibleEntry>& atlas, long max_periods, int threads, long* agree,
                         long* checked);
// Its two halves: follow_unstable gives, entry by entry, the Followed of each unstable interval in order (periods
// -1: not feasible at the midpoint; OpenMP over all of them); followed_table writes the CSV and the counts.
std::vector<std::vector<Followed>> follow_unstable(const std::vector<FeasibleEntry>& atlas, long max_periods,
                                                   int threads, const core::CancelToken* cancel = nullptr);
std::string followed_table(const std::vector<FeasibleEntry>& atlas, const std::vector<std::vector<Followed>>& followed,
                           long max_periods, long* agree, long* checked);

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
  std::vector<long> periodic;   // per r: orbits with an eventual period
  std::vector<Detected> found;  // sorted by r, then count (descending)
};
DetectionRun detect_patterns(const std::vector<double>& r, long ics, long iterations, long tail, std::uint64_t seed,
                             int max_period, int threads, const core::CancelToken* cancel = nullptr);
// The eventual period of one symbol stream (0 when not periodic with period <= max_period).
int eventual_period(const std::uint8_t* s, long n, int max_period);

// Table 6.1's r values.
std::vector<double> table_6_1_r();

}  // namespace btob::patterns
