// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the Lyapunov exponents in map iterations per second: the scalar QR route (Eigen, one orbit,
// the baseline), the TangentRecorder on the plain batched kernel, and the fused cocycle kernel (map_exponents),
// double and float, 1 and 2 threads; and the covariant Lyapunov vectors, scalar and batched.
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"
#include "lyapunov/orbit.hpp"
#include "lyapunov/tangent.hpp"

#include <benchmark/benchmark.h>

#include "plain_reference.hpp"

#include <type_traits>

namespace {

using namespace btob;

// The speed goal's workload: r in [0.0717, 0.6] x the 32-point grid of Section 4.
iterate::Ensemble workload(long r_count) {
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.0717, 0.6, r_count);
  e.initial = iterate::paper_grid();
  e.grid_description = "paper";
  return e;
}

// Scalar baseline: projective QR route (two tangent vectors, Gram-Schmidt every step) on one orbit, in every
// precision of the lab; the MPFR digits are the benchmark's second argument.  Orbit = true: the one-orbit route that
// `btob lyapunov` runs (projective_orbit: the kernel's step, Gram-Schmidt every few steps), the same workload.
template <class T, bool Orbit = false> void BM_qr_route(benchmark::State& st) {
  if constexpr (std::is_same_v<T, core::mpfr_float>)
    core::mpfr_float::default_precision(static_cast<unsigned>(st.range(1)));
  const long n = st.range(0);
  lyapunov::Options o;
  o.transient = n / 10;
  o.iterations = n;
  o.blocks = 10;
  const Eigen::Matrix<T, 3, 1> u0(T(1), T(-0.9), T(-0.2));
  for (auto _ : st) {
    auto res =
        Orbit ? lyapunov::projective_orbit<T>(u0, T(0.3), o) : lyapunov::projective_exponents_qr<T>(u0, T(0.3), o);
    benchmark::DoNotOptimize(res.lambda[0].value);
  }
  st.SetItemsProcessed(st.iterations() * (o.transient + o.iterations));
}

// The orbit: r = 0.12 from (1, -0.5, -1.1), chaotic (lambda1 = 0.58: the symbols are unpredictable, so a
// branchy step would pay a mispredicted jump on about every other step), one orbit by the route `btob lyapunov` runs.
// Arguments: steps, MPFR digits, weighted: 1 = n/10 transient + n averaged steps (the weighted averages read every
// averaged step's state, weighted.hpp), 0 = n transient steps + 2 averaged (the step and the Gram-Schmidt alone).
template <class T> void BM_orbit_chaotic(benchmark::State& st) {
  if constexpr (std::is_same_v<T, core::mpfr_float>)
    core::mpfr_float::default_precision(static_cast<unsigned>(st.range(1)));
  const long n = st.range(0);
  lyapunov::Options o;
  o.blocks = 2;
  o.transient = st.range(2) ? n / 10 : n;
  o.iterations = st.range(2) ? n : 2;
  const Eigen::Matrix<T, 3, 1> u0(T(1), T(-0.5), T(-1.1));
  const T r = core::from_decimal<T>("0.12");
  for (auto _ : st) {
    auto res = lyapunov::projective_exponents<T>(u0, r, o);
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

// The route before the fused cocycle kernel: the plain kernel with the TangentRecorder (its 13 per-orbit arrays
// loaded and stored every step; still the classification's recorder), the same workload.
void BM_map_recorder(benchmark::State& st) {
  const iterate::Ensemble e = workload(st.range(0));
  const long n = st.range(1);
  iterate::RunOptions run;
  run.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    lyapunov::TangentRecorder rec(e, n / 10, n, 10);
    iterate::run<double>(e, rec.total_steps(), rec, run);
    auto m = lyapunov::exponents_from(rec);
    benchmark::DoNotOptimize(m.lambda1.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * (n / 10 + n));
}

// Covariant Lyapunov vectors of `hyperbolicity-orbits`: r_count values x the 32-point grid, 10000 transient +
// 10000 window + 10000 backward steps each (the command's defaults), `threads` threads.  clv_scalar is the route
// before the batched one (covariant_vectors per orbit, OpenMP over the orbits); clv_batched the batched route with
// everything clv_row reads (per-orbit and pooled angle statistics, histograms, exponents, expanding fractions).
lyapunov::ClvOptions clv_workload() {
  lyapunov::ClvOptions o;
  o.transient = o.window = o.backward_transient = 10000;
  return o;
}
void BM_clv_scalar(benchmark::State& st) {
  const iterate::Ensemble e = workload(st.range(0));
  const lyapunov::ClvOptions o = clv_workload();
  const long n = static_cast<long>(e.orbits());
  for (auto _ : st) {
    std::vector<double> med(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) num_threads(static_cast <int>(st.range(1)))
    for (long i = 0; i < n; ++i) {
      const std::size_t o_ = static_cast<std::size_t>(i);
      med[o_] = lyapunov::covariant_vectors<double>(e.initial[o_ % e.initial.size()], e.r[o_ / e.initial.size()], o)
                    .median_angle;
    }
    benchmark::DoNotOptimize(med.data());
  }
  st.SetItemsProcessed(st.iterations() * n * (o.transient + o.window + o.backward_transient));
}
void BM_clv_batched(benchmark::State& st) {
  const iterate::Ensemble e = workload(st.range(0));
  const lyapunov::ClvOptions o = clv_workload();
  iterate::RunOptions run;
  run.threads = static_cast<int>(st.range(1));
  for (auto _ : st) {
    auto rows = lyapunov::covariant_vectors_batched(e.r, e.initial, o, run);
    benchmark::DoNotOptimize(rows.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) *
                       (o.transient + o.window + o.backward_transient));
}

BENCHMARK(BM_qr_route<double>)->Name("smoke_qr_route")->Args({2000, 0});
BENCHMARK(BM_map<false>)->Name("smoke_map_double")->Args({4, 500, 1})->UseRealTime();
BENCHMARK(BM_qr_route<float>)->Name("qr_route/float")->Args({1000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<double>)->Name("qr_route/double")->Args({1000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<long double>)->Name("qr_route/long-double")->Args({200000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<core::float128>)->Name("qr_route/float128")->Args({20000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<core::mpfr_float>)
    ->Name("qr_route/mpfr")
    ->Args({5000, 50})
    ->Args({5000, 100})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<double, true>)->Name("smoke_orbit")->Args({2000, 0});
BENCHMARK(BM_qr_route<float, true>)->Name("orbit/float")->Args({10000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<double, true>)->Name("orbit/double")->Args({10000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<long double, true>)->Name("orbit/long-double")->Args({1000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<core::float128, true>)->Name("orbit/float128")->Args({200000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_qr_route<core::mpfr_float, true>)
    ->Name("orbit/mpfr")
    ->Args({100000, 50})
    ->Args({100000, 100})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_orbit_chaotic<float>)
    ->Name("orbit_chaotic/float")
    ->Args({10000000, 0, 1})
    ->Args({10000000, 0, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_orbit_chaotic<double>)
    ->Name("orbit_chaotic/double")
    ->Args({10000000, 0, 1})
    ->Args({10000000, 0, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_orbit_chaotic<long double>)
    ->Name("orbit_chaotic/long-double")
    ->Args({2000000, 0, 1})
    ->Args({2000000, 0, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_orbit_chaotic<core::float128>)
    ->Name("orbit_chaotic/float128")
    ->Args({200000, 0, 1})
    ->Args({200000, 0, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_orbit_chaotic<core::mpfr_float>)
    ->Name("orbit_chaotic/mpfr")
    ->Args({200000, 50, 1})
    ->Args({200000, 50, 0})
    ->Unit(benchmark::kMillisecond);
BTOB_PLAIN_REFERENCE;
BENCHMARK(BM_map<false>)
    ->Name("map_double")
    ->Args({500, 10000, 1})
    ->Args({500, 10000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_map<true>)
    ->Name("map_float")
    ->Args({500, 10000, 1})
    ->Args({500, 10000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_clv_scalar)->Name("clv_scalar")->Args({4, 1})->Args({4, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_clv_batched)
    ->Name("clv_batched")
    ->Args({20, 1})
    ->Args({20, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_map_recorder)
    ->Name("map_recorder/double")
    ->Args({500, 10000, 1})
    ->Args({500, 10000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
