// SPDX-License-Identifier: GPL-3.0-or-later
// The stats requests' validation (correlate, measure) and the observables they name.
#include "stats/request_detail.hpp"
#include "stats/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace btob::stats {

namespace detail {
namespace {
Observable observable_field(const std::string& name) {
  try {
    return parse_observable(name, "observable");
  } catch (const std::invalid_argument&) {
    throw core::InvalidField("observable", "'" + name + "'", "one of " + observable_names() + " (phi[,psi])");
  }
}
}  // namespace

std::pair<Observable, Observable> observables(const std::string& spec) {
  const auto comma = spec.find(',');
  const Observable phi = observable_field(spec.substr(0, comma));
  return {phi, comma == std::string::npos ? phi : observable_field(spec.substr(comma + 1))};
}
}  // namespace detail

void CorrelateRequest::validate() const {
  core::require_r(r, "r");
  (void)core::parse_point(point, "point");
  (void)detail::observables(observable);
  if (iterations < 2) throw core::InvalidField("iterations", std::to_string(iterations), "at least 2");
  if (n_max < 0 || n_max >= iterations)
    throw core::InvalidField("n-max", std::to_string(n_max), fmt::format("0 <= n-max < iterations = {}", iterations));
  if (transient < 0) throw core::InvalidField("transient", std::to_string(transient), "at least 0");
  if (method != "fft" && method != "direct" && method != "both")
    throw core::InvalidField("method", "'" + method + "'", "fft, direct or both");
  (void)core::require_precision(precision, {"float", "double", "long-double"});
  if (window < 1) throw core::InvalidField("window", std::to_string(window), "at least 1");
  if (fit_lags < window)
    throw core::InvalidField("fit-lags", std::to_string(fit_lags), fmt::format("at least window = {}", window));
  iterate::checked_bytes(static_cast<std::size_t>(iterations + n_max), 3 * sizeof(double) + 1 + 4 * sizeof(double),
                         "iterations");
}

// ---- measure --------------------------------------------------------------------------------------------------

void MeasureRequest::validate() const {
  core::require_r(r, "r");
  if (iterations < 16) throw core::InvalidField("iterations", std::to_string(iterations), "at least 16");
  if (transient < 0) throw core::InvalidField("transient", std::to_string(transient), "at least 0");
  if (bins < 1 || bins > 4000) throw core::InvalidField("bins", std::to_string(bins), "1..4000");
  if (!(tv_same > 0 && tv_same <= 1)) throw core::InvalidField("tv-same", fmt::format("{}", tv_same), "in (0, 1]");
  try {
    (void)parse_chart(coords, "coords");
  } catch (const std::invalid_argument&) {
    throw core::InvalidField("coords", "'" + coords + "'", "strip or angles");
  }
  if (!extent.empty() && (extent.size() != 4 || !(extent[0] < extent[1]) || !(extent[2] < extent[3])))
    throw core::InvalidField("extent", fmt::format("{} values", extent.size()),
                             "u_lo,u_hi,v_lo,v_hi with u_lo < u_hi, v_lo < v_hi");
  const auto ics = iterate::parse_grid(grid, seed, "grid");
  iterate::checked_bytes(ics.size() * static_cast<std::size_t>(bins) * bins, 2 * sizeof(double), "grid x bins^2");
  iterate::checked_bytes(2 * ics.size() * static_cast<std::size_t>(iterations), 3 * sizeof(double) + 1,
                         "grid x iterations");
}

}  // namespace btob::stats
