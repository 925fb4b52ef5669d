// Template bodies of hyperbolicity.hpp (singular values of D P-hat, Ginelli's covariant Lyapunov vectors);
// included by hyperbolicity.cpp and by code that needs other scalar types.
#pragma once

#include "core/coords.hpp"
#include "iterate/ensemble.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/lyapunov_impl.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace btob::lyapunov {

template <class T> std::array<T, 2> singular_values(const Mat3<T>& P, const T& det_P, const Vec3<T>& u) {
  using std::abs;
  using std::max;
  using std::sqrt;
  const Vec3<T> pu = P * u;
  const T g = pu.norm();
  const Vec3<T> w = pu / g;
  // A = B_w^T D B_u with D = projective_derivative(P, u); B_w^T w = 0 leaves B_w^T P B_u / |P u|.
  const Eigen::Matrix<T, 2, 2> A = tangent_basis<T>(w).transpose() * P * tangent_basis<T>(u) / g;
  const T F = A.squaredNorm();           // s1^2 + s2^2
  const T D = abs(det_P) / (g * g * g);  // s1 s2: det P = |P u| * det(|P u| A) in the frames [u B_u], [w B_w]
  // F >= 2 D (arithmetic-geometric mean); rounding can make (F - 2D) slightly negative where s1 = s2.
  const T disc = sqrt(max(T(0), (F - 2 * D) * (F + 2 * D)));
  const T s1 = sqrt((F + disc) / 2);
  return {s1, D / s1};  // s2 = D / s1: no cancellation when s2 << s1
}

template <class T> ClvResult covariant_vectors(const Vec3<T>& u0, const T& r, const ClvOptions& opt) {
  using std::abs;
  using std::atan2;
  using std::log;
  using std::sqrt;
  validate(opt);
  detail::check_start(u0, r);
  const long T0 = opt.transient, N = opt.window, Nb = opt.backward_transient, K = T0 + N + Nb;
  iterate::checked_bytes(static_cast<std::size_t>(N + Nb), sizeof(std::array<T, 3>) + 4 * sizeof(double), "window");
  const Mat3<T> Pm[3] = {core::P1(r), core::P2(r), core::P3(r)};
  const T r3 = r * r * r, dets[3] = {r3 * r, r3, r3 * r};  // det P1 = det P3 = r^4, det P2 = r^3 (Section 5.1)
  // The point is kept scaled by powers of two (detail::pow2_scaled), never divided by its norm: the branches are
  // those of the user's point to the last bit (a unit vector's rounding can cross a branch line); the derivative
  // and the singular values are taken at the unit point u / |u|.
  Vec3<T> u = detail::pow2_scaled<T>(core::to_quadrant<T>(u0));
  Eigen::Matrix<T, 3, 2> V = tangent_basis(Vec3<T>(u / u.norm()));
  std::vector<std::array<T, 3>> R(static_cast<std::size_t>(N + Nb));  // (R11, R12, R22) of step T0 + j
  std::vector<Eigen::Matrix<T, 3, 2>> frames;
  ClvResult res;
  res.expanding.reserve(static_cast<std::size_t>(N));
  res.symbols.reserve(static_cast<std::size_t>(N));
  long double log_sum[2] = {0, 0};
  long n_expanding = 0;
  for (long k = 0; k < K; ++k) {
    const int s = core::branch(u, r);
    const Vec3<T> pu = detail::apply(s, u, r);
    const T nu = u.norm(), npu = pu.norm();
    const T g = npu / nu;  // |P u| at the unit point
    const Vec3<T> w = pu / npu;
    const bool in_window = k >= T0 && k < T0 + N;
    if (in_window) {
      const Vec3<T> unit = u / nu;
      const bool e = singular_values<T>(Pm[s - 1], dets[s - 1], unit)[0] >= 1;
      res.expanding.push_back(e);
      res.symbols.push_back(static_cast<std::uint8_t>(s));
      n_expanding += e;
      if (opt.keep_vectors) {
        res.points.emplace_back(unit.template cast<double>());
        frames.push_back(V);
      }
    }
    // D_k V_k = (P V - w (w . P V)) / |P u| (Section 8.1 (3)), then D_k V_k = V_{k+1} R_k by Gram-Schmidt.
    Eigen::Matrix<T, 3, 2> W = Pm[s - 1] * V;
    W -= w * (w.transpose() * W);
    W /= g;
    const T n1 = W.col(0).norm();
    W.col(0) /= n1;
    T r12 = W.col(0).dot(W.col(1));
    W.col(1) -= W.col(0) * r12;
    // A second pass (classical Gram-Schmidt twice): keeps the frame orthonormal to rounding even when the two
    // images are nearly parallel, as they become after a few steps when lambda1 - lambda2 is large.
    const T r12b = W.col(0).dot(W.col(1));
    W.col(1) -= W.col(0) * r12b;
    r12 += r12b;
    const T n2 = W.col(1).norm();
    W.col(1) /= n2;
    if (k >= T0) R[static_cast<std::size_t>(k - T0)] = {n1, r12, n2};
    if (in_window) {
      log_sum[0] += static_cast<long double>(log(n1));
      log_sum[1] += static_cast<long double>(log(n2));
    }
    V = W;
    u = detail::pow2_scaled<T>(pu);
  }
  // Backward: the coefficients c of the second CLV in the frame V_k; the first CLV is V_k e1 (C upper
  // triangular).  c_k = R_k^{-1} c_{k+1}, normalised, from c = e2 after the last forward step.
  res.angle.assign(static_cast<std::size_t>(N), 0.0);
  if (opt.keep_vectors) {
    res.clv1.resize(static_cast<std::size_t>(N));
    res.clv2.resize(static_cast<std::size_t>(N));
  }
  T c1 = 0, c2 = 1;
  for (long j = N + Nb - 1; j >= 0; --j) {
    const auto& Rj = R[static_cast<std::size_t>(j)];
    c2 /= Rj[2];
    c1 = (c1 - Rj[1] * c2) / Rj[0];
    const T n = sqrt(c1 * c1 + c2 * c2);
    c1 /= n;
    c2 /= n;
    if (j < N) {
      res.angle[static_cast<std::size_t>(j)] = static_cast<double>(atan2(abs(c2), abs(c1)));
      if (opt.keep_vectors) {
        const auto& F = frames[static_cast<std::size_t>(j)];
        res.clv1[static_cast<std::size_t>(j)] = F.col(0).template cast<double>();
        res.clv2[static_cast<std::size_t>(j)] = (F.col(0) * c1 + F.col(1) * c2).template cast<double>();
      }
    }
  }
  res.lambda = {static_cast<double>(log_sum[0] / N), static_cast<double>(log_sum[1] / N)};
  // The finite-time bias of a bounded cocycle is <= log(kappa) / n (maps.hpp); 10 / n is the same floor.
  res.degenerate = res.lambda[0] - res.lambda[1] < 10.0 / static_cast<double>(N);
  res.expanding_fraction = static_cast<double>(n_expanding) / static_cast<double>(N);
  res.median_angle = quantile(res.angle, 0.5);
  res.q05_angle = quantile(res.angle, 0.05);
  res.min_angle = *std::min_element(res.angle.begin(), res.angle.end());
  res.histogram.assign(static_cast<std::size_t>(opt.bins), 0.0);
  for (double a : res.angle) res.histogram[static_cast<std::size_t>(angle_bin(a, opt.bins))] += 1;
  return res;
}

}  // namespace btob::lyapunov
