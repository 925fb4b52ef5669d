// SPDX-License-Identifier: GPL-3.0-or-later
// `btob classify` (one orbit), `btob basins` (one r over a grid: basin image and fractions), `btob basins-r`
// (basin fractions across r, compared to Table 6.1): the attractors of Section 8.1 (1), flags ->
// attractors::*Request -> run -> files.
#include "attractors/requests.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/csv.hpp"
#include "io/io.hpp"

#include <fmt/format.h>

#include <iostream>

namespace btob::cli {

// basins-r --table: Table 6.1 is data of the lab (io::data_file) unless --reference names another CSV; read before
// the request is validated, so a dry run samples its r values too.
template <> struct Prepare<attractors::BasinsRRequest> {
  static void apply(attractors::BasinsRRequest& req) {
    req.reference_csv = io::data_text(req.reference, attractors::table_6_1_file);
  }
};

namespace {

// ---- btob classify ----
void classify(const attractors::ClassifyRequest& req, const Output&, const Context& ctx) {
  const attractors::ClassifyResult res = attractors::run(req, ctx.control);
  const attractors::OrbitVerdict& v = res.verdict;
  std::cout << res.csv();
}

// ---- btob basins ----
void basins(const attractors::BasinsRequest& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("basins");
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its share of the rows; rank 0 writes
  if (!got) return;
  const attractors::BasinsResult& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "basins", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("attractors_basins.py");  // the script reads NAME.h5 alone
  const auto written = files.commit();
  const attractors::Basins& b = res.basins;
  const std::size_t n = res.points();
  if (!o.quiet)
    std::cerr << fmt::format(
        "btob: basins at r = {}: {} points x {} grids in {:.2f} s ({:.3g} points/s, {} threads), "
        "{} attractors, undecided {:.4f} ({} before refinement); wrote {}\n",
        req.r, n, req.replicates + 1, b.seconds,
        static_cast<double>(n * static_cast<std::size_t>(req.replicates + 1)) / b.seconds, res.threads,
        b.attractors.size(), b.undecided.value, b.undecided_first_pass, listing(written));
  if (o.quiet) return;
  // Each attractor's fraction with its 95% interval (sampling only), of the measure the grid samples.
  std::cerr << "  fractions of the measure: " << attractors::measure_name(b.grid) << "\n";
  if (b.grid.kind == core::GridKind::strip)
    std::cerr << fmt::format(
        "  the rectangle leaves out {:.4f} of the uniform measure on the sphere of directions "
        "(sphere:NxM counts that measure)\n",
        1 - attractors::sphere_share(b.grid));
  for (std::size_t i = 0; i < b.attractors.size(); ++i)
    std::cerr << fmt::format("  {} {} {}: {:.4f} [{:.4f}, {:.4f}]\n", b.attractors[i].id,
                             attractors::type_name(b.attractors[i].type), b.attractors[i].pattern, b.fractions[i].value,
                             b.fractions[i].low, b.fractions[i].high);
  std::cerr << fmt::format("  0 undecided: {:.4f} [{:.4f}, {:.4f}]\n", b.undecided.value, b.undecided.low,
                           b.undecided.high);
  std::cerr << attractors::boundary_summary(b.boundary);
}

// ---- btob basins-r ----
void basins_r(const attractors::BasinsRRequest& req, const Output& o, const Context& ctx) {
  Context run_ctx = ctx;
  const auto progress = terminal_progress("basins-r");
  if (!o.quiet) run_ctx.control.progress = progress.get();
  const auto got = sweep(req, run_ctx);  // every MPI rank computes its share of the r values; rank 0 writes
  if (!got) return;
  const attractors::BasinsRResult& res = *got;
  if (!o.quiet)
    for (const auto& row : res.rows) {
      std::cerr << fmt::format("btob: basins-r r = {}: {} attractors\n", row.r, row.attractors.size());
      if (row.has_boundary) std::cerr << attractors::boundary_summary(row.boundary);
    }
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "basins-r", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("attractors_fractions_r.py");
  const auto written = files.commit();
  if (!o.quiet)
    std::cerr << fmt::format("btob: basins-r in {:.2f} s; fractions of the measure: {}; wrote {}\n", res.seconds,
                             attractors::grid_measure(req.grid), listing(written));
}

struct Registration {
  Registration() {
    command<attractors::ClassifyRequest>("classify",
                                         "Classify one orbit: periodic, collapse, quasi-periodic, chaotic or undecided",
                                         Output::to_stdout(), classify);
    command<attractors::BasinsRequest>(
        "basins",
        "Basins of the attractors at one r over a grid: image, fractions, basin entropies, uncertainty exponent, Wada "
        "test; writes NAME_fractions.csv, NAME_boundary.csv, NAME.h5, NAME.json, NAME.png",
        Output{"results/attractors/basins", "basins", "", 0, false, false}, basins);
    command<attractors::BasinsRRequest>(
        "basins-r",
        "Basin fractions across r (Table 6.1 with many orbits), stacked areas, and basin entropies and uncertainty "
        "exponent per r; writes NAME.csv, table_6_1_comparison.csv, NAME_boundary.csv, NAME.h5, NAME.json, NAME.png",
        Output{"results/attractors/basins_r", "fractions_r", "", 0, false, false}, basins_r);
  }
} registration;

}  // namespace
}  // namespace btob::cli
