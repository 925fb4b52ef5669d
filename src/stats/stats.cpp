// Observables, correlation functions (direct and FFTW) and empirical measures along orbits of P_r.
#include "stats/stats.hpp"

#include "core/coords.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace btob::stats {

Observable parse_observable(const std::string& name, const char* field) {
  static const std::map<std::string, Observable> m = {
      {"theta", Observable::theta},     {"phi", Observable::phi},         {"w1", Observable::w1},
      {"w2", Observable::w2},           {"cos-phi", Observable::cos_phi}, {"symbol1", Observable::symbol1},
      {"symbol2", Observable::symbol2}, {"symbol3", Observable::symbol3}};
  const auto it = m.find(name);
  if (it == m.end())
    throw std::invalid_argument(fmt::format(
        "{}: got '{}', expected theta, phi, w1, w2, cos-phi, symbol1, symbol2 or symbol3", field, name));
  return it->second;
}

std::string observable_name(Observable o) {
  switch (o) {
    case Observable::theta: return "theta";
    case Observable::phi: return "phi";
    case Observable::w1: return "w1";
    case Observable::w2: return "w2";
    case Observable::cos_phi: return "cos-phi";
    case Observable::symbol1: return "symbol1";
    case Observable::symbol2: return "symbol2";
    case Observable::symbol3: return "symbol3";
  }
  return "?";
}

OrbitSeries orbit_series(double r, const iterate::Vec3<double>& u0, long transient, long length) {
  core::validate_r(r, "r");
  core::validate_point(u0(0), u0(1), u0(2), "point");
  if (transient < 0) throw std::invalid_argument(fmt::format("transient: got {}, expected >= 0", transient));
  if (length < 1) throw std::invalid_argument(fmt::format("iterations: got {}, expected >= 1", length));
  iterate::checked_bytes(static_cast<std::size_t>(length), 2 * sizeof(double) + 1, "iterations");
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {u0};
  const long total = transient + length;
  iterate::TailRecorder th(iterate::Coord::theta, 1, total, length), ph(iterate::Coord::phi, 1, total, length);
  iterate::Both<iterate::TailRecorder, iterate::TailRecorder> both(th, ph);
  iterate::run<double>(e, total, both);
  iterate::SymbolRecorder sy(1, transient + 1, total);
  iterate::run<double>(e, total, sy);  // the same orbit, bit for bit (deterministic kernel)
  return {std::move(th.out), std::move(ph.out), std::move(sy.out)};
}

std::vector<double> observe(const OrbitSeries& s, Observable o, const std::function<double(double)>& f) {
  std::vector<double> v(s.theta.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    double x = 0;
    switch (o) {
      case Observable::theta: x = s.theta[k]; break;
      case Observable::phi: x = s.phi[k]; break;
      case Observable::cos_phi: x = std::cos(s.phi[k]); break;
      case Observable::w1:
      case Observable::w2: {
        const auto u = core::from_angles<double>(s.theta[k], s.phi[k]);
        const auto [w1, w2] = core::strip<double>(u);
        x = o == Observable::w1 ? w1 : w2;
        break;
      }
      case Observable::symbol1: x = s.symbol[k] == 1; break;
      case Observable::symbol2: x = s.symbol[k] == 2; break;
      case Observable::symbol3: x = s.symbol[k] == 3; break;
    }
    v[k] = f ? f(x) : x;
  }
  return v;
}

namespace {
void check_lengths(const std::vector<double>& phi, const std::vector<double>& psi, long N, long n_max) {
  if (N < 1) throw std::invalid_argument(fmt::format("iterations: got N = {}, expected N >= 1", N));
  if (n_max < 0 || n_max >= N)
    throw std::invalid_argument(fmt::format("n-max: got {}, expected 0 <= n-max < N = {}", n_max, N));
  if (static_cast<long>(phi.size()) < N || static_cast<long>(psi.size()) < N + n_max)
    throw std::invalid_argument(fmt::format("series: got {} and {} values, expected at least N = {} and N + n-max = {}",
                                            phi.size(), psi.size(), N, N + n_max));
}
double mean(const std::vector<double>& x, long N) {
  // Pairwise-free but compensated (Neumaier) so that 1e6-term means are accurate to ~1e-16 relative.
  double s = 0, c = 0;
  for (long k = 0; k < N; ++k) {
    const double t = s + x[k];
    c += std::fabs(s) >= std::fabs(x[k]) ? (s - t) + x[k] : (x[k] - t) + s;
    s = t;
  }
  return (s + c) / static_cast<double>(N);
}
}  // namespace

std::vector<double> correlation_direct(const std::vector<double>& phi, const std::vector<double>& psi, long N, long n_max) {
  check_lengths(phi, psi, N, n_max);
  const double mp = mean(phi, N), mq = mean(psi, N);
  std::vector<double> c(static_cast<std::size_t>(n_max + 1));
  for (long n = 0; n <= n_max; ++n) {
    double s = 0;
    for (long k = 0; k < N; ++k) s += phi[k] * psi[k + n];
    c[n] = s / static_cast<double>(N) - mp * mq;
  }
  return c;
}

namespace {
std::mutex& planner_mutex() {  // one process-wide lock for FFTW's planner
  static std::mutex m;
  return m;
}
// Smallest 2^a 3^b 5^c >= n (FFTW is fastest on such sizes).
long fast_size(long n) {
  long best = 1;
  while (best < n) best *= 2;
  for (long p2 = 1; p2 < best; p2 *= 2)
    for (long p3 = p2; p3 < best; p3 *= 3)
      for (long p5 = p3; p5 < best; p5 *= 5)
        if (p5 >= n && p5 < best) best = p5;
  return best;
}
struct Plan {
  long L = 0;
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan fwd = nullptr, inv = nullptr;
  explicit Plan(long L_) : L(L_) {
    std::lock_guard<std::mutex> lock(planner_mutex());
    in = fftw_alloc_real(static_cast<std::size_t>(L));
    out = fftw_alloc_complex(static_cast<std::size_t>(L / 2 + 1));
    if (!in || !out) throw std::length_error(fmt::format("series: FFT of length {} does not fit in memory", L));
    fwd = fftw_plan_dft_r2c_1d(static_cast<int>(L), in, out, FFTW_ESTIMATE);
    inv = fftw_plan_dft_c2r_1d(static_cast<int>(L), out, in, FFTW_ESTIMATE);
  }
  ~Plan() {
    std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(inv);
    fftw_free(in);
    fftw_free(out);
  }
};
}  // namespace

struct Correlator::Impl {
  std::map<long, std::unique_ptr<Plan>> plans;  // reused across orbits of the same length
  Plan& plan(long L) {
    auto& p = plans[L];
    if (!p) p = std::make_unique<Plan>(L);
    return *p;
  }
};

Correlator::Correlator() : impl_(std::make_unique<Impl>()) {}
Correlator::~Correlator() = default;

std::vector<double> Correlator::correlation(const std::vector<double>& phi, const std::vector<double>& psi, long N,
                                            long n_max) {
  check_lengths(phi, psi, N, n_max);
  const long L = fast_size(N + n_max);
  Plan& p = impl_->plan(L);
  const long H = L / 2 + 1;
  // Centring both series by their means over k < N before transforming keeps the products small, so the
  // FFT's rounding (eps * sum |phi| |psi|) stays relative to the covariance, not to the raw second moment.
  const double mp = mean(phi, N), mq = mean(psi, N);
  std::vector<std::complex<double>> A(static_cast<std::size_t>(H));
  std::fill(p.in, p.in + L, 0.0);
  for (long k = 0; k < N; ++k) p.in[k] = phi[k] - mp;
  fftw_execute_dft_r2c(p.fwd, p.in, p.out);
  for (long j = 0; j < H; ++j) A[j] = {p.out[j][0], p.out[j][1]};
  std::fill(p.in, p.in + L, 0.0);
  for (long k = 0; k < N + n_max; ++k) p.in[k] = psi[k] - mq;
  fftw_execute_dft_r2c(p.fwd, p.in, p.out);
  for (long j = 0; j < H; ++j) {
    const std::complex<double> v = std::conj(A[j]) * std::complex<double>(p.out[j][0], p.out[j][1]);
    p.out[j][0] = v.real();
    p.out[j][1] = v.imag();
  }
  fftw_execute_dft_c2r(p.inv, p.out, p.in);  // unnormalised: multiply by 1/L
  // sum_{k<N} (phi_k - mp)(psi_{k+n} - mq) = sum phi_k psi_{k+n} - mq sum phi_k - mp sum_{k<N} psi_{k+n} + N mp mq
  //   = N C_N(n) + N mp mq - mp sum_{k<N} psi_{k+n} ... corrected below with the running window sums of psi.
  std::vector<double> c(static_cast<std::size_t>(n_max + 1));
  double window = 0;  // sum_{k<N} (psi_{k+n} - mq), updated as n grows
  for (long k = 0; k < N; ++k) window += psi[k] - mq;
  for (long n = 0; n <= n_max; ++n) {
    const double centred = p.in[n] / static_cast<double>(L);  // sum_{k<N} (phi_k - mp)(psi_{k+n} - mq)
    // sum phi_k psi_{k+n} / N - mp mq = centred / N + mp * window / N  (the mq terms cancel)
    c[n] = centred / static_cast<double>(N) + mp * window / static_cast<double>(N);
    if (n < n_max) window += (psi[n + N] - mq) - (psi[n] - mq);
  }
  return c;
}

std::vector<double> Correlator::power_spectrum(const std::vector<double>& x, long N) {
  if (N < 2 || static_cast<long>(x.size()) < N)
    throw std::invalid_argument(fmt::format("series: got {} values for N = {}, expected N >= 2 values", x.size(), N));
  Plan& p = impl_->plan(N);
  const double m = mean(x, N);
  for (long k = 0; k < N; ++k) p.in[k] = x[k] - m;
  fftw_execute_dft_r2c(p.fwd, p.in, p.out);
  std::vector<double> s(static_cast<std::size_t>(N / 2 + 1));
  for (long j = 0; j <= N / 2; ++j) s[j] = (p.out[j][0] * p.out[j][0] + p.out[j][1] * p.out[j][1]) / static_cast<double>(N);
  return s;
}

Decay fit_decay(const std::vector<double>& c, long n_fit, long window) {
  if (window < 1 || n_fit < 2 * window || static_cast<long>(c.size()) <= n_fit)
    throw std::invalid_argument(fmt::format("n-fit: got {} with window {} for {} lags, expected 2 window <= n-fit < lags",
                                            n_fit, window, c.size()));
  // Envelope: max |C_N| over consecutive windows of lags 1.., then a least-squares line through log(envelope).
  std::vector<double> xs, ys;
  for (long start = 1; start + window <= n_fit + 1; start += window) {
    double m = 0;
    for (long n = start; n < start + window; ++n) m = std::max(m, std::fabs(c[n]));
    xs.push_back(static_cast<double>(start) + 0.5 * static_cast<double>(window - 1));
    ys.push_back(std::log(std::max(m, 1e-300)));
  }
  const double n = static_cast<double>(xs.size());
  const double mx = std::accumulate(xs.begin(), xs.end(), 0.0) / n, my = std::accumulate(ys.begin(), ys.end(), 0.0) / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sxx += (xs[i] - mx) * (xs[i] - mx);
    sxy += (xs[i] - mx) * (ys[i] - my);
  }
  const double slope = sxy / sxx;
  double sse = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) sse += std::pow(ys[i] - my - slope * (xs[i] - mx), 2);
  Decay d;
  d.rate = -slope;
  d.rate_error = xs.size() > 2 ? std::sqrt(sse / (n - 2) / sxx) : 0;
  d.envelope_first = std::exp(ys.front());
  d.envelope_last = std::exp(ys.back());
  return d;
}

std::vector<double> Measure::marginal_u() const {
  std::vector<double> m(static_cast<std::size_t>(bins_u), 0);
  for (int i = 0; i < bins_u; ++i)
    for (int j = 0; j < bins_v; ++j) m[i] += mass[static_cast<std::size_t>(i) * bins_v + j];
  return m;
}
std::vector<double> Measure::marginal_v() const {
  std::vector<double> m(static_cast<std::size_t>(bins_v), 0);
  for (int i = 0; i < bins_u; ++i)
    for (int j = 0; j < bins_v; ++j) m[j] += mass[static_cast<std::size_t>(i) * bins_v + j];
  return m;
}

Measure empirical_measure(const OrbitSeries& s, Chart chart, int bins_u, int bins_v, long first, long count) {
  if (bins_u < 1 || bins_v < 1 || bins_u > 100000 || bins_v > 100000)
    throw std::invalid_argument(fmt::format("bins: got {}x{}, expected 1..100000 in each direction", bins_u, bins_v));
  const long n_all = static_cast<long>(s.theta.size());
  if (count < 0) count = n_all - first;
  if (first < 0 || count < 1 || first + count > n_all)
    throw std::invalid_argument(fmt::format("iterations: got points [{}, {}) of {}, expected a non-empty range", first,
                                            first + count, n_all));
  Measure m;
  m.chart = chart;
  m.bins_u = bins_u;
  m.bins_v = bins_v;
  if (chart == Chart::strip) {
    m.u_lo = -std::numbers::pi / 2, m.u_hi = std::numbers::pi / 2, m.v_lo = -1, m.v_hi = 1;
  } else {
    m.u_lo = 0, m.u_hi = std::numbers::pi / 2, m.v_lo = 0, m.v_hi = std::numbers::pi;
  }
  m.mass.assign(static_cast<std::size_t>(bins_u) * bins_v, 0);
  m.points = count;
  const double w = 1.0 / static_cast<double>(count);
  for (long k = first; k < first + count; ++k) {
    double u, v;
    if (chart == Chart::strip) {
      const auto [w1, w2] = core::strip<double>(core::from_angles<double>(s.theta[k], s.phi[k]));
      u = std::atan(w1);
      v = w2;
    } else {
      u = s.theta[k];
      v = s.phi[k];
    }
    const int i = std::clamp(static_cast<int>((u - m.u_lo) / (m.u_hi - m.u_lo) * bins_u), 0, bins_u - 1);
    const int j = std::clamp(static_cast<int>((v - m.v_lo) / (m.v_hi - m.v_lo) * bins_v), 0, bins_v - 1);
    m.mass[static_cast<std::size_t>(i) * bins_v + j] += w;
  }
  return m;
}

double total_variation(const Measure& a, const Measure& b) {
  if (a.bins_u != b.bins_u || a.bins_v != b.bins_v || a.chart != b.chart)
    throw std::invalid_argument("measure: the two measures must use the same chart and bins");
  double s = 0;
  for (std::size_t i = 0; i < a.mass.size(); ++i) s += std::fabs(a.mass[i] - b.mass[i]);
  return 0.5 * s;
}

double wasserstein_1d(const std::vector<double>& a, const std::vector<double>& b, double lo, double hi) {
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("marginal: expected two marginals on the same bins");
  const double dx = (hi - lo) / static_cast<double>(a.size());
  double fa = 0, fb = 0, s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    fa += a[i];
    fb += b[i];
    s += std::fabs(fa - fb) * dx;
  }
  return s;
}

}  // namespace btob::stats
