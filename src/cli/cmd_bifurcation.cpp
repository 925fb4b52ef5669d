// SPDX-License-Identifier: GPL-3.0-or-later
// `btob bifurcation`: flags -> bifurcation::Request -> run -> NAME.h5, NAME.json, NAME.png (Figures 4.1-4.7, 6.1-6.8).
#include "bifurcation/bifurcation.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "extras/extras.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iostream>

namespace btob::cli {
namespace {

// Tail points outside the range, and orbits the precision lost: said on stderr, recorded in the attributes.
void warn(const bifurcation::Request& req, const bifurcation::Result& res) {
  const std::uint64_t under = res.points_below(), over = res.points_above();
  const double tail_points = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.tail);
  // On a log scale -inf means theta underflowed to 0: the small component of the state fell below the
  // precision's smallest number (float near 7-4*sqrt(3), Figures 4.3-4.6); the diagram then lacks those points.
  if (under + over > 0 && static_cast<double>(under + over) > 1e-3 * tail_points)
    std::cerr << fmt::format("btob: warning: {:.1f}% of the tail points fall outside [{}, {}] ({} below, {} above){}\n",
                             100.0 * static_cast<double>(under + over) / tail_points, res.lo, res.hi, under, over,
                             req.log && req.precision == "float"
                                 ? "; in float, theta underflows to 0 where double still resolves it: use double"
                                 : "; widen --range to see them");
  if (res.degenerate > 0)
    std::cerr << fmt::format(
        "btob: warning: {} of {} orbits ended in a non-finite or zero state in {}: this precision "
        "cannot cope at these r; use double or wider\n",
        res.degenerate, res.ensemble.orbits(), res.scalar_type);
}

void body(const bifurcation::Request& req, const Output& o, const Context& ctx) {
  const auto t0 = std::chrono::steady_clock::now();
  extras::check(req);  // unknown overlay names fail first; the lines are computed after the run, on rank 0
  Context run_ctx = ctx;
  const auto progress = terminal_progress("bifurcation " + o.name);
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its share; rank 0 writes
  if (!got) return;
  const bifurcation::Result& res = *got;
  const extras::Extras ex = extras::of(req, res, ctx.control);  // the attractors field classifies every orbit here
  warn(req, res);
  core::Contents c;
  res.describe(c);
  ex.add_to(c);
  io::Attrs at = ctx.attrs(o, c, "bifurcation", res.scalar_type);
  ex.apply(at);
  io::ResultFiles files(o.out, o.name);
  files.h5(c, at);
  at["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("bifurcation.py");
  const auto written = files.commit();
  const double its = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.iterations);
  if (!o.quiet)
    std::cerr << fmt::format(
        "btob: {} orbits x {} iterations = {:.3g} map iterations in {:.3f} s ({:.3g} it/s, {} threads); "
        "wrote {}\n",
        res.ensemble.orbits(), req.iterations, its, res.iteration_seconds, its / res.iteration_seconds,
        std::get<long>(at["threads"]), listing(written));
}

struct Registration {
  Registration() {
    command<bifurcation::Request>("bifurcation",
                                  "Tails of theta or phi against r, as a density image (Figures 4.x, 6.x)",
                                  Output{"results/bifurcation", "bifurcation", "", 0, false, false}, body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
