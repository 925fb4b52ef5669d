// `btob measure` (empirical measures of many initial conditions) and `btob correlate` (C_N), Section 7 (2).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "io/io.hpp"
#include "iterate/ensemble.hpp"
#include "stats/stats.hpp"

#include <btob/build_info.hpp>
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

struct CorrelateArgs {
  double r = 0.11;
  std::string point = "1,-3,-1.1";
  std::string observable = "phi";
  long n_max = 1000, iterations = 100000, transient = 10000;
  std::string method = "fft";
  std::string out = "results/stats", name = "correlation";
  bool no_plot = false;
};

iterate::Vec3<double> parse_point(const std::string& text) {
  const auto pts = iterate::parse_grid(text, 0, "point");
  if (pts.size() != 1) throw UsageError(fmt::format("point: got '{}', expected one point x,y,z", text));
  return pts[0];
}

void correlate(const CorrelateArgs& a) {
  core::validate_r(a.r, "r");
  const auto u0 = parse_point(a.point);
  const auto comma = a.observable.find(',');
  const stats::Observable phi = stats::parse_observable(a.observable.substr(0, comma));
  const stats::Observable psi = stats::parse_observable(comma == std::string::npos ? a.observable.substr(0, comma)
                                                                                    : a.observable.substr(comma + 1));
  if (a.iterations < 2) throw UsageError(fmt::format("iterations: got {}, expected at least 2", a.iterations));
  if (a.n_max < 0 || a.n_max >= a.iterations)
    throw UsageError(fmt::format("n-max: got {}, expected 0 <= n-max < iterations = {}", a.n_max, a.iterations));
  if (a.transient < 0) throw UsageError(fmt::format("transient: got {}, expected >= 0", a.transient));
  if (a.method != "fft" && a.method != "direct")
    throw UsageError(fmt::format("method: got '{}', expected fft or direct", a.method));
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const long N = a.iterations;
  const stats::OrbitSeries s = stats::orbit_series(a.r, u0, a.transient, N + a.n_max);
  const auto x = stats::observe(s, phi), y = stats::observe(s, psi);
  const auto t0 = std::chrono::steady_clock::now();
  stats::Correlator corr;
  const std::vector<double> c =
      a.method == "fft" ? corr.correlation(x, y, N, a.n_max) : stats::correlation_direct(x, y, N, a.n_max);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<double> spectrum = corr.power_spectrum(x, N);
  std::ostringstream csv;
  csv << fmt::format("# C_N({}, {}; n), r = {}, point {}, N = {}, transient {}, method {}, btob {}\n",
                     stats::observable_name(phi), stats::observable_name(psi), a.r, a.point, N, a.transient, a.method,
                     build::git_commit);
  csv << "lag,C_N\n";
  for (std::size_t n = 0; n < c.size(); ++n) csv << n << "," << fmt::format("{:.17g}", c[n]) << "\n";
  io::write_text_atomic(out / (a.name + ".csv"), csv.str());
  io::Attrs attrs = io::provenance(invocation());
  attrs["r"] = a.r;
  attrs["point"] = a.point;
  attrs["observables"] = stats::observable_name(phi) + "," + stats::observable_name(psi);
  attrs["N"] = N;
  attrs["n_max"] = a.n_max;
  attrs["transient"] = a.transient;
  attrs["method"] = a.method;
  attrs["seconds"] = secs;
  attrs["scalar_type"] = std::string("double");
  if (a.n_max >= 40) {
    const stats::Decay d = stats::fit_decay(c, std::min<long>(a.n_max, 200), 10);
    attrs["decay_rate"] = d.rate;
    attrs["decay_rate_error"] = d.rate_error;
    attrs["envelope_first"] = d.envelope_first;
    attrs["envelope_last"] = d.envelope_last;
    std::cerr << fmt::format("btob: |C_N| envelope {:.3g} -> {:.3g} over lags 1..{}; fitted decay rate {:.4g} +- {:.2g} "
                             "per iteration\n",
                             d.envelope_first, d.envelope_last, std::min<long>(a.n_max, 200), d.rate, d.rate_error);
  }
  {
    io::H5Writer w(out / (a.name + ".h5"));
    w.attrs(attrs);
    w.dataset("C_N", c, {c.size()});
    w.dataset("power_spectrum", spectrum, {spectrum.size()});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  if (!a.no_plot) io::run_plot("stats_correlation.py", {(out / (a.name + ".h5")).string(), (out / (a.name + ".png")).string()});
}

struct MeasureArgs {
  double r = 0.15;
  std::string grid = "paper";
  std::uint64_t seed = 1;
  long iterations = 100000, transient = 10000;
  int bins = 200;
  std::string chart = "strip";
  std::string out = "results/stats", name = "measure";
  bool no_plot = false;
};

void measure(const MeasureArgs& a) {
  core::validate_r(a.r, "r");
  if (a.iterations < 1) throw UsageError(fmt::format("iterations: got {}, expected at least 1", a.iterations));
  if (a.transient < 0) throw UsageError(fmt::format("transient: got {}, expected >= 0", a.transient));
  if (a.bins < 1 || a.bins > 4000) throw UsageError(fmt::format("bins: got {}, expected 1..4000", a.bins));
  if (a.chart != "strip" && a.chart != "angles")
    throw UsageError(fmt::format("chart: got '{}', expected strip or angles", a.chart));
  const stats::Chart chart = a.chart == "strip" ? stats::Chart::strip : stats::Chart::angles;
  const auto ics = iterate::parse_grid(a.grid, a.seed, "grid");
  iterate::checked_bytes(ics.size() * static_cast<std::size_t>(a.bins) * a.bins, sizeof(double), "grid x bins^2");
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  io::Progress progress("measure");
  std::vector<stats::Measure> ms;
  for (std::size_t i = 0; i < ics.size(); ++i) {
    const stats::OrbitSeries s = stats::orbit_series(a.r, ics[i], a.transient, a.iterations);
    ms.push_back(stats::empirical_measure(s, chart, a.bins, a.bins));
    progress.update(i + 1, ics.size());
  }
  // The mean measure, and each initial condition's distance to it (the paper's test for a physical measure).
  stats::Measure mean = ms[0];
  std::fill(mean.mass.begin(), mean.mass.end(), 0.0);
  for (const auto& m : ms)
    for (std::size_t k = 0; k < m.mass.size(); ++k) mean.mass[k] += m.mass[k] / static_cast<double>(ms.size());
  std::ostringstream csv;
  csv << fmt::format("# empirical measures at r = {}, grid {} ({} initial conditions), {} iterations after {} transient, "
                     "{}x{} bins in the {} chart\n",
                     a.r, a.grid, ics.size(), a.iterations, a.transient, a.bins, a.bins, a.chart);
  csv << "ic,x,y,z,tv_to_mean,w1_marginal_u,w1_marginal_v,tv_max_pair\n";
  std::vector<double> tv(ms.size());
  double worst_pair = 0;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    double pair = 0;
    for (std::size_t j = 0; j < ms.size(); ++j) pair = std::max(pair, stats::total_variation(ms[i], ms[j]));
    worst_pair = std::max(worst_pair, pair);
    tv[i] = stats::total_variation(ms[i], mean);
    csv << fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", i, ics[i](0), ics[i](1), ics[i](2), tv[i],
                       stats::wasserstein_1d(ms[i].marginal_u(), mean.marginal_u(), mean.u_lo, mean.u_hi),
                       stats::wasserstein_1d(ms[i].marginal_v(), mean.marginal_v(), mean.v_lo, mean.v_hi), pair);
  }
  io::write_text_atomic(out / (a.name + "_report.csv"), csv.str());
  // Convergence against N for the first initial condition: TV between mu_N and mu of the whole run.
  const stats::OrbitSeries s0 = stats::orbit_series(a.r, ics[0], a.transient, a.iterations);
  std::vector<double> conv_n, conv_tv;
  for (long n = 16; n < a.iterations; n *= 2) {
    conv_n.push_back(static_cast<double>(n));
    conv_tv.push_back(stats::total_variation(stats::empirical_measure(s0, chart, a.bins, a.bins, 0, n), ms[0]));
  }
  io::Attrs attrs = io::provenance(invocation());
  attrs["r"] = a.r;
  attrs["grid"] = a.grid;
  attrs["seed"] = static_cast<long>(a.seed);
  attrs["iterations"] = a.iterations;
  attrs["transient"] = a.transient;
  attrs["bins"] = static_cast<long>(a.bins);
  attrs["chart"] = a.chart;
  attrs["initial_conditions"] = static_cast<long>(ics.size());
  attrs["tv_max_pair"] = worst_pair;
  attrs["scalar_type"] = std::string("double");
  {
    io::H5Writer w(out / (a.name + ".h5"));
    w.attrs(attrs);
    w.dataset("mean_measure", mean.mass, {static_cast<std::size_t>(a.bins), static_cast<std::size_t>(a.bins)});
    w.dataset("tv_to_mean", tv, {tv.size()});
    w.dataset("convergence_n", conv_n, {conv_n.size()});
    w.dataset("convergence_tv", conv_tv, {conv_tv.size()});
    w.dataset("extent", std::vector<double>{mean.u_lo, mean.u_hi, mean.v_lo, mean.v_hi}, {4});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), attrs);
  std::cerr << fmt::format("btob: {} initial conditions, largest total variation between two of their measures {:.3g}\n",
                           ics.size(), worst_pair);
  if (!a.no_plot) io::run_plot("stats_measure.py", {(out / (a.name + ".h5")).string(), (out / (a.name + ".png")).string()});
}

Register reg([](CLI::App& app) {
  auto c = std::make_shared<CorrelateArgs>();
  CLI::App* cc = app.add_subcommand("correlate", "Correlation function C_N(phi, psi; n) along one orbit (Section 7)");
  cc->add_option("--r", c->r, "restitution coefficient, in (0,1)")->capture_default_str();
  cc->add_option("--point", c->point, "initial point x,y,z (domain x*z <= 0)")->capture_default_str();
  cc->add_option("--observable", c->observable,
                 "phi[,psi] among theta, phi, w1, w2, cos-phi, symbol1, symbol2, symbol3")->capture_default_str();
  cc->add_option("--n-max", c->n_max, "largest lag")->capture_default_str();
  cc->add_option("--iterations", c->iterations, "N, the length of the average")->capture_default_str();
  cc->add_option("--transient", c->transient, "steps discarded first")->capture_default_str();
  cc->add_option("--method", c->method, "fft (FFTW) or direct (the sum)")->capture_default_str();
  cc->add_option("--out", c->out, "output directory")->capture_default_str();
  cc->add_option("--name", c->name, "file stem")->capture_default_str();
  cc->add_flag("--no-plot", c->no_plot, "write data only");
  cc->callback([c] { correlate(*c); });

  auto m = std::make_shared<MeasureArgs>();
  CLI::App* mc = app.add_subcommand("measure", "Empirical measures of many initial conditions and their distances");
  mc->add_option("--r", m->r, "restitution coefficient, in (0,1)")->capture_default_str();
  mc->add_option("--grid", m->grid, "initial conditions: paper, strip:NxM, random:N or x,y,z;...")->capture_default_str();
  mc->add_option("--seed", m->seed, "seed of random grids")->capture_default_str();
  mc->add_option("--iterations", m->iterations, "points per measure (after the transient)")->capture_default_str();
  mc->add_option("--transient", m->transient, "steps discarded first")->capture_default_str();
  mc->add_option("--bins", m->bins, "bins per direction")->capture_default_str();
  mc->add_option("--chart", m->chart, "strip (atan w1, w2) or angles (theta, phi)")->capture_default_str();
  mc->add_option("--out", m->out, "output directory")->capture_default_str();
  mc->add_option("--name", m->name, "file stem")->capture_default_str();
  mc->add_flag("--no-plot", m->no_plot, "write data only");
  mc->callback([m] { measure(*m); });
});

}  // namespace
}  // namespace btob::cli
