// SPDX-License-Identifier: GPL-3.0-or-later
// Orbit series, observables, empirical measures, distances and the decay fit (Section 8.1 (2)).
#include "stats/stats.hpp"

#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/request.hpp"
#include "iterate/kernel.hpp"
#include "stats/series.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace btob::stats {

std::vector<OrbitSeries> orbit_series(double r, const std::vector<iterate::Vec3<double>>& u0, long transient,
                                      long length, int threads) {
  iterate::RunOptions opt;
  opt.threads = threads;
  return orbit_series(r, u0, transient, length, opt);
}

std::vector<OrbitSeries> orbit_series(double r, const std::vector<iterate::Vec3<double>>& u0, long transient,
                                      long length, const iterate::RunOptions& opt) {
  core::validate_r(r, "r");
  for (const auto& u : u0) core::validate_point(u(0), u(1), u(2), "point");
  if (transient < 0) throw core::InvalidField("transient", fmt::format("{}", transient), ">= 0");
  if (length < 1) throw core::InvalidField("iterations", fmt::format("{}", length), ">= 1");
  if (u0.empty()) throw core::InvalidField("grid", "no initial condition", "at least one");
  iterate::Ensemble e;
  e.r = {r};
  e.initial = u0;
  // Twice the series (recorder, then the per-orbit copies) must fit.
  iterate::checked_bytes(2 * u0.size() * static_cast<std::size_t>(length), 3 * sizeof(double) + 1, "iterations");
  stats::SeriesRecorder rec(u0.size(), transient + 1, length);
  iterate::run<double>(e, transient + length, rec, opt);
  std::vector<OrbitSeries> out(u0.size());
  if (u0.size() == 1) {  // one orbit: the recorder's arrays are its series (a copy cost twice the run)
    out[0].x = std::move(rec.x), out[0].y = std::move(rec.y), out[0].z = std::move(rec.z);
    out[0].symbol = std::move(rec.symbol);
    return out;
  }
  for (std::size_t o = 0; o < u0.size(); ++o) {
    const auto b = static_cast<std::ptrdiff_t>(o * static_cast<std::size_t>(length)),
               n = static_cast<std::ptrdiff_t>(length);
    out[o].x.assign(rec.x.begin() + b, rec.x.begin() + b + n);
    out[o].y.assign(rec.y.begin() + b, rec.y.begin() + b + n);
    out[o].z.assign(rec.z.begin() + b, rec.z.begin() + b + n);
    out[o].symbol.assign(rec.symbol.begin() + b, rec.symbol.begin() + b + n);
  }
  return out;
}

OrbitSeries orbit_series(double r, const iterate::Vec3<double>& u0, long transient, long length) {
  return std::move(orbit_series(r, std::vector<iterate::Vec3<double>>{u0}, transient, length, 1)[0]);
}

namespace {
const std::map<std::string, Observable>& observable_table() {
  static const std::map<std::string, Observable> m = {
      {"theta", Observable::theta},     {"phi", Observable::phi},         {"w1", Observable::w1},
      {"w2", Observable::w2},           {"cos-phi", Observable::cos_phi}, {"symbol1", Observable::symbol1},
      {"symbol2", Observable::symbol2}, {"symbol3", Observable::symbol3}};
  return m;
}
}  // namespace

std::string observable_names() { return "theta, phi, w1, w2, cos-phi, symbol1, symbol2, symbol3"; }

Observable parse_observable(const std::string& name, const char* field) {
  const auto it = observable_table().find(name);
  if (it == observable_table().end())
    throw core::InvalidField(field, fmt::format("'{}'", name), fmt::format("one of {}", observable_names()));
  return it->second;
}

std::string observable_name(Observable o) {
  for (const auto& [name, v] : observable_table())
    if (v == o) return name;
  return "?";
}

double value(Observable o, const iterate::Vec3<double>& u, int symbol) {
  const double x = u(0), y = u(1), z = u(2);  // a unit vector in Q: x >= 0, z <= 0
  switch (o) {
    case Observable::theta: return std::atan2(-z, x);                       // Section 4
    case Observable::phi: return std::atan2(std::sqrt(x * x + z * z), -y);  // eq. (6.1), cos phi = -y/|u|
    case Observable::w1: return y / (x - z);                                // eq. (6.4)
    case Observable::w2: return (x + z) / (x - z);                          // eq. (6.4)
    case Observable::cos_phi: return -y;
    case Observable::symbol1: return symbol == 1;
    case Observable::symbol2: return symbol == 2;
    case Observable::symbol3: return symbol == 3;
  }
  return 0;
}

std::vector<double> observe(const OrbitSeries& s, Observable o, const std::function<double(double)>& f,
                            const core::CancelToken* cancel) {
  std::vector<double> v(static_cast<std::size_t>(s.size()));
  for (long k = 0; k < s.size(); ++k) {
    core::poll_cancel(cancel, k);  // ~25 ns a value: a second for the 6e7 states of a long correlation
    const double a = value(o, s.state(k), s.symbol[k]);
    v[k] = f ? f(a) : a;
  }
  return v;
}

std::vector<double> observe(const OrbitSeries& s, const StateFunction& f) {
  std::vector<double> v(static_cast<std::size_t>(s.size()));
  for (long k = 0; k < s.size(); ++k) v[k] = f(s.state(k), s.symbol[k]);
  return v;
}

std::vector<double> envelope(const std::vector<double>& c, long window) {
  if (window < 1) throw core::InvalidField("window", fmt::format("{}", window), ">= 1");
  std::vector<double> e;
  for (long start = 1; start + window <= static_cast<long>(c.size()); start += window) {
    double m = 0;
    for (long n = start; n < start + window; ++n) m = std::max(m, std::fabs(c[n]));
    e.push_back(m);
  }
  return e;
}

namespace {
// Least-squares line through (xs, ys): d.rate = -slope, its standard error and 95% interval (>= 3 points).
void fit_line(const std::vector<double>& xs, const std::vector<double>& ys, Decay& d) {
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
  d.rate = -slope;
  d.rate_error = std::sqrt(sse / (n - 2) / sxx);
  const double t = boost::math::quantile(boost::math::students_t(n - 2), 0.975);
  d.rate_low = d.rate - t * d.rate_error;
  d.rate_high = d.rate + t * d.rate_error;
}

// The verdict of Decay (stats.hpp) from the fitted windows; `span` is the number of lags they cover.
void decide(Decay& d, double span) {
  if (d.windows < 3) {
    d.verdict = "undecided";
    d.reason = d.floor_lag >= 0 ? fmt::format(
                                      "|C_N| reaches the noise floor at lag {} after {} window(s): too few to "
                                      "fit a rate (more iterations lower the floor, a smaller window gives "
                                      "more points)",
                                      d.floor_lag, d.windows)
                                : "fewer than 3 windows of lags to fit";
    return;
  }
  const double fall = d.envelope_first / d.envelope_last;
  // A decay that the fit sees: the rate's 95% interval above 0 and the fitted line falling by 10% or more over the
  // fitted lags (a significant slope of 1e-18 on a periodic orbit is rounding, not decay).
  const bool falls = d.rate_low > 0 && d.rate * span >= std::log(1.1);
  if (falls && fall >= 10) {
    d.verdict = "decaying";
    d.reason = fmt::format("rate > 0 at 95% and the envelope fell {:.3g}-fold before the noise floor", fall);
  } else if (falls) {
    d.verdict = "undecided";
    d.reason = fmt::format(
        "rate > 0 at 95% but the envelope fell only {:.3g}-fold before the noise floor or the end "
        "of the fit (more fit lags or iterations)",
        fall);
  } else if (d.floor_lag < 0 && d.rate_high * span < std::log(10.0)) {
    d.verdict = "not decaying";
    d.reason = fmt::format(
        "above the noise floor over all {} lags, and at the 95% upper rate the envelope would fall "
        "less than tenfold over them",
        static_cast<long>(span));
  } else {
    d.verdict = "undecided";
    d.reason = "no significant decay, but a tenfold fall over the fitted lags is not excluded";
  }
  d.decays = d.verdict == "decaying";
}
}  // namespace

Decay fit_decay(const std::vector<double>& c, long n_fit, long window, double floor) {
  if (window < 1 || n_fit < window || n_fit >= static_cast<long>(c.size()))
    throw core::InvalidField("n-fit", fmt::format("{} with window {} for {} lags", n_fit, window, c.size()),
                             "window <= n-fit < lags");
  const std::vector<double> env = envelope(std::vector<double>(c.begin(), c.begin() + n_fit + 1), window);
  std::vector<double> xs, ys;
  Decay d;
  for (std::size_t i = 0; i < env.size(); ++i) {
    if (!(env[i] > floor)) {  // the first window at the noise floor ends the fit
      d.floor_lag = 1 + static_cast<long>(i) * window;
      break;
    }
    xs.push_back(1.0 + static_cast<double>(i * window) + 0.5 * static_cast<double>(window - 1));
    ys.push_back(std::log(env[i]));
  }
  d.windows = static_cast<long>(xs.size());
  if (!xs.empty()) {
    d.envelope_first = std::exp(ys.front());
    d.envelope_last = std::exp(ys.back());
  }
  if (xs.size() >= 3) fit_line(xs, ys, d);
  decide(d, static_cast<double>(d.windows * window));
  return d;
}

Chart parse_chart(const std::string& name, const char* field) {
  if (name == "strip") return Chart::strip;
  if (name == "angles") return Chart::angles;
  throw core::InvalidField(field, fmt::format("'{}'", name), "strip or angles");
}
std::string chart_name(Chart c) { return c == Chart::strip ? "strip" : "angles"; }

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

namespace {
void check_bins(int bins_u, int bins_v) {
  if (bins_u < 1 || bins_v < 1 || bins_u > 100000 || bins_v > 100000)
    throw core::InvalidField("bins", fmt::format("{}x{}", bins_u, bins_v), "1..100000 in each direction");
}
}  // namespace

Measure measure_frame(Chart chart, int bins_u, int bins_v, const std::vector<double>& extent) {
  check_bins(bins_u, bins_v);
  Measure m;
  m.chart = chart;
  m.bins_u = bins_u;
  m.bins_v = bins_v;
  if (chart == Chart::strip) {
    m.u_lo = -std::numbers::pi / 2, m.u_hi = std::numbers::pi / 2, m.v_lo = -1, m.v_hi = 1;
  } else {
    m.u_lo = 0, m.u_hi = std::numbers::pi / 2, m.v_lo = 0, m.v_hi = std::numbers::pi;
  }
  if (!extent.empty()) {
    if (extent.size() != 4 || !(extent[0] < extent[1]) || !(extent[2] < extent[3]))
      throw core::InvalidField("extent", fmt::format("{} values", extent.size()), "u_lo < u_hi, v_lo < v_hi");
    m.u_lo = extent[0], m.u_hi = extent[1], m.v_lo = extent[2], m.v_hi = extent[3];
  }
  return m;
}

namespace {
void check_range(long first, long& count, long n_all) {
  if (count < 0) count = n_all - first;
  if (first < 0 || count < 1 || first + count > n_all)
    throw core::InvalidField("iterations", fmt::format("points [{}, {}) of {}", first, first + count, n_all),
                             "a non-empty range");
}

// Calls cell(c) with the bin i * bins_v + j of each point first..first+count-1 of s, or -1 outside the extent.
template <class F> void each_cell(const OrbitSeries& s, const Measure& m, bool whole, long first, long count, F cell) {
  const double su = m.bins_u / (m.u_hi - m.u_lo), sv = m.bins_v / (m.v_hi - m.v_lo);
  for (long k = first; k < first + count; ++k) {
    const double x = s.x[k], y = s.y[k], z = s.z[k];
    double u, v;
    if (m.chart == Chart::strip) {
      u = std::atan2(y, x - z);  // atan(w1), x - z > 0 in Q
      v = (x + z) / (x - z);
    } else {
      u = std::atan2(-z, x);
      v = std::atan2(std::sqrt(x * x + z * z), -y);
    }
    if (!whole && !(u >= m.u_lo && u <= m.u_hi && v >= m.v_lo && v <= m.v_hi)) {
      cell(-1);
      continue;
    }
    const int i = std::clamp(static_cast<int>((u - m.u_lo) * su), 0, m.bins_u - 1);
    const int j = std::clamp(static_cast<int>((v - m.v_lo) * sv), 0, m.bins_v - 1);
    cell(static_cast<long>(i) * m.bins_v + j);
  }
}

// Integer counts first, one division at the end: the masses are exact multiples of 1/N to rounding.
void masses(Measure& m, const std::vector<long>& counts, long out, long count) {
  m.mass.assign(counts.size(), 0);
  m.points = count;
  for (std::size_t b = 0; b < counts.size(); ++b)
    m.mass[b] = static_cast<double>(counts[b]) / static_cast<double>(count);
  m.outside = static_cast<double>(out) / static_cast<double>(count);
}
}  // namespace

Measure empirical_measure(const OrbitSeries& s, Chart chart, int bins_u, int bins_v, long first, long count,
                          const std::vector<double>& extent) {
  check_bins(bins_u, bins_v);
  check_range(first, count, s.size());  // the order of the checks: bins, the range, the extent
  Measure m = measure_frame(chart, bins_u, bins_v, extent);
  std::vector<long> counts(static_cast<std::size_t>(bins_u) * static_cast<std::size_t>(bins_v), 0);
  long out = 0;
  each_cell(s, m, extent.empty(), first, count, [&](long c) { c < 0 ? ++out : ++counts[static_cast<std::size_t>(c)]; });
  masses(m, counts, out, count);
  return m;
}

std::vector<std::int32_t> measure_cells(const OrbitSeries& s, const Measure& frame, bool whole) {
  if (static_cast<long>(frame.bins_u) * frame.bins_v > std::numeric_limits<std::int32_t>::max())
    throw core::InvalidField("bins", fmt::format("{}x{}", frame.bins_u, frame.bins_v), "at most 2^31 - 1 cells");
  std::vector<std::int32_t> cells;
  cells.reserve(static_cast<std::size_t>(s.size()));
  each_cell(s, frame, whole, 0, s.size(), [&](long c) { cells.push_back(static_cast<std::int32_t>(c)); });
  return cells;
}

Measure measure_of_cells(const Measure& frame, const std::int32_t* cells, long count) {
  if (count < 1) throw core::InvalidField("iterations", fmt::format("{} points", count), "at least 1");
  Measure m = frame;
  std::vector<long> counts(static_cast<std::size_t>(m.bins_u) * static_cast<std::size_t>(m.bins_v), 0);
  long out = 0;
  for (long k = 0; k < count; ++k) cells[k] < 0 ? ++out : ++counts[static_cast<std::size_t>(cells[k])];
  masses(m, counts, out, count);
  return m;
}

double total_variation(const Measure& a, const Measure& b) {
  if (a.bins_u != b.bins_u || a.bins_v != b.bins_v || a.chart != b.chart || a.u_lo != b.u_lo || a.u_hi != b.u_hi ||
      a.v_lo != b.v_lo || a.v_hi != b.v_hi)
    throw std::invalid_argument(
        fmt::format("measure: got {} {}x{} and {} {}x{}, expected the same chart, extent and bins", chart_name(a.chart),
                    a.bins_u, a.bins_v, chart_name(b.chart), b.bins_u, b.bins_v));
  double s = 0;
  for (std::size_t i = 0; i < a.mass.size(); ++i) s += std::fabs(a.mass[i] - b.mass[i]);
  return 0.5 * (s + std::fabs(a.outside - b.outside));
}

double wasserstein_1d(const std::vector<double>& a, const std::vector<double>& b, double lo, double hi) {
  if (a.size() != b.size() || a.empty())
    throw std::invalid_argument(fmt::format(
        "marginal: got {} and {} bins, expected two non-empty marginals on the same bins", a.size(), b.size()));
  const double dx = (hi - lo) / static_cast<double>(a.size());
  double fa = 0, fb = 0, s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    fa += a[i];
    fb += b[i];
    s += std::fabs(fa - fb) * dx;
  }
  return s;
}

std::vector<int> group_measures(const std::vector<Measure>& ms, double tv_same) {
  if (!(tv_same > 0 && tv_same <= 1)) throw core::InvalidField("tv-same", fmt::format("{}", tv_same), "in (0, 1]");
  std::vector<int> label(ms.size(), -1);
  std::vector<std::size_t> heads;  // first member of each group
  for (std::size_t i = 0; i < ms.size(); ++i) {
    for (std::size_t g = 0; g < heads.size(); ++g)
      if (total_variation(ms[i], ms[heads[g]]) < tv_same) {
        label[i] = static_cast<int>(g);
        break;
      }
    if (label[i] < 0) {
      label[i] = static_cast<int>(heads.size());
      heads.push_back(i);
    }
  }
  return label;
}

}  // namespace btob::stats
