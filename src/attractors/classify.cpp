// SPDX-License-Identifier: GPL-3.0-or-later
// Per-orbit classification on the batched kernel (Section 8.1 (1)): pass 1 (return, collapse), pass 2 (lambda1, the
// P2 rotation number), refinement; attractor identity and collection.
#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/multiprecision/gmp.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "attractors/recorders.hpp"
#include "attractors/stages.hpp"
#include "core/coords.hpp"
#include "core/error_bar.hpp"
#include "core/fields.hpp"
#include "iterate/cocycle.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/maps.hpp"
#include "lyapunov/tangent.hpp"

namespace btob::attractors {
namespace stages {

// No margin: for the double r, 7 - r > 0 and (7 - r)^2 >= 48 in rational arithmetic (a collapse verdict above the
// threshold is one the paper rules out).
bool collapse_possible(double r) {
  using Q = boost::multiprecision::mpq_rational;
  const Q d = Q(7) - Q(r);
  return d * d >= 48;
}

namespace {
// Order 1 < 3 < 2 of patterns::canonical.
int rank(std::uint8_t s) { return s == 1 ? 0 : (s == 3 ? 1 : 2); }
bool less_word(const patterns::Word& a, const patterns::Word& b) {
  return std::lexicographical_compare(a.s.begin(), a.s.end(), b.s.begin(), b.s.end(),
                                      [](std::uint8_t x, std::uint8_t y) { return rank(x) < rank(y); });
}
}  // namespace

patterns::Word smallest_rotation(const patterns::Word& w, std::size_t* shift) {
  patterns::Word best = w;
  std::size_t k_best = 0;
  for (std::size_t k = 1; k < w.size(); ++k) {
    patterns::Word c = patterns::rotate(w, k);
    if (less_word(c, best)) best = std::move(c), k_best = k;
  }
  if (shift) *shift = k_best;
  return best;
}

}  // namespace stages

using namespace stages;

namespace {

// The floor lyapunov puts under every bar (lyapunov_impl.hpp, with_rounding_floor): 4 eps |lambda1| (at least 4 eps),
// the arithmetic's share, which batch means cannot see (a cycle's block means agree exactly) and which is the whole
// error of a cycle's exponent log|mu2/mu1|/p evaluated in double.  So err is never 0, and a periodic orbit's
// printed interval contains lyapunov's estimate of the same orbit.
namespace {
double rounding_floor(double lambda1) {
  return 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(lambda1));
}
}  // namespace

// ---- pass 1: the window after the transient (return, collapse) ----

// What pass 1 saw of orbit o: its point, final state, closest return, whether it stayed in the P2 region.
void window_evidence(const ReturnRecorder& rec, std::size_t o, OrbitVerdict& v) {
  v.iterations = rec.total_steps();
  v.point = Vec3<double>(rec.s0x[o], rec.s0y[o], rec.s0z[o]);
  v.residual = rec.best_d[o];
  v.closest_return = rec.best_j[o];
  v.p2_region = rec.n1[o] == 0 && rec.n3[o] == 0;
}

// Three-particle collapse (Section 5.2): symbol 1 (3) over the whole window and theta -> 0 (pi/2).  True if decided.
bool collapse_verdict(const ReturnRecorder& rec, std::size_t o, double r, const Vec3<double>& fin, const Options& opt,
                      OrbitVerdict& v) {
  const double th = core::theta<double>(fin);
  if (rec.n1[o] == opt.window && th < opt.collapse_theta) {
    v.type = Type::collapse, v.period = 1, v.word.s = {1}, v.key = "C1";
    v.lambda1 = patterns::analyse<double>(v.word, r).lyapunov2;  // exponent of P1 on z = 0 (exact)
    v.err1 = rounding_floor(v.lambda1);
    v.detail = fmt::format("theta = {:.3g} after {} steps, symbol 1 throughout the window", th, v.iterations);
    return true;
  }
  if (rec.n3[o] == opt.window && std::numbers::pi / 2 - th < opt.collapse_theta) {
    v.type = Type::collapse, v.period = 1, v.word.s = {3}, v.key = "C3";
    v.lambda1 = patterns::analyse<double>(v.word, r).lyapunov2;  // exponent of P3 on x = 0 (exact)
    v.err1 = rounding_floor(v.lambda1);
    v.detail = fmt::format("pi/2 - theta = {:.3g} after {} steps, symbol 3 throughout the window",
                           std::numbers::pi / 2 - th, v.iterations);
    return true;
  }
  return false;
}

// The exact cycle of a key word at r, computed once per key.
const ExactCycle& exact_cycle(const std::string& key, const patterns::Word& key_word, double r, ExactCycles& exact) {
  auto it = exact.find(key);
  if (it == exact.end()) {
    ExactCycle e;
    e.verdict = patterns::analyse<double>(key_word, r);
    for (const auto& q : e.verdict.orbit) e.points.push_back(q);
    it = exact.emplace(key, std::move(e)).first;
  }
  return it->second;
}

// An orbit that returned after p steps: periodic if its point lies on the exact cycle of its word.  False when the
// return is left to pass 2 (no exact orbit for the word outside the P2 region).
bool periodic_verdict(const ReturnRecorder& rec, std::size_t o, int p, double r, const Options& opt, ExactCycles& exact,
                      OrbitVerdict& v) {
  patterns::Word w;
  for (int j = 1; j <= p; ++j) w.s.push_back(static_cast<std::uint8_t>(rec.symbol(o, j)));
  v.period = p;
  v.residual = rec.resid[o];
  v.closest_return = p;
  v.word = w;
  const patterns::Word key_word = smallest_rotation(w);
  const std::string key = "P" + patterns::to_digits(key_word);
  const ExactCycle& e = exact_cycle(key, key_word, r, exact);
  v.lambda1 = e.verdict.lyapunov2;  // the cycle's exponent log|l2/l1|/p from the pattern tool (exact)
  v.err1 = rounding_floor(v.lambda1);
  if (e.points.empty()) {
    // No feasible real eigenvector: a numerically periodic orbit the pattern tool cannot confirm.  In the P2 region
    // a rational P2 rotation (Section 5.2, whose cycles are neutral): periodic, reported, not hidden.  Elsewhere a
    // slow passage that no periodic orbit explains (e.g. near 7 - 4 sqrt(3), where P3's (y, z) rotation turns by
    // ~1e-9 per step near its slow direction): measured in pass 2 like an orbit without a period.
    if (!v.p2_region) {
      v.period = 0, v.word = {}, v.lambda1 = 0, v.err1 = 0;
      v.residual = rec.best_d[o], v.closest_return = rec.best_j[o];
      return false;
    }
    v.type = Type::periodic, v.key = key;
    v.detail = fmt::format("no exact orbit for this word at r ({}: {})", patterns::outcome_name(e.verdict.outcome),
                           e.verdict.reason);
    return true;
  }
  double d = std::numeric_limits<double>::infinity();
  for (const auto& q : e.points) d = std::min(d, dist_max(q, v.point));
  if (d < opt.point_tol) {
    v.type = Type::periodic, v.key = key;
    v.detail = fmt::format("|u_p - u_0| = {:.2g}, distance to the exact cycle {:.2g}", v.residual, d);
  } else {
    v.detail = fmt::format("returns after {} steps ({:.2g}) but lies {:.2g} from the exact cycle of its word", p,
                           v.residual, d);
  }
  return true;
}

// Pass 1's verdict on orbit o; false when it needs pass 2 (no period, no collapse).
bool window_verdict(const ReturnRecorder& rec, std::size_t o, const iterate::Ensemble& ens, const Options& opt,
                    ExactCycles& exact, OrbitVerdict& v, Vec3<double>& latest) {
  const double r = ens.r[0];
  window_evidence(rec, o, v);
  const Vec3<double> fin(rec.fx[o], rec.fy[o], rec.fz[o]);
  latest = fin;
  if (collapse_possible(r) && collapse_verdict(rec, o, r, fin, opt, v)) return true;
  // Above 7 - 4 sqrt(3) no orbit collapses, and an orbit whose x (z) underflowed to 0 from a start off that plane
  // is still followed faithfully: 0 is x rounded to double (x far below the other components' last bit), every
  // later rounded value is the one the exact x would give (x enters a y - x, r x and a x only, next to terms
  // 2^-400 times larger or more), and the plane is left when the (y, z) rotation of P3 leaves the cone a y < z,
  // which does not depend on x.  The verdict is that of the orbit, from the steps below.
  const int p = rec.period[o];
  if (p <= 0) return false;
  return periodic_verdict(rec, o, p, r, opt, exact, v);
}

// ---- pass 2: lambda1 and the P2 rotation number of the orbits without a period ----

// Pass 2's measurements: lambda1 of every orbit, the rotation run of those it decides, and every orbit's last state.
struct PassTwo {
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  lyapunov::OrbitExponents exponents;
  std::vector<std::size_t> rotation_index;  // orbit i's index in the rotation run, or none
  std::optional<RotationRecorder> rotation;
  std::vector<Vec3<double>> last;
};

// The rotation number and the P2 invariant decide only between quasi-periodic and undecided: wanted for the orbits
// whose lambda1 is zero within its bar where P2 rotates.
bool wants_rotation(const PassTwo& two, std::size_t i, double r, const Options& opt) {
  return RotationRecorder::defined(r) &&
         lyapunov::classify(two.exponents.lambda1[i], two.exponents.err1[i], opt.lyap_iterations) == 0;
}

// lambda1 from the fused cocycle kernel (iterate/cocycle.hpp) for every orbit; the rotation from a plain run of the
// orbits that want it (the run records every step's point and steps the same points bit for bit).
void pass_two_fused(const iterate::Ensemble& pass_two, const Options& opt, PassTwo& two) {
  const double r = pass_two.r[0];
  const long steps = opt.lyap_transient + opt.lyap_iterations;
  PassTwoSums sums(pass_two, opt.lyap_transient, opt.lyap_iterations, opt.lyap_blocks);
  iterate::run_cocycle<double>(pass_two, steps, sums, opt.run);
  two.exponents = lyapunov::exponents_from(pass_two, sums.n, sums.blocks, sums.block_end, sums.cum);
  iterate::Ensemble rotation_orbits;
  rotation_orbits.r = {r};
  for (std::size_t i = 0; i < pass_two.initial.size(); ++i) {
    two.last[i] = Vec3<double>(sums.fx[i], sums.fy[i], sums.fz[i]);
    if (wants_rotation(two, i, r, opt))
      two.rotation_index[i] = rotation_orbits.initial.size(), rotation_orbits.initial.push_back(pass_two.initial[i]);
  }
  if (rotation_orbits.initial.empty()) return;  // no recorder: its weights cost 2 exp per step (a chaotic point's 20%)
  two.rotation.emplace(rotation_orbits.initial.size(), r, opt.lyap_transient, opt.lyap_iterations);
  iterate::run<double>(rotation_orbits, steps, *two.rotation, opt.run);
}

// Below the r the fused kernel takes (r < 4.7e-7, where pass 1 has nearly always found a collapse) the tangent
// vector rides one plain run with the rotation as a per-step recorder.
void pass_two_plain(const iterate::Ensemble& pass_two, const Options& opt, PassTwo& two) {
  const double r = pass_two.r[0];
  const std::size_t n = pass_two.initial.size();
  lyapunov::TangentRecorder tan(pass_two, opt.lyap_transient, opt.lyap_iterations, opt.lyap_blocks);
  two.rotation.emplace(n, r, opt.lyap_transient, opt.lyap_iterations);
  iterate::Both<lyapunov::TangentRecorder, RotationRecorder> both(tan, *two.rotation);
  iterate::run<double>(pass_two, opt.lyap_transient + opt.lyap_iterations, both, opt.run);
  two.exponents = lyapunov::exponents_from(tan);
  for (std::size_t i = 0; i < n; ++i) {
    two.last[i] = Vec3<double>(two.rotation->fx[i], two.rotation->fy[i], two.rotation->fz[i]);
    if (wants_rotation(two, i, r, opt)) two.rotation_index[i] = i;
  }
}

PassTwo run_pass_two(const iterate::Ensemble& pass_two, const Options& opt) {
  PassTwo two;
  two.rotation_index.assign(pass_two.initial.size(), PassTwo::none);
  two.last.resize(pass_two.initial.size());
  if (iterate::cocycle_accepts<double>(pass_two.r)) pass_two_fused(pass_two, opt, two);
  else pass_two_plain(pass_two, opt, two);
  return two;
}

// Pass 2's verdict on its orbit i: chaotic, quasi-periodic or undecided (with the reason).
void exponent_verdict(const PassTwo& two, std::size_t i, double r, const Options& opt, OrbitVerdict& v) {
  v.iterations += opt.lyap_transient + opt.lyap_iterations;
  v.lambda1 = two.exponents.lambda1[i], v.err1 = std::max(two.exponents.err1[i], rounding_floor(v.lambda1));
  if (const std::size_t k = two.rotation_index[i]; k != PassTwo::none) {
    const RotationRecorder& rot = *two.rotation;
    v.invariant = rot.invariant(k);
    v.invariant_spread = (rot.i_max[k] - rot.i_min[k]) / std::fabs(v.invariant);
    v.rotation = rot.rotation(k);
    v.rotation_delta = std::fabs(rot.rotation(k) - rot.rotation_half(k));
  }
  const int sign = lyapunov::classify(v.lambda1, v.err1, opt.lyap_iterations);
  const core::ValueWithError shown = core::with_error(v.lambda1, v.err1);  // the interval contains lambda1
  const std::string lam =
      fmt::format("lambda1 = {} +- {} (batch means, without the finite-time bias)", shown.value, shown.error);
  // "zero" means within lyapunov::classify's bar, which the detail states: three standard errors plus the
  // finite-time floor 10 / n, so that an exponent many standard errors from 0 but under the floor reads as such.
  const std::string zero = fmt::format("{} is zero within 3 batch_err + 10/n = {:.2g}", lam,
                                       3 * v.err1 + 10.0 / static_cast<double>(opt.lyap_iterations));
  if (sign > 0) {
    v.type = Type::chaotic, v.key = "X";
    v.detail = lam + " > 0";
  } else if (sign < 0) {
    v.detail = fmt::format(
        "{} < 0 but no return within {} steps (closest {:.2g} at {}): slow convergence or a "
        "longer period",
        lam, opt.max_period, v.residual, v.closest_return);
  } else if (!RotationRecorder::defined(r)) {
    v.detail = zero + ", but r <= 3 - 2 sqrt(2): no P2 rotation to test";
  } else if (v.rotation_delta < opt.rotation_tol) {
    v.type = Type::quasi_periodic;
    v.key = v.p2_region ? "Q2" : "Q";
    v.detail = fmt::format("{}; rotation {:.10f} turns (half-record change {:.2g}), I = {:.6g}", zero, v.rotation,
                           v.rotation_delta, v.invariant);
  } else {
    v.detail =
        fmt::format("{}, but the weighted rotation number did not converge (change {:.2g})", zero, v.rotation_delta);
  }
}

// Pass 1 and pass 2 for the orbits of `ens` (one r), writing verdicts and the latest unit states.
void run_pass(const iterate::Ensemble& ens, long transient, const Options& opt, std::vector<OrbitVerdict>& out,
              std::vector<Vec3<double>>& latest, ExactCycles& exact) {
  const std::size_t N = ens.orbits();
  out.assign(N, OrbitVerdict{});
  latest.assign(N, Vec3<double>::Zero());
  ReturnRecorder rec(N, transient, opt.window, opt.max_period, opt.return_tol);
  iterate::run<double>(ens, rec.total_steps(), rec, opt.run);
  std::vector<std::size_t> rest;  // the orbits pass 2 decides
  for (std::size_t o = 0; o < N; ++o)
    if (!window_verdict(rec, o, ens, opt, exact, out[o], latest[o])) rest.push_back(o);
  if (rest.empty()) return;
  iterate::Ensemble pass_two;  // from the window's end
  pass_two.r = {ens.r[0]};
  for (std::size_t o : rest) pass_two.initial.push_back(latest[o]);
  const PassTwo two = run_pass_two(pass_two, opt);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    latest[rest[i]] = two.last[i];
    exponent_verdict(two, i, ens.r[0], opt, out[rest[i]]);
  }
}

// Refinement: continue only the undecided orbits, with refine_factor times the transient.
void refine(const iterate::Ensemble& ens, const Options& opt, const std::vector<Vec3<double>>& latest,
            ExactCycles& exact, std::vector<OrbitVerdict>& out) {
  std::vector<std::size_t> idx;
  for (std::size_t o = 0; o < out.size(); ++o)
    if (out[o].type == Type::undecided) idx.push_back(o);
  if (idx.empty()) return;
  iterate::Ensemble again;
  again.r = ens.r;
  for (std::size_t o : idx) again.initial.push_back(latest[o]);
  std::vector<OrbitVerdict> refined;
  std::vector<Vec3<double>> refined_latest;
  run_pass(again, opt.transient * opt.refine_factor, opt, refined, refined_latest, exact);
  for (std::size_t i = 0; i < idx.size(); ++i) {
    OrbitVerdict& v = out[idx[i]];
    const long before = v.iterations;
    const std::string first = v.detail;
    v = std::move(refined[i]);
    v.iterations += before;
    if (v.type == Type::undecided) v.detail += " (also after refinement)";
    else v.detail += " (after refinement; first pass: " + first + ")";
  }
}

template <class F> void check(bool ok, const char* field, F&& got, const std::string& expected) {
  if (!ok) throw core::InvalidField(field, got(), expected);
}

}  // namespace

std::vector<OrbitVerdict> stages::classify_from(const iterate::Ensemble& ens, const Options& opt, long done) {
  if (ens.r.size() != 1)
    throw std::invalid_argument(fmt::format("r: got {} values, expected one r per classification", ens.r.size()));
  core::validate_r(ens.r[0], "r");
  ExactCycles exact;
  std::vector<OrbitVerdict> out;
  std::vector<Vec3<double>> latest;
  run_pass(ens, opt.transient - done, opt, out, latest, exact);
  for (auto& v : out) v.iterations += done;
  if (opt.refine_factor > 0) refine(ens, opt, latest, exact, out);
  return out;
}

const char* type_name(Type t) {
  switch (t) {
    case Type::collapse: return "collapse";
    case Type::periodic: return "periodic";
    case Type::quasi_periodic: return "quasi-periodic";
    case Type::chaotic: return "chaotic";
    default: return "undecided";  // Type::undecided: the window cannot decide
  }
}

void validate(const Options& o) {
  const auto str = [](auto x) { return [x] { return fmt::format("{}", x); }; };
  check(o.transient >= 1, "transient", str(o.transient), "at least 1");
  check(o.max_period >= 1 && o.max_period <= 1024, "max-period", str(o.max_period), "1..1024");
  check(o.window >= o.max_period, "window", str(o.window), fmt::format("at least max-period = {}", o.max_period));
  check(o.return_tol > 0 && o.return_tol <= 1e-3, "return-tol", str(o.return_tol), "a value in (0, 1e-3]");
  check(o.point_tol > 0 && o.point_tol <= 1e-2, "point-tol", str(o.point_tol), "a value in (0, 1e-2]");
  check(o.collapse_theta > 0 && o.collapse_theta <= 0.1, "collapse-theta", str(o.collapse_theta),
        "a value in (0, 0.1]");
  check(o.lyap_transient >= 1, "lyap-transient", str(o.lyap_transient), "at least 1");
  check(o.lyap_blocks >= 2 && o.lyap_blocks <= 1000, "lyap-blocks", str(o.lyap_blocks), "2..1000");
  check(o.lyap_iterations >= 10L * o.lyap_blocks, "lyap-iterations", str(o.lyap_iterations),
        fmt::format("at least 10 x lyap-blocks = {}", 10L * o.lyap_blocks));
  check(o.rotation_tol > 0 && o.rotation_tol <= 0.1, "rotation-tol", str(o.rotation_tol), "a value in (0, 0.1]");
  check(o.refine_factor >= 0 && o.refine_factor <= 1000, "refine-factor", str(o.refine_factor), "0..1000");
  core::require_threads(o.run.threads);
}

std::string attractor_key(const OrbitVerdict& v) { return v.key; }

bool same_attractor(const OrbitVerdict& a, const OrbitVerdict& b, double r, double point_tol, double curve_tol) {
  if (a.type != b.type || a.key != b.key || a.type == Type::undecided) return false;
  if (a.type == Type::periodic) {
    // Same word up to phase (the key) and b's point on a's cycle: walk the cycle from a's point.
    Vec3<double> u = a.point;
    double d = dist_max(u, b.point);
    for (auto s : a.word.s) {
      u = core::to_quadrant<double>(core::P<double>(s, r) * u);
      u /= u.norm();
      d = std::min(d, dist_max(u, b.point));
    }
    return d < point_tol;
  }
  if (a.type == Type::quasi_periodic) {
    const double di = std::fabs(a.invariant - b.invariant) / std::max(std::fabs(a.invariant), std::fabs(b.invariant));
    return std::fabs(a.rotation - b.rotation) < curve_tol && di < curve_tol;
  }
  return true;  // collapse on the same line, or the chaotic set of this r (not resolved further)
}

std::vector<OrbitVerdict> classify(const iterate::Ensemble& ens, const Options& opt) {
  validate(opt);
  return classify_from(ens, opt, 0);
}

OrbitVerdict classify_point(const Vec3<double>& u0, double r, const Options& opt) {
  core::validate_point(u0(0), u0(1), u0(2), "point");
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {u0};
  return classify(e, opt)[0];
}

Attractor stages::attractor_of(const OrbitVerdict& v, double r) {
  Attractor a;
  a.type = v.type, a.key = v.key, a.point = v.point, a.period = v.period;
  a.rotation_min = a.rotation_max = v.rotation;
  a.invariant_min = a.invariant_max = v.invariant;
  if (v.type == Type::periodic || v.type == Type::collapse) {
    const patterns::Word w = smallest_rotation(v.word);
    const patterns::Word c = patterns::canonical(w);
    a.canonical = patterns::to_paper(c);
    a.pattern = smallest_rotation(c) == w ? patterns::to_paper(c) : patterns::to_paper(patterns::apply_J(c));
    a.collisions = patterns::collisions(w);
    if (v.type == Type::periodic) {
      const patterns::Verdict<double> pv = patterns::analyse<double>(w, r);
      a.stability = patterns::outcome_name(pv.outcome);
      if (!pv.reason.empty()) a.stability += std::string(" (") + pv.reason + ")";
      a.lyapunov2 = pv.lyapunov2;
      a.letters = pv.letters;
      if (!pv.orbit.empty()) a.point = pv.orbit[0];
    }
  } else if (v.type == Type::quasi_periodic) {
    a.pattern = v.key == "Q2" ? "P2 invariant curves" : "invariant curves";
  } else if (v.type == Type::chaotic) {
    a.pattern = "chaotic";
  }
  return a;
}

std::vector<Attractor> collect(const std::vector<OrbitVerdict>& vs, double r, std::vector<std::uint32_t>* labels) {
  // One attractor per (type, key), sorted: ids do not depend on the order of the verdicts.
  std::map<std::pair<int, std::string>, Attractor> by_key;
  for (const OrbitVerdict& v : vs) {
    if (v.type == Type::undecided) continue;
    auto [it, fresh] = by_key.try_emplace({static_cast<int>(v.type), v.key});
    if (fresh) it->second = attractor_of(v, r);
    ++it->second.count;
    widen_curve_ranges(it->second, v);
  }
  std::vector<Attractor> out;
  std::map<std::string, std::uint32_t> id_of;
  for (auto& [k, a] : by_key) {
    a.id = static_cast<int>(out.size()) + 1;
    id_of[k.second] = static_cast<std::uint32_t>(a.id);
    out.push_back(a);
  }
  if (labels) {
    labels->assign(vs.size(), 0);
    for (std::size_t o = 0; o < vs.size(); ++o)
      if (vs[o].type != Type::undecided) (*labels)[o] = id_of[vs[o].key];
  }
  return out;
}

Fraction fraction(std::size_t k, std::size_t n, double confidence) {
  Fraction f;
  if (n == 0) return f;
  const double a = (1 - confidence) / 2;
  using B = boost::math::binomial_distribution<double>;
  f.value = static_cast<double>(k) / static_cast<double>(n);
  f.low = k == 0 ? 0.0 : B::find_lower_bound_on_p(static_cast<double>(n), static_cast<double>(k), a);
  f.high = k == n ? 1.0 : B::find_upper_bound_on_p(static_cast<double>(n), static_cast<double>(k), a);
  return f;
}

}  // namespace btob::attractors
