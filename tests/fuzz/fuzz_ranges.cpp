// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: core::parse_int_range ("A..B" or "A", the --n flag of `btob windows`).  A parse either throws
// core::InvalidField naming the field, or returns lo <= A <= B <= hi, and then the canonical text "A..B" parses
// back to the same pair (the parser reads what the manifests write).
#include "core/fields.hpp"
#include "core/request.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 256) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  constexpr long lo = 1, hi = 5000;  // windows::max_range_n
  try {
    const auto [a, b] = btob::core::parse_int_range(text, lo, hi, "n");
    if (!(lo <= a && a <= b && b <= hi)) std::abort();
    const auto back = btob::core::parse_int_range(std::to_string(a) + ".." + std::to_string(b), lo, hi, "n");
    if (back.first != a || back.second != b) std::abort();
  } catch (const btob::core::InvalidField& e) {
    if (e.field != "n") std::abort();
  }
  return 0;
}
