// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the single-orbit routes in map iterations per second (wall time), beside the plain
// batched kernel (plain_reference, in the same program: quote ratios of rates from one run).  The orbit is the issue's:
// r = 0.12 from (1, -0.5, -1.1), chaotic (lambda1 = 0.58), so the symbols are unpredictable.
//  * one/<precision>: iterate::run with one orbit and the final state only (`btob iterate` with record = final): the
//    kernel's batch of few_lanes<T>() lanes (one vector for float and double, one lane for the others).
//  * lane_of_batch/<precision>: the route before, one orbit as one lane of a full batch (48 doubles, 96 floats, 8 of
//    the other precisions): an ensemble of few_lanes<T>() + 1 copies of the orbit, items counted for one orbit.
//  * few/double: 2 and 8 orbits (one vector), items counted for all of them.
//  * fma_chain: the core's clock (4 cycles per dependent FMA), to turn the rates into cycles per step.
//  * series, classify, strip_orbits: the users' routes for one point (correlate's and measure's series, the
//    classification of one point as the explorer's click runs it, strip-orbits with one orbit).
#include "attractors/attractors.hpp"
#include "core/scalar.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "orbits/orbits.hpp"
#include "patterns/patterns.hpp"
#include "stats/stats.hpp"

#include <benchmark/benchmark.h>

#include "plain_reference.hpp"

#include <type_traits>

namespace {

using namespace btob;

const core::Vec3<double> kStart(1, -0.5, -1.1);

// Copies that make a full batch of the route before: more than one vector's lanes (8 doubles, 16 floats with AVX-512,
// fewer on the narrower instruction sets) and at most a full batch (6 vectors); 2 for the per-lane precisions.
template <class T> constexpr long lane_of_batch_copies() {
  if constexpr (std::is_same_v<T, float>) return 17;
  else if constexpr (std::is_same_v<T, double>) return 9;
  else return 2;
}

// Arguments: steps, copies of the orbit (1: the one-orbit route), MPFR digits.  Items: one orbit's steps times the
// counted orbits (all of them when `count_all`, else one).
template <class T, bool CountAll = false> void BM_iterate(benchmark::State& st) {
  core::MpfrDigits digits(static_cast<int>(st.range(2) ? st.range(2) : 50));
  const long n = st.range(0), copies = st.range(1);
  iterate::Ensemble e;
  e.set_r_list({core::Decimal::parse("0.12", "r")});
  e.initial.assign(static_cast<std::size_t>(copies), kStart);
  iterate::RunOptions opt;
  opt.threads = 1;
  for (auto _ : st) {
    iterate::FinalRecorder rec(e.orbits(), n);
    iterate::run<T>(e, n, rec, opt);
    benchmark::DoNotOptimize(rec.out.data());
  }
  st.SetItemsProcessed(st.iterations() * n * (CountAll ? copies : 1));
}

// correlate's and measure's series: the states and symbols of `steps` steps after 1000 transient ones.
void BM_series(benchmark::State& st) {
  const long n = st.range(0);
  for (auto _ : st) {
    const stats::OrbitSeries s = stats::orbit_series(0.12, kStart, 1000, n);
    benchmark::DoNotOptimize(s.x.data());
  }
  st.SetItemsProcessed(st.iterations() * (1000 + n));
}

// classify of one point with the defaults (5000 transient, the 1000-step window, the 4500-step Lyapunov pass).
void BM_classify(benchmark::State& st) {
  iterate::Ensemble e;
  e.r = {0.12};
  e.initial = {kStart};
  attractors::Options o;
  o.run.threads = 1;
  long steps = 0;
  for (auto _ : st) {
    const std::vector<attractors::OrbitVerdict> v = attractors::classify(e, o);
    steps = v[0].iterations;
    benchmark::DoNotOptimize(v.data());
  }
  st.SetItemsProcessed(st.iterations() * steps);
}

// strip-orbits with one orbit: `steps` iterations, the last 2000 kept, and its classification.
void BM_strip_orbits(benchmark::State& st) {
  orbits::StripOrbitsRequest q;
  q.r = 0.12;
  q.orbits = 1;
  q.iterations = st.range(0);
  for (auto _ : st) {
    const orbits::StripOrbitsResult res = orbits::run(q);
    benchmark::DoNotOptimize(res.w1.data());
  }
  st.SetItemsProcessed(st.iterations() * st.range(0));
}

// pattern's verdict on a word at r (`btob pattern WORD --r R`): the word's matrix product, its cubic, and the orbit
// walk (3x3 products along the word, each normalised: the stable direction's forward walk, the power iterations
// for the others) with the feasibility tests.  Items: the verdicts times the word's symbols.  Arguments: the case
// (0: the saddle 1133 at r = 0.12, 1: the sink 312^150 at r = 0.171599), MPFR digits.
template <class T> void BM_pattern_verdict(benchmark::State& st) {
  core::MpfrDigits digits(static_cast<int>(st.range(1) ? st.range(1) : 50));
  const bool sink = st.range(0) == 1;
  const patterns::Word w = patterns::parse_word(sink ? "312^150" : "1133");
  const T r = core::from_decimal<T>(sink ? "0.171599" : "0.12");
  for (auto _ : st) {
    const patterns::Verdict<T> v = patterns::analyse<T>(w, r);
    benchmark::DoNotOptimize(v.outcome);
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(w.size()));
}

// The core's clock in the same run, for the ceilings (docs/performance.md): a chain of dependent scalar FMAs, 4 cycles
// each on AMD Zen 3-5 and Intel since Skylake, so 4 x items_per_second (CPU time) is the clock in cycles per second.
void BM_fma_chain(benchmark::State& st) {
  if (!__builtin_cpu_supports("fma")) {
    st.SkipWithError("no FMA instruction");
    return;
  }
  constexpr long n = 10000000;
  double x = 1, a = 0.9999999, b = 1e-9;
  __asm__ volatile("vzeroupper");  // this unit's SSE code after the kernel's 512-bit code: no dirty upper state
  for (auto _ : st) {
    long count = n / 4;  // 4 dependent FMAs per turn, the loop's counter beside them (other pipes)
    __asm__ volatile(
        "1:\n\tvfmadd132sd %3, %2, %0\n\tvfmadd132sd %3, %2, %0\n\tvfmadd132sd %3, %2, %0\n\t"
        "vfmadd132sd %3, %2, %0\n\tdec %1\n\tjnz 1b"
        : "+x"(x), "+r"(count)
        : "x"(b), "x"(a));
  }
  benchmark::DoNotOptimize(x);
  st.SetItemsProcessed(st.iterations() * n);
}

BENCHMARK(BM_iterate<double>)->Name("smoke_one")->Args({20000, 1, 0})->UseRealTime();
BENCHMARK(BM_iterate<float>)->Name("one/float")->Args({10000000, 1, 0})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<double>)->Name("one/double")->Args({10000000, 1, 0})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<long double>)
    ->Name("one/long-double")
    ->Args({2000000, 1, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<core::float128>)
    ->Name("one/float128")
    ->Args({200000, 1, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<core::mpfr_float>)
    ->Name("one/mpfr")
    ->Args({200000, 1, 50})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<float>)
    ->Name("lane_of_batch/float")
    ->Args({2000000, lane_of_batch_copies<float>(), 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<double>)
    ->Name("lane_of_batch/double")
    ->Args({2000000, lane_of_batch_copies<double>(), 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<long double>)
    ->Name("lane_of_batch/long-double")
    ->Args({500000, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<core::float128>)
    ->Name("lane_of_batch/float128")
    ->Args({50000, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<core::mpfr_float>)
    ->Name("lane_of_batch/mpfr")
    ->Args({50000, 2, 50})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_iterate<double, true>)
    ->Name("few/double")
    ->Args({5000000, 2, 0})
    ->Args({5000000, 8, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_series)->Name("series/double")->Args({1000000})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_classify)->Name("classify/double")->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_strip_orbits)->Name("strip_orbits/double")->Args({1000000})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_pattern_verdict<double>)->Name("pattern_verdict/double")->Args({0, 0})->Args({1, 0})->UseRealTime();
BENCHMARK(BM_pattern_verdict<core::mpfr_float>)
    ->Name("pattern_verdict/mpfr")
    ->Args({0, 50})
    ->Args({1, 50})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fma_chain)->Name("fma_chain")->Unit(benchmark::kMillisecond);
BTOB_PLAIN_REFERENCE;

}  // namespace

BENCHMARK_MAIN();
