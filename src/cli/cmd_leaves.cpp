// SPDX-License-Identifier: GPL-3.0-or-later
// `btob leaves`: flags -> leaves::Request -> run -> NAME.h5, NAME.csv, NAME_landing.csv, NAME_leaves.csv, NAME.json,
// NAME.png: P2's invariant curves (Section 8's programme (i), (ii), (iv)) at one r or across r.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "leaves/requests.hpp"

#include <fmt/format.h>

#include <iostream>

namespace btob::cli {
namespace {

void body(const leaves::Request& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("leaves " + o.name);
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its share of the r values; rank 0 writes
  if (!got) return;
  const leaves::Result& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "leaves", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("leaves.py");  // the script reads NAME.h5 alone
  const auto written = files.commit();
  if (o.quiet) return;
  std::cerr << fmt::format("btob: leaves at {} r values, {} points each, in {:.2f} s; wrote {}\n", res.r.size(),
                           res.grid.cells(), res.seconds, listing(written));
  for (std::size_t i = 0; i < res.r.size(); ++i)
    std::cerr << fmt::format(
        "  r = {:.10g}: theta/2pi = {:.10f}, region {:.4f}, on a P2 curve {:.4f} [{:.4f}, {:.4f}], "
        "landing t mean {:.4f} sd {:.4f}\n",
        res.r[i], res.rotation[i], res.region_share[i], res.mass[i], res.mass_low[i], res.mass_high[i],
        res.landing_mean[i], res.landing_sd[i]);
}

struct Registration {
  Registration() {
    command<leaves::Request>(
        "leaves",
        "P2's invariant curves: labels, region, rotation numbers, where orbits land and the measure on a leaf, at one "
        "r "
        "or across r; writes NAME.csv, NAME_landing.csv, NAME_leaves.csv, NAME.h5, NAME.json, NAME.png",
        Output{"results/leaves", "leaves", "", 0, false, false}, body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
