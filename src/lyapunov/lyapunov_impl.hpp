// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of lyapunov.hpp (the projective and linear QR cocycles); included by lyapunov.cpp and by
// code that needs other scalar types (float128, mpfr).
#pragma once

#include "lyapunov/lyapunov.hpp"
#include "lyapunov/orbit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace btob::lyapunov {
namespace detail {

// One step of the map from u in Q with the branch s already chosen, in the form of eq. (3.5) (Theorem 3.3):
// written with c1 = alpha y - x and c3 = alpha y - z so that the image stays in Q exactly (x' = -r c1 >= 0
// on branch 2, etc.), which the plain matrix product does not guarantee under rounding near boundaries.
template <class T> Vec3<T> apply(int s, const Vec3<T>& u, const T& r) {
  const T a = core::alpha(r);
  const T c1 = a * u(1) - u(0), c3 = a * u(1) - u(2);
  if (s == 1) return Vec3<T>(r * c1, a * c1 - r * u(1) + r * a * u(2), r * r * u(2));
  if (s == 3) return Vec3<T>(r * r * u(0), a * c3 - r * u(1) + r * a * u(0), r * c3);
  return Vec3<T>(-r * c1, -a * c1 - a * c3 + r * u(1), -r * c3);
}

// One step of the batched kernel's orbit in scalar form (iterate/kernel_impl.hpp map_step with exact signs: the fused
// c1 = a y - x and c3 = a y - z, x' = r x or |c1|, z' = r z or -|c3|, y' = k (x' + z') -+ y, fused in float and
// double), so that linear_exponents follows projective_orbit's orbit bit for bit (M_s u = P_s u / r: the same direction
// as P_s u, other roundings).  k = a / r in T, as the kernel's.  Returns the symbol.
template <class T> int orbit_step(Vec3<T>& u, const T& r, const T& a, const T& k) {
  using std::fabs;
  using std::fma;
  const T c1 = core::fms<T>(a, u(1), u(0)), c3 = core::fms<T>(a, u(1), u(2));
  const bool s1 = core::sign_of_fms<T>(a, u(1), u(0), c1) > 0, s3 = core::sign_of_fms<T>(a, u(1), u(2), c3) < 0;
  const T xn = s3 ? T(r * u(0)) : T(fabs(c1));
  const T zn = s1 ? T(r * u(2)) : T(-fabs(c3));
  const T sy = (s1 || s3) ? T(-u(1)) : T(u(1));
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>) u(1) = fma(k, T(xn + zn), sy);
  else u(1) = T(k * T(xn + zn) + sy);
  u(0) = xn;
  u(2) = zn;
  return s1 ? 1 : (s3 ? 3 : 2);
}

// Where QR happens and where exponents are recorded.  Steps are numbered 1..transient+iterations; step
// k is "averaged" when k > transient.  QR at every multiple of m counted from the transient's end, at
// the transient's end, and at every checkpoint (block ends, powers of two of the averaged length).
struct Schedule {
  long transient, n;
  int m, blocks;
  std::vector<long> block_end;   // averaged-step counts at which blocks end, increasing, last = n
  std::vector<long> checkpoint;  // averaged-step counts recorded in the convergence report
  explicit Schedule(const Options& o)
      : transient(o.transient), n(o.iterations), m(o.reorthonormalise), blocks(o.blocks) {
    for (int j = 1; j <= blocks; ++j) block_end.push_back(n * j / blocks);
    for (long p = 1; p < n; p *= 2) checkpoint.push_back(p);
    checkpoint.insert(checkpoint.end(), block_end.begin(), block_end.end());
    std::sort(checkpoint.begin(), checkpoint.end());
    checkpoint.erase(std::unique(checkpoint.begin(), checkpoint.end()), checkpoint.end());
  }
  bool qr_at(long k, std::size_t next_cp) const {
    if (k <= transient) return k % m == 0 || k == transient;
    const long j = k - transient;
    return j % m == 0 || (next_cp < checkpoint.size() && checkpoint[next_cp] == j);
  }
};

// Accumulates the sums of log R_ii; records cumulative sums at block ends and averages at checkpoints.
template <int N> struct Accumulator {
  const Schedule& sc;
  std::array<long double, N> sum{}, wsum{};
  long double wnorm = 0;
  bool weigh_intervals = true;  // false: the caller fills wsum and wnorm step by step (projective_orbit)
  long last = 0;                // averaged-step count at the previous QR
  std::vector<std::array<double, N>> at_block_end;
  std::size_t next_cp = 0, next_block = 0;
  Convergence conv;
  explicit Accumulator(const Schedule& s) : sc(s) { conv.exponents.assign(N, {}); }
  template <class T> void add(long k, const std::array<T, N>& logs) {
    if (k <= sc.transient) return;
    for (int i = 0; i < N; ++i) sum[i] += static_cast<long double>(logs[i]);
    const long j = k - sc.transient;
    if (weigh_intervals) weigh_interval(j, logs);
    last = j;
    record(j);
  }
  template <class T> void weigh_interval(long j, const std::array<T, N>& logs) {
    // Weighted Birkhoff average (Das, Sander, Yorke 2017): weight exp(-1/(t(1-t))) at the middle t of the
    // steps since the last QR.  On periodic and quasi-periodic orbits the per-step logs are quasi-periodic
    // and this average converges faster than any power of 1/n, where the plain one converges like 1/n.
    const long double t = (static_cast<long double>(last + j) / 2) / static_cast<long double>(sc.n);
    const long double w = (j - last) * std::exp(-1 / (t * (1 - t)));
    for (int i = 0; i < N; ++i) wsum[i] += w * static_cast<long double>(logs[i]) / (j - last);
    wnorm += w;
  }
  void record(long j) {
    if (next_cp < sc.checkpoint.size() && sc.checkpoint[next_cp] == j) {
      conv.n.push_back(j);
      for (int i = 0; i < N; ++i) conv.exponents[i].push_back(static_cast<double>(sum[i] / j));
      ++next_cp;
    }
    if (next_block < sc.block_end.size() && sc.block_end[next_block] == j) {
      std::array<double, N> c;
      for (int i = 0; i < N; ++i) c[i] = static_cast<double>(sum[i]);
      at_block_end.push_back(c);
      ++next_block;
    }
  }
  Estimate estimate(int i) const;
  double weighted(int i) const { return static_cast<double>(wsum[i] / wnorm); }
};

// Batch means from cumulative sums at block ends (cum[j] after block j) and the block ends themselves.
Estimate batch_means(const std::vector<double>& cum, const std::vector<long>& block_end);

template <int N> Estimate Accumulator<N>::estimate(int i) const {
  std::vector<double> cum;
  for (const auto& c : at_block_end) cum.push_back(c[i]);
  Estimate e = batch_means(cum, sc.block_end);
  e.value = static_cast<double>(sum[i] / sc.n);  // the full-length average, in the accumulator's precision
  return e;
}

// The error bar includes the arithmetic: batch means see only the statistical spread (on a sink computed in
// float the block means agree exactly while the exponent is off by ~2e-7), so the error is at least
// 4 eps |lambda| (eps of T, and at least double's: the result is reported in double); measured errors on
// sinks: float 1.6 eps, double 2.5 eps.
template <class T> Estimate with_rounding_floor(Estimate e) {
  const double eps =
      std::max(static_cast<double>(std::numeric_limits<T>::epsilon()), std::numeric_limits<double>::epsilon());
  e.error = std::max(e.error, 4 * eps * std::max(1.0, std::fabs(e.value)));
  return e;
}

// u scaled by an exact power of two so that its largest component lies in [1, 2): the same direction to the last
// bit, so the branches are those of the user's point (a division by |u| rounds it, and a point on or next to a
// branch line could change side: core::branch decides on exact signs).
template <class T> Vec3<T> pow2_scaled(const Vec3<T>& u) {
  using std::fabs;
  using std::frexp;
  using std::ldexp;
  const T m = fabs(u(0)) > fabs(u(1)) ? (fabs(u(0)) > fabs(u(2)) ? T(fabs(u(0))) : T(fabs(u(2))))
                                      : (fabs(u(1)) > fabs(u(2)) ? T(fabs(u(1))) : T(fabs(u(2))));
  int e = 0;
  frexp(m, &e);
  return Vec3<T>(T(ldexp(u(0), 1 - e)), T(ldexp(u(1), 1 - e)), T(ldexp(u(2), 1 - e)));
}

template <class T> void check_start(const Vec3<T>& u0, const T& r) {
  core::validate_r(r);
  core::validate_point(static_cast<double>(u0(0)), static_cast<double>(u0(1)), static_cast<double>(u0(2)), "point");
}

}  // namespace detail

template <class T> Eigen::Matrix<T, 3, 2> tangent_basis(const Vec3<T>& u) {
  using std::abs;
  int i = 0;  // the coordinate axis least aligned with u
  for (int j = 1; j < 3; ++j)
    if (abs(u(j)) < abs(u(i))) i = j;
  Vec3<T> axis = Vec3<T>::Zero();
  axis(i) = T(1);
  Eigen::Matrix<T, 3, 2> b;
  b.col(0) = u.cross(axis).normalized();
  b.col(1) = u.cross(Vec3<T>(b.col(0))).normalized();
  return b;
}

template <class T> Mat3<T> projective_derivative(const Mat3<T>& P, const Vec3<T>& u) {
  const Vec3<T> pu = P * u;
  const T g = pu.norm();
  const Vec3<T> w = pu / g;
  return (Mat3<T>::Identity() - w * w.transpose()) * P / g;
}

// The one-orbit route at the scalar limit (orbit.hpp); the QR route (below) stays as the tests' and benchmarks'
// reference.  Its weighted averages weigh every step (weighted.hpp), as the QR route's do.
template <class T> ProjectiveResult projective_exponents(const Vec3<T>& u0, const T& r, const Options& opt) {
  return projective_orbit<T>(u0, r, opt);
}

template <class T> ProjectiveResult projective_exponents_qr(const Vec3<T>& u0, const T& r, const Options& opt) {
  using std::log;
  validate(opt);
  detail::check_start(u0, r);
  const detail::Schedule sc(opt);
  detail::Accumulator<2> acc(sc);
  const Mat3<T> Pm[3] = {core::P1(r), core::P2(r), core::P3(r)};
  // The point is kept scaled by powers of two (detail::pow2_scaled), never divided by its norm.
  Vec3<T> u = detail::pow2_scaled<T>(core::to_quadrant<T>(u0));
  Eigen::Matrix<T, 3, 2> V = tangent_basis(Vec3<T>(u / u.norm()));
  const long total = opt.transient + opt.iterations;
  ProjectiveResult res;
  const long keep = std::min<long>(opt.iterations, 4096);
  for (long k = 1; k <= total; ++k) {
    core::poll_cancel(opt.cancel, k);
    const int s = core::branch(u, r);
    const Vec3<T> pu = detail::apply(s, u, r);
    const T g = pu.norm();
    const Vec3<T> w = pu / g;
    // D(u) V = (P V - w (w . P V)) |u| / |P u| (Section 8.1 (3): the derivative cocycle on tangent planes, at the
    // unit point u / |u|).
    Eigen::Matrix<T, 3, 2> W = Pm[s - 1] * V;
    W -= w * (w.transpose() * W);
    V = W * T(u.norm() / g);
    u = detail::pow2_scaled<T>(pu);
    if (k > total - keep) res.symbols_tail.push_back(s);
    if (sc.qr_at(k, acc.next_cp)) {  // Gram-Schmidt QR of the two tangent vectors
      const T n1 = V.col(0).norm();
      V.col(0) /= n1;
      V.col(1) -= V.col(0) * V.col(0).dot(V.col(1));
      const T n2 = V.col(1).norm();
      V.col(1) /= n2;
      acc.add(k, std::array<T, 2>{log(n1), log(n2)});
    }
  }
  res.lambda = {detail::with_rounding_floor<T>(acc.estimate(0)), detail::with_rounding_floor<T>(acc.estimate(1))};
  res.weighted = {acc.weighted(0), acc.weighted(1)};
  // lambda1 >= lambda2: the first QR vector's growth converges to the larger exponent, but where the two are equal
  // (a complex pair, an elliptic point) the finite-time estimates may come out in either order.
  if (res.lambda[0].value < res.lambda[1].value) {
    std::swap(res.lambda[0], res.lambda[1]);
    std::swap(res.weighted[0], res.weighted[1]);
  }
  res.iterations = opt.iterations;
  res.blocks = opt.blocks;
  res.convergence = acc.conv;
  u /= u.norm();
  res.final_point = Vec3<double>(static_cast<double>(u(0)), static_cast<double>(u(1)), static_cast<double>(u(2)));
  return res;
}

template <class T> LinearResult linear_exponents(const Vec3<T>& u0, const T& r, const Options& opt) {
  using std::abs;
  using std::log;
  validate(opt);
  detail::check_start(u0, r);
  const detail::Schedule sc(opt);
  detail::Accumulator<3> acc(sc);
  const Mat3<T> Pm[3] = {core::P1(r), core::P2(r), core::P3(r)};
  Vec3<T> u = detail::pow2_scaled<T>(core::to_quadrant<T>(u0));  // branches of the user's point, to the last bit
  const T a = (T(1) + r) / T(2), kr = T(a / r);                  // the kernel's alpha and k (OrbitFrame)
  Mat3<T> Q;
  Q.col(0) = u / u.norm();
  Q.template rightCols<2>() = tangent_basis(u);
  const long total = opt.transient + opt.iterations;
  for (long k = 1; k <= total; ++k) {
    core::poll_cancel(opt.cancel, k);
    const int s = detail::orbit_step<T>(u, r, a, kr);  // the orbit of projective_exponents (projective_orbit)
    u = detail::pow2_scaled<T>(u);
    Q = Pm[s - 1] * Q;  // the linear cocycle: products of P_i along the orbit
    if (sc.qr_at(k, acc.next_cp)) {
      const Eigen::HouseholderQR<Mat3<T>> qr(Q);
      const Mat3<T> R = qr.matrixQR().template triangularView<Eigen::Upper>();
      Mat3<T> Qn = qr.householderQ();
      std::array<T, 3> logs;
      for (int i = 0; i < 3; ++i) logs[i] = log(abs(R(i, i)));
      // The first column is the orbit vector (Q.col(0) = +-u up to rounding): pin it to the orbit so that
      // rounding in the frame cannot drift it away from the orbit on chaotic orbits.
      Qn.col(0) = u / u.norm();
      Q = Qn;
      acc.add(k, logs);
    }
  }
  LinearResult res;
  res.chi = {detail::with_rounding_floor<T>(acc.estimate(0)), detail::with_rounding_floor<T>(acc.estimate(1)),
             detail::with_rounding_floor<T>(acc.estimate(2))};
  res.weighted = {acc.weighted(0), acc.weighted(1), acc.weighted(2)};
  res.iterations = opt.iterations;
  res.blocks = opt.blocks;
  res.convergence = acc.conv;
  return res;
}

}  // namespace btob::lyapunov
