// SPDX-License-Identifier: GPL-3.0-or-later
// The precision study (precision/tradeoff.hpp): every method against a 256-digit MPFR run of the same orbits; and
// its cost.
#include "precision/tradeoff.hpp"

#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/map.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/lyapunov.hpp"
#include "reference/reference.hpp"
#include "windows/verify.hpp"
#include "windows/windows.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>

namespace btob::precision {

core::Work work(const TradeoffRequest& req) {
  core::Work w;
  std::string route = "precision study";
  core::Args args;
  TradeoffRequest fields = req;  // fields() visits members by reference
  fields.fields(core::ArgsWriter{&args});
  for (const auto& [name, values] : args) route += " " + name + "=" + fmt::format("{}", fmt::join(values, ","));
  w.terms.push_back(core::self_term(req, route,
                                    "the precision study (one indivisible run: every method's window tests, Lyapunov "
                                    "errors and throughput, then the orbits' symbols against 256-digit MPFR)"));
  const double methods = 8, r = static_cast<double>(req.r.size());
  w.output_bytes = methods * (200 + 40 * r) + 2000;  // tradeoff.csv: a row per method, four columns per r
  w.peak_bytes = methods * static_cast<double>(req.orbits) * r * static_cast<double>(req.iterations) + 4e6;  // symbols
  return w;
}

using namespace btob::iterate;
using core::mpfr_float;
using Clock = std::chrono::steady_clock;

namespace {

// Symbols 1/2/3 of `iterations` steps of each orbit of e, and the final unit states, in precision T.
struct Trace {
  std::vector<std::uint8_t> symbols;
  std::vector<Vec3<double>> final;
};
template <class T> Trace trace(const Ensemble& e, long iterations, const RunOptions& ro) {
  FinalRecorder f(e.orbits(), iterations);
  SymbolRecorder s(e.orbits(), 1, iterations);
  Both<FinalRecorder, SymbolRecorder> both(f, s);
  run<T>(e, iterations, both, ro);
  return {std::move(s.out), std::move(f.out)};
}
template <class T> std::vector<std::uint8_t> symbols(const Ensemble& e, long iterations, const RunOptions& ro) {
  SymbolRecorder s(e.orbits(), 1, iterations);
  run<T>(e, iterations, s, ro);
  return s.out;
}

// The same with the trigonometric algorithm of Appendix A.1 (double); a broken orbit's remaining symbols are 0
// (never equal to the reference).
Trace trig_trace(const Ensemble& e, long iterations, const RunOptions& ro) {
  Trace t;
  t.symbols.assign(e.orbits() * static_cast<std::size_t>(iterations), 0);
  t.final.assign(e.orbits(), Vec3<double>::Constant(std::numeric_limits<double>::quiet_NaN()));
  auto& out = t.symbols;
  const std::size_t n_ic = e.initial.size();
  for (std::size_t o = 0; o < e.orbits(); ++o) {
    const double r = e.r[o / n_ic];
    const Vec3<double> u = core::to_quadrant<double>(e.initial[o % n_ic] / e.initial[o % n_ic].norm());
    auto s = reference::trig_start<double>(std::atan2(-u(2), u(0)), std::atan2(std::hypot(u(0), u(2)), -u(1)));
    for (long k = 0; k < iterations; ++k) {
      core::poll_cancel(ro.cancel, k);  // one orbit's scalar loop, outside any OpenMP region
      const auto c = reference::trig_b_to_b<double>(s, r);
      if (c.status != reference::TrigStatus::ok) break;
      out[o * iterations + k] = c.letters == "ab" ? 1 : (c.letters == "cb" ? 3 : 2);
      if (k == iterations - 1) t.final[o] = core::from_angles<double>(c.theta, c.phi);
    }
  }
  return t;
}
std::vector<std::uint8_t> trig_symbols(const Ensemble& e, long iterations, const RunOptions& ro) {
  return trig_trace(e, iterations, ro).symbols;
}

// Iterations per second of precision T on e (FinalRecorder, the run's threads), timed over >= 0.3 s.
template <class T> double throughput(const Ensemble& e, long iterations, const RunOptions& ro) {
  double items = 0, secs = 0;
  while (secs < 0.3) {
    FinalRecorder f(e.orbits(), iterations);
    const auto t0 = Clock::now();
    run<T>(e, iterations, f, ro);
    secs += core::seconds_since(t0);
    items += static_cast<double>(e.orbits()) * static_cast<double>(iterations);
  }
  return items / secs;
}
double trig_throughput(const Ensemble& e, long iterations, const RunOptions& ro) {
  const auto t0 = Clock::now();
  trig_symbols(e, iterations, ro);
  return static_cast<double>(e.orbits()) * static_cast<double>(iterations) / core::seconds_since(t0);
}

using SymFn = std::function<std::vector<std::uint8_t>(const Ensemble&, long, const RunOptions&)>;

// Largest n of the list such that, for it and every smaller listed n, the 8 first orbits of the Section 4 grid end
// on (ab)^n(cb)^n at the middle of the window (lower bound + r_crit,2)/2.
int window_n_max(const SymFn& sym, const std::vector<int>& ns, const RunOptions& ro) {
  int best = 0;
  for (int n : ns) {
    const double lo = static_cast<double>(windows::window_lower_bound(n, 20));
    const double hi = static_cast<double>(windows::r_crit2(n, 20));
    Ensemble e;
    e.r = {0.5 * (lo + hi)};
    const auto g = paper_grid();
    e.initial.assign(g.begin(), g.begin() + 8);
    const long iters = 20000 + 400L * n;  // transients grow with n near 7-4 sqrt(3) (see windows verify)
    const std::vector<std::uint8_t> s = sym(e, iters, ro);
    const long tail = 8L * n;
    for (std::size_t o = 0; o < e.orbits(); ++o)
      if (!windows::on_pattern(&s[o * iters + (iters - tail)], tail, n)) return best;
    best = n;
  }
  return best;
}

// Largest error of lambda1 (weighted Birkhoff average of the projective cocycle, 1e5 steps after a 2000-step
// transient) against the eigenvalues of the period matrix, on the sinks 1133 (r = 0.15), 111333 (r = 0.1) and
// 132312 (r = 0.5), started from the Section 4 grid's first point (0.1, 0.15) or a random point (0.5).
template <class T> double lyapunov_error() {
  struct Case {
    core::Decimal r;  // read in T from its decimal (lyapunov::OrbitRequest's route)
    Vec3<double> u;
  };
  const std::vector<Case> cases = {{0.15, paper_grid()[0]}, {0.1, paper_grid()[0]}, {0.5, random_points(1, 3)[0]}};
  double worst = 0;
  for (const Case& c : cases) {
    lyapunov::Options opt;
    opt.transient = 2000;
    opt.iterations = 100000;
    const Vec3<T> u(T(c.u(0)), T(c.u(1)), T(c.u(2)));
    const lyapunov::ProjectiveResult res = lyapunov::projective_exponents<T>(u, core::from_decimal<T>(c.r.text), opt);
    const int p = lyapunov::detect_period(res.symbols_tail, 64, 512);
    if (p == 0) return std::numeric_limits<double>::quiet_NaN();  // not on a sink: no exact value
    const std::vector<int> period(res.symbols_tail.end() - p, res.symbols_tail.end());
    worst = std::max(worst, std::fabs(res.weighted[0] - exact_lambda1(period, c.r)));
  }
  return worst;
}

// The hard case: the weakly contracting sink 312^150 (period 152, lambda1 = -0.0116) at r = 0.171599, just
// above 3 - 2 sqrt(2), from the Section 4 grid's first point.  |lambda1 - exact| whatever the orbit does: an
// arithmetic whose rounding moves the orbit off the sink is off by up to |lambda1| (the exact value needs no period
// detection: the eigenvalues of the word's period matrix do not depend on its phase).
template <class T> double lyapunov_error_near_neutral() {
  const core::Decimal r = 0.171599;  // read in T from its decimal
  std::vector<int> word = {3, 1};
  word.insert(word.end(), 150, 2);
  lyapunov::Options opt;
  // The double orbit is on the sink after 6000 steps (btob classify); the weighted average of a period-152 orbit whose
  // tangent frame rotates (a complex pair) needs ~400000 steps to reach 1e-11 (1e5 steps: 6.5e-8 in every precision).
  opt.transient = 100000;
  opt.iterations = 400000;
  const Vec3<double> u0 = paper_grid()[0];
  const lyapunov::ProjectiveResult res =
      lyapunov::projective_exponents<T>(Vec3<T>(T(u0(0)), T(u0(1)), T(u0(2))), core::from_decimal<T>(r.text), opt);
  return std::fabs(res.weighted[0] - exact_lambda1(word, r));
}

// A method: its name and digits, and its symbols, throughput, trace and Lyapunov error, each run in its own
// arithmetic (an MPFR method holds its digits with a guard for each call).
struct Method {
  std::string name;
  int digits;
  SymFn sym;
  std::function<double(const Ensemble&, long, const RunOptions&)> rate;
  std::function<Trace(const Ensemble&, long, const RunOptions&)> tr;
  std::function<double()> lyapunov;               // empty for trig
  std::function<double()> lyapunov_near_neutral;  // empty for trig
};

template <class T> Method linear(const std::string& name, int digits) {
  return {name, digits, symbols<T>, throughput<T>, trace<T>, lyapunov_error<T>, lyapunov_error_near_neutral<T>};
}

Method mpfr_method(int d) {
  const auto at = [d](auto f) {
    return [d, f](auto&&... args) {
      core::MpfrDigits guard(d);
      return f(args...);
    };
  };
  return {fmt::format("linear/mpfr:{}", d),
          d,
          at(symbols<mpfr_float>),
          at(throughput<mpfr_float>),
          at(trace<mpfr_float>),
          at(lyapunov_error<mpfr_float>),
          at(lyapunov_error_near_neutral<mpfr_float>)};
}

// The row of one method: agreement with the reference per r, throughput, window test, Lyapunov error.
TradeoffRow measure(const Method& m, const TradeoffRequest& req, const Ensemble& e, const Trace& reference,
                    const std::vector<int>& window_n, const RunOptions& ro) {
  TradeoffRow row;
  row.method = m.name;
  row.digits = m.digits;
  const long N = req.iterations;
  const Trace tr = m.tr(e, N, ro);
  const std::vector<std::uint8_t>& s = tr.symbols;
  const std::vector<std::uint8_t>& ref = reference.symbols;
  const std::size_t n_ic = e.initial.size();
  for (std::size_t ir = 0; ir < e.r.size(); ++ir) {
    std::vector<long> agree;
    std::vector<double> err;
    for (std::size_t ic = 0; ic < n_ic; ++ic) {
      const std::size_t o = ir * n_ic + ic;
      long k = 0;
      while (k < N && s[o * N + k] == ref[o * N + k]) ++k;
      agree.push_back(k);
      const Vec3<double>& a = tr.final[o];
      const Vec3<double>& b = reference.final[o];
      err.push_back(std::isfinite(a.sum()) ? std::atan2(a.cross(b).norm(), a.dot(b)) : M_PI);
    }
    std::sort(err.begin(), err.end());
    row.error_median.push_back(err[err.size() / 2]);
    std::sort(agree.begin(), agree.end());
    row.agree_min.push_back(agree.front());
    row.agree_median.push_back(agree[agree.size() / 2]);
  }
  // Throughput on a workload sized to the method's speed: enough orbits to fill the SIMD batches and both threads
  // (8192 for float/double), fewer for the slow types so that one timing takes about a second.
  Ensemble w;
  w.set_r_list({0.2});
  const long n_orbits = m.digits > 34 ? 16 : (m.digits > 16 || m.name.starts_with("trig") ? 256 : 8192);
  w.initial = random_points(n_orbits, req.seed + 1);
  row.rate = m.rate(w, m.digits > 34 ? 200 : 2000, ro);
  row.n_max = m.name.starts_with("trig") ? -1 : window_n_max(m.sym, window_n, ro);
  row.lyapunov_error = m.lyapunov ? m.lyapunov() : std::numeric_limits<double>::quiet_NaN();
  row.lyapunov_near_neutral =
      m.lyapunov_near_neutral ? m.lyapunov_near_neutral() : std::numeric_limits<double>::quiet_NaN();
  return row;
}

}  // namespace

double exact_lambda1(const std::vector<int>& period, const core::Decimal& r_decimal) {
  using core::Mat3;
  core::MpfrDigits sixty(60);
  const mpfr_float r = core::from_decimal<mpfr_float>(r_decimal.text);  // the decimal to 60 digits, not a double
  Mat3<mpfr_float> M = Mat3<mpfr_float>::Identity();
  for (int s : period) M = Mat3<mpfr_float>(core::P<mpfr_float>(s, r) * M);
  const mpfr_float tr = M(0, 0) + M(1, 1) + M(2, 2);
  const mpfr_float c2 = M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0) + M(0, 0) * M(2, 2) - M(0, 2) * M(2, 0) +
                        M(1, 1) * M(2, 2) - M(1, 2) * M(2, 1);
  const mpfr_float det = M(0, 0) * (M(1, 1) * M(2, 2) - M(1, 2) * M(2, 1)) -
                         M(0, 1) * (M(1, 0) * M(2, 2) - M(1, 2) * M(2, 0)) +
                         M(0, 2) * (M(1, 0) * M(2, 1) - M(1, 1) * M(2, 0));
  Mat3<double> Md;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Md(i, j) = static_cast<double>(M(i, j));
  const Eigen::EigenSolver<Mat3<double>> es(Md, false);
  std::complex<double> best = es.eigenvalues()(0);
  for (int i = 1; i < 3; ++i)
    if (std::abs(es.eigenvalues()(i)) > std::abs(best)) best = es.eigenvalues()(i);
  mpfr_float l1(best.real());  // a sink's dominant eigenvalue is real (its eigenvector is the periodic point)
  for (int it = 0; it < 60; ++it) {
    const mpfr_float f = ((l1 - tr) * l1 + c2) * l1 - det, df = (3 * l1 - 2 * tr) * l1 + c2;
    l1 -= f / df;
  }
  const mpfr_float b = tr - l1, c = det / l1, disc = b * b - 4 * c;
  mpfr_float l2abs;
  if (disc < 0) l2abs = sqrt(abs(c));
  else {
    const mpfr_float sq = sqrt(disc), up = abs((b + sq) / 2), down = abs((b - sq) / 2);
    l2abs = up > down ? up : down;
  }
  return static_cast<double>(log(l2abs / abs(l1)) / static_cast<int>(period.size()));
}

TradeoffResult run(const TradeoffRequest& req, const core::RunControl& control) {
  req.validate();
  RunOptions ro;
  ro.threads = control.threads;
  ro.cancel = control.cancel;
  std::vector<int> window_n;
  for (double n : req.window_n) window_n.push_back(static_cast<int>(n));
  Ensemble e;
  e.set_r_list(req.r);  // each precision reads r from its decimal (Ensemble::r_at)
  e.initial = random_points(req.orbits, req.seed);
  const std::vector<Method> methods = {
      linear<float>("linear/float", 7),
      linear<double>("linear/double", 16),
      linear<long double>("linear/long-double", 19),
      linear<core::float128>("linear/float128", 34),
      mpfr_method(50),
      mpfr_method(100),
      {"trig/double", 16, trig_symbols, trig_throughput, trig_trace, {}},
  };
  Trace reference;  // 256 decimal digits
  {
    core::MpfrDigits guard(256);
    reference = trace<mpfr_float>(e, req.iterations, ro);
  }
  TradeoffResult res;
  for (std::size_t step = 0; step < methods.size(); ++step) {
    if (control.progress) control.progress->update(step, methods.size());
    core::check_cancel(control.cancel);
    res.rows.push_back(measure(methods[step], req, e, reference, window_n, ro));
  }
  if (control.progress) control.progress->update(methods.size(), methods.size());
  res.r = core::values(req.r);
  res.iterations = req.iterations;
  for (const TradeoffRow& row : res.rows) {
    res.method.push_back(row.method);
    res.digits.push_back(row.digits);
    res.rate.push_back(row.rate);
    res.window_n_max.push_back(row.n_max);
    res.lyapunov_error.push_back(row.lyapunov_error);
    res.lyapunov_near_neutral.push_back(row.lyapunov_near_neutral);
    for (std::size_t i = 0; i < row.agree_min.size(); ++i) {
      res.agree_min.push_back(static_cast<double>(row.agree_min[i]));
      res.agree_median.push_back(static_cast<double>(row.agree_median[i]));
      res.error_median.push_back(row.error_median[i]);
    }
  }
  return res;
}

}  // namespace btob::precision
