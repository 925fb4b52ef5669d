// SPDX-License-Identifier: GPL-3.0-or-later
// The atlas result's output: its summary and the description of its arrays and attributes (word_output.cpp
// holds the pattern result's).
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

std::string AtlasResult::summary() const {
  if (feasible)
    return fmt::format(
        "feasible atlas of {} canonical primitive words: {} feasible for some r ({} stable somewhere, {} only "
        "unstable) ({:.1f} s); unstable orbits followed by the map in double from their periodic point: {} "
        "of {} within a factor 2 (+-2 periods) of ln(margin/eps)/ln(expansion)",
        words_scanned, feasible_entries.size(), stable_words, unstable_only_words, atlas_seconds, followed_agree,
        followed_checked);
  std::string s = fmt::format("atlas of {} canonical primitive words: {} with a stability window ({:.1f} s)",
                              words_scanned, stable_words, atlas_seconds);
  if (checked)
    s += fmt::format(
        "; iterator check at {} r values: {} (r, pattern) pairs, {} not stable in the analysis, {} "
        "quasi-periodic (neutral period matrix), {} stable atlas entries not reached ({:.1f} s)",
        table_6_1_r().size(), detected, disagreements, quasi_periodic, missed, check_seconds);
  return s;
}

// The iterator check's tables (NAME_detected.csv, NAME_long_windows.csv, NAME_missed.csv) as datasets.
void AtlasResult::describe_check(core::Contents& c) const {
  const Detections& d = detections;
  const std::size_t n = d.r.size();
  c.array("detected_r", d.r, {n}, "detection", "1", "r of the (r, pattern) pair: one of Table 6.1's r values");
  c.text("detected_word", d.word, "detection", "word", "the pattern the iterator found at r, paper notation");
  c.array("detected_symbols", d.symbols, {n}, "detection", "symbols", "length of the pattern's word");
  c.array("detected_collisions", d.collisions, {n}, "detection", "collisions", "collisions in one period of the word");
  c.array("detected_count", d.count, {n}, "detection", "orbits", "random initial points whose tail has this pattern");
  c.array("detected_symbol_periodic_fraction", d.symbol_periodic_fraction, {n}, "detection", "1",
          "fraction of the initial points at r whose symbol sequence is eventually periodic (P2's curves included)");
  c.array("detected_periodic_fraction", d.periodic_fraction, {n}, "detection", "1",
          "fraction of the initial points at r on a pattern whose status is not quasi-periodic (periodic orbits)");
  c.text("detected_status", d.status, "detection", "text",
         "the pattern against the atlas: stable in atlas; NOT stable in atlas (verdict); quasi-periodic (neutral "
         "period matrix); longer than L: stable or NOT stable (verdict)");
  const LongWindows& l = long_windows;
  c.text("long_word", l.word, "long interval", "word",
         "a found pattern longer than max_length (not in the atlas), one row per interval of its stability set");
  c.array("long_symbols", l.symbols, {l.r_low.size()}, "long interval", "symbols", "length of the word");
  c.array("long_r_low", l.r_low, {l.r_low.size()}, "long interval", "1", "lower end of the stability interval in r");
  c.array("long_r_high", l.r_high, {l.r_high.size()}, "long interval", "1", "upper end of the stability interval in r");
  const Missed& m = missed_entries;
  c.array("missed_r", m.r, {m.r.size()}, "missed", "1",
          "a Table 6.1 r inside a stability interval of an atlas word the iterator did not find there");
  c.text("missed_word", m.word, "missed", "word", "that word, paper notation");
  c.array("missed_symbols", m.symbols, {m.r.size()}, "missed", "symbols", "length of the word");
  c.array("missed_r_low", m.r_low, {m.r.size()}, "missed", "1", "lower end of the interval containing r");
  c.array("missed_r_high", m.r_high, {m.r.size()}, "missed", "1", "upper end of the interval containing r");
}

void AtlasResult::describe(core::Contents& c) const {
  c.array("r_low", r_low, {r_low.size()}, "interval", "1", "lower ends of the intervals in r (all words, CSV order)");
  c.array("r_high", r_high, {r_high.size()}, "interval", "1", "upper ends of the intervals in r");
  c.array("symbols", symbols, {symbols.size()}, "interval", "symbols", "length of the interval's word");
  c.array("stable", stable, {stable.size()}, "interval", "1",
          "1: a stable periodic orbit on the interval, 0: unstable");
  c.text("word", word, "interval", "word", "the interval's word in the paper's notation (e.g. 132^3312^3)");
  c.text("low_reason", low_reason, "interval", "text", "what begins the interval at r_low (the analysis's words)");
  c.text("high_reason", high_reason, "interval", "text", "what ends the interval at r_high");
  if (feasible) {
    c.array("count_r", counts.r, {counts.r.size()}, "count_r", "1",
            "restitution coefficients of the counts (0.001, 0.002, ..., 0.999)");
    c.array("count_stable", counts.stable, {counts.r.size()}, "count_r", "words",
            "words with a stable feasible periodic point at r");
    c.array("count_unstable", counts.unstable, {counts.r.size()}, "count_r", "words",
            "words with an unstable feasible periodic point at r");
    c.array("count_feasible", counts.feasible, {counts.r.size()}, "count_r", "words",
            "words with a feasible periodic point at r (stable, unstable, neutral or undecided)");
    c.array("count_stable_collapse", counts.stable_collapse, {counts.r.size()}, "count_r", "words",
            "of count_stable, the orbits four particles can follow in a collapse");
    c.array("count_unstable_collapse", counts.unstable_collapse, {counts.r.size()}, "count_r", "words",
            "of count_unstable, the orbits four particles can follow in a collapse");
  }
  if (checked) describe_check(c);
  c.attr("max_length", request.max_length);
  c.attr("words", words_scanned);
  c.attr("words_scanned", words_scanned);
  c.attr("stable_words", stable_words);
  c.attr("grid_points", grid_points);
  c.attr("bisection_tol", tol);
  c.attr("atlas_seconds", atlas_seconds);
  if (feasible) {
    c.attr("feasible_words", static_cast<long>(feasible_entries.size()));
    c.attr("unstable_only_words", unstable_only_words);
    c.attr("followed_checked", followed_checked);
    c.attr("followed_agree", followed_agree);
  }
  if (checked) {
    c.attr("check_r_values", static_cast<long>(table_6_1_r().size()));
    c.attr("check_ics", request.ics);
    c.attr("check_iterations", request.iterations);
    c.attr("check_tail", request.tail);
    c.attr("check_max_period", request.max_period);
    c.attr("check_seed", static_cast<long>(request.seed));
    c.attr("check_grid", std::string("random (uniform on the quarter sphere)"));
    c.attr("check_detected_patterns", detected);
    c.attr("check_disagreements", disagreements);
    c.attr("check_quasi_periodic", quasi_periodic);
    c.attr("check_missed", missed);
    c.attr("check_seconds", check_seconds);
  }
}

}  // namespace btob::patterns
