// SPDX-License-Identifier: GPL-3.0-or-later
// The transfer requests' validation (transfer, transfer-r): boxes, domain, samples, eigenvalues, the r range and the
// cycles named.
#include "transfer/transfer.hpp"

#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/grid.hpp"
#include "core/run.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/coords.hpp"
#include "core/map.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/patterns.hpp"
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"
#include "transfer/transfer_impl.hpp"
#include "windows/windows.hpp"

namespace btob::transfer {

// ---- Requests ---------------------------------------------------------------------------------------------
namespace {
std::string str(double v) { return fmt::format("{}", v); }
constexpr long kMaxSide = 1L << 15;  // a stated bound on N and M (2^30 boxes is far beyond memory anyway)
constexpr long kMaxSamples = 65536;

void check_size(long n, long samples) {
  // int indices of the sparse matrix: every sample's transition must be addressable.
  if (static_cast<double>(n) * static_cast<double>(samples) >= 2147483647.0)
    throw core::InvalidField("boxes", fmt::format("{} boxes x {} samples", n, samples),
                             "fewer than 2^31 samples in all (int indices of the sparse matrix)");
  // Memory: per box its row (<= samples entries of 12 bytes, counted at most 32 per box: rows of a map
  // concentrate), the chunk buffers, the decomposition and K eigenvectors (~ 400 bytes); refused up front.
  try {
    iterate::checked_bytes(static_cast<std::size_t>(n),
                           12 * static_cast<std::size_t>(std::min<long>(samples, 32)) + 400, "boxes");
  } catch (const std::length_error& e) {
    throw core::InvalidField("boxes", fmt::format("{} boxes", n),
                             "a partition that fits in memory (" + std::string(e.what()) + ")");
  }
}
}  // namespace

std::pair<long, long> parse_boxes(const std::string& s, const char* field) {
  static const core::GridSyntax boxes{core::grid_kinds({core::GridKind::boxes}), false, kMaxSide,
                                      fmt::format("NxM with 1 <= N, M <= {}", kMaxSide)};
  const core::Grid g = core::parse_grid(s, boxes, field);
  return {g.axis1.cells, g.axis2.cells};
}

Domain parse_domain(const std::string& s, const char* field) {
  if (s == "strip") return Domain::strip;
  if (s == "angles") return Domain::angles;
  throw core::InvalidField(field, "'" + s + "'", "strip or angles");
}

namespace {
// eigenvalues_min: 1 for transfer-r (its output is the spectrum), 0 for transfer (0: no spectrum, only the basins).
void check_common(double r, const std::string& boxes, const std::string& domain, int samples, int eigenvalues,
                  const std::string& route, const char* r_field, int eigenvalues_min = 1) {
  core::require_r(r, r_field);
  const auto [n1, n2] = parse_boxes(boxes);
  parse_domain(domain);
  if (samples < 1 || samples > kMaxSamples)
    throw core::InvalidField("samples", std::to_string(samples), fmt::format("1..{}", kMaxSamples));
  check_size(n1 * n2, samples);
  if (eigenvalues < eigenvalues_min || eigenvalues > n1 * n2)
    throw core::InvalidField("eigenvalues", std::to_string(eigenvalues),
                             fmt::format("{}..{} (the number of boxes{})", eigenvalues_min, n1 * n2,
                                         eigenvalues_min == 0 ? "; 0: no spectrum, only the basins" : ""));
  if (route != "direct" && route != "kernel") throw core::InvalidField("route", "'" + route + "'", "direct or kernel");
}
}  // namespace

std::vector<std::string> TransferRequest::cycle_words() const {
  std::vector<std::string> words;
  for (const auto& item : cycles)
    for (std::size_t at = 0; at <= item.size();) {
      const std::size_t end = std::min(item.find(',', at), item.size());
      if (end > at) words.push_back(item.substr(at, end - at));
      at = end + 1;
    }
  return words;
}

bool TransferRequest::names_an_attractor() const {
  if (detail::p2_level(r) > 0) return true;  // the P2 region exists
  for (const auto& w : cycle_words())
    if (patterns::analyse<double>(patterns::parse_word(w, "cycle"), r).outcome == patterns::Outcome::stable)
      return true;
  return false;
}

void TransferRequest::validate() const {
  check_common(r, boxes, domain, samples, eigenvalues, route, "r", 0);
  if (!(near_one > 0 && near_one < 1)) throw core::InvalidField("near-one", str(near_one), "a distance in (0, 1)");
  if (w1_range.size() != 2 || !(w1_range[0] < w1_range[1]) || !std::isfinite(w1_range[0]) ||
      !std::isfinite(w1_range[1]))
    throw core::InvalidField("w1-range", fmt::format("{} values", w1_range.size()), "two finite numbers a < b");
  if (measure_orbits < 0 || measure_orbits > 64)
    throw core::InvalidField("measure-orbits", std::to_string(measure_orbits), "0..64 (an NxN grid; 0 skips)");
  if (measure_iterations < 100 || measure_iterations > 100000000)
    throw core::InvalidField("measure-iterations", std::to_string(measure_iterations), "100..1e8");
  if (measure_transient < 0 || measure_transient > 100000000)
    throw core::InvalidField("measure-transient", std::to_string(measure_transient), "0..1e8");
  const auto [n1, n2] = parse_boxes(boxes);
  if (tv_bins < 1 || n1 % tv_bins != 0 || n2 % tv_bins != 0)
    throw core::InvalidField("tv-bins", std::to_string(tv_bins), fmt::format("a divisor of both {} and {}", n1, n2));
  for (const auto& w : cycle_words()) patterns::parse_word(w, "cycle");
  if (eigenvalues == 0 && check_whole)
    throw core::InvalidField("eigenvalues", "0 with check-whole", "1 or more: the cross-check compares spectra");
  if (eigenvalues == 0 && !names_an_attractor())
    throw core::InvalidField("eigenvalues", fmt::format("0 at r = {} with no stable --cycle and no P2 region", str(r)),
                             "1 or more, or an attractor for the basins (0 computes only them)");
  if (measure_orbits > 0)
    iterate::checked_bytes(
        static_cast<std::size_t>(measure_orbits * measure_orbits) * 2 * static_cast<std::size_t>(measure_iterations),
        25, "measure-iterations");
}

void TransferRRequest::validate() const {
  check_common(r_min, boxes, domain, samples, eigenvalues, route, "r-min");
  if (r_count < 1 || r_count > 100000) throw core::InvalidField("r-count", std::to_string(r_count), "1..100000");
  core::require_r_range(r_min, r_max, r_count);
  if (!(peripheral > 0 && peripheral < 1))
    throw core::InvalidField("peripheral", str(peripheral), "a distance in (0, 1)");
}

}  // namespace btob::transfer
