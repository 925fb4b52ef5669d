// SPDX-License-Identifier: GPL-3.0-or-later
// Statistics along orbits of P^_r (Section 8.1 (2)): observables, empirical measures and their distances,
// correlation functions C_N (FFTW and the direct sum), power spectra, decay of correlations.
#pragma once

#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "stats/fft.hpp"

#include <complex>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace btob::stats {

// ---- Orbits and observables -------------------------------------------------------------------------
// The states x_k = P^_r^{transient+1+k}(u0), k = 0..length-1, as unit vectors in the quadrant Q (double),
// with the symbol 1/2/3 of the step that produced each (one batched run, stats::SeriesRecorder).
struct OrbitSeries {
  std::vector<double> x, y, z;
  std::vector<std::uint8_t> symbol;
  long size() const { return static_cast<long>(x.size()); }
  iterate::Vec3<double> state(long k) const { return {x[k], y[k], z[k]}; }
};
// Validates r, u0 (domain x z <= 0), transient >= 0, length >= 1 and the memory (25 bytes per point);
// throws core::InvalidField / std::length_error naming the field.
OrbitSeries orbit_series(double r, const iterate::Vec3<double>& u0, long transient, long length);
// Many initial conditions at one r in one OpenMP run (threads <= 0: OpenMP's default; results do not
// depend on it).
std::vector<OrbitSeries> orbit_series(double r, const std::vector<iterate::Vec3<double>>& u0, long transient,
                                      long length, int threads = 0);
// The same with the kernel's run options (threads, progress, cancellation between batches).
std::vector<OrbitSeries> orbit_series(double r, const std::vector<iterate::Vec3<double>>& u0, long transient,
                                      long length, const iterate::RunOptions& run);

// theta in [0, pi/2], phi in [0, pi] (rad, Section 4 and 5.1), w1 in R, w2 in [-1, 1] (strip, eq. (6.4)),
// cos(phi) in [-1, 1], and the indicators 1{symbol = s} in {0, 1} of the symbols 1, 2, 3.
enum class Observable { theta, phi, w1, w2, cos_phi, symbol1, symbol2, symbol3 };
// Throws std::invalid_argument "<field>: got 'x', expected theta, phi, ..." for an unknown name.
Observable parse_observable(const std::string& name, const char* field = "observable");
std::string observable_name(Observable o);
std::string observable_names();  // "theta, phi, w1, w2, cos-phi, symbol1, symbol2, symbol3"
double value(Observable o, const iterate::Vec3<double>& u, int symbol);

// The series o(x_k), or f(o(x_k)) when f is given (a user function composed with the observable).
// `cancel` is polled every core::cancel_stride states (core::Cancelled).
std::vector<double> observe(const OrbitSeries& s, Observable o, const std::function<double(double)>& f = {},
                            const core::CancelToken* cancel = nullptr);
// Any user function of the unit state and the symbol.
using StateFunction = std::function<double(const iterate::Vec3<double>& u, int symbol)>;
std::vector<double> observe(const OrbitSeries& s, const StateFunction& f);

// ---- Correlation functions C_N (Section 8.1 (2)) ---------------------------------------------------
//     C_N(phi, psi; n) = (1/N) sum_{k<N} phi_k psi_{k+n} - ((1/N) sum_{k<N} phi_k) ((1/N) sum_{k<N} psi_k)
// for lags n = 0..n_max: phi needs N values, psi needs N + n_max (both means over k < N, as printed).
// Both routes throw core::InvalidField naming the field: "n-max: got M, expected 0 <= n-max < N = ..."
// (n_max >= N is rejected: fewer than half the pairs would be averaged), "iterations" for N < 1,
// "series" for too short inputs.  T = float, double, long double (all arithmetic in T).

// The direct sum, O(N n_max): on the centred series a = phi - mean(phi), b = psi - mean(psi), per lag
// C_N(n) = (1/N) sum_{k<N} a_k b_{k+n} + mean(phi) (1/N) sum_{k<N} b_{k+n} (exact identity, no cancellation
// against mean(phi) mean(psi)); 8 interleaved partial sums over blocks of 1024 terms, each block added to a
// compensated (Neumaier) total; the means are compensated too; lags in parallel (OpenMP, static: the
// result does not depend on the thread count).
// `cancel` is polled every core::cancel_stride blocks of every lag (core::Cancelled after the loop).
template <class T>
std::vector<T> correlation_direct(const std::vector<T>& phi, const std::vector<T>& psi, long N, long n_max,
                                  const core::CancelToken* cancel = nullptr);

// The FFT route, O(L log L), L = fast_fft_length(N + n_max): phi_k - mean(phi) (k < N) and psi_k -
// mean(psi) (k < N + n_max) are zero padded to L, so the circular correlation IFFT(conj(FFT a) FFT b)/L
// has no wrap-around for lags 0..n_max; then C_N(n) = that / N + mean(phi) * sum_{k<N}(psi_{k+n} -
// mean(psi)) / N (exact identity; centring keeps the FFT's rounding relative to the covariance, not to
// the raw second moment).  One object = one length = one plan pair, reused for every orbit.  `cancel` is polled every
// 2^20 points of its passes over the buffers and while a long transform runs (RealFft); cancelled, it throws
// core::Cancelled and the object must not be used again.
template <class T> class Correlator {
 public:
  // Validates N >= 1, 0 <= n_max < N; plans length L (polling `cancel` as RealFft does).
  Correlator(long N, long n_max, const core::CancelToken* cancel = nullptr);
  std::vector<T> operator()(const std::vector<T>& phi, const std::vector<T>& psi,
                            const core::CancelToken* cancel = nullptr);
  long N() const { return N_; }
  long n_max() const { return n_max_; }
  long fft_length() const { return fft_.size(); }

 private:
  long N_, n_max_;
  RealFft<T> fft_;
  std::vector<std::complex<T>> a_;
};

// Periodogram of x_0..x_{N-1}: S_j = |sum_k (x_k - mean) exp(-2 pi i j k / N)|^2 / N, j = 0..N/2, at
// frequency j / N cycles per iteration (no padding; S is the DFT of the circular autocovariance with
// weights 1/N, so sum over all N frequencies = N * variance).  One plan per object; `cancel` as Correlator's.
template <class T> class Periodogram {
 public:
  explicit Periodogram(long N, const core::CancelToken* cancel = nullptr);  // N >= 2
  std::vector<T> operator()(const std::vector<T>& x, const core::CancelToken* cancel = nullptr);

 private:
  long N_;
  RealFft<T> fft_;
};

// Envelope and decay of |C_N(n)|: max |C_N| over consecutive windows of `window` lags starting at lag 1;
// the least-squares line through log(envelope) over windows up to lag n_fit whose envelope is above
// `floor` (the statistical noise of C_N, ~C_N(0)/sqrt(N): below it a fit measures noise, not decay).
// The verdict says only what these windows can decide (Section 8.1 (2): decay of correlations against
// quasi-periodic oscillation without decay):
//   decaying      the rate's 95% interval is above 0 and the fitted envelope fell tenfold;
//   not decaying  the envelope stays above the floor over all fitted lags and even the upper end of the rate's
//                 interval would make it fall less than tenfold over them;
//   undecided     anything else, in particular fewer than 3 windows above the floor (no line with an error):
//                 C_N reaches the noise floor too fast for this N and window; `reason` says which.
struct Decay {
  double rate = 0, rate_error = 0;               // |C_N| ~ exp(-rate n); one-sigma error of the slope (>= 3 windows)
  double rate_low = 0, rate_high = 0;            // 95% interval of the rate (Student t, windows - 2 dof)
  double envelope_first = 0, envelope_last = 0;  // first and last windows above the floor (>= 1 window)
  long windows = 0;                              // windows above the floor, all fitted
  long floor_lag = -1;                           // first lag of the first window at or below the floor; -1: not
                                                 // reached up to n_fit
  bool decays = false;                           // verdict == "decaying"
  std::string verdict = "undecided", reason;
};
std::vector<double> envelope(const std::vector<double>& c, long window);  // windows over lags 1..
Decay fit_decay(const std::vector<double>& c, long n_fit, long window, double floor = 0);

// ---- Empirical measures (Section 8.1 (2): mu_{N,x} = (1/N) sum_{k<N} delta_{x_k}) --------------------
// 2-D histograms with weights 1/N: in the strip (u = atan(w1) = atan2(y, x - z) in (-pi/2, pi/2),
// v = w2 in [-1, 1]) or in the angles (u = theta in [0, pi/2], v = phi in [0, pi]).  Equal bins; a value on
// the upper edge goes to the last bin.
enum class Chart { strip, angles };
Chart parse_chart(const std::string& name, const char* field = "coords");
std::string chart_name(Chart c);
struct Measure {
  Chart chart = Chart::strip;
  int bins_u = 0, bins_v = 0;
  double u_lo = 0, u_hi = 0, v_lo = 0, v_hi = 0;
  std::vector<double> mass;  // bins_u * bins_v, row-major in u: mass[i * bins_v + j]
  double outside = 0;        // mass of the points outside [u_lo, u_hi] x [v_lo, v_hi]; mass + outside = 1
  long points = 0;
  std::vector<double> marginal_u() const;
  std::vector<double> marginal_v() const;
};
// Points first..first+count-1 of s (count < 0: to the end).  bins in 1..100000 per direction, else
// std::invalid_argument "bins: got ...".  `extent` {u_lo, u_hi, v_lo, v_hi} zooms into part of the chart
// (empty: the whole chart); points outside it count in Measure::outside.
Measure empirical_measure(const OrbitSeries& s, Chart chart, int bins_u, int bins_v, long first = 0, long count = -1,
                          const std::vector<double>& extent = {});
// The same in two steps, for measures of prefixes of one series and for sweeps (stats/requests.hpp, measure):
// the frame (chart, bins and extent, no mass), the bin i * bins_v + j of every point of s (-1 outside the extent;
// whole: no extent given) and the measure of the first `count` cells, bitwise empirical_measure(s, ..., 0, count).
Measure measure_frame(Chart chart, int bins_u, int bins_v, const std::vector<double>& extent = {});
std::vector<std::int32_t> measure_cells(const OrbitSeries& s, const Measure& frame, bool whole);
Measure measure_of_cells(const Measure& frame, const std::int32_t* cells, long count);

// (1/2) (sum over bins |a - b| + |a.outside - b.outside|), in [0, 1] (total variation of the binned measures).
double total_variation(const Measure& a, const Measure& b);
// W1 of two marginals on the same equal bins over [lo, hi]: sum_i |F_a(i) - F_b(i)| * bin width (units
// of the axis; mass at bin granularity, so W1 <= (hi - lo)).
double wasserstein_1d(const std::vector<double>& a, const std::vector<double>& b, double lo, double hi);

// Groups measures that are closer than tv_same in total variation (greedy in index order: a measure
// joins the first group whose first member is within tv_same): the labels 0, 1, ... of the groups, one
// per measure.  Orbits ending on the same attractor with a physical measure land in one group.
std::vector<int> group_measures(const std::vector<Measure>& ms, double tv_same);

extern template std::vector<float> correlation_direct(const std::vector<float>&, const std::vector<float>&, long, long,
                                                      const core::CancelToken*);
extern template std::vector<double> correlation_direct(const std::vector<double>&, const std::vector<double>&, long,
                                                       long, const core::CancelToken*);
extern template std::vector<long double> correlation_direct(const std::vector<long double>&,
                                                            const std::vector<long double>&, long, long,
                                                            const core::CancelToken*);
extern template class Correlator<float>;
extern template class Correlator<double>;
extern template class Correlator<long double>;
extern template class Periodogram<float>;
extern template class Periodogram<double>;
extern template class Periodogram<long double>;

}  // namespace btob::stats
