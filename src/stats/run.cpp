// SPDX-License-Identifier: GPL-3.0-or-later
// The stats requests' runs: C_N by the chosen route and precision, the measures over a grid (run_part, merge), and the
// work estimates.
#include "stats/request_detail.hpp"
#include "stats/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace btob::stats {

namespace {
// C_N in precision T by the chosen route; the result in double.
template <class T>
std::vector<double> correlate_in(const std::vector<double>& x, const std::vector<double>& y, long N, long n_max,
                                 bool fft, const core::CancelToken* cancel) {
  // The series in T, copied 2^20 values at a time between polls (a second for two series of 6e7 values).
  const auto in_t = [cancel](const std::vector<double>& v) {
    constexpr std::size_t block = std::size_t(1) << 20;
    std::vector<T> out;
    out.reserve(v.size());
    for (std::size_t lo = 0; lo < v.size(); lo += block) {
      core::check_cancel(cancel);
      const std::size_t hi = std::min(v.size(), lo + block);
      out.insert(out.end(), v.begin() + static_cast<long>(lo), v.begin() + static_cast<long>(hi));
    }
    return out;
  };
  const std::vector<T> a = in_t(x), b = in_t(y);
  std::vector<T> c;
  if (fft) {
    Correlator<T> corr(N, n_max, cancel);
    c = corr(a, b, cancel);
  } else {
    c = correlation_direct(a, b, N, n_max, cancel);
  }
  return {c.begin(), c.end()};
}
std::vector<double> correlate_as(const std::string& precision, const std::vector<double>& x,
                                 const std::vector<double>& y, long N, long n_max, bool fft,
                                 const core::CancelToken* cancel) {
  if (precision == "float") return correlate_in<float>(x, y, N, n_max, fft, cancel);
  if (precision == "long-double") return correlate_in<long double>(x, y, N, n_max, fft, cancel);
  return correlate_in<double>(x, y, N, n_max, fft, cancel);
}

// The periodogram of x (first N values), averaged over blocks of consecutive frequencies to at most 8192 points
// so that the stored file stays small; returns the frequency of the unaveraged peak.
double spectrum(const std::vector<double>& x, long N, std::vector<double>& freq, std::vector<double>& power,
                const core::CancelToken* cancel) {
  Periodogram<double> pg(N, cancel);
  const std::vector<double> spec = pg(x, cancel);
  const std::size_t per = (spec.size() + 8191) / 8192;
  for (std::size_t j = 1; j < spec.size(); j += per) {  // j = 0 (the mean) is zero after centring
    const std::size_t e = std::min(spec.size(), j + per);
    double sum = 0;
    for (std::size_t i = j; i < e; ++i) sum += spec[i];
    freq.push_back(0.5 * static_cast<double>(j + e - 1) / static_cast<double>(N));
    power.push_back(sum / static_cast<double>(e - j));
  }
  const auto peak = std::max_element(spec.begin() + 1, spec.end()) - spec.begin();
  return static_cast<double>(peak) / static_cast<double>(N);
}
}  // namespace

namespace {
// The probe of both routes: the default orbit (r = 0.11 from the first point of the Section 4 grid) with 200 lags.
double correlate_probe(const std::string& precision, const std::string& method, long iterations,
                       const core::RunControl& c) {
  CorrelateRequest p;
  p.precision = precision;
  p.method = method;
  p.transient = 0;
  p.n_max = 200;
  p.fit_lags = 200;
  p.iterations = std::max(iterations, 100000L);  // FFTW's planning and the fit amortised, as in a long run
  (void)run(p, c);
  return method == "fft" ? static_cast<double>(p.iterations + p.n_max)
                         : static_cast<double>(p.iterations) * static_cast<double>(p.n_max + 1);
}
}  // namespace

core::Work work(const CorrelateRequest& req) {
  const double N = static_cast<double>(req.iterations), M = static_cast<double>(req.n_max);
  core::Work w;
  core::Term orbit;
  orbit.route = "correlate orbit and fft " + req.precision;
  orbit.units = static_cast<double>(req.transient) + N + M;
  orbit.what =
      "map steps of one orbit in double (transient + iterations + n-max), priced with its FFT correlation "
      "(O(N log N)) and spectrum by the probe";
  orbit.probe = [precision = req.precision](double n, const core::RunControl& c) {
    return correlate_probe(precision, "fft", static_cast<long>(n), c);
  };
  w.terms.push_back(orbit);
  if (req.method != "fft") {
    core::Term direct;
    direct.route = "correlate direct sum " + req.precision;
    direct.units = N * (M + 1);
    direct.what = "products of the direct sum (iterations x (n-max + 1))";
    direct.probe = [precision = req.precision](double n, const core::RunControl& c) {
      return correlate_probe(precision, "direct", static_cast<long>(n / 201), c);  // at least 1e5 x 201 products
    };
    w.terms.push_back(direct);
  }
  // C_N, its envelope and fit per lag in NAME.h5 and NAME.csv (~110 bytes a lag), the binned spectrum; the run holds
  // the orbit's states, the two observables and the FFT's padded complex buffers (~90 bytes a state).
  w.output_bytes = 110 * (M + 1) + 16384;
  w.peak_bytes = 90 * (N + M) + 65536;
  return w;
}

CorrelateResult run(const CorrelateRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  CorrelateResult res;
  res.request = req;
  std::tie(res.phi, res.psi) = detail::observables(req.observable);
  const long N = req.iterations, M = req.n_max;
  iterate::RunOptions opt;  // one orbit: one thread, cancellable between batches
  opt.threads = 1;
  opt.cancel = control.cancel;
  const OrbitSeries s =
      std::move(orbit_series(req.r, {core::parse_point(req.point, "point")}, req.transient, N + M, opt)[0]);
  const auto x = observe(s, res.phi, {}, control.cancel), y = observe(s, res.psi, {}, control.cancel);
  core::check_cancel(control.cancel);
  auto t0 = std::chrono::steady_clock::now();
  res.c = correlate_as(req.precision, x, y, N, M, req.method != "direct", control.cancel);
  res.seconds = core::seconds_since(t0);
  if (req.method == "both") {
    core::check_cancel(control.cancel);
    t0 = std::chrono::steady_clock::now();
    res.c_direct = correlate_as(req.precision, x, y, N, M, false, control.cancel);
    res.seconds_direct = core::seconds_since(t0);
    double scale = 0;
    for (std::size_t n = 0; n < res.c.size(); ++n) {
      scale = std::max(scale, std::fabs(res.c_direct[n]));
      res.max_rel_diff = std::max(res.max_rel_diff, std::fabs(res.c[n] - res.c_direct[n]));
    }
    res.max_rel_diff = scale > 0 ? res.max_rel_diff / scale : res.max_rel_diff;
  }
  res.peak_frequency = spectrum(x, N, res.frequency, res.power, control.cancel);
  // Noise floor of C_N(n) for uncorrelated values: ~|C_N(0)| / sqrt(N); the fit stops at 4 times that.
  res.noise_floor = 4 * std::fabs(res.c[0]) / std::sqrt(static_cast<double>(N));
  res.envelope = envelope(res.c, req.window);
  res.fitted = M >= req.fit_lags && req.fit_lags >= 3 * req.window;
  if (res.fitted) res.decay = fit_decay(res.c, req.fit_lags, req.window, res.noise_floor);
  return res;
}

namespace {
// Groups of coinciding measures: each group's head (first member) and size.
void group_heads(MeasureResult& res, std::size_t count) {
  const int G = *std::max_element(res.group.begin(), res.group.end()) + 1;
  res.head.assign(static_cast<std::size_t>(G), count);
  res.size.assign(static_cast<std::size_t>(G), 0);
  for (std::size_t i = 0; i < count; ++i) {
    if (res.head[res.group[i]] == count) res.head[res.group[i]] = i;
    ++res.size[res.group[i]];
  }
  res.group_index.assign(res.group.begin(), res.group.end());
}

// Per initial condition: distances to the first member of its group (the paper's test: measures of orbits in one
// basin coincide), and the largest distance within each group.
void distances(MeasureResult& res, const std::vector<Measure>& ms) {
  const std::size_t n = ms.size();
  res.tv.resize(n);
  res.w1_u.resize(n);
  res.w1_v.resize(n);
  res.tv_max_group.assign(res.groups(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int g = res.group[i];
    const auto& h = ms[res.head[g]];
    res.tv[i] = total_variation(ms[i], h);
    res.w1_u[i] = wasserstein_1d(ms[i].marginal_u(), h.marginal_u(), h.u_lo, h.u_hi);
    res.w1_v[i] = wasserstein_1d(ms[i].marginal_v(), h.marginal_v(), h.v_lo, h.v_hi);
    for (std::size_t j = 0; j < i; ++j)
      if (res.group[j] == g) res.tv_max_group[g] = std::max(res.tv_max_group[g], total_variation(ms[i], ms[j]));
  }
}

// Convergence against N: at N = 16, 32, ..., the largest TV within each group between mu_N of its members and
// mu_N of its first member, and the TV between mu_N of the first member and its mu at the full length.
template <class MeasureOf> void convergence(MeasureResult& res, const std::vector<Measure>& ms, MeasureOf measure) {
  const MeasureRequest& a = res.request;
  const std::size_t G = res.groups();
  std::vector<long> checkpoints;
  for (long n = 16; n < a.iterations; n *= 2) checkpoints.push_back(n);
  checkpoints.push_back(a.iterations);
  for (const long n : checkpoints) {
    res.conv_n.push_back(static_cast<double>(n));
    std::vector<Measure> heads;
    for (std::size_t g = 0; g < G; ++g) heads.push_back(measure(res.head[g], n));
    std::vector<double> within(G, 0);
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const int g = res.group[i];
      if (i != res.head[g]) within[g] = std::max(within[g], total_variation(measure(i, n), heads[g]));
    }
    for (std::size_t g = 0; g < G; ++g) {
      res.conv_within.push_back(within[g]);
      res.conv_to_full.push_back(total_variation(heads[g], ms[res.head[g]]));
    }
  }
}
}  // namespace

std::size_t MeasureRequest::work_items() const { return iterate::parse_grid(grid, seed, "grid").size(); }

MeasurePart run_part(const MeasureRequest& req, const std::vector<std::size_t>& items,
                     const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  MeasurePart p;
  p.items = items;
  if (items.empty()) return p;  // a rank without initial conditions
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<iterate::Vec3<double>> grid = iterate::parse_grid(req.grid, req.seed, "grid");
  std::vector<iterate::Vec3<double>> mine;  // each orbit on its own: the same for any other orbits in the run
  for (std::size_t i : items) mine.push_back(grid.at(i));
  iterate::RunOptions opt;
  opt.threads = control.threads;
  opt.progress = control.progress;
  opt.cancel = control.cancel;
  const Measure frame = measure_frame(parse_chart(req.coords, "coords"), req.bins, req.bins, req.extent);
  std::vector<OrbitSeries> series = orbit_series(req.r, mine, req.transient, req.iterations, opt);
  core::check_cancel(control.cancel);
  p.cells.reserve(items.size() * static_cast<std::size_t>(req.iterations));
  for (auto& s : series) {
    const std::vector<std::int32_t> c = measure_cells(s, frame, req.extent.empty());
    p.cells.insert(p.cells.end(), c.begin(), c.end());
    s = OrbitSeries{};  // free each orbit once binned
  }
  p.seconds = core::seconds_since(t0);
  return p;
}

MeasureResult merge(const MeasureRequest& req, std::vector<MeasurePart> parts) {
  req.validate();
  MeasureResult res;
  res.request = req;
  res.initial = iterate::parse_grid(req.grid, req.seed, "grid");
  const std::size_t I = res.initial.size(), N = static_cast<std::size_t>(req.iterations);
  const auto order = core::item_order(parts, I);
  const std::vector<std::int32_t> cells = core::merge_rows<MeasurePart, std::int32_t>(
      parts, order, N, [](const MeasurePart& p) -> const std::vector<std::int32_t>& { return p.cells; });
  parts.clear();
  const Measure frame = measure_frame(parse_chart(req.coords, "coords"), req.bins, req.bins, req.extent);
  // Measure of the first n points of orbit i: bitwise empirical_measure(series i, ..., 0, n).
  const auto measure = [&](std::size_t i, long n) { return measure_of_cells(frame, cells.data() + i * N, n); };
  std::vector<Measure> ms;
  for (std::size_t i = 0; i < I; ++i) ms.push_back(measure(i, req.iterations));
  res.group = group_measures(ms, req.tv_same);
  group_heads(res, ms.size());
  distances(res, ms);
  convergence(res, ms, measure);
  for (std::size_t g = 0; g < res.groups(); ++g) {
    const auto& m = ms[res.head[g]];
    for (double v : m.mass)
      res.counts.push_back(static_cast<std::uint32_t>(std::llround(v * static_cast<double>(m.points))));
    const auto mu = m.marginal_u(), mv = m.marginal_v();
    res.outside.push_back(m.outside);
    res.marginal_u.insert(res.marginal_u.end(), mu.begin(), mu.end());
    res.marginal_v.insert(res.marginal_v.end(), mv.begin(), mv.end());
  }
  res.extent = {ms[0].u_lo, ms[0].u_hi, ms[0].v_lo, ms[0].v_hi};
  return res;
}

MeasureResult run(const MeasureRequest& req, const core::RunControl& control) {
  return merge(req, {run_part(req, core::all_items(req), control)});
}

}  // namespace btob::stats
