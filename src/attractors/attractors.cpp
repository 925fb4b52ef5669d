// Attractor classification, identity and basins (Section 8.1 (1)) on the batched kernel.
#include "attractors/attractors.hpp"

#include "core/coords.hpp"
#include "core/sweep.hpp"
#include "attractors/recorders.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/tangent.hpp"
#include "lyapunov/maps.hpp"

#include <boost/math/distributions/binomial.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>

namespace btob::attractors {
namespace {

// r <= 7 - 4 sqrt(3): the eigenvalues of P1 and P3 are real and the collapse z = 0 (x = 0) attracts
// (Section 5.2).  A relative margin of 1e-12 absorbs the rounding of the constant.
const double kCollapseMaxR = 7 - 4 * std::numbers::sqrt3;

// Order 1 < 3 < 2 of patterns::canonical.
int rank(std::uint8_t s) { return s == 1 ? 0 : (s == 3 ? 1 : 2); }
bool less_word(const patterns::Word& a, const patterns::Word& b) {
  return std::lexicographical_compare(a.s.begin(), a.s.end(), b.s.begin(), b.s.end(),
                                      [](std::uint8_t x, std::uint8_t y) { return rank(x) < rank(y); });
}
// The smallest rotation of w (no J: mirrors stay apart) and its shift k (w rotated by k).
patterns::Word rotation_min(const patterns::Word& w, std::size_t* shift = nullptr) {
  patterns::Word best = w;
  std::size_t k_best = 0;
  for (std::size_t k = 1; k < w.size(); ++k) {
    patterns::Word c = patterns::rotate(w, k);
    if (less_word(c, best)) best = std::move(c), k_best = k;
  }
  if (shift) *shift = k_best;
  return best;
}

double dist_max(const Vec3<double>& a, const Vec3<double>& b) { return (a - b).cwiseAbs().maxCoeff(); }

// One periodic key's exact orbit (patterns::analyse), cached per classification.
struct Exact {
  patterns::Verdict<double> verdict;
  std::vector<Vec3<double>> points;
};

template <class F> void check(bool ok, F&& message) {
  if (!ok) throw std::invalid_argument(message());
}

// Pass 1 and pass 2 for the orbits of `ens` (one r), writing verdicts and the latest unit states.
void run_pass(const iterate::Ensemble& ens, long transient, const Options& opt, std::vector<OrbitVerdict>& out,
              std::vector<Vec3<double>>& latest, std::map<std::string, Exact>& exact) {
  const double r = ens.r[0];
  const std::size_t N = ens.orbits();
  out.assign(N, OrbitVerdict{});
  latest.assign(N, Vec3<double>::Zero());
  attractors::ReturnRecorder rec(N, transient, opt.window, opt.max_period, opt.return_tol);
  iterate::run<double>(ens, rec.total_steps(), rec, opt.run);

  std::vector<std::size_t> rest;
  for (std::size_t o = 0; o < N; ++o) {
    OrbitVerdict& v = out[o];
    v.iterations = rec.total_steps();
    v.point = Vec3<double>(rec.s0x[o], rec.s0y[o], rec.s0z[o]);
    const Vec3<double> fin(rec.fx[o], rec.fy[o], rec.fz[o]);
    latest[o] = fin;
    v.residual = rec.best_d[o];
    v.closest_return = rec.best_j[o];
    v.p2_region = rec.n1[o] == 0 && rec.n3[o] == 0;
    // Three-particle collapse (Section 5.2): symbol 1 (3) over the whole window and theta -> 0 (pi/2).
    const double th = core::theta<double>(fin);
    if (r <= kCollapseMaxR * (1 + 1e-12)) {
      if (rec.n1[o] == opt.window && th < opt.collapse_theta) {
        v.type = Type::collapse, v.period = 1, v.word.s = {1}, v.key = "C1";
        v.lambda1 = patterns::analyse<double>(v.word, r).lyapunov2;  // exponent of P1 on z = 0 (exact)
        v.detail = fmt::format("theta = {:.3g} after {} steps, symbol 1 throughout the window", th, v.iterations);
        continue;
      }
      if (rec.n3[o] == opt.window && std::numbers::pi / 2 - th < opt.collapse_theta) {
        v.type = Type::collapse, v.period = 1, v.word.s = {3}, v.key = "C3";
        v.lambda1 = patterns::analyse<double>(v.word, r).lyapunov2;  // exponent of P3 on x = 0 (exact)
        v.detail = fmt::format("pi/2 - theta = {:.3g} after {} steps, symbol 3 throughout the window",
                               std::numbers::pi / 2 - th, v.iterations);
        continue;
      }
    }
    const int p = rec.period[o];
    if (p > 0) {
      patterns::Word w;
      for (int j = 1; j <= p; ++j) w.s.push_back(static_cast<std::uint8_t>(rec.symbol(o, j)));
      v.period = p;
      v.residual = rec.resid[o];
      v.closest_return = p;
      v.word = w;
      std::size_t shift = 0;
      const patterns::Word key_word = rotation_min(w, &shift);
      const std::string key = "P" + patterns::to_digits(key_word);
      auto it = exact.find(key);
      if (it == exact.end()) {
        Exact e;
        e.verdict = patterns::analyse<double>(key_word, r);
        for (const auto& q : e.verdict.orbit) e.points.push_back(q);
        it = exact.emplace(key, std::move(e)).first;
      }
      const Exact& e = it->second;
      v.lambda1 = e.verdict.lyapunov2;  // the cycle's exponent log|l2/l1|/p from the pattern tool (exact)
      if (e.points.empty()) {
        // No feasible real eigenvector: a numerically periodic orbit the pattern tool cannot confirm
        // (e.g. a rational P2 rotation, Section 5.2, whose cycles are neutral).  Reported, not hidden.
        v.type = Type::periodic, v.key = key;
        v.detail = fmt::format("no exact orbit for this word at r ({}: {})",
                               patterns::outcome_name(e.verdict.outcome), e.verdict.reason);
        continue;
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
      continue;
    }
    rest.push_back(o);
  }
  if (rest.empty()) return;

  // Pass 2: Lyapunov exponent and rotation number of the orbits without a period, from their window end.
  iterate::Ensemble e2;
  e2.r = {r};
  for (std::size_t o : rest) e2.initial.push_back(latest[o]);
  lyapunov::TangentRecorder tan(e2, opt.lyap_transient, opt.lyap_iterations, opt.lyap_blocks);
  attractors::RotationRecorder rot(rest.size(), r, opt.lyap_transient, opt.lyap_iterations);
  iterate::Both<lyapunov::TangentRecorder, attractors::RotationRecorder> both(tan, rot);
  iterate::run<double>(e2, tan.total_steps(), both, opt.run);
  const lyapunov::OrbitExponents ex = lyapunov::exponents_from(tan);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    OrbitVerdict& v = out[rest[i]];
    v.iterations += tan.total_steps();
    latest[rest[i]] = Vec3<double>(rot.fx[i], rot.fy[i], rot.fz[i]);
    v.lambda1 = ex.lambda1[i], v.err1 = ex.err1[i];
    v.invariant = rot.invariant(i);
    v.invariant_spread = (rot.i_max[i] - rot.i_min[i]) / std::fabs(v.invariant);
    v.rotation = rot.rotation(i);
    v.rotation_delta = std::fabs(rot.rotation(i) - rot.rotation_half(i));
    const int sign = lyapunov::classify(v.lambda1, v.err1, opt.lyap_iterations);
    const std::string lam = fmt::format("lambda1 = {:.3g} +- {:.2g}", v.lambda1, v.err1);
    if (sign > 0) {
      v.type = Type::chaotic, v.key = "X";
      v.detail = lam + " > 0";
    } else if (sign < 0) {
      v.detail = fmt::format("{} < 0 but no return within {} steps (closest {:.2g} at {}): slow convergence or a "
                             "longer period",
                             lam, opt.max_period, v.residual, v.closest_return);
    } else if (!rot.rotation_defined) {
      v.detail = lam + " is zero, but r <= 3 - 2 sqrt(2): no P2 rotation to test";
    } else if (v.rotation_delta < opt.rotation_tol) {
      v.type = Type::quasi_periodic;
      v.key = v.p2_region ? "Q2" : "Q";
      v.detail = fmt::format("{} is zero; rotation {:.10f} turns (half-record change {:.2g}), I = {:.6g}", lam,
                             v.rotation, v.rotation_delta, v.invariant);
    } else {
      v.detail = fmt::format("{} is zero but the weighted rotation number did not converge (change {:.2g})", lam,
                             v.rotation_delta);
    }
  }
}

}  // namespace

const char* type_name(Type t) {
  switch (t) {
    case Type::collapse: return "collapse";
    case Type::periodic: return "periodic";
    case Type::quasi_periodic: return "quasi-periodic";
    case Type::chaotic: return "chaotic";
    default: return "unresolved";
  }
}

void validate(const Options& o) {
  check(o.transient >= 1, [&] { return fmt::format("transient: got {}, expected at least 1", o.transient); });
  check(o.max_period >= 1 && o.max_period <= 1024,
        [&] { return fmt::format("max-period: got {}, expected 1..1024", o.max_period); });
  check(o.window >= o.max_period,
        [&] { return fmt::format("window: got {}, expected at least max-period = {}", o.window, o.max_period); });
  check(o.return_tol > 0 && o.return_tol <= 1e-3,
        [&] { return fmt::format("return-tol: got {}, expected a value in (0, 1e-3]", o.return_tol); });
  check(o.point_tol > 0 && o.point_tol <= 1e-2,
        [&] { return fmt::format("point-tol: got {}, expected a value in (0, 1e-2]", o.point_tol); });
  check(o.collapse_theta > 0 && o.collapse_theta <= 0.1,
        [&] { return fmt::format("collapse-theta: got {}, expected a value in (0, 0.1]", o.collapse_theta); });
  check(o.lyap_transient >= 1,
        [&] { return fmt::format("lyap-transient: got {}, expected at least 1", o.lyap_transient); });
  check(o.lyap_blocks >= 2 && o.lyap_blocks <= 1000,
        [&] { return fmt::format("lyap-blocks: got {}, expected 2..1000", o.lyap_blocks); });
  check(o.lyap_iterations >= 10L * o.lyap_blocks, [&] {
    return fmt::format("lyap-iterations: got {}, expected at least 10 x lyap-blocks = {}", o.lyap_iterations,
                       10L * o.lyap_blocks);
  });
  check(o.rotation_tol > 0 && o.rotation_tol <= 0.1,
        [&] { return fmt::format("rotation-tol: got {}, expected a value in (0, 0.1]", o.rotation_tol); });
  check(o.refine_factor >= 0 && o.refine_factor <= 1000,
        [&] { return fmt::format("refine-factor: got {}, expected 0..1000", o.refine_factor); });
  check(o.run.threads >= 0, [&] { return fmt::format("threads: got {}, expected at least 1", o.run.threads); });
}

std::string attractor_key(const OrbitVerdict& v) { return v.key; }

bool same_attractor(const OrbitVerdict& a, const OrbitVerdict& b, double r, double point_tol, double curve_tol) {
  if (a.type != b.type || a.key != b.key || a.type == Type::unresolved) return false;
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
  if (ens.r.size() != 1)
    throw std::invalid_argument(fmt::format("r: got {} values, expected one r per classification", ens.r.size()));
  core::validate_r(ens.r[0], "r");
  std::map<std::string, Exact> exact;
  std::vector<OrbitVerdict> out;
  std::vector<Vec3<double>> latest;
  run_pass(ens, opt.transient, opt, out, latest, exact);
  if (opt.refine_factor > 0) {
    // Refinement: continue only the unresolved orbits, with refine_factor times the transient.
    std::vector<std::size_t> idx;
    for (std::size_t o = 0; o < out.size(); ++o)
      if (out[o].type == Type::unresolved) idx.push_back(o);
    if (!idx.empty()) {
      iterate::Ensemble e2;
      e2.r = ens.r;
      for (std::size_t o : idx) e2.initial.push_back(latest[o]);
      std::vector<OrbitVerdict> v2;
      std::vector<Vec3<double>> l2;
      run_pass(e2, opt.transient * opt.refine_factor, opt, v2, l2, exact);
      for (std::size_t i = 0; i < idx.size(); ++i) {
        const long before = out[idx[i]].iterations;
        const std::string first = out[idx[i]].detail;
        out[idx[i]] = std::move(v2[i]);
        out[idx[i]].iterations += before;
        if (out[idx[i]].type == Type::unresolved) out[idx[i]].detail += " (also after refinement)";
        else out[idx[i]].detail += " (after refinement; first pass: " + first + ")";
      }
    }
  }
  return out;
}

OrbitVerdict classify_point(const Vec3<double>& u0, double r, const Options& opt) {
  core::validate_point(u0(0), u0(1), u0(2), "point");
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {u0};
  return classify(e, opt)[0];
}

std::vector<Attractor> collect(const std::vector<OrbitVerdict>& vs, double r, std::vector<std::uint32_t>* labels) {
  struct Agg {
    Attractor a;
    std::size_t first = 0;
    bool seen = false;
  };
  // Keys sorted by (type, key): ids do not depend on the order of the verdicts.
  std::map<std::pair<int, std::string>, Agg> m;
  for (std::size_t o = 0; o < vs.size(); ++o) {
    const OrbitVerdict& v = vs[o];
    if (v.type == Type::unresolved) continue;
    Agg& g = m[{static_cast<int>(v.type), v.key}];
    if (!g.seen) {
      g.seen = true;
      g.first = o;
      g.a.type = v.type;
      g.a.key = v.key;
      g.a.point = v.point;
      g.a.period = v.period;
      g.a.rotation_min = g.a.rotation_max = v.rotation;
      g.a.invariant_min = g.a.invariant_max = v.invariant;
      if (v.type == Type::periodic || v.type == Type::collapse) {
        std::size_t shift = 0;
        const patterns::Word w = rotation_min(v.word, &shift);
        const patterns::Word c = patterns::canonical(w);
        g.a.canonical = patterns::to_paper(c);
        g.a.pattern = rotation_min(c) == w ? patterns::to_paper(c) : patterns::to_paper(patterns::apply_J(c));
        g.a.collisions = patterns::collisions(w);
        if (v.type == Type::periodic) {
          const patterns::Verdict<double> pv = patterns::analyse<double>(w, r);
          g.a.stability = patterns::outcome_name(pv.outcome);
          if (!pv.reason.empty()) g.a.stability += std::string(" (") + pv.reason + ")";
          g.a.lyapunov2 = pv.lyapunov2;
          g.a.letters = pv.letters;
          if (!pv.orbit.empty()) g.a.point = pv.orbit[0];
        }
      } else if (v.type == Type::quasi_periodic) {
        g.a.pattern = v.key == "Q2" ? "P2 invariant curves" : "invariant curves";
      } else if (v.type == Type::chaotic) {
        g.a.pattern = "chaotic";
      }
    }
    ++g.a.count;
    g.a.rotation_min = std::min(g.a.rotation_min, v.rotation);
    g.a.rotation_max = std::max(g.a.rotation_max, v.rotation);
    g.a.invariant_min = std::min(g.a.invariant_min, v.invariant);
    g.a.invariant_max = std::max(g.a.invariant_max, v.invariant);
  }
  std::vector<Attractor> out;
  std::map<std::string, std::uint32_t> id_of;
  for (auto& [k, g] : m) {
    g.a.id = static_cast<int>(out.size()) + 1;
    id_of[k.second] = static_cast<std::uint32_t>(g.a.id);
    out.push_back(g.a);
  }
  if (labels) {
    labels->assign(vs.size(), 0);
    for (std::size_t o = 0; o < vs.size(); ++o)
      if (vs[o].type != Type::unresolved) (*labels)[o] = id_of[vs[o].key];
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

Grid parse_grid(const std::string& spec, double w1_min, double w1_max, const char* field) {
  Grid g;
  const auto colon = spec.find(':');
  const auto bad = [&] {
    return std::invalid_argument(
        fmt::format("{}: got '{}', expected sphere:NxM, strip:NxM or angles:NxM with N, M >= 1", field, spec));
  };
  if (colon == std::string::npos) throw bad();
  g.kind = spec.substr(0, colon);
  if (g.kind != "sphere" && g.kind != "strip" && g.kind != "angles") throw bad();
  const std::string dims = spec.substr(colon + 1);
  const auto x = dims.find('x');
  if (x == std::string::npos) throw bad();
  try {
    std::size_t p1 = 0, p2 = 0;
    g.n1 = std::stol(dims.substr(0, x), &p1);
    g.n2 = std::stol(dims.substr(x + 1), &p2);
    if (p1 != x || p2 != dims.size() - x - 1) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  if (g.n1 < 1 || g.n2 < 1)
    throw std::invalid_argument(fmt::format("{}: got {} x {} points (empty grid), expected N, M >= 1", field, g.n1, g.n2));
  if (g.kind == "strip") {
    if (!(std::isfinite(w1_min) && std::isfinite(w1_max) && w1_min < w1_max))
      throw std::invalid_argument(
          fmt::format("w1-range: got [{}, {}], expected finite a < b", w1_min, w1_max));
    g.lo1 = w1_min, g.hi1 = w1_max, g.lo2 = -1, g.hi2 = 1;
  } else if (g.kind == "sphere") {
    g.lo1 = 0, g.hi1 = std::numbers::pi / 2, g.lo2 = -1, g.hi2 = 1;
  } else {
    g.lo1 = 0, g.hi1 = std::numbers::pi / 2, g.lo2 = 0, g.hi2 = std::numbers::pi;
  }
  return g;
}

std::vector<Vec3<double>> grid_points(const Grid& g, double du, double dv) {
  const std::size_t n = iterate::checked_bytes(static_cast<std::size_t>(g.n1), static_cast<std::size_t>(g.n2),
                                               sizeof(Vec3<double>), "grid") / sizeof(Vec3<double>);
  std::vector<Vec3<double>> pts(n);
  for (long j = 0; j < g.n2; ++j)
    for (long i = 0; i < g.n1; ++i) {
      const double a = g.lo1 + (static_cast<double>(i) + 0.5 + du) * (g.hi1 - g.lo1) / static_cast<double>(g.n1);
      const double b = g.lo2 + (static_cast<double>(j) + 0.5 + dv) * (g.hi2 - g.lo2) / static_cast<double>(g.n2);
      pts[static_cast<std::size_t>(j) * static_cast<std::size_t>(g.n1) + static_cast<std::size_t>(i)] =
          g.kind == "strip"    ? core::from_strip<double>(a, b)
          : g.kind == "sphere" ? core::from_height<double>(a, b)
                               : core::from_angles<double>(a, b);
    }
  return pts;
}

double strip_sphere_share(double a, double b) {
  const auto F = [](double w) { return std::asin(w / std::sqrt(1 + 2 * w * w)); };
  return 2 / std::numbers::pi * (F(b) - F(a));
}

std::string strip_measure_name(double a, double b) {
  return fmt::format("Lebesgue on the strip rectangle w1 in [{}, {}] x w2 in [-1, 1] ({:.4f} of the sphere measure)", a,
                     b, strip_sphere_share(a, b));
}

double sphere_share(const Grid& g) { return g.kind == "strip" ? strip_sphere_share(g.lo1, g.hi1) : 1.0; }

std::string measure_name(const Grid& g) {
  if (g.kind == "sphere") return "uniform on the sphere of directions of the domain (equal-area grid)";
  if (g.kind == "strip") return strip_measure_name(g.lo1, g.hi1);
  return "uniform in the angles (theta, phi), not the sphere's area";
}

namespace {
void check_basins(double r, const Grid& g, int replicates, const Options& opt) {
  validate(opt);
  core::validate_r(r, "r");
  if (replicates < 0 || replicates > 100)
    throw std::invalid_argument(fmt::format("replicates: got {}, expected 0..100", replicates));
  // Per orbit: the verdict (~200 bytes with its word), pass-1 recorder (~120), pass-2 tangent (~400).
  iterate::checked_bytes(static_cast<std::size_t>(g.n1) * static_cast<std::size_t>(g.n2), 800, "grid");
}
}  // namespace

std::size_t basin_items(const Grid& g, int replicates) {
  return static_cast<std::size_t>(replicates + 1) * static_cast<std::size_t>(g.n2);
}

BasinRows basin_rows(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt,
                     const std::vector<std::size_t>& items) {
  check_basins(r, g, replicates, opt);
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n1 = static_cast<std::size_t>(g.n1), n2 = static_cast<std::size_t>(g.n2);
  BasinRows part;
  part.items = items;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> shift(-0.45, 0.45);  // strictly inside the cell: no boundary points
  for (int k = 0; k <= replicates; ++k) {
    const double du = k == 0 ? 0.0 : shift(rng), dv = k == 0 ? 0.0 : shift(rng);  // every grid's shift, always
    iterate::Ensemble e;
    e.r = {r};
    std::vector<Vec3<double>> pts;
    for (std::size_t i : items)
      if (i / n2 == static_cast<std::size_t>(k)) {
        if (pts.empty()) pts = grid_points(g, du, dv);
        const std::size_t j = i % n2;
        e.initial.insert(e.initial.end(), pts.begin() + static_cast<std::ptrdiff_t>(j * n1),
                         pts.begin() + static_cast<std::ptrdiff_t>((j + 1) * n1));
      }
    if (e.initial.empty()) continue;
    std::vector<OrbitVerdict> v = classify(e, opt);
    std::move(v.begin(), v.end(), std::back_inserter(part.verdicts));
  }
  part.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return part;
}

Basins merge_basins(double r, const Grid& g, int replicates, const Options& opt, std::vector<BasinRows> parts) {
  check_basins(r, g, replicates, opt);
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n1 = static_cast<std::size_t>(g.n1), n2 = static_cast<std::size_t>(g.n2), n = n1 * n2;
  const auto order = core::item_order(parts, basin_items(g, replicates));
  Basins b;
  b.r = r;
  b.grid = g;
  // The verdicts of every grid, grid k at [k n, (k + 1) n), rows placed by item (any partition gives the same).
  std::vector<OrbitVerdict> joined(static_cast<std::size_t>(replicates + 1) * n);
  for (std::size_t i = 0; i < order.size(); ++i) {
    auto& src = parts[order[i].part].verdicts;
    if (src.size() < (order[i].index + 1) * n1) throw std::logic_error("basin rows: a row is missing");
    std::move(src.begin() + static_cast<std::ptrdiff_t>(order[i].index * n1),
              src.begin() + static_cast<std::ptrdiff_t>((order[i].index + 1) * n1),
              joined.begin() + static_cast<std::ptrdiff_t>((i / n2) * n + (i % n2) * n1));
  }
  double part_seconds = 0;
  for (const auto& p : parts) part_seconds = std::max(part_seconds, p.seconds);
  for (std::size_t o = 0; o < joined.size(); ++o) {
    OrbitVerdict& v = joined[o];
    b.iterations_total += v.iterations;
    if (o < n)
      b.unresolved_first_pass += v.type == Type::unresolved || v.detail.find("after refinement") != std::string::npos;
    std::string().swap(v.detail);  // per-orbit evidence text: not used below (~100 bytes each)
  }
  // Attractors of the union (ids by sorted key), then counts per grid.
  b.attractors = collect(joined, r, nullptr);
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < b.attractors.size(); ++i) index[b.attractors[i].key] = i;
  const std::size_t A = b.attractors.size(), grids = static_cast<std::size_t>(replicates + 1);
  b.replicate_fractions.assign(A + 1, std::vector<double>(grids, 0.0));
  for (std::size_t k = 0; k < grids; ++k) {
    const OrbitVerdict* grid = joined.data() + k * n;
    std::vector<std::size_t> count(A + 1, 0);
    for (std::size_t o = 0; o < n; ++o) ++count[grid[o].type == Type::unresolved ? A : index[grid[o].key]];
    for (std::size_t i = 0; i <= A; ++i)
      b.replicate_fractions[i][k] = static_cast<double>(count[i]) / static_cast<double>(n);
    if (k == 0) {
      b.labels.assign(n, 0);
      for (std::size_t o = 0; o < n; ++o)
        if (grid[o].type != Type::unresolved) b.labels[o] = static_cast<std::uint32_t>(index[grid[o].key] + 1);
      for (std::size_t i = 0; i < A; ++i) {
        b.attractors[i].count = count[i];
        b.fractions.push_back(fraction(count[i], n));
      }
      b.unresolved = fraction(count[A], n);
    }
  }
  b.seconds = part_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return b;
}

Basins basins(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt) {
  check_basins(r, g, replicates, opt);
  return merge_basins(r, g, replicates, opt,
                      {basin_rows(r, g, replicates, seed, opt, core::all_items(basin_items(g, replicates)))});
}

}  // namespace btob::attractors
