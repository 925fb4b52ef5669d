// SPDX-License-Identifier: GPL-3.0-or-later
// The patterns requests' validation (pattern, atlas) and the atlas's work items.
#include "patterns/requests.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
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

void WordRequest::validate() const {
  const Word w = parse_word(word, "word");  // throws naming the field
  (void)w;
  if (window && charpoly) throw core::InvalidField("charpoly", "with --window", "one of --window, --charpoly or --r R");
  if (charpoly && !r.empty())
    throw core::InvalidField("charpoly", "with --r " + r, "no --r with --charpoly (exact in r)");
  if (window && !r.empty()) throw core::InvalidField("r", r, "no --r with --window (the window is a set of r)");
  if (!window && !charpoly && r.empty())
    throw core::InvalidField("r", "nothing", "one of --r R (verdict at one r), --window or --charpoly");
  if (digits != 0 && (!window || digits < 5 || digits > 1000))
    throw core::InvalidField("digits", std::to_string(digits), window ? "5..1000" : "only with --window");
  const core::Precision prec = core::parse_precision(precision, "precision");
  if (window && prec.kind != core::Precision::Kind::mpfr && prec.kind != core::Precision::Kind::f64)
    throw core::InvalidField("precision", precision, "double or mpfr:<digits> with --window");
  if (r.empty()) return;
  double x = 0;
  try {
    std::size_t pos = 0;
    x = std::stod(r, &pos);
    if (pos != r.size()) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw core::InvalidField("r", "'" + r + "'", "a value in the open interval (0, 1)");
  }
  core::require_r(x, "r");
}

void AtlasRequest::validate() const {
  if (max_length < 1 || max_length > 16) throw core::InvalidField("max-length", std::to_string(max_length), "1..16");
  if (feasible && no_check) throw core::InvalidField("no-check", "with --feasible", "only for the stable atlas");
  if (ics < 1 || ics > 10'000'000) throw core::InvalidField("ics", std::to_string(ics), "1..10000000");
  if (iterations < 1) throw core::InvalidField("iterations", std::to_string(iterations), "at least 1");
  if (tail < 1 || tail > iterations)
    throw core::InvalidField("tail", std::to_string(tail), fmt::format("1..iterations ({})", iterations));
  if (max_period < 1 || 2 * max_period > tail)
    throw core::InvalidField("max-period", std::to_string(max_period), fmt::format("1..tail/2 ({})", tail / 2));
}

std::size_t AtlasRequest::work_items() const { return work_items(nullptr); }

std::size_t AtlasRequest::work_items(const core::CancelToken* cancel) const {
  return enumerate_canonical(static_cast<int>(max_length), cancel).size() + (checks() ? table_6_1_r().size() : 0);
}

}  // namespace btob::patterns
