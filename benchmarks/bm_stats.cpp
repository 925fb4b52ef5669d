// SPDX-License-Identifier: GPL-3.0-or-later
// C_N(phi, psi; n) by FFT (FFTW) against the direct sum, templated on T; items = lag-products N (n_max + 1).
// The direct sum costs N (n_max + 1) multiply-adds: at N = 1e6, n_max = 1e5 that is 1e11; it is measured
// at n_max = 1e3 and 1e4 (linear in n_max) and run once (Iterations(1), ~10 s on 2 cores) at the full size;
// the FFT route is measured at the full size.  A scalar baseline (one accumulator, no blocking, no threads) sits beside
// the direct sum. BM_orbit_correlation is the whole user path: iterate 1.1e6 states, observe phi, C_N over 1e6 points.
#include "stats/stats.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace {
template <class T> std::vector<T> series(long n) {
  std::mt19937_64 g(1);
  std::normal_distribution<double> d;
  std::vector<T> x(static_cast<std::size_t>(n));
  for (auto& v : x) v = static_cast<T>(d(g));
  return x;
}

template <class T> void BM_fft(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  const auto x = series<T>(N + n_max);
  btob::stats::Correlator<T> c(N, n_max);  // planning outside the loop: plans are reused across orbits
  for (auto _ : st) benchmark::DoNotOptimize(c(x, x).data());
  st.SetItemsProcessed(st.iterations() * N * (n_max + 1));
  st.counters["fft_length"] = static_cast<double>(c.fft_length());
}
template <class T> void BM_direct(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  const auto x = series<T>(N + n_max);
  for (auto _ : st) benchmark::DoNotOptimize(btob::stats::correlation_direct(x, x, N, n_max).data());
  st.SetItemsProcessed(st.iterations() * N * (n_max + 1));
}
// The textbook double loop: the baseline of the blocked, threaded direct sum.
template <class T> void BM_direct_scalar(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  const auto x = series<T>(N + n_max);
  for (auto _ : st) {
    std::vector<T> c(static_cast<std::size_t>(n_max + 1));
    T m = 0;
    for (long k = 0; k < N; ++k) m += x[k];
    m /= static_cast<T>(N);
    for (long n = 0; n <= n_max; ++n) {
      T s = 0;
      for (long k = 0; k < N; ++k) s += x[k] * x[k + n];
      c[n] = s / static_cast<T>(N) - m * m;
    }
    benchmark::DoNotOptimize(c.data());
  }
  st.SetItemsProcessed(st.iterations() * N * (n_max + 1));
}
void BM_orbit_correlation(benchmark::State& st) {
  const long N = st.range(0), n_max = st.range(1);
  btob::stats::Correlator<double> c(N, n_max);
  for (auto _ : st) {
    const auto s = btob::stats::orbit_series(0.11, {1, -3, -1.1}, 1000, N + n_max);
    const auto x = btob::stats::observe(s, btob::stats::Observable::phi);
    benchmark::DoNotOptimize(c(x, x).data());
  }
  st.SetItemsProcessed(st.iterations() * (1000 + N + n_max));  // map iterations
}
}  // namespace

BENCHMARK(BM_fft<double>)
    ->Name("correlation_fft<double>")
    ->Args({1000000, 100000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_fft<float>)
    ->Name("correlation_fft<float>")
    ->Args({1000000, 100000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_fft<long double>)
    ->Name("correlation_fft<long double>")
    ->Args({1000000, 100000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_direct<double>)
    ->Name("correlation_direct<double>")
    ->Args({1000000, 1000})
    ->Args({1000000, 10000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_direct<double>)
    ->Name("correlation_direct<double>")
    ->Args({1000000, 100000})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_direct_scalar<double>)
    ->Name("correlation_direct_scalar<double>")
    ->Args({1000000, 1000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_orbit_correlation)
    ->Name("orbit_correlation<double>")
    ->Args({1000000, 100000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_fft<double>)->Name("smoke/correlation_fft<double>")->Args({1000, 100});
BENCHMARK(BM_fft<float>)->Name("smoke/correlation_fft<float>")->Args({1000, 100});
BENCHMARK(BM_direct<double>)->Name("smoke/correlation_direct<double>")->Args({1000, 100});
BENCHMARK(BM_direct_scalar<double>)->Name("smoke/correlation_direct_scalar<double>")->Args({1000, 100});
BENCHMARK(BM_orbit_correlation)->Name("smoke/orbit_correlation<double>")->Args({1000, 100});

BENCHMARK_MAIN();
