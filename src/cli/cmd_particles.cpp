// `btob particles WORD --r R`: four particles realise the periodic pattern WORD, event by event (issue 19).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/csv.hpp"
#include "io/io.hpp"
#include "particles/particles.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace btob::cli {
namespace {

struct ParticlesArgs {
  particles::ParticlesRequest req;
  std::string out;
  bool header = false, no_plot = false;
};

const char* csv_header() { return "word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse"; }

std::string csv_row(const particles::ParticlesResult& s) {
  return fmt::format("{},{},{},{},{},{:.15g},{:.15g},{:.15g}", core::csv_text(s.word), s.r, s.periods, s.letters,
                     s.sequence_ok ? "true" : "false", s.length_contraction, s.length_predicted, s.time_to_collapse);
}

void particles_cmd(const ParticlesArgs& a, const std::string& command_line) {
  a.req.validate();  // before anything is written
  if (a.out.empty()) throw UsageError("out: got nothing, expected an output directory");
  const particles::ParticlesResult s = particles::run(a.req);
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto since = start_time();  // for the list of files written
  if (a.header) std::cout << csv_header() << "\n";
  std::cout << csv_row(s) << std::endl;

  core::CsvTable t(std::string(csv_header()) +
                   ",digits,outcome,periods_ok,velocity_contraction,velocity_predicted,time_contraction,time_predicted,"
                   "length_spread,energy_ratio,collisions_unrescaled,collisions_limit_predicted,failure");
  t.line(csv_row(s) + fmt::format(",{},{},{},{:.15g},{:.15g},{:.15g},{:.15g},{:.3g},{:.15g},{},{:.1f},{}", s.digits,
                                  core::csv_text(s.outcome), s.periods_ok, s.velocity_contraction, s.velocity_predicted,
                                  s.time_contraction, s.time_predicted, s.length_spread, s.energy_ratio,
                                  s.collisions_unrescaled, s.collisions_limit_predicted, core::csv_text(s.failure)));
  io::write_text_atomic(out / "particles.csv", t.text());
  // Convergence: every period up to 100, then about 20 per decade.
  core::CsvTable c("period,length_ratio,velocity_ratio,time_ratio");
  long next = 1;
  for (std::size_t n = 0; n < s.length_ratio.size(); ++n) {
    const long k = static_cast<long>(n) + 1;
    if (k < 100 || k >= next || n + 1 == s.length_ratio.size()) {
      c.line(fmt::format("{},{:.17g},{:.17g},{:.17g}", k, s.length_ratio[n], s.velocity_ratio[n], s.time_ratio[n]));
      if (k >= 100) next = static_cast<long>(std::ceil(k * std::pow(10.0, 0.05)));
    }
  }
  io::write_text_atomic(out / "convergence.csv", c.text());
  core::CsvTable e("period,time,time_to_collapse,x1,x2,x3,x4,letter");
  for (std::size_t i = 0; i + 8 <= s.events.size(); i += 8) {
    const int l = static_cast<int>(s.events[i + 7]);
    e.line(fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}", static_cast<long>(s.events[i]), s.events[i + 1],
                     s.events[i + 2], s.events[i + 3], s.events[i + 4], s.events[i + 5], s.events[i + 6],
                     l == 0 ? "start" : std::string(1, char('a' + l - 1))));
  }
  io::write_text_atomic(out / "events.csv", e.text());
  // JSON has no NaN or infinity: such values are recorded as the strings "nan", "inf".
  const auto num = [](double v) -> io::Attr {
    if (std::isfinite(v)) return v;
    return std::string(std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
  };
  io::Attrs at = io::provenance(command_line);
  at["kind"] = std::string("particles");
  at["word"] = s.word;
  at["digits"] = s.digits;
  at["letters"] = s.letters;
  at["outcome"] = s.outcome;
  at["r"] = s.r;
  at["periods"] = s.periods;
  at["periods_ok"] = s.periods_ok;
  at["scalar_type"] = s.precision;
  at["start"] = a.req.start;
  at["sequence_ok"] = std::string(s.sequence_ok ? "true" : "false");
  at["length_contraction"] = num(s.length_contraction);
  at["length_predicted"] = num(s.length_predicted);
  at["velocity_contraction"] = num(s.velocity_contraction);
  at["velocity_predicted"] = num(s.velocity_predicted);
  at["time_contraction"] = num(s.time_contraction);
  at["time_predicted"] = num(s.time_predicted);
  at["time_to_collapse"] = num(s.time_to_collapse);
  at["time_unit"] = std::string("|p0|/|q0| (unit gaps and unit relative velocities at the start)");
  at["collisions_unrescaled"] = s.collisions_unrescaled;
  at["unrescaled_end"] = s.unrescaled_end;
  at["collisions_limit_predicted"] = num(s.collisions_limit_predicted);
  at["failure"] = s.failure;
  at["seconds"] = s.seconds;
  io::write_manifest(out / "particles.json", at);
  std::cerr << fmt::format("btob: {} at r = {}: {} of {} periods reproduced ({} collisions per period); lengths x{:.12g} "
                           "per period (predicted {:.12g}), velocities x{:.12g} ({:.12g}), times x{:.12g} ({:.12g}); "
                           "collapse after {:.12g} |p0|/|q0|; without rescaling {} collisions ({}; predicted {:.0f}) "
                           "({:.2f} s)\n",
                           s.word, s.r, s.periods_ok, s.periods, s.letters.size(), s.length_contraction, s.length_predicted,
                           s.velocity_contraction, s.velocity_predicted, s.time_contraction, s.time_predicted,
                           s.time_to_collapse, s.collisions_unrescaled, s.unrescaled_end, s.collisions_limit_predicted,
                           s.seconds);
  if (!s.failure.empty()) std::cerr << "btob: warning: " << s.failure << "\n";
  if (!a.no_plot) io::run_plot("particles.py", {out.string()});
  print_written({out / "particles.csv", out / "convergence.csv", out / "events.csv", out / "particles.json",
                 out / "spacetime.png", out / "animation.gif"},
                since);
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<ParticlesArgs>();
  CLI::App* c = app.add_subcommand(
      "particles",
      "Four particles realise the periodic pattern WORD: event-driven collapse, letters and contraction per period "
      "against the period matrix; prints word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse");
  a->req.fields([&](const char* name, auto& member, const char* help) {
    if (std::string(name) == "word") c->add_option("word", member, help)->required();
    else c->add_option(std::string("--") + name, member, help)->capture_default_str();
  });
  c->add_option("--out", a->out, "output directory (CSV, manifest, space-time diagram, animation)")->required();
  c->add_flag("--header", a->header, "print the CSV header line first");
  c->add_flag("--no-plot", a->no_plot, "write data only");
  c->callback([a, c] { particles_cmd(*a, command_line_of(c)); });
});

}  // namespace
}  // namespace btob::cli
