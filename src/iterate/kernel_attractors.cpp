// The batched kernel instantiated with the recorders of the attractor classification (kernel flags).
#include "iterate/attractor_recorder.hpp"
#include "iterate/kernel_impl.hpp"
#include "iterate/tangent.hpp"

namespace btob::iterate {
template void run<double, ReturnRecorder>(const Ensemble&, long, ReturnRecorder&, const RunOptions&);
template void run_scalar<double, ReturnRecorder>(const Ensemble&, long, ReturnRecorder&);
template void run<double, Both<TangentRecorder, RotationRecorder>>(const Ensemble&, long,
                                                                   Both<TangentRecorder, RotationRecorder>&,
                                                                   const RunOptions&);
}  // namespace btob::iterate
