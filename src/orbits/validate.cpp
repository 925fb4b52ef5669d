// SPDX-License-Identifier: GPL-3.0-or-later
// strip-orbits: the request's validation.
#include "orbits/orbits.hpp"

#include "core/fields.hpp"

#include <fmt/format.h>

#include <cmath>

namespace btob::orbits {

void StripOrbitsRequest::validate() const {
  core::require_r(r, "r");
  if (orbits < 1 || orbits > 1000) throw core::InvalidField("orbits", fmt::format("{}", orbits), "1..1000");
  if (tail < 1) throw core::InvalidField("tail", fmt::format("{}", tail), "at least 1");
  if (iterations < tail || iterations > 10000000)
    throw core::InvalidField("iterations", fmt::format("{}", iterations), fmt::format("tail ({})..1e7", tail));
  if (static_cast<double>(orbits) * static_cast<double>(tail) > 1e8)
    throw core::InvalidField("tail", fmt::format("{}", tail), "orbits * tail <= 1e8 (memory)");
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  if (!(std::abs(w1_range[0]) <= 1e6 && std::abs(w1_range[1]) <= 1e6 && w1_range[0] < w1_range[1]))
    throw core::InvalidField("w1-range", fmt::format("[{}, {}]", w1_range[0], w1_range[1]), "a < b, |a|, |b| <= 1e6");
}

}  // namespace btob::orbits
