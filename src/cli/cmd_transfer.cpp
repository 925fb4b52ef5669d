// SPDX-License-Identifier: GPL-3.0-or-later
// `btob transfer`: flags -> transfer::TransferRequest -> run -> spectrum.csv, components.csv, cycles.csv (cycles
// asked for or found), basins.csv (when there is an attractor), classes.csv (without --cycle), NAME.h5, NAME.json,
// NAME.png: Ulam's
// transfer operator at one r (spectrum, invariant densities, Lebesgue projection, TV to the empirical measure; with
// --eigenvalues 0 only the basins: cycles.csv, basins.csv and the files).  `btob
// transfer-r`: flags -> transfer::TransferRRequest -> run -> spectrum_r.csv, peripheral_r.csv, windows.csv, NAME.h5,
// NAME.json, NAME.png: the peripheral spectrum and its gap across r.  Section 8's programme.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "transfer/transfer.hpp"

#include <iostream>

namespace btob::cli {
namespace {

void transfer_body(const transfer::TransferRequest& req, const Output& o, const Context& ctx) {
  const transfer::TransferResult res = run_with_progress(req, o, ctx, "transfer");
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "transfer", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("transfer.py");  // the script reads NAME.h5 alone (no spectrum: the basins' panels)
  const auto written = files.commit();
  if (!o.quiet) std::cerr << res.summary() << "btob: wrote " << listing(written) << "\n";
}

void transfer_r_body(const transfer::TransferRRequest& req, const Output& o, const Context& ctx) {
  const transfer::TransferRResult res = run_with_progress(req, o, ctx, "transfer-r");
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "transfer-r", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("transfer_r.py");  // the script reads NAME.h5 alone
  const auto written = files.commit();
  if (!o.quiet) std::cerr << res.summary() << "btob: wrote " << listing(written) << "\n";
}

struct Registration {
  Registration() {
    command<transfer::TransferRequest>(
        "transfer",
        "Ulam's transfer operator of P^_r on a box partition (Section 8): leading spectrum (Spectra), closed classes "
        "and invariant densities, projection of Lebesgue measure, almost-invariant sets, TV distance to the empirical "
        "measure, basins from the Ulam graph (absorption into the named attractors; without --cycle, into those found "
        "by "
        "classifying the closed classes' boxes); writes spectrum.csv, components.csv, cycles.csv, basins.csv, "
        "classes.csv, NAME.h5/.json/.png",
        Output{"results/transfer/r0.15", "transfer", "", 0, false, false}, transfer_body);
    command<transfer::TransferRRequest>(
        "transfer-r",
        "Peripheral spectrum of Ulam's operator across r (eigenvalues within --peripheral of the unit circle) and its "
        "gap "
        "to the rest; writes spectrum_r.csv, peripheral_r.csv, windows.csv, NAME.h5/.json/.png",
        Output{"results/transfer/r_scan", "transfer_r", "", 0, false, false}, transfer_r_body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
