// SPDX-License-Identifier: GPL-3.0-or-later
// `btob hyperbolicity` (singular values of the one-step derivative over a strip grid, as an image) and
// `btob hyperbolicity-orbits` (per r: fraction of expanding steps and CLV angles along orbits, beside lambda1):
// the (non-)hyperbolicity of Section 8.1 (3).  Flags -> lyapunov::Hyperbolicity*Request -> run -> files; both are
// sweeps (cli/sweep.hpp): under mpirun the ranks share the w1 columns or the r values and rank 0 writes.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/csv.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>

namespace btob::cli {
namespace {

void strip(const lyapunov::HyperbolicityRequest& req, const Output& o, const Context& ctx) {
  const auto got = sweep(req, ctx);  // every MPI rank computes its columns; rank 0 writes
  if (!got) return;
  const lyapunov::HyperbolicityResult& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "hyperbolicity-strip", "double");
  io::ResultFiles files(o.out, o.name);
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("hyperbolicity_strip.py");
  const auto written = files.commit();
  const auto& img = res.image;
  const auto [mn, mx] = std::minmax_element(img.s1.begin(), img.s1.end());
  std::cout << "r,cells,expanding_fraction,s1_min,s1_max\n"
            << fmt::format("{},{},{:.6f},{:.6g},{:.6g}\n", req.r, img.s1.size(), img.expanding_fraction, *mn, *mx);
  if (!o.quiet)
    std::cerr << fmt::format("btob: {} cells in {:.3f} s; wrote {}\n", img.s1.size(), res.seconds, listing(written));
}

void orbits(const lyapunov::HyperbolicityOrbitsRequest& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("hyperbolicity-orbits");
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its r values; rank 0 writes
  if (!got) return;
  const lyapunov::HyperbolicityOrbitsResult& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "hyperbolicity-orbits", "double");
  io::ResultFiles files(o.out, o.name);
  files.h5(c, at);
  files.tables(res.tables());
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("hyperbolicity_orbits.py");
  const auto written = files.commit();
  if (!o.quiet)
    std::cerr << fmt::format("btob: {} orbits x {} steps with CLVs in {:.3f} s; wrote {}\n", res.ensemble.orbits(),
                             req.transient + req.iterations + req.backward, res.clv_seconds, listing(written));
}

struct Registration {
  Registration() {
    command<lyapunov::HyperbolicityRequest>(
        "hyperbolicity", "Singular values of the one-step derivative of the projective map over a strip grid",
        Output{"results/hyperbolicity", "", "", 0, false, false}, strip);
    command<lyapunov::HyperbolicityOrbitsRequest>(
        "hyperbolicity-orbits",
        "Per r: fraction of expanding steps and CLV angles (Ginelli) along orbits, beside lambda1",
        Output{"results/hyperbolicity", "hyperbolicity_orbits", "", 0, false, false}, orbits);
  }
} registration;

}  // namespace
}  // namespace btob::cli
