// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit instantiations of the kernel for one scalar type T (included by kernel_<T>.cpp).
#pragma once
#include "iterate/kernel_impl.hpp"
#include "iterate/recorders.hpp"

#define BTOB_INSTANTIATE_KERNEL(T)                                                                                     \
  template int renormalisation_interval<T>(const std::vector<double>&);                                                \
  template void run<T, TailRecorder>(const Ensemble&, long, TailRecorder&, const RunOptions&);                         \
  template void run<T, SymbolRecorder>(const Ensemble&, long, SymbolRecorder&, const RunOptions&);                     \
  template void run<T, FinalRecorder>(const Ensemble&, long, FinalRecorder&, const RunOptions&);                       \
  template void run<T, DensityRecorder>(const Ensemble&, long, DensityRecorder&, const RunOptions&);                   \
  template void run<T, Both<TailRecorder, SymbolRecorder>>(const Ensemble&, long, Both<TailRecorder, SymbolRecorder>&, \
                                                           const RunOptions&);                                         \
  template void run<T, Both<DensityRecorder, TailRecorder>>(const Ensemble&, long,                                     \
                                                            Both<DensityRecorder, TailRecorder>&, const RunOptions&);  \
  template void run<T, Both<SymbolRecorder, TailRecorder>>(const Ensemble&, long, Both<SymbolRecorder, TailRecorder>&, \
                                                           const RunOptions&);                                         \
  template void run<T, Both<FinalRecorder, SymbolRecorder>>(const Ensemble&, long,                                     \
                                                            Both<FinalRecorder, SymbolRecorder>&, const RunOptions&);  \
  template void run<T, Both<TailRecorder, TailRecorder>>(const Ensemble&, long, Both<TailRecorder, TailRecorder>&,     \
                                                         const RunOptions&);                                           \
  template void run<T, OrbitRecorders>(const Ensemble&, long, OrbitRecorders&, const RunOptions&);                     \
  template void run_scalar<T, TailRecorder>(const Ensemble&, long, TailRecorder&);                                     \
  template void run_scalar<T, SymbolRecorder>(const Ensemble&, long, SymbolRecorder&);                                 \
  template void run_scalar<T, FinalRecorder>(const Ensemble&, long, FinalRecorder&);                                   \
  template void run_scalar<T, DensityRecorder>(const Ensemble&, long, DensityRecorder&);
