// SPDX-License-Identifier: GPL-3.0-or-later
// Non-template parts of the recorders.
#include "iterate/recorders.hpp"

#include "core/request.hpp"
#include "core/run.hpp"

#include <fmt/format.h>

namespace btob::iterate {

Coord parse_coord(const std::string& name, const char* field) {
  if (name == "theta") return Coord::theta;
  if (name == "log10-theta" || name == "log-theta") return Coord::log10_theta;
  if (name == "phi") return Coord::phi;
  if (name == "w1") return Coord::w1;
  if (name == "w2") return Coord::w2;
  throw core::InvalidField(field, fmt::format("'{}'", name), "theta, log10-theta, phi, w1 or w2");
}

const char* coord_name(Coord c) {
  switch (c) {
    case Coord::theta: return "theta";
    case Coord::log10_theta: return "log10-theta";
    case Coord::phi: return "phi";
    case Coord::w1: return "w1";
    case Coord::w2: return "w2";
  }
  return "?";
}

DensityRecorder::DensityRecorder(Coord c, const Ensemble& e, long iterations_, long tail_, std::size_t bins_,
                                 double lo_, double hi_, int threads)
    : coord(c),
      iterations(iterations_),
      tail(tail_),
      n_ic(e.initial.size()),
      columns(e.r.size()),
      bins(bins_),
      lo(lo_),
      hi(hi_) {
  if (bins < 1) throw core::InvalidField("bins", fmt::format("{}", bins), "at least 1");
  if (bins > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw core::InvalidField("bins", fmt::format("{}", bins),
                             fmt::format("at most {}", std::numeric_limits<std::int32_t>::max()));
  if (!(lo < hi)) throw core::InvalidField("range", fmt::format("[{}, {}]", lo, hi), "lo < hi");
  const int nt = core::thread_count(threads);
  checked_bytes(columns * bins * static_cast<std::size_t>(nt + 1), sizeof(std::uint32_t), "density image");
  // Each thread zeroes (first-touches) its own image: no serial memset and copy of nt images.
  per_thread.resize(static_cast<std::size_t>(nt));
#pragma omp parallel for schedule(static, 1) num_threads(nt)
  for (int t = 0; t < nt; ++t) per_thread[static_cast<std::size_t>(t)].assign(columns * bins, 0);
  under_t.assign(static_cast<std::size_t>(nt), std::vector<std::uint64_t>(columns, 0));
  over_t = under_t;
}

std::vector<std::uint32_t> DensityRecorder::merge() {
  // Integer sums into thread 0's image (in place, no new allocation); the image is consumed.
  if (per_thread.empty()) throw std::logic_error("DensityRecorder::merge: called twice");
  std::vector<std::uint32_t> img = std::move(per_thread[0]);
  const std::size_t n = img.size();
  under.assign(columns, 0);
  over.assign(columns, 0);
  for (std::size_t t = 1; t < per_thread.size(); ++t) {
    const std::uint32_t* src = per_thread[t].data();
    std::uint32_t* dst = img.data();
#pragma omp parallel for simd schedule(static) num_threads(static_cast <int>(per_thread.size()))
    for (std::size_t i = 0; i < n; ++i) dst[i] += src[i];
  }
  per_thread.clear();
  for (std::size_t t = 0; t < under_t.size(); ++t) {
    for (std::size_t c = 0; c < columns; ++c) {
      under[c] += under_t[t][c];
      over[c] += over_t[t][c];
    }
  }
  return img;
}

}  // namespace btob::iterate
