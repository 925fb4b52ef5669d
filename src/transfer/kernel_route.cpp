// SPDX-License-Identifier: GPL-3.0-or-later
// The kernel route of Ulam's matrix: one step of the batched SIMD kernel (iterate::run) for every sample, with a
// recorder that writes the image's chart coordinates.  This file includes iterate/kernel_impl.hpp and is the
// only file of the module compiled with the kernel flags (cmake/KernelFlags.cmake), as src/iterate's kernel_*.cpp.
#include "iterate/kernel_impl.hpp"
#include "transfer/transfer.hpp"

#include <cstdint>

namespace btob::transfer {

// Records the state after one step (k = 1) as chart coordinates (a, b) of each orbit (the chart formulas are
// invariant under the kernel's power-of-two rescaling).
struct ChartRecorder {
  static constexpr bool needs_symbols = false;
  Domain domain;
  double* a;
  double* b;
  long first_step() const { return 1; }
  template <class T>
  void record(std::size_t o0, int lanes, long, const T* x, const T* y, const T* z, const std::uint8_t*) {
    for (int l = 0; l < lanes; ++l)
      vector_to_chart(domain, static_cast<double>(x[l]), static_cast<double>(y[l]), static_cast<double>(z[l]),
                      a[o0 + static_cast<std::size_t>(l)], b[o0 + static_cast<std::size_t>(l)]);
  }
};

void map_kernel(double r, Domain d, double* a, double* b, std::size_t n, int threads) {
  iterate::Ensemble e;
  e.r = {r};
  e.initial.resize(n);
  for (std::size_t k = 0; k < n; ++k) chart_to_vector(d, a[k], b[k], e.initial[k](0), e.initial[k](1), e.initial[k](2));
  ChartRecorder rec{d, a, b};
  iterate::RunOptions opt;
  opt.threads = threads;
  iterate::run<double, ChartRecorder>(e, 1, rec, opt);
}

}  // namespace btob::transfer
