// SPDX-License-Identifier: GPL-3.0-or-later
// The stats results' output: their CSV tables and the description of their arrays and attributes.
#include "stats/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace btob::stats {

core::Tables CorrelateResult::tables() const {
  const bool both = !c_direct.empty();
  core::CsvTable t(both ? "lag,C_N,C_N_direct" : "lag,C_N");
  for (std::size_t n = 0; n < c.size(); ++n)
    t.line(both ? fmt::format("{},{:.17g},{:.17g}", n, c[n], c_direct[n]) : fmt::format("{},{:.17g}", n, c[n]));
  return {{"", t.text()}};
}

void CorrelateResult::describe(core::Contents& c) const {
  const std::string lags = "lag n = 0..n-max", cn = "observable units squared (rad^2 for angles)";
  c.array("C_N", this->c, {this->c.size()}, lags, cn, "C_N(phi, psi; n), the centred correlation along the orbit");
  if (!c_direct.empty())
    c.array("C_N_direct", c_direct, {c_direct.size()}, lags, cn, "C_N by the direct sum (method both)");
  c.array("envelope", envelope, {envelope.size()}, "window of lags from lag 1", cn,
          fmt::format("max |C_N| over consecutive windows of {} lags", request.window));
  c.array("spectrum_frequency", frequency, {frequency.size()}, "frequency block", "cycles per iteration",
          "centre of each block of periodogram frequencies");
  c.array("power_spectrum", power, {power.size()}, "frequency block", "observable units squared",
          "periodogram of phi over the first N values, averaged over each block");
  c.attr("r", request.r);
  c.attr("point", request.point);
  c.attr("observables", observable_name(phi) + "," + observable_name(psi));
  c.attr("N", N());
  c.attr("n_max", request.n_max);
  c.attr("transient", request.transient);
  c.attr("method", request.method);
  c.attr("seconds", seconds);
  if (!c_direct.empty()) {
    c.attr("seconds_direct", seconds_direct);
    c.attr("max_rel_diff_fft_direct", max_rel_diff);
  }
  c.attr("spectrum_peak_frequency", peak_frequency);
  c.attr("noise_floor", noise_floor);
  if (fitted) {  // what the fit measured, only what it measured (stats.hpp, Decay)
    c.attr("decay_verdict", decay.verdict);
    c.attr("decay_reason", decay.reason);
    c.attr("decay_windows", decay.windows);
    c.attr("decay_window_lags", request.window);
    c.attr("decay_fit_lags", request.fit_lags);
    c.attr("decay_floor_reached", std::string(decay.floor_lag >= 0 ? "yes" : "no"));
    if (decay.floor_lag >= 0) c.attr("decay_floor_lag", decay.floor_lag);
    if (decay.windows >= 1) {
      c.attr("envelope_first", decay.envelope_first);
      c.attr("envelope_last", decay.envelope_last);
    }
    if (decay.windows >= 3) {
      c.attr("decay_rate", decay.rate);
      c.attr("decay_rate_error", decay.rate_error);
      c.attr("decay_rate_low", decay.rate_low);
      c.attr("decay_rate_high", decay.rate_high);
    }
  }
  if (!envelope.empty()) {
    c.attr("envelope_min", *std::min_element(envelope.begin(), envelope.end()));
    c.attr("envelope_max", *std::max_element(envelope.begin(), envelope.end()));
  }
}

double MeasureResult::tv_max_within_groups() const {
  return *std::max_element(tv_max_group.begin(), tv_max_group.end());
}

core::Tables MeasureResult::tables() const {
  core::CsvTable t("ic,x,y,z,group,tv_to_group_head,w1_u_to_group_head,w1_v_to_group_head");
  for (std::size_t i = 0; i < initial.size(); ++i) {
    const auto& u = initial[i];
    t.line(fmt::format("{},{},{},{},{},{:.6g},{:.6g},{:.6g}", i, u(0), u(1), u(2), group[i], tv[i], w1_u[i], w1_v[i]));
  }
  return {{"report", t.text()}};
}

void MeasureResult::describe(core::Contents& c) const {
  const std::size_t G = groups(), B = static_cast<std::size_t>(request.bins), I = group.size(), C = conv_n.size();
  const std::string chart = request.coords == "angles" ? "theta, phi (rad)" : "atan w1 (rad), w2";
  c.array("group_counts", counts, {G, B, B}, "group, u bin, v bin (" + chart + ")", "count",
          "points of the group's first orbit in each bin");
  c.array("group_marginal_u", marginal_u, {G, B}, "group, u bin", "1", "marginal mass of the group's measure in u");
  c.array("group_marginal_v", marginal_v, {G, B}, "group, v bin", "1", "marginal mass of the group's measure in v");
  c.array("group_head", head, {G}, "group", "index", "first initial condition of each group");
  c.array("group_size", size, {G}, "group", "count", "initial conditions in each group");
  c.array("group_outside", outside, {G}, "group", "1", "mass of the group's measure outside the extent");
  c.array("group_tv_max", tv_max_group, {G}, "group", "1", "largest total variation between two members");
  c.array("group", group_index, {I}, "initial condition", "index", "group of each initial condition");
  c.array("tv_to_group_head", tv, {I}, "initial condition", "1", "total variation to the group's first measure");
  c.array("w1_u_to_group_head", w1_u, {I}, "initial condition", "u units",
          "1-D Wasserstein distance of the u marginals to the group's first measure");
  c.array("w1_v_to_group_head", w1_v, {I}, "initial condition", "v units",
          "1-D Wasserstein distance of the v marginals to the group's first measure");
  c.array("convergence_n", conv_n, {C}, "checkpoint", "iterations", "N = 16, 32, ..., iterations");
  c.coordinate("checkpoint", "convergence_n");
  c.array("convergence_tv_within_group", conv_within, {C, G}, "checkpoint, group", "1",
          "largest TV between mu_N of a member and mu_N of the group's first orbit");
  c.array("convergence_tv_to_full", conv_to_full, {C, G}, "checkpoint, group", "1",
          "TV between mu_N of the group's first orbit and its measure at the full length");
  c.array("extent", extent, {4}, "u_lo, u_hi, v_lo, v_hi", chart, "the histogram's window in the chart");
  if (extent.size() == 4) {  // a result that ran: the bins' centres in the window
    c.coordinate_array("u_bin", core::bin_centres(extent[0], extent[1], B), {"u bin"}, chart,
                       "centre of each u bin of the histograms (the first chart coordinate)");
    c.coordinate_array("v_bin", core::bin_centres(extent[2], extent[3], B), {"v bin", "v bin (" + chart + ")"}, chart,
                       "centre of each v bin of the histograms (the second chart coordinate)");
  }
  c.attr("r", request.r);
  c.attr("grid", request.grid);
  c.attr("seed", static_cast<long>(request.seed));
  c.attr("iterations", request.iterations);
  c.attr("transient", request.transient);
  c.attr("bins", static_cast<long>(request.bins));
  c.attr("coords", request.coords);
  c.attr("tv_same", request.tv_same);
  c.attr("initial_conditions", static_cast<long>(I));
  c.attr("groups", static_cast<long>(G));
  c.attr("tv_max_within_groups", tv_max_within_groups());
}

}  // namespace btob::stats
