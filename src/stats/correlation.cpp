// SPDX-License-Identifier: GPL-3.0-or-later
// C_N(phi, psi; n) by the direct sum and by FFT (FFTW), and the periodogram (Section 8.1 (2)); T = float,
// double, long double.
#include "stats/stats.hpp"

#include "core/cancel.hpp"
#include "core/request.hpp"
#include "iterate/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace btob::stats {
namespace {

// Neumaier's compensated sum: add v to (s, c); the total is s + c.
template <class T> inline void add(T& s, T& c, T v) {
  const T t = s + v;
  c += std::fabs(s) >= std::fabs(v) ? (s - t) + v : (v - t) + s;
  s = t;
}

// f(lo, hi) over [0, n) in order, in blocks of 2^20 indices (about a millisecond each), polling `cancel` before
// each: the FFT route's passes over its series and padded buffers take ~1 s each at the 3e8 points memory allows.
template <class F> void in_blocks(long n, const core::CancelToken* cancel, F&& f) {
  constexpr long block = 1L << 20;
  for (long lo = 0; lo < n; lo += block) {
    core::check_cancel(cancel);
    f(lo, std::min(n, lo + block));
  }
}

template <class T> T mean(const std::vector<T>& x, long N, const core::CancelToken* cancel = nullptr) {
  T s = 0, c = 0;
  in_blocks(N, cancel, [&](long lo, long hi) {
    T bs = s, bc = c;  // locals: the compiler keeps them in registers (s and c might alias x through the capture)
    for (long k = lo; k < hi; ++k) add(bs, bc, x[k]);
    s = bs, c = bc;
  });
  return (s + c) / static_cast<T>(N);
}

void check_sizes(long N, long n_max) {
  if (N < 1) throw core::InvalidField("iterations", fmt::format("N = {}", N), "N >= 1");
  if (n_max < 0 || n_max >= N)
    throw core::InvalidField("n-max", fmt::format("{}", n_max), fmt::format("0 <= n-max < N = {}", N));
}

template <class T> void check_series(const std::vector<T>& phi, const std::vector<T>& psi, long N, long n_max) {
  check_sizes(N, n_max);
  if (static_cast<long>(phi.size()) < N || static_cast<long>(psi.size()) < N + n_max)
    throw core::InvalidField("series", fmt::format("{} and {} values", phi.size(), psi.size()),
                             fmt::format("at least N = {} and N + n-max = {}", N, N + n_max));
}

long checked_fft_length(long N, long n_max) {
  check_sizes(N, n_max);
  return fast_fft_length(N + n_max);
}

}  // namespace

template <class T>
std::vector<T> correlation_direct(const std::vector<T>& phi, const std::vector<T>& psi, long N, long n_max,
                                  const core::CancelToken* cancel) {
  check_series(phi, psi, N, n_max);
  const T mp = mean(phi, N), mq = mean(psi, N);
  // Centred copies: the raw sum (1/N) sum phi psi - mp mq cancels to ~eps E[phi]E[psi] / C_N(0) (1e-12 on an
  // invariant curve where C_N(0) ~ 1e-3); with a_k = phi_k - mp, b_j = psi_j - mq, exactly
  //     C_N(n) = (1/N) sum_{k<N} a_k b_{k+n} + mp (1/N) sum_{k<N} b_{k+n},
  // both sums taken directly for every lag.
  std::vector<T> a(static_cast<std::size_t>(N)), b(static_cast<std::size_t>(N + n_max));
  for (long k = 0; k < N; ++k) a[k] = phi[k] - mp;
  for (long k = 0; k < N + n_max; ++k) b[k] = psi[k] - mq;
  std::vector<T> c(static_cast<std::size_t>(n_max + 1));
  constexpr long block = 1024;  // rounding per block ~ 128 eps (8 partial sums of 128 products each)
  const T* pa = a.data();
  iterate::parallel_for(static_cast<std::size_t>(n_max + 1), 0, [&](std::size_t n) {
    const T* pb = b.data() + n;
    T total = 0, comp = 0, wt = 0, wc = 0;
    for (long k0 = 0; k0 < N; k0 += block) {
      if (core::cancel_due(cancel, k0 / block)) return;  // no exception may leave an OpenMP region
      const long k1 = std::min(N, k0 + block);
      T acc[8] = {}, w[8] = {};
      long k = k0;
      for (; k + 8 <= k1; k += 8)
        for (int j = 0; j < 8; ++j) {
          acc[j] += pa[k + j] * pb[k + j];
          w[j] += pb[k + j];
        }
      T s = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
      T sw = ((w[0] + w[1]) + (w[2] + w[3])) + ((w[4] + w[5]) + (w[6] + w[7]));
      for (; k < k1; ++k) {
        s += pa[k] * pb[k];
        sw += pb[k];
      }
      add(total, comp, s);
      add(wt, wc, sw);
    }
    c[n] = (total + comp) / static_cast<T>(N) + mp * ((wt + wc) / static_cast<T>(N));
  });
  core::check_cancel(cancel);
  return c;
}

template <class T>
Correlator<T>::Correlator(long N, long n_max, const core::CancelToken* cancel)
    : N_(N), n_max_(n_max), fft_(checked_fft_length(N, n_max), cancel) {
  a_.resize(static_cast<std::size_t>(fft_.size() / 2 + 1));
}

template <class T>
std::vector<T> Correlator<T>::operator()(const std::vector<T>& phi, const std::vector<T>& psi,
                                         const core::CancelToken* cancel) {
  check_series(phi, psi, N_, n_max_);
  const long L = fft_.size(), H = L / 2 + 1, N = N_, M = n_max_;
  const T mp = mean(phi, N, cancel), mq = mean(psi, N, cancel);
  T* d = fft_.data();
  std::complex<T>* X = fft_.spectrum();
  // Zero padding: phi beyond N, psi beyond N + n_max (centre(v, m, n) writes d[k] = v[k] - m for k < n, else 0).
  const auto centre = [&](const std::vector<T>& v, T m, long n) {
    in_blocks(L, cancel, [&](long lo, long hi) {
      const long split = std::clamp(n, lo, hi);
      for (long k = lo; k < split; ++k) d[k] = v[k] - m;
      std::fill(d + split, d + hi, T(0));
    });
  };
  centre(phi, mp, N);
  fft_.forward(cancel);
  in_blocks(H, cancel, [&](long lo, long hi) { std::copy(X + lo, X + hi, a_.begin() + lo); });
  centre(psi, mq, N + M);
  fft_.forward(cancel);
  in_blocks(H, cancel, [&](long lo, long hi) {
    for (long j = lo; j < hi; ++j) X[j] = std::conj(a_[j]) * X[j];
  });
  fft_.inverse(cancel);  // d[n] = L sum_{k<N} (phi_k - mp)(psi_{k+n} - mq) for n <= n_max (no wrap-around)
  // sum_{k<N} phi_k psi_{k+n} / N - mp mq = centred(n) / N + mp W(n) / N, W(n) = sum_{k<N} (psi_{k+n} - mq),
  // W updated lag by lag with a compensated sum.
  T w = 0, wc = 0;
  in_blocks(N, cancel, [&](long lo, long hi) {
    T bw = w, bwc = wc;  // locals, as in mean()
    for (long k = lo; k < hi; ++k) add(bw, bwc, psi[k] - mq);
    w = bw, wc = bwc;
  });
  std::vector<T> c(static_cast<std::size_t>(M + 1));
  const T invL = T(1) / static_cast<T>(L), invN = T(1) / static_cast<T>(N);
  in_blocks(M + 1, cancel, [&](long lo, long hi) {
    T bw = w, bwc = wc;  // locals, as in mean()
    for (long n = lo; n < hi; ++n) {
      c[n] = d[n] * invL * invN + mp * (bw + bwc) * invN;
      if (n < M) {
        add(bw, bwc, psi[n + N] - mq);
        add(bw, bwc, -(psi[n] - mq));
      }
    }
    w = bw, wc = bwc;
  });
  return c;
}

template <class T>
Periodogram<T>::Periodogram(long N, const core::CancelToken* cancel) : N_(N), fft_(std::max<long>(N, 1), cancel) {
  if (N < 2) throw core::InvalidField("iterations", fmt::format("N = {}", N), "N >= 2 for a spectrum");
}

template <class T> std::vector<T> Periodogram<T>::operator()(const std::vector<T>& x, const core::CancelToken* cancel) {
  if (static_cast<long>(x.size()) < N_)
    throw core::InvalidField("series", fmt::format("{} values", x.size()), fmt::format("at least N = {}", N_));
  const T m = mean(x, N_, cancel);
  T* d = fft_.data();
  in_blocks(N_, cancel, [&](long lo, long hi) {
    for (long k = lo; k < hi; ++k) d[k] = x[k] - m;
  });
  fft_.forward(cancel);
  const std::complex<T>* X = fft_.spectrum();
  std::vector<T> s(static_cast<std::size_t>(N_ / 2 + 1));
  in_blocks(N_ / 2 + 1, cancel, [&](long lo, long hi) {
    for (long j = lo; j < hi; ++j) s[j] = std::norm(X[j]) / static_cast<T>(N_);
  });
  return s;
}

template std::vector<float> correlation_direct(const std::vector<float>&, const std::vector<float>&, long, long,
                                               const core::CancelToken*);
template std::vector<double> correlation_direct(const std::vector<double>&, const std::vector<double>&, long, long,
                                                const core::CancelToken*);
template std::vector<long double> correlation_direct(const std::vector<long double>&, const std::vector<long double>&,
                                                     long, long, const core::CancelToken*);
template class Correlator<float>;
template class Correlator<double>;
template class Correlator<long double>;
template class Periodogram<float>;
template class Periodogram<double>;
template class Periodogram<long double>;

}  // namespace btob::stats
