// RealFft<T>: FFTW plans behind the module's one planner mutex (float, double, long double).
#include "stats/fft.hpp"

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
#define BTOB_FFTW_TRAITS(T, P)                                                                              \
  template <> struct Fftw<T> {                                                                              \
    using plan = P##_plan;                                                                                  \
    using complex = P##_complex;                                                                            \
    static T* alloc_real(std::size_t n) { return P##_alloc_real(n); }                                      \
    static complex* alloc_complex(std::size_t n) { return P##_alloc_complex(n); }                          \
    static void free(void* p) { P##_free(p); }                                                              \
    static plan r2c(int n, T* in, complex* out) { return P##_plan_dft_r2c_1d(n, in, out, FFTW_ESTIMATE); } \
    static plan c2r(int n, complex* in, T* out) { return P##_plan_dft_c2r_1d(n, in, out, FFTW_ESTIMATE); } \
    static void exec_r2c(void* p, T* in, complex* out) { P##_execute_dft_r2c(static_cast<plan>(p), in, out); } \
    static void exec_c2r(void* p, complex* in, T* out) { P##_execute_dft_c2r(static_cast<plan>(p), in, out); } \
    static void destroy(void* p) { P##_destroy_plan(static_cast<plan>(p)); }                                \
  };
BTOB_FFTW_TRAITS(float, fftwf)
BTOB_FFTW_TRAITS(double, fftw)
BTOB_FFTW_TRAITS(long double, fftwl)
#undef BTOB_FFTW_TRAITS

}  // namespace

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

template <class T> RealFft<T>::RealFft(long n) : n_(n) {
  using F = Fftw<T>;
  if (n < 1 || n > INT_MAX)
    throw std::invalid_argument(fmt::format("fft length: got {}, expected 1..{}", n, INT_MAX));
  // std::complex<T> and FFTW's T[2] have the same layout (C++ [complex.numbers], FFTW manual 4.1.1).
  std::lock_guard<std::mutex> lock(planner_mutex());
  in_ = F::alloc_real(static_cast<std::size_t>(n));
  auto* out = F::alloc_complex(static_cast<std::size_t>(n / 2 + 1));
  out_ = reinterpret_cast<std::complex<T>*>(out);
  if (!in_ || !out) {
    F::free(in_);
    F::free(out);
    throw std::length_error(fmt::format("fft length: got {}, which does not fit in memory", n));
  }
  fwd_ = F::r2c(static_cast<int>(n), in_, out);
  inv_ = F::c2r(static_cast<int>(n), out, in_);
}

template <class T> RealFft<T>::~RealFft() {
  using F = Fftw<T>;
  std::lock_guard<std::mutex> lock(planner_mutex());
  if (fwd_) F::destroy(fwd_);
  if (inv_) F::destroy(inv_);
  F::free(in_);
  F::free(out_);
}

template <class T> void RealFft<T>::forward() {
  Fftw<T>::exec_r2c(fwd_, in_, reinterpret_cast<typename Fftw<T>::complex*>(out_));
}
template <class T> void RealFft<T>::inverse() {
  Fftw<T>::exec_c2r(inv_, reinterpret_cast<typename Fftw<T>::complex*>(out_), in_);
}

template class RealFft<float>;
template class RealFft<double>;
template class RealFft<long double>;

}  // namespace btob::stats
