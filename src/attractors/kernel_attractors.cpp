// SPDX-License-Identifier: GPL-3.0-or-later
// The batched kernel instantiated with the recorders of the attractor classification (kernel flags).
#include "attractors/recorders.hpp"
#include "iterate/cocycle_impl.hpp"
#include "iterate/kernel_impl.hpp"
#include "lyapunov/tangent.hpp"

namespace btob::iterate {
template void run<double, attractors::ReturnRecorder>(const Ensemble&, long, attractors::ReturnRecorder&,
                                                      const RunOptions&);
template void run_cocycle<double, attractors::PassTwoSums>(const Ensemble&, long, attractors::PassTwoSums&,
                                                           const RunOptions&);
template void run<double, attractors::RotationRecorder>(const Ensemble&, long, attractors::RotationRecorder&,
                                                        const RunOptions&);
template void run<double, attractors::StateRecorder>(const Ensemble&, long, attractors::StateRecorder&,
                                                     const RunOptions&);
template void run_scalar<double, attractors::ReturnRecorder>(const Ensemble&, long, attractors::ReturnRecorder&);
template void run<double, Both<lyapunov::TangentRecorder, attractors::RotationRecorder>>(
    const Ensemble&, long, Both<lyapunov::TangentRecorder, attractors::RotationRecorder>&, const RunOptions&);
}  // namespace btob::iterate
