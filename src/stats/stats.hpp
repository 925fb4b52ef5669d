// Statistics along orbits (Section 7 (2)): observables, empirical measures and their distances,
// correlation functions C_N by FFT (FFTW) and by the direct sum.
#pragma once

#include "iterate/ensemble.hpp"

#include <complex>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace btob::stats {

// ---- Observables ---------------------------------------------------------------------------------
// theta, phi (rad), w1, w2 (strip, eq. 5.5), cos(phi), and the indicators of the symbols 1, 2, 3.
enum class Observable { theta, phi, w1, w2, cos_phi, symbol1, symbol2, symbol3 };
// Throws std::invalid_argument "observable: got 'x', expected ..." for an unknown name.
Observable parse_observable(const std::string& name, const char* field = "observable");
std::string observable_name(Observable o);

// The orbit of one initial point at r, after `transient` steps, as the states' angles and symbols of
// `length` consecutive steps (batched kernel, double).  Memory is checked up front.
struct OrbitSeries {
  std::vector<double> theta, phi;  // angles of the states
  std::vector<std::uint8_t> symbol;  // symbol of the step that produced each state
};
OrbitSeries orbit_series(double r, const iterate::Vec3<double>& u0, long transient, long length);

// The values of an observable along a recorded orbit, optionally composed with f (user function).
std::vector<double> observe(const OrbitSeries& s, Observable o, const std::function<double(double)>& f = {});

// ---- Correlation functions -----------------------------------------------------------------------
// C_N(phi, psi; n) = (1/N) sum_{k<N} phi_k psi_{k+n} - (1/N sum_{k<N} phi_k)(1/N sum_{k<N} psi_k), n = 0..n_max
// (Section 7 (2)).  Needs phi.size() >= N and psi.size() >= N + n_max; throws std::invalid_argument naming
// the field otherwise (n_max must be < N).
std::vector<double> correlation_direct(const std::vector<double>& phi, const std::vector<double>& psi, long N, long n_max);

// The same by FFT: phi_{0..N-1} and psi_{0..N+n_max-1} zero-padded to L >= N + n_max (no wrap-around for lags
// 0..n_max), c = IFFT(conj(FFT phi) FFT psi) / L.  Real-to-complex transforms; plans are made once per size
// and reused (one plan per object), planner calls behind one process-wide mutex (FFTW's planner is not
// thread-safe; execution is).  Precision: double.
class Correlator {
 public:
  Correlator();
  ~Correlator();
  Correlator(const Correlator&) = delete;
  Correlator& operator=(const Correlator&) = delete;
  std::vector<double> correlation(const std::vector<double>& phi, const std::vector<double>& psi, long N, long n_max);
  // Power spectrum |FFT(x - mean)|^2 / N of x_0..x_{N-1}, frequencies k/N, k = 0..N/2.
  std::vector<double> power_spectrum(const std::vector<double>& x, long N);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The decay of |C_N(n)|: least-squares slope of log(max |C_N| over windows of `window` lags) against n, over
// lags 1..n_fit.  rate > 0 means exponential decay exp(-rate n); ~0 means no decay.
struct Decay {
  double rate = 0, rate_error = 0;
  double envelope_first = 0, envelope_last = 0;  // max |C_N| over the first and the last window
};
Decay fit_decay(const std::vector<double>& c, long n_fit, long window);

// ---- Empirical measures --------------------------------------------------------------------------
// A 2-D histogram with weights 1/N: in the strip (u = atan(w1) in (-pi/2, pi/2), v = w2 in [-1, 1]) or in
// the angles (u = theta in [0, pi/2], v = phi in [0, pi]).
enum class Chart { strip, angles };
struct Measure {
  Chart chart = Chart::strip;
  int bins_u = 0, bins_v = 0;
  double u_lo = 0, u_hi = 0, v_lo = 0, v_hi = 0;
  std::vector<double> mass;  // bins_u * bins_v, row-major in u; sums to 1
  long points = 0;
  std::vector<double> marginal_u() const;
  std::vector<double> marginal_v() const;
};
Measure empirical_measure(const OrbitSeries& s, Chart chart, int bins_u, int bins_v, long first = 0, long count = -1);

double total_variation(const Measure& a, const Measure& b);  // (1/2) sum |a - b| over bins, in [0, 1]
// 1-D Wasserstein distance of two marginals on the same bins: sum |F_a - F_b| * bin width.
double wasserstein_1d(const std::vector<double>& a, const std::vector<double>& b, double lo, double hi);

}  // namespace btob::stats
