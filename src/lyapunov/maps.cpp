// SPDX-License-Identifier: GPL-3.0-or-later
// Lyapunov maps on the batched kernel: run the TangentRecorder, turn its cumulative sums into exponents.
#include "lyapunov/maps.hpp"

#include "iterate/cocycle.hpp"
#include "lyapunov/exponent_sums.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/lyapunov_impl.hpp"
#include "lyapunov/tangent.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace btob::lyapunov {

OrbitExponents map_exponents(const iterate::Ensemble& ens, const MapOptions& opt) {
  Options o;
  o.transient = opt.transient;
  o.iterations = opt.iterations;
  o.blocks = opt.blocks;
  validate(o);
  for (double r : ens.r) core::validate_r(r);
  lyapunov::ExponentSums sums(ens, opt.transient, opt.iterations, opt.blocks);
  if (opt.single_precision) iterate::run_cocycle<float>(ens, sums.total_steps(), sums, opt.run);
  else iterate::run_cocycle<double>(ens, sums.total_steps(), sums, opt.run);
  return exponents_from(ens, sums.n, sums.blocks, sums.block_end, sums.cum);
}

OrbitExponents exponents_from(const lyapunov::TangentRecorder& rec) {
  return exponents_from(*rec.ens, rec.n, rec.blocks, rec.block_end, rec.cum);
}

OrbitExponents exponents_from(const iterate::Ensemble& ens, long n, int blocks, const std::vector<long>& block_end,
                              const std::vector<double>& cum) {
  const std::size_t N = ens.orbits(), B = static_cast<std::size_t>(blocks), n_ic = ens.initial.size();
  OrbitExponents out;
  out.iterations = n;
  out.blocks = blocks;
  for (auto* v : {&out.lambda1, &out.err1, &out.lambda2, &out.err2, &out.chi1, &out.lambda_max, &out.err_max,
                  &out.lambda_min, &out.err_min})
    v->resize(N);
  std::vector<double> c1(B), c2(B), cc(B);
  for (std::size_t o = 0; o < N; ++o) {
    const double* c = cum.data() + o * (B + 1) * 3;
    const double logr = std::log(ens.r[o / n_ic]);
    // Cumulative sums over averaged steps at each block end (Section 8.1 (3); identities in tangent.hpp).
    for (std::size_t j = 0; j < B; ++j) {
      const double* e = c + (j + 1) * 3;
      const double dL = e[0] - c[0], dG = e[1] - c[1], dn = e[2] - c[2];
      c1[j] = dL - dG;                                        // log |D^n v0|
      c2[j] = dn * logr - 3 * dG - c1[j];                     // log |det D^n| - log |D^n v0|
      cc[j] = dG + static_cast<double>(block_end[j]) * logr;  // log |P^n u0|
    }
    const Estimate l1 = detail::batch_means(c1, block_end), l2 = detail::batch_means(c2, block_end),
                   x1 = detail::batch_means(cc, block_end);
    out.lambda1[o] = l1.value, out.err1[o] = l1.error;
    out.lambda2[o] = l2.value, out.err2[o] = l2.error;
    out.chi1[o] = x1.value;
    const bool swap = l2.value > l1.value;  // order them (maps.hpp: equal exponents fall either side)
    out.lambda_max[o] = swap ? l2.value : l1.value, out.err_max[o] = swap ? l2.error : l1.error;
    out.lambda_min[o] = swap ? l1.value : l2.value, out.err_min[o] = swap ? l1.error : l2.error;
  }
  return out;
}

int classify(double lambda, double err, long n) {
  const double bar = 3 * err + 10.0 / static_cast<double>(n);
  if (lambda > bar) return 1;
  if (lambda < -bar) return -1;
  return 0;
}

RSummary summarise(const OrbitExponents& e, std::size_t r_count, std::size_t n_ic) {
  RSummary s;
  for (auto* v : {&s.min, &s.median, &s.max, &s.err_min, &s.err_median, &s.err_max, &s.frac_positive, &s.frac_zero,
                  &s.frac_negative})
    v->resize(r_count);
  std::vector<std::size_t> idx(n_ic);
  for (std::size_t i = 0; i < r_count; ++i) {
    int pos = 0, neg = 0, zero = 0;
    const std::size_t o0 = i * n_ic;
    for (std::size_t j = 0; j < n_ic; ++j) {
      idx[j] = o0 + j;
      const int c = classify(e.lambda1[o0 + j], e.err1[o0 + j], e.iterations);
      (c > 0 ? pos : c < 0 ? neg : zero)++;
    }
    // Stable by orbit index among equal values, so the error reported with a statistic does not depend on the sort.
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return e.lambda1[a] < e.lambda1[b]; });
    s.min[i] = e.lambda1[idx.front()], s.err_min[i] = e.err1[idx.front()];
    s.max[i] = e.lambda1[idx.back()], s.err_max[i] = e.err1[idx.back()];
    const std::size_t m = n_ic / 2;
    if (n_ic % 2) {
      s.median[i] = e.lambda1[idx[m]], s.err_median[i] = e.err1[idx[m]];
    } else {
      s.median[i] = 0.5 * (e.lambda1[idx[m - 1]] + e.lambda1[idx[m]]);
      s.err_median[i] = 0.5 * std::hypot(e.err1[idx[m - 1]], e.err1[idx[m]]);
    }
    const double n = static_cast<double>(n_ic);
    s.frac_positive[i] = pos / n, s.frac_zero[i] = zero / n, s.frac_negative[i] = neg / n;
  }
  return s;
}

}  // namespace btob::lyapunov
