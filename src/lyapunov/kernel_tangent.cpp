// The batched kernel instantiated with the TangentRecorder (Lyapunov maps; compiled with the kernel flags).
#include "iterate/kernel_impl.hpp"
#include "lyapunov/tangent.hpp"

namespace btob::iterate {
template void run<double, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&, const RunOptions&);
template void run<float, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&, const RunOptions&);
template void run_scalar<double, lyapunov::TangentRecorder>(const Ensemble&, long, lyapunov::TangentRecorder&);
}  // namespace btob::iterate
