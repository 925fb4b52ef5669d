// SPDX-License-Identifier: GPL-3.0-or-later
// RealFft<T>: FFTW plans behind the module's one planner mutex (float, double, long double).
#include "stats/fft.hpp"

#include "core/abandonable.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <climits>
#include <mutex>
#include <stdexcept>

namespace btob::stats {
namespace {

std::mutex& planner_mutex() {  // FFTW's planner (and plan destruction) is not thread-safe: one lock
  static std::mutex m;
  return m;
}

template <class T> struct Fftw;
#define BTOB_FFTW_TRAITS(T, P)                                                                                 \
  template <> struct Fftw<T> {                                                                                 \
    using plan = P##_plan;                                                                                     \
    using complex = P##_complex;                                                                               \
    static T* alloc_real(std::size_t n) { return P##_alloc_real(n); }                                          \
    static complex* alloc_complex(std::size_t n) { return P##_alloc_complex(n); }                              \
    static void free(void* p) { P##_free(p); }                                                                 \
    static plan r2c(int n, T* in, complex* out) { return P##_plan_dft_r2c_1d(n, in, out, FFTW_ESTIMATE); }     \
    static plan c2r(int n, complex* in, T* out) { return P##_plan_dft_c2r_1d(n, in, out, FFTW_ESTIMATE); }     \
    static void exec_r2c(void* p, T* in, complex* out) { P##_execute_dft_r2c(static_cast<plan>(p), in, out); } \
    static void exec_c2r(void* p, complex* in, T* out) { P##_execute_dft_c2r(static_cast<plan>(p), in, out); } \
    static void destroy(void* p) { P##_destroy_plan(static_cast<plan>(p)); }                                   \
  };
BTOB_FFTW_TRAITS(float, fftwf)
BTOB_FFTW_TRAITS(double, fftw)
BTOB_FFTW_TRAITS(long double, fftwl)
#undef BTOB_FFTW_TRAITS

// Runs `exec` (one FFTW execution on buffers that `keep` owns): on this thread without a token or below `inline_n`
// points, else by core::run_abandonable, the execution keeping its buffers alive (`keep`) until it returns.  The
// same plan on the same buffers: the same bits on either thread.
template <class Keep, class Exec>
void execute(long n, long inline_n, const core::CancelToken* cancel, std::shared_ptr<Keep> keep, Exec exec) {
  core::check_cancel(cancel);
  if (!cancel || n < inline_n) {
    exec();
    return;
  }
  core::run_abandonable(cancel, [keep = std::move(keep), exec] { exec(); });
}

}  // namespace

template <class T> struct RealFft<T>::Plans {
  T* in = nullptr;
  typename Fftw<T>::complex* out = nullptr;
  void* fwd = nullptr;
  void* inv = nullptr;
  ~Plans() {
    using F = Fftw<T>;
    std::lock_guard<std::mutex> lock(planner_mutex());
    if (fwd) F::destroy(fwd);
    if (inv) F::destroy(inv);
    F::free(in);
    F::free(out);
  }
};

long fast_fft_length(long n) {
  if (n <= 1) return 1;
  long best = 1;
  while (best < n) best *= 2;
  for (long p2 = 1; p2 < best; p2 *= 2)
    for (long p3 = p2; p3 < best; p3 *= 3)
      for (long p5 = p3; p5 < best; p5 *= 5)
        if (p5 >= n && p5 < best) best = p5;
  return best;
}

template <class T> RealFft<T>::RealFft(long n, const core::CancelToken* cancel) : n_(n) {
  using F = Fftw<T>;
  if (n < 1 || n > INT_MAX) throw std::invalid_argument(fmt::format("fft length: got {}, expected 1..{}", n, INT_MAX));
  p_ = std::make_shared<Plans>();
  execute(n, kInlineLength, cancel, p_, [p = p_.get(), n] {
    std::lock_guard<std::mutex> lock(planner_mutex());  // released before the Plans' destructor takes it
    p->in = F::alloc_real(static_cast<std::size_t>(n));
    p->out = F::alloc_complex(static_cast<std::size_t>(n / 2 + 1));
    if (p->in && p->out) {
      p->fwd = F::r2c(static_cast<int>(n), p->in, p->out);
      p->inv = F::c2r(static_cast<int>(n), p->out, p->in);
    }
  });
  if (!p_->in || !p_->out) throw std::length_error(fmt::format("fft length: got {}, which does not fit in memory", n));
  // std::complex<T> and FFTW's T[2] have the same layout (C++ [complex.numbers], FFTW manual 4.1.1).
  in_ = p_->in;
  out_ = reinterpret_cast<std::complex<T>*>(p_->out);
}

template <class T> void RealFft<T>::forward(const core::CancelToken* cancel) {
  execute(n_, kInlineLength, cancel, p_, [p = p_.get()] { Fftw<T>::exec_r2c(p->fwd, p->in, p->out); });
}
template <class T> void RealFft<T>::inverse(const core::CancelToken* cancel) {
  execute(n_, kInlineLength, cancel, p_, [p = p_.get()] { Fftw<T>::exec_c2r(p->inv, p->out, p->in); });
}

template class RealFft<float>;
template class RealFft<double>;
template class RealFft<long double>;

}  // namespace btob::stats
