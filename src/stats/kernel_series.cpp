// SPDX-License-Identifier: GPL-3.0-or-later
// The batched kernel instantiated with the SeriesRecorder (observable series of src/stats; kernel flags).
#include "iterate/kernel_impl.hpp"
#include "stats/series.hpp"

namespace btob::iterate {
template void run<double, stats::SeriesRecorder>(const Ensemble&, long, stats::SeriesRecorder&, const RunOptions&);
template void run<float, stats::SeriesRecorder>(const Ensemble&, long, stats::SeriesRecorder&, const RunOptions&);
template void run<long double, stats::SeriesRecorder>(const Ensemble&, long, stats::SeriesRecorder&, const RunOptions&);
template void run_scalar<double, stats::SeriesRecorder>(const Ensemble&, long, stats::SeriesRecorder&);
}  // namespace btob::iterate
