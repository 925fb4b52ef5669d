// SPDX-License-Identifier: GPL-3.0-or-later
// Ulam's matrix of P^_r: samples (map evaluations) per second for the two routes (core::step per sample against
// one step of the batched SIMD kernel), 1 and 2 threads; and the whole `btob transfer` analysis at 512 x 512 boxes
// with 64 samples per box (the target: under 60 s on 2 cores).
#include "transfer/transfer.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace btob;

// Args: boxes per side, samples per box, threads, route (0 direct, 1 kernel); items = samples.
void BM_matrix(benchmark::State& st) {
  const long n = st.range(0);
  const int samples = static_cast<int>(st.range(1));
  core::RunControl c;
  c.threads = static_cast<int>(st.range(2));
  const char* route = st.range(3) ? "kernel" : "direct";
  const transfer::Partition p = transfer::domain_partition(transfer::Domain::strip, n, n);
  for (auto _ : st) {
    auto P = transfer::ulam_btob(0.2, transfer::Domain::strip, p, samples, route, c);
    benchmark::DoNotOptimize(P.val.data());
  }
  st.SetItemsProcessed(st.iterations() * n * n * samples);
  st.SetLabel(route);
}

// The whole analysis (matrix, decomposition, block spectra, projection; no empirical measure); items = samples.
void BM_analysis(benchmark::State& st) {
  transfer::TransferRequest q;
  q.r = static_cast<double>(st.range(0)) / 1000;
  q.boxes = std::to_string(st.range(1)) + "x" + std::to_string(st.range(1));
  q.samples = static_cast<int>(st.range(2));
  q.eigenvalues = 16;
  q.measure_orbits = 0;
  q.tv_bins = 16;
  core::RunControl c;
  c.threads = static_cast<int>(st.range(3));
  for (auto _ : st) {
    auto res = transfer::run(q, c);
    benchmark::DoNotOptimize(res.density.data());
  }
  st.SetItemsProcessed(st.iterations() * st.range(1) * st.range(1) * st.range(2));
}

BENCHMARK(BM_matrix)->Name("smoke_matrix")->Args({16, 4, 1, 0})->Args({16, 4, 1, 1})->UseRealTime();
BENCHMARK(BM_analysis)->Name("smoke_analysis")->Args({150, 16, 4, 1})->UseRealTime();
BENCHMARK(BM_matrix)
    ->Name("matrix")
    ->Args({512, 64, 1, 0})
    ->Args({512, 64, 1, 1})
    ->Args({512, 64, 2, 0})
    ->Args({512, 64, 2, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_analysis)
    ->Name("analysis")
    ->Args({150, 512, 64, 2})
    ->Args({210, 512, 64, 2})
    ->Args({300, 512, 64, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
