// SPDX-License-Identifier: GPL-3.0-or-later
// Lyapunov maps: the projective exponents of every orbit of an ensemble (r values x initial conditions),
// computed on the batched SIMD kernel (lyapunov::TangentRecorder), and their summary per r value.
#pragma once

#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"

#include <vector>

namespace btob::lyapunov {

struct TangentRecorder;

struct MapOptions {
  long transient = 1000;          // steps before averaging (orbit and tangent vector together), >= 0
  long iterations = 10000;        // averaged steps per orbit, >= blocks
  int blocks = 10;                // batch-means blocks, >= 2
  bool single_precision = false;  // run the plain kernel in float, the tangent recorder in double (otherwise: the fused
                                  // cocycle kernel in double, iterate/cocycle.hpp)
  iterate::RunOptions run;        // threads, progress
};

// Per-orbit exponents, in the ensemble's orbit order (o = r index * initial.size() + ic index).
// Which is which (tangent.hpp): lambda1 is the growth rate of one tangent vector (v0 = e1, the paper's
// lambda_n(x)), which converges to the larger projective exponent; lambda2 = (log |det D^n|)/n - lambda1.  With the
// linear cocycle of the products P_s (exponents chi1 >= chi2 >= chi3 in frame order, chi1 that of the orbit vector
// u itself) they are lambda_i = chi_{i+1} - chi1.  Where the two projective exponents are equal (invariant curves:
// both 0; sinks with a complex pair: both (1/2p) log|det| of the period) the finite-time lambda1 and lambda2 differ
// by O(1/n) either way, which batch means do not see: lambda2 > lambda1 then says nothing.  lambda_max >= lambda_min
// are the same two numbers ordered, each with its own error.
struct OrbitExponents {
  std::vector<double> lambda1, err1, lambda2, err2;              // projective exponents and batch-means errors
  std::vector<double> lambda_max, err_max, lambda_min, err_min;  // the same, ordered
  std::vector<double> chi1;  // growth rate of the orbit vector under P (linear cocycle)
  long iterations = 0;
  int blocks = 0;
};

// Throws std::invalid_argument naming the field for invalid options (see lyapunov::validate).
OrbitExponents map_exponents(const iterate::Ensemble& ensemble, const MapOptions& opt);

// The exponents from a finished run of a TangentRecorder (batch means over its blocks).
OrbitExponents exponents_from(const TangentRecorder& rec);
// The same from cumulative sums (L1, logG, n13 per orbit at the end of the transient and at each of `blocks` block
// ends, layout of ExponentSums::cum) over n averaged steps.
OrbitExponents exponents_from(const iterate::Ensemble& ensemble, long n, int blocks, const std::vector<long>& block_end,
                              const std::vector<double>& cum);

// Sign of an exponent given its error bar: +1 when lambda > k err + b, -1 when lambda < -(k err + b), else 0,
// with k = 3 (three standard errors) and b = 10 / n (finite-time bias floor: for a bounded cocycle
// |lambda_n - lambda| <= log(kappa) / n, kappa the conditioning of the frame, taken <= e^10).
int classify(double lambda, double err, long n);

// Summary of lambda1 per r value over its initial conditions, with error bars: err_min and err_max are the
// batch-means errors of the orbits realising min and max, err_median that of the median (the middle orbit's error,
// or half the root sum of squares of the two middle orbits' errors).  The finite-time floor 10/n is not in them.
struct RSummary {
  std::vector<double> min, median, max;
  std::vector<double> err_min, err_median, err_max;
  std::vector<double> frac_positive, frac_zero, frac_negative;
};
RSummary summarise(const OrbitExponents& e, std::size_t r_count, std::size_t n_ic);

}  // namespace btob::lyapunov
