// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: iterate::parse_grid ("paper", "strip:NxM[:w1min:w1max]", "random:N", "x,y,z;x,y,z;...").
// A parse either throws a std::logic_error (invalid_argument for a malformed spec, domain_error for a point
// outside the domain, length_error for a grid that does not fit in memory) or returns at least one finite,
// non-zero point of the domain x*z <= 0 with x, z not both zero (eq. 3.2).
#include "iterate/ensemble.hpp"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace {
// The point count a "strip:" or "random:" spec asks for, as a double (no overflow), or 0 for other specs.
// Legal counts above 1e5 are skipped below: allocating them only measures the machine, and the harness must
// stay within libFuzzer's memory limit.  Counts whose product overflows a long are still fed in: they must throw.
double requested_points(std::string_view s) {
  auto number = [](std::string_view t) {
    long v = 0;
    std::from_chars(t.data(), t.data() + t.size(), v);
    return static_cast<double>(v);
  };
  if (s.starts_with("random:")) return number(s.substr(7));
  if (s.starts_with("strip:")) {
    s.remove_prefix(6);
    const auto x = s.find('x');
    if (x == std::string_view::npos) return 0;
    return number(s.substr(0, x)) * number(s.substr(x + 1));
  }
  return 0;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const std::string_view spec(reinterpret_cast<const char*>(data), size);
  const double n = requested_points(spec);
  if (n > 1e5 && n < 1e15) return 0;
  try {
    const auto pts = btob::iterate::parse_grid(spec, 1, "grid");
    if (pts.empty()) std::abort();
    for (const auto& p : pts) {
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) std::abort();
      if (p.x() * p.z() > 0 || (p.x() == 0 && p.z() == 0)) std::abort();
    }
  } catch (const std::logic_error&) {
  }
  return 0;
}
