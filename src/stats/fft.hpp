// SPDX-License-Identifier: GPL-3.0-or-later
// One FFTW wrapper for the module: a real-to-complex / complex-to-real transform pair of one length.
#pragma once

#include "core/request.hpp"

#include <complex>
#include <memory>

namespace btob::stats {

// RealFft<T> owns one plan pair (forward r2c, inverse c2r) of length n and its two aligned buffers; T is
// float, double or long double (FFTW's fftwf_, fftw_, fftwl_ families).  Conventions (FFTW's own):
//     forward:  X_j = sum_{k<n} x_k exp(-2 pi i j k / n),  j = 0..n/2      (unnormalised)
//     inverse:  x_k = sum_{j<n} X_j exp(+2 pi i j k / n)                   (unnormalised: inverse o forward = n)
// The inverse overwrites spectrum().  Plans are made with FFTW_ESTIMATE (no timing runs, so the same
// plan and bitwise the same result on every run) and made and destroyed under one process-wide mutex
// (FFTW's planner is not thread-safe); forward()/inverse() only execute and may run concurrently on
// different objects.  Throws std::invalid_argument for n < 1 or n > 2^31 - 1 ("fft length: got ...").
// Given a cancellation token, the planning (its twiddle factors: ~0.7 s a plan at 6e7 points) and a transform of
// kInlineLength points or more run on a thread of their own while the caller polls the token every 5 ms: one FFTW
// call cannot be interrupted and a transform takes seconds at 10^8 points (1.6 s at 2^26 in double).  Cancelled, the
// caller throws core::Cancelled at once and abandons the call, which finishes alone on the buffers it shares with
// the object and frees them; the object must not be used again.
template <class T> class RealFft {
 public:
  static constexpr long kInlineLength = 1L << 20;  // shorter transforms run on the caller's thread (~0.02 s)
  explicit RealFft(long n, const core::CancelToken* cancel = nullptr);
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;
  long size() const { return n_; }
  T* data() { return in_; }                                 // n real values
  std::complex<T>* spectrum() { return out_; }              // n/2 + 1 complex values
  void forward(const core::CancelToken* cancel = nullptr);  // data() -> spectrum()
  void inverse(const core::CancelToken* cancel = nullptr);  // spectrum() -> data()

 private:
  struct Plans;  // the buffers and the plan pair, shared with a transform running on its own thread
  long n_;
  std::shared_ptr<Plans> p_;
  T* in_ = nullptr;
  std::complex<T>* out_ = nullptr;
};

// The smallest 2^a 3^b 5^c >= n (lengths on which FFTW's codelets are fastest), for zero padding.
long fast_fft_length(long n);

extern template class RealFft<float>;
extern template class RealFft<double>;
extern template class RealFft<long double>;

}  // namespace btob::stats
