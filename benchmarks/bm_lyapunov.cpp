// Throughput of the Lyapunov exponents in map iterations per second: the scalar QR route (Eigen, one orbit,
// the baseline) against the TangentRecorder on the batched SIMD kernel, 1 and 2 threads.
#include "iterate/kernel.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace btob;

// The workload: r in [0.0717, 0.6] x the 32-point grid of Section 4.
iterate::Ensemble workload(long r_count) {
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.0717, 0.6, r_count);
  e.initial = iterate::paper_grid();
  e.grid_description = "paper";
  return e;
}

// Scalar baseline: projective QR route (two tangent vectors, Gram-Schmidt every step) on one orbit.
void BM_qr_route(benchmark::State& st) {
  const long n = st.range(0);
  lyapunov::Options o;
  o.transient = n / 10;
  o.iterations = n;
  o.blocks = 10;
  for (auto _ : st) {
    auto res = lyapunov::projective_exponents<double>(Eigen::Vector3d(1, -0.9, -0.2), 0.3, o);
    benchmark::DoNotOptimize(res.lambda[0].value);
  }
  st.SetItemsProcessed(st.iterations() * (o.transient + o.iterations));
}

// The batched map: r_count values x 32 orbits, transient n/10 + n steps each, `threads` threads.
template <bool Float> void BM_map(benchmark::State& st) {
  const iterate::Ensemble e = workload(st.range(0));
  lyapunov::MapOptions o;
  o.iterations = st.range(1);
  o.transient = o.iterations / 10;
  o.single_precision = Float;
  o.run.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    auto m = lyapunov::map_exponents(e, o);
    benchmark::DoNotOptimize(m.lambda1.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * (o.transient + o.iterations));
}

BENCHMARK(BM_qr_route)->Name("smoke_qr_route")->Arg(2000);
BENCHMARK(BM_map<false>)->Name("smoke_map_double")->Args({4, 500, 1})->UseRealTime();
BENCHMARK(BM_qr_route)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_map<false>)->Name("map_double")->Args({500, 10000, 1})->Args({500, 10000, 2})->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_map<true>)->Name("map_float")->Args({500, 10000, 1})->Args({500, 10000, 2})->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
