// SPDX-License-Identifier: GPL-3.0-or-later
// The particle check of a periodic pattern: the start from the periodic point, the predictions from the period
// matrix, the run and its cost, and explicit instantiations of the simulator.
#include "particles/particles_impl.hpp"

#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "patterns/patterns.hpp"
#include "reference/reference_impl.hpp"

#include <boost/multiprecision/eigen.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace btob::particles {

#define BTOB_PARTICLES_INSTANTIATE_G(T, G)                              \
  template void collide<T, G>(Vec<T, G>&, int, const T&);               \
  template int next_collision<T, G>(const Gaps<T, G>&, T&);             \
  template void advance<T, G>(Gaps<T, G>&, const T&, int, const T&);    \
  template Eigen::Matrix<T, G + 1, 1> absolute<T, G>(const Vec<T, G>&); \
  template T kinetic_energy<T, G>(const Vec<T, G>&);
#define BTOB_PARTICLES_INSTANTIATE(T)                                                                           \
  BTOB_PARTICLES_INSTANTIATE_G(T, 1)                                                                            \
  BTOB_PARTICLES_INSTANTIATE_G(T, 2)                                                                            \
  BTOB_PARTICLES_INSTANTIATE_G(T, 3)                                                                            \
  template PatternRun<T> simulate_pattern<T>(const Gaps<T, 3>&, const std::string&, const T&, long, bool, long, \
                                             const core::CancelToken*);
BTOB_PARTICLES_INSTANTIATE(double)
BTOB_PARTICLES_INSTANTIATE(long double)
BTOB_PARTICLES_INSTANTIATE(core::float128)
BTOB_PARTICLES_INSTANTIATE(core::mpfr_float)
#undef BTOB_PARTICLES_INSTANTIATE
#undef BTOB_PARTICLES_INSTANTIATE_G

namespace {

template <class T> T sqrt_(const T& x) {
  using std::sqrt;
  return sqrt(x);
}

}  // namespace

// The restriction of K_w to the plane normal to u (invariant: u is a left eigenvector of K_w, since
// cof(K_w) u = r^n2 M_w u is parallel to u), in the orthonormal basis e1 = p/|p|, e2 = u x e1.
template <class T>
bool self_similar_start(const core::Vec3<T>& u, const std::string& letters, const T& r, Gaps<T, 3>& out) {
  const core::Particles<T> normal = core::to_particles<T>(u);
  out = {normal.p, normal.q};
  const Vec<T, 3>& p = normal.p;
  Vec<T, 3>& q = out.q;
  core::Mat3<T> K = core::Mat3<T>::Identity();
  for (char c : letters) K = reference::collision_matrix<T>(c, r) * K;
  const Vec<T, 3> e1 = p / detail::norm3(p);
  Vec<T, 3> e2 = u.cross(e1);
  e2 /= detail::norm3(e2);
  const T a = e1.dot(K * e1), b = e1.dot(K * e2), c = e2.dot(K * e1), d = e2.dot(K * e2);
  const T tr = a + d, det = a * d - b * c, disc = tr * tr / 4 - det;
  if (!(disc >= 0)) return false;
  const T s = sqrt_<T>(disc);
  const T mu = tr >= 0 ? T(tr / 2 + s) : T(tr / 2 - s);  // largest modulus
  if (!(mu > 0)) return false;
  // (K - mu) restricted: rows (a - mu, b), (c, d - mu); the eigenvector from the larger row.
  Vec<T, 3> v;
  using std::abs;
  if (abs(a - mu) + abs(b) >= abs(c) + abs(d - mu)) v = b * e1 - (a - mu) * e2;
  else v = (d - mu) * e1 - c * e2;
  v /= detail::norm3(v);
  if (v(1) < 0) v = -v;
  q = v;
  return true;
}

template bool self_similar_start<double>(const core::Vec3<double>&, const std::string&, const double&,
                                         Gaps<double, 3>&);
template bool self_similar_start<long double>(const core::Vec3<long double>&, const std::string&, const long double&,
                                              Gaps<long double, 3>&);
template bool self_similar_start<core::float128>(const core::Vec3<core::float128>&, const std::string&,
                                                 const core::float128&, Gaps<core::float128, 3>&);
template bool self_similar_start<core::mpfr_float>(const core::Vec3<core::mpfr_float>&, const std::string&,
                                                   const core::mpfr_float&, Gaps<core::mpfr_float, 3>&);

namespace {

// The word's verdict at r as the result's header: names, moduli of M_w (squares of those of J M_h when
// w = h J(h)), and whether K_w predicts a self-similar collapse.  Returns the moduli in T.
template <class T>
std::vector<T> pattern_header(const ParticlesRequest& req, const patterns::Verdict<T>& v, const T& r,
                              ParticlesResult& res, const core::CancelToken* cancel) {
  res.word = patterns::to_paper(v.word);
  res.digits = patterns::to_digits(v.word);
  res.letters = v.letters;
  res.outcome = patterns::outcome_name(v.outcome);
  res.r = req.r;
  res.periods = req.periods;
  res.precision = req.precision;
  res.start = req.start;
  std::vector<T> mod;
  for (const auto& e : v.spectrum) mod.push_back(v.reduced ? T(e.modulus * e.modulus) : e.modulus);
  for (const auto& m : mod) res.moduli.push_back(static_cast<double>(m));
  res.orbit_eigen = v.orbit_eigen;
  res.collapse = patterns::classify<T>(v.word, r, cancel).collapse;
  return mod;
}

// The contractions per period of length, velocity and time that the period matrix predicts for a collapse (NaN
// and the reason otherwise).
template <class T>
void predict_contractions(const patterns::Verdict<T>& v, const T& r, const std::vector<T>& mod, ParticlesResult& res) {
  if (res.collapse) {
    const int o = v.orbit_eigen, ia = o == 0 ? 1 : 0, ib = o == 2 ? 1 : 2;
    long n2 = 0;
    for (auto c : v.word.s) n2 += c == 2;
    using std::pow;
    const T rn2 = pow(r, static_cast<int>(n2));
    res.length_predicted = static_cast<double>(sqrt_(T(rn2 * mod[o] * mod[ib] / mod[ia])));
    res.velocity_predicted = static_cast<double>(sqrt_(T(rn2 * mod[o] * mod[ia] / mod[ib])));
    res.time_predicted = static_cast<double>(T(mod[ib] / mod[ia]));
  } else {
    res.length_predicted = res.velocity_predicted = res.time_predicted = std::nan("");
    res.failure =
        "no collapse: the eigenvalues of K_w on the orbit's plane are not real with a positive dominant one "
        "(M_w's other two eigenvalues are not real, or tie); started normal";
  }
}

// The start right after the b-collision of the periodic point u (in Q), p = u x e_y = (-z, 0, x), unit gaps: the
// exact self-similar collapse when asked and predicted, else the best of q - lambda p for lambda = 0, then
// 4^k |q| / |p| (k = 0..40): the first that reproduces three periods (or fewer if asked), else the one that
// reproduces the most collisions.
template <class T>
Gaps<T, 3> pattern_start(const ParticlesRequest& req, const patterns::Verdict<T>& v, const T& r, bool collapse,
                         const core::RunControl& control) {
  const Vec<T, 3> u = v.orbit.front();
  const core::Particles<T> normal = core::to_particles<T>(u);
  Gaps<T, 3> start{normal.p, normal.q};
  if (!(req.start == "self-similar" && collapse && self_similar_start<T>(u, v.letters, r, start))) {
    const long probe = std::min<long>(3, req.periods);
    T lambda = T(0);
    long best = -1;
    for (int k = 0; k <= 41; ++k) {
      Gaps<T, 3> s{normal.p, Vec<T, 3>(normal.q - lambda * normal.p)};
      const PatternRun<T> pr = simulate_pattern<T>(s, v.letters, r, probe, true, 0, control.cancel);
      if (pr.collisions > best) {
        best = pr.collisions;
        start = s;
      }
      if (pr.periods_ok == probe) break;
      lambda = k == 0 ? T(1) : T(lambda * 4);
    }
  }
  start.p /= detail::norm3(start.p);
  start.q /= detail::norm3(start.q);
  return start;
}

// The rescaled run, polling the cancellation token every core::cancel_stride periods: the first diagram_periods
// with their events (kept in res.events), then, when more are asked, all periods again from the start (the first
// diagram_periods recomputed identically; the cost is negligible) so that the run is one trajectory.
template <class T>
PatternRun<T> rescaled_run(const ParticlesRequest& req, const Gaps<T, 3>& start, const std::string& letters, const T& r,
                           const core::RunControl& control, ParticlesResult& res) {
  PatternRun<T> run = simulate_pattern<T>(start, letters, r, std::min<long>(req.periods, req.diagram_periods), true,
                                          req.diagram_periods, control.cancel);
  res.events = run.events;
  if (req.periods > req.diagram_periods && run.failure.empty()) {
    core::check_cancel(control.cancel);
    run = simulate_pattern<T>(start, letters, r, req.periods, true, 0, control.cancel);
  }
  if (control.progress) control.progress->update(1, 1);
  return run;
}

// The measured contractions: per-period ratios, their last values, the spread of the length ratio over the second
// half, and the time to collapse (the simulated periods plus the geometric tail with the last ratio; NaN when the
// particles left the pattern).
template <class T>
void measured_contractions(const ParticlesRequest& req, const PatternRun<T>& run, ParticlesResult& res) {
  res.periods_ok = run.periods_ok;
  res.sequence_ok = run.periods_ok == req.periods;
  if (!run.failure.empty()) res.failure = res.failure.empty() ? run.failure : res.failure + "; " + run.failure;
  res.length_ratio = run.length_ratio;
  res.velocity_ratio = run.velocity_ratio;
  res.time_ratio = run.time_ratio;
  const std::size_t N = run.length_ratio.size();
  if (N > 0) {
    res.length_contraction = run.length_ratio.back();
    res.velocity_contraction = run.velocity_ratio.back();
    res.energy_ratio = res.velocity_contraction * res.velocity_contraction;
    res.time_contraction = N > 1 ? res.time_ratio.back() : std::nan("");
    for (std::size_t n = N / 2; n < N; ++n)
      res.length_spread = std::max(res.length_spread, std::abs(run.length_ratio[n] / res.length_contraction - 1));
    const double q = N > 1 ? res.time_ratio.back() : res.time_predicted;
    res.time_to_collapse = static_cast<double>(run.total_time) + (q < 1 ? run.duration.back() * q / (1 - q) : INFINITY);
  }
  if (N == 0)
    res.length_contraction = res.velocity_contraction = res.time_contraction = res.energy_ratio = std::nan("");
  if (!res.sequence_ok) res.time_to_collapse = std::nan("");
}

// The diagram's events with their times: since the start and to collapse (the rest of their period, the later
// periods and the geometric tail; NaN when the particles left the pattern).  7 values per event in, 8 out.
template <class T> std::vector<double> timed_events(const PatternRun<T>& run, const ParticlesResult& res) {
  const std::size_t N = run.length_ratio.size();
  std::vector<double> after(N + 1, 0.0), before(N + 1, 0.0);  // time from the end / up to the start of period n
  const double q = N > 1 ? res.time_ratio.back() : res.time_predicted;
  after[N] = N > 0 && q < 1 ? run.duration.back() * q / (1 - q) : 0.0;
  for (std::size_t n = N; n-- > 0;) after[n] = after[n + 1] + run.duration[n];
  for (std::size_t n = 0; n < N; ++n) before[n + 1] = before[n] + run.duration[n];
  std::vector<double> ev;
  for (std::size_t e = 0; e + 7 <= res.events.size(); e += 7) {
    const auto n = static_cast<std::size_t>(res.events[e]);
    const double offset = res.events[e + 1];
    ev.push_back(res.events[e]);
    ev.push_back(before[std::min(n, N)] + offset);
    ev.push_back(res.sequence_ok && n < N ? (run.duration[n] - offset) + after[n + 1] : std::nan(""));
    for (int k = 2; k < 7; ++k) ev.push_back(res.events[e + k]);
  }
  return ev;
}

// Without rescaling: the same run until the gaps underflow, against the collisions T's range predicts.
template <class T>
void unrescaled_run(const ParticlesRequest& req, const Gaps<T, 3>& start, const std::string& letters, const T& r,
                    const core::RunControl& control, ParticlesResult& res) {
  const PatternRun<T> raw = simulate_pattern<T>(start, letters, r, req.periods, false, 0, control.cancel);
  res.collisions_unrescaled = raw.collisions;
  res.unrescaled_end = raw.failure.empty() ? fmt::format("all {} periods reproduced", req.periods) : raw.failure;
  using std::log;
  const double lmin = static_cast<double>(T(log(std::numeric_limits<T>::min())));
  res.collisions_limit_predicted = res.length_predicted > 0 && res.length_predicted < 1
                                       ? lmin / std::log(res.length_predicted) * static_cast<double>(letters.size())
                                       : INFINITY;
}

// header -> predictions -> start -> rescaled run -> contractions -> timed events -> unrescaled run.
template <class T> ParticlesResult run_impl(const ParticlesRequest& req, const core::RunControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  const T r = core::from_decimal<T>(req.r.text);  // T nearest the decimal, not double's value widened
  const patterns::Verdict<T> v = patterns::analyse<T>(patterns::parse_word(req.word, "word"), r, control.cancel);
  ParticlesResult res;
  const std::vector<T> mod = pattern_header<T>(req, v, r, res, control.cancel);
  predict_contractions<T>(v, r, mod, res);
  const Gaps<T, 3> start = pattern_start<T>(req, v, r, res.collapse, control);
  const PatternRun<T> run = rescaled_run<T>(req, start, v.letters, r, control, res);
  measured_contractions<T>(req, run, res);
  res.events = timed_events<T>(run, res);
  res.split_events();
  unrescaled_run<T>(req, start, v.letters, r, control, res);
  res.seconds = core::seconds_since(t0);
  return res;
}

}  // namespace

ParticlesResult run(const ParticlesRequest& req, const core::RunControl& control) {
  req.validate();
  core::check_cancel(control.cancel);
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  switch (prec.kind) {
    case core::Precision::Kind::f80: return run_impl<long double>(req, control);
    case core::Precision::Kind::f128: return run_impl<core::float128>(req, control);
    case core::Precision::Kind::mpfr: {
      core::mpfr_float::default_precision(static_cast<unsigned>(prec.mpfr_digits));
      return run_impl<core::mpfr_float>(req, control);
    }
    default: return run_impl<double>(req, control);
  }
}

namespace {
// The collisions run() simulates for `periods` periods of `letters` collisions each: the diagram's first periods
// (event by event), then the rescaled run of every period, then the unrescaled run.  That last run stops where its
// gaps underflow: in MPFR (an exponent range of ~2^30 binary orders) it runs every period and is counted; in double,
// long double and float128 it stops after a few hundred to a few thousand periods and is not counted.  A normal start
// adds up to 42 trial runs of 3 periods, also not counted.  A pattern that fails stops early (an upper bound).
double collisions(double letters, long periods, long diagram_periods, bool mpfr) {
  const double rescaled = static_cast<double>(std::min(periods, diagram_periods)) +
                          (periods > diagram_periods ? static_cast<double>(periods) : 0.0);
  return letters * (rescaled + (mpfr ? static_cast<double>(periods) : 0.0));
}
}  // namespace

core::Work work(const ParticlesRequest& req) {
  const core::Precision prec = core::parse_precision(req.precision, "precision");
  const bool mpfr = prec.kind == core::Precision::Kind::mpfr;
  // The collision letters of one period (a symbol 1 or 3 is one collision, 2 is two): the pattern tool's, in double.
  const double letters = static_cast<double>(
      patterns::analyse<double>(patterns::parse_word(req.word, "word"), static_cast<double>(req.r)).letters.size());
  core::Work w;
  core::Term t;
  t.route = "particles events " + prec.name();
  t.units = collisions(letters, req.periods, req.diagram_periods, mpfr);
  t.what =
      fmt::format("particle collisions in {} ({} per period x ({} periods{}))", req.precision, letters, req.periods,
                  mpfr ? " rescaled + as many unrescaled"
                       : " rescaled; the unrescaled run stops "
                         "where its gaps underflow, not counted");
  t.probe = [precision = req.precision, mpfr](double n, const core::RunControl& c) {
    ParticlesRequest p;  // 1133 at r = 0.15: a stable collapse, simulated to the last period
    p.word = "1133";
    p.r = core::Decimal::parse("0.15", "r");
    p.precision = precision;
    p.diagram_periods = 1;
    p.periods = std::clamp(static_cast<long>(n / (mpfr ? 16 : 8)), 2L, 100000000L);
    (void)run(p, c);
    return collisions(8, p.periods, p.diagram_periods, mpfr);
  };
  w.terms.push_back(std::move(t));
  w.bound = "a pattern that fails stops there";
  // NAME.csv (one row), convergence.csv (a row per period up to 100, then 20 per decade, 7 numbers), events.csv (a row
  // per event of the diagram's periods, 8 numbers); ~20 bytes a number.  The run keeps per period a few doubles.
  const double p = static_cast<double>(req.periods);
  const double conv_rows = std::min(p, 100.0) + (p > 100 ? 20 * std::log10(p / 100) : 0.0);
  // NAME.h5 holds three ratios per period (length, time, velocity; 8 bytes each) and the diagram's events.
  w.output_bytes = 400 + 140 * conv_rows + 160 * letters * static_cast<double>(req.diagram_periods) + 24 * p;
  w.peak_bytes = 64 * p + 64 * letters * static_cast<double>(req.diagram_periods) + 65536;
  return w;
}

}  // namespace btob::particles
