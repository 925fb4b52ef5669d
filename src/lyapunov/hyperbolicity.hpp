// SPDX-License-Identifier: GPL-3.0-or-later
// (Non-)hyperbolicity of the projective map (paper, Section 8.1 (3)): singular values of the one-step derivative
// D P-hat(u) on the tangent plane, the fraction of expanding steps along an orbit, and the covariant Lyapunov
// vectors (Ginelli's forward-backward method) with the angle between the two Oseledets directions.
#pragma once

#include "iterate/kernel.hpp"
#include "lyapunov/lyapunov.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numbers>
#include <vector>

namespace btob::lyapunov {

// Conventions:
//  * Everything is measured in the round metric of the unit sphere: D P-hat(u) maps the tangent plane u^perp to
//    w^perp, w = P u / |P u|.  In orthonormal bases B_u, B_w of these planes it is the 2x2 matrix
//    A = B_w^T P B_u / |P u| (B_w^T w = 0 removes the projection of projective_derivative).
//  * Closed form (|u| = 1): s1^2 + s2^2 = |A|_F^2 and s1 s2 = |det P| / |P u|^3 (det P1 = det P3 = r^4,
//    det P2 = r^3), so s1,2^2 = (F +- sqrt(F^2 - 4 D^2)) / 2.  s1 >= 1 marks an expanding step.
//  * The CLV angle is the angle between the two covariant directions as lines, in radians, in [0, pi/2]:
//    pi/2 when they are orthogonal, near 0 when the splitting is nearly degenerate (far from uniform
//    hyperbolicity).  It is undefined when lambda1 = lambda2 (e.g. a sink whose period matrix has a complex
//    subdominant pair, like 132312): such orbits are flagged `degenerate`.

// Singular values s1 >= s2 > 0 of D P-hat at u (|u| = 1, P u != 0) for the branch matrix P with det P = det_P.
template <class T> std::array<T, 2> singular_values(const Mat3<T>& P, const T& det_P, const Vec3<T>& u);

// The same at any u in the domain (normalised and brought into Q first), with the branch the map uses there.
struct StepSingularValues {
  double s1 = 0, s2 = 0;
  int symbol = 0;  // 1, 2 or 3
};
StepSingularValues step_singular_values(const Vec3<double>& u, double r);

// s1, s2 and the branch over the n1 x n2 cell centres of the strip (eq. (6.4)), w1 in [w1_min, w1_max],
// w2 in [-1, 1]; arrays in iterate::strip_grid order (w1-major: index i1 * n2 + i2).
struct StripSingularValues {
  long n1 = 0, n2 = 0;
  double w1_min = 0, w1_max = 0;
  std::vector<double> w1, w2, s1, s2;
  std::vector<std::uint8_t> symbol;
  double expanding_fraction = 0;  // fraction of cells with s1 >= 1
};
// Throws std::invalid_argument / std::domain_error naming the field for a bad r, size or range.
StripSingularValues strip_singular_values(double r, long n1, long n2, double w1_min, double w1_max);

struct ClvOptions {
  long transient = 10000;           // forward steps before the window (orbit and forward frame converge), >= 0
  long window = 10000;              // steps at which CLVs, angles and expanding flags are recorded, >= 1
  long backward_transient = 10000;  // forward steps after the window, iterated back first (Ginelli), >= 1
  int bins = 90;                    // histogram bins of the angle over [0, pi/2], >= 1
  bool keep_vectors = false;        // also return the orbit points and both CLVs at every window step
};
// Throws std::invalid_argument "field: got X, expected Y".
void validate(const ClvOptions& o);

struct ClvResult {
  std::vector<double> angle;            // per window step, radians in [0, pi/2]
  std::vector<std::uint8_t> expanding;  // per window step: 1 when s1 >= 1 at that point
  std::vector<std::uint8_t> symbols;    // per window step: the branch 1, 2, 3
  double expanding_fraction = 0;        // mean of `expanding`
  std::array<double, 2> lambda{};       // exponents from the forward QR over the window (per step, natural log)
  bool degenerate = false;              // lambda1 - lambda2 < 10 / window: the splitting is not resolved
  double median_angle = 0, q05_angle = 0, min_angle = 0;  // radians
  std::vector<double> histogram;                          // counts of `angle` in `bins` equal bins over [0, pi/2]
  std::vector<Vec3<double>> points, clv1, clv2;           // if keep_vectors: u_k (unit, in Q) and unit CLVs at u_k
};

// Ginelli et al. (PRL 99, 130601, 2007): forward QR D_k V_k = V_{k+1} R_k over transient + window +
// backward_transient steps, storing R_k over the last two; backward C_k = R_k^{-1} C_{k+1} from C = I (columns
// normalised); CLV_j(k) = V_k C_k e_j.  u0 in the domain, r in (0, 1).
template <class T> ClvResult covariant_vectors(const Vec3<T>& u0, const T& r, const ClvOptions& opt);

// Quantile q in [0, 1] of a sample (nearest rank on the sorted copy); NaN for an empty sample.
double quantile(std::vector<double> sample, double q);
// Its rank among n >= 1 ascending values: nearest rank of q (n - 1), q clamped to [0, 1].
inline std::size_t quantile_rank(double q, std::size_t n) {
  return static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(n - 1) + 0.5);
}

// The histogram bin of an angle in [0, pi/2] among `bins` equal bins (the last one closed).
inline long angle_bin(double angle, int bins) {
  return std::clamp<long>(static_cast<long>(angle / (std::numbers::pi / 2) * bins), 0, bins - 1);
}

// The CLVs of many orbits at one r: per orbit what covariant_vectors gives (angle, expanding and symbols only with
// keep_steps; points and vectors never; a degenerate orbit's angle statistics NaN and its histogram empty: its
// angles are undefined), and the angle statistics pooled over the non-degenerate orbits, as
// `btob hyperbolicity-orbits` reports them.
struct ClvRow {
  std::vector<ClvResult> orbit;
  double median_angle = 0, q05_angle = 0, min_angle = 0;  // NaN when every orbit is degenerate
  std::vector<double> histogram;                          // summed over the non-degenerate orbits
};
using ClvRows = std::vector<ClvRow>;
// The batched route (kernel_clv.cpp), one row per r: lanes of orbits in SIMD registers through the plain kernel's
// map step (the symbols are iterate::run<double>'s), the Ginelli frame carried unnormalised (divisions only at the
// steps whose R is stored), the backward pass over each batch's stored window coefficients.  An orbit's bits depend
// on its start, its r and opt only: not on threads nor on the other orbits.  Memory: per thread one batch's
// coefficients, 16 lanes (AVX-512; 8 with AVX2, 4 with SSE2) x 3 window doubles (the backward transient is composed
// as it is stepped, into one map of tau per lane), and for the r values in flight (4 per thread) initial.size() x
// window doubles each (the angles pooled per r).
// run: threads, cancellation (checked per 4 r per thread; throws core::Cancelled), progress.
ClvRows covariant_vectors_batched(const std::vector<double>& r, const std::vector<Vec3<double>>& initial,
                                  const ClvOptions& opt, const iterate::RunOptions& run = {}, bool keep_steps = false);

extern template std::array<double, 2> singular_values<double>(const Mat3<double>&, const double&, const Vec3<double>&);
extern template std::array<long double, 2> singular_values<long double>(const Mat3<long double>&, const long double&,
                                                                        const Vec3<long double>&);
extern template ClvResult covariant_vectors<double>(const Vec3<double>&, const double&, const ClvOptions&);
extern template ClvResult covariant_vectors<long double>(const Vec3<long double>&, const long double&,
                                                         const ClvOptions&);

}  // namespace btob::lyapunov
