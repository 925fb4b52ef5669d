// SPDX-License-Identifier: GPL-3.0-or-later
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

namespace detail {

// One step of Ginelli's forward QR: D_k V_k = (P V - w (w . P V)) / |P u| (Section 8.1 (3)), w = P u / |P u|, then
// D_k V_k = V_{k+1} R_k by Gram-Schmidt, R = (R11, R12, R22).
template <class T> struct QrStep {
  Eigen::Matrix<T, 3, 2> V;
  std::array<T, 3> R;
};
template <class T> QrStep<T> qr_step(const Mat3<T>& P, const Eigen::Matrix<T, 3, 2>& V, const Vec3<T>& w, const T& g) {
  Eigen::Matrix<T, 3, 2> W = P * V;
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
  return {W, {n1, r12, n2}};
}

// What the forward pass keeps: R of every step from the window on, the window's frames (keep_vectors), the sums
// of log R11 and log R22 over the window and its expanding steps.
template <class T> struct GinelliForward {
  std::vector<std::array<T, 3>> R;  // (R11, R12, R22) of step transient + j
  std::vector<Eigen::Matrix<T, 3, 2>> frames;
  long double log_sum[2] = {0, 0};
  long n_expanding = 0;
};

// Forward over transient + window + backward transient steps from u0: the QR of every step, and in the window the
// expanding flags, symbols (and points) into res.
template <class T>
GinelliForward<T> ginelli_forward(const Vec3<T>& u0, const T& r, const ClvOptions& opt, ClvResult& res) {
  using std::log;
  const long T0 = opt.transient, N = opt.window, Nb = opt.backward_transient, K = T0 + N + Nb;
  const Mat3<T> Pm[3] = {core::P1(r), core::P2(r), core::P3(r)};
  const T r3 = r * r * r, dets[3] = {r3 * r, r3, r3 * r};  // det P1 = det P3 = r^4, det P2 = r^3 (Section 5.1)
  // The point is kept scaled by powers of two (detail::pow2_scaled), never divided by its norm: the branches are
  // those of the user's point to the last bit (a unit vector's rounding can cross a branch line); the derivative
  // and the singular values are taken at the unit point u / |u|.
  Vec3<T> u = detail::pow2_scaled<T>(core::to_quadrant<T>(u0));
  Eigen::Matrix<T, 3, 2> V = tangent_basis(Vec3<T>(u / u.norm()));
  GinelliForward<T> fw;
  fw.R.resize(static_cast<std::size_t>(N + Nb));
  res.expanding.reserve(static_cast<std::size_t>(N));
  res.symbols.reserve(static_cast<std::size_t>(N));
  for (long k = 0; k < K; ++k) {
    const int s = core::branch(u, r);
    const Vec3<T> pu = apply(s, u, r);
    const T nu = u.norm(), npu = pu.norm();
    const T g = npu / nu;  // |P u| at the unit point
    const Vec3<T> w = pu / npu;
    const bool in_window = k >= T0 && k < T0 + N;
    if (in_window) {
      const Vec3<T> unit = u / nu;
      const bool e = singular_values<T>(Pm[s - 1], dets[s - 1], unit)[0] >= 1;
      res.expanding.push_back(e);
      res.symbols.push_back(static_cast<std::uint8_t>(s));
      fw.n_expanding += e;
      if (opt.keep_vectors) {
        res.points.emplace_back(unit.template cast<double>());
        fw.frames.push_back(V);
      }
    }
    const QrStep<T> q = qr_step<T>(Pm[s - 1], V, w, g);
    if (k >= T0) fw.R[static_cast<std::size_t>(k - T0)] = q.R;
    if (in_window) {
      fw.log_sum[0] += static_cast<long double>(log(q.R[0]));
      fw.log_sum[1] += static_cast<long double>(log(q.R[2]));
    }
    V = q.V;
    u = detail::pow2_scaled<T>(pu);
  }
  return fw;
}

// Backward: the coefficients c of the second CLV in the frame V_k; the first CLV is V_k e1 (C upper triangular).
// c_k = R_k^{-1} c_{k+1}, normalised, from c = e2 after the last forward step; the window's angles (and vectors).
template <class T> void ginelli_backward(const GinelliForward<T>& fw, const ClvOptions& opt, ClvResult& res) {
  using std::abs;
  using std::atan2;
  using std::sqrt;
  const long N = opt.window, Nb = opt.backward_transient;
  res.angle.assign(static_cast<std::size_t>(N), 0.0);
  if (opt.keep_vectors) {
    res.clv1.resize(static_cast<std::size_t>(N));
    res.clv2.resize(static_cast<std::size_t>(N));
  }
  T c1 = 0, c2 = 1;
  for (long j = N + Nb - 1; j >= 0; --j) {
    const auto& Rj = fw.R[static_cast<std::size_t>(j)];
    c2 /= Rj[2];
    c1 = (c1 - Rj[1] * c2) / Rj[0];
    const T n = sqrt(c1 * c1 + c2 * c2);
    c1 /= n;
    c2 /= n;
    if (j >= N) continue;
    res.angle[static_cast<std::size_t>(j)] = static_cast<double>(atan2(abs(c2), abs(c1)));
    if (opt.keep_vectors) {
      const auto& F = fw.frames[static_cast<std::size_t>(j)];
      res.clv1[static_cast<std::size_t>(j)] = F.col(0).template cast<double>();
      res.clv2[static_cast<std::size_t>(j)] = (F.col(0) * c1 + F.col(1) * c2).template cast<double>();
    }
  }
}

// The exponents, the expanding fraction and the angles' statistics and histogram over the window.
template <class T> void clv_summary(const GinelliForward<T>& fw, const ClvOptions& opt, ClvResult& res) {
  const long N = opt.window;
  res.lambda = {static_cast<double>(fw.log_sum[0] / N), static_cast<double>(fw.log_sum[1] / N)};
  // The finite-time bias of a bounded cocycle is <= log(kappa) / n (maps.hpp); 10 / n is the same floor.
  res.degenerate = res.lambda[0] - res.lambda[1] < 10.0 / static_cast<double>(N);
  res.expanding_fraction = static_cast<double>(fw.n_expanding) / static_cast<double>(N);
  res.median_angle = quantile(res.angle, 0.5);
  res.q05_angle = quantile(res.angle, 0.05);
  res.min_angle = *std::min_element(res.angle.begin(), res.angle.end());
  res.histogram.assign(static_cast<std::size_t>(opt.bins), 0.0);
  for (double a : res.angle) res.histogram[static_cast<std::size_t>(angle_bin(a, opt.bins))] += 1;
}

}  // namespace detail

// check -> forward QR -> backward recursion -> summary.
template <class T> ClvResult covariant_vectors(const Vec3<T>& u0, const T& r, const ClvOptions& opt) {
  validate(opt);
  detail::check_start(u0, r);
  iterate::checked_bytes(static_cast<std::size_t>(opt.window + opt.backward_transient),
                         sizeof(std::array<T, 3>) + 4 * sizeof(double), "window");
  ClvResult res;
  const detail::GinelliForward<T> fw = detail::ginelli_forward<T>(u0, r, opt, res);
  detail::ginelli_backward<T>(fw, opt, res);
  detail::clv_summary<T>(fw, opt, res);
  return res;
}

}  // namespace btob::lyapunov
