// SPDX-License-Identifier: GPL-3.0-or-later
// `btob pattern-curves`: flags -> patterns::CurvesRequest -> run -> NAME.h5, NAME_critical.csv, NAME.json and the
// figures: spectrum and feasibility quantities of a word's period matrix against r (Figures 7.1-7.8).
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "patterns/curves.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iostream>

namespace btob::cli {
namespace {

void body(const patterns::CurvesRequest& req, const Output& o, const Context& ctx) {
  const auto t0 = std::chrono::steady_clock::now();
  const patterns::CurvesResult res = patterns::run(req, ctx.control);
  core::Contents c;
  res.describe(c);
  io::Attrs at = ctx.attrs(o, c, "pattern-curves", "double (spectrum in long double)");
  at["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();  // plot excluded
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot_figures("pattern_curves.py", {o.name + ".h5"});  // the script reads NAME.h5 alone
  const auto written = files.commit();
  if (!o.quiet)
    std::cerr << fmt::format("btob: {} ({}analysed as {}) at {} r values; {} critical r; wrote {}\n", res.word,
                             res.reduced ? "J-square, " : "", res.analysed, res.r.size(), res.critical.size(),
                             listing(written));
}

struct Registration {
  Registration() {
    command<patterns::CurvesRequest>(
        "pattern-curves", "Spectrum and feasibility quantities of a word's period matrix against r (Figures 7.1-7.8)",
        Output{"results/pattern_curves", "curves", "", 0, false, false}, body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
