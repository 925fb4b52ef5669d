// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: core::parse_point ("x,y,z", the --point flag of lyapunov, stats, classify).  A parse either
// throws a std::logic_error (core::InvalidField or domain_error, naming the field) or returns a finite, non-zero
// point of the domain x*z <= 0 with x, z not both zero (eq. 3.4), scaled so that its largest component lies in
// [1, 2) (core/fields.hpp).
#include "core/fields.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto p = btob::core::parse_point(text, "point");
    const double x = p[0], y = p[1], z = p[2];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) std::abort();
    if (x * z > 0 || (x == 0 && z == 0)) std::abort();
    const double m = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
    if (!(m >= 1 && m < 2)) std::abort();
  } catch (const std::logic_error&) {
  }
  return 0;
}
