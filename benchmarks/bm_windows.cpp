// SPDX-License-Identifier: GPL-3.0-or-later
// Windows of stability: the exact certificate of the n-th lower bound (Descartes' rule after Moebius
// transforms, the default) against the Sturm sequence it replaced, on the same reduced polynomial and the
// same intervals; and the lower bound itself at 512 decimals (Newton from a 30-decimal seed).
// Items = certificates (or bounds).  Sturm is run once per size (Iterations(1)): ~1 s at n = 40, ~45 s at n = 120.
#include "windows/windows.hpp"

#include <benchmark/benchmark.h>

namespace {
using namespace btob::windows;

// The certificate's two counts on the reduced cofactor of Q_n (s = r + 1/r): (s_a, inf) and (s_b, s_a).
struct Counts {
  IntPoly reduced;
  mpq_class sa, sb;
};
Counts counts_setup(int n) {
  const Certificate c = certify_lower_bound(n, 30);
  return {palindromic_reduce(factorise(window_polynomial(n)).cofactor), c.a + 1 / c.a, c.b + 1 / c.b};
}

void BM_counts_descartes(benchmark::State& st) {
  const Counts k = counts_setup(static_cast<int>(st.range(0)));
  for (auto _ : st) {
    const long above = descartes_count_to_infinity(k.reduced, k.sa), inside = descartes_count(k.reduced, k.sb, k.sa);
    if (above != 0 || inside != 1) st.SkipWithError("Descartes counts differ from the certificate's 0 and 1");
  }
  st.SetItemsProcessed(st.iterations());
}

void BM_counts_sturm(benchmark::State& st) {
  const Counts k = counts_setup(static_cast<int>(st.range(0)));
  for (auto _ : st) {
    const auto seq = sturm_sequence(k.reduced);
    const long above = sturm_count_to_infinity(seq, k.sa), inside = sturm_count(seq, k.sb, k.sa);
    if (above != 0 || inside != 1) st.SkipWithError("Sturm counts differ from the certificate's 0 and 1");
  }
  st.SetItemsProcessed(st.iterations());
}

// The whole certificate as `btob windows bounds --certify --digits 30` computes it (bound + exact checks).
void BM_certify(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  (void)window_polynomial(n);  // the cached traces T_1..T_n, shared by all n in a run
  for (auto _ : st) {
    const Certificate c = certify_lower_bound(n, 30);
    if (!c.valid()) st.SkipWithError("certificate not valid");
  }
  st.SetItemsProcessed(st.iterations());
}

void BM_lower_bound(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0)), digits = static_cast<int>(st.range(1));
  (void)window_polynomial(n);
  for (auto _ : st) benchmark::DoNotOptimize(window_lower_bound(n, digits));
  st.SetItemsProcessed(st.iterations());
}

}  // namespace

BENCHMARK(BM_counts_descartes)->Name("smoke/counts_descartes")->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_counts_descartes)
    ->Name("counts_descartes")
    ->Arg(40)
    ->Arg(60)
    ->Arg(120)
    ->Arg(150)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_counts_sturm)->Name("counts_sturm")->Arg(40)->Arg(60)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_certify)->Name("certify")->Arg(60)->Arg(150)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_lower_bound)->Name("lower_bound")->Args({150, 30})->Args({150, 512})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
