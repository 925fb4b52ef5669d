// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the basin classification in grid points per second (items) at r = 0.2 (periodic sink and
// P2 curves) and r = 0.102 (chaotic: every point goes through pass 2), 1 and 2 threads; the scalar
// reference of pass 1 (one orbit at a time, Appendix A.2 normalisation) as the baseline; pass 2's two routes.
#include "attractors/attractors.hpp"
#include "attractors/recorders.hpp"
#include "iterate/kernel.hpp"
#include "lyapunov/maps.hpp"
#include "lyapunov/tangent.hpp"

#include <benchmark/benchmark.h>

#include "plain_reference.hpp"

namespace {

using namespace btob;

// Basins over an n x n strip grid (range 3: replicate grids); items = grid points of all grids.
void BM_basins(benchmark::State& st) {
  const int replicates = static_cast<int>(st.range(3));
  const double r = static_cast<double>(st.range(0)) / 1000;
  const attractors::Grid g =
      attractors::parse_grid("strip:" + std::to_string(st.range(1)) + "x" + std::to_string(st.range(1)), -2, 2);
  attractors::Options o;
  o.run.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    auto b = attractors::basins(r, g, replicates, 1, o);
    benchmark::DoNotOptimize(b.labels.data());
    st.counters["certified"] =
        static_cast<double>(b.certified) / static_cast<double>(g.axis1.cells * g.axis2.cells * (replicates + 1));
    st.counters["map_iterations"] = static_cast<double>(b.iterations_total);
  }
  st.SetItemsProcessed(st.iterations() * g.axis1.cells * g.axis2.cells * (replicates + 1));
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

// Pass 2 alone with every orbit taking the rotation (the orbits pass 1 leaves without a period): lambda1 from the fused
// cocycle kernel and a plain run with the rotation recorder (Fused: run_pass's two runs, its bound when every orbit's
// lambda1 is zero), or both recorders on one plain run (the per-step route before, kept for r below the fused
// kernel's range).  r = 0.102 (chaotic: the invariant I, no rotation) and r = 0.3 (I and the
// rotation's angle every step); items = map iterations (lyap_transient + lyap_iterations).
template <bool Fused> void BM_pass2(benchmark::State& st) {
  iterate::Ensemble e;
  e.r = {static_cast<double>(st.range(0)) / 1000};
  e.initial = attractors::grid_points(attractors::parse_grid("strip:" + std::to_string(st.range(1)) + "x16", -2, 2));
  const attractors::Options o;
  iterate::RunOptions run;
  run.threads = static_cast<int>(st.range(2));
  const long steps = o.lyap_transient + o.lyap_iterations;
  for (auto _ : st) {
    attractors::RotationRecorder rot(e.orbits(), e.r[0], o.lyap_transient, o.lyap_iterations);
    if constexpr (Fused) {
      lyapunov::MapOptions mo;
      mo.transient = o.lyap_transient, mo.iterations = o.lyap_iterations, mo.blocks = o.lyap_blocks, mo.run = run;
      benchmark::DoNotOptimize(lyapunov::map_exponents(e, mo).lambda1.data());
      iterate::run<double>(e, steps, rot, run);
    } else {
      lyapunov::TangentRecorder tan(e, o.lyap_transient, o.lyap_iterations, o.lyap_blocks);
      iterate::Both<lyapunov::TangentRecorder, attractors::RotationRecorder> both(tan, rot);
      iterate::run<double>(e, steps, both, run);
      benchmark::DoNotOptimize(tan.cum.data());
    }
    benchmark::DoNotOptimize(rot.i_mean.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * steps);
}

// The whole classification of 1024 orbits (pass 1, pass 2 and any refinement), r = 0.102 (chaotic: pass 2 is the
// cocycle kernel alone) and r = 0.3 (periodic and P2 curves: the curves' orbits also take the rotation run); items =
// the map iterations spent (the verdicts' sum), to set against the plain kernel's.
void BM_classify(benchmark::State& st) {
  iterate::Ensemble e;
  e.r = {static_cast<double>(st.range(0)) / 1000};
  e.initial = attractors::grid_points(attractors::parse_grid("strip:64x16", -2, 2));
  attractors::Options o;
  o.run.threads = static_cast<int>(st.range(1));
  long steps = 0;
  for (auto _ : st) {
    const auto v = attractors::classify(e, o);
    steps = 0;
    for (const auto& x : v) steps += x.iterations;
    benchmark::DoNotOptimize(v.data());
  }
  st.SetItemsProcessed(st.iterations() * steps);
}

BENCHMARK(BM_basins)->Name("smoke_basins")->Args({200, 8, 1, 0})->UseRealTime();
BENCHMARK(BM_pass1<false>)->Name("smoke_pass1_batched")->Args({2})->UseRealTime();
BENCHMARK(BM_basins)
    ->Name("basins")
    ->Args({200, 300, 1, 0})
    ->Args({200, 300, 2, 0})
    ->Args({102, 100, 1, 0})
    ->Args({102, 100, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
// The basins' speed workload: btob basins --r 0.2 --grid strip:1000x1000 (two replicates), 2 threads; and a ninth of
// it.
BENCHMARK(BM_basins)
    ->Name("basins_replicates")
    ->Args({200, 333, 2, 2})
    ->Args({200, 1000, 2, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BTOB_PLAIN_REFERENCE;
BENCHMARK(BM_classify)
    ->Name("classify")
    ->ArgsProduct({{102, 300}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pass2<true>)
    ->Name("pass2_fused")
    ->ArgsProduct({{102, 300}, {64}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pass2<false>)
    ->Name("pass2_recorder")
    ->ArgsProduct({{102, 300}, {64}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pass1<true>)->Name("pass1_scalar")->Args({4})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pass1<false>)->Name("pass1_batched")->Args({64})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
