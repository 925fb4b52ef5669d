// SPDX-License-Identifier: GPL-3.0-or-later
// `btob particles WORD --r R`: flags -> particles::ParticlesRequest -> run -> one CSV row on stdout, and NAME.csv,
// convergence.csv, events.csv, NAME.json, spacetime.png, animation.gif: four particles realise the periodic pattern
// WORD, event by event.
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "particles/particles.hpp"

#include <iostream>

namespace btob::cli {
namespace {

// The request and whether the printed row has its header line (presentation only: no number depends on it).
struct ParticlesCommand : particles::ParticlesRequest {
  bool header = false;
  template <class V> void fields(V&& v) {
    ParticlesRequest::fields(v);
    v("header", header, "print the CSV header line before the row");
  }
};

void body(const ParticlesCommand& req, const Output& o, const Context& ctx) {
  const particles::ParticlesResult res = particles::run(req, ctx.control);
  std::cout << res.row_csv(req.header) << std::flush;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "particles", res.precision);
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot_figures("particles.py", {o.name + ".h5"});  // the script reads NAME.h5 alone
  const auto written = files.commit();
  if (!o.quiet) std::cerr << res.summary();
  if (!res.failure.empty()) std::cerr << "btob: warning: " << res.failure << "\n";  // even with --quiet
  if (!o.quiet) std::cerr << "btob: wrote " << listing(written) << "\n";
}

struct Registration {
  Registration() {
    command<ParticlesCommand>(
        "particles",
        "Four particles realise the periodic pattern WORD: event-driven collapse, letters and contraction per period "
        "against the period matrix; prints word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse",
        Output{"", "particles", "", 0, false, false}, body);
  }
} registration;

}  // namespace
}  // namespace btob::cli
