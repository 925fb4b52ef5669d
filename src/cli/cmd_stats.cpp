// SPDX-License-Identifier: GPL-3.0-or-later
// `btob correlate` (C_N along one orbit) and `btob measure` (empirical measures of many initial conditions, their
// distances and convergence), Section 8.1 (2): flags -> stats::*Request -> run -> files.  measure is a sweep
// (cli/sweep.hpp): under mpirun the ranks share the initial conditions and rank 0 writes.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/error_bar.hpp"
#include "stats/requests.hpp"

#include <fmt/format.h>

#include <cmath>

#include <iostream>

namespace btob::cli {
namespace {

void correlate(const stats::CorrelateRequest& req, const Output& o, const Context& ctx) {
  const stats::CorrelateResult res = stats::run(req, ctx.control);
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "correlate", req.precision);
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());  // NAME.csv
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("stats_correlation.py");
  const auto written = files.commit();
  if (o.quiet) return;
  // Everything below is read from the attributes NAME.json and NAME.h5 carry, so the terminal and the files agree.
  const auto num = [&](const char* k) {
    const auto& v = c.attrs.at(k);
    return std::holds_alternative<long>(v) ? fmt::format("{}", std::get<long>(v))
                                           : fmt::format("{:.4g}", std::get<double>(v));
  };
  const auto has = [&](const char* k) { return c.attrs.count(k) > 0; };
  std::cerr << fmt::format("btob: C_N({}, {}; 0..{}) over N = {} in {:.3g} s ({}, {}); noise floor {}",
                           stats::observable_name(res.phi), stats::observable_name(res.psi), req.n_max, res.N(),
                           res.seconds, req.method, req.precision, num("noise_floor"));
  if (res.fitted) {
    std::cerr << fmt::format("; {}: {} window(s) of {} lags above the floor",
                             std::get<std::string>(c.attrs.at("decay_verdict")), num("decay_windows"), req.window);
    if (has("envelope_first"))
      std::cerr << fmt::format(", envelope {} .. {}", num("envelope_first"), num("envelope_last"));
    std::cerr << (has("decay_floor_lag") ? fmt::format(", floor reached at lag {}", num("decay_floor_lag"))
                                         : fmt::format(", floor not reached by lag {}", req.fit_lags));
    if (has("decay_rate")) {  // the rate and its bar by core::with_error: the printed interval holds the rate
      const double v = std::get<double>(c.attrs.at("decay_rate")), e = std::get<double>(c.attrs.at("decay_rate_error"));
      const core::ValueWithError rate = std::isfinite(v) && std::isfinite(e) && e >= 0
                                            ? core::with_error(v, e)
                                            : core::ValueWithError{num("decay_rate"), num("decay_rate_error")};
      std::cerr << fmt::format(", rate {} +- {} per iteration (95%: {} .. {})", rate.value, rate.error,
                               num("decay_rate_low"), num("decay_rate_high"));
    }
    std::cerr << " (" << std::get<std::string>(c.attrs.at("decay_reason")) << ")";
  }
  if (!res.c_direct.empty())
    std::cerr << fmt::format("; fft vs direct {:.2g} relative, direct {:.3g} s", res.max_rel_diff, res.seconds_direct);
  std::cerr << "; wrote " << listing(written) << "\n";
}

void measure(const stats::MeasureRequest& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("measure");
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its initial conditions' orbits; rank 0 writes
  if (!got) return;
  const stats::MeasureResult& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "measure", "double");
  io::ResultFiles files(o.out, o.name);
  files.h5(c, at);
  files.tables(res.tables());  // NAME_report.csv
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("stats_measure.py");
  const auto written = files.commit();
  if (!o.quiet)
    std::cerr << fmt::format(
        "btob: {} initial conditions in {} group(s) (TV < {}); largest TV within a group {:.3g}; "
        "wrote {}\n",
        res.initial.size(), res.groups(), req.tv_same, res.tv_max_within_groups(), listing(written));
}

struct Registration {
  Registration() {
    command<stats::CorrelateRequest>(
        "correlate",
        "C_N(phi, psi; n) = (1/N) sum_{k<N} phi(x_k) psi(x_{k+n}) - mean(phi) mean(psi), n = 0..n-max, along one orbit "
        "(Section 8.1 (2)); writes NAME.csv (lag,C_N), NAME.h5 (C_N, envelope, power spectrum), NAME.json, NAME.png",
        Output{"results/stats", "correlation", "", 0, false, false}, correlate);
    command<stats::MeasureRequest>(
        "measure",
        "Empirical measures mu_{N,x} = (1/N) sum_{k<N} delta_{x_k} of many initial conditions at one r (Section 8.1 "
        "(2)): 2-D histograms, marginals, total variation and 1-D Wasserstein distances, groups of coinciding "
        "measures, "
        "convergence against N; writes NAME.h5, NAME_report.csv, NAME.json, NAME.png",
        Output{"results/stats", "measure", "", 0, false, false}, measure);
  }
} registration;

}  // namespace
}  // namespace btob::cli
