// SPDX-License-Identifier: GPL-3.0-or-later
// The precision study's request: its validation.
#include "precision/tradeoff.hpp"

#include "core/fields.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace btob::precision {

void TradeoffRequest::validate() const {
  if (orbits < 1 || orbits > 4096) throw core::InvalidField("orbits", std::to_string(orbits), "1..4096");
  if (iterations < 10 || iterations > 1000000)
    throw core::InvalidField("iterations", std::to_string(iterations), "10..1000000");
  core::require_r_values(core::values(r), "r-values");
  if (window_n.empty()) throw core::InvalidField("window-n", "no value", "one or more integers 2..400");
  for (double n : window_n)
    if (!(n >= 2 && n <= 400 && n == std::floor(n)))
      throw core::InvalidField("window-n", fmt::format("{}", n), "2..400");
}

}  // namespace btob::precision
