// SPDX-License-Identifier: GPL-3.0-or-later
// `btob pattern`: flags -> patterns::WordRequest (verdict of one word at r, its stability set, its exact
// characteristic polynomial; printed on stdout) or patterns::AtlasRequest (`btob pattern atlas`: the atlas of
// stable patterns and its check against the iterator, or every feasible periodic orbit; files).  The atlas is a
// sweep (cli/sweep.hpp): under mpirun the ranks share the words and the check's r values, and rank 0 writes.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/cancel.hpp"
#include "patterns/requests.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <string>

namespace btob::cli {
namespace {

void word_body(const patterns::WordRequest& req, const Output& o, const Context& ctx) {
  // The run polls the token (the analysis along the word's symbols); the text (O(length): milliseconds for the
  // longest word) does not, and a signal during it prints nothing.
  const patterns::WordResult res = patterns::run(req, ctx.control);
  const std::string text = res.text();
  core::check_cancel(ctx.control.cancel);
  std::cout << text;
  // An empty stability set is a claim about every r: say what the scan could not see (patterns/scan_impl.hpp).
  if (res.mode == patterns::WordRequest::Mode::window && res.intervals.empty() && !o.quiet)
    std::cerr << "btob: no stability interval found; the scan follows every change of the dominant eigenvalue "
                 "between its grid points down to the bisection width, but an interval bounded by feasibility "
                 "changes alone and narrower than the grid step there (4.75e-5 on [0.07, 0.26)) may be missed\n";
}

void atlas_body(const patterns::AtlasRequest& req, const Output& o, const Context& ctx) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto got = sweep(req, ctx);
  if (!got) return;
  const patterns::AtlasResult& res = *got;
  if (!o.quiet) std::cerr << "btob: " << res.summary() << "\n";
  core::Contents c;
  res.describe(c);
  io::Attrs at = ctx.attrs(o, c, req.feasible ? "patterns-feasible-atlas" : "patterns-atlas", "double");
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  at["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot(req.feasible ? "patterns_feasible.py" : "patterns_atlas.py");  // NAME.h5 alone
  const auto written = files.commit();
  if (!o.quiet) std::cerr << "btob: wrote " << listing(written) << "\n";
}

struct Registration {
  Registration() {
    command<patterns::WordRequest>(
        "pattern", "Periodic patterns: verdict of a word at r, its stability windows, or the atlas (Sections 6.2, 7)",
        Output::to_stdout(), word_body);
    command<patterns::AtlasRequest>(
        "pattern atlas", "Every canonical primitive word up to a length: stability sets, checked against the iterator",
        Output{"results/patterns", "", "", 0, false, false}, atlas_body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
