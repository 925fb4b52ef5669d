// `btob correlate` (C_N along one orbit) and `btob measure` (empirical measures of many initial
// conditions, their distances and convergence), Section 8.1 (2).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "io/io.hpp"
#include "iterate/ensemble.hpp"
#include "stats/stats.hpp"

#include <btob/build_info.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <omp.h>
#include <sstream>

namespace btob::cli {
namespace {

struct CorrelateArgs {
  double r = 0.11;
  std::string point = "1,-3,-1.1";  // the first point of the Section 4 grid
  std::string observable = "phi";
  long n_max = 1000, iterations = 100000, transient = 10000;
  std::string method = "fft", precision = "double";
  long window = 10, fit_lags = 200;
  std::string out = "results/stats", name = "correlation";
  bool no_plot = false;
};

iterate::Vec3<double> parse_point(const std::string& text) {
  const auto pts = iterate::parse_grid(text, 0, "point");
  if (pts.size() != 1) throw UsageError(fmt::format("point: got '{}', expected one point x,y,z", text));
  return pts[0];
}

// C_N in precision T by the chosen route(s); the result in double for output.
template <class T>
std::vector<double> correlate_in(const std::vector<double>& x, const std::vector<double>& y, long N, long n_max, bool fft) {
  const std::vector<T> a(x.begin(), x.end()), b(y.begin(), y.end());
  std::vector<T> c;
  if (fft) {
    stats::Correlator<T> corr(N, n_max);
    c = corr(a, b);
  } else {
    c = stats::correlation_direct(a, b, N, n_max);
  }
  return {c.begin(), c.end()};
}
std::vector<double> correlate_as(const std::string& precision, const std::vector<double>& x, const std::vector<double>& y,
                                 long N, long n_max, bool fft) {
  if (precision == "float") return correlate_in<float>(x, y, N, n_max, fft);
  if (precision == "long-double") return correlate_in<long double>(x, y, N, n_max, fft);
  return correlate_in<double>(x, y, N, n_max, fft);
}

void correlate(const CorrelateArgs& a) {
  // Everything is validated before any output is created.
  core::validate_r(a.r, "r");
  const auto u0 = parse_point(a.point);
  const auto comma = a.observable.find(',');
  const stats::Observable phi = stats::parse_observable(a.observable.substr(0, comma));
  const stats::Observable psi =
      comma == std::string::npos ? phi : stats::parse_observable(a.observable.substr(comma + 1));
  if (a.iterations < 2) throw UsageError(fmt::format("iterations: got {}, expected at least 2", a.iterations));
  if (a.n_max < 0 || a.n_max >= a.iterations)
    throw UsageError(fmt::format("n-max: got {}, expected 0 <= n-max < iterations = {}", a.n_max, a.iterations));
  if (a.transient < 0) throw UsageError(fmt::format("transient: got {}, expected >= 0", a.transient));
  if (a.method != "fft" && a.method != "direct" && a.method != "both")
    throw UsageError(fmt::format("method: got '{}', expected fft, direct or both", a.method));
  if (a.precision != "float" && a.precision != "double" && a.precision != "long-double")
    throw UsageError(fmt::format("precision: got '{}', expected float, double or long-double", a.precision));
  if (a.window < 1) throw UsageError(fmt::format("window: got {}, expected >= 1", a.window));
  if (a.fit_lags < a.window)
    throw UsageError(fmt::format("fit-lags: got {}, expected >= window = {}", a.fit_lags, a.window));
  const long N = a.iterations, M = a.n_max;
  iterate::checked_bytes(static_cast<std::size_t>(N + M), 3 * sizeof(double) + 1 + 4 * sizeof(double), "iterations");
  const io::fs::path out(a.out);
  io::ensure_dir(out);

  const stats::OrbitSeries s = stats::orbit_series(a.r, u0, a.transient, N + M);  // N + n_max states
  const auto x = stats::observe(s, phi), y = stats::observe(s, psi);
  const auto clock = [] { return std::chrono::steady_clock::now(); };
  std::vector<double> c, c_other;
  auto t0 = clock();
  c = correlate_as(a.precision, x, y, N, M, a.method != "direct");
  const double secs = std::chrono::duration<double>(clock() - t0).count();
  double secs_direct = 0, max_rel = 0;
  if (a.method == "both") {
    t0 = clock();
    c_other = correlate_as(a.precision, x, y, N, M, false);
    secs_direct = std::chrono::duration<double>(clock() - t0).count();
    double scale = 0;
    for (std::size_t n = 0; n < c.size(); ++n) {
      scale = std::max(scale, std::fabs(c_other[n]));
      max_rel = std::max(max_rel, std::fabs(c[n] - c_other[n]));
    }
    max_rel = scale > 0 ? max_rel / scale : max_rel;
  }
  // Periodogram of the first observable (first N values), averaged over blocks of consecutive frequencies
  // to at most 8192 points so that the stored file stays small.
  stats::Periodogram<double> pg(N);
  const std::vector<double> spec = pg(x);
  const std::size_t per = (spec.size() + 8191) / 8192;
  std::vector<double> freq, power;
  for (std::size_t j = 1; j < spec.size(); j += per) {  // j = 0 (the mean) is zero after centring
    const std::size_t e = std::min(spec.size(), j + per);
    double sum = 0;
    for (std::size_t i = j; i < e; ++i) sum += spec[i];
    freq.push_back(0.5 * static_cast<double>(j + e - 1) / static_cast<double>(N));
    power.push_back(sum / static_cast<double>(e - j));
  }
  const auto peak = std::max_element(spec.begin() + 1, spec.end()) - spec.begin();

  std::ostringstream csv;
  csv << fmt::format("# C_N({}, {}; n), r = {}, point {}, N = {}, transient {}, method {}, precision {}, btob {}\n",
                     stats::observable_name(phi), stats::observable_name(psi), a.r, a.point, N, a.transient, a.method,
                     a.precision, build::git_commit);
  csv << (a.method == "both" ? "lag,C_N,C_N_direct\n" : "lag,C_N\n");
  for (std::size_t n = 0; n < c.size(); ++n) {
    csv << n << "," << fmt::format("{:.17g}", c[n]);
    if (a.method == "both") csv << "," << fmt::format("{:.17g}", c_other[n]);
    csv << "\n";
  }
  io::write_text_atomic(out / (a.name + ".csv"), csv.str());

  io::Attrs attrs = io::provenance(invocation());
  attrs["r"] = a.r;
  attrs["point"] = a.point;
  attrs["observables"] = stats::observable_name(phi) + "," + stats::observable_name(psi);
  attrs["N"] = N;
  attrs["n_max"] = M;
  attrs["transient"] = a.transient;
  attrs["method"] = a.method;
  attrs["scalar_type"] = a.precision;
  attrs["seconds"] = secs;
  attrs["threads"] = static_cast<long>(omp_get_max_threads());
  if (a.method == "both") {
    attrs["seconds_direct"] = secs_direct;
    attrs["max_rel_diff_fft_direct"] = max_rel;
  }
  attrs["spectrum_peak_frequency"] = static_cast<double>(peak) / static_cast<double>(N);
  // Noise floor of C_N(n) for uncorrelated values: ~|C_N(0)| / sqrt(N); the fit stops at 4 times that.
  const double floor = 4 * std::fabs(c[0]) / std::sqrt(static_cast<double>(N));
  const std::vector<double> env = stats::envelope(c, a.window);
  attrs["noise_floor"] = floor;
  std::string decay_line;
  if (M >= a.fit_lags && a.fit_lags >= 3 * a.window) {
    const stats::Decay d = stats::fit_decay(c, a.fit_lags, a.window, floor);
    attrs["decay_rate"] = d.rate;
    attrs["decay_rate_error"] = d.rate_error;
    attrs["decay_windows"] = d.windows;
    attrs["decays"] = std::string(d.decays ? "yes" : "no");
    attrs["envelope_first"] = d.envelope_first;
    attrs["envelope_last"] = d.envelope_last;
    decay_line = fmt::format("fitted decay rate {:.4g} +- {:.2g} per iteration over {} windows of {} lags ({}decaying)",
                             d.rate, d.rate_error, d.windows, a.window, d.decays ? "" : "not ");
  }
  if (!env.empty()) {
    attrs["envelope_min"] = *std::min_element(env.begin(), env.end());
    attrs["envelope_max"] = *std::max_element(env.begin(), env.end());
  }
  {
    io::H5Writer w(out / (a.name + ".h5"));
    w.attrs(attrs);
    w.dataset("C_N", c, {c.size()});
    if (a.method == "both") w.dataset("C_N_direct", c_other, {c_other.size()});
    w.dataset("envelope", env, {env.size()});
    w.dataset("spectrum_frequency", freq, {freq.size()});
    w.dataset("power_spectrum", power, {power.size()});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  std::cerr << fmt::format("btob: C_N({}, {}; 0..{}) over N = {} in {:.3g} s ({}, {}); |C_N| window envelope {:.3g} .. {:.3g}",
                           stats::observable_name(phi), stats::observable_name(psi), M, N, secs, a.method, a.precision,
                           env.empty() ? 0.0 : std::get<double>(attrs["envelope_min"]),
                           env.empty() ? 0.0 : std::get<double>(attrs["envelope_max"]));
  if (!decay_line.empty()) std::cerr << "; " << decay_line;
  if (a.method == "both") std::cerr << fmt::format("; fft vs direct {:.2g} relative, direct {:.3g} s", max_rel, secs_direct);
  std::cerr << "\n";
  if (!a.no_plot) io::run_plot("stats_correlation.py", {(out / (a.name + ".h5")).string(), (out / (a.name + ".png")).string()});
}

struct MeasureArgs {
  double r = 0.15;
  std::string grid = "paper";
  std::uint64_t seed = 1;
  long iterations = 100000, transient = 10000;
  int bins = 200, threads = 0;
  double tv_same = 0.05;
  std::string coords = "strip";
  std::vector<double> extent;
  std::string out = "results/stats", name = "measure";
  bool no_plot = false;
};

void measure(const MeasureArgs& a) {
  core::validate_r(a.r, "r");
  if (a.iterations < 16) throw UsageError(fmt::format("iterations: got {}, expected at least 16", a.iterations));
  if (a.transient < 0) throw UsageError(fmt::format("transient: got {}, expected >= 0", a.transient));
  if (a.bins < 1 || a.bins > 4000) throw UsageError(fmt::format("bins: got {}, expected 1..4000", a.bins));
  if (!(a.tv_same > 0 && a.tv_same <= 1)) throw UsageError(fmt::format("tv-same: got {}, expected in (0, 1]", a.tv_same));
  const stats::Chart chart = stats::parse_chart(a.coords, "coords");
  if (!a.extent.empty() && (a.extent.size() != 4 || !(a.extent[0] < a.extent[1]) || !(a.extent[2] < a.extent[3])))
    throw UsageError(fmt::format("extent: got {} values, expected u_lo,u_hi,v_lo,v_hi with u_lo < u_hi, v_lo < v_hi",
                                 a.extent.size()));
  const auto ics = iterate::parse_grid(a.grid, a.seed, "grid");
  iterate::checked_bytes(ics.size() * static_cast<std::size_t>(a.bins) * a.bins, 2 * sizeof(double), "grid x bins^2");
  iterate::checked_bytes(2 * ics.size() * static_cast<std::size_t>(a.iterations), 3 * sizeof(double) + 1, "grid x iterations");
  const io::fs::path out(a.out);
  io::ensure_dir(out);

  const auto series = stats::orbit_series(a.r, ics, a.transient, a.iterations, a.threads);
  std::vector<stats::Measure> ms;
  for (const auto& s : series) ms.push_back(stats::empirical_measure(s, chart, a.bins, a.bins, 0, -1, a.extent));
  const std::vector<int> group = stats::group_measures(ms, a.tv_same);
  const int G = *std::max_element(group.begin(), group.end()) + 1;
  std::vector<std::size_t> head(static_cast<std::size_t>(G), ms.size()), size(static_cast<std::size_t>(G), 0);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    if (head[group[i]] == ms.size()) head[group[i]] = i;
    ++size[group[i]];
  }
  // Per initial condition: distances to the first member of its group (the paper's test: measures of
  // orbits in one basin coincide), and the largest distance within each group.
  std::vector<double> tv(ms.size()), w_u(ms.size()), w_v(ms.size()), tv_max_group(static_cast<std::size_t>(G), 0);
  std::ostringstream csv;
  csv << fmt::format("# empirical measures at r = {}, grid {} ({} initial conditions), {} iterations after {} transient, "
                     "{}x{} bins in the {} chart; groups: total variation < {}\n",
                     a.r, a.grid, ics.size(), a.iterations, a.transient, a.bins, a.bins, a.coords, a.tv_same);
  csv << "ic,x,y,z,group,tv_to_group_head,w1_u_to_group_head,w1_v_to_group_head\n";
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const auto& h = ms[head[group[i]]];
    tv[i] = stats::total_variation(ms[i], h);
    w_u[i] = stats::wasserstein_1d(ms[i].marginal_u(), h.marginal_u(), h.u_lo, h.u_hi);
    w_v[i] = stats::wasserstein_1d(ms[i].marginal_v(), h.marginal_v(), h.v_lo, h.v_hi);
    for (std::size_t j = 0; j < i; ++j)
      if (group[j] == group[i]) tv_max_group[group[i]] = std::max(tv_max_group[group[i]], stats::total_variation(ms[i], ms[j]));
    csv << fmt::format("{},{},{},{},{},{:.6g},{:.6g},{:.6g}\n", i, ics[i](0), ics[i](1), ics[i](2), group[i], tv[i], w_u[i],
                       w_v[i]);
  }
  io::write_text_atomic(out / (a.name + "_report.csv"), csv.str());
  // Convergence against N: at N = 16, 32, ..., the largest TV within each group between mu_N of its members
  // and mu_N of its first member, and the TV between mu_N of the first member and its mu at the full length.
  std::vector<double> conv_n, conv_within, conv_self;
  std::vector<long> checkpoints;
  for (long n = 16; n < a.iterations; n *= 2) checkpoints.push_back(n);
  checkpoints.push_back(a.iterations);
  for (const long n : checkpoints) {
    conv_n.push_back(static_cast<double>(n));
    std::vector<stats::Measure> heads;
    for (int g = 0; g < G; ++g) heads.push_back(stats::empirical_measure(series[head[g]], chart, a.bins, a.bins, 0, n, a.extent));
    std::vector<double> within(static_cast<std::size_t>(G), 0);
    for (std::size_t i = 0; i < ms.size(); ++i)
      if (i != head[group[i]])
        within[group[i]] = std::max(within[group[i]], stats::total_variation(
                                                          stats::empirical_measure(series[i], chart, a.bins, a.bins, 0, n, a.extent),
                                                          heads[group[i]]));
    for (int g = 0; g < G; ++g) {
      conv_within.push_back(within[g]);
      conv_self.push_back(stats::total_variation(heads[g], ms[head[g]]));
    }
  }
  std::vector<std::uint32_t> counts;  // per group head: counts per bin (mass * N)
  std::vector<double> marg_u, marg_v, outside;
  for (int g = 0; g < G; ++g) {
    const auto& m = ms[head[g]];
    for (double v : m.mass) counts.push_back(static_cast<std::uint32_t>(std::llround(v * static_cast<double>(m.points))));
    const auto mu = m.marginal_u(), mv = m.marginal_v();
    outside.push_back(m.outside);
    marg_u.insert(marg_u.end(), mu.begin(), mu.end());
    marg_v.insert(marg_v.end(), mv.begin(), mv.end());
  }
  io::Attrs attrs = io::provenance(invocation());
  attrs["r"] = a.r;
  attrs["grid"] = a.grid;
  attrs["seed"] = static_cast<long>(a.seed);
  attrs["iterations"] = a.iterations;
  attrs["transient"] = a.transient;
  attrs["bins"] = static_cast<long>(a.bins);
  attrs["coords"] = a.coords;
  attrs["tv_same"] = a.tv_same;
  attrs["initial_conditions"] = static_cast<long>(ics.size());
  attrs["groups"] = static_cast<long>(G);
  attrs["tv_max_within_groups"] = *std::max_element(tv_max_group.begin(), tv_max_group.end());
  attrs["scalar_type"] = std::string("double");
  const auto u64 = [](const std::vector<std::size_t>& v) { return std::vector<std::uint64_t>(v.begin(), v.end()); };
  const auto G_ = static_cast<std::size_t>(G), B = static_cast<std::size_t>(a.bins);
  {
    io::H5Writer w(out / (a.name + ".h5"));
    w.attrs(attrs);
    w.dataset("group_counts", counts, {G_, B, B});
    w.dataset("group_marginal_u", marg_u, {G_, B});
    w.dataset("group_marginal_v", marg_v, {G_, B});
    w.dataset("group_head", u64(head), {G_});
    w.dataset("group_size", u64(size), {G_});
    w.dataset("group_outside", outside, {G_});
    w.dataset("group_tv_max", tv_max_group, {G_});
    std::vector<std::uint64_t> gl(group.begin(), group.end());
    w.dataset("group", gl, {gl.size()});
    w.dataset("tv_to_group_head", tv, {tv.size()});
    w.dataset("w1_u_to_group_head", w_u, {w_u.size()});
    w.dataset("w1_v_to_group_head", w_v, {w_v.size()});
    w.dataset("convergence_n", conv_n, {conv_n.size()});
    w.dataset("convergence_tv_within_group", conv_within, {conv_n.size(), G_});
    w.dataset("convergence_tv_to_full", conv_self, {conv_n.size(), G_});
    w.dataset("extent", std::vector<double>{ms[0].u_lo, ms[0].u_hi, ms[0].v_lo, ms[0].v_hi}, {4});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  std::cerr << fmt::format("btob: {} initial conditions in {} group(s) (TV < {}); largest TV within a group {:.3g}\n",
                           ics.size(), G, a.tv_same, std::get<double>(attrs["tv_max_within_groups"]));
  if (!a.no_plot) io::run_plot("stats_measure.py", {(out / (a.name + ".h5")).string(), (out / (a.name + ".png")).string()});
}

Register reg([](CLI::App& app) {
  auto c = std::make_shared<CorrelateArgs>();
  CLI::App* cc = app.add_subcommand(
      "correlate", "C_N(phi, psi; n) = (1/N) sum_{k<N} phi(x_k) psi(x_{k+n}) - mean(phi) mean(psi), n = 0..n-max, along "
                   "one orbit (Section 8.1 (2)); writes NAME.csv (lag,C_N), NAME.h5 (C_N, envelope, power spectrum), "
                   "NAME.json, NAME.png");
  cc->add_option("--r", c->r, "restitution coefficient, in (0,1)")->capture_default_str();
  cc->add_option("--point", c->point, "initial point x,y,z (domain x*z <= 0; any scale)")->capture_default_str();
  cc->add_option("--observable", c->observable, "phi[,psi], each one of " + stats::observable_names() +
                                                    " (angles in rad; psi = phi when omitted)")->capture_default_str();
  cc->add_option("--n-max", c->n_max, "largest lag n, 0 <= n-max < iterations")->capture_default_str();
  cc->add_option("--iterations", c->iterations, "N, the number of terms averaged (the orbit has N + n-max states)")
      ->capture_default_str();
  cc->add_option("--transient", c->transient, "map iterations discarded before x_0")->capture_default_str();
  cc->add_option("--method", c->method, "fft (FFTW, O(N log N)), direct (the sum, O(N n-max)) or both (compared)")
      ->capture_default_str();
  cc->add_option("--precision", c->precision, "arithmetic of C_N: float, double or long-double")->capture_default_str();
  cc->add_option("--window", c->window, "lags per window of the |C_N| envelope")->capture_default_str();
  cc->add_option("--fit-lags", c->fit_lags, "lags 1..fit-lags enter the decay-rate fit (needs n-max >= fit-lags)")
      ->capture_default_str();
  cc->add_option("--out", c->out, "output directory")->capture_default_str();
  cc->add_option("--name", c->name, "file stem")->capture_default_str();
  cc->add_flag("--no-plot", c->no_plot, "write data only");
  cc->callback([c] { correlate(*c); });

  auto m = std::make_shared<MeasureArgs>();
  CLI::App* mc = app.add_subcommand(
      "measure", "Empirical measures mu_{N,x} = (1/N) sum_{k<N} delta_{x_k} of many initial conditions at one r "
                 "(Section 8.1 (2)): 2-D histograms, marginals, total variation and 1-D Wasserstein distances, groups "
                 "of coinciding measures, convergence against N; writes NAME.h5, NAME_report.csv, NAME.json, NAME.png");
  mc->add_option("--r", m->r, "restitution coefficient, in (0,1)")->capture_default_str();
  mc->add_option("--grid", m->grid, "initial conditions: paper (Section 4, 32 points), strip:NxM, random:N, x,y,z;...")
      ->capture_default_str();
  mc->add_option("--seed", m->seed, "seed of random grids")->capture_default_str();
  mc->add_option("--iterations", m->iterations, "N, points per measure (after the transient), >= 16")->capture_default_str();
  mc->add_option("--transient", m->transient, "map iterations discarded first")->capture_default_str();
  mc->add_option("--bins", m->bins, "bins per direction, 1..4000")->capture_default_str();
  mc->add_option("--coords", m->coords, "strip (atan w1 in (-pi/2, pi/2), w2 in [-1,1]) or angles (theta, phi in rad)")
      ->capture_default_str();
  mc->add_option("--extent", m->extent, "u_lo,u_hi,v_lo,v_hi: histogram only this part of the chart (zoom); "
                                        "mass outside is kept as one extra cell")->delimiter(',');
  mc->add_option("--tv-same", m->tv_same, "two measures closer than this in total variation count as one attractor")
      ->capture_default_str();
  mc->add_option("--threads", m->threads, "OpenMP threads of the iteration (0: default); results do not depend on it")
      ->capture_default_str();
  mc->add_option("--out", m->out, "output directory")->capture_default_str();
  mc->add_option("--name", m->name, "file stem")->capture_default_str();
  mc->add_flag("--no-plot", m->no_plot, "write data only");
  mc->callback([m] { measure(*m); });
});

}  // namespace
}  // namespace btob::cli
