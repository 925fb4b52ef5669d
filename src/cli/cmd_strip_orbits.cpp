// `btob strip-orbits`: tails of individual orbits at one r in the strip (w1, w2), each with the classifier's
// verdict (Figures 6.9-6.11); a thin adapter over orbits::run.
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/csv.hpp"
#include "orbits/orbits.hpp"

#include <fmt/format.h>

#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

struct StripOrbitsArgs {
  orbits::StripOrbitsRequest q;
  int threads = 0;
  std::string out = "results/strip_orbits", name = "strip_orbits", title;
  double plot_w1 = 2;  // the plot shows -plot_w1 <= w1 <= plot_w1 (the paper: 2, and 30 for Figure 6.10)
  long only = 0;       // the plot shows only this orbit (1-based), 0 = all
  bool no_plot = false;
};

void strip_orbits(const StripOrbitsArgs& a, const std::string& command_line) {
  if (!(a.plot_w1 > 0)) throw UsageError(fmt::format("plot-w1: got {}, expected a positive number", a.plot_w1));
  if (a.only < 0 || a.only > a.q.orbits)
    throw UsageError(fmt::format("only: got {}, expected 0 (all) or 1..orbits ({})", a.only, a.q.orbits));
  core::RunControl control;
  control.threads = a.threads;
  const orbits::StripOrbitsResult res = orbits::run(a.q, control);  // validates first: nothing written on error
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto since = start_time();  // for the list of files written
  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("strip-orbits");
  attrs["name"] = a.name;
  attrs["title"] = a.title;
  attrs["r"] = a.q.r;
  attrs["orbits"] = a.q.orbits;
  attrs["iterations"] = a.q.iterations;
  attrs["tail"] = a.q.tail;
  attrs["seed"] = static_cast<long>(a.q.seed);
  attrs["w1_min"] = a.q.w1_min;
  attrs["w1_max"] = a.q.w1_max;
  attrs["initial_conditions"] = fmt::format("random strip points: w1 uniform in [{}, {}], w2 uniform in (-1, 1), seed {}",
                                            a.q.w1_min, a.q.w1_max, a.q.seed);
  attrs["plot_w1"] = a.plot_w1;
  attrs["only"] = a.only;
  attrs["scalar_type"] = std::string("double");
  attrs["periodic"] = static_cast<long>(res.periodic);
  attrs["quasi_periodic"] = static_cast<long>(res.quasi_periodic);
  attrs["other"] = static_cast<long>(res.other);
  attrs["total_seconds"] = res.seconds;  // iteration and classification, plot excluded
  // One line per orbit: where it started and what the classifier says (the panel titles).
  core::CsvTable csv("orbit,start_w1,start_w2,verdict,pattern,period,lambda1,err1,rotation,residual,detail");
  for (std::size_t o = 0; o < res.verdicts.size(); ++o) {
    const auto& v = res.verdicts[o];
    csv.row({fmt::format("{}", o + 1), fmt::format("{:.17g}", res.start_w1[o]), fmt::format("{:.17g}", res.start_w2[o]),
             orbits::panel_word(v.type), res.pattern[o], fmt::format("{}", v.period), fmt::format("{:.6g}", v.lambda1),
             fmt::format("{:.3g}", v.err1), fmt::format("{:.12g}", v.rotation), fmt::format("{:.3g}", v.residual),
             v.detail});
  }
  io::write_text_atomic(out / (a.name + ".csv"), csv.text());
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(attrs);
    const std::size_t n = res.start_w1.size(), t = static_cast<std::size_t>(a.q.tail);
    w.dataset("w1", res.w1, {n, t});
    w.dataset("w2", res.w2, {n, t});
    w.dataset("start_w1", res.start_w1, {n});
    w.dataset("start_w2", res.start_w2, {n});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  std::cerr << fmt::format("btob: r = {}: {} orbits x {} iterations, {} periodic, {} quasi-periodic, {} other ({:.2f} s); "
                           "plotting\n",
                           a.q.r, a.q.orbits, a.q.iterations, res.periodic, res.quasi_periodic, res.other, res.seconds);
  if (!a.no_plot)
    io::run_plot("strip_orbits.py", {h5.string(), (out / (a.name + ".csv")).string(), (out / (a.name + ".png")).string()});
  print_written({out / (a.name + ".csv"), h5, out / (a.name + ".json"), out / (a.name + ".png")}, since);
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<StripOrbitsArgs>();
  CLI::App* c = app.add_subcommand(
      "strip-orbits", "Tails of orbits at one r in the strip (w1, w2), titled by the classifier (Figures 6.9-6.11)");
  a->q.fields([c](const char* name, auto& member, const char* help) {
    c->add_option(std::string("--") + name, member, help)->capture_default_str();
  });
  c->add_option("--threads", a->threads, "OpenMP threads (results do not depend on it)");
  c->add_option("--out", a->out, "output directory")->capture_default_str();
  c->add_option("--name", a->name, "file stem of the outputs")->capture_default_str();
  c->add_option("--title", a->title, "figure title (r, orbits and iterations are added)");
  c->add_option("--plot-w1", a->plot_w1, "plot: -plot-w1 <= w1 <= plot-w1")->capture_default_str();
  c->add_option("--only", a->only, "plot: only this orbit (1-based), 0 = all")->capture_default_str();
  c->add_flag("--no-plot", a->no_plot, "write data only");
  c->callback([a, c] { strip_orbits(*a, command_line_of(c)); });
});

}  // namespace
}  // namespace btob::cli
