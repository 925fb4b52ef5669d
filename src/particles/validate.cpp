// SPDX-License-Identifier: GPL-3.0-or-later
// The particle check's request: its validation, and where its word is feasible when it is not at r.
#include "particles/particles.hpp"

#include "core/fields.hpp"
#include "core/scalar.hpp"
#include "patterns/atlas.hpp"
#include "patterns/patterns.hpp"

#include <fmt/format.h>

#include <exception>
#include <string>

namespace btob::particles {
namespace {

using core::InvalidField;

std::string shortest(double v) { return fmt::format("{}", v); }

// The feasible intervals of w on the atlas grid, for the error message of a word not feasible at r.
std::string feasible_where(const patterns::Word& w) {
  const auto set = patterns::feasibility_set<double>(w, patterns::feasible_grid(), 1e-6);
  if (set.empty()) return "never feasible on the atlas grid of (0, 1)";
  std::string s = "feasible for r in";
  for (std::size_t i = 0; i < set.size() && i < 4; ++i)
    s += fmt::format("{} ({:.6f}, {:.6f}) {}", i ? "," : "", set[i].lo, set[i].hi, outcome_name(set[i].outcome));
  if (set.size() > 4) s += ", ...";
  return s;
}

}  // namespace

void ParticlesRequest::validate() const {
  patterns::Word w;
  try {
    w = patterns::parse_word(word, "word");
  } catch (const std::exception&) {
    throw InvalidField("word", "'" + word + "'", "a word over 1, 2, 3 such as 132312, 132^3312^3 or (ab)(cb)(acb)");
  }
  core::require_r(r, "r");
  if (periods < 1 || periods > 100000000) throw InvalidField("periods", std::to_string(periods), "1..100000000");
  core::Precision prec;
  try {
    prec = core::parse_precision(precision, "precision");
  } catch (const std::exception&) {
    throw InvalidField("precision", "'" + precision + "'",
                       "double, long-double, float128 or mpfr:D (10 <= D <= 10000)");
  }
  if (prec.kind == core::Precision::Kind::f32)
    throw InvalidField("precision", "'float'",
                       "double, long-double, float128 or mpfr:D (float is too short for the check)");
  if (start != "self-similar" && start != "normal")
    throw InvalidField("start", "'" + start + "'", "self-similar or normal");
  if (diagram_periods < 1 || diagram_periods > 50)
    throw InvalidField("diagram-periods", std::to_string(diagram_periods), "1..50");
  if (patterns::analyse<double>(w, r).outcome == patterns::Outcome::none)
    throw InvalidField("word", "'" + word + "'",
                       fmt::format("a word with a feasible periodic point at r = {} ({} {})", shortest(r),
                                   patterns::to_paper(patterns::primitive_root(w)), feasible_where(w)));
}

}  // namespace btob::particles
