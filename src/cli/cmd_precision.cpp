// `btob precision`: speed against accuracy of each precision and algorithm (issue 9), measured against a
// 256-digit MPFR reference run of the same orbits; writes results/precision/tradeoff.csv and a plot.
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/scalar.hpp"
#include "io/io.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/lyapunov.hpp"
#include "reference/reference.hpp"
#include "windows/verify.hpp"
#include "windows/windows.hpp"

#include <btob/build_info.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <chrono>
#include <complex>
#include <functional>
#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

using namespace btob::iterate;
using Clock = std::chrono::steady_clock;

struct PrecisionArgs {
  long orbits = 16, iterations = 3000;
  std::vector<double> r_values{0.11, 0.2, 0.3, 0.58};
  std::vector<int> window_n{2, 3, 5, 8, 12, 20, 30, 45, 60, 80, 100, 125};
  std::uint64_t seed = 7;
  std::string out = "results/precision";
  bool no_plot = false;
};

// Symbols 1/2/3 of `iterations` steps of each orbit of e, and the final unit states, in precision T.
struct Trace {
  std::vector<std::uint8_t> symbols;
  std::vector<Vec3<double>> final;
};
template <class T> Trace trace(const Ensemble& e, long iterations) {
  FinalRecorder f(e.orbits(), iterations);
  SymbolRecorder s(e.orbits(), 1, iterations);
  Both<FinalRecorder, SymbolRecorder> both(f, s);
  run<T>(e, iterations, both);
  return {std::move(s.out), std::move(f.out)};
}
template <class T> std::vector<std::uint8_t> symbols(const Ensemble& e, long iterations) {
  SymbolRecorder s(e.orbits(), 1, iterations);
  run<T>(e, iterations, s);
  return s.out;
}

// The same with the trigonometric algorithm of Appendix A.1 (double); a broken orbit's remaining
// symbols are 0 (never equal to the reference).
Trace trig_trace(const Ensemble& e, long iterations) {
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
      const auto c = reference::trig_b_to_b<double>(s, r);
      if (c.status != reference::TrigStatus::ok) break;
      out[o * iterations + k] = c.letters == "ab" ? 1 : (c.letters == "cb" ? 3 : 2);
      if (k == iterations - 1) t.final[o] = core::from_angles<double>(c.theta, c.phi);
    }
  }
  return t;
}
std::vector<std::uint8_t> trig_symbols(const Ensemble& e, long iterations) { return trig_trace(e, iterations).symbols; }

// Iterations per second of precision T on e (FinalRecorder, all threads), timed over >= 0.3 s.
template <class T> double throughput(const Ensemble& e, long iterations) {
  double items = 0, secs = 0;
  while (secs < 0.3) {
    FinalRecorder f(e.orbits(), iterations);
    const auto t0 = Clock::now();
    run<T>(e, iterations, f);
    secs += std::chrono::duration<double>(Clock::now() - t0).count();
    items += static_cast<double>(e.orbits()) * static_cast<double>(iterations);
  }
  return items / secs;
}

// Largest n of the list such that, for it and every smaller listed n, the 8 first orbits of the Section 4
// grid end on (ab)^n(cb)^n at the middle of the window (lower bound + r_crit,2)/2.
int window_n_max(const std::function<std::vector<std::uint8_t>(const Ensemble&, long)>& sym, const std::vector<int>& ns) {
  int best = 0;
  for (int n : ns) {
    const double lo = static_cast<double>(windows::window_lower_bound(n, 20));
    const double hi = static_cast<double>(windows::r_crit2(n, 20));
    Ensemble e;
    e.r = {0.5 * (lo + hi)};
    const auto g = paper_grid();
    e.initial.assign(g.begin(), g.begin() + 8);
    const long iters = 20000 + 400L * n;  // transients grow with n near 7-4 sqrt(3) (see windows verify)
    const std::vector<std::uint8_t> s = sym(e, iters);
    const long tail = 8L * n;
    for (std::size_t o = 0; o < e.orbits(); ++o)
      if (!windows::on_pattern(&s[o * iters + (iters - tail)], tail, n)) return best;
    best = n;
  }
  return best;
}

// The exact lambda1 = log|l2/l1| / p of a periodic word at r (r the double value, converted exactly), in MPFR
// with 60 digits: the period matrix M, its dominant eigenvalue l1 by Newton on det(t - M) from the double
// estimate, and l2, l3 from t^2 - (tr M - l1) t + det M / l1 (a complex pair when the discriminant is
// negative, then |l2| = sqrt(det M / l1)).  The reference of the Lyapunov error column (double's own
// periodic_exponents is good to ~1e-15 only, too coarse for long double and beyond).
double exact_lambda1(const std::vector<int>& period, double r_double) {
  using core::Mat3;
  using core::mpfr_float;
  const unsigned saved = mpfr_float::default_precision();
  mpfr_float::default_precision(60);
  const mpfr_float r(r_double);
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
  const double res = static_cast<double>(log(l2abs / abs(l1)) / static_cast<int>(period.size()));
  mpfr_float::default_precision(saved);
  return res;
}

// Largest error of lambda1 (weighted Birkhoff average of the projective cocycle, 1e5 steps after a 2000-step
// transient) against the eigenvalues of the period matrix, on the sinks 1133 (r = 0.15), 111333 (r = 0.1)
// and 132312 (r = 0.5), started from the Section 4 grid's first point (0.1, 0.15) or a random point (0.5).
template <class T> double lyapunov_error() {
  struct Case {
    double r;
    Vec3<double> u;
  };
  const std::vector<Case> cases = {{0.15, paper_grid()[0]}, {0.1, paper_grid()[0]}, {0.5, random_points(1, 3)[0]}};
  double worst = 0;
  for (const Case& c : cases) {
    lyapunov::Options opt;
    opt.transient = 2000;
    opt.iterations = 100000;
    const Vec3<T> u(T(c.u(0)), T(c.u(1)), T(c.u(2)));
    const lyapunov::ProjectiveResult res = lyapunov::projective_exponents<T>(u, T(c.r), opt);
    const int p = lyapunov::detect_period(res.symbols_tail, 64, 512);
    if (p == 0) return std::numeric_limits<double>::quiet_NaN();  // not on a sink: no exact value
    const std::vector<int> period(res.symbols_tail.end() - p, res.symbols_tail.end());
    worst = std::max(worst, std::fabs(res.weighted[0] - exact_lambda1(period, c.r)));
  }
  return worst;
}

struct Row {
  std::string method;
  int digits = 0;  // decimal digits of the arithmetic
  double rate = 0;
  std::vector<long> agree_min, agree_median;
  std::vector<double> error_median;  // median angle (rad) between the final state and the reference's
  double lyapunov_error = std::numeric_limits<double>::quiet_NaN();  // linear methods (not trig)
  int n_max = 0;
};

void precision_study(const PrecisionArgs& a) {
  if (a.orbits < 1 || a.orbits > 4096) throw UsageError(fmt::format("orbits: got {}, expected 1..4096", a.orbits));
  if (a.iterations < 10 || a.iterations > 1000000)
    throw UsageError(fmt::format("iterations: got {}, expected 10..1000000", a.iterations));
  for (double r : a.r_values) core::validate_r(r, "r");
  for (int n : a.window_n)
    if (n < 2 || n > 400) throw UsageError(fmt::format("window-n: got {}, expected 2..400", n));
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  io::Progress progress("precision study");

  Ensemble e;
  e.r = a.r_values;
  e.initial = random_points(a.orbits, a.seed);
  const long N = a.iterations;
  using core::mpfr_float;
  // Reference: 256 decimal digits.
  mpfr_float::default_precision(256);
  const Trace reference_trace = trace<mpfr_float>(e, N);
  const std::vector<std::uint8_t>& ref = reference_trace.symbols;

  using SymFn = std::function<std::vector<std::uint8_t>(const Ensemble&, long)>;
  using TraceFn = std::function<Trace(const Ensemble&, long)>;
  struct Method {
    std::string name;
    int digits;
    SymFn sym;
    std::function<double(const Ensemble&, long)> rate;
    TraceFn tr;
  };
  const auto mp = [](int d) {
    return Method{fmt::format("linear/mpfr:{}", d), d,
                  [d](const Ensemble& en, long it) {
                    mpfr_float::default_precision(d);
                    return symbols<mpfr_float>(en, it);
                  },
                  [d](const Ensemble& en, long it) {
                    mpfr_float::default_precision(d);
                    return throughput<mpfr_float>(en, it);
                  },
                  [d](const Ensemble& en, long it) {
                    mpfr_float::default_precision(d);
                    return trace<mpfr_float>(en, it);
                  }};
  };
  std::vector<Method> methods = {
      {"linear/float", 7, symbols<float>, throughput<float>, trace<float>},
      {"linear/double", 16, symbols<double>, throughput<double>, trace<double>},
      {"linear/long-double", 19, symbols<long double>, throughput<long double>, trace<long double>},
      {"linear/float128", 34, symbols<core::float128>, throughput<core::float128>, trace<core::float128>},
      mp(50),
      mp(100),
      {"trig/double", 16, trig_symbols,
       [](const Ensemble& en, long it) {
         const auto t0 = Clock::now();
         trig_symbols(en, it);
         return static_cast<double>(en.orbits()) * static_cast<double>(it) /
                std::chrono::duration<double>(Clock::now() - t0).count();
       },
       trig_trace},
  };

  std::vector<Row> rows;
  std::size_t step = 0;
  for (const Method& m : methods) {
    progress.update(step++, methods.size());
    Row row;
    row.method = m.name;
    row.digits = m.digits;
    const Trace tr = m.tr(e, N);
    const std::vector<std::uint8_t>& s = tr.symbols;
    const std::size_t n_ic = e.initial.size();
    for (std::size_t ir = 0; ir < e.r.size(); ++ir) {
      std::vector<long> agree;
      std::vector<double> err;
      for (std::size_t ic = 0; ic < n_ic; ++ic) {
        const std::size_t o = ir * n_ic + ic;
        long k = 0;
        while (k < N && s[o * N + k] == ref[o * N + k]) ++k;
        agree.push_back(k);
        const Vec3<double>& a_ = tr.final[o];
        const Vec3<double>& b_ = reference_trace.final[o];
        err.push_back(std::isfinite(a_.sum()) ? std::atan2(a_.cross(b_).norm(), a_.dot(b_)) : M_PI);
      }
      std::sort(err.begin(), err.end());
      row.error_median.push_back(err[err.size() / 2]);
      std::sort(agree.begin(), agree.end());
      row.agree_min.push_back(agree.front());
      row.agree_median.push_back(agree[agree.size() / 2]);
    }
    // Throughput on a workload sized to the method's speed.
    Ensemble w;
    w.r = {0.2};
    // Enough orbits to fill the SIMD batches and both threads (8192 for float/double), fewer for the
    // slow types so that one timing takes about a second.
    const long n_orbits = m.digits > 34 ? 16 : (m.digits > 16 || m.name.starts_with("trig") ? 256 : 8192);
    w.initial = random_points(n_orbits, a.seed + 1);
    row.rate = m.rate(w, m.digits > 34 ? 200 : 2000);
    row.n_max = m.name.starts_with("trig") ? -1 : window_n_max(m.sym, a.window_n);
    if (m.name == "linear/float") row.lyapunov_error = lyapunov_error<float>();
    if (m.name == "linear/double") row.lyapunov_error = lyapunov_error<double>();
    if (m.name == "linear/long-double") row.lyapunov_error = lyapunov_error<long double>();
    if (m.name == "linear/float128") row.lyapunov_error = lyapunov_error<core::float128>();
    if (m.name.starts_with("linear/mpfr:")) {
      mpfr_float::default_precision(static_cast<unsigned>(m.digits));
      row.lyapunov_error = lyapunov_error<mpfr_float>();
    }
    rows.push_back(row);
  }
  progress.update(methods.size(), methods.size());

  std::ostringstream csv;
  csv << "# btob precision study: symbol agreement with a 256-digit MPFR run of the same orbits, and the angle (rad) "
         "between the final states (median over orbits); lyapunov_error: largest |lambda1 - exact| on the sinks 1133 "
         "(r=0.15), 111333 (r=0.1), 132312 (r=0.5), weighted average of 1e5 steps, against log|l2/l1|/p of the period "
         "matrix in 60-digit MPFR (exponents are reported in double: 0 means below the double resolution, ~1e-16)\n";
  csv << fmt::format("# orbits={} random:{} seed={} iterations={} window test: 8 orbits of the Section 4 grid at "
                     "the middle of window n, 20000+400n iterations, n in [{}]; version {} ({})\n",
                     a.orbits, a.orbits, a.seed, N, fmt::join(a.window_n, " "), build::version, build::git_commit);
  csv << "method,decimal_digits,iterations_per_second";
  for (double r : a.r_values) csv << fmt::format(",agree_min_r{0},agree_median_r{0},final_error_median_r{0}", r);
  csv << ",window_n_max,lyapunov_error\n";
  for (const Row& row : rows) {
    csv << fmt::format("{},{},{:.4g}", row.method, row.digits, row.rate);
    for (std::size_t i = 0; i < row.agree_min.size(); ++i)
      csv << "," << row.agree_min[i] << "," << row.agree_median[i] << fmt::format(",{:.3g}", row.error_median[i]);
    csv << "," << (row.n_max < 0 ? std::string("") : std::to_string(row.n_max)) << ","
        << (std::isnan(row.lyapunov_error) ? std::string("") : fmt::format("{:.3g}", row.lyapunov_error)) << "\n";
  }
  io::write_text_atomic(out / "tradeoff.csv", csv.str());
  io::Attrs attrs = io::provenance(invocation());
  attrs["orbits"] = a.orbits;
  attrs["iterations"] = N;
  attrs["seed"] = static_cast<long>(a.seed);
  attrs["reference"] = std::string("mpfr:256");
  io::write_manifest(out / "tradeoff.json", attrs);
  std::cout << csv.str();
  if (!a.no_plot) io::run_plot("precision_tradeoff.py", {(out / "tradeoff.csv").string(), (out / "tradeoff.png").string()});
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<PrecisionArgs>();
  CLI::App* c = app.add_subcommand("precision", "Speed against accuracy of each precision and algorithm (vs 256-digit MPFR)");
  c->add_option("--orbits", a->orbits, "random initial conditions per r")->capture_default_str();
  c->add_option("--iterations", a->iterations, "symbols compared per orbit")->capture_default_str();
  c->add_option("--r", a->r_values, "r values of the symbol comparison")->expected(1, -1);
  c->add_option("--window-n", a->window_n, "window indices n tested near 7-4*sqrt(3)")->expected(1, -1);
  c->add_option("--seed", a->seed, "seed of the random initial conditions")->capture_default_str();
  c->add_option("--out", a->out, "output directory")->capture_default_str();
  c->add_flag("--no-plot", a->no_plot, "write data only");
  c->callback([a] { precision_study(*a); });
});

}  // namespace
}  // namespace btob::cli
