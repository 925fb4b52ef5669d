// SPDX-License-Identifier: GPL-3.0-or-later
// `btob precision`: flags -> precision::TradeoffRequest -> run -> results/precision/tradeoff.csv, manifest, plot.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "extras/extras.hpp"
#include "precision/tradeoff.hpp"

#include <fmt/format.h>

#include <iostream>

namespace btob::cli {
namespace {

void tradeoff(const precision::TradeoffRequest& req, const Output& o, const Context& ctx) {
  core::RunControl control = ctx.control;
  const auto bar = terminal_progress("precision study");
  if (!o.quiet) control.progress = bar.get();
  const precision::TradeoffResult res = precision::run(req, control);
  core::Contents c;
  res.describe(c);
  io::Attrs at = ctx.attrs(o, c, "precision_tradeoff", "float,double,long-double,float128,mpfr:50,mpfr:100,mpfr:256");
  extras::of(req).apply(at);
  io::ResultFiles files(o.out, o.name);
  const core::Tables tables = res.tables();  // NAME.csv, also printed
  files.tables(tables);
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("precision_tradeoff.py", o.name + ".h5");  // the script reads NAME.h5 alone
  files.commit();
  for (const auto& [role, text] : tables) std::cout << text;
}

struct Registration {
  Registration() {
    command<precision::TradeoffRequest>(
        "precision",
        "Speed against accuracy of each precision and algorithm (vs 256-digit MPFR). Most of its time is fixed parts "
        "(each method's window tests up to the largest window-n, its Lyapunov errors on the sinks and its throughput), "
        "about a minute whatever the orbits, which no short probe prices: --dry-run of a request not yet run on this "
        "machine runs it once (writing nothing); a completed run keeps its time for the dry runs after it",
        Output{"results/precision", "tradeoff", "", 0, false, false}, tradeoff);
  }
} registration;

}  // namespace
}  // namespace btob::cli
