// SPDX-License-Identifier: GPL-3.0-or-later
// The certification of early exits (attractors/certify.hpp): trapping cones of stable cycles, the P2 ellipses.
#include "attractors/certify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "attractors/recorders.hpp"
#include "attractors/stages.hpp"
#include "core/coords.hpp"
#include "core/grid.hpp"

namespace btob::attractors::stages {
namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- trapping cones ----

// The ratio test of one phase's rays (the branch of symbol s holds on E (1, +-d, +-d) with margin).
bool rays_in_branch(const Eigen::Matrix3d& E, double d, int s, double alpha) {
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d u = E * Eigen::Vector3d(1, (i & 1) ? d : -d, (i & 2) ? d : -d);
    const double m = 1e-9 * u.cwiseAbs().maxCoeff();  // far above the kernel's rounding of a y - x (a few eps)
    const double c1 = alpha * u(1) - u(0), c3 = alpha * u(1) - u(2);
    const bool ok = s == 1 ? c1 > m : (s == 3 ? c1 < -m && c3 < -m : c1 < -m && c3 > m);
    if (!ok) return false;  // (the cone may leave Q: the kernel's states stay in Q, and Q is invariant)
  }
  return true;
}

// E_0 of the monodromy A (see Cone), or nullopt when its dominant eigenvalue is not real and positive.
std::optional<Eigen::Matrix3d> eigen_frame(const Eigen::Matrix3d& A) {
  Eigen::EigenSolver<Eigen::Matrix3d> es(A);
  const auto ev = es.eigenvalues();
  int i1 = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(ev(i)) > std::abs(ev(i1))) i1 = i;
  if (std::fabs(ev(i1).imag()) != 0 || ev(i1).real() <= 0) return std::nullopt;
  Eigen::Matrix3d E;
  Eigen::Vector3d v1 = es.eigenvectors().col(i1).real();
  if (v1(0) < 0 || (v1(0) == 0 && v1(2) > 0)) v1 = -v1;
  E.col(0) = v1 / v1.norm();
  const int j2 = i1 == 0 ? 1 : 0, j3 = 3 - i1 - j2;
  if (ev(j2).imag() != 0) {  // a complex pair: real and imaginary parts of one eigenvector
    // One scale for both parts: the monodromy then acts on them as |lambda2| times a rotation.
    const Eigen::Vector3cd z = es.eigenvectors().col(j2) / es.eigenvectors().col(j2).norm();
    E.col(1) = z.real(), E.col(2) = z.imag();
  } else {
    E.col(1) = es.eigenvectors().col(j2).real(), E.col(2) = es.eigenvectors().col(j3).real();
    E.col(1) /= E.col(1).norm(), E.col(2) /= E.col(2).norm();
  }
  return E;
}

// The blocks of D = E_0^-1 A E_0 that bound one period's ratio map: e -> (d21 + D22 e) / (D11 - d12 e).
struct RatioMap {
  double D11 = 0, d12 = 0, d21 = 0, D22 = 0;
};
RatioMap ratio_map(const Eigen::Matrix3d& E, const Eigen::Matrix3d& A) {
  const Eigen::Matrix3d D = E.inverse() * A * E;
  return {D(0, 0), D.block<1, 2>(0, 1).norm(), D.block<2, 1>(1, 0).norm(),
          D.block<2, 2>(1, 1).jacobiSvd().singularValues()(0)};
}

// The frames E_j carried along the word, their inverses and the constants of the bounds (see Cone).
struct Frames {
  std::vector<Eigen::Matrix3d> E, inv;
  double cond = 0, G = 0, q_dist = 0, separation = kInf;
};
std::optional<Frames> carry_frames(const Eigen::Matrix3d& E0, const patterns::Word& w, const Eigen::Matrix3d* M,
                                   const std::vector<Vec3<double>>& exact_points) {
  const std::size_t p = w.size();
  Frames f;
  f.E.resize(p);
  f.E[0] = E0;
  for (std::size_t j = 1; j < p; ++j) f.E[j] = M[w.s[j - 1]] * f.E[j - 1];
  std::vector<Vec3<double>> q(p);
  for (std::size_t j = 0; j < p; ++j) {
    const Eigen::Matrix3d& Ej = f.E[j];
    const auto sv = Ej.jacobiSvd().singularValues();
    if (!(sv(2) > 0)) return std::nullopt;
    f.cond = std::max(f.cond, sv(0) / sv(2));
    const Eigen::Matrix<double, 3, 2> tail = Ej.block<3, 2>(0, 1);
    f.G = std::max(f.G, 2 * tail.jacobiSvd().singularValues()(0) / Ej.col(0).norm());
    q[j] = Ej.col(0) / Ej.col(0).norm();
    double d = kInf;
    for (const auto& e : exact_points) d = std::min(d, dist_max(e, q[j]));
    f.q_dist = std::max(f.q_dist, d);
    f.inv.push_back(Ej.inverse());
  }
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = i + 1; j < p; ++j) f.separation = std::min(f.separation, dist_max(q[i], q[j]));
  return f;
}

// The largest radius of a fixed ladder whose cone maps into itself with the rounding's room and whose rays keep
// their branches; fills c's radius, ratio map and noise.
bool choose_radius(const RatioMap& m, const Frames& f, const patterns::Word& w, double r, Cone& c) {
  const int p = static_cast<int>(w.size());
  // Rounding: a kernel step perturbs the state by a few eps relative (the step, the rounded a and k of the
  // kernel against ours); 16 eps per step in the coordinates, times the condition of E_j, p steps per period.
  const double per_period = 16 * kEps * f.cond * static_cast<double>(p) * 2;
  for (double delta : {0.3, 0.1, 0.03, 0.01, 3e-3, 1e-3, 1e-4, 1e-5}) {
    const double den = m.D11 - m.d12 * delta;
    if (!(den > 0)) continue;
    const double a = m.d21 / den, b = m.D22 / den;
    if (!(b < 1 - 1e-6) || !(a + b * delta + per_period <= 0.999 * delta)) continue;
    bool ok = true;
    for (int j = 0; j < p && ok; ++j)
      ok = rays_in_branch(f.E[static_cast<std::size_t>(j)], delta, w.s[static_cast<std::size_t>(j)], core::alpha(r));
    if (!ok) continue;
    c.delta = delta, c.a = a, c.b = b;
    c.noise = (a + per_period) / (1 - b) + 8 * kEps * f.cond;
    return true;
  }
  return false;
}
}  // namespace

std::optional<Cone> make_cone(const std::string& key, const patterns::Word& w, double r, const Options& opt,
                              const std::vector<Vec3<double>>& exact_points) {
  const int p = static_cast<int>(w.size());
  if (p < 1 || p > opt.max_period || exact_points.empty()) return std::nullopt;
  const bool one_symbol = std::all_of(w.s.begin(), w.s.end(), [](auto s) { return s == 1; }) ||
                          std::all_of(w.s.begin(), w.s.end(), [](auto s) { return s == 3; });
  if (one_symbol && collapse_possible(r)) return std::nullopt;  // the collapse test comes first
  Eigen::Matrix3d M[4];
  for (int s = 1; s <= 3; ++s) M[s] = core::P<double>(s, r) / r;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (auto s : w.s) A = M[s] * A;
  const std::optional<Eigen::Matrix3d> E = eigen_frame(A);
  if (!E) return std::nullopt;
  const RatioMap m = ratio_map(*E, A);
  std::optional<Frames> f = carry_frames(*E, w, M, exact_points);
  if (!f) return std::nullopt;
  Cone c;
  c.key = key, c.word = w, c.p = p;
  if (!choose_radius(m, *f, w, r, c)) return std::nullopt;
  c.inv = std::move(f->inv);
  c.G = f->G, c.q_dist = f->q_dist, c.separation = f->separation;
  if (!(c.separation > 100 * opt.return_tol) || !(c.q_dist < opt.point_tol / 100)) return std::nullopt;
  return c;
}

// At step transient the orbit has gone through at least m = steps_left / p whole periods, so its ratio is at most
// e_T = b^m e + noise; then |u_T - q| <= G e_T, the return after p steps is within 2 G e_T, the returns before p
// are at least separation - 2 G e_T away, and u_T is within G e_T + q_dist of the pattern tool's cycle.  Each
// bound must be below its tolerance with a factor 2 to spare.
double cone_limit(const Cone& c, long steps_left, const Options& opt) {
  const double lim = std::min({opt.return_tol / (4 * c.G), (opt.point_tol / 2 - c.q_dist) / c.G,
                               (c.separation - 2 * opt.return_tol) / (2 * c.G)});
  const double bm = std::pow(c.b, static_cast<double>(steps_left / c.p));
  if (!(lim > c.noise)) return 0;
  return bm > 0 ? std::min(c.delta, (lim - c.noise) / bm) : c.delta;
}

bool in_cone(const Cone& c, const Vec3<double>& u, double e_max) {
  for (int j = 0; j < c.p; ++j) {
    const Eigen::Vector3d x = c.inv[static_cast<std::size_t>(j)] * u;
    if (x(0) > 0 && x(1) * x(1) + x(2) * x(2) < e_max * e_max * x(0) * x(0)) return true;
  }
  return false;
}

// ---- the P2 invariant ellipses ----
namespace {
// The chart a = 1: (s, y) -> v = ((1 + s) / 2, y, (s - 1) / 2); (xi, eta) = T (s, y).  P2's action on the chart
// (measured, not assumed): it must fix the centre, scale a by r and be a rotation in (xi, eta).  Its rotation
// angle beta, or nullopt.
std::optional<double> p2_rotation_angle(const Eigen::Matrix3d& P2, const Eigen::Matrix2d& T) {
  const auto chart = [&](double s, double y, double& s2, double& y2) {
    const Eigen::Vector3d v((1 + s) / 2, y, (s - 1) / 2), u = P2 * v;
    const double a2 = u(0) - u(2);
    s2 = (u(0) + u(2)) / a2, y2 = u(1) / a2;
    return a2;
  };
  double s0, y0, s1, y1, s2, y2;
  const double a0 = chart(0, 0, s0, y0), a1 = chart(1, 0, s1, y1), a2 = chart(0, 1, s2, y2);
  if (std::fabs(a0 - 1) > 1e-13 || std::fabs(a1 - 1) > 1e-13 || std::fabs(a2 - 1) > 1e-13 || std::fabs(s0) > 1e-13 ||
      std::fabs(y0) > 1e-13)
    return std::nullopt;
  Eigen::Matrix2d Ach;
  Ach << s1, s2, y1, y2;
  const Eigen::Matrix2d R = T * Ach * T.inverse();
  if ((R.transpose() * R - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff() > 1e-12 || R.determinant() < 0)
    return std::nullopt;
  const double beta = std::atan2(R(1, 0), R(0, 0));
  if (std::fabs(std::fabs(beta) - std::numbers::pi) < 1e-6) return std::nullopt;  // the wrap must be unambiguous
  return beta;
}

// Return distance after j steps, for two chart points v, v' on the ellipse (radius sqrt(I)/2 in (xi, eta)):
// |v - v'|_2 >= sigma sqrt(I)/2 |2 sin(j beta / 2)| (sigma: smallest singular value of (xi, eta) -> v), the
// sine of their angle >= |v - v'| / (sqrt(2) |v| |v'|) (the plane x - z = 1 is 1/sqrt(2) from 0), and the unit
// vectors' max-norm distance >= that sine / sqrt(3).  The constant return_k of P2Trap.
double return_constant(const Eigen::Matrix2d& T, double beta, int max_period) {
  double smin = kInf;
  for (int j = 1; j <= max_period; ++j)
    smin = std::min(smin, std::fabs(2 * std::sin(static_cast<double>(j) * beta / 2)));
  Eigen::Matrix<double, 3, 2> L;
  const Eigen::Matrix2d Ti = T.inverse();  // (xi, eta) -> (s, y)
  L << Ti(0, 0) / 2, Ti(0, 1) / 2, Ti(1, 0), Ti(1, 1), Ti(0, 0) / 2, Ti(0, 1) / 2;
  const double sigma = L.jacobiSvd().singularValues()(1);
  return sigma / 2 * smin / (std::numbers::sqrt2 * std::numbers::sqrt3);
}

// cond(S) of P2 / r = S diag(1, rotation) S^-1 (S: the real eigenvector, the real and imaginary parts of the
// complex one), or nullopt when P2 / r is not of that form.
std::optional<double> p2_eigenbasis_condition(const Eigen::Matrix3d& P2) {
  Eigen::EigenSolver<Eigen::Matrix3d> es(P2);
  Eigen::Matrix3d S;
  int ir = -1;
  for (int i = 0; i < 3; ++i)
    if (es.eigenvalues()(i).imag() == 0) ir = i;
  if (ir < 0) return std::nullopt;
  for (int i = 0; i < 3; ++i)
    if (std::fabs(std::abs(es.eigenvalues()(i)) - 1) > 1e-12) return std::nullopt;
  const int ic = ir == 0 ? 1 : 0;
  S.col(0) = es.eigenvectors().col(ir).real();
  S.col(1) = es.eigenvectors().col(ic).real(), S.col(2) = es.eigenvectors().col(ic).imag();
  const auto sv = S.jacobiSvd().singularValues();
  return sv(0) / sv(2);
}
}  // namespace

P2Trap make_trap(double r, const Options& opt) {
  P2Trap t;
  const double al = core::alpha(r), c2 = RotationRecorder::eta2(r);
  if (!(c2 > 0)) return t;  // r <= 3 - 2 sqrt(2): no rotation (pass 2 cannot call it quasi-periodic)
  t.alpha = al, t.r = r, t.I_max = (2 * r - al * al) / r;
  const Eigen::Matrix3d P2 = core::P<double>(2, r) / r;
  Eigen::Matrix2d T;
  T << 1 / std::numbers::sqrt2, -al / std::numbers::sqrt2, 0, std::sqrt(c2);
  const std::optional<double> beta = p2_rotation_angle(P2, T);
  if (!beta) return t;
  t.return_k = return_constant(T, *beta, opt.max_period);
  // |v|^2 = (1 + s^2) / 2 + y^2 with s^2 <= I r / (2r - alpha^2) and y^2 <= I / (2 (2r - alpha^2)) on the ellipse.
  t.v1 = r / (2 * (2 * r - al * al)), t.v2 = 1 / (2 * (2 * r - al * al));
  // pass 2's exponent: over any stretch the projective derivative changes a tangent vector's length by at most
  // cond(S)^2: |lambda1| <= 2 log cond(S) / lyap_iterations, which must stay below the bar 10 / lyap_iterations of
  // lyapunov::classify (its 3 err only widens it).
  const std::optional<double> condS = p2_eigenbasis_condition(P2);
  if (!condS) return t;
  // The steps a certified orbit would still make at full length: transient + window + pass 2 (its verdict is
  // reached there).  The drift of the state off its ellipse: 16 eps per step relative, times cond(S)^2.
  const double steps = static_cast<double>(opt.transient + opt.window + opt.lyap_transient + opt.lyap_iterations);
  const double drift = 16 * kEps * steps * *condS * *condS;
  if (!(2 * std::log(*condS) * 1.001 + drift < 10.0) || !(drift < 1e-7)) return t;
  t.margin = std::max(1e-7, 100 * drift);
  t.on = true;
  return t;
}

double invariant_of(const Vec3<double>& u, double r, double al) {
  const double s = u(0) + u(2), a = u(0) - u(2);
  return (2 * s * s - 4 * al * s * u(1) + 4 * r * u(1) * u(1)) / (a * a);
}

bool on_p2_curve(const P2Trap& t, const Vec3<double>& u, const Options& opt, double& I) {
  if (!t.on) return false;
  I = invariant_of(u, t.r, t.alpha);
  if (!(I > 0) || !(1 - std::sqrt(I / t.I_max) >= t.margin)) return false;
  const double V = 0.5 + t.v1 * I + t.v2 * I;  // |v|^2 bound on the chart
  return t.return_k * std::sqrt(I) / V >= 100 * opt.return_tol;
}

std::vector<Cone> probe_cones(double r, const Options& opt) {
  iterate::Ensemble e;
  e.r = {r};
  e.initial = grid_points(core::make_grid(core::GridKind::sphere, 16, 16));
  Options o = opt;
  o.run.progress = nullptr;
  const std::vector<OrbitVerdict> v = classify(e, o);
  std::vector<Cone> cones;
  std::set<std::string> seen;
  for (const auto& x : v) {
    if (x.type != Type::periodic || !seen.insert(x.key).second) continue;
    const patterns::Word w = smallest_rotation(x.word);
    const patterns::Verdict<double> pv = patterns::analyse<double>(w, r);
    if (auto c = make_cone(x.key, w, r, opt, pv.orbit)) cones.push_back(std::move(*c));
  }
  return cones;
}

Certificates make_certificates(double r, const Options& opt) {
  Certificates cert;
  cert.cones = probe_cones(r, opt);
  cert.trap = make_trap(r, opt);
  for (long t = 64; t < opt.transient; t *= 2) cert.checkpoints.push_back(t);
  return cert;
}

}  // namespace btob::attractors::stages
