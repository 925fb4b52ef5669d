// SPDX-License-Identifier: GPL-3.0-or-later
// The plain kernel on Figure 4.1's workload (bm_iterate's batched/double), registered again in the programs whose
// workloads are quoted against it (the speed ratios: the cocycle, the covariant vectors, the classification).
// analyses/benchmarks.sh runs those programs with five repetitions in random interleaving, so a workload and this
// reference are measured in the same minutes: on a shared machine whose speed can move by 2x between two programs
// of one run, a ratio of rates from different programs measures the machine as much as the code.
// analyses/benchmark_ratios.py divides each workload's best (and median) repetition by this reference's, from the same
// program.
#pragma once

#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <benchmark/benchmark.h>

namespace btob::bench {

// Figure 4.1: r in [0.0717, 0.1717] x the 32-point grid of Section 4.  `r_count` values of r.  bm_iterate's workloads
// and this reference are built from it, so the ratios divide rates of the same workload.
inline iterate::Ensemble fig41(long r_count) {
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.0717, 0.1717, r_count);
  e.initial = iterate::paper_grid();
  e.grid_description = "paper";
  return e;
}

// Arguments: r values (the paper's grid of 32 points each), iterations, threads; items = map iterations.
inline void plain_reference(benchmark::State& st) {
  const iterate::Ensemble e = fig41(st.range(0));
  const long iters = st.range(1);
  iterate::RunOptions opt;
  opt.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    iterate::FinalRecorder rec(e.orbits(), iters);
    iterate::run<double>(e, iters, rec, opt);
    benchmark::DoNotOptimize(rec.out.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * iters);
}

}  // namespace btob::bench

// The same arguments as bm_iterate's batched/double: 1000 r x 32 points x 5000 steps, 1 and 2 threads.
#define BTOB_PLAIN_REFERENCE              \
  BENCHMARK(btob::bench::plain_reference) \
      ->Name("plain_reference")           \
      ->Args({1000, 5000, 1})             \
      ->Args({1000, 5000, 2})             \
      ->UseRealTime()                     \
      ->Unit(benchmark::kMillisecond)
