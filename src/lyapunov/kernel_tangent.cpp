// SPDX-License-Identifier: GPL-3.0-or-later
// The batched kernels of the Lyapunov maps (compiled with the kernel flags): the fused cocycle kernel with
// ExponentSums (double and float), and the plain kernel with the TangentRecorder (the float-point route, the
// classification's recorder, and the reference the fused kernel is tested against).
#include "iterate/cocycle_impl.hpp"
#include "lyapunov/exponent_sums.hpp"
#include "lyapunov/tangent.hpp"

namespace btob::iterate {
template void run<double, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&,
                                                     const RunOptions&);
template void run<float, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&,
                                                    const RunOptions&);
template void run_scalar<double, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&);
template void run_cocycle<double, lyapunov::ExponentSums>(const Ensemble&, long, lyapunov::ExponentSums&,
                                                          const RunOptions&);
template void run_cocycle<float, lyapunov::ExponentSums>(const Ensemble&, long, lyapunov::ExponentSums&,
                                                         const RunOptions&);
}  // namespace btob::iterate
