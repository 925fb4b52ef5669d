// SPDX-License-Identifier: GPL-3.0-or-later
// `btob strip-orbits`: flags -> orbits::StripOrbitsRequest -> run -> NAME.h5, NAME.csv, NAME.json, NAME.png: tails of
// individual orbits at one r in the strip (w1, w2), each with the classifier's verdict (Figures 6.9-6.11).
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "orbits/orbits.hpp"

#include <fmt/format.h>

#include <iostream>

namespace btob::cli {
namespace {

// The request and how its figure is drawn (presentation only: no number depends on these two).
struct StripOrbitsCommand : orbits::StripOrbitsRequest {
  double plot_w1 = 2;  // the plot shows -plot_w1 <= w1 <= plot_w1 (the paper: 2, and 30 for Figure 6.10)
  long only = 0;       // the plot shows only this orbit (1-based), 0 = all
  void validate() const {
    StripOrbitsRequest::validate();
    if (!(plot_w1 > 0 && plot_w1 <= 1e6))
      throw core::InvalidField("plot-w1", fmt::format("{}", plot_w1), "a number in (0, 1e6]");
    if (only < 0 || only > orbits)
      throw core::InvalidField("only", std::to_string(only), fmt::format("0 (all) or 1..orbits ({})", orbits));
  }
  template <class V> void fields(V&& v) {
    StripOrbitsRequest::fields(v);
    v("plot-w1", plot_w1, "plot: -plot-w1 <= w1 <= plot-w1");
    v("only", only, "plot: only this orbit (1-based), 0 = all");
  }
};

void body(const StripOrbitsCommand& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("strip-orbits " + o.name);
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const orbits::StripOrbitsResult res = orbits::run(req, run_ctx.control);
  core::Contents c;
  res.describe(c);
  io::Attrs at = ctx.attrs(o, c, "strip-orbits", "double");
  at["plot_w1"] = req.plot_w1;
  at["only"] = req.only;
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("strip_orbits.py");  // the script reads NAME.h5 alone
  const auto written = files.commit();
  if (!o.quiet)
    std::cerr << fmt::format(
        "btob: r = {}: {} orbits x {} iterations, {} periodic, {} quasi-periodic, {} other ({:.2f} s); "
        "wrote {}\n",
        req.r, req.orbits, req.iterations, res.periodic, res.quasi_periodic, res.other, res.seconds, listing(written));
}

struct Registration {
  Registration() {
    command<StripOrbitsCommand>(
        "strip-orbits", "Tails of orbits at one r in the strip (w1, w2), titled by the classifier (Figures 6.9-6.11)",
        Output{"results/strip_orbits", "strip_orbits", "", 0, false, false}, body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
