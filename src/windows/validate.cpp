// SPDX-License-Identifier: GPL-3.0-or-later
// The windows requests' validation, their n ranges and the names of their files (requests.hpp).
#include "windows/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "core/sweep.hpp"
#include "windows/direct.hpp"

#include <numbers>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iterator>
#include <optional>
#include <utility>

namespace btob::windows {

NRange parse_n_range(std::string_view text, int min_n, const std::string& field) {
  const auto [a, b] = core::parse_int_range(text, min_n, max_range_n, field);
  return {static_cast<int>(a), static_cast<int>(b)};
}

void require_digits(long digits, const std::string& field) {
  if (digits < 10 || digits > 10000) throw core::InvalidField(field, std::to_string(digits), "10..10000");
}

// ---- poly ------------------------------------------------------------------------------------------------
void PolyRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  if (form != "developed" && form != "factorised" && form != "both")
    throw core::InvalidField("form", "'" + form + "'", "developed, factorised or both");
}

std::size_t PolyRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 1, "n").count()); }

// ---- bounds ----------------------------------------------------------------------------------------------
void BoundsRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  require_digits(digits);
}

std::size_t BoundsRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 1, "n").count()); }

void ThresholdsRequest::validate() const { require_digits(digits); }

void StripesRequest::validate() const {
  if (max_m < 1 || max_m > 100000) throw core::InvalidField("max-m", std::to_string(max_m), "1..100000");
  require_digits(digits);
}

// ---- verify ----------------------------------------------------------------------------------------------
void VerifyRequest::validate() const {
  (void)parse_n_range(n, 2, "n");  // n = 1 (abcb) is never stable and has no r_crit,2
  if (iterations < 100) throw core::InvalidField("iterations", std::to_string(iterations), "at least 100");
  if (per_n < 0) throw core::InvalidField("per-n", std::to_string(per_n), "at least 0");
  if (tail < 1 || tail >= iterations)
    throw core::InvalidField("tail", std::to_string(tail), fmt::format("1..iterations-1 = {}", iterations - 1));
  (void)core::require_precision(precision, {"double", "long-double"});
}

std::size_t VerifyRequest::work_items() const { return static_cast<std::size_t>(parse_n_range(n, 2, "n").count()); }

std::string verify_stem(const NRange& r) {
  return r.first == 2 && r.last == 125 ? std::string("verify") : fmt::format("verify_{}-{}", r.first, r.last);
}

std::string VerifyRequest::default_name() const { return verify_stem(parse_n_range(n, 2, "n")); }

// ---- precision study of the lower bound ------------------------------------------------------------------
void BoundPrecisionRequest::validate() const {
  (void)parse_n_range(n, 1, "n");
  if (mpfr_digits < 10 || mpfr_digits > 1000)
    throw core::InvalidField("mpfr-digits", std::to_string(mpfr_digits), "10..1000");
}

std::size_t BoundPrecisionRequest::work_items() const {
  return static_cast<std::size_t>(parse_n_range(n, 1, "n").count());
}

}  // namespace btob::windows
