// `btob pattern-curves`: spectrum and feasibility quantities of a word's period matrix against r (Figures
// 7.1-7.8); a thin adapter over patterns::run(CurvesRequest).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/csv.hpp"
#include "patterns/curves.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

struct CurvesArgs {
  patterns::CurvesRequest q;
  int threads = 0;
  std::string out = "results/pattern_curves", name = "curves", title;
  bool no_plot = false;
};

void curves(const CurvesArgs& a, const std::string& command_line) {
  core::RunControl control;
  control.threads = a.threads;
  const auto t0 = std::chrono::steady_clock::now();
  const patterns::CurvesResult res = patterns::run(a.q, control);  // validates first: nothing written on error
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto since = start_time();  // for the list of files written
  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("pattern-curves");
  attrs["name"] = a.name;
  attrs["title"] = a.title;
  attrs["word"] = res.word;
  attrs["analysed"] = res.analysed;
  attrs["reduced"] = static_cast<long>(res.reduced);
  attrs["track"] = a.q.track;
  attrs["r_min"] = a.q.r_min;
  attrs["r_max"] = a.q.r_max;
  attrs["r_count"] = a.q.r_count;
  attrs["scalar_type"] = std::string("double (spectrum in long double)");
  attrs["total_seconds"] = seconds;  // plot excluded
  std::string names;
  for (const auto& s : res.feas_names) names += (names.empty() ? "" : ",") + s;
  attrs["feas_names"] = names;
  core::CsvTable csv("what,r");
  for (const auto& c : res.critical) csv.row({c.what, fmt::format("{:.16f}", c.r)});
  io::write_text_atomic(out / (a.name + "_critical.csv"), csv.text());
  const io::fs::path h5 = out / (a.name + ".h5");
  const std::size_t n = res.r.size();
  {
    io::H5Writer w(h5);
    w.attrs(attrs);
    w.dataset("r", res.r, {n});
    w.dataset("eig_re", res.eig_re, {n, 3});
    w.dataset("eig_im", res.eig_im, {n, 3});
    w.dataset("modulus", res.modulus, {n, 3});
    w.dataset("tracked", res.tracked, {n});
    w.dataset("dominance", res.dominance, {n});
    w.dataset("feas", res.feas, {n, res.feas_names.size()});
    std::vector<double> crit;
    for (const auto& c : res.critical) crit.push_back(c.r);
    w.dataset("critical_r", crit, {crit.size()});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  std::cerr << fmt::format("btob: {} ({}analysed as {}) at {} r values; {} critical r\n", res.word,
                           res.reduced ? "J-square, " : "", res.analysed, n, res.critical.size());
  if (!a.no_plot)
    io::run_plot("pattern_curves.py", {h5.string(), (out / (a.name + "_critical.csv")).string(), out.string()});
  std::vector<io::fs::path> files{out / (a.name + "_critical.csv"), h5, out / (a.name + ".json")};
  for (const auto& f : io::fs::directory_iterator(out))  // the plot's figures (one or several PNGs)
    if (f.path().extension() == ".png") files.push_back(f.path());
  print_written(files, since);
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<CurvesArgs>();
  CLI::App* c = app.add_subcommand("pattern-curves",
                                   "Spectrum and feasibility quantities of a word's period matrix against r (Figures 7.1-7.8)");
  a->q.fields([c](const char* name, auto& member, const char* help) {
    c->add_option(std::string("--") + name, member, help)->capture_default_str();
  });
  c->add_option("--threads", a->threads, "OpenMP threads (results do not depend on it)");
  c->add_option("--out", a->out, "output directory")->capture_default_str();
  c->add_option("--name", a->name, "file stem of the outputs")->capture_default_str();
  c->add_option("--title", a->title, "figure title prefix");
  c->add_flag("--no-plot", a->no_plot, "write data only");
  c->callback([a, c] { curves(*a, command_line_of(c)); });
});

}  // namespace
}  // namespace btob::cli
