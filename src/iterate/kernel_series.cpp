// The batched kernel instantiated with the SeriesRecorder (observable series of src/stats; kernel flags).
#include "iterate/kernel_impl.hpp"
#include "iterate/series.hpp"

namespace btob::iterate {
template void run<double, SeriesRecorder>(const Ensemble&, long, SeriesRecorder&, const RunOptions&);
template void run<float, SeriesRecorder>(const Ensemble&, long, SeriesRecorder&, const RunOptions&);
template void run<long double, SeriesRecorder>(const Ensemble&, long, SeriesRecorder&, const RunOptions&);
template void run_scalar<double, SeriesRecorder>(const Ensemble&, long, SeriesRecorder&);
}  // namespace btob::iterate
