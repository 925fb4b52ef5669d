// SPDX-License-Identifier: GPL-3.0-or-later
// Individual orbits at fixed r in the strip (Figures 6.9-6.11): seeded initial points, tails, verdicts.
#include "orbits/orbits.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

namespace btob::orbits {
namespace {

std::uint64_t splitmix(std::uint64_t x) {  // SplitMix64 finaliser (Steele, Lea, Flood 2014)
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
double unit_open(std::uint64_t x) { return (static_cast<double>(x >> 11) + 0.5) * 0x1.0p-53; }  // (0, 1)

}  // namespace

void StripOrbitsRequest::validate() const {
  core::require_r(r, "r");
  if (orbits < 1 || orbits > 1000) throw core::InvalidField("orbits", fmt::format("{}", orbits), "1..1000");
  if (tail < 1) throw core::InvalidField("tail", fmt::format("{}", tail), "at least 1");
  if (iterations < tail || iterations > 10000000)
    throw core::InvalidField("iterations", fmt::format("{}", iterations), fmt::format("tail ({})..1e7", tail));
  if (static_cast<double>(orbits) * static_cast<double>(tail) > 1e8)
    throw core::InvalidField("tail", fmt::format("{}", tail), "orbits * tail <= 1e8 (memory)");
  if (w1_range.size() != 2)
    throw core::InvalidField("w1-range", fmt::format("{} numbers", w1_range.size()), "two numbers a,b");
  if (!(std::abs(w1_range[0]) <= 1e6 && std::abs(w1_range[1]) <= 1e6 && w1_range[0] < w1_range[1]))
    throw core::InvalidField("w1-range", fmt::format("[{}, {}]", w1_range[0], w1_range[1]), "a < b, |a|, |b| <= 1e6");
}

const char* panel_word(attractors::Type t) {
  switch (t) {
    case attractors::Type::periodic: return "periodic";
    case attractors::Type::quasi_periodic: return "quasi-periodic";
    case attractors::Type::chaotic: return "chaotic";
    case attractors::Type::collapse: return "collapse";
    default: return "undecided";
  }
}

StripOrbitsResult run(const StripOrbitsRequest& q, const core::RunControl& control) {
  q.validate();
  core::check_cancel(control.cancel);
  const auto t0 = std::chrono::steady_clock::now();
  StripOrbitsResult res;
  res.request = q;
  iterate::Ensemble ens;
  ens.r = {q.r};
  ens.seed = q.seed;
  ens.grid_description = fmt::format("random strip points: w1 uniform in [{}, {}], w2 uniform in (-1, 1), seed {}",
                                     q.w1_range[0], q.w1_range[1], q.seed);
  for (long i = 0; i < q.orbits; ++i) {
    const std::uint64_t base = splitmix(q.seed ^ splitmix(static_cast<std::uint64_t>(i)));
    const double w1 = q.w1_range[0] + (q.w1_range[1] - q.w1_range[0]) * unit_open(splitmix(base + 1));
    const double w2 = 2 * unit_open(splitmix(base + 2)) - 1;
    res.start_w1.push_back(w1);
    res.start_w2.push_back(w2);
    ens.initial.push_back(core::from_strip(w1, w2));
  }
  iterate::RunOptions ro;
  ro.threads = control.threads;
  ro.cancel = control.cancel;
  iterate::TailRecorder t1(iterate::Coord::w1, ens.orbits(), q.iterations, q.tail);
  iterate::TailRecorder t2(iterate::Coord::w2, ens.orbits(), q.iterations, q.tail);
  iterate::Both<iterate::TailRecorder, iterate::TailRecorder> both(t1, t2);
  iterate::run<double>(ens, q.iterations, both, ro);
  if (control.progress) control.progress->update(1, 2);
  core::check_cancel(control.cancel);
  res.w1 = std::move(t1.out);
  res.w2 = std::move(t2.out);
  // The verdicts: the classifier continues each orbit from its start with the same transient as the figure.
  attractors::Options opt;
  opt.transient = q.iterations;
  opt.run.threads = control.threads;
  opt.run.cancel = control.cancel;
  res.verdicts = attractors::classify(ens, opt);
  for (const auto& v : res.verdicts) {
    res.pattern.push_back(v.type == attractors::Type::periodic ? patterns::to_paper(patterns::canonical(v.word)) : "");
    res.verdict.emplace_back(panel_word(v.type));
    res.period.push_back(static_cast<std::uint32_t>(v.period));
    res.rotation.push_back(v.rotation);
    if (v.type == attractors::Type::periodic) ++res.periodic;
    else if (v.type == attractors::Type::quasi_periodic) ++res.quasi_periodic;
    else ++res.other;
  }
  if (control.progress) control.progress->update(2, 2);
  res.seconds = core::seconds_since(t0);
  return res;
}

std::string StripOrbitsResult::csv() const {
  core::CsvTable csv("orbit,start_w1,start_w2,verdict,pattern,period,lambda1,err1,rotation,residual,detail");
  for (std::size_t o = 0; o < verdicts.size(); ++o) {
    const auto& v = verdicts[o];
    const core::ValueWithError l = core::with_error(v.lambda1, v.err1);  // the printed interval contains lambda1
    csv.row({fmt::format("{}", o + 1), fmt::format("{:.17g}", start_w1[o]), fmt::format("{:.17g}", start_w2[o]),
             panel_word(v.type), pattern[o], fmt::format("{}", v.period), l.value, l.error,
             fmt::format("{:.12g}", v.rotation), fmt::format("{:.3g}", v.residual), v.detail});
  }
  return csv.text();
}

void StripOrbitsResult::describe(core::Contents& c) const {
  const std::size_t n = start_w1.size(), t = static_cast<std::size_t>(request.tail);
  c.array("w1", w1, {n, t}, "orbit, step (the last tail iterations)", "1", "strip coordinate w1 of eq. (6.4)");
  c.array("w2", w2, {n, t}, "orbit, step (the last tail iterations)", "1",
          "strip coordinate w2 of eq. (6.4), in (-1, 1)");
  c.array("start_w1", start_w1, {n}, "orbit", "1", "initial w1");
  c.array("start_w2", start_w2, {n}, "orbit", "1", "initial w2");
  // The classifier's verdict on each orbit (the panel titles; also NAME.csv).
  c.text("verdict", verdict, "orbit", "name",
         "the classifier's verdict: periodic, quasi-periodic, chaotic, collapse or undecided");
  c.text("pattern", pattern, "orbit", "name",
         "paper notation of the periodic word (canonical; empty when not periodic)");
  c.array("period", period, {n}, "orbit", "iterations", "period of a periodic verdict in map iterations (0 otherwise)");
  c.array("rotation", rotation, {n}, "orbit", "turns/iteration",
          "weighted Birkhoff rotation number about the P2 centre (quasi-periodic verdicts; 0 when not computed)");
  c.attr("r", request.r);
  c.attr("orbits", request.orbits);
  c.attr("iterations", request.iterations);
  c.attr("tail", request.tail);
  c.attr("seed", static_cast<long>(request.seed));
  c.attr("w1_min", request.w1_range[0]);
  c.attr("w1_max", request.w1_range[1]);
  c.attr("initial_conditions",
         fmt::format("random strip points: w1 uniform in [{}, {}], w2 uniform in (-1, 1), seed {}", request.w1_range[0],
                     request.w1_range[1], request.seed));
  c.attr("periodic", static_cast<long>(periodic));
  c.attr("quasi_periodic", static_cast<long>(quasi_periodic));
  c.attr("other", static_cast<long>(other));
  c.attr("iteration_seconds", seconds);
}

core::Work work(const StripOrbitsRequest& req) {
  const double orbits = static_cast<double>(req.orbits), tail = static_cast<double>(req.tail);
  core::Work w;
  core::Term t;
  t.route = "strip-orbits tails and classifier double";
  t.units = orbits * static_cast<double>(req.iterations);
  t.what = "map steps of the orbits (orbits x iterations), each orbit classified again from its start";
  t.probe = [](double n, const core::RunControl& c) {
    StripOrbitsRequest p;  // 10 orbits at r = 0.2
    p.iterations = std::max(static_cast<long>(n / 10), 2L);
    p.tail = 1;
    (void)run(p, c);
    return 10.0 * static_cast<double>(p.iterations);
  };
  w.terms.push_back(std::move(t));
  w.bound = "the classifier decides a periodic orbit or a collapse without its second pass";
  // The tails w1, w2 [orbits x tail] in NAME.h5 (8 bytes each) and NAME.csv (~20 bytes a number); the run keeps them.
  w.output_bytes = orbits * tail * 2 * (8 + 20) + 200 * orbits;
  w.peak_bytes = orbits * tail * 2 * 8 * 2 + 65536;
  return w;
}

}  // namespace btob::orbits
