// SPDX-License-Identifier: GPL-3.0-or-later
// Lyapunov exponents of the b-to-b map (paper, Section 8.1 (3)): the projective derivative cocycle and the
// linear cocycle of the products of P_i along an orbit, both with QR (Benettin) re-orthonormalisation.
#pragma once

#include "core/cancel.hpp"
#include "core/map.hpp"
#include "core/result.hpp"

#include <array>
#include <string>
#include <vector>

namespace btob::lyapunov {

using core::Mat3;
using core::Vec3;

// Conventions:
//  * Exponents are per map iteration, natural log.  The projective exponents lambda1 >= lambda2 are those
//    of u -> P u / |P u| on the sphere (the 2-D map of the paper); the linear exponents chi1, chi2, chi3
//    are those of the products P_{s_n} ... P_{s_1} along the same orbit, with the frame started at
//    [u0, e1, e2] (e1, e2 the tangent basis below), so that chi1 is the growth rate of the orbit vector
//    itself and lambda_i = chi_{i+1} - chi1 holds step by step, up to rounding.
//  * Both routes run transient + iterations steps from u0 (brought into Q); the orbit and the tangent
//    frame are iterated together and only the last `iterations` steps are averaged.
//  * Besides the plain averages (the paper's lambda_n), weighted Birkhoff averages with the weight
//    exp(-1/(t(1-t))), t = step/iterations (Das, Sander, Yorke, Nonlinearity 2017): on periodic orbits whose
//    tangent frame rotates (complex eigenvalues) the plain average converges like 1/n, the weighted one
//    faster than any power of 1/n.
//  * Error bars: batch means.  The averaged steps are cut into `blocks` consecutive blocks (sizes differ
//    by at most one step); error = standard deviation of the block means / sqrt(blocks), but at least
//    4 eps |lambda| (eps of T or of double, whichever is larger): the arithmetic's own floor, which batch
//    means cannot see on a sink.
struct Options {
  long transient = 1000;     // steps discarded before averaging (orbit and frame converge), >= 0
  long iterations = 100000;  // averaged steps, >= blocks
  int reorthonormalise = 1;  // QR every this many steps (also at the transient's end and block ends), >= 1
  int blocks = 20;           // batch-means blocks, >= 2
  // The weighted Birkhoff averages too (projective_orbit: a trace of the states between projections and a pass over
  // it, about 40% of a double step).  false: ProjectiveResult::weighted is not computed (has_weighted = false).
  bool weighted = true;
  const core::CancelToken* cancel = nullptr;  // how to run, not what: polled every core::cancel_stride steps
};

// Throws std::invalid_argument "field: got X, expected Y" for non-positive lengths or blocks > iterations.
void validate(const Options& opt);

struct Estimate {
  double value = 0;  // per iteration, natural log
  double error = 0;  // batch-means standard error
};

// Exponent against the number of averaged steps n (powers of two and block ends, increasing).
struct Convergence {
  std::vector<std::uint64_t> n;                // averaged-step counts: powers of two and block ends
  std::vector<std::vector<double>> exponents;  // exponents[i][j]: exponent i at n[j]
};

struct ProjectiveResult {
  std::array<Estimate, 2> lambda;  // lambda1 >= lambda2 of the projective cocycle
  std::array<double, 2> weighted;  // the same, as weighted Birkhoff averages (fast on (quasi-)periodic orbits)
  bool has_weighted = true;        // whether `weighted` was computed (Options::weighted)
  long iterations = 0;             // map iterations averaged (the request's, after the transient)
  int blocks = 0;                  // batch-means blocks of the error bars (the request's)
  Convergence convergence;         // the running averages at every checkpoint (what --convergence writes)
  std::vector<int> symbols_tail;   // symbols of the last min(iterations, 4096) steps (for period detection)
  Vec3<double> final_point;        // u after transient + iterations steps (unit, in Q)
  // Attributes lambda1, err1, lambda2, err2, lambda1_weighted, lambda2_weighted, iterations, blocks (the
  // columns `btob lyapunov --weighted` prints); arrays convergence_n, convergence_lambda1, convergence_lambda2 (the
  // table `btob lyapunov --convergence FILE` writes: the running averages at every checkpoint).  lambda1 and
  // lambda2 are estimates (core::Status): the error bar is the batch-means standard error (floored at the
  // arithmetic's 4 eps |lambda|).
  void describe(core::Contents& c) const;
  // What `btob lyapunov` prints and --out writes to NAME.csv: lambda1,err1,lambda2,err2,iterations,status (with the
  // weighted averages first when weighted_columns), each value and its bar by core::with_error, so that the
  // printed interval contains the stored value.
  bool weighted_columns = false;
  std::string csv() const;
  core::Tables tables() const { return {{"", csv()}}; }
};

struct LinearResult {
  std::array<Estimate, 3> chi;     // in frame order: chi1 = growth of the orbit vector, then QR order
  std::array<double, 3> weighted;  // the same, as weighted Birkhoff averages
  long iterations = 0;
  int blocks = 0;
  Convergence convergence;
};

// Orthonormal basis (e1, e2) of the tangent plane u^perp, u != 0 (columns of a 3x2 matrix).
template <class T> Eigen::Matrix<T, 3, 2> tangent_basis(const Vec3<T>& u);

// The derivative of u -> P u / |P u| at u as a 3x3 matrix acting on tangent vectors v (v . u = 0):
// D(u) v = (P v - w (w . P v)) / |P u|, w = P u / |P u|.  Valid for any u != 0 with |u| = 1.
template <class T> Mat3<T> projective_derivative(const Mat3<T>& P, const Vec3<T>& u);

// Both projective exponents from u0 at restitution r (r in (0,1), u0 in the domain, non-zero).
template <class T> ProjectiveResult projective_exponents(const Vec3<T>& u0, const T& r, const Options& opt);

// The three exponents of the linear cocycle along the same orbit (Householder QR of 3 vectors).
template <class T> LinearResult linear_exponents(const Vec3<T>& u0, const T& r, const Options& opt);

// Finite differences: two orbits a distance delta apart, the partner re-placed at distance delta along
// the current separation after every step.  Returns the average log-stretching per step, the naive
// estimate of lambda1 that is wrong wherever the pair straddles a branch boundary (the map is
// discontinuous there).  `straddles` counts the steps at which the two points used different branches.
struct FiniteDifference {
  double lambda1 = 0;
  long straddles = 0;
};
FiniteDifference finite_difference_exponent(const Vec3<double>& u0, double r, double delta, const Options& opt);

// The exponents of a periodic orbit from the eigenvalues l1, l2, l3 (|l1| >= |l2| >= |l3|) of its period
// matrix M = P_{s_p} ... P_{s_1}: {log|l2/l1| / p, log|l3/l1| / p}.  Symbols in {1, 2, 3}.  |l3| is taken as
// |det M| / (|l1| |l2|) with det M the product of det P_i (r^4, r^3, r^4): an eigen-solver gives the smallest
// eigenvalue only to eps |l1|, far too coarse when |l3/l1| ~ 1e-13.
std::array<double, 2> periodic_exponents(const std::vector<int>& period_symbols, double r);

// Median of a sample (mean of the middle pair for an even size); NaN for an empty sample.  The per-r medians
// of lyapunov-map and hyperbolicity-orbits both use it, so their columns are comparable.
double median(std::vector<double> sample);

// The shortest period p of the tail of a symbol sequence (the last `check` symbols repeat with period p),
// or 0 when none up to max_period.
int detect_period(const std::vector<int>& symbols, int max_period, int check);

extern template Eigen::Matrix<double, 3, 2> tangent_basis<double>(const Vec3<double>&);
extern template Mat3<double> projective_derivative<double>(const Mat3<double>&, const Vec3<double>&);
extern template ProjectiveResult projective_exponents<double>(const Vec3<double>&, const double&, const Options&);
extern template ProjectiveResult projective_exponents<long double>(const Vec3<long double>&, const long double&,
                                                                   const Options&);
extern template LinearResult linear_exponents<double>(const Vec3<double>&, const double&, const Options&);
extern template LinearResult linear_exponents<long double>(const Vec3<long double>&, const long double&,
                                                           const Options&);
// float, float128 and MPFR: lyapunov_mp.cpp (include core/scalar.hpp for the latter two).
extern template ProjectiveResult projective_exponents<float>(const Vec3<float>&, const float&, const Options&);
extern template LinearResult linear_exponents<float>(const Vec3<float>&, const float&, const Options&);

}  // namespace btob::lyapunov
