// SPDX-License-Identifier: GPL-3.0-or-later
// The generic Ulam construction, templated on the map (used for P^_r and for the validation maps of the tests).
#pragma once

#include "core/cancel.hpp"
#include "core/run.hpp"
#include "transfer/transfer.hpp"

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace btob::transfer {

namespace ulam_detail {

// Rows of Ulam's matrix as they are counted: per box its target boxes (sorted) and their probabilities.
struct Rows {
  std::vector<std::vector<int>> cols;
  std::vector<std::vector<double>> vals;
};

// The samples of the boxes box0 .. box0 + count - 1, box after box (S = off.size() each), into a and b.
inline void place_samples(const Partition& p, const std::vector<std::pair<double, double>>& off, long box0, long count,
                          std::vector<double>& a, std::vector<double>& b, int threads) {
  const std::size_t S = off.size();
  const double h1 = (p.hi1 - p.lo1) / static_cast<double>(p.n1), h2 = (p.hi2 - p.lo2) / static_cast<double>(p.n2);
  a.resize(static_cast<std::size_t>(count) * S);
  b.resize(static_cast<std::size_t>(count) * S);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long k = 0; k < count; ++k) {
    const long box = box0 + k, i1 = box / p.n2, i2 = box % p.n2;
    const std::size_t first = static_cast<std::size_t>(k) * S;
    for (std::size_t s = 0; s < S; ++s) {
      a[first + s] = p.lo1 + (static_cast<double>(i1) + off[s].first) * h1;
      b[first + s] = p.lo2 + (static_cast<double>(i2) + off[s].second) * h2;
    }
  }
}

// One box's row from the boxes of its S images (`target`, sorted in place; `kept` of them in the chart).
inline void count_row(std::vector<long>& target, std::size_t kept, std::vector<int>& cols, std::vector<double>& vals) {
  std::sort(target.begin(), target.begin() + static_cast<long>(kept));
  for (std::size_t s = 0; s < kept;) {
    std::size_t e = s;
    while (e < kept && target[e] == target[s]) ++e;
    cols.push_back(static_cast<int>(target[s]));
    vals.push_back(static_cast<double>(e - s) / static_cast<double>(kept));
    s = e;
  }
}

// The rows of boxes box0 .. box0 + count - 1 from their samples' images (a, b); returns the samples lost (outside
// the chart or not finite).  OpenMP, static schedule over boxes: the rows do not depend on the thread count.
inline std::uint64_t count_images(const Partition& p, const std::vector<double>& a, const std::vector<double>& b,
                                  long box0, long count, std::size_t S, Rows& rows, int threads) {
  std::uint64_t lost = 0;
#pragma omp parallel num_threads(threads) reduction(+ : lost)
  {
    std::vector<long> target(S);
#pragma omp for schedule(static)
    for (long k = 0; k < count; ++k) {
      std::size_t kept = 0;
      for (std::size_t s = 0; s < S; ++s) {
        const std::size_t sample = static_cast<std::size_t>(k) * S + s;
        const long t = p.locate(a[sample], b[sample]);
        if (t < 0) ++lost;
        else target[kept++] = t;
      }
      const auto box = static_cast<std::size_t>(box0 + k);
      count_row(target, kept, rows.cols[box], rows.vals[box]);
    }
  }
  return lost;
}

// The rows in compressed form (their memory freed as they are copied).
inline UlamMatrix compress(Rows& rows, std::uint64_t lost) {
  UlamMatrix P;
  P.n = static_cast<long>(rows.cols.size());
  P.lost = lost;
  P.row_ptr.assign(rows.cols.size() + 1, 0);
  for (std::size_t i = 0; i < rows.cols.size(); ++i)
    P.row_ptr[i + 1] = P.row_ptr[i] + static_cast<int>(rows.cols[i].size());
  P.col.reserve(static_cast<std::size_t>(P.row_ptr.back()));
  P.val.reserve(static_cast<std::size_t>(P.row_ptr.back()));
  for (std::size_t i = 0; i < rows.cols.size(); ++i) {
    P.col.insert(P.col.end(), rows.cols[i].begin(), rows.cols[i].end());
    P.val.insert(P.val.end(), rows.vals[i].begin(), rows.vals[i].end());
    std::vector<int>().swap(rows.cols[i]);
    std::vector<double>().swap(rows.vals[i]);
  }
  return P;
}

}  // namespace ulam_detail

// f(a, b, n): images of the n points (a[k], b[k]) in place.  Boxes are processed in chunks of ~2^18 samples
// (memory stays small); in each chunk the samples are built, mapped by f, located and counted per box.
template <class BatchMap>
UlamMatrix ulam(const Partition& p, int samples, BatchMap&& f, const core::RunControl& c = {}) {
  const long n = p.size();
  const auto off = sample_offsets(samples);
  const long chunk = std::max<long>(1, (1L << 18) / samples);
  ulam_detail::Rows rows{std::vector<std::vector<int>>(static_cast<std::size_t>(n)),
                         std::vector<std::vector<double>>(static_cast<std::size_t>(n))};
  std::vector<double> a, b;
  std::uint64_t lost = 0;
  const int threads = core::thread_count(c.threads);
  for (long box0 = 0; box0 < n; box0 += chunk) {
    core::check_cancel(c.cancel);
    const long count = std::min(chunk, n - box0);
    ulam_detail::place_samples(p, off, box0, count, a, b, threads);
    f(a.data(), b.data(), a.size());
    lost += ulam_detail::count_images(p, a, b, box0, count, off.size(), rows, threads);
    if (c.progress) c.progress->update(static_cast<std::size_t>(box0 + count), static_cast<std::size_t>(n));
  }
  return ulam_detail::compress(rows, lost);
}

}  // namespace btob::transfer
