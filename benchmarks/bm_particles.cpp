// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the particle check (collisions per second, items) in double, long double, float128 and MPFR-50, and
// of the feasible atlas's inner loop (patterns::classify, evaluations per second) for words of length 8 and 14.
#include "core/scalar.hpp"
#include "particles/particles.hpp"
#include "patterns/patterns.hpp"

#include <benchmark/benchmark.h>
#include <boost/multiprecision/eigen.hpp>

namespace {

using namespace btob;

// 1133 at r = 0.15 from its self-similar start, rescaled every period; items = collisions.
template <class T> void BM_simulate(benchmark::State& st) {
  if constexpr (std::is_same_v<T, core::mpfr_float>) core::mpfr_float::default_precision(50);
  const T r = T(15) / 100;
  const auto v = patterns::analyse<T>(patterns::parse_word("1133"), r);
  particles::Gaps<T, 3> g;
  particles::self_similar_start<T>(v.orbit.front(), v.letters, r, g);
  const long periods = st.range(0);
  for (auto _ : st) {
    auto run = particles::simulate_pattern<T>(g, v.letters, r, periods, true);
    benchmark::DoNotOptimize(run.length_ratio.data());
  }
  st.SetItemsProcessed(st.iterations() * periods * static_cast<long>(v.letters.size()));
}

// classify (spectrum, eigenvectors, feasibility) at 64 values of r; items = evaluations.
void BM_classify(benchmark::State& st) {
  const auto w = patterns::parse_word(st.range(0) == 8 ? "13223122" : "11113333111333");
  for (auto _ : st)
    for (int i = 0; i < 64; ++i) benchmark::DoNotOptimize(patterns::classify<double>(w, 0.05 + 0.01 * i));
  st.SetItemsProcessed(st.iterations() * 64);
}

}  // namespace

BENCHMARK(BM_simulate<double>)->Name("simulate_double")->Arg(10000);
BENCHMARK(BM_simulate<long double>)->Name("simulate_long_double")->Arg(10000);
BENCHMARK(BM_simulate<core::float128>)->Name("simulate_float128")->Arg(1000);
BENCHMARK(BM_simulate<core::mpfr_float>)->Name("simulate_mpfr50")->Arg(1000);
BENCHMARK(BM_classify)->Name("classify")->Arg(8)->Arg(14);
BENCHMARK(BM_simulate<double>)->Name("smoke_simulate")->Arg(10);
BENCHMARK(BM_classify)->Name("smoke_classify")->Arg(8);
BENCHMARK_MAIN();
