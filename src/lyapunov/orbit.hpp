// SPDX-License-Identifier: GPL-3.0-or-later
// One orbit at the scalar limit: the point and two tangent vectors stepped together by the kernel's step (M_s = P_s /
// r, iterate/kernel_impl.hpp map_step, the exact branch rule), with no division, normalisation, allocation or indirect
// call per step; Gram-Schmidt only every few steps (the interval derived in orbit.cpp), the weighted Birkhoff averages
// step by step from the states between (weighted.hpp).  What projective_exponents runs.
#pragma once

#include "lyapunov/lyapunov.hpp"

#include <cstdint>
#include <type_traits>

namespace btob::lyapunov {

// The single-orbit route at the scalar limit: the point stepped by the batched kernel's
// step (M_s = P_s / r, the kernel's orbit bit for bit) with two tangent vectors stepped by the same M_s, no division or
// normalisation per step, one tangent vector projected every `len` steps (adaptive, see orbit.cpp; reorthonormalise > 1
// fixes it). Exponents differ from projective_exponents_qr's in the last digits (other roundings), within the error
// bars. float, double, long double, float128, MPFR (include core/scalar.hpp for the last two).
template <class T> ProjectiveResult projective_orbit(const Vec3<T>& u0, const T& r, const Options& opt);

// The route before projective_orbit, kept as the reference of the tests and benchmarks: P_s u with the tangent plane
// projected, divided and Gram-Schmidt orthonormalised every `reorthonormalise` steps (Eigen, every precision).
template <class T> ProjectiveResult projective_exponents_qr(const Vec3<T>& u0, const T& r, const Options& opt);

extern template ProjectiveResult projective_exponents_qr<double>(const Vec3<double>&, const double&, const Options&);

}  // namespace btob::lyapunov

namespace btob::lyapunov::detail {

// The symbols of the last kSymbolRing steps, written in place (step i at ring[i & (kSymbolRing - 1)]): the
// result's symbols_tail without a push per step.
inline constexpr long kSymbolRing = 4096;

// The orbit's state between two Gram-Schmidt steps.  u: the point in Q, scaled by exact powers of two (the batched
// kernel's orbit, bit for bit: the same step, the same start, rescaled by the same kind of factor); v: a tangent
// vector stepped by the same linear map M_s as u, without projection (the projective tangent vector of
// u -> M u / |M u| is the component of v orthogonal to u divided by |u|, taken at the Gram-Schmidt step).  One vector
// is enough: lambda1 + lambda2 is the orbit's own area growth (orbit.cpp), so lambda2 needs no second vector.
template <class T> struct OrbitFrame {
  T u[3];
  T v[3];
  T r, a, k;     // r, alpha = (1 + r) / 2 and k = alpha / r, in T (the kernel's)
  T scratch[5];  // the MPFR step's temporaries, allocated once per orbit (unused by the other precisions)
};

// The type in which the weighted Birkhoff average reads the orbit's states (weighted.hpp): double for float and double,
// long double (its 15-bit exponent: the squares of the states of one interval stay in range) for the others.
template <class T>
using TraceReal = std::conditional_t<std::is_same_v<T, float> || std::is_same_v<T, double>, double, long double>;

// Where advance writes the state after each step when the weighted average needs it: component c (u0, u1, u2, v0, v1,
// v2) of the state after step i (1..n) at at[c * stride + i]; at[c * stride] is the caller's (the start).
template <class W> struct Trace {
  W* at = nullptr;
  long stride = 0;
};

// n steps of the frame from step number `first` (the symbol of step first + i goes to ring[(first + i) % kSymbolRing]),
// and the states into `trace` when trace.at is not null (over the averaged steps).  Defined in kernel_orbit.cpp (the
// kernel's flags: FMA inline) for float, double, long double and float128, and in orbit_mpfr.cpp for MPFR (the mpfr_*
// C API on preallocated numbers).
template <class T> void advance(OrbitFrame<T>& f, long n, long first, std::uint8_t* ring, Trace<TraceReal<T>> trace);

}  // namespace btob::lyapunov::detail
