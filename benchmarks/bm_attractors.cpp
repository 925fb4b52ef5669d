// Throughput of the basin classification in grid points per second (items) at r = 0.2 (periodic sink and
// P2 curves) and r = 0.102 (chaotic: every point goes through pass 2), 1 and 2 threads; the scalar
// reference of pass 1 (one orbit at a time, Appendix A.2 normalisation) as the baseline.
#include "attractors/attractors.hpp"
#include "attractors/recorders.hpp"
#include "iterate/kernel.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace btob;

// Basins over an n x n strip grid (range 3: replicate grids); items = grid points of all grids.
void BM_basins(benchmark::State& st) {
  const int replicates = static_cast<int>(st.range(3));
  const double r = static_cast<double>(st.range(0)) / 1000;
  const attractors::Grid g = attractors::parse_grid("strip:" + std::to_string(st.range(1)) + "x" +
                                                        std::to_string(st.range(1)), -2, 2);
  attractors::Options o;
  o.run.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    auto b = attractors::basins(r, g, replicates, 1, o);
    benchmark::DoNotOptimize(b.labels.data());
    st.counters["certified"] = static_cast<double>(b.certified) / static_cast<double>(g.n1 * g.n2 * (replicates + 1));
    st.counters["map_iterations"] = static_cast<double>(b.iterations_total);
  }
  st.SetItemsProcessed(st.iterations() * g.n1 * g.n2 * (replicates + 1));
}

// Pass 1 alone, batched vs scalar: items = map iterations.
template <bool Scalar> void BM_pass1(benchmark::State& st) {
  iterate::Ensemble e;
  e.r = {0.2};
  const attractors::Grid g = attractors::parse_grid("strip:" + std::to_string(st.range(0)) + "x16", -2, 2);
  e.initial = attractors::grid_points(g);
  const attractors::Options o;
  iterate::RunOptions run;
  run.threads = 1;
  for (auto _ : st) {
    attractors::ReturnRecorder rec(e.orbits(), o.transient, o.window, o.max_period, o.return_tol);
    if constexpr (Scalar) iterate::run_scalar<double>(e, rec.total_steps(), rec);
    else iterate::run<double>(e, rec.total_steps(), rec, run);
    benchmark::DoNotOptimize(rec.period.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * (o.transient + o.window));
}

BENCHMARK(BM_basins)->Name("smoke_basins")->Args({200, 8, 1, 0})->UseRealTime();
BENCHMARK(BM_pass1<false>)->Name("smoke_pass1_batched")->Args({2})->UseRealTime();
BENCHMARK(BM_basins)->Name("basins")->Args({200, 300, 1, 0})->Args({200, 300, 2, 0})->Args({102, 100, 1, 0})
    ->Args({102, 100, 2, 0})->UseRealTime()->Unit(benchmark::kMillisecond);
// Issue 17's workload: btob basins --r 0.2 --grid strip:1000x1000 (two replicates), 2 threads; and a ninth of it.
BENCHMARK(BM_basins)->Name("basins_replicates")->Args({200, 333, 2, 2})->Args({200, 1000, 2, 2})->UseRealTime()
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_pass1<true>)->Name("pass1_scalar")->Args({4})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pass1<false>)->Name("pass1_batched")->Args({64})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
