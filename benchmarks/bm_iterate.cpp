// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the iterator in map iterations per second: the scalar loop of Appendix A.2 (baseline)
// against the batched SIMD kernel, float and double, 1 and 2 threads, on the Figure 4.1 workload.
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <benchmark/benchmark.h>

#include "plain_reference.hpp"

#include <fstream>
#include <string>

namespace {

using namespace btob::iterate;

using btob::bench::fig41;  // Figure 4.1's ensemble (plain_reference.hpp)

// MPFR's digits come from the benchmark's last argument (range(digits_arg)).
template <class T> void set_digits(const benchmark::State& st, int digits_arg) {
  if constexpr (std::is_same_v<T, btob::core::mpfr_float>)
    btob::core::mpfr_float::default_precision(static_cast<unsigned>(st.range(digits_arg)));
}

// Appendix A.2 as printed: one orbit at a time, branches, normalise every step.
template <class T> void BM_scalar_loop(benchmark::State& st) {
  set_digits<T>(st, 2);
  const Ensemble e = fig41(st.range(0));
  const long iters = st.range(1);
  for (auto _ : st) {
    FinalRecorder rec(e.orbits(), iters);
    run_scalar<T>(e, iters, rec);
    benchmark::DoNotOptimize(rec.out.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * iters);
}

// The batched kernel, recording only the final state (the iteration phase alone).
template <class T> void BM_batched(benchmark::State& st) {
  set_digits<T>(st, 3);
  const Ensemble e = fig41(st.range(0));
  const long iters = st.range(1);
  RunOptions opt;
  opt.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    FinalRecorder rec(e.orbits(), iters);
    run<T>(e, iters, rec, opt);
    benchmark::DoNotOptimize(rec.out.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * iters);
}

// The whole Figure 4.1 computation: 5000 iterations, the last 100 binned into the density image (Density = true), or
// the same workload keeping only the final state: the plain iteration it is compared with (the goal: within 10%).
// Coord C = w2 bins the strip coordinate (x + z) / (x - z) over [-1, 1] instead of theta: one division and no atan, the
// floor of what recording 100 steps and binning them costs.
template <class T, bool Density, Coord C = Coord::theta> void BM_fig41(benchmark::State& st) {
  const Ensemble e = fig41(st.range(0));
  const long iters = st.range(1);
  RunOptions opt;
  opt.threads = static_cast<int>(st.range(2));
  for (auto _ : st) {
    if constexpr (Density) {
      const double lo = C == Coord::w2 ? -1.0 : 0.0, hi = C == Coord::w2 ? 1.0 : 1.5707963267948966;
      DensityRecorder rec(C, e, iters, 100, 800, lo, hi, opt.threads);
      run<T>(e, iters, rec, opt);
      benchmark::DoNotOptimize(rec.merge().data());
    } else {
      FinalRecorder rec(e.orbits(), iters);
      run<T>(e, iters, rec, opt);
      benchmark::DoNotOptimize(rec.out.data());
    }
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(e.orbits()) * iters);
}

// The core clock under load, for the hardware-limit estimate: a chain of dependent 1-cycle integer adds
// retires one add per cycle, so adds per second = cycles per second (counter "GHz").
void BM_core_clock(benchmark::State& st) {
  constexpr long kChain = 1L << 24;
  for (auto _ : st) {
    long v = 0;
    for (long i = 0; i < kChain; i += 8) {
#if defined(__x86_64__)
      asm volatile(
          "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\t"
          "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0"
          : "+r"(v));
#else
      v += 8;
      benchmark::DoNotOptimize(v);
#endif
    }
    benchmark::DoNotOptimize(v);
  }
  st.counters["GHz"] = benchmark::Counter(static_cast<double>(kChain) * static_cast<double>(st.iterations()) * 1e-9,
                                          benchmark::Counter::kIsRate);
}

// "cpu family" and "model" of /proc/cpuinfo (Zen 4 is AMD family 25, Zen 5 family 26), for the JSON.
std::string cpuinfo_field(const std::string& key) {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0 && line.find(':') != std::string::npos) {
      const std::string v = line.substr(line.find(':') + 1);
      return v.empty() ? v : v.substr(v.find_first_not_of(' '));
    }
  return "unknown";
}

}  // namespace

BENCHMARK(BM_core_clock)->Name("core_clock")->Unit(benchmark::kMillisecond);
// Baseline: 50 r values x 32 orbits x 5000 iterations (8e6 map iterations per run).
BENCHMARK(BM_scalar_loop<double>)->Name("scalar_loop/double")->Args({50, 5000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_scalar_loop<float>)->Name("scalar_loop/float")->Args({50, 5000})->Unit(benchmark::kMillisecond);
// Batched: 1000 r values x 32 orbits x 5000 iterations (1.6e8 map iterations), threads 1 and 2.
BENCHMARK(BM_batched<double>)
    ->Name("batched/double")
    ->Args({1000, 5000, 1})
    ->Args({1000, 5000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_batched<float>)
    ->Name("batched/float")
    ->Args({1000, 5000, 1})
    ->Args({1000, 5000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
// The full Figure 4.1 workload (5000 r, 8e8 map iterations) with the density recorder.
BENCHMARK(BM_fig41<double, true>)
    ->Name("fig41_density/double")
    ->Args({5000, 5000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fig41<float, true>)
    ->Name("fig41_density/float")
    ->Args({5000, 5000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fig41<double, false>)
    ->Name("fig41_plain/double")
    ->Args({5000, 5000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fig41<double, true>)->Name("fig41_density/double")->Args({5000, 5000, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fig41<double, false>)->Name("fig41_plain/double")->Args({5000, 5000, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fig41<double, true, Coord::w2>)
    ->Name("fig41_density_w2/double")
    ->Args({5000, 5000, 1})
    ->Unit(benchmark::kMillisecond);
// Wider precisions: batched 1 and 2 threads, scalar loop.
BENCHMARK(BM_batched<long double>)
    ->Name("batched/long-double")
    ->Args({20, 2000, 1, 0})
    ->Args({20, 2000, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_batched<btob::core::float128>)
    ->Name("batched/float128")
    ->Args({4, 1000, 1, 0})
    ->Args({4, 1000, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_batched<btob::core::mpfr_float>)
    ->Name("batched/mpfr")
    ->Args({1, 500, 1, 50})
    ->Args({1, 500, 2, 50})
    ->Args({1, 500, 1, 100})
    ->Args({1, 500, 2, 100})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_scalar_loop<long double>)->Name("scalar_loop/long-double")->Args({4, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_scalar_loop<btob::core::float128>)
    ->Name("scalar_loop/float128")
    ->Args({2, 1000})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_scalar_loop<btob::core::mpfr_float>)
    ->Name("scalar_loop/mpfr")
    ->Args({1, 300, 50})
    ->Args({1, 300, 100})
    ->Unit(benchmark::kMillisecond);
// Smoke runs for CTest (tiny sizes).
BENCHMARK(BM_scalar_loop<double>)->Name("smoke/scalar_loop")->Args({2, 50});
BENCHMARK(BM_batched<double>)->Name("smoke/batched")->Args({2, 50, 2})->UseRealTime();
BENCHMARK(BM_fig41<float, true>)->Name("smoke/density")->Args({2, 200, 2})->UseRealTime();

int main(int argc, char** argv) {
  benchmark::AddCustomContext("cpu_vendor", cpuinfo_field("vendor_id"));
  benchmark::AddCustomContext("cpu_family", cpuinfo_field("cpu family"));
  benchmark::AddCustomContext("cpu_model", cpuinfo_field("model\t"));
  benchmark::AddCustomContext("cpu_model_name", cpuinfo_field("model name"));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
