// SPDX-License-Identifier: GPL-3.0-or-later
// The window lower bound without huge coefficients: Q_n's sign from 3x3 matrix powers, in any scalar T.
#pragma once

#include "core/scalar.hpp"
#include "windows/windows.hpp"

namespace btob::windows {

// Two ways to evaluate the sign of Q_n(r) in a floating type T (float, double, long double, float128,
// mpfr_float at its current default precision):
//  * matrix: Q_n(r) / r^(2n) = tr(J (BA)^n)(r) * tr(J (B~A~)^n)(r) / r^(2n) - 1, where B~ = r B(1/r) and
//    A~ = r A(1/r) have polynomial entries, so no 1/r appears; matrix powers carry a separate power-of-two
//    exponent (exact rescaling), so nothing under- or overflows for any n.
//  * polynomial: Horner on Q_n's exact coefficients rounded to T (what the paper did with 32 and 512 digits).
enum class Route { matrix, polynomial };
const char* route_name(Route r);

// Q_n(r) / r^(2n) computed by the matrix route, r in (0, 1).
template <class T> T window_condition(int n, const T& r);

// The window lower bound by bisection in T on (7 - 4 sqrt 3, r_crit,2(n)) (upper 1/2 for n = 1), the
// bracket of window_lower_bound.  Returns NaN when the bracket shows no sign change in T.
template <class T> T window_lower_bound_in(int n, Route route);

extern template float window_condition<float>(int, const float&);
extern template double window_condition<double>(int, const double&);
extern template long double window_condition<long double>(int, const long double&);
extern template core::float128 window_condition<core::float128>(int, const core::float128&);
extern template mpfr_float window_condition<mpfr_float>(int, const mpfr_float&);
extern template float window_lower_bound_in<float>(int, Route);
extern template double window_lower_bound_in<double>(int, Route);
extern template long double window_lower_bound_in<long double>(int, Route);
extern template core::float128 window_lower_bound_in<core::float128>(int, Route);
extern template mpfr_float window_lower_bound_in<mpfr_float>(int, Route);

}  // namespace btob::windows
