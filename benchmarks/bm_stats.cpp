// C_N by FFT (FFTW) against the direct sum: N = 1e6, n_max = 1e5.  The direct sum costs N * n_max = 1e11
// multiply-adds; it is measured at n_max = 1e3 and scales linearly in n_max (items = N * (n_max + 1)).
#include "stats/stats.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace {
std::vector<double> series(long n) {
  std::mt19937_64 g(1);
  std::normal_distribution<double> d;
  std::vector<double> x(static_cast<std::size_t>(n));
  for (auto& v : x) v = d(g);
  return x;
}

void BM_fft(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  const auto x = series(N + n_max);
  btob::stats::Correlator c;
  for (auto _ : st) benchmark::DoNotOptimize(c.correlation(x, x, N, n_max).data());
  st.SetItemsProcessed(st.iterations() * N * (n_max + 1));  // lag-products computed, to compare with direct
}
void BM_direct(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  const auto x = series(N + n_max);
  for (auto _ : st) benchmark::DoNotOptimize(btob::stats::correlation_direct(x, x, N, n_max).data());
  st.SetItemsProcessed(st.iterations() * N * (n_max + 1));
}
}  // namespace

BENCHMARK(BM_fft)->Name("correlation_fft")->Args({1000000, 100000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_direct)->Name("correlation_direct")->Args({1000000, 1000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fft)->Name("smoke/correlation_fft")->Args({1000, 100});
BENCHMARK(BM_direct)->Name("smoke/correlation_direct")->Args({1000, 100});

BENCHMARK_MAIN();
