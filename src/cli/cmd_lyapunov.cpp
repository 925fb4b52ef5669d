// SPDX-License-Identifier: GPL-3.0-or-later
// `btob lyapunov`, `btob lyapunov-map`, `btob lyapunov-strip`: flags -> lyapunov::*Request -> run -> files.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "extras/extras.hpp"
#include "lyapunov/requests.hpp"

#include <fmt/format.h>

#include <fmt/ranges.h>
#include <optional>

#include <iostream>

namespace btob::cli {
namespace {

void orbit(const lyapunov::OrbitRequest& req, const Output&, const Context& ctx) {
  const lyapunov::ProjectiveResult res = lyapunov::run(req, ctx.control);
  const auto& l = res.lambda;
  // The table of --out's NAME.csv (with --weighted the weighted Birkhoff averages first: super-polynomial on
  // (quasi-)periodic orbits, no batch error); each exponent printed with its bar by core::with_error.
  std::cout << res.csv();
  if (req.precision == "float") {  // float rounding can move an orbit off a weak sink: the same orbit in double
    lyapunov::OrbitRequest d = req;
    d.precision = "double";
    d.convergence.clear();
    const lyapunov::ProjectiveResult rd = lyapunov::run(d, ctx.control);
    const int cf = lyapunov::classify(l[0].value, l[0].error, res.iterations),
              cd = lyapunov::classify(rd.lambda[0].value, rd.lambda[0].error, rd.iterations);
    const auto name = [](int c) { return c > 0 ? "positive" : c < 0 ? "negative" : "zero"; };
    const core::ValueWithError dl = core::with_error(rd.lambda[0].value, rd.lambda[0].error);
    if (cf != cd)
      std::cerr << fmt::format(
          "btob: warning: in double this orbit has lambda1 = {} +- {} ({}), float {:.6g} "
          "({}): float rounding moves orbits off weakly contracting sinks; use --precision double\n",
          dl.value, dl.error, name(cd), l[0].value, name(cf));
  }
  if (!req.convergence.empty()) {
    core::CsvTable csv("n,lambda1,lambda2");
    const auto& c = res.convergence;
    for (std::size_t j = 0; j < c.n.size(); ++j)
      csv.line(fmt::format("{},{:.12g},{:.12g}", c.n[j], c.exponents[0][j], c.exponents[1][j]));
    io::write_text_atomic(req.convergence, csv.text());
  }
}

// Runs a map or strip request and writes NAME.h5, NAME.json (and for a map NAME_summary.csv), then the plot.
template <class Req>
void maps(const Req& req, const Output& o, const Context& ctx, const std::string& kind, const std::string& script) {
  extras::check(req);  // unknown overlay names fail first; the lines are computed after the run, on rank 0
  Context run_ctx = ctx;
  const auto progress = terminal_progress(kind);
  if (!o.quiet) run_ctx.control.progress = progress.get();
  std::optional<lyapunov::MapResult> got;
  if constexpr (core::Sweep<Req>) got = sweep(req, run_ctx);  // every MPI rank computes its share; rank 0 writes
  else got = lyapunov::run(req, run_ctx.control);
  if (!got) return;
  const lyapunov::MapResult& res = *got;
  const extras::Extras ex = extras::of(req, res, ctx.control);  // the attractors field classifies every orbit here
  core::Contents c;
  res.describe(c);
  ex.add_to(c);
  io::Attrs at = ctx.attrs(o, c, kind, req.precision);
  ex.apply(at);
  io::ResultFiles files(o.out, o.name);
  files.h5(c, at);
  files.tables(res.tables());
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot(script);
  const auto written = files.commit();
  if constexpr (std::is_same_v<Req, lyapunov::MapRequest>)
    if (res.float_disagree > 0)
      std::cerr << fmt::format(
          "btob: warning: float and double give another sign of lambda1 on {} of the {} orbits "
          "re-run in double (first at r = {}): float rounding moves orbits off weakly contracting "
          "sinks; use --precision double\n",
          res.float_disagree, res.float_checked, res.float_disagree_r);
  const double steps = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.transient + req.iterations);
  if (!o.quiet)
    std::cerr << fmt::format(
        "btob: {} orbits x {} steps = {:.3g} map iterations with the tangent cocycle in {:.3f} s "
        "({:.3g} it/s); wrote {}\n",
        res.ensemble.orbits(), req.transient + req.iterations, steps, res.iteration_seconds,
        steps / res.iteration_seconds, listing(written));
}

struct Registration {
  Registration() {
    command<lyapunov::OrbitRequest>(
        "lyapunov",
        "Both Lyapunov exponents of one orbit (projective derivative cocycle, QR). Only the tangent cocycle is used: "
        "two nearby orbits straddle the branch boundaries of this piecewise-linear map and give wrong exponents.",
        Output::to_stdout(), orbit);
    command<lyapunov::MapRequest>("lyapunov-map",
                                  "Lyapunov exponents of every orbit over r values x a grid, summarised per r",
                                  Output{"results/lyapunov", "lyapunov_map", "", 0, false, false},
                                  [](const lyapunov::MapRequest& r, const Output& o, const Context& c) {
                                    maps(r, o, c, "lyapunov-map", "lyapunov_map.py");
                                  });
    command<lyapunov::StripRequest>("lyapunov-strip",
                                    "Lyapunov exponent at one r over a strip grid (w1, w2), as an image",
                                    Output{"results/lyapunov", "lyapunov_strip", "", 0, false, false},
                                    [](const lyapunov::StripRequest& r, const Output& o, const Context& c) {
                                      maps(r, o, c, "lyapunov-strip", "lyapunov_strip.py");
                                    });
  }
} registration;

}  // namespace
}  // namespace btob::cli
