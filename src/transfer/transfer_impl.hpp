// The generic Ulam construction, templated on the map (used for P^_r and for the validation maps of the tests).
#pragma once

#include "transfer/transfer.hpp"

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace btob::transfer {

// f(a, b, n): images of the n points (a[k], b[k]) in place.  Boxes are processed in chunks of ~2^18 samples
// (memory stays small); in each chunk the samples are built, mapped by f, located and counted per box (OpenMP,
// static schedule over boxes: the matrix does not depend on the thread count).
template <class BatchMap>
UlamMatrix ulam(const Partition& p, int samples, BatchMap&& f, const core::RunControl& c = {}) {
  const long n = p.size();
  const auto off = sample_offsets(samples);
  const long S = samples;
  const long chunk = std::max<long>(1, (1L << 18) / S);
  const double h1 = (p.hi1 - p.lo1) / static_cast<double>(p.n1), h2 = (p.hi2 - p.lo2) / static_cast<double>(p.n2);
  std::vector<std::vector<int>> cols(static_cast<std::size_t>(n));
  std::vector<std::vector<double>> vals(static_cast<std::size_t>(n));
  std::vector<double> a, b;
  std::uint64_t lost = 0;
  const int threads = c.threads > 0 ? c.threads : omp_get_max_threads();
  for (long box0 = 0; box0 < n; box0 += chunk) {
    c.check_cancelled();
    const long nb = std::min(chunk, n - box0);
    a.resize(static_cast<std::size_t>(nb * S));
    b.resize(static_cast<std::size_t>(nb * S));
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long k = 0; k < nb; ++k) {
      const long box = box0 + k, i1 = box / p.n2, i2 = box % p.n2;
      for (long s = 0; s < S; ++s) {
        a[static_cast<std::size_t>(k * S + s)] = p.lo1 + (static_cast<double>(i1) + off[s].first) * h1;
        b[static_cast<std::size_t>(k * S + s)] = p.lo2 + (static_cast<double>(i2) + off[s].second) * h2;
      }
    }
    f(a.data(), b.data(), static_cast<std::size_t>(nb * S));
    std::uint64_t lost_chunk = 0;
#pragma omp parallel num_threads(threads) reduction(+ : lost_chunk)
    {
      std::vector<long> target(static_cast<std::size_t>(S));
#pragma omp for schedule(static)
      for (long k = 0; k < nb; ++k) {
        long kept = 0;
        for (long s = 0; s < S; ++s) {
          const long t = p.locate(a[static_cast<std::size_t>(k * S + s)], b[static_cast<std::size_t>(k * S + s)]);
          if (t < 0) ++lost_chunk;
          else target[static_cast<std::size_t>(kept++)] = t;
        }
        std::sort(target.begin(), target.begin() + kept);
        auto& cc = cols[static_cast<std::size_t>(box0 + k)];
        auto& vv = vals[static_cast<std::size_t>(box0 + k)];
        for (long s = 0; s < kept;) {
          long e = s;
          while (e < kept && target[static_cast<std::size_t>(e)] == target[static_cast<std::size_t>(s)]) ++e;
          cc.push_back(static_cast<int>(target[static_cast<std::size_t>(s)]));
          vv.push_back(static_cast<double>(e - s) / static_cast<double>(kept));
          s = e;
        }
      }
    }
    lost += lost_chunk;
    if (c.progress) c.progress->update(static_cast<std::size_t>(box0 + nb), static_cast<std::size_t>(n));
  }
  UlamMatrix P;
  P.n = n;
  P.lost = lost;
  P.row_ptr.assign(static_cast<std::size_t>(n + 1), 0);
  for (long i = 0; i < n; ++i)
    P.row_ptr[static_cast<std::size_t>(i + 1)] = P.row_ptr[static_cast<std::size_t>(i)] +
                                                 static_cast<int>(cols[static_cast<std::size_t>(i)].size());
  P.col.reserve(static_cast<std::size_t>(P.row_ptr.back()));
  P.val.reserve(static_cast<std::size_t>(P.row_ptr.back()));
  for (long i = 0; i < n; ++i) {
    P.col.insert(P.col.end(), cols[static_cast<std::size_t>(i)].begin(), cols[static_cast<std::size_t>(i)].end());
    P.val.insert(P.val.end(), vals[static_cast<std::size_t>(i)].begin(), vals[static_cast<std::size_t>(i)].end());
    std::vector<int>().swap(cols[static_cast<std::size_t>(i)]);
    std::vector<double>().swap(vals[static_cast<std::size_t>(i)]);
  }
  return P;
}

}  // namespace btob::transfer
