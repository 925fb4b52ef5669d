// The batched kernel instantiated with the TangentRecorder (Lyapunov maps; compiled with the kernel flags).
#include "iterate/kernel_impl.hpp"
#include "iterate/tangent.hpp"

namespace btob::iterate {
template void run<double, TangentRecorder>(const Ensemble&, long, TangentRecorder&, const RunOptions&);
template void run<float, TangentRecorder>(const Ensemble&, long, TangentRecorder&, const RunOptions&);
template void run_scalar<double, TangentRecorder>(const Ensemble&, long, TangentRecorder&);
}  // namespace btob::iterate
