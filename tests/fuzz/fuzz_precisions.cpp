// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: core::parse_precision ("float", "double", "long-double", "float128", "mpfr:<digits>").
// A parse either throws std::invalid_argument or returns a precision whose name parses back to itself, with
// 10 <= digits <= 10000 for mpfr.
#include "core/scalar.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using btob::core::Precision;
  if (size > 1024) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Precision p;
  try {
    p = btob::core::parse_precision(text, "precision");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (p.kind == Precision::Kind::mpfr && (p.mpfr_digits < 10 || p.mpfr_digits > 10000)) std::abort();
  const Precision q = btob::core::parse_precision(p.name(), "precision");
  if (q.kind != p.kind || q.mpfr_digits != p.mpfr_digits) std::abort();
  return 0;
}
