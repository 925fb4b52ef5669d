// SPDX-License-Identifier: GPL-3.0-or-later
// Individual orbits at fixed r in the strip (Figures 6.9-6.11): seeded initial points, tails, verdicts; and the
// run's cost.
#include "orbits/orbits.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/run.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
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
